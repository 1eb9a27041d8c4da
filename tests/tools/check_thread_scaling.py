#!/usr/bin/env python3
"""Smoke run of tools/bench/threads/thread_scaling.py (docs/bench/threads.md):
1 and 2 threads, 2 rounds, the Cornell box at 1 spp. Checks what it reads from
the run records (the same camera samples at every thread count, a positive
render time and render CPU time), the markdown table it prints and the
load average it states. Bounds nothing in time.

    check_thread_scaling.py REPO PATHTRACER_EXE
"""
import json
import os
import subprocess
import sys
import tempfile


def main():
    repo, exe = sys.argv[1], sys.argv[2]
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "runs.json")
        r = subprocess.run([sys.executable, os.path.join(repo, "tools", "bench", "threads", "thread_scaling.py"),
                            "--exe", exe, "--threads", "1,2", "--rounds", "2",
                            "--scene", f"box={os.path.join(repo, 'scenes', 'cornell-box.json')}:1", "--json", out],
                           capture_output=True, text=True)
        if r.returncode != 0:
            sys.exit(f"thread_scaling.py failed ({r.returncode}):\n{r.stderr}")
        with open(out) as f:
            runs = json.load(f)
    box = runs["scenes"]["box"]
    assert sorted(box) == ["1", "2"], box.keys()
    for t, rs in box.items():
        assert len(rs) == 2, (t, rs)
        for x in rs:
            assert x["samples"] == 256 * 256, x  # 256x256 at 1 spp, whatever the thread count
            assert x["render"] > 0 and x["cpu"] > 0 and x["sps"] > 0, x
    assert "lscpu" in runs and runs["load_before"], runs.keys()
    for needle in ("| threads | render (wall) |", "\n| 1 | ", "\n| 2 | ", "Load average (1, 5, 15 min) before:"):
        assert needle in r.stdout, (needle, r.stdout)
    print("thread_scaling.py: ok")


if __name__ == "__main__":
    main()
