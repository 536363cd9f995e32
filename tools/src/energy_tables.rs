//! The generator of the crate's global energy tables
//! (`radiometry_brdfs::microfacet::fresnel_table`): `f64` quadrature of
//! GGX (height-correlated Smith `G2`) with a Fresnel factor on the unit
//! square of the visible-normal map (Heitz 2018, "Sampling the GGX
//! Distribution of Visible Normals", JCGT 7(4)), by product Gauss–Legendre
//! rules of 8 × 8 nodes per panel. `tools/examples/energy_tables.rs` writes
//! the tables with it; the tests below recompute a sample of the written
//! nodes, and `tools/examples/energy_tables_check.rs` measures the
//! interpolation error against the independent references of
//! [`reference`](crate::reference).
//!
//! ```text
//! E_F(μo, α) = ∫∫_[0,1]² F(ωo·m(u)) G2(ωi(u), ωo) / G1(ωo) du,   R = E_F / E₁
//! ```

#![allow(clippy::needless_range_loop)] // index arithmetic of the tables' layouts reads as the math

use std::f64::consts::PI;

/// `μ` nodes per row.
pub const NX: usize = 33;
/// Roughness nodes.
pub const NA: usize = 32;
/// Index nodes.
pub const NZ: usize = 32;
/// `μ` nodes per row of the `η < 1` table (its rounded kink needs more).
pub const NX_IN: usize = 65;
/// Index nodes of the `η < 1` table.
pub const NZ_IN: usize = 16;

/// 8-point Gauss–Legendre nodes and weights on `[0, 1]`.
pub fn gl8() -> ([f64; 8], [f64; 8]) {
    let x = [
        -0.960_289_856_497_536_3,
        -0.796_666_477_413_626_7,
        -0.525_532_409_916_329,
        -0.183_434_642_495_649_8,
        0.183_434_642_495_649_8,
        0.525_532_409_916_329,
        0.796_666_477_413_626_7,
        0.960_289_856_497_536_3,
    ];
    let w = [
        0.101_228_536_290_376_26,
        0.222_381_034_453_374_47,
        0.313_706_645_877_887_3,
        0.362_683_783_378_362,
        0.362_683_783_378_362,
        0.313_706_645_877_887_3,
        0.222_381_034_453_374_47,
        0.101_228_536_290_376_26,
    ];
    let mut xs = [0.0; 8];
    let mut ws = [0.0; 8];
    for i in 0..8 {
        xs[i] = 0.5 * (x[i] + 1.0);
        ws[i] = 0.5 * w[i];
    }
    (xs, ws)
}

/// GGX Smith `Λ(μ) = (√(1 + α² tan²θ) − 1)/2` (Heitz 2014, eq. 86).
pub fn lambda(alpha: f64, mu: f64) -> f64 {
    let s2 = (1.0 - mu * mu).max(0.0);
    if s2 == 0.0 {
        return 0.0;
    }
    let x = alpha * alpha * s2 / (mu * mu);
    0.5 * x / ((1.0 + x).sqrt() + 1.0)
}

/// GGX visible normal for `wo = (s, 0, μ)` (Heitz 2018, JCGT 7(4), listing 1).
pub fn vndf(alpha: f64, wo: [f64; 3], u1: f64, u2: f64) -> [f64; 3] {
    let vh = {
        let v = [alpha * wo[0], alpha * wo[1], wo[2]];
        let l = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
        [v[0] / l, v[1] / l, v[2] / l]
    };
    let lensq = vh[0] * vh[0] + vh[1] * vh[1];
    let t1 = if lensq > 0.0 {
        let il = 1.0 / lensq.sqrt();
        [-vh[1] * il, vh[0] * il, 0.0]
    } else {
        [1.0, 0.0, 0.0]
    };
    let t2 = [
        vh[1] * t1[2] - vh[2] * t1[1],
        vh[2] * t1[0] - vh[0] * t1[2],
        vh[0] * t1[1] - vh[1] * t1[0],
    ];
    let r = u1.sqrt();
    let phi = 2.0 * PI * u2;
    let p1 = r * phi.cos();
    let mut p2 = r * phi.sin();
    let s = 0.5 * (1.0 + vh[2]);
    p2 = (1.0 - s) * (1.0 - p1 * p1).max(0.0).sqrt() + s * p2;
    let pz = (1.0 - p1 * p1 - p2 * p2).max(0.0).sqrt();
    let nh = [
        p1 * t1[0] + p2 * t2[0] + pz * vh[0],
        p1 * t1[1] + p2 * t2[1] + pz * vh[1],
        p1 * t1[2] + p2 * t2[2] + pz * vh[2],
    ];
    let ne = [alpha * nh[0], alpha * nh[1], nh[2].max(0.0)];
    let l = (ne[0] * ne[0] + ne[1] * ne[1] + ne[2] * ne[2]).sqrt();
    [ne[0] / l, ne[1] / l, ne[2] / l]
}

