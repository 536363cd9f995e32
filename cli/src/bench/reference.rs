//! Reference kernels of `radiometry bench`: what this CPU can do on the same
//! inputs, timed in the same process as the plugins.
//!
//! * [`ggx_scalar`] — GGX written the way one would without the plugin
//!   machinery: a plain indexed loop over AoS [`Vec3`] pairs, no input
//!   checks (no horizon tests, no normalisation of the inputs, no special
//!   cases), `F = 1`, evaluated one pair at a time (the index is opaque to
//!   the optimiser, which would otherwise vectorise the loop and turn the
//!   scalar reference into a second vector one).
//! * [`ggx_soa`] — the same formula over structure-of-arrays slices, a
//!   branch-free indexed loop over `&[f32]` that LLVM auto-vectorises (to
//!   whatever vector width the build's target features allow).
//! * [`stream`] — the memory-stream bound: per element, read the six SoA
//!   components of `wi` and `wo` (24 B) and write one `f32` (4 B).
//! * [`ggx_sample_scalar`], [`ggx_sample_soa`] — GGX visible-normal
//!   sampling with the sample's `pdf` and weight, as a plain scalar loop
//!   over AoS input and as a branch-free loop over SoA slices that LLVM
//!   auto-vectorises: the limit of the `sample` and `sample_batch` paths.
//!
//! # The GGX formula (height-correlated Smith, `F = 1`)
//!
//! The references are written in the formulation with the fewest divisions
//! and square roots known for this function, so that they are the limit of
//! a plain loop, not a textbook transcription. With the **un-normalised**
//! half vector `h = ωi + ωo` (`D` is homogeneous of degree 0 in `h`, so the
//! normalisation cancels):
//!
//! ```text
//! L = |h|²,  d = h_z² (α² − 1) + L  (= α² h_z² + h_x² + h_y²)
//! D = α² L² / (π d²)                                   (Walter et al. 2007, eq. 33, times |h|⁴/|h|⁴)
//! V = G2 / (4 cos θi cos θo)
//!   = 1 / (2 (cos θo √(cos²θi (1 − α²) + α²) + cos θi √(cos²θo (1 − α²) + α²)))
//!                                                      (Heitz 2014, eq. 99 with eq. 86; Filament's
//!                                                       `V_SmithGGXCorrelated`, Karis 2014 / Lagarde 2018)
//! f = D V = (α²/2π) L² / (d² (cos θo √(…i) + cos θi √(…o)))
//! ```
//!
//! one division and two square roots per pair, `0` where a direction is at
//! or below the horizon (a select, no branch).
//!
//! # GGX visible-normal sampling (`F = 1`)
//!
//! Spherical caps (Dupuy & Benyoub 2023, §3) in the stretched configuration
//! (Heitz 2018, JCGT 7(4)), written with every vector scaled by
//! `ℓ = |(α wo_x, α wo_y, wo_z)|` instead of normalised (the sampled normal
//! only matters up to scale), and the pdf and weight from the same
//! quantities (Heitz 2014, eqs. 16 and 99):
//!
//! ```text
//! s    = (α wo_x, α wo_y, wo_z),  ℓ = |s|                   ℓ v = s (v the stretched wo)
//! ℓ(1 − z_c) = u₁ (ℓ + wo_z),  ℓ(1 + z_c) = (1 − u₁)(ℓ + wo_z) + ℓ − wo_z
//! φ = 2π u₀,  ℓ sin θ_c = √(ℓ(1 − z_c) · ℓ(1 + z_c))
//! ℓh   = (ℓ sin θ_c cos φ + s_x, ℓ sin θ_c sin φ + s_y, (1 − u₁)(ℓ + wo_z))    h = c + v
//! m̃    = (α ℓh_x, α ℓh_y, ℓh_z)                                unstretched, not normalised
//! wi   = 2 (wo·m̃)/|m̃|² m̃ − wo
//! pdf  = D(m)/(4 A(wo)) = |m̃|⁴ / (2π α² |ℓh|⁴ (wo_z + ℓ))      A(wo) = cos θo (1 + Λ(wo)) = (wo_z + ℓ)/2
//! w    = G2/G1(wo) = wi_z (wo_z + ℓ) / (wo_z √(wi_z² (1 − α²) + α²) + wi_z ℓ)
//! ```
//!
//! three square roots and two divisions per sample (`pdf` and `w` share one
//! reciprocal of the product of their denominators).
//!
//! `(sin φ, cos φ)` come from [`radiometry::math::sincos_turn`] (the
//! samplers' own: quadrant reduction and Taylor polynomials, branch-free, so
//! the SoA loop vectorises).
//!
//! Valid (and used) only for unit directions strictly above the horizon,
//! which the bench inputs are; anything else gives garbage, not `0`.
//!
//! # The other plugins' own formulas
//!
//! The GGX references measure this CPU; the two below measure what a plain
//! loop of *another plugin's* formula reaches, so that a plugin's speed can
//! also be read against its own arithmetic (`vs_own_ref`). Both call `libm`
//! for the special functions, as a plain loop would.
//!
//! * [`beckmann_scalar`] — Beckmann, height-correlated Smith, `F = 1`, in
//!   the same un-normalised, projected-area form as GGX (four divisions,
//!   two square roots, `libm`'s `expf` three times and `erff` twice):
//!
//!   ```text
//!   h    = wi + wo,  L = |h|²,  x = (h_x² + h_y²)/(α² h_z²)       (tan²θh/α²)
//!   D    = exp(−x) L² / (π α² h_z⁴)                               (Walter et al. 2007, eq. 25)
//!   a(w) = z / (α √(x² + y²))
//!   A(w) = cos θ (1 + Λ(w)) = (z (1 + erf a) + α √(x² + y²) e^{−a²}/√π) / 2
//!                                                                 (Walter et al. 2007, eq. 27, times cos θ)
//!   f    = D / (4 (cos θo A(wi) + cos θi A(wo) − cos θi cos θo))  (Heitz 2014, eq. 99)
//!   ```
//!
//! * [`tabulated_scalar`] — a Rusinkiewicz-grid table (MERL layout,
//!   Matusik et al. 2003) looked up the textbook way (Rusinkiewicz 1998,
//!   §3): `h = normalize(wi + wo)`, `θh = acos h_z`, `φh` from `h`'s azimuth
//!   (its cosine and sine as `h_x, h_y` over `sin θh`), the difference vector
//!   `d = R_y(−θh) R_z(−φh) wi`, `θd = acos d_z`, `φd = atan2(d_y, d_x)`
//!   folded into `[0, π)`; continuous indices `√(θh/(π/2)) Nh`,
//!   `θd/(π/2) Nd`, `φd/π Nφ` (clamped to the last node; `φd` periodic) and
//!   trilinear interpolation of the 8 surrounding values.

