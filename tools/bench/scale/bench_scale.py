#!/usr/bin/env python3
"""Load-and-build time and peak memory per triangle of large inputs, for both
backends (issue 18, deliverable 4), written to docs/bench/scale.{json,md}.

Inputs (made in --work, not committed):
  - grid:       a displaced grid of --triangles triangles (10 million) as a
                binary PLY (gen_grid_ply), in a native scene;
  - sponza:     Crytek Sponza's OBJ (../shared/assets/sponza) in a native scene;
  - bunny-obj:  the Stanford bunny's OBJ (../shared/assets/meshes) in a native scene;
  - bunny-cgr:  the same 69,451 triangles written as CGR "triangle" shapes, each
                with its inline material, as a course file holds them;
  - sponza-import: Sponza's OBJ with its MTL materials placed by {"type": "import"}
                (src/scene/asset_obj.cpp; textures loaded too);
  - obj-grid:   a displaced grid of --obj-triangles triangles (1 million) as an
                OBJ text file with v, vt, vn and v/vt/vn faces, in a native scene;
  - gltf-grid:  that grid's positions and triangles as a glTF 2.0 file, placed by
                {"type": "import"};
  - bunny-gltf: the bunny's triangles written as a glTF 2.0 file (.gltf + .bin,
                float positions, uint32 indices) placed by {"type": "import"};
  - baseline:   one triangle in a native scene: the process's own footprint.
With --compare OTHER_BUILD, every run is made with both builds back to back
(OTHER_BUILD first) and an A/B table of the medians is printed (and the runs
written to --json): the interleaved comparison of two versions.
Each is rendered by the pathtracer at 16x16, 1 spp, with --report; the run
record gives the time of each phase (parse, mesh load, scene build, accel
build: "load and build" is their sum) and the process's peak RSS
(getrusage). Memory per triangle is (peak RSS - the baseline's peak RSS with
the same backend) / triangles. The runs alternate input by input and backend
by backend, --runs rounds; medians are reported with their range. The process
CPU time of each run (rusage of the child) is recorded too: on a machine shared
with other jobs, wall-clock times include the waiting.

  python3 tools/bench/scale/bench_scale.py [--build build] [--work /tmp/pt-scale] [--runs 3]
          [--threads 2] [--triangles 10000000] [--inputs grid,sponza,sponza-import,bunny-obj,bunny-gltf,bunny-cgr]
          [--obj-triangles 1000000] [--compare OTHER_BUILD]
          [--image exr|ppm] [--json docs/bench/scale.json] [--markdown docs/bench/scale.md] [--note TEXT]
"""
import argparse
import json
import os
import platform
import resource
import statistics
import struct
import subprocess
import sys
import time

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))
SHARED = os.path.join(os.path.dirname(REPO), "shared")
SPONZA_OBJ = os.path.join(SHARED, "assets", "sponza", "sponza.obj")
BUNNY_OBJ = os.path.join(SHARED, "assets", "meshes", "stanford-bunny.obj")
MARKER = "<!-- hand-written analysis: kept when bench_scale.py rewrites the tables above -->"
PHASES = ["parse", "mesh_load", "scene_build", "accel_build"]
COURSE_MATERIAL = {"ks": 0.1, "kd": 0.9, "specularexponent": 20, "diffusecolor": [0.8, 0.8, 0.8],
                   "specularcolor": [1.0, 1.0, 1.0], "isreflective": False, "reflectivity": 1.0,
                   "isrefractive": False, "refractiveindex": 1.0}


def native_scene(path, shapes, camera):
    scene = {"format": "pathtracer-scene", "version": 1, "camera": camera,
             "film": {"width": 16, "height": 16}, "render": {"integrator": "path", "max_depth": 2, "spp": 1},
             "materials": {"white": {"type": "lambert", "diffuse": [0.7, 0.7, 0.7]}},
             "lights": [{"type": "point", "position": [0, 10, 0], "intensity": [1, 1, 1]}],
             "shapes": shapes}
    with open(path, "w") as f:
        json.dump(scene, f, indent=1)


