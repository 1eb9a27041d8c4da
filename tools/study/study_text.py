"""The fixed prose of the report (docs/report/README.md); the numbers in it come
from the run. Kept apart from the code that computes them."""

METHOD = """## How it was measured

- **Error**: MSE as the course defines it (`pt-imgerr`, `pt::compute_image_error`, docs/samplers.md):
  linear RGB clamped to [0, 1], the three channels' squared differences summed per pixel, averaged over
  the pixels of the region. RMSE slopes are half the MSE slopes.
- **Checkpoints**: `build/tools/study/pt-converge` renders in one process and measures the error at
  each checkpoint. For `random` and `sobol` one progressive render per seed: samples [0, n) of every
  pixel are exactly the n-spp render (the sample values depend only on seed, pixel, sample index and
  dimension), so the passes [previous, n) are added to the same film. `jittered` stratifies over the
  total sample count (n samples are an a x b grid with a * b = n), so a prefix of a larger jittered
  render is not an n-spp jittered render: **every jittered checkpoint is its own render** from an empty
  film, and its time is that render's time. Wall time counts the integrator's render calls only (not
  the scene build, the film resolve or the error computation).
- **Seeds**: every curve is repeated with independent seeds; the slope is fitted for each seed by
  least squares on log MSE against log spp (on all checkpoints, and on the powers of two alone), and
  the table gives the mean and its standard error over the seeds. The plotted curve is the mean MSE
  over the seeds. Checkpoints of one progressive render are correlated, which is why the spread is
  taken across seeds, not from the residuals of one fit.
- **References**: each study scene rendered twice with `sobol` at the reference spp with two seeds
  far from the study's; the MSE between the two is twice one reference's own noise. That noise is
  drawn as the dash-dotted line in the plots and compared with the smallest MSE the study measures
  (it must be under 10% of it; if it is not, the report says so). This is how "no visible noise" was
  checked: numerically, at the region's scale, rather than by eye."""

LITERATURE = """Expected MSE slopes (twice the RMSE slopes in the literature):

| integrand | random | jittered | scrambled (0,2)-sequence (sobol) |
|---|---|---|---|
| any (finite variance) | -1 | | |
| smooth, 2D | -1 | -2 | -3 (times log N), at powers of two |
| 2D with edges (discontinuities along curves) | -1 | -1.5 (Mitchell 1996) | -1.5 |

- **random**: independent samples, MSE = variance / N, slope -1 whatever the integrand.
- **jittered**: one sample per stratum of an a x b grid; for a smooth 2D integrand the variance
  per stratum falls as the stratum's area squared, giving -2; with an edge only the O(sqrt N) strata
  the edge crosses keep variance, giving -1.5 (Mitchell, "Consequences of stratified sampling in
  graphics", SIGGRAPH 1996).
- **sobol** (Owen-scrambled (0,2)-sequence, padded): at powers of two each dimension pair is a
  (0,m,2)-net, and a scrambled net's variance is O(N^-3 log N) for smooth integrands (Owen 1997) —
  at least as good as jittered, and better than -2 — and O(N^-1.5) across edges, the same rate as
  jittered with a smaller constant. Between powers of two the prefix is not a net, so the all-points
  fit sits between the power-of-two fit and jittered.
- **Sample counts that are not powers of two**: jittered uses an a x b grid with a the largest
  divisor of n not above sqrt(n), so counts without a divisor near sqrt(n) get elongated strata
  (610 = 10 x 61, 1010 = 10 x 101), which stratify an edge less well than square ones; the powers of
  two are 2^k x 2^k or 2^k x 2^(k+1). Sobol' counts between powers of two are a full net plus part of
  the next one. Both effects make the all-points fits a little shallower and noisier than the
  powers-of-two fits.
- **Padding**: both stratified samplers stratify each 2D pair (and 1D dimension) on its own and pair
  them up at random. An integrand that is a sum of functions of single pairs converges at the rates
  above; the part that couples two pairs (the interaction in the ANOVA sense, e.g. where a soft
  shadow's visibility depends on both the point seen through the pixel and the point sampled on the
  light, or a defocused edge that depends on both the pixel and the lens position) is only sampled at
  random, at slope -1. So in a scene whose integrand couples the pairs, the stratified curves start
  steep and bend towards -1 once the coupled part dominates: the fitted slope lands between -1 and the
  2D rate, and on the powers-of-two fit too. This is the main reason the measured slopes of the
  soft-shadow and thin-lens scenes are shallower than the 2D rates above.
- **The smooth case** is not among the study scenes (each isolates an edge: of an emitter, of a
  shadow, of a defocused emitter). It is measured on analytic integrands by the sampler tests
  (`tests/render/test_samplers.cpp`, docs/samplers.md: a 2D Gaussian, N = 16..1024 at powers of two,
  256 replicas): MSE slopes about -1.0 (random), -2.0 (jittered) and -2.7 (sobol), where
  N^-3 log N fitted over that range gives -2.8; and on a disk indicator -1.0, -1.5 and -1.6. So
  the smooth-integrand rates of the literature hold where the integrand is smooth in one pair."""

SPEED_NOTES = """Render wall time against MSE, one seed, for `--accel embree` and `--accel bvh` and each
sampler, 2 render threads. For `random` and `sobol` the time at a checkpoint is the cumulative time
of one progressive render; for `jittered` it is the time of a separate render at that spp (a user
would render once at the chosen spp). Each run stops at the first checkpoint past its budget (given
with each case); the equal-time columns are times every configuration reached. One seed per
configuration, so differences of a few tens of percent between configurations are within the noise
of the error and, under load, of the timing. The Cornell box is
`scenes/cornell-box.json` at 256x256 (64 bounces) against the Cycles render at 8192 spp in
`../shared/reference/cornell-box/`; that reference comes from another renderer, so part of the MSE
at high spp is the difference between the renderers, which no sampler removes (the curves flatten
there)."""

