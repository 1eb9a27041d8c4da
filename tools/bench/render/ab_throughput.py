#!/usr/bin/env python3
"""A/B of builds: samples per second of `bench_render throughput`, the builds
alternating run by run, so that the machine's drift falls on all of them alike.

    python3 tools/bench/render/ab_throughput.py [--rounds 12] [--scene scenes/cornell-box.json]
            [--accel bvh] [--spp 32] BUILD_DIR [BUILD_DIR ...]

Each BUILD_DIR is a build tree with tools/bench/render/bench_render (e.g. build/
and a second tree configured with other flags). Prints, per build, the median
and the largest of its runs and the ratio of its median to the first build's.
The renders are the same image in every build (the error is the same), so the
ratio is one of speed at equal error. Nothing is written to docs/: the figures
quoted in docs/performance.md say which command made them.
"""
import argparse
import json
import os
import statistics
import subprocess
import tempfile

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))


def samples_per_second(build, a, out):
    exe = os.path.join(build, "tools", "bench", "render", "bench_render")
    subprocess.run([exe, "throughput", a.scene, "--accel", a.accel, "--threads", str(a.threads), "--spp", str(a.spp),
                    "--runs", "1", "--json", out], cwd=REPO, check=True, capture_output=True)
    with open(out) as f:
        return json.load(f)[0]["median_samples_per_second"]


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("builds", nargs="+")
    p.add_argument("--rounds", type=int, default=12)
    p.add_argument("--scene", default="scenes/cornell-box.json")
    p.add_argument("--accel", default="bvh", choices=["bvh", "embree"])
    p.add_argument("--threads", type=int, default=2)
    p.add_argument("--spp", type=int, default=32)
    a = p.parse_args()
    runs = {b: [] for b in a.builds}
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "throughput.json")
        for _ in range(a.rounds):
            for b in a.builds:
                runs[b].append(samples_per_second(b, a, out))
    base = statistics.median(runs[a.builds[0]])
    for b in a.builds:
        m = statistics.median(runs[b])
        print(f"{b}: median {m / 1e6:.3f} M samples/s, largest {max(runs[b]) / 1e6:.3f} M, "
              f"ratio to {a.builds[0]} {m / base:.3f} ({a.rounds} runs)")


if __name__ == "__main__":
    main()
