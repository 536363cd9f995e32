//! Unit tests of the combinators on two closed-form test lobes; the
//! property suites (`tests/`) run them over the plugins.

use super::*;
use crate::brdf::IsotropicBrdf;
use crate::frame::spherical_direction;
use crate::warp::{cosine_hemisphere_pdf, square_to_cosine_hemisphere};
use core::f32::consts::FRAC_1_PI;

/// `ρ/π`, with its exact albedo.
#[derive(Clone, Copy, Debug)]
struct Flat(f32);
impl Brdf for Flat {
    type Spectrum = f32;
    fn eval(&self, wi: Vec3, wo: Vec3) -> f32 {
        if wi.z > 0.0 && wo.z > 0.0 {
            self.0 * FRAC_1_PI
        } else {
            0.0
        }
    }
    fn directional_albedo(&self, wo: Vec3) -> Albedo<f32> {
        if wo.z > 0.0 {
            Albedo::bounded(self.0, 0.0)
        } else {
            Albedo::zero()
        }
    }
}
impl IsotropicBrdf for Flat {}

/// A reciprocal peaked lobe `k (n + 1)/(2π) max(wi·r(wo), 0)^n` about the
/// mirror direction `r(wo)`, sampled by a cosine lobe (default sampler) —
/// a lobe whose albedo depends on `ωo`, and the default albedo rule.
#[derive(Clone, Copy, Debug)]
struct Glossy(f32);
impl Brdf for Glossy {
    type Spectrum = f32;
    fn eval(&self, wi: Vec3, wo: Vec3) -> f32 {
        if !(wi.z > 0.0 && wo.z > 0.0) {
            return 0.0;
        }
        let r = Vec3::new(-wo.x, -wo.y, wo.z);
        let c = wi.dot(r).max(0.0);
        0.3 * (self.0 + 1.0) / (2.0 * core::f32::consts::PI) * libm::powf(c, self.0)
    }
}
impl IsotropicBrdf for Glossy {}

fn directions() -> impl Iterator<Item = Vec3> {
    (0..12).flat_map(|i| (0..5).map(move |j| spherical_direction(0.13 * i as f32, 1.3 * j as f32)))
}

fn us() -> impl Iterator<Item = [f32; 2]> {
    (0..9)
        .flat_map(|i| (0..9).map(move |j| [(i as f32 + 0.3) / 9.0, (j as f32 + 0.6) / 9.0]))
        .chain([[0.0, 0.0], [ONE_MINUS_EPS, ONE_MINUS_EPS]])
}

fn check_sampling<B: Brdf<Spectrum = f32>>(b: &B) {
    for wo in directions() {
        for u in us() {
            if let Some(s) = b.sample(wo, u) {
                assert_eq!(s.pdf, b.pdf(s.wi, wo), "wo={wo:?} u={u:?}");
                assert!(s.pdf > 0.0 && s.weight.is_finite() && s.weight >= 0.0);
                let w = b.eval(s.wi, wo) * s.wi.z / s.pdf;
                assert!((s.weight - w).abs() <= 1e-5 * w.abs().max(1.0));
            }
        }
    }
}

#[test]
fn default_albedo_rule_is_exact_for_a_cosine_sampled_flat_lobe() {
    struct Plain;
    impl Brdf for Plain {
        type Spectrum = f32;
        fn eval(&self, wi: Vec3, wo: Vec3) -> f32 {
            if wi.z > 0.0 && wo.z > 0.0 {
                0.7 * FRAC_1_PI
            } else {
                0.0
            }
        }
    }
    let e = Plain.directional_albedo(spherical_direction(1.2, 0.4));
    assert!(
        (e.value - 0.7).abs() < 1e-6 && e.error < 1e-6 && !e.is_bound,
        "{e:?}"
    );
    assert_eq!(Plain.directional_albedo(Vec3::new(0.0, 1.0, 0.0)), Albedo::zero());
    assert_eq!(Plain.directional_albedo(Vec3::NAN), Albedo::zero());
}

