//! 8-wide `f32` kernels behind [`Brdf::eval_batch`] (feature `simd`).
//!
//! # What is vectorised
//!
//! | BRDF | kernel |
//! |---|---|
//! | [`Microfacet<Ggx, HeightCorrelated, F>`](crate::Microfacet) for every Fresnel `F` | GGX `D`, `Λ`/`G1`, `G2 = 1/(1 + Λ(ωi) + Λ(ωo))` |
//! | [`Microfacet<Ggx, Separable, F>`](crate::Microfacet) for every Fresnel `F` | GGX `D`, `G2 = G1(ωi) G1(ωo)` |
//! | [`Lambertian<S>`](crate::Lambertian) for every spectrum `S` (fully vector stores for `S = f32`) | horizon and finiteness tests |
//! | [`ModifiedPhong<S>`](crate::ModifiedPhong) for every spectrum `S` | normalisation, horizon tests, `δ = 1 − cos α`, vector `exp(n ln(1 − δ))` (not bit-exact: see below) |
//!
//! Every other plugin keeps the default `eval_batch`, a loop over
//! [`Brdf::eval`]. The formulas are those of the scalar code: the microfacet
//! model of Walter et al. 2007 (EGSR, eq. 20) with the GGX distribution
//! (eq. 33) and its Smith `Λ` (Heitz 2014, JCGT 3(2), eq. 86; `G2` variants
//! eqs. 98–99); see [`crate::microfacet`] and [`crate::lambertian`].
//!
//! # Accuracy: bit-identical to `eval` (Phong: propagated tolerance)
//!
//! The GGX and Lambertian kernels perform the *same* IEEE-754 operations as
//! the scalar code, in
//! the same order (`+ − × ÷ √` only, all correctly rounded both in `wide`'s
//! `f32x8` and in scalar `f32`/`libm::sqrtf`; no fused multiply–add, no
//! reciprocal approximations, no polynomial `exp`/`log`). Each lane is
//! therefore bit-identical to `eval` of the same pair; the test
//! `brdfs/tests/batch.rs` checks this (it asserts at most 2 ulp so that a
//! future FMA-using target would still pass, and reports the measured
//! maximum: 0 ulp on x86_64, both for the SSE2 baseline and with
//! `-C target-cpu=native` on an AVX-512/FMA machine).
//!
//! The exception is the modified-Phong lobe `cos^n α = exp(n ln(1 − δ))`,
//! which uses `wide`'s vector `ln_1p`/`exp` (polynomials, a few ulp) rather
//! than `libm`: its lanes differ from `eval` by the propagated rounding,
//! relative `≤ 8 (1 + |n ln(1 − δ)|) 2⁻²⁴` (measured worst: 4.3 of these
//! units), plus an absolute `10⁻⁴⁴ (1 + ks (n+2)/(2π))` where the lobe is
//! subnormal. `|n ln(1 − δ)|` is the condition number of `exp`, so the
//! scalar `libm` result carries a rounding error of the same order. Structural
//! zeros (horizon, degenerate input) are exact.
//!
//! GGX inputs outside the kernel's fast path — a direction whose squared length
//! is outside `[1e-30, 1e30]` (zero, subnormal-tiny, huge, infinite or NaN
//! components) — are recomputed lane by lane with the scalar `eval`, so the
//! special-case handling (`0` for degenerate input) is the scalar one by
//! construction. Below-horizon, grazing (`cos θ = 0` or `1e-7`, or so small
//! that `cos²θ` underflows) and `ωi = −ωo` inputs stay in the kernel and
//! return `0` exactly where `eval` does (masked selects replace the scalar
//! early returns). The Lambertian and Phong kernels evaluate the scalar
//! degenerate-input tests (finiteness; `try_normalize`'s `‖w‖² ∈ (0, ∞)`)
//! lane-wise themselves. A tail of `len % 8` elements goes through `eval` (or
//! the identical scalar expression).
//!
//! # How the override reaches only GGX (no specialisation in Rust)
//!
//! `Microfacet<D, G, F>` has one generic `impl Brdf`. With this feature its
//! `eval_batch` asks two hidden, defaulted trait items:
//! `MicrofacetDistribution::batch_kind(&self) -> DistributionKind` (only
//! [`Ggx`](crate::Ggx) returns `Ggx { alpha }`) and the associated constant
//! `ShadowingMasking::BATCH_KIND: G2Kind` (`HeightCorrelated`/`Separable`).
//! Both are known after monomorphisation, so the `match` folds away; a
//! third-party distribution or shadowing type inherits the `Scalar` default
//! and the plain loop. The Fresnel term is evaluated per lane with the
//! scalar `Fresnel::eval` (it inlines to `1.0` for `NoFresnel`).
//! [`Lambertian`](crate::Lambertian) and [`ModifiedPhong`](crate::ModifiedPhong)
//! override `eval_batch` directly (for every spectrum type); for Lambertian with
//! `S = f32` it stores whole `f32x8` vectors, found with a safe
//! `core::any::Any` downcast of the output chunk (`Spectrum: 'static`).
//!
//! No `unsafe` code: the module uses only `wide`'s safe API, so the crate
//! keeps `#![forbid(unsafe_code)]`. `wide` selects AVX/SSE at compile time
//! from the target features (`-C target-cpu=native` to get AVX on x86_64;
//! the baseline is two SSE `f32x4` halves).
//!
//! ```
//! use radiometry::{Brdf, glam::Vec3};
//! use radiometry_brdfs::{Ggx, Microfacet, NoFresnel, Separable};
//! # fn main() -> Result<(), radiometry_brdfs::BrdfError> {
//! let b = Microfacet::<_, Separable, _>::new(Ggx::new(0.3)?, NoFresnel);
//! let wi: Vec<Vec3> = (0..19).map(|k| Vec3::new(0.05 * k as f32, -0.3, 0.9)).collect();
//! let wo = vec![Vec3::new(-0.2, 0.1, 0.7); 19];
//! let mut out = vec![0.0f32; 19];
//! b.eval_batch(&wi, &wo, &mut out);
//! for k in 0..19 {
//!     assert_eq!(out[k].to_bits(), b.eval(wi[k], wo[k]).to_bits());
//! }
//! # Ok(())
//! # }
//! ```
//!
//! [`Brdf::eval_batch`]: radiometry::Brdf::eval_batch
//! [`Brdf::eval`]: radiometry::Brdf::eval

