//! Photometry and colorimetry against independent references: CIE table
//! values, closed forms and f64 sums written here.

use radiometry::spectral::{
    self, Blackbody, FnCurve, IlluminantA, Scaled, SpectralCurve, photometry, tables,
};

/// CIE 015:2018 §7.1 summation at 5 nm, in f64, written independently of the library's
/// trapezoid integration: Σ S(λ) V(λ) Δλ over the common range 360–780 nm.
fn d65_v_sum_f64() -> f64 {
    let mut s = 0.0f64;
    for i in 0..=84 {
        let l = 360 + 5 * i; // 360..780
        let d = tables::CIE_D65[(l - 300) / 5] as f64;
        let v = tables::CIE_PHOTOPIC_V[(l - 360) / 5] as f64;
        s += d * v * 5.0;
    }
    s
}

#[test]
fn d65_scaled_to_1000_lux_reads_1000_lux() {
    let k = 1000.0 / (683.0 * d65_v_sum_f64());
    let e = Scaled::new(spectral::d65(), k as f32);
    let lux = photometry::illuminance_lux(&e);
    let rel = (lux as f64 - 1000.0).abs() / 1000.0;
    println!("D65 scaled to 1000 lx reads {lux} lx (rel. error {rel:.2e})");
    assert!(rel < 1e-3, "{lux}");
}

#[test]
fn v_lambda_peak_is_one_at_555() {
    let v = spectral::photopic_v();
    assert_eq!(v.value(555.0), 1.0);
    let mut best = (0.0, 0.0);
    for i in 0..=4700 {
        let l = 360.0 + i as f32 * 0.1;
        if v.value(l) > best.1 {
            best = (l, v.value(l));
        }
    }
    assert!((best.0 - 555.0).abs() < 0.05 && best.1 == 1.0, "{best:?}");
    // CIE 1924 V(λ) values (CIE S 010, 4 significant figures).
    for (l, want) in [
        (450.0, 0.038),
        (500.0, 0.323),
        (550.0, 0.99495),
        (600.0, 0.631),
        (650.0, 0.107),
    ] {
        assert!((v.value(l) - want).abs() < 1e-4, "V({l}) = {}", v.value(l));
    }
}

#[test]
fn monochromatic_555_is_683_lux_per_watt() {
    assert!((photometry::illuminance_monochromatic(555.0, 1.0) - 683.0).abs() < 1e-3);
    assert_eq!(photometry::illuminance_monochromatic(300.0, 1.0), 0.0);
    assert_eq!(photometry::illuminance_monochromatic(f32::NAN, 1.0), 0.0);
    assert_eq!(photometry::illuminance_monochromatic(555.0, f32::NAN), 0.0);
    assert_eq!(photometry::illuminance_monochromatic(555.0, f32::INFINITY), 0.0);
    assert_eq!(photometry::illuminance_monochromatic(555.0, f32::MAX), f32::MAX); // saturates
}

#[test]
fn d65_chromaticity_matches_cie() {
    let c = photometry::chromaticity(photometry::xyz(&spectral::d65())).unwrap();
    // CIE 015:2018 Table T.3: D65, 2° observer: x = 0.31272, y = 0.32903.
    println!("D65 xy = {c:?}");
    assert!(
        (c[0] - 0.31272).abs() < 3e-4 && (c[1] - 0.32903).abs() < 3e-4,
        "{c:?}"
    );
}

#[test]
fn illuminant_a_matches_cie_table_and_chromaticity() {
    // CIE 015:2018 Table T.1, illuminant A.
    for (l, want) in [
        (300.0f32, 0.930483f32),
        (400.0, 14.7080),
        (500.0, 59.8611),
        (560.0, 100.0),
        (600.0, 129.043),
        (700.0, 198.261),
        (780.0, 241.675),
    ] {
        let got = IlluminantA.value(l);
        assert!(((got - want) / want).abs() < 2e-5, "A({l}) = {got}, want {want}");
    }
    let c = photometry::chromaticity(photometry::xyz(&IlluminantA)).unwrap();
    // CIE 015:2018 Table T.3: A: x = 0.44758, y = 0.40745.
    assert!(
        (c[0] - 0.44758).abs() < 3e-4 && (c[1] - 0.40745).abs() < 3e-4,
        "{c:?}"
    );
    assert_eq!(IlluminantA.value(f32::NAN), 0.0);
    assert_eq!(IlluminantA.value(900.0), 0.0);
}

