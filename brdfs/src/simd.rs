//! Vector `f32` kernels (8 or 16 lanes) behind [`Brdf::eval_batch`],
//! [`Brdf::eval_batch_soa`], [`Brdf::pdf_batch`] and
//! [`Brdf::sample_batch`] (feature `simd`).
//!
//! This module holds the shared vector math ([`LANES`] directions in
//! structure-of-arrays form, the chunk drivers for array-of-structures and
//! structure-of-arrays input, bit-exact vector ports of `libm`'s `expf`,
//! `log1pf`, `powf`, `logf`, `expm1f` and `acosf` and of the crate's own `sincos_turn`, `f32` ↔ `f64` lane conversions, spectrum
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
//! | [`Eon<S>`](crate::Eon), [`Fon<S>`](crate::Fon), [`OrenNayar<S>`](crate::OrenNayar) | `(ρ/π) A (1 + σ s/t)` (Fujii 2012 in the form of Portsmouth, Kutz & Hill 2025; pbrt-v3's `A + B s/t` for the classic model); EON's lobe `k_ms (c₁ − G(μi)/π)⁺ (c₁ − G(μo)/π)⁺` with `G` from `acos` (Portsmouth, Kutz & Hill 2025, Listing 1, `E_FON_exact`); `ωo`'s factor computed once when every lane has the same `cos θo` | `(1 − p_u) cos θi/π + p_u/(2π)` | 0 ulp |
//! | `sample_batch` of [`Eon<S>`](crate::Eon), [`Fon<S>`](crate::Fon), [`OrenNayar<S>`](crate::OrenNayar) | the cosine/uniform mixture: uniform hemisphere (`cos θ = u₀/p_u`) or Malley's cosine-weighted concentric map (Shirley & Chiu 1997; the Phong family's warp), pdf and `f_r cos θi/pdf` of the normalised `ωi` | — | 0 ulp (`wi`, pdf, weight; same `None`s) |
//! | `directional_albedo_batch` of a [prepared](radiometry::Brdf::with_prepared_albedo) [`Microfacet<Ggx, HeightCorrelated, Dielectric>`](crate::Microfacet) (also through [`Achromatic`](crate::microfacet::Achromatic)), `η > 1` outside the first roughness cell | the global tables' read of `E_F = E₁ R` (`crate::microfacet::fresnel_table`): each row's coordinate `√μ'` (two roots and a division) and the ratio's `√μ` in vector form, the cells' entries per lane, the Catmull–Rom and bilinear sums in vector form | — | 0 ulp |
//! | `directional_albedo_batch` of [`Eon<S>`](crate::Eon) | `ρ E_FON + ρ_ms (1 − E_FON)` with `G(μo)/π` from the vector `acosf` | — | 0 ulp |
//! | [`OpenPbr<S>`](crate::OpenPbr) `eval_batch`, `eval_batch_soa`, `pdf_batch`, `sample_batch` | in chunks of 32: the lobes' own kernels at the unit directions (`sample_batch`: each GGX lobe's sampling kernel over the elements that pick it), the layers' albedos at `μo` (and `E_s(μi)`) in lanes, the layering and the mixture density per element | | 0 ulp (`sample_batch`: `wi`, pdf, weight; same `None`s) |
//!
//! `radiometry::compose::Coated`'s batch paths likewise run its lobes'
//! kernels and the top's `directional_albedo_batch` in chunks (with this
//! feature, vector kernels for the crate's lobes). Every other plugin keeps
//! the scalar-loop defaults of [`Brdf`].
//!
//! # Accuracy
//!
//! **Bit-identical kernels.** The kernels perform the *same* IEEE-754
//! operations as the scalar code, in the same order: `+ − × ÷ √`,
//! comparisons and selects, all correctly rounded in `wide`'s vectors and in
//! scalar `f32` / [`radiometry::math::sqrtf`] (bit for bit `libm::sqrtf`); no fused multiply–add, no reciprocal
//! estimates. The transcendentals are bit-exact vector ports of the
//! functions the scalar code calls — of `libm`: `expf` (FreeBSD `e_expf.c`), `log1pf`
//! (`s_log1pf.c`), `powf` (`e_powf.c`), `logf` (`e_logf.c`), `expm1f` (`s_expm1f.c`)
//! and `acosf` (`e_acosf.c`; as musl has them all);
//! of this project: [`radiometry::math::sincos_turn`] (the samplers' azimuths);
//! with integer operations on the
//! bits through `wide`'s integer vectors, checked against the scalar functions by this
//! module's unit tests (one file per function under `simd/`, with its test) on every 7th `f32` of their ranges (with `RADIOMETRY_FULL_SWEEP=1`, as CI runs them; every 61st in a plain `cargo test`) (`powf`: for
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
//! the same inputs; for EON, FON and the classic Oren–Nayar (`f32`, RGB, 4
//! channels, `σ` from 0 to 1) 100 000 random `(ωo, u)` per roughness, the
//! hard cases and proptest cases with random `σ`. EON's `G(μ)/π` (with the
//! vector `acosf`) is also compared with the scalar function on every 7th
//! `f32` of `[0, 1]` by its own unit test.
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
//! (finiteness; `try_normalize`'s `‖w‖² ∈ (0, ∞)`) lane-wise. The rough
//! diffuse kernels normalise both directions lane-wise on the two hot
//! branches of the scalar `unitize` (unit already, or `‖w‖² ∈ [10⁻³⁰,
//! 10³⁰]`) and hand back the other lanes, in `eval`, `pdf` and `sample`
//! alike. A tail of `len % LANES` elements goes through the scalar
//! `eval`/`pdf`.
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
//! scalar value). Sixteen lanes halve the instructions per element.
//!
//! CI runs this crate's unit tests (every plugin's batch = scalar checks,
//! the sweeps of the vector `libm` ports) in both widths: 8 lanes in the
//! default build, and 16 lanes with `RUSTFLAGS="-C
//! target-feature=+avx512f,+avx512bw"` where the CPU has AVX-512 (`wide`
//! 1.7 needs `avx512bw` beside `avx512f`). A unit test asserts that
//! [`LANES`] is 16 exactly when `avx512f` is compiled in, else 8.
//!
//! Per-lane scalar code inside a kernel (the table reads of `Tabulated`)
//! takes its roots in vector form, one instruction for every lane (the same
//! correctly rounded values). The crate's scalar root is
//! [`radiometry::math::sqrtf`], which the compiler encodes in the target's
//! own form: `libm::sqrtf` is a legacy-SSE `sqrtss` in inline assembly on
//! x86, which between AVX instructions, with the upper register state dirty,
//! pays an SSE/AVX transition on Intel cores.
//!
//! No `unsafe` code: only `wide`'s safe API, so the crate keeps
//! `#![forbid(unsafe_code)]`.
//!
//! # Throughput
//!
//! GGX height-correlated, `F = 1`, `α = 0.3`, n = 4096 random pairs in
//! cache, one thread of a shared Intel Xeon (Cascade Lake, AVX-512, 16
//! lanes, `-C target-cpu=native`), example `ggx_guarantee_cost`: the
//! `eval_batch_soa` kernel runs at 0.49× an auto-vectorised loop of the
//! fewest-division formulation with no input checks (one division, two
//! square roots), and a loop that adds the kernel's guarantees to that
//! formulation at 0.41×; the half-vector length correction alone takes the
//! plain loop to 0.54×. `eval_batch` pays for gathering `&[Vec3]` into
//! vectors (0.22× in `radiometry bench`): `wide` has no shuffles, and LLVM
//! builds the vectors with one insert per element; structure-of-arrays
//! input is three plain loads per direction. Figures and the command:
//! `docs/performance.md`.
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

