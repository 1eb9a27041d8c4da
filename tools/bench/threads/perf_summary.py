#!/usr/bin/env python3
# Summary of device_perf.py's perf-device.json: per camera sample of the render phase (each run less
# its configuration's --base-spp run), for a = 1 thread, b = T threads in one process, c = T
# single-thread processes at once; medians over the rounds [smallest, largest], and b/a, c/a.
#   python3 tools/bench/threads/perf_summary.py perf-device.json [--top 25]
import argparse, json, statistics

ap = argparse.ArgumentParser()
ap.add_argument("json")
ap.add_argument("--top", type=int, default=25)
a = ap.parse_args()
d = json.load(open(a.json))
T = d["argv"]["threads"]
NAMES = {"a": "1 thread", "b": f"{T} threads, 1 process", "c": f"{T} processes x 1 thread"}

model = next((l.split(":", 1)[1].strip() for l in d.get("lscpu", "").splitlines() if l.startswith("Model name")), "?")
print(f"machine: {model}, {d['nproc']} CPUs, kernel {d['uname']}; load {d['loadavg_before']} -> {d.get('loadavg_after', d.get('loadavg_now'))}")
print(f"perf: {d['perf_version']}; uid {d['uid']}, perf_event_paranoid {d['perf_event_paranoid']}, "
      f"PMUs {','.join(d['pmus'])}, arch_perfmon flag {d['cpu_flags_have_arch_perfmon']}; THP {d['thp_enabled']}")
bad = {k: v for k, v in d["events"].items() if v != "ok"}
print("counters counted: " + (", ".join(d["stat_events"]) or "NONE"))
if bad:
    print("UNAVAILABLE: " + "; ".join(f"{k} ({v})" for k, v in bad.items()))
print(f"scene {d['argv']['scene']}, {d['argv']['spp']} spp (b: x{T}), base {d['argv']['base_spp']} spp subtracted; "
      f"{d['argv']['rounds']} rounds; elapsed {d.get('elapsed_s', 0):.0f} s")

runs = [r for r in d["runs"] if r["rc"] == 0]
base = {r["cfg"]: r for r in runs if r["kind"] == "base"}
stat = {c: [r for r in runs if r["cfg"] == c and r["kind"] == "stat"] for c in "abc"}

def med(xs):
    xs = [x for x in xs if x is not None]
    return (statistics.median(xs), min(xs), max(xs)) if xs else None

def fmt(m, prec=3):
    if m is None: return "-"
    v, lo, hi = m
    f = (lambda x: f"{x:.{prec}g}") if abs(v) < 1000 else (lambda x: f"{x:.4g}")
    return f"{f(v)} [{f(lo)}, {f(hi)}]" if lo != hi else f(v)