use radiometry::batch::Vec3Soa;
use radiometry::glam::Vec3;
use std::f32::consts::PI;

/// The constants of [`ggx_hc`] for one `α`.
#[derive(Clone, Copy)]
struct GgxConsts {
    /// `α²`.
    a2: f32,
    /// `1 − α²`.
    one_minus_a2: f32,
    /// `α² − 1`.
    a2_minus_one: f32,
    /// `α²/(2π)`.
    c: f32,
}

impl GgxConsts {
    fn new(alpha: f32) -> Self {
        let a2 = alpha * alpha;
        GgxConsts {
            a2,
            one_minus_a2: 1.0 - a2,
            a2_minus_one: a2 - 1.0,
            c: a2 / (2.0 * PI),
        }
    }
}

/// The GGX height-correlated `f_r` with `F = 1` of one pair (see the module
/// docs: un-normalised half vector, one division, two square roots), `0`
/// below the horizon, no other checks.
#[inline(always)]
fn ggx_hc(k: GgxConsts, i: [f32; 3], o: [f32; 3]) -> f32 {
    let [xi, yi, zi] = i;
    let [xo, yo, zo] = o;
    let (hx, hy, hz) = (xi + xo, yi + yo, zi + zo);
    let hz2 = hz * hz;
    let l = hx * hx + hy * hy + hz2;
    let d = hz2 * k.a2_minus_one + l;
    let ri = (zi * zi * k.one_minus_a2 + k.a2).sqrt();
    let ro = (zo * zo * k.one_minus_a2 + k.a2).sqrt();
    let f = k.c * (l * l) / (d * d * (zo * ri + zi * ro));
    if zi > 0.0 && zo > 0.0 { f } else { 0.0 }
}

