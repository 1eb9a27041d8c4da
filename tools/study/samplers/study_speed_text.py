"""The discussion of each speed-against-error case (docs/report/README.md):
every comparison is computed from the numbers the case's tables are built
from (samples per second, equal-time and equal-spp MSE, the time traces), so
the words follow the run. `facts` is what study_report.speed_facts gathers:

    case, accels, samplers, times, rows[(accel, sampler)], traces[(accel, sampler)],
    rate[(accel, sampler)] (spp per second at the last checkpoint),
    equal_time[(accel, sampler)] (MSE at each of times, None where not reached),
    equal_spp (spp, {(accel, sampler): MSE}) or None
"""
from study_fit import loglog_slope, time_to_mse
from study_text import CORNELL_DEEP, SMALL_IMAGE, SOBOL_COST_WHY
from study_words import count_phrase, ratio_span, sl, x

STRATIFIED = ("jittered", "sobol")
# Ratios within this of 1 count as "the same".
SAME = 0.1
# The early / late slopes of a speed curve are fitted from this spp on (as the convergence fits).
FLAT_MIN_SPP = 16
# A curve flattens when its late slope is shallower than its early one by more than this.
FLATTEN = 0.15
# The issue-4 time-to-error target, per-channel RMSE 0.005, as this report's MSE (channels summed).
TARGET_MSE = 3 * 0.005 ** 2


def cost(f, accel, sampler):
    """Time per sample relative to random on the same backend."""
    r = f["rate"].get((accel, sampler))
    return f["rate"][(accel, "random")] / r if r else None


def cost_sentence(f):
    parts = ["%s: %s" % (a, ", ".join("%s %s" % (s, x(cost(f, a, s))) for s in STRATIFIED)) for a in f["accels"]]
    costs = [cost(f, a, s) for a in f["accels"] for s in STRATIFIED if cost(f, a, s)]
    return ("Cost per sample relative to random on the same backend (random's samples per second over theirs) "
            "— %s; from %s to %s." % ("; ".join(parts), x(min(costs)), x(max(costs)))) if costs else ""


def equal_spp_ratios(f):
    """{(accel, sampler): MSE / same backend's random at equal spp}, or None."""
    if not f["equal_spp"]:
        return None
    mse = f["equal_spp"][1]
    return {(a, s): mse[(a, s)] / mse[(a, "random")] for a in f["accels"] for s in STRATIFIED
            if mse.get((a, "random"))}


def equal_spp_sentence(f):
    ratios = equal_spp_ratios(f)
    if not ratios:
        return ""
    same = all(abs(ratios[(a, s)] / ratios[(f["accels"][0], s)] - 1) < 1e-9 for a, s in ratios)
    if same:
        body = " and ".join("%s has %s" % (s, x(ratios[(f["accels"][0], s)])) for s in STRATIFIED)
        return "At equal spp (%d) %s random's MSE, on both backends." % (f["equal_spp"][0], body)
    body = "; ".join("%s/%s %s" % (a, s, x(r)) for (a, s), r in ratios.items())
    return "At equal spp (%d), MSE relative to random on the same backend: %s." % (f["equal_spp"][0], body)


def equal_time_ratios(f, sampler):
    """[(accel, T, MSE / same backend's random at T)] over the equal-time cells both reached."""
    out = []
    for a in f["accels"]:
        for t, e, b in zip(f["times"], f["equal_time"][(a, sampler)], f["equal_time"][(a, "random")]):
            if e and b:
                out.append((a, t, e / b))
    return out


def equal_time_sentence(f):
    parts = []
    for s in STRATIFIED:
        cells = equal_time_ratios(f, s)
        if cells:
            lower = sum(1 for _, _, r in cells if r < 1)
            parts.append("%s %s, lower in %s" % (s, ratio_span(r for _, _, r in cells),
                                                 count_phrase(lower, len(cells), "cell")))
    return "At equal time, MSE relative to random on the same backend: %s." % "; ".join(parts) if parts else ""