EXPECTED = {
    "aa-edges": ("The only integrand is the 2D pixel area (a box filter over emitters: indicator "
                 "functions with straight and circular edges), the case of Mitchell's analysis. "
                 "Expected: random -1, jittered -1.5, sobol -1.5 with a smaller constant; pixels "
                 "without an edge have no variance at all."),
    "soft-shadow": ("Each pixel integrates over its area (the floor seen through it is smooth) and "
                    "over the light's area (visibility has an edge in the penumbra), and the MIS "
                    "BSDF sample adds a pair. One pair alone would converge at -1.5 (edge in the light "
                    "pair) or better; but where the penumbra is, visibility depends jointly on the "
                    "pixel position and the light sample, which padding samples at random (slope -1)."),
    "thin-lens": ("A 4D integrand: pixel area times lens disk. A defocused edge is crossed by a ray "
                  "depending on pixel and lens position together, so most of the variance is in the "
                  "coupling of the two pairs, which padded samplers do not stratify: expected close "
                  "to -1 for every sampler, the stratified ones with a smaller constant."),
}


# How the measurement compares with the expectation (written from the full run of
# docs/report/; the numbers beside it are recomputed on every run).
VERDICT = {
    "aa-edges": ("This is the literature's case and it agrees: random -1, both stratified samplers close to "
                 "-1.5 (Mitchell's edge rate) on every fit, sobol with a lower constant than jittered. The "
                 "jittered all-points fit is a little shallower than its powers-of-two fit because of its "
                 "elongated grids at counts like 610 = 10 x 61."),
    "soft-shadow": ("The stratified curves start near the 2D edge rate (-1.5) and bend towards -1 above a few "
                    "hundred spp, as padding predicts: the low-spp fits are steep, the high-spp fits shallow. "
                    "The reference's own noise is a few percent of the smallest MSE, too little to cause the bend. "
                    "Sobol' does not reach -3 here because the integrand is not smooth (the penumbra) and its "
                    "pairs are coupled; it keeps the lowest error at every spp. The jittered curve is jagged "
                    "between powers of two: counts like 310 = 10 x 31 give elongated strata."),
    "thin-lens": ("All three slopes are close to -1: the variance is almost all in the coupling of the pixel "
                  "and lens pairs, which no padded sampler stratifies, so stratification only lowers the "
                  "constant (by about 3x here), not the rate. A sampler stratifying the 4D integrand jointly "
                  "(a (0,m,4)-net is impossible in base 2; higher-dimensional Sobol' or a (t,m,4)-net) would "
                  "be needed for a steeper slope."),
}


def discussion(scene, conv):
    """One paragraph: what the scene isolates, what was expected, what was measured."""
    def s(sampler, subset):
        fit = conv[sampler]["fit"].get(subset, {})
        return "%.2f" % fit["mean"] if fit.get("mean") is not None else "n/a"
    measured = ("Measured MSE slopes (all points / powers of two): random %s / %s, jittered %s / %s, sobol %s / %s;"
                " at low / high spp: jittered %s / %s, sobol %s / %s." % (
                    s("random", "all"), s("random", "pow2"), s("jittered", "all"), s("jittered", "pow2"),
                    s("sobol", "all"), s("sobol", "pow2"), s("jittered", "low"), s("jittered", "high"),
                    s("sobol", "low"), s("sobol", "high")))
    last = {k: conv[k]["curve"][-1][1] for k in ("random", "jittered", "sobol")}
    ratio = ""
    if last["random"] > 0:
        ratio = " At %d spp jittered has %.3gx and sobol %.3gx the MSE of random." % (
            conv["random"]["curve"][-1][0], last["jittered"] / last["random"], last["sobol"] / last["random"])
    return "**Discussion.** %s %s%s %s" % (EXPECTED.get(scene, ""), measured, ratio, VERDICT.get(scene, ""))


# The speed cases, in words (written from the full run; the tables beside it are recomputed).
SPEED_VERDICT = {
    "cornell-box": ("**Discussion.** With 64 bounces most of the Cornell box's variance is in the deep "
                    "dimensions of the path, which the padded samplers stratify only pair by pair, so at a few spp "
                    "the three samplers give the same error and the curves coincide; the stratified samplers pull "
                    "ahead only as spp grows (see the equal-spp line: at the end of the budget jittered and sobol "
                    "have clearly less error than random at equal spp). Their cost per sample is within about 30% of "
                    "random's (the samples-per-second line), so at equal time the gain is smaller than at equal "
                    "spp; one seed per configuration, so differences of a few tens of percent are within the "
                    "noise. The backends give the same images (equal MSE at equal spp) and differ only in time "
                    "(docs/bench/ has the backend timings measured for that purpose, over several runs; two runs "
                    "of this report on a loaded machine disagreed on them by tens of percent). Part of the MSE at the "
                    "end is the difference between this renderer and Cycles."),
    "soft-shadow": ("**Discussion.** Direct light only, so the stratified samplers' gain is large at every spp "
                    "(see the convergence section) and it survives their cost per sample: at equal time both "
                    "reach several times less error than random, whichever backend. Sobol' costs more per sample "
                    "than random here (up to about 2x the time in these runs, see the samples-per-second line: its "
                    "hashing and scrambling are a larger share of a sample when a sample is only three short "
                    "rays), which is why at equal time it is not consistently better than jittered although at "
                    "equal spp it is. The 32x32 image makes the times short and noisy (per-render overhead "
                    "weighs more; the backends' order here is not the one on larger images)."),
}
