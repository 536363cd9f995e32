//! Vector `f32` kernels (8 or 16 lanes) behind [`Brdf::eval_batch`],
//! [`Brdf::eval_batch_soa`], [`Brdf::pdf_batch`] and
//! [`Brdf::sample_batch`] (feature `simd`).
//!
//! This module holds the shared vector math ([`LANES`] directions in
//! structure-of-arrays form, the chunk drivers for array-of-structures and
//! structure-of-arrays input, bit-exact vector ports of `libm`'s `expf`,
//! `log1pf`, `powf`, `logf` and `expm1f` and of the crate's own `sincos_turn`, `f32` ↔ `f64` lane conversions, spectrum
//! stores, the chunk driver of the sampling kernels); it imports nothing from
//! the plugins. Each
//! plugin's kernel lives next to its scalar code and follows its formula
//! operation for operation:
//!
//! | BRDF | `eval_batch` / `eval_batch_soa` | `pdf_batch` | vs scalar |
//! |---|---|---|---|
//! | [`Microfacet<Ggx, HeightCorrelated, F>`](crate::Microfacet), every Fresnel `F` | GGX `D` (Walter et al. 2007, eq. 33), projected areas `A = cos θ (1 + Λ)`, `V = 1/(4 (cos θo Ai + cos θi Ao − cos θi cos θo))` (Heitz 2014, eq. 99) | `D/(4 A(ωo))` | 0 ulp |
//! | [`Microfacet<Ggx, Separable, F>`](crate::Microfacet), every Fresnel `F` | as above, `V = 1/(4 Ai Ao)` (Heitz 2014, eq. 98) | `D/(4 A(ωo))` | 0 ulp |
//! | [`Microfacet<Beckmann, G, F>`](crate::Microfacet), either `G`, every `F` | Beckmann `D = exp(−tan²θh/α²)/(π α² cos⁴θh)` (Walter et al. 2007, eq. 25), `A = cos θ + α sin θ · aΛ(a)` with the loop-free `Λ = e^{−a²} T(a)/(2√π a)` (its `f64` rational on `f64` vectors) | `D/(4 A(ωo))` | 0 ulp |
//! | `sample_batch` of [`Microfacet<Ggx, G, F>`](crate::Microfacet), either `G`, every `F` | visible normals by spherical caps (Dupuy & Benyoub 2023; Heitz 2018 stretch), `ωi = 2(ωo·m)m − ωo`, pdf `D/(4 A(ωo))`, weight `F G2/G1` | — | 0 ulp (`wi`, pdf, weight; same `None`s) |
//! | `sample_batch` of [`Microfacet<Beckmann, G, F>`](crate::Microfacet), either `G`, every `F` | visible slopes (Heitz & d'Eon 2014, §4): the bounded start and two bracketed Halley steps of the scalar inversion, `erfinv` for the second slope, on `f64` vectors where the scalar code uses `f64` | — | 0 ulp (`wi`, pdf, weight; same `None`s) |
//! | Fresnel of the microfacet kernels: [`NoFresnel`](crate::NoFresnel), [`Schlick`](crate::Schlick) (Schlick 1994, eq. 15), [`Dielectric`](crate::Dielectric), [`Conductor`](crate::Conductor) | vector, per channel | — | 0 ulp |
//! | [`Tabulated<S>`](crate::tabulated::Tabulated) | the Rusinkiewicz coordinates of the pairs (sums, products, one division, root and arctangent polynomial per angle), then the trilinear reads per lane | the half-vector/cosine mixture density, the bin reads per lane | 0 ulp |
//! | [`Lambertian<S>`](crate::Lambertian) | horizon and finiteness masks | `cos θi/π` | 0 ulp |
//! | `sample_batch` of [`Lambertian<S>`](crate::Lambertian) | Malley's cosine-weighted concentric map (Shirley & Chiu 1997; the Phong family's warp), pdf `cos θi/π` of the normalised `ωi` | — | 0 ulp (`wi`, pdf, weight; same `None`s) |
//! | [`ModifiedPhong<S>`](crate::ModifiedPhong) | `kd/π + ks (n+2)/(2π) exp(n log1p(−δ))` (Lafortune & Willems 1994) | `pd cos θi/π + ps (n+1)/(2π) cos^n α` | 0 ulp |
//! | `sample_batch` of [`ModifiedPhong<S>`](crate::ModifiedPhong) | one-sample mixture (Veach 1997, §9.2.4): Malley's cosine-weighted concentric map (Shirley & Chiu 1997) or `cos α = ξ^{1/(n+1)}`, `1 − cos α = −expm1(ln ξ/(n+1))` around `ωr` (Lafortune & Willems 1994), rotated by Duff et al. 2017; pdf and weight from one lobe evaluation | — | 0 ulp (`wi`, pdf, weight; same `None`s) |
//! | [`BlinnPhong<S>`](crate::BlinnPhong) | `kd/π + ks N(n) cos^n θh` (Blinn 1977) | `pd cos θi/π + ps (n+1)/(2π) cos^n θh/(4 ωo·h)` | 0 ulp |
//! | `sample_batch` of [`BlinnPhong<S>`](crate::BlinnPhong) | the same mixture with the half vector `cos θh = ξ^{1/(n+1)}` reflected, `ωi = 2(ωo·h)h − ωo`, pdf `pd cos θi/π + ps (n+1)/(2π) cos^n θh/(4 ωo·h)` (the reflection Jacobian of Torrance & Sparrow 1967; Walter et al. 2007) | — | 0 ulp (`wi`, pdf, weight; same `None`s) |
//!
//! Every other plugin keeps the scalar-loop defaults of [`Brdf`].
//!
//! # Accuracy
//!
//! **Bit-identical kernels.** The kernels perform the *same* IEEE-754
//! operations as the scalar code, in the same order: `+ − × ÷ √`,
//! comparisons and selects, all correctly rounded in `wide`'s vectors and in
//! scalar `f32` / `libm::sqrtf`; no fused multiply–add, no reciprocal
//! estimates. The transcendentals are bit-exact vector ports of the
//! functions the scalar code calls — of `libm`: `expf` (FreeBSD `e_expf.c`), `log1pf`
//! (`s_log1pf.c`), `powf` (`e_powf.c`), `logf` (`e_logf.c`) and `expm1f` (`s_expm1f.c`);
//! of this project: [`radiometry::math::sincos_turn`] (the samplers' azimuths);
//! with integer operations on the
//! bits through `wide`'s integer vectors, checked against the scalar functions by this
//! module's unit tests on every 7th `f32` of their ranges (`powf`: for
//! `y = 30`; sparser grids for other exponents). Each lane is therefore bit-identical to
//! `eval` / `pdf` of the same pair, on every target: `brdfs/tests/batch.rs`
//! asserts 0 ulp for every such kernel, array-of-structures and
//! structure-of-arrays alike, over proptest cases, hard cases in every lane
//! position and a deterministic sweep of 200 000 pairs (x86_64, SSE2
//! baseline with 8 lanes and `-C target-cpu=native` with AVX-512 and 16
//! lanes). The sampling kernels have their own test,
//! `brdfs/tests/sample_batch.rs`: the same `None` decisions and 0 ulp in
//! `wi`, pdf and weight, and the pdf equal to `pdf_batch` of the returned
//! `wi`, over 1.2 million random `(ωo, u)` and hard cases (grazing and
//! non-unit `ωo`, `u` at 0, 1 − ε, 1 and out of range, `α = 10⁻⁴` and 1)
//! in every lane position; for the Phong family 100 000 random `(ωo, u)` and
//! the same hard cases for each of a dozen `(kd, ks, n)` (`n` from 0 to
//! 10⁷, `kd = 0`, `ks = 0`, both), RGB and 4-channel spectra, and proptest
//! cases with random `(kd, ks, n)`; for Lambertian (`f32`, RGB, 4 channels)
//! the same inputs.
//!
//! # Special inputs
//!
//! The microfacet kernels evaluate lanes whose directions are unit to within
//! `4ε` (`|‖ω‖² − 1| ≤ 4ε`, the scalar hot path's test) in vector form and
//! recompute any other lane — non-unit, zero, subnormal, huge, infinite or
//! NaN components: the scalar cold path — with the scalar `eval`/`pdf`, so
//! the special-case handling is the scalar one by construction. They also
//! hand back the lanes where the product of the denominators of `D` and of
//! `1/V` (or `4A(ωo)`) is not a normal `f32` (the scalar path's two-division
//! `#[cold]` form).
//! The sampling kernels hand back lanes with a non-unit `ωo` and lanes where
//! one of the sampler's normalisations (of the stretched `ωo`, of `m`, of
//! `ωi`) leaves the scalar `unitize`'s two hot branches (unit already, or
//! `‖w‖² ∈ [10⁻³⁰, 10³⁰]`); the Phong-family samplers hand back lanes whose
//! sampled `ωi` is not unit to within `4ε` (the scalar `unit_or_normalize`
//! or `upper_pair` would normalise it).
//! Below-horizon, grazing (`cos θ = 0`, or so small that `cos²θ` underflows)
//! and `ωi = −ωo` lanes stay in the kernel and give `0` exactly where `eval`
//! does (masked selects replace the scalar early returns). The Lambertian and
//! Phong-family kernels evaluate the scalar degenerate-input tests
//! (finiteness; `try_normalize`'s `‖w‖² ∈ (0, ∞)`) lane-wise. A tail of
//! `len % LANES` elements goes through the scalar `eval`/`pdf`.
//!
//! # How the overrides reach only the supported types
//!
//! `Microfacet<D, G, F>` has one generic `impl Brdf`; with this feature its
//! batch methods ask two hidden, defaulted trait items (not a stable API):
//! `MicrofacetDistribution::batch_kind` (only [`Ggx`](crate::Ggx) and
//! [`Beckmann`](crate::Beckmann) opt in)
//! and the associated constant `ShadowingMasking::BATCH_KIND`. Both are known
//! after monomorphisation, so the `match` folds away; a third-party
//! distribution or shadowing type inherits the scalar loop. The Fresnel
//! factor goes through the hidden provided method `Fresnel::eval_scaled_lanes`
//! (`F(cos θd)·s` for one vector of lanes), whose default is the per-lane scalar
//! `eval`; the four Fresnel types of this crate override it with vector code.
//! For `S = f32` whole vectors are stored, found with a safe
//! `core::any::Any` downcast of the output chunk (`Spectrum: 'static`).
//!
//! # Lane width
//!
//! The kernels are written once against the vector type `Vf` with
//! [`LANES`] lanes, chosen at compile time from the target features:
//! `wide::f32x16` (one 512-bit register) when the build enables AVX-512,
//! else `wide::f32x8` (one AVX register with `-C target-cpu=native` on an AVX
//! CPU; two SSE `f32x4` halves on the x86_64 baseline; two NEON halves on
//! aarch64). The results do not depend on the width (every lane is the
//! scalar value). Sixteen lanes halve the instructions per element: on an
//! AVX-512 CPU (AMD EPYC, Zen 4) the GGX `eval_batch_soa` went from about
//! 0.6× to 0.9× of an auto-vectorised loop of the same formula (which LLVM
//! compiles to 512-bit vectors there).
//!
//! No `unsafe` code: only `wide`'s safe API, so the crate keeps
//! `#![forbid(unsafe_code)]`.
//!
//! # Throughput
//!
//! GGX height-correlated, `F = 1`, `α = 0.3`, n = 4096 pairs in cache, one
//! thread of a shared AMD EPYC (Zen 4), best of 400 repetitions; the
//! reference is a branch-free loop of the same formula over `&[f32]` slices
//! that LLVM auto-vectorises (no input checks; same bits on these inputs):
//!
//! | build | `eval` loop | `eval_batch` | `eval_batch_soa` | reference | batch / ref | soa / ref |
//! |---|---|---|---|---|---|---|
//! | `-C target-cpu=native` (16 lanes) | 8.48 ns | 1.51 ns | 0.79–1.07 ns | 0.69–0.94 ns | 0.46–0.62 | 0.88 |
//! | x86_64 baseline (SSE2, 8 lanes) | 9.66 ns | 3.42 ns | 2.33 ns | 1.59 ns | 0.47 | 0.68 |
//!
//! (Ratios are rates: reference time / kernel time, each pair from one run;
//! the machine alternated between two speeds, which moved both columns
//! together.) `eval_batch` pays for gathering `&[Vec3]` into vectors: `wide`
//! has no shuffles, and LLVM builds the vectors with one insert per element;
//! structure-of-arrays input is three plain loads per direction.
//!
//! ```
//! use radiometry::{Brdf, batch::Vec3Soa, glam::Vec3};
//! use radiometry_brdfs::{Ggx, Microfacet, Schlick, Separable};
//! # fn main() -> Result<(), radiometry_brdfs::BrdfError> {
//! let b = Microfacet::<_, Separable, _>::new(Ggx::new(0.3)?, Schlick::new(0.04f32)?);
//! let wi: Vec<Vec3> = (0..19).map(|k| Vec3::new(0.05 * k as f32, -0.3, 0.9).normalize()).collect();
//! let wo = vec![Vec3::new(-0.2, 0.1, 0.7).normalize(); 19];
//! let mut out = vec![0.0f32; 19];
//! b.eval_batch(&wi, &wo, &mut out);
//! // The same directions in structure-of-arrays form.
//! let (x, y, z): (Vec<f32>, Vec<f32>, Vec<f32>) = (
//!     wi.iter().map(|w| w.x).collect(),
//!     wi.iter().map(|w| w.y).collect(),
//!     wi.iter().map(|w| w.z).collect(),
//! );
//! let (ox, oy, oz) = (vec![wo[0].x; 19], vec![wo[0].y; 19], vec![wo[0].z; 19]);
//! let mut soa = vec![0.0f32; 19];
//! b.eval_batch_soa(Vec3Soa::new(&x, &y, &z), Vec3Soa::new(&ox, &oy, &oz), &mut soa);
//! for k in 0..19 {
//!     assert_eq!(out[k].to_bits(), b.eval(wi[k], wo[k]).to_bits());
//!     assert_eq!(soa[k].to_bits(), out[k].to_bits());
//! }
//! # Ok(())
//! # }
//! ```
//!
//! [`Brdf`]: radiometry::Brdf
//! [`Brdf::eval_batch`]: radiometry::Brdf::eval_batch
//! [`Brdf::eval_batch_soa`]: radiometry::Brdf::eval_batch_soa
//! [`Brdf::pdf_batch`]: radiometry::Brdf::pdf_batch
//! [`Brdf::sample_batch`]: radiometry::Brdf::sample_batch

