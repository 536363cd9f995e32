//! [`Precomputed`]: a lobe whose directional albedo is read once into a
//! table, for lobe picking that costs a table read.

use crate::batch::Vec3Soa;
use crate::brdf::{Albedo, Brdf, BrdfSample, IsotropicBrdf};
use crate::frame::cos_theta;
use crate::spectrum::Spectrum;
use glam::Vec3;

/// Nodes of the table: `μ_k = (k/63)²`, `k = 0..64` (`μ_0` raised to
/// `10⁻⁶`), dense near the horizon.
const NODES: usize = 64;

/// An isotropic lobe with its [directional albedo](Brdf::directional_albedo)
/// tabulated at construction:
///
/// ```text
/// E(μ) ≈ E_k + (x − k)(E_{k+1} − E_k),   x = 63 √μ ∈ [k, k + 1],   E_k = E(μ_k)
/// ```
///
/// `eval`, `sample`, `pdf` and the batches are the lobe's own, bit for bit;
/// only [`directional_albedo`](Brdf::directional_albedo) changes — from
/// whatever the lobe computes to two table reads. Composites query the
/// albedo of every lobe at every `sample` and `pdf` call to pick lobes
/// (`radiometry::compose`), several times over when they nest, so a lobe
/// whose albedo is costly (a microfacet lobe with a Fresnel term averages
/// its Fresnel factor over 20 visible normals each time) is worth wrapping
/// where it sits deep in a material.
///
/// The stated error is the largest error the lobe stated at the nodes plus
/// the largest step between neighbouring nodes (a crude bound on the
/// interpolation error where the albedo is monotone between nodes; not a
/// bound in general, so `is_bound` is false).
///
/// ```
/// use radiometry::compose::Precomputed;
/// use radiometry::{Albedo, Brdf, IsotropicBrdf, glam::Vec3};
/// # #[derive(Clone, Copy)]
/// # struct Flat(f32);
/// # impl Brdf for Flat {
/// #     type Spectrum = f32;
/// #     fn eval(&self, wi: Vec3, wo: Vec3) -> f32 {
/// #         if wi.z > 0.0 && wo.z > 0.0 { self.0 * core::f32::consts::FRAC_1_PI } else { 0.0 }
/// #     }
/// #     fn directional_albedo(&self, wo: Vec3) -> Albedo<f32> {
/// #         if wo.z > 0.0 { Albedo::bounded(self.0, 0.0) } else { Albedo::zero() }
/// #     }
/// # }
/// # impl IsotropicBrdf for Flat {}
/// let lobe = Precomputed::new(Flat(0.4));
/// let wo = Vec3::new(0.6, 0.0, 0.8);
/// assert_eq!(lobe.directional_albedo(wo).value, 0.4);
/// assert_eq!(lobe.eval(Vec3::Z, wo), Flat(0.4).eval(Vec3::Z, wo));
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Precomputed<B: Brdf> {
    lobe: B,
    table: [B::Spectrum; NODES],
    error: f32,
}

impl<B: IsotropicBrdf> Precomputed<B> {
    /// Reads `lobe`'s albedo at the 64 nodes (the lobe must be isotropic:
    /// its albedo a function of `μo` alone).
    pub fn new(lobe: B) -> Self {
        let mut table = [B::Spectrum::zero(); NODES];
        let mut stated = 0.0f32;
        for (k, e) in table.iter_mut().enumerate() {
            let x = k as f32 / (NODES - 1) as f32;
            let mu = (x * x).max(1e-6);
            let s = crate::math::sqrtf((1.0 - mu * mu).max(0.0));
            let a = lobe.directional_albedo(Vec3::new(s, 0.0, mu));
            *e = a.value.map(|v| if v.is_finite() { v.max(0.0) } else { 0.0 });
            if a.error.is_finite() {
                stated = stated.max(a.error);
            }
        }
        let mut step = 0.0f32;
        for (a, b) in table.iter().zip(table.iter().skip(1)) {
            step = step.max((*b - *a).map(f32::abs).max_channel());
        }
        Self {
            lobe,
            table,
            error: stated + step,
        }
    }
}

impl<B: Brdf> Precomputed<B> {
    /// The lobe.
    pub fn lobe(&self) -> &B {
        &self.lobe
    }
}

impl<B: Brdf> Brdf for Precomputed<B> {
    type Spectrum = B::Spectrum;

    #[inline]
    fn eval(&self, wi: Vec3, wo: Vec3) -> B::Spectrum {
        self.lobe.eval(wi, wo)
    }
    #[inline]
    fn sample(&self, wo: Vec3, u: [f32; 2]) -> Option<BrdfSample<B::Spectrum>> {
        self.lobe.sample(wo, u)
    }
    #[inline]
    fn pdf(&self, wi: Vec3, wo: Vec3) -> f32 {
        self.lobe.pdf(wi, wo)
    }
    fn eval_batch(&self, wi: &[Vec3], wo: &[Vec3], out: &mut [B::Spectrum]) {
        self.lobe.eval_batch(wi, wo, out)
    }
    fn eval_batch_soa(&self, wi: Vec3Soa<'_>, wo: Vec3Soa<'_>, out: &mut [B::Spectrum]) {
        self.lobe.eval_batch_soa(wi, wo, out)
    }
    fn pdf_batch(&self, wi: &[Vec3], wo: &[Vec3], out: &mut [f32]) {
        self.lobe.pdf_batch(wi, wo, out)
    }
    fn sample_batch(&self, wo: &[Vec3], u: &[[f32; 2]], out: &mut [Option<BrdfSample<B::Spectrum>>]) {
        self.lobe.sample_batch(wo, u, out)
    }
    fn sampling_components(&self) -> usize {
        self.lobe.sampling_components()
    }
    fn component_weight(&self, wo: Vec3, k: usize) -> f32 {
        self.lobe.component_weight(wo, k)
    }
    fn sample_component(&self, wo: Vec3, k: usize, u: [f32; 2]) -> Option<Vec3> {
        self.lobe.sample_component(wo, k, u)
    }
    fn is_smooth(&self) -> bool {
        self.lobe.is_smooth()
    }

    /// The tabulated albedo, linear in `√μo` between the nodes.
    fn directional_albedo(&self, wo: Vec3) -> Albedo<B::Spectrum> {
        let mu = cos_theta(wo);
        if mu.is_nan() || mu <= 0.0 {
            return Albedo::zero();
        }
        let x = crate::math::sqrtf(mu.min(1.0)) * (NODES - 1) as f32;
        let i = (x as usize).min(NODES - 2);
        let f = (x - i as f32).clamp(0.0, 1.0);
        match (self.table.get(i), self.table.get(i + 1)) {
            (Some(&a), Some(&b)) => Albedo {
                value: a + (b - a) * f,
                error: self.error,
                is_bound: false,
            },
            _ => Albedo::zero(),
        }
    }
}

impl<B: IsotropicBrdf> IsotropicBrdf for Precomputed<B> {}