def obj_triangles(path):
    vertices, triangles = [], []
    with open(path) as f:
        for line in f:
            parts = line.split()
            if not parts:
                continue
            if parts[0] == "v":
                vertices.append([float(x) for x in parts[1:4]])
            elif parts[0] == "f":
                idx = [int(p.split("/")[0]) - 1 for p in parts[1:]]
                for k in range(1, len(idx) - 1):
                    triangles.append((idx[0], idx[k], idx[k + 1]))
    return vertices, triangles


def obj_grid(path, triangles):
    """A displaced grid of about `triangles` triangles as OBJ text: v, vt, vn, f v/vt/vn."""
    n = max(2, int((triangles / 2) ** 0.5))
    with open(path, "w") as f:
        f.write(f"# displaced grid, {n}x{n} quads, {2 * n * n} triangles (bench_scale.py)\n")
        for j in range(n + 1):
            f.write("".join(f"v {i / n - 0.5:.6f} {0.05 * ((i * 7 + j * 13) % 17) / 17:.6f} {j / n - 0.5:.6f}\n"
                            for i in range(n + 1)))
        for j in range(n + 1):
            f.write("".join(f"vt {i / n:.6f} {j / n:.6f}\n" for i in range(n + 1)))
        for j in range(n + 1):
            f.write("".join(f"vn {0.1 * ((i + j) % 5) / 5:.6f} 0.994987 {0.05:.6f}\n" for i in range(n + 1)))
        for j in range(n):
            rows = []
            for i in range(n):
                a, b = j * (n + 1) + i + 1, j * (n + 1) + i + 2
                c, d = b + n + 1, a + n + 1
                rows.append(f"f {a}/{a}/{a} {d}/{d}/{d} {c}/{c}/{c}\nf {a}/{a}/{a} {c}/{c}/{c} {b}/{b}/{b}\n")
            f.write("".join(rows))
    return 2 * n * n


def course_file(path, obj):
    """The OBJ's triangles as CGR 'triangle' shapes, each with its own material."""
    vertices, triangles = obj_triangles(obj)
    shapes = [{"type": "triangle", "v0": vertices[a], "v1": vertices[b], "v2": vertices[c],
               "material": COURSE_MATERIAL} for a, b, c in triangles]
    scene = {"nbounces": 2, "rendermode": "phong",
             "camera": {"type": "pinhole", "width": 16, "height": 16, "position": [0.0, 0.1, 0.4],
                        "lookAt": [-0.02, 0.1, 0.0], "upVector": [0.0, 1.0, 0.0], "fov": 45.0, "exposure": 0.1},
             "scene": {"backgroundcolor": [0.25, 0.25, 0.25],
                       "lightsources": [{"type": "pointlight", "position": [0, 1.0, 0.5], "intensity": [0.75, 0.75, 0.75]}],
                       "shapes": shapes}}
    with open(path, "w") as f:
        json.dump(scene, f)
    return len(triangles)


def gltf_file(path, obj):
    """The OBJ's positions and triangles as a glTF 2.0 file with one mesh."""
    vertices, triangles = obj_triangles(obj)
    pos = struct.pack(f"<{3 * len(vertices)}f", *[c for v in vertices for c in v])
    idx = struct.pack(f"<{3 * len(triangles)}I", *[i for t in triangles for i in t])
    binary = os.path.splitext(path)[0] + ".bin"
    with open(binary, "wb") as f:
        f.write(pos + idx)
    lo = [min(v[k] for v in vertices) for k in range(3)]
    hi = [max(v[k] for v in vertices) for k in range(3)]
    doc = {"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
           "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
           "buffers": [{"uri": os.path.basename(binary), "byteLength": len(pos) + len(idx)}],
           "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": len(pos), "target": 34962},
                           {"buffer": 0, "byteOffset": len(pos), "byteLength": len(idx), "target": 34963}],
           "accessors": [{"bufferView": 0, "componentType": 5126, "count": len(vertices), "type": "VEC3",
                          "min": lo, "max": hi},
                         {"bufferView": 1, "componentType": 5125, "count": 3 * len(triangles), "type": "SCALAR"}]}
    with open(path, "w") as f:
        json.dump(doc, f)
    return len(triangles), len(pos) + len(idx)


