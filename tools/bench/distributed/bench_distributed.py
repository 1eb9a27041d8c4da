#!/usr/bin/env python3
"""The cost of splitting a render into shards (docs/distributed.md).

    python3 tools/bench/distributed/bench_distributed.py [--exe build/pathtracer]
            [--scene scenes/cornell-box.json] [--width 640 --height 360] [--spp 64]
            [--shards 2,4] [--rounds 5] [--merge-width 1920 --merge-height 1080] [--merge-rounds 5]
            [--merge-shards 2,4] [--merge-baseline OTHER_PATHTRACER] [--skip-overhead] [--tmp DIR]
            [--shard-dir DIR] [--merge-compressions zip,none] [--merge-threads N] [--render-write]
            [--baseline-shards]

1. Overhead at equal total samples: one render of --spp samples against N
   shards of --spp/N each, run one after another on this machine (as a farm
   would run them side by side), plus their merge. Each round runs the single
   render, then every N (the order of the Ns rotating), so the machine's drift
   falls on all alike, and each variant's overhead is paired with its round's
   single render. From the renderer's own timers (run records, the merge's
   report): the render phases' wall and CPU time (every thread), summed over the
   shards, plus the merge (wall: its reading and adding, since its EXR write is
   the single render's own cost, shown beside it; CPU: the whole merge, the
   write included), against the single render's render phase; and the CPU time of every process (start-up, parse, build, shard
   files, merge) against the single render's process. CPU time counts the time
   the processes ran, not the time they waited for a core: the robust figure on
   a shared, loaded machine. Medians with the smallest and largest round. Every
   merge is checked to be bit-identical to the single render (idiff).
2. The merge of a --merge-width x --merge-height frame with every AOV the path
   integrator makes, Cryptomatte included: the shard files' size, and the merge's read-and-add and
   EXR write times, wall and CPU (its own report), and the whole merge
   process's wall and CPU time, medians over --merge-rounds merges of each of
   --merge-shards (after one merge that brings the files into the page cache).
   With --merge-baseline EXE (e.g. main's build), its merges alternate with
   --exe's, and each pair's EXRs are checked to be the same bytes (but for the
   time they were written, capDate); with --baseline-shards the baseline
   renders shards of its own (a film-state version of its own), so the check
   also proves the two formats merge to the same image. --shard-dir DIR keeps the shard files in
   DIR and reuses them on the next run. --merge-compressions zip,none measures
   each --exr-compression; --merge-threads N gives --exe's merges --threads N.
3. With --baseline EXE (a build before exact sums): the render phase and the
   CPU time of the same render with both executables, alternating, with and
   without every AOV (--ab-rounds rounds), so the cost of exact sums is
   measured at equal error (the images agree to float rounding).

4. With --render-write and --merge-baseline: the single render's EXR write
   (the writer the merge shares), a --merge-width x --merge-height render of
   1 spp with every AOV by both executables, alternating, EXRs compared.

Prints markdown for docs/distributed.md, with lscpu's model and core count and
the load average before and after (progress goes to stderr).
"""
import argparse
import json
import os
import re
import resource
import statistics
import subprocess
import tempfile
import sys
import time

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))
sys.path.insert(0, os.path.join(REPO, "tools", "pylib"))
import pt_tools  # noqa: E402
ALL_AOVS = ("albedo,N,P,Z,IndexOB,IndexMA,emission,diffuse_direct,diffuse_indirect,specular_direct,"
            "specular_indirect,variance,samples,nonfinite,CryptoObject,CryptoMaterial")


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


def run_record(report):
    with open(report) as f:
        rec = json.load(f)
    t = rec["timings"]
    return {"render": t["render"], "render_cpu": rec["performance"].get("render_cpu_seconds", 0.0), "total": t["total"],
            "write": t["write"]}


def merge_times(stdout):
    # "read and add" (the merged film; its write resolves it), "read, add and resolve" (the band merge), or
    # "read, add, resolve and write" (the streamed band merge: the write overlaps the merge; no write phase, 0 here).
    m = re.search(r"read(?:,)? (?:and )?add(?:,? (?:and )?resolve)?(?: and write)? ([0-9.]+) s \(CPU ([0-9.]+) s\)"
                  r"(?:, write ([0-9.]+) s \(CPU ([0-9.]+) s\))?", stdout)
    if not m:
        raise SystemExit(f"the merge printed no times:\n{stdout}")
    return tuple(float(m.group(i) or 0) for i in range(1, 5))


