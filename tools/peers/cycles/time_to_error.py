#!/usr/bin/env python3
"""Time to a target error, our renderer against Blender's Cycles, in one interleaved run.

    python3 tools/peers/cycles/time_to_error.py SCENE.json --reference REF.exr [--width W --height H]
        [--target 0.01] [--seeds 3] [--threads 2] [--min-spp 4] [--max-spp 4096] [--ref-spp 16384]
        [--md docs/bench/peers.md] [--json docs/bench/peers.json]

1. The reference: if REF.exr does not exist, our renderer renders the scene once at --ref-spp (a
   small EXR meant to be committed beside the scene) and later runs reuse it. Both renderers are
   measured against the same reference, so a bias of either against it is an error floor that
   the table shows (the RMSE at the largest spp rendered).
2. For spp = min-spp, 2 min-spp, ... each seed renders with ours (`--report`: its `timings.render`,
   the render phase alone, and `timings.total`) and then with Cycles (tools/peers/cycles/
   scene_to_cycles.py: its path tracing time from Cycles' own progress timer, and the time around
   bpy.ops.render.render, which adds scene sync, BVH and light-distribution building), alternating
   renderer and seed so that a change of the machine's load hits both. The RMSE of each image
   against the reference is pt-imgerr's (docs/samplers.md). A renderer stops when every seed has
   reached the target.
3. Time to the target, per seed: interpolated log-log between the last spp above the target and the
   first at or below it (RMSE and time are both close to power laws in spp); the table gives the
   median over seeds and the spread (min-max), and the ratio ours / Cycles of the medians.
4. The load average (1 minute) is sampled before every render; its min, median and max go in the
   table with `lscpu`.

Both renderers get the same scene at the same size (a copy written with --width/--height), the same
threads and the bounce cap of the scene (scene_to_cycles.py maps it); Cycles gets seed s + 1 where
ours gets s (a Cycles seed of 0 is fine too; they just differ per run).
"""
import argparse
import json
import math
import os
import statistics
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.normpath(os.path.join(HERE, "..", "..", ".."))
sys.path.insert(0, os.path.join(REPO, "tools", "pylib"))
import pt_tools  # noqa: E402

CONVERTER = os.path.join(HERE, "scene_to_cycles.py")


def sized_scene(scene_path, width, height):
    """A copy of the scene at the given size, written beside the original (relative paths keep working)."""
    scene = json.load(open(scene_path))
    if width:
        scene.setdefault("film", {})["width"] = width
    if height:
        scene.setdefault("film", {})["height"] = height
    fd, path = tempfile.mkstemp(suffix=".json", prefix=".tte-", dir=os.path.dirname(os.path.abspath(scene_path)))
    with os.fdopen(fd, "w") as f:
        json.dump(scene, f)
    return path


def run_ours(exe, scene, spp, seed, threads, out):
    report = out + ".report.json"
    cmd = ["nice", "-n", "10", exe, scene, "-o", out, "--spp", str(spp), "--seed", str(seed), "--threads",
           str(threads), "--quiet", "--report", report]
    subprocess.run(cmd, check=True, capture_output=True, text=True)
    r = json.load(open(report))
    return {"render": r["timings"]["render"], "total": r["timings"]["total"]}


def run_cycles(blender, scene, spp, seed, threads, out):
    stats = out + ".stats.json"
    cmd = ["nice", "-n", "10", blender, "-b", "--factory-startup", "--python", CONVERTER, "--", scene,
           "--spp", str(spp), "--seed", str(seed), "--threads", str(threads), "-o", out, "--stats", stats]
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:
        raise RuntimeError(f"Cycles failed ({p.returncode}):\n{p.stderr[-3000:]}")
    s = json.load(open(stats))
    return {"render": s["path_tracing_seconds"], "total": s["render_seconds"]}


def time_at_target(points, target, key):
    """Interpolated time (log-log) at which the RMSE reaches `target`; None if never reached."""
    points = sorted(points, key=lambda p: p["spp"])
    for prev, cur in zip([None] + points[:-1], points):
        if cur["rmse"] <= target:
            if prev is None or prev["rmse"] <= target or prev[key] <= 0 or cur[key] <= 0:
                return cur[key]
            f = math.log(prev["rmse"] / target) / math.log(prev["rmse"] / cur["rmse"])
            return math.exp(math.log(prev[key]) + f * (math.log(cur[key]) - math.log(prev[key])))
    return None


