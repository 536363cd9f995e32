//! The reflection integrand of a [`Cap`] light with the sampling strategies
//! a renderer chooses between: light (cone) sampling, BRDF sampling, and
//! their multiple-importance combination.

use super::Cap;
use crate::brdf::Brdf;
use crate::integrator::chunk::CHUNK;
use crate::integrator::{Integrand, IntegrandSample};
use crate::math::safe_sqrt;
use crate::spectrum::Spectrum;
use core::f32::consts::TAU;
use glam::Vec3;

/// Which sampling map [`CapSampled`] offers.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum CapStrategy {
    /// Uniform over the whole cone of the cap, density `1/(2π(1 − cos σ))`;
    /// draws below the horizon contribute zero (PBR 4th ed. §12.2.2, sampling
    /// a sphere light by its subtended cone).
    Light,
    /// The BRDF's own [`Brdf::sample`]; draws outside the cap contribute
    /// zero.
    Brdf,
    /// One-sample multiple importance sampling with the balance heuristic:
    /// the mixture `½ p_light + ½ p_brdf` (the first coordinate picks the
    /// technique and is re-used; Veach & Guibas 1995, "Optimally combining
    /// sampling techniques for Monte Carlo rendering", §4.1: one-sample
    /// model, whose balance-heuristic estimator is `g / (½p_L + ½p_B)`).
    Mis,
}

/// `g(ω) = f_r(ω, ωo) L 1_cap(ω) cos θ`, the integrand of the reflected
/// radiance `L_r(ωo) = ∫_cap f_r L cos θi dωi` of a [`Cap`] light, with the
/// sampling map chosen by a [`CapStrategy`]. Monte Carlo over its map
/// ([`MonteCarlo`](crate::integrator::MonteCarlo) with
/// [`Strategy::Integrand`](crate::integrator::Strategy::Integrand)) is the
/// classic light / BRDF / MIS comparison; deterministic quadrature of the
/// same integral is [`super::CapIntegrand`] (which maps every node into the
/// visible cap).
///
/// The cap test is [`Cap::contains`] (exact for the sun's 0.27°). Light
/// samples are inside the cap by construction (no test), so the light
/// estimator does not see the `f32` resolution of the cap boundary.
///
/// Caps too small for an `f32` cone density — `1 − cos σ` below
/// `1/(2π · f32::MAX)`, i.e. `σ ≲ 1.9·10⁻¹⁹` rad (a solid angle below
/// `10⁻³⁷` sr) — have no light technique: cone draws return `None` and the
/// light density is 0, so light sampling reports `no-support-seen`
/// (unresolved) instead of an infinite weight, and MIS keeps only its BRDF
/// half. (Such a cap reflects at most `L f_r Ω ≤ 10³⁰ · f_r · 10⁻³⁷`.)
///
/// ```
/// use radiometry::light::{Cap, CapSampled, CapStrategy};
/// use radiometry::integrator::{Integrator, MonteCarlo, PointSet, Strategy};
/// use radiometry::{Brdf, glam::Vec3};
/// struct Lambert;
/// impl Brdf for Lambert {
///     type Spectrum = f32;
///     fn eval(&self, wi: Vec3, wo: Vec3) -> f32 {
///         if wi.z > 0.0 && wo.z > 0.0 { core::f32::consts::FRAC_1_PI } else { 0.0 }
///     }
/// }
/// // A white Lambertian surface under a cap at the zenith: L_r = E / π.
/// let cap = Cap::new(Vec3::Z, 0.2, 1.0f32).unwrap();
/// let g = CapSampled::new(Lambert, Vec3::Z, &cap, CapStrategy::Light);
/// let mc = MonteCarlo::new(Strategy::Integrand, PointSet::Sobol, 1);
/// let e = mc.integrate(&g, 4096).unwrap();
/// let exact = cap.irradiance() as f64 / core::f64::consts::PI;
/// assert!((e.value - exact).abs() < 1e-4 * exact);
/// ```
#[derive(Clone, Copy, Debug)]
pub struct CapSampled<B: Brdf> {
    brdf: B,
    wo: Vec3,
    cap: Cap<B::Spectrum>,
    /// `1 − cos σ` (without cancellation) and the cone density.
    v_sigma: f32,
    cone_pdf: f32,
    /// Orthonormal complement of the axis.
    e1: Vec3,
    e2: Vec3,
    strategy: CapStrategy,
}

