//! The RGB run-time BRDF: colours survive, named metals are coloured by an
//! independent `f64` reduction of their measured `η`, `k`, MERL channels are
//! kept, and a grey spec gives the monochrome values on every channel.

use super::*;
use crate::parse_brdf;
use radiometry::spectral::{SpectralCurve, d65, x_bar, y_bar, z_bar};

fn mono(text: &str) -> AnyBrdf {
    build_brdf(text, &parse_brdf(text).unwrap()).unwrap()
}

fn rgb(text: &str) -> AnyBrdfRgb {
    build_brdf_rgb(text, &parse_brdf(text).unwrap()).unwrap()
}

fn dir(theta_deg: f64, phi_deg: f64) -> Vec3 {
    let (t, p) = (theta_deg.to_radians(), phi_deg.to_radians());
    Vec3::new(
        (t.sin() * p.cos()) as f32,
        (t.sin() * p.sin()) as f32,
        t.cos() as f32,
    )
}

/// Exact Fresnel reflectance of a conductor `η + ik` at `cos θ = mu`, in
/// `f64` (unpolarised mean of `R_s` and `R_p`; Born & Wolf § 14.2, in the
/// form of pbrt-v3's `FrConductor`).
fn fresnel_conductor_f64(mu: f64, eta: f64, k: f64) -> f64 {
    let c2 = mu * mu;
    let s2 = 1.0 - c2;
    let t0 = eta * eta - k * k - s2;
    let a2b2 = (t0 * t0 + 4.0 * eta * eta * k * k).sqrt();
    let a = (0.5 * (a2b2 + t0)).max(0.0).sqrt();
    let t1 = a2b2 + c2;
    let t2 = 2.0 * mu * a;
    let rs = (t1 - t2) / (t1 + t2);
    let t3 = c2 * a2b2 + s2 * s2;
    let t4 = t2 * s2;
    let rp = rs * (t3 - t4) / (t3 + t4);
    0.5 * (rs + rp)
}

/// `(η, k)` of gold at `lambda` nm, linear between the published rows
/// (Johnson & Christy 1972, as tabulated in the crate's metal data).
fn gold_eta_k(lambda: f64) -> (f64, f64) {
    let t = radiometry_brdfs::metals::Metal::Au.table();
    let l: Vec<f64> = t.lambda_nm.iter().map(|&v| v as f64).collect();
    let j = l.iter().position(|&v| v > lambda).unwrap();
    let s = (lambda - l[j - 1]) / (l[j] - l[j - 1]);
    let lerp = |v: &[f32]| v[j - 1] as f64 + s * (v[j] as f64 - v[j - 1] as f64);
    (lerp(t.eta), lerp(t.k))
}

/// Gold's spectral Fresnel reflectance at `cos θ = mu` reduced to linear
/// sRGB, all in `f64`: `XYZ = Σ F(λ) D65(λ) x̄ȳz̄(λ) / Σ D65(λ) ȳ(λ)` over 360,
/// 365, …, 780 nm (CIE 1931 2°, CIE 015:2018 tables), then the IEC 61966-2-1
/// matrix, each channel clamped to [0, 1].
fn gold_rgb_f64(mu: f64) -> [f64; 3] {
    let (xb, yb, zb, d) = (x_bar(), y_bar(), z_bar(), d65());
    let (mut xyz, mut white) = ([0.0f64; 3], 0.0f64);
    for i in 0..85 {
        let l = 360.0 + 5.0 * i as f64;
        let (eta, k) = gold_eta_k(l);
        let f = fresnel_conductor_f64(mu, eta, k);
        let w = d.value(l as f32) as f64;
        let y = yb.value(l as f32) as f64;
        xyz[0] += f * w * xb.value(l as f32) as f64;
        xyz[1] += f * w * y;
        xyz[2] += f * w * zb.value(l as f32) as f64;
        white += w * y;
    }
    let xyz = xyz.map(|v| v / white);
    let m = [
        [3.2406, -1.5372, -0.4986],
        [-0.9689, 1.8758, 0.0415],
        [0.0557, -0.2040, 1.0570],
    ];
    std::array::from_fn(|r| (m[r][0] * xyz[0] + m[r][1] * xyz[1] + m[r][2] * xyz[2]).clamp(0.0, 1.0))
}