/// `out[k] = f_GGX(wi[k], wo[k])` for `k < out.len()` (panics if an input is
/// shorter): the plain scalar loop over AoS input.
#[inline(never)]
#[allow(clippy::needless_range_loop)] // the indexed loop is the point: it is what a renderer writes
pub fn ggx_scalar(alpha: f32, wi: &[Vec3], wo: &[Vec3], out: &mut [f32]) {
    let n = out.len();
    let (wi, wo) = (&wi[..n], &wo[..n]);
    let c = GgxConsts::new(alpha);
    for k in 0..n {
        // An opaque index keeps LLVM from vectorising across elements: this
        // is the one-pair-at-a-time limit a scalar `eval` loop competes
        // with (the vector limit is `ggx_soa`). It costs one register move.
        let k = std::hint::black_box(k);
        let (i, o) = (wi[k], wo[k]);
        out[k] = ggx_hc(c, [i.x, i.y, i.z], [o.x, o.y, o.z]);
    }
}

/// `out[k] = f_GGX(wi.get(k), wo.get(k))` for `k < out.len()` (panics if an
/// input is shorter): the same formula over SoA slices, written so that
/// LLVM auto-vectorises it (indexed loop over equal-length slices, no
/// branches).
#[inline(never)]
#[allow(clippy::needless_range_loop)]
pub fn ggx_soa(alpha: f32, wi: Vec3Soa<'_>, wo: Vec3Soa<'_>, out: &mut [f32]) {
    let n = out.len();
    let (xi, yi, zi) = (&wi.x[..n], &wi.y[..n], &wi.z[..n]);
    let (xo, yo, zo) = (&wo.x[..n], &wo.y[..n], &wo.z[..n]);
    let c = GgxConsts::new(alpha);
    for k in 0..n {
        out[k] = ggx_hc(c, [xi[k], yi[k], zi[k]], [xo[k], yo[k], zo[k]]);
    }
}

/// The memory-stream bound: `out[k] = x_i + y_i + z_i + x_o + y_o + z_o`
/// (six `f32` read, one written per element) for `k < out.len()`.
#[inline(never)]
#[allow(clippy::needless_range_loop)]
pub fn stream(wi: Vec3Soa<'_>, wo: Vec3Soa<'_>, out: &mut [f32]) {
    let n = out.len();
    let (xi, yi, zi) = (&wi.x[..n], &wi.y[..n], &wi.z[..n]);
    let (xo, yo, zo) = (&wo.x[..n], &wo.y[..n], &wo.z[..n]);
    for k in 0..n {
        out[k] = xi[k] + yi[k] + zi[k] + xo[k] + yo[k] + zo[k];
    }
}

/// One GGX visible-normal sample `(wi, pdf, weight)` of `wo` (see the
/// module docs for the formulas: scaled, never normalised), no checks.
#[inline(always)]
fn ggx_vndf(alpha: f32, k: GgxConsts, o: [f32; 3], u: [f32; 2]) -> ([f32; 3], f32, f32) {
    let [xo, yo, zo] = o;
    // s = (α wo_x, α wo_y, wo_z), ℓ = |s|: ℓ v = s
    let (sx, sy) = (alpha * xo, alpha * yo);
    let l = (sx * sx + sy * sy + zo * zo).sqrt();
    // ℓ h = ℓ c + s on the spherical cap, in cancellation-free forms
    let lpz = l + zo;
    let one_minus = u[1] * lpz;
    let hz = (1.0 - u[1]) * lpz;
    let one_plus = hz + (l - zo);
    let sc = (one_minus * one_plus).sqrt();
    let (sp, cp) = radiometry::math::sincos_turn(u[0]);
    let (hx, hy) = (sc * cp + sx, sc * sp + sy);
    // m̃ = (α h_x, α h_y, h_z); wi = 2 (wo·m̃)/|m̃|² m̃ − wo
    let (mx, my, mz) = (alpha * hx, alpha * hy, hz);
    let mm = mx * mx + my * my + mz * mz;
    let t = 2.0 * (xo * mx + yo * my + zo * mz) / mm;
    let (xi, yi, zi) = (t * mx - xo, t * my - yo, t * mz - zo);
    // pdf = |m̃|⁴ / P, w = zi (wo_z + ℓ) / W, one reciprocal of P·W
    let hh = hx * hx + hy * hy + hz * hz;
    let p = (2.0 * PI) * k.a2 * (hh * hh) * lpz;
    let ri = (zi * zi * k.one_minus_a2 + k.a2).sqrt();
    let w = zo * ri + zi * l;
    let r = 1.0 / (p * w);
    ([xi, yi, zi], (mm * mm) * w * r, zi * lpz * p * r)
}

