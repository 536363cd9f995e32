//! Sampling warps: maps from the unit square `[0,1)²` to disks, hemispheres
//! and cones, each with its density.
//!
//! Densities are in the measure of the target domain: area for disks,
//! solid angle (sr⁻¹) for directions. Formulas follow Pharr, Jakob &
//! Humphreys, *Physically Based Rendering* 4th ed., §A.5 (and Shirley &
//! Chiu 1997 for the concentric map).
//!
//! Every warp accepts any `u` in `[0, 1]²` — including exactly `0` and
//! [`ONE_MINUS_EPSILON`](crate::math::ONE_MINUS_EPSILON) — and returns a
//! finite, unit-length direction on the closed domain.

use crate::math::{clamp01, safe_sqrt, sincos_turn};
use core::f32::consts::{FRAC_1_PI, PI, TAU};
use glam::{Vec2, Vec3};

/// Concentric map of the unit square onto the unit disk (Shirley & Chiu
/// 1997, "A Low Distortion Map Between Disk and Square", JGT 2(3)).
/// Uniform in area: density `1/π`.
#[inline]
pub fn square_to_concentric_disk(u: [f32; 2]) -> Vec2 {
    let ox = 2.0 * clamp01(u[0]) - 1.0;
    let oy = 2.0 * clamp01(u[1]) - 1.0;
    if ox == 0.0 && oy == 0.0 {
        return Vec2::ZERO;
    }
    // θ = π/4 · o_y/o_x or π/2 − π/4 · o_x/o_y, in turns (θ/2π).
    let (r, turns) = if ox.abs() > oy.abs() {
        (ox, 0.125 * (oy / ox))
    } else {
        (oy, 0.25 - 0.125 * (ox / oy))
    };
    let (s, c) = sincos_turn(turns);
    Vec2::new(r * c, r * s)
}

/// Density of [`square_to_concentric_disk`] w.r.t. area: `1/π` inside the disk.
#[inline]
pub fn concentric_disk_pdf(p: Vec2) -> f32 {
    if p.length_squared() <= 1.0 { FRAC_1_PI } else { 0.0 }
}

/// Uniform direction on the upper hemisphere:
/// `cos θ = u₀`, `φ = 2π u₁`; density `1/(2π)`.
#[inline]
pub fn square_to_uniform_hemisphere(u: [f32; 2]) -> Vec3 {
    let z = clamp01(u[0]);
    let r = safe_sqrt(1.0 - z * z);
    let (s, c) = sincos_turn(clamp01(u[1]));
    Vec3::new(r * c, r * s, z)
}

/// Density of [`square_to_uniform_hemisphere`]: `1/(2π)` for `cos θ ≥ 0`.
#[inline]
pub fn uniform_hemisphere_pdf(w: Vec3) -> f32 {
    if w.z >= 0.0 { 0.5 * FRAC_1_PI } else { 0.0 }
}

/// Cosine-weighted direction on the upper hemisphere (Malley's method:
/// a concentric-disk point lifted to the hemisphere). Density `cos θ/π`.
#[inline]
pub fn square_to_cosine_hemisphere(u: [f32; 2]) -> Vec3 {
    let d = square_to_concentric_disk(u);
    let z = safe_sqrt(1.0 - d.length_squared());
    Vec3::new(d.x, d.y, z)
}

/// Density of [`square_to_cosine_hemisphere`]: `max(cos θ, 0)/π` (sr⁻¹).
#[inline]
pub fn cosine_hemisphere_pdf(w: Vec3) -> f32 {
    w.z.max(0.0) * FRAC_1_PI
}

/// Uniform direction in the cone of half-angle θmax around `+Z`, given
/// `cos θmax`: `cos θ = 1 − u₀(1 − cos θmax)`, `φ = 2π u₁`.
/// Density `1/(2π(1 − cos θmax))`.
///
/// `cos_theta_max` is clamped to `[-1, 1]`; `cos θmax = 1` (a zero-width
/// cone) returns `+Z`.
#[inline]
pub fn square_to_uniform_cone(u: [f32; 2], cos_theta_max: f32) -> Vec3 {
    let ctm = cos_theta_max.clamp(-1.0, 1.0);
    let z = (1.0 - clamp01(u[0]) * (1.0 - ctm)).clamp(-1.0, 1.0);
    let r = safe_sqrt(1.0 - z * z);
    let (s, c) = sincos_turn(clamp01(u[1]));
    Vec3::new(r * c, r * s, z)
}

