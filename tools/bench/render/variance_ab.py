#!/usr/bin/env python3
"""Variants of the renderer on one scene, interleaved in one invocation: the
variance of a render (from several seeds) and its render-phase CPU time, so
that a change trading variance for cost (splitting, Russian roulette) can be
judged by time to equal error; writes a section of docs/bench/splitting.md
(and the runs as JSON beside it).

    python3 tools/bench/render/variance_ab.py --title TITLE NAME=EXE[@VAR=VALUE,...] NAME=... \
        [--scene tools/peers/cycles/scenes/sponza-env-sun.json] [--spp 128] [--rounds 6] [--threads 2]
        [--out docs/bench/splitting.md] [--set key=value ...]

The first variant is the base. @VAR=VALUE,... sets environment variables for
that variant's renders (an experimental build's knobs). Round r renders every
variant once with seed r + 1, the order rotated by one each round. Variance of a
render: the mean over all pairs of seeds (i, j) of pt-imgerr's MSE between the
two renders, halved (which equals the unbiased per-pixel sample variance,
summed over R, G, B as pt-imgerr's MSE is, and averaged over pixels); unlike an MSE against a reference it holds no bias
and no reference noise, and 6 seeds of 1024 pixels x 3 channels resolve it to a
few percent. CPU time: the run record's `performance.render_cpu_seconds`
(every thread, so that other jobs on a shared machine count less), as a ratio
to the base's render of the same round. Time to equal error = variance ratio x
median CPU ratio.
"""
import argparse
import itertools
import json
import os
import statistics
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", "..", ".."))
sys.path.insert(0, os.path.join(ROOT, "tools", "pylib"))
from pt_tools import image_error, write_section  # noqa: E402

MARKER = "<!-- variance_ab.py writes the sections below this line -->"


def parse_variant(text):
    name, _, rest = text.partition("=")
    exe, _, env = rest.partition("@")
    if not name or not exe:
        raise SystemExit("variance_ab: a variant is NAME=EXE[@VAR=VALUE,...], not '%s'" % text)
    pairs = dict(kv.split("=", 1) for kv in env.split(",") if kv)
    return name, exe, pairs


def render(a, exe, env, seed, out):
    report = out + ".report.json"
    cmd = ["nice", "-n", "10", exe, os.path.join(ROOT, a.scene), "-o", out, "--spp", str(a.spp), "--seed", str(seed),
           "--threads", str(a.threads), "--quiet", "--report", report]
    for kv in a.set:
        cmd += ["--set", kv]
    r = subprocess.run(cmd, capture_output=True, text=True, env=dict(os.environ, **env))
    if r.returncode != 0:
        raise RuntimeError("%s: %s" % (" ".join(cmd), r.stderr.strip()))
    with open(report) as f:
        perf = json.load(f)["performance"]
    return perf["render_cpu_seconds"], perf["rays"] / perf["pixel_samples"]


def run(a, variants, tmp):
    res = {name: {"cpu": [], "rays_per_sample": 0.0, "load": []} for name, _, _ in variants}
    for r in range(a.rounds):
        k = r % len(variants)
        for name, exe, env in variants[k:] + variants[:k]:
            load = float(open("/proc/loadavg").read().split()[0])
            cpu, rays = render(a, exe, env, r + 1, os.path.join(tmp, "%s-%d.exr" % (name, r)))
            res[name]["cpu"].append(cpu)
            res[name]["load"].append(load)
            res[name]["rays_per_sample"] = rays
            print("round %d %s: %.3f CPU s, load %.1f" % (r, name, cpu, load), file=sys.stderr)
    for name, _, _ in variants:
        files = [os.path.join(tmp, "%s-%d.exr" % (name, r)) for r in range(a.rounds)]
        res[name]["variance"] = statistics.mean(
            image_error(a.imgerr, x, y)["mse"] / 2 for x, y in itertools.combinations(files, 2))
    return res


def section(a, variants, res, argv):
    base = variants[0][0]
    loads = [x for r in res.values() for x in r["load"]]
    lines = [
        "## %s" % a.title, "",
        "`tools/bench/render/variance_ab.py %s`; %d rounds, seeds 1-%d, order rotated each round; render CPU time "
        "from the run record; variance of one render at %d spp from all pairs of seeds. 1-minute load average before "
        "each render: min %.1f, median %.1f, max %.1f." % (" ".join(argv), a.rounds, a.rounds, a.spp, min(loads),
                                                           statistics.median(loads), max(loads)), "",
        "| variant | variance (R+G+B) | variance / base | rays per sample | CPU / base per round, median (min-max) "
        "| time to equal error / base |",
        "|---|---|---|---|---|---|",
    ]
    for name, _, env in variants:
        r = res[name]
        ratios = [c / b for c, b in zip(r["cpu"], res[base]["cpu"])]
        v = r["variance"] / res[base]["variance"]
        label = name + (" (" + ", ".join("%s=%s" % kv for kv in env.items()) + ")" if env else "")
        lines.append("| %s | %.4g | %.3f | %.2f | %.3f (%.3f-%.3f) | **%.3f** |" % (
            label, r["variance"], v, r["rays_per_sample"], statistics.median(ratios), min(ratios), max(ratios),
            v * statistics.median(ratios)))
    return "\n".join(lines) + "\n"


def write(a, text, res):
    entry = {"scene": a.scene, "spp": a.spp, "threads": a.threads, "set": a.set, "runs": res}
    write_section(a.out, MARKER, a.title, text, entry, heading="# Splitting")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("variants", nargs="+", help="NAME=EXE[@VAR=VALUE,...]; the first is the base")
    ap.add_argument("--title", required=True)
    ap.add_argument("--scene", default="tools/peers/cycles/scenes/sponza-env-sun.json")
    ap.add_argument("--spp", type=int, default=128)
    ap.add_argument("--rounds", type=int, default=6)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--set", action="append", default=[], help="a --set key=value for every variant")
    ap.add_argument("--imgerr", default=os.path.join(ROOT, "build", "tools", "imgerr", "pt-imgerr"))
    ap.add_argument("--out", default=os.path.join(ROOT, "docs", "bench", "splitting.md"))
    a = ap.parse_args()
    if a.rounds < 2:
        raise SystemExit("variance_ab: --rounds must be at least 2 (the variance needs two seeds)")
    variants = [parse_variant(v) for v in a.variants]
    with tempfile.TemporaryDirectory() as tmp:
        res = run(a, variants, tmp)
    text = section(a, variants, res, sys.argv[1:])
    write(a, text, res)
    print(text)


if __name__ == "__main__":
    main()
