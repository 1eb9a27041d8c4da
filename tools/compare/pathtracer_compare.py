#!/usr/bin/env python3
"""pathtracer-compare: which backend and sampler reach a given error first on YOUR scene.

    pathtracer-compare SCENE --out DIR [--reference REF.exr | --reference-spp N]
                       [--budget SECONDS] [--steps K] [--spp-series N1,N2,...] [--max-spp N]
                       [--accel embree,bvh] [--sampler random,jittered,sobol] [--repeats R]
                       [--errors E1,E2,...] [--metric rmse|relmse|mse] [--threads N] [--width W]

1. The reference: REF (an EXR of the scene's size), or SCENE rendered with
   `pathtracer --spp N --sampler sobol --accel bvh` (default N = 1024) into DIR/reference.exr.
2. Every chosen backend x sampler is rendered by `pathtracer` at a series of time budgets
   (`--time-budget`: BUDGET/2^(K-1) ... BUDGET, the renderer's own clock), or of sample counts
   (--spp-series), each configuration once per budget and repeat, in alternating order
   (A B C, C B A, ...: a machine that slows down or speeds up during the run biases none of them);
   each render's error against the reference is measured by pt-imgerr, its render time, spp and
   samples per second read from its run record (--report).
3. DIR/README.md: the time each configuration needs to reach given errors (interpolated, log-log,
   between the measured budgets), samples per second, backend build times, the reference's own
   noise, the commands and the machine (lscpu); DIR/error-vs-time.png (and .svg): error against
   render time, log-log; DIR/data/runs.csv and DIR/data/run.json: every measurement.

Needs build/pathtracer, build/tools/imgerr/pt-imgerr and matplotlib (Debian: python3-matplotlib).
Exit status: 0 done, 1 a render or a measurement failed (the message says which), 2 bad arguments,
77 matplotlib missing.
"""
import argparse
import csv
import itertools
import json
import os
import shutil
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))  # tools/compare -> repository
sys.path.insert(0, os.path.join(ROOT, "tools", "pylib"))
from pt_tools import image_error, lscpu, need_matplotlib  # noqa: E402

EXIT_FAILURE, EXIT_USAGE, EXIT_NO_MATPLOTLIB = 1, 2, 77
ACCELS = ["embree", "bvh"]
SAMPLERS = ["random", "jittered", "sobol"]
METRICS = {"rmse": "RMSE", "relmse": "relMSE", "mse": "MSE"}  # option value -> pt-imgerr's name in the table
IMGERR_KEY = {"rmse": "rmse", "relmse": "rel_mse", "mse": "mse"}
REFERENCE_SEED = 1000003  # far from the runs' seeds (1, 2, ...)


class Failure(Exception):
    """A render or a measurement that failed; main() prints it and exits 1."""


def names(text, valid, what):
    items = [x for x in text.replace(" ", "").split(",") if x]
    bad = [x for x in items if x not in valid]
    if bad or not items:
        raise argparse.ArgumentTypeError("%s: %s (choose from %s)" % (what, ",".join(bad) or "empty", ",".join(valid)))
    return list(dict.fromkeys(items))


def numbers(text, kind, what):
    try:
        values = [kind(x) for x in text.split(",") if x]
    except ValueError:
        raise argparse.ArgumentTypeError("%s: expected comma-separated numbers, got '%s'" % (what, text))
    if not values or any(v <= 0 for v in values):
        raise argparse.ArgumentTypeError("%s: expected positive numbers, got '%s'" % (what, text))
    return sorted(set(values))


def positive(kind):
    def parse(text):
        try:
            v = kind(text)
        except ValueError:
            raise argparse.ArgumentTypeError("expected a number, got '%s'" % text)
        if not v > 0 or v != v or v == float("inf"):
            raise argparse.ArgumentTypeError("must be positive and finite, got '%s'" % text)
        return v
    return parse


