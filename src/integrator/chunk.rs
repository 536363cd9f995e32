//! Chunked evaluation: the integrators hand the integrand up to [`CHUNK`]
//! points at a time through [`Integrand::eval_batch`] /
//! [`Integrand::sample_batch`] / [`Integrand::pdf_batch`], in fixed-size
//! stack buffers, and then accumulate the values one by one in the same
//! order as a point-by-point loop would (so estimates do not depend on the
//! chunking).
//!
//! Errors: a chunk is evaluated whole, then checked in order; the first
//! non-finite value (in point order) is reported, as the point-by-point
//! loop would (the points after it are evaluated but discarded).

use super::acc::{direction, to_unit_f32};
use super::{Integrand, IntegrandSample, IntegrateError, WideOf, check_finite};
use crate::brdf::{Brdf, BrdfSample};
use crate::spectrum::{Spectrum, WideSpectrum};
use core::f64::consts::TAU;
use glam::Vec3;

/// Most points an integrator passes to one call of the batch methods of
/// [`Integrand`], and the length of their stack buffers: 32, a multiple of
/// the SIMD widths in use (8 lanes of `f32`). The buffers of one chunk
/// (directions, values, samples, their `f64` widenings) take 1–2 KiB for
/// `f32` and RGB spectra, growing linearly with the channel count of a
/// sampled spectrum; several frames hold such buffers at once, so this size
/// sets most of an integrator's stack (firmware: ≤ 8 KB at a budget of
/// 1,024). The estimates do not depend on it: values are accumulated point
/// by point in the same order (Monte Carlo's moments take their draws 64 at
/// a time whatever this size).
pub const CHUNK: usize = 32;

/// `&s[..n]` without a panic path: the prefix when `n ≤ s.len()` (every
/// caller's case: `n` counts points of a buffer of that length), else empty.
#[inline(always)]
pub(crate) fn head<T>(s: &[T], n: usize) -> &[T] {
    s.get(..n).unwrap_or_default()
}

/// `&mut s[..n]` without a panic path (see [`head`]).
#[inline(always)]
pub(crate) fn head_mut<T>(s: &mut [T], n: usize) -> &mut [T] {
    s.get_mut(..n).unwrap_or_default()
}

/// Integrand values at a batch of points of the unit square, as the
/// quadrature rules consume them: `f(p, out)` sets `out[k] = f(p[k])` for
/// every `k < p.len()` (`out.len() == p.len()`; any length, chunked
/// inside), or fails on the first non-finite value in point order.
pub(crate) trait BatchFn<W>: FnMut(&[[f64; 2]], &mut [W]) -> Result<(), IntegrateError> {}
impl<W, F: FnMut(&[[f64; 2]], &mut [W]) -> Result<(), IntegrateError>> BatchFn<W> for F {}

/// One draw of the integrand's sampling map as the importance weight
/// `g(ω)/p(ω)` in `f64`, together with the direction and density.
///
/// * `None` (from [`Integrand::sample`]) is a zero-contribution sample.
/// * A non-finite value or density is [`IntegrateError::NonFiniteIntegrand`].
/// * A density `≤ 0` (outside the trait contract) contributes zero if the
///   value is black, and is reported as `NonFiniteIntegrand` otherwise (the
///   weight would be infinite).
#[inline]
pub(crate) fn sample_weight<S: Spectrum>(
    s: Option<IntegrandSample<S>>,
) -> Result<Option<(Vec3, f64, S::Wide)>, IntegrateError> {
    let Some(s) = s else {
        return Ok(None);
    };
    let v = check_finite(s.value.to_wide())?;
    if !s.pdf.is_finite() {
        return Err(IntegrateError::NonFiniteIntegrand);
    }
    if s.pdf <= 0.0 {
        return if s.value.is_black() {
            Ok(None)
        } else {
            Err(IntegrateError::NonFiniteIntegrand)
        };
    }
    let p = s.pdf as f64;
    Ok(Some((s.w, p, v.map(|x| x / p))))
}

