#!/usr/bin/env python3
"""Time to a target error, our renderer against Blender's Cycles, in one interleaved run.

    python3 tools/peers/cycles/time_to_error.py SCENE.json --reference REF.exr [--width W --height H]
        [--target 0.01] [--seeds 3] [--threads 2] [--min-spp 4] [--max-spp 4096] [--ref-spp 16384]
        [--cycles-ref-spp N] [--name NAME] [--md docs/bench/peers.md] [--json docs/bench/peers/NAME.json]

1. The reference: if REF.exr does not exist, it is made once (a small EXR meant to be committed
   beside the scene) and later runs reuse it. With --cycles-ref-spp N it is the mean of two
   converged renders, ours at --ref-spp (REF-ours.exr) and Cycles' at N (REF-cycles.exr), each kept
   (and reused if present): independent of either renderer, and the RMSE between the two (their
   noise and any bias of one against the other) is recorded; the mean's own error is about half of
   it. Without, ours alone at --ref-spp. Both renderers are measured against the same reference, so
   a bias of either against it is an error floor that the table shows (the RMSE at the largest spp).
2. For spp = min-spp, 2 min-spp, ... each seed renders with ours (`--report`: its `timings.render`,
   the render phase alone, and `timings.total`) and then with Cycles (tools/peers/cycles/
   scene_to_cycles.py: its path tracing time from Cycles' own progress timer, and the time around
   bpy.ops.render.render, which adds scene sync, BVH and light-distribution building), alternating
   renderer and seed so that a change of the machine's load hits both. The RMSE of each image
   against the reference is pt-imgerr's (docs/samplers.md). A renderer stops when every seed has
   reached the target.
3. Time to the target, per seed: interpolated log-log between the last spp above the target and the
   first at or below it (RMSE and time are both close to power laws in spp); the table gives the
   median over seeds and the spread (min-max), and the ratio ours / Cycles of the medians. With
   --extrapolate (where the machine cannot afford the spp the target needs), a seed that never
   reaches it gets the time of its largest spp times (RMSE / target)^2, which the table says.
4. The load average (1 minute) is sampled before every render; its min, median and max go in the
   table with `lscpu`.
5. Each scene's runs are kept in docs/bench/peers/NAME.json (NAME: the scene file's stem); the
   Markdown file gets one section per JSON file there, so that scenes measured in separate
   invocations share one page.
6. With --cpu-time, CPU seconds too, the measure to read when the machine is loaded (wall time then
   depends on what else runs; CPU time much less): ours, `performance.render_cpu_seconds` of the
   run record (the render phase); Cycles, which reports no CPU time, the user + system seconds of
   its process (os.wait4) less its fixed part, the median of three 1-spp renders of the same
   scene made first (Blender's start, the converter, scene sync, BVH, writing). Both processes'
   whole CPU seconds are kept as well.

Both renderers get the same scene at the same size (--width/--height passed to both: ours takes them
on its command line, scene_to_cycles.py as its own --width/--height; no copy of the scene is written
anywhere, so nothing appears beside it for a concurrent build to pick up), the same
threads and the bounce cap of the scene (scene_to_cycles.py maps it); Cycles gets seed s + 1 where
ours gets s (a Cycles seed of 0 is fine too; they just differ per run).
"""
import argparse
import json
import math
import os
import re
import shutil
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


def size_args(a):
    """The film size asked for, as arguments that both pathtracer and scene_to_cycles.py take."""
    return (["--width", str(a.width)] if a.width else []) + (["--height", str(a.height)] if a.height else [])


def run_timed(cmd):
    """Runs cmd; returns (exit status, stderr, CPU seconds (user + system) of the process and its children)."""
    with tempfile.TemporaryFile() as err:
        p = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=err)
        _, status, usage = os.wait4(p.pid, 0)
        p.returncode = os.waitstatus_to_exitcode(status)
        err.seek(0)
        return p.returncode, err.read().decode(errors="replace"), usage.ru_utime + usage.ru_stime


def run_ours(exe, scene, spp, seed, threads, out):
    """scene: [the scene file, more arguments (size_args)]."""
    report = out + ".report.json"
    cmd = ["nice", "-n", "10", exe, *scene, "-o", out, "--spp", str(spp), "--seed", str(seed), "--threads",
           str(threads), "--quiet", "--report", report]
    code, err, cpu = run_timed(cmd)
    if code != 0:
        raise RuntimeError(f"ours failed ({code}):\n{err[-3000:]}")
    r = json.load(open(report))
    return {"render": r["timings"]["render"], "total": r["timings"]["total"],
            "cpu": r["performance"]["render_cpu_seconds"], "cpu_total": cpu}


