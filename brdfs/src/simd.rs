//! Vector `f32` kernels (8 or 16 lanes) behind [`Brdf::eval_batch`],
//! [`Brdf::eval_batch_soa`] and [`Brdf::pdf_batch`] (feature `simd`).
//!
//! This module holds the shared vector math ([`LANES`] directions in
//! structure-of-arrays form, the chunk drivers for array-of-structures and
//! structure-of-arrays input, bit-exact vector ports of `libm`'s `expf` and
//! `log1pf`, spectrum stores); it imports nothing from the plugins. Each
//! plugin's kernel lives next to its scalar code and follows its formula
//! operation for operation:
//!
//! | BRDF | `eval_batch` / `eval_batch_soa` | `pdf_batch` | vs scalar |
//! |---|---|---|---|
//! | [`Microfacet<Ggx, HeightCorrelated, F>`](crate::Microfacet), every Fresnel `F` | GGX `D` (Walter et al. 2007, eq. 33), projected areas `A = cos θ (1 + Λ)`, `V = 1/(4 (cos θo Ai + cos θi Ao − cos θi cos θo))` (Heitz 2014, eq. 99) | `D/(4 A(ωo))` | 0 ulp |
//! | [`Microfacet<Ggx, Separable, F>`](crate::Microfacet), every Fresnel `F` | as above, `V = 1/(4 Ai Ao)` (Heitz 2014, eq. 98) | `D/(4 A(ωo))` | 0 ulp |
//! | [`Microfacet<Beckmann, G, F>`](crate::Microfacet), either `G`, every `F` | Beckmann `D = exp(−tan²θh/α²)/(π α² cos⁴θh)` (Walter et al. 2007, eq. 25) in vector form; `A` per lane through the scalar `projected_area` | `D/(4 A(ωo))` | 0 ulp |
//! | Fresnel of the microfacet kernels: [`NoFresnel`](crate::NoFresnel), [`Schlick`](crate::Schlick) (Schlick 1994, eq. 15), [`Dielectric`](crate::Dielectric), [`Conductor`](crate::Conductor) | vector, per channel | — | 0 ulp |
//! | [`Lambertian<S>`](crate::Lambertian) | horizon and finiteness masks | `cos θi/π` | 0 ulp |
//! | [`ModifiedPhong<S>`](crate::ModifiedPhong) | `kd/π + ks (n+2)/(2π) exp(n log1p(−δ))` (Lafortune & Willems 1994) | `pd cos θi/π + ps (n+1)/(2π) cos^n α` | 0 ulp |
//! | [`BlinnPhong<S>`](crate::BlinnPhong) | `kd/π + ks N(n) cos^n θh` (Blinn 1977) | scalar loop | 0 ulp for `cos θh ≥ 1/2`, else propagated (below) |
//!
//! Every other plugin keeps the scalar-loop defaults of [`Brdf`].
//!
//! # Accuracy
//!
//! **Bit-identical kernels.** The kernels perform the *same* IEEE-754
//! operations as the scalar code, in the same order: `+ − × ÷ √`,
//! comparisons and selects, all correctly rounded in `wide`'s vectors and in
//! scalar `f32` / `libm::sqrtf`; no fused multiply–add, no reciprocal
//! estimates. The transcendentals are bit-exact vector ports of the `libm`
//! functions the scalar code calls — `expf` (FreeBSD `e_expf.c`) and
//! `log1pf` (`s_log1pf.c`), checked against `libm` on every 7th `f32` of
//! their ranges by this module's unit tests — except the `hypot` inside the
//! complex square root of [`Conductor`](crate::Conductor), which is
//! `libm::hypotf` called per lane (it rounds a sum formed in `f64`, and
//! `wide` has no `f64` conversion). Each lane is therefore bit-identical to
//! `eval` / `pdf` of the same pair, on every target: `brdfs/tests/batch.rs`
//! asserts 0 ulp for every such kernel, array-of-structures and
//! structure-of-arrays alike, over proptest cases, hard cases in every lane
//! position and a deterministic sweep of 200 000 pairs (x86_64, SSE2
//! baseline with 8 lanes and `-C target-cpu=native` with AVX-512 and 16
//! lanes).
//!
//! **Propagated tolerance (Blinn–Phong below `cos θh = 1/2`).** There the
//! scalar lobe is `powf(cos θh, n)`; the kernel computes `exp(n ln cos θh)`
//! with `wide`'s polynomial `exp`/`ln`. Every other operation is the scalar
//! one, so such a lane differs from `eval` only by that rounding: relative
//! `≤ 8 (1 + |y|) 2⁻²⁴` with `y = n ln cos θh` (`|y|` is the condition number
//! of `exp(y)`), plus an absolute `10⁻⁴⁴ (1 + ks N(n))` where the lobe is
//! subnormal; measured worst over the sweep 2.1 of these units. Structural
//! zeros (horizon, degenerate input) are exact.
//!
//! # Special inputs
//!
//! The microfacet kernels evaluate lanes whose directions are unit to within
//! `4ε` (`|‖ω‖² − 1| ≤ 4ε`, the scalar hot path's test) in vector form and
//! recompute any other lane — non-unit, zero, subnormal, huge, infinite or
//! NaN components: the scalar cold path — with the scalar `eval`/`pdf`, so
//! the special-case handling is the scalar one by construction. The Beckmann
//! kernel also hands back lanes with `cos²θh < 10⁻⁸` (the scalar `D`'s
//! separate grazing form).
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

    /// `radiometry::frame::try_normalize` lane-wise: `(w/√‖w‖², mask)` where
    /// the mask holds `‖w‖² ∈ (0, ∞)` (the lanes `try_normalize` accepts).
    #[inline(always)]
    pub(crate) fn try_normalize(self) -> (Dirs, Vf) {
        let l2 = self.length_squared();
        let ok = l2.simd_gt(Vf::ZERO) & l2.is_finite();
        (self.div(l2.sqrt()), ok)
    }
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