mod expm1f;
mod logf;
mod sample;
mod sincos;

pub(crate) use expm1f::expm1f;
pub(crate) use logf::logf;
pub(crate) use sample::{SampleKernel, run_samples};
pub(crate) use sincos::sincos_turn;

use core::any::Any;
use radiometry::Spectrum;
use radiometry::batch::Vec3Soa;
use radiometry::glam::Vec3;

/// The vector type of the kernels: `wide::f32x16` when the build enables
/// AVX-512 (`-C target-cpu=native` on such a CPU; one 512-bit register), else
/// `wide::f32x8` (one AVX register, or two SSE / NEON halves). Chosen at
/// compile time from the target features, like `wide`'s own code paths.
#[cfg(target_feature = "avx512f")]
#[doc(hidden)]
pub type Vf = wide::f32x16;
/// The vector type of the kernels (see the AVX-512 variant).
#[cfg(not(target_feature = "avx512f"))]
#[doc(hidden)]
pub type Vf = wide::f32x8;

/// Number of lanes of the kernels: 16 with AVX-512, else 8.
pub const LANES: usize = core::mem::size_of::<Vf>() / core::mem::size_of::<f32>();

/// [`LANES`] directions in structure-of-arrays form.
#[derive(Clone, Copy)]
pub(crate) struct Dirs {
    pub(crate) x: Vf,
    pub(crate) y: Vf,
    pub(crate) z: Vf,
}