/// One sample of [`ggx_sample_scalar`]: what a renderer keeps of a sample
/// (written by the timed loop, read only by the tests).
#[derive(Clone, Copy, Debug, Default)]
#[cfg_attr(not(test), allow(dead_code))]
pub struct RefSample {
    pub wi: Vec3,
    pub pdf: f32,
    pub weight: f32,
}

/// `out[k] = ` GGX visible-normal sample of `wo[k]` at `u[k]` for
/// `k < out.len()` (panics if an input is shorter): the plain scalar loop
/// over AoS input (opaque index, as in [`ggx_scalar`]).
#[inline(never)]
#[allow(clippy::needless_range_loop)]
pub fn ggx_sample_scalar(alpha: f32, wo: &[Vec3], u: &[[f32; 2]], out: &mut [RefSample]) {
    let n = out.len();
    let (wo, u) = (&wo[..n], &u[..n]);
    let c = GgxConsts::new(alpha);
    for k in 0..n {
        let k = std::hint::black_box(k);
        let o = wo[k];
        let (wi, pdf, weight) = ggx_vndf(alpha, c, [o.x, o.y, o.z], u[k]);
        out[k] = RefSample {
            wi: Vec3::from_array(wi),
            pdf,
            weight,
        };
    }
}

/// The outputs of [`ggx_sample_soa`]: `wi` by component, `pdf`, weight.
pub struct SampleSoa<'a> {
    pub x: &'a mut [f32],
    pub y: &'a mut [f32],
    pub z: &'a mut [f32],
    pub pdf: &'a mut [f32],
    pub weight: &'a mut [f32],
}

/// The samples of [`ggx_sample_scalar`] over SoA slices (`u0`, `u1` the two
/// sample coordinates) into [`SampleSoa`], for `k < out.x.len()` (panics if
/// a slice is shorter): a branch-free indexed loop LLVM auto-vectorises.
#[inline(never)]
#[allow(clippy::needless_range_loop)]
pub fn ggx_sample_soa(alpha: f32, wo: Vec3Soa<'_>, u0: &[f32], u1: &[f32], out: SampleSoa<'_>) {
    let n = out.x.len();
    let (xo, yo, zo) = (&wo.x[..n], &wo.y[..n], &wo.z[..n]);
    let (u0, u1) = (&u0[..n], &u1[..n]);
    let (ox, oy, oz) = (&mut out.x[..n], &mut out.y[..n], &mut out.z[..n]);
    let (opdf, ow) = (&mut out.pdf[..n], &mut out.weight[..n]);
    let c = GgxConsts::new(alpha);
    for k in 0..n {
        let ([x, y, z], pdf, w) = ggx_vndf(alpha, c, [xo[k], yo[k], zo[k]], [u0[k], u1[k]]);
        ox[k] = x;
        oy[k] = y;
        oz[k] = z;
        opdf[k] = pdf;
        ow[k] = w;
    }
}

/// The Beckmann height-correlated `f_r` with `F = 1` of one pair, no checks
/// (see the module docs). `inv_a2 = 1/α²`, `k = 1/(4π α²)`.
#[inline(always)]
fn beckmann_hc(alpha: f32, inv_a2: f32, k: f32, i: [f32; 3], o: [f32; 3]) -> f32 {
    let [xi, yi, zi] = i;
    let [xo, yo, zo] = o;
    let (hx, hy, hz) = (xi + xo, yi + yo, zi + zo);
    let s = hx * hx + hy * hy;
    let hz2 = hz * hz;
    let l = s + hz2;
    let x = s * inv_a2 / hz2;
    // A(w) = (z (1 + erf a) + α sin θ e^{−a²}/√π) / 2, a = z/(α sin θ)
    let area = |x: f32, y: f32, z: f32| {
        let as_ = alpha * (x * x + y * y).sqrt();
        let a = z / as_;
        0.5 * (z * (1.0 + libm::erff(a)) + as_ * libm::expf(-a * a) * FRAC_1_SQRT_PI)
    };
    let v = zo * area(xi, yi, zi) + zi * area(xo, yo, zo) - zi * zo;
    k * libm::expf(-x) * (l * l) / (hz2 * hz2 * v)
}

