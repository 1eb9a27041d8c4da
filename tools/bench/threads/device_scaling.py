#!/usr/bin/env python3
# Thread scaling on a machine without the renderer's libraries, from the bundle of device_bundle.sh:
# the render phase's time from the renderer's own "wrote" line (a run record would load the image
# module), the process's CPU from getrusage; the thread counts rotate round by round.
#   python3 device_scaling.py 1,2,4,8,12,16 ROUNDS   -> $OUT/threads-device.json (or /tmp)
import json, os, re, resource, subprocess, sys, time
D = os.path.dirname(os.path.abspath(__file__)); OUT = os.environ.get("OUT", "/tmp")
threads = [int(t) for t in sys.argv[1].split(",")]; rounds = int(sys.argv[2])
scenes = [("cornell", "cornell-box.json", 256), ("sponza-sky-sun", "sponza-sky-sun.json", 64)]
res = []
info = {"lscpu": subprocess.run(["lscpu"], capture_output=True, text=True).stdout,
        "loadavg_before": open("/proc/loadavg").read().strip(), "nproc": os.cpu_count()}
for r in range(rounds):
    for name, f, spp in scenes:
        order = threads[r % len(threads):] + threads[:r % len(threads)]
        for t in order:
            before = resource.getrusage(resource.RUSAGE_CHILDREN)
            p = subprocess.run([os.path.join(D, "pathtracer"), os.path.join(D, f), "--threads", str(t),
                                "--spp", str(spp), "-o", os.path.join("/tmp", f"x{t}.ppm")],
                               capture_output=True, text=True)
            after = resource.getrusage(resource.RUSAGE_CHILDREN)
            m = re.search(r"render ([0-9.]+) s \(([0-9]+) samples/s", p.stderr + p.stdout)
            cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
            row = {"scene": name, "threads": t, "round": r, "rc": p.returncode,
                   "render_s": float(m.group(1)) if m else None,
                   "samples_per_s": int(m.group(2)) if m else None, "process_cpu_s": cpu}
            if not m: row["err"] = (p.stderr + p.stdout)[-500:]
            print(json.dumps(row), flush=True); res.append(row)
info["loadavg_after"] = open("/proc/loadavg").read().strip(); info["runs"] = res
json.dump(info, open(os.path.join(OUT, "threads-device.json"), "w"), indent=1)
print(info["lscpu"][:1500]); print(info["loadavg_before"], info["loadavg_after"])