use crate::microfacet::{Fresnel, Microfacet, MicrofacetDistribution, ShadowingMasking};
use core::any::Any;
use core::f32::consts::{FRAC_1_PI, PI};
use radiometry::frame::{reflect_z, try_normalize};
use radiometry::glam::Vec3;
use radiometry::{Brdf, Spectrum};
use wide::f32x8;

/// Number of lanes of the kernels.
pub const LANES: usize = 8;

/// Which batched kernel a [`MicrofacetDistribution`] supports (hidden hook;
/// not a stable API).
#[doc(hidden)]
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum DistributionKind {
    /// No kernel: `eval_batch` loops over `eval`.
    Scalar,
    /// GGX with this roughness.
    Ggx {
        /// The roughness `α`.
        alpha: f32,
    },
}

/// Which batched `G2` a [`ShadowingMasking`] supports (hidden hook; not a
/// stable API).
#[doc(hidden)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum G2Kind {
    /// No kernel: `eval_batch` loops over `eval`.
    Scalar,
    /// `1/(1 + Λ(ωi) + Λ(ωo))`.
    HeightCorrelated,
    /// `G1(ωi) G1(ωo)`.
    Separable,
}

/// Eight vectors in structure-of-arrays form.
#[derive(Clone, Copy)]
struct V8 {
    x: f32x8,
    y: f32x8,
    z: f32x8,
}

impl V8 {
    #[inline(always)]
    fn load(v: &[Vec3; LANES]) -> V8 {
        V8 {
            x: f32x8::new(core::array::from_fn(|k| v[k].x)),
            y: f32x8::new(core::array::from_fn(|k| v[k].y)),
            z: f32x8::new(core::array::from_fn(|k| v[k].z)),
        }
    }

    /// `(x·x' + y·y') + z·z'`, glam's order.
    #[inline(always)]
    fn dot(self, o: V8) -> f32x8 {
        self.x * o.x + self.y * o.y + self.z * o.z
    }

    #[inline(always)]
    fn div(self, s: f32x8) -> V8 {
        V8 {
            x: self.x / s,
            y: self.y / s,
            z: self.z / s,
        }
    }

    #[inline(always)]
    fn add(self, o: V8) -> V8 {
        V8 {
            x: self.x + o.x,
            y: self.y + o.y,
            z: self.z + o.z,
        }
    }
}