#[test]
fn sum_and_mix_add_albedos_and_sample_consistently() {
    let s = Sum::new(Flat(0.25), Glossy(20.0));
    let m = Mix::new(0.3, Flat(0.9), Glossy(20.0)).unwrap();
    check_sampling(&s);
    check_sampling(&m);
    let wo = spherical_direction(0.4, 0.0);
    let g = Glossy(20.0).directional_albedo(wo).value;
    assert!((s.directional_albedo(wo).value - (0.25 + g)).abs() < 1e-6);
    assert!((m.directional_albedo(wo).value - (0.27 + 0.7 * g)).abs() < 1e-6);
    // Albedo-proportional picking.
    assert!((s.pick_probability(wo) - 0.25 / (0.25 + g)).abs() < 1e-6);
    assert_eq!(
        Mix::new(0.0, Flat(1.0), Flat(0.5)).unwrap().pick_probability(wo),
        0.0
    );
    for w in [-0.1, 1.1, f32::NAN] {
        assert!(matches!(
            Mix::new(w, Flat(1.0), Flat(1.0)),
            Err(ComposeError::Weight(_))
        ));
    }
}

#[test]
fn a_lobe_with_zero_albedo_is_never_picked() {
    let s = Sum::new(Flat(0.0), Glossy(5.0));
    let wo = spherical_direction(0.8, 0.0);
    assert_eq!(s.pick_probability(wo), 0.0);
    check_sampling(&s);
    // Neither reflects: half and half, and every sample's weight is zero.
    let z = Sum::new(Flat(0.0), Flat(0.0));
    assert_eq!(z.pick_probability(wo), 0.5);
    check_sampling(&z);
}

#[test]
fn nested_sums_are_three_lobe_mixtures() {
    let s = Sum::new(Sum::new(Flat(0.1), Glossy(50.0)), Flat(0.2));
    check_sampling(&s);
    let wo = spherical_direction(0.3, 1.0);
    let wi = spherical_direction(0.5, 2.0);
    let direct = 0.3 * FRAC_1_PI + Glossy(50.0).eval(wi, wo);
    assert!((s.eval(wi, wo) - direct).abs() < 1e-6);
}

#[test]
fn scaled_multiplies_values_weights_and_albedo_only() {
    let b = Scaled::new(Glossy(10.0), 0.5f32).unwrap();
    check_sampling(&b);
    let wo = spherical_direction(0.7, 0.0);
    let s = b.sample(wo, [0.2, 0.9]).unwrap();
    let t = Glossy(10.0).sample(wo, [0.2, 0.9]).unwrap();
    assert_eq!((s.wi, s.pdf), (t.wi, t.pdf));
    assert_eq!(s.weight, t.weight * 0.5);
    for bad in [-1.0, f32::INFINITY, f32::NAN] {
        assert!(Scaled::new(Flat(1.0), bad).is_err());
    }
}