def make_inputs(a):
    os.makedirs(a.work, exist_ok=True)
    cam = {"position": [0, 3, 3], "look_at": [0, 0, 0], "up": [0, 1, 0], "fov": 45}
    inputs = {}
    base = os.path.join(a.work, "baseline.json")
    native_scene(base, [{"type": "triangle", "material": "white", "vertices": [[0, 0, 0], [1, 0, 0], [0, 0, 1]]}], cam)
    inputs["baseline"] = {"scene": base, "triangles": 1, "source": "one triangle"}
    if "grid" in a.inputs:
        ply = os.path.join(a.work, f"grid-{a.triangles}.ply")
        if not os.path.exists(ply):
            subprocess.run([os.path.join(a.build, "tools", "bench", "scale", "gen_grid_ply"), ply,
                            "--triangles", str(a.triangles)], check=True)
        with open(ply, "rb") as f:
            header = f.read(400).decode("latin-1")
        faces = int(header.split("element face ")[1].split()[0])
        scene = os.path.join(a.work, "grid.json")
        native_scene(scene, [{"type": "mesh", "material": "white", "file": ply}], cam)
        inputs["grid"] = {"scene": scene, "triangles": faces, "source": f"gen_grid_ply, binary PLY, {os.path.getsize(ply)} bytes"}
    far = {"position": [0, 20, 0], "look_at": [-100, 60, 0], "up": [0, 1, 0], "fov": 60}
    for name, obj in (("sponza", SPONZA_OBJ), ("bunny-obj", BUNNY_OBJ)):
        if name in a.inputs and os.path.exists(obj):
            scene = os.path.join(a.work, name + ".json")
            native_scene(scene, [{"type": "mesh", "material": "white", "file": obj}], far)
            inputs[name] = {"scene": scene, "triangles": None, "source": f"OBJ, {os.path.getsize(obj)} bytes"}
    if "obj-grid" in a.inputs or "gltf-grid" in a.inputs:
        obj = os.path.join(a.work, f"grid-{a.obj_triangles}.obj")
        if not os.path.exists(obj):
            obj_grid(obj + ".tmp", a.obj_triangles)
            os.replace(obj + ".tmp", obj)
        with open(obj) as f:
            n = int(f.readline().split(" triangles")[0].split()[-1])
        scene = os.path.join(a.work, "obj-grid.json")
        native_scene(scene, [{"type": "mesh", "material": "white", "file": obj}], cam)
        if "obj-grid" in a.inputs:
            inputs["obj-grid"] = {"scene": scene, "triangles": n,
                                  "source": f"OBJ v/vt/vn grid, {os.path.getsize(obj)} bytes"}
        if "gltf-grid" in a.inputs:
            gltf = os.path.join(a.work, f"grid-{a.obj_triangles}.gltf")
            n, size = gltf_file(gltf, obj)
            scene = os.path.join(a.work, "gltf-grid.json")
            native_scene(scene, [{"type": "import", "file": gltf}], cam)
            inputs["gltf-grid"] = {"scene": scene, "triangles": n,
                                   "source": f"glTF 2.0 (import), the obj-grid's {n} triangles, {size} bytes of buffer"}
    if "sponza-import" in a.inputs and os.path.exists(SPONZA_OBJ):
        scene = os.path.join(a.work, "sponza-import.json")
        native_scene(scene, [{"type": "import", "file": SPONZA_OBJ}], far)
        inputs["sponza-import"] = {"scene": scene, "triangles": None,
                                   "source": f"OBJ + MTL (import), {os.path.getsize(SPONZA_OBJ)} bytes"}
    if "bunny-gltf" in a.inputs and os.path.exists(BUNNY_OBJ):
        gltf = os.path.join(a.work, "bunny.gltf")
        n, size = gltf_file(gltf, BUNNY_OBJ)
        scene = os.path.join(a.work, "bunny-gltf.json")
        native_scene(scene, [{"type": "import", "file": gltf}], cam)
        inputs["bunny-gltf"] = {"scene": scene, "triangles": n,
                                "source": f"glTF 2.0 through Assimp (import), {n} triangles, {size} bytes of buffer"}
    if "bunny-cgr" in a.inputs and os.path.exists(BUNNY_OBJ):
        scene = os.path.join(a.work, "bunny-cgr.json")
        n = course_file(scene, BUNNY_OBJ)
        inputs["bunny-cgr"] = {"scene": scene, "triangles": n, "file_bytes": os.path.getsize(scene),
                               "source": f"CGR course file, {n} triangle shapes, {os.path.getsize(scene)} bytes"}
    return inputs


