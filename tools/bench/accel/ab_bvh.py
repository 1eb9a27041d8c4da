#!/usr/bin/env python3
"""A/B of two builds of our BVH (or, with --backend embree, of our Embree
backend), each against bare Embree in its own process.

    python3 tools/bench/accel/ab_bvh.py OLD_BENCH_ACCEL NEW_BENCH_ACCEL [--rounds 4]
        [--scenes sponza,bunny,sphere] [--repetitions 5] [--backend bvh|embree] [--json out.json]
        [-- extra bench_accel args]

Runs `bench_accel --clock cpu --threads 1` of the two builds alternately, round
after round (old, new, new, old, ...), and collects per scene and ray kind the
ratio BVH (or `--accel=embree`) / bare Embree that each run measured in its own process (the
yardstick shares the process's machine conditions, so the ratio is what is
compared across builds). Prints, per build, the median ratio over the rounds
with its spread (max - min) / 2, and new / old of the medians. lscpu and the
load average are printed with the result (and written to --json).
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile

KINDS = ("camera", "shadow", "diffuse", "build_time")


RATIO_KEYS = {"bvh": "ratios_bvh_over_embree_reference", "embree": "ratios_embree_backend_over_embree_reference"}


def run_once(binary, args, scenes, reps, tmp, backend="bvh"):
    out = os.path.join(tmp, "r.json")
    cmd = [binary, "--clock", "cpu", "--threads", "1", "--builds", "3", "--repetitions", str(reps),
           "--scenes", scenes, "--json", out] + args
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
    with open(out) as f:
        data = json.load(f)
    result = {}
    for s in data["scenes"]:
        r = s["runs"][0][RATIO_KEYS[backend]]
        result[s["name"]] = {k: r[k] for k in KINDS}
    return result


def summary(values):
    med = statistics.median(values)
    return med, (max(values) - min(values)) / 2


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("old")
    ap.add_argument("new")
    ap.add_argument("--rounds", type=int, default=4)
    ap.add_argument("--scenes", default="sponza,bunny,sphere")
    ap.add_argument("--repetitions", type=int, default=5)
    ap.add_argument("--backend", choices=sorted(RATIO_KEYS), default="bvh")
    ap.add_argument("--json")
    ap.add_argument("extra", nargs="*")
    a = ap.parse_args()
    load_start = open("/proc/loadavg").read().split()[:3]
    runs = {"old": [], "new": []}
    with tempfile.TemporaryDirectory() as tmp:
        for i in range(a.rounds):
            order = ("old", "new") if i % 2 == 0 else ("new", "old")
            for which in order:
                binary = a.old if which == "old" else a.new
                runs[which].append(run_once(binary, a.extra, a.scenes, a.repetitions, tmp, a.backend))
                print(f"round {i + 1} {which}: " + json.dumps(runs[which][-1]), file=sys.stderr)
    load_end = open("/proc/loadavg").read().split()[:3]
    table = {}
    label = "BVH" if a.backend == "bvh" else "--accel=embree"
    print(f"{label} / bare Embree, CPU time, 1 thread, {a.rounds} rounds; load {' '.join(load_start)} -> {' '.join(load_end)}")
    print("| scene | kind | old (median ± half range) | new | new / old |")
    print("|---|---|---|---|---|")
    for scene in runs["old"][0]:
        for k in KINDS:
            o = summary([r[scene][k] for r in runs["old"]])
            n = summary([r[scene][k] for r in runs["new"]])
            table[f"{scene}/{k}"] = {"old": o, "new": n}
            print(f"| {scene} | {k} | {o[0]:.3f} ± {o[1]:.3f} | {n[0]:.3f} ± {n[1]:.3f} | {n[0] / o[0]:.3f} |")
    lscpu = subprocess.run(["lscpu"], capture_output=True, text=True).stdout
    print("\n".join(l for l in lscpu.splitlines() if l.startswith(("Model name", "CPU(s):"))))
    if a.json:
        with open(a.json, "w") as f:
            json.dump({"old": a.old, "new": a.new, "backend": a.backend, "runs": runs, "summary": table,
                       "load": {"start": load_start, "end": load_end}, "lscpu": lscpu}, f, indent=1)


if __name__ == "__main__":
    main()