def median_spread(values):
    v = [x for x in values if x is not None]
    if len(v) < len(values) or not v:
        return None, None, None
    return statistics.median(v), min(v), max(v)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("scene")
    p.add_argument("--reference", required=True)
    p.add_argument("--width", type=int)
    p.add_argument("--height", type=int)
    p.add_argument("--target", type=float, default=0.01)
    p.add_argument("--seeds", type=int, default=3)
    p.add_argument("--threads", type=int, default=2)
    p.add_argument("--min-spp", type=int, default=4)
    p.add_argument("--max-spp", type=int, default=4096)
    p.add_argument("--ref-spp", type=int, default=16384)
    p.add_argument("--exe", default=os.path.join(REPO, "build", "pathtracer"))
    p.add_argument("--imgerr", default=os.path.join(REPO, "build", "tools", "imgerr", "pt-imgerr"))
    p.add_argument("--blender", default="blender")
    p.add_argument("--md", default=os.path.join(REPO, "docs", "bench", "peers.md"))
    p.add_argument("--json", default=os.path.join(REPO, "docs", "bench", "peers.json"))
    p.add_argument("--rewrite", action="store_true",
                   help="render nothing: rewrite --md from the runs recorded in --json (same other arguments)")
    a = p.parse_args()
    if a.rewrite:
        rec = json.load(open(a.json))
        write_results(a, rec["runs"], rec["loads"])
        return 0

    scene = sized_scene(a.scene, a.width, a.height)
    work = tempfile.mkdtemp(prefix="pt-tte-")
    loads = []
    try:
        if not os.path.exists(a.reference):
            print(f"reference: ours at {a.ref_spp} spp -> {a.reference}", file=sys.stderr)
            t = run_ours(a.exe, scene, a.ref_spp, 1000, a.threads, a.reference)
            os.unlink(a.reference + ".report.json")
            print(f"  {t['render']:.1f} s", file=sys.stderr)
        runs = {"ours": [], "cycles": []}
        done = {"ours": False, "cycles": False}
        spp = a.min_spp
        while spp <= a.max_spp and not all(done.values()):
            for seed in range(a.seeds):
                for name in ("ours", "cycles") if seed % 2 == 0 else ("cycles", "ours"):
                    if done[name]:
                        continue
                    loads.append(os.getloadavg()[0])
                    out = os.path.join(work, f"{name}-{spp}-{seed}.exr")
                    if name == "ours":
                        t = run_ours(a.exe, scene, spp, seed, a.threads, out)
                    else:
                        t = run_cycles(a.blender, scene, spp, seed + 1, a.threads, out)
                    err = pt_tools.image_error(a.imgerr, out, a.reference)
                    runs[name].append({"spp": spp, "seed": seed, "rmse": err["rmse"], **t})
                    print(f"{name:6} spp {spp:5d} seed {seed}: RMSE {err['rmse']:.5f}, render {t['render']:.3f} s, "
                          f"total {t['total']:.3f} s, load {loads[-1]:.2f}", file=sys.stderr)
            for name in done:
                last = [r for r in runs[name] if r["spp"] == spp]
                if last and all(r["rmse"] <= a.target for r in last):
                    done[name] = True
            spp *= 2
    finally:
        os.unlink(scene)
    write_results(a, runs, loads)
    return 0


def summarise(a, runs):
    out = {}
    for name, rs in runs.items():
        per_seed = {}
        for key in ("render", "total"):
            per_seed[key] = [time_at_target([r for r in rs if r["seed"] == s], a.target, key) for s in range(a.seeds)]
        out[name] = {key: median_spread(v) for key, v in per_seed.items()}
        out[name]["per_seed"] = per_seed
        top = max(r["spp"] for r in rs)
        out[name]["floor"] = statistics.median(r["rmse"] for r in rs if r["spp"] == top), top
        out[name]["spp_per_s"] = statistics.median(r["spp"] / r["render"] for r in rs if r["render"] > 0)
    return out