/// `finite_nonneg`: `x > 0 ? min(x, f32::MAX) : 0` (NaN → 0).
#[inline(always)]
fn finite_nonneg(x: f32x8) -> f32x8 {
    x.simd_gt(f32x8::ZERO)
        .select(x.min(f32x8::splat(f32::MAX)), f32x8::ZERO)
}

/// Scalar fallback: `out[k] = b.eval(wi[k], wo[k])`.
#[inline]
fn scalar<B: Brdf>(b: &B, wi: &[Vec3], wo: &[Vec3], out: &mut [B::Spectrum]) {
    for ((o, &a), &c) in out.iter_mut().zip(wi).zip(wo) {
        *o = b.eval(a, c);
    }
}

/// `Brdf::eval_batch` of [`Microfacet`]: the GGX kernel when `D` and `G`
/// opt in through the hidden hooks, else the scalar loop.
#[inline]
pub(crate) fn microfacet_eval_batch<D, G, F>(
    b: &Microfacet<D, G, F>,
    wi: &[Vec3],
    wo: &[Vec3],
    out: &mut [F::Spectrum],
) where
    D: MicrofacetDistribution,
    G: ShadowingMasking,
    F: Fresnel,
{
    match (b.distribution.batch_kind(), G::BATCH_KIND) {
        (DistributionKind::Ggx { alpha }, G2Kind::HeightCorrelated) => {
            ggx_batch::<false, _>(b, alpha, wi, wo, out)
        }
        (DistributionKind::Ggx { alpha }, G2Kind::Separable) => ggx_batch::<true, _>(b, alpha, wi, wo, out),
        _ => scalar(b, wi, wo, out),
    }
}

/// Drives [`ggx_x8`] over whole chunks of 8 and `eval` over the tail.
#[inline]
fn ggx_batch<const SEPARABLE: bool, B>(b: &B, alpha: f32, wi: &[Vec3], wo: &[Vec3], out: &mut [B::Spectrum])
where
    B: Brdf + FresnelOf,
{
    let n = wi.len().min(wo.len()).min(out.len());
    let (wi, wo, out) = (&wi[..n], &wo[..n], &mut out[..n]);
    let (ci, ti) = wi.as_chunks::<LANES>();
    let (co, to) = wo.as_chunks::<LANES>();
    let (cout, tout) = out.as_chunks_mut::<LANES>();
    for ((a, c), o) in ci.iter().zip(co).zip(cout.iter_mut()) {
        let (s, cos_d, fallback) = ggx_x8::<SEPARABLE>(alpha, V8::load(a), V8::load(c));
        let (s, cos_d) = (s.to_array(), cos_d.to_array());
        for k in 0..LANES {
            o[k] = if fallback & (1 << k) != 0 {
                b.eval(a[k], c[k])
            } else if s[k] == 0.0 {
                B::Spectrum::zero()
            } else {
                b.fresnel_times(cos_d[k], s[k])
            };
        }
    }
    scalar(b, ti, to, tout);
}

/// Access to `F(cos θd) · s` of a microfacet BRDF without naming `D, G`.
trait FresnelOf: Brdf {
    fn fresnel_times(&self, cos_d: f32, s: f32) -> Self::Spectrum;
}

impl<D, G, F> FresnelOf for Microfacet<D, G, F>
where
    D: MicrofacetDistribution,
    G: ShadowingMasking,
    F: Fresnel,
{
    /// The last line of `Microfacet::eval`: `F(cos θd) · s`.
    #[inline(always)]
    fn fresnel_times(&self, cos_d: f32, s: f32) -> F::Spectrum {
        self.fresnel.eval(cos_d) * s
    }
}

/// GGX `A(ω) = (cos θ + √(cos²θ + α² sin²θ))/2` of a unit `w`
/// (`Ggx::projected_area` of the scalar code).
#[inline(always)]
fn ggx_area(a2: f32x8, w: V8) -> f32x8 {
    f32x8::splat(0.5) * (w.z + (w.z * w.z + a2 * (w.x * w.x + w.y * w.y)).sqrt())
}

