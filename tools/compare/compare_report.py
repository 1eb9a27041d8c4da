"""pathtracer-compare's report: the plot (error against render time, log-log) and
README.md (time to given errors, samples per second, the machine) from its
measurements (the rows of data/runs.csv and data/run.json)."""
import math
import os
import statistics

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

METRIC_NAMES = {"rmse": "RMSE", "relmse": "relMSE", "mse": "MSE"}


def label(config):
    return "%s + %s" % tuple(config)


def curves(rows, configs, metric):
    """Per configuration, one point per level (budget or spp): the medians over the repeats
    of render time and error, in increasing time."""
    out = {}
    for config in configs:
        mine = [r for r in rows if (r["accel"], r["sampler"]) == tuple(config)]
        points = []
        for level in sorted({r["level"] for r in mine}):
            at = [r for r in mine if r["level"] == level]
            points.append((statistics.median(r["render_seconds"] for r in at),
                           statistics.median(r[metric] for r in at)))
        out[tuple(config)] = sorted(points)
    return out


def time_to(points, target):
    """Render time at which the error curve (log-log, linear between its points) first
    falls to `target`: (seconds, how) with how '' (interpolated), '<=' (already below
    at the first point: at most that time) or '>' (never: more than the last time)."""
    if not points:
        return None, ">"
    if points[0][1] <= target:
        return points[0][0], "<="
    for (t0, e0), (t1, e1) in zip(points, points[1:]):
        if e1 <= target < e0 and t0 > 0 and t1 > 0 and e1 > 0:
            f = (math.log(target) - math.log(e0)) / (math.log(e1) - math.log(e0))
            return math.exp(math.log(t0) + f * (math.log(t1) - math.log(t0))), ""
    return points[-1][0], ">"


def round_up(x):
    """x rounded up to two significant digits."""
    if x <= 0:
        return x
    scale = 10 ** (math.floor(math.log10(x)) - 1)
    return math.ceil(x / scale - 1e-9) * scale


def targets(run, curve, count=4):
    """The errors to report the time to: --errors, or `count` errors spaced evenly (log)
    from the error the worst configuration ends at (so that every one reaches the first) down
    to the smallest error any reaches (so that the best reaches them all, and the table shows
    where the others fall behind)."""
    if run.get("errors"):
        return sorted(run["errors"], reverse=True)
    pts = [p for p in curve.values() if p]
    lo = round_up(min(min(e for _, e in p) for p in pts))
    hi = round_up(max(min(e for _, e in p) for p in pts))
    if hi <= lo:
        return [lo]
    goals = [round_up(math.exp(math.log(hi) + k * (math.log(lo) - math.log(hi)) / (count - 1))) for k in range(count)]
    return sorted(set(goals), reverse=True)


def reference_noise(rows, run, metric):
    """An upper bound on the reference's own error when it was rendered here (sobol, N spp):
    the MSE of a sobol render of n spp times n/N (its MSE falls at least as fast as 1/spp,
    docs/samplers.md), the smallest over the sobol renders. None when unknown."""
    ref = run["reference"]
    if not ref.get("spp"):
        return None
    bounds = [r["mse"] * r["spp"] / ref["spp"] for r in rows if r["sampler"] == "sobol" and r["spp"] > 0]
    if not bounds:
        return None
    mse = min(bounds)
    if metric == "mse":
        return mse
    if metric == "rmse":
        return math.sqrt(mse)
    bounds = [r["relmse"] * r["spp"] / ref["spp"] for r in rows if r["sampler"] == "sobol" and r["spp"] > 0]
    return min(bounds)


def plot(out, curve, rows, run, goals, floor):
    metric = run["metric"]
    fig, ax = plt.subplots(figsize=(7.5, 5))
    accels = sorted({c[0] for c in curve})
    samplers = sorted({c[1] for c in curve})
    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    for config, pts in curve.items():  # a colour per sampler, a line style and marker per backend
        mine = [r for r in rows if (r["accel"], r["sampler"]) == config]
        a = accels.index(config[0])
        line, = ax.plot([t for t, _ in pts], [e for _, e in pts], marker="os^D"[a % 4], ls=["-", "--", ":"][a % 3],
                        color=colours[samplers.index(config[1]) % len(colours)], label=label(config))
        ax.scatter([r["render_seconds"] for r in mine], [r[metric] for r in mine], s=10, alpha=0.35,
                   color=line.get_color())
    for g in goals:
        ax.axhline(g, color="grey", lw=0.6, ls=":")
    if floor:
        ax.axhline(floor, color="black", lw=0.8, ls="--", label="reference's own error (upper bound)")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("render time, s (the renderer's own clock)")
    ax.set_ylabel("%s against the reference" % METRIC_NAMES[metric])
    ax.set_title("%s: error against time (lines: medians; dots: each render)" % os.path.basename(run["scene"]),
                 fontsize=10)
    ax.grid(True, which="both", lw=0.3, alpha=0.5)
    ax.legend(fontsize=8)
    fig.tight_layout()
    for ext in ("png", "svg"):
        fig.savefig(os.path.join(out, "error-vs-time." + ext), dpi=110)
    plt.close(fig)


def fmt_time(t, how):
    if t is None:
        return "n/a"
    return {"": "%.3g s", "<=": "≤ %.3g s", ">": "> %.3g s"}[how] % t