def run_cycles(blender, scene, spp, seed, threads, out):
    """scene: as run_ours'."""
    stats = out + ".stats.json"
    cmd = ["nice", "-n", "10", blender, "-b", "--factory-startup", "--python", CONVERTER, "--", *scene,
           "--spp", str(spp), "--seed", str(seed), "--threads", str(threads), "-o", out, "--stats", stats]
    code, err, cpu = run_timed(cmd)
    if code != 0:
        raise RuntimeError(f"Cycles failed ({code}):\n{err[-3000:]}")
    s = json.load(open(stats))
    return {"render": s["path_tracing_seconds"], "total": s["render_seconds"], "cpu_total": cpu}


def cycles_overhead(a, scene, work):
    """Cycles' CPU seconds for everything but path tracing (Blender's start, our converter, sync, BVH,
    writing): the median of three 1-spp renders of the scene (their 64x64 samples cost next to nothing)."""
    cpus = [run_cycles(a.blender, scene, 1, 1000 + i, a.threads, os.path.join(work, f"overhead-{i}.exr"))["cpu_total"]
            for i in range(3)]
    return statistics.median(cpus)


def image_mean(path):
    """The mean R, G, B of an EXR (oiiotool --stats)."""
    out = subprocess.run(["oiiotool", "--stats", path], capture_output=True, text=True, check=True).stdout
    line = next(l for l in out.splitlines() if "Stats Avg:" in l)
    return [float(x) for x in line.split(":")[1].split()[:3]]


def make_reference(a, scene):
    """Makes a.reference if missing (see the docstring, 1.) and returns what is known of it: for a
    reference that exists, what the scene's record (--json) says of that file, if it names it (the
    flags of this run may not be those that made it)."""
    if os.path.exists(a.reference) and os.path.exists(a.json):
        rec = json.load(open(a.json))
        if rec.get("reference") == os.path.relpath(a.reference, REPO) and "reference_info" in rec:
            return rec["reference_info"]
    base = os.path.splitext(a.reference)[0]
    ours, cycles = base + "-ours.exr", base + "-cycles.exr"
    info = {"kind": "ours", "ours_spp": a.ref_spp}
    os.makedirs(os.path.dirname(os.path.abspath(a.reference)), exist_ok=True)
    if not a.cycles_ref_spp:
        if not os.path.exists(a.reference):
            print(f"reference: ours at {a.ref_spp} spp -> {a.reference}", file=sys.stderr)
            run_ours(a.exe, scene, a.ref_spp, 1000, a.threads, a.reference)
            os.unlink(a.reference + ".report.json")
        return info
    if not os.path.exists(ours):
        print(f"reference: ours at {a.ref_spp} spp -> {ours}", file=sys.stderr)
        run_ours(a.exe, scene, a.ref_spp, 1000, a.threads, ours)
        os.unlink(ours + ".report.json")
    if not os.path.exists(cycles):
        print(f"reference: Cycles at {a.cycles_ref_spp} spp -> {cycles}", file=sys.stderr)
        run_cycles(a.blender, scene, a.cycles_ref_spp, 1000, a.threads, cycles)
        os.unlink(cycles + ".stats.json")
    if not os.path.exists(a.reference):
        subprocess.run(["oiiotool", ours, cycles, "--add", "--mulc", "0.5", "-d", "float", "-o", a.reference],
                       check=True)
    d = pt_tools.image_error(a.imgerr, ours, cycles)["rmse"]
    info = {"kind": "mean", "ours_spp": a.ref_spp, "cycles_spp": a.cycles_ref_spp, "rmse_between": d,
            "mean_ours": image_mean(ours), "mean_cycles": image_mean(cycles)}
    print(f"reference: RMSE between ours and Cycles' {d:.5f}; means {info['mean_ours']} / {info['mean_cycles']}",
          file=sys.stderr)
    return info


LOG_LINE = re.compile(r"^(ours|cycles) +spp +(\d+) seed (\d+): RMSE ([0-9.]+), render ([0-9.]+) s, "
                      r"total ([0-9.]+) s, load ([0-9.]+)$")


