#!/usr/bin/env python3
# Why does one process of T threads scale worse than T single-thread processes? (issue 18 item 5,
# docs/bench/threads.md, session 14). Runs, from the bundle of device_bundle.sh (./perf packed with
# its libraries), the same scene in three configurations:
#   a  1 thread, --spp N
#   b  T threads in one process, --spp N*T (about as long as a)
#   c  T single-thread processes at once, --spp N each (counted together: perf stat follows children)
# under `perf stat` with the counters that tell the candidate causes apart (those this machine has;
# each is probed first and what is missing is said), --rounds rounds, the order rotating. Each
# configuration also runs once at --base-spp (parse, BVH build, start-up), which is subtracted: the
# per-sample figures are the render phase's. Then one `perf record -g` (cpu-clock, -D past the load)
# of a ~--profile-seconds render of each configuration (for c: one of the copies while the others
# run), reported flat (perf report --stdio --no-children). Without perf, or where it may not count,
# the timings still run. Everything goes to $OUT (or /tmp/dp-out): perf-device.json (rewritten
# after every run, so a run cut short keeps what it measured), the raw perf stat CSVs and reports,
# and summary.txt from perf_summary.py, which is also printed.
#   python3 device_perf.py                      # on the lent machine: T = nproc, N = 64 (~5-7 min)
#   python3 device_perf.py --threads 2 --spp 4 --rounds 1 --profile-seconds 3   # a try-out
import argparse, json, os, re, resource, shutil, subprocess, tempfile, time
D = os.path.dirname(os.path.abspath(__file__))
ap = argparse.ArgumentParser()
ap.add_argument("--scene", default="sponza-sky-sun.json")
ap.add_argument("--exe", default="pathtracer")
ap.add_argument("--perf", default=None, help="default: ./perf of the bundle, else perf on PATH")
ap.add_argument("--threads", type=int, default=os.cpu_count())
ap.add_argument("--spp", type=int, default=64, help="a's and each c copy's; b gets spp*threads")
ap.add_argument("--base-spp", type=int, default=1)
ap.add_argument("--rounds", type=int, default=3)
ap.add_argument("--profile-seconds", type=float, default=10, help="0: no perf record")
ap.add_argument("--freq", type=int, default=499, help="perf record sampling frequency (Hz)")
ap.add_argument("--budget-s", type=float, default=420,
                help="skip runs that would end after this (the stat rounds leave the profiles their time)")
ap.add_argument("--out", default=os.environ.get("OUT") or "/tmp/dp-out")
a = ap.parse_args()
os.makedirs(a.out, exist_ok=True)
T0 = time.monotonic()
TMP = tempfile.mkdtemp(prefix="dp-work-")   # renders' images and logs, perf.data (not copied back)
PERF = a.perf or (os.path.join(D, "perf") if os.path.exists(os.path.join(D, "perf")) else shutil.which("perf"))

# counters: name -> what it separates (perf_summary.py prints them per sample)
SOFTWARE = ["task-clock", "context-switches", "cpu-migrations", "page-faults"]
EVENTS = SOFTWARE + [
          "cycles", "instructions", "L1-dcache-load-misses", "LLC-loads", "LLC-load-misses",
          "dTLB-load-misses",
          # Sapphire Rapids' own names (perf knows them only where the guest has a PMU)
          "l2_rqsts.miss", "dtlb_load_misses.walk_completed", "dtlb_load_misses.walk_active",
          "mem_load_l3_hit_retired.xsnp_fwd", "machine_clears.memory_ordering",
          # the effective clock (aperf/mperf: the host's share of the core), where the msr PMU has them
          "msr/aperf/", "msr/mperf/"]

def sh(cmd, **kw):
    try: return subprocess.run(cmd, capture_output=True, text=True, **kw)
    except OSError as e: return subprocess.CompletedProcess(cmd, 127, "", f"cannot run {cmd[0]}: {e}")
    except subprocess.TimeoutExpired as e:
        return subprocess.CompletedProcess(cmd, 124, (e.stdout or b"").decode(errors="replace"),
                                           f"timed out after {e.timeout} s")

def read(path):
    try: return open(path).read().strip()
    except OSError as e: return f"unreadable ({e.strerror})"

