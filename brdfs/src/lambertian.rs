//! The Lambertian (ideal diffuse) BRDF.
//!
//! # Formula
//!
//! ```text
//! f_r(ωi, ωo) = ρ/π      for cos θi > 0 and cos θo > 0,
//!             = 0        otherwise,
//! ```
//!
//! with albedo `ρ`. The directional albedo `∫_H f_r cos θi dωi = ρ` for
//! every `ωo`, because `∫_H cos θ dω = π`. Source: J. H. Lambert,
//! *Photometria* (1760); in BRDF form e.g. Nicodemus et al. 1977 (NBS
//! Monograph 160) and Pharr, Jakob & Humphreys, *Physically Based
//! Rendering* 4th ed., §9.2.
//!
//! # Parameters and domain
//!
//! * `albedo` ρ: a spectrum with every channel in `[0, 1]`.
//! * Directions: any finite vectors (only the sign of `cos θ` matters for
//!   `eval`; `pdf` normalises `ωi`).
//!
//! # Sampling
//!
//! Cosine-weighted hemisphere sampling (Malley's method,
//! [`square_to_cosine_hemisphere`]), density `cos θi/π`, which is exactly
//! proportional to `f_r cos θi`: every sample has weight `ρ`. Samples on
//! the horizon (`cos θi = 0`, only at the edge `u` of the square) are
//! rejected.
//!
//! # Example
//!
//! ```
//! use radiometry::{Brdf, glam::Vec3};
//! use radiometry_brdfs::Lambertian;
//!
//! let white = Lambertian::new(0.8f32)?;
//! assert!((white.eval(Vec3::Z, Vec3::new(0.6, 0.0, 0.8)) - 0.8 / core::f32::consts::PI).abs() < 1e-7);
//! let s = white.sample(Vec3::Z, [0.25, 0.5]).unwrap();
//! assert!((s.weight - 0.8).abs() < 1e-6);
//! assert!(Lambertian::new(1.5f32).is_err());
//! # Ok::<(), radiometry_brdfs::BrdfError>(())
//! ```

use crate::error::{BrdfError, check_range};
use core::f32::consts::FRAC_1_PI;
#[cfg(feature = "simd")]
use radiometry::batch::Vec3Soa;
use radiometry::frame::try_normalize;
use radiometry::glam::Vec3;
use radiometry::warp::square_to_cosine_hemisphere;
use radiometry::{Albedo, Brdf, BrdfSample, IsotropicBrdf, Spectrum};

/// The Lambertian BRDF `f_r = ρ/π`; see the [module documentation](self).
///
/// ```
/// use radiometry::{Brdf, glam::Vec3};
/// use radiometry_brdfs::Lambertian;
///
/// let rgb = Lambertian::new(Vec3::new(0.9, 0.5, 0.1))?;
/// assert_eq!(rgb.albedo(), Vec3::new(0.9, 0.5, 0.1));
/// assert_eq!(rgb.eval(Vec3::Z, -Vec3::Z), Vec3::ZERO);
/// # Ok::<(), radiometry_brdfs::BrdfError>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Lambertian<S: Spectrum = f32> {
    albedo: S,
}

impl<S: Spectrum> Lambertian<S> {
    /// Builds the BRDF.
    ///
    /// # Errors
    /// [`BrdfError::NotFinite`] for a NaN/infinite channel,
    /// [`BrdfError::OutOfRange`] for a channel outside `[0, 1]`.
    pub fn new(albedo: S) -> Result<Self, BrdfError> {
        for i in 0..S::CHANNELS {
            check_range("albedo", albedo.channel(i), 0.0, 1.0)?;
        }
        Ok(Self { albedo })
    }

    /// The albedo ρ (equal to the directional albedo for every `ωo`).
    pub fn albedo(&self) -> S {
        self.albedo
    }
}

impl<S: Spectrum> Brdf for Lambertian<S> {
    type Spectrum = S;

    /// Constant on the hemisphere: `f_r cos θi = ρ cos θi / π` is smooth.
    fn is_smooth(&self) -> bool {
        true
    }

    /// `E(ωo) = ∫ (ρ/π) cos θi dωi = ρ` for `ωo` above the horizon (exact;
    /// the stated error `2⁻²³ ρ` covers the rounding of `ρ/π` in `eval`).
    fn directional_albedo(&self, wo: Vec3) -> Albedo<S> {
        if wo.z > 0.0 && wo.is_finite() {
            Albedo::bounded(self.albedo, self.albedo.max_channel() * f32::EPSILON)
        } else {
            Albedo::zero()
        }
    }