def read_log(path):
    """The runs and loads of the progress lines main() prints."""
    runs, loads = {"ours": [], "cycles": []}, []
    for line in open(path):
        m = LOG_LINE.match(line.strip())
        if m:
            runs[m.group(1)].append({"spp": int(m.group(2)), "seed": int(m.group(3)), "rmse": float(m.group(4)),
                                     "render": float(m.group(5)), "total": float(m.group(6))})
            loads.append(float(m.group(7)))
    return runs, loads


def reference_from_log(path, a):
    """What make_reference() printed about a mean reference, else ours alone."""
    for line in open(path):
        m = re.match(r"reference: RMSE between ours and Cycles' ([0-9.]+); means \[(.*)\] / \[(.*)\]", line)
        if m:
            return {"kind": "mean", "ours_spp": a.ref_spp, "cycles_spp": a.cycles_ref_spp,
                    "rmse_between": float(m.group(1)), "mean_ours": [float(x) for x in m.group(2).split(",")],
                    "mean_cycles": [float(x) for x in m.group(3).split(",")]}
    return {"kind": "ours", "ours_spp": a.ref_spp}


def time_at_target(points, target, key, extrapolate=False):
    """Interpolated time (log-log) at which the RMSE reaches `target`. If it is never reached:
    None, or with `extrapolate` the time of the largest spp rendered scaled by (RMSE / target)^2
    (MSE falling as 1 / spp, time growing as spp)."""
    points = sorted(points, key=lambda p: p["spp"])
    if extrapolate and points and all(p["rmse"] > target for p in points):
        return points[-1][key] * (points[-1]["rmse"] / target) ** 2
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
    p.add_argument("--cycles-ref-spp", type=int, default=0,
                   help="make the reference the mean of ours (--ref-spp) and Cycles' at this spp (see 1.)")
    p.add_argument("--extrapolate", action="store_true",
                   help="a seed that never reaches the target within --max-spp: extrapolate its time (see 3.)")
    p.add_argument("--from-log", metavar="LOG",
                   help="render nothing: write the record from the progress lines of a run cut short (its "
                        "stderr), extrapolating where the target was not reached")
    p.add_argument("--references-only", action="store_true", help="make the reference (1.) and stop")
    p.add_argument("--cpu-time", action="store_true",
                   help="also record CPU seconds (see 6.): the measure to read on a loaded machine")
    p.add_argument("--name", help="the scene's record: docs/bench/peers/NAME.json (default: the scene's stem)")
    p.add_argument("--exe", default=os.path.join(REPO, "build", "pathtracer"))
    p.add_argument("--imgerr", default=os.path.join(REPO, "build", "tools", "imgerr", "pt-imgerr"))
    p.add_argument("--blender", default="blender")
    p.add_argument("--md", default=os.path.join(REPO, "docs", "bench", "peers.md"))
    p.add_argument("--json", help="this scene's record (default docs/bench/peers/NAME.json)")
    p.add_argument("--rewrite", action="store_true",
                   help="render nothing: rewrite --md from the runs recorded in --json (same other arguments)")
    a = p.parse_args()
    a.name = a.name or os.path.splitext(os.path.basename(a.scene))[0]
    a.json = a.json or os.path.join(REPO, "docs", "bench", "peers", a.name + ".json")
    if a.rewrite:
        write_markdown(a.md, os.path.dirname(a.json))
        return 0
    if a.from_log:
        runs, loads = read_log(a.from_log)
        a.extrapolate = True
        write_record(a, runs, loads, reference_from_log(a.from_log, a))
        write_markdown(a.md, os.path.dirname(a.json))
        return 0

    scene = [a.scene] + size_args(a)
    work = tempfile.mkdtemp(prefix="pt-tte-")
    loads = []
    try:
        reference = make_reference(a, scene)
        if a.references_only:
            return 0
        runs = {"ours": [], "cycles": []}
        overhead = cycles_overhead(a, scene, work) if a.cpu_time else None
        if overhead is not None:
            print(f"Cycles' CPU overhead (1 spp, median of 3): {overhead:.3f} s", file=sys.stderr)
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
                        if overhead is not None:
                            t["cpu"] = max(0.0, t["cpu_total"] - overhead)
                    err = pt_tools.image_error(a.imgerr, out, a.reference)
                    runs[name].append({"spp": spp, "seed": seed, "rmse": err["rmse"], **t})
                    cpu = f", cpu {t['cpu']:.3f} s, cpu_total {t['cpu_total']:.3f} s" if "cpu" in t else ""
                    print(f"{name:6} spp {spp:5d} seed {seed}: RMSE {err['rmse']:.5f}, render {t['render']:.3f} s, "
                          f"total {t['total']:.3f} s, load {loads[-1]:.2f}{cpu}", file=sys.stderr)
            for name in done:
                last = [r for r in runs[name] if r["spp"] == spp]
                if last and all(r["rmse"] <= a.target for r in last):
                    done[name] = True
            spp *= 2
    finally:
        shutil.rmtree(work, ignore_errors=True)
    write_record(a, runs, loads, reference, overhead)
    write_markdown(a.md, os.path.dirname(a.json))
    return 0


