#!/usr/bin/env python3
"""CTest: build/pathtracer-compare on a 32x32 scene, bounded by sample counts
(--spp-series, --max-spp) and the renderer's own clock (--time-budget), never by
this process's time; then checks what it wrote: README.md (time-to-error table,
samples per second, lscpu), the log-log plot, data/runs.csv (one row per render,
in alternating order, errors falling with the sample count) and its refusals of
bad input. Exit 0 pass, 1 fail, 77 skip (matplotlib missing).

    check_compare.py SOURCE_DIR BUILD_DIR
"""
import csv
import os
import re
import shutil
import statistics
import subprocess
import sys
import tempfile

from checks import SKIP, check, fail  # tests/tools/checks.py, beside this script


def compare(build, args):
    r = subprocess.run([os.path.join(build, "pathtracer-compare")] + args, capture_output=True, text=True)
    print("$ pathtracer-compare " + " ".join(args) + "\n" + r.stdout + r.stderr)
    if r.returncode == SKIP:
        sys.exit(SKIP)
    return r


def check_png(path):
    check(os.path.isfile(path), "%s missing" % path)
    with open(path, "rb") as f:
        head = f.read(24)
    check(head[:8] == b"\x89PNG\r\n\x1a\n", "%s is no PNG" % path)
    width, height = int.from_bytes(head[16:20], "big"), int.from_bytes(head[20:24], "big")
    check(width >= 400 and height >= 300, "%s is %dx%d" % (path, width, height))
    check(os.path.getsize(path) > 10000, "%s is only %d bytes: an empty plot?" % (path, os.path.getsize(path)))


def check_spp_series(source, build, out):
    scene = os.path.join(source, "tools", "study", "samplers", "scenes", "soft-shadow.json")
    series, configs, repeats = [4, 16, 64], [("embree", "random"), ("embree", "sobol"), ("bvh", "random"),
                                             ("bvh", "sobol")], 2
    r = compare(build, [scene, "--out", out, "--reference-spp", "1024", "--spp-series", "4,16,64", "--repeats", "2",
                        "--accel", "embree,bvh", "--sampler", "random,sobol", "--threads", "2"])
    check(r.returncode == 0, "exit %d" % r.returncode)
    check("Fastest to" in r.stdout, "no verdict printed")
    rows = list(csv.DictReader(open(os.path.join(out, "data", "runs.csv"))))
    check(len(rows) == len(series) * len(configs) * repeats, "%d rows in runs.csv" % len(rows))
    # Alternating order: each level runs every configuration, forwards then backwards at the next.
    for k in range(len(series) * repeats):
        block = [(x["accel"], x["sampler"]) for x in rows[k * len(configs):(k + 1) * len(configs)]]
        check(block == (configs if k % 2 == 0 else configs[::-1]), "block %d runs %s" % (k, block))
        check(len({x["level"] for x in rows[k * len(configs):(k + 1) * len(configs)]}) == 1, "levels mixed")
    check(len({x["seed"] for x in rows}) == len(rows), "a seed was used twice")
    for x in rows:
        check(int(x["spp"]) == int(float(x["level"])), "a render of %s spp reached %s" % (x["level"], x["spp"]))
        check(float(x["render_seconds"]) > 0 and float(x["samples_per_second"]) > 0, "no speed: %s" % x)
        check(abs(float(x["rmse"]) ** 2 - float(x["mse"])) <= 1e-6 * float(x["mse"]), "RMSE is not sqrt(MSE)")
    med = {}
    for c in configs:
        for n in series:
            med[c + (n,)] = statistics.median(float(x["rmse"]) for x in rows
                                              if (x["accel"], x["sampler"]) == c and int(x["spp"]) == n)
        # 16x the samples: RMSE at least 2.5x smaller (random: 4x expected; sobol more).
        check(med[c + (64,)] < med[c + (4,)] / 2.5, "%s: RMSE %.4g at 4 spp, %.4g at 64" % (
            c, med[c + (4,)], med[c + (64,)]))
    for accel in ("embree", "bvh"):  # soft shadow, direct light: sobol's error is about a third of random's
        check(med[(accel, "sobol", 64)] < 0.7 * med[(accel, "random", 64)], "%s: sobol no better than random" % accel)
    check(os.path.isfile(os.path.join(out, "reference.exr")), "no reference.exr")

    readme = open(os.path.join(out, "README.md")).read()
    for what in ("## Time to reach an error", "## Samples per second", "## Machine", "Architecture",
                 "error-vs-time.png", "at most", "--spp N"):
        check(what in readme, "README.md lacks '%s'" % what)
    table = readme.split("## Time to reach an error")[1].split("## Samples per second")[0]
    lines = [x for x in table.splitlines() if x.startswith("| ") and "+" in x and "backend" not in x]
    check(len(lines) == len(configs), "time table has %d rows" % len(lines))
    for line in lines:
        cells = [c.strip() for c in line.strip("|").split("|")]
        check(len(cells) == 5, "time table row %s" % line)  # the configuration and four errors
        check(re.match(r"^(≤ )?[0-9.e+-]+ s", cells[1]), "the largest error is not reached by %s" % cells[0])
    check(table.count("**fastest**") >= 4, "no fastest configuration marked per error")
    speed = readme.split("## Samples per second")[1].split("##")[0]
    check(len([x for x in speed.splitlines() if x.startswith("| ") and "+" in x and "samples/s" not in x])
          == len(configs), "samples-per-second table")
    check_png(os.path.join(out, "error-vs-time.png"))
    check(os.path.getsize(os.path.join(out, "error-vs-time.svg")) > 5000, "SVG plot")


