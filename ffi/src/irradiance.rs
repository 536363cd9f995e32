//! Irradiance closed forms on a surface with normal +Z
//! (`radiometry::light`, `radiometry::radiometric`):
//! `E = ∫_H L(ω) cos θ dω` (Nicodemus et al. 1977; PBR 4th ed. §4.1.3 eq. 4.7).
//! Lights are validated like the Rust constructors (`UniformSky::new`,
//! `Directional::new`, `Cap::new`): radiance finite in `[0, 1e30]`,
//! directions finite and non-zero (normalised here), cap half-angle in
//! `(0, π/2]` radians.

use crate::ptr::as_mut;
use crate::{RadStatus, RadVec3};
use radiometry::light::{Cap, Directional, UniformSky};
use radiometry::radiometric;

fn write(out: *mut f32, v: Result<f32, RadStatus>) -> RadStatus {
    // SAFETY: every caller forwards its own contract that `out` is null or
    // points to a writable float.
    match (unsafe { as_mut(out) }, v) {
        (Ok(o), Ok(v)) => {
            *o = v;
            RadStatus::Ok
        }
        (Err(s), _) | (_, Err(s)) => s,
    }
}

/// Uniform sky of radiance `L` over the upper hemisphere: `E = π L`
/// (PBR 4th ed. eq. 4.8).
///
/// # Safety
/// `out` is null or points to a writable `float`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rad_irradiance_sky(radiance: f32, out: *mut f32) -> RadStatus {
    write(
        out,
        UniformSky::new(radiance)
            .map(|l| l.irradiance())
            .map_err(Into::into),
    )
}

/// Directional (delta) light toward `direction` with irradiance `E⊥` on a
/// plane facing it: `E = E⊥ max(0, cos θ)` (Lambert's cosine law).
///
/// # Safety
/// `out` is null or points to a writable `float`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rad_irradiance_directional(
    direction: RadVec3,
    normal_irradiance: f32,
    out: *mut f32,
) -> RadStatus {
    write(
        out,
        Directional::new(direction.into(), normal_irradiance)
            .map(|l| l.irradiance())
            .map_err(Into::into),
    )
}

/// Uniform spherical cap (sun, spherical lamp) of radiance `L` and half-angle
/// `σ` (radians) around `axis`, clipped at the horizon: `E = L Ω⊥` with the
/// projected solid angle of Snyder 1996 (MSR-TR-96-11) in the form of Lagarde
/// & de Rousiers 2014 §4.7.2; `π L sin²σ cos θa` when the cap is fully above
/// the horizon.
///
/// # Safety
/// `out` is null or points to a writable `float`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rad_irradiance_cap(
    axis: RadVec3,
    half_angle: f32,
    radiance: f32,
    out: *mut f32,
) -> RadStatus {
    write(
        out,
        Cap::new(axis.into(), half_angle, radiance)
            .map(|l| l.irradiance())
            .map_err(Into::into),
    )
}

/// Solid angle of a cone of half-angle `θ` (radians):
/// `Ω = 2π(1 − cos θ) = 4π sin²(θ/2)` (PBR 4th ed. §4.1.1). `θ` is clamped to
/// `[0, π]`; NaN gives 0. Never fails.
#[unsafe(no_mangle)]
pub extern "C" fn rad_cap_solid_angle(half_angle: f32) -> f32 {
    radiometric::cap_solid_angle(half_angle)
}
