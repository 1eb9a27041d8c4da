#!/usr/bin/env python3
"""Compares the path integrator's samplers on one scene (docs/samplers.md).

Renders a reference (random sampler, --ref-spp), then each sampler at each
--spp with several seeds, and measures with pt-imgerr the MSE against the
reference, and the render time (from --report). Writes docs/bench/samplers.md
and .json with the machine description (lscpu). All figures come from one run.

  python3 tools/study/compare_samplers/compare_samplers.py --build build [--scene scenes/cornell-box.json]
      [--width 160] [--spp 4 16 64] [--ref-spp 4096] [--seeds 3] [--out docs/bench/samplers]
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "pylib"))
from pt_tools import image_error, lscpu  # noqa: E402


def run(cmd):
    return subprocess.run(cmd, check=True, capture_output=True, text=True)


def render(args, tmp, name, sampler, spp, seed):
    image = os.path.join(tmp, name + ".exr")
    report = os.path.join(tmp, name + ".json")
    run([os.path.join(args.build, "pathtracer"), args.scene, "-o", image, "--integrator", "path",
         "--width", str(args.width), "--spp", str(spp), "--seed", str(seed), "--sampler", sampler,
         "--report", report])
    with open(report) as f:
        record = json.load(f)
    seconds = record["timings"]["render"]
    return image, seconds


def imgerr(args, test, reference):
    return image_error(os.path.join(args.build, "tools", "imgerr", "pt-imgerr"), test, reference)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--build", default="build")
    parser.add_argument("--scene", default="scenes/cornell-box.json")
    parser.add_argument("--width", type=int, default=160)
    parser.add_argument("--spp", type=int, nargs="+", default=[4, 16, 64])
    parser.add_argument("--ref-spp", type=int, default=4096)
    parser.add_argument("--seeds", type=int, default=3)
    parser.add_argument("--out", default="docs/bench/samplers")
    args = parser.parse_args()

    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        reference, ref_seconds = render(args, tmp, "reference", "random", args.ref_spp, 1000)
        for spp in args.spp:
            for sampler in ["random", "jittered", "sobol"]:
                mse, rel, secs = [], [], []
                for seed in range(args.seeds):
                    image, seconds = render(args, tmp, f"{sampler}_{spp}_{seed}", sampler, spp, seed)
                    e = imgerr(args, image, reference)
                    mse.append(e["mse"])
                    rel.append(e["rel_mse"])
                    secs.append(seconds)
                rows.append({"sampler": sampler, "spp": spp, "mse": sum(mse) / len(mse),
                             "rel_mse": sum(rel) / len(rel), "mse_per_seed": mse,
                             "render_seconds": secs})
                print(f"{sampler:9s} {spp:5d} spp  MSE {rows[-1]['mse']:.4g}  relMSE {rows[-1]['rel_mse']:.4g}",
                      file=sys.stderr)
    record = {"scene": args.scene, "width": args.width, "reference_spp": args.ref_spp,
              "reference_seconds": ref_seconds, "seeds": args.seeds, "rows": rows, "machine": lscpu()}
    os.makedirs(os.path.dirname(args.out) or ".", exist_ok=True)
    with open(args.out + ".json", "w") as f:
        json.dump(record, f, indent=2)
    lines = ["# Samplers compared", "",
             f"`python3 tools/study/compare_samplers/compare_samplers.py` on `{args.scene}`, width {args.width}, "
             f"reference: random sampler at {args.ref_spp} spp (its own noise is included in every MSE). "
             f"Mean over {args.seeds} seeds; MSE and relMSE as in docs/samplers.md; ratios to random at equal spp.",
             "", "| spp | sampler | MSE | relMSE | MSE / random | render s (median) |", "|---|---|---|---|---|---|"]
    for row in rows:
        base = next(r for r in rows if r["spp"] == row["spp"] and r["sampler"] == "random")
        secs = sorted(row["render_seconds"])
        med = f"{secs[len(secs) // 2]:.3f}" if secs else "n/a"
        lines.append(f"| {row['spp']} | {row['sampler']} | {row['mse']:.4g} | {row['rel_mse']:.4g} | "
                     f"{row['mse'] / base['mse']:.3f} | {med} |")
    lines += ["", "Machine (`lscpu`):", "", "```", record["machine"].strip(), "```", ""]
    with open(args.out + ".md", "w") as f:
        f.write("\n".join(lines))
    return 0


if __name__ == "__main__":
    sys.exit(main())