def run(a, scene, accel, build=None, env=None):
    report = os.path.join(a.work, "report.json")
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.monotonic()
    p = subprocess.run([os.path.join(build or a.build, "pathtracer"), scene, "-o", os.path.join(a.work, "out." + a.image),
                        "--width", "16", "--height", "16", "--spp", "1", "--threads", str(a.threads),
                        "--accel", accel, "--report", report], capture_output=True, text=True,
                       env=dict(os.environ, **(env or {})))
    wall = time.monotonic() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if p.returncode != 0:
        sys.exit(f"pathtracer failed on {scene}:\n{p.stderr}")
    with open(report) as f:
        r = json.load(f)
    t = r["timings"]
    return {"load_build_seconds": sum(t[k] for k in PHASES), "phases": {k: t[k] for k in PHASES},
            "process_wall_seconds": wall,
            "process_cpu_seconds": (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime),
            "peak_rss_bytes": r["memory"]["peak_rss_bytes"], "estimate_bytes": r["memory"].get("estimate_bytes"),
            # The peak before the acceleration structure is built (the memory pre-flight's reading).
            "load_peak_bytes": r["memory"].get("estimate_parts", {}).get("peak_so_far"),
            "accel_memory_bytes": r["accel"]["memory_bytes"],
            "accel_build_peak_bytes": r["accel"].get("build_peak_bytes", 0),
            "primitives": r["accel"]["primitive_count"], "backend": r["accel"]["backend"]}


def summary(values):
    return {"median": statistics.median(values), "min": min(values), "max": max(values)}


def lscpu():
    try:
        return subprocess.run(["lscpu"], check=True, text=True, capture_output=True).stdout
    except (OSError, subprocess.CalledProcessError):
        return platform.processor()