/// `1/√π`.
const FRAC_1_SQRT_PI: f32 = 0.564_189_6;

/// `out[k] = f_Beckmann(wi[k], wo[k])` for `k < out.len()` (panics if an
/// input is shorter): the plain scalar loop over AoS input (opaque index, as
/// in [`ggx_scalar`]).
#[inline(never)]
#[allow(clippy::needless_range_loop)]
pub fn beckmann_scalar(alpha: f32, wi: &[Vec3], wo: &[Vec3], out: &mut [f32]) {
    let n = out.len();
    let (wi, wo) = (&wi[..n], &wo[..n]);
    let a2 = alpha as f64 * alpha as f64;
    let (inv_a2, k) = (
        (1.0 / a2) as f32,
        (0.25 * std::f64::consts::FRAC_1_PI / a2) as f32,
    );
    for j in 0..n {
        let j = std::hint::black_box(j);
        let (i, o) = (wi[j], wo[j]);
        out[j] = beckmann_hc(alpha, inv_a2, k, [i.x, i.y, i.z], [o.x, o.y, o.z]);
    }
}

/// `c₁ = 1/2 − 2/(3π)` of FON/EON.
const EON_C1: f32 = 0.5 - 2.0 / (3.0 * std::f32::consts::PI);
/// `c₂ = 2/3 − 28/(15π)`.
const EON_C2: f32 = 2.0 / 3.0 - 28.0 / (15.0 * std::f32::consts::PI);

/// `c₁ − G(μ)/π` (Portsmouth, Kutz & Hill 2025, Listing 1, `E_FON_exact`):
/// `G = sin θ (θ − sin θ cos θ) + (2/3)(sin θ cos θ (1 + sin θ + sin²θ)/(1 + sin θ) − sin θ)`.
#[inline(always)]
fn eon_deficit(mu: f32) -> f32 {
    let sin2 = (1.0 - mu) * (1.0 + mu);
    let sin = sin2.sqrt();
    let theta = libm::acosf(mu);
    let g = sin * (theta - sin * mu) + (2.0 / 3.0) * sin * (mu * (1.0 + sin + sin2) / (1.0 + sin) - 1.0);
    EON_C1 - g * std::f32::consts::FRAC_1_PI
}

/// `out[k] = f_EON(wi[k], wo[k])` for `k < out.len()` (panics if an input is
/// shorter): the plain scalar loop of EON's formula (Portsmouth, Kutz & Hill,
/// JCGT 2025, Listing 1 with `exact = true`), with the fewest operations that
/// compute it —
/// `f = (ρ/π) A (1 + σ s/t) + (ρ_ms/π) A σ (c₁ − G(μi)/π)(c₁ − G(μo)/π)/(c₁ − c₂)`,
/// `s = ωi·ωo − μi μo`, `t = max(μi, μo)` where `s > 0` (else 1), two `acosf`,
/// two square roots — and no checks (unit inputs above the horizon assumed:
/// the bench's).
#[inline(never)]
#[allow(clippy::needless_range_loop)]
pub fn eon_scalar(rho: f32, sigma: f32, wi: &[Vec3], wo: &[Vec3], out: &mut [f32]) {
    let n = out.len();
    let (wi, wo) = (&wi[..n], &wo[..n]);
    let a = 1.0 / (1.0 + EON_C1 * sigma);
    let mean = a * (1.0 + EON_C2 * sigma);
    let loss = a * sigma * (EON_C1 - EON_C2);
    let rho_ms = rho * rho * mean / (1.0 - rho * loss);
    let k_ss = rho * a * std::f32::consts::FRAC_1_PI;
    let k_ms = rho_ms * std::f32::consts::FRAC_1_PI * a * sigma / (EON_C1 - EON_C2);
    for j in 0..n {
        let j = std::hint::black_box(j);
        let (i, o) = (wi[j], wo[j]);
        let s = i.dot(o) - i.z * o.z;
        let s_over_t = if s > 0.0 { s / i.z.max(o.z) } else { s };
        out[j] = k_ss * (1.0 + sigma * s_over_t) + k_ms * eon_deficit(i.z) * eon_deficit(o.z);
    }
}