mod acosf;
mod bits;
mod expf;
mod expm1f;
mod log1pf;
mod logf;
mod powf;
mod sample;
mod sincos;

pub(crate) use acosf::acosf;
use bits::{Vi, fmask, from_bits, int_to_float, to_bits};
pub(crate) use expf::expf;
pub(crate) use expm1f::expm1f;
pub(crate) use log1pf::log1pf;
pub(crate) use logf::logf;
pub(crate) use powf::powf;
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

/// The chunk driver of the `directional_albedo_batch` kernels: `lanes(w,
/// o)` on each full chunk of [`LANES`] directions, `one(w)` on the tail, for
/// the first `n = min(len)` elements, after the [batch length
/// rule](radiometry::batch::zero_tail) for the rest of `out`.
#[inline(always)]
pub(crate) fn albedo_chunks<S: radiometry::Spectrum>(
    wo: &[Vec3],
    out: &mut [S],
    mut lanes: impl FnMut(&[Vec3], &mut [S]),
    mut one: impl FnMut(Vec3) -> S,
) {
    let n = wo.len().min(out.len());
    radiometry::batch::zero_tail(out, n);
    let (Some(wo), Some(out)) = (wo.get(..n), out.get_mut(..n)) else {
        return;
    };
    let mut wc = wo.chunks_exact(LANES);
    let mut oc = out.chunks_exact_mut(LANES);
    for (w, o) in (&mut wc).zip(&mut oc) {
        lanes(w, o);
    }
    for (o, &w) in oc.into_remainder().iter_mut().zip(wc.remainder()) {
        *o = one(w);
    }
}

/// The table cells of lane coordinates `s ∈ [0, n − 2]` (already clamped;
/// NaN-free): `i = trunc(s)` per lane as an index, and `i` as `f32` — what
/// the scalar reads compute as `(s as u32) as usize` and `i as f32` (exact
/// for these `s`), in vector form.
#[inline(always)]
pub(crate) fn cells_of(s: Vf) -> ([usize; LANES], Vf) {
    let i = s.fast_trunc_int();
    let idx = i.to_array();
    (core::array::from_fn(|k| idx[k].max(0) as usize), i.round_float())
}

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

