"""The report of the convergence study: docs/report/README.md, the plots, and
data/summary.json, from the run description (data/run.json) and the CSVs.

The prose is report_template.md, written by hand. This module only measures:
it fills the template's {{key}} placeholders with numbers and tables computed
from the run's data, and drops the {{#if key}} ... {{/if}} blocks whose key
the run has no data for (the Cornell box when ../shared is missing)."""
import datetime
import json
import math
import os
import re

import study_plots
from study_fit import loglog_slope, mean_curve, mse_at_time, read_rows, slope_summary, time_to_mse, time_trace

HERE = os.path.dirname(os.path.abspath(__file__))
TEMPLATE = os.path.join(HERE, "report_template.md")
# Fits start at this spp: below it the curves are pre-asymptotic (jittered at
# 10 spp is a 2x5 grid; Sobol' at 10 spp is not a net).
FIT_MIN_SPP = 16
# The low- and high-spp fits meet here: where a curve bends (padding), they differ.
SPLIT_SPP = 256
# The early / late slopes of a speed curve are fitted from this spp on.
FLAT_MIN_SPP = 16
# The issue-4 time-to-error target, per-channel RMSE 0.005, as this report's MSE (channels summed).
TARGET_MSE = 3 * 0.005 ** 2
STRATIFIED = ("jittered", "sobol")


def _g(v, digits=3):
    return "—" if v is None else "%.*g" % (digits, v)


def _x(ratio):
    """A ratio as '1.17x' or '0.0217x'."""
    if ratio is None:
        return "—"
    return "%.2fx" % ratio if ratio >= 0.1 else "%.3gx" % ratio


def _sl(s):
    return "—" if s is None else "%.2f" % s


def _fmt_slope(s):
    if s["mean"] is None:
        return "—"
    se = " ± %.2f" % s["stderr"] if s["stderr"] is not None else ""
    return "%.2f%s" % (s["mean"], se)


def _machine_lines(info):
    keep = ("Model name", "CPU(s)", "Thread(s) per core", "Core(s) per socket", "L2 cache", "L3 cache",
            "CPU max MHz")
    return [ln.strip() for ln in info["lscpu"].splitlines() if ln.split(":")[0].strip() in keep]


def nlogn_slope(lo=16, hi=1024):
    """Least-squares slope of log(N^-3 log N) against log N at the powers of two in [lo, hi]."""
    ns = [n for n in (2 ** k for k in range(0, 31)) if lo <= n <= hi]
    return loglog_slope([(n, n ** -3.0 * math.log(n)) for n in ns])


def convergence_table(fits, curves, split, checkpoints):
    md = ["| sampler | MSE slope, all points | MSE slope, powers of two | RMSE slope (all) | "
          "MSE slope %d-%d | MSE slope %d-%d | MSE at %d spp | MSE at %d spp |" % (
              FIT_MIN_SPP, split, split, checkpoints[-1], checkpoints[0], checkpoints[-1]),
          "|---|---|---|---|---|---|---|---|"]
    for sampler, fit in fits.items():
        rmse = fit["all"]["mean"] / 2 if fit["all"]["mean"] is not None else None
        md.append("| %s | %s | %s | %s | %s | %s | %s | %s |" % (
            sampler, _fmt_slope(fit["all"]), _fmt_slope(fit["pow2"]), _g(rmse), _fmt_slope(fit["low"]),
            _fmt_slope(fit["high"]), _g(curves[sampler][0][1]), _g(curves[sampler][-1][1])))
    return "\n".join(md)


def curve_values(v, name, curves):
    """Per sampler: MSE relative to random over the checkpoints, and how often the mean curve rises."""
    rnd = {c[0]: c[1] for c in curves["random"]}
    for sampler, curve in curves.items():
        ratios = [c[1] / rnd[c[0]] for c in curve if rnd.get(c[0])]
        key = "%s.%s." % (name, sampler)
        v[key + "ratio_last"] = _x(ratios[-1])
        v[key + "ratio_min"], v[key + "ratio_max"] = _x(min(ratios)), _x(max(ratios))
        v[key + "lower"] = "%d" % sum(1 for r in ratios if r < 1)
        v[key + "rises"] = "%d" % sum(1 for a, b in zip(curve, curve[1:]) if b[1] > a[1])
    jit, sob = curves["jittered"], curves["sobol"]
    v[name + ".sobol_lower"] = "%d" % sum(1 for j, s in zip(jit, sob) if s[1] < j[1])
    v[name + ".checkpoints"] = "%d" % len(jit)
    v[name + ".steps"] = "%d" % (len(jit) - 1)