def log(msg): print(f"[{time.monotonic() - T0:6.1f} s] {msg}", flush=True)

info = {"argv": vars(a), "nproc": os.cpu_count(), "uid": os.getuid(),
        "lscpu": sh(["lscpu"]).stdout if shutil.which("lscpu") else "",
        "uname": os.uname().release, "loadavg_before": read("/proc/loadavg"),
        "perf_event_paranoid": read("/proc/sys/kernel/perf_event_paranoid"),
        "kptr_restrict": read("/proc/sys/kernel/kptr_restrict"),
        "thp_enabled": read("/sys/kernel/mm/transparent_hugepage/enabled"),
        "thp_defrag": read("/sys/kernel/mm/transparent_hugepage/defrag"),
        "pmus": sorted(os.listdir("/sys/bus/event_source/devices"))
                if os.path.isdir("/sys/bus/event_source/devices") else [],
        "cpu_flags_have_arch_perfmon": "arch_perfmon" in read("/proc/cpuinfo"),
        "perf": PERF, "events": {}, "stat_events": [], "runs": [], "profiles": {}}

def save():
    info["loadavg_now"] = read("/proc/loadavg")
    json.dump(info, open(os.path.join(a.out, "perf-device.json"), "w"), indent=1)

# --- is perf there, and which counters may it count? ---
if PERF:
    v = sh([PERF, "--version"])
    info["perf_version"] = (v.stdout + v.stderr).strip() if v.returncode == 0 else f"FAILS: {v.stderr.strip()[:300]}"
    if v.returncode != 0: PERF = None
else:
    info["perf_version"] = "MISSING (not in the bundle, not on PATH)"
log(f"perf: {PERF} -> {info['perf_version']}; paranoid {info['perf_event_paranoid']}, uid {info['uid']}, "
    f"PMUs {info['pmus']}, arch_perfmon {info['cpu_flags_have_arch_perfmon']}")
PROBE = ["sh", "-c", "i=0; while [ $i -lt 30000 ]; do i=$((i+1)); done"]

def parse_csv(text):
    """perf stat -x, lines: value,unit,event,run_time,pct_enabled,... -> {event: (value|str, pct)}"""
    out = {}
    for line in text.splitlines():
        f = line.split(",")
        if line.startswith("#") or len(f) < 3 or not f[2]: continue
        name = re.sub(r":[ukhHGp]+$", "", f[2])
        try: val = float(f[0])
        except ValueError: val = f[0]
        try: pct = float(f[4])
        except (IndexError, ValueError): pct = None
        out[name] = (val, pct)
    return out

if PERF:
    for ev in EVENTS:
        p = sh([PERF, "stat", "-x,", "-e", ev, "--"] + PROBE)
        got = parse_csv(p.stderr).get(ev)
        if p.returncode != 0 or got is None:
            err = [l for l in p.stderr.splitlines() if l.strip()]
            st = "error: " + (err[0][:160] if err else f"rc {p.returncode}")
        elif isinstance(got[0], str): st = got[0].strip("<>")
        elif got[0] > 0 or ev in SOFTWARE: st = "ok"    # no migration in the probe is no news
        else: st = "ok but counted 0 (the guest may not really count it)"
        info["events"][ev] = st
        if st == "ok": info["stat_events"].append(ev)
    bad = {k: v for k, v in info["events"].items() if v != "ok"}
    log(f"counters ok: {info['stat_events']}")
    for k, v in bad.items(): log(f"  UNAVAILABLE {k}: {v}")
    save()

# --- the three configurations ---
T, N = a.threads, a.spp
def render_cmd(threads, spp, tag):
    return [os.path.join(D, a.exe), os.path.join(D, a.scene), "--threads", str(threads),
            "--spp", str(spp), "-o", os.path.join(TMP, f"{tag}.ppm")]

def copies_script(spp, tag, first=None):
    """sh script that starts T single-thread renders at once (the first one wrapped in `first`)."""
    lines = ["#!/bin/sh"]
    for i in range(T):
        c = " ".join(f"'{x}'" for x in render_cmd(1, spp, f"{tag}-{i}"))
        if i == 0 and first: c = first + " " + c
        lines.append(f"{c} > {TMP}/{tag}-{i}.log 2>&1 &")
    lines.append("wait")
    path = os.path.join(TMP, f"{tag}.sh"); open(path, "w").write("\n".join(lines) + "\n")
    return ["sh", path], [os.path.join(TMP, f"{tag}-{i}.log") for i in range(T)]

