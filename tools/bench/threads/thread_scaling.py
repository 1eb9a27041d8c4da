#!/usr/bin/env python3
"""Thread scaling of the renderer (issue 18, docs/bench/threads.md).

    python3 tools/bench/threads/thread_scaling.py [--exe build/pathtracer] [--threads 1,2,4,8,16]
            [--rounds 5] [--scene NAME=FILE[:SPP] ...] [--json OUT.json]

For each scene, `pathtracer SCENE --threads T --spp SPP --report run.json` for
every thread count T, the order of the counts rotating round by round, so that
the machine's drift (other jobs on a shared machine) falls on all alike. From
the renderer's own run record (docs/cli.md, "Run record"), per run:

- the render phase's wall time and samples/s (camera samples per second);
- the render phase's CPU time (every thread, user + system), hence the samples
  per CPU-second per thread and the threads' occupancy, CPU / (wall x T): on a
  machine shared with other jobs, wall time counts the time a thread waited
  for a core; CPU time counts only the time it ran.

Prints markdown for docs/bench/threads.md: per scene and T, the median render
time and samples/s with their smallest and largest runs, the speed-up over one
thread (the ratio of medians, and the smallest and largest of the per-round
ratios), the efficiency per CPU-second (samples per CPU-second at T over that at
one thread: 1.0 means threading costs no work, so the speed-up on T idle cores
would be T), and the occupancy; with `lscpu` and the load average before and
after. The images are the same at every T (a sample depends on the seed, the
pixel and its index only), so every figure is at equal error.

Scenes default to the Cornell box (scenes/cornell-box.json) and Crytek Sponza
lit by an environment map and a sun (tools/bench/threads/sponza-env-sun.json,
needing ../shared/assets; skipped, saying so, when absent).
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))
sys.path.insert(0, os.path.join(REPO, "tools", "pylib"))
import pt_tools  # noqa: E402

DEFAULT_SCENES = [
    f"cornell={os.path.join(REPO, 'scenes', 'cornell-box.json')}:64",
    f"sponza-env-sun={os.path.join(REPO, 'tools', 'bench', 'threads', 'sponza-env-sun.json')}:16",
]


def load_average():
    with open("/proc/loadavg") as f:
        return " ".join(f.read().split()[:3])


def lscpu_summary(text):
    fields = dict(line.split(":", 1) for line in text.splitlines() if ":" in line)
    get = lambda k: fields.get(k, "?").strip()  # noqa: E731
    return (f"{get('Model name')}, {get('CPU(s)')} CPUs ({get('Thread(s) per core')} threads per core,"
            f" {get('Core(s) per socket')} cores per socket, {get('Socket(s)')} sockets)")


def parse_scene(text):
    name, _, rest = text.partition("=")
    path, _, spp = rest.rpartition(":") if rest.rsplit(":", 1)[-1].isdigit() else (rest, "", "")
    return name, os.path.abspath(path), int(spp) if spp else None


def render(a, scene, spp, threads, tmp):
    report = os.path.join(tmp, "run.json")
    cmd = [a.exe, scene, "--threads", str(threads), "--quiet", "--report", report, "-o", os.path.join(tmp, "out.exr")]
    if spp:
        cmd += ["--spp", str(spp)]
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        raise SystemExit(f"failed ({r.returncode}): {' '.join(cmd)}\n{r.stderr}")
    with open(report) as f:
        rec = json.load(f)
    perf = rec["performance"]
    if rec["threads"] != threads:
        raise SystemExit(f"asked for {threads} threads, the run record says {rec['threads']}")
    return {"render": rec["timings"]["render"], "sps": perf["samples_per_second"],
            "cpu": perf["render_cpu_seconds"], "samples": perf["pixel_samples"]}


def table(name, scene, spp, counts, runs):
    med = {t: {k: statistics.median(x[k] for x in runs[t]) for k in runs[t][0]} for t in counts}
    one = counts[0]
    print(f"**{name}** (`{os.path.relpath(scene, REPO)}`{f', {spp} spp' if spp else ''};"
          f" {med[one]['samples']:.0f} camera samples a run; medians of {len(runs[one])} rounds,"
          f" [smallest, largest]):\n")
    print(f"| threads | render (wall) | samples/s | speed-up over {one} | samples per CPU-second |"
          f" efficiency per CPU-s | occupancy CPU/(wall·T) |")
    print("|---|---|---|---|---|---|---|")
    for t in counts:
        m, rs = med[t], runs[t]
        ratios = [r1["render"] / rt["render"] for r1, rt in zip(runs[one], rs)]
        per_cpu = [x["samples"] / x["cpu"] for x in rs]  # samples per CPU-second (every thread's seconds)
        per_cpu_one = statistics.median(x["samples"] / x["cpu"] for x in runs[one])
        occupancy = [x["cpu"] / (x["render"] * t) for x in rs]
        print(f"| {t} | {m['render']:.3f} s [{min(x['render'] for x in rs):.3f}, {max(x['render'] for x in rs):.3f}]"
              f" | {m['sps'] / 1e6:.3f} M [{min(x['sps'] for x in rs) / 1e6:.3f}, {max(x['sps'] for x in rs) / 1e6:.3f}]"
              f" | {med[one]['render'] / m['render']:.2f}× [{min(ratios):.2f}, {max(ratios):.2f}]"
              f" | {statistics.median(per_cpu) / 1e6:.3f} M"
              f" | {statistics.median(per_cpu) / per_cpu_one:.3f} [{min(per_cpu) / per_cpu_one:.3f},"
              f" {max(per_cpu) / per_cpu_one:.3f}]"
              f" | {statistics.median(occupancy):.2f} [{min(occupancy):.2f}, {max(occupancy):.2f}] |")
    print()
    return {str(t): runs[t] for t in counts}


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--exe", default=os.path.join(REPO, "build", "pathtracer"))
    p.add_argument("--threads", default="1,2", help="thread counts, comma-separated; the first is the reference")
    p.add_argument("--rounds", type=int, default=5)
    p.add_argument("--scene", action="append", metavar="NAME=FILE[:SPP]",
                   help="a scene to measure (repeatable; default: the Cornell box and Sponza with env+sun)")
    p.add_argument("--json", help="also write every run's figures here")
    a = p.parse_args()
    a.exe = os.path.abspath(a.exe)
    counts = [int(t) for t in a.threads.split(",")]
    scenes = []
    for s in a.scene or DEFAULT_SCENES:
        name, path, spp = parse_scene(s)
        if not os.path.exists(path):
            print(f"skipping {name}: {path} is missing", file=sys.stderr)
            continue
        with open(path) as f:
            if "shared/assets" in f.read() and not os.path.isdir(os.path.join(REPO, "..", "shared", "assets")):
                print(f"skipping {name}: it needs ../shared/assets, which is absent", file=sys.stderr)
                continue
        scenes.append((name, path, spp))
    lscpu = pt_tools.lscpu()
    load_before = load_average()
    runs = {(n, t): [] for n, _, _ in scenes for t in counts}
    with tempfile.TemporaryDirectory() as tmp:
        for r in range(a.rounds):
            order = counts[r % len(counts):] + counts[:r % len(counts)]
            for name, path, spp in scenes:
                for t in order:
                    runs[(name, t)].append(render(a, path, spp, t, tmp))
            print(f"round {r + 1}/{a.rounds} done, load average {load_average()}", file=sys.stderr)
    load_after = load_average()
    print(f"Machine (`lscpu`): {lscpu_summary(lscpu)}.\n")
    print(f"Load average (1, 5, 15 min) before: {load_before}; after: {load_after}.\n")
    out = {"lscpu": lscpu, "load_before": load_before, "load_after": load_after, "scenes": {}}
    for name, path, spp in scenes:
        out["scenes"][name] = table(name, path, spp, counts, {t: runs[(name, t)] for t in counts})
    if a.json:
        with open(a.json, "w") as f:
            json.dump(out, f, indent=1)


if __name__ == "__main__":
    main()
