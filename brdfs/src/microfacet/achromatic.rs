//! [`Achromatic`]: a monochrome Fresnel term inside a spectral or RGB BRDF.

use super::fresnel::Fresnel;
use core::marker::PhantomData;
use radiometry::Spectrum;

/// A monochrome Fresnel term `F` applied equally to every channel of the
/// spectrum `S`:
///
/// ```text
/// F_S(cos θd) = (F(cos θd), F(cos θd), …)
/// ```
///
/// For interfaces whose reflectance does not depend on wavelength in the
/// model — the exact [`Dielectric`](super::Dielectric) of a clear coat or of
/// a plastic's specular layer — inside a material whose other lobes are RGB
/// or spectral (composites need one spectrum type). Same domain, smoothness
/// and bounds as `F`.
///
/// ```
/// use radiometry::glam::Vec3;
/// use radiometry_brdfs::microfacet::{Achromatic, Dielectric, Fresnel};
/// let glass = Dielectric::new(1.5).unwrap();
/// let rgb: Achromatic<_, Vec3> = Achromatic::new(glass);
/// assert_eq!(rgb.eval(0.6), Vec3::splat(glass.eval(0.6)));
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Achromatic<F, S> {
    fresnel: F,
    spectrum: PhantomData<S>,
}

impl<F, S> Achromatic<F, S> {
    /// `F` on every channel of `S`.
    pub const fn new(fresnel: F) -> Self {
        Self {
            fresnel,
            spectrum: PhantomData,
        }
    }

    /// The monochrome term.
    pub fn inner(&self) -> &F {
        &self.fresnel
    }
}

impl<F: Fresnel<Spectrum = f32>, S: Spectrum> Fresnel for Achromatic<F, S> {
    type Spectrum = S;

    #[inline]
    fn eval(&self, cos_theta_d: f32) -> S {
        S::splat(self.fresnel.eval(cos_theta_d))
    }

    fn is_smooth(&self) -> bool {
        self.fresnel.is_smooth()
    }

    fn bounds(&self) -> (S, S) {
        let (lo, hi) = self.fresnel.bounds();
        (S::splat(lo), S::splat(hi))
    }

    fn with_albedo_cells(self, alpha: f32) -> Self {
        Self {
            fresnel: self.fresnel.with_albedo_cells(alpha),
            ..self
        }
    }

    #[inline(always)]
    fn albedo_cells(&self, alpha: f32) -> Option<&super::prepared::DielectricCells> {
        self.fresnel.albedo_cells(alpha)
    }

    /// The inner term's vector lanes, each value put on every channel:
    /// `S::splat(F(c)) · s = S::splat(F(c) · s)` channel by channel, so bit
    /// for bit what the scalar path computes per lane (and exactly 0 where
    /// `s = 0`, as the inner term's lanes are).
    #[cfg(feature = "simd")]
    #[inline]
    fn eval_scaled_lanes(
        &self,
        cos_theta_d: crate::simd::Vf,
        scale: crate::simd::Vf,
        out: &mut [S; crate::simd::LANES],
    ) {
        let mut mono = [0.0f32; crate::simd::LANES];
        self.fresnel.eval_scaled_lanes(cos_theta_d, scale, &mut mono);
        for (o, &m) in out.iter_mut().zip(&mono) {
            *o = S::splat(m);
        }
    }

    fn form(&self) -> super::FresnelForm<S> {
        match self.fresnel.form() {
            super::FresnelForm::One => super::FresnelForm::One,
            super::FresnelForm::Dielectric(eta) => super::FresnelForm::Dielectric(eta),
            super::FresnelForm::Linear { f0, a } => super::FresnelForm::Linear {
                f0: S::splat(f0),
                a: S::splat(a),
            },
            super::FresnelForm::Other => super::FresnelForm::Other,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::microfacet::{Conductor, Dielectric};
    use radiometry::glam::Vec3;

    #[test]
    fn every_channel_is_the_monochrome_value() {
        let d = Dielectric::new(1.0 / 1.5).unwrap();
        let a: Achromatic<_, Vec3> = Achromatic::new(d);
        for k in 0..=64 {
            let c = k as f32 / 64.0;
            assert_eq!(a.eval(c), Vec3::splat(d.eval(c)));
        }
        assert_eq!(a.is_smooth(), d.is_smooth());
        let (lo, hi) = d.bounds();
        assert_eq!(a.bounds(), (Vec3::splat(lo), Vec3::splat(hi)));
        let c = Conductor::new(0.2, 3.0).unwrap();
        assert!(Achromatic::<_, Vec3>::new(c).is_smooth());
    }
}