def gain_sentence(f):
    """Is the gain over random smaller at equal time than at equal spp (at the longest time)?"""
    es = equal_spp_ratios(f)
    if not es:
        return ""
    pairs = []
    for (a, s), r_spp in es.items():
        cells = [c for c in equal_time_ratios(f, s) if c[0] == a]
        if cells:
            pairs.append(("%s/%s" % (a, s), cells[-1][2], r_spp, cells[-1][1]))
    if not pairs:
        return ""
    smaller = sum(1 for _, t, n, _ in pairs if t > n)
    return ("At the longest time (T = %.3g s) the gain over random is smaller than at equal spp in %s "
            "(equal time / equal spp: %s)." % (pairs[0][3], count_phrase(smaller, len(pairs), "case"),
                                               ", ".join("%s %s / %s" % (k, x(t), x(n)) for k, t, n, _ in pairs)))


def sobol_vs_jittered(f):
    cells = [(a, t, e_s, e_j) for a in f["accels"]
             for t, e_s, e_j in zip(f["times"], f["equal_time"][(a, "sobol")], f["equal_time"][(a, "jittered")])
             if e_s and e_j]
    if not cells:
        return ""
    wins = [c for c in cells if c[2] < c[3]]
    ex = (wins or cells)[0]
    text = "Sobol' has less MSE than jittered at equal time in %s (e.g. %s, T = %.3g s: %.3g against %.3g)" % (
        count_phrase(len(wins), len(cells), "cell"), ex[0], ex[1], ex[2], ex[3])
    if not f["equal_spp"]:
        return text + "."
    n, mse = f["equal_spp"]
    a = f["accels"][0]
    s_lower = mse[(a, "sobol")] < mse[(a, "jittered")]
    text += "; at equal spp (%d) %s is lower, %.3g against %.3g." % (
        n, "sobol" if s_lower else "jittered", min(mse[(a, "sobol")], mse[(a, "jittered")]),
        max(mse[(a, "sobol")], mse[(a, "jittered")]))
    time_wins = len(wins) > len(cells) / 2
    c_s, c_j = [cost(f, b, "sobol") for b in f["accels"]], [cost(f, b, "jittered") for b in f["accels"]]
    if time_wins != s_lower and None not in c_s + c_j:
        sobol_cheaper = all(s < j for s, j in zip(c_s, c_j))
        if sobol_cheaper == time_wins and (sobol_cheaper or all(s > j for s, j in zip(c_s, c_j))):
            text += " The order flips between equal spp and equal time with the cost per sample: a jittered sample " \
                    "costs %s random's, a Sobol' one %s (%s)." % (
                        " / ".join(x(c) for c in c_j), " / ".join(x(c) for c in c_s), " / ".join(f["accels"]))
    return text


def backend_sentence(f, others):
    a0, a1 = f["accels"][0], f["accels"][-1]
    if a0 == a1:
        return ""
    text = ""
    if f["equal_spp"]:
        mse = f["equal_spp"][1]
        dev = max(abs(mse[(a1, s)] / mse[(a0, s)] - 1) for s in f["samplers"] if mse.get((a0, s)))
        text = ("The backends give the same images (the same MSE at equal spp for every sampler) and differ only in "
                "time: " if dev < 1e-9 else "MSE at equal spp differs between the backends by up to %.2g%%; " %
                (100 * dev))
    speed = {s: f["rate"][(a1, s)] / f["rate"][(a0, s)] for s in f["samplers"]}
    text += "%s renders %s %s's samples per second (%s)" % (
        a1, ", ".join(x(speed[s]) for s in f["samplers"]), a0, ", ".join(f["samplers"]))
    for o in others:
        theirs = o["rate"][(a1, "random")] / o["rate"][(a0, "random")]
        if (theirs > 1) != (speed["random"] > 1):
            text += "; the reverse of %s's order (%s there, random)" % (o["case"], x(theirs))
    return text + ". docs/bench/ measures the backends' speed over several runs."