impl<O: Default> Batch<'_, O> {
    /// Runs `k` over whole chunks of [`LANES`] and `k.one` over the tail;
    /// outputs past the shortest input are set to zero (the batch length
    /// rule, [`radiometry::batch::zero_tail`]).
    #[inline(always)]
    pub(crate) fn run<K: Kernel<Out = O>>(self, k: &K) {
        match self {
            Batch::Aos(wi, wo, out) => {
                let n = wi.len().min(wo.len()).min(out.len());
                radiometry::batch::zero_tail(out, n);
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
                radiometry::batch::zero_tail(out, n);
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

    /// The plain loop `out[k] = f(ωi[k], ωo[k])` (no kernel), with the same
    /// length rule as [`run`](Self::run).
    #[inline(always)]
    pub(crate) fn scalar(self, mut f: impl FnMut(Vec3, Vec3) -> O) {
        match self {
            Batch::Aos(wi, wo, out) => {
                for ((o, &a), &c) in out.iter_mut().zip(wi).zip(wo) {
                    *o = f(a, c);
                }
                radiometry::batch::zero_tail(out, wi.len().min(wo.len()));
            }
            Batch::Soa(wi, wo, out) => {
                for ((o, a), c) in out.iter_mut().zip(wi.iter()).zip(wo.iter()) {
                    *o = f(a, c);
                }
                radiometry::batch::zero_tail(out, wi.len().min(wo.len()));
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

/// Test support: appends, for each of `bits`, the `f32`s within ±2 ulp of
/// it (by bit pattern), and their negatives too when `both_signs`.
#[cfg(test)]
pub(crate) fn push_near(values: &mut impl Extend<f32>, bits: &[u32], both_signs: bool) {
    for &b in bits {
        for d in -2i32..=2 {
            let v = f32::from_bits(b.wrapping_add_signed(d));
            values.extend([v]);
            if both_signs {
                values.extend([-v]);
            }
        }
    }
}

/// Test support: calls `check` on every [`dense_stride`]-th `f32` from 0 to
/// `end` with the given sign bit, for each `(sign, end)`.
#[cfg(test)]
pub(crate) fn sweep(check: &dyn Fn(&[f32; LANES]), ranges: &[(u32, f32)]) {
    sweep_stride(check, ranges, dense_stride())
}

/// Test support: the stride of the dense sweeps of the bit-exact ports —
/// every 7th `f32` when the environment variable `RADIOMETRY_FULL_SWEEP` is
/// set (CI sets it: about 1.5 × 10⁸ values per unit-exponent range), every
/// 61st (a prime, so every residue of the mantissa bits is still visited;
/// 1.7 × 10⁷ values per range) in a plain `cargo test`, where these sweeps
/// were half of the test run's time. Same assertions either way.
#[cfg(test)]
pub(crate) fn dense_stride() -> u32 {
    extern crate std;
    if std::env::var_os("RADIOMETRY_FULL_SWEEP").is_some() {
        7
    } else {
        61
    }
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

/// The kernel selection: the lane width follows the build's target features.
#[cfg(test)]
mod lane_width {
    use super::{HALF, LANES, Vd, Vf, bits, narrow, widen};
    use core::mem::size_of;

    /// 16 lanes exactly when the build enables AVX-512 (`avx512f`), else 8;
    /// `Vf`, its integer views and the two `f64` halves have that width, and
    /// every lane holds its own value through the vector and `f64` round trips.
    /// CI runs the library tests in both builds (`.ci/run`).
    #[test]
    fn lanes_follow_avx512f() {
        extern crate std;
        let avx512 = cfg!(target_feature = "avx512f");
        let want = if avx512 { 16 } else { 8 };
        std::println!("target_feature avx512f: {avx512}; LANES = {LANES}");
        assert_eq!(LANES, want, "avx512f = {avx512}");
        assert_eq!(size_of::<Vf>(), 4 * want);
        assert_eq!(size_of::<bits::Vi>(), 4 * want);
        assert_eq!(size_of::<bits::Vu>(), 4 * want);
        assert_eq!(HALF, want / 2);
        assert_eq!(size_of::<Vd>(), 8 * (want / 2));
        let xs: [f32; LANES] = core::array::from_fn(|k| k as f32 + 0.25);
        let v = Vf::new(xs);
        assert_eq!(v.to_array(), xs);
        assert_eq!(narrow(widen(v)).to_array(), xs);
        let ints = bits::to_bits(v).to_array();
        assert!((0..LANES).all(|k| ints[k] == xs[k].to_bits() as i32));
        assert_eq!(bits::from_bits(bits::to_bits(v)).to_array(), xs);
    }
}
