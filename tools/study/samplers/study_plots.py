"""Plots of the convergence study (PNG and SVG, matplotlib's Agg backend)."""
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

# Fixed ids in the SVGs, so that regenerating unchanged data rewrites identical files.
matplotlib.rcParams["svg.hashsalt"] = "pathtracer-study"

from study_fit import is_power_of_two, mean_curve, time_trace  # noqa: E402

COLORS = {"random": "tab:red", "jittered": "tab:blue", "sobol": "tab:green"}
STYLES = {"embree": "-", "bvh": "--"}


def _save(fig, out_dir, stem):
    paths = []
    for ext in ("png", "svg"):
        path = "%s/%s.%s" % (out_dir, stem, ext)
        fig.savefig(path, dpi=110, metadata={"Date": None} if ext == "svg" else None)
        paths.append(path)
    plt.close(fig)
    return paths


def convergence_plot(out_dir, scene, title, rows_by_sampler, reference_noise):
    """log-log MSE (mean over seeds) against spp, one line per sampler, powers
    of two marked, guide slopes -1, -1.5, -2 and -3 through the first points."""
    fig, ax = plt.subplots(figsize=(6.4, 4.6))
    first = {}
    for sampler, rows in rows_by_sampler.items():
        curve = mean_curve(rows)
        spp = [c[0] for c in curve]
        mse = [c[1] for c in curve]
        first[sampler] = (spp[0], mse[0])
        ax.plot(spp, mse, "-", color=COLORS[sampler], lw=1.2, label=sampler)
        p2 = [(s, e) for s, e in zip(spp, mse) if is_power_of_two(s)]
        ax.plot([p[0] for p in p2], [p[1] for p in p2], "o", color=COLORS[sampler], ms=4)
    xs = [c[0] for c in mean_curve(next(iter(rows_by_sampler.values())))]
    x0, x1 = xs[0], xs[-1]
    for slope, anchor in ((-1, "random"), (-1.5, "jittered"), (-2, "sobol"), (-3, "sobol")):
        if anchor in first:
            s0, e0 = first[anchor]
            e0 *= 0.5
            ax.plot([x0, x1], [e0 * (x0 / s0) ** slope, e0 * (x1 / s0) ** slope], ":", color="gray", lw=0.9)
            ax.annotate("%g" % slope, (x1, e0 * (x1 / s0) ** slope), fontsize=8, color="gray")
    if reference_noise > 0:
        ax.axhline(reference_noise, color="black", lw=0.8, ls="-.", label="reference noise (MSE)")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("samples per pixel")
    ax.set_ylabel("MSE (mean over seeds)")
    ax.set_title(title, fontsize=10)
    lo = min(min(c[1] for c in mean_curve(r)) for r in rows_by_sampler.values())
    ax.set_ylim(bottom=min(lo, reference_noise if reference_noise > 0 else lo) * 0.3)
    ax.grid(True, which="both", alpha=0.25)
    ax.legend(fontsize=8)
    return _save(fig, out_dir, "convergence-" + scene)


def speed_plot(out_dir, case, rows_by_config):
    """log-log MSE against render wall time, one line per (accel, sampler)."""
    fig, ax = plt.subplots(figsize=(6.4, 4.6))
    for (accel, sampler), rows in rows_by_config.items():
        trace = time_trace(rows)
        ax.plot([t for t, _ in trace], [e for _, e in trace], STYLES[accel], color=COLORS[sampler], lw=1.2,
                marker=".", ms=3, label="%s / %s" % (accel, sampler))
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("render wall time (s)")
    ax.set_ylabel("MSE")
    ax.set_title("%s: MSE against time" % case, fontsize=10)
    ax.grid(True, which="both", alpha=0.25)
    ax.legend(fontsize=8)
    return _save(fig, out_dir, "speed-" + case)
