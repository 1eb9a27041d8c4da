#!/usr/bin/env python3
"""The sampler convergence study and the speed-versus-error comparison, in one
command; writes docs/report/ from scratch (README.md, PNG/SVG plots, CSV/JSON).

    python3 tools/study/samplers/run_study.py                  # the real run, ~6 min on 2 idle cores
    python3 tools/study/samplers/run_study.py --quick --out /tmp/report   # smoke run, < 1 min

Needs the build (build/pathtracer, build/tools/study/samplers/pt-converge,
build/tools/imgerr/pt-imgerr) and matplotlib (Debian: apt-get install
python3-matplotlib). Steps:

1. references: every study scene (tools/study/samplers/scenes/) rendered twice with the
   sobol sampler at REF_SPP and two seeds far from the study's; the MSE between
   the two is twice the noise of one, and must be far below the smallest MSE
   the study measures (checked and reported);
2. convergence: pt-converge for every scene and sampler, checkpoints from 10 to
   2000 spp in steps of 50 plus the powers of two, several seeds; per-seed
   least-squares slopes of log MSE against log spp (all points, powers of two);
3. speed against error: pt-converge with wall time for --accel embree and bvh
   and every sampler, on the Cornell box (256x256, the Cycles reference in
   ../shared) and the soft-shadow study scene; equal-time and equal-error tables;
4. the report: report_template.md (prose written by hand) filled with the
   run's numbers and tables (study_report.py).
"""
import argparse
import json
import os
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(os.path.dirname(HERE)))  # tools/study/samplers -> repository
EXIT_NO_MATPLOTLIB = 77  # CTest's skip code for the test that runs --quick

SAMPLERS = ["random", "jittered", "sobol"]
ACCELS = ["embree", "bvh"]
# name, file, MSE region (X,Y,W,H), what it isolates
SCENES = [
    ("aa-edges", "aa-edges.json", "0,0,32,32", "antialiasing alone: edges of emitters, no lighting (max_depth 0)"),
    ("soft-shadow", "soft-shadow.json", "0,4,32,24",
     "soft shadow of a sphere from an area light, direct light only (max_depth 1: light -> surface -> camera)"),
    ("thin-lens", "thin-lens.json", "0,0,32,32", "thin-lens depth of field: defocused emitters (max_depth 0)"),
]


def need_matplotlib():
    try:
        import matplotlib  # noqa: F401
        return True
    except ImportError:
        debian = "/usr/bin/python3"
        if os.path.realpath(sys.executable) != os.path.realpath(debian) and os.path.exists(debian):
            probe = subprocess.run([debian, "-c", "import matplotlib"], capture_output=True)
            if probe.returncode == 0:  # this interpreter lacks it, Debian's has it
                os.execv(debian, [debian] + sys.argv)
        print("error: matplotlib is missing: install it with `sudo apt-get install -y python3-matplotlib`"
              " (Debian 12) and run this tool with /usr/bin/python3", file=sys.stderr)
        return False


def settings(quick):
    if quick:
        return {"mode": "quick", "ref_spp": {s[0]: 1024 for s in SCENES}, "seeds": [1, 2], "checkpoints": sorted(
            set(range(10, 201, 50)) | {16, 32, 64, 128, 256}),
            # The speed runs stop at 32 spp, not at a time budget: under load a short budget left
            # configurations whose time ranges did not overlap, and empty tables. The budget
            # is only a cap that an idle or a loaded machine does not reach.
            "cornell_budget_s": 60.0, "study_budget_s": 60.0,
            "speed_checkpoints": [1, 2, 4, 8, 16, 32]}
    geometric = sorted({int(round(1.5 ** k)) for k in range(0, 40)} | {2 ** k for k in range(0, 20)})
    return {"mode": "full", "ref_spp": {"aa-edges": 16384, "soft-shadow": 65536, "thin-lens": 65536}, "seeds": list(range(1, 7)),
            "checkpoints": sorted(set(range(10, 2001, 50)) | {2000} | {2 ** k for k in range(4, 12)}),
            "cornell_budget_s": 10.0, "study_budget_s": 3.0,
            "speed_checkpoints": [n for n in geometric if n <= 1 << 18]}