def convergence_values(v, out, data, run, summary):
    checkpoints = run["cfg"]["checkpoints"]
    split = SPLIT_SPP if checkpoints[-1] > SPLIT_SPP else checkpoints[-1] // 4
    v["seeds"], v["fit_min_spp"], v["split"] = "%d" % len(run["cfg"]["seeds"]), "%d" % FIT_MIN_SPP, "%d" % split
    v["first_spp"], v["last_spp"] = "%d" % checkpoints[0], "%d" % checkpoints[-1]
    for name, _, rect, _ in run["scenes"]:
        rows = {s: read_rows(os.path.join(data, run["conv"]["%s/%s" % (name, s)])) for s in run["samplers"]}
        ref = run["refs"][name]
        study_plots.convergence_plot(out, name, "%s (region %s, %d seeds)" % (name, rect, len(run["cfg"]["seeds"])),
                                     rows, ref["noise_mse"])
        fits, curves = {}, {}
        for sampler, r in rows.items():
            fits[sampler] = slope_summary(r, FIT_MIN_SPP)
            fits[sampler]["low"] = slope_summary([x for x in r if x["spp"] <= split], FIT_MIN_SPP)["all"]
            fits[sampler]["high"] = slope_summary([x for x in r if x["spp"] >= split], split)["all"]
            curves[sampler] = mean_curve(r)
            for subset in ("all", "pow2", "low", "high"):
                v["%s.%s.%s" % (name, sampler, subset)] = _sl(fits[sampler][subset]["mean"])
        smallest = min(c[-1][1] for c in curves.values())
        ratio = ref["noise_mse"] / smallest if smallest else None
        summary["convergence"][name] = {s: {"fit": fits[s], "curve": curves[s]} for s in rows}
        summary["convergence"][name]["reference_noise_ratio"] = ratio
        v[name + ".table"] = convergence_table(fits, curves, split, checkpoints)
        v[name + ".ref_spp"] = "%d" % ref["spp"]
        v[name + ".ref_pair_mse"], v[name + ".ref_noise"] = _g(ref["pair_mse"]), _g(ref["noise_mse"])
        v[name + ".ref_noise_pct"] = "%.1f%%" % (100 * ratio) if ratio is not None else "—"
        curve_values(v, name, curves)


def speed_facts(out, data, run, case):
    """The numbers of one speed case; draws its plot."""
    by_config = {(a, s): read_rows(os.path.join(data, run["speed"]["%s/%s/%s" % (case, a, s)]))
                 for a in run["accels"] for s in run["samplers"]}
    study_plots.speed_plot(out, case, by_config)
    traces = {k: time_trace(v) for k, v in by_config.items()}
    # Times every configuration covers: from the latest first checkpoint to the earliest last one.
    t_lo = max(t[0][0] for t in traces.values())
    t_hi = min(t[-1][0] for t in traces.values())
    times = sorted({min(t_hi, float("%.2g" % max(t_lo, t_hi * f))) for f in (0.1, 0.3, 1.0)})
    times = [t for t in times if t_lo <= t <= t_hi] or [t_hi]
    rate = {k: max(rows, key=lambda r: r["spp"])["spp"] / max(rows, key=lambda r: r["spp"])["seconds"]
            for k, rows in by_config.items()}
    equal_time = {k: [mse_at_time(trace, t) for t in times] for k, trace in traces.items()}
    common = set.intersection(*[{r["spp"] for r in rows} for rows in by_config.values()])
    equal_spp = None
    if common:
        n = max(common)
        equal_spp = (n, {k: next(r["mse"] for r in rows if r["spp"] == n) for k, rows in by_config.items()})
    return {"case": case, "accels": run["accels"], "samplers": run["samplers"], "times": times, "rows": by_config,
            "traces": traces, "rate": rate, "equal_time": equal_time, "equal_spp": equal_spp, "common": common,
            "budget": run["budgets"][case]}