# --- timing: samples/s and the per-thread efficiency against a of the same round ---
def sps(r):
    xs = sorted(x["sps"] for x in r["render"] if x["sps"])
    return xs[len(xs) // 2] if xs else None
print("\nrender speed (renderer's own samples/s; c: the median copy)   per-thread efficiency vs a, same round;"
      "\n  occupancy: the render phase's CPU (task-clock less the base run's) / (its wall x threads): below ~0.97"
      "\n  the threads wait (tail, locks, scheduling), at ~1 with efficiency low each sample costs more CPU")
a_by_round = {r["round"]: sps(r) for r in stat["a"]}
a_med = med(a_by_round.values())
for c in "abc":
    s = [sps(r) for r in stat[c]]
    eff = []
    for r in stat[c]:
        ar = a_by_round.get(r["round"]) or (a_med and a_med[0])
        if ar and sps(r): eff.append(sps(r) / ar / (T if c == "b" else 1))
    occ = []
    for r in stat[c]:
        b, rs = base.get(c), [x["render_s"] for x in r["render"] if x["render_s"]]
        def cpu_s(x):   # the process's CPU: perf's task-clock (ms), else getrusage
            v = x.get("counters", {}).get("task-clock")
            return v / 1e3 if isinstance(v, float) else x["user_s"] + x["sys_s"]
        if b and rs:
            wall = max(rs) - max(x["render_s"] or 0 for x in b["render"])
            occ.append((cpu_s(r) - cpu_s(b)) / wall / (1 if c == "a" else T))
    extra = f"  speed-up over a {fmt(med([e * T for e in eff]))}" if c == "b" else ""
    print(f"  {c} {NAMES[c]:28s} {fmt(med(s), 4):>28s}   eff {fmt(med(eff))}  occupancy {fmt(med(occ))}{extra}")

# --- counters per sample ---
def per_sample(r, ev, src="counters"):
    b = base.get(r["cfg"])
    def val(x):
        if ev in ("user_s", "sys_s"): return x[ev]
        v = x.get(src, {}).get(ev)
        return v if isinstance(v, (int, float)) else None
    v = val(r)
    if v is None: return None
    if b is not None and val(b) is not None and r["samples"] > b["samples"]:
        return (v - val(b)) / (r["samples"] - b["samples"])
    return v / r["samples"] if r["samples"] else None

ROWS = [  # label, event, scale, (derived: numerator, denominator)
    ("CPU ns (task-clock)", "task-clock", 1e6), ("user CPU ns (rusage)", "user_s", 1e9),
    ("sys CPU ns (rusage)", "sys_s", 1e9), ("cycles", "cycles", 1), ("instructions", "instructions", 1),
    ("IPC", ("instructions", "cycles"), None), ("L1d load misses", "L1-dcache-load-misses", 1),
    ("L2 misses", "l2_rqsts.miss", 1), ("LLC loads", "LLC-loads", 1), ("LLC load misses", "LLC-load-misses", 1),
    ("dTLB load misses", "dTLB-load-misses", 1), ("dTLB page walks", "dtlb_load_misses.walk_completed", 1),
    ("% cycles in page walks", ("dtlb_load_misses.walk_active", "cycles"), 100),
    ("HITM snoops /1k smp", "mem_load_l3_hit_retired.xsnp_fwd", 1e3),
    ("mem-order clears /1k", "machine_clears.memory_ordering", 1e3),
    ("clock aperf/mperf", ("msr/aperf/", "msr/mperf/"), None),
    ("context switches /1M", "context-switches", 1e6), ("cpu-migrations /1M", "cpu-migrations", 1e6),
    ("page faults /1M smp", "page-faults", 1e6)]
print("\nper camera sample, render phase (median over rounds [smallest, largest])")
print(f"  {'':24s} {'a':>22s} {'b':>22s} {'c':>22s} {'b/a':>6s} {'c/a':>6s}")
cpu_ns = {}
for label, ev, scale in ROWS:
    ms = {}
    for c in "abc":
        if isinstance(ev, tuple):
            xs = [(per_sample(r, ev[0]), per_sample(r, ev[1])) for r in stat[c]]
            ms[c] = med([x / y * (scale or 1) for x, y in xs if x is not None and y])
        else:
            ms[c] = med([v * scale for v in (per_sample(r, ev) for r in stat[c]) if v is not None])
    if all(m is None for m in ms.values()): continue
    if ev == "task-clock": cpu_ns = {c: m[0] for c, m in ms.items() if m}
    ratio = lambda c: f"{ms[c][0] / ms['a'][0]:6.3f}" if ms[c] and ms["a"] and ms["a"][0] else "     -"
    print(f"  {label:24s} {fmt(ms['a']):>22s} {fmt(ms['b']):>22s} {fmt(ms['c']):>22s} {ratio('b')} {ratio('c')}")
if not cpu_ns:   # no perf stat: CPU from rusage
    for c in "abc":
        m = med([(per_sample(r, "user_s") or 0) + (per_sample(r, "sys_s") or 0) for r in stat[c]])
        if m: cpu_ns[c] = m[0] * 1e9

# --- profiles: where the CPU time of a sample goes, per symbol ---
pr = d.get("profiles", {})
for c in "abc":
    if c in pr and "error" in pr[c]: print(f"\nprofile {c}: UNAVAILABLE: {pr[c]['error'][:300]}")
have = [c for c in "abc" if c in pr and pr[c].get("top")]
if have:
    print(f"\nprofile (perf record -g, {pr[have[0]].get('event', '?')}, self time, --no-children): share %, and ns per "
          f"sample = share x CPU ns/sample above; top {a.top} by the largest share")
    for c in have: print(f"  {c}: {pr[c].get('samples')} samples, {pr[c]['report']}")
    rows = {}
    for c in have:
        for pct, n, dso, sym in pr[c]["top"]:   # overloads share a name in perf's listing: summed
            r = rows.setdefault((dso, sym), {}); r[c] = r.get(c, 0) + pct
    keys = sorted(rows, key=lambda k: -max(rows[k].values()))[:a.top]
    hdr = "".join(f"{c + ' %':>7s}" for c in have) + "".join(f"{c + ' ns':>8s}" for c in have)
    print(f"  {hdr}{'b-a ns':>8s}{'c-a ns':>8s}  {'dso':14s} symbol")
    for k in keys:
        sh = rows[k]
        ns = {c: sh.get(c, 0) / 100 * cpu_ns[c] for c in have if c in cpu_ns}
        line = "".join(f"{sh.get(c, 0):7.2f}" for c in have) + "".join(f"{ns.get(c, 0):8.0f}" for c in have)
        diff = "".join(f"{ns[c] - ns['a']:8.0f}" if "a" in ns and c in ns else "       -" for c in "bc")
        print(f"  {line}{diff}  {k[0][:14]:14s} {k[1][:70]}")

print("""
reading: b/a well above c/a in CPU ns is the cost of sharing one address space. Then:
  LLC/L2 misses per sample up in b, not in c   -> shared-cache traffic / memory layout of the shared BVH & mesh
  HITM snoops or memory-order clears up in b   -> (false) sharing of written lines: counters, film, refcounts
  dTLB misses / walk cycles up in b, not in c  -> TLB: huge pages for more arrays (THP above)
  context switches / migrations up in b        -> TBB scheduling / thread placement (affinity)
  sys CPU or page faults up in b               -> kernel: allocator (mmap, page faults on one mm)
  aperf/mperf lower in b than in c             -> the host's clock, not our threads
  same counters, IPC down in b                 -> look at the profile: which symbols gained ns in b-a
  a symbol of libtbb / malloc / futex gaining   -> scheduler spinning, allocator, locks""")
