extern crate std;
use super::*;
use crate::Lambertian;
use radiometry::integrator::{Auto, DEFAULT_MAX_BUDGET, DirectionalAlbedo, integrate_to_tolerance};

fn dir(theta_deg: f32, phi: f32) -> Vec3 {
    let t = theta_deg.to_radians();
    Vec3::new(t.sin() * phi.cos(), t.sin() * phi.sin(), t.cos())
}

/// `∫ f cos θi dωi` by the crate's `auto` integrator to an absolute
/// tolerance (the integrators are verified against independent references in
/// the root crate's suites): the albedo of the BRDF as evaluated, not as it
/// reports it.
fn integrated_albedo<B: Brdf<Spectrum = f32>>(b: &B, wo: Vec3, tol: f64) -> (f64, f64) {
    let g = DirectionalAlbedo { brdf: b, wo };
    let out = integrate_to_tolerance(&Auto::new(), &g, tol, 64, DEFAULT_MAX_BUDGET).unwrap();
    assert!(out.reached(), "albedo at {wo:?} did not reach {tol}: {out:?}");
    (out.estimate.value, out.estimate.error)
}

/// `∫ f cos θi dωi` by plain (unwarped) adaptive cubature at 2¹⁷ and 2¹⁸
/// evaluations: the finer value, after checking that the two agree to
/// `2·10⁻⁴` (the layered materials have kinks and mixture seams that the
/// warped rules of `auto` can misjudge; plain subdivision converges on them).
fn robust_albedo<B: Brdf<Spectrum = f32>>(b: &B, wo: Vec3) -> f64 {
    use radiometry::integrator::{Adaptive, Integrator};
    let g = DirectionalAlbedo { brdf: b, wo };
    let a = Adaptive::new(0.0, 0.0).unwrap();
    let coarse = a.integrate(&g, 1 << 17).unwrap().value;
    let fine = a.integrate(&g, 1 << 18).unwrap().value;
    assert!((coarse - fine).abs() < 2e-4, "{wo:?}: {coarse} vs {fine}");
    fine
}

const THETAS: [f32; 9] = [0.0, 20.0, 40.0, 60.0, 70.0, 80.0, 85.0, 89.0, 89.9];

#[test]
fn defaults_are_openpbr_defaults_and_keep_albedo_below_one() {
    let p = OpenPbrParams::<f32>::default();
    assert_eq!((p.base_weight, p.base_color, p.base_metalness), (1.0, 0.8, 0.0));
    assert_eq!(
        (p.specular_roughness, p.specular_ior, p.coat_ior),
        (0.3, 1.5, 1.6)
    );
    assert_eq!((p.coat_weight, p.fuzz_weight, p.fuzz_roughness), (0.0, 0.0, 0.5));
    let m = OpenPbr::new(p).unwrap();
    for t in THETAS {
        let wo = dir(t, 0.4);
        let e = robust_albedo(&m, wo);
        assert!(e <= 1.0, "θo = {t}°: albedo {e}");
        assert!(e > 0.5, "θo = {t}°: albedo {e} (a white-ish base)");
        // The reported albedo is close to the integral.
        let r = m.directional_albedo(wo);
        assert!(
            (f64::from(r.value) - e).abs() <= f64::from(r.error),
            "{t}: {r:?} vs {e}"
        );
    }
}

#[test]
fn white_metal_loses_less_than_one_percent_up_to_alpha_half() {
    for r in [0.1f32, 0.3, 0.5, 0.7] {
        let m = OpenPbr::new(OpenPbrParams::<f32> {
            base_metalness: 1.0,
            base_color: 1.0,
            specular_color: 1.0,
            specular_roughness: r,
            ..OpenPbrParams::default()
        })
        .unwrap();
        for t in THETAS {
            let (e, err) = integrated_albedo(&m, dir(t, 1.1), 1e-3);
            assert!(
                e - err >= 0.99,
                "r = {r}, θo = {t}°: white metal albedo {e} ± {err}"
            );
            // The tables' consistency, not a margin, bounds the excess.
            assert!(
                e - err <= 1.0 + 2e-3,
                "r = {r}, θo = {t}°: albedo {e} ± {err} above 1 + 2e-3"
            );
        }
    }
}