/// A table on a Rusinkiewicz grid in the MERL layout (flat index
/// `k + Nφ (j + Nd i)`), for [`tabulated_scalar`].
#[derive(Clone, Copy, Debug)]
pub struct Table<'a> {
    pub values: &'a [f32],
    /// `[Nh, Nd, Nφ]`.
    pub dims: [usize; 3],
}

/// The trilinear lookup of one pair, no checks beyond the index clamps
/// (see the module docs).
#[inline(always)]
fn tabulated(t: Table<'_>, i: Vec3, o: Vec3) -> f32 {
    use std::f32::consts::FRAC_PI_2;
    let [nh, nd, np] = t.dims;
    let h = (i + o).normalize();
    let theta_h = libm::acosf(h.z);
    let sin_h = (h.x * h.x + h.y * h.y).sqrt();
    let (cos_p, sin_p) = if sin_h > 0.0 {
        (h.x / sin_h, h.y / sin_h)
    } else {
        (1.0, 0.0)
    };
    // d = R_y(−θh) R_z(−φh) wi
    let (x1, y1) = (cos_p * i.x + sin_p * i.y, cos_p * i.y - sin_p * i.x);
    let (dx, dz) = (h.z * x1 - sin_h * i.z, sin_h * x1 + h.z * i.z);
    let theta_d = libm::acosf(dz.clamp(-1.0, 1.0));
    let mut phi_d = libm::atan2f(y1, dx);
    if phi_d < 0.0 {
        phi_d += PI;
    }
    // Continuous indices, cell and weight per axis.
    let axis = |u: f32, n: usize| {
        let u = u.clamp(0.0, (n - 1) as f32);
        let i0 = u as usize;
        (i0, (i0 + 1).min(n - 1), u - i0 as f32)
    };
    let (h0, h1, th) = axis((theta_h / FRAC_PI_2).sqrt() * nh as f32, nh);
    let (d0, d1, td) = axis(theta_d / FRAC_PI_2 * nd as f32, nd);
    let up = (phi_d / PI * np as f32).clamp(0.0, np as f32);
    let p0 = (up as usize).min(np - 1);
    let (p1, tp) = ((p0 + 1) % np, up - p0 as f32);
    let at = |a: usize, b: usize, c: usize| t.values[c + np * (b + nd * a)];
    let lerp = |a: f32, b: f32, w: f32| a * (1.0 - w) + b * w;
    let row = |a: usize, b: usize| lerp(at(a, b, p0), at(a, b, p1), tp);
    let plane = |a: usize| lerp(row(a, d0), row(a, d1), td);
    lerp(plane(h0), plane(h1), th)
}