impl<B: Brdf> CapSampled<B> {
    /// The integrand for `brdf` seen from `wo` (local frame) under `cap`.
    pub fn new(brdf: B, wo: Vec3, cap: &Cap<B::Spectrum>, strategy: CapStrategy) -> Self {
        let a = cap.axis();
        // Duff et al. 2017 ("Building an orthonormal basis, revisited").
        let sign = if a.z >= 0.0 { 1.0 } else { -1.0 };
        let p = -1.0 / (sign + a.z);
        let q = a.x * a.y * p;
        let e1 = Vec3::new(1.0 + sign * a.x * a.x * p, sign * q, -sign * a.x);
        let e2 = Vec3::new(q, sign + a.y * a.y * p, -a.y);
        let h = crate::math::sin(0.5 * cap.half_angle());
        let v_sigma = 2.0 * h * h;
        // No cone technique where its density is not an f32 (see the type's docs).
        let cone_pdf = 1.0 / (TAU * v_sigma);
        let cone_pdf = if cone_pdf.is_finite() { cone_pdf } else { 0.0 };
        Self {
            brdf,
            wo,
            cap: *cap,
            v_sigma,
            cone_pdf,
            e1,
            e2,
            strategy,
        }
    }

    /// The sampling strategy.
    pub fn strategy(&self) -> CapStrategy {
        self.strategy
    }

    /// Uniform cone sample: `v = 1 − cos α = u₀ (1 − cos σ)`, `β = 2π u₁`.
    #[inline]
    fn cone_sample(&self, u: [f32; 2]) -> Vec3 {
        let v = u[0].clamp(0.0, 1.0) * self.v_sigma;
        let sin_a = safe_sqrt(v * (2.0 - v));
        let (sb, cb) = crate::math::sincos_turn(u[1].clamp(0.0, 1.0));
        (1.0 - v) * self.cap.axis() + sin_a * (cb * self.e1 + sb * self.e2)
    }

    /// `f_r L cos θ` at `w`, without the cap test.
    #[inline]
    fn unmasked(&self, w: Vec3) -> B::Spectrum {
        if w.z <= 0.0 {
            return B::Spectrum::zero();
        }
        self.brdf.eval(w, self.wo) * self.cap.cap_radiance() * w.z
    }

    /// `out[k] = unmasked(w)` where `dirs[k]` is `Some(w)`, zero elsewhere:
    /// one [`Brdf::eval_batch`] over the directions above the horizon, then
    /// `f_r · L · cos θ` in the order of `unmasked`. (Buffers through
    /// iterators and `get`: no panic path.)
    fn unmasked_where(&self, dirs: &[Option<Vec3>], out: &mut [B::Spectrum]) {
        let wos = [self.wo; CHUNK];
        let mut dense = [Vec3::ZERO; CHUNK];
        let mut index = [0usize; CHUNK];
        let mut vals = [B::Spectrum::zero(); CHUNK];
        let mut m = 0;
        for (k, (o, d)) in out.iter_mut().zip(dirs).take(CHUNK).enumerate() {
            *o = B::Spectrum::zero();
            if let Some(w) = d.filter(|w| w.z > 0.0)
                && let (Some(dw), Some(ix)) = (dense.get_mut(m), index.get_mut(m))
            {
                (*dw, *ix) = (w, k);
                m += 1;
            }
        }
        if let (Some(d), Some(wv), Some(v)) = (dense.get(..m), wos.get(..m), vals.get_mut(..m)) {
            self.brdf.eval_batch(d, wv, v);
        }
        let l = self.cap.cap_radiance();
        for ((&k, w), &v) in index.iter().zip(&dense).zip(&vals).take(m) {
            if let Some(o) = out.get_mut(k) {
                *o = v * l * w.z;
            }
        }
    }

    #[inline]
    fn light_pdf(&self, w: Vec3) -> f32 {
        if self.cap.contains(w) { self.cone_pdf } else { 0.0 }
    }
}

impl<B: Brdf> Integrand for CapSampled<B> {
    type Spectrum = B::Spectrum;

    fn eval(&self, w: Vec3) -> B::Spectrum {
        if self.cap.contains(w) {
            self.unmasked(w)
        } else {
            B::Spectrum::zero()
        }
    }

    fn has_sampling_map(&self) -> bool {
        true
    }