impl Dirs {
    /// Gathers [`LANES`] [`Vec3`] (array-of-structures input).
    #[inline(always)]
    pub(crate) fn from_aos(v: &[Vec3; LANES]) -> Dirs {
        Dirs {
            x: Vf::new(core::array::from_fn(|k| v[k].x)),
            y: Vf::new(core::array::from_fn(|k| v[k].y)),
            z: Vf::new(core::array::from_fn(|k| v[k].z)),
        }
    }

    /// Loads [`LANES`] consecutive components of each axis (structure-of-arrays
    /// input): three plain vector loads.
    #[inline(always)]
    pub(crate) fn from_soa(x: &[f32; LANES], y: &[f32; LANES], z: &[f32; LANES]) -> Dirs {
        Dirs {
            x: Vf::new(*x),
            y: Vf::new(*y),
            z: Vf::new(*z),
        }
    }

    /// `(x·x' + y·y') + z·z'`, glam's order.
    #[inline(always)]
    pub(crate) fn dot(self, o: Dirs) -> Vf {
        self.x * o.x + self.y * o.y + self.z * o.z
    }

    /// [`radiometry::frame::half_vector_sum`] lane-wise (the scalar's
    /// operations in the scalar's order, so bit-identical): the
    /// length-corrected `ωi + ωo` and `|ωi + ωo|²`.
    #[inline(always)]
    pub(crate) fn half_vector_sum(self, wo: Dirs) -> (Dirs, Vf) {
        let wi = self;
        let s = wi.add(wo);
        let sum2 = s.length_squared();
        let correct = sum2.simd_lt(Vf::splat(radiometry::frame::HALF_VECTOR_CORRECTION_BELOW));
        if !correct.any() {
            return (s, sum2);
        }
        let d = Dirs {
            x: wi.x - wo.x,
            y: wi.y - wo.y,
            z: wi.z - wo.z,
        };
        let q = Vf::splat(0.25);
        let k = Dirs {
            x: q * d.x,
            y: q * d.y,
            z: q * d.z,
        }
        .dot(s);
        let h = Dirs {
            x: correct.select(s.x - k * d.x, s.x),
            y: correct.select(s.y - k * d.y, s.y),
            z: correct.select(s.z - k * d.z, s.z),
        };
        (h, sum2)
    }

    /// `‖w‖²` in glam's order.
    #[inline(always)]
    pub(crate) fn length_squared(self) -> Vf {
        self.dot(self)
    }

    /// `x² + y²` (`sin²θ` of a unit direction).
    #[inline(always)]
    pub(crate) fn xy_length_squared(self) -> Vf {
        self.x * self.x + self.y * self.y
    }

    /// Component-wise quotient by `s` (glam's `Vec3 / f32`).
    #[inline(always)]
    pub(crate) fn div(self, s: Vf) -> Dirs {
        Dirs {
            x: self.x / s,
            y: self.y / s,
            z: self.z / s,
        }
    }

    /// Component-wise sum.
    #[inline(always)]
    pub(crate) fn add(self, o: Dirs) -> Dirs {
        Dirs {
            x: self.x + o.x,
            y: self.y + o.y,
            z: self.z + o.z,
        }
    }

    /// Mask of the lanes whose three components are finite.
    #[inline(always)]
    pub(crate) fn is_finite(self) -> Vf {
        self.x.is_finite() & self.y.is_finite() & self.z.is_finite()
    }

    /// Mask of the lanes that are unit to within `4ε`
    /// (`|‖w‖² − 1| ≤ 4ε`, the microfacet hot path's `is_unit`).
    #[inline(always)]
    pub(crate) fn is_unit(self) -> Vf {
        (self.length_squared() - Vf::ONE)
            .abs()
            .simd_le(Vf::splat(4.0 * f32::EPSILON))
    }

    /// The hot part of the microfacet `unitize` lane-wise: `w` unchanged
    /// where it is unit to within `4ε`, else `w · (1/√‖w‖²)` where
    /// `‖w‖² ∈ [10⁻³⁰, 10³⁰]` (the scalar's second branch); returns the
    /// result and the mask of the lanes outside both (the scalar's rescaling
    /// or degenerate branch: the caller hands them back).
    #[inline(always)]
    pub(crate) fn unitize(self) -> (Dirs, Vf) {
        let l2 = self.length_squared();
        let unit = (l2 - Vf::ONE).abs().simd_le(Vf::splat(4.0 * f32::EPSILON));
        let in_range = l2.simd_ge(Vf::splat(1e-30)) & l2.simd_le(Vf::splat(1e30));
        let r = Vf::ONE / l2.sqrt();
        let scaled = Dirs {
            x: self.x * r,
            y: self.y * r,
            z: self.z * r,
        };
        let pick = |a: Vf, b: Vf| unit.select(a, b);
        let out = Dirs {
            x: pick(self.x, scaled.x),
            y: pick(self.y, scaled.y),
            z: pick(self.z, scaled.z),
        };
        (out, !(unit | in_range))
    }

    /// [`unitize`](Self::unitize) with a shortcut for the usual case that
    /// every lane is already unit (a re-normalisation of a normalised
    /// vector): then `w` itself and no cold lane, with no square root or
    /// division.
    #[inline(always)]
    pub(crate) fn unitize_again(self) -> (Dirs, Vf) {
        let l2 = self.length_squared();
        let unit = (l2 - Vf::ONE).abs().simd_le(Vf::splat(4.0 * f32::EPSILON));
        if unit.all() {
            (self, Vf::ZERO)
        } else {
            self.unitize()
        }
    }