def time_table(curve, goals, metric):
    """The table's lines, and per error the shortest time any configuration needs (None if none
    reaches it); an interpolated time gets its ratio to that, a bound ('<=') only when it is that."""
    lines = ["| backend + sampler | " + " | ".join("%s %.3g" % (METRIC_NAMES[metric], g) for g in goals) + " |",
             "|---" * (len(goals) + 1) + "|"]
    best = {}
    for g in goals:
        known = [t for t, how in (time_to(pts, g) for pts in curve.values()) if how in ("", "<=")]
        best[g] = min(known) if known else None
    for config, pts in curve.items():
        cells = []
        for g in goals:
            t, how = time_to(pts, g)
            cell = fmt_time(t, how)
            if how != ">" and best[g] and t <= best[g]:
                cell += " (**fastest**)"
            elif how == "" and best[g]:
                cell += " (%.2fx)" % (t / best[g])
            cells.append(cell)
        lines.append("| %s | %s |" % (label(config), " | ".join(cells)))
    return lines, best


def speed_table(rows, curve, metric):
    lines = ["| backend + sampler | samples/s (median) | accel build, s | spp at the largest level | "
             "%s there | backend |" % METRIC_NAMES[metric], "|---|---|---|---|---|---|"]
    for config in curve:
        mine = [r for r in rows if (r["accel"], r["sampler"]) == config]
        top = max(r["level"] for r in mine)
        last = [r for r in mine if r["level"] == top]
        lines.append("| %s | %.4g | %.3g | %s | %.4g | %s |" % (
            label(config), statistics.median(r["samples_per_second"] for r in mine),
            statistics.median(r["accel_build_seconds"] for r in mine),
            "/".join(str(r["spp"]) for r in last), statistics.median(r[metric] for r in last), mine[0]["backend"]))
    return lines


def fastest_line(curve, goals, best):
    """One sentence: which configuration reaches the smallest error first."""
    g = goals[-1]
    if not best.get(g):
        return "No configuration reached %.3g: give a larger --budget." % g
    t, config = min((time_to(pts, g)[0], config) for config, pts in curve.items() if time_to(pts, g)[1] != ">")
    return "Fastest to %s %.3g: %s (%.3g s of rendering)." % ("the error", g, label(config), t)


def write(out, rows, run):
    """Writes README.md and the plot into `out`; returns {"fastest": one line, "goals": [...]}."""
    metric = run["metric"]
    configs = [tuple(c) for c in run["configs"]]
    curve = curves(rows, configs, metric)
    goals = targets(run, curve)
    floor = reference_noise(rows, run, metric)
    plot(out, curve, rows, run, goals, floor)
    times, best = time_table(curve, goals, metric)
    fastest = fastest_line(curve, goals, best)
    ref = run["reference"]
    kind = run["levels"][0][0]
    levels = ", ".join("%g" % v for _, v in run["levels"])
    md = ["# Speed against error: %s" % run["scene"], "",
          "Written by `%s` on %s in %.0f s (load average %.2f at the start, %.2f at the end, %s CPUs, "
          "threads: %s)." % (run["command"], run["date"], run["seconds"], run["loadavg"][0][0],
                             run["loadavg"][1][0], run["cpus"], run["threads"] or "all"), "",
          "![error against render time](error-vs-time.png)", ""]
    if fastest:
        md += ["**%s**" % fastest, ""]
    md += ["## Time to reach an error", "",
           "Render time (the renderer's own clock: no parsing, build or writing) each backend + sampler needs "
           "to reach each %s against the reference, interpolated log-log between the medians of the measured %s; "
           "`≤`: reached at the first, `>`: not reached at the last; ratios to the fastest." % (
               METRIC_NAMES[metric], "time budgets" if kind == "budget" else "sample counts"), ""]
    md += times + [""]
    md += ["## Samples per second", ""] + speed_table(rows, curve, metric) + [""]
    md += ["## How it was measured", "",
           "- Each configuration rendered with `pathtracer %s` at %s %s, %d time(s) each, in alternating order "
           "(each level: the configurations forwards, then backwards at the next), a new seed every render; "
           "the commands are in `data/commands.log`, every measurement in `data/runs.csv`." % (
               "--time-budget T" if kind == "budget" else "--spp N",
               "budgets (s)" if kind == "budget" else "sample counts", levels, run["repeats"]),
           "- Error: %s over the whole image as `pt-imgerr` computes it (docs/samplers.md)." % METRIC_NAMES[metric]]
    if ref.get("spp"):
        md.append("- Reference: `reference.exr`, the scene rendered with the sobol sampler at %d spp (seed %d, "
                  "%.1f s of rendering)." % (ref["spp"], ref["seed"], ref["render_seconds"]))
    else:
        md.append("- Reference: `%s` (given)." % ref["path"])
    if floor:
        low = min(goals)
        md.append("- The reference's own %s is at most %.3g (a sobol render's MSE times its spp over the "
                  "reference's); measured errors near it are the reference's noise, not the render's%s." % (
                      METRIC_NAMES[metric], floor,
                      ": **the smallest error above is within 3x of it, render a longer reference**"
                      if low < 3 * floor else ""))
    integrators = sorted({r["integrator"] for r in rows})
    if integrators != ["path"]:
        md.append("- The scene's integrator is %s: samplers apply to the path integrator only, so the "
                  "sampler columns differ by noise alone." % ", ".join(integrators))
    md += ["", "## Machine", "", "```", run["lscpu"].strip(), "```", ""]
    with open(os.path.join(out, "README.md"), "w") as f:
        f.write("\n".join(md))
    return {"fastest": fastest, "goals": goals}