/// One chunk of `Microfacet<Ggx, G, F>::eval` without the Fresnel factor.
///
/// Returns `(s, cos θd, fallback)` where `s = finite_nonneg(D V)` (0 where
/// `eval` returns 0), `cos θd = min(1, |ωi + ωo|/2)`, and `fallback` has
/// bit `k` set when lane `k` must be recomputed by `eval` (a direction that
/// is not unit to within `4ε`: `eval`'s cold path).
#[inline(always)]
fn ggx_x8<const SEPARABLE: bool>(alpha: f32, wi: V8, wo: V8) -> (f32x8, f32x8, u32) {
    let one = f32x8::ONE;
    let zero = f32x8::ZERO;
    let four = f32x8::splat(4.0);
    let alpha = f32x8::splat(alpha);

    // is_unit of both directions, else the scalar (cold) path.
    let tol = f32x8::splat(4.0 * f32::EPSILON);
    let unit_i = (wi.dot(wi) - one).abs().simd_le(tol);
    let unit_o = (wo.dot(wo) - one).abs().simd_le(tol);
    let fallback = !(unit_i & unit_o);

    // Half::of: both strictly above the horizon, |h|² > 1e-14, one division.
    let up = wi.z.simd_gt(zero) & wo.z.simd_gt(zero);
    let h = wi.add(wo);
    let len2 = h.dot(h);
    let h_ok = len2.simd_gt(f32x8::splat(1e-14));
    let inv = one / len2;
    let cos2 = (h.z * h.z) * inv;
    let sin2 = (h.x * h.x + h.y * h.y) * inv;

    // Ggx::d_cos2.
    let a2 = alpha * alpha;
    let t = a2 * cos2 + sin2;
    let d = finite_nonneg(a2 / (f32x8::splat(PI) * t * t));

    // ShadowingMasking::visibility from the projected areas.
    let (ai, ao) = (ggx_area(a2, wi), ggx_area(a2, wo));
    let v = if SEPARABLE {
        one / (four * (ai * ao))
    } else {
        one / (four * ((wo.z * ai + wi.z * ao) - wi.z * wo.z))
    };

    let s = finite_nonneg(d * v);
    let s = (up & h_ok).select(s, zero);
    // cos θd = |ωi + ωo|/2, as the scalar `Half::cos_theta_d`.
    let cos_d = (f32x8::splat(0.5) * len2.sqrt()).min(one);
    (s, cos_d, fallback.to_bitmask())
}

/// `Brdf::eval_batch` of [`Lambertian`](crate::Lambertian):
/// `out[k] = value` when `cos θi > 0`, `cos θo > 0` and both directions are
/// finite, else 0 — the scalar test of `Lambertian::eval`, with `value =
/// ρ/π` computed by the caller exactly as `eval` computes it.
#[inline]
pub(crate) fn lambertian_eval_batch<S: Spectrum>(value: S, wi: &[Vec3], wo: &[Vec3], out: &mut [S]) {
    let n = wi.len().min(wo.len()).min(out.len());
    let (wi, wo, out) = (&wi[..n], &wo[..n], &mut out[..n]);
    let (ci, ti) = wi.as_chunks::<LANES>();
    let (co, to) = wo.as_chunks::<LANES>();
    let (cout, tout) = out.as_chunks_mut::<LANES>();
    let zero = f32x8::ZERO;
    // `Some(ρ/π)` exactly when `S = f32`: then whole vectors are stored.
    let mono = (&value as &dyn Any)
        .downcast_ref::<f32>()
        .map(|&v| f32x8::splat(v));
    for ((a, c), o) in ci.iter().zip(co).zip(cout.iter_mut()) {
        let (a8, c8) = (V8::load(a), V8::load(c));
        let finite = a8.x.is_finite()
            & a8.y.is_finite()
            & a8.z.is_finite()
            & c8.x.is_finite()
            & c8.y.is_finite()
            & c8.z.is_finite();
        let mask = a8.z.simd_gt(zero) & c8.z.simd_gt(zero) & finite;
        match (mono, (o as &mut dyn Any).downcast_mut::<[f32; LANES]>()) {
            (Some(v), Some(o32)) => *o32 = mask.select(v, zero).to_array(),
            _ => {
                let bits = mask.to_bitmask();
                for (k, ok) in o.iter_mut().enumerate() {
                    *ok = if bits & (1 << k) != 0 { value } else { S::zero() };
                }
            }
        }
    }
    for ((o, a), c) in tout.iter_mut().zip(ti).zip(to) {
        let ok = a.z > 0.0 && c.z > 0.0 && a.is_finite() && c.is_finite();
        *o = if ok { value } else { S::zero() };
    }
}

