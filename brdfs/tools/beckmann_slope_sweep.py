#!/usr/bin/env python3
"""Exact-arithmetic (f64) sweep of the fixed-step Beckmann visible-slope
inversion in `brdfs/src/microfacet/beckmann.rs` (`sample_slope_x`).

Mirrors the Rust scheme step for step, in f64 with the exact erfc of Python's
`math` module, and reports, for 0..4 Halley steps, the worst
    |C(x)/C(b) − u|            (absolute, over the whole sweep) and
    |C(x) − uC(b)| / min(uC(b), (1 − u)C(b))   (relative to the tail mass)
over θ ∈ [0, π/2] (97 angles + near-grazing ones) and u from 1e-38 to
1 − 6e-8. Run: `python3 beckmann_slope_sweep.py` (standard library only).
The Rust unit tests measure the f32 implementation itself.
"""
import math

SQPI = math.sqrt(math.pi)
MAX_SLOPE = 9.0


def erfcx(y):
    if y < 25:
        return math.exp(y * y) * math.erfc(y)
    return 1 / (SQPI * y) * (1 - 0.5 / (y * y))


def cdf(c, s, x):
    """C(x) = cos θ erfc(−x)/2 + sin θ e^{−x²}/(2√π)."""
    return 0.5 * c * math.erfc(-x) + 0.5 * s * math.exp(-x * x) / SQPI


def beckmann_s(a):
    """S(a) = e^{−a²} − √π a erfc(a)."""
    return math.exp(-a * a) - SQPI * a * math.erfc(a)


def erfcinv(q):
    lo, hi = -10.0, 10.0
    for _ in range(100):
        m = 0.5 * (lo + hi)
        if math.erfc(m) > q:
            lo = m
        else:
            hi = m
    return 0.5 * (lo + hi)


def slope_lower(c, s, u, total2, c0, steps):
    l0 = max(-math.log(u * total2 / c0), 0.0)
    x = -math.sqrt(l0)
    if c > 0:
        x = max(x, -l0 * (0.5 * SQPI * c0 / c))
    x = max(x, -MAX_SLOPE)
    lo, hi = x, 0.0
    for _ in range(steps):
        h = c * erfcx(-x) + s / SQPI
        g = l0 - x * x + math.log(h / c0)
        if g > 0:
            hi = x
        else:
            lo = x
        den = c - x * s
        gp = 2 * den / (SQPI * h)
        try:
            n = g / gp
            nxt = x - n / (1 + n * (0.5 * s / den + 0.5 * gp + x))
        except ZeroDivisionError:
            nxt = float("nan")
        x = nxt if lo <= nxt <= hi else 0.5 * (lo + hi)
    return min(max(x, -MAX_SLOPE), 0.0)


def slope_upper(c, s, u, b, total2, excess, steps):
    gs = (1 - u) * total2
    ln_gs = math.log(gs)
    x = b
    if c > 0:
        q = (gs - excess) / c
        if 0 < q < 2:
            z = erfcinv(q)
            zs = z * s
            x = min(x, z - s / (math.sqrt(c * c + zs * zs) + c - zs))
    if b < MAX_SLOPE:
        xe = max(b - math.sqrt(SQPI * gs / (s * math.exp(-b * b))), 0.0)
        x = min(x, b - math.sqrt(SQPI * gs * math.exp(xe * xe) / s))
    x = max(x, 0.0)
    # TAIL_RESOLUTION: a target below the f32 resolution of G keeps the start.
    if b < MAX_SLOPE and gs <= 16 * 2.0 ** -23 * (excess + s / SQPI * math.exp(-b * b)):
        return min(x, b)
    lo, hi = 0.0, b
    for _ in range(steps):
        e = math.exp(-x * x)
        den = c - x * s
        p = den * e / SQPI
        g = excess + e * (c * erfcx(x) - s / SQPI)
        nxt = float("nan")
        if g > 0:
            phi = math.log(g) - ln_gs
            if phi > 0:
                lo = x
            else:
                hi = x
            try:
                n = -phi * g / (2 * p)
                nxt = x - n / (1 + n * (0.5 * s / den + x - p / g))
            except ZeroDivisionError:
                pass
        else:
            hi = x
        x = nxt if lo <= nxt <= hi else 0.5 * (lo + hi)
    return min(max(x, 0.0), b)


def sample_slope_x(c, s, u, steps):
    b = MAX_SLOPE if s * MAX_SLOPE <= c else c / s
    if u <= 0:
        return -MAX_SLOPE
    if u >= 1:
        return b
    excess = s * beckmann_s(b) / SQPI
    total2 = 2 * c + excess
    c0 = c + s / SQPI
    if u * total2 <= c0:
        return slope_lower(c, s, u, total2, c0, steps)
    return slope_upper(c, s, u, b, total2, excess, steps)


def main():
    thetas = [k / 96 * math.pi / 2 for k in range(97)] + [math.pi / 2 - 1e-3, math.pi / 2 - 1e-5, 1e-4]
    us = [1e-38, 1e-30, 1e-20, 1e-12, 1e-7, 1e-5, 1e-3] + [i / 400 for i in range(1, 400)]
    us += [1 - 1e-3, 1 - 1e-5, 1 - 6e-8]
    for steps in range(5):
        w_abs = w_rel = 0.0
        for th in thetas:
            s, c = math.sin(th), math.cos(th)
            b = MAX_SLOPE if s * MAX_SLOPE <= c else c / s
            total = cdf(c, s, b)
            for u in us:
                x = sample_slope_x(c, s, u, steps)
                t = u * total
                err = abs(cdf(c, s, x) - t)
                w_abs = max(w_abs, err / total)
                if x > -MAX_SLOPE:  # below: the MAX_SLOPE clamp, by design
                    w_rel = max(w_rel, err / min(t, total - t))
        print(f"{steps} Halley steps: max |C(x)/C(b) - u| = {w_abs:.2e}, max tail-relative = {w_rel:.2e}")


if __name__ == "__main__":
    main()
