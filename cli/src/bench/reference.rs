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
//! ```text
//! h    = normalize(wi + wo)
//! D    = α² / (π (α² h_z² + h_x² + h_y²)²)                  (Walter et al. 2007, eq. 33, for |h| = 1)
//! Λ(w) = (sqrt(1 + α² tan²θ) − 1) / 2,  tan²θ = (x² + y²) / z²   (Heitz 2014, eq. 86)
//! f    = D / (1 + Λ(wi) + Λ(wo)) / (4 z_i z_o)               (G2 height-correlated, Heitz 2014, eq. 99)
//! ```
//!
//! # GGX visible-normal sampling (`F = 1`)
//!
//! ```text
//! v    = normalize(α wo_x, α wo_y, wo_z)                        stretch (Heitz 2018, JCGT 7(4))
//! φ    = 2π u₀,  z_c = (1 − u₁)(1 + v_z) − v_z                   spherical cap (Dupuy & Benyoub 2023, §3)
//! m    = normalize(α (√(1 − z_c²) cos φ + v_x), α (√(1 − z_c²) sin φ + v_y), z_c + v_z)
//! wi   = 2 (wo·m) m − wo
//! pdf  = D(m) / (4 wo_z (1 + Λ(wo)))                             D_wo(m)/(4 wo·m) (Heitz 2014, eq. 16)
//! w    = f cos θi / pdf = (1 + Λ(wo)) / (1 + Λ(wo) + Λ(wi))      G2/G1(wo)
//! ```
//!
//! with `D`, `Λ` as above and `(sin φ, cos φ)` from
//! [`radiometry::math::sincos_turn`] (the samplers' own: quadrant reduction
//! and Taylor polynomials, branch-free, so the SoA loop vectorises).
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
//! * [`beckmann_scalar`] — Beckmann, height-correlated Smith, `F = 1`:
//!
//!   ```text
//!   h    = normalize(wi + wo),  tan²θh = (h_x² + h_y²)/h_z²
//!   D    = exp(−tan²θh/α²) / (π α² h_z⁴)                          (Walter et al. 2007, eq. 25)
//!   a(w) = z / (α √(x² + y²))
//!   Λ(w) = (e^{−a²}/(a √π) − erfc(a)) / 2                         (Walter et al. 2007, eq. 27)
//!   f    = D / (1 + Λ(wi) + Λ(wo)) / (4 z_i z_o)
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

/// The GGX height-correlated `f_r` with `F = 1` of one pair, no checks (see
/// the module docs for the formula). `alpha2 = α²`.
#[inline(always)]
fn ggx_hc(alpha2: f32, i: [f32; 3], o: [f32; 3]) -> f32 {
    let [xi, yi, zi] = i;
    let [xo, yo, zo] = o;
    // h = normalize(wi + wo)
    let (hx, hy, hz) = (xi + xo, yi + yo, zi + zo);
    let inv_len = 1.0 / (hx * hx + hy * hy + hz * hz).sqrt();
    let (hx, hy, hz) = (hx * inv_len, hy * inv_len, hz * inv_len);
    // D = α² / (π (α² h_z² + h_x² + h_y²)²)
    let t = alpha2 * hz * hz + hx * hx + hy * hy;
    let d = alpha2 / (PI * t * t);
    // Λ(w) = (sqrt(1 + α² tan²θ) − 1) / 2
    let tan2_i = (xi * xi + yi * yi) / (zi * zi);
    let tan2_o = (xo * xo + yo * yo) / (zo * zo);
    let lambda_i = 0.5 * ((1.0 + alpha2 * tan2_i).sqrt() - 1.0);
    let lambda_o = 0.5 * ((1.0 + alpha2 * tan2_o).sqrt() - 1.0);
    // f = D G2 / (4 z_i z_o), G2 = 1 / (1 + Λi + Λo)
    d / (1.0 + lambda_i + lambda_o) / (4.0 * zi * zo)
}

