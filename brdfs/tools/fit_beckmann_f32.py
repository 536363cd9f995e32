#!/usr/bin/env python3
"""Coefficients of the f32 Beckmann projected-area rational in
`brdfs/src/microfacet/beckmann_f32.rs` (run: `python3 fit_beckmann_f32.py`,
needs `mpmath` and `numpy`, imports the helpers of `fit_beckmann.py`;
deterministic, ~1 min).

The hot path of the Beckmann BRDF needs the projected area
    A = cos θ (1 + Λ) = cos θ + α sin θ · aΛ(a),   a = cos θ / (α sin θ),
with aΛ(a) = e^{-a²} T(a)/(2√π), T(a) = 1 − √π a erfcx(a) (Heitz 2014, eq. 80
times a). Only A matters, to f32 accuracy, so aΛ needs

    |δ(aΛ)| ≤ ε (a + aΛ(a))        (relative error ε of A),

i.e. relative accuracy where Λ dominates (a → 0, grazing) and only absolute
accuracy ~ε·a where Λ is small. Under that weight aΛ itself — exponential
included — is fitted by one rational P(a)/Q(a) of degree 6/6 on [0, A_CUT],
with A_CUT = 3.5 where Λ(3.5) = 1.4·10⁻⁸ (2⁻²⁶): beyond it A = cos θ (the
dropped cos θ·Λ is below a quarter of an f32 ulp of A).

Method: Sanathanan–Koerner linearisation with Lawson reweighting on the
weighted error |P/Q − aΛ| / (a + aΛ) (60-digit mpmath references), then the
coefficients are rounded to f32. Printed: the weighted error of the rounded
coefficients in exact arithmetic, and the error of A itself in f32 ulps with
the Rust evaluation order (Horner in f32) simulated in numpy float32, against
A = cos θ (1 + Λ) in 60 digits at the same f32 inputs.
"""
import numpy as np

from fit_beckmann import SQPI, cheb_grid, horner, lam, mp, t_lambda

A_CUT = 3.5
DEG = 6


def a_lambda(a):
    a = mp.mpf(a)
    return mp.exp(-a * a) * t_lambda(a) / (2 * SQPI)


def weight(a):
    a = mp.mpf(a)
    return a + a_lambda(a)


def weighted_rational_fit(f, wf, lo, hi, m, n, npts=1200, outer=40, lawson=60):
    """Near-minimax P_m/Q_n (Q(0) = 1) of max |P/Q − f| / wf, in the scaled
    variable v = x/hi; returns mp coefficients in x."""
    xs = cheb_grid(lo, hi, npts)
    fx = np.array([float(f(x)) for x in xs])
    wx = np.array([float(wf(x)) for x in xs])
    v = np.array([float(x / hi) for x in xs])
    vp = np.vander(v, m + 1, increasing=True)
    vq = np.vander(v, n + 1, increasing=True)
    q = np.ones(npts)
    w = np.ones(npts) / npts
    best = None
    for _ in range(outer):
        a = np.hstack([vp, -fx[:, None] * vq[:, 1:]]) / (wx * q)[:, None]
        b = fx / (wx * q)
        for _ in range(lawson):
            sw = np.sqrt(w)
            c, *_ = np.linalg.lstsq(a * sw[:, None], b * sw, rcond=None)
            r = np.abs(a @ c - b)
            w = w * r
            w /= w.sum()
        p = c[: m + 1]
        qq = np.concatenate([[1.0], c[m + 1:]])
        err = np.max(np.abs((vp @ p / (vq @ qq) - fx) / wx))
        if best is None or err < best[0]:
            best = (err, p, qq)
        q = vq @ qq
    _, p, qq = best
    hi = mp.mpf(hi)
    return [mp.mpf(p[k]) / hi**k for k in range(m + 1)], [mp.mpf(qq[k]) / hi**k for k in range(n + 1)]


def area_f32(p32, q32, alpha, c, s2):
    """The Rust `projected_area` in float32, operation for operation."""
    f = np.float32
    s = f(np.sqrt(s2))
    alpha_s = f(f(alpha) * s)
    a = f(c / alpha_s)
    if a >= f(A_CUT):
        return c
    ph, qh = p32[-1], q32[-1]
    for k in range(DEG - 1, -1, -1):
        ph = f(f(ph * a) + p32[k])
        qh = f(f(qh * a) + q32[k])
    return f(c + f(alpha_s * f(ph / qh)))


def main():
    p, q = weighted_rational_fit(a_lambda, weight, 0, A_CUT, DEG, DEG)
    # P(0)/Q(0) must be 1/(2√π) (the grazing value), which no single f32
    # represents to better than 5·10⁻⁸: scale P and Q by the f32 q0 ∈
    # [1 − 2⁻¹², 1] whose partner p0 = f32(q0/(2√π)) makes p0/q0 closest.
    c0 = 1 / (2 * SQPI)
    scales = [np.float32(1) - np.float32(k) * np.float32(2.0**-24) for k in range(4096)]
    q0 = min(scales, key=lambda v: abs(mp.mpf(float(np.float32(float(c0 * float(v))))) / float(v) - c0))
    print(f"Q(0) = {float(q0)!r}: P(0)/Q(0) = 1/(2√π) to "
          f"{float(abs(mp.mpf(float(np.float32(float(c0 * float(q0))))) / float(q0) / c0 - 1)):.1e}")
    p32 = [np.float32(float(v * float(q0))) for v in p]
    q32 = [np.float32(float(v * float(q0))) for v in q]
    p32[0] = np.float32(float(c0 * float(q0)))
    q32[0] = q0
    worst = max(
        abs(horner([mp.mpf(float(v)) for v in p32], x) / horner([mp.mpf(float(v)) for v in q32], x) - a_lambda(x))
        / weight(x)
        for x in cheb_grid(0, A_CUT, 4000)
    )
    print(f"Λ({A_CUT}) = {float(lam(A_CUT)):.3e}")
    print(f"weighted error |P/Q − aΛ|/(a + aΛ), f32 coefficients: {float(worst):.3e}")
    worst_ulp = 0.0
    for alpha in [1.0, 0.3, 0.05]:
        for t in np.linspace(0.0005, np.pi / 2, 3001):
            c = np.float32(np.cos(t))
            s2 = np.float32(np.float32(np.sin(t)) ** 2)
            got = area_f32(p32, q32, alpha, c, s2)
            a = mp.mpf(float(c)) / (alpha * mp.sqrt(mp.mpf(float(s2))))
            ref = float(mp.mpf(float(c)) * (1 + lam(a)))
            worst_ulp = max(worst_ulp, abs(float(got) - ref) / float(np.spacing(np.float32(ref))))
    print(f"A in f32 (simulated), α ∈ {{1, 0.3, 0.05}}, θ grid: worst {worst_ulp:.2f} ulp")
    fmt = lambda cs: ", ".join(repr(float(v)) for v in cs)
    print(f"const AREA_P: [f32; {DEG + 1}] = [{fmt(p32)}];")
    print(f"const AREA_Q: [f32; {DEG + 1}] = [{fmt(q32)}];")


if __name__ == "__main__":
    main()
