#!/usr/bin/env python3
"""Coefficients of the f32 special functions in `brdfs/src/microfacet/special.rs`.

Reproduces every coefficient table of that file (run: `python3 fit_beckmann.py`,
needs `mpmath` and `numpy`; deterministic, ~1 min). For each fit it prints the
Rust constants and the maximum relative error of the fitted function *with the
coefficients rounded to f32*, evaluated in 60-digit arithmetic on a dense grid
(so it is the approximation error alone; the f32 evaluation adds rounding,
which the Rust unit tests measure).

Reference values come from mpmath (`erfc`, `erfinv`) at 60+ digits.

1. Smith Λ of Beckmann. With a = 1/(α tan θ),
       Λ(a) = (e^{-a²}/(a√π) − erfc(a))/2 = e^{-a²} T(a) / (2√π a),
       T(a) = 1 − √π a erfcx(a),   erfcx(a) = e^{a²} erfc(a),
   T falls from 1 (a = 0) to ~1/(2a²); it is fitted as P(a)/Q(a), deg 4 / 6,
   on [0, A_ZERO], where A_ZERO is the a beyond which Λ < 2^-150 (rounds to 0
   in f32). Q is returned pre-multiplied by 2√π. The rationals are evaluated
   in f64 (coefficients kept in f64): Horner in f32 would add up to ~6 ulp.
2. erfcx(y) = P(y)/Q(y), deg 4 / 5, on [0, ERFC_ZERO] (erfc < 2^-150 beyond).
3. erfinv (f64 coefficients, evaluated in f64), in the form of M. Giles,
   "Approximating the erfinv function",
   GPU Computing Gems Jade Edition (2011), ch. 10 / 2010 preprint: with
   q = 1 − |x| and w = −ln(q (2 − q)) = −ln(1 − x²),
     central (w < 5):      erfinv(x) = x · P_c(w − 2.5),              deg 9
     tail   (w ≥ 5):       erfcinv(q) = P_t(√w − centre),  two pieces:
                           √w ∈ [√5, 4] deg 7 and √w ∈ [4, S_MAX] deg 8,
   where S_MAX corresponds to erfcinv(q) = 9 (MAX_SLOPE). Giles' own single
   precision coefficients stop near q ≈ 1e-7; these are refitted (own fit) to
   reach q ≈ 4e-37.
4. e^r = P(r) on |r| ≤ ln2/2, deg 6, for the exp kernel.
5. ln(1 + f)/f = P(f) on [√½ − 1, √2 − 1], deg 9, for the log kernel.

The slope sampler's fixed-step scheme is checked separately by
beckmann_slope_sweep.py.
"""
import mpmath as mp
import numpy as np

mp.mp.dps = 60
SQPI = mp.sqrt(mp.pi)


def f32(x):
    return float(np.float32(float(x)))


# ----------------------------------------------------------------- functions
def erfcx(y):
    y = mp.mpf(y)
    return mp.exp(y * y) * mp.erfc(y)


def t_lambda(a):
    a = mp.mpf(a)
    return 1 - SQPI * a * erfcx(a)


def lam(a):
    a = mp.mpf(a)
    return mp.exp(-a * a) * t_lambda(a) / (2 * SQPI * a)


def erfinv_over_x(w):
    """erfinv(x)/x as a function of w = −ln(1 − x²)."""
    w = mp.mpf(w)
    if w == 0:
        return SQPI / 2
    x = mp.sqrt(-mp.expm1(-w))
    return mp.erfinv(x) / x


def erfcinv_of_s(s):
    """erfcinv(q) where q (2 − q) = e^{−s²}."""
    w = mp.mpf(s) ** 2
    q = -mp.expm1(mp.log1p(-mp.exp(-w)) / 2)
    return -mp.erfinv(q - 1)


# ------------------------------------------------------------------- fitting
def cheb_grid(lo, hi, n):
    return [mp.mpf(lo) + (mp.mpf(hi) - lo) * (1 - mp.cos(mp.pi * i / (n - 1))) / 2 for i in range(n)]


