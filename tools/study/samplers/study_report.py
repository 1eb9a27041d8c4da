"""The report of the convergence study: docs/report/README.md, the plots, and
data/summary.json, from the run description (data/run.json) and the CSVs."""
import datetime
import json
import os

import study_plots
from study_fit import mean_curve, mse_at_time, read_rows, slope_summary, time_to_mse, time_trace
from study_speed_text import speed_discussion
from study_text import LITERATURE, METHOD, SPEED_NOTES
from study_verdict import discussion, literature_measured, nlogn_slope

# Fits start at this spp: below it the curves are pre-asymptotic (jittered at
# 10 spp is a 2x5 grid; Sobol' at 10 spp is not a net).
FIT_MIN_SPP = 16
# The low- and high-spp fits meet here: where a curve bends (padding), they differ.
SPLIT_SPP = 256


def _fmt_slope(s):
    if s["mean"] is None:
        return "—"
    se = " ± %.2f" % s["stderr"] if s["stderr"] is not None else ""
    return "%.2f%s" % (s["mean"], se)


def _g(x, digits=3):
    return "—" if x is None else "%.*g" % (digits, x)


def _machine_lines(info):
    keep = ("Model name", "CPU(s)", "Thread(s) per core", "Core(s) per socket", "L2 cache", "L3 cache",
            "CPU max MHz")
    lines = [ln.strip() for ln in info["lscpu"].splitlines() if ln.split(":")[0].strip() in keep]
    return lines


def _under_load(info):
    # The end's 1-minute load includes the study's own render threads.
    return max(info["loadavg_start"][0], info["loadavg_end"][0] - info["threads"]) > \
        0.5 * max(1, info["cpus"] - info["threads"]) + 0.5


def convergence_section(out, data, run, summary):
    md = ["## Convergence: MSE against spp", ""]
    for name, _, rect, what in run["scenes"]:
        rows_by_sampler = {s: read_rows(os.path.join(data, run["conv"]["%s/%s" % (name, s)]))
                           for s in run["samplers"]}
        ref = run["refs"][name]
        study_plots.convergence_plot(out, name, "%s (region %s, %d seeds)" % (name, rect, len(run["cfg"]["seeds"])),
                                     rows_by_sampler, ref["noise_mse"])
        md += ["### %s — %s" % (name, what), "",
               "![%s](convergence-%s.png) ([SVG](convergence-%s.svg))" % (name, name, name), ""]
        split = SPLIT_SPP if run["cfg"]["checkpoints"][-1] > SPLIT_SPP else run["cfg"]["checkpoints"][-1] // 4
        md += ["| sampler | MSE slope, all points | MSE slope, powers of two | RMSE slope (all) | "
               "MSE slope %d-%d | MSE slope %d-%d | MSE at %d spp | MSE at %d spp |" % (
                   FIT_MIN_SPP, split, split, run["cfg"]["checkpoints"][-1], run["cfg"]["checkpoints"][0],
                   run["cfg"]["checkpoints"][-1]),
               "|---|---|---|---|---|---|---|---|"]
        summary["convergence"][name] = {}
        smallest = None
        for sampler, rows in rows_by_sampler.items():
            fit = slope_summary(rows, FIT_MIN_SPP)
            curve = mean_curve(rows)
            smallest = curve[-1][1] if smallest is None else min(smallest, curve[-1][1])
            summary["convergence"][name][sampler] = {"fit": fit, "curve": curve}
            low = slope_summary([r for r in rows if r["spp"] <= split], FIT_MIN_SPP)["all"]
            high = slope_summary([r for r in rows if r["spp"] >= split], split)["all"]
            fit["low"], fit["high"] = low, high
            rmse = fit["all"]["mean"] / 2 if fit["all"]["mean"] is not None else None
            md.append("| %s | %s | %s | %s | %s | %s | %s | %s |" % (
                sampler, _fmt_slope(fit["all"]), _fmt_slope(fit["pow2"]), _g(rmse), _fmt_slope(low),
                _fmt_slope(high), _g(curve[0][1]), _g(curve[-1][1])))
        ratio = ref["noise_mse"] / smallest if smallest else None
        summary["convergence"][name]["reference_noise_ratio"] = ratio
        md += ["", "Slopes: least squares of log MSE against log spp for each seed (spp >= %d), mean ± standard "
               "error over the %d seeds. Reference: %d spp (sobol); the MSE between two references of different "
               "seeds is %s, so one reference's own noise (%s) is %s of the smallest MSE measured here%s." % (
                   FIT_MIN_SPP, len(run["cfg"]["seeds"]), ref["spp"], _g(ref["pair_mse"]), _g(ref["noise_mse"]),
                   "%.1f%%" % (100 * ratio) if ratio is not None else "—",
                   "" if ratio is not None and ratio < 0.1 else " — **too large: the reference limits this study**"),
               "", discussion(name, summary["convergence"][name], split), ""]
    return md


