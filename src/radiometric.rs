//! Radiometric closed forms: solid angles of cones, and the irradiance on a
//! surface (normal `+Z`) from a uniform sky, a directional (delta) light and a
//! uniform spherical cap (sun, spherical lamp) — including a cap that is
//! partly below the horizon.
//!
//! Irradiance is `E = ∫_H L(ω) cos θ dω` (Nicodemus et al. 1977, NBS
//! Monograph 160; Pharr, Jakob & Humphreys, *Physically Based Rendering* 4th
//! ed., §4.1.3 eq. 4.7). For a source of uniform radiance `L` occupying a set
//! `C` of directions, `E = L · Ω⊥(C ∩ H)` where
//! `Ω⊥(A) = ∫_A cos θ dω` is the *projected solid angle* of `A`.
//!
//! Every function is `f32`, uses only `libm` (no hidden `f64`), and returns a
//! finite value for every finite input.
//!
//! ```
//! use radiometry::radiometric::{cap_irradiance, cap_solid_angle, sky_irradiance};
//! use core::f32::consts::{FRAC_PI_2, PI};
//! // A hemisphere is a cap of half-angle π/2: Ω = 2π.
//! assert!((cap_solid_angle(FRAC_PI_2) - 2.0 * PI).abs() < 1e-6);
//! // A uniform sky of radiance 1 gives E = π.
//! assert!((sky_irradiance(1.0f32) - PI).abs() < 1e-6);
//! // A cap whose axis lies on the horizon: half of it is visible.
//! let sigma = 0.3f32;
//! let e = cap_irradiance(1.0f32, 0.0, sigma);
//! assert!((e - (sigma - libm::sinf(sigma) * libm::cosf(sigma))).abs() < 1e-6);
//! ```

use crate::math::safe_sqrt;
use crate::spectrum::Spectrum;
use core::f32::consts::{FRAC_PI_2, PI};

/// Solid angle of a cone (spherical cap) of half-angle `θ`:
/// `Ω = 2π(1 − cos θ) = 4π sin²(θ/2)`.
///
/// Source: PBR 4th ed. §4.1.1 (solid angle of a cone); the half-angle form
/// `4π sin²(θ/2)` is used because it keeps full relative precision for tiny
/// cones (the sun: `θ ≈ 4.65·10⁻³`), where `1 − cos θ` cancels.
///
/// Domain: `θ ∈ [0, π]` (radians); values outside are clamped to it, NaN
/// gives 0.
#[inline]
pub fn cap_solid_angle(half_angle: f32) -> f32 {
    let t = clamp_or_zero(half_angle, 0.0, PI);
    let s = libm::sinf(0.5 * t);
    4.0 * PI * s * s
}

/// Irradiance on a surface from a uniform sky of radiance `L` over the whole
/// upper hemisphere: `E = L ∫_H cos θ dω = π L`.
///
/// Source: PBR 4th ed. §4.1.3 (irradiance from constant radiance, eq. 4.8).
/// Domain: any `L` (channel-wise); the result is finite when `L` is finite
/// and `|L| < f32::MAX/π`.
#[inline]
pub fn sky_irradiance<S: Spectrum>(radiance: S) -> S {
    radiance * PI
}

/// Irradiance from a directional (delta) light of irradiance `E⊥` measured
/// on a plane perpendicular to the light, at polar angle `θ` from the normal:
/// `E = E⊥ max(0, cos θ)` (Lambert's cosine law; PBR 4th ed. §4.1.3,
/// eq. 4.9 for a distant light).
///
/// Domain: `cos θ` is clamped to `[−1, 1]` (NaN counts as below the horizon).
#[inline]
pub fn directional_irradiance<S: Spectrum>(e_perp: S, cos_theta: f32) -> S {
    let c = clamp_or_zero(cos_theta, 0.0, 1.0);
    e_perp * c
}