    /// `ρ/π` when both `cos θ > 0`, else 0.
    #[inline]
    fn eval(&self, wi: Vec3, wo: Vec3) -> S {
        if wi.z > 0.0 && wo.z > 0.0 && wi.is_finite() && wo.is_finite() {
            self.albedo * FRAC_1_PI
        } else {
            S::zero()
        }
    }

    /// With the `simd` feature a vector kernel ([`crate::simd`]) tests the
    /// horizon/finiteness conditions; results equal [`Brdf::eval`] exactly.
    #[cfg(feature = "simd")]
    #[inline]
    fn eval_batch(&self, wi: &[Vec3], wo: &[Vec3], out: &mut [S]) {
        crate::simd::Batch::Aos(wi, wo, out).run(&batch::Eval(self))
    }

    /// With the `simd` feature the vector kernel of
    /// [`eval_batch`](Brdf::eval_batch) on plain vector loads; results equal
    /// [`Brdf::eval`] exactly.
    #[cfg(feature = "simd")]
    #[inline]
    fn eval_batch_soa(&self, wi: Vec3Soa<'_>, wo: Vec3Soa<'_>, out: &mut [S]) {
        crate::simd::Batch::Soa(wi, wo, out).run(&batch::Eval(self))
    }

    /// With the `simd` feature a vector kernel for `cos θi/π`; results
    /// equal [`Brdf::pdf`] exactly.
    #[cfg(feature = "simd")]
    #[inline]
    fn pdf_batch(&self, wi: &[Vec3], wo: &[Vec3], out: &mut [f32]) {
        crate::simd::Batch::Aos(wi, wo, out).run(&batch::Pdf(self))
    }

    /// With the `simd` feature a vector kernel: the concentric map lifted
    /// to the hemisphere and the pdf of [`Brdf::pdf`], lane for lane
    /// (results, `None`s included, equal [`Brdf::sample`] exactly).
    #[cfg(feature = "simd")]
    #[inline]
    fn sample_batch(&self, wo: &[Vec3], u: &[[f32; 2]], out: &mut [Option<BrdfSample<S>>]) {
        crate::simd::run_samples(&batch::Sample(self), wo, u, out)
    }

    /// Cosine-weighted sampling; `weight = ρ`. `None` when `wo` is at or
    /// below the horizon (or not finite) or `wi` lands on the horizon.
    fn sample(&self, wo: Vec3, u: [f32; 2]) -> Option<BrdfSample<S>> {
        if !wo.is_finite() || wo.z <= 0.0 {
            return None;
        }
        let wi = square_to_cosine_hemisphere(u);
        let pdf = self.pdf(wi, wo);
        (pdf > 0.0).then_some(BrdfSample {
            wi,
            pdf,
            weight: self.albedo,
        })
    }

    /// `cos θi/π` (of the normalised `wi`) when both directions are above
    /// the horizon, else 0.
    #[inline]
    fn pdf(&self, wi: Vec3, wo: Vec3) -> f32 {
        if !wo.is_finite() || wo.z <= 0.0 {
            return 0.0;
        }
        match try_normalize(wi) {
            Some(w) if w.z > 0.0 => w.z * FRAC_1_PI,
            _ => 0.0,
        }
    }
}

impl<S: Spectrum> IsotropicBrdf for Lambertian<S> {}

/// The vector kernels (feature `simd`): the scalar tests of `eval` and
/// `pdf` as lane masks, the same values selected (0 ulp; see
/// [`crate::simd`]).
#[cfg(feature = "simd")]
mod batch {
    use super::Lambertian;
    use crate::simd::Vf;
    use crate::simd::{Dirs, Kernel, LANES, SampleKernel, store};
    use core::f32::consts::FRAC_1_PI;
    use radiometry::glam::Vec3;
    use radiometry::{Brdf, BrdfSample, Spectrum};

