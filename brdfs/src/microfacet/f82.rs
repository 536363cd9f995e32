//! The F82-tint metal Fresnel term of OpenPBR Surface.

use super::fresnel::{Fresnel, clamp_cos};
use crate::error::{BrdfError, check_range};
use radiometry::Spectrum;

/// `μ̄ = cos 82° ≈ 1/7`, where the F82-tint term is pinned
/// (Hoffman 2019 takes `μ̄ = 1/7` exactly: the maximum of `μ (1 − μ)⁶`).
pub const MU_BAR: f32 = 1.0 / 7.0;

/// `μ̄ (1 − μ̄)⁶ = 6⁶/7⁷`, the largest value of `μ (1 − μ)⁶` on `[0, 1]`.
const G_BAR: f32 = 46_656.0 / 823_543.0;

/// `(1 − μ̄)⁵ = (6/7)⁵`, Schlick's weight at `μ̄`.
pub(crate) const W_BAR: f32 = 7_776.0 / 16_807.0;

/// The F82-tint Fresnel term for metals (Hoffman 2019, "Fresnel Equations
/// Considered Harmful", EGSR Industry Track, eq. 9–10, in the tinted form of
/// Hoffman 2023 that OpenPBR Surface 1.1 §"Metal" specifies):
///
/// ```text
/// F_S(μ) = f0 + (1 − f0)(1 − μ)⁵                      (Schlick)
/// F(μ)   = F_S(μ) − a μ (1 − μ)⁶,   a = F_S(μ̄)(1 − t) / (μ̄ (1 − μ̄)⁶),   μ̄ = 1/7
/// ```
///
/// per channel, with `f0` the reflectance at normal incidence (OpenPBR's
/// `base_color`) and `t` the F82 tint (`specular_color`): the reflectance at
/// `μ̄` (82°) is `F(μ̄) = t · F_S(μ̄)`, and `F(1) = f0`, `F(0) = 1`. With
/// `t = 1` it is Schlick's approximation. Domain: every channel of `f0` and
/// `t` in `[0, 1]`.
///
/// `F ≤ F_S ≤ 1` always; for a dark `f0` with a small tint the polynomial
/// dips below 0 between the two pins (e.g. `f0 = t = 0` at `μ = ½`), and `F`
/// is clamped to `[0, 1]` there (a documented clamp: OpenPBR meant metals,
/// whose `f0` keeps it positive). [`is_smooth`](Fresnel::is_smooth) is
/// `true` when no channel can reach the clamp (`f0 ≥ (1 − t) F_S(μ̄)`, which
/// gives `F ≥ f0 − (1 − t)F_S(μ̄) ≥ 0` since `μ(1 − μ)⁶ ≤ μ̄(1 − μ̄)⁶`).
///
/// ```
/// use radiometry::glam::Vec3;
/// use radiometry_brdfs::microfacet::{F82Tint, Fresnel, Schlick};
/// let gold = F82Tint::new(Vec3::new(0.944, 0.776, 0.373), Vec3::new(0.962, 0.919, 0.772)).unwrap();
/// assert!((gold.eval(1.0) - Vec3::new(0.944, 0.776, 0.373)).abs().max_element() < 1e-6);
/// // A white tint is Schlick's approximation.
/// let plain = F82Tint::new(0.5f32, 1.0).unwrap();
/// assert!((plain.eval(0.3) - Schlick::new(0.5f32).unwrap().eval(0.3)).abs() < 1e-6);
/// assert!(F82Tint::new(0.5f32, 1.5).is_err());
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct F82Tint<S = f32> {
    f0: S,
    tint: S,
    /// `a = F_S(μ̄)(1 − t)/(μ̄(1 − μ̄)⁶)` per channel.
    a: S,
    /// Whether no channel reaches the clamp at 0 (see the type's docs).
    smooth: bool,
}

impl<S: Spectrum> F82Tint<S> {
    /// Validates `f0 ∈ [0, 1]` (parameter `f0`) and the tint `t ∈ [0, 1]`
    /// (parameter `f82`) per channel.
    pub fn new(f0: S, f82_tint: S) -> Result<Self, BrdfError> {
        for i in 0..S::CHANNELS {
            check_range("f0", f0.channel(i), 0.0, 1.0)?;
            check_range("f82", f82_tint.channel(i), 0.0, 1.0)?;
        }
        Ok(Self::from_valid(f0, f82_tint))
    }

    /// [`new`](Self::new) without the checks, for parameters known to be
    /// in `[0, 1]`.
    pub(crate) fn from_valid(f0: S, f82_tint: S) -> Self {
        let fs_bar = S::from_fn(|i| {
            let f = f0.channel(i);
            f + (1.0 - f) * W_BAR
        });
        let a = S::from_fn(|i| fs_bar.channel(i) * (1.0 - f82_tint.channel(i)) / G_BAR);
        let smooth =
            (0..S::CHANNELS).all(|i| f0.channel(i) >= (1.0 - f82_tint.channel(i)) * fs_bar.channel(i));
        F82Tint {
            f0,
            tint: f82_tint,
            a,
            smooth,
        }
    }

    /// The normal-incidence reflectance `f0`.
    pub fn f0(&self) -> S {
        self.f0
    }

    /// The F82 tint `t` (`F(μ̄) = t F_S(μ̄)`).
    pub fn f82_tint(&self) -> S {
        self.tint
    }
}

impl<S: Spectrum> Fresnel for F82Tint<S> {
    type Spectrum = S;

