#!/usr/bin/env python3
"""Start table of the fast Beckmann visible-slope sampler
(`brdfs/src/microfacet/beckmann_slope.rs`), and an exact-arithmetic sweep of
the scheme it starts.

The slope x̃ of the standard (α = 1) Beckmann surface seen at angle θ has the
unnormalised CDF (Heitz & d'Eon 2014, §4.2)

    2C(x) = c erfc(−x) + s e^{−x²}/√π,   x ≤ b = min(cot θ, 9),   c = cos θ, s = sin θ.

The table holds the exact quantile x(β, t) (bisection on 2C in f64, Python's
`math.erfc`) at the nodes

    β_i = i / (NB − 1)                    β = c/(c + s) ∈ [0, 1]
    t_j = T_LO + (T_HI − T_LO) j/(NT − 1)  t = log2(u/(1 − u)) ∈ [−20, 10]

(u ∈ [9.5·10⁻⁷, 1 − 9.8·10⁻⁴]); the sampler interpolates it bilinearly and
takes one Halley step on 2C(x) − 2uC(b) (see the Rust module). `β` and the
logit make the quantile smooth: β → 1 is the Gaussian (θ = 0), β → 0 the
grazing limit x = −√(−ln u); in t the tails approach x ∓ √|t| and
b − O(e^{−t/2}).

Run: `python3 beckmann_slope_table.py > ../src/microfacet/beckmann_slope_table.rs`
writes the Rust table; `python3 beckmann_slope_table.py --sweep` evaluates the
scheme (table start, log2 polynomial, one Halley step) in f64 with the exact
erfc on random and edge (θ, u) and prints the worst
    |C(x)/C(b) − u|                         (absolute) and
    |C(x) − uC(b)| / min(uC(b), (1 − u)C(b)) (relative to the tail mass).
Standard library only (numpy for the f32 literals of the table). The Rust unit tests measure the f32 implementation.
"""
import math
import random
import sys

SQPI = math.sqrt(math.pi)
MAX_SLOPE = 9.0
NB, NT = 33, 41
T_LO, T_HI = -20.0, 10.0
# log2(1 + f) ≈ f·P(f) on [0, 1), least squares on Chebyshev nodes (numpy
# lstsq, rounded to f32 in the Rust file): max error 1.7e-5.
LOG2_POLY = [1.4418798958064658, -0.708865217733883, 0.41524556038937144,
             -0.19351652460557642, 0.045268292603908925]


def cdf2(c, s, x):
    """2C(x) = c erfc(−x) + s e^{−x²}/√π."""
    return c * math.erfc(-x) + s * math.exp(-x * x) / SQPI


def bound(c, s):
    return MAX_SLOPE if s * MAX_SLOPE <= c else c / s


def quantile(c, s, u):
    b = bound(c, s)
    t = u * cdf2(c, s, b)
    lo, hi = -MAX_SLOPE, b
    for _ in range(200):
        m = 0.5 * (lo + hi)
        if cdf2(c, s, m) < t:
            lo = m
        else:
            hi = m
    return 0.5 * (lo + hi)


def cs_of_beta(beta):
    if beta >= 1.0:
        return 1.0, 0.0
    r = beta / (1.0 - beta)  # cot θ
    n = math.hypot(r, 1.0)
    return r / n, 1.0 / n


def u_of_t(t):
    return 1.0 / (1.0 + 2.0 ** (-t))


def table():
    return [[quantile(*cs_of_beta(i / (NB - 1)), u_of_t(T_LO + (T_HI - T_LO) * j / (NT - 1)))
             for j in range(NT)] for i in range(NB)]


def log2_approx(q):
    m, e = math.frexp(q)  # q = m 2^e, m ∈ [1/2, 1)
    f = 2.0 * m - 1.0
    p = 0.0
    for k in reversed(LOG2_POLY):
        p = p * f + k
    return (e - 1) + f * p


def start(tab, c, s, u):
    beta = c / (c + s)
    t = min(max(log2_approx(u / (1.0 - u)), T_LO), T_HI)
    fi = beta * (NB - 1)
    fj = (t - T_LO) * ((NT - 1) / (T_HI - T_LO))
    i, j = min(int(fi), NB - 2), min(int(fj), NT - 2)
    a, w = fi - i, fj - j
    lo = tab[i][j] + w * (tab[i][j + 1] - tab[i][j])
    hi = tab[i + 1][j] + w * (tab[i + 1][j + 1] - tab[i + 1][j])
    return lo + a * (hi - lo)