/// `out[k] = f_GGX(wi[k], wo[k])` for `k < out.len()` (panics if an input is
/// shorter): the plain scalar loop over AoS input.
#[inline(never)]
#[allow(clippy::needless_range_loop)] // the indexed loop is the point: it is what a renderer writes
pub fn ggx_scalar(alpha: f32, wi: &[Vec3], wo: &[Vec3], out: &mut [f32]) {
    let n = out.len();
    let (wi, wo) = (&wi[..n], &wo[..n]);
    let alpha2 = alpha * alpha;
    for k in 0..n {
        // An opaque index keeps LLVM from vectorising across elements: this
        // is the one-pair-at-a-time limit a scalar `eval` loop competes
        // with (the vector limit is `ggx_soa`). It costs one register move.
        let k = std::hint::black_box(k);
        let (i, o) = (wi[k], wo[k]);
        out[k] = ggx_hc(alpha2, [i.x, i.y, i.z], [o.x, o.y, o.z]);
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
    let alpha2 = alpha * alpha;
    for k in 0..n {
        out[k] = ggx_hc(alpha2, [xi[k], yi[k], zi[k]], [xo[k], yo[k], zo[k]]);
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
/// module docs for the formulas), no checks. `alpha2 = α²`.
#[inline(always)]
fn ggx_vndf(alpha: f32, alpha2: f32, o: [f32; 3], u: [f32; 2]) -> ([f32; 3], f32, f32) {
    let [xo, yo, zo] = o;
    // v = normalize(α wo_x, α wo_y, wo_z)
    let (sx, sy) = (alpha * xo, alpha * yo);
    let inv_v = 1.0 / (sx * sx + sy * sy + zo * zo).sqrt();
    let (vx, vy, vz) = (sx * inv_v, sy * inv_v, zo * inv_v);
    // a point of the spherical cap z_c ∈ [−v_z, 1], and h = c + v
    let (sp, cp) = radiometry::math::sincos_turn(u[0]);
    let zc = (1.0 - u[1]) * (1.0 + vz) - vz;
    let sc = (1.0 - zc * zc).max(0.0).sqrt();
    let (hx, hy, hz) = (sc * cp + vx, sc * sp + vy, zc + vz);
    // m = normalize(α h_x, α h_y, h_z)
    let (mx, my, mz) = (alpha * hx, alpha * hy, hz.max(0.0));
    let inv_m = 1.0 / (mx * mx + my * my + mz * mz).sqrt();
    let (mx, my, mz) = (mx * inv_m, my * inv_m, mz * inv_m);
    // wi = 2 (wo·m) m − wo
    let dot = xo * mx + yo * my + zo * mz;
    let (xi, yi, zi) = (2.0 * dot * mx - xo, 2.0 * dot * my - yo, 2.0 * dot * mz - zo);
    // D(m), Λ(wo), Λ(wi)
    let t = alpha2 * mz * mz + mx * mx + my * my;
    let d = alpha2 / (PI * t * t);
    let lambda_o = 0.5 * ((1.0 + alpha2 * (xo * xo + yo * yo) / (zo * zo)).sqrt() - 1.0);
    let lambda_i = 0.5 * ((1.0 + alpha2 * (xi * xi + yi * yi) / (zi * zi)).sqrt() - 1.0);
    let pdf = d / (4.0 * zo * (1.0 + lambda_o));
    let weight = (1.0 + lambda_o) / (1.0 + lambda_o + lambda_i);
    ([xi, yi, zi], pdf, weight)
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
    let alpha2 = alpha * alpha;
    for k in 0..n {
        let k = std::hint::black_box(k);
        let o = wo[k];
        let (wi, pdf, weight) = ggx_vndf(alpha, alpha2, [o.x, o.y, o.z], u[k]);
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
    let alpha2 = alpha * alpha;
    for k in 0..n {
        let ([x, y, z], pdf, w) = ggx_vndf(alpha, alpha2, [xo[k], yo[k], zo[k]], [u0[k], u1[k]]);
        ox[k] = x;
        oy[k] = y;
        oz[k] = z;
        opdf[k] = pdf;
        ow[k] = w;
    }
}

/// The Beckmann height-correlated `f_r` with `F = 1` of one pair, no checks
/// (see the module docs). `inv_a2 = 1/α²`, `k = 1/(π α²)`.
#[inline(always)]
fn beckmann_hc(alpha: f32, inv_a2: f32, k: f32, i: [f32; 3], o: [f32; 3]) -> f32 {
    let [xi, yi, zi] = i;
    let [xo, yo, zo] = o;
    let (hx, hy, hz) = (xi + xo, yi + yo, zi + zo);
    let inv_len2 = 1.0 / (hx * hx + hy * hy + hz * hz);
    let cos2 = hz * hz * inv_len2;
    let tan2 = (hx * hx + hy * hy) / (hz * hz);
    // D = exp(−tan²θh/α²) / (π α² cos⁴θh)
    let d = libm::expf(-tan2 * inv_a2) * k / (cos2 * cos2);
    // Λ(w) = (e^{−a²}/(a √π) − erfc(a)) / 2,  a = z/(α sin θ)
    let lambda = |x: f32, y: f32, z: f32| {
        let a = z / (alpha * (x * x + y * y).sqrt());
        0.5 * (libm::expf(-a * a) / (a * SQRT_PI) - libm::erfcf(a))
    };
    d / (1.0 + lambda(xi, yi, zi) + lambda(xo, yo, zo)) / (4.0 * zi * zo)
}

/// `√π`.
const SQRT_PI: f32 = 1.772_453_9;

/// `out[k] = f_Beckmann(wi[k], wo[k])` for `k < out.len()` (panics if an
/// input is shorter): the plain scalar loop over AoS input (opaque index, as
/// in [`ggx_scalar`]).
#[inline(never)]
#[allow(clippy::needless_range_loop)]
pub fn beckmann_scalar(alpha: f32, wi: &[Vec3], wo: &[Vec3], out: &mut [f32]) {
    let n = out.len();
    let (wi, wo) = (&wi[..n], &wo[..n]);
    let a2 = alpha as f64 * alpha as f64;
    let (inv_a2, k) = ((1.0 / a2) as f32, (std::f64::consts::FRAC_1_PI / a2) as f32);
    for j in 0..n {
        let j = std::hint::black_box(j);
        let (i, o) = (wi[j], wo[j]);
        out[j] = beckmann_hc(alpha, inv_a2, k, [i.x, i.y, i.z], [o.x, o.y, o.z]);
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

    /// The reference kernels compute the plugin's `f_r` (up to rounding) on
    /// directions above the horizon, so timing them is timing the same work.
    #[test]
    fn references_match_the_plugin() {
        let alpha = 0.3;
        let plugin = Microfacet::<_, HeightCorrelated, _>::new(Ggx::new(alpha).unwrap(), NoFresnel);
        let n = 257;
        let wi: Vec<Vec3> = (0..n)
            .map(|k| spherical_direction(0.006 * k as f32, 0.7 * k as f32))
            .collect();
        let wo: Vec<Vec3> = (0..n)
            .map(|k| spherical_direction(1.5 - 0.0055 * k as f32, 2.1 + 1.3 * k as f32))
            .collect();
        let soa = |w: &[Vec3]| -> [Vec<f32>; 3] {
            [
                w.iter().map(|v| v.x).collect(),
                w.iter().map(|v| v.y).collect(),
                w.iter().map(|v| v.z).collect(),
            ]
        };
        let (si, so) = (soa(&wi), soa(&wo));
        let (vi, vo) = (
            Vec3Soa::new(&si[0], &si[1], &si[2]),
            Vec3Soa::new(&so[0], &so[1], &so[2]),
        );
        let mut a = vec![0.0f32; n];
        let mut b = vec![0.0f32; n];
        let mut s = vec![0.0f32; n];
        ggx_scalar(alpha, &wi, &wo, &mut a);
        ggx_soa(alpha, vi, vo, &mut b);
        stream(vi, vo, &mut s);
        for k in 0..n {
            let want = plugin.eval(wi[k], wo[k]);
            assert!(want > 0.0, "k={k}");
            for got in [a[k], b[k]] {
                assert!((got - want).abs() <= 1e-5 * want, "k={k}: {got} vs {want}");
            }
            let sum = wi[k].x + wi[k].y + wi[k].z + wo[k].x + wo[k].y + wo[k].z;
            assert!((s[k] - sum).abs() <= 1e-5, "k={k}");
        }
    }

    /// The Beckmann reference computes the plugin's `f_r` (up to the
    /// rounding of `libm`'s `expf`, `erfcf` and of the cancelling `Λ` form).
    #[test]
    fn beckmann_reference_matches_the_plugin() {
        use radiometry_brdfs::Beckmann;
        let alpha = 0.3;
        let plugin = Microfacet::<_, HeightCorrelated, _>::new(Beckmann::new(alpha).unwrap(), NoFresnel);
        let n = 401;
        let wi: Vec<Vec3> = (0..n)
            .map(|k| spherical_direction(0.0035 * k as f32, 0.7 * k as f32))
            .collect();
        let wo: Vec<Vec3> = (0..n)
            .map(|k| spherical_direction(1.5 - 0.0036 * k as f32, 2.1 + 1.3 * k as f32))
            .collect();
        let mut a = vec![0.0f32; n];
        beckmann_scalar(alpha, &wi, &wo, &mut a);
        let mut compared = 0;
        for k in 0..n {
            let want = plugin.eval(wi[k], wo[k]);
            // Far out in the tail the two `exp(−x)` differ in relative terms by ~x·ε.
            if want > 1e-20 {
                assert!((a[k] - want).abs() <= 1e-4 * want, "k={k}: {} vs {want}", a[k]);
                compared += 1;
            }
        }
        assert!(compared > n / 2, "{compared}");
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

    /// The reference samplers draw the plugin's samples (up to rounding):
    /// the same direction, pdf and weight, so timing them is timing the
    /// same work.
    #[test]
    fn reference_samplers_match_the_plugin() {
        let alpha = 0.3;
        let plugin = Microfacet::<_, HeightCorrelated, _>::new(Ggx::new(alpha).unwrap(), NoFresnel);
        let n = 509;
        let wo: Vec<Vec3> = (0..n)
            .map(|k| spherical_direction(0.003 * k as f32, 0.7 * k as f32))
            .collect();
        let u: Vec<[f32; 2]> = (0..n)
            .map(|k| [(k as f32 * 0.618_034).fract(), (k as f32 * 0.754_877_7).fract()])
            .collect();
        let (u0, u1): (Vec<f32>, Vec<f32>) = u.iter().map(|v| (v[0], v[1])).unzip();
        let comp = |j: usize| -> Vec<f32> { wo.iter().map(|v| v[j]).collect() };
        let (x, y, z) = (comp(0), comp(1), comp(2));
        let mut a = vec![RefSample::default(); n];
        ggx_sample_scalar(alpha, &wo, &u, &mut a);
        let mut b: [Vec<f32>; 5] = std::array::from_fn(|_| vec![0.0; n]);
        let [bx, by, bz, bp, bw] = &mut b;
        ggx_sample_soa(
            alpha,
            Vec3Soa::new(&x, &y, &z),
            &u0,
            &u1,
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
                // Relative: the pdf of a near-grazing wi moves with its
                // last bits; 1e-4 is far above the sampling formulas' rounding.
                assert!(
                    (got.pdf - want.pdf).abs() <= 1e-4 * want.pdf,
                    "k={k}: {got:?} vs {want:?}"
                );
                assert!((got.weight - want.weight).abs() <= 1e-4 * want.weight, "k={k}");
            }
            compared += 1;
        }
        assert!(compared > n * 9 / 10, "{compared}");
    }
}
