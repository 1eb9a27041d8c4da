"""Numbers of the convergence study: CSV rows, log-log slope fits, and the
equal-time / equal-error interpolation (docs/report/README.md).

Pure functions of their arguments (no plotting, no processes), used by
run_study.py and by its test.
"""
import csv
import math
import statistics


def read_rows(path):
    """The rows of a pt-converge CSV, with numeric fields converted."""
    rows = []
    with open(path, newline="") as f:
        for r in csv.DictReader(f):
            rows.append({"scene": r["scene"], "accel": r["accel"], "sampler": r["sampler"],
                         "seed": int(r["seed"]), "spp": int(r["spp"]), "seconds": float(r["seconds"]),
                         "mse": float(r["mse"]), "rel_mse": float(r["rel_mse"]), "rmse": float(r["rmse"])})
    return rows


def is_power_of_two(n):
    return n > 0 and (n & (n - 1)) == 0


def least_squares_slope(xs, ys):
    """Slope of the least-squares line through (xs, ys); None with fewer than 2 distinct xs."""
    n = len(xs)
    if n < 2:
        return None
    mx, my = sum(xs) / n, sum(ys) / n
    sxx = sum((x - mx) ** 2 for x in xs)
    if sxx == 0:
        return None
    return sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sxx


def loglog_slope(points):
    """Slope of log(MSE) against log(spp) for [(spp, mse)], positive MSE only."""
    pts = [(math.log(s), math.log(e)) for s, e in points if e > 0]
    return least_squares_slope([p[0] for p in pts], [p[1] for p in pts])


def by_seed(rows):
    out = {}
    for r in rows:
        out.setdefault(r["seed"], []).append(r)
    for seed in out:
        out[seed].sort(key=lambda r: r["spp"])
    return out


def slope_summary(rows, min_spp=1):
    """Per-seed MSE slopes, on all checkpoints and on the powers of two only
    (spp >= min_spp), with their mean and standard error across seeds."""
    result = {}
    for subset, keep in (("all", lambda n: True), ("pow2", is_power_of_two)):
        slopes = []
        for seed_rows in by_seed(rows).values():
            s = loglog_slope([(r["spp"], r["mse"]) for r in seed_rows if keep(r["spp"]) and r["spp"] >= min_spp])
            if s is not None:
                slopes.append(s)
        mean = statistics.fmean(slopes) if slopes else None
        se = statistics.stdev(slopes) / math.sqrt(len(slopes)) if len(slopes) > 1 else None
        result[subset] = {"slopes": slopes, "mean": mean, "stderr": se}
    return result


def mean_curve(rows):
    """[(spp, mean MSE over seeds, number of seeds)] sorted by spp."""
    acc = {}
    for r in rows:
        acc.setdefault(r["spp"], []).append(r["mse"])
    return [(spp, statistics.fmean(v), len(v)) for spp, v in sorted(acc.items())]


def _interp_loglog(x0, y0, x1, y1, x):
    """y at x on the straight line through (x0, y0), (x1, y1) in log-log."""
    if x1 == x0 or y0 <= 0 or y1 <= 0:
        return y1
    t = (math.log(x) - math.log(x0)) / (math.log(x1) - math.log(x0))
    return math.exp(math.log(y0) + t * (math.log(y1) - math.log(y0)))


def mse_at_time(trace, seconds):
    """MSE reached after `seconds` of rendering, for a trace [(seconds, mse)]
    sorted by time: log-log interpolation between the checkpoints around it;
    None if the trace does not reach that time or starts after it."""
    if not trace or seconds < trace[0][0] or seconds > trace[-1][0]:
        return None
    for (t0, e0), (t1, e1) in zip(trace, trace[1:]):
        if t0 <= seconds <= t1:
            return _interp_loglog(t0, e0, t1, e1, seconds)
    return trace[-1][1]


def time_to_mse(trace, target):
    """First time the trace [(seconds, mse)] reaches MSE <= target, interpolated
    in log-log between the checkpoints that cross it; None if it never does."""
    if not trace:
        return None
    if trace[0][1] <= target:
        return trace[0][0]
    for (t0, e0), (t1, e1) in zip(trace, trace[1:]):
        if e1 <= target < e0:
            if t0 <= 0 or e1 <= 0:
                return t1
            u = (math.log(target) - math.log(e0)) / (math.log(e1) - math.log(e0))
            return math.exp(math.log(t0) + u * (math.log(t1) - math.log(t0)))
    return None


def time_trace(rows):
    """[(seconds, mse)] of one configuration, seed-averaged at each spp: the
    mean time and mean MSE of the seeds at that checkpoint, sorted by time.
    (For jittered each checkpoint is its own render, so its time need not grow
    with spp exactly; the trace is sorted by time and made monotone in MSE by
    keeping the best error reached so far, as a user would stop at it.)"""
    acc = {}
    for r in rows:
        acc.setdefault(r["spp"], []).append((r["seconds"], r["mse"]))
    pts = sorted((statistics.fmean(t for t, _ in v), statistics.fmean(e for _, e in v)) for v in acc.values())
    out, best = [], math.inf
    for t, e in pts:
        best = min(best, e)
        out.append((t, best))
    return out