/// Unpolarised dielectric Fresnel reflectance at incidence cosine `c` for
/// relative index `eta` (either side of 1; 1 under total internal reflection).
pub fn fresnel(eta: f64, c: f64) -> f64 {
    let c = c.clamp(0.0, 1.0);
    let s2t = (1.0 - c * c) / (eta * eta);
    if s2t >= 1.0 {
        return 1.0;
    }
    let ct = (1.0 - s2t).sqrt();
    let rs = (c - eta * ct) / (c + eta * ct);
    let rp = (eta * c - ct) / (eta * c + ct);
    0.5 * (rs * rs + rp * rp)
}

/// `∫∫ w(ωo·m) G2/G1 du` for weights `w` (several at once), with `p × p`
/// panels of 8 × 8 Gauss–Legendre nodes.
pub fn integrate<const K: usize>(alpha: f64, mu: f64, p: usize, w: impl Fn(f64) -> [f64; K]) -> [f64; K] {
    let mut acc = [0.0f64; K];
    for (c, weight) in nodes(alpha, mu, p) {
        let v = w(c);
        for k in 0..K {
            acc[k] += weight * v[k];
        }
    }
    acc
}

/// The quadrature nodes of [`integrate`] as `(c = ωo·m, weight)` pairs (the
/// weight includes `G2/G1` and the rule's weight): any `∫ w(c) G2/G1 du` is
/// then `Σ w(c) weight`, so one pass over the geometry serves every index.
pub fn nodes(alpha: f64, mu: f64, p: usize) -> Vec<(f64, f64)> {
    let (gx, gw) = gl8();
    let s = (1.0 - mu * mu).max(0.0).sqrt();
    let wo = [s, 0.0, mu];
    let lo = lambda(alpha, mu);
    let h = 1.0 / p as f64;
    let mut v = Vec::with_capacity(p * p * 64);
    for a in 0..p {
        for i in 0..8 {
            let u1 = (a as f64 + gx[i]) * h;
            for b in 0..p {
                for j in 0..8 {
                    let u2 = (b as f64 + gx[j]) * h;
                    let m = vndf(alpha, wo, u1, u2);
                    let d = wo[0] * m[0] + wo[1] * m[1] + wo[2] * m[2];
                    let wi_z = 2.0 * d * m[2] - wo[2];
                    if d <= 0.0 || wi_z <= 0.0 {
                        continue;
                    }
                    let g = (1.0 + lo) / (1.0 + lo + lambda(alpha, wi_z));
                    v.push((d, gw[i] * gw[j] * h * h * g));
                }
            }
        }
    }
    v
}

/// `(E_F, E₁)` from nodes.
pub fn pair_nodes(nodes: &[(f64, f64)], eta: f64) -> [f64; 2] {
    let mut e = 0.0;
    let mut e1 = 0.0;
    for &(c, w) in nodes {
        if eta != 1.0 {
            e += fresnel(eta, c) * w;
        }
        e1 += w;
    }
    [e, e1]
}

/// Roughness node `α_k = (0.01 + 0.99 k/31)²`.
pub fn alpha_node(k: usize) -> f64 {
    let t = 0.01 + 0.99 * k as f64 / (NA - 1) as f64;
    t * t
}

/// Index node `z_l = l/31` (`z = F0^¼`).
pub fn z_node(l: usize) -> f64 {
    l as f64 / (NZ - 1) as f64
}

/// Index node of the `η < 1` table, `z_l = l/15`.
pub fn z_node_in(l: usize) -> f64 {
    l as f64 / (NZ_IN - 1) as f64
}

/// `η > 1` with `F0^¼ = z`.
pub fn eta_out(z: f64) -> f64 {
    let r = z * z;
    if r >= 1.0 { 1e3 } else { (1.0 + r) / (1.0 - r) }
}