def write_results(a, runs, loads):
    s = summarise(a, runs)
    fmt = lambda m: "not reached" if m[0] is None else f"{m[0]:.2f} s ({m[1]:.2f}–{m[2]:.2f})"
    ratio = lambda key: ("—" if s["ours"][key][0] is None or s["cycles"][key][0] is None
                         else f"{s['ours'][key][0] / s['cycles'][key][0]:.2f}×")
    ref = os.path.relpath(a.reference, REPO)
    scene = os.path.relpath(a.scene, REPO)
    size = f"{a.width}×{a.height}" if a.width else "the scene's size"
    lines = [
        "# Peers: time to a target error against Blender's Cycles", "",
        "Written by `tools/peers/cycles/time_to_error.py` (how it measures: its docstring and "
        "`tools/peers/cycles/README.md`).", "",
        "**Preliminary.** The machine is shared by several engineers and was loaded during the run "
        f"(1-minute load average sampled before each render: min {min(loads):.2f}, median "
        f"{statistics.median(loads):.2f}, max {max(loads):.2f}, on {os.cpu_count()} hardware threads). "
        "Renders are interleaved (ours and Cycles alternate, seed by seed) so the load hits both alike, "
        "but the absolute times are inflated and the ratios are noisy; rerun on a quiet machine before "
        "quoting them.", "",
        f"## {scene}", "",
        f"{size}, {a.threads} threads each, target RMSE {a.target} against `{ref}` (ours at {a.ref_spp} spp), "
        f"{a.seeds} seeds, spp doubling from {a.min_spp}. Median time to the target over the seeds "
        "(min–max), interpolated log-log between the two spp counts around it.", "",
        "Caveats: the reference is ours, so a bias of Cycles against ours shows as Cycles' error floor "
        "(last row), and every RMSE includes the reference's own noise (the same for both renderers). "
        "Cycles gets a sphere of refracting or emitting material as a 256 × 128 UV-sphere mesh "
        "(`tools/peers/cycles/README.md`: it finds no exit from inside its exact point spheres), so its "
        "total time includes that mesh's BVH and its path tracing intersects triangles where ours "
        "intersects an analytic sphere. Samplers: ours `sobol` (the default), Cycles its default "
        "progressive multi-jitter. Render time is what each renderer's own timer reports; Blender's "
        "start-up (about a second) is in neither column.", "",
        "| | ours | Cycles 3.4 | ours / Cycles |", "|---|---|---|---|",
        f"| render time (ours: `timings.render`; Cycles: path tracing, its progress timer) | {fmt(s['ours']['render'])} | "
        f"{fmt(s['cycles']['render'])} | {ratio('render')} |",
        f"| total (ours: `timings.total`; Cycles: around `bpy.ops.render.render`, incl. sync and BVH) | "
        f"{fmt(s['ours']['total'])} | {fmt(s['cycles']['total'])} | {ratio('total')} |",
        f"| samples per pixel per second of render time (median over runs) | {s['ours']['spp_per_s']:.1f} | "
        f"{s['cycles']['spp_per_s']:.1f} | {s['ours']['spp_per_s'] / s['cycles']['spp_per_s']:.2f}× |",
        f"| RMSE at the largest spp rendered (error floor against the reference) | {s['ours']['floor'][0]:.5f} at "
        f"{s['ours']['floor'][1]} spp | {s['cycles']['floor'][0]:.5f} at {s['cycles']['floor'][1]} spp | |", "",
        "Every run (spp, seed, RMSE, render and total seconds):", "",
        "| renderer | spp | seed | RMSE | render s | total s |", "|---|---|---|---|---|---|"]
    for name in ("ours", "cycles"):
        for r in runs[name]:
            lines.append(f"| {name} | {r['spp']} | {r['seed']} | {r['rmse']:.5f} | {r['render']:.3f} | {r['total']:.3f} |")
    lines += ["", "## Machine", "", "```", pt_tools.lscpu().strip(), "```", ""]
    os.makedirs(os.path.dirname(a.md), exist_ok=True)
    with open(a.md, "w") as f:
        f.write("\n".join(lines))
    with open(a.json, "w") as f:
        json.dump({"scene": scene, "reference": ref, "target": a.target, "threads": a.threads, "size": size,
                   "loads": loads, "runs": runs, "summary": s}, f, indent=1)
    print("\n".join(lines[:20]))


if __name__ == "__main__":
    sys.exit(main())
