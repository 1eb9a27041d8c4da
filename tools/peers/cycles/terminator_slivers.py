#!/usr/bin/env python3
"""The shadow terminator side by side with Cycles: four renders of one scene, their pairwise
differences and crops of a region (docs/rendering.md, "Shadow terminator").

    terminator_slivers.py SCENE.json --out-dir DIR --spp N [--cycles-spp M] [--threads T]
        [--crop X,Y,W,H] [--png-prefix docs/compare/terminator/sponza] [--reuse]

Renders (or, with --reuse, reads again from --out-dir) our image with the shadow-terminator offset
off (`--set render.shadow_terminator_geometry_offset=0`) and on (the scene's value, default 0.1),
a second seed of ours with it on (the noise floor of the statistic), and Cycles' with its per-object
Shadow Terminator > Geometry Offset at 0 and at its default 0.1 (scene_to_cycles.py
--terminator-geometry-offset). For every pair it prints the share of pixels whose channel mean
differs by more than --threshold (0.05), each way, and the means; with --png-prefix it writes
PREFIX-crop.png: the crop of the four images side by side (ours off, ours on, Cycles 0, Cycles 0.1),
magnified 4x (nearest), sRGB after --exposure stops. --json writes the numbers.

Needs build/pathtracer, blender (Debian's 3.4) and oiiotool (openimageio-tools).
"""
import argparse
import json
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.normpath(os.path.join(HERE, "..", "..", ".."))
sys.path.insert(0, HERE)
from compare_images import read_rgb  # noqa: E402

KEY = "render.shadow_terminator_geometry_offset"


def run(cmd, log):
    with open(log, "w") as f:
        subprocess.run(cmd, stdout=f, stderr=subprocess.STDOUT, check=True)


def render_all(args):
    """(name, path) of the five images, rendering those missing (or all without --reuse); Cycles'
    first, the longest renders, so that a cut-short run keeps them for --reuse."""
    exe = os.path.join(REPO, "build", "pathtracer")
    os.makedirs(args.out_dir, exist_ok=True)
    ours = [("ours-off", ["--set", f"{KEY}=0"], 1), ("ours-on", [], 1), ("ours-on-seed2", [], 2)]
    cycles = [("cycles-0", 0.0), ("cycles-0.1", 0.1)]
    path = {name: os.path.join(args.out_dir, name + ".exr") for name, *_ in ours + cycles}
    todo = [name for name in path if not (args.reuse and os.path.exists(path[name]))]
    for name, offset in cycles:
        if name in todo:
            run(["nice", "-n", "10", "blender", "-b", "--factory-startup", "--python",
                 os.path.join(HERE, "scene_to_cycles.py"), "--", args.scene, "--spp", str(args.cycles_spp),
                 "--seed", "1", "--threads", str(args.threads), "-o", path[name],
                 "--terminator-geometry-offset", str(offset)], path[name] + ".log")
    for name, extra, seed in ours:
        if name in todo:
            run(["nice", "-n", "10", exe, args.scene, "-o", path[name], "--spp", str(args.spp),
                 "--seed", str(seed), "--threads", str(args.threads), "--report", path[name] + ".json"]
                + extra, path[name] + ".log")
    return [(name, path[name]) for name, *_ in ours + cycles]


def channel_means(path):
    w, h, px = read_rgb(path)
    return w, h, [(r + g + b) / 3.0 for r, g, b in px]


def compare(a, b, threshold):
    n = len(a)
    return {"darker": sum(1 for x, y in zip(a, b) if x < y - threshold) / n,
            "brighter": sum(1 for x, y in zip(a, b) if x > y + threshold) / n,
            "mean_a": sum(a) / n, "mean_b": sum(b) / n}


def write_crop(images, crop, exposure, prefix):
    x, y, w, h = crop
    cmd = ["oiiotool"]
    for _, path in images:
        cmd += [path, "--ch", "R,G,B", "--cut", f"{w}x{h}+{x}+{y}", "--origin", "+0+0",
                "--mulc", str(2.0 ** exposure), "--resample", f"{4 * w}x{4 * h}"]
    cmd += ["--mosaic:pad=4", f"{len(images)}x1", "--colorconvert", "linear", "sRGB", "-d", "uint8",
            "-o", prefix + "-crop.png"]
    os.makedirs(os.path.dirname(os.path.abspath(prefix)), exist_ok=True)
    subprocess.run(cmd, check=True)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("scene")
    p.add_argument("--out-dir", required=True)
    p.add_argument("--spp", type=int, required=True, help="ours")
    p.add_argument("--cycles-spp", type=int, help="Cycles' (default: --spp)")
    p.add_argument("--threads", type=int, default=2)
    p.add_argument("--threshold", type=float, default=0.05)
    p.add_argument("--crop", help="X,Y,W,H in pixels, from the top left")
    p.add_argument("--exposure", type=float, default=0.0, help="stops, for the crop's PNG only")
    p.add_argument("--png-prefix")
    p.add_argument("--json")
    p.add_argument("--reuse", action="store_true", help="read the images already in --out-dir")
    args = p.parse_args()
    args.cycles_spp = args.cycles_spp or args.spp
    images = render_all(args)
    means = {name: channel_means(path)[2] for name, path in images}
    pairs = [("ours-off", "cycles-0"), ("ours-on", "cycles-0.1"), ("ours-off", "cycles-0.1"),
             ("ours-on", "cycles-0"), ("ours-off", "ours-on"), ("cycles-0", "cycles-0.1"),
             ("ours-on", "ours-on-seed2")]
    result = {"scene": os.path.relpath(os.path.abspath(args.scene), REPO), "spp": args.spp,
              "cycles_spp": args.cycles_spp, "threshold": args.threshold, "pairs": []}
    print(f"share of pixels whose channel mean differs by more than {args.threshold}:")
    for a, b in pairs:
        c = compare(means[a], means[b], args.threshold)
        result["pairs"].append(dict(a=a, b=b, **c))
        print(f"  {a:>13} vs {b:<13} {a} darker {100 * c['darker']:6.2f}%  brighter {100 * c['brighter']:6.2f}%"
              f"   means {c['mean_a']:.4f} / {c['mean_b']:.4f}")
    if args.crop and args.png_prefix:
        crop = [int(v) for v in args.crop.split(",")]
        shown = [img for img in images if img[0] != "ours-on-seed2"]
        shown = [shown[0], shown[1], shown[2], shown[3]]
        write_crop(shown, crop, args.exposure, args.png_prefix)
        result["crop"] = crop
    if args.json:
        with open(args.json, "w") as f:
            json.dump(result, f, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