/// `out[k]` = the table of `t` at `(wi[k], wo[k])` for `k < out.len()`
/// (panics if an input is shorter or the table shorter than its dims): the
/// plain scalar loop over AoS input (opaque index, as in [`ggx_scalar`]).
#[inline(never)]
#[allow(clippy::needless_range_loop)]
pub fn tabulated_scalar(t: Table<'_>, wi: &[Vec3], wo: &[Vec3], out: &mut [f32]) {
    let n = out.len();
    let (wi, wo) = (&wi[..n], &wo[..n]);
    for k in 0..n {
        let k = std::hint::black_box(k);
        out[k] = tabulated(t, wi[k], wo[k]);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use radiometry::Brdf;
    use radiometry::frame::spherical_direction;
    use radiometry_brdfs::{Ggx, HeightCorrelated, Microfacet, NoFresnel};

    use crate::bench::timing::{InputSet, Inputs};

    /// The bench's own inputs (both sets) at the in-cache size.
    fn bench_inputs() -> [Inputs; 2] {
        InputSet::ALL.map(|set| Inputs::new(4096, set))
    }

    /// Asserts `|got − want| ≤ tol·|want|`.
    fn assert_rel(got: f32, want: f32, tol: f32, what: &str) {
        assert!(
            (got - want).abs() <= tol * want.abs(),
            "{what}: {got:e} vs {want:e} (rel {:e})",
            (got - want).abs() / want.abs()
        );
    }

    /// The reference kernels compute the plugin's `f_r` to a relative 10⁻⁵
    /// on the bench's inputs (both sets), so timing them is timing the same
    /// work.
    #[test]
    fn references_match_the_plugin() {
        let alpha = 0.3;
        let plugin = Microfacet::<_, HeightCorrelated, _>::new(Ggx::new(alpha).unwrap(), NoFresnel);
        for inputs in bench_inputs() {
            let n = inputs.n;
            let (wi, wo) = (inputs.wi(n), inputs.wo(n));
            let (vi, vo) = (inputs.wi_soa(n), inputs.wo_soa(n));
            let mut a = vec![0.0f32; n];
            let mut b = vec![0.0f32; n];
            let mut s = vec![0.0f32; n];
            ggx_scalar(alpha, wi, wo, &mut a);
            ggx_soa(alpha, vi, vo, &mut b);
            stream(vi, vo, &mut s);
            for k in 0..n {
                let want = plugin.eval(wi[k], wo[k]);
                assert!(want > 0.0, "k={k}");
                assert_rel(a[k], want, 1e-5, &format!("scalar k={k}"));
                assert_rel(b[k], want, 1e-5, &format!("soa k={k}"));
                let sum = wi[k].x + wi[k].y + wi[k].z + wo[k].x + wo[k].y + wo[k].z;
                assert!((s[k] - sum).abs() <= 1e-5, "k={k}");
            }
            // Below the horizon the reference gives 0, as the plugin.
            let down = Vec3::new(0.3, 0.1, -0.9).normalize();
            ggx_scalar(alpha, &[down, wi[1]], &[wo[1], down], &mut a[..2]);
            assert_eq!(&a[..2], &[0.0, 0.0]);
        }
    }

    /// The EON reference computes the plugin's `f_r` to a relative 10⁻⁵ on
    /// the bench's inputs (both sets).
    #[test]
    fn eon_reference_matches_the_plugin() {
        use radiometry_brdfs::Eon;
        let plugin = Eon::new(0.8f32, 0.5).unwrap();
        for inputs in bench_inputs() {
            let n = inputs.n;
            let (wi, wo) = (inputs.wi(n), inputs.wo(n));
            let mut a = vec![0.0f32; n];
            eon_scalar(0.8, 0.5, wi, wo, &mut a);
            for k in 0..n {
                let want = plugin.eval(wi[k], wo[k]);
                assert!(want > 0.0, "k={k}");
                assert_rel(a[k], want, 1e-5, &format!("eon k={k}"));
            }
        }
    }

    /// The Beckmann reference computes the plugin's `f_r` to a relative
    /// 10⁻⁵ on the bench's inputs (both sets) wherever `tan²θh/α² ≤ 30`
    /// (`D` above `e⁻³⁰ ≈ 10⁻¹³` of its peak): further out the two
    /// exponentials (`libm`'s and the plugin's, ≤ 4 + 3x ulp) differ by
    /// about `x·ε` relative, as any two `f32` evaluations of `e^{−x}` do.
    #[test]
    fn beckmann_reference_matches_the_plugin() {
        use radiometry_brdfs::Beckmann;
        let alpha = 0.3f32;
        let plugin = Microfacet::<_, HeightCorrelated, _>::new(Beckmann::new(alpha).unwrap(), NoFresnel);
        for inputs in bench_inputs() {
            let n = inputs.n;
            let (wi, wo) = (inputs.wi(n), inputs.wo(n));
            let mut a = vec![0.0f32; n];
            beckmann_scalar(alpha, wi, wo, &mut a);
            let mut compared = 0;
            for k in 0..n {
                let want = plugin.eval(wi[k], wo[k]);
                let h = (wi[k] + wo[k]).as_dvec3();
                let x = (h.x * h.x + h.y * h.y) / (h.z * h.z) / (alpha as f64).powi(2);
                if x <= 30.0 {
                    assert_rel(a[k], want, 1e-5, &format!("k={k}"));
                    compared += 1;
                }
            }
            assert!(compared > n / 2, "{compared}");
        }
    }

    /// The tabulated reference interpolates what the plugin interpolates:
    /// on a small grid of arbitrary (non-smooth) values, so that a wrong
    /// index, stride, wrap or weight shows, and on the MERL grid.
    #[test]
    fn tabulated_reference_matches_the_plugin() {
        use radiometry_brdfs::tabulated::{RusinkiewiczGrid, Tabulated};
        let n = 2000;
        let wi: Vec<Vec3> = (0..n)
            .map(|k| spherical_direction(1.55 * (k as f32 * 0.618_034).fract(), 0.37 * k as f32))
            .collect();
        let wo: Vec<Vec3> = (0..n)
            .map(|k| spherical_direction(1.55 * (k as f32 * 0.754_877_7).fract(), 2.1 + 1.3 * k as f32))
            .collect();
        for dims in [[9usize, 7, 18], [90, 90, 180]] {
            let grid = RusinkiewiczGrid::new(dims[0], dims[1], dims[2]).unwrap();
            let values: Vec<f32> = (0..grid.len())
                .map(|k| 0.5 + ((k as u64 * 2_654_435_761) % 1000) as f32 * 1e-3)
                .collect();
            let plugin = Tabulated::new(grid, &values[..]).unwrap();
            let mut a = vec![0.0f32; n];
            tabulated_scalar(
                Table {
                    values: &values,
                    dims,
                },
                &wi,
                &wo,
                &mut a,
            );
            let mut worst = 0.0f32;
            for k in 0..n {
                let want = plugin.eval(wi[k], wo[k]);
                // `acos` of a cosine near 1 is the textbook route's weak spot
                // (θh off by ~ε/θh rad); the plugin's atan2 form is not
                // compared there.
                if RusinkiewiczGrid::half_diff(wi[k], wo[k]).0 >= 0.01 {
                    worst = worst.max((a[k] - want).abs());
                }
            }
            // Values jump by up to 1 between neighbours, so this bounds the
            // difference of the continuous indices by about 10⁻³ cells.
            assert!(worst <= 1e-3, "{dims:?}: {worst:e}");
        }
    }

    /// The reference samplers draw the plugin's samples on the bench's
    /// inputs (both sets): the same direction (to 10⁻⁵), pdf and weight (to
    /// a relative 10⁻⁵; the weight of a sample within a few degrees of the
    /// horizon to the rounding of its `cos θi`), so timing them is timing
    /// the same work.
    #[test]
    fn reference_samplers_match_the_plugin() {
        let alpha = 0.3;
        let plugin = Microfacet::<_, HeightCorrelated, _>::new(Ggx::new(alpha).unwrap(), NoFresnel);
        for inputs in bench_inputs() {
            let n = inputs.n;
            let (wo, u) = (inputs.wo(n), &inputs.u[..n]);
            let (u0, u1) = inputs.u_soa(n);
            let mut a = vec![RefSample::default(); n];
            ggx_sample_scalar(alpha, wo, u, &mut a);
            let mut b: [Vec<f32>; 5] = std::array::from_fn(|_| vec![0.0; n]);
            let [bx, by, bz, bp, bw] = &mut b;
            ggx_sample_soa(
                alpha,
                inputs.wo_soa(n),
                u0,
                u1,
                SampleSoa {
                    x: bx,
                    y: by,
                    z: bz,
                    pdf: bp,
                    weight: bw,
                },
            );
            let mut compared = 0;
            for k in 0..n {
                let Some(want) = plugin.sample(wo[k], u[k]) else {
                    continue;
                };
                let soa = RefSample {
                    wi: Vec3::new(b[0][k], b[1][k], b[2][k]),
                    pdf: b[3][k],
                    weight: b[4][k],
                };
                for got in [a[k], soa] {
                    assert!((got.wi - want.wi).length() <= 1e-5, "k={k}: {got:?} vs {want:?}");
                    assert_rel(got.pdf, want.pdf, 1e-5, &format!("pdf k={k}"));
                    // w ∝ cos θi near the horizon: the ~10⁻⁷ rounding of wi_z
                    // (both sides) moves it by 10⁻⁷/cos θi relative.
                    let tol = 1e-5f32.max(3e-7 / want.wi.z);
                    assert_rel(got.weight, want.weight, tol, &format!("weight k={k}"));
                }
                compared += 1;
            }
            assert!(compared > n * 9 / 10, "{compared}");
        }
    }
}