/// The hemisphere in coordinates `(a, b) ∈ [0,1]²`: `μ = cos θ = a`,
/// `φ = 2π turn(b)`, `dω = dμ dφ = 2π da db`:
/// `out[k] = 2π g(ω(a_k, b_k))`, widened and checked for NaN/∞, for
/// `k < min(p.len(), out.len())`. `turn` re-maps the azimuth fraction
/// (identity, or a rotation of the periodic azimuth).
pub(crate) fn hemisphere_values<I: Integrand>(
    g: &I,
    p: &[[f64; 2]],
    turn: impl Fn(f64) -> f64,
    out: &mut [WideOf<I>],
) -> Result<(), IntegrateError> {
    let mut dirs = [Vec3::ZERO; CHUNK];
    let mut vals = [I::Spectrum::zero(); CHUNK];
    for (p, out) in p.chunks(CHUNK).zip(out.chunks_mut(CHUNK)) {
        let n = p.len().min(out.len());
        for (d, &[a, b]) in head_mut(&mut dirs, n).iter_mut().zip(p) {
            *d = direction(a, TAU * turn(b));
        }
        g.eval_batch(head(&dirs, n), head_mut(&mut vals, n));
        for (o, v) in out.iter_mut().zip(head(&vals, n)) {
            *o = check_finite(v.to_wide())?.map(|x| x * TAU);
        }
    }
    Ok(())
}

/// The plain square through a map: `out[k] = J_k g(ω_k)` where
/// `(μ_k, φ_k, J_k) = map(a_k, b_k)` and `ω_k = ω(μ_k, φ_k)`, for
/// `k < min(p.len(), out.len())`.
pub(crate) fn mapped_hemisphere_values<I: Integrand>(
    g: &I,
    p: &[[f64; 2]],
    map: impl Fn(f64, f64) -> (f64, f64, f64),
    out: &mut [WideOf<I>],
) -> Result<(), IntegrateError> {
    // The Jacobian is recomputed at the output instead of kept: no third
    // chunk-sized buffer on the stack (firmware-sized frames).
    let mut dirs = [Vec3::ZERO; CHUNK];
    let mut vals = [I::Spectrum::zero(); CHUNK];
    for (p, out) in p.chunks(CHUNK).zip(out.chunks_mut(CHUNK)) {
        let n = p.len().min(out.len());
        for (d, &[a, b]) in head_mut(&mut dirs, n).iter_mut().zip(p) {
            let (mu, phi, _) = map(a, b);
            *d = direction(mu, phi);
        }
        g.eval_batch(head(&dirs, n), head_mut(&mut vals, n));
        for ((o, v), &[a, b]) in out.iter_mut().zip(head(&vals, n)).zip(p) {
            let j = map(a, b).2;
            *o = check_finite(v.to_wide())?.map(|x| x * j);
        }
    }
    Ok(())
}

/// The sampling-map square through the bend `s(x) = x + κ x (1 − x)` of
/// both coordinates (`|κ| < 1`, a smooth monotone map of `[0, 1]` onto
/// itself): `out[k] = s'(a_k) s'(b_k) w(s(a_k), s(b_k))` with `w` the
/// values of [`warped_values`].
pub(crate) fn bent_warped_values<I: Integrand>(
    g: &I,
    p: &[[f64; 2]],
    kappa: f64,
    out: &mut [WideOf<I>],
) -> Result<(), IntegrateError> {
    let mut q = [[0.0f64; 2]; CHUNK];
    let mut jac = [0.0f64; CHUNK];
    let bend = |x: f64| (x + kappa * x * (1.0 - x), 1.0 + kappa * (1.0 - 2.0 * x));
    for (p, out) in p.chunks(CHUNK).zip(out.chunks_mut(CHUNK)) {
        let n = p.len().min(out.len());
        for ((q, j), &[a, b]) in head_mut(&mut q, n).iter_mut().zip(jac.iter_mut()).zip(p) {
            let ((sa, da), (sb, db)) = (bend(a), bend(b));
            *q = [sa.clamp(0.0, 1.0), sb.clamp(0.0, 1.0)];
            *j = da * db;
        }
        let out = head_mut(out, n);
        warped_values(g, head(&q, n), out)?;
        for (o, &j) in out.iter_mut().zip(jac.iter()) {
            *o = o.map(|x| x * j);
        }
    }
    Ok(())
}