def remez_linear(basis, g, f, xs, iters=40):
    """Minimax of max |Σ c_k basis_k(x) − g(x)| / |f(x)| over the grid xs
    (Remez exchange on a fine grid). Returns the coefficient list."""
    npts, m = len(xs), len(basis) + 1
    B = [[phi(x) for phi in basis] for x in xs]
    gx = [g(x) for x in xs]
    fx = [f(x) for x in xs]
    ref = [int(round((npts - 1) * (1 - np.cos(np.pi * i / (m - 1))) / 2)) for i in range(m)]
    best = None
    for _ in range(iters):
        A = mp.matrix(m, m)
        bb = mp.matrix(m, 1)
        for r, j in enumerate(ref):
            for k in range(m - 1):
                A[r, k] = B[j][k]
            A[r, m - 1] = (-1) ** r * abs(fx[j])
            bb[r] = gx[j]
        sol = mp.lu_solve(A, bb)
        c = [sol[k] for k in range(m - 1)]
        es = [(sum(ck * bk for ck, bk in zip(c, B[j])) - gx[j]) / abs(fx[j]) for j in range(npts)]
        emax = max(abs(e) for e in es)
        if best is None or emax < best[1]:
            best = (c, emax)
        segs, cur = [], [0]
        for j in range(1, npts):
            if (es[j] >= 0) == (es[cur[-1]] >= 0):
                cur.append(j)
            else:
                segs.append(cur)
                cur = [j]
        segs.append(cur)
        ext = [max(sg, key=lambda j: abs(es[j])) for sg in segs]
        while len(ext) > m:
            if abs(es[ext[0]]) < abs(es[ext[-1]]):
                ext.pop(0)
            else:
                ext.pop()
        if len(ext) < m:
            break
        ref = ext
        lev = abs(sol[m - 1])
        if abs(emax - lev) < 1e-4 * lev:
            break
    return best[0]


def remez_poly64(f, lo, hi, deg, centre, npts=800):
    """Minimax relative-error polynomial Σ c_k (x − centre)^k on [lo, hi],
    coefficients rounded to f64 (negligible)."""
    xs = cheb_grid(lo, hi, npts)
    basis = [(lambda x, j=j: (x - centre) ** j) for j in range(deg + 1)]
    return [mp.mpf(float(v)) for v in remez_linear(basis, f, f, xs)]


def horner(c, t):
    p = mp.mpf(0)
    for k in reversed(range(len(c))):
        p = p * t + c[k]
    return p


def rational_fit(f, lo, hi, m, n, npts=3000, outer=40, lawson=60):
    """Near-minimax relative-error rational P_m/Q_n with P(0) free, Q(0) = 1,
    by Sanathanan–Koerner linearisation with Lawson reweighting, in the
    scaled variable v = x/hi (for conditioning); returns mp coefficients in x."""
    xs = cheb_grid(lo, hi, npts)
    fx = np.array([float(f(x)) for x in xs])
    v = np.array([float(x / hi) for x in xs])
    Vp = np.vander(v, m + 1, increasing=True)
    Vq = np.vander(v, n + 1, increasing=True)
    q = np.ones(npts)
    w = np.ones(npts) / npts
    best = None
    for _ in range(outer):
        A = np.hstack([Vp, -fx[:, None] * Vq[:, 1:]]) / (fx * q)[:, None]
        b = 1.0 / q
        for _ in range(lawson):
            sw = np.sqrt(w)
            c, *_ = np.linalg.lstsq(A * sw[:, None], b * sw, rcond=None)
            r = np.abs(A @ c - b)
            w = w * r
            w /= w.sum()
        p = c[: m + 1]
        qq = np.concatenate([[1.0], c[m + 1:]])
        P, Q = Vp @ p, Vq @ qq
        err = np.max(np.abs(P / Q / fx - 1))
        if best is None or err < best[0]:
            best = (err, p, qq)
        q = Q
    _, p, qq = best
    hi = mp.mpf(hi)
    return [mp.mpf(p[k]) / hi ** k for k in range(m + 1)], [mp.mpf(qq[k]) / hi ** k for k in range(n + 1)]


def max_rel_err_rational(f, lo, hi, P, Q, scale=1, n=4000):
    worst = mp.mpf(0)
    for x in cheb_grid(lo, hi, n):
        e = abs(horner(P, x) * scale / horner(Q, x) / f(x) - 1)
        worst = max(worst, e)
    return worst


def max_rel_err_poly(f, lo, hi, c, centre, n=4000):
    worst = mp.mpf(0)
    for x in cheb_grid(lo, hi, n):
        worst = max(worst, abs(horner(c, x - centre) / f(x) - 1))
    return worst


def rust64(name, coeffs):
    body = ", ".join(repr(float(c)) for c in coeffs)
    return f"const {name}: [f64; {len(coeffs)}] = [{body}];"


def solve_increasing(fun, target, lo, hi):
    """x in [lo, hi] with fun(x) = target for a decreasing fun."""
    return mp.findroot(lambda x: mp.log(fun(x)) - mp.log(target), ((lo + hi) / 2), tol=1e-40)