/// Density of [`square_to_uniform_cone`] (sr⁻¹); zero outside the cone and
/// `f32::INFINITY`-free: a degenerate cone (`cos θmax = 1`) reports 0.
#[inline]
pub fn uniform_cone_pdf(w: Vec3, cos_theta_max: f32) -> f32 {
    let ctm = cos_theta_max.clamp(-1.0, 1.0);
    let solid_angle = TAU * (1.0 - ctm);
    if solid_angle <= 0.0 || w.z < ctm {
        0.0
    } else {
        1.0 / solid_angle
    }
}

/// Uniform direction on the whole sphere: `z = 1 − 2u₀`; density `1/(4π)`.
#[inline]
pub fn square_to_uniform_sphere(u: [f32; 2]) -> Vec3 {
    let z = 1.0 - 2.0 * clamp01(u[0]);
    let r = safe_sqrt(1.0 - z * z);
    let (s, c) = sincos_turn(clamp01(u[1]));
    Vec3::new(r * c, r * s, z)
}

/// Density of [`square_to_uniform_sphere`]: `1/(4π)`.
#[inline]
pub fn uniform_sphere_pdf(_w: Vec3) -> f32 {
    0.25 * FRAC_1_PI
}

/// Solid angle of a cone of half-angle θ: `Ω = 2π(1 − cos θ)`.
#[inline]
pub fn cone_solid_angle(cos_theta_max: f32) -> f32 {
    TAU * (1.0 - cos_theta_max.clamp(-1.0, 1.0))
}

/// `π`, re-exported for plugins that want the constant with the name of
/// its role: the projected solid angle of the hemisphere, `∫_H cos θ dω = π`.
pub const PROJECTED_HEMISPHERE: f32 = PI;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::ONE_MINUS_EPSILON;

    const EDGE: [f32; 5] = [0.0, 1e-7, 0.5, ONE_MINUS_EPSILON, 1.0];

    #[test]
    fn warps_total_on_edges() {
        for &a in &EDGE {
            for &b in &EDGE {
                let u = [a, b];
                let d = square_to_concentric_disk(u);
                assert!(d.is_finite() && d.length() <= 1.0 + 1e-6);
                for w in [
                    square_to_uniform_hemisphere(u),
                    square_to_cosine_hemisphere(u),
                    square_to_uniform_cone(u, 0.9),
                    square_to_uniform_sphere(u),
                ] {
                    assert!(w.is_finite(), "{u:?}");
                    assert!((w.length() - 1.0).abs() < 1e-5, "{u:?} {w:?}");
                }
                assert!(square_to_cosine_hemisphere(u).z >= 0.0);
                assert!(square_to_uniform_cone(u, 0.9).z >= 0.9 - 1e-6);
            }
        }
        assert!(square_to_uniform_hemisphere([f32::NAN, f32::NAN]).is_finite());
    }

    /// Midpoint-rule check that each density integrates to one over its
    /// domain (independent of the warps themselves).
    #[test]
    fn densities_integrate_to_one() {
        let n = 400;
        let (mut hemi_cos, mut cone) = (0.0f64, 0.0f64);
        let ctm = 0.7f32;
        for i in 0..n {
            let theta = (i as f64 + 0.5) / n as f64 * core::f64::consts::FRAC_PI_2;
            let w = Vec3::new(libm::sin(theta) as f32, 0.0, libm::cos(theta) as f32);
            let dtheta = core::f64::consts::FRAC_PI_2 / n as f64;
            let ring = core::f64::consts::TAU * libm::sin(theta) * dtheta;
            hemi_cos += cosine_hemisphere_pdf(w) as f64 * ring;
            cone += uniform_cone_pdf(w, ctm) as f64 * ring;
        }
        assert!((hemi_cos - 1.0).abs() < 1e-4, "{hemi_cos}");
        // The cone's edge falls inside a cell; allow one cell's mass.
        assert!((cone - 1.0).abs() < 2e-2, "{cone}");
    }
}
