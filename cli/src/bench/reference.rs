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
//! Valid (and used) only for unit directions strictly above the horizon,
//! which the bench inputs are; anything else gives garbage, not `0`.

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
}