def main():
    tiny = mp.mpf(2) ** -150
    a_zero = solve_increasing(lam, tiny, 9, 11)
    erfc_zero = solve_increasing(mp.erfc, tiny, 9, 11)
    a_zero_f = f32(mp.ceil(a_zero * 64) / 64)
    erfc_zero_f = f32(mp.ceil(erfc_zero * 64) / 64)
    print(f"// Λ(a) < 2^-150 for a > {mp.nstr(a_zero, 10)}; erfc(x) < 2^-150 for x > {mp.nstr(erfc_zero, 10)}")
    print(f"const LAMBDA_ZERO_A: f32 = {a_zero_f!r};")
    print(f"const ERFC_ZERO: f32 = {erfc_zero_f!r};")

    # 1. Λ: T(a) = P/Q on [0, a_zero_f]; Q scaled by 2√π.
    P, Q = rational_fit(t_lambda, 0, a_zero_f, 4, 6)
    P64 = [mp.mpf(float(c)) for c in P]
    Q64 = [mp.mpf(float(2 * SQPI * c)) for c in Q]
    e = max_rel_err_rational(t_lambda, 0, a_zero_f, P64, Q64, scale=2 * SQPI)
    print(f"// T(a) = 2√π P(a)/Q(a) on [0, {a_zero_f}]: max rel error {mp.nstr(e, 3)} (f64 coefficients)")
    print(rust64("LAMBDA_P", P64))
    print(rust64("LAMBDA_Q", Q64))

    # 2. erfcx on [0, erfc_zero_f]
    P, Q = rational_fit(erfcx, 0, erfc_zero_f, 4, 5)
    P64 = [mp.mpf(float(c)) for c in P]
    Q64 = [mp.mpf(float(c)) for c in Q]
    e = max_rel_err_rational(erfcx, 0, erfc_zero_f, P64, Q64)
    print(f"// erfcx(y) = P(y)/Q(y) on [0, {erfc_zero_f}]: max rel error {mp.nstr(e, 3)} (f64 coefficients)")
    print(rust64("ERFCX_P", P64))
    print(rust64("ERFCX_Q", Q64))

    # 3. erfinv (f64 coefficients, evaluated in f64)
    c = remez_poly64(erfinv_over_x, mp.mpf(0), mp.mpf(5), 9, mp.mpf("2.5"))
    e = max_rel_err_poly(erfinv_over_x, 0, 5, c, mp.mpf("2.5"))
    print(f"// erfinv(x)/x = P(w − 2.5), w ∈ [0, 5]: max rel error {mp.nstr(e, 3)} (f64 coefficients)")
    print(rust64("ERFINV_CENTRAL", c))
    s_max = mp.sqrt(-mp.log(mp.erfc(9) * (2 - mp.erfc(9))))
    s_max_f = f32(mp.ceil(s_max * 64) / 64)
    print(f"// erfcinv(q) = 9 at s = √w = {mp.nstr(s_max, 10)}")
    for lo, hi, deg, name in [(mp.sqrt(5), mp.mpf(4), 7, "ERFINV_TAIL1"), (mp.mpf(4), mp.mpf(s_max_f), 8, "ERFINV_TAIL2")]:
        centre = mp.mpf(f32((lo + hi) / 2))
        c = remez_poly64(erfcinv_of_s, lo, hi, deg, centre)
        e = max_rel_err_poly(erfcinv_of_s, lo, hi, c, centre)
        print(f"// erfcinv = P(s − {f32(centre)!r}), s ∈ [{mp.nstr(lo, 8)}, {mp.nstr(hi, 8)}]: max rel error {mp.nstr(e, 3)} (f64 coefficients)")
        print(rust64(name, c))

    # 4. e^r on |r| ≤ ln2/2 for the exp kernel
    h = mp.log(2) / 2
    c = remez_poly64(mp.exp, -h, h, 6, mp.mpf(0))
    e = max_rel_err_poly(mp.exp, -h, h, c, mp.mpf(0))
    print(f"// e^r = P(r), |r| ≤ ln2/2: max rel error {mp.nstr(e, 3)} (f64 coefficients)")
    print(rust64("EXP_POLY", c))

    # 5. ln(1 + f) = f P(f) on f ∈ [√½ − 1, √2 − 1] for the log kernel
    lo, hi = mp.sqrt(2) / 2 - 1, mp.sqrt(2) - 1
    log1p_over = lambda f: mp.log1p(f) / f if f != 0 else mp.mpf(1)
    c = remez_poly64(log1p_over, lo, hi, 9, mp.mpf(0), npts=400)
    e = max_rel_err_poly(log1p_over, lo, hi, c, mp.mpf(0))
    print(f"// ln(1+f)/f = P(f), f ∈ [√½−1, √2−1]: max rel error {mp.nstr(e, 3)} (f64 coefficients)")
    print(rust64("LOG_POLY", c))


if __name__ == "__main__":
    main()
