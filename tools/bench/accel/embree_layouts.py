#!/usr/bin/env python3
"""Embree's triangle layouts side by side: rays per second of the --accel=embree
backend under each Embree device configuration (PT_EMBREE_CONFIG, read by
src/accel/embree/embree_device.cpp), against bare Embree with the default
configuration measured in the same round (issue 18: the memory of the build
against Embree's ray speed; docs/bench/scale.md).

Each round runs bench_accel once per variant, the variants back to back; the
ratio of a round is the variant's --accel=embree rays per second over the
first variant's bare-Embree rays per second in that round (so the first
variant, the default, gives the backend's own overhead). Medians and ranges
over the rounds; CPU-time clock (a shared machine).

  python3 tools/bench/accel/embree_layouts.py [--build build] [--rounds 3] [--scenes bunny,sponza]
          [--threads 2] [--variant LABEL CONFIG]... [--json FILE]
  (default variants: default "", 8i "tri_accel=bvh8.triangle4i", 4i "tri_accel=bvh4.triangle4i")

Speed only: Embree 3.13 pairs the tri_accel=...triangle4i layouts with its fast,
non-robust triangle test (Embree.ClosedMeshesDoNotLeakThroughEdges fails with
them; docs/geometry.md), so their rays per second are not the robust layout's.
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))
KINDS = ("camera", "shadow", "diffuse")


def run(a, config, out):
    env = dict(os.environ)
    env.pop("PT_EMBREE_CONFIG", None)
    if config:
        env["PT_EMBREE_CONFIG"] = config
    cmd = [os.path.join(a.build, "tools", "bench", "accel", "bench_accel"), "--scenes", a.scenes, "--quick",
           "--clock", "cpu", "--threads", str(a.threads), "--json", out]
    p = subprocess.run(cmd, env=env, capture_output=True, text=True)
    if p.returncode != 0:
        sys.exit(f"bench_accel failed ({config}):\n{p.stderr}")
    with open(out) as f:
        j = json.load(f)
    rates = {}
    for s in j["scenes"]:
        run_all = max(s["runs"], key=lambda r: r["threads"])  # the all-threads run
        for k in KINDS:
            rates[(s["name"], k, "bare")] = run_all["embree_reference"][f"{k}_mrays_per_s"]["median"]
            rates[(s["name"], k, "backend")] = run_all["embree_backend"][f"{k}_mrays_per_s"]["median"]
    return rates, j.get("load_average")


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--build", default=os.path.join(REPO, "build"))
    p.add_argument("--rounds", type=int, default=3)
    p.add_argument("--scenes", default="bunny,sponza")
    p.add_argument("--threads", type=int, default=2)
    p.add_argument("--variant", action="append", nargs=2, metavar=("LABEL", "CONFIG"))
    p.add_argument("--json")
    a = p.parse_args()
    variants = a.variant or [("default", ""), ("8i", "tri_accel=bvh8.triangle4i"), ("4i", "tri_accel=bvh4.triangle4i")]
    ratios = {}
    loads = []
    with tempfile.TemporaryDirectory() as work:
        for _ in range(a.rounds):
            base = None
            for label, config in variants:
                rates, load = run(a, config, os.path.join(work, "run.json"))
                loads.append(load)
                base = base or rates
                for (scene, kind, which), v in rates.items():
                    if which == "backend":
                        ratios.setdefault((label, scene, kind), []).append(v / base[(scene, kind, "bare")])
                print(f"{label}: " + ", ".join(f"{s} {k} {v:.2f}" for (s, k, w), v in rates.items() if w == "backend"),
                      flush=True)
    scenes = a.scenes.split(",")
    first, last = loads[0] or {}, loads[-1] or {}
    out = [f"{a.rounds} rounds, the variants back to back, {a.threads} threads, CPU clock; load average "
           f"{first.get('before', '?')} at the start, {last.get('after', '?')} at the end", "",
           "| variant (PT_EMBREE_CONFIG) | " + " | ".join(f"{s} {k}" for s in scenes for k in KINDS) + " |",
           "|---|" + "---|" * (len(scenes) * len(KINDS))]
    for label, config in variants:
        cells = []
        for s in scenes:
            for k in KINDS:
                r = ratios[(label, s, k)]
                cells.append(f"{statistics.median(r):.2f} ({min(r):.2f}-{max(r):.2f})")
        out.append(f"| {label} (`{config or 'none'}`) | " + " | ".join(cells) + " |")
    print("\n".join(out))
    if a.json:
        with open(a.json, "w") as f:
            json.dump({"command": " ".join(sys.argv), "variants": variants, "load_average": loads,
                       "ratios": {"|".join(k): v for k, v in ratios.items()}, "table": out}, f, indent=2)


if __name__ == "__main__":
    main()
