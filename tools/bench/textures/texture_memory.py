#!/usr/bin/env python3
"""Memory of Crytek Sponza's textures: decoded into memory (what the renderer
did before issue 17) against OpenImageIO's TextureSystem with a bounded cache,
from the source images (the cache makes MIP levels from them) and from tiled,
MIP-mapped .tx files made by maketx.

Each configuration is one fresh process of bench_texture_memory (peak resident
set from getrusage, the time to open the images and to make --lookups lookups
spread over them with footprints from one texel to the whole image); the
configurations alternate within each of --runs rounds, and the table gives
the median of each. "none" is the process with OpenImageIO loaded and nothing
opened: the figures above it are the textures'.

Writes docs/bench/texture-memory.{json,md} with the machine (lscpu). Needs a
Release build, ../shared and maketx (Debian: openimageio-tools). About 5
minutes on 2 cores.

  python3 tools/bench/textures/texture_memory.py [--exe build/tools/bench/textures/bench_texture_memory]
          [--runs 3] [--lookups 2000000] [--quick]
"""
import argparse
import glob
import json
import os
import shutil
import statistics
import subprocess
import sys
import tempfile

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))
SPONZA = os.path.join(os.path.dirname(REPO), "shared", "assets", "sponza", "textures")
sys.path.insert(0, os.path.join(REPO, "tools", "bench", "render"))
from run_benchmarks import lscpu  # noqa: E402


def run(exe, mode, folder, cache, lookups):
    cmd = [exe, mode, folder, "--lookups", str(lookups)] + (["--cache", str(cache)] if cache else [])
    print("+ " + " ".join(cmd), file=sys.stderr)
    return json.loads(subprocess.run(cmd, check=True, text=True, capture_output=True).stdout)


def make_tx(folder):
    """A copy of the textures with a maketx .tx beside each (sRGB-encoded 8-bit, as the sources)."""
    for image in sorted(glob.glob(os.path.join(SPONZA, "*"))):
        shutil.copy(image, folder)
        tx = os.path.join(folder, os.path.splitext(os.path.basename(image))[0] + ".tx")
        subprocess.run(["maketx", "--oiio", image, "-o", tx], check=True, stdout=subprocess.DEVNULL)


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--exe", default=os.path.join(REPO, "build", "tools", "bench", "textures", "bench_texture_memory"))
    p.add_argument("--runs", type=int, default=3)
    p.add_argument("--lookups", type=int, default=2000000)
    p.add_argument("--quick", action="store_true", help="one run of 200000 lookups, nothing written to docs/")
    a = p.parse_args()
    if a.quick:
        a.runs, a.lookups = 1, 200000
    if not os.path.isdir(SPONZA):
        sys.exit("needs " + SPONZA)
    # Sources through a cache smaller than their decoded MIP pyramids thrash: a JPEG has no random access, so
    # every evicted 64 x 64 tile is decoded again from the file's start (minutes for 200000 lookups at 16 MiB).
    # The sources are measured with a cache that holds them; the small caches with the tiled .tx files.
    configs = [("none", None, "source"), ("decode", None, "source"), ("cache", 256, "source"),
               ("cache", 16, "tx"), ("cache", 64, "tx"), ("cache", 256, "tx")]
    results = {c: [] for c in configs}
    load_start = os.getloadavg()
    with tempfile.TemporaryDirectory() as tmp:
        make_tx(tmp)
        folders = {"source": SPONZA, "tx": tmp}
        for _ in range(a.runs):
            for c in configs:
                results[c].append(run(a.exe, c[0], folders[c[2]], c[1], a.lookups))
    rows = []
    for c in configs:
        r = results[c]
        rows.append({"mode": c[0], "cache_mib": c[1], "files": c[2], "images": r[0]["images"],
                     "peak_rss_mib": statistics.median(x["peak_rss_kib"] for x in r) / 1024.0,
                     "open_seconds": statistics.median(x["open_seconds"] for x in r),
                     "lookup_seconds": statistics.median(x["lookup_seconds"] for x in r),
                     "repeat_seconds": statistics.median(x["repeat_seconds"] for x in r), "runs": r})
    load = {"start": list(load_start), "end": list(os.getloadavg())}
    doc = {"lookups": a.lookups, "runs": a.runs, "machine": lscpu(), "load_average": load, "rows": rows}
    if a.quick:
        print(json.dumps(rows, indent=1))
        return
    with open(os.path.join(REPO, "docs", "bench", "texture-memory.json"), "w") as f:
        json.dump(doc, f, indent=1)
    base = rows[0]["peak_rss_mib"]
    lines = ["# Sponza's textures: decoded into memory against the texture cache", "",
             "Written by `tools/bench/textures/texture_memory.py` (%d runs, medians; %d lookups per run, footprints "
             "log-uniform from 1/4096 to the whole image). Peak resident set of one process per row; the textures' "
             "share is the peak minus the baseline (`none`: OpenImageIO loaded, nothing opened, %.1f MiB). "
             "24 images (22 of 1024 x 1024, 23.3 million texels), 16 MB of JPEG and PNG files." % (a.runs, a.lookups, base),
             "Lookups: the first pass (reading the tiles it needs), then the same lookups again (`repeat`), in "
             "thousands of lookups per second.",
             "", "| how | files | cache | peak RSS (MiB) | textures (MiB) | open (s) | lookups (s) | k lookups/s | "
             "repeat k lookups/s |",
             "|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        how = {"none": "nothing opened", "decode": "decoded into memory (before)", "cache": "TextureSystem"}[r["mode"]]
        cache = "%d MiB" % r["cache_mib"] if r["cache_mib"] else "-"
        files = "sources" if r["files"] == "source" else "maketx .tx"
        rate = lambda seconds: "%.0f" % (a.lookups / seconds / 1000.0) if seconds > 0 and r["mode"] != "none" else "-"
        lines.append("| %s | %s | %s | %.1f | %.1f | %.2f | %.2f | %s | %s |" % (
            how, files, cache, r["peak_rss_mib"], r["peak_rss_mib"] - base, r["open_seconds"], r["lookup_seconds"],
            rate(r["lookup_seconds"]), rate(r["repeat_seconds"])))
    lines += ["", "Load average (1, 5, 15 min; the machine is shared, so times are comparable within this table "
              "only): %s at the start, %s at the end." % (", ".join("%.1f" % x for x in load["start"]),
                                                          ", ".join("%.1f" % x for x in load["end"])),
              "", "Machine:", "", "```", doc["machine"].strip(), "```", ""]
    with open(os.path.join(REPO, "docs", "bench", "texture-memory.md"), "w") as f:
        f.write("\n".join(lines))


if __name__ == "__main__":
    main()
