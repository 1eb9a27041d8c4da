#!/usr/bin/env python3
"""Pre-flight memory estimate against measured peak RSS (issue 20, docs/cli.md "Memory pre-flight").

Renders scenes of different kinds (analytic shapes, a large film with every AOV, OBJ and PLY meshes,
Sponza with an environment map, large textures) with `pathtracer --report` and compares the record's
memory.estimate_bytes (what --max-memory checks) with memory.peak_rss_bytes (getrusage ru_maxrss).
Each scene is run --runs times, interleaved; the table shows the median peak.

  python3 tools/bench/memory/memory_bench.py [--exe build/pathtracer] [--shared ../shared]
        [--runs 3] [--json docs/bench/memory.json] [--markdown docs/bench/memory.md] [--outputs]

--outputs runs the film and output cases instead (the Cornell box at sizes up to 4K, with and without
every AOV, one EXR part or one per layer, EXR with PNG): the film, Film::layers() and the EXR writer's
band of packed rows (io/exr_bands.h), the parts of the estimate that grow with the pixels.

Mesh scenes need ../shared (assets/meshes, assets/sponza, assets/env); without it they are skipped.
The "per triangle" column is (peak - everything else the estimate counts) / triangles: what the
acceleration structure and its build really took, the figure kBvhBytesPerTriangle and
kEmbreeBytesPerTriangle (src/app/memory_estimate.cpp) are set from.
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))
ALL_AOVS = ("albedo,N,P,Z,IndexOB,IndexMA,diffuse_direct,diffuse_indirect,specular_direct,specular_indirect,"
            "emission,variance,samples,nonfinite")


def native(shapes, width=256, height=256, extra=""):
    return ('{"format": "pathtracer-scene", "version": 1, "camera": {"position": [0, 1, 4], "look_at": [0, 0.5, 0]},'
            ' "film": {"width": %d, "height": %d}, "render": {"integrator": "path", "spp": 1, "max_depth": 4},%s'
            ' "shapes": [%s]}' % (width, height, extra, shapes))


def write_grid_ply(path, n):
    """A binary PLY height field of n x n quads (2 n^2 triangles): a large mesh without ../shared."""
    import struct
    with open(path, "wb") as f:
        f.write(("ply\nformat binary_little_endian 1.0\nelement vertex %d\nproperty float x\nproperty float y\n"
                 "property float z\nelement face %d\nproperty list uchar int vertex_indices\nend_header\n"
                 % ((n + 1) ** 2, 2 * n * n)).encode())
        row = struct.Struct("<3f")
        for y in range(n + 1):  # a row at a time: this process stays small
            f.write(b"".join(row.pack(x / n - 0.5, 0.05 * ((x * 7 + y * 13) % 5) / 5, y / n - 0.5)
                             for x in range(n + 1)))
        tri = struct.Struct("<B3i")
        for y in range(n):
            faces = []
            for x in range(n):
                v = y * (n + 1) + x
                faces.append(tri.pack(3, v, v + 1, v + n + 2))
                faces.append(tri.pack(3, v, v + n + 2, v + n + 1))
            f.write(b"".join(faces))


def scenes(shared, work):
    """(name, scene file, extra arguments, accel backends)"""
    write_grid_ply(os.path.join(work, "grid.ply"), 700)
    with open(os.path.join(work, "grid.json"), "w") as f:
        f.write(native('{"type": "mesh", "file": "grid.ply"}'))
    out = [("cornell box 256x256 (quads, spheres)", os.path.join(REPO, "scenes", "cornell-box.json"),
            ["--width", "256", "--height", "256"], ["bvh", "embree"]),
           ("cornell box 1024x1024, every AOV", os.path.join(REPO, "scenes", "cornell-box.json"),
            ["--width", "1024", "--height", "1024", "--aov", ALL_AOVS], ["bvh"]),
           ("generated grid, 980k triangles (PLY)", os.path.join(work, "grid.json"), [], ["bvh", "embree"])]
    if not os.path.isdir(os.path.join(shared, "assets")):
        print("note: %s/assets not found; mesh and texture scenes skipped" % shared, file=sys.stderr)
        return out
    a = os.path.join(os.path.abspath(shared), "assets")
    files = {
        "bunny.json": native('{"type": "mesh", "file": "%s/meshes/stanford-bunny.obj"}' % a),
        "dragon.json": native('{"type": "mesh", "file": "%s/meshes/dragon_vrip_res3.ply"}' % a),
        "sponza.json": native('{"type": "mesh", "file": "%s/sponza/sponza.obj"}' % a,
                              extra=' "environment": {"file": "%s/env/aristea_wreck_puresky_1k.hdr"},' % a),
        "textures.json": native(", ".join('{"type": "sphere", "center": [%d, 0.5, 0], "radius": 0.4, "material": "m%d"}'
                                          % (i - 2, i) for i in range(4)),
                                extra=' "materials": {%s},' % ", ".join(
                                    '"m%d": {"type": "lambert", "texture": "%s/env/%s"}' % (i, a, f) for i, f in enumerate(
                                        ["aristea_wreck_puresky_1k.hdr", "brown_photostudio_02_1k.hdr",
                                         "noon_grass_1k.hdr", "luxcore_arch.exr"]))),
    }
    for name, text in files.items():
        with open(os.path.join(work, name), "w") as f:
            f.write(text)
    w = lambda n: os.path.join(work, n)
    out += [("Stanford bunny (OBJ mesh)", w("bunny.json"), [], ["bvh", "embree"]),
            ("dragon res3 (PLY mesh)", w("dragon.json"), [], ["bvh", "embree"]),
            ("Sponza (OBJ) + 1k HDR environment", w("sponza.json"), [], ["bvh", "embree"]),
            ("four textured spheres (1k HDR/EXR textures)", w("textures.json"), [], ["bvh"])]
    return out


def output_cases():
    """(name, scene file, extra arguments, accel backends): the film and output buffers at several sizes."""
    cornell = os.path.join(REPO, "scenes", "cornell-box.json")
    size = lambda w, h: ["--width", str(w), "--height", str(h)]
    every = ["--aov", ALL_AOVS]
    return [("1024x1024, EXR", cornell, size(1024, 1024), ["bvh"]),
            ("1024x1024 every AOV, EXR", cornell, size(1024, 1024) + every, ["bvh"]),
            ("1024x1024 every AOV, multi-part EXR", cornell, size(1024, 1024) + every + ["--multipart"], ["bvh"]),
            ("1024x1024 every AOV, EXR piz", cornell, size(1024, 1024) + every + ["--exr-compression", "piz"], ["bvh"]),
            ("2048x1024 every AOV, EXR", cornell, size(2048, 1024) + every, ["bvh"]),
            ("1920x1080 every AOV, EXR and PNG", cornell, size(1920, 1080) + every + ["-o", "{work}/out.png"], ["bvh"]),
            ("2048x2048, EXR", cornell, size(2048, 2048), ["bvh"]),
            ("3840x2160, EXR", cornell, size(3840, 2160), ["bvh"])]


def run_once(exe, scene, extra, accel, work):
    report = os.path.join(work, "run.json")
    extra = [e.replace("{work}", work) for e in extra]
    cmd = [exe, scene, "-o", os.path.join(work, "out.exr"), "--spp", "1", "--threads", "2", "--quiet",
           "--accel", accel, "--report", report] + extra
    subprocess.run(cmd, check=True)
    with open(report) as f:
        r = json.load(f)
    return r["memory"], r["accel"]["primitive_count"]


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--exe", default=os.path.join(REPO, "build", "pathtracer"))
    ap.add_argument("--shared", default=os.path.join(REPO, "..", "shared"))
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--json")
    ap.add_argument("--markdown")
    ap.add_argument("--outputs", action="store_true", help="the film and output cases instead of the scenes")
    a = ap.parse_args()
    rows = []
    with tempfile.TemporaryDirectory() as work:
        chosen = output_cases() if a.outputs else scenes(a.shared, work)
        cases = [(n, s, e, acc) for n, s, e, accs in chosen for acc in accs]
        results = {i: [] for i in range(len(cases))}
        for _ in range(a.runs):  # interleaved: every case once per round
            for i, (name, scene, extra, accel) in enumerate(cases):
                results[i].append(run_once(a.exe, scene, extra, accel, work))
        for i, (name, scene, extra, accel) in enumerate(cases):
            peaks = [m["peak_rss_bytes"] for m, _ in results[i]]
            mem, prims = results[i][len(peaks) // 2]
            peak = statistics.median(peaks)
            est = mem["estimate_bytes"]
            parts = mem.get("estimate_parts", {})
            rows.append({"scene": name, "accel": accel, "estimate": est, "peak": peak, "peaks": peaks,
                         "ratio": est / peak, "parts": parts, "primitives": prims})
    if a.outputs:  # the parts that grow with the pixels, and the spread of the peaks
        lines = ["| case | estimate (MiB) | measured peak RSS (MiB), median [min, max] | estimate / peak | "
                 "film (MiB) | images: layers and writer (MiB) | baseline (MiB) |", "|---|---|---|---|---|---|---|"]
        for r in rows:
            p = r["parts"]
            lines.append("| %s | %.1f | %.1f [%.1f, %.1f] | %.3f | %.1f | %.1f | %.1f |" % (
                r["scene"], r["estimate"] / 2**20, r["peak"] / 2**20, min(r["peaks"]) / 2**20,
                max(r["peaks"]) / 2**20, r["ratio"], p.get("film", 0) / 2**20, p.get("images", 0) / 2**20,
                p.get("baseline", 0) / 2**20))
    else:
        lines = ["| scene | accel | estimate (MiB) | measured peak RSS (MiB) | estimate / peak | of which baseline (MiB) |",
                 "|---|---|---|---|---|---|"]
        for r in rows:
            lines.append("| %s | %s | %.1f | %.1f | %.2f | %.1f |" % (
                r["scene"], r["accel"], r["estimate"] / 2**20, r["peak"] / 2**20, r["ratio"],
                r["parts"].get("baseline", 0) / 2**20))
    table = "\n".join(lines)
    print(table)
    worst = max(abs(r["ratio"] - 1) for r in rows)
    print("largest deviation: %.1f%%" % (100 * worst))
    if a.json:
        with open(a.json, "w") as f:
            json.dump(rows, f, indent=1)
    if a.markdown:
        with open(a.markdown, "w") as f:
            f.write(table + "\n")


if __name__ == "__main__":
    main()