    /// `eval`: `ρ/π` where `cos θi > 0`, `cos θo > 0` and both directions
    /// are finite, else 0.
    pub(super) struct Eval<'a, S: Spectrum>(pub(super) &'a Lambertian<S>);

    impl<S: Spectrum> Kernel for Eval<'_, S> {
        type Out = S;

        #[inline(always)]
        fn lanes(&self, wi: Dirs, wo: Dirs, out: &mut [S; LANES]) -> u32 {
            let zero = Vf::ZERO;
            let mask = wi.z.simd_gt(zero) & wo.z.simd_gt(zero) & wi.is_finite() & wo.is_finite();
            let value = self.0.albedo * FRAC_1_PI;
            store(out, |c| mask.select(Vf::splat(value.channel(c)), zero));
            0
        }

        #[inline(always)]
        fn one(&self, wi: Vec3, wo: Vec3) -> S {
            self.0.eval(wi, wo)
        }
    }

    /// `pdf`: `(ωi/‖ωi‖)_z/π` where `ωo` is finite and above the horizon and
    /// the normalised `ωi` is defined and above it, else 0.
    pub(super) struct Pdf<'a, S: Spectrum>(pub(super) &'a Lambertian<S>);

    impl<S: Spectrum> Kernel for Pdf<'_, S> {
        type Out = f32;

        #[inline(always)]
        fn lanes(&self, wi: Dirs, wo: Dirs, out: &mut [f32; LANES]) -> u32 {
            let zero = Vf::ZERO;
            let (w, ok) = wi.try_normalize();
            let mask = wo.is_finite() & wo.z.simd_gt(zero) & ok & w.z.simd_gt(zero);
            *out = mask.select(w.z * Vf::splat(FRAC_1_PI), zero).to_array();
            0
        }

        #[inline(always)]
        fn one(&self, wi: Vec3, wo: Vec3) -> f32 {
            self.0.pdf(wi, wo)
        }
    }

    /// `sample`: `ωi = square_to_cosine_hemisphere(u)` (the Phong family's
    /// vector warp with every lane diffuse: Shirley & Chiu's concentric
    /// map, lifted by `z = √(1 − |d|²)`), its pdf as [`Pdf`] computes it, and
    /// `Some { ωi, pdf, ρ }` where `ωo` is finite and above the horizon and
    /// `pdf > 0`, else `None`.
    pub(super) struct Sample<'a, S: Spectrum>(pub(super) &'a Lambertian<S>);

    impl<S: Spectrum> SampleKernel for Sample<'_, S> {
        type Out = Option<BrdfSample<S>>;

        #[inline(always)]
        fn lanes(&self, wo: Dirs, u0: Vf, u1: Vf, out: &mut [Self::Out; LANES]) -> u32 {
            let zero = Vf::ZERO;
            let all = zero.simd_eq(zero);
            let wi = crate::phong::batch::warp(all, u0, u1, 1.0);
            let (w, ok) = wi.try_normalize();
            let pdf = (wo.is_finite() & wo.z.simd_gt(zero) & ok & w.z.simd_gt(zero))
                .select(w.z * Vf::splat(FRAC_1_PI), zero);
            let some = pdf.simd_gt(zero).to_bitmask();
            let (x, y, z, p) = (wi.x.to_array(), wi.y.to_array(), wi.z.to_array(), pdf.to_array());
            for (k, o) in out.iter_mut().enumerate() {
                *o = (some & (1 << k) != 0).then(|| BrdfSample {
                    wi: Vec3::new(x[k], y[k], z[k]),
                    pdf: p[k],
                    weight: self.0.albedo,
                });
            }
            0
        }

        #[inline(always)]
        fn one(&self, wo: Vec3, u: [f32; 2]) -> Self::Out {
            self.0.sample(wo, u)
        }
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;
    use crate::phong::test_support::*;
    use core::f64::consts::PI as PI64;
    use std::string::ToString;

    #[test]
    fn eval_is_albedo_over_pi_above_horizon_only() {
        let b = Lambertian::new(Vec3::new(0.9, 0.5, 0.0)).unwrap();
        for &(ti, to) in &[
            (0.0f64, 0.0f64),
            (0.3, -1.2),
            (1.5, 1.5),
            (core::f64::consts::FRAC_PI_2 - 1e-7, 0.1),
        ] {
            let f = b.eval(dir_xz(ti), dir_xz(to));
            for (c, rho) in [0.9f64, 0.5, 0.0].into_iter().enumerate() {
                assert!((f.channel(c) as f64 - rho / PI64).abs() < 1e-7, "{ti} {to} {c}");
            }
        }
        for &(wi, wo) in &[
            (Vec3::new(1.0, 0.0, 0.0), Vec3::Z),
            (Vec3::Z, Vec3::new(0.6, 0.0, -0.8)),
            (Vec3::Z, -Vec3::Z),
            (Vec3::ZERO, Vec3::Z),
            (Vec3::new(0.0, 0.0, -1e-30), Vec3::Z),
        ] {
            assert_eq!(b.eval(wi, wo), Vec3::ZERO, "{wi:?} {wo:?}");
            assert_eq!(b.eval(wo, wi), Vec3::ZERO, "{wi:?} {wo:?}");
            assert_eq!(b.pdf(wi, wo), 0.0);
        }
        // Non-unit and grazing-but-above inputs.
        assert_eq!(
            b.eval(Vec3::new(5.0, 0.0, 1e-7), Vec3::Z * 0.01),
            b.albedo() * FRAC_1_PI
        );
    }

    #[test]
    fn constructor_validation_and_messages() {
        let e = Lambertian::new(f32::NAN).unwrap_err();
        assert_eq!(e.to_string(), "parameter `albedo` must be finite");
        let e = Lambertian::new(-0.25f32).unwrap_err();
        assert_eq!(e.to_string(), "parameter `albedo` = -0.25 is outside [0, 1]");
        assert!(matches!(
            Lambertian::new(1.0001f32),
            Err(BrdfError::OutOfRange { .. })
        ));
        assert!(Lambertian::new(Vec3::new(0.5, 0.5, f32::INFINITY)).is_err());
        assert!(Lambertian::new(Vec3::new(0.5, -0.0001, 0.5)).is_err());
        assert!(Lambertian::new(0.0f32).is_ok() && Lambertian::new(1.0f32).is_ok());
    }

    /// Directional albedo = ρ for every ωo, by independent f64 quadrature.
    #[test]
    fn albedo_equals_rho_by_quadrature() {
        let b = Lambertian::new(Vec3::new(0.8, 0.45, 0.1)).unwrap();
        for &t in &[0.0f64, 0.7, 1.4, 1.5706] {
            for (c, rho) in [0.8f64, 0.45, 0.1].into_iter().enumerate() {
                let a = albedo(&b, dir_xz(t), c, 2000, 16);
                assert!((a - rho).abs() < 1e-6, "θo={t} c={c}: {a}");
            }
        }
    }

    /// ∫_H pdf = 1 (cosine sampling never leaves the hemisphere).
    #[test]
    fn pdf_integrates_to_one() {
        let b = Lambertian::new(0.5f32).unwrap();
        for &t in &[0.0f64, 1.0, 1.55] {
            let m = pdf_mass(&b, dir_xz(t), 2000, 16);
            assert!((m - 1.0).abs() < 1e-6, "{m}");
        }
    }

    #[test]
    fn sampling_matches_pdf_and_weight_on_grid() {
        let b = Lambertian::new(Vec3::new(0.3, 0.6, 0.9)).unwrap();
        for &t in &[0.0f64, 0.9, core::f64::consts::FRAC_PI_2 - 1e-7] {
            let wo = dir_xz(t);
            let (some, _, _) = check_sampling(&b, wo);
            // Only the border of the square maps to the horizon (u0 or u1 = 0).
            assert!(some >= 100, "{some}");
            let s = b.sample(wo, [0.4, 0.8]).unwrap();
            assert_eq!(s.weight, b.albedo());
        }
        assert!(b.sample(Vec3::new(0.6, 0.0, -0.8), [0.5, 0.5]).is_none());
        assert!(b.sample(Vec3::new(1.0, 0.0, 0.0), [0.5, 0.5]).is_none());
        let mc = sampled_albedo(&b, dir_xz(0.4), 256);
        assert!((mc - 0.3).abs() < 1e-3, "{mc}");
    }

    /// Any `Spectrum` works: a sampled spectrum behaves channel-wise.
    #[test]
    fn sampled_spectrum_channels() {
        use radiometry::SampledSpectrum;
        let rho = SampledSpectrum([0.1, 0.4, 0.7, 1.0]);
        let b = Lambertian::new(rho).unwrap();
        let s = b.sample(Vec3::Z, [0.2, 0.9]).unwrap();
        assert_eq!(s.weight, rho);
        let f = b.eval(Vec3::Z, Vec3::Z);
        for c in 0..4 {
            assert!((f.0[c] as f64 - rho.0[c] as f64 / PI64).abs() < 1e-7);
        }
        assert!(Lambertian::new(SampledSpectrum([0.1, 0.4, 1.7, 1.0])).is_err());
    }
}