def first_spp_sentence(f):
    """The samplers at the first checkpoint every configuration reached."""
    a = f["accels"][0]
    first = min(set.intersection(*[{r["spp"] for r in rows} for rows in f["rows"].values()]), default=None)
    if first is None:
        return ""
    at = {s: next(r["mse"] for r in f["rows"][(a, s)] if r["spp"] == first) for s in f["samplers"]}
    ratios = [at[s] / at["random"] for s in STRATIFIED]
    word = ("the three agree within %.0f%%" % (100 * SAME) if all(abs(r - 1) <= SAME for r in ratios)
            else "already apart")
    return "At %d spp (%s) jittered and sobol have %s and %s random's MSE: %s." % (
        first, a, x(ratios[0]), x(ratios[1]), word)


def flatten_sentence(f):
    """Early against late slope of MSE against spp, per sampler on the first backend."""
    a, parts, flat = f["accels"][0], [], []
    for s in f["samplers"]:
        pts = [(r["spp"], r["mse"]) for r in f["rows"][(a, s)] if r["spp"] >= FLAT_MIN_SPP]
        if len(pts) < 4:
            continue
        mid = (pts[0][0] * pts[-1][0]) ** 0.5
        early, late = loglog_slope([p for p in pts if p[0] <= mid]), loglog_slope([p for p in pts if p[0] >= mid])
        if early is None or late is None:
            continue
        parts.append("%s %s / %s" % (s, sl(early), sl(late)))
        if late > early + FLATTEN:
            flat.append(s)
    if not parts:
        return ""
    verdict = ("the %s curve%s flatten%s" % (", ".join(flat), "s" if len(flat) > 1 else "", "" if len(flat) > 1
                                              else "s")) if flat else "no curve flattens within the budget"
    return "Slope of MSE against spp (%s) in the first / second half of the checkpoints from %d spp (log scale): " \
           "%s; %s." % (a, FLAT_MIN_SPP, ", ".join(parts), verdict)


def target_sentence(f):
    times = {k: time_to_mse(t, TARGET_MSE) for k, t in f["traces"].items()}
    cells = ", ".join("%s/%s %s" % (a, s, "%.3g s" % t if t else "not reached") for (a, s), t in times.items())
    return ("Time to MSE %.2g (the issue-4 target's per-channel RMSE 0.005 in this report's units, but on values "
            "clamped to [0, 1]: the light's own pixels, where most of the unclamped error is, count for little here, "
            "so these times are shorter than bench_render's time to the target in docs/bench/cornell.md): %s."
            % (TARGET_MSE, cells))


def convergence_gain(conv):
    """The stratified samplers against random over the convergence study's checkpoints."""
    rnd = {c[0]: c[1] for c in conv["random"]["curve"]}
    parts = []
    for s in STRATIFIED:
        ratios = [c[1] / rnd[c[0]] for c in conv[s]["curve"] if rnd.get(c[0])]
        parts.append("%s %s (lower at %s)" % (s, ratio_span(ratios), count_phrase(
            sum(1 for r in ratios if r < 1), len(ratios), "checkpoint")))
    return "Direct light only: in the convergence section the MSE relative to random is %s." % \
        "; ".join(parts)


def sobol_cost_sentence(f):
    costs = [cost(f, a, "sobol") for a in f["accels"]]
    if None in costs or min(costs) <= 1 + SAME / 2:
        return ""
    return "Sobol' costs %s random's time per sample here %s." % (ratio_span(costs), SOBOL_COST_WHY)


def speed_discussion(f, others, conv):
    """The paragraph under a speed case's tables. others: the other cases' facts; conv: the convergence
    summary of the same scene, if the study has one."""
    common = [cost_sentence(f), equal_time_sentence(f), equal_spp_sentence(f), gain_sentence(f),
              sobol_vs_jittered(f), backend_sentence(f, others)]
    if f["case"] == "cornell-box":
        parts = [CORNELL_DEEP, first_spp_sentence(f)] + common + [flatten_sentence(f), target_sentence(f)]
    elif conv:
        parts = [convergence_gain(conv)] + common[:1] + [sobol_cost_sentence(f)] + common[1:] + [SMALL_IMAGE]
    else:
        parts = common
    return "**Discussion.** " + " ".join(p for p in parts if p)
