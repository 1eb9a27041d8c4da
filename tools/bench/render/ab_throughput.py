#!/usr/bin/env python3
"""A/B of builds or backends: samples per second of `bench_render throughput`,
the contenders alternating run by run, so that the machine's drift falls on all
of them alike.

    python3 tools/bench/render/ab_throughput.py [--rounds 12] [--scene scenes/cornell-box.json]
            [--accel bvh [embree]] [--spp 32] [--clock wall|cpu] BUILD_DIR [BUILD_DIR ...]

Each BUILD_DIR is a build tree with tools/bench/render/bench_render (e.g. build/
and a second tree configured with other flags); each (build, backend) pair is a
contender, so `--accel embree bvh build` compares the two backends of one build.
Prints, per contender, the median, the smallest and the largest of its runs and
the ratio of its median to the first contender's. Between builds the renders
are the same image (the same error), so the ratio is one of speed at equal
error; between backends they agree statistically (docs/geometry.md), at the
same samples per pixel. --clock cpu divides by the process's CPU time during
the render (every thread) instead of the wall-clock time: on a machine shared
with other jobs it counts the time the render ran, not the time it waited for a
core. Nothing is written to docs/: the figures quoted in
docs/performance.md say which command made them.
"""
import argparse
import json
import os
import statistics
import subprocess
import tempfile

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))


def samples_per_second(build, accel, a, out):
    exe = os.path.join(build, "tools", "bench", "render", "bench_render")
    subprocess.run([exe, "throughput", a.scene, "--accel", accel, "--threads", str(a.threads), "--spp", str(a.spp),
                    "--runs", "1", "--json", out], cwd=REPO, check=True, capture_output=True)
    with open(out) as f:
        key = "median_samples_per_cpu_second" if a.clock == "cpu" else "median_samples_per_second"
        return json.load(f)[0][key]


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("builds", nargs="+")
    p.add_argument("--rounds", type=int, default=12)
    p.add_argument("--scene", default="scenes/cornell-box.json")
    p.add_argument("--accel", nargs="+", default=["bvh"], choices=["bvh", "embree"])
    p.add_argument("--threads", type=int, default=2)
    p.add_argument("--spp", type=int, default=32)
    p.add_argument("--clock", default="wall", choices=["wall", "cpu"])
    a = p.parse_args()
    contenders = [(b, accel) for b in a.builds for accel in a.accel]
    runs = {c: [] for c in contenders}
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "throughput.json")
        for _ in range(a.rounds):
            for c in contenders:
                runs[c].append(samples_per_second(c[0], c[1], a, out))
    first = contenders[0]
    base = statistics.median(runs[first])
    for c in contenders:
        m = statistics.median(runs[c])
        unit = "samples per CPU-second" if a.clock == "cpu" else "samples/s"
        print(f"{c[0]} --accel={c[1]}: median {m / 1e6:.3f} M {unit}, runs {min(runs[c]) / 1e6:.3f}-"
              f"{max(runs[c]) / 1e6:.3f} M, ratio to {first[0]} --accel={first[1]} {m / base:.3f} ({a.rounds} runs)")


if __name__ == "__main__":
    main()
