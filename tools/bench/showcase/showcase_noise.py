#!/usr/bin/env python3
"""The showcase's render time and noise (issue 21, docs/bench/showcase.md).

Renders scenes/showcase.json as the README's first command does (its own spp, seed and filter), and a
long reference of the same scene with another seed, and states the error between them: RMSE over the
frame (pt-imgerr: linear RGB clamped to [0, 1], docs/samplers.md). The reference's own noise is part of the figure: with R times the samples, it adds
about RMSE^2 / R to the squared error, which the table also states.

Times are the renderer's own (its run record: render seconds and the process's CPU seconds), never
this script's clock; on a loaded machine the wall time of the render stretches, its CPU time does not,
and CPU seconds / cores is what the render takes on an idle machine.

  python3 tools/bench/showcase/showcase_noise.py [--exe build/pathtracer] [--imgerr build/tools/imgerr/pt-imgerr]
        [--reference-spp 2048] [--runs 2] [--reference FILE.exr] [--markdown docs/bench/showcase.md]
"""
import argparse
import json
import os
import resource
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "pylib"))
from pt_tools import image_error, lscpu  # noqa: E402

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))
SCENE = os.path.join(REPO, "scenes", "showcase.json")


def showcase_aovs():
    """The --aov list tools/showcase.sh passes (its two `aovs=` lines): the first command's cost."""
    with open(os.path.join(REPO, "tools", "showcase.sh")) as f:
        parts = [line.split("=", 1)[1].strip() for line in f if line.startswith("aovs=") or line.startswith("aovs+=")]
    return "".join(parts)


def render(exe, out, extra):
    """Renders SCENE to OUT; returns its run record with the process's CPU seconds added."""
    report = out + ".run.json"
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    subprocess.run([exe, SCENE, "-o", out, "--report", report, "--quiet"] + extra, check=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    with open(report) as f:
        record = json.load(f)
    record["cpu_seconds"] = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return record


def machine():
    """The lines of `lscpu` that name the machine."""
    keep = ("Architecture", "Model name", "CPU(s)", "Thread(s) per core", "Core(s) per socket", "L3 cache")
    return "\n".join(line for line in lscpu().splitlines() if line.split(":")[0].strip() in keep)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--exe", default=os.path.join(REPO, "build", "pathtracer"))
    ap.add_argument("--imgerr", default=os.path.join(REPO, "build", "tools", "imgerr", "pt-imgerr"))
    ap.add_argument("--reference-spp", type=int, default=2048)
    ap.add_argument("--reference", help="an existing reference EXR (rendered with --seed 1000003 and the spp given)")
    ap.add_argument("--runs", type=int, default=2, help="renders of the showcase as the README makes it")
    ap.add_argument("--spp", type=int, help="override the scene's spp (a quick check of this script)")
    ap.add_argument("--markdown")
    ap.add_argument("--work", help="keep images here (default: a temporary folder)")
    args = ap.parse_args()

    work = args.work or tempfile.mkdtemp(prefix="pt-showcase-")
    os.makedirs(work, exist_ok=True)
    reference = args.reference or os.path.join(work, "reference.exr")
    ref_record = None
    if not args.reference:
        ref_record = render(args.exe, reference, ["--spp", str(args.reference_spp), "--seed", "1000003"])
    rows = []
    for run in range(args.runs):
        test = os.path.join(work, "showcase-%d.exr" % run)
        extra = ["--aov", showcase_aovs()] + (["--spp", str(args.spp)] if args.spp else [])
        record = render(args.exe, test, extra)
        linear = image_error(args.imgerr, test, reference)
        rows.append((record, linear))
        print("run %d: render %.1f s wall, %.1f s CPU, RMSE %.5f" % (
            run, record["timings"]["render"], record["cpu_seconds"],
            linear["rmse"]), file=sys.stderr)
    if args.markdown:
        write_markdown(args, rows, ref_record)


def write_markdown(args, rows, ref_record):
    spp = rows[0][0]["image"]["spp"]
    ratio = args.reference_spp / spp
    lines = [
        "# The showcase: render time and noise (issue 21)",
        "",
        "`scenes/showcase.json` as the README's first command renders it (`tools/showcase.sh`, its AOVs too), against a",
        "reference of the same scene at %d spp with another seed. Made by" % args.reference_spp,
        "`python3 tools/bench/showcase/showcase_noise.py --markdown docs/bench/showcase.md`.",
        "",
        "| run | spp | render s (wall) | process CPU s | CPU s / 2 cores | RMSE (linear) |",
        "|---|---|---|---|---|---|",
    ]
    for i, (record, linear) in enumerate(rows):
        cpu = record["cpu_seconds"]
        lines.append("| %d | %d | %.1f | %s | %s | %.5f |" % (
            i, spp, record["timings"]["render"], "%.1f" % cpu if cpu else "-",
            "%.1f" % (cpu / 2) if cpu else "-", linear["rmse"]))
    rmse = rows[0][1]["rmse"]
    lines += [
        "",
        "The reference has %.0f times the samples: its own noise adds about RMSE² / %.0f to the squared"
        % (ratio, ratio),
        "error, so the showcase's error against the converged image is about %.5f." % (
            rmse * (1 - 1 / ratio) ** 0.5),
    ]
    if ref_record:
        lines.append("The reference took %.0f s of rendering." % ref_record["timings"]["render"])
    lines += ["", "Machine (`lscpu`):", "", "```", machine(), "```", ""]
    with open(args.markdown, "w") as f:
        f.write("\n".join(lines))


if __name__ == "__main__":
    main()
