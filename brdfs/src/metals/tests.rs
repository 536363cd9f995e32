use super::*;
use crate::microfacet::{MAX_ETA, MAX_K, MIN_ETA};
use radiometry::spectral::tables::{CIE_D65, CIE1931_X_BAR, CIE1931_Y_BAR, CIE1931_Z_BAR, D65_START_NM};

/// Normal-incidence reflectance in `f64`, written out independently.
fn r0(n: f64, k: f64) -> f64 {
    ((n - 1.0).powi(2) + k * k) / ((n + 1.0).powi(2) + k * k)
}

#[test]
fn tables_are_well_formed_and_inside_the_conductor_domain() {
    for m in Metal::ALL {
        let t = m.table();
        assert_eq!(t.lambda_nm.len(), t.eta.len(), "{m:?}");
        assert_eq!(t.lambda_nm.len(), t.k.len(), "{m:?}");
        assert!(t.lambda_nm.windows(2).all(|w| w[0] < w[1]), "{m:?}");
        let (lo, hi) = m.range_nm();
        assert!(lo <= 360.0 && hi >= 830.0, "{m:?}: {lo}–{hi}");
        for (&n, &k) in t.eta.iter().zip(t.k) {
            assert!(
                (MIN_ETA..=MAX_ETA).contains(&n) && (0.0..=MAX_K).contains(&k),
                "{m:?}"
            );
        }
        assert!(!t.source.is_empty() && !t.doi.is_empty());
    }
}

#[test]
fn interpolation_hits_the_rows_exactly() {
    for m in Metal::ALL {
        let t = m.table();
        for i in 0..t.lambda_nm.len() {
            assert_eq!(m.eta_k(t.lambda_nm[i]), Ok((t.eta[i], t.k[i])), "{m:?} row {i}");
        }
        // Halfway between two rows: the mean.
        for i in 0..t.lambda_nm.len() - 1 {
            let mid = 0.5 * (t.lambda_nm[i] + t.lambda_nm[i + 1]);
            let (n, k) = m.eta_k(mid).unwrap();
            assert!((n - 0.5 * (t.eta[i] + t.eta[i + 1])).abs() < 1e-5 * (1.0 + n));
            assert!((k - 0.5 * (t.k[i] + t.k[i + 1])).abs() < 1e-5 * (1.0 + k));
        }
    }
}

#[test]
fn wavelengths_outside_the_table_are_typed_errors_or_a_documented_clamp() {
    let (lo, hi) = Metal::Au.range_nm();
    assert_eq!(
        Metal::Au.eta_k(lo - 1.0),
        Err(BrdfError::WavelengthOutOfRange {
            lambda_nm: lo - 1.0,
            min_nm: lo,
            max_nm: hi
        })
    );
    assert!(matches!(
        Metal::Pt.eta_k(2000.0),
        Err(BrdfError::WavelengthOutOfRange { .. })
    ));
    assert_eq!(
        Metal::Cu.eta_k(f32::NAN),
        Err(BrdfError::NotFinite { name: "lambda" })
    );
    assert!(Metal::Cu.eta_k(f32::INFINITY).is_err());
    let t = Metal::Au.table();
    let last = t.lambda_nm.len() - 1;
    assert_eq!(Metal::Au.eta_k_clamped(100.0), (t.eta[0], t.k[0]));
    assert_eq!(Metal::Au.eta_k_clamped(1e9), (t.eta[last], t.k[last]));
    assert_eq!(Metal::Au.eta_k_clamped(f32::NAN), (t.eta[0], t.k[0]));
    assert!(Conductor::metal_sampled(Metal::Ag, &[500.0, 1500.0]).is_err());
    assert!(Metal::Brass.eta_k_sampled(&[450.0, 550.0, 650.0]).is_ok());
}

#[test]
fn names_are_case_insensitive() {
    for m in Metal::ALL {
        assert_eq!(Metal::from_name(m.name()), Some(m));
        assert_eq!(Metal::from_name(&m.name().to_ascii_lowercase()), Some(m));
        assert_eq!(Metal::from_name(&m.name().to_ascii_uppercase()), Some(m));
    }
    assert_eq!(Metal::from_name("cuzn"), Some(Metal::Brass));
    assert_eq!(Metal::from_name("steel"), None);
}

extern crate std;

