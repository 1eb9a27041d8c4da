#!/usr/bin/env python3
"""The cost of splitting a render into shards (docs/distributed.md).

    python3 tools/bench/distributed/bench_distributed.py [--exe build/pathtracer]
            [--scene scenes/cornell-box.json] [--width 640 --height 360] [--spp 64]
            [--shards 2,4] [--rounds 5] [--merge-width 1920 --merge-height 1080] [--merge-rounds 5]

1. Overhead at equal total samples: one render of --spp samples against N
   shards of --spp/N each, run one after another on this machine (as a farm
   would run them side by side), plus their merge. Each round runs the single
   render and every N in turn (the order rotates), so the machine's drift falls
   on all alike. Per variant: the summed wall time of its processes, the summed
   CPU time (user + system: less disturbed by other processes on a shared
   machine), the summed render phases (run records), what the shards add
   (parse, build, writing the shard file) and the merge's own time; medians
   over the rounds. Every merge is
   checked to be bit-identical to the single render (idiff).
2. The merge of a --merge-width x --merge-height frame with every AOV the path
   integrator makes: the shard files' size, and the merge's read-and-add and
   EXR write times, wall and CPU (its own report), medians over --merge-rounds
   merges of 2 and 4 shards.
3. With --baseline EXE (a build before exact sums): the render phase and the
   CPU time of the same render with both executables, alternating, with and
   without every AOV (--ab-rounds rounds), so the cost of exact sums is
   measured at equal error (the images agree to float rounding).

Prints markdown for docs/distributed.md, with lscpu's model and core count.
"""
import argparse
import json
import os
import re
import resource
import statistics
import subprocess
import tempfile
import time

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))
ALL_AOVS = ("albedo,N,P,Z,IndexOB,IndexMA,emission,diffuse_direct,diffuse_indirect,specular_direct,"
            "specular_indirect,variance,samples,nonfinite")


# CPU seconds (user + system) of the finished child processes so far.
def children_cpu():
    u = resource.getrusage(resource.RUSAGE_CHILDREN)
    return u.ru_utime + u.ru_stime


CPU = [0.0]  # the CPU seconds of the last timed() command


def timed(cmd, cwd):
    t0, c0 = time.perf_counter(), children_cpu()
    r = subprocess.run(cmd, cwd=cwd, capture_output=True, text=True)
    wall = time.perf_counter() - t0
    CPU[0] = children_cpu() - c0
    if r.returncode != 0:
        raise SystemExit(f"failed ({r.returncode}): {' '.join(cmd)}\n{r.stderr}")
    return wall, r.stdout


def render_phases(report):
    with open(report) as f:
        t = json.load(f)["timings"]
    return t["render"], t["total"] - t["render"]


def merge_times(stdout):
    m = re.search(r"read and add ([0-9.]+) s \(CPU ([0-9.]+) s\), write ([0-9.]+) s \(CPU ([0-9.]+) s\)", stdout)
    return tuple(float(m.group(i)) for i in range(1, 5))


def single(a, tmp):
    wall, _ = timed([a.exe, a.scene, "--width", str(a.width), "--height", str(a.height), "--spp", str(a.spp),
                     "-o", "single.exr", "--quiet", "--report", "single.json"], tmp)
    render, other = render_phases(os.path.join(tmp, "single.json"))
    return {"wall": wall, "cpu": CPU[0], "render": render, "other": other, "merge": 0.0}


def sharded(a, n, tmp):
    wall = cpu = render = other = 0.0
    files = []
    for k in range(n):
        f = f"s{n}_{k}.ptshard"
        w, _ = timed([a.exe, a.scene, "--width", str(a.width), "--height", str(a.height), "--spp", str(a.spp),
                      "--shard", f"{k}/{n}", "--shard-out", f, "--quiet", "--report", "shard.json"], tmp)
        r, o = render_phases(os.path.join(tmp, "shard.json"))
        wall, cpu, render, other = wall + w, cpu + CPU[0], render + r, other + o
        files.append(f)
    w, out = timed([a.exe, "merge", *files, "-o", f"merged{n}.exr"], tmp)
    cpu += CPU[0]
    check = subprocess.run(["idiff", "-fail", "0", "-warn", "0", "single.exr", f"merged{n}.exr"], cwd=tmp,
                           capture_output=True, text=True)
    if check.returncode != 0:
        raise SystemExit(f"the merge of {n} shards differs from the single render:\n{check.stdout}")
    return {"wall": wall + w, "cpu": cpu, "render": render, "other": other, "merge": w}


def overhead(a, tmp):
    variants = ["1"] + [str(n) for n in a.shards]
    runs = {v: [] for v in variants}
    for r in range(a.rounds):
        order = variants[r % len(variants):] + variants[:r % len(variants)]
        if "1" in order[1:]:  # the single render first: the merges compare with it
            order.remove("1")
            order.insert(0, "1")
        for v in order:
            runs[v].append(single(a, tmp) if v == "1" else sharded(a, int(v), tmp))
    med = {v: {k: statistics.median(x[k] for x in runs[v]) for k in runs[v][0]} for v in variants}
    base = med["1"]
    print(f"Scene `{os.path.relpath(a.scene, REPO)}`, {a.width}x{a.height}, {a.spp} spp in total, path integrator;"
          f" medians of {a.rounds} interleaved rounds.\n")
    print("| variant | wall, all processes | CPU, all processes | render phases | parse+build+write |"
          " merge (process) | overhead: wall | overhead: CPU |")
    print("|---|---|---|---|---|---|---|---|")
    for v in variants:
        m = med[v]
        wall = "" if v == "1" else (f"{100 * (m['wall'] - base['wall']) / base['render']:+.1f}% of the render"
                                    f" ({100 * (m['wall'] - m['merge'] - base['wall']) / base['render']:+.1f}%"
                                    " without the merge)")
        cpu = "" if v == "1" else f"{100 * (m['cpu'] - base['cpu']) / base['cpu']:+.1f}%"
        name = "one render" if v == "1" else f"{v} shards + merge"
        print(f"| {name} | {m['wall']:.3f} s | {m['cpu']:.3f} s | {m['render']:.3f} s | {m['other']:.3f} s |"
              f" {m['merge']:.3f} s | {wall} | {cpu} |")
    print()


