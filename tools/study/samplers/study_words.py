"""Small wording helpers for the report's measured sentences (study_verdict.py,
study_speed_text.py): counts, ratios and slopes put into words that follow the
numbers."""
import math


def x(ratio):
    """A ratio as '1.17x' / '1.00x' / '0.0217x'; '—' for None."""
    if ratio is None:
        return "—"
    return "%.2fx" % ratio if ratio >= 0.1 else "%.3gx" % ratio


def sl(slope):
    """A slope as '-1.43'; 'n/a' for None."""
    return "n/a" if slope is None else "%.2f" % slope


def count_phrase(k, n, noun):
    """'all 6 cells', '4 of 6 cells', 'none of the 6 cells' (noun singular)."""
    nouns = noun if n == 1 else noun + "s"
    if n > 1 and k == n:
        return "all %d %s" % (n, nouns)
    if n > 1 and k == 0:
        return "none of the %d %s" % (n, nouns)
    return "%d of %d %s" % (k, n, nouns)


def spp_list(values, most=12):
    """'110, 210 and 810 spp', or 'N other checkpoints' when there are more than `most`."""
    values = list(values)
    if len(values) > most:
        return "%d other checkpoints" % len(values)
    if len(values) == 1:
        return "%d spp" % values[0]
    return "%s and %d spp" % (", ".join(str(v) for v in values[:-1]), values[-1])


def span(values):
    """'-1.39 to -1.48' (least to most negative), or one value when all are equal."""
    values = [v for v in values if v is not None]
    if not values:
        return "n/a"
    lo, hi = max(values), min(values)
    return sl(lo) if "%.2f" % lo == "%.2f" % hi else "%s to %s" % (sl(lo), sl(hi))


def ratio_span(values):
    """'0.07x-0.10x' or '0.45x' for the ratios given (None skipped)."""
    values = [v for v in values if v is not None]
    if not values:
        return "—"
    lo, hi = min(values), max(values)
    return x(lo) if x(lo) == x(hi) else "%s-%s" % (x(lo), x(hi))


def jittered_grid(n):
    """The a x b grid jittered uses for n samples: a the largest divisor of n not above sqrt(n)."""
    a = max(d for d in range(1, math.isqrt(n) + 1) if n % d == 0)
    return a, n // a