/// Published rows (typed from the papers' tables, not read from `data.rs`)
/// and the normal-incidence reflectance they give.
#[test]
fn published_normal_incidence_reflectances() {
    // (metal, λ nm, n, k) — rows of Johnson & Christy 1972 (Au, Ag, Cu at
    // 2.26 eV = 548.6 nm), Johnson & Christy 1974 (Ni at 549 nm) and
    // Querry 1985 (brass at 550 nm), typed here from the published tables.
    let rows: [(Metal, f32, f64, f64); 5] = [
        (Metal::Au, 548.6, 0.43, 2.455),
        (Metal::Ag, 548.6, 0.06, 3.586),
        (Metal::Cu, 548.6, 1.02, 2.577),
        (Metal::Ni, 549.0, 1.92, 3.61),
        (Metal::Brass, 550.0, 0.527, 2.765),
    ];
    for (m, l, n, k) in rows {
        let want = r0(n, k);
        let got = f64::from(m.reflectance(l).unwrap());
        assert!((got - want).abs() < 1e-4, "{m:?}: {got} vs {want}");
    }
    // Handbook figures (Bennett & Bennett in Handbook of Optics; Palik):
    // gold reflects ~0.8 of green light, silver ~0.98, aluminium ~0.92.
    let au = Metal::Au.reflectance(550.0).unwrap();
    let ag = Metal::Ag.reflectance(550.0).unwrap();
    let al = Metal::Al.reflectance(550.0).unwrap();
    assert!((0.75..0.85).contains(&au), "{au}");
    assert!((0.95..0.99).contains(&ag), "{ag}");
    assert!((0.90..0.93).contains(&al), "{al}");
}

/// The colour reduction, independently in `f64` from the CIE tables (the
/// rows: 360, 365, …, 780 nm; D65 starts at 300 nm).
fn rgb_f64(m: Metal, mu: f64) -> [f64; 3] {
    let mut xyz = [0.0f64; 3];
    let mut white = 0.0;
    for i in 0..85 {
        let l = 360.0 + 5.0 * i as f64;
        let (n, k) = m.eta_k_clamped(l as f32);
        let f = fresnel_f64(mu, f64::from(n), f64::from(k));
        let d = f64::from(CIE_D65[i + ((360.0 - D65_START_NM) / 5.0) as usize]);
        let (x, y, z) = (
            f64::from(CIE1931_X_BAR[i]),
            f64::from(CIE1931_Y_BAR[i]),
            f64::from(CIE1931_Z_BAR[i]),
        );
        xyz[0] += f * d * x;
        xyz[1] += f * d * y;
        xyz[2] += f * d * z;
        white += d * y;
    }
    let xyz = xyz.map(|v| v / white);
    // IEC 61966-2-1 XYZ → linear sRGB.
    [
        3.2406 * xyz[0] - 1.5372 * xyz[1] - 0.4986 * xyz[2],
        -0.9689 * xyz[0] + 1.8758 * xyz[1] + 0.0415 * xyz[2],
        0.0557 * xyz[0] - 0.2040 * xyz[1] + 1.0570 * xyz[2],
    ]
    .map(|v| v.clamp(0.0, 1.0))
}

/// Unpolarised conductor Fresnel reflectance in `f64` complex arithmetic
/// (Born & Wolf §14.2), written out independently of `fresnel.rs`.
fn fresnel_f64(mu: f64, n: f64, k: f64) -> f64 {
    // (a, b) complex helpers.
    let mul = |a: (f64, f64), b: (f64, f64)| (a.0 * b.0 - a.1 * b.1, a.0 * b.1 + a.1 * b.0);
    let div = |a: (f64, f64), b: (f64, f64)| {
        let d = b.0 * b.0 + b.1 * b.1;
        ((a.0 * b.0 + a.1 * b.1) / d, (a.1 * b.0 - a.0 * b.1) / d)
    };
    let sqrt = |a: (f64, f64)| {
        let r = a.0.hypot(a.1);
        let re = ((r + a.0) / 2.0).sqrt();
        let im = ((r - a.0) / 2.0).sqrt().copysign(a.1);
        (re, im)
    };
    let e = (n, k);
    let e2 = mul(e, e);
    let s2 = div((1.0 - mu * mu, 0.0), e2);
    let ct = sqrt((1.0 - s2.0, -s2.1));
    let ec = (n * mu, k * mu);
    let ect = mul(e, ct);
    let norm2 = |a: (f64, f64)| a.0 * a.0 + a.1 * a.1;
    let rp = norm2((ec.0 - ct.0, ec.1 - ct.1)) / norm2((ec.0 + ct.0, ec.1 + ct.1));
    let rs = norm2((mu - ect.0, -ect.1)) / norm2((mu + ect.0, ect.1));
    0.5 * (rp + rs)
}