/// `x^n` for `x ∈ (0, 1]` and `n ≥ 0` (`libm::powf` of the scalar code) as
/// `exp(n ln x)` with `wide`'s `ln`/`exp`. `wide`'s `ln` maps subnormal
/// arguments to `−∞`, so those are scaled by `2²⁴` first
/// (`ln x = ln(2²⁴ x) − 24 ln 2`); `n = 0` gives exactly 1 (`powf(x, 0)`).
/// Lanes outside `(0, 1]` are unspecified (the caller masks them).
#[inline(always)]
pub(crate) fn pow_unit(x: Vf, n: f32) -> Vf {
    if n == 0.0 {
        return Vf::ONE;
    }
    let tiny = x.simd_lt(Vf::splat(f32::MIN_POSITIVE));
    let scaled = tiny.select(x * Vf::splat(16_777_216.0), x);
    let ln = scaled.ln() - tiny.select(Vf::splat(24.0 * core::f32::consts::LN_2), Vf::ZERO);
    (Vf::splat(n) * ln).exp()
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
    // scalbnf(y, k), k ∈ [−150, 128]: prescale by 2^-102 below −126 and by
    // 2^127 above 127 (exact), then one rounding multiply by 2^{k₂}.
    let low = k.simd_lt(Vf::splat(-126.0));
    let high = k.simd_gt(Vf::splat(127.0));
    let pre = low.select(
        Vf::splat(f32::from_bits(0x0c80_0000)),
        high.select(Vf::splat(f32::from_bits(0x7f00_0000)), one),
    );
    let k2 = low.select(k + Vf::splat(102.0), high.select(k - Vf::splat(127.0), k));
    // 2^{k₂}: k₂ ∈ [−126, 127] after the prescale on every lane that is kept.
    let k2 = k2.max(Vf::splat(-126.0)).min(Vf::splat(127.0));
    let pow2: Vf = wide::bytemuck::cast(((k2 + Vf::splat(127.0)).trunc_int()) << 23);
    let v = (y * pre) * pow2;
    // Special cases, in the scalar order of precedence.
    let v = above(0x3900_0000).select(v, one + x);
    let v = (!neg & ax.simd_ge(Vf::splat(f32::from_bits(0x42b1_7218)))).select(Vf::splat(f32::INFINITY), v);
    let v = (neg & ax.simd_ge(Vf::splat(f32::from_bits(0x42cf_f1b5)))).select(zero, v);
    x.is_nan().select(x, v)
}

/// The integer vector of the same width as [`Vf`] (bit manipulation in
/// [`log1pf`]).
#[cfg(target_feature = "avx512f")]
type Vi = wide::i32x16;
#[cfg(not(target_feature = "avx512f"))]
type Vi = wide::i32x8;

/// `i32` lanes to `f32` (exact for `|k| < 2²⁴`).
#[inline(always)]
fn int_to_float(k: Vi) -> Vf {
    #[cfg(target_feature = "avx512f")]
    return Vf::from_i32x16(k);
    #[cfg(not(target_feature = "avx512f"))]
    return Vf::from_i32x8(k);
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
        let check = |xs: &[f32; LANES]| {
            let got = expf(Vf::new(*xs)).to_array();
            for (x, g) in xs.iter().zip(got) {
                let want = libm::expf(*x);
                assert!(
                    want.to_bits() == g.to_bits() || (want.is_nan() && g.is_nan()),
                    "expf({x:e} = {:#x}): libm {want:e}, vector {g:e}",
                    x.to_bits()
                );
            }
        };
        for chunk in specials.chunks(LANES) {
            let mut xs = [0.5f32; LANES];
            xs[..chunk.len()].copy_from_slice(chunk);
            check(&xs);
        }
        sweep(&check, &[(0, 89.0), (0x8000_0000, 104.0)]);
    }

    /// Calls `check` on every 7th `f32` from 0 to `end` with the given sign
    /// bit, for each `(sign, end)`.
    fn sweep(check: &dyn Fn(&[f32; LANES]), ranges: &[(u32, f32)]) {
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
                bits += 7;
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
        let check = |xs: &[f32; LANES]| {
            let got = log1pf(Vf::new(*xs)).to_array();
            for (x, g) in xs.iter().zip(got) {
                let want = libm::log1pf(*x);
                assert!(
                    want.to_bits() == g.to_bits() || (want.is_nan() && g.is_nan()),
                    "log1pf({x:e} = {:#x}): libm {want:e}, vector {g:e}",
                    x.to_bits()
                );
            }
        };
        for chunk in specials.chunks(LANES) {
            let mut xs = [0.5f32; LANES];
            xs[..chunk.len()].copy_from_slice(chunk);
            check(&xs);
        }
        sweep(&check, &[(0, f32::MAX), (0x8000_0000, 1.0)]);
    }
}
