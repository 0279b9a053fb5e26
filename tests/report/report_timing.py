"""report.py's timings (a median with the fastest and slowest run), their ratios with the
noise marks, and how the report writes numbers."""


class Timing:
    """Seconds: a median, the fastest and slowest run, and how many runs they are of.
    Timings add up (a total over images: medians, fastest and slowest summed)."""

    def __init__(self, median, lo, hi, n):
        self.median, self.lo, self.hi, self.n = median, lo, hi, n

    def __add__(self, other):
        return Timing(self.median + other.median, self.lo + other.lo, self.hi + other.hi, min(self.n, other.n))

    @staticmethod
    def total(timings):
        timings = list(timings)
        if not timings or any(t is None for t in timings):
            return None
        out = timings[0]
        for t in timings[1:]:
            out = out + t
        return out


def ratio_text(num, den):
    """num / den as "1.23x"; "within noise" when the runs' spreads overlap (the fastest of
    either is no faster than the slowest of the other), "one run" when there is no spread
    to judge by."""
    if num is None or den is None or den.median <= 0:
        return "—"
    text = f"{num.median / den.median:.2f}x"
    if min(num.n, den.n) < 2:
        return text + " (one run)"
    if num.lo <= den.hi and den.lo <= num.hi:
        return text + " (within noise)"
    return text


def fs(x, digits=3):
    return "—" if x is None else f"{x:.{digits}f}"


def pct(n, total, digits=2):
    return "—" if n is None or not total else f"{100.0 * n / total:.{digits}f}%"


def mean(xs):
    xs = [x for x in xs if x is not None]
    return sum(xs) / len(xs) if xs else None


def worst(xs):
    xs = [x for x in xs if x is not None]
    return max(xs) if xs else None


def pct_s(x, digits=3):
    return "—" if x is None else f"{x:.{digits}f}%"