    fn sample(&self, u: [f32; 2]) -> Option<IntegrandSample<B::Spectrum>> {
        match self.strategy {
            CapStrategy::Light => {
                let w = self.cone_sample(u);
                if w.z <= 0.0 || self.cone_pdf == 0.0 {
                    return None;
                }
                Some(IntegrandSample {
                    w,
                    pdf: self.cone_pdf,
                    value: self.unmasked(w),
                })
            }
            CapStrategy::Brdf => {
                let s = self.brdf.sample(self.wo, u)?;
                Some(IntegrandSample {
                    w: s.wi,
                    pdf: s.pdf,
                    value: self.eval(s.wi),
                })
            }
            CapStrategy::Mis => {
                let u0 = u[0].clamp(0.0, 1.0);
                let w = if u0 < 0.5 {
                    let w = self.cone_sample([2.0 * u0, u[1]]);
                    if w.z <= 0.0 || self.cone_pdf == 0.0 {
                        return None;
                    }
                    w
                } else {
                    let v = (2.0 * u0 - 1.0).min(crate::math::ONE_MINUS_EPSILON);
                    self.brdf.sample(self.wo, [v, u[1]])?.wi
                };
                let pdf = self.pdf(w);
                if pdf.is_nan() || pdf <= 0.0 {
                    return None;
                }
                Some(IntegrandSample {
                    w,
                    pdf,
                    value: self.eval(w),
                })
            }
        }
    }

    fn pdf(&self, w: Vec3) -> f32 {
        match self.strategy {
            CapStrategy::Light => self.light_pdf(w),
            CapStrategy::Brdf => self.brdf.pdf(w, self.wo),
            CapStrategy::Mis => 0.5 * (self.light_pdf(w) + self.brdf.pdf(w, self.wo)),
        }
    }

    /// As [`Integrand::eval`], with one [`Brdf::eval_batch`] per chunk over
    /// the points inside the cap and above the horizon.
    fn eval_batch(&self, w: &[Vec3], out: &mut [B::Spectrum]) {
        crate::batch::zero_tail(out, w.len());
        let mut dirs = [None; CHUNK];
        for (w, out) in w.chunks(CHUNK).zip(out.chunks_mut(CHUNK)) {
            let n = w.len().min(out.len());
            for (d, &w) in dirs.iter_mut().zip(w) {
                *d = self.cap.contains(w).then_some(w);
            }
            if let (Some(d), Some(o)) = (dirs.get(..n), out.get_mut(..n)) {
                self.unmasked_where(d, o);
            }
        }
    }