/// Projected solid angle `Ω⊥ = ∫_{C ∩ H} cos θ dω` of a spherical cap `C` of
/// half-angle `σ` whose axis makes angle `θa` with the normal, clipped to the
/// upper hemisphere `H`. The irradiance from a uniform cap of radiance `L` is
/// `L · Ω⊥` ([`cap_irradiance`]).
///
/// With `c = cos θa`, `s = sin θa`:
/// * fully above the horizon (`θa + σ ≤ π/2`, i.e. `c ≥ sin σ`):
///   `Ω⊥ = π sin²σ cos θa` (the classic sphere-light result, e.g. PBR 4th ed.
///   §12.2.2; Snyder 1996);
/// * fully below (`θa − σ ≥ π/2`, i.e. `c ≤ −sin σ`): `Ω⊥ = 0`;
/// * partly below: the horizon-clipped closed form of Snyder 1996, "Area
///   light sources for real-time graphics", Microsoft Research
///   MSR-TR-96-11, in the form given by Lagarde & de Rousiers 2014, "Moving
///   Frostbite to Physically Based Rendering", SIGGRAPH course notes §4.7.2
///   (sphere-light illuminance with horizon handling):
///   with `x = cot σ`, `y = −x c / s`,
///   `Ω⊥ = (c·acos y − x s √(1−y²)) sin²σ + atan(s √(1−y²) / x)`.
///
/// Numerically, with `t = s √(1−y²)` and `u = t tan σ`, the partial case is
/// evaluated as `c sin²σ acos y + sin²σ u + (atan u − u)`, where `atan u − u`
/// uses its Taylor series for `u ≤ 1/2`; this removes the cancellation of
/// two `O(σ)` terms that the literal formula suffers for small caps (where
/// the result is `O(σ³)`), and when `u > 1/2` the equivalent
/// `c sin²σ acos y + atan2(t sin σ, cos σ) − t sin σ cos σ` is used (finite at
/// `σ = π/2`, where it equals `π(1 + cos θa)/2`). The result is continuous
/// across the three cases and tends to `π σ² max(0, cos θa)` as `σ → 0`.
///
/// Accuracy (measured against an f64 quadrature in `tests/illumination.rs`,
/// 136 cases, 77 of them clipped): absolute error ≤ 2.2·10⁻⁷ · π sin²σ;
/// relative error ≤ 6·10⁻⁶ where `Ω⊥ > 10⁻³ π sin²σ`. When only a thin
/// sliver of the cap is visible (`θa − σ` just below π/2) the three terms
/// of the partial-case formula cancel and the *relative* error grows
/// (e.g. 0.8 % for `Ω⊥ = 4·10⁻⁸ π sin²σ`), while the absolute error stays
/// at the `f32` level above.
///
/// Domain: `cos θa` clamped to `[−1, 1]`, `σ` clamped to `[0, π/2]` (a cap
/// larger than a hemisphere is not a cap light here); NaN inputs give 0.
/// Output is in `[0, π]`.
pub fn cap_projected_solid_angle(cos_axis: f32, half_angle: f32) -> f32 {
    let c = clamp_or_zero(cos_axis, -1.0, 1.0);
    let sigma = clamp_or_zero(half_angle, 0.0, FRAC_PI_2);
    let (ss, cs) = libm::sincosf(sigma);
    let ss = ss.clamp(0.0, 1.0);
    // f32 π/2 rounds above π/2, where cos is −4e-8: clamp.
    let cs = cs.clamp(0.0, 1.0);
    let ss2 = ss * ss;
    if c >= ss {
        return PI * ss2 * c;
    }
    if c <= -ss {
        return 0.0;
    }
    // Partly below the horizon: |c| < sin σ ≤ 1, so s > 0 and sin σ > 0.
    let s = safe_sqrt((1.0 - c) * (1.0 + c));
    // y = −cot σ · c / s, computed as a product of two ratios bounded by 1 in
    // magnitude (|c| < sin σ and cos σ ≤ s) so nothing under/overflows.
    let y = (-(c / ss) * (cs / s)).clamp(-1.0, 1.0);
    let q = safe_sqrt((1.0 - y) * (1.0 + y));
    let t = s * q;
    let ts = t * ss;
    let first = c * ss2 * libm::acosf(y);
    let result = if ts <= 0.5 * cs {
        // u = t tan σ ≤ 1/2.
        let u = ts / cs;
        first + ss2 * u + atan_minus_identity(u)
    } else {
        first + libm::atan2f(ts, cs) - ts * cs
    };
    result.clamp(0.0, PI)
}

