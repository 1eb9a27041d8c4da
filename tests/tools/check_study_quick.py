#!/usr/bin/env python3
"""CTest: `tools/study/samplers/run_study.py --quick` into a fresh folder, then checks what
it wrote: the report, every CSV (rows, columns, values), the PNG/SVG plots and
sane slopes. Exit 0 pass, 1 fail, 77 skip (matplotlib missing: the tool says
how to install it).

    check_study_quick.py SOURCE_DIR BUILD_DIR
"""
import csv
import json
import math
import os
import shutil
import subprocess
import sys
import tempfile

from checks import SKIP, check, fail  # tests/tools/checks.py, beside this script


def main():
    source, build = sys.argv[1], sys.argv[2]
    out = tempfile.mkdtemp(prefix="pt-study-quick-")
    try:
        r = subprocess.run([sys.executable, os.path.join(source, "tools", "study", "samplers", "run_study.py"), "--quick",
                            "--build", build, "--out", out], capture_output=True, text=True)
        print(r.stdout + r.stderr)
        if r.returncode == SKIP:
            return SKIP
        check(r.returncode == 0, "run_study.py --quick exited %d" % r.returncode)
        data = os.path.join(out, "data")
        run = json.load(open(os.path.join(data, "run.json")))
        summary = json.load(open(os.path.join(data, "summary.json")))
        readme = open(os.path.join(out, "README.md")).read()
        for heading in ("## Machine", "## Convergence", "## Comparison with the literature", "## Speed against error",
                        "Equal time", "Equal error", "Quick mode"):
            check(heading in readme, "README.md lacks '%s'" % heading)

        # Convergence CSVs: one row per seed and checkpoint, positive finite errors, RMSE = sqrt(MSE).
        checkpoints, seeds = run["cfg"]["checkpoints"], run["cfg"]["seeds"]
        for key, name in run["conv"].items():
            rows = list(csv.DictReader(open(os.path.join(data, name))))
            check(len(rows) == len(checkpoints) * len(seeds), "%s: %d rows" % (name, len(rows)))
            for seed in seeds:
                spp = [int(x["spp"]) for x in rows if int(x["seed"]) == seed]
                check(spp == checkpoints, "%s seed %d: checkpoints %s" % (name, seed, spp))
            for x in rows:
                mse, rmse = float(x["mse"]), float(x["rmse"])
                check(0 < mse < 1 and math.isfinite(float(x["rel_mse"])), "%s: bad MSE %s" % (name, x))
                check(abs(rmse - math.sqrt(mse)) <= 1e-6 * rmse, "%s: RMSE is not sqrt(MSE)" % name)
                check(float(x["seconds"]) > 0, "%s: non-positive time" % name)
            # Progressive samplers: the time of one seed's render grows with spp.
            if key.endswith(("/random", "/sobol")):
                t = [float(x["seconds"]) for x in rows if int(x["seed"]) == seeds[0]]
                check(all(b > a for a, b in zip(t, t[1:])), "%s: cumulative time not increasing" % name)

        # Plots: PNG signature, SVG root element, for every scene and speed case.
        stems = ["convergence-" + s[0] for s in run["scenes"]] + ["speed-" + c for c in run["speed_cases"]]
        for stem in stems:
            png = open(os.path.join(out, stem + ".png"), "rb").read()
            check(png.startswith(b"\x89PNG") and len(png) > 5000, stem + ".png is not a plot")
            svg = open(os.path.join(out, stem + ".svg")).read()
            check("<svg" in svg and "</svg>" in svg, stem + ".svg is not an SVG")
            check(stem + ".png" in readme, "README.md does not show " + stem)

        # Slopes: random near -1 everywhere; on the antialiasing scene (2D edges) the
        # stratified samplers near -1.5, clearly steeper than random; at the last
        # checkpoint both stratified samplers beat random on every scene.
        conv = summary["convergence"]
        for scene, per_sampler in conv.items():
            s = per_sampler["random"]["fit"]["all"]["mean"]
            check(-1.3 < s < -0.7, "%s: random slope %.2f, expected about -1" % (scene, s))
            last = {k: per_sampler[k]["curve"][-1][1] for k in ("random", "jittered", "sobol")}
            check(last["jittered"] < 0.7 * last["random"] and last["sobol"] < 0.7 * last["random"],
                  "%s: stratified samplers not better than random at the end: %s" % (scene, last))
        for sampler in ("jittered", "sobol"):
            s = conv["aa-edges"][sampler]["fit"]["pow2"]["mean"]
            check(-1.9 < s < -1.2, "aa-edges %s slope %.2f, expected about -1.5" % (sampler, s))

        # Speed: every configuration has a CSV, the tables were filled.
        for case in run["speed_cases"]:
            for accel in run["accels"]:
                for sampler in run["samplers"]:
                    name = run["speed"]["%s/%s/%s" % (case, accel, sampler)]
                    rows = list(csv.DictReader(open(os.path.join(data, name))))
                    check(len(rows) >= 1 and {x["accel"] for x in rows} == {accel}, "%s: rows" % name)
            check(any(v is not None for v in summary["speed"][case]["equal_time"].values()),
                  "%s: empty equal-time table" % case)
            check(any(v is not None for v in summary["speed"][case]["equal_error"].values()),
                  "%s: empty equal-error table" % case)
        print("study --quick: report, %d CSVs, %d plots and slopes checked" % (len(run["conv"]), 2 * len(stems)))
        return 0
    finally:
        shutil.rmtree(out, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(main())