/// Per channel, the `η`, `k` on Gulbrandsen's (2014) family with `F(1) = r`
/// whose `F(1/7) = h` (bisection in `f64`), then its exact Fresnel at `mu`.
/// As documented in `radiometry_brdfs::metals`, `r` is limited to
/// `[10⁻⁴, 0.996]` (gold's red, out of the sRGB gamut, reduces to 1).
fn two_angle_fit_f64(r: f64, h: f64, mu: f64) -> f64 {
    let r = r.clamp(1e-4, 0.996);
    let sr = r.sqrt();
    let at = |g: f64| {
        let n = g * (1.0 - r) / (1.0 + r) + (1.0 - g) * (1.0 + sr) / (1.0 - sr);
        let k2 = (r * (n + 1.0) * (n + 1.0) - (n - 1.0) * (n - 1.0)) / (1.0 - r);
        (n, k2.max(0.0).sqrt())
    };
    let (mut lo, mut hi) = (0.0f64, 1.0f64);
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        let (n, k) = at(mid);
        if fresnel_conductor_f64(1.0 / 7.0, n, k) < h {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let (n, k) = at(0.5 * (lo + hi));
    fresnel_conductor_f64(mu, n, k)
}

/// The target: `ggx(alpha=0.3, fresnel=conductor(metal=Au))` at
/// `--wi 30,0 --wo 30,180` (the half vector is the normal, `cos θd = cos 30°`)
/// has three channels whose ratios are those of gold's Fresnel reduced the
/// documented way, recomputed here in `f64` from the published `η`, `k`
/// (within 10⁻⁴); each value is `D G2 F / (4 cos² 30°)` in `f64` (within
/// 10⁻⁵); and the run-time BRDF is the typed plugin bit for bit.
#[test]
fn gold_rgb_is_the_independent_reduction() {
    let text = "ggx(alpha=0.3, fresnel=conductor(metal=Au))";
    let (wi, wo) = (dir(30.0, 0.0), dir(30.0, 180.0));
    let f = rgb(text).eval(wi, wo);
    let mu = 30f64.to_radians().cos();
    let (f0, fb) = (gold_rgb_f64(1.0), gold_rgb_f64(1.0 / 7.0));
    let fresnel: [f64; 3] = std::array::from_fn(|c| two_angle_fit_f64(f0[c], fb[c], mu));
    // Gold: red above green above blue.
    assert!(f.x > f.y && f.y > f.z, "{f}");
    for (a, b) in [(0, 2), (1, 2), (0, 1)] {
        let got = f[a] as f64 / f[b] as f64;
        let want = fresnel[a] / fresnel[b];
        assert!(
            (got / want - 1.0).abs() < 1e-4,
            "channels {a}/{b}: {got} vs {want}"
        );
    }
    let alpha = 0.3f64;
    let d = 1.0 / (std::f64::consts::PI * alpha * alpha);
    let tan2 = 30f64.to_radians().tan().powi(2);
    let lambda = 0.5 * (-1.0 + (1.0 + alpha * alpha * tan2).sqrt());
    let g2 = 1.0 / (1.0 + 2.0 * lambda);
    for c in 0..3 {
        let want = d * g2 * fresnel[c] / (4.0 * mu * mu);
        assert!(
            (f[c] as f64 / want - 1.0).abs() < 1e-5,
            "channel {c}: {} vs {want}",
            f[c]
        );
    }
    let typed = Microfacet::<Ggx, HeightCorrelated, _>::new(
        Ggx::new(0.3).unwrap(),
        Conductor::<Vec3>::metal(radiometry_brdfs::metals::Metal::Au),
    );
    assert_eq!(f, typed.eval(wi, wo));
    // The two-angle fit against the reduction of the spectral Fresnel at the
    // evaluation angle itself: they differ by the fit's error (stated in
    // docs/cli.md), well under 1 % for gold at 30°.
    let direct = gold_rgb_f64(mu);
    for c in 0..3 {
        assert!(
            (fresnel[c] / direct[c] - 1.0).abs() < 1e-2,
            "{c}: {fresnel:?} {direct:?}"
        );
    }
}

/// Every named metal is coloured in RGB (not grey) and its monochrome form
/// stays today's luminance conductor.
#[test]
fn metals_are_coloured_per_channel() {
    let (wi, wo) = (dir(20.0, 0.0), dir(40.0, 180.0));
    for m in radiometry_brdfs::metals::Metal::ALL {
        let text = format!("ggx(alpha=0.2, fresnel=conductor(metal={}))", m.name());
        let spec = parse_brdf(&text).unwrap();
        assert!(!spec.is_grey(), "{text}");
        let c = build_brdf_rgb(&text, &spec).unwrap().eval(wi, wo);
        assert!(c.is_finite() && c.min_element() > 0.0, "{text}: {c}");
        let typed =
            Microfacet::<Ggx, HeightCorrelated, _>::new(Ggx::new(0.2).unwrap(), Conductor::<Vec3>::metal(m));
        assert_eq!(c, typed.eval(wi, wo), "{text}");
    }
    // Copper is red, silver nearly neutral.
    let cu = rgb("ggx(alpha=0.2, fresnel=conductor(metal=Cu))").eval(wi, wo);
    assert!(cu.x > 1.3 * cu.z, "{cu}");
    let ag = rgb("ggx(alpha=0.2, fresnel=conductor(metal=Ag))").eval(wi, wo);
    assert!(ag.z > 0.85 * ag.x, "{ag}");
}

/// `rgb(R, G, B)` survives to the BRDF: the channel ratios of a Lambertian
/// (and of EON, a sheen and OpenPBR's diffuse-only base) are the colour's.
#[test]
fn rgb_colours_survive_to_the_brdf() {
    let (wi, wo) = (dir(35.0, 10.0), dir(50.0, 200.0));
    let f = rgb("lambertian(albedo=rgb(0.8, 0.4, 0.1))").eval(wi, wo);
    let pi = std::f32::consts::PI;
    assert_eq!(f, Vec3::new(0.8, 0.4, 0.1) / pi);
    assert!(
        (f.x / f.z - 8.0).abs() < 1e-6 && (f.y / f.z - 4.0).abs() < 1e-6,
        "{f}"
    );
    // The monochrome path is the colour's luminance.
    let m = mono("lambertian(albedo=rgb(0.8, 0.4, 0.1))").eval(wi, wo);
    assert_eq!(m, (0.2126 * 0.8 + 0.7152 * 0.4 + 0.0722 * 0.1) as f32 / pi);
    // FON is linear in ρ (EON is not: its multiple-scattering term goes with ρ²).
    let e = rgb("fon(rho=rgb(0.2, 0.4, 0.8), sigma=0.5)").eval(wi, wo);
    assert!(
        (e.y / e.x - 2.0).abs() < 1e-6 && (e.z / e.x - 4.0).abs() < 1e-6,
        "{e}"
    );
    let s = rgb("sheen(color=rgb(0.9, 0.3, 0.6), roughness=0.5)").eval(wi, wo);
    assert!(
        (s.x / s.y - 3.0).abs() < 1e-5 && (s.z / s.y - 2.0).abs() < 1e-5,
        "{s}"
    );
    // A red OpenPBR plastic: red above green and blue, green = blue.
    let o = rgb("openpbr(base_color=rgb(0.8, 0.1, 0.1))").eval(wi, wo);
    assert!(o.x > 3.0 * o.y && o.y == o.z, "{o}");
    // Per-channel albedos: the colour times the white albedo.
    let a = rgb("lambertian(albedo=rgb(0.8, 0.4, 0.1))")
        .directional_albedo(wo)
        .value;
    assert_eq!(a, Vec3::new(0.8, 0.4, 0.1));
}

/// A grey spec gives the monochrome values on every channel: `eval` and the
/// directional albedo bit for bit, over a grid of directions and every plugin
/// and composition. Densities agree to rounding (10⁻⁶ relative; samples 10⁻⁵):
/// composites pick their lobes in proportion to the lobes' channel-average
/// albedos, and `(x + x + x)/3` need not round to `x`.
#[test]
fn grey_specs_are_the_same_in_rgb_and_mono() {
    let close = |a: f32, b: f32| (a - b).abs() <= 1e-6 * a.abs().max(b.abs());
    let specs = [
        "lambertian(albedo=0.5)",
        "lambertian(albedo=rgb(0.3, 0.3, 0.3))",
        "phong(exponent=40, ks=0.6, kd=0.3)",
        "blinn-phong(exponent=80, ks=0.5, kd=0.5)",
        "ggx(alpha=0.3)",
        "ggx(alpha=0.3, fresnel=dielectric(eta=1.5), ms=kulla-conty, kd=0.3)",
        "beckmann(alpha=0.2, g=separable, fresnel=schlick(f0=0.04))",
        "ggx(alpha=0.5, fresnel=conductor(eta=0.2, k=3.9), ms=kulla-conty)",
        "ggx(alpha=0.4, fresnel=f82(f0=0.9, f82=0.7))",
        "eon(rho=0.7, sigma=0.5)",
        "fon(rho=0.7, sigma=0.5)",
        "oren-nayar(rho=0.5, sigma_rad=0.35)",
        "sheen(color=0.8, roughness=0.4)",
        "ltc-sheen(color=0.8, roughness=0.4)",
        "openpbr",
        "openpbr(base_color=rgb(0.5, 0.5, 0.5), base_metalness=0.5, coat_weight=0.7, coat_color=0.8, fuzz_weight=0.3)",
        "coated(ggx(alpha=0.1, fresnel=dielectric(eta=1.5)), eon(rho=0.6, sigma=0.3), coat_color=0.5)",
        "mix(0.3, lambertian(albedo=0.4), ggx(alpha=0.2, fresnel=schlick(f0=0.5)))",
        "lambertian(albedo=0.2) + ggx(alpha=0.6, fresnel=dielectric(eta=1.4))",
    ];
    let splat = |v: f32| Vec3::splat(v);
    for text in specs {
        assert!(parse_brdf(text).unwrap().is_grey(), "{text}");
        let (m, c) = (mono(text), rgb(text));
        for to in [0.0, 25.0, 60.0, 85.0, 89.9] {
            let wo = dir(to, 0.0);
            let (am, ac) = (m.directional_albedo(wo), c.directional_albedo(wo));
            assert_eq!(splat(am.value), ac.value, "{text} albedo at {to}°");
            // A sampled albedo's error estimate is the spread of the channel averages of 16 strata:
            // (x + x + x)/3 rounds, and the spread of nearly equal numbers amplifies it (≈ 1.4e-6
            // seen), so it agrees to rounding, not bit for bit (the value does).
            assert_eq!(am.is_bound, ac.is_bound, "{text} albedo at {to}°");
            assert!(
                (ac.error - am.error).abs() <= 1e-5 * am.error,
                "{text} albedo error at {to}°: {} vs {}",
                ac.error,
                am.error
            );
            for ti in [0.0, 30.0, 70.0, 89.0] {
                for pi in [0.0, 90.0, 180.0, 300.0] {
                    let wi = dir(ti, pi);
                    assert_eq!(
                        splat(m.eval(wi, wo)),
                        c.eval(wi, wo),
                        "{text} eval {ti},{pi} {to}"
                    );
                    let (pm, pc) = (m.pdf(wi, wo), c.pdf(wi, wo));
                    assert!(close(pm, pc), "{text} pdf {ti},{pi} {to}: {pm} vs {pc}");
                }
            }
            for u in [[0.1f32, 0.2], [0.5, 0.5], [0.93, 0.77], [0.999_999, 0.3]] {
                let (sm, sc) = (m.sample(wo, u), c.sample(wo, u));
                assert_eq!(sm.is_some(), sc.is_some(), "{text} sample {u:?}");
                if let (Some(sm), Some(sc)) = (sm, sc) {
                    // The rescaled sample number of the picked lobe differs by rounding, so the
                    // direction does (≈ 1e-7), and the density of a sharp lobe with it (≈ 1e-6).
                    let near = |a: f32, b: f32| (a - b).abs() <= 1e-5 * a.abs().max(b.abs());
                    assert!((sm.wi - sc.wi).abs().max_element() <= 1e-6, "{text} sample {u:?}");
                    assert!(near(sm.pdf, sc.pdf), "{text} sample pdf {u:?}: {sm:?} {sc:?}");
                    for ch in 0..3 {
                        assert!(
                            near(sm.weight, sc.weight[ch]),
                            "{text} weight {u:?}: {sm:?} {sc:?}"
                        );
                    }
                }
            }
        }
        // The batch path: the same values as the scalar path of each kind.
        let wi: Vec<Vec3> = (0..37).map(|i| dir(i as f64 * 2.4, i as f64 * 37.0)).collect();
        let wo: Vec<Vec3> = (0..37)
            .map(|i| dir(80.0 - i as f64 * 2.0, 180.0 + i as f64))
            .collect();
        let mut om = vec![0.0f32; 37];
        let mut oc = vec![Vec3::ZERO; 37];
        m.eval_batch(&wi, &wo, &mut om);
        c.eval_batch(&wi, &wo, &mut oc);
        for i in 0..37 {
            let (vm, vc) = (om[i], oc[i]);
            // Vector kernels (monochrome) are within a few ulps of the scalar path.
            let tol = 1e-5 * vm.abs().max(1e-6);
            for ch in 0..3 {
                assert!((vc[ch] - vm).abs() <= tol, "{text} batch {i}: {vc} vs {vm}");
            }
        }
    }
}

/// Grey and not grey: named metals and MERL files are colour even when
/// nothing else is.
#[test]
fn the_grey_predicate() {
    for (text, grey) in [
        ("lambertian(albedo=0.3)", true),
        ("lambertian(albedo=rgb(0.3, 0.3, 0.31))", false),
        ("ggx(alpha=0.1, fresnel=conductor(metal=Cu))", false),
        ("ggx(alpha=0.1, fresnel=conductor(eta=1, k=2))", true),
        ("openpbr(fuzz_color=rgb(1, 0.9, 1))", false),
        ("openpbr(base_color=0.3)", true),
        ("mix(0.5, lambertian, lambertian(albedo=rgb(1, 0, 0)))", false),
        (
            "coated(ggx(alpha=0.1), eon(rho=rgb(0.2, 0.2, 0.2), sigma=0.1))",
            true,
        ),
        ("lambertian + ggx(alpha=0.3, fresnel=conductor(metal=Au))", false),
        ("tabulated(file=/nonexistent.binary)", false),
    ] {
        assert_eq!(parse_brdf(text).unwrap().is_grey(), grey, "{text}");
    }
}

/// A MERL file keeps its three channels in RGB and is its luminance in
/// monochrome; a missing file is the same typed error in both.
#[test]
fn merl_files_keep_their_channels() {
    use radiometry_brdfs::tabulated::RusinkiewiczGrid;
    let colour = Lambertian::new(Vec3::new(0.6, 0.3, 0.15)).unwrap();
    let table = crate::merl::tabulate(&colour, RusinkiewiczGrid::new(8, 8, 8).unwrap()).unwrap();
    let dir_ = std::env::temp_dir().join(format!("radiometry-spec-rgb-merl-{}", std::process::id()));
    std::fs::create_dir_all(&dir_).unwrap();
    let path = dir_.join("orange.binary");
    crate::merl::write(&path, &table).unwrap();
    let text = format!("tabulated(file={})", path.display());
    let (wi, wo) = (dir(30.0, 0.0), dir(45.0, 150.0));
    let c = rgb(&text).eval(wi, wo);
    // The table stores f_r / scale in f64 per channel; the ratios are the colour's.
    assert!(
        (c.x / c.y - 2.0).abs() < 1e-5 && (c.y / c.z - 2.0).abs() < 1e-5,
        "{c}"
    );
    let m = mono(&text).eval(wi, wo);
    let lum = 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z;
    assert!((m - lum).abs() <= 1e-6 * lum, "{m} vs {lum}");
    std::fs::remove_dir_all(&dir_).ok();
    let bad = "tabulated(file=/nonexistent/x.binary)";
    let e = build_brdf_rgb(bad, &parse_brdf(bad).unwrap())
        .err()
        .expect("missing file");
    assert_eq!(&bad[e.start..e.end], "/nonexistent/x.binary");
    assert!(e.message.contains("cannot read MERL file"), "{e}");
}

/// `openpbr(base_color=rgb(0.8, 0.1, 0.1))` in RGB is `OpenPbr<Vec3>` with that base colour, bit for bit (the
/// issue's target for the front ends, which all build it here).
#[test]
fn rgb_openpbr_is_the_typed_plugin() {
    let text = "openpbr(base_color=rgb(0.8, 0.1, 0.1), coat_weight=0.5, fuzz_weight=0.2, fuzz_color=rgb(0.2, 0.3, 0.9))";
    let b = rgb(text);
    let typed = OpenPbr::new(OpenPbrParams {
        base_color: Vec3::new(0.8, 0.1, 0.1),
        coat_weight: 0.5,
        fuzz_weight: 0.2,
        fuzz_color: Vec3::new(0.2, 0.3, 0.9),
        ..OpenPbrParams::default()
    })
    .unwrap();
    for to in [0.0, 30.0, 75.0] {
        let wo = dir(to, 0.0);
        assert_eq!(
            b.directional_albedo(wo),
            typed.directional_albedo(wo),
            "albedo at {to}°"
        );
        for (ti, pi) in [(0.0, 0.0), (30.0, 180.0), (60.0, 45.0), (85.0, 300.0)] {
            let wi = dir(ti, pi);
            assert_eq!(b.eval(wi, wo), typed.eval(wi, wo), "{ti},{pi} {to}");
            assert_eq!(b.pdf(wi, wo), typed.pdf(wi, wo));
        }
        for u in [[0.1f32, 0.9], [0.6, 0.3]] {
            assert_eq!(b.sample(wo, u), typed.sample(wo, u));
        }
    }
}