    /// As [`Integrand::sample`] point for point, with the BRDF's
    /// [`Brdf::sample_batch`], [`Brdf::pdf_batch`] and [`Brdf::eval_batch`]
    /// once per chunk.
    fn sample_batch(&self, u: &[[f32; 2]], out: &mut [Option<IntegrandSample<B::Spectrum>>]) {
        crate::batch::zero_tail(out, u.len());
        let wos = [self.wo; CHUNK];
        // Per chunk of `n ≤ CHUNK` points; the buffers are read and written through
        // iterators and `get` (no panic path).
        for (u, out) in u.chunks(CHUNK).zip(out.chunks_mut(CHUNK)) {
            let n = u.len().min(out.len());
            // 1. Directions and densities, as `sample` draws them.
            let mut dirs = [None; CHUNK];
            let mut pdfs = [0.0f32; CHUNK];
            let mut s = [None; CHUNK];
            match self.strategy {
                CapStrategy::Light => {
                    for ((d, p), &uk) in dirs.iter_mut().zip(pdfs.iter_mut()).zip(u).take(n) {
                        let w = self.cone_sample(uk);
                        if w.z > 0.0 && self.cone_pdf != 0.0 {
                            (*d, *p) = (Some(w), self.cone_pdf);
                        }
                    }
                }
                CapStrategy::Brdf => {
                    if let (Some(wv), Some(uv), Some(sv)) = (wos.get(..n), u.get(..n), s.get_mut(..n)) {
                        self.brdf.sample_batch(wv, uv, sv);
                    }
                    for ((d, p), sk) in dirs.iter_mut().zip(pdfs.iter_mut()).zip(&s).take(n) {
                        if let Some(sk) = sk {
                            (*d, *p) = (Some(sk.wi), sk.pdf);
                        }
                    }
                }
                CapStrategy::Mis => {
                    // Cone lanes directly; the BRDF lanes compacted into one
                    // `sample_batch`, then one `pdf_batch` for the mixture.
                    let mut ub = [[0.0f32; 2]; CHUNK];
                    let mut index = [0usize; CHUNK];
                    let mut m = 0;
                    for (k, (d, &uk)) in dirs.iter_mut().zip(u).take(n).enumerate() {
                        let u0 = uk[0].clamp(0.0, 1.0);
                        if u0 < 0.5 {
                            let w = self.cone_sample([2.0 * u0, uk[1]]);
                            if w.z > 0.0 && self.cone_pdf != 0.0 {
                                *d = Some(w);
                            }
                        } else if let (Some(b), Some(ix)) = (ub.get_mut(m), index.get_mut(m)) {
                            let v = (2.0 * u0 - 1.0).min(crate::math::ONE_MINUS_EPSILON);
                            (*b, *ix) = ([v, uk[1]], k);
                            m += 1;
                        }
                    }
                    if let (Some(wv), Some(uv), Some(sv)) = (wos.get(..m), ub.get(..m), s.get_mut(..m)) {
                        self.brdf.sample_batch(wv, uv, sv);
                    }
                    for (&k, sk) in index.iter().zip(&s).take(m) {
                        if let Some(d) = dirs.get_mut(k) {
                            *d = sk.map(|s| s.wi);
                        }
                    }
                    let mut dense = [Vec3::ZERO; CHUNK];
                    let mut bp = [0.0f32; CHUNK];
                    let mut m = 0;
                    for (k, d) in dirs.iter().take(n).enumerate() {
                        if let Some(w) = *d
                            && let (Some(dw), Some(ix)) = (dense.get_mut(m), index.get_mut(m))
                        {
                            (*dw, *ix) = (w, k);
                            m += 1;
                        }
                    }
                    if let (Some(dv), Some(wv), Some(bv)) = (dense.get(..m), wos.get(..m), bp.get_mut(..m)) {
                        self.brdf.pdf_batch(dv, wv, bv);
                    }
                    for ((&k, &w), &b) in index.iter().zip(&dense).zip(&bp).take(m) {
                        let pdf = 0.5 * (self.light_pdf(w) + b);
                        if pdf.is_nan() || pdf <= 0.0 {
                            if let Some(d) = dirs.get_mut(k) {
                                *d = None;
                            }
                        } else if let Some(p) = pdfs.get_mut(k) {
                            *p = pdf;
                        }
                    }
                }
            }
            // 2. Values: `unmasked` for the cone technique (its draws are in
            // the cap by construction), `eval` (cap test first) otherwise.
            let mut masked = [None; CHUNK];
            for (mk, &d) in masked.iter_mut().zip(&dirs).take(n) {
                *mk = match self.strategy {
                    CapStrategy::Light => d,
                    _ => d.filter(|&w| self.cap.contains(w)),
                };
            }
            let mut vals = [B::Spectrum::zero(); CHUNK];
            if let (Some(mv), Some(vv)) = (masked.get(..n), vals.get_mut(..n)) {
                self.unmasked_where(mv, vv);
            }
            for (((o, &d), &pdf), &value) in out.iter_mut().zip(&dirs).zip(&pdfs).zip(&vals).take(n) {
                *o = d.map(|w| IntegrandSample { w, pdf, value });
            }
        }
    }

    /// As [`Integrand::pdf`], with one [`Brdf::pdf_batch`] per chunk where
    /// the BRDF's density is needed.
    fn pdf_batch(&self, w: &[Vec3], out: &mut [f32]) {
        crate::batch::zero_tail(out, w.len());
        let wos = [self.wo; CHUNK];
        for (w, out) in w.chunks(CHUNK).zip(out.chunks_mut(CHUNK)) {
            let n = w.len().min(out.len());
            let (Some(w), Some(out), Some(wos)) = (w.get(..n), out.get_mut(..n), wos.get(..n)) else {
                continue;
            };
            match self.strategy {
                CapStrategy::Light => {
                    for (o, &w) in out.iter_mut().zip(w) {
                        *o = self.light_pdf(w);
                    }
                }
                CapStrategy::Brdf => self.brdf.pdf_batch(w, wos, out),
                CapStrategy::Mis => {
                    self.brdf.pdf_batch(w, wos, out);
                    for (o, &w) in out.iter_mut().zip(w) {
                        *o = 0.5 * (self.light_pdf(w) + *o);
                    }
                }
            }
        }
    }
}