def check_time_budgets(source, build, out):
    """The default mode: time budgets on the renderer's clock, here also capped at 8 spp."""
    scene = os.path.join(source, "tools", "study", "samplers", "scenes", "soft-shadow.json")
    r = compare(build, [scene, "--out", out, "--reference", os.path.join(os.path.dirname(out), "a", "reference.exr"),
                        "--budget", "0.2", "--steps", "2", "--max-spp", "8", "--repeats", "1", "--accel", "bvh",
                        "--sampler", "sobol,random"])
    check(r.returncode == 0, "exit %d" % r.returncode)
    rows = list(csv.DictReader(open(os.path.join(out, "data", "runs.csv"))))
    check(len(rows) == 4, "%d rows" % len(rows))
    check(sorted({float(x["level"]) for x in rows}) == [0.1, 0.2], "budgets %s" % {x["level"] for x in rows})
    check(all(x["level_kind"] == "budget" and 1 <= int(x["spp"]) <= 8 for x in rows), "spp beyond --max-spp")
    readme = open(os.path.join(out, "README.md")).read()
    check("--time-budget T" in readme and "(given)" in readme, "README.md does not say how it measured")
    check(not os.path.exists(os.path.join(out, "reference.exr")), "a given reference was copied")


def check_refusals(source, build, out):
    scene = os.path.join(source, "tools", "study", "samplers", "scenes", "soft-shadow.json")
    r = compare(build, [os.path.join(out, "nope.json"), "--out", out])
    check(r.returncode == 2 and "no such scene file" in r.stderr, "a missing scene")
    r = compare(build, [scene, "--out", out, "--sampler", "sobol,halton"])
    check(r.returncode == 2 and "halton" in r.stderr, "an unknown sampler")
    other = os.path.join(source, "tools", "study", "samplers", "scenes", "aa-edges.json")
    wrong = os.path.join(os.path.dirname(out), "a", "reference.exr")
    r = compare(build, [other, "--out", out, "--reference", wrong, "--spp-series", "1", "--width", "16",
                        "--accel", "bvh", "--sampler", "sobol", "--repeats", "1"])
    check(r.returncode == 1 and "pt-imgerr" in r.stderr, "a reference of another size")
    check(not os.path.exists(os.path.join(out, "README.md")), "a README.md after a failure")
    mine = os.path.join(os.path.dirname(out), "mine")  # a user's folder is never replaced
    os.makedirs(os.path.join(mine, "data"))
    open(os.path.join(mine, "notes.txt"), "w").write("mine")
    r = compare(build, [scene, "--out", mine, "--spp-series", "1"])
    check(r.returncode == 2 and "did not write" in r.stderr, "a folder of other files was accepted")
    check(os.path.isdir(os.path.join(mine, "data")) and os.path.isfile(os.path.join(mine, "notes.txt")),
          "a user's files were touched")


def main():
    source, build = sys.argv[1], sys.argv[2]
    root = tempfile.mkdtemp(prefix="pt-compare-")
    try:
        check_spp_series(source, build, os.path.join(root, "a"))
        check_time_budgets(source, build, os.path.join(root, "b"))
        check_refusals(source, build, os.path.join(root, "c"))
    finally:
        shutil.rmtree(root, ignore_errors=True)
    print("pathtracer-compare: ok")
    return 0


if __name__ == "__main__":
    sys.exit(main())