/// The sampling-map square: `out[k] = g(ω)/p(ω)` at `u = (a_k, b_k)`
/// (rounded to `f32` in `[0, 1)`), zero where the map has no direction
/// (see [`sample_weight`]), for `k < min(p.len(), out.len())`.
pub(crate) fn warped_values<I: Integrand>(
    g: &I,
    p: &[[f64; 2]],
    out: &mut [WideOf<I>],
) -> Result<(), IntegrateError> {
    let mut us = [[0.0f32; 2]; CHUNK];
    let mut ss = [None; CHUNK];
    for (p, out) in p.chunks(CHUNK).zip(out.chunks_mut(CHUNK)) {
        let n = p.len().min(out.len());
        for (u, &[a, b]) in head_mut(&mut us, n).iter_mut().zip(p) {
            *u = [to_unit_f32(a), to_unit_f32(b)];
        }
        g.sample_batch(head(&us, n), head_mut(&mut ss, n));
        for (o, &s) in out.iter_mut().zip(head(&ss, n)) {
            *o = match sample_weight(s)? {
                Some((_, _, w)) => w,
                None => WideOf::<I>::splat(0.0),
            };
        }
    }
    Ok(())
}

/// Most components of a mixture sampling map integrated each on its own
/// square ([`Components`]).
pub(crate) const MAX_COMPONENTS: usize = 8;

/// Most components [`Components::of`] asks the weight of (a map that
/// declares more is integrated whole).
const MAX_DECLARED: usize = 64;

/// The components of an integrand's sampling map with a positive weight
/// ([`Integrand::sampling_components`]): the `i`-th square of a warped
/// run is component `index[i]`, weight `weight[i]`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Components {
    index: [usize; MAX_COMPONENTS],
    weight: [f64; MAX_COMPONENTS],
    n: usize,
}

impl Components {
    /// The components of `g` with a positive weight, in order; none (length
    /// 0: integrate the whole map) when `g` declares one component, more
    /// than [`MAX_DECLARED`], or more than [`MAX_COMPONENTS`] have a
    /// positive weight.
    pub(crate) fn of<I: Integrand>(g: &I) -> Self {
        let mut c = Self {
            index: [0; MAX_COMPONENTS],
            weight: [0.0; MAX_COMPONENTS],
            n: 0,
        };
        let declared = g.sampling_components();
        if declared <= 1 || declared > MAX_DECLARED {
            return c;
        }
        for k in 0..declared {
            let w = g.component_weight(k);
            if !(w.is_finite() && w > 0.0) {
                continue;
            }
            let (Some(i), Some(x)) = (c.index.get_mut(c.n), c.weight.get_mut(c.n)) else {
                c.n = 0;
                return c;
            };
            *i = k;
            *x = w;
            c.n += 1;
        }
        c
    }

    /// The number of squares (components with a positive weight).
    pub(crate) fn len(&self) -> usize {
        self.n
    }

    /// The square of the point `x ∈ [0, len]` of the first coordinate and
    /// the point's coordinate in it: square `⌊x⌋` (the last one for
    /// `x = len`), `x − ⌊x⌋`.
    fn square_of(&self, x: f64) -> (usize, f64) {
        let s = (libm::floor(x).max(0.0) as usize).min(self.n.saturating_sub(1));
        (s, (x - s as f64).clamp(0.0, 1.0))
    }
}

/// `S(t) = t² (3 − 2t)` and `S'(t) = 6 t (1 − t)`: a smooth monotone map
/// of `[0, 1]` onto itself whose derivative vanishes at both ends. A
/// component's map whose density vanishes like `cos θ` at the horizon (the
/// cosine hemisphere, the Kulla–Conty lobe sampler: `cos θ ∝ √u` at the
/// square's edge) meets there a mixture density that does not (the other
/// components'), so its weight `c_k g/p ∝ cos θ ∝ √u` has a square-root
/// singularity at the edge; through `S`, `√(S(t)) ∝ t` and the values
/// `g/p · S'` are smooth.
#[inline]
fn smoothstep(t: f64) -> (f64, f64) {
    (t * t * (3.0 - 2.0 * t), 6.0 * t * (1.0 - t))
}