/// Parameter sets that turn each layer on.
fn variety() -> [OpenPbrParams<f32>; 5] {
    let d = OpenPbrParams::<f32>::default();
    [
        d,
        OpenPbrParams {
            base_metalness: 0.4,
            base_diffuse_roughness: 0.7,
            specular_roughness: 0.1,
            ..d
        },
        OpenPbrParams {
            coat_weight: 1.0,
            coat_roughness: 0.2,
            coat_color: 0.7,
            base_metalness: 1.0,
            base_color: 0.9,
            specular_color: 0.8,
            ..d
        },
        OpenPbrParams {
            fuzz_weight: 0.8,
            fuzz_roughness: 0.4,
            fuzz_color: 0.9,
            coat_weight: 0.5,
            ..d
        },
        OpenPbrParams {
            specular_roughness: 0.0,
            coat_roughness: 0.0,
            coat_weight: 0.3,
            fuzz_weight: 1.0,
            fuzz_roughness: 0.0,
            specular_weight: 0.5,
            ..d
        },
    ]
}

#[test]
fn reciprocal_and_pdf_of_sample_is_bit_exact() {
    for p in variety() {
        let m = OpenPbr::with_layering(p, Layering::Reciprocal).unwrap();
        let mut n = 0;
        for i in 0..24 {
            let wo = dir(3.7 * i as f32, 0.9 * i as f32);
            for j in 0..24 {
                let wi = dir(3.9 * j as f32 + 1.0, 2.1 * j as f32);
                let (a, b) = (m.eval(wi, wo), m.eval(wo, wi));
                assert!(a.is_finite() && a >= 0.0);
                assert!((a - b).abs() <= 1e-5 * a.max(b).max(1.0), "{p:?}: {a} vs {b}");
                let u = [(j as f32 + 0.5) / 24.0, (i as f32 * 0.618_034).fract()];
                if let Some(s) = m.sample(wo, u) {
                    assert_eq!(s.pdf, m.pdf(s.wi, wo), "{p:?}");
                    assert!(s.weight.is_finite() && s.weight >= 0.0);
                    n += 1;
                }
            }
        }
        assert!(n > 400, "{p:?}: only {n} samples");
    }
}

#[test]
fn energy_at_most_one_for_every_variety() {
    for p in variety() {
        let m = OpenPbr::new(p).unwrap();
        for t in [0.0f32, 45.0, 75.0, 88.0] {
            let wo = dir(t, 0.3);
            let (e, err) = integrated_albedo(&m, wo, 1e-3);
            let stated = m.directional_albedo(wo);
            // Allowed: the tops' stated albedo errors (the layering's bound).
            assert!(
                e - err <= 1.0 + f64::from(stated.error),
                "{p:?} θo = {t}°: {e} ± {err}"
            );
        }
    }
}

#[test]
fn hard_inputs_stay_finite() {
    for p in variety() {
        let m = OpenPbr::new(p).unwrap();
        let hard = [
            Vec3::Z,
            Vec3::new(1.0, 0.0, 1e-7),
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(0.0, 0.0, -1.0),
            Vec3::new(f32::NAN, 0.0, 1.0),
            Vec3::new(f32::INFINITY, 0.0, 1.0),
            Vec3::ZERO,
        ];
        for &wo in &hard {
            for &wi in &hard {
                let f = m.eval(wi, wo);
                assert!(f.is_finite() && f >= 0.0, "{wi:?} {wo:?}: {f}");
                let pdf = m.pdf(wi, wo);
                assert!(pdf.is_finite() && pdf >= 0.0);
            }
            for u in [
                [0.0, 0.0],
                [1.0 - f32::EPSILON / 2.0; 2],
                [f32::NAN, 0.5],
                [2.0, -1.0],
            ] {
                if let Some(s) = m.sample(wo, u) {
                    assert!(s.weight.is_finite() && s.pdf > 0.0 && s.wi.is_finite());
                }
            }
            let a = m.directional_albedo(wo);
            assert!(a.value.is_finite() && a.error.is_finite());
        }
    }
}