def equal_time_table(f, case_summary):
    md = ["| accel | sampler | " + " | ".join("T = %.3g s" % t for t in f["times"]) + " |",
          "|---|---|" + "---|" * len(f["times"])]
    base = f["equal_time"][("embree", "random")]
    for (accel, sampler), values in f["equal_time"].items():
        cells = ["%s (%s)" % (_g(e), "%.2fx" % (e / b) if e and b else "—") for e, b in zip(values, base)]
        for t, e in zip(f["times"], values):
            case_summary["equal_time"]["%s/%s/%g" % (accel, sampler, t)] = e
        md.append("| %s | %s | %s |" % (accel, sampler, " | ".join(cells)))
    return "\n".join(md)


def equal_error_table(f, case_summary):
    base = f["traces"][("embree", "random")]
    targets = [x for x in f["equal_time"][("embree", "random")] if x]
    md = ["| accel | sampler | " + " | ".join("MSE %s" % _g(x) for x in targets) + " |",
          "|---|---|" + "---|" * len(targets)]
    for (accel, sampler), trace in f["traces"].items():
        cells = []
        for x in targets:
            t, b = time_to_mse(trace, x), time_to_mse(base, x)
            cells.append("%s (%s)" % (_g(t), "%.2fx" % (b / t) if t and b else "—"))
            case_summary["equal_error"]["%s/%s/%.3g" % (accel, sampler, x)] = t
            if t and b and sampler != "random":
                f.setdefault("speedups", []).append(b / t)
        md.append("| %s | %s | %s |" % (accel, sampler, " | ".join(cells)))
    return "\n".join(md)


def speed_ratio_values(v, f):
    """Per backend and stratified sampler: cost per sample, equal-time and equal-spp MSE against random."""
    c = f["case"]
    for a in f["accels"]:
        for s in f["samplers"]:
            key = "%s.%s.%s." % (c, a, s)
            v[key + "cost"] = _x(f["rate"][(a, "random")] / f["rate"][(a, s)])
            last_t, last_r = f["equal_time"][(a, s)][-1], f["equal_time"][(a, "random")][-1]
            v[key + "time_ratio"] = _x(last_t / last_r) if last_t and last_r else "—"
            v[key + "time_mse"] = ", ".join(_g(e) for e in f["equal_time"][(a, s)])
            t = time_to_mse(f["traces"][(a, s)], TARGET_MSE)
            v[key + "target_s"] = "%.3g s" % t if t else "not reached"
            if f["equal_spp"]:
                mse = f["equal_spp"][1]
                v[key + "spp_ratio"] = _x(mse[(a, s)] / mse[(a, "random")])
                v[key + "spp_mse"] = _g(mse[(a, s)])
        lower = {s: sum(1 for e, b in zip(f["equal_time"][(a, s)], f["equal_time"][(a, "random")])
                        if e and b and e < b) for s in STRATIFIED}
        for s in STRATIFIED:
            v["%s.%s.%s.time_lower" % (c, a, s)] = "%d" % lower[s]
        v["%s.%s.sobol_time_lower" % (c, a)] = "%d" % sum(
            1 for e_s, e_j in zip(f["equal_time"][(a, "sobol")], f["equal_time"][(a, "jittered")])
            if e_s and e_j and e_s < e_j)
    a0, a1 = f["accels"][0], f["accels"][-1]
    for s in f["samplers"]:
        v["%s.%s_over_%s.%s" % (c, a1, a0, s)] = _x(f["rate"][(a1, s)] / f["rate"][(a0, s)])
    if f["equal_spp"]:
        mse = f["equal_spp"][1]
        dev = max(abs(mse[(a1, s)] / mse[(a0, s)] - 1) for s in f["samplers"] if mse.get((a0, s)))
        v[c + ".backend_mse_dev"] = "%.2g%%" % (100 * dev)