def common(a):
    return [a.scene, "--width", str(a.width), "--height", str(a.height), "--spp", str(a.spp), "--quiet"] + (
        ["--threads", str(a.threads)] if a.threads else [])


# One render of every sample: the renderer's own timers (run record) and the process's wall and CPU time.
def single(a, tmp):
    wall, _ = timed([a.exe, *common(a), "-o", "single.exr", "--report", "single.json"], tmp)
    rec = run_record(os.path.join(tmp, "single.json"))
    return {"proc_wall": wall, "proc_cpu": CPU[0], **rec, "merge": 0.0, "merge_cpu": 0.0, "merge_write": 0.0}


# N shards one after another, then their merge, checked bit for bit against the single render.
def sharded(a, n, tmp):
    out = {"proc_wall": 0.0, "proc_cpu": 0.0, "render": 0.0, "render_cpu": 0.0, "total": 0.0, "write": 0.0}
    files = []
    for k in range(n):
        f = f"s{n}_{k}.ptshard"
        w, _ = timed([a.exe, *common(a), "--shard", f"{k}/{n}", "--shard-out", f, "--report", "shard.json"], tmp)
        rec = run_record(os.path.join(tmp, "shard.json"))
        out["proc_wall"] += w
        out["proc_cpu"] += CPU[0]
        for key in rec:
            out[key] += rec[key]
        files.append(f)
    w, stdout = timed([a.exe, "merge", *files, "-o", f"merged{n}.exr"], tmp)
    add, add_cpu, write, write_cpu = merge_times(stdout)
    out["proc_wall"] += w
    out["proc_cpu"] += CPU[0]
    out.update(merge=add, merge_cpu=add_cpu + write_cpu, merge_write=write)
    check = subprocess.run(["idiff", "-fail", "0", "-warn", "0", "single.exr", f"merged{n}.exr"], cwd=tmp,
                           capture_output=True, text=True)
    if check.returncode != 0:
        raise SystemExit(f"the merge of {n} shards differs from the single render:\n{check.stdout}")
    return out


def spread(values, fmt):
    return f"{fmt(statistics.median(values))} [{fmt(min(values))}, {fmt(max(values))}]"


def overhead(a, tmp):
    variants = ["1"] + [str(n) for n in a.shards]
    runs = {v: [] for v in variants}
    for r in range(a.rounds):
        rest = variants[1:]
        rest = rest[r % len(rest):] + rest[:r % len(rest)]
        # The single render first (the merges compare with it), then the sharded variants, rotating.
        for v in ["1"] + rest:
            runs[v].append(single(a, tmp) if v == "1" else sharded(a, int(v), tmp))
        print(f"round {r + 1}/{a.rounds} done, load average {load_average()}", file=sys.stderr)
    pct = lambda x: f"{100 * x:+.1f}%"  # noqa: E731
    sec = lambda x: f"{x:.3f} s"  # noqa: E731
    print(f"Scene `{os.path.relpath(a.scene, REPO)}`, {a.width}x{a.height}, {a.spp} spp in total, path integrator,"
          f" {a.threads or 'all'} threads a process; {a.rounds} rounds, each the single render then the sharded"
          f" variants (rotating); medians [smallest, largest]; overheads are paired with the same round's single"
          f" render.\n")
    print("| variant | render phases (wall) | render phases (CPU) | merge: read and add | merge: EXR write |"
          " overhead: render + merge, wall | overhead: render + merge, CPU | overhead: every process, CPU |")
    print("|---|---|---|---|---|---|---|---|")
    base = runs["1"]
    for v in variants:
        rs = runs[v]
        if v == "1":
            print(f"| one render | {spread([x['render'] for x in rs], sec)} | {spread([x['render_cpu'] for x in rs], sec)}"
                  f" | | {spread([x['write'] for x in rs], sec)} | | | |")
            continue
        # Render phases plus the merge: in wall time its reading and adding (its EXR write is the single
        # render's own cost too); in CPU time the whole merge, the write included (errs towards overhead).
        wall = [(x["render"] + x["merge"] - b["render"]) / b["render"] for x, b in zip(rs, base)]
        cpu = [(x["render_cpu"] + x["merge_cpu"] - b["render_cpu"]) / b["render_cpu"] for x, b in zip(rs, base)]
        proc = [(x["proc_cpu"] - b["proc_cpu"]) / b["proc_cpu"] for x, b in zip(rs, base)]
        print(f"| {v} shards + merge | {spread([x['render'] for x in rs], sec)} |"
              f" {spread([x['render_cpu'] for x in rs], sec)} | {spread([x['merge'] for x in rs], sec)} |"
              f" {spread([x['merge_write'] for x in rs], sec)} | {spread(wall, pct)} | {spread(cpu, pct)} |"
              f" {spread(proc, pct)} |")
    print()
    fixed = [(x["proc_cpu"] - x["render_cpu"]) / int(v) for v in variants[1:] for x in runs[v]]
    print(f"Outside the render phase, a shard process costs {spread(fixed, sec)} of CPU (start-up, parse, build, the"
          f" shard file; the single render's: {spread([x['proc_cpu'] - x['render_cpu'] for x in base], sec)}).\n")