#[test]
fn layers_reduce_to_their_pieces() {
    let wo = dir(50.0, 0.2);
    let dirs: [Vec3; 4] = [dir(10.0, 1.0), dir(45.0, 3.0), dir(70.0, -2.0), dir(89.0, 0.5)];
    // specular_weight 0: η_s = 1, no specular reflection; the glossy base is
    // EON alone, bit for bit.
    let d = OpenPbrParams::<f32> {
        specular_weight: 0.0,
        base_color: 0.6,
        base_weight: 0.9,
        base_diffuse_roughness: 0.4,
        ..OpenPbrParams::default()
    };
    let m = OpenPbr::new(d).unwrap();
    let eon = Eon::new(0.6f32 * 0.9, 0.4).unwrap();
    for wi in dirs {
        assert_eq!(m.eval(wi, wo), eon.eval(wi, wo));
    }
    // base_metalness 1: the F82-tint metal with Kulla & Conty's multiple
    // scattering, scaled by ξ_s — the crate's `KullaConty` plugin (the same
    // lobe shape, its normalisation integrated per instance) to 1 %.
    let d = OpenPbrParams::<f32> {
        base_metalness: 1.0,
        specular_weight: 0.7,
        specular_color: 0.9,
        ..OpenPbrParams::default()
    };
    let m = OpenPbr::new(d).unwrap();
    let metal = crate::KullaConty::<_, HeightCorrelated, _>::new(
        Ggx::new(0.09).unwrap(),
        F82Tint::new(0.8f32, 0.9).unwrap(),
    );
    for wi in dirs {
        let (a, b) = (m.eval(wi, wo), metal.eval(wi, wo) * 0.7);
        assert!((a - b).abs() <= 1e-2 * b + 1e-4, "{wi:?}: {a} vs {b}");
    }
    // A coat of index 1 reflects nothing and lets everything through.
    let base = OpenPbrParams::<f32>::default();
    let clear = OpenPbrParams {
        coat_weight: 1.0,
        coat_ior: 1.0,
        coat_color: 1.0,
        ..base
    };
    let (a, b) = (OpenPbr::new(base).unwrap(), OpenPbr::new(clear).unwrap());
    for wi in dirs {
        assert_eq!(a.eval(wi, wo), b.eval(wi, wo));
    }
    // A fuzz of weight 0 is skipped; the same stack under a fuzz of tiny
    // weight differs by about that weight.
    let fuzzy = OpenPbr::new(OpenPbrParams {
        fuzz_weight: 1e-3,
        ..base
    })
    .unwrap();
    for wi in dirs {
        let (x, y) = (a.eval(wi, wo), fuzzy.eval(wi, wo));
        assert!((x - y).abs() <= 2e-3 * x.max(1.0), "{x} vs {y}");
    }
    // A different (non-test) spectrum type builds too.
    let _ = Lambertian::new(0.5f32).unwrap();
}

#[test]
fn specular_weight_scales_f0_through_the_index() {
    let f0 = |eta: f32| ((eta - 1.0) / (eta + 1.0)).powi(2);
    for eta in [1.2f32, 1.5, 2.4, 0.8] {
        assert!((modulated_ior(eta, 1.0) - eta).abs() <= 1e-5 * eta);
        assert_eq!(modulated_ior(eta, 0.0), 1.0);
        for xi in [0.25f32, 0.5, 2.0] {
            let e = modulated_ior(eta, xi);
            assert!((f0(e) - xi * f0(eta)).abs() <= 1e-6, "η {eta} ξ {xi}: {e}");
            assert_eq!(e > 1.0, eta > 1.0);
        }
    }
    assert_eq!(modulated_ior(1.0, 1.0), 1.0);
}

