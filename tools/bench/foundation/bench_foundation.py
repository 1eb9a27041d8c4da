#!/usr/bin/env python3
"""Times loading, accelerator build and rendering of a scene with 1 and N threads.

Runs `pathtracer SCENE --report run.json` several times per thread count, takes the
median of each phase, checks that the images of all thread counts are identical
(`idiff`, from openimageio-tools), and writes a JSON record and a markdown section
with the machine description (lscpu).

Default scene: the official Path of Light example at 800x800 (../shared).

  python3 tools/bench/foundation/bench_foundation.py [--scene S] [--threads 1 2] [--runs 5]
                                    [--json docs/bench/foundation.json]
                                    [--markdown docs/bench/foundation.md]
"""
import argparse
import json
import os
import platform
import statistics
import subprocess
import sys
import tempfile

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))
DEFAULT_SCENE = os.path.join(REPO, "..", "shared", "seed-scenes", "path-of-light", "examples",
                             "example.json")
PHASES = ["parse", "scene_build", "accel_build", "render", "write", "total"]


def run(cmd, **kw):
    return subprocess.run(cmd, check=True, text=True, capture_output=True, **kw)


def lscpu():
    try:
        return run(["lscpu"]).stdout
    except (OSError, subprocess.CalledProcessError):
        return platform.processor()


def one_run(exe, scene, threads, out_exr, report):
    run([exe, scene, "-o", out_exr, "--threads", str(threads), "--quiet", "--report", report])
    with open(report) as f:
        return json.load(f)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--exe", default=os.path.join(REPO, "build", "pathtracer"))
    ap.add_argument("--scene", default=DEFAULT_SCENE)
    ap.add_argument("--threads", type=int, nargs="+", default=[1, 2])
    ap.add_argument("--runs", type=int, default=5)
    ap.add_argument("--json", default=os.path.join(REPO, "docs", "bench", "foundation.json"))
    ap.add_argument("--markdown", default=os.path.join(REPO, "docs", "bench", "foundation.md"))
    args = ap.parse_args()

    scene = os.path.abspath(args.scene)
    if not os.path.exists(scene):
        print(f"bench_foundation: scene not found: {scene} (is ../shared beside the checkout?)")
        return 0
    if not os.path.exists(args.exe):
        print(f"bench_foundation: {args.exe} not found; build first (tools/setup.sh)")
        return 1

    results = {}
    images = {}
    with tempfile.TemporaryDirectory() as tmp:
        for t in args.threads:
            samples = []
            for r in range(args.runs):
                exr = os.path.join(tmp, f"t{t}.exr")
                samples.append(one_run(args.exe, scene, t, exr, os.path.join(tmp, f"t{t}_{r}.json")))
            images[t] = exr
            med = {p: statistics.median(s["timings"][p] for s in samples) for p in PHASES}
            mn = {p: min(s["timings"][p] for s in samples) for p in PHASES}
            results[t] = {"median_seconds": med, "min_seconds": mn, "runs": args.runs,
                          "accel": samples[0]["accel"], "image": samples[0]["image"]}
        # The renders are deterministic: every thread count must give the same image.
        base = images[args.threads[0]]
        identical = {}
        for t in args.threads[1:]:
            identical[t] = subprocess.run(["idiff", "-q", "-fail", "0", "-warn", "0", base, images[t]],
                                          capture_output=True).returncode == 0

    first = results[args.threads[0]]
    record = {
        "scene": os.path.relpath(scene, REPO),
        "image": first["image"],
        "accel": first["accel"],
        "threads": {str(t): results[t] for t in args.threads},
        "identical_to_first_thread_count": {str(t): v for t, v in identical.items()},
        "machine": lscpu(),
    }
    os.makedirs(os.path.dirname(args.json), exist_ok=True)
    with open(args.json, "w") as f:
        json.dump(record, f, indent=2)

    lines = [f"# Foundation timings: `{record['scene']}`", "",
             f"Image {first['image']['width']}x{first['image']['height']}, "
             f"{first['image']['spp']} spp, integrator `{first['image']['integrator']}`, "
             f"backend {first['accel']['backend']}, {first['accel']['primitive_count']} primitives.",
             f"Median of {args.runs} runs per thread count (minimum in brackets), seconds.", "",
             "| phase | " + " | ".join(f"{t} thread{'s' if t > 1 else ''}" for t in args.threads) + " |",
             "|---|" + "---|" * len(args.threads)]
    for p in PHASES:
        row = " | ".join(f"{results[t]['median_seconds'][p]:.4f} ({results[t]['min_seconds'][p]:.4f})"
                         for t in args.threads)
        lines.append(f"| {p} | {row} |")
    t0 = args.threads[0]
    for t in args.threads[1:]:
        sp = results[t0]["median_seconds"]["render"] / max(results[t]["median_seconds"]["render"], 1e-9)
        lines.append("")
        lines.append(f"Render speed-up {t} threads vs {t0}: {sp:.2f}x (ratio of medians, same run). "
                     f"Images identical to the {t0}-thread image: {'yes' if identical[t] else 'NO'}.")
    lines += ["", "Error: the classic integrator is deterministic at 1 spp (pixel centres); the "
              "figures are for the exact image, checked bit-identical across thread counts.", "",
              "Machine (`lscpu`):", "", "```", record["machine"].strip(), "```", ""]
    with open(args.markdown, "w") as f:
        f.write("\n".join(lines))
    print("\n".join(lines[:12 + len(PHASES)]))
    print(f"wrote {args.json} and {args.markdown}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
