#!/usr/bin/env python3
"""N-way interleaved A/B of builds of our BVH, each against bare Embree in its
own process (ab_bvh.py's measurement, for more than two builds at once).

    python3 tools/bench/accel/abn_bvh.py NAME=BENCH_ACCEL NAME=BENCH_ACCEL ... [--rounds 5]
        [--scenes sponza,bunny] [--repetitions 5] [--json out.json]

Each round runs `bench_accel --clock cpu --threads 1 --builds 3` of every
build, the order rotated from round to round and reversed every other round,
and takes per scene and ray kind the ratio BVH / bare Embree each process
measured. Prints, per build, the median ratio over the rounds ± half their
range, and for every build after the first the per-round ratio build / first
build (measured in the same round, a minute apart): median (min-max). lscpu
and the load average go with the result (and into --json).
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from ab_bvh import run_once  # noqa: E402

KINDS = ("camera", "shadow", "diffuse")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("builds", nargs="+", help="NAME=PATH of a bench_accel binary; the first is the reference")
    ap.add_argument("--rounds", type=int, default=5)
    ap.add_argument("--scenes", default="sponza,bunny")
    ap.add_argument("--repetitions", type=int, default=5)
    ap.add_argument("--json")
    a = ap.parse_args()
    names, bins = zip(*(b.split("=", 1) for b in a.builds))
    load_start = open("/proc/loadavg").read().split()[:3]
    runs = {n: [] for n in names}
    with tempfile.TemporaryDirectory() as tmp:
        for i in range(a.rounds):
            order = list(range(len(names)))
            order = order[i % len(order):] + order[:i % len(order)]
            if i % 2:
                order.reverse()
            for j in order:
                runs[names[j]].append(run_once(bins[j], [], a.scenes, a.repetitions, tmp))
                print(f"round {i + 1} {names[j]}: " + json.dumps(runs[names[j]][-1]), file=sys.stderr, flush=True)
    load_end = open("/proc/loadavg").read().split()[:3]
    base = names[0]
    print(f"BVH / bare Embree, CPU time, 1 thread, {a.rounds} rounds; load {' '.join(load_start)} -> "
          f"{' '.join(load_end)}; per build: median ± half range [per-round build / {base}: median (range)]")
    print("| scene | kind | " + " | ".join(names) + " |")
    print("|---|---|" + "---|" * len(names))
    for scene in runs[base][0]:
        for k in KINDS:
            cells = []
            for n in names:
                v = [r[scene][k] for r in runs[n]]
                cell = f"{statistics.median(v):.3f} ± {(max(v) - min(v)) / 2:.3f}"
                if n != base:
                    p = [runs[n][i][scene][k] / runs[base][i][scene][k] for i in range(a.rounds)]
                    cell += f" [{statistics.median(p):.3f} ({min(p):.3f}-{max(p):.3f})]"
                cells.append(cell)
            print(f"| {scene} | {k} | " + " | ".join(cells) + " |")
    lscpu = subprocess.run(["lscpu"], capture_output=True, text=True).stdout
    print("\n".join(l for l in lscpu.splitlines() if l.startswith(("Model name", "CPU(s):"))))
    if a.json:
        with open(a.json, "w") as f:
            json.dump({"builds": dict(zip(names, bins)), "runs": runs, "load": {"start": load_start, "end": load_end},
                       "lscpu": lscpu}, f, indent=1)


if __name__ == "__main__":
    main()