#[test]
fn bad_parameters_name_the_parameter() {
    let d = OpenPbrParams::<f32>::default();
    let cases: [(OpenPbrParams<f32>, &str); 8] = [
        (
            OpenPbrParams {
                base_weight: 1.5,
                ..d
            },
            "base_weight",
        ),
        (
            OpenPbrParams {
                base_color: -0.1,
                ..d
            },
            "base_color",
        ),
        (
            OpenPbrParams {
                base_metalness: f32::NAN,
                ..d
            },
            "base_metalness",
        ),
        (
            OpenPbrParams {
                specular_roughness: 2.0,
                ..d
            },
            "specular_roughness",
        ),
        (
            OpenPbrParams {
                specular_ior: 0.5,
                ..d
            },
            "specular_ior",
        ),
        (OpenPbrParams { coat_color: 1.2, ..d }, "coat_color"),
        (
            OpenPbrParams {
                coat_ior: f32::INFINITY,
                ..d
            },
            "coat_ior",
        ),
        (
            OpenPbrParams {
                fuzz_weight: -1.0,
                ..d
            },
            "fuzz_weight",
        ),
    ];
    for (p, name) in cases {
        match OpenPbr::new(p) {
            Err(BrdfError::OutOfRange { name: n, .. }) | Err(BrdfError::NotFinite { name: n }) => {
                assert_eq!(n, name)
            }
            other => panic!("{name}: {other:?}"),
        }
    }
}

#[test]
fn rgb_colours_are_per_channel() {
    let p = OpenPbrParams::<Vec3> {
        base_color: Vec3::new(0.9, 0.2, 0.05),
        ..OpenPbrParams::default()
    };
    let m = OpenPbr::new(p).unwrap();
    let (wi, wo) = (dir(30.0, 0.0), dir(40.0, 2.0));
    let f = m.eval(wi, wo);
    assert!(f.x > f.y && f.y > f.z && f.z > 0.0);
    // Each channel equals the monochrome material of that channel's colour.
    for (c, v) in [0.9f32, 0.2, 0.05].into_iter().enumerate() {
        let mono = OpenPbr::new(OpenPbrParams::<f32> {
            base_color: v,
            ..OpenPbrParams::default()
        })
        .unwrap();
        let x = mono.eval(wi, wo);
        assert!(
            (f[c] - x).abs() <= 1e-6 * x.max(1.0),
            "channel {c}: {} vs {x}",
            f[c]
        );
    }
}

/// A prepared view gives the bits of the per-call methods.
#[test]
fn a_prepared_view_gives_the_bits_of_the_per_call_methods() {
    for layering in [Layering::EnergyConserving, Layering::Reciprocal] {
        for p in variety() {
            let m = OpenPbr::with_layering(p, layering).unwrap();
            for i in 0..8 {
                let wo = dir(11.0 * i as f32, 0.9 * i as f32);
                let view = m.prepare(wo);
                for j in 0..8 {
                    let wi = dir(10.9 * j as f32 + 0.5, 2.1 * j as f32);
                    assert_eq!(view.eval(wi).to_bits(), m.eval(wi, wo).to_bits());
                    assert_eq!(view.pdf(wi).to_bits(), m.pdf(wi, wo).to_bits());
                    let u = [(j as f32 + 0.5) / 8.0, 0.37];
                    assert_eq!(view.sample(u), m.sample(wo, u));
                }
            }
        }
    }
}