    /// `radiometry::frame::try_normalize` lane-wise: `(w/√‖w‖², mask)` where
    /// the mask holds `‖w‖² ∈ (0, ∞)` (the lanes `try_normalize` accepts).
    #[inline(always)]
    pub(crate) fn try_normalize(self) -> (Dirs, Vf) {
        let l2 = self.length_squared();
        let ok = l2.simd_gt(Vf::ZERO) & l2.is_finite();
        (self.div(l2.sqrt()), ok)
    }
}

/// Bit `k` set when lane `k` is off the Phong family's hot path (a
/// direction that is not unit to within `4ε`, [`Dirs::is_unit`]): the
/// driver recomputes it with the scalar method, whose cold path normalises.
#[inline(always)]
pub(crate) fn cold_lanes(wi: Dirs, wo: Dirs) -> u32 {
    (!(wi.is_unit() & wo.is_unit())).to_bitmask()
}

/// `finite_nonneg`: `x > 0 ? min(x, f32::MAX) : 0` (NaN → 0).
#[inline(always)]
pub(crate) fn finite_nonneg(x: Vf) -> Vf {
    // `fast_min` returns its second operand for NaN; those lanes are masked.
    x.simd_gt(Vf::ZERO)
        .select(x.fast_min(Vf::splat(f32::MAX)), Vf::ZERO)
}

/// `(1 − δ)^n` for `δ = 1 − cos` (`pow_one_minus` of the scalar code):
/// `0` for `δ ≥ 1` or NaN, `1` for `δ ≤ 0`, else `exp(n · log1p(−δ))` with
/// the bit-exact ports [`expf`] and [`log1pf`]: bit-identical to the scalar
/// `libm::expf(n * libm::log1pf(-delta))`.
#[inline(always)]
pub(crate) fn pow_one_minus(delta: Vf, n: f32) -> Vf {
    let zero = Vf::ZERO;
    let one = Vf::ONE;
    let lobe = expf(Vf::splat(n) * log1pf(-delta));
    let lobe = delta.simd_le(zero).select(one, lobe);
    (delta.simd_ge(one) | delta.is_nan()).select(zero, lobe)
}

/// The `f64` vector holding half of a [`Vf`] (`f64x8` with AVX-512, else
/// `f64x4`): for kernels whose scalar code computes in `f64`.
#[cfg(target_feature = "avx512f")]
pub(crate) type Vd = wide::f64x8;
/// The `f64` vector holding half of a [`Vf`].
#[cfg(not(target_feature = "avx512f"))]
pub(crate) type Vd = wide::f64x4;

/// Lanes per [`Vd`].
const HALF: usize = LANES / 2;

/// `x as f64` per lane (exact), in two halves.
#[inline(always)]
pub(crate) fn widen(x: Vf) -> [Vd; 2] {
    let a = x.to_array();
    [
        Vd::new(core::array::from_fn(|k| a[k] as f64)),
        Vd::new(core::array::from_fn(|k| a[HALF + k] as f64)),
    ]
}

/// `d as f32` per lane (round to nearest, as the scalar `as f32`).
#[inline(always)]
pub(crate) fn narrow(d: [Vd; 2]) -> Vf {
    let (a, b) = (d[0].to_array(), d[1].to_array());
    Vf::new(core::array::from_fn(|k| {
        if k < HALF { a[k] as f32 } else { b[k - HALF] as f32 }
    }))
}

/// The integer vectors of the same width as [`Vf`] (bit manipulation in
/// the `libm` ports below).
#[cfg(target_feature = "avx512f")]
type Vi = wide::i32x16;
#[cfg(not(target_feature = "avx512f"))]
type Vi = wide::i32x8;
#[cfg(target_feature = "avx512f")]
type Vu = wide::u32x16;
#[cfg(not(target_feature = "avx512f"))]
type Vu = wide::u32x8;

/// `i32` lanes to `f32` (exact for `|k| < 2²⁴`).
#[inline(always)]
fn int_to_float(k: Vi) -> Vf {
    k.round_float()
}

/// The bits of each lane (`f32::to_bits`).
#[inline(always)]
fn to_bits(x: Vf) -> Vi {
    wide::bytemuck::cast(x)
}

/// Lanes from bits (`f32::from_bits`).
#[inline(always)]
fn from_bits(i: Vi) -> Vf {
    wide::bytemuck::cast(i)
}

/// An integer mask (all ones / all zeros per lane) as a float mask.
#[inline(always)]
fn fmask(m: Vi) -> Vf {
    wide::bytemuck::cast(m)
}

/// `a >> b` per lane (arithmetic; `b ∈ [0, 31]`).
#[inline(always)]
fn shr_var(a: Vi, b: Vi) -> Vi {
    a >> wide::bytemuck::cast::<Vi, Vu>(b)
}

/// `x` with the low bits cleared: `f32::from_bits(x.to_bits() & mask)`.
#[inline(always)]
fn clear_low(x: Vf, mask: u32) -> Vf {
    from_bits(to_bits(x) & Vi::splat(mask as i32))
}

/// `scalbnf(y, k)` of libm (`y · 2^k` with one rounding) for integer-valued
/// `k ∈ [−228, 254]` and `y` normal: a prescale by `2^-102` below `−126`
/// or by `2^127` above `127` (exact), then one multiply by `2^{k₂}`,
/// `k₂ ∈ [−126, 127]`, as libm's `scalbn`.
#[inline(always)]
fn scalbnf(y: Vf, k: Vf) -> Vf {
    let one = Vf::ONE;
    let low = k.simd_lt(Vf::splat(-126.0));
    let high = k.simd_gt(Vf::splat(127.0));
    let pre = low.select(
        Vf::splat(f32::from_bits(0x0c80_0000)),
        high.select(Vf::splat(f32::from_bits(0x7f00_0000)), one),
    );
    let k2 = low.select(k + Vf::splat(102.0), high.select(k - Vf::splat(127.0), k));
    let k2 = k2.max(Vf::splat(-126.0)).min(Vf::splat(127.0));
    let pow2 = from_bits((k2 + Vf::splat(127.0)).trunc_int() << 23_u32);
    (y * pre) * pow2
}