/// The squares of a mixture map's components side by side,
/// `[0, len] × [0, 1]` (see [`Components`]): at the point `(x_j, y_j)` of
/// square `⌊x_j⌋` (component `k`, weight `c_k`), with `a = x_j − ⌊x_j⌋`,
/// `b = y_j`, each coordinate bent by `s(x) = x + κ x (1 − x)` (the bend of
/// [`bent_warped_values`]; `κ = 0`: none) and then smoothed by
/// [`smoothstep`] `S`, `out[j] = c_k (S∘s)'(a) (S∘s)'(b) g(ω)/p(ω)` at
/// `ω = ω_k(S(s(a)), S(s(b)))`, the draw of component `k` through
/// [`Integrand::component_sample_batch`] (`p` the mixture's density), zero
/// where the component draws no direction, for `j < min(p.len(),
/// out.len())`. Summed over the squares, `∫ Σ_k c_k g/p du = ∫_H g dω`
/// exactly (`Σ_k c_k p_k = p`), and each square's integrand is as smooth as
/// `g` and the densities: no seam at the pick thresholds.
pub(crate) fn component_warped_values<I: Integrand>(
    g: &I,
    comps: &Components,
    kappa: f64,
    p: &[[f64; 2]],
    out: &mut [WideOf<I>],
) -> Result<(), IntegrateError> {
    let mut us = [[0.0f32; 2]; CHUNK];
    let mut sq = [0usize; CHUNK];
    let mut jac = [1.0f64; CHUNK];
    let mut ss = [None; CHUNK];
    let bend = |x: f64| (x + kappa * x * (1.0 - x), 1.0 + kappa * (1.0 - 2.0 * x));
    for (p, out) in p.chunks(CHUNK).zip(out.chunks_mut(CHUNK)) {
        let n = p.len().min(out.len());
        for (((u, s), j), &[x, y]) in head_mut(&mut us, n)
            .iter_mut()
            .zip(sq.iter_mut())
            .zip(jac.iter_mut())
            .zip(p)
        {
            let (square, a) = comps.square_of(x);
            let ((sa, da), (sb, db)) = if kappa == 0.0 {
                ((a, 1.0), (y, 1.0))
            } else {
                (bend(a), bend(y))
            };
            let ((ta, ea), (tb, eb)) = (smoothstep(sa.clamp(0.0, 1.0)), smoothstep(sb.clamp(0.0, 1.0)));
            *u = [to_unit_f32(ta), to_unit_f32(tb)];
            *s = square;
            *j = da * db * ea * eb;
        }
        // Runs of points of the same square go to the integrand together.
        let mut start = 0;
        while start < n {
            let square = sq.get(start).copied().unwrap_or(0);
            let mut end = start + 1;
            while end < n && sq.get(end) == Some(&square) {
                end += 1;
            }
            let k = comps.index.get(square).copied().unwrap_or(0);
            if let (Some(u), Some(s)) = (us.get(start..end), ss.get_mut(start..end)) {
                g.component_sample_batch(k, u, s);
            }
            start = end;
        }
        for (((o, &s), &square), &j) in out.iter_mut().zip(head(&ss, n)).zip(sq.iter()).zip(jac.iter()) {
            let c = comps.weight.get(square).copied().unwrap_or(0.0) * j;
            *o = match sample_weight(s)? {
                Some((_, _, w)) => w.map(|x| x * c),
                None => WideOf::<I>::splat(0.0),
            };
        }
    }
    Ok(())
}

/// `out[k] = f_r(wi[k], wo)` where `wi[k]` is `Some` (other elements are
/// left untouched), for `k < min(wi.len(), out.len())`: one
/// [`Brdf::eval_batch`] per [`CHUNK`] over the compacted directions, so
/// integrands that are zero on part of the hemisphere (a light's support,
/// the horizon) do not evaluate the BRDF there.
pub(crate) fn brdf_eval_where<B: Brdf>(brdf: &B, wo: Vec3, wi: &[Option<Vec3>], out: &mut [B::Spectrum]) {
    let wos = [wo; CHUNK];
    let mut dense = [Vec3::ZERO; CHUNK];
    let mut index = [0usize; CHUNK];
    let mut vals = [B::Spectrum::zero(); CHUNK];
    for (wi, out) in wi.chunks(CHUNK).zip(out.chunks_mut(CHUNK)) {
        // Checked writes: `m ≤ k < CHUNK` by construction, and the code
        // keeps no panic path for it.
        let mut m = 0;
        for (k, w) in wi.iter().take(out.len()).enumerate() {
            if let (Some(w), Some(d), Some(i)) = (*w, dense.get_mut(m), index.get_mut(m)) {
                *d = w;
                *i = k;
                m += 1;
            }
        }
        let m = m.min(CHUNK);
        brdf.eval_batch(head(&dense, m), head(&wos, m), head_mut(&mut vals, m));
        for (&k, &v) in head(&index, m).iter().zip(head(&vals, m)) {
            if let Some(o) = out.get_mut(k) {
                *o = v;
            }
        }
    }
}

