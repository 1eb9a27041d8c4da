#!/usr/bin/env python3
"""A/B of the path integrator's light choice: render.light_sampler bvh against power
(docs/path-tracing.md, "Choosing a light"), writes docs/bench/lights.md.

For each scene: a reference rendered with the bvh sampler at many samples (its
own seed), then ROUNDS rounds of one render per sampler at the test sample
count, alternating which goes first, each timed by the renderer's own clock
(the "render X s" of its summary line) and measured with pt-imgerr against
the reference. Reported: time per sample, MSE at equal samples, and the
efficiency 1 / (MSE x time), whose ratio is the ratio of the times the two
need to reach the same error (MSE falls as 1 / samples), and the RMSE each
would reach in the other's time.

Usage: lights_ab.py [--build build] [--out docs/bench/lights.md] [--rounds 3] [--quick]
                    [--against OLD_PATHTRACER] [--case NAME]

--against: instead of power against bvh, the bvh sampler of another build of the
renderer ("before", e.g. a copy of main's build/pathtracer with its pt_oiio.so
beside it) against this build's ("after"), rounds alternating as above; the
reference is this build's. --case runs only the cases whose name starts with NAME.
"""
import argparse
import os
import re
import statistics
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", "..", ".."))
sys.path.insert(0, os.path.join(ROOT, "tools", "pylib"))
from pt_tools import image_error, lscpu  # noqa: E402

# name, scene, width (None: the scene's), reference spp, test spp, rectangle of interest
CASES = [
    ("spot + sky", "tests/data/scenes/spot-sky.json", None, 1024, 64, "100,90,60,30"),
    ("Cornell box", "scenes/cornell-box.json", 128, 1024, 64, None),
    ("many lights (248)", "scenes/many-lights.json", 120, 512, 16, None),
]
SAMPLERS = ["power", "bvh"]


def render(exe, scene, width, spp, sampler, seed, out):
    cmd = ["nice", "-n", "10", exe, os.path.join(ROOT, scene), "-o", out, "--spp", str(spp), "--seed", str(seed),
           "--set", "render.light_sampler=" + sampler]
    if width:
        cmd += ["--width", str(width)]
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        raise RuntimeError("%s: %s" % (" ".join(cmd), r.stderr.strip()))
    m = re.search(r"render ([0-9.]+) s", r.stdout + r.stderr)
    if not m:
        raise RuntimeError("no render time in: " + r.stdout + r.stderr)
    size = re.search(r"\((\d+)x(\d+),", r.stdout + r.stderr)
    return float(m.group(1)), int(size.group(1)) * int(size.group(2))


def loadavg():
    with open("/proc/loadavg") as f:
        return " ".join(f.read().split()[:3])


def run_case(args, tmp, case):
    name, scene, width, ref_spp, spp, rect = case
    if args.quick:
        ref_spp, spp = ref_spp // 8, max(1, spp // 4)
    ref = os.path.join(tmp, "ref.exr")
    render(args.pathtracer, scene, width, ref_spp, "bvh", 1000, ref)
    res = {s: {"time": [], "mse": [], "rect": []} for s in args.variants}
    pixels = 0
    for r in range(args.rounds):
        order = list(args.variants) if r % 2 == 0 else list(args.variants)[::-1]
        for s in order:
            out = os.path.join(tmp, "%s.exr" % s)
            exe, sampler = args.variants[s]
            t, pixels = render(exe, scene, width, spp, sampler, r + 1, out)
            res[s]["time"].append(t)
            res[s]["mse"].append(image_error(args.imgerr, out, ref)["mse"])
            if rect:
                res[s]["rect"].append(image_error(args.imgerr, out, ref, rect)["mse"])
    return {"name": name, "scene": scene, "spp": spp, "ref_spp": ref_spp, "pixels": pixels, "rect": rect, "res": res}


def table(cases, variants):
    base = variants[0]
    lines = ["| scene | sampler | render s (median) | ns per sample | MSE at equal spp | RMSE | "
             "efficiency 1/(MSE t) | time to equal error (%s = 1) | RMSE in %s's time |" % (base, base),
             "|---|---|---|---|---|---|---|---|---|"]
    for c in cases:
        stats = {}
        for s in variants:
            t = statistics.median(c["res"][s]["time"])
            mse = statistics.mean(c["res"][s]["mse"])
            stats[s] = (t, mse)
        tp, mp = stats[base]
        for s in variants:
            t, mse = stats[s]
            eff = 1.0 / (mse * t)
            ratio = (mse * t) / (mp * tp)
            rmse_equal_time = (mse * t / tp) ** 0.5
            lines.append("| %s | %s | %.3f | %.0f | %.3g | %.4f | %.3g | %.2f | %.4f |" % (
                c["name"], s, t, 1e9 * t / (c["pixels"] * c["spp"]), mse, mse ** 0.5, eff, ratio, rmse_equal_time))
        if c["rect"]:
            for s in variants:
                lines.append("| %s, rect %s | %s | | | %.3g | %.4f | | | |" % (
                    c["name"], c["rect"], s, statistics.mean(c["res"][s]["rect"]),
                    statistics.mean(c["res"][s]["rect"]) ** 0.5))
    return "\n".join(lines)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--build", default=os.path.join(ROOT, "build"))
    ap.add_argument("--out", default=os.path.join(ROOT, "docs", "bench", "lights.md"))
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--quick", action="store_true", help="an eighth of the samples (a smoke run)")
    ap.add_argument("--against", help="another build's pathtracer: its bvh sampler against this build's")
    ap.add_argument("--case", default="", help="only the cases whose name starts with this")
    args = ap.parse_args()
    args.pathtracer = os.path.join(args.build, "pathtracer")
    if args.against:
        args.variants = {"before": (args.against, "bvh"), "after": (args.pathtracer, "bvh")}
    else:
        args.variants = {s: (args.pathtracer, s) for s in SAMPLERS}
    names = list(args.variants)
    args.imgerr = os.path.join(args.build, "tools", "imgerr", "pt-imgerr")
    load_before = loadavg()
    cases = []
    with tempfile.TemporaryDirectory() as tmp:
        for case in CASES:
            if case[0].startswith(args.case):
                cases.append(run_case(args, tmp, case))
                print(table(cases[-1:], names), flush=True)
    load_after = loadavg()
    with open(args.out + ".table", "w") as f:
        f.write("load average before: %s, after: %s\n\n%s\n\n```\n%s```\n" % (load_before, load_after, table(cases, names),
                                                                          lscpu()))
    print("wrote %s.table (paste into %s)" % (args.out, args.out))


if __name__ == "__main__":
    main()