/// `libm::expf` lane-wise, **bit for bit** (a port of its algorithm, FreeBSD
/// `e_expf.c`, with the same operations in the same order; no FMA):
///
/// * `|x| ≤ 2⁻¹⁴`: `1 + x`;
/// * otherwise `k = round(x/ln 2)` (`trunc(x/ln 2 ± 1/2)`, or `±1` for
///   `|x| ≤ 1.5 ln 2`, or `0` for `|x| ≤ ln 2/2`), `r = (x − k ln2_hi) − k ln2_lo`,
///   the Remez form `c = r − r²(P1 + r² P2)`, `y = 1 + (r c/(2 − c) − lo + hi)`
///   and `scalbnf(y, k)` — a product by `2^k` with one rounding, formed here
///   as `(y · 2^{k₁}) · 2^{k₂}` with an exact first factor;
/// * `x ≥ 88.7228`: `+∞`; `x ≤ −103.972`: `0`; NaN: NaN.
///
/// The `brdfs` unit test `expf_is_libm_bit_for_bit` compares it with
/// `libm::expf` on every `f32` in `[−104, 89]` with a stride and on the
/// special values.
#[inline(always)]
pub(crate) fn expf(x: Vf) -> Vf {
    // libm's constants, by their bits.
    const LN2_HI: f32 = f32::from_bits(0x3f31_7200); // 6.9314575195e-01
    const LN2_LO: f32 = f32::from_bits(0x35bf_be8e); // 1.4286067653e-06
    const INV_LN2: f32 = f32::from_bits(0x3fb8_aa3b); // 1.4426950216e+00
    const P1: f32 = f32::from_bits(0x3e2a_aa8f); // 1.6666625440e-1
    const P2: f32 = f32::from_bits(0xbb35_5215); // -2.7667332906e-3
    let (zero, one) = (Vf::ZERO, Vf::ONE);
    let ax = x.abs();
    let neg = x.is_sign_negative();
    let above = |bits: u32| ax.simd_gt(Vf::splat(f32::from_bits(bits)));
    // k as a float: |x| > 1.5 ln2, |x| > ln2/2, else 0.
    let half = neg.select(Vf::splat(-0.5), Vf::splat(0.5));
    let k_big = (Vf::splat(INV_LN2) * x + half).trunc();
    let k_mid = neg.select(-one, one);
    let k = above(0x3f85_1592).select(k_big, above(0x3eb1_7218).select(k_mid, zero));
    // (For k = 0 these are hi = x, lo = 0, r = x, exactly as the scalar branch.)
    let hi = x - k * Vf::splat(LN2_HI);
    let lo = k * Vf::splat(LN2_LO);
    let r = hi - lo;
    let rr = r * r;
    let c = r - rr * (Vf::splat(P1) + rr * Vf::splat(P2));
    let y = one + (r * c / (Vf::splat(2.0) - c) - lo + hi);
    // k ∈ [−150, 128].
    let v = scalbnf(y, k);
    // Special cases, in the scalar order of precedence.
    let v = above(0x3900_0000).select(v, one + x);
    let v = (!neg & ax.simd_ge(Vf::splat(f32::from_bits(0x42b1_7218)))).select(Vf::splat(f32::INFINITY), v);
    let v = (neg & ax.simd_ge(Vf::splat(f32::from_bits(0x42cf_f1b5)))).select(zero, v);
    x.is_nan().select(x, v)
}

/// `libm::log1pf` lane-wise, **bit for bit** (a port of its algorithm,
/// FreeBSD `s_log1pf.c`, same operations in the same order; no FMA):
///
/// * `|x| < 2⁻²⁴`: `x`; `x = −1`: `−∞`; `x < −1`, NaN: NaN; `+∞`: `+∞`;
/// * `−0.2929 ≤ x < 0.4142` (`√2/2 ≤ 1 + x < √2`): `k = 0`, `f = x`, `c = 0`;
/// * otherwise `u = 1 + x` is split as `2^k (1 + f)` with `1 + f ∈ [√2/2, √2)`
///   by integer operations on its bits, and `c` is the rounding error of
///   `1 + x` divided by `u` (0 for `k ≥ 25`);
/// * `s = f/(2 + f)`, the Remez polynomial `R(s²)` (`LG1…LG4`) and
///   `log1p = s (f²/2 + R) + (k ln2_lo + c) − f²/2 + f + k ln2_hi`.
///
/// The `brdfs` unit test `log1pf_is_libm_bit_for_bit` compares it with
/// `libm::log1pf` on every 7th `f32` of `[−1, 2¹²⁸)` and on the special
/// values.
#[inline(always)]
pub(crate) fn log1pf(x: Vf) -> Vf {
    const LN2_HI: f32 = f32::from_bits(0x3f31_7180); // 6.9313812256e-01
    const LN2_LO: f32 = f32::from_bits(0x3717_f7d1); // 9.0580006145e-06
    const LG1: f32 = f32::from_bits(0x3f2a_aaaa); // 0.66666662693
    const LG2: f32 = f32::from_bits(0x3ecc_ce13); // 0.40000972152
    const LG3: f32 = f32::from_bits(0x3e91_e9ee); // 0.28498786688
    const LG4: f32 = f32::from_bits(0x3e78_9e26); // 0.24279078841
    let (zero, one) = (Vf::ZERO, Vf::ONE);
    // √2/2 ≤ 1 + x < √2: no reduction.
    let k0 =
        x.simd_lt(Vf::splat(f32::from_bits(0x3ed4_13d0))) & x.simd_ge(Vf::splat(f32::from_bits(0xbe95_f619)));
    // u = 1 + x = 2^k (1 + f) by the bits of u (u > 0 on every kept lane).
    let u = one + x;
    let iu: Vi = wide::bytemuck::cast::<Vf, Vi>(u) + Vi::splat(0x3f80_0000 - 0x3f35_04f3);
    let k_int = (iu >> 23_u32) - Vi::splat(0x7f);
    let k = int_to_float(k_int);
    let c = k.simd_ge(Vf::splat(2.0)).select(one - (u - x), x - (u - one)) / u;
    let c = k.simd_lt(Vf::splat(25.0)).select(c, zero);
    let m: Vf = wide::bytemuck::cast((iu & Vi::splat(0x007f_ffff)) + Vi::splat(0x3f35_04f3));
    let f = k0.select(x, m - one);
    let c = k0.select(zero, c);
    let dk = k0.select(zero, k);
    let s = f / (Vf::splat(2.0) + f);
    let z = s * s;
    let w = z * z;
    let t1 = w * (Vf::splat(LG2) + w * Vf::splat(LG4));
    let t2 = z * (Vf::splat(LG1) + w * Vf::splat(LG3));
    let r = t2 + t1;
    let hfsq = Vf::splat(0.5) * f * f;
    let v = s * (hfsq + r) + (dk * Vf::splat(LN2_LO) + c) - hfsq + f + dk * Vf::splat(LN2_HI);
    // Special cases, in the scalar order of precedence.
    let v = x
        .abs()
        .simd_lt(Vf::splat(f32::from_bits(0x3380_0000)))
        .select(x, v);
    let v = x.simd_eq(Vf::splat(f32::INFINITY)).select(x, v);
    let v = x.simd_eq(-one).select(Vf::splat(f32::NEG_INFINITY), v);
    (x.simd_lt(-one) | x.is_nan()).select(Vf::splat(f32::NAN), v)
}