def summarise(target, seeds, runs, extrapolate=False):
    out = {}
    for name, rs in runs.items():
        per_seed = {}
        for key in ("render", "total") + (("cpu", "cpu_total") if all("cpu" in r for r in rs) else ()):
            per_seed[key] = [time_at_target([r for r in rs if r["seed"] == s], target, key, extrapolate)
                             for s in range(seeds)]
        out[name] = {key: median_spread(v) for key, v in per_seed.items()}
        out[name]["per_seed"] = per_seed
        # seeds whose time is extrapolated (never reached the target)
        out[name]["extrapolated"] = sum(all(r["rmse"] > target for r in rs if r["seed"] == s) for s in range(seeds))
        top = max(r["spp"] for r in rs)
        out[name]["floor"] = statistics.median(r["rmse"] for r in rs if r["spp"] == top), top
        out[name]["spp_per_s"] = statistics.median(r["spp"] / r["render"] for r in rs if r["render"] > 0)
    return out


def write_record(a, runs, loads, reference, overhead=None):
    film = json.load(open(a.scene)).get("film", {})
    size = f"{a.width or film.get('width')}×{a.height or film.get('height')}"
    os.makedirs(os.path.dirname(a.json), exist_ok=True)
    with open(a.json, "w") as f:
        json.dump({"scene": os.path.relpath(a.scene, REPO), "reference": os.path.relpath(a.reference, REPO),
                   "reference_info": reference, "target": a.target, "threads": a.threads, "size": size,
                   "seeds": a.seeds, "min_spp": a.min_spp, "extrapolate": a.extrapolate, "cpus": os.cpu_count(), "loads": loads, "runs": runs,
                   **({"cycles_overhead_cpu": overhead} if overhead is not None else {})},
                  f, indent=1)


def reference_text(r):
    info = r.get("reference_info", {"kind": "ours", "ours_spp": None})
    ref = f"`{r['reference']}`"
    if info["kind"] != "mean":
        return f"{ref} (ours at {info['ours_spp']} spp)"
    mo, mc = info["mean_ours"], info["mean_cycles"]
    ratio = ", ".join(f"{o / c:.4f}" for o, c in zip(mo, mc))
    return (f"{ref}, the mean of ours at {info['ours_spp']} spp and Cycles' at {info['cycles_spp']} spp (RMSE "
            f"between the two {info['rmse_between']:.4f}, so the mean's own error is about "
            f"{info['rmse_between'] / 2:.4f}; mean RGB ours / Cycles {ratio})")


