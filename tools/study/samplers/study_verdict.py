"""The measured half of each convergence discussion (docs/report/README.md):
every comparison here is computed from the fitted slopes and mean curves the
report is built from (summary.json's "convergence"), so the words follow the
numbers of the run. The expectations (the literature) are fixed prose in
study_text.py."""
import math

from study_fit import loglog_slope
from study_text import EXPECTED, JOINT_4D, SOBOL_NOT_SMOOTH
from study_words import count_phrase, jittered_grid, ratio_span, sl, span, spp_list, x

STRATIFIED = ("jittered", "sobol")
# A measured slope agrees with a predicted rate within this (the sampler tests' band).
AGREE = 0.15
# A curve bends when its high-spp fit differs from its low-spp fit by more than
# this and by more than BEND_SIGMAS standard errors of the difference.
BEND = 0.1
BEND_SIGMAS = 3
# What each scene is compared with: predicted MSE slope per sampler, and the fits checked.
PREDICTED = {
    "aa-edges": ({"random": -1, "jittered": -1.5, "sobol": -1.5}, ("all", "pow2", "low", "high")),
    "soft-shadow": ({"random": -1}, ("all", "pow2", "low", "high")),
    "thin-lens": ({"random": -1, "jittered": -1, "sobol": -1}, ("all", "pow2")),
}


def slope(conv, sampler, subset):
    return conv[sampler]["fit"].get(subset, {}).get("mean")


def curve(conv, sampler):
    return [(c[0], c[1]) for c in conv[sampler]["curve"]]


def agreement(conv, scene):
    """How far each sampler's fits are from the rate predicted for the scene."""
    rates, subsets = PREDICTED.get(scene, ({"random": -1}, ("all", "pow2")))
    parts = []
    for sampler, rate in rates.items():
        fits = [slope(conv, sampler, s) for s in subsets if slope(conv, sampler, s) is not None]
        if not fits:
            continue
        off = max(abs(f - rate) for f in fits)
        verdict = "agrees" if off <= AGREE else "off by up to %.2f" % off
        parts.append("%s %s (predicted %g: %s)" % (sampler, span(fits), rate, verdict))
    if not parts:
        return ""
    which = "every fit" if len(subsets) == 4 else "the all-points and powers-of-two fits"
    return "Against the predicted rates (%s; agreement: within %.2f): %s." % (which, AGREE, "; ".join(parts))


def bend(conv, sampler):
    """(low fit, high fit, 'bends'|'steepens'|'keeps its slope')."""
    fit = conv[sampler]["fit"]
    lo, hi = fit.get("low", {}), fit.get("high", {})
    if lo.get("mean") is None or hi.get("mean") is None:
        return None
    d = hi["mean"] - lo["mean"]
    se = math.hypot(lo.get("stderr") or 0.0, hi.get("stderr") or 0.0)
    if abs(d) <= BEND or abs(d) <= BEND_SIGMAS * se:
        return lo["mean"], hi["mean"], "keeps its slope"
    return lo["mean"], hi["mean"], "bends towards -1" if d > 0 else "steepens"


def bend_sentence(conv, split, last):
    parts, bent = [], False
    for sampler in STRATIFIED:
        b = bend(conv, sampler)
        if b:
            parts.append("%s %s / %s: %s" % (sampler, sl(b[0]), sl(b[1]), b[2]))
            bent = bent or b[2] == "bends towards -1"
    if not parts:
        return "", False
    text = "Slopes below / above %d spp (up to %d): %s." % (split, last, "; ".join(parts))
    if bent:
        text += " A bend towards -1 is what padding predicts once the coupled part of the integrand dominates."
    return text, bent


def reference_sentence(conv, bent):
    ratio = conv.get("reference_noise_ratio")
    if not bent or ratio is None:
        return ""
    if ratio < 0.1:
        return "The reference's own noise is %.1f%% of the smallest MSE, too little to cause the bend." % (100 * ratio)
    return "The reference's own noise is %.0f%% of the smallest MSE: part of the bend may be the reference's." % (
        100 * ratio)


