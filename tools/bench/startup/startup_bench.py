#!/usr/bin/env python3
"""Start-up cost of the pathtracer executable (issue 20, docs/bench/startup.md).

Runs each command --runs times, interleaved across the executables given (A/B: e.g. the build before
and after a change), and reports the median wall-clock and CPU (user + system) seconds and the peak RSS
of each, and the shared objects the command loaded (LD_DEBUG=files: those the executable needs and
those it opened with dlopen, e.g. the image module pt_oiio.so and OpenImageIO behind it); then where
the time goes: the shared libraries the executable needs (ldd), the dynamic loader's own share
(LD_DEBUG=statistics), and the same figures for an empty C program linked only against
libOpenImageIO (what that library's dependencies cost by themselves). The machine (lscpu) and the
load average before and after are printed with the table.

  python3 tools/bench/startup/startup_bench.py [--exe build/pathtracer ...] [--runs 10]

CPU seconds are the robust figure on a shared machine; wall-clock seconds grow with the load.
"""
import argparse
import os
import re
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "pylib"))
from pt_tools import lscpu  # noqa: E402

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))


def measure(cmd, cwd):
    t0 = time.perf_counter()
    p = subprocess.Popen(cmd, cwd=cwd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    _, status, usage = os.wait4(p.pid, 0)
    wall = time.perf_counter() - t0
    return wall, usage.ru_utime + usage.ru_stime, usage.ru_maxrss / 1024.0


def loader_stats(cmd):
    env = dict(os.environ, LD_DEBUG="statistics")
    err = subprocess.run(cmd, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True).stderr
    m = re.search(r"total startup time in dynamic loader: (\d+) cycles", err)
    r = re.search(r"final number of relocations: (\d+)", err)
    return (int(m.group(1)) if m else 0), (int(r.group(1)) if r else 0)


def loaded_objects(cmd, cwd):
    """The shared objects the command loaded, as the dynamic loader reports them (LD_DEBUG=files)."""
    env = dict(os.environ, LD_DEBUG="files")
    err = subprocess.run(cmd, cwd=cwd, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                         text=True, errors="replace").stderr
    # Named by soname or by path (dlopen's dependencies): compared by file name.
    found = re.findall(r"file=(\S+) \[\d+\];  (?:needed by|dynamically loaded by)", err)
    return {os.path.basename(f) for f in found}


def library_count(exe):
    out = subprocess.run(["ldd", exe], stdout=subprocess.PIPE, text=True).stdout
    return len([l for l in out.splitlines() if l.strip()])


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--exe", action="append", help="executables to compare (default: build/pathtracer)")
    ap.add_argument("--runs", type=int, default=10)
    a = ap.parse_args()
    exes = a.exe or [os.path.join(REPO, "build", "pathtracer")]
    with tempfile.TemporaryDirectory() as work:
        with open(os.path.join(work, "s.json"), "w") as f:
            f.write('{"format": "pathtracer-scene", "version": 1, "camera": {"position": [0, 1, 4], '
                    '"look_at": [0, 0.5, 0]}, "film": {"width": 8, "height": 6}, "render": {"spp": 1}, '
                    '"shapes": [{"type": "sphere", "center": [0, 0.5, 0], "radius": 0.5}]}')
        commands = {"--version": ["--version"], "--help": ["--help"], "unknown option": ["s.json", "--samples", "4"],
                    "bad scene (missing)": ["missing.json", "-o", "x.exr"],
                    "8x6 render to PPM": ["s.json", "-o", "x.ppm", "--quiet"],
                    "8x6 render to EXR": ["s.json", "-o", "x.exr", "--quiet"],
                    "8x6 render to PNG": ["s.json", "-o", "x.png", "--quiet"]}
        machine = "; ".join(" ".join(l.split()) for l in lscpu().splitlines() if l.startswith(("Model name", "CPU(s):")))
        print("machine (lscpu): %s; load average before: %s" % (machine, " ".join(map(str, os.getloadavg()))))
        # An empty program that only links libOpenImageIO: what its dependencies cost alone.
        probe = None
        cc = shutil.which("cc")
        if cc:
            src = os.path.join(work, "empty.c")
            with open(src, "w") as f:
                f.write("int main(void) { return 0; }\n")
            probe = os.path.join(work, "empty-oiio")
            if subprocess.run([cc, src, "-o", probe, "-Wl,--no-as-needed", "-lOpenImageIO"]).returncode != 0:
                probe = None
        runs = {}
        for _ in range(a.runs):
            for exe in exes:
                for name, args in commands.items():
                    runs.setdefault((exe, name), []).append(measure([exe] + args, work))
            if probe:
                runs.setdefault(("empty program + libOpenImageIO", ""), []).append(measure([probe], work))
        print("load average after: %s; %d runs of each, interleaved" % (" ".join(map(str, os.getloadavg())), a.runs))
        print()
        print("| executable | command | wall s (median) | CPU s (median) | peak RSS MiB | shared objects loaded |")
        print("|---|---|---|---|---|---|")
        for (exe, name), values in runs.items():
            objects = loaded_objects([exe] + commands[name], work) if name in commands else set()
            oiio = " (OpenImageIO)" if any("libOpenImageIO" in o for o in objects) else ""
            print("| %s | %s | %.3f | %.3f | %.0f | %s |" % (
                os.path.relpath(exe, REPO) if exe.startswith("/") else exe, name,
                statistics.median(v[0] for v in values), statistics.median(v[1] for v in values),
                statistics.median(v[2] for v in values), ("%d%s" % (len(objects), oiio)) if name else ""))
        print()
        for exe in exes + ([probe] if probe else []):
            cycles, relocs = loader_stats([exe, "--version"] if exe != probe else [exe])
            print("%s: %d shared libraries, %d relocations, dynamic loader %.0f Mcycles" % (
                os.path.basename(exe), library_count(exe), relocs, cycles / 1e6))


if __name__ == "__main__":
    main()
