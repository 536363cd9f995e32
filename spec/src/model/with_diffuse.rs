//! The additive diffuse + specular BRDF of a microfacet spec with `kd > 0`.

use radiometry::glam::Vec3;
use radiometry::{Brdf, BrdfSample, Spectrum};
use radiometry_brdfs::Lambertian;

/// `f_r(ωi, ωo) = kd/π + f_s(ωi, ωo)`: a Lambertian lobe of albedo `kd` added
/// to a specular BRDF `f_s` (the form of `phong`'s `kd`, Lafortune & Willems
/// 1994; no layering, so the albedo is the sum of the two albedos).
///
/// Sampling is the one-sample mixture of the two strategies (Veach 1997,
/// § 9.2.2): the cosine lobe with probability `pd = kd/(kd + 1)` (1 bounds the
/// specular albedo), `f_s`'s own sampling otherwise; the density is the exact
/// mixture `pd cos θi/π + (1 − pd) p_s(ωi)` and the weight `f_r cos θi / pdf`.
///
/// ```
/// use radiometry::Brdf;
/// use radiometry::glam::Vec3;
/// use radiometry_spec::model::build_brdf;
/// use radiometry_spec::parse_brdf;
/// let text = "ggx(alpha=0.3, kd=0.5)";
/// let sum = build_brdf(text, &parse_brdf(text)?)?;
/// let spec = build_brdf("ggx(alpha=0.3)", &parse_brdf("ggx(alpha=0.3)")?)?;
/// let (wi, wo) = (Vec3::new(0.6, 0.0, 0.8), Vec3::new(0.0, 0.6, 0.8));
/// let want = 0.5 / std::f32::consts::PI + spec.eval(wi, wo);
/// assert!((sum.eval(wi, wo) - want).abs() <= 1e-6 * want);
/// # Ok::<(), radiometry_spec::SpecError>(())
/// ```
pub(crate) struct WithDiffuse<B, S: Spectrum = f32> {
    diffuse: Lambertian<S>,
    specular: B,
    /// Probability `kd/(kd + 1)` of sampling the cosine lobe.
    p_diffuse: f32,
}

impl<S: Spectrum, B: Brdf<Spectrum = S>> WithDiffuse<B, S> {
    /// The sum of `diffuse` (albedo `kd` on every channel) and `specular`.
    pub(crate) fn new(diffuse: Lambertian<S>, kd: f32, specular: B) -> Self {
        WithDiffuse {
            diffuse,
            specular,
            p_diffuse: kd / (kd + 1.0),
        }
    }

    /// The mixture density `pd p_d + (1 − pd) p_s`.
    fn mixture_pdf(&self, wi: Vec3, wo: Vec3) -> f32 {
        let pd = self.p_diffuse;
        pd * self.diffuse.pdf(wi, wo) + (1.0 - pd) * self.specular.pdf(wi, wo)
    }
}

impl<S: Spectrum, B: Brdf<Spectrum = S>> Brdf for WithDiffuse<B, S> {
    type Spectrum = S;

    /// `kd/π + f_s(ωi, ωo)`.
    #[inline]
    fn eval(&self, wi: Vec3, wo: Vec3) -> S {
        self.diffuse.eval(wi, wo) + self.specular.eval(wi, wo)
    }

    /// As smooth as the specular lobe (the diffuse term is constant).
    fn is_smooth(&self) -> bool {
        self.specular.is_smooth()
    }

    /// Picks a strategy with `u[0]` (rescaled to `[0, 1)` for the chosen one),
    /// then returns the mixture density and `f_r cos θi / pdf`.
    fn sample(&self, wo: Vec3, u: [f32; 2]) -> Option<BrdfSample<S>> {
        let pd = self.p_diffuse;
        let wi = if u[0] < pd {
            let u0 = (u[0] / pd).min(1.0 - f32::EPSILON / 2.0);
            self.diffuse.sample(wo, [u0, u[1]])?.wi
        } else {
            let u0 = ((u[0] - pd) / (1.0 - pd)).clamp(0.0, 1.0 - f32::EPSILON / 2.0);
            self.specular.sample(wo, [u0, u[1]])?.wi
        };
        let pdf = self.mixture_pdf(wi, wo);
        if !(pdf > 0.0 && pdf.is_finite()) || wi.z <= 0.0 {
            return None;
        }
        let weight = self.eval(wi, wo) * wi.z / pdf;
        weight.is_finite().then_some(BrdfSample { wi, pdf, weight })
    }

