"""Stability boundaries of Gragg-Bulirsch-Stoer extrapolation, as bwc_ode::Extrapolation takes
its steps (midpoint sequences n = 2, 4, ..., 2k, no smoothing step, Aitken-Neville in h^2):
where the amplification |T_kk(z)| of y' = lambda y, z = lambda H, first exceeds 1 on the
negative real axis, for k = 2..8; and the amplification on the imaginary axis at order 16.

An independent implementation in floats, for BENCHMARKS.md ("The double-double path"): the double-double
path's stability check trips at |lambda H| = 8 (its second sequence), just past order 16's
boundary of 7.3.

    python3 benches/gbs_stability.py
"""


def amplification(z, k):
    """T_kk for y' = z y over one step of size 1 (z complex or real)."""
    prev = []
    for j in range(k):
        n = 2 * (j + 1)
        hs = z / n
        y0, y1 = 1.0, 1.0 + hs
        for _ in range(1, n):
            y0, y1 = y1, y0 + 2 * hs * y1
        row = [y1]
        for l in range(1, j + 1):
            nl = 2 * (j - l + 1)
            w = nl * nl / (n * n - nl * nl)
            row.append(row[l - 1] + (row[l - 1] - prev[l - 1]) * w)
        prev = row
    return prev[-1]


def boundary(k):
    """The first real x < 0 with |T_kk(x)| > 1, by a scan and bisection."""
    x = 0.0
    while abs(amplification(x - 0.01, k)) <= 1.0:
        x -= 0.01
    lo, hi = x - 0.01, x
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if abs(amplification(mid, k)) > 1.0 else (lo, mid)
    return 0.5 * (lo + hi)


if __name__ == "__main__":
    print("k\torder\treal boundary")
    for k in range(2, 9):
        print(f"{k}\t{2 * k}\t{boundary(k):.3f}")
    print("order 16 on the imaginary axis: y\t|T_88(iy)|")
    for y in (2, 4, 6, 8):
        print(f"{y}\t{abs(amplification(1j * y, 8)):.6f}")