#[test]
fn blackbody_obeys_stefan_boltzmann() {
    // π ∫ L(λ,T) dλ = σ T⁴ (Lambertian emitter), σ = 5.670374419e-8 W m⁻² K⁻⁴.
    for t in [1000.0f32, 2856.0, 5778.0] {
        let bb = Blackbody::new(t).unwrap();
        // f64 trapezoid with a geometric grid 50 nm – 1e5 nm, written here.
        let n = 20000;
        let (a, b) = (50.0f64.ln(), 1.0e5f64.ln());
        let mut s = 0.0f64;
        for i in 0..n {
            let l0 = (a + (b - a) * i as f64 / n as f64).exp();
            let l1 = (a + (b - a) * (i + 1) as f64 / n as f64).exp();
            s += 0.5 * (bb.value(l0 as f32) as f64 + bb.value(l1 as f32) as f64) * (l1 - l0);
        }
        let m = std::f64::consts::PI * s;
        let want = 5.670374419e-8 * (t as f64).powi(4);
        assert!((m / want - 1.0).abs() < 2e-3, "T={t}: {m} vs {want}");
    }
    assert!(Blackbody::new(0.0).is_err());
    assert!(Blackbody::new(-5.0).is_err());
    assert!(Blackbody::new(f32::NAN).is_err());
    let cold = Blackbody::new(1e-3).unwrap();
    assert_eq!(cold.value(500.0), 0.0);
    let hot = Blackbody::new(1e9).unwrap();
    assert!(hot.value(1.0).is_finite());
}

#[test]
fn srgb_matrix_maps_d65_white_to_one_and_matches_primaries() {
    let w = photometry::xyz_to_linear_srgb([0.95047, 1.0, 1.08883]);
    for c in w {
        assert!((c - 1.0).abs() < 1e-3, "{w:?}");
    }
    // Independent derivation (f64): columns = primaries' XYZ scaled so that R+G+B = white.
    let prim = [[0.64f64, 0.33], [0.30, 0.60], [0.15, 0.06]];
    let white = [0.3127f64, 0.3290];
    let col = |p: [f64; 2]| [p[0] / p[1], 1.0, (1.0 - p[0] - p[1]) / p[1]];
    let p = [col(prim[0]), col(prim[1]), col(prim[2])];
    let wv = col(white);
    // Solve P s = W where P has columns p[j]; 3x3 Cramer's rule.
    let m = |r: usize, c: usize| p[c][r];
    let det3 = |a: [[f64; 3]; 3]| {
        a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0])
            + a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0])
    };
    let pm: [[f64; 3]; 3] = core::array::from_fn(|r| core::array::from_fn(|c| m(r, c)));
    let d = det3(pm);
    let s: [f64; 3] = core::array::from_fn(|j| {
        let mut a = pm;
        for (row, w) in a.iter_mut().zip(wv) {
            row[j] = w;
        }
        det3(a) / d
    });
    // M_rgb→xyz = P diag(s); check M_xyz→rgb · M_rgb→xyz ≈ I.
    for (j, sj) in s.iter().enumerate() {
        let xyz = [m(0, j) * sj, m(1, j) * sj, m(2, j) * sj];
        let rgb = photometry::xyz_to_linear_srgb(xyz.map(|v| v as f32));
        for (i, v) in rgb.iter().enumerate() {
            let want = if i == j { 1.0 } else { 0.0 };
            assert!((v - want).abs() < 2e-3, "col {j}: {rgb:?}");
        }
    }
}

#[test]
fn hard_cases_are_finite() {
    let nan = FnCurve::new(360.0, 830.0, |_| f32::NAN);
    assert_eq!(photometry::illuminance_lux(&nan), 0.0);
    let neg = Scaled::new(spectral::d65(), -0.01);
    let pos = Scaled::new(spectral::d65(), 0.01);
    assert_eq!(
        photometry::illuminance_lux(&neg),
        -photometry::illuminance_lux(&pos)
    );
    let zero = FnCurve::new(360.0, 830.0, |_| 0.0);
    assert_eq!(photometry::illuminance_lux(&zero), 0.0);
    assert_eq!(photometry::chromaticity(photometry::xyz(&zero)), None);
    assert_eq!(photometry::chromaticity([f32::NAN, 1.0, 1.0]), None);
    // A source entirely outside the V(λ) table gives 0 lx.
    let ir = FnCurve::new(900.0, 1000.0, |_| 1.0);
    assert_eq!(photometry::illuminance_lux(&ir), 0.0);
    assert_eq!(Scaled::new(spectral::d65(), f32::NAN).value(500.0), 0.0);
}