#[test]
fn coated_is_reciprocal_energy_safe_and_consistent() {
    let top = Glossy(30.0);
    for (base, layering) in [
        (Flat(1.0), Layering::Reciprocal),
        (Flat(0.4), Layering::Reciprocal),
        (Flat(1.0), Layering::EnergyConserving),
    ] {
        let c = Coated::new(top, base).with_layering(layering);
        let tinted = Coated::with_absorption(top, base, 0.6f32, 1.5)
            .unwrap()
            .with_layering(layering);
        check_sampling(&c);
        check_sampling(&tinted);
        for wo in directions() {
            for wi in directions() {
                for layer in [&c, &tinted] {
                    let (a, b) = (layer.eval(wi, wo), layer.eval(wo, wi));
                    if layering == Layering::Reciprocal {
                        assert!((a - b).abs() <= 1e-6 * a.abs().max(1e-3), "{a} vs {b}");
                    }
                    assert!(a.is_finite() && a >= 0.0);
                }
            }
            // Energy, by cosine-weighted quadrature of the layer itself
            // (stratified 64×64; the lobe is broad enough for this rule).
            let mut e = 0.0f64;
            for i in 0..64 {
                for j in 0..64 {
                    let wi = square_to_cosine_hemisphere([(i as f32 + 0.5) / 64.0, (j as f32 + 0.5) / 64.0]);
                    let p = cosine_hemisphere_pdf(wi);
                    if p > 0.0 {
                        e += f64::from(c.eval(wi, wo) * wi.z / p) / 4096.0;
                    }
                }
            }
            // E ≤ E_T + (1 − E_T,reported) E_B exceeds 1 by at most what the
            // top's reported albedo (here the default 16-sample estimate)
            // misses of its true albedo (the same quadrature of the top
            // alone), in both modes.
            let mut e_top = 0.0f64;
            for i in 0..64 {
                for j in 0..64 {
                    let wi = square_to_cosine_hemisphere([(i as f32 + 0.5) / 64.0, (j as f32 + 0.5) / 64.0]);
                    let p = cosine_hemisphere_pdf(wi);
                    if p > 0.0 {
                        e_top += f64::from(top.eval(wi, wo) * wi.z / p) / 4096.0;
                    }
                }
            }
            let slack = (e_top - f64::from(top.directional_albedo(wo).value)).max(0.0);
            assert!(e <= 1.0 + 2e-3 + slack, "albedo {e} at {wo:?} ({layering:?})");
            let claim = c.directional_albedo(wo);
            assert!(
                (e - f64::from(claim.value)).abs() <= f64::from(claim.error) + 2e-3 + slack,
                "{e} vs {claim:?}"
            );
        }
    }
    assert!(matches!(
        Coated::with_absorption(Flat(0.1), Flat(1.0), 1.5f32, 1.5),
        Err(ComposeError::CoatColor(_))
    ));
    assert!(matches!(
        Coated::with_absorption(Flat(0.1), Flat(1.0), 0.5f32, 0.9),
        Err(ComposeError::CoatIor(_))
    ));
}

#[test]
fn a_clear_coat_over_a_white_lambertian_keeps_what_the_formula_says() {
    // Energy-conserving: E = E_T + (1 − E_T) · 1 = 1 at every ωo.
    let c = Coated::new(Flat(0.1), Flat(1.0));
    for t in [0.0f32, 0.6, 1.2, 1.55] {
        let e = c.directional_albedo(spherical_direction(t, 0.0));
        assert!((e.value - 1.0).abs() < 1e-5, "{e:?}");
    }
}

/// A prepared view equals the plain calls bit for bit: `eval`, `pdf` and
/// `sample` at every `ωo` (below the horizon included), in both layering
/// modes, clear, absorbing and tinted, against the pre-view definitions
/// (`sample` = pick with `pick_probability`, then the mixture pdf and the
/// plain `eval`).
#[test]
fn coated_view_equals_the_plain_calls() {
    let below = [Vec3::new(0.6, 0.0, -0.8), Vec3::new(1.0, 0.0, 0.0)];
    for layering in [Layering::EnergyConserving, Layering::Reciprocal] {
        let plain = Coated::new(Glossy(30.0), Flat(0.8)).with_layering(layering);
        let absorbing = Coated::with_absorption(Glossy(30.0), Flat(0.8), 0.6f32, 1.5)
            .unwrap()
            .with_layering(layering);
        let tinted = Coated::new(Glossy(8.0), Flat(0.3))
            .with_layering(layering)
            .with_top_tint(0.5f32)
            .unwrap();
        for layer in [&plain, &absorbing, &tinted] {
            for wo in directions().chain(below) {
                let view = layer.prepare(wo);
                for wi in directions().chain(below) {
                    assert_eq!(view.eval(wi).to_bits(), layer.eval(wi, wo).to_bits(), "{wi} {wo}");
                    assert_eq!(view.pdf(wi).to_bits(), layer.pdf(wi, wo).to_bits(), "{wi} {wo}");
                }
                for u in us() {
                    let p = layer.pick_probability(wo);
                    let reference = pick_and_sample(
                        p,
                        u,
                        |v| layer.top().sample(wo, v),
                        |v| layer.base().sample(wo, v),
                    )
                    .and_then(|wi| {
                        let pdf = mixture_pdf(p, layer.top().pdf(wi, wo), layer.base().pdf(wi, wo));
                        finish_sample(wi, layer.eval(wi, wo), pdf)
                    });
                    assert_eq!(view.sample(u), reference, "{wo} {u:?}");
                    assert_eq!(layer.sample(wo, u), reference, "{wo} {u:?}");
                }
            }
        }
    }
}