def speed_facts(out, data, run, case):
    """The numbers of one speed case (study_speed_text.py lists them); draws its plot."""
    by_config = {(a, s): read_rows(os.path.join(data, run["speed"]["%s/%s/%s" % (case, a, s)]))
                 for a in run["accels"] for s in run["samplers"]}
    study_plots.speed_plot(out, case, by_config)
    traces = {k: time_trace(v) for k, v in by_config.items()}
    # Times every configuration covers: from the latest first checkpoint to the earliest last one.
    t_lo = max(t[0][0] for t in traces.values())
    t_hi = min(t[-1][0] for t in traces.values())
    times = sorted({min(t_hi, float("%.2g" % max(t_lo, t_hi * f))) for f in (0.1, 0.3, 1.0)})
    times = [t for t in times if t_lo <= t <= t_hi] or [t_hi]
    rate = {}
    for k, rows in by_config.items():
        last = max(rows, key=lambda r: r["spp"])
        rate[k] = last["spp"] / last["seconds"]
    equal_time = {k: [mse_at_time(trace, t) for t in times] for k, trace in traces.items()}
    common = set.intersection(*[{r["spp"] for r in rows} for rows in by_config.values()])
    equal_spp = None
    if common:
        n = max(common)
        equal_spp = (n, {k: next(r["mse"] for r in rows if r["spp"] == n) for k, rows in by_config.items()})
    return {"case": case, "accels": run["accels"], "samplers": run["samplers"], "times": times, "rows": by_config,
            "traces": traces, "rate": rate, "equal_time": equal_time, "equal_spp": equal_spp,
            "budget": run["budgets"][case]}


def equal_time_table(f, case_summary):
    md = ["**Equal time**: MSE reached after T seconds of rendering (log-log interpolation between "
          "checkpoints; in brackets, relative to embree/random).", "",
          "| accel | sampler | " + " | ".join("T = %.3g s" % t for t in f["times"]) + " |",
          "|---|---|" + "---|" * len(f["times"])]
    base = f["equal_time"][("embree", "random")]
    for (accel, sampler), values in f["equal_time"].items():
        cells = ["%s (%s)" % (_g(e), "%.2fx" % (e / b) if e and b else "—") for e, b in zip(values, base)]
        for t, e in zip(f["times"], values):
            case_summary["equal_time"]["%s/%s/%g" % (accel, sampler, t)] = e
        md.append("| %s | %s | %s |" % (accel, sampler, " | ".join(cells)))
    return md


def equal_error_table(f, case_summary):
    base = f["traces"][("embree", "random")]
    targets = [x for x in f["equal_time"][("embree", "random")] if x]
    md = ["**Equal error**: seconds each configuration needs to reach the MSE that embree/random reaches "
          "at %s s (in brackets, speed-up over embree/random; — : not reached within the budget)." %
          ", ".join("%.3g" % t for t in f["times"][:len(targets)]), "",
          "| accel | sampler | " + " | ".join("MSE %s" % _g(x) for x in targets) + " |",
          "|---|---|" + "---|" * len(targets)]
    for (accel, sampler), trace in f["traces"].items():
        cells = []
        for x in targets:
            t, b = time_to_mse(trace, x), time_to_mse(base, x)
            cells.append("%s (%s)" % (_g(t), "%.2fx" % (b / t) if t and b else "—"))
            case_summary["equal_error"]["%s/%s/%.3g" % (accel, sampler, x)] = t
        md.append("| %s | %s | %s |" % (accel, sampler, " | ".join(cells)))
    return md