/// Irradiance from a uniform spherical cap of radiance `L`, half-angle `σ`,
/// axis at angle `θa` from the normal (given as `cos θa`), clipped at the
/// horizon: `E = L · Ω⊥(cos θa, σ)` with `Ω⊥` from
/// [`cap_projected_solid_angle`] (Snyder 1996, MSR-TR-96-11; Lagarde & de
/// Rousiers 2014 §4.7.2).
///
/// For a sphere of radius `r` at distance `d` (centre), `sin σ = r/d`.
/// As `σ → 0` with `π L sin²σ = E⊥` fixed this tends to the directional
/// result `E⊥ max(0, cos θa)`.
///
/// Domain: as [`cap_projected_solid_angle`]; `L` channel-wise.
#[inline]
pub fn cap_irradiance<S: Spectrum>(radiance: S, cos_axis: f32, half_angle: f32) -> S {
    radiance * cap_projected_solid_angle(cos_axis, half_angle)
}

/// The irradiance at normal incidence `E⊥ = π L sin²σ` of a uniform cap of
/// radiance `L` and half-angle `σ` (the fully-visible case of
/// [`cap_projected_solid_angle`] with `θa = 0`). Useful to convert a sun
/// given by its irradiance into a cap radiance and back:
/// `L = E⊥ / (π sin²σ)`.
///
/// Domain: `σ` clamped to `[0, π/2]`, NaN gives 0.
#[inline]
pub fn cap_normal_irradiance<S: Spectrum>(radiance: S, half_angle: f32) -> S {
    let s = libm::sinf(clamp_or_zero(half_angle, 0.0, FRAC_PI_2)).clamp(0.0, 1.0);
    radiance * (PI * s * s)
}

/// `atan(u) − u` for `0 ≤ u ≤ 1/2` without cancellation, from the Taylor
/// series `Σ_{k≥1} (−1)^k u^{2k+1}/(2k+1)` (Abramowitz & Stegun 4.4.42),
/// truncated after the `u^31` term (remainder `< 2⁻³¹ · u³`, i.e. below
/// `f32` rounding relative to the leading term). For `u > 1/2` it falls
/// back to the direct difference.
#[inline]
fn atan_minus_identity(u: f32) -> f32 {
    if u > 0.5 {
        return libm::atanf(u) - u;
    }
    let w = u * u;
    // Horner over k = 15 … 1 of (−1)^k w^(k−1)/(2k+1).
    let mut p = 0.0f32;
    let mut k = 15;
    while k >= 1 {
        let sign = if k % 2 == 0 { 1.0 } else { -1.0 };
        p = p * w + sign / (2 * k + 1) as f32;
        k -= 1;
    }
    u * w * p
}

/// Clamps `x` to `[lo, hi]`, mapping NaN to `0` clamped into the range.
#[inline]
fn clamp_or_zero(x: f32, lo: f32, hi: f32) -> f32 {
    if x.is_nan() {
        0.0f32.clamp(lo, hi)
    } else {
        x.clamp(lo, hi)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn atan_series_matches_f64() {
        for i in 0..=100 {
            let u = i as f32 * 0.005;
            let exact = libm::atan(u as f64) - u as f64;
            let got = atan_minus_identity(u) as f64;
            let tol = 2e-7 * exact.abs() + 1e-30;
            assert!((got - exact).abs() <= tol, "u={u} got={got} exact={exact}");
        }
    }

    #[test]
    fn cases_are_continuous() {
        let sigma = 0.2f32;
        let s = libm::sinf(sigma);
        let above = cap_projected_solid_angle(s, sigma);
        let just = cap_projected_solid_angle(s * (1.0 - 1e-6), sigma);
        assert!((above - just).abs() < 1e-5 * above, "{above} {just}");
        let below = cap_projected_solid_angle(-s * (1.0 - 1e-6), sigma);
        assert!(below.abs() < 1e-9, "{below}");
    }

    #[test]
    fn total_on_edges() {
        for &c in &[-1.0f32, -0.5, -1e-7, 0.0, 1e-7, 0.5, 1.0, 2.0, -3.0, f32::NAN] {
            for &sigma in &[0.0f32, 1e-30, 1e-7, 1e-3, 0.5, FRAC_PI_2, 2.0, -1.0, f32::NAN] {
                let v = cap_projected_solid_angle(c, sigma);
                assert!(v.is_finite() && (0.0..=PI).contains(&v), "c={c} s={sigma} v={v}");
            }
        }
        // Hemisphere tilted by θa: π(1 + cos θa)/2.
        for &c in &[-0.9f32, -0.3, 0.0, 0.4, 0.99] {
            let v = cap_projected_solid_angle(c, FRAC_PI_2);
            assert!((v - PI * (1.0 + c) / 2.0).abs() < 2e-6, "c={c} v={v}");
        }
    }
}
