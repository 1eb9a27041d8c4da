#!/usr/bin/env python3
"""A/B of the path integrator's guiding (render.light_guiding and render.path_guiding,
docs/path-tracing.md, "Light guiding" and "Path guiding"): the same build, off against on, in one
interleaved run; writes docs/bench/guiding.md (or --out; and the runs as JSON beside it).

A variant is name=L (light guiding's pre-pass paths per pixel) or name=L/P (and path guiding's),
optionally followed by @EXE: that variant is rendered by another build's pathtracer (e.g. a copy of
main's build/pathtracer with its pt_oiio.so beside it), to compare builds with the same settings.

For each case: a reference (the case's committed one, or one rendered once here with guiding off
at many samples, its own seed), then ROUNDS rounds of one render per variant at the case's sample
count, alternating which goes first, each timed by the renderer's own clocks (its --report: the pre-pass counts, it runs inside the
render phase) and measured with pt-imgerr
against the reference. Time is the render phase's CPU time (`performance.render_cpu_seconds` of the
run record, both threads; the machine is shared, so wall time mostly measures the others' load).
Reported per variant: median render CPU time and its spread, MSE at equal
samples, and the time to equal error against the first variant, (MSE x t) / (MSE_0 x t_0) per
round (MSE falling as 1 / samples; the pre-pass is a fixed cost, so this holds at the case's
sample count, which is chosen near the error the peers comparison targets), median and min-max.

Usage: guiding_ab.py [--build build] [--out docs/bench/guiding.md] [--rounds 3] [--case NAME]
                     [--variants off=0,on=4 | off=0/0,light=16/0,path=0/16,both=16/16
                                 | before=16@/tmp/main/pathtracer,after=16]
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", "..", ".."))
sys.path.insert(0, os.path.join(ROOT, "tools", "pylib"))
from pt_tools import image_error, lscpu  # noqa: E402

# name, scene, width, height (None: the scene's), reference (None: rendered here), reference spp, test spp
CASES = [
    ("Sponza, sky + sun (32x32)", "tools/peers/cycles/scenes/sponza-env-sun.json", None, None,
     "tools/peers/cycles/references/sponza-env-sun-32.exr", 0, 512),
    ("bunny outdoors, sky (48x48)", "tools/bench/render/bunny-env.json", 48, 48, None, 2048, 128),
    ("Cornell box (64x64)", "scenes/cornell-box.json", 64, 64, None, 1024, 64),
    ("sunlit room, one roof opening (48x48)", "tools/bench/render/sunroom.json", None, None, None, 1024, 64),
    ("many lights, peer scene (36x24)", "tools/peers/cycles/scenes/many-lights-peer.json", None, None,
     "tools/peers/cycles/references/many-lights-peer-36x24.exr", 0, 64),
]


MARKER = "<!-- guiding_ab.py writes everything below this line -->"


def loadavg():
    with open("/proc/loadavg") as f:
        return float(f.read().split()[0])


def parse_variant(text):
    """name=L, name=L/P, either with @EXE -> (name, (L, P, EXE or None))."""
    name, value = text.split("=", 1)
    exe = None
    if "@" in value:
        value, exe = value.split("@", 1)
    parts = [int(x) for x in value.split("/")]
    return name, (parts[0], parts[1] if len(parts) > 1 else 0, exe)


def describe(guiding):
    light, path, exe = guiding
    return "`light_guiding` %d" % light + (", `path_guiding` %d" % path if path else "") + (
        ", build %s" % exe if exe else "")


def render(exe, scene, width, height, spp, guiding, seed, out):
    report = out + ".report.json"
    light, path = guiding[0], guiding[1]
    if len(guiding) > 2 and guiding[2]:
        exe = guiding[2]
    cmd = ["nice", "-n", "10", exe, os.path.join(ROOT, scene), "-o", out, "--spp", str(spp), "--seed", str(seed),
           "--threads", "2", "--quiet", "--report", report, "--set", "render.light_guiding=%d" % light]
    if path:
        cmd += ["--set", "render.path_guiding=%d" % path]
    if width:
        cmd += ["--width", str(width), "--height", str(height)]
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        raise RuntimeError("%s: %s" % (" ".join(cmd), r.stderr.strip()))
    r = json.load(open(report))
    return r["timings"]["render"], r["performance"]["render_cpu_seconds"]


def run_case(args, tmp, case, variants):
    name, scene, width, height, ref, ref_spp, spp = case
    if ref is None:
        ref = os.path.join(tmp, "ref.exr")
        render(args.exe, scene, width, height, ref_spp, (0, 0), 1000, ref)
    else:
        ref = os.path.join(ROOT, ref)
    res = {v: {"time": [], "wall": [], "mse": [], "load": []} for v, _ in variants}
    for r in range(args.rounds):
        order = variants if r % 2 == 0 else variants[::-1]
        for v, guiding in order:
            out = os.path.join(tmp, "%s.exr" % v)
            load = loadavg()
            wall, t = render(args.exe, scene, width, height, spp, guiding, r + 1, out)
            mse = image_error(args.imgerr, out, ref)["mse"]
            res[v]["time"].append(t)
            res[v]["wall"].append(wall)
            res[v]["mse"].append(mse)
            res[v]["load"].append(load)
            print("%s %s round %d: %.3f CPU s (%.3f s wall), MSE %.4g, load %.1f" % (name, v, r, t, wall, mse, load),
                  file=sys.stderr)
    return {"name": name, "scene": scene, "spp": spp, "ref_spp": ref_spp, "res": res}


def table(cases, variants):
    base = variants[0][0]
    lines = ["| scene | variant | spp | render CPU s, median (min-max) | MSE (mean) | RMSE | "
             "time to equal error (%s = 1), median (min-max) over rounds |" % base, "|---|---|---|---|---|---|---|"]
    for c in cases:
        b = c["res"][base]
        for v, guiding in variants:
            r = c["res"][v]
            ratios = [(m * t) / (mb * tb) for m, t, mb, tb in zip(r["mse"], r["time"], b["mse"], b["time"])]
            mse = statistics.mean(r["mse"])
            lines.append("| %s | %s (%s) | %d | %.2f (%.2f-%.2f) | %.3g | %.4f | %.2f (%.2f-%.2f) |" % (
                c["name"], v, describe(guiding), c["spp"], statistics.median(r["time"]), min(r["time"]), max(r["time"]), mse,
                mse ** 0.5, statistics.median(ratios), min(ratios), max(ratios)))
    return "\n".join(lines)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--build", default=os.path.join(ROOT, "build"))
    ap.add_argument("--out", default=os.path.join(ROOT, "docs", "bench", "guiding.md"))
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--case", default="", help="only the cases whose name starts with this")
    ap.add_argument("--variants", default="off=0,on=16", help="name=L or name=L/P (light and path guiding's pre-pass paths per pixel), ...; the first is the base")
    args = ap.parse_args()
    args.exe = os.path.join(args.build, "pathtracer")
    args.imgerr = os.path.join(args.build, "tools", "imgerr", "pt-imgerr")
    variants = [parse_variant(v) for v in args.variants.split(",")]
    loads = [loadavg()]
    with tempfile.TemporaryDirectory() as tmp:
        cases = [run_case(args, tmp, c, variants) for c in CASES if c[0].startswith(args.case)]
    loads.append(loadavg())
    all_loads = [l for c in cases for v in c["res"].values() for l in v["load"]]
    text = ["# Guiding: A/B", "", MARKER, "",
            "Written by `tools/bench/guiding/guiding_ab.py --variants %s --rounds %d` (how it measures: its "
            "docstring). %s, interleaved, 2 threads, the render phase's CPU time from the run record (the "
            "pre-pass included). 1-minute load average before each render: min %.1f, median %.1f, max %.1f." % (
                args.variants, args.rounds,
                "Two builds (a variant's @EXE, else this build)" if any(v[1][2] for v in variants) else "Same build",
                min(all_loads), statistics.median(all_loads), max(all_loads)), "",
            table(cases, variants), "", "## Machine", "", "```", lscpu().strip(), "```", ""]
    # The hand-written part above MARKER (the steps and their verdicts) is kept.
    kept = ""
    if os.path.exists(args.out):
        old = open(args.out).read()
        if MARKER in old:
            kept = old[:old.index(MARKER)]
    with open(args.out, "w") as f:
        f.write(kept + "\n".join(text[2:]) if kept else "\n".join(text))
    with open(os.path.splitext(args.out)[0] + ".json", "w") as f:
        json.dump({"variants": variants, "rounds": args.rounds, "cases": cases}, f, indent=1)
    print("\n".join(text[:6]))


if __name__ == "__main__":
    main()