/// `out[k] = pdf(w[k], wo)` for `k < min(w.len(), out.len())` with `wo`
/// broadcast: one [`Brdf::pdf_batch`] per [`CHUNK`].
pub(crate) fn brdf_pdf_batch<B: Brdf>(brdf: &B, wo: Vec3, w: &[Vec3], out: &mut [f32]) {
    crate::batch::zero_tail(out, w.len());
    let wos = [wo; CHUNK];
    for (w, out) in w.chunks(CHUNK).zip(out.chunks_mut(CHUNK)) {
        let n = w.len().min(out.len());
        brdf.pdf_batch(head(w, n), head(&wos, n), head_mut(out, n));
    }
}

/// `out[k]` = the integrand sample built by `value` from
/// `sample(wo, u[k])` (`None` stays `None`), for `k < min(u.len(),
/// out.len())`: one [`Brdf::sample_batch`] per [`CHUNK`] with `wo`
/// broadcast. `value` turns a BRDF sample into the integrand's value at
/// `s.wi` (e.g. `s.weight · s.pdf`).
pub(crate) fn brdf_sample_batch<B: Brdf>(
    brdf: &B,
    wo: Vec3,
    u: &[[f32; 2]],
    out: &mut [Option<IntegrandSample<B::Spectrum>>],
    value: impl Fn(&BrdfSample<B::Spectrum>) -> B::Spectrum,
) {
    crate::batch::zero_tail(out, u.len());
    let wos = [wo; CHUNK];
    let mut s = [None; CHUNK];
    for (u, out) in u.chunks(CHUNK).zip(out.chunks_mut(CHUNK)) {
        let n = u.len().min(out.len());
        brdf.sample_batch(head(&wos, n), head(u, n), head_mut(&mut s, n));
        for (o, s) in out.iter_mut().zip(head(&s, n)) {
            *o = s.as_ref().map(|s| IntegrandSample {
                w: s.wi,
                pdf: s.pdf,
                value: value(s),
            });
        }
    }
}

/// `out[j]` = the integrand sample `(ω, pdf(ω), f_r(ω, wo) cos θ)` at
/// `ω = brdf.sample_component(wo, k, u[j])` where that direction is above
/// the horizon and its (mixture) density positive, else `None`, for
/// `j < min(u.len(), out.len())`; the rest of `out` is set to `None`. One
/// [`Brdf::eval_batch`] and one [`Brdf::pdf_batch`] per [`CHUNK`] over the
/// compacted directions.
pub(crate) fn brdf_component_batch<B: Brdf>(
    brdf: &B,
    wo: Vec3,
    k: usize,
    u: &[[f32; 2]],
    out: &mut [Option<IntegrandSample<B::Spectrum>>],
) {
    crate::batch::zero_tail(out, 0);
    let wos = [wo; CHUNK];
    let mut dense = [Vec3::ZERO; CHUNK];
    let mut index = [0usize; CHUNK];
    let mut vals = [B::Spectrum::zero(); CHUNK];
    let mut pdfs = [0.0f32; CHUNK];
    for (u, out) in u.chunks(CHUNK).zip(out.chunks_mut(CHUNK)) {
        // Checked writes: `m ≤ j < CHUNK` by construction, and the code
        // keeps no panic path for it.
        let mut m = 0;
        for (j, &v) in u.iter().take(out.len()).enumerate() {
            if let Some(w) = brdf.sample_component(wo, k, v)
                && crate::frame::cos_theta(w) > 0.0
                && let (Some(d), Some(i)) = (dense.get_mut(m), index.get_mut(m))
            {
                *d = w;
                *i = j;
                m += 1;
            }
        }
        let m = m.min(CHUNK);
        brdf.eval_batch(head(&dense, m), head(&wos, m), head_mut(&mut vals, m));
        brdf.pdf_batch(head(&dense, m), head(&wos, m), head_mut(&mut pdfs, m));
        for ((&j, &w), (&f, &p)) in head(&index, m)
            .iter()
            .zip(head(&dense, m))
            .zip(head(&vals, m).iter().zip(head(&pdfs, m)))
        {
            if p > 0.0
                && let Some(o) = out.get_mut(j)
            {
                *o = Some(IntegrandSample {
                    w,
                    pdf: p,
                    value: f * crate::frame::cos_theta(w),
                });
            }
        }
    }
}