def speed_curve_values(v, f):
    """The first common checkpoint's ratios, and early / late slopes of MSE against spp (first backend)."""
    c, a = f["case"], f["accels"][0]
    first = min(f["common"]) if f["common"] else None
    if first is not None:
        at = {s: next(r["mse"] for r in f["rows"][(a, s)] if r["spp"] == first) for s in f["samplers"]}
        v[c + ".first_spp"] = "%d" % first
        for s in STRATIFIED:
            v["%s.first.%s" % (c, s)] = _x(at[s] / at["random"])
    for s in f["samplers"]:
        pts = [(r["spp"], r["mse"]) for r in f["rows"][(a, s)] if r["spp"] >= FLAT_MIN_SPP]
        mid = (pts[0][0] * pts[-1][0]) ** 0.5 if pts else 0
        early = loglog_slope([p for p in pts if p[0] <= mid])
        late = loglog_slope([p for p in pts if p[0] >= mid])
        v["%s.early.%s" % (c, s)], v["%s.late.%s" % (c, s)] = _sl(early), _sl(late)


def speed_values(v, out, data, run, summary):
    for case in run["speed_cases"]:
        f = speed_facts(out, data, run, case)
        case_summary = {"equal_time": {}, "equal_error": {}}
        v[case] = "yes"
        v[case + ".budget"] = "%g" % f["budget"]
        v[case + ".rates"] = ", ".join("%s/%s %.3g" % (a, s, r) for (a, s), r in f["rate"].items())
        v[case + ".times"] = ", ".join("%.3g" % t for t in f["times"])
        v[case + ".t_last"] = "%.3g" % f["times"][-1]
        v[case + ".equal_time_table"] = equal_time_table(f, case_summary)
        v[case + ".equal_error_table"] = equal_error_table(f, case_summary)
        if f.get("speedups"):
            v[case + ".speedup_min"], v[case + ".speedup_max"] = _x(min(f["speedups"])), _x(max(f["speedups"]))
        if f["equal_spp"]:
            n, at_n = f["equal_spp"]
            case_summary["equal_spp"] = {"spp": n, "mse": {"%s/%s" % k: e for k, e in at_n.items()}}
            v[case + ".equal_spp"] = "%d" % n
            v[case + ".equal_spp_list"] = ", ".join("%s/%s %s" % (a, s, _g(e)) for (a, s), e in at_n.items())
        speed_ratio_values(v, f)
        speed_curve_values(v, f)
        summary["speed"][case] = case_summary


def header_values(v, run, prose_run):
    info = run["info"]
    v.update(command=info["command"], mode=run["cfg"]["mode"], date=info["date"], seconds="%.0f" % info["seconds"],
             threads="%d" % info["threads"], cpus="%d" % info["cpus"], machine="\n".join(_machine_lines(info)),
             load_start="%.2f" % info["loadavg_start"][0], load_end="%.2f" % info["loadavg_end"][0],
             nlogn="%.2f" % nlogn_slope(), target_mse="%.2g" % TARGET_MSE, prose_run=prose_run)
    if run["cfg"]["mode"] != "full":
        v["quick"] = "yes"
    if info["date"] != prose_run:
        v["other_run"] = "yes"


def fill(template, values):
    """{{#if key}}...{{/if}} kept where values has key; every {{key}} replaced (an unknown key is an error)."""
    template = re.sub(r"\{\{#if ([^}]+)\}\}(.*?)\{\{/if\}\}",
                      lambda m: m.group(2) if m.group(1) in values else "", template, flags=re.S)

    def value(m):
        if m.group(1) not in values:
            raise KeyError("report_template.md: no value for {{%s}}" % m.group(1))
        return values[m.group(1)]
    return re.sub(r"\{\{([^}#/][^}]*)\}\}", value, template)


def write_report(out):
    data = os.path.join(out, "data")
    with open(os.path.join(data, "run.json")) as f:
        run = json.load(f)
    with open(TEMPLATE) as f:
        template = f.read()
    # The run the hand-written discussions describe (the template says so): other data get a warning.
    prose_run = re.search(r"<!-- prose written for the run of (.*?) -->", template).group(1)
    template = re.sub(r"<!--.*?-->\n", "", template, flags=re.S)  # notes for whoever edits the template
    summary = {"convergence": {}, "speed": {}, "info": run["info"], "cfg": run["cfg"]}
    values = {}
    header_values(values, run, prose_run)
    convergence_values(values, out, data, run, summary)
    speed_values(values, out, data, run, summary)
    with open(os.path.join(out, "README.md"), "w") as f:
        f.write(fill(template, values))
    with open(os.path.join(data, "summary.json"), "w") as f:
        json.dump(summary, f, indent=1)
    return summary


def now():
    return datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
