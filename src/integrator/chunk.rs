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
