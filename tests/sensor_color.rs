//! Colour architectures: Bayer mosaic + demosaicing, dichroic prism, filter wheel,
//! stacked layers.

use radiometry::sensor::SensorError;
use radiometry::sensor::color::{
    BayerPattern, DichroicPrism, FilterWheel, SILICON_ALPHA_PER_UM, SILICON_LAMBDA_NM, StackedLayers,
    demosaic_bilinear, demosaic_malvar, false_colour_energy, mosaic, silicon_absorption,
};
use radiometry::spectral::{FnCurve, Irregular, SpectralCurve};

type Demosaic = fn(&[f32], usize, usize, BayerPattern, &mut [[f32; 3]]) -> Result<(), SensorError>;
const METHODS: [(&str, Demosaic); 2] = [("bilinear", demosaic_bilinear), ("malvar", demosaic_malvar)];

fn run(img: &[[f32; 3]], w: usize, h: usize, p: BayerPattern, f: Demosaic) -> Vec<[f32; 3]> {
    let mut raw = vec![0.0; w * h];
    mosaic(img, w, h, p, &mut raw).unwrap();
    let mut out = vec![[0.0; 3]; w * h];
    f(&raw, w, h, p, &mut out).unwrap();
    out
}

#[test]
fn bayer_phases_have_one_r_two_g_one_b_per_block() {
    for p in BayerPattern::ALL {
        for (bx, by) in [(0, 0), (2, 4), (7, 3)] {
            let mut count = [0; 3];
            for (dx, dy) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
                count[p.channel_at(2 * bx + dx, 2 * by + dy)] += 1;
            }
            assert_eq!(count, [1, 2, 1], "{p:?}");
        }
        // Greens form a quincunx: diagonal neighbours of a green are green.
        let g = (0..2).find(|&x| p.channel_at(x, 0) == 1).unwrap();
        assert_eq!(p.channel_at(g + 1, 1), 1);
    }
}

#[test]
fn uniform_grey_stays_grey_for_every_phase_and_method() {
    for (w, h) in [(2, 2), (3, 5), (16, 12), (17, 9)] {
        for grey in [0.0f32, 0.18, 1.0, 1000.0] {
            let img = vec![[grey; 3]; w * h];
            for p in BayerPattern::ALL {
                for (name, f) in METHODS {
                    let out = run(&img, w, h, p, f);
                    for px in &out {
                        for &v in px {
                            assert!(
                                (v - grey).abs() <= 1e-5 * grey.max(1.0),
                                "{name} {p:?} {w}x{h}: {px:?}"
                            );
                        }
                    }
                    assert!(false_colour_energy(&out) <= 1e-9 * grey.max(1.0).powi(2));
                }
            }
        }
    }
}