def speed_section(out, data, run, summary):
    md = ["## Speed against error", "", SPEED_NOTES, ""]
    facts = [speed_facts(out, data, run, case) for case in run["speed_cases"]]
    for f in facts:
        case = f["case"]
        rate = ", ".join("%s/%s %.3g" % (a, s, r) for (a, s), r in f["rate"].items())
        md += ["### %s" % case, "", "![%s](speed-%s.png) ([SVG](speed-%s.svg))" % (case, case, case), "",
               "Budget %g s of rendering per configuration. Samples per pixel per second at the last checkpoint "
               "(the cost of a sample; for jittered, of its last render): %s." % (f["budget"], rate), ""]
        case_summary = {"equal_time": {}, "equal_error": {}}
        md += equal_time_table(f, case_summary) + [""] + equal_error_table(f, case_summary)
        if f["equal_spp"]:
            n, at_n = f["equal_spp"]
            case_summary["equal_spp"] = {"spp": n, "mse": {"%s/%s" % k: v for k, v in at_n.items()}}
            md += ["", "**Equal spp**: MSE at %d spp, the last checkpoint every configuration reached: %s." % (
                n, ", ".join("%s/%s %s" % (a, sm, _g(v)) for (a, sm), v in at_n.items()))]
        others = [o for o in facts if o is not f]
        md += ["", speed_discussion(f, others, summary["convergence"].get(case)), ""]
        summary["speed"][case] = case_summary
    return md


def write_report(out):
    data = os.path.join(out, "data")
    with open(os.path.join(data, "run.json")) as f:
        run = json.load(f)
    info = run["info"]
    summary = {"convergence": {}, "speed": {}, "info": info, "cfg": run["cfg"]}
    load = _under_load(info)
    md = ["# Sampler convergence and speed against error", "",
          "Generated by `%s` (%s mode, %s, %.0f s, %d render threads); every file in this folder is rewritten "
          "by it — do not edit by hand." % (info["command"], run["cfg"]["mode"], info["date"], info["seconds"],
                                           info["threads"]), ""]
    if run["cfg"]["mode"] != "full":
        md += ["**Quick mode: a smoke run, not a measurement.**", ""]
    md += ["## Machine", "", "```"] + _machine_lines(info) + ["```", "",
           "Load average (1 min) %.2f at the start, %.2f at the end, on %d CPUs. %s" % (
               info["loadavg_start"][0], info["loadavg_end"][0], info["cpus"],
               "**Timings were taken under load** (other builds were running on this machine): the times are "
               "upper bounds and the ratios between configurations are less certain than on an idle machine; "
               "rerun the command above on an idle machine to replace them." if load else
               "The machine was idle enough for the timings to stand."), "", METHOD, ""]
    md += convergence_section(out, data, run, summary)
    md += ["## Comparison with the literature", "", LITERATURE.replace("{nlogn}", "%.2f" % nlogn_slope()), "",
           literature_measured(summary["convergence"]), ""]
    md += speed_section(out, data, run, summary)
    md += ["## Data", "", "`data/`: `run.json` (settings, references, machine), `summary.json` (every fitted slope "
           "and per-seed value, the mean curves, the tables), `converge-SCENE-SAMPLER.csv` and "
           "`speed-CASE-ACCEL-SAMPLER.csv` (pt-converge's rows: scene, accel, sampler, seed, spp, seconds, mse, "
           "rel_mse, rmse), the references `ref-SCENE-SEED.exr`, and `commands.log` (every command run).", ""]
    with open(os.path.join(out, "README.md"), "w") as f:
        f.write("\n".join(md))
    with open(os.path.join(data, "summary.json"), "w") as f:
        json.dump(summary, f, indent=1)
    return summary


def now():
    return datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