/// OpenPBR's "White furnace testing" configurations (white colours, no
/// absorption) keep all their energy in the energy-conserving mode:
/// `|E − 1| ≤ 2·10⁻³` by integration of `eval`, at roughnesses 0.05–1 and
/// indices 1.1–3.
#[test]
fn white_furnace_holds_in_the_energy_conserving_mode() {
    let w = OpenPbrParams::<f32> {
        base_color: 1.0,
        ..OpenPbrParams::default()
    };
    let configs = [
        OpenPbrParams {
            specular_roughness: 0.05,
            specular_ior: 3.0,
            ..w
        },
        OpenPbrParams {
            specular_roughness: 1.0,
            specular_ior: 1.1,
            ..w
        },
        OpenPbrParams {
            base_metalness: 1.0,
            specular_roughness: 0.5,
            ..w
        },
        OpenPbrParams {
            coat_weight: 1.0,
            coat_roughness: 0.05,
            coat_ior: 2.5,
            specular_weight: 0.0,
            ..w
        },
        OpenPbrParams {
            coat_weight: 0.6,
            coat_roughness: 0.7,
            base_metalness: 0.4,
            specular_roughness: 0.2,
            ..w
        },
        OpenPbrParams {
            fuzz_weight: 1.0,
            fuzz_roughness: 0.3,
            ..w
        },
        OpenPbrParams {
            coat_weight: 1.0,
            coat_roughness: 0.2,
            fuzz_weight: 1.0,
            base_metalness: 0.5,
            ..w
        },
    ];
    for p in configs {
        let m = OpenPbr::new(p).unwrap();
        for t in [0.0f32, 45.0, 75.0, 85.0] {
            let e = robust_albedo(&m, dir(t, 0.3));
            assert!((e - 1.0).abs() <= 2e-3, "{p:?} θo = {t}°: {e}");
        }
    }
}

/// The reciprocal mode: reciprocal to 10⁻⁵, a dielectric over a white
/// diffuse body within 2·10⁻³ of 1, and no white configuration above
/// `1 + 2·10⁻³`.
#[test]
fn reciprocal_mode_is_reciprocal_and_keeps_energy_bounded() {
    let w = OpenPbrParams::<f32> {
        base_color: 1.0,
        ..OpenPbrParams::default()
    };
    let configs = [
        (w, true),
        (
            OpenPbrParams {
                coat_weight: 1.0,
                coat_roughness: 0.1,
                specular_weight: 0.0,
                ..w
            },
            false,
        ),
        (
            OpenPbrParams {
                coat_weight: 1.0,
                coat_roughness: 0.1,
                base_metalness: 1.0,
                ..w
            },
            false,
        ),
        (
            OpenPbrParams {
                coat_weight: 1.0,
                coat_roughness: 0.2,
                fuzz_weight: 1.0,
                base_metalness: 0.5,
                ..w
            },
            false,
        ),
    ];
    for (p, tight) in configs {
        let m = OpenPbr::with_layering(p, Layering::Reciprocal).unwrap();
        for i in 0..12 {
            let wo = dir(7.3 * i as f32, 0.9 * i as f32);
            for j in 0..12 {
                let wi = dir(7.1 * j as f32 + 1.0, 2.1 * j as f32);
                let (a, b) = (m.eval(wi, wo), m.eval(wo, wi));
                assert!((a - b).abs() <= 1e-5 * a.max(b).max(1.0), "{p:?}: {a} vs {b}");
            }
        }
        for t in [0.0f32, 45.0, 75.0, 85.0] {
            let e = robust_albedo(&m, dir(t, 0.3));
            assert!(e <= 1.0 + 2e-3, "{p:?} θo = {t}°: {e}");
            if tight {
                assert!((e - 1.0).abs() <= 2e-3, "{p:?} θo = {t}°: {e}");
            }
        }
    }
}