#[test]
fn rgb_reduction_matches_an_f64_reduction() {
    let mut worst = 0.0f64;
    for m in Metal::ALL {
        for mu in [1.0f32, 0.5, MU_BAR] {
            let got = m.fresnel_rgb(mu);
            let want = rgb_f64(m, f64::from(mu));
            for c in 0..3 {
                worst = worst.max((f64::from(got[c]) - want[c]).abs());
            }
        }
    }
    assert!(worst < 1e-4, "{worst}");
}

#[test]
fn silver_and_aluminium_are_near_white_gold_and_copper_warm() {
    for m in [Metal::Ag, Metal::Al] {
        let c = m.reflectance_rgb();
        assert!(
            c.min_element() > 0.85 && c.min_element() / c.max_element() > 0.9,
            "{m:?}: {c}"
        );
    }
    for m in [Metal::Au, Metal::Cu, Metal::Brass] {
        let c = m.reflectance_rgb();
        assert!(c.x > c.y && c.y > c.z && c.z < 0.7 * c.x, "{m:?}: {c}");
    }
    // A perfect reflector reduces to white.
    let xyz = reduce_xyz(&SampledSpectrum([1.0; N_CIE]));
    let m = &XYZ_TO_SRGB;
    for row in m {
        let v = row[0] * xyz[0] + row[1] * xyz[1] + row[2] * xyz[2];
        assert!((v - 1.0).abs() < 2e-3, "{v}");
    }
}

#[test]
fn conductor_fit_reproduces_both_reduced_reflectances() {
    for m in Metal::ALL {
        let c = Conductor::metal(m);
        assert!(
            Conductor::new(c.eta(), c.k()).is_ok(),
            "{m:?}: outside the domain"
        );
        let (f0, fb) = (m.fresnel_rgb(1.0), m.fresnel_rgb(MU_BAR));
        // A reduced reflectance above 0.996 (gold's red channel, 1 after the
        // clamp to the sRGB gamut) is fitted at 0.996, the largest the
        // fit allows; its 82° value then moves by as much.
        let excess = (f0 - Vec3::splat(0.996)).max(Vec3::ZERO);
        let d0 = ((c.eval(1.0) - f0).abs() - excess).max_element();
        let db = ((c.eval(MU_BAR) - fb).abs() - excess).max_element();
        assert!(d0 < 1e-4 && db < 2e-3, "{m:?}: {d0} {db}");
        let mono = Conductor::metal_luminance(m);
        assert!(Conductor::new(mono.eta(), mono.k()).is_ok());
        assert!((mono.eval(1.0) - m.fresnel_luminance(1.0)).abs() < 1e-4, "{m:?}");
        assert!(
            (mono.eval(MU_BAR) - m.fresnel_luminance(MU_BAR)).abs() < 2e-3,
            "{m:?}"
        );
    }
}

#[test]
fn f82_tint_of_a_metal_pins_both_angles() {
    for m in Metal::ALL {
        let f = F82Tint::metal(m);
        let (f0, fb) = (m.fresnel_rgb(1.0), m.fresnel_rgb(MU_BAR));
        assert!((f.eval(1.0) - f0).abs().max_element() < 1e-6, "{m:?}");
        // The tint is clamped at 1 where the metal is brighter than Schlick
        // at 82° (gold's green, brass's blue): F(μ̄) is then Schlick's, below.
        let e = f.eval(MU_BAR) - fb;
        for c in 0..3 {
            let clamped = f.f82_tint()[c] == 1.0 && e[c] <= 0.0;
            assert!(e[c].abs() < 1e-5 || clamped, "{m:?}: {e}");
        }
    }
}

#[test]
fn sampled_conductor_uses_the_table() {
    let t = Metal::Cu.table();
    let lambdas = [t.lambda_nm[5], t.lambda_nm[10], t.lambda_nm[15]];
    let c = Conductor::metal_sampled(Metal::Cu, &lambdas).unwrap();
    for (i, j) in [5usize, 10, 15].into_iter().enumerate() {
        let f = f64::from(c.eval(1.0).0[i]);
        assert!((f - r0(f64::from(t.eta[j]), f64::from(t.k[j]))).abs() < 1e-5);
        let f = f64::from(c.eval(0.3).0[i]);
        assert!((f - fresnel_f64(0.3, f64::from(t.eta[j]), f64::from(t.k[j]))).abs() < 1e-5);
    }
}