def run(cmd, log):
    """Runs cmd from the repository root (so paths inside it, like the scene column of the CSVs, are relative)."""
    log.write("$ " + " ".join(cmd) + "\n")
    log.flush()
    result = subprocess.run(cmd, capture_output=True, text=True, cwd=ROOT)
    log.write(result.stdout + result.stderr)
    if result.returncode != 0:
        sys.exit("error: %s failed (exit %d):\n%s" % (cmd[0], result.returncode, result.stderr.strip()))
    return result.stdout


def imgerr(tools, test, ref, rect, log):
    out = run([tools["imgerr"], test, ref, "--rect", rect, "--json"], log)
    return json.loads(out)


def make_references(cfg, tools, data, threads, log):
    refs = {}
    for name, scene_file, rect, _ in SCENES:
        paths = []
        t = time.monotonic()
        for seed in (100001, 100002):
            path = os.path.join(data, "ref-%s-%d.exr" % (name, seed))
            run([tools["pathtracer"], os.path.join(HERE, "scenes", scene_file), "-o", path, "--spp",
                 str(cfg["ref_spp"][name]), "--sampler", "sobol", "--seed", str(seed), "--threads", str(threads),
                 "--quiet"], log)
            paths.append(path)
        pair = imgerr(tools, paths[1], paths[0], rect, log)
        refs[name] = {"path": paths[0], "spp": cfg["ref_spp"][name], "pair_mse": pair["mse"],
                      "noise_mse": pair["mse"] / 2, "seconds": time.monotonic() - t}
        print("reference %s: %d spp, MSE between two seeds %.3g" % (name, cfg["ref_spp"][name], pair["mse"]))
    return refs


def converge(tools, scene, ref, out_csv, accel, sampler, checkpoints, seeds, threads, log, rect=None,
             max_seconds=None):
    cmd = [tools["converge"], os.path.relpath(scene, ROOT), "--reference", ref, "--accel", accel, "--sampler", sampler,
           "--checkpoints", ",".join(map(str, checkpoints)), "--seeds", ",".join(map(str, seeds)),
           "--threads", str(threads), "--csv", out_csv]
    if rect:
        cmd += ["--rect", rect]
    if max_seconds:
        cmd += ["--max-seconds", str(max_seconds)]
    run(cmd, log)
    return out_csv


def convergence_study(cfg, tools, data, refs, threads, log):
    csvs = {}
    for name, scene_file, rect, _ in SCENES:
        for sampler in SAMPLERS:
            t = time.monotonic()
            csvs[(name, sampler)] = converge(
                tools, os.path.join(HERE, "scenes", scene_file), refs[name]["path"],
                os.path.join(data, "converge-%s-%s.csv" % (name, sampler)), "embree", sampler,
                cfg["checkpoints"], cfg["seeds"], threads, log, rect=rect)
            print("convergence %s %s: %.1f s" % (name, sampler, time.monotonic() - t))
    return csvs


def speed_study(cfg, tools, data, refs, threads, log):
    cornell_ref = os.path.join(ROOT, "..", "shared", "reference", "cornell-box", "cornell_cycles_8192spp.exr")
    cases = []
    if os.path.exists(cornell_ref):
        cases.append(("cornell-box", os.path.join(ROOT, "scenes", "cornell-box.json"), cornell_ref, None,
                      cfg["cornell_budget_s"]))
    else:
        print("warning: %s not found: the Cornell box part of the speed study is skipped" % cornell_ref)
    name, scene_file, rect, _ = SCENES[1]
    cases.append((name, os.path.join(HERE, "scenes", scene_file), refs[name]["path"], rect, cfg["study_budget_s"]))
    csvs = {}
    for case, scene, ref, rect, budget in cases:
        for accel in ACCELS:
            for sampler in SAMPLERS:
                t = time.monotonic()
                csvs[(case, accel, sampler)] = converge(
                    tools, scene, ref, os.path.join(data, "speed-%s-%s-%s.csv" % (case, accel, sampler)), accel,
                    sampler, cfg["speed_checkpoints"], [1], threads, log, rect=rect, max_seconds=budget)
                print("speed %s %s %s: %.1f s" % (case, accel, sampler, time.monotonic() - t))
    return csvs, [c[0] for c in cases], {c[0]: c[4] for c in cases}