def versus_random(conv):
    """Stratified against random: checkpoints lower, and the range of their MSE ratios."""
    rnd = dict(curve(conv, "random"))
    parts = []
    for sampler in STRATIFIED:
        pts = [(n, e / rnd[n]) for n, e in curve(conv, sampler) if rnd.get(n)]
        if not pts:
            continue
        lower = sum(1 for _, r in pts if r < 1)
        parts.append("%s at %s (%s of random's MSE)" % (
            sampler, count_phrase(lower, len(pts), "checkpoint"), ratio_span(r for _, r in pts)))
    return "Less MSE than random: %s." % "; ".join(parts) if parts else ""


def stratified_order(conv):
    """Which of jittered and sobol has the lower mean MSE, at how many checkpoints."""
    jit = dict(curve(conv, "jittered"))
    pts = [(n, e < jit[n]) for n, e in curve(conv, "sobol") if n in jit]
    if not pts:
        return ""
    sobol_lower = [n for n, s in pts if s]
    jit_lower = [n for n, s in pts if not s]
    first, second = ("sobol", "jittered") if len(sobol_lower) >= len(jit_lower) else ("jittered", "sobol")
    won, lost = (sobol_lower, jit_lower) if first == "sobol" else (jit_lower, sobol_lower)
    text = "Of the two stratified samplers %s has the lower mean MSE at %s" % (
        first, count_phrase(len(won), len(pts), "checkpoint"))
    return text + (" (%s at %s)." % (second, spp_list(lost)) if lost else ".")


def roughness(points):
    """(rises between consecutive checkpoints, (worst excess over the log-log
    interpolation of the two neighbours, its spp)) of a mean curve."""
    rises = sum(1 for a, b in zip(points, points[1:]) if b[1] > a[1])
    worst = (1.0, None)
    for (n0, e0), (n1, e1), (n2, e2) in zip(points, points[1:], points[2:]):
        t = (math.log(n1) - math.log(n0)) / (math.log(n2) - math.log(n0))
        excess = e1 / math.exp(math.log(e0) + t * (math.log(e2) - math.log(e0)))
        worst = max(worst, (excess, n1), key=lambda w: w[0])
    return rises, worst


def jagged_sentence(conv):
    """The jittered curve between powers of two, against sobol's, and its all-points against powers-of-two fit."""
    rises = {s: roughness(curve(conv, s)) for s in ("random",) + STRATIFIED}
    steps = len(conv["jittered"]["curve"]) - 1
    (excess, at) = rises["jittered"][1]
    n = rises["jittered"][0]
    text = "The jittered mean curve rises from one checkpoint to the next %s in %d steps (sobol %d, random %d)" % (
        {0: "never", 1: "once"}.get(n, "%d times" % n), steps, rises["sobol"][0], rises["random"][0])
    if at is not None and excess > 1.2:
        a, b = jittered_grid(at)
        text += "; its largest jump is at %d spp, a %d x %d grid, %.2fx the interpolation between its neighbours" % (
            at, a, b, excess)
        if b >= 4 * a:
            text += " (an elongated grid, which stratifies an edge less well than a square one)"
    text += "."
    all_fit, pow2 = slope(conv, "jittered", "all"), slope(conv, "jittered", "pow2")
    if all_fit is not None and pow2 is not None:
        text += " Its all-points fit (%s) is %s its powers-of-two fit (%s)." % (
            sl(all_fit), "shallower than" if all_fit > pow2 + 0.005 else "not shallower than", sl(pow2))
    return text


def measured_slopes(conv):
    def s(sampler, subset):
        return sl(slope(conv, sampler, subset))
    return ("Measured MSE slopes (all points / powers of two): random %s / %s, jittered %s / %s, sobol %s / %s."
            % (s("random", "all"), s("random", "pow2"), s("jittered", "all"), s("jittered", "pow2"),
               s("sobol", "all"), s("sobol", "pow2")))