    /// Linear in the moments where no channel reaches the clamp at 0.
    fn form(&self) -> super::FresnelForm<S> {
        if self.smooth {
            super::FresnelForm::Linear {
                f0: self.f0,
                a: self.a,
            }
        } else {
            super::FresnelForm::Other
        }
    }

    /// `true` when no channel can reach the clamp at 0 (a kink).
    fn is_smooth(&self) -> bool {
        self.smooth
    }

    /// `F_S(μ) − a μ (1 − μ)⁶` per channel, clamped to `[0, 1]`;
    /// `cos θd` clamped to `[0, 1]` (NaN → 0, where `F = 1`).
    #[inline]
    fn eval(&self, cos_theta_d: f32) -> S {
        let c = clamp_cos(cos_theta_d);
        let m = 1.0 - c;
        let m2 = m * m;
        let m5 = m2 * m2 * m;
        let g = c * m5 * m;
        S::from_fn(|i| {
            let f0 = self.f0.channel(i);
            (f0 + (1.0 - f0) * m5 - self.a.channel(i) * g).clamp(0.0, 1.0)
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use radiometry::glam::Vec3;

    /// Independent `f64` form of OpenPBR's F82-tint (Hoffman 2023 eq. for
    /// the tinted variant), straight from the formula.
    fn reference(f0: f64, t: f64, mu: f64) -> f64 {
        let mu = mu.clamp(0.0, 1.0);
        let schlick = |m: f64| f0 + (1.0 - f0) * (1.0 - m).powi(5);
        let mb = 1.0 / 7.0;
        let a = schlick(mb) * (1.0 - t) / (mb * (1.0 - mb).powi(6));
        (schlick(mu) - a * mu * (1.0 - mu).powi(6)).clamp(0.0, 1.0)
    }

    #[test]
    fn matches_the_f64_formula() {
        let mut worst = 0.0f64;
        for &f0 in &[0.0, 0.02, 0.3, 0.56, 0.9, 1.0] {
            for &t in &[0.0, 0.25, 0.7, 1.0] {
                let f = F82Tint::new(f0 as f32, t as f32).unwrap();
                for j in 0..=200 {
                    let mu = j as f64 / 200.0;
                    let d = (f64::from(f.eval(mu as f32)) - reference(f0, t, mu)).abs();
                    worst = worst.max(d);
                }
            }
        }
        assert!(worst < 2e-6, "{worst}");
    }

    #[test]
    fn pins_at_normal_incidence_and_82_degrees() {
        for &f0 in &[0.05f32, 0.5, 0.95] {
            for &t in &[0.0f32, 0.6, 1.0] {
                let f = F82Tint::new(f0, t).unwrap();
                assert_eq!(f.eval(1.0), f0);
                assert_eq!(f.eval(0.0), 1.0);
                let fs = f64::from(f0) + (1.0 - f64::from(f0)) * (6.0f64 / 7.0).powi(5);
                let want = (f64::from(t) * fs).max(0.0);
                assert!((f64::from(f.eval(MU_BAR)) - want).abs() < 2e-6, "{f0} {t}");
            }
        }
    }

    #[test]
    fn stays_in_unit_interval_and_finite() {
        let f = F82Tint::new(Vec3::new(0.0, 0.4, 1.0), Vec3::new(0.0, 0.5, 1.0)).unwrap();
        for &c in &[
            f32::NAN,
            f32::INFINITY,
            f32::NEG_INFINITY,
            -1.0,
            -0.3,
            0.0,
            1e-30,
            0.5,
            1.0,
            2.0,
        ] {
            let v = f.eval(c);
            assert!(
                v.is_finite() && v.min_element() >= 0.0 && v.max_element() <= 1.0,
                "{c}: {v}"
            );
        }
        for j in 0..=1000 {
            let v = f.eval(j as f32 / 1000.0);
            assert!(v.min_element() >= 0.0 && v.max_element() <= 1.0);
        }
        // f0 = t = 0 dips below zero unclamped: the clamp is what keeps F ≥ 0.
        assert!(reference(0.0, 0.0, 0.5) == 0.0 && !f.is_smooth());
        assert!(F82Tint::new(0.9f32, 0.8).unwrap().is_smooth());
    }

    #[test]
    fn rejects_invalid_parameters() {
        assert_eq!(
            F82Tint::new(f32::NAN, 0.5),
            Err(BrdfError::NotFinite { name: "f0" })
        );
        assert!(matches!(
            F82Tint::new(0.5f32, -0.1),
            Err(BrdfError::OutOfRange { name: "f82", .. })
        ));
        assert!(F82Tint::new(Vec3::new(0.5, 1.1, 0.5), Vec3::ONE).is_err());
    }

    #[test]
    fn bounds_enclose_every_value() {
        for &(f0, t) in &[(0.9f32, 0.3f32), (0.2, 0.0), (0.05, 1.0), (0.0, 0.0)] {
            let f = F82Tint::new(f0, t).unwrap();
            let (lo, hi) = f.bounds();
            let mut true_lo = 1.0f64;
            for j in 0..=20_000 {
                let v = reference(f64::from(f0), f64::from(t), j as f64 / 20_000.0);
                true_lo = true_lo.min(v);
                assert!(f64::from(lo) <= v + 1e-6 && v <= f64::from(hi) + 1e-6);
            }
            assert!(f64::from(lo) - true_lo < 1e-5, "{f0} {t}: {lo} vs {true_lo}");
        }
    }
}