/// `libm::powf(x, y)` lane-wise, **bit for bit**, for a lane-constant
/// exponent `y` (a port of libm's algorithm, FreeBSD `e_powf.c`, restricted
/// to `x ≥ 0` — negative `x` lanes are unspecified):
///
/// * the scalar special cases of `y` first (`y = 0`: 1; `y = ±1`: `x`,
///   `1/x`; `y = 2`: `x·x`; `y = 1/2`: `√x`), and `x ∈ {0, 1, +∞}`, NaN;
/// * otherwise `log2 x = n + log2(1 + f)` from the bits of `x` (subnormal `x`
///   prescaled by `2²⁴`), `1 + f` reduced around 1 or 1.5, the odd series in
///   `s = (x − bp)/(x + bp)`, carried as a head with 12 trailing zero bits
///   and a tail; `y log2 x` likewise as `p_h + p_l`; overflow to `+∞` and
///   underflow to 0 by libm's tests; `2^{p_h + p_l}` from an integer part
///   (integer operations on the bits) and the Remez polynomial of
///   `exp`, scaled by `2^n` (`scalbnf` where the result is subnormal).
///
/// Exponents that are not finite or exceed `2²⁷` in magnitude (libm's
/// `|1 − x|`-series branch) go through `libm::powf` per lane. The unit test
/// `powf_is_libm_bit_for_bit` compares with `libm::powf` on every 7th `f32`
/// of `(0, 1]` for several `y` and on a sparser grid up to `f32::MAX`.
#[inline(always)]
pub(crate) fn powf(x: Vf, y: f32) -> Vf {
    const DP_H1: f32 = f32::from_bits(0x3f15_c000); // 5.84960938e-01
    const DP_L1: f32 = f32::from_bits(0x35d1_cfdc); // 1.56322085e-06
    const L1: f32 = f32::from_bits(0x3f19_999a);
    const L2: f32 = f32::from_bits(0x3edb_6db7);
    const L3: f32 = f32::from_bits(0x3eaa_aaab);
    const L4: f32 = f32::from_bits(0x3e8b_a305);
    const L5: f32 = f32::from_bits(0x3e6c_3255);
    const L6: f32 = f32::from_bits(0x3e53_f142);
    const P1: f32 = f32::from_bits(0x3e2a_aaab);
    const P2: f32 = f32::from_bits(0xbb36_0b61);
    const P3: f32 = f32::from_bits(0x388a_b355);
    const P4: f32 = f32::from_bits(0xb5dd_ea0e);
    const P5: f32 = f32::from_bits(0x3331_bb4c);
    const LG2: f32 = f32::from_bits(0x3f31_7218);
    const LG2_H: f32 = f32::from_bits(0x3f31_7200);
    const LG2_L: f32 = f32::from_bits(0x35bf_be8c);
    const OVT: f32 = 4.299_566_6e-8; // −(128 − log2(ovfl + ½ulp))
    const CP: f32 = f32::from_bits(0x3f76_384f); // 2/(3 ln 2)
    const CP_H: f32 = f32::from_bits(0x3f76_4000);
    const CP_L: f32 = f32::from_bits(0xb8f6_23c6);
    let (zero, one) = (Vf::ZERO, Vf::ONE);
    let si = |v: i32| Vi::splat(v);
    // The scalar branches on y, in libm's order (x = 1 gives 1 in each).
    if y == 0.0 {
        return one;
    }
    if y.is_nan() || y.abs() > 134_217_728.0 {
        let xs = x.to_array();
        return Vf::new(core::array::from_fn(|k| libm::powf(xs[k], y)));
    }
    if y == 1.0 {
        return x;
    }
    if y == -1.0 {
        return one / x;
    }
    if y == 2.0 {
        return x * x;
    }
    if y == 0.5 {
        return x.sqrt();
    }
    // log2 x = n + log2(ax), ax ∈ [√2/2·…, …) around bp ∈ {1, 1.5}.
    let ix0 = to_bits(x);
    let sub = ix0.simd_lt(si(0x0080_0000));
    let ix1 = to_bits(fmask(sub).select(x * Vf::splat(16_777_216.0), x));
    let jm = ix1 & si(0x007f_ffff);
    let k1 = jm.simd_gt(si(0x001c_c471)) & jm.simd_lt(si(0x005d_b3d7));
    let k_up = !jm.simd_lt(si(0x005d_b3d7));
    let n = sub.select(si(-24), si(0)) + ((ix1 >> 23_u32) - si(0x7f)) + k_up.select(si(1), si(0));
    let ix = (jm | si(0x3f80_0000)) - k_up.select(si(0x0080_0000), si(0));
    let ax = from_bits(ix);
    let k1f = fmask(k1);
    let bp = k1f.select(Vf::splat(1.5), one);
    let dp_h = k1f.select(Vf::splat(DP_H1), zero);
    let dp_l = k1f.select(Vf::splat(DP_L1), zero);
    let u = ax - bp;
    let v = one / (ax + bp);
    let s = u * v;
    let s_h = clear_low(s, 0xffff_f000);
    let t_h = from_bits(
        (((ix >> 1_u32) & si(0xffff_f000_u32 as i32)) | si(0x2000_0000))
            + si(0x0040_0000)
            + k1.select(si(1 << 21), si(0)),
    );
    let t_l = ax - (t_h - bp);
    let s_l = v * ((u - s_h * t_h) - s_h * t_l);
    let s2 = s * s;
    let sp = |c: f32| Vf::splat(c);
    let r = s2 * s2 * (sp(L1) + s2 * (sp(L2) + s2 * (sp(L3) + s2 * (sp(L4) + s2 * (sp(L5) + s2 * sp(L6))))));
    let r = r + s_l * (s_h + s);
    let s2 = s_h * s_h;
    let three = sp(3.0);
    let t_h = clear_low(three + s2 + r, 0xffff_f000);
    let t_l = r - ((t_h - three) - s2);
    let u = s_h * t_h;
    let v = s_l * t_h + t_l * s;
    let p_h = clear_low(u + v, 0xffff_f000);
    let p_l = v - (p_h - u);
    let z_h = sp(CP_H) * p_h;
    let z_l = sp(CP_L) * p_h + p_l * sp(CP) + dp_l;
    let t = int_to_float(n);
    let t1 = clear_low(((z_h + z_l) + dp_h) + t, 0xffff_f000);
    let t2 = z_l - (((t1 - t) - dp_h) - z_h);
    // y log2 x = p_h + p_l with y split as y1 (12 trailing zero bits) + rest.
    let y1 = f32::from_bits(y.to_bits() & 0xffff_f000);
    let p_l = sp(y - y1) * t1 + sp(y) * t2;
    let p_h = sp(y1) * t1;
    let z = p_l + p_h;
    let j = to_bits(z);
    let at_max = j.simd_eq(si(0x4300_0000));
    let over = fmask(j.simd_gt(si(0x4300_0000))) | (fmask(at_max) & (p_l + sp(OVT)).simd_gt(z - p_h));
    let under = fmask(j.simd_lt(si(0)) & (j & si(0x7fff_ffff)).simd_gt(si(0x4316_0000)))
        | (fmask(j.simd_eq(si(0xc316_0000_u32 as i32))) & p_l.simd_le(z - p_h));
    // 2^z: integer part n (nearest) from the bits of z, fraction by the
    // Remez polynomial.
    let i = j & si(0x7fff_ffff);
    let k = (i >> 23_u32) - si(0x7f);
    let big = i.simd_gt(si(0x3f00_0000));
    let nn = j + shr_var(si(0x0080_0000), k + si(1));
    let k = ((nn & si(0x7fff_ffff)) >> 23_u32) - si(0x7f);
    let tt = from_bits(nn & !shr_var(si(0x007f_ffff), k));
    let nn = shr_var((nn & si(0x007f_ffff)) | si(0x0080_0000), si(23) - k);
    let nn = j.simd_lt(si(0)).select(si(0) - nn, nn);
    let n = big.select(nn, si(0));
    let p_h = fmask(big).select(p_h - tt, p_h);
    let t = clear_low(p_l + p_h, 0xffff_8000);
    let u = t * sp(LG2_H);
    let v = (p_l - (t - p_h)) * sp(LG2) + t * sp(LG2_L);
    let z = u + v;
    let w = v - (z - u);
    let t = z * z;
    let t1 = z - t * (sp(P1) + t * (sp(P2) + t * (sp(P3) + t * (sp(P4) + t * sp(P5)))));
    let r = (z * t1) / (t1 - sp(2.0)) - (w + z * w);
    let z = one - (r - z);
    let jz = to_bits(z) + (n << 23_u32);
    let normal = fmask((jz >> 23_u32).simd_gt(si(0)));
    let v = normal.select(from_bits(jz), scalbnf(z, int_to_float(n)));
    let v = over.select(sp(f32::INFINITY), under.select(zero, v));
    // x ∈ {0, 1, +∞} (libm returns |x| for y > 0, 1/|x| for y < 0), NaN.
    let v = x.simd_eq(one).select(one, v);
    let edge = x.simd_eq(zero) | x.simd_eq(sp(f32::INFINITY));
    let v = edge.select(if y > 0.0 { x } else { one / x }, v);
    x.is_nan().select(x, v)
}

