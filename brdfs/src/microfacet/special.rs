//! Special functions for the Beckmann distribution, in `f32`.

use core::f32::consts::PI;

/// `1/√π`.
pub(crate) const FRAC_1_SQRT_PI: f32 = 0.564_189_6;

/// Largest slope magnitude the samplers produce: `erfc(9) ≈ 4·10⁻³⁷`, so the
/// Gaussian mass beyond it is below anything an `f32` sample can resolve,
/// and `e^{9²}` is still finite in `f32`.
pub(crate) const MAX_SLOPE: f32 = 9.0;

/// `erfinv(2p − 1)` for `p ∈ [0, 1]` (the quantile of a normal
/// distribution with variance 1/2), clamped to `[−MAX_SLOPE, MAX_SLOPE]`.
///
/// The tail parameter `q = 2 min(p, 1 − p)` is formed exactly, and
/// `y = erfcinv(q)` is found from Winitzki's approximation (S. Winitzki
/// 2008, "A handy approximation for the error function and its inverse",
/// eq. 7 with `a = 0.147`, relative error ≈ 2·10⁻³) refined by two Newton
/// steps on `g(y) = ln erfc(y) − ln q`, whose derivative is
/// `g'(y) = −2 e^{−y²} / (√π erfc(y))`. Working with the logarithm keeps the
/// tail (`q → 0`) as accurate as the centre.
pub(crate) fn erfinv_2p_minus_1(p: f32) -> f32 {
    let (q, sign) = tail(p);
    sign * erfcinv_upper(q, 2)
}

/// Winitzki's approximation of `erfinv(2p − 1)` alone (relative error
/// ≈ 2·10⁻³), used as a cheap starting point for other Newton iterations.
pub(crate) fn erfinv_2p_minus_1_guess(p: f32) -> f32 {
    let (q, sign) = tail(p);
    sign * erfcinv_upper(q, 0)
}

/// `(q, sign)` with `q = 2 min(p, 1 − p)` formed exactly.
#[inline]
fn tail(p: f32) -> (f32, f32) {
    let p = super::clamp01(p);
    if p < 0.5 {
        (2.0 * p, -1.0)
    } else {
        (2.0 * (1.0 - p), 1.0)
    }
}

/// `y ≥ 0` with `erfc(y) = q`, for `q ∈ [0, 1]`; `MAX_SLOPE` for tiny `q`.
/// `steps` Newton refinements follow the initial approximation (two bring
/// the 2·10⁻³ start to `f32` accuracy: the convergence is quadratic).
fn erfcinv_upper(q: f32, steps: usize) -> f32 {
    if q >= 1.0 {
        return 0.0;
    }
    if q < 1e-36 {
        return MAX_SLOPE;
    }
    // Winitzki: erfinv(x) ≈ sqrt( sqrt(b² − L/a) − b ), b = 2/(πa) + L/2,
    // L = ln(1 − x²) = ln(q (2 − q)) with x = 1 − q.
    const A: f32 = 0.147;
    let l = libm::logf(q * (2.0 - q));
    let b = 2.0 / (PI * A) + 0.5 * l;
    let mut y = libm::sqrtf((libm::sqrtf(b * b - l / A) - b).max(0.0));
    let lnq = if steps > 0 { libm::logf(q) } else { 0.0 };
    for _ in 0..steps {
        y = y.clamp(0.0, MAX_SLOPE);
        let e = libm::erfcf(y);
        if e <= 0.0 {
            break;
        }
        // y ← y − g/g' = y + (ln erfc(y) − ln q) · √π erfc(y) e^{y²} / 2
        let step = (libm::logf(e) - lnq) * e * libm::expf(y * y) / (2.0 * FRAC_1_SQRT_PI);
        if !step.is_finite() {
            break;
        }
        y += step;
    }
    y.clamp(0.0, MAX_SLOPE)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Reference: f64 bisection on libm's f64 `erf` (independent of the f32
    /// Newton scheme above).
    fn erfinv_ref(x: f64) -> f64 {
        let (mut lo, mut hi) = (-10.0f64, 10.0f64);
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if libm::erf(mid) < x { lo = mid } else { hi = mid }
        }
        0.5 * (lo + hi)
    }

    /// The error is measured against the conditioning of the problem: an
    /// `f32` evaluation of `erfc` has relative error ~ε, which moves the root
    /// by `ε·erfc(y)/|erfc'(y)|`; we require at most 8 such units (plus
    /// 4 ulp of `y`).
    #[test]
    fn erfinv_matches_bisection() {
        let eps = f32::EPSILON as f64;
        let mut worst = 0.0f64;
        for i in 1..4000 {
            let p = i as f32 / 4000.0;
            let y = erfinv_2p_minus_1(p) as f64;
            let r = erfinv_ref(2.0 * p as f64 - 1.0);
            let slope = 2.0 / libm::sqrt(core::f64::consts::PI) * libm::exp(-r * r);
            let unit = eps * libm::erfc(r.abs()) / slope + 4.0 * eps * r.abs();
            worst = worst.max((y - r).abs() / unit);
        }
        assert!(worst < 8.0, "worst error {worst} conditioning units");
    }

    #[test]
    fn erfinv_tails() {
        // q = 2(1 − p) small: compare with the f64 complementary reference.
        for &p in &[0.999f32, 0.99999, 0.99999994, 1e-7, 1e-20, 1e-30] {
            let y = erfinv_2p_minus_1(p) as f64;
            let q = if p >= 0.5 {
                2.0 * (1.0 - p as f64)
            } else {
                2.0 * p as f64
            };
            // erfc(|y|) must reproduce q to f32-level relative accuracy.
            let back = libm::erfc(y.abs());
            assert!((back - q).abs() <= 1e-4 * q, "p={p} y={y} erfc={back} q={q}");
            assert!((p >= 0.5) == (y >= 0.0));
        }
        assert_eq!(erfinv_2p_minus_1(0.5), 0.0);
        assert_eq!(erfinv_2p_minus_1(1.0), MAX_SLOPE);
        assert_eq!(erfinv_2p_minus_1(0.0), -MAX_SLOPE);
        assert_eq!(erfinv_2p_minus_1(f32::NAN), -MAX_SLOPE);
    }
}