def last_ratio(conv):
    last = {k: conv[k]["curve"][-1][1] for k in ("random",) + STRATIFIED}
    if last["random"] <= 0:
        return ""
    return "At %d spp jittered has %s and sobol %s the MSE of random." % (
        conv["random"]["curve"][-1][0], x(last["jittered"] / last["random"]), x(last["sobol"] / last["random"]))


def soft_shadow_tail(conv):
    s = slope(conv, "sobol", "pow2")
    if s is None:
        return ""
    if s > -3 + 0.5:
        return "Sobol's powers-of-two fit is %s, far from the smooth-integrand -3: %s" % (sl(s), SOBOL_NOT_SMOOTH)
    return "Sobol's powers-of-two fit is %s, close to the smooth-integrand -3." % sl(s)


def thin_lens_tail(conv):
    fits = [slope(conv, s, f) for s in ("random",) + STRATIFIED for f in ("all", "pow2")]
    if None in fits or any(abs(f + 1) > AGREE for f in fits):
        return "The stratified samplers' slopes are not all within %.2f of -1: %s" % (AGREE, JOINT_4D)
    return ("Every fit is within %.2f of -1, so stratification lowers only the constant (the ratios above), "
            "not the rate: %s" % (AGREE, JOINT_4D))


# Scene-specific measured sentences, after the generic ones.
SCENE_TAIL = {"soft-shadow": soft_shadow_tail, "thin-lens": thin_lens_tail}


def discussion(scene, conv, split):
    """What the scene isolates and what was expected (prose), then what was measured (computed)."""
    last = conv["random"]["curve"][-1][0]
    bend_text, bent = bend_sentence(conv, split, last)
    measured = [measured_slopes(conv), last_ratio(conv), versus_random(conv), agreement(conv, scene), bend_text,
                reference_sentence(conv, bent), stratified_order(conv), jagged_sentence(conv)]
    tail = SCENE_TAIL.get(scene)
    if tail:
        measured.append(tail(conv))
    return "**Discussion.** %s\n\n%s" % (EXPECTED.get(scene, ""), " ".join(m for m in measured if m))


def literature_measured(convergence):
    """What this run measured about the literature section's expectations."""
    cases = [(scene, s) for scene in convergence for s in STRATIFIED]
    shallower = [(sc, s) for sc, s in cases if None not in (slope(convergence[sc], s, "all"),
                                                             slope(convergence[sc], s, "pow2"))
                 and slope(convergence[sc], s, "all") > slope(convergence[sc], s, "pow2") + 0.005]
    lines = ["**In this run**: the all-points fit of a stratified sampler is shallower than its powers-of-two fit "
             "in %s%s." % (count_phrase(len(shallower), len(cases), "(scene, sampler) case"),
                           "" if len(shallower) in (0, len(cases)) else " (%s)" % ", ".join(
                               "%s/%s" % c for c in shallower))]
    edge = [(sc, [slope(convergence[sc], s, "pow2") for s in STRATIFIED]) for sc in convergence]
    parts = ["%s %s" % (sc, " / ".join(sl(v) for v in vals)) for sc, vals in edge]
    shallow = [sc for sc, vals in edge if all(v is not None and v > -1.5 + AGREE for v in vals)]
    lines.append("Powers-of-two slopes of jittered / sobol: %s; shallower than the 2D edge rate -1.5 (by more than "
                 "%.2f) on %s." % ("; ".join(parts), AGREE, " and ".join(shallow) if shallow else "no scene"))
    return " ".join(lines)


def nlogn_slope(lo=16, hi=1024):
    """Least-squares slope of log(N^-3 log N) against log N at the powers of two in [lo, hi]."""
    ns = [n for n in (2 ** k for k in range(0, 31)) if lo <= n <= hi]
    return loglog_slope([(n, n ** -3.0 * math.log(n)) for n in ns])