/// Stores [`LANES`] spectra `out[k] = S::from_fn(|c| channel(c)[k])`, calling
/// `channel` once per channel. For `S = f32` this is one whole-vector store
/// (a safe `Any` downcast, folded at monomorphisation).
#[inline(always)]
pub(crate) fn store<S: Spectrum>(out: &mut [S; LANES], mut channel: impl FnMut(usize) -> Vf) {
    if let Some(o) = (out as &mut dyn Any).downcast_mut::<[f32; LANES]>() {
        *o = channel(0).to_array();
        return;
    }
    // Channels in groups of at most `GROUP` (a bounded stack buffer).
    const GROUP: usize = 16;
    let mut base = 0;
    while base < S::CHANNELS {
        let m = (S::CHANNELS - base).min(GROUP);
        let mut buf = [[0.0f32; LANES]; GROUP];
        for (c, b) in buf.iter_mut().enumerate().take(m) {
            *b = channel(base + c).to_array();
        }
        for (k, o) in out.iter_mut().enumerate() {
            let old = *o;
            *o = S::from_fn(|c| {
                if c >= base && c < base + m {
                    buf[c - base][k]
                } else {
                    old.channel(c)
                }
            });
        }
        base += m;
    }
}

/// A kernel over [`LANES`] `(ωi, ωo)` pairs with its scalar counterpart.
pub(crate) trait Kernel {
    /// The value per pair.
    type Out;
    /// Writes the [`LANES`] values of one chunk and returns a bit mask of the
    /// lanes it did not handle (bit `k` for lane `k`): the driver recomputes
    /// those with [`one`](Self::one) from the original inputs.
    fn lanes(&self, wi: Dirs, wo: Dirs, out: &mut [Self::Out; LANES]) -> u32;
    /// The scalar value of one pair (the tail, the lanes `lanes` hands back;
    /// what `lanes` must equal).
    fn one(&self, wi: Vec3, wo: Vec3) -> Self::Out;
}

/// Recomputes the lanes of `cold` with `k.one` (rare: the scalar method's
/// cold path), reading the inputs through `get`.
#[cold]
#[inline(never)]
fn fix_cold<K: Kernel>(k: &K, cold: u32, out: &mut [K::Out; LANES], get: impl Fn(usize) -> (Vec3, Vec3)) {
    for (j, o) in out.iter_mut().enumerate() {
        if cold & (1 << j) != 0 {
            let (a, c) = get(j);
            *o = k.one(a, c);
        }
    }
}

/// The inputs and output of one batch call, array-of-structures or
/// structure-of-arrays: `out[k] = f(ωi[k], ωo[k])` for
/// `k < min(len(ωi), len(ωo), len(out))`.
pub(crate) enum Batch<'a, O> {
    /// `&[Vec3]` inputs ([`Brdf::eval_batch`](radiometry::Brdf::eval_batch)).
    Aos(&'a [Vec3], &'a [Vec3], &'a mut [O]),
    /// [`Vec3Soa`] inputs ([`Brdf::eval_batch_soa`](radiometry::Brdf::eval_batch_soa)).
    Soa(Vec3Soa<'a>, Vec3Soa<'a>, &'a mut [O]),
}

impl<O> Batch<'_, O> {
    /// Runs `k` over whole chunks of [`LANES`] and `k.one` over the tail.
    #[inline(always)]
    pub(crate) fn run<K: Kernel<Out = O>>(self, k: &K) {
        match self {
            Batch::Aos(wi, wo, out) => {
                let n = wi.len().min(wo.len()).min(out.len());
                let (wi, wo, out) = (&wi[..n], &wo[..n], &mut out[..n]);
                let (ci, ti) = wi.as_chunks::<LANES>();
                let (co, to) = wo.as_chunks::<LANES>();
                let (cout, tout) = out.as_chunks_mut::<LANES>();
                for ((a, c), o) in ci.iter().zip(co).zip(cout) {
                    let cold = k.lanes(Dirs::from_aos(a), Dirs::from_aos(c), o);
                    if cold != 0 {
                        fix_cold(k, cold, o, |j| (a[j], c[j]));
                    }
                }
                for ((o, &a), &c) in tout.iter_mut().zip(ti).zip(to) {
                    *o = k.one(a, c);
                }
            }
            Batch::Soa(wi, wo, out) => {
                let n = wi.len().min(wo.len()).min(out.len());
                let (wi, wo, out) = (wi.truncate(n), wo.truncate(n), &mut out[..n]);
                let (ix, _) = wi.x.as_chunks::<LANES>();
                let (iy, _) = wi.y.as_chunks::<LANES>();
                let (iz, _) = wi.z.as_chunks::<LANES>();
                let (ox, _) = wo.x.as_chunks::<LANES>();
                let (oy, _) = wo.y.as_chunks::<LANES>();
                let (oz, _) = wo.z.as_chunks::<LANES>();
                let (cout, tout) = out.as_chunks_mut::<LANES>();
                let inputs = ix.iter().zip(iy).zip(iz).zip(ox.iter().zip(oy).zip(oz));
                for ((((a, b), c), ((d, e), f)), o) in inputs.zip(cout) {
                    let cold = k.lanes(Dirs::from_soa(a, b, c), Dirs::from_soa(d, e, f), o);
                    if cold != 0 {
                        let get = |j: usize| (Vec3::new(a[j], b[j], c[j]), Vec3::new(d[j], e[j], f[j]));
                        fix_cold(k, cold, o, get);
                    }
                }
                let start = n - tout.len();
                for (j, o) in (start..n).zip(tout) {
                    let a = Vec3::new(wi.x[j], wi.y[j], wi.z[j]);
                    let c = Vec3::new(wo.x[j], wo.y[j], wo.z[j]);
                    *o = k.one(a, c);
                }
            }
        }
    }

    /// The plain loop `out[k] = f(ωi[k], ωo[k])` (no kernel).
    #[inline(always)]
    pub(crate) fn scalar(self, mut f: impl FnMut(Vec3, Vec3) -> O) {
        match self {
            Batch::Aos(wi, wo, out) => {
                for ((o, &a), &c) in out.iter_mut().zip(wi).zip(wo) {
                    *o = f(a, c);
                }
            }
            Batch::Soa(wi, wo, out) => {
                for ((o, a), c) in out.iter_mut().zip(wi.iter()).zip(wo.iter()) {
                    *o = f(a, c);
                }
            }
        }
    }
}

