#!/usr/bin/env python3
"""Aliasing of a checkerboard floor at 1 sample per pixel: point-sampled
texture lookups against filtered ones (issue 17).

The scene (floor.json): an infinite plane seen from 1 m above it, towards the
horizon, textured with a black and white checker of 6.25 cm squares (a 512 x
512 image of 64 x 64 squares, repeated every 4 m, made here with oiiotool),
lit from straight above so that every pixel shows the texture's mean over
what it sees. The reference is the same image rendered with point lookups
(the nearest texel: the exact checker) at 4096 samples per pixel, stratified
(the box-filtered pixel, converged). Each variant is rendered at 1 sample per
pixel (the pixel centre), and its error against the reference is measured
with pt-imgerr over the whole frame and over the far field (the rows above the
middle of the floor, where the squares are smaller than a pixel):
  - image, filter point (nearest texel: what aliases);
  - image, filter bilinear (finest level, bilinear: what the renderer did before);
  - image, filter trilinear and anisotropic (MIP-mapped, footprint from the
    camera ray's differentials);
  - the procedural checker of the same squares (closed-form box filter).
Also each at 16 spp, where point sampling has had 16 samples per pixel to
average: filtering should still not be worse there (its footprint is one
pixel whatever the sample count: docs/textures.md).

Writes docs/bench/texture-aliasing.{json,md} and the 1-spp images of the
point and anisotropic lookups as PNG beside them, with the machine (lscpu).
Needs a Release build (pathtracer, pt-imgerr) and oiiotool. About 3 minutes
on 2 cores.

  python3 tools/study/texture_aliasing/aliasing_study.py [--exe build/pathtracer] [--reference-spp 4096]
"""
import argparse
import json
import os
import shutil
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(os.path.dirname(HERE)))
sys.path.insert(0, os.path.join(REPO, "tools", "bench", "render"))
from run_benchmarks import lscpu  # noqa: E402

VARIANTS = [("image, point", ["textures.image.filter=point"]),
            ("image, bilinear (before)", ["textures.image.filter=bilinear"]),
            ("image, trilinear", ["textures.image.filter=trilinear"]),
            ("image, anisotropic", ["textures.image.filter=anisotropic"]),
            ("procedural checker", ["materials.floor.texture=procedural"])]
FAR = "0,53,320,30"  # the far field: rows 53-82 of 160 (the horizon is at row 51)


def render(exe, scene, out, spp, sets, threads):
    cmd = [exe, scene, "-o", out, "--spp", str(spp), "--threads", str(threads), "--quiet"]
    for s in sets:
        cmd += ["--set", s]
    print("+ " + " ".join(cmd), file=sys.stderr)
    subprocess.run(cmd, check=True)


def load_text(load):
    return ", ".join("%.1f" % x for x in load)


def error(imgerr, test, ref, rect=None):
    cmd = [imgerr, test, ref, "--json"] + (["--rect", rect] if rect else [])
    return json.loads(subprocess.run(cmd, check=True, text=True, capture_output=True).stdout)["rmse"]


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--exe", default=os.path.join(REPO, "build", "pathtracer"))
    p.add_argument("--imgerr", default=os.path.join(REPO, "build", "tools", "imgerr", "pt-imgerr"))
    p.add_argument("--reference-spp", type=int, default=4096)
    p.add_argument("--threads", type=int, default=2)
    p.add_argument("--quick", action="store_true", help="a 256-spp reference, nothing written to docs/")
    a = p.parse_args()
    if a.quick:
        a.reference_spp = 256
    load_start = os.getloadavg()
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        scene = os.path.join(tmp, "floor.json")
        shutil.copy(os.path.join(HERE, "floor.json"), scene)
        subprocess.run(["oiiotool", "--pattern", "checker:width=8:height=8:color1=0,0,0:color2=1,1,1", "512x512", "3",
                        "-d", "uint8", "-o", os.path.join(tmp, "checker.png")], check=True)
        ref = os.path.join(tmp, "reference.exr")
        render(a.exe, scene, ref, a.reference_spp, VARIANTS[0][1], a.threads)
        for name, sets in VARIANTS:
            row = {"variant": name}
            for spp in (1, 16):
                out = os.path.join(tmp, "v%d_%d.exr" % (len(rows), spp))
                render(a.exe, scene, out, spp, sets, a.threads)
                row["rmse_%d" % spp] = error(a.imgerr, out, ref)
                row["rmse_far_%d" % spp] = error(a.imgerr, out, ref, FAR)
                if spp == 1 and not a.quick and name in ("image, point", "image, anisotropic"):
                    png = os.path.join(REPO, "docs", "bench", "texture-aliasing-%s.png" % name.split(", ")[1])
                    render(a.exe, scene, png, 1, sets, a.threads)
            rows.append(row)
    if a.quick:
        print(json.dumps(rows, indent=1))
        return
    load = {"start": list(load_start), "end": list(os.getloadavg())}
    doc = {"reference_spp": a.reference_spp, "rows": rows, "machine": lscpu(), "load_average": load}
    with open(os.path.join(REPO, "docs", "bench", "texture-aliasing.json"), "w") as f:
        json.dump(doc, f, indent=1)
    point = rows[0]
    lines = ["# Checkerboard floor at 1 spp: point-sampled against filtered texture lookups", "",
             "Written by `tools/study/texture_aliasing/aliasing_study.py`: `floor.json` (320 x 160), RMSE against a "
             "%d-spp point-sampled reference (pt-imgerr, linear RGB clamped to [0, 1]) over the frame and over the far "
             "field (rows 53-82, just below the horizon, where the squares are smaller than a pixel). The ratio is the "
             "point lookup's RMSE over the variant's, at 1 spp." % a.reference_spp, "",
             "| lookups | RMSE 1 spp | far field 1 spp | ratio (far) | RMSE 16 spp | far field 16 spp |",
             "|---|---|---|---|---|---|"]
    for r in rows:
        lines.append("| %s | %.4f | %.4f | %.1f | %.4f | %.4f |" % (r["variant"], r["rmse_1"], r["rmse_far_1"],
                                                                 point["rmse_far_1"] / r["rmse_far_1"], r["rmse_16"],
                                                                 r["rmse_far_16"]))
    lines += ["", "1 spp, point lookups: ![point](texture-aliasing-point.png) anisotropic: "
              "![anisotropic](texture-aliasing-anisotropic.png)", "",
              "Load average (1, 5, 15 min; the machine is shared): %s at the start, %s at the end (errors do not depend "
              "on it)." % (load_text(load["start"]), load_text(load["end"])), "", "Machine:", "", "```",
              doc["machine"].strip(), "```", ""]
    with open(os.path.join(REPO, "docs", "bench", "texture-aliasing.md"), "w") as f:
        f.write("\n".join(lines))


if __name__ == "__main__":
    main()