def parse_render(text):
    r = {}
    for key, pat in [("parse_s", r"parse ([0-9.]+) s"), ("build_s", r"build ([0-9.]+) s"),
                     ("render_s", r"render ([0-9.]+) s"), ("sps", r"\(([0-9]+) samples/s")]:
        m = re.search(pat, text); r[key] = float(m.group(1)) if m else None
    m = re.search(r"\(([0-9]+)x([0-9]+),", text)
    r["pixels"] = int(m.group(1)) * int(m.group(2)) if m else None
    if r["render_s"] is None: r["err"] = text[-400:]
    return r

CFG = {"a": (1, 1), "b": (T, 1), "c": (1, T)}   # threads per process, processes
def spp_of(cfg, n): return n * T if cfg == "b" else n

def run(cfg, kind, spp, rnd=0, wrap=None):
    """wrap: None (plain), 'stat' or a perf record prefix list. Returns the row."""
    threads, copies = CFG[cfg]; tag = f"{cfg}-{kind}-{rnd}"
    csv = os.path.join(a.out, f"perf-stat-{tag}.csv")
    pre = []
    if wrap == "stat" and PERF and info["stat_events"]:
        pre = [PERF, "stat", "-x,", "-o", csv, "-e", ",".join(info["stat_events"]), "--"]
    if cfg == "c":
        cmd, logs = copies_script(spp, tag, " ".join(wrap) if isinstance(wrap, list) else None)
        cmd = pre + cmd
    else:
        cmd = pre + (wrap if isinstance(wrap, list) else []) + render_cmd(threads, spp, tag); logs = None
    r0 = resource.getrusage(resource.RUSAGE_CHILDREN); t0 = time.monotonic()
    p = sh(cmd)
    wall = time.monotonic() - t0; r1 = resource.getrusage(resource.RUSAGE_CHILDREN)
    outs = [open(f).read() for f in logs] if logs else [p.stdout + p.stderr]
    rr = [parse_render(o) for o in outs]
    row = {"cfg": cfg, "kind": kind, "round": rnd, "threads": threads, "copies": copies, "spp": spp,
           "rc": p.returncode, "wall_s": wall, "user_s": r1.ru_utime - r0.ru_utime,
           "sys_s": r1.ru_stime - r0.ru_stime, "render": rr,
           "samples": sum((x["pixels"] or 0) * spp for x in rr)}
    if pre:
        row["counters"] = {k: v[0] for k, v in parse_csv(read(csv)).items()}
        row["counter_pct_enabled"] = {k: v[1] for k, v in parse_csv(read(csv)).items()}
    if p.returncode != 0: row["err"] = " ".join((p.stderr or "")[-600:].split())
    if pre and all(x["render_s"] is None for x in rr):   # perf stat itself failed: the timing still
        log(f"{cfg} {kind} r{rnd}: perf stat FAILED ({row.get('err', '')[-200:]}); again without it")
        info["stat_events"] = []                          # no counters from here on
        return run(cfg, kind, spp, rnd, None)
    info["runs"].append(row); save()
    sps = sorted(x["sps"] for x in rr if x["sps"]) or [None]
    log(f"{cfg} {kind} r{rnd}: {threads} thr x {copies} proc, {spp} spp, wall {wall:.1f} s, "
        f"render {[x['render_s'] for x in rr][:3]}{'...' if copies > 3 else ''} s, "
        f"samples/s {sps[len(sps) // 2]}{' (median copy)' if copies > 1 else ''}"
        + (f", rc {p.returncode}: {row.get('err', '')[-200:]}" if p.returncode else ""))
    return row

def expected(cfg):
    """seconds a stat run of cfg will take, from its earlier runs (None: not known yet)"""
    w = [r["wall_s"] for r in info["runs"] if r["cfg"] == cfg and r["kind"] == "stat"]
    return max(w) if w else None

def fits(cfg, est, reserve=0.0):
    e = est if est is not None else 0
    if time.monotonic() - T0 + e + reserve > a.budget_s:
        log(f"SKIPPED {cfg}: would end after --budget-s {a.budget_s:.0f} s"); return False
    return True