/// Test support: calls `check` on `values` in chunks of [`LANES`], the last
/// chunk padded with `0.5`.
#[cfg(test)]
pub(crate) fn check_values(check: &dyn Fn(&[f32; LANES]), values: &[f32]) {
    for chunk in values.chunks(LANES) {
        let mut xs = [0.5f32; LANES];
        xs[..chunk.len()].copy_from_slice(chunk);
        check(&xs);
    }
}

/// Test support: calls `check` on every 7th `f32` from 0 to `end` with the
/// given sign bit, for each `(sign, end)`.
#[cfg(test)]
pub(crate) fn sweep(check: &dyn Fn(&[f32; LANES]), ranges: &[(u32, f32)]) {
    sweep_stride(check, ranges, 7)
}

/// [`sweep`] with another stride (a chunk not yet full when a range ends
/// is completed by the next range's values; the last one is dropped).
#[cfg(test)]
pub(crate) fn sweep_stride(check: &dyn Fn(&[f32; LANES]), ranges: &[(u32, f32)], stride: u32) {
    let mut xs = [0.0f32; LANES];
    let mut n = 0;
    for &(sign, end) in ranges {
        let mut bits = 0u32;
        while f32::from_bits(bits) <= end {
            xs[n] = f32::from_bits(bits | sign);
            n += 1;
            if n == LANES {
                check(&xs);
                n = 0;
            }
            bits += stride;
        }
    }
}

/// Test support of the bit-exact ports: asserts that `vector` returns the
/// bits of `scalar` (any NaN for a NaN) in every lane of `xs`.
#[cfg(test)]
pub(crate) fn assert_lanes_match(
    name: &str,
    vector: impl Fn(Vf) -> Vf,
    scalar: impl Fn(f32) -> f32,
    xs: &[f32; LANES],
) {
    let got = vector(Vf::new(*xs)).to_array();
    for (&x, g) in xs.iter().zip(got) {
        let want = scalar(x);
        assert!(
            want.to_bits() == g.to_bits() || (want.is_nan() && g.is_nan()),
            "{name}({x:e} = {:#x}): libm {want:e}, vector {g:e}",
            x.to_bits()
        );
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;
    use std::vec;

    /// `expf` equals `libm::expf` bit for bit: every 7th `f32` of
    /// `[−104, 89]` (both signs; about 150 million values), plus the special
    /// values and the thresholds of the scalar branches ± 1 ulp.
    #[test]
    fn expf_is_libm_bit_for_bit() {
        let mut specials = vec![
            0.0f32,
            -0.0,
            f32::NAN,
            f32::INFINITY,
            f32::NEG_INFINITY,
            f32::MAX,
            f32::MIN,
            f32::MIN_POSITIVE,
            -f32::MIN_POSITIVE,
            1e-45,
            -1e-45,
            1.0,
            -1.0,
        ];
        for bits in [
            0x3900_0000u32,
            0x3eb1_7218,
            0x3f85_1592,
            0x42ae_ac50,
            0x42b1_7218,
            0x42cf_f1b5,
        ] {
            for d in [-2i32, -1, 0, 1, 2] {
                let v = f32::from_bits(bits.wrapping_add_signed(d));
                specials.push(v);
                specials.push(-v);
            }
        }
        let check = |xs: &[f32; LANES]| super::assert_lanes_match("expf", expf, libm::expf, xs);
        check_values(&check, &specials);
        sweep(&check, &[(0, 89.0), (0x8000_0000, 104.0)]);
    }

    /// `powf` equals `libm::powf` bit for bit: every 7th `f32` of `(0, 1]`
    /// for `y = 30`, every 61st for 0.3 and 10⁷, every 997th one of
    /// `(0, f32::MAX]` for more exponents (including subnormal and overflowing
    /// results and libm's special exponents), and the special values of `x`.
    #[test]
    fn powf_is_libm_bit_for_bit() {
        let check_y = |y: f32| {
            move |xs: &[f32; LANES]| {
                let got = powf(Vf::new(*xs), y).to_array();
                for (x, g) in xs.iter().zip(got) {
                    let want = libm::powf(*x, y);
                    assert!(
                        want.to_bits() == g.to_bits() || (want.is_nan() && g.is_nan()),
                        "powf({x:e} = {:#x}, {y:e}): libm {want:e}, vector {g:e}",
                        x.to_bits()
                    );
                }
            }
        };
        sweep(&check_y(30.0), &[(0, 1.0)]);
        for y in [0.3f32, 1e7] {
            sweep_stride(&check_y(y), &[(0, 1.0)], 61);
        }
        let ys = [
            0.0f32,
            1e-30,
            0.001,
            0.5,
            1.0,
            1.5,
            2.0,
            2.5,
            7.25,
            100.0,
            1000.0,
            1e5,
            1.3e8,
            2e8,
            -0.5,
            -1.0,
            -2.0,
            -3.7,
            f32::INFINITY,
        ];
        let xs_special = [
            0.0f32,
            f32::MIN_POSITIVE,
            1e-45,
            1.0,
            f32::MAX,
            f32::INFINITY,
            f32::NAN,
            0.5,
            2.0,
        ];
        for y in ys {
            let check = check_y(y);
            let mut xs = [0.75f32; LANES];
            xs[..xs_special.len().min(LANES)].copy_from_slice(&xs_special[..xs_special.len().min(LANES)]);
            check(&xs);
            let mut n = 0;
            let mut bits = 1u32;
            while bits < 0x7f80_0000 {
                xs[n] = f32::from_bits(bits);
                n += 1;
                if n == LANES {
                    check(&xs);
                    n = 0;
                }
                bits += 997;
            }
        }
    }

    /// `log1pf` equals `libm::log1pf` bit for bit: every 7th `f32` of
    /// `[−1, f32::MAX]` (about 300 million values), the special values and
    /// the branch thresholds ± 2 ulp.
    #[test]
    fn log1pf_is_libm_bit_for_bit() {
        let mut specials = vec![
            0.0f32,
            -0.0,
            f32::NAN,
            -f32::NAN,
            f32::INFINITY,
            f32::NEG_INFINITY,
            f32::MAX,
            f32::MIN,
            -1.0,
            -1.0 - f32::EPSILON,
            -1.0 + f32::EPSILON / 2.0,
            -2.0,
            1e-45,
            -1e-45,
            f32::MIN_POSITIVE,
            -f32::MIN_POSITIVE,
        ];
        for bits in [
            0x3380_0000u32,
            0x3ed4_13d0,
            0xbe95_f619,
            0x3f80_0000,
            0x4b80_0000,
            0x4c00_0000,
        ] {
            for d in [-2i32, -1, 0, 1, 2] {
                let v = f32::from_bits(bits.wrapping_add_signed(d));
                specials.push(v);
                specials.push(-v);
            }
        }
        let check = |xs: &[f32; LANES]| super::assert_lanes_match("log1pf", log1pf, libm::log1pf, xs);
        check_values(&check, &specials);
        sweep(&check, &[(0, f32::MAX), (0x8000_0000, 1.0)]);
    }
}