def parse_args(argv):
    p = argparse.ArgumentParser(prog="pathtracer-compare", description=__doc__.split("\n\n")[0],
                                epilog="Example: pathtracer-compare scenes/showcase.json --budget 8 --out compare/",
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("scene", help="scene file (any format the pathtracer reads)")
    p.add_argument("--out", required=True, help="folder for README.md, the plot and data/ (created; files replaced)")
    ref = p.add_mutually_exclusive_group()
    ref.add_argument("--reference", help="reference image (EXR, the render's size): no reference render")
    ref.add_argument("--reference-spp", type=positive(int), default=1024,
                     help="render the reference with this many samples per pixel (default 1024)")
    p.add_argument("--budget", type=positive(float), default=8.0,
                   help="the largest render time budget, seconds (default 8)")
    p.add_argument("--steps", type=positive(int), default=5,
                   help="time budgets: BUDGET/2^(STEPS-1) ... BUDGET, doubling (default 5)")
    p.add_argument("--spp-series", type=lambda t: numbers(t, int, "--spp-series"),
                   help="render these sample counts instead of time budgets (equal-spp comparison)")
    p.add_argument("--max-spp", type=positive(int), help="with time budgets: stop a render at this spp too")
    p.add_argument("--accel", type=lambda t: names(t, ACCELS, "--accel"), default=ACCELS,
                   help="backends, comma-separated (default embree,bvh)")
    p.add_argument("--sampler", type=lambda t: names(t, SAMPLERS, "--sampler"), default=SAMPLERS,
                   help="samplers of the path integrator, comma-separated (default random,jittered,sobol)")
    p.add_argument("--repeats", type=positive(int), default=2, help="renders per configuration and budget (default 2)")
    p.add_argument("--errors", type=lambda t: numbers(t, float, "--errors"),
                   help="errors to report the time to (default: chosen from the measured range)")
    p.add_argument("--metric", choices=sorted(METRICS), default="rmse",
                   help="error measure (docs/samplers.md; default rmse)")
    p.add_argument("--threads", type=positive(int), help="render threads (default: all)")
    p.add_argument("--width", type=positive(int), help="image width (the height keeps the scene's aspect ratio)")
    p.add_argument("--build", default=os.environ.get("PT_BUILD_DIR", os.path.join(ROOT, "build")),
                   help="build folder with pathtracer and tools/imgerr/pt-imgerr (default: build/)")
    p.add_argument("--keep-images", action="store_true", help="keep every render's EXR in DIR/data/")
    args = p.parse_args(argv)
    if args.spp_series and args.max_spp:
        p.error("--max-spp caps time-budgeted renders; with --spp-series the sample counts are given")
    return args


class Runner:
    """Runs the pathtracer and pt-imgerr, logs every command to DIR/data/commands.log."""

    def __init__(self, args, data):
        self.args, self.data = args, data
        self.pathtracer = os.path.join(args.build, "pathtracer")
        self.imgerr = os.path.join(args.build, "tools", "imgerr", "pt-imgerr")
        self.log = open(os.path.join(data, "commands.log"), "w")

    def common(self):
        extra = []
        if self.args.threads:
            extra += ["--threads", str(self.args.threads)]
        if self.args.width:
            extra += ["--width", str(self.args.width)]
        return extra

    def render(self, name, options):
        """Renders SCENE into data/NAME.exr with the run record data/NAME.json; returns both paths."""
        exr, report = os.path.join(self.data, name + ".exr"), os.path.join(self.data, name + ".json")
        cmd = [self.pathtracer, self.args.scene, "-o", exr, "--report", report, "--quiet"] + options + self.common()
        self.log.write("$ " + " ".join(cmd) + "\n")
        self.log.flush()
        r = subprocess.run(cmd, capture_output=True, text=True)
        self.log.write(r.stdout + r.stderr)
        if r.returncode != 0:
            raise Failure("%s exited %d:\n%s" % (" ".join(cmd), r.returncode, r.stderr.strip()))
        with open(report) as f:
            return exr, json.load(f)

    def error(self, exr, reference):
        try:
            return image_error(self.imgerr, exr, reference)
        except RuntimeError as e:
            raise Failure("pt-imgerr %s %s: %s" % (exr, reference, e))


def levels_of(args):
    if args.spp_series:
        return [("spp", n) for n in args.spp_series]
    return [("budget", args.budget / 2 ** k) for k in reversed(range(args.steps))]


def schedule(configs, levels, repeats):
    """(repeat, level, config) in the order they run: every level ascending, and at each the
    configurations forwards, then backwards at the next, and so on (ABC CBA ABC ...)."""
    order, turn = [], 0
    for rep in range(repeats):
        for level in levels:
            for config in (configs if turn % 2 == 0 else configs[::-1]):
                order.append((rep, level, config))
            turn += 1
    return order


def make_reference(args, runner, out):
    """The reference image's path and what is known of it."""
    if args.reference:
        return os.path.abspath(args.reference), {"path": os.path.abspath(args.reference), "spp": None}
    exr, record = runner.render("reference", ["--spp", str(args.reference_spp), "--sampler", "sobol", "--accel", "bvh",
                                              "--seed", str(REFERENCE_SEED)])
    path = os.path.join(out, "reference.exr")
    os.replace(exr, path)
    print("reference: %d spp, %.1f s of rendering -> %s" % (args.reference_spp, record["timings"]["render"], path))
    return path, {"path": path, "spp": args.reference_spp, "sampler": "sobol", "seed": REFERENCE_SEED,
                  "render_seconds": record["timings"]["render"], "integrator": record["image"]["integrator"]}


def measure(args, runner, reference, configs):
    rows = []
    plan = schedule(configs, levels_of(args), args.repeats)
    for i, (rep, (kind, value), (accel, sampler)) in enumerate(plan):
        options = ["--accel", accel, "--sampler", sampler, "--seed", str(i + 1)]
        if kind == "spp":
            options += ["--spp", str(value)]
        else:
            options += ["--time-budget", "%.6g" % value] + (["--spp", str(args.max_spp)] if args.max_spp else [])
        exr, record = runner.render("run-%03d" % i, options)
        e = runner.error(exr, reference)
        if not args.keep_images:
            os.remove(exr)
        rows.append({"order": i, "repeat": rep, "accel": accel, "sampler": sampler, "level_kind": kind,
                     "level": value, "seed": i + 1, "spp": record["progress"]["spp_reached"],
                     "render_seconds": record["timings"]["render"],
                     "samples_per_second": record["performance"]["samples_per_second"],
                     "accel_build_seconds": record["timings"]["accel_build"],
                     "backend": record["accel"]["backend"], "integrator": record["image"]["integrator"],
                     "mse": e["mse"], "rmse": e["rmse"], "relmse": e["rel_mse"]})
        r = rows[-1]
        print("[%d/%d] %-6s %-8s %s %-8g -> %6d spp in %7.3f s, %s %.4g" % (
            i + 1, len(plan), accel, sampler, kind, value, r["spp"], r["render_seconds"], METRICS[args.metric],
            r[args.metric]), flush=True)
    return rows


def write_data(data, rows, run):
    with open(os.path.join(data, "runs.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)
    with open(os.path.join(data, "run.json"), "w") as f:
        json.dump(run, f, indent=1)


def foreign_files(out):
    """The names in `out` that an earlier comparison did not write (the folder is only ever
    replaced when it holds a comparison: never a user's README.md or data/)."""
    ours = {"README.md", "reference.exr", "error-vs-time.png", "error-vs-time.svg", "data"}
    if not os.path.isdir(out):
        return []
    names = sorted(os.listdir(out))
    if not names:
        return []
    if not os.path.isfile(os.path.join(out, "data", "commands.log")):  # written first, by every run
        return names[:5]
    return [n for n in names if n not in ours][:5]


def main(argv):
    args = parse_args(argv)
    if not need_matplotlib():
        return EXIT_NO_MATPLOTLIB
    import compare_report  # after the check: it imports matplotlib
    for exe in ("pathtracer", os.path.join("tools", "imgerr", "pt-imgerr")):
        if not os.access(os.path.join(args.build, exe), os.X_OK):
            print("error: %s not found: build it first (cmake --build %s --target pathtracer pt-imgerr)"
                  % (os.path.join(args.build, exe), args.build), file=sys.stderr)
            return EXIT_USAGE
    if not os.path.isfile(args.scene):
        print("error: %s: no such scene file" % args.scene, file=sys.stderr)
        return EXIT_USAGE
    if args.reference and not os.path.isfile(args.reference):
        print("error: --reference %s: no such file" % args.reference, file=sys.stderr)
        return EXIT_USAGE
    out = os.path.abspath(args.out)
    data = os.path.join(out, "data")
    foreign = foreign_files(out)
    if foreign:
        print("error: --out %s holds files pathtracer-compare did not write (%s): choose a new or empty folder"
              % (out, ", ".join(foreign)), file=sys.stderr)
        return EXIT_USAGE
    if os.path.isdir(data):
        shutil.rmtree(data)  # nothing of an earlier comparison survives
    os.makedirs(data)
    runner = Runner(args, data)
    configs = list(itertools.product(args.accel, args.sampler))
    started = time.monotonic()
    loadavg = os.getloadavg()
    try:
        reference, ref_info = make_reference(args, runner, out)
        rows = measure(args, runner, reference, configs)
    except Failure as e:
        print("error: %s" % e, file=sys.stderr)
        return EXIT_FAILURE
    run = {"command": "pathtracer-compare " + " ".join(argv), "scene": args.scene, "metric": args.metric,
           "reference": ref_info, "configs": configs, "levels": levels_of(args), "repeats": args.repeats,
           "errors": args.errors, "seconds": time.monotonic() - started, "loadavg": [loadavg, os.getloadavg()],
           "date": time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime()), "cpus": os.cpu_count(),
           "threads": args.threads, "lscpu": lscpu()}
    write_data(data, rows, run)
    summary = compare_report.write(out, rows, run)
    print("wrote %s and %s (%.0f s)" % (os.path.join(out, "README.md"), os.path.join(out, "error-vs-time.png"),
                                        run["seconds"]))
    if summary.get("fastest"):
        print(summary["fastest"])
    return 0


if __name__ == "__main__":
    sys.dont_write_bytecode = True  # no __pycache__ in the source tree
    sys.path.insert(0, HERE)
    sys.exit(main(sys.argv[1:]))