for cfg in "abc":
    run(cfg, "base", spp_of(cfg, a.base_spp), 0, "stat")
order = list("abc")
PROFILES_S = 3 * (a.profile_seconds + 12) if PERF and a.profile_seconds > 0 else 0
for rnd in range(a.rounds):
    for cfg in order[rnd % 3:] + order[:rnd % 3]:
        if fits(cfg, expected(cfg), PROFILES_S): run(cfg, "stat", spp_of(cfg, N), rnd, "stat")

# --- profiles ---
def report(cfg, data):
    txt = os.path.join(a.out, f"perf-report-{cfg}.txt")
    p = sh([PERF, "report", "-f", "-i", data, "--stdio", "--no-children", "-g", "none",
            "--sort", "dso,sym", "-n", "--percent-limit", "0.2"], timeout=120)
    open(txt, "w").write(p.stdout + ("\n# stderr:\n" + p.stderr[-2000:] if p.returncode else ""))
    prof = {"report": os.path.basename(txt), "rc": p.returncode, "top": []}
    m = re.search(r"# Samples: (\S+)\s+of event '([^']+)'", p.stdout)
    if m: prof["samples"], prof["event"] = m.group(1), m.group(2)
    m = re.search(r"# Event count \(approx\.\): (\d+)", p.stdout)
    if m: prof["event_count"] = int(m.group(1))
    for line in p.stdout.splitlines():
        m = re.match(r"\s*([0-9.]+)%\s+(\d+)\s+(\S+)\s+\[(.)\]\s+(.*\S)", line)
        if m: prof["top"].append([float(m.group(1)), int(m.group(2)), m.group(3), m.group(5)])
    # the callers of the hottest entries, for reading by hand (frame-pointer chains: may be short)
    g = sh([PERF, "report", "-f", "-i", data, "--stdio", "--no-children", "--sort", "dso,sym",
            "-g", "caller,2,callee", "--percent-limit", "2"], timeout=60)
    open(os.path.join(a.out, f"perf-report-{cfg}-callers.txt"), "w").write(g.stdout[:400000])
    return prof

if PERF and a.profile_seconds > 0:
    for cfg in "abc":
        st = [r for r in info["runs"] if r["cfg"] == cfg and r["kind"] == "stat" and r["render"][0]["sps"]]
        base = [r for r in info["runs"] if r["cfg"] == cfg and r["kind"] == "base"]
        if not st or not base: log(f"no profile of {cfg}: no timed run"); continue
        x = st[0]["render"][0]
        spp = max(1, round(a.profile_seconds * x["sps"] / x["pixels"]))
        load = max(rb["parse_s"] + rb["build_s"] for rb in base[0]["render"] if rb["parse_s"] is not None)
        delay_ms = int(1000 * load + 300)
        if not fits(f"profile {cfg}", a.profile_seconds + load + 15): continue
        data = os.path.join(TMP, f"prof-{cfg}.data")
        rec = [PERF, "record", "-e", "cpu-clock", "-F", str(a.freq), "-g", "-N", "-D", str(delay_ms),
               "-o", data, "--"]
        row = run(cfg, "profile", spp, 0, rec)
        if not os.path.exists(data) or os.path.getsize(data) == 0:
            why = row.get("err") or " ".join(row["render"][0].get("err", "").split())
            info["profiles"][cfg] = {"error": "perf record wrote nothing: " + why[-300:]}
            log(f"profile {cfg}: UNAVAILABLE ({info['profiles'][cfg]['error'][:200]})"); save(); continue
        info["profiles"][cfg] = report(cfg, data); info["profiles"][cfg]["delay_ms"] = delay_ms
        log(f"profile {cfg}: {info['profiles'][cfg].get('samples')} samples, report rc {info['profiles'][cfg]['rc']}")
        save()
elif not PERF:
    log("no profiles: perf missing")

info["loadavg_after"] = read("/proc/loadavg"); info["elapsed_s"] = time.monotonic() - T0; save()
s = sh(["python3", os.path.join(D, "perf_summary.py"), os.path.join(a.out, "perf-device.json")])
open(os.path.join(a.out, "summary.txt"), "w").write(s.stdout + s.stderr)
print(s.stdout + s.stderr, flush=True)