# The shards of the large merge, rendered by `exe`; `tag` names the executable's files (a baseline with
# another film-state version needs shards of its own).
def big_shards(a, tmp, n, exe, tag=""):
    files = []
    for k in range(n):
        f = f"big{n}_{k}{tag}.ptshard"
        files.append(f)
        if a.shard_dir and os.path.exists(os.path.join(tmp, f)):
            continue  # kept from an earlier run (--shard-dir)
        timed([exe, a.scene, "--width", str(a.merge_width), "--height", str(a.merge_height), "--spp", str(n),
               "--aov", ALL_AOVS, "--shard", f"{k}/{n}", "--shard-out", f, "--quiet"] +
              (["--threads", str(a.threads)] if a.threads else []), tmp)
    return files


# The bytes of two EXR files are the same but for the capDate attribute's value (the time of writing) and,
# for renders, `timed` attributes (pathtracer:renderTime).
def same_exr_bytes(a, b, timed=()):
    with open(a, "rb") as f, open(b, "rb") as g:
        x, y = bytearray(f.read()), bytearray(g.read())
    keys = [b"capDate\0string\0"] + [name.encode() + b"\0float\0" for name in timed]
    for data in (x, y):
        for key in keys:
            at = data.find(key)
            while at >= 0:  # one per part of a multi-part file
                start = at + len(key) + 4  # the value's size (int32), then the value
                size = int.from_bytes(data[start - 4:start], "little")
                data[start:start + size] = b"\0" * size
                at = data.find(key, start)
    return x == y