/// `μ` of node coordinate `x` on the inside table (critical cosine `mc`,
/// roughness `alpha`, index `eta < 1`): `x = ½ ∓ ½ s(|μ − μc|)` below and above
/// `μc`, with the side coordinate [`side_coord`].
pub fn mu_in(x: f64, mc: f64, alpha: f64, eta: f64) -> f64 {
    let w = kink_width(alpha, eta);
    let (span, sign) = if x <= 0.5 { (mc, -1.0) } else { (1.0 - mc, 1.0) };
    let target = ((x - 0.5).abs() / 0.5).clamp(0.0, 1.0);
    if span <= 0.0 {
        return mc;
    }
    // Bisection of the monotone side coordinate s(d) = target, d ∈ [0, span].
    let (mut lo, mut hi) = (0.0f64, span);
    for _ in 0..100 {
        let mid = 0.5 * (lo + hi);
        if side_coord(mid, span, w) < target {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    (mc + sign * 0.5 * (lo + hi)).clamp(0.0, 1.0)
}

/// The width in `μ` over which roughness smooths the onset of total internal
/// reflection: `w = max(α η, 10⁻⁴)` (`sin θc = η`, the lobe spreads by about
/// `α` in angle).
pub fn kink_width(alpha: f64, eta: f64) -> f64 {
    (alpha * eta).max(1e-4)
}

/// The side coordinate `s ∈ [0, 1]` of a distance `d ∈ [0, span]` from the
/// critical cosine: `½ √(d/span) + ½ asinh(d/w)/asinh(span/w)` — fine (about
/// `w`) near the kink, where roughness rounds it, and `√`-spaced far from it,
/// with weights 0.3 and 0.7,
/// where the Fresnel factor goes like `√d` (`f32` reader:
/// `radiometry_brdfs::microfacet::fresnel_table`).
pub fn side_coord(d: f64, span: f64, w: f64) -> f64 {
    if span <= 0.0 {
        return 0.0;
    }
    let d = d.clamp(0.0, span);
    0.3 * (d / span).sqrt() + 0.7 * (d / w).asinh() / (span / w).asinh()
}

/// Smallest `μ` at which a node is computed.
pub const MU_FLOOR: f64 = 1e-6;

/// `E_F/E₁` from `(E_F, E₁)`, in `[0, 1]` (0 where `E₁ = 0`).
pub fn ratio(v: [f64; 2]) -> f64 {
    if v[1] > 0.0 {
        (v[0] / v[1]).clamp(0.0, 1.0)
    } else {
        0.0
    }
}

/// Gauss–Legendre on `[a, b]` with `n` 8-point panels of `f`.
pub fn gl_interval(a: f64, b: f64, panels: usize, f: &mut impl FnMut(f64) -> f64) -> f64 {
    let (gx, gw) = gl8();
    let h = (b - a) / panels as f64;
    let mut s = 0.0;
    for p in 0..panels {
        for i in 0..8 {
            s += gw[i] * h * f(a + (p as f64 + gx[i]) * h);
        }
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;
    use radiometry_brdfs::microfacet::fresnel_table::{
        dielectric_average, dielectric_ratio, fresnel_moments,
    };

    /// A sample of the written nodes, recomputed (16 × 16 panels for `η > 1`
    /// and the moments, 32 × 32 for `η < 1`; the generator wrote 32 × 32):
    /// they agree to the generator's stated convergence plus the `u16`
    /// rounding.
    #[test]
    fn a_sample_of_nodes_regenerates() {
        for &(k, l, j) in &[
            (3usize, 5usize, 7usize),
            (10, 12, 20),
            (20, 2, 31),
            (31, 25, 16),
            (6, 30, 2),
            (15, 15, 32),
        ] {
            let (alpha, z) = (alpha_node(k), z_node(l));
            let x = j as f64 / (NX - 1) as f64;
            // Outside.
            let eta = eta_out(z);
            let mu = (x * x).max(MU_FLOOR);
            let want = ratio(pair_nodes(&nodes(alpha, mu, 16), eta));
            let got = f64::from(dielectric_ratio(mu as f32, alpha as f32, eta as f32));
            assert!(
                (want - got).abs() < 1e-3,
                "out α {alpha} η {eta} μ {mu}: {want} vs {got}"
            );
            // Inside (its own grid: 16 indices, 65 μ nodes).
            let ei = 1.0 / eta_out(z_node_in(l % NZ_IN));
            let mc = (1.0 - ei * ei).max(0.0).sqrt();
            let x = (2 * j) as f64 / (NX_IN - 1) as f64;
            let mu = mu_in(x, mc, alpha, ei).max(MU_FLOOR);
            let want = ratio(pair_nodes(&nodes(alpha, mu, 32), ei));
            let got = f64::from(dielectric_ratio(mu as f32, alpha as f32, ei as f32));
            assert!(
                (want - got).abs() < 2e-3,
                "in α {alpha} η {ei} μ {mu}: {want} vs {got}"
            );
            // Moments.
            let mu = (x * x).max(MU_FLOOR);
            let m = integrate(alpha, mu, 16, |c: f64| {
                let q = 1.0 - c;
                let q5 = q * q * q * q * q;
                [q5, c * q5 * q, 1.0]
            });
            let (r5, r6) = fresnel_moments(mu as f32, alpha as f32);
            assert!((m[0] / m[2] - f64::from(r5)).abs() < 1e-3 && (m[1] / m[2] - f64::from(r6)).abs() < 1e-3);
        }
        // An average: 2∫E μ dμ with 32 Gauss–Legendre nodes.
        let (alpha, eta) = (alpha_node(9), eta_out(z_node(7)));
        let mut f = |mu: f64| 2.0 * mu * pair_nodes(&nodes(alpha, mu.max(MU_FLOOR), 8), eta)[0];
        let want = gl_interval(0.0, 1.0, 4, &mut f);
        let got = f64::from(dielectric_average(alpha as f32, eta as f32));
        assert!((want - got).abs() < 1e-4, "{want} vs {got}");
    }
}
