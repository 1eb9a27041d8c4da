#!/usr/bin/env python3
"""A/B of two builds of the renderer on one scene: the CPU cost of a sample and
the error reached, interleaved in one invocation; writes a section of
docs/bench/sample-cost.md (and the runs as JSON beside it).

    python3 tools/bench/render/ab_sample_cost.py BASE_PATHTRACER NEW_PATHTRACER --title TITLE
        [--scene tools/peers/cycles/scenes/sponza-env-sun.json] [--reference EXR] [--spp 512]
        [--rounds 4] [--threads 2] [--out docs/bench/sample-cost.md] [--set key=value ...]

BASE_PATHTRACER is typically a copy of `pathtracer` built before the change
(e.g. from a worktree of main), NEW_PATHTRACER the build with it. Each round
renders the scene once with each build, the same seed for both (round r: seed
r + 1), alternating which goes first; each render is timed by the renderer's
own run record (`performance.render_cpu_seconds`: the render phase's CPU time,
every thread, so that the other jobs on a shared machine do not count) and
measured with pt-imgerr against the reference (by default the committed
converged image of the Sponza peers comparison). The two renders of a
round are also compared pixel for pixel (`idiff -fail 0`): a change that
claims to be exact must give identical images, round after round.

Reported per build: median render CPU time with its min-max, MSE (mean over
rounds), and per round the ratios new / base of the CPU time (time per sample at
equal samples) and of MSE x time (time to equal error, MSE falling as 1 / spp),
median and min-max over the rounds, with the 1-minute load average before
each render and `lscpu`.
"""
import argparse
import json
import os
import shutil
import statistics
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", "..", ".."))
sys.path.insert(0, os.path.join(ROOT, "tools", "pylib"))
from pt_tools import image_error, write_section  # noqa: E402

MARKER = "<!-- ab_sample_cost.py writes the sections below this line -->"


def loadavg():
    with open("/proc/loadavg") as f:
        return float(f.read().split()[0])


def render(exe, a, seed, out):
    report = out + ".report.json"
    cmd = ["nice", "-n", "10", exe, os.path.join(ROOT, a.scene), "-o", out, "--spp", str(a.spp), "--seed",
           str(seed), "--threads", str(a.threads), "--quiet", "--report", report]
    for s in a.set:
        cmd += ["--set", s]
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        raise RuntimeError("%s: %s" % (" ".join(cmd), r.stderr.strip()))
    with open(report) as f:
        rec = json.load(f)
    return rec["timings"]["render"], rec["performance"]["render_cpu_seconds"]


def identical(a, b):
    """True if the two images' pixels are equal (idiff with no tolerance)."""
    if shutil.which("idiff") is None:
        return None
    return subprocess.run(["idiff", "-fail", "0", "-warn", "0", a, b], capture_output=True).returncode == 0


def run(a, tmp):
    builds = [("base", a.base), ("new", a.new)]
    res = {name: {"cpu": [], "wall": [], "mse": [], "load": []} for name, _ in builds}
    same = []
    for r in range(a.rounds):
        order = builds if r % 2 == 0 else builds[::-1]
        for name, exe in order:
            out = os.path.join(tmp, "%s.exr" % name)
            load = loadavg()
            wall, cpu = render(exe, a, r + 1, out)
            mse = image_error(a.imgerr, out, a.reference)["mse"]
            for key, v in (("cpu", cpu), ("wall", wall), ("mse", mse), ("load", load)):
                res[name][key].append(v)
            print("round %d %s: %.3f CPU s (%.2f s wall), MSE %.5g, load %.1f" % (r, name, cpu, wall, mse, load),
                  file=sys.stderr)
        same.append(identical(os.path.join(tmp, "base.exr"), os.path.join(tmp, "new.exr")))
    return res, same


def med_range(values, fmt="%.3f"):
    return (fmt + " (" + fmt + "-" + fmt + ")") % (statistics.median(values), min(values), max(values))


def section(a, res, same):
    b, n = res["base"], res["new"]
    t_ratio = [tn / tb for tn, tb in zip(n["cpu"], b["cpu"])]
    e_ratio = [(mn * tn) / (mb * tb) for mn, tn, mb, tb in zip(n["mse"], n["cpu"], b["mse"], b["cpu"])]
    loads = b["load"] + n["load"]
    if all(s is True for s in same):
        images = "identical pixels in every round (`idiff -fail 0`)"
    elif any(s is None for s in same):
        images = "not compared (no idiff)"
    else:
        images = "different pixels in %d of %d rounds" % (sum(1 for s in same if not s), len(same))
    cmd = "tools/bench/render/ab_sample_cost.py BASE NEW --title '%s' --scene %s --spp %d --rounds %d --threads %d%s" % (
        a.title, a.scene, a.spp, a.rounds, a.threads, "".join(" --set " + s for s in a.set))
    lines = [
        "## %s" % a.title, "",
        "`%s`; %d rounds, seeds 1-%d (both builds the same seed per round), alternating order; render CPU time "
        "from the run record; MSE against `%s`. 1-minute load average before each render: min %.1f, median %.1f, "
        "max %.1f. Images: %s." % (cmd, a.rounds, a.rounds, os.path.relpath(a.reference, ROOT), min(loads),
                                   statistics.median(loads), max(loads), images), "",
        "| build | spp | render CPU s, median (min-max) | MSE (mean) | RMSE |",
        "|---|---|---|---|---|",
    ]
    for name in ("base", "new"):
        r = res[name]
        mse = statistics.mean(r["mse"])
        lines.append("| %s | %d | %s | %.4g | %.4f |" % (name, a.spp, med_range(r["cpu"]), mse, mse ** 0.5))
    lines += ["", "new / base, per round: CPU time per sample **%s**; time to equal error (MSE x time) **%s**." % (
        med_range(t_ratio), med_range(e_ratio)), ""]
    return "\n".join(lines)


def write(a, text, res, same):
    entry = {"scene": a.scene, "spp": a.spp, "threads": a.threads, "set": a.set, "runs": res, "identical": same}
    write_section(a.out, MARKER, a.title, text, entry, heading="# Cost of a sample")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("base")
    ap.add_argument("new")
    ap.add_argument("--title", required=True)
    ap.add_argument("--scene", default="tools/peers/cycles/scenes/sponza-env-sun.json")
    ap.add_argument("--reference", default="tools/peers/cycles/references/sponza-env-sun-32.exr")
    ap.add_argument("--spp", type=int, default=512)
    ap.add_argument("--rounds", type=int, default=4)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--set", action="append", default=[], help="a --set key=value for both builds")
    ap.add_argument("--imgerr", default=os.path.join(ROOT, "build", "tools", "imgerr", "pt-imgerr"))
    ap.add_argument("--out", default=os.path.join(ROOT, "docs", "bench", "sample-cost.md"))
    a = ap.parse_args()
    a.reference = os.path.join(ROOT, a.reference)
    with tempfile.TemporaryDirectory() as tmp:
        res, same = run(a, tmp)
    text = section(a, res, same)
    write(a, text, res, same)
    print(text)


if __name__ == "__main__":
    main()