    /// `pd cos θi/π + (1 − pd) p_s(ωi)`.
    #[inline]
    fn pdf(&self, wi: Vec3, wo: Vec3) -> f32 {
        self.mixture_pdf(wi, wo)
    }

    /// The cosine lobe (component 0, weight `pd`), then the specular
    /// lobe's components (weights `(1 − pd) c_k`): the mixture `pdf` is.
    fn sampling_components(&self) -> usize {
        1 + self.specular.sampling_components()
    }

    fn component_weight(&self, wo: Vec3, k: usize) -> f32 {
        let pd = self.p_diffuse;
        match k {
            0 => pd,
            _ => (1.0 - pd) * self.specular.component_weight(wo, k - 1),
        }
    }

    fn sample_component(&self, wo: Vec3, k: usize, u: [f32; 2]) -> Option<Vec3> {
        match k {
            0 => self.diffuse.sample(wo, u).map(|s| s.wi),
            _ => self.specular.sample_component(wo, k - 1, u),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use radiometry_brdfs::{Ggx, HeightCorrelated, Microfacet, Schlick};

    fn sum() -> WithDiffuse<Microfacet<Ggx, HeightCorrelated, Schlick>> {
        WithDiffuse::new(
            Lambertian::new(0.3).unwrap(),
            0.3,
            Microfacet::new(Ggx::new(0.2).unwrap(), Schlick::new(0.5).unwrap()),
        )
    }

    fn dir(theta: f32, phi: f32) -> Vec3 {
        Vec3::new(theta.sin() * phi.cos(), theta.sin() * phi.sin(), theta.cos())
    }

    /// Every sample's pdf and weight are what `pdf` and `eval` give for its
    /// direction (the mixture is exact, not approximate).
    #[test]
    fn samples_agree_with_pdf_and_eval() {
        let b = sum();
        let mut n = 0;
        for &to in &[0.0f32, 0.7, 1.4, 1.569] {
            let wo = dir(to, 0.3);
            for i in 0..64 {
                for j in 0..16 {
                    let u = [(i as f32 + 0.5) / 64.0, (j as f32 + 0.5) / 16.0];
                    let Some(s) = b.sample(wo, u) else { continue };
                    n += 1;
                    let pdf = b.pdf(s.wi, wo);
                    assert!((s.pdf - pdf).abs() <= 1e-5 * pdf, "{} vs {pdf}", s.pdf);
                    let w = b.eval(s.wi, wo) * s.wi.z / pdf;
                    assert!((s.weight - w).abs() <= 1e-4 * w.max(1e-3), "{} vs {w}", s.weight);
                }
            }
        }
        assert!(n > 3000, "{n}");
    }

    /// `∫ pdf dω` over the upper hemisphere (midpoint rule in (cos θ, φ),
    /// which is dω).
    fn mass(pdf: impl Fn(Vec3) -> f32) -> f64 {
        let (nm, np) = (2000, 400);
        let mut acc = 0.0f64;
        for i in 0..nm {
            let mu = (i as f64 + 0.5) / nm as f64;
            let st = (1.0 - mu * mu).sqrt();
            for j in 0..np {
                let phi = (j as f64 + 0.5) / np as f64 * std::f64::consts::TAU;
                let wi = Vec3::new((st * phi.cos()) as f32, (st * phi.sin()) as f32, mu as f32);
                acc += pdf(wi) as f64;
            }
        }
        acc * std::f64::consts::TAU / (nm * np) as f64
    }

    /// The mixture density is the mixture of the two densities: its mass is
    /// `pd · 1 + (1 − pd) · m_s`, where `m_s < 1` is the specular strategy's
    /// mass above the horizon (visible-normal samples that reflect below the
    /// horizon are rejected, ≈ 4 % here).
    #[test]
    fn pdf_is_the_exact_mixture() {
        let b = sum();
        let wo = dir(0.5, 0.0);
        let pd = 0.3 / 1.3;
        let m_d = mass(|wi| b.diffuse.pdf(wi, wo));
        let m_s = mass(|wi| b.specular.pdf(wi, wo));
        let m = mass(|wi| b.pdf(wi, wo));
        assert!((m_d - 1.0).abs() < 1e-5, "{m_d}");
        assert!(m_s > 0.9 && m_s < 1.0, "{m_s}");
        assert!(
            (m - (pd * m_d + (1.0 - pd) * m_s)).abs() < 1e-5,
            "{m} {m_d} {m_s}"
        );
    }
}