# The merge of a large frame with every AOV: with --merge-baseline, the baseline's merge and this build's
# alternate (which goes first alternating too), and each pair's outputs are checked to be the same pixels.
def big_merge(a, tmp):
    exes = [("this build", a.exe)] + ([("baseline", a.merge_baseline)] if a.merge_baseline else [])
    sizes, times, files, exr = {}, {}, {}, {}
    cases = [(n, c) for n in a.merge_shards for c in a.merge_compressions]
    extra = ["--threads", str(a.merge_threads)] if a.merge_threads else []
    for n in a.merge_shards:
        for e, exe in exes:
            # --baseline-shards: the baseline renders its own shards (another film-state version).
            files[(n, e)] = big_shards(a, tmp, n, exe, ".base" if e == "baseline" and a.baseline_shards else "")
            sizes[(n, e)] = os.path.getsize(os.path.join(tmp, files[(n, e)][0]))
    for n in a.merge_shards:
        for e, exe in exes:
            timed([exe, "merge", *files[(n, e)], "-o", "warm.exr"], tmp)  # the shard files into the page cache
    for case in cases:
        for e, _ in exes:
            times[(case, e)] = []
    loads = [load_average()]
    for r in range(a.merge_rounds):
        for n, c in cases:
            outs = []
            for e, exe in (exes if r % 2 == 0 else exes[::-1]):
                out = f"big_{len(outs)}.exr"
                # A fresh output path, as a farm's merge writes: replacing the last round's 447 MiB file would
                # time the kernel freeing its page cache (0.3-0.5 s in rename at load 8), not the merge.
                if os.path.exists(os.path.join(tmp, out)):
                    os.remove(os.path.join(tmp, out))
                wall, stdout = timed([exe, "merge", *files[(n, e)], "-o", out, "--exr-compression", c]
                                     + (extra if e == "this build" else []), tmp)
                times[((n, c), e)].append((wall, CPU[0], *merge_times(stdout)))
                outs.append(out)
            exr[(n, c)] = os.path.getsize(os.path.join(tmp, outs[0]))
            # Shards of their own: the merged render times (summed over the shards) differ too.
            timed_keys = ["pathtracer:renderTime"] if a.baseline_shards else []
            if len(outs) == 2 and not same_exr_bytes(*[os.path.join(tmp, o) for o in outs], timed=timed_keys):
                raise SystemExit(f"the merges of {n} shards ({c}) by the two builds differ")
        loads.append(load_average())
        print(f"merge round {r + 1}/{a.merge_rounds} done, load average {loads[-1]}", file=sys.stderr)
    print(f"Merge of a {a.merge_width}x{a.merge_height} frame with every AOV of the path integrator"
          f" ({ALL_AOVS}), shard files in the page cache, each merge writing a new file (the last one removed"
          f" before it); {a.merge_rounds} rounds"
          + (", the two builds alternating (which goes first alternates), every pair's EXRs the same bytes but"
             " for their capDate" + (" and pathtracer:renderTime (each build merged shards it rendered)"
                                      if a.baseline_shards else "")
             if len(exes) == 2 else "") + "; medians [smallest, largest]. Load average (1 min) after each round: "
          + ", ".join(x.split()[0] for x in loads[1:]) + ".\n")
    print("(\"Read and add\" is the merge's first phase: with the merged film, reading and adding (its write then"
          " resolves the film); band by band, reading, adding and resolving.)\n")
    print("| shards | compression | build | read and add: wall | read and add: CPU | EXR write: wall | EXR write: CPU |"
          " merge process: wall | merge process: CPU | EXR |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    sec = lambda x: f"{x:.2f} s"  # noqa: E731
    for n, c in cases:
        for e, _ in exes:
            t = times[((n, c), e)]
            cols = [spread([x[i] for x in t], sec) for i in (2, 3, 4, 5, 0, 1)]
            print(f"| {n} | {c} | {e} | " + " | ".join(cols) + f" | {exr[(n, c)] / 2**20:.0f} MiB |")
    if len(exes) == 2:
        print("\nRatios, baseline / this build, of the medians [smallest, largest ratio of a round's pair]:\n")
        print("| shards | compression | merge process: wall | merge process: CPU |")
        print("|---|---|---|---|")
        for case in cases:
            b, t = times[(case, "baseline")], times[(case, "this build")]
            cols = []
            for i in (0, 1):
                ratios = [x[i] / y[i] for x, y in zip(b, t)]
                cols.append(f"{statistics.median(x[i] for x in b) / statistics.median(y[i] for y in t):.2f}x"
                            f" [{min(ratios):.2f}, {max(ratios):.2f}]")
            print(f"| {case[0]} | {case[1]} | " + " | ".join(cols) + " |")
    print(f"\nOne shard file: " + ", ".join(f"{sizes[(n, e)]:,} bytes ({n} shards, {e})" for n in a.merge_shards
                                           for e, _ in exes) + ".\n")


# The single render's EXR write (the writer the merge shares): a --merge-width x --merge-height render of
# 1 spp with every AOV by --exe and --merge-baseline, alternating; the run record's write phase (wall) and
# the process's CPU time outside its render phase (start-up, scene, the write), and the EXRs' bytes.
def render_write(a, tmp):
    exes = [("this build", a.exe), ("baseline", a.merge_baseline)]
    runs = {e: [] for e, _ in exes}
    for r in range(a.merge_rounds):
        outs = []
        for e, exe in (exes if r % 2 == 0 else exes[::-1]):
            out = f"single_{len(outs)}.exr"
            timed([exe, a.scene, "--width", str(a.merge_width), "--height", str(a.merge_height), "--spp", "1",
                   "--aov", ALL_AOVS, "-o", out, "--quiet", "--report", "single.json"], tmp)
            rec = run_record(os.path.join(tmp, "single.json"))
            runs[e].append((rec["write"], CPU[0] - rec["render_cpu"]))
            outs.append(out)
        if not same_exr_bytes(*[os.path.join(tmp, o) for o in outs], timed=["pathtracer:renderTime"]):
            raise SystemExit("the single renders' EXRs by the two builds differ")
    print(f"The single render's EXR write: {a.merge_width}x{a.merge_height}, 1 spp, every AOV, zip; {a.merge_rounds}"
          " rounds, the builds alternating, every pair's EXRs the same bytes but for their capDate and"
          " pathtracer:renderTime; medians"
          " [smallest, largest]. Load average (1 min) at the end: " + load_average().split()[0] + ".\n")
    print("| build | write phase (wall) | process CPU outside the render phase |")
    print("|---|---|---|")
    sec = lambda x: f"{x:.2f} s"  # noqa: E731
    for e, _ in exes:
        print(f"| {e} | {spread([x[0] for x in runs[e]], sec)} | {spread([x[1] for x in runs[e]], sec)} |")
    print()


def ab_exact(a, tmp):
    variants = [("beauty", []), ("every AOV", ["--aov", ALL_AOVS])]
    exes = [("baseline", a.baseline), ("this build", a.exe)]
    runs = {(v, e): [] for v, _ in variants for e, _ in exes}
    for r in range(a.ab_rounds):
        for v, extra in variants:
            for e, exe in (exes if r % 2 == 0 else exes[::-1]):
                timed([exe, a.scene, "--width", str(a.width), "--height", str(a.height), "--spp", str(a.ab_spp),
                       "-o", "ab.exr", "--quiet", "--report", "ab.json", *extra], tmp)
                runs[(v, e)].append((run_record(os.path.join(tmp, "ab.json"))["render"], CPU[0]))
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
    out = pt_tools.lscpu()
    model = re.search(r"Model name:\s*(.*)", out)
    cpus = re.search(r"^CPU\(s\):\s*(\d+)", out, re.M)
    return f"{model.group(1).strip() if model else '?'}, {cpus.group(1) if cpus else '?'} CPUs"


def load_average():
    with open("/proc/loadavg") as f:
        return " ".join(f.read().split()[:3])


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--exe", default=os.path.join(REPO, "build", "pathtracer"))
    p.add_argument("--scene", default=os.path.join(REPO, "scenes", "cornell-box.json"))
    p.add_argument("--width", type=int, default=640)
    p.add_argument("--height", type=int, default=360)
    p.add_argument("--spp", type=int, default=64)
    p.add_argument("--shards", default="2,4")
    p.add_argument("--threads", type=int, default=0, help="--threads of every render (default: all)")
    p.add_argument("--rounds", type=int, default=5)
    p.add_argument("--merge-width", type=int, default=1920)
    p.add_argument("--merge-height", type=int, default=1080)
    p.add_argument("--merge-rounds", type=int, default=5)
    p.add_argument("--merge-shards", default="2,4", help="the shard counts of the large merge")
    p.add_argument("--merge-baseline", help="another pathtracer (e.g. main's): its merges alternate with --exe's")
    p.add_argument("--baseline-shards", action="store_true",
                   help="--merge-baseline renders its own shards (its film-state version differs from --exe's)")
    p.add_argument("--merge-compressions", default="zip", help="--exr-compression of the large merges, e.g. zip,none")
    p.add_argument("--merge-threads", type=int, default=0, help="--threads of --exe's merges (default: all)")
    p.add_argument("--render-write", action="store_true",
                   help="also the single render's EXR write, --exe against --merge-baseline")
    p.add_argument("--skip-merge", action="store_true", help="only the overhead table")
    p.add_argument("--tmp", help="where the shard files go (the large merge's take 2 GiB each)")
    p.add_argument("--shard-dir", help="the large merge's shard files here, reused if they exist")
    p.add_argument("--skip-overhead", action="store_true", help="only the merge table")
    p.add_argument("--baseline", help="a pathtracer from before exact sums: also measure their cost")
    p.add_argument("--ab-rounds", type=int, default=6)
    p.add_argument("--ab-spp", type=int, default=16)
    a = p.parse_args()
    a.exe, a.scene = os.path.abspath(a.exe), os.path.abspath(a.scene)
    a.shards = [int(n) for n in a.shards.split(",")]
    a.merge_shards = [int(n) for n in a.merge_shards.split(",")]
    a.merge_compressions = a.merge_compressions.split(",")
    if a.merge_baseline:
        a.merge_baseline = os.path.abspath(a.merge_baseline)
    print(f"Machine: {machine()} (lscpu); load average (1, 5, 15 min) at the start {load_average()}.\n")
    tempfile.tempdir = a.tmp or None
    with tempfile.TemporaryDirectory() as tmp:
        if a.baseline:
            a.baseline = os.path.abspath(a.baseline)
            ab_exact(a, tmp)
        if not a.skip_overhead:
            overhead(a, tmp)
        if not a.skip_merge:
            big_merge(a, os.path.abspath(a.shard_dir) if a.shard_dir else tmp)
        if a.render_write and a.merge_baseline:
            render_write(a, tmp)
    print(f"Load average at the end: {load_average()}.")


if __name__ == "__main__":
    main()