/// The reciprocal mode's normalisations — `1/(1 − Ē_F)` and the joint
/// `1/(2∫ Π t μ dμ)` of the two coverage parts — are the 8-point
/// Gauss–Legendre sums written out (each integrand evaluated at each node by
/// its own reads, the nodes in order) bit for bit, for random parameters
/// with each layer on and off.
#[test]
fn reciprocal_normalisations_are_the_quadrature_written_out() {
    let x = [0.183_434_65f32, 0.525_532_4, 0.796_666_5, 0.960_289_9];
    let w = [0.362_683_78f32, 0.313_706_65, 0.222_381_03, 0.101_228_54];
    let written_out = |e: &dyn Fn(f32) -> f32| {
        let mut s = 0.0f32;
        for (x, w) in x.iter().zip(w) {
            for mu in [0.5 * (1.0 - x), 0.5 * (1.0 + x)] {
                s += 0.5 * w * 2.0 * mu * e(mu);
            }
        }
        s.clamp(0.0, 1.0)
    };
    let mut u = crate::test_stream::uniforms(0x3c6e_f372_fe94_f82b);
    for n in 0..200 {
        let on = |v: f32, k: usize| if (n >> k) & 1 == 0 { 0.0 } else { v };
        let p = OpenPbrParams::<f32> {
            specular_roughness: u(),
            specular_ior: 1.0 + 2.0 * u(),
            coat_weight: on(u(), 0),
            coat_roughness: u(),
            coat_ior: 1.0 + 2.0 * u(),
            fuzz_weight: on(u(), 1),
            fuzz_roughness: u(),
            base_metalness: u(),
            ..OpenPbrParams::default()
        };
        let m = OpenPbr::with_layering(p, Layering::Reciprocal).unwrap();
        let t = SheenAlbedoTable::get();
        let r_f = p.fuzz_roughness.max(MIN_SHEEN_ROUGHNESS);
        let (w_f, w_c) = (p.fuzz_weight, p.coat_weight);
        let e_s = |mu: f32| lobe_albedo(&m.spec, m.spec_ae)(mu);
        let e_c = |mu: f32| lobe_albedo(&m.coat, m.coat_ae)(mu);
        let t_f = |mu: f32| {
            if w_f > 0.0 {
                1.0 - w_f * t.albedo(mu, r_f)
            } else {
                1.0
            }
        };
        let t_c = |mu: f32| if w_c > 0.0 { 1.0 - e_c(mu) } else { 1.0 };
        let fuzz_norm = if w_f > 0.0 {
            inv(1.0 - written_out(&|mu| w_f * t.albedo(mu, r_f)))
        } else {
            1.0
        };
        let joint = [
            inv(written_out(&|mu| t_f(mu) * (1.0 - e_s(mu)))),
            inv(written_out(&|mu| t_f(mu) * t_c(mu) * (1.0 - e_s(mu)))),
        ];
        assert_eq!(m.fuzz_norm.to_bits(), fuzz_norm.to_bits(), "{p:?}");
        assert_eq!(m.joint_norm.map(f32::to_bits), joint.map(f32::to_bits), "{p:?}");
    }
}

