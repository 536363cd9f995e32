//! Closed-form radiometry: any finite cap geometry gives a finite,
//! non-negative irradiance no larger than π L.
#![no_main]
mod common;
use common::Floats;
use libfuzzer_sys::fuzz_target;
use radiometry::light::{Cap, Light};
use radiometry::radiometric::{cap_irradiance, cap_projected_solid_angle, cap_solid_angle};

fuzz_target!(|data: &[u8]| {
    let mut f = Floats(data);
    // Radiance within the documented domain (|L| < f32::MAX/π; lights cap it at MAX_RADIANCE).
    let (cos_axis, half, l) = (
        f.f32(),
        f.f32(),
        f.f32().abs().min(radiometry::light::MAX_RADIANCE),
    );
    let e: f32 = cap_irradiance(l, cos_axis, half);
    assert!(e.is_finite() && e >= 0.0, "{cos_axis} {half} {l} -> {e}");
    let p = cap_projected_solid_angle(cos_axis, half);
    assert!(
        p.is_finite() && (0.0..=core::f32::consts::PI * 1.0001).contains(&p),
        "{p}"
    );
    assert!(cap_solid_angle(half).is_finite());
    if let Ok(c) = Cap::new(f.vec3(), half, l) {
        if let Some(e) = c.closed_form_irradiance() {
            assert!(e.is_finite() && e >= 0.0);
        }
    }
});