def erfcx(y):
    return math.exp(y * y) * math.erfc(y) if y < 25 else 1 / (SQPI * y)


def halley(c, s, u, x):
    """One Halley step on r(x) = 2C(x) − 2uC(b), written as in the Rust code."""
    b = bound(c, s)
    e_b = s * (math.exp(-b * b) - SQPI * b * math.erfc(b)) / SQPI  # 2C(b) − 2c
    total2 = 2 * c + e_b
    if x <= 0:
        r = -u * total2 + math.exp(-x * x) * (s / SQPI + c * erfcx(-x))
    else:
        r = ((1 - u) * total2 - e_b) + math.exp(-x * x) * (s / SQPI - c * erfcx(x))
    e = math.exp(-x * x)
    d = c - x * s
    den = 4 * d * d * e + r * SQPI * (s + 2 * x * d)
    x1 = x - 2 * r * SQPI * d / den if den != 0 else x
    return min(max(x1, -MAX_SLOPE), b)


def sweep(n=200_000):
    tab = table()
    rng = random.Random(1)
    u_lo, u_hi = 2.0 ** -20, 1.0 - 2.0 ** -10
    worst = {}
    for k in range(n):
        if k % 10:
            th = rng.random() * math.pi / 2
        else:
            th = math.pi / 2 * (1 - 10 ** -rng.uniform(0, 8))
        if k % 20 == 1:
            th = 10 ** -rng.uniform(0, 8)
        u = u_lo + (u_hi - u_lo) * rng.random()
        if k % 7 == 0:
            u = u_lo * (1 + 10 * rng.random()) if k % 2 else u_hi - 2 ** -10 * 10 * rng.random()
        if k % 13 == 0:
            u = 10 ** -rng.uniform(0.3, 6)
        u = min(max(u, u_lo), u_hi)
        s, c = math.sin(th), math.cos(th)
        total = cdf2(c, s, bound(c, s))
        x0 = start(tab, c, s, u)
        for name, x in (("start", x0), ("1 Halley step", halley(c, s, u, x0))):
            err = abs(cdf2(c, s, x) / total - u)
            rel = err / min(u, 1 - u)
            if err > worst.get((name, "abs"), (0,))[0]:
                worst[(name, "abs")] = (err, th, u)
            if rel > worst.get((name, "rel"), (0,))[0]:
                worst[(name, "rel")] = (rel, th, u)
    for name in ("start", "1 Halley step"):
        a, r = worst[(name, "abs")], worst[(name, "rel")]
        print(f"{name}: max |C(x)/C(b) - u| = {a[0]:.2e} (θ={a[1]:.9f}, u={a[2]:.6g}); "
              f"tail-relative {r[0]:.2e} (θ={r[1]:.9f}, u={r[2]:.6g})")


def f32(v):
    """The shortest decimal that rounds to the same f32 as v (numpy's repr)."""
    import numpy as np
    r = str(np.float32(v))
    return r if ("." in r or "e" in r) else r + ".0"


def emit():
    tab = table()
    print("//! Generated by `brdfs/tools/beckmann_slope_table.py` (do not edit): the")
    print("//! start table of the fast Beckmann visible-slope sampler (`beckmann_slope.rs`).")
    print()
    print(f"/// Rows over β = c/(c + s): `NB = {NB}` nodes on [0, 1].")
    print(f"pub(super) const NB: usize = {NB};")
    print(f"/// Columns over t = log2(u/(1 − u)): `NT = {NT}` nodes on [T_LO, T_HI].")
    print(f"pub(super) const NT: usize = {NT};")
    print("/// The lowest `t` node.")
    print(f"pub(super) const T_LO: f32 = {T_LO};")
    print("/// The highest `t` node.")
    print(f"pub(super) const T_HI: f32 = {T_HI};")
    print("/// `log2(1 + f) ≈ f·P(f)` on `[0, 1)` (least squares, max error 1.7·10⁻⁵).")
    print("pub(super) const LOG2_POLY: [f32; 5] = [" + ", ".join(f32(v) for v in LOG2_POLY) + "];")
    print("/// The exact quantile `x(β_i, t_j)` (row-major, `i` slow), rounded to `f32`.")
    print("#[rustfmt::skip]")
    print(f"pub(super) static TABLE: [f32; {NB * NT}] = [")
    for row in tab:
        vals = [f32(v) for v in row]
        for k in range(0, len(vals), 8):
            print("    " + ", ".join(vals[k:k + 8]) + ",")
    print("];")


if __name__ == "__main__":
    if "--sweep" in sys.argv:
        sweep()
    else:
        emit()
