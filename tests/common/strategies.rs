//! Proptest strategies that deliberately hit the edges of the domains (issue 2): grazing directions
//! (`cos θ < 1e-4`), near-normal directions, pairs with `ωi` near `ωo`, near the mirror direction of `ωo`
//! and near `−ωo` (both grazing, on opposite sides of the normal), roughness `α < 1e-3` (down to `1e-4`),
//! Phong exponents above `1e4` (up to the maximum `1e7`), plus generic ranges.
//!
//! Directions are built in `f64` and rounded to `f32` at the end, so they are unit to within `f32`
//! rounding — as a renderer would pass them.

use proptest::prelude::*;
use radiometry::glam::{DVec3, Vec3};
use std::f64::consts::TAU;

/// Rounds an `f64` direction to `f32`.
pub fn to_f32(w: DVec3) -> Vec3 {
    Vec3::new(w.x as f32, w.y as f32, w.z as f32)
}

/// `f32` direction to `f64`.
pub fn to_f64(w: Vec3) -> DVec3 {
    DVec3::new(w.x as f64, w.y as f64, w.z as f64)
}

/// Unit direction from `cos θ` and φ.
pub fn dir(cos_theta: f64, phi: f64) -> DVec3 {
    let c = cos_theta.clamp(-1.0, 1.0);
    let s = (1.0 - c * c).max(0.0).sqrt();
    DVec3::new(s * phi.cos(), s * phi.sin(), c)
}

/// Log-uniform `f64` in `[lo, hi]`.
pub fn log_uniform(lo: f64, hi: f64) -> impl Strategy<Value = f64> + Clone {
    (lo.ln()..=hi.ln()).prop_map(f64::exp)
}

/// `cos θ` of an upper direction: grazing (`1e-9 ≤ cos θ < 1e-4`), generic, near-normal, exactly normal.
pub fn cos_theta() -> impl Strategy<Value = f64> + Clone {
    prop_oneof![
        2 => log_uniform(1e-9, 1e-4),
        5 => 1e-4f64..=1.0,
        1 => log_uniform(1e-9, 1e-3).prop_map(|d| 1.0 - d),
        1 => Just(1.0),
    ]
}

/// An upper-hemisphere direction (in `f64`, before rounding).
pub fn upper_dir() -> impl Strategy<Value = DVec3> + Clone {
    (cos_theta(), 0.0..TAU).prop_map(|(c, p)| dir(c, p))
}

/// `w` turned by the small angle `delta` in azimuth direction `psi` about itself, reflected into the
/// upper hemisphere if it crosses the horizon.
pub fn perturb(w: DVec3, delta: f64, psi: f64) -> DVec3 {
    let a = if w.z.abs() < 0.9 { DVec3::Z } else { DVec3::X };
    let s = a.cross(w).normalize();
    let t = w.cross(s);
    let v = (delta.cos() * w + delta.sin() * (psi.cos() * s + psi.sin() * t)).normalize();
    if v.z > 0.0 {
        v
    } else {
        DVec3::new(v.x, v.y, (-v.z).max(1e-12)).normalize()
    }
}

/// The relation between the two directions of a pair (for reporting).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PairKind {
    /// Independent directions.
    Independent,
    /// `ωi ≈ ωo`.
    NearSame,
    /// `ωi ≈` the mirror direction of `ωo` (the specular peak).
    NearMirror,
    /// `ωi ≈ −ωo` with both just above the horizon (half vector nearly undefined).
    NearOpposite,
}

/// A pair `(ωi, ωo)` of upper-hemisphere directions (rounded to `f32`) hitting the edges.
pub fn dir_pair() -> impl Strategy<Value = (Vec3, Vec3, PairKind)> + Clone {
    let small = log_uniform(1e-7, 1e-1);
    prop_oneof![
        4 => (upper_dir(), upper_dir()).prop_map(|(a, b)| (to_f32(a), to_f32(b), PairKind::Independent)),
        2 => (upper_dir(), small.clone(), 0.0..TAU)
            .prop_map(|(wo, d, p)| (to_f32(perturb(wo, d, p)), to_f32(wo), PairKind::NearSame)),
        3 => (upper_dir(), small.clone(), 0.0..TAU).prop_map(|(wo, d, p)| {
            let r = DVec3::new(-wo.x, -wo.y, wo.z);
            (to_f32(perturb(r, d, p)), to_f32(wo), PairKind::NearMirror)
        }),
        2 => (log_uniform(1e-9, 1e-3), log_uniform(1e-9, 1e-3), 0.0..TAU, small)
            .prop_map(|(ci, co, p, d)| {
                let wo = dir(co, p);
                let wi = dir(ci, p + std::f64::consts::PI + d);
                (to_f32(wi), to_f32(wo), PairKind::NearOpposite)
            }),
    ]
}

/// Microfacet roughness α ∈ [1e-4, 1]: below 1e-3, generic (log-uniform), and the two end points.
pub fn alpha() -> impl Strategy<Value = f32> + Clone {
    prop_oneof![
        2 => log_uniform(1e-4, 1e-3).prop_map(|a| a as f32),
        5 => log_uniform(1e-3, 1.0).prop_map(|a| a as f32),
        1 => Just(1e-4f32),
        1 => Just(1.0f32),
    ]
    .prop_map(|a: f32| a.clamp(1e-4, 1.0))
}

/// Phong exponent n ∈ [0, 1e7]: small, generic (log-uniform), huge (> 1e4), and the end points.
pub fn exponent() -> impl Strategy<Value = f32> + Clone {
    prop_oneof![
        2 => 0.0f64..10.0,
        3 => log_uniform(10.0, 1e4),
        2 => log_uniform(1e4, 1e7),
        1 => Just(0.0),
        1 => Just(1e7),
    ]
    .prop_map(|n: f64| (n as f32).clamp(0.0, 1e7))
}

/// `(kd, ks)` with `kd, ks ≥ 0` and `kd + ks ≤ 1` in `f32`, including the energy-conserving edge
/// `kd + ks = 1` and the pure-lobe case `kd = 0`.
pub fn kd_ks() -> impl Strategy<Value = (f32, f32)> + Clone {
    prop_oneof![
        3 => (0.0f32..=1.0, 0.0f32..=1.0).prop_map(|(a, b)| {
            let s = a + b;
            if s > 1.0 { (a / s, b / s) } else { (a, b) }
        }),
        2 => (0.0f32..=1.0).prop_map(|a| (a, 1.0 - a)),
        1 => Just((0.0f32, 1.0f32)),
    ]
    .prop_map(|(kd, mut ks): (f32, f32)| {
        while kd + ks > 1.0 {
            ks = ks.next_down();
        }
        (kd, ks.max(0.0))
    })
}