def section(r):
    s = summarise(r["target"], r["seeds"], r["runs"], r.get("extrapolate", False))
    loads = r["loads"]
    def fmt(name, key):
        m = s[name][key]
        if m[0] is None:
            return "not reached"
        x = s[name]["extrapolated"]
        return f"{m[0]:.2f} s ({m[1]:.2f}–{m[2]:.2f})" + (f", {x} of {r['seeds']} seeds extrapolated" if x else "")
    ratio = lambda key: ("—" if s["ours"][key][0] is None or s["cycles"][key][0] is None
                         else f"{s['ours'][key][0] / s['cycles'][key][0]:.2f}×")
    lines = [
        f"## {r['scene']}", "",
        f"{r['size']}, {r['threads']} threads each, target RMSE {r['target']} against {reference_text(r)}, "
        f"{r['seeds']} seeds, spp doubling from {r['min_spp']}. Median time to the target over the seeds "
        "(min–max), interpolated log-log between the two spp counts around it"
        + (" (a seed that never reached it within the largest spp rendered: that render's time x "
           "(its RMSE / target)^2, MSE falling as 1 / spp)" if r.get("extrapolate") else "") + ". 1-minute load average "
        f"before each render: min {min(loads):.2f}, median {statistics.median(loads):.2f}, max {max(loads):.2f} "
        f"(on {r['cpus']} hardware threads).", "",
        "| | ours | Cycles 3.4 | ours / Cycles |", "|---|---|---|---|",
        f"| render time (ours: `timings.render`; Cycles: path tracing, its progress timer) | {fmt('ours', 'render')} | "
        f"{fmt('cycles', 'render')} | {ratio('render')} |",
        f"| total (ours: `timings.total`; Cycles: around `bpy.ops.render.render`, incl. sync and BVH) | "
        f"{fmt('ours', 'total')} | {fmt('cycles', 'total')} | {ratio('total')} |"]
    if "cpu" in s["ours"] and "cpu" in s["cycles"]:
        lines += [
            f"| CPU seconds (ours: `performance.render_cpu_seconds`; Cycles: its process's, less its 1-spp run's "
            f"{r['cycles_overhead_cpu']:.2f} s) | {fmt('ours', 'cpu')} | {fmt('cycles', 'cpu')} | {ratio('cpu')} |",
            f"| CPU seconds of the whole process (both: user + system, from `wait4`) | {fmt('ours', 'cpu_total')} | "
            f"{fmt('cycles', 'cpu_total')} | {ratio('cpu_total')} |"]
    def per_seed(key):
        o, c = s["ours"]["per_seed"].get(key), s["cycles"]["per_seed"].get(key)
        if not o or not c or None in o or None in c:
            return None
        return [x / y for x, y in zip(o, c)]
    pairs = [(k, per_seed(k)) for k in ("render", "cpu") if per_seed(k)]
    if pairs:
        what = " and ".join("render time" if k == "render" else "CPU seconds" for k, _ in pairs)
        ratios = "; ".join(", ".join(f"{x:.2f}×" for x in v) for _, v in pairs)
        lines.append(f"| ours / Cycles seed by seed (seed s of each, rendered one after the other so that they "
                     f"share the load), {what} | | | {ratios} |")
    lines += [
        f"| samples per pixel per second of render time (median over runs) | {s['ours']['spp_per_s']:.1f} | "
        f"{s['cycles']['spp_per_s']:.1f} | {s['ours']['spp_per_s'] / s['cycles']['spp_per_s']:.2f}× |",
        f"| RMSE at the largest spp rendered (error floor against the reference) | {s['ours']['floor'][0]:.5f} at "
        f"{s['ours']['floor'][1]} spp | {s['cycles']['floor'][0]:.5f} at {s['cycles']['floor'][1]} spp | |", "",
        "<details><summary>Every run (spp, seed, RMSE, render and total seconds)</summary>", ""]
    cpu = "cpu" in s["ours"] and "cpu" in s["cycles"]
    lines += (["| renderer | spp | seed | RMSE | render s | total s | CPU s | process CPU s |",
               "|---|---|---|---|---|---|---|---|"] if cpu else
              ["| renderer | spp | seed | RMSE | render s | total s |", "|---|---|---|---|---|---|"])
    for name in ("ours", "cycles"):
        for run in r["runs"][name]:
            lines.append(f"| {name} | {run['spp']} | {run['seed']} | {run['rmse']:.5f} | {run['render']:.3f} | "
                         f"{run['total']:.3f} |" + (f" {run['cpu']:.3f} | {run['cpu_total']:.3f} |" if cpu else ""))
    return lines + ["", "</details>", ""]


def write_markdown(md, folder):
    """docs/bench/peers.md: the hand-written part above the first "## " heading is kept (the verdicts),
    then one section per record in `folder`, then the machine."""
    head = []
    if os.path.exists(md):
        for line in open(md).read().split("\n"):
            if line.startswith("## "):
                break
            head.append(line)
    if not any(l.strip() for l in head):
        head = ["# Peers: time to a target error against Blender's Cycles", "",
                "Written by `tools/peers/cycles/time_to_error.py` (how it measures: its docstring and "
                "`tools/peers/cycles/README.md`).", ""]
    lines = head[:]
    for name in sorted(os.listdir(folder)):
        if name.endswith(".json"):
            lines += section(json.load(open(os.path.join(folder, name))))
    lines += ["## Machine", "", "```", pt_tools.lscpu().strip(), "```", ""]
    with open(md, "w") as f:
        f.write("\n".join(lines))


if __name__ == "__main__":
    sys.exit(main())