/// Black/white test charts: a vertical edge at a pixel boundary, and a slanted edge.
fn charts(w: usize, h: usize) -> [(&'static str, Vec<[f32; 3]>); 2] {
    let vertical = (0..w * h)
        .map(|i| if i % w >= w / 2 { [1.0; 3] } else { [0.0; 3] })
        .collect();
    let slanted = (0..w * h)
        .map(|i| {
            let (x, y) = ((i % w) as f32 + 0.5, (i / w) as f32 + 0.5);
            // Area coverage of the half-plane x > 0.3 y + w/3 over the pixel, 16×16 supersampled.
            let mut c = 0.0;
            for sy in 0..16 {
                for sx in 0..16 {
                    let (px, py) = (
                        x - 0.5 + (sx as f32 + 0.5) / 16.0,
                        y - 0.5 + (sy as f32 + 0.5) / 16.0,
                    );
                    if px > 0.3 * py + w as f32 / 3.0 {
                        c += 1.0 / 256.0;
                    }
                }
            }
            [c; 3]
        })
        .collect();
    [("vertical", vertical), ("slanted", slanted)]
}

#[test]
fn edge_aware_has_less_false_colour_than_bilinear() {
    let (w, h) = (32, 32);
    for (chart, img) in charts(w, h) {
        for p in BayerPattern::ALL {
            let e_bil = false_colour_energy(&run(&img, w, h, p, demosaic_bilinear));
            let e_mal = false_colour_energy(&run(&img, w, h, p, demosaic_malvar));
            println!(
                "false-colour energy, {chart} edge, {p:?}: bilinear {e_bil:.4}, Malvar-He-Cutler {e_mal:.4}"
            );
            assert!(
                e_bil > 0.0,
                "a B/W edge through a CFA must produce some false colour with bilinear"
            );
            assert!(e_mal < e_bil, "{chart} {p:?}: malvar {e_mal} ≥ bilinear {e_bil}");
        }
    }
}

#[test]
fn demosaic_keeps_known_samples_and_rejects_bad_buffers() {
    let (w, h) = (6, 4);
    let img: Vec<[f32; 3]> = (0..w * h)
        .map(|i| [i as f32, 2.0 * i as f32, 0.5 * i as f32])
        .collect();
    for p in BayerPattern::ALL {
        for (_, f) in METHODS {
            let out = run(&img, w, h, p, f);
            for y in 0..h {
                for x in 0..w {
                    let c = p.channel_at(x, y);
                    assert_eq!(out[y * w + x][c], img[y * w + x][c]);
                }
            }
        }
    }
    let mut raw = vec![0.0; 5];
    assert_eq!(
        mosaic(&img, w, h, BayerPattern::Rggb, &mut raw),
        Err(SensorError::BadBuffer)
    );
    let mut out = vec![[0.0; 3]; w * h];
    assert_eq!(
        demosaic_malvar(&raw, w, h, BayerPattern::Rggb, &mut out),
        Err(SensorError::BadBuffer)
    );
    let one = [0.0f32; 3];
    let mut o1 = [[0.0f32; 3]; 3];
    assert_eq!(
        demosaic_bilinear(&one, 3, 1, BayerPattern::Rggb, &mut o1),
        Err(SensorError::BadBuffer)
    );
    assert_eq!(
        demosaic_bilinear(&[], usize::MAX, 2, BayerPattern::Rggb, &mut []),
        Err(SensorError::BadBuffer)
    );
    // NaN samples stay local: they do not crash, and false_colour_energy skips them.
    let mut nanraw = vec![0.5f32; 16];
    nanraw[5] = f32::NAN;
    let mut o = vec![[0.0f32; 3]; 16];
    demosaic_malvar(&nanraw, 4, 4, BayerPattern::Rggb, &mut o).unwrap();
    assert!(false_colour_energy(&o).is_finite());
}

#[test]
fn bilinear_reproduces_linear_ramps_in_the_interior() {
    // Bilinear interpolation is exact for an image linear in x and y (interior pixels).
    let (w, h) = (10, 8);
    let img: Vec<[f32; 3]> = (0..w * h)
        .map(|i| {
            let (x, y) = ((i % w) as f32, (i / w) as f32);
            [
                0.1 * x + 0.2 * y,
                0.3 * x - 0.1 * y + 2.0,
                0.05 * x + 0.07 * y + 1.0,
            ]
        })
        .collect();
    for p in BayerPattern::ALL {
        for (name, f) in METHODS {
            let out = run(&img, w, h, p, f);
            for y in 2..h - 2 {
                for x in 2..w - 2 {
                    for c in 0..3 {
                        let (a, b) = (out[y * w + x][c], img[y * w + x][c]);
                        assert!((a - b).abs() < 1e-4, "{name} {p:?} ({x},{y}) c{c}: {a} vs {b}");
                    }
                }
            }
        }
    }
}

#[test]
fn dichroic_prism_conserves_energy_and_separates_bands() {
    let p = DichroicPrism::new(490.0, 590.0, 5.0).unwrap();
    for i in 0..=600 {
        let l = 350.0 + i as f32;
        let t = p.transmittances(l);
        assert!(t.iter().all(|&v| (0.0..=1.0).contains(&v)));
        assert!((t.iter().sum::<f32>() - 1.0).abs() < 1e-6, "{l}: {t:?}");
    }
    assert_eq!(p.transmittances(f32::NAN), [0.0; 3]);
    let flat = FnCurve::new(380.0, 780.0, |_| 1.0);
    let qe = FnCurve::new(300.0, 1100.0, |_| 0.5);
    let s = p.split(&flat, &qe);
    // Σ channels = ∫ E q dλ = 0.5 · 400 = 200; bands ≈ 110, 100, 190 nm × 0.5.
    assert!((s.iter().sum::<f32>() - 200.0).abs() < 0.01, "{s:?}");
    assert!(
        (s[2] - 55.0).abs() < 0.5 && (s[1] - 50.0).abs() < 0.5 && (s[0] - 95.0).abs() < 0.5,
        "{s:?}"
    );
    // A black/white edge seen by a 3-chip camera is grey in every pixel: zero false colour.
    let grey_pix: Vec<[f32; 3]> = (0..64).map(|i| [(i % 8 >= 4) as u8 as f32; 3]).collect();
    assert_eq!(false_colour_energy(&grey_pix), 0.0);
    assert!(DichroicPrism::new(600.0, 500.0, 5.0).is_err());
    assert!(DichroicPrism::new(500.0, 600.0, 0.0).is_err());
    assert!(DichroicPrism::new(f32::NAN, 600.0, 1.0).is_err());
}

#[test]
fn filter_wheel_misregisters_a_moving_bar() {
    // A bright bar 2 px wide moving right at v px/s; 3 filters of 10 ms each.
    let (w, h, v, slot) = (64usize, 2usize, 200.0f32, 0.01f32);
    let wheel = FilterWheel::new(3, slot, 64).unwrap();
    let scene = |x: f32, _y: f32, t: f32, _k: usize| {
        let x0 = 10.0 + v * t;
        if x >= x0 && x < x0 + 2.0 { 1.0 } else { 0.0 }
    };
    let mut out = vec![0.0f32; 3 * w * h];
    wheel.capture(scene, w, h, &mut out).unwrap();
    let centroid = |k: usize| {
        let row = &out[k * w * h..k * w * h + w];
        let (m, s): (f32, f32) = row
            .iter()
            .enumerate()
            .fold((0.0, 0.0), |(m, s), (i, &a)| (m + a * (i as f32 + 0.5), s + a));
        m / s
    };
    let c: Vec<f32> = (0..3).map(centroid).collect();
    // Closed form: the bar's centre at the middle of slot k is 10 + 1 + v (k + 1/2) slot.
    for (k, ck) in c.iter().enumerate() {
        let want = 11.0 + v * (k as f32 + 0.5) * slot;
        assert!((ck - want).abs() < 0.05, "filter {k}: centroid {ck}, want {want}");
    }
    println!(
        "filter wheel: misregistration between filters = {:.3} px (v·slot = {} px)",
        c[1] - c[0],
        v * slot
    );
    assert!(FilterWheel::new(0, 0.01, 4).is_err());
    assert!(FilterWheel::new(3, f32::NAN, 4).is_err());
    assert_eq!(
        wheel.capture(scene, w, h, &mut out[..5]),
        Err(SensorError::BadBuffer)
    );
    // NaN scene values read as 0.
    let mut o = vec![1.0f32; 3 * 4];
    wheel.capture(|_, _, _, _| f32::NAN, 2, 2, &mut o).unwrap();
    assert!(o.iter().all(|&v| v == 0.0));
}

#[test]
fn stacked_layers_follow_beer_lambert() {
    let s = StackedLayers::foveon();
    // Table sanity: the constant table is a valid Irregular curve.
    assert!(Irregular::new(&SILICON_LAMBDA_NM, &SILICON_ALPHA_PER_UM).is_ok());
    // Green & Keevers 1995 at 500 nm: α = 1.11e4 /cm → absorption depth 0.90 µm.
    assert!((1.0 / silicon_absorption().value(500.0) - 0.901).abs() < 0.01);
    for i in 0..=700 {
        let l = 400.0 + i as f32;
        let f = s.fractions(l);
        let t = s.transmitted(l);
        assert!(f.iter().all(|&v| (0.0..=1.0).contains(&v)));
        assert!((f.iter().sum::<f32>() + t - 1.0).abs() < 1e-6, "{l}");
        // Independent closed form for the top layer: 1 − exp(−α·0.2 µm).
        let a = silicon_absorption().value(l) as f64;
        assert!((f[0] as f64 - (1.0 - (-a * 0.2).exp())).abs() < 1e-6);
    }
    // Peak wavelengths of the layer responses order blue < green < red.
    let peak = |k: usize| {
        (400..=1100)
            .map(|l| (l, s.fractions(l as f32)[k]))
            .fold((0, 0.0), |b, x| if x.1 > b.1 { x } else { b })
            .0
    };
    let (pb, pg, pr) = (peak(0), peak(1), peak(2));
    println!("stacked layers: response peaks at {pb} / {pg} / {pr} nm");
    assert!(pb < pg && pg <= pr, "{pb} {pg} {pr}");
    // Out of table / NaN: nothing absorbed (documented), everything transmitted.
    assert_eq!(s.fractions(300.0), [0.0; 3]);
    assert_eq!(s.fractions(f32::NAN), [0.0; 3]);
    assert_eq!(s.transmitted(1500.0), 1.0);
    let flat = FnCurve::new(300.0, 1200.0, |_| 1.0);
    let r = s.respond(&flat);
    assert!(r.iter().all(|v| v.is_finite() && *v > 0.0));
    assert!(StackedLayers::new([0.5, 0.2]).is_err());
    assert!(StackedLayers::new([0.0, 0.2]).is_err());
    assert!(StackedLayers::new([f32::NAN]).is_err());
}

#[test]
fn slanted_edge_chart_covers_the_right_area() {
    use radiometry::sensor::color::slanted_edge;
    let (w, h) = (40, 30);
    let mut img = vec![[0.0f32; 3]; w * h];
    slanted_edge(w, h, 0.25, 10.0, &mut img).unwrap();
    // Bright area = Σ_rows (w − (0.25·y_mid + 10)) exactly for a line crossing each row: closed form.
    let total: f32 = img.iter().map(|p| p[0]).sum();
    let want: f32 = (0..h).map(|y| w as f32 - (0.25 * (y as f32 + 0.5) + 10.0)).sum();
    assert!((total - want).abs() < 0.5, "{total} vs {want}");
    assert!(
        img.iter()
            .all(|p| p[0] == p[1] && p[1] == p[2] && (0.0..=1.0).contains(&p[0]))
    );
    assert_eq!(
        slanted_edge(w, h, f32::NAN, 1.0, &mut img),
        Err(SensorError::NotFinite)
    );
    assert_eq!(
        slanted_edge(w, h + 1, 0.0, 1.0, &mut img),
        Err(SensorError::BadBuffer)
    );
}
