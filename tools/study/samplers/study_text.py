"""The fixed prose of the report (docs/report/README.md): how it was measured
and what the literature predicts. Nothing here states a measured result; the
sentences about what was measured are computed from the run's numbers
(study_verdict.py for the convergence scenes, study_speed_text.py for speed
against error). Kept apart from the code that computes them."""

METHOD = """## How it was measured

- **Error**: MSE as the course defines it (`pt-imgerr`, `pt::compute_image_error`, docs/samplers.md):
  linear RGB clamped to [0, 1], the three channels' squared differences summed per pixel, averaged over
  the pixels of the region. **RMSE** in this report (the CSVs' `rmse` column, the RMSE slopes) is the
  square root of that MSE, so it is **sqrt(3) times the per-channel RMSE** (squared differences
  averaged over pixels *and* channels, on unclamped values) that docs/bench/cornell.md and the issue-4
  time-to-error target use: that target, per-channel RMSE 0.005, is RMSE 0.00866 and MSE 7.5e-5 in
  this report's units (exactly so where no value is clamped).
  The factor does not change slopes; RMSE slopes are half the MSE slopes.
- **Checkpoints**: `build/tools/study/samplers/pt-converge` renders in one process and measures the error at
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
  fit is expected to be shallower than the powers-of-two fit.
- **Sample counts that are not powers of two**: jittered uses an a x b grid with a the largest
  divisor of n not above sqrt(n), so counts without a divisor near sqrt(n) get elongated strata
  (610 = 10 x 61, 1010 = 10 x 101), which stratify an edge less well than square ones; the powers of
  two are 2^k x 2^k or 2^k x 2^(k+1). Sobol' counts between powers of two are a full net plus part of
  the next one. Both effects are expected to make the all-points fits a little shallower and noisier
  than the powers-of-two fits.
- **Padding**: both stratified samplers stratify each 2D pair (and 1D dimension) on its own and pair
  them up at random. An integrand that is a sum of functions of single pairs converges at the rates
  above; the part that couples two pairs (the interaction in the ANOVA sense, e.g. where a soft
  shadow's visibility depends on both the point seen through the pixel and the point sampled on the
  light, or a defocused edge that depends on both the pixel and the lens position) is only sampled at
  random, at slope -1. So in a scene whose integrand couples the pairs, the stratified curves start
  steep and bend towards -1 once the coupled part dominates: the fitted slope lands between -1 and the
  2D rate, and on the powers-of-two fit too. The soft-shadow and thin-lens scenes couple pairs (see
  their descriptions above), so their slopes are expected to be shallower than the 2D rates above.
- **The smooth case** is not among the study scenes (each isolates an edge: of an emitter, of a
  shadow, of a defocused emitter). It is measured on analytic integrands by the sampler tests
  (`tests/render/test_samplers.cpp`; the figures are docs/samplers.md's table of RMSE slopes, doubled,
  not recomputed by this tool: a 2D Gaussian, N = 16..1024 at powers of two, 256 replicas): MSE
  slopes about -1.0 (random), -2.0 (jittered) and -2.7 (sobol), where N^-3 log N fitted over that
  range gives {nlogn}; and on a disk indicator -1.0, -1.5 and -1.6 to -1.7. So in those tests the
  smooth-integrand rates of the literature hold where the integrand is smooth in one pair."""

SPEED_NOTES = """Render wall time against MSE, one seed, for `--accel embree` and `--accel bvh` and each
sampler, 2 render threads. For `random` and `sobol` the time at a checkpoint is the cumulative time
of one progressive render; for `jittered` it is the time of a separate render at that spp (a user
would render once at the chosen spp). Each run stops at the first checkpoint past its budget (given
with each case); the equal-time columns are times every configuration reached. One seed per
configuration, so differences of a few tens of percent between configurations may be within the
noise of the error and, under load, of the timing. Errors are this report's MSE (sum over channels, see
above): the issue-4 target, per-channel RMSE 0.005, is MSE 7.5e-5 where nothing is clamped (the
Cornell box's light is: its pixels' errors are mostly clamped away here). The Cornell box is
`scenes/cornell-box.json` at 256x256 (64 bounces) against the Cycles render at 8192 spp in
`../shared/reference/cornell-box/`; that reference comes from another renderer, so part of the MSE
at high spp is the difference between the renderers, which no sampler removes: the curves would
flatten where it dominates (whether they do within the budget is measured below)."""

EXPECTED = {
    "aa-edges": ("The only integrand is the 2D pixel area (a box filter over emitters: indicator "
                 "functions with straight and circular edges), the case of Mitchell's analysis. "
                 "Expected: random -1, jittered -1.5, sobol -1.5 with a smaller constant; pixels "
                 "without an edge have no variance at all."),
    "soft-shadow": ("max_depth 1 means direct light only: light -> surface -> camera, one scattering event "
                    "(the one bounce of the issue's \"soft shadows from an area light with one bounce\"); "
                    "light arriving after two or more bounces is not rendered. "
                    "Each pixel integrates over its area (the floor seen through it is smooth) and "
                    "over the light's area (visibility has an edge in the penumbra), and the MIS "
                    "BSDF sample adds a pair. One pair alone would converge at -1.5 (edge in the light "
                    "pair) or better; but where the penumbra is, visibility depends jointly on the "
                    "pixel position and the light sample, which padding samples at random (slope -1)."),
    "thin-lens": ("A 4D integrand: pixel area times lens disk. A defocused edge is crossed by a ray "
                  "depending on pixel and lens position together, so most of the variance is in the "
                  "coupling of the two pairs, which padded samplers do not stratify: expected close "
                  "to -1 for every sampler, the stratified ones with a smaller constant."),
}


# Explanations the measured sentences add when the numbers call for them.
SOBOL_NOT_SMOOTH = ("the integrand is not smooth (the penumbra) and its pairs are coupled, so the -3 of smooth 2D "
                    "integrands does not apply.")
JOINT_4D = ("the variance of a defocused edge is in the coupling of the pixel and lens pairs, which no padded "
            "sampler stratifies; a sampler stratifying the 4D integrand jointly (a (0,m,4)-net is impossible in "
            "base 2; higher-dimensional Sobol' or a (t,m,4)-net) would be needed for a steeper slope.")
CORNELL_DEEP = ("With 64 bounces much of the Cornell box's variance is expected in the deep dimensions of the "
                "path, which the padded samplers stratify only pair by pair, so the samplers should differ little "
                "at a few spp and pull apart as spp grows.")
SOBOL_COST_WHY = ("(its hashing and scrambling are a larger share of a sample when a sample is only a few short "
                  "rays)")
SMALL_IMAGE = ("The 32x32 image makes the times short and noisy (per-render overhead weighs more, "
               "jittered's most of all since each of its checkpoints is a separate render).")