/// The diffuse lobe's maps and the metal's multiple-scattering lobe take the
/// polar angle from `u₁` alone and the azimuth from the pick's rescaled `u₀`
/// (`polar_first`; what lets `sample` draw the polar part before the pick):
/// at one `u₁`, every `u₀` that picks the diffuse lobe gives the same `cos θi`
/// bit for bit, and the azimuth still turns with `u₀`; and `sample` draws
/// what its component's map draws at the rescaled `u₀`.
#[test]
fn polar_angle_of_the_diffuse_draw_is_u1_alone() {
    for sigma in [0.0f32, 0.7] {
        let m = OpenPbr::new(OpenPbrParams::<f32> {
            base_diffuse_roughness: sigma,
            ..OpenPbrParams::default()
        })
        .unwrap();
        for (theta, u1) in [(10.0f32, 0.31f32), (50.0, 0.77), (80.0, 0.05)] {
            let wo = dir(theta, 0.4);
            let view = m.prepare(wo);
            // The diffuse lobe is the last: its interval ends at 1. Split at the
            // uniform share p_u, each of its two components keeps its own polar map.
            let c = OpenPbrView::<f32>::COMPONENTS;
            let (w_u, w_t) = (view.component_weight(c - 2), view.component_weight(c - 1));
            assert!(w_t > 0.1, "{theta}°: transmission-shaped weight {w_t}");
            let lo = 1.0 - w_t;
            let mut seen = std::vec::Vec::new();
            for f in [0.1f32, 0.35, 0.6, 0.85] {
                let u0 = lo + f * w_t;
                let s = view.sample([u0, u1]).unwrap();
                let comp = view.sample_component(c - 1, [f, u1]).unwrap();
                assert!(
                    (s.wi - comp).length() < 1e-5,
                    "{theta}°, u₀ {u0}: {:?} vs {comp:?}",
                    s.wi
                );
                seen.push(s.wi);
            }
            for w in &seen {
                assert_eq!(
                    w.z.to_bits(),
                    seen[0].z.to_bits(),
                    "σ {sigma}, {theta}°: {seen:?}"
                );
            }
            assert!(
                (seen[0] - seen[2]).length() > 1e-3,
                "the azimuth does not turn: {seen:?}"
            );
            if w_u > 0.0 {
                // The uniform component: cos θi = u₁ (its map's polar coordinate).
                let s = view.sample([lo - 0.5 * w_u, u1]).unwrap();
                assert_eq!(s.wi.z, u1, "σ {sigma}, {theta}°: {:?}", s.wi);
            }
        }
    }
}

/// The lobes a material builds without their own checks (`from_valid`) get
/// parameters inside those checks' domains: on random valid parameters
/// (each at its bounds too), every lobe's checked constructor accepts what
/// the material gave the unchecked one, and builds the same lobe.
#[test]
fn unchecked_lobes_get_parameters_their_checks_accept() {
    let mut u = crate::test_stream::uniforms(0x0c4e_cced_10be_0505);
    let mut pick = |k: usize| match k % 4 {
        0 => 0.0,
        1 => 1.0,
        _ => u(),
    };
    for n in 0..3_000 {
        let p = OpenPbrParams::<f32> {
            base_weight: pick(n),
            base_color: pick(n / 2),
            base_metalness: pick(n / 3),
            base_diffuse_roughness: pick(n / 5),
            specular_weight: pick(n / 7),
            specular_roughness: pick(n / 11),
            specular_ior: 1.0 + 3.0 * pick(n / 13),
            coat_weight: pick(n / 17),
            coat_roughness: pick(n / 19),
            coat_ior: 1.0 + 3.0 * pick(n / 23),
            fuzz_weight: pick(n / 29),
            fuzz_roughness: pick(n / 31),
            ..OpenPbrParams::default()
        };
        let m = OpenPbr::new(p).unwrap_or_else(|e| panic!("{p:?}: {e}"));
        let (a_s, eta_s) = m.spec_ae;
        let (a_c, eta_c) = m.coat_ae;
        assert_eq!(
            Ggx::new(a_s).map(|g| g.alpha()),
            Ok(m.spec.distribution.alpha()),
            "{p:?}"
        );
        assert_eq!(
            Ggx::new(a_c).map(|g| g.alpha()),
            Ok(m.coat.distribution.alpha()),
            "{p:?}"
        );
        assert!(
            Dielectric::new(eta_s).is_ok() && Dielectric::new(eta_c).is_ok(),
            "{p:?}"
        );
        let rho = p.base_color * p.base_weight;
        assert_eq!(
            Eon::new(rho, p.base_diffuse_roughness).as_ref(),
            Ok(&m.diffuse),
            "{p:?}"
        );
        if let Some(f) = &m.fuzz {
            assert_eq!(
                LtcSheen::new(p.fuzz_color, p.fuzz_roughness).as_ref(),
                Ok(f),
                "{p:?}"
            );
        }
    }
}
