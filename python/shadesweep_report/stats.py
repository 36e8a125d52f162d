"""Numbers and statistics: CSV fields as floats, means, SDs, Student t, fits."""
import math



def num(s):
    """A CSV field as a float, or None when empty, NaN or not a number."""
    if s is None:
        return None
    try:
        v = float(s)
    except (TypeError, ValueError):
        return None
    return None if math.isnan(v) else v


def mean(xs):
    xs = [x for x in xs if x is not None]
    return sum(xs) / len(xs) if xs else None


def median(xs):
    xs = sorted(x for x in xs if x is not None)
    if not xs:
        return None
    n = len(xs)
    return xs[n // 2] if n % 2 else (xs[n // 2 - 1] + xs[n // 2]) / 2


def sd(xs):
    xs = [x for x in xs if x is not None]
    if len(xs) < 2:
        return None
    m = sum(xs) / len(xs)
    return math.sqrt(sum((x - m) ** 2 for x in xs) / (len(xs) - 1))


_T975 = {1: 12.706, 2: 4.303, 3: 3.182, 4: 2.776, 5: 2.571, 6: 2.447, 7: 2.365, 8: 2.306,
         9: 2.262, 10: 2.228, 12: 2.179, 15: 2.131, 20: 2.086, 25: 2.060, 30: 2.042,
         40: 2.021, 60: 2.000, 120: 1.980}


def t975(df):
    """Student t, 97.5% quantile, for df degrees of freedom (the nearest tabled df below)."""
    best = 1.96
    for k in sorted(_T975):
        if k <= df:
            best = _T975[k]
    return best


def ci95(xs):
    xs = [x for x in xs if x is not None]
    s = sd(xs)
    return None if s is None else t975(len(xs) - 1) * s / math.sqrt(len(xs))


def linfit(xs, ys):
    """Least squares y = a + b x: (a, b, r2)."""
    pts = [(x, y) for x, y in zip(xs, ys) if x is not None and y is not None]
    n = len(pts)
    if n < 3:
        return None
    mx = sum(p[0] for p in pts) / n
    my = sum(p[1] for p in pts) / n
    sxx = sum((p[0] - mx) ** 2 for p in pts)
    sxy = sum((p[0] - mx) * (p[1] - my) for p in pts)
    syy = sum((p[1] - my) ** 2 for p in pts)
    if sxx == 0:
        return None
    b = sxy / sxx
    a = my - b * mx
    r2 = 1.0 if syy == 0 else (sxy * sxy) / (sxx * syy)
    return a, b, r2


def _solve3(m, v):
    """Gaussian elimination for a 3x3 system; None when singular."""
    a = [row[:] + [v[i]] for i, row in enumerate(m)]
    for c in range(3):
        p = max(range(c, 3), key=lambda r: abs(a[r][c]))
        if abs(a[p][c]) < 1e-12:
            return None
        a[c], a[p] = a[p], a[c]
        for r in range(3):
            if r != c:
                f = a[r][c] / a[c][c]
                for k in range(c, 4):
                    a[r][k] -= f * a[c][k]
    return [a[i][3] / a[i][i] for i in range(3)]


def hinge_fit(xs, ys):
    """The continuous two-segment line that fits best: (break x, slope before, slope after).

    The break is tried at every point with at least three points on each side."""
    pts = sorted((x, y) for x, y in zip(xs, ys) if x is not None and y is not None)
    best = None
    for i in range(3, len(pts) - 2):
        b = pts[i][0]
        rows = [(1.0, x, max(0.0, x - b)) for x, _ in pts]
        ata = [[sum(r[j] * r[k] for r in rows) for k in range(3)] for j in range(3)]
        aty = [sum(r[j] * p[1] for r, p in zip(rows, pts)) for j in range(3)]
        sol = _solve3(ata, aty)
        if sol is None:
            continue
        sse = sum((p[1] - (sol[0] + sol[1] * r[1] + sol[2] * r[2])) ** 2 for r, p in zip(rows, pts))
        if best is None or sse < best[0]:
            best = (sse, b, sol[1], sol[1] + sol[2])
    return None if best is None else best[1:]