def load_average():
    try:
        with open("/proc/loadavg") as f:
            return " ".join(f.read().split()[:3])
    except OSError:
        return "unknown"


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--build", default=os.path.join(REPO, "build"))
    p.add_argument("--work", default="/tmp/pt-scale")
    p.add_argument("--runs", type=int, default=3)
    p.add_argument("--threads", type=int, default=2)
    p.add_argument("--triangles", type=int, default=10_000_000)
    p.add_argument("--inputs", default="grid,sponza,sponza-import,bunny-obj,bunny-gltf,bunny-cgr")
    p.add_argument("--accel", default="embree,bvh")
    p.add_argument("--json")
    p.add_argument("--markdown")
    p.add_argument("--note", default="")
    p.add_argument("--obj-triangles", type=int, default=1_000_000)
    p.add_argument("--compare", help="another build folder: every run is made with it and with --build, back to back")
    p.add_argument("--variant", action="append", nargs="+", metavar="LABEL BUILD [ENV=VALUE]",
                   help="a build folder and environment to compare (repeatable): every run is made with each "
                        "variant back to back, e.g. --variant fast build --variant 4i build "
                        "PT_EMBREE_CONFIG=tri_accel=bvh8.triangle4i")
    # ppm: no image module is loaded (docs/architecture.md), so the baseline is the bare process
    # (~17 MiB, not ~135) and a transient of loading (a course file's JSON tree) is not hidden
    # under the module's pages, which an EXR run maps only after the scene is loaded.
    p.add_argument("--image", choices=["exr", "ppm"], default="exr")
    a = p.parse_args()
    a.inputs = a.inputs.split(",")
    accels = a.accel.split(",")
    inputs = make_inputs(a)
    a.variants = [(v[0], v[1], dict(e.split("=", 1) for e in v[2:])) for v in (a.variant or [])]
    if a.compare:
        a.variants = [("A", a.compare, {}), ("B", a.build, {})]
    if a.variants:
        return compare(a, inputs, accels)
    load_before = load_average()
    runs = {(name, accel): [] for name in inputs for accel in accels}
    for _ in range(a.runs):
        for name, spec in inputs.items():
            for accel in accels:
                r = run(a, spec["scene"], accel)
                runs[(name, accel)].append(r)
                print(f"{name} {accel}: load+build {r['load_build_seconds']:.2f} s, cpu {r['process_cpu_seconds']:.2f} s, "
                      f"peak {r['peak_rss_bytes'] / 2**20:.0f} MiB", flush=True)
    results = []
    for name, spec in inputs.items():
        for accel in accels:
            rs = runs[(name, accel)]
            base = statistics.median(x["peak_rss_bytes"] for x in runs[("baseline", accel)])
            tris = spec["triangles"] or rs[0]["primitives"]
            peak = statistics.median(x["peak_rss_bytes"] for x in rs)
            entry = {"input": name, "accel": accel, "backend": rs[0]["backend"], "source": spec["source"],
                     "triangles": tris, "runs": rs,
                     "load_build_seconds": summary([x["load_build_seconds"] for x in rs]),
                     "process_cpu_seconds": summary([x["process_cpu_seconds"] for x in rs]),
                     "phases_median": {k: statistics.median(x["phases"][k] for x in rs) for k in PHASES},
                     "peak_rss_bytes": peak, "baseline_peak_rss_bytes": base,
                     "bytes_per_triangle_above_baseline": (peak - base) / tris if name != "baseline" else None,
                     "accel_memory_bytes": rs[0]["accel_memory_bytes"],
                     "estimate_over_peak": (rs[0]["estimate_bytes"] / peak) if rs[0]["estimate_bytes"] else None}
            if "file_bytes" in spec:
                entry["file_bytes"] = spec["file_bytes"]
                entry["peak_above_baseline_over_file_size"] = (peak - base) / spec["file_bytes"]
            results.append(entry)
    record = {"command": " ".join(sys.argv), "threads": a.threads, "runs": a.runs, "note": a.note, "image": a.image,
              "load_average": {"before": load_before, "after": load_average()}, "results": results,
              "machine_lscpu": lscpu()}
    if a.json:
        with open(a.json, "w") as f:
            json.dump(record, f, indent=2)
    md = markdown(record)
    if a.markdown:
        # The hand-written analysis after MARKER (if the file has one) is kept.
        kept = ""
        if os.path.exists(a.markdown):
            with open(a.markdown) as f:
                text = f.read()
            if MARKER in text:
                kept = "\n" + text[text.index(MARKER):]
        with open(a.markdown, "w") as f:
            f.write(md + kept)
    else:
        print(md)


def compare(a, inputs, accels):
    """Each input, backend and round with every variant back to back; the medians side by side."""
    builds = a.variants
    labels = [b[0] for b in builds]
    runs = {(n, acc, b): [] for n in inputs for acc in accels for b in labels}
    for _ in range(a.runs):
        for name, spec in inputs.items():
            for accel in accels:
                for label, build, env in builds:
                    r = run(a, spec["scene"], accel, build, env)
                    runs[(name, accel, label)].append(r)
                    print(f"{label} {name} {accel}: load+build {r['load_build_seconds']:.2f} s (mesh "
                          f"{r['phases']['mesh_load']:.2f}), cpu {r['process_cpu_seconds']:.2f} s, "
                          f"peak {r['peak_rss_bytes'] / 2**20:.0f} MiB", flush=True)
    med = lambda rs, f: statistics.median(f(x) for x in rs)
    arrow = " -> ".join(labels)
    out = ["; ".join(f"{label} = {build}" + "".join(f" {k}={v}" for k, v in env.items()) for label, build, env in builds)
           + f"; {a.runs} rounds, the variants back to back; load average {load_average()}", "",
           f"| input | backend | triangles | above baseline (B/triangle) {arrow} | loading only (B/triangle) {arrow} | "
           f"peak (MiB) {arrow} | accel structure / its build's peak (B/triangle, the backend's count) {arrow} | "
           f"CPU (s) {arrow} |", "|---|---|---|---|---|---|---|---|"]
    for name, spec in inputs.items():
        if name == "baseline":
            continue
        for accel in accels:
            cells = []
            for label in labels:
                rs = runs[(name, accel, label)]
                base = runs[("baseline", accel, label)]
                tris = spec["triangles"] or rs[0]["primitives"]
                peak = med(rs, lambda x: x["peak_rss_bytes"])
                load = med(rs, lambda x: x["load_peak_bytes"]) - med(base, lambda x: x["load_peak_bytes"])
                cells.append({"above": (peak - base_peak(base)) / tris, "peak": peak / 2**20, "load": load / tris,
                              "accel": rs[0]["accel_memory_bytes"] / tris,
                              "accel_peak": rs[0].get("accel_build_peak_bytes", 0) / tris,
                              "cpu": ", ".join(f"{x['process_cpu_seconds']:.2f}" for x in rs), "tris": tris})
            col = lambda fmt: " -> ".join(fmt.format(**c) for c in cells)
            out.append(f"| {name} | {accel} | {cells[0]['tris']:,} | {col('{above:.0f}')} | {col('{load:.0f}')} | "
                       f"{col('{peak:.1f}')} | {col('{accel:.0f} / {accel_peak:.0f}')} | {col('{cpu}')} |")
    print("\n".join(out))
    if a.json:
        with open(a.json, "w") as f:
            json.dump({"command": " ".join(sys.argv), "variants": builds, "load_average_end": load_average(),
                       "runs": {"|".join(k): v for k, v in runs.items()}, "table": out,
                       "machine_lscpu": lscpu()}, f, indent=2)


