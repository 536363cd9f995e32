//! Light specs: `+`-sums of `cap(...)`, `sky(...)` and `directional(...)`.

use crate::SpecError;
use crate::args::Args;
use crate::call::parse_sum;
use crate::error::err_span;

/// Help text describing the light spec language.
pub const LIGHT_SPEC_HELP: &str = "Light spec (angles in degrees; `+` sums lights), e.g. \
`cap(axis_theta=95, axis_phi=0, half_angle=10, radiance=1)`, `sky(radiance=1)`, \
`directional(theta=30, phi=0, irradiance=1)`, `sky(radiance=0.2) + directional(theta=30, irradiance=3)`. \
Defaults: phi/axis_phi=0, radiance/irradiance=1; theta/axis_theta ∈ [0, 180] and half_angle ∈ (0, 90] are required.";

/// One light of a light spec (angles in degrees).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum LightSpec {
    /// Uniform spherical cap of radiance `radiance` around the axis (θ, φ).
    Cap {
        /// Polar angle of the axis from +Z, degrees.
        axis_theta: f64,
        /// Azimuth of the axis, degrees.
        axis_phi: f64,
        /// Half opening angle, degrees.
        half_angle: f64,
        /// Radiance.
        radiance: f64,
    },
    /// Uniform sky (whole upper hemisphere) of radiance `radiance`.
    Sky {
        /// Radiance.
        radiance: f64,
    },
    /// Directional (delta) light of normal irradiance `irradiance` from (θ, φ).
    Directional {
        /// Polar angle, degrees.
        theta: f64,
        /// Azimuth, degrees.
        phi: f64,
        /// Irradiance on a surface facing the light.
        irradiance: f64,
    },
}

/// Parses and validates a light spec (a `+`-sum of lights).
pub fn parse_lights(spec: &str) -> Result<Vec<LightSpec>, SpecError> {
    let calls = parse_sum(spec)?;
    let mut out = Vec::new();
    for c in &calls {
        out.push(match c.name.as_str() {
            "cap" | "cone" | "sun" => {
                let mut a = Args::new(spec, c, &["axis_theta", "axis_phi", "half_angle", "radiance"])?;
                LightSpec::Cap {
                    axis_theta: a.num("axis_theta", None, 0.0, 180.0, false)?,
                    axis_phi: a.num("axis_phi", Some(0.0), -360.0, 360.0, false)?,
                    half_angle: a.num("half_angle", None, 0.0, 90.0, true)?,
                    radiance: a.num("radiance", Some(1.0), 0.0, 1e30, false)?,
                }
            }
            "sky" => {
                let mut a = Args::new(spec, c, &["radiance"])?;
                LightSpec::Sky {
                    radiance: a.num("radiance", Some(1.0), 0.0, 1e30, false)?,
                }
            }
            "directional" => {
                let mut a = Args::new(spec, c, &["theta", "phi", "irradiance"])?;
                LightSpec::Directional {
                    theta: a.num("theta", None, 0.0, 180.0, false)?,
                    phi: a.num("phi", Some(0.0), -360.0, 360.0, false)?,
                    irradiance: a.num("irradiance", Some(1.0), 0.0, 1e30, false)?,
                }
            }
            other => {
                return Err(err_span(
                    spec,
                    c.name_span,
                    format!("unknown light `{other}` (expected cap, sky or directional)"),
                ));
            }
        });
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn caret_of(e: &SpecError) -> &str {
        &e.spec[e.start..e.end]
    }

    #[test]
    fn lights() {
        let l = parse_lights("cap(axis_theta=95, half_angle=10, radiance=1)").unwrap();
        assert_eq!(
            l,
            vec![LightSpec::Cap {
                axis_theta: 95.0,
                axis_phi: 0.0,
                half_angle: 10.0,
                radiance: 1.0
            }]
        );
        let l = parse_lights("sky(radiance=2) + directional(theta=30, irradiance=1)+sky").unwrap();
        assert_eq!(l.len(), 3);
        assert_eq!(l[0], LightSpec::Sky { radiance: 2.0 });
        assert_eq!(
            l[1],
            LightSpec::Directional {
                theta: 30.0,
                phi: 0.0,
                irradiance: 1.0
            }
        );
        for (spec, bad) in [
            ("cap(axis_theta=95, radiance=1)", "cap"),
            ("sky(radiance=1) +", ""),
            ("sky(radiance=1) + lamp", "lamp"),
            ("directional(theta=200)", "200"),
            ("sky(radiance=1) sky", "sky"),
        ] {
            let e = parse_lights(spec).expect_err(spec);
            assert_eq!(caret_of(&e), bad, "{spec}: {e}");
        }
    }
}
