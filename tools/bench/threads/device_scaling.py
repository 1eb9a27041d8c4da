#!/usr/bin/env python3
# Thread scaling on a machine without the renderer's libraries, from the bundle of device_bundle.sh:
# the render phase's time from the renderer's own "render X s" line (a run record would load the
# image module), the process's CPU from getrusage. Phases, each figure in $OUT/threads-device.json
# (or /tmp), rewritten after every run so that a run cut short still leaves what it measured:
#   ab     every executable at the --ab thread counts, --rounds rounds, executables and counts
#          alternating (an A/B of two builds in one interleaved run)
#   sweep  the first executable at every --threads count once (the scaling table)
#   ceiling  the machine's own limit: one single-thread render alone, then --concurrent copies of
#          it at once (independent processes: no sharing but the machine's caches, memory and
#          clock); their per-process rate over the lone one is the most any threading could reach
#   long   the --ab executables at the largest --ab count with --long-factor times the samples
#          (the tail of a render is a smaller share of a longer one)
#   python3 device_scaling.py --exes new=pathtracer,old=pathtracer-old --ab 8,16 --threads 1,2,4,12 \
#       --rounds 3 --concurrent 16 --phases ab,sweep,ceiling,long
import argparse, json, os, re, resource, subprocess, time
D = os.path.dirname(os.path.abspath(__file__)); OUT = os.environ.get("OUT", "/tmp")
ap = argparse.ArgumentParser()
ap.add_argument("--exes", default="new=pathtracer")
ap.add_argument("--ab", default="16")
ap.add_argument("--threads", default="1,2,4,8,12,16")
ap.add_argument("--rounds", type=int, default=2)
ap.add_argument("--concurrent", type=int, default=os.cpu_count())
ap.add_argument("--long-factor", type=int, default=4)
ap.add_argument("--phases", default="ab,sweep,ceiling,long")
ap.add_argument("--spp-divisor", type=int, default=1, help="fewer samples, to try the tool out")
a = ap.parse_args()
exes = [e.split("=", 1) for e in a.exes.split(",")]
scenes = [("cornell", "cornell-box.json", 256 // a.spp_divisor),
          ("sponza-sky-sun", "sponza-sky-sun.json", 64 // a.spp_divisor)]
info = {"lscpu": subprocess.run(["lscpu"], capture_output=True, text=True).stdout,
        "loadavg_before": open("/proc/loadavg").read().strip(), "nproc": os.cpu_count(),
        "exes": dict(exes), "runs": []}

def save():
    info["loadavg_now"] = open("/proc/loadavg").read().strip()
    json.dump(info, open(os.path.join(OUT, "threads-device.json"), "w"), indent=1)

def parse(text):
    m = re.search(r"render ([0-9.]+) s \(([0-9]+) samples/s", text)
    return (float(m.group(1)), int(m.group(2))) if m else (None, None)

def cmd(exe, f, t, spp, tag):
    return [os.path.join(D, exe), os.path.join(D, f), "--threads", str(t), "--spp", str(spp),
            "-o", os.path.join("/tmp", f"x-{tag}.ppm")]

def run(phase, label, exe, name, f, t, spp, r):
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    p = subprocess.run(cmd(exe, f, t, spp, f"{label}{t}"), capture_output=True, text=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    render_s, sps = parse(p.stderr + p.stdout)
    row = {"phase": phase, "exe": label, "scene": name, "threads": t, "spp": spp, "round": r,
           "rc": p.returncode, "render_s": render_s, "samples_per_s": sps,
           "process_cpu_s": (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)}
    if render_s is None: row["err"] = (p.stderr + p.stdout)[-500:]
    print(json.dumps(row), flush=True); info["runs"].append(row); save()

phases = a.phases.split(",")
ab = [int(t) for t in a.ab.split(",")]
for ph in phases:
    if ph == "ab":
        for r in range(a.rounds):
            for name, f, spp in scenes:
                order = exes if r % 2 == 0 else exes[::-1]
                for t in (ab if r % 2 == 0 else ab[::-1]):
                    for label, exe in order: run("ab", label, exe, name, f, t, spp, r)
    elif ph == "sweep":
        label, exe = exes[0]
        for name, f, spp in scenes:
            for t in [int(x) for x in a.threads.split(",")]: run("sweep", label, exe, name, f, t, spp, 0)
    elif ph == "long":
        for name, f, spp in scenes:
            for label, exe in exes: run("long", label, exe, name, f, max(ab), spp * a.long_factor, 0)
    elif ph == "ceiling":
        label, exe = exes[0]
        for name, f, spp in scenes:
            spp = spp // 4
            run("ceiling-alone", label, exe, name, f, 1, spp, 0)
            procs = [subprocess.Popen(cmd(exe, f, 1, spp, f"c{i}"), stdout=subprocess.PIPE,
                                      stderr=subprocess.STDOUT, text=True) for i in range(a.concurrent)]
            for i, p in enumerate(procs):
                out = p.communicate()[0]; render_s, sps = parse(out)
                row = {"phase": "ceiling-concurrent", "exe": label, "scene": name, "threads": 1,
                       "copies": a.concurrent, "spp": spp, "copy": i, "rc": p.returncode,
                       "render_s": render_s, "samples_per_s": sps}
                print(json.dumps(row), flush=True); info["runs"].append(row)
            save()
info["loadavg_after"] = open("/proc/loadavg").read().strip(); save()
print(info["lscpu"][:1200]); print(info["loadavg_before"], info["loadavg_after"])