def base_peak(rs):
    return statistics.median(x["peak_rss_bytes"] for x in rs)


def markdown(rec):
    out = ["# Scale: load and build time, memory per triangle", "",
           f"Produced by `python3 tools/bench/scale/bench_scale.py` (`{rec['command'].split('bench_scale.py', 1)[-1].strip()}`); "
           f"{rec['threads']} threads, {rec['runs']} rounds, inputs and backends alternating run by run.", ""]
    if rec["note"]:
        out += [f"**Note.** {rec['note']}", ""]
    out += ["Load and build: parse + mesh load + scene build + accel build from the run record (wall clock), median "
            "and range. CPU: the whole process's CPU time (user + system, all threads; includes the 16x16 render "
            f"and the {rec.get('image', 'exr').upper()}). Peak: the process's peak RSS; above baseline: minus the one-triangle scene's peak with "
            "the same backend. Goals (issue 18): the 10M grid in at most 5 s and 80 bytes per triangle above the "
            "baseline; any mesh format at most 100 bytes per triangle; a course file at most 4x its size.", "",
           "| input | backend | triangles | load + build (s) | parse / mesh / scene / accel (s) | CPU (s) | peak (MiB) | "
           "above baseline (B/triangle) | accel structure (B/triangle) | pre-flight estimate / peak |",
           "|---|---|---|---|---|---|---|---|---|---|"]
    for r in rec["results"]:
        lb, cpu, ph = r["load_build_seconds"], r["process_cpu_seconds"], r["phases_median"]
        per = r["bytes_per_triangle_above_baseline"]
        est = "—" if r["estimate_over_peak"] is None else f"{r['estimate_over_peak']:.2f}"
        extra = ""
        if "peak_above_baseline_over_file_size" in r:
            extra = f" ({r['peak_above_baseline_over_file_size']:.1f}x the file)"
        out.append(f"| {r['input']} | {r['accel']} | {r['triangles']:,} | {lb['median']:.2f} ({lb['min']:.2f}-{lb['max']:.2f}) | "
                   f"{ph['parse']:.2f} / {ph['mesh_load']:.2f} / {ph['scene_build']:.2f} / {ph['accel_build']:.2f} | "
                   f"{cpu['median']:.2f} | {r['peak_rss_bytes'] / 2**20:.0f} | "
                   f"{'—' if per is None else f'{per:.0f}'}{extra} | {r['accel_memory_bytes'] / r['triangles']:.0f} | "
                   f"{est} |")
    out += ["", "Inputs:", ""]
    seen = set()
    for r in rec["results"]:
        if r["input"] not in seen:
            seen.add(r["input"])
            out.append(f"- **{r['input']}**: {r['source']}")
    out += ["", "## Machine", "",
            f"Load average at the start: {rec['load_average']['before']}; at the end: {rec['load_average']['after']}.",
            "", "```", rec["machine_lscpu"].rstrip(), "```", ""]
    return "\n".join(out)


if __name__ == "__main__":
    main()