def big_merge(a, tmp):
    sizes, times = {}, {}
    for n in (2, 4):
        files = []
        for k in range(n):
            f = f"big{n}_{k}.ptshard"
            timed([a.exe, a.scene, "--width", str(a.merge_width), "--height", str(a.merge_height), "--spp", str(n),
                   "--aov", ALL_AOVS, "--shard", f"{k}/{n}", "--shard-out", f, "--quiet"], tmp)
            files.append(f)
        sizes[n] = os.path.getsize(os.path.join(tmp, files[0]))
        times[n] = []
    for _ in range(a.merge_rounds):
        for n in (2, 4):
            files = [f"big{n}_{k}.ptshard" for k in range(n)]
            wall, out = timed([a.exe, "merge", *files, "-o", "big.exr"], tmp)
            times[n].append((wall, *merge_times(out)))
    exr = os.path.getsize(os.path.join(tmp, "big.exr"))
    print(f"Merge of a {a.merge_width}x{a.merge_height} frame with every AOV of the path integrator"
          f" ({ALL_AOVS}); medians of {a.merge_rounds} merges, alternating:\n")
    print("| shards | one shard file | read and add: wall | read and add: CPU | EXR write: wall | EXR write: CPU |"
          " merge process: wall |")
    print("|---|---|---|---|---|---|---|")
    for n in (2, 4):
        w, ra, rac, wr, wrc = [statistics.median(t[i] for t in times[n]) for i in range(5)]
        print(f"| {n} | {sizes[n] / 2**20:.0f} MiB | {ra:.3f} s | {rac:.3f} s | {wr:.3f} s | {wrc:.3f} s | {w:.3f} s |")
    print(f"\nThe merged EXR: {exr / 2**20:.0f} MiB.\n")


def ab_exact(a, tmp):
    variants = [("beauty", []), ("every AOV", ["--aov", ALL_AOVS])]
    exes = [("baseline", a.baseline), ("this build", a.exe)]
    runs = {(v, e): [] for v, _ in variants for e, _ in exes}
    for r in range(a.ab_rounds):
        for v, extra in variants:
            for e, exe in (exes if r % 2 == 0 else exes[::-1]):
                timed([exe, a.scene, "--width", str(a.width), "--height", str(a.height), "--spp", str(a.ab_spp),
                       "-o", "ab.exr", "--quiet", "--report", "ab.json", *extra], tmp)
                runs[(v, e)].append((render_phases(os.path.join(tmp, "ab.json"))[0], CPU[0]))
    print(f"Exact sums against the doubles before them (`{a.baseline}`): `{os.path.relpath(a.scene, REPO)}`,"
          f" {a.width}x{a.height}, {a.ab_spp} spp; medians of {a.ab_rounds} alternating runs.\n")
    print("| film | render phase: baseline | render phase: exact sums | ratio |"
          " CPU: baseline | CPU: exact sums | ratio |")
    print("|---|---|---|---|---|---|---|")
    for v, _ in variants:
        (rb, cb), (rn, cn) = [[statistics.median(x[i] for x in runs[(v, e)]) for i in range(2)] for e, _ in exes]
        print(f"| {v} | {rb:.3f} s | {rn:.3f} s | {rn / rb:.3f} | {cb:.3f} s | {cn:.3f} s | {cn / cb:.3f} |")
    print()


def machine():
    out = subprocess.run(["lscpu"], capture_output=True, text=True).stdout
    model = re.search(r"Model name:\s*(.*)", out)
    cpus = re.search(r"^CPU\(s\):\s*(\d+)", out, re.M)
    return f"{model.group(1).strip() if model else '?'}, {cpus.group(1) if cpus else '?'} CPUs"


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--exe", default=os.path.join(REPO, "build", "pathtracer"))
    p.add_argument("--scene", default=os.path.join(REPO, "scenes", "cornell-box.json"))
    p.add_argument("--width", type=int, default=640)
    p.add_argument("--height", type=int, default=360)
    p.add_argument("--spp", type=int, default=64)
    p.add_argument("--shards", default="2,4")
    p.add_argument("--rounds", type=int, default=5)
    p.add_argument("--merge-width", type=int, default=1920)
    p.add_argument("--merge-height", type=int, default=1080)
    p.add_argument("--merge-rounds", type=int, default=5)
    p.add_argument("--skip-merge", action="store_true", help="only the overhead table")
    p.add_argument("--skip-overhead", action="store_true", help="only the merge table")
    p.add_argument("--baseline", help="a pathtracer from before exact sums: also measure their cost")
    p.add_argument("--ab-rounds", type=int, default=6)
    p.add_argument("--ab-spp", type=int, default=16)
    a = p.parse_args()
    a.exe, a.scene = os.path.abspath(a.exe), os.path.abspath(a.scene)
    a.shards = [int(n) for n in a.shards.split(",")]
    print(f"Machine: {machine()} (lscpu).\n")
    with tempfile.TemporaryDirectory() as tmp:
        if a.baseline:
            a.baseline = os.path.abspath(a.baseline)
            ab_exact(a, tmp)
        if not a.skip_overhead:
            overhead(a, tmp)
        if not a.skip_merge:
            big_merge(a, tmp)


if __name__ == "__main__":
    main()