def machine():
    try:
        lscpu = subprocess.run(["lscpu"], capture_output=True, text=True).stdout
    except OSError:
        lscpu = "(lscpu not available)"
    return {"lscpu": lscpu, "cpus": os.cpu_count(), "loadavg_start": os.getloadavg()}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--build", default=os.path.join(ROOT, "build"), help="build folder (default: build/)")
    parser.add_argument("--out", default=os.path.join(ROOT, "docs", "report"), help="report folder")
    parser.add_argument("--threads", type=int, default=2, help="render threads (default 2)")
    parser.add_argument("--quick", action="store_true", help="smoke run (< 1 min): few spp, 2 seeds, short budgets")
    parser.add_argument("--report-only", action="store_true",
                        help="rewrite README.md, the plots and data/summary.json from the CSVs and run.json of an "
                             "earlier run in data/ (no rendering, no build needed)")
    args = parser.parse_args()
    args.build, args.out = os.path.abspath(args.build), os.path.abspath(args.out)  # commands run from the root
    if not need_matplotlib():
        return EXIT_NO_MATPLOTLIB
    tools = {"pathtracer": os.path.join(args.build, "pathtracer"),
             "converge": os.path.join(args.build, "tools", "study", "samplers", "pt-converge"),
             "imgerr": os.path.join(args.build, "tools", "imgerr", "pt-imgerr")}
    import study_report  # after the matplotlib check: it imports matplotlib

    if args.report_only:  # the markdown, plots and summary again, from data/ of an earlier run: no build needed
        study_report.write_report(args.out)
        print("wrote %s" % os.path.join(args.out, "README.md"))
        return 0
    for exe in tools.values():
        if not os.access(exe, os.X_OK):
            sys.exit("error: %s not found: build first (cmake --build %s)" % (exe, args.build))
    cfg = settings(args.quick)
    data = os.path.join(args.out, "data")
    os.makedirs(data, exist_ok=True)
    for f in os.listdir(data):  # from scratch: nothing of an earlier run survives
        if f.endswith((".csv", ".exr", ".json", ".log")):
            os.remove(os.path.join(data, f))
    info = machine()
    started = time.monotonic()
    with open(os.path.join(data, "commands.log"), "w") as log:
        refs = make_references(cfg, tools, data, args.threads, log)
        conv = convergence_study(cfg, tools, data, refs, args.threads, log)
        speed, speed_cases, budgets = speed_study(cfg, tools, data, refs, args.threads, log)
    info["loadavg_end"] = os.getloadavg()
    info["seconds"] = time.monotonic() - started
    info["threads"] = args.threads
    info["command"] = "python3 tools/study/samplers/run_study.py" + (" --quick" if args.quick else "")
    info["date"] = study_report.now()
    run_desc = {"cfg": cfg, "scenes": SCENES, "samplers": SAMPLERS, "accels": ACCELS, "info": info,
                "refs": {k: dict(v, path=os.path.basename(v["path"])) for k, v in refs.items()},
                "conv": {"%s/%s" % k: os.path.basename(v) for k, v in conv.items()},
                "speed": {"%s/%s/%s" % k: os.path.basename(v) for k, v in speed.items()},
                "speed_cases": speed_cases, "budgets": budgets}
    with open(os.path.join(data, "run.json"), "w") as f:
        json.dump(run_desc, f, indent=1)
    summary = study_report.write_report(args.out)
    print("wrote %s (%.0f s)" % (os.path.join(args.out, "README.md"), info["seconds"]))
    return 0 if summary else 1


if __name__ == "__main__":
    sys.dont_write_bytecode = True  # no __pycache__ in the source tree
    sys.path.insert(0, HERE)
    sys.exit(main())