/// `cos^n α = (1 − δ)^n` of the modified-Phong lobe (`pow_one_minus` of the
/// scalar code): `0` for `δ ≥ 1` or NaN, `1` for `δ ≤ 0`, else
/// `exp(n · ln(1 − δ))` with `wide`'s `ln_1p` and `exp` (polynomial
/// approximations, a few ulp; `ln_1p` keeps relative accuracy for tiny `δ`).
#[inline(always)]
fn pow_one_minus(delta: f32x8, n: f32) -> f32x8 {
    let zero = f32x8::ZERO;
    let one = f32x8::ONE;
    let lobe = (f32x8::splat(n) * (-delta).ln_1p()).exp();
    let lobe = delta.simd_le(zero).select(one, lobe);
    (delta.simd_ge(one) | delta.is_nan()).select(zero, lobe)
}

/// `Brdf::eval_batch` of [`ModifiedPhong`](crate::ModifiedPhong):
/// `f = kd/π + ks (n+2)/(2π) cos^n α` (Lafortune & Willems 1994), zero unless
/// both (normalised) directions are strictly above the horizon.
///
/// Everything but `cos^n α` is bit-identical to `eval`; `cos^n α =
/// exp(n ln(1 − δ))` uses `wide`'s vector `ln_1p`/`exp` instead of `libm`,
/// so lanes differ from `eval` by the propagated rounding of the exponent:
/// relative `≲ (c₁ + c₂ |n ln(1 − δ)|) 2⁻²⁴` (the condition number of
/// `exp(y)` is `|y|`; the test uses `c₁ = c₂ = 8`), plus an absolute
/// `≈ 10⁻⁴⁵ ks (n+2)/(2π)` where `cos^n α` is subnormal or below `e^{−103.6}`.
#[inline]
pub(crate) fn phong_eval_batch<S: Spectrum>(kd: S, ks: S, n: f32, wi: &[Vec3], wo: &[Vec3], out: &mut [S]) {
    let len = wi.len().min(wo.len()).min(out.len());
    let (wi, wo, out) = (&wi[..len], &wo[..len], &mut out[..len]);
    let (ci, ti) = wi.as_chunks::<LANES>();
    let (co, to) = wo.as_chunks::<LANES>();
    let (cout, tout) = out.as_chunks_mut::<LANES>();
    let zero = f32x8::ZERO;
    let diffuse = kd * FRAC_1_PI;
    let norm = (n + 2.0) * (0.5 * FRAC_1_PI);
    for ((a, c), o) in ci.iter().zip(co).zip(cout.iter_mut()) {
        // `try_normalize`: `w/√‖w‖²` when `‖w‖² ∈ (0, ∞)`, else degenerate.
        let (a, c) = (V8::load(a), V8::load(c));
        let (la, lc) = (a.dot(a), c.dot(c));
        let ok = la.simd_gt(zero) & la.is_finite() & lc.simd_gt(zero) & lc.is_finite();
        let (a, c) = (a.div(la.sqrt()), c.div(lc.sqrt()));
        let up = ok & a.z.simd_gt(zero) & c.z.simd_gt(zero);
        // δ = |ωi − reflect_z(ωo)|²/2 = 1 − cos α.
        let d = V8 {
            x: a.x - (-c.x),
            y: a.y - (-c.y),
            z: a.z - c.z,
        };
        let delta = f32x8::splat(0.5) * d.dot(d);
        let lobe = pow_one_minus(delta, n).to_array();
        let bits = up.to_bitmask();
        for (k, ok) in o.iter_mut().enumerate() {
            *ok = if bits & (1 << k) != 0 {
                diffuse + ks * (norm * lobe[k])
            } else {
                S::zero()
            };
        }
    }
    for ((o, &a), &c) in tout.iter_mut().zip(ti).zip(to) {
        *o = match (try_normalize(a), try_normalize(c)) {
            (Some(a), Some(c)) if a.z > 0.0 && c.z > 0.0 => {
                let delta = 0.5 * (a - reflect_z(c)).length_squared();
                let lobe = if delta.is_nan() || delta >= 1.0 {
                    0.0
                } else if delta <= 0.0 {
                    1.0
                } else {
                    libm::expf(n * libm::log1pf(-delta))
                };
                diffuse + ks * (norm * lobe)
            }
            _ => S::zero(),
        };
    }
}
