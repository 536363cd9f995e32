//! The new plugins (EON, FON, classic Oren–Nayar, sheen, F82-tint and named
//! metal Fresnel), the materials (sum, mix, coated) and OpenPBR of the C API, called
//! as C would call them: every value equals the Rust plugin's or composite's
//! bit for bit, `pdf(sample) == sample.pdf` bit for bit, batches equal single
//! calls, bad parameters and scribbled handles are statuses.
//!
//! Run with `cargo test --features std`.

use core::f32::consts::PI;
use core::ptr::{null, null_mut};
use radiometry::compose::{Coated, Layering, Mix, Sum};
use radiometry::glam::Vec3;
use radiometry::{Brdf, BrdfSample};
use radiometry_brdfs::metals::Metal;
use radiometry_brdfs::openpbr::{OpenPbr, OpenPbrParams};
use radiometry_brdfs::{
    Conductor, Dielectric, Eon, F82Tint, Fon, Ggx, HeightCorrelated, Lambertian, Microfacet, OrenNayar, Sheen,
};
use radiometry_ffi::brdf::*;
use radiometry_ffi::material::*;
use radiometry_ffi::openpbr::*;
use radiometry_ffi::{RadBrdf, RadBrdfSample, RadMaterial, RadOpenPbr, RadOpenPbrParams, RadStatus, RadVec3};

type GgxHc<F> = Microfacet<Ggx, HeightCorrelated, F>;

fn ggx<F: radiometry_brdfs::Fresnel<Spectrum = f32>>(alpha: f32, f: F) -> GgxHc<F> {
    Microfacet::new(Ggx::new(alpha).unwrap(), f)
}

fn ok(s: RadStatus) {
    assert_eq!(s, RadStatus::Ok);
}

fn c_ggx(alpha: f32, fresnel: u32, a: f32, b: f32) -> RadBrdf {
    let mut h = RadBrdf::default();
    ok(unsafe {
        rad_brdf_microfacet(
            RAD_DISTRIBUTION_GGX,
            alpha,
            RAD_SHADOWING_HEIGHT_CORRELATED,
            fresnel,
            a,
            b,
            &mut h,
        )
    });
    h
}

fn c_plugin(f: unsafe extern "C" fn(f32, f32, *mut RadBrdf) -> RadStatus, p: f32, q: f32) -> RadBrdf {
    let mut h = RadBrdf::default();
    ok(unsafe { f(p, q, &mut h) });
    h
}

fn c_coated(top: &RadBrdf, base: &RadBrdf, color: f32, ior: f32) -> RadMaterial {
    let mut m = RadMaterial::default();
    ok(unsafe { rad_material_coated(top, base, color, ior, &mut m) });
    m
}

/// Unit directions over the hemisphere (some grazing, some below).
fn directions(n: usize, seed: f32) -> Vec<RadVec3> {
    (0..n)
        .map(|k| {
            let a = (k as f32 * 0.618_034 + seed).fract();
            let b = (k as f32 * 0.754_878 + seed * 0.5).fract();
            let z = match k % 23 {
                0 => -0.25,
                1 => 1e-4,
                _ => 0.01 + 0.99 * a,
            };
            let r = (1.0 - z * z).max(0.0).sqrt();
            let p = 2.0 * PI * b;
            RadVec3 {
                x: r * p.cos(),
                y: r * p.sin(),
                z,
            }
        })
        .collect()
}

fn us(n: usize) -> Vec<[f32; 2]> {
    (0..n)
        .map(|k| {
            [
                (k as f32 * 0.377_3 + 0.01).fract(),
                (k as f32 * 0.711_9 + 0.3).fract(),
            ]
        })
        .collect()
}

/// The C calls of a handle (a plugin or a material), for the shared checks.
trait CHandle {
    fn eval(&self, wi: RadVec3, wo: RadVec3) -> f32;
    fn pdf(&self, wi: RadVec3, wo: RadVec3) -> f32;
    fn sample(&self, wo: RadVec3, u: [f32; 2]) -> RadBrdfSample;
    fn eval_batch(&self, wi: &[RadVec3], wo: &[RadVec3]) -> Vec<f32>;
    fn pdf_batch(&self, wi: &[RadVec3], wo: &[RadVec3]) -> Vec<f32>;
    fn sample_batch(&self, wo: &[RadVec3], u: &[[f32; 2]]) -> Vec<RadBrdfSample>;
}

macro_rules! c_handle {
    ($t:ty, $eval:ident, $pdf:ident, $sample:ident, $eb:ident, $pb:ident, $sb:ident) => {
        impl CHandle for $t {
            fn eval(&self, wi: RadVec3, wo: RadVec3) -> f32 {
                let mut f = f32::NAN;
                ok(unsafe { $eval(self, wi, wo, &mut f) });
                f
            }
            fn pdf(&self, wi: RadVec3, wo: RadVec3) -> f32 {
                let mut f = f32::NAN;
                ok(unsafe { $pdf(self, wi, wo, &mut f) });
                f
            }
            fn sample(&self, wo: RadVec3, u: [f32; 2]) -> RadBrdfSample {
                let mut s = RadBrdfSample::default();
                ok(unsafe { $sample(self, wo, u[0], u[1], &mut s) });
                s
            }
            fn eval_batch(&self, wi: &[RadVec3], wo: &[RadVec3]) -> Vec<f32> {
                let mut out = vec![f32::NAN; wi.len()];
                ok(unsafe { $eb(self, wi.as_ptr(), wo.as_ptr(), out.as_mut_ptr(), wi.len()) });
                out
            }
            fn pdf_batch(&self, wi: &[RadVec3], wo: &[RadVec3]) -> Vec<f32> {
                let mut out = vec![f32::NAN; wi.len()];
                ok(unsafe { $pb(self, wi.as_ptr(), wo.as_ptr(), out.as_mut_ptr(), wi.len()) });
                out
            }
            fn sample_batch(&self, wo: &[RadVec3], u: &[[f32; 2]]) -> Vec<RadBrdfSample> {
                let mut out = vec![RadBrdfSample::default(); wo.len()];
                ok(unsafe {
                    $sb(
                        self,
                        wo.as_ptr(),
                        u.as_ptr().cast(),
                        out.as_mut_ptr(),
                        wo.len(),
                    )
                });
                out
            }
        }
    };
}

c_handle!(
    RadBrdf,
    rad_brdf_eval,
    rad_brdf_pdf,
    rad_brdf_sample,
    rad_brdf_eval_batch,
    rad_brdf_pdf_batch,
    rad_brdf_sample_batch
);
c_handle!(
    RadMaterial,
    rad_material_eval,
    rad_material_pdf,
    rad_material_sample,
    rad_material_eval_batch,
    rad_material_pdf_batch,
    rad_material_sample_batch
);
c_handle!(
    RadOpenPbr,
    rad_openpbr_eval,
    rad_openpbr_pdf,
    rad_openpbr_sample,
    rad_openpbr_eval_batch,
    rad_openpbr_pdf_batch,
    rad_openpbr_sample_batch
);

fn same_sample(c: RadBrdfSample, r: Option<BrdfSample<f32>>) -> bool {
    match r {
        None => c == RadBrdfSample::default(),
        Some(r) => {
            c.wi.x.to_bits() == r.wi.x.to_bits()
                && c.wi.y.to_bits() == r.wi.y.to_bits()
                && c.wi.z.to_bits() == r.wi.z.to_bits()
                && c.pdf.to_bits() == r.pdf.to_bits()
                && c.weight.iter().all(|w| w.to_bits() == r.weight.to_bits())
        }
    }
}

/// `c` (through the C API) and `r` (the Rust plugin or composite) give the
/// same bits for eval, pdf and sample, single and batched; the sample's pdf
/// is `pdf(sample)` bit for bit.
fn check_equal(name: &str, c: &impl CHandle, r: &impl Brdf<Spectrum = f32>) {
    let n = 157;
    let (wi, wo, u) = (directions(n, 0.0), directions(n, 0.37), us(n));
    let v = |d: RadVec3| Vec3::new(d.x, d.y, d.z);
    let (fb, pb, sb) = (
        c.eval_batch(&wi, &wo),
        c.pdf_batch(&wi, &wo),
        c.sample_batch(&wo, &u),
    );
    let mut drawn = 0;
    for k in 0..n {
        let (f, p) = (r.eval(v(wi[k]), v(wo[k])), r.pdf(v(wi[k]), v(wo[k])));
        assert_eq!(c.eval(wi[k], wo[k]).to_bits(), f.to_bits(), "{name} eval k={k}");
        assert_eq!(fb[k].to_bits(), f.to_bits(), "{name} eval_batch k={k}");
        assert_eq!(c.pdf(wi[k], wo[k]).to_bits(), p.to_bits(), "{name} pdf k={k}");
        assert_eq!(pb[k].to_bits(), p.to_bits(), "{name} pdf_batch k={k}");
        let want = r.sample(v(wo[k]), u[k]);
        let s = c.sample(wo[k], u[k]);
        assert!(same_sample(s, want), "{name} sample k={k}: {s:?} vs {want:?}");
        assert_eq!(sb[k], s, "{name} sample_batch k={k}");
        if s.pdf > 0.0 {
            drawn += 1;
            assert_eq!(
                c.pdf(s.wi, wo[k]).to_bits(),
                s.pdf.to_bits(),
                "{name}: pdf(sample) k={k}"
            );
            assert!(
                s.weight.iter().all(|w| w.is_finite() && *w >= 0.0),
                "{name} {s:?}"
            );
        }
    }
    assert!(drawn > n / 2, "{name}: {drawn} samples of {n}");
}

#[test]
fn new_plugins_equal_the_rust_plugins_bit_for_bit() {
    check_equal(
        "eon",
        &c_plugin(rad_brdf_eon, 0.8, 0.5),
        &Eon::new(0.8f32, 0.5).unwrap(),
    );
    check_equal(
        "fon",
        &c_plugin(rad_brdf_fon, 0.7, 1.0),
        &Fon::new(0.7f32, 1.0).unwrap(),
    );
    check_equal(
        "oren-nayar",
        &c_plugin(rad_brdf_oren_nayar, 0.9, 0.35),
        &OrenNayar::new(0.9f32, 0.35).unwrap(),
    );
    check_equal(
        "sheen",
        &c_plugin(rad_brdf_sheen, 0.8, 0.3),
        &Sheen::new(0.8f32, 0.3).unwrap(),
    );
    check_equal(
        "f82",
        &c_ggx(0.3, RAD_FRESNEL_F82, 0.9, 0.7),
        &ggx(0.3, F82Tint::new(0.9f32, 0.7).unwrap()),
    );
    let ids = [
        RAD_METAL_AU,
        RAD_METAL_AG,
        RAD_METAL_CU,
        RAD_METAL_AL,
        RAD_METAL_CR,
        RAD_METAL_FE,
        RAD_METAL_NI,
        RAD_METAL_TI,
        RAD_METAL_PT,
        RAD_METAL_BRASS,
    ];
    assert_eq!(ids.len(), Metal::ALL.len());
    for (id, m) in ids.into_iter().zip(Metal::ALL) {
        let h = c_ggx(0.2, RAD_FRESNEL_METAL, id as f32, 0.0);
        let c = Conductor::metal_luminance(m);
        assert_eq!((h.metal, h.params[1], h.params[2]), (id, c.eta(), c.k()), "{m:?}");
        check_equal(m.name(), &h, &ggx(0.2, c));
    }
}

#[test]
fn materials_equal_the_rust_composites_bit_for_bit() {
    let dielectric = c_ggx(0.1, RAD_FRESNEL_DIELECTRIC, 1.5, 0.0);
    let eon = c_plugin(rad_brdf_eon, 0.8, 0.5);
    let r_dielectric = || ggx(0.1, Dielectric::new(1.5).unwrap());
    let r_eon = || Eon::new(0.8f32, 0.5).unwrap();

    // The plastic: GGX α = 0.1, η = 1.5 over EON, clear.
    let plastic = c_coated(&dielectric, &eon, 1.0, 1.5);
    let r_plastic = Coated::new(r_dielectric(), r_eon());
    assert_eq!(plastic.kind, RAD_MATERIAL_COATED);
    check_equal("plastic", &plastic, &r_plastic);
    let mut reciprocal = RadMaterial::default();
    ok(unsafe { rad_material_coated_reciprocal(&dielectric, &eon, 0.7, 1.5, &mut reciprocal) });
    check_equal(
        "reciprocal plastic, absorbing",
        &reciprocal,
        &Coated::with_absorption(r_dielectric(), r_eon(), 0.7, 1.5)
            .unwrap()
            .with_layering(Layering::Reciprocal),
    );

    // A coated gold with an absorbing coat.
    let gold = c_ggx(0.3, RAD_FRESNEL_METAL, RAD_METAL_AU as f32, 0.0);
    let r_gold = ggx(0.3, Conductor::metal_luminance(Metal::Au));
    check_equal(
        "coated gold",
        &c_coated(&dielectric, &gold, 0.6, 1.6),
        &Coated::with_absorption(r_dielectric(), r_gold, 0.6, 1.6).unwrap(),
    );

    // Sheen over FON.
    let sheen = c_plugin(rad_brdf_sheen, 1.0, 0.5);
    let fon = c_plugin(rad_brdf_fon, 0.6, 0.8);
    check_equal(
        "sheen over fon",
        &c_coated(&sheen, &fon, 1.0, 1.5),
        &Coated::new(Sheen::new(1.0f32, 0.5).unwrap(), Fon::new(0.6f32, 0.8).unwrap()),
    );

    // A sum and a mix.
    let f82 = c_ggx(0.25, RAD_FRESNEL_F82, 0.9, 0.7);
    let r_f82 = ggx(0.25, F82Tint::new(0.9f32, 0.7).unwrap());
    let mut m = RadMaterial::default();
    ok(unsafe { rad_material_sum(&eon, &f82, &mut m) });
    check_equal("eon + f82", &m, &Sum::new(r_eon(), r_f82));
    let on = c_plugin(rad_brdf_oren_nayar, 0.9, 0.35);
    let r_on = OrenNayar::new(0.9f32, 0.35).unwrap();
    for w in [0.0, 0.3, 1.0] {
        ok(unsafe { rad_material_mix(w, &sheen, &on, &mut m) });
        check_equal(
            "mix",
            &m,
            &Mix::new(w, Sheen::new(1.0f32, 0.5).unwrap(), r_on).unwrap(),
        );
    }

    // One lobe: the plugin itself.
    ok(unsafe { rad_material_brdf(&eon, &mut m) });
    check_equal("brdf", &m, &r_eon());
    let lambert = {
        let mut h = RadBrdf::default();
        ok(unsafe { rad_brdf_lambertian(0.4, &mut h) });
        h
    };
    ok(unsafe { rad_material_mix(0.5, &lambert, &eon, &mut m) });
    check_equal(
        "mix(lambertian, eon)",
        &m,
        &Mix::new(0.5, Lambertian::new(0.4).unwrap(), r_eon()).unwrap(),
    );
}

#[test]
fn materials_match_their_soa_batches() {
    let plastic = c_coated(
        &c_ggx(0.1, RAD_FRESNEL_DIELECTRIC, 1.5, 0.0),
        &c_plugin(rad_brdf_eon, 0.8, 0.5),
        1.0,
        1.5,
    );
    let n = 77;
    let (wi, wo) = (directions(n, 0.1), directions(n, 0.6));
    let comp = |d: &[RadVec3], c: usize| -> Vec<f32> { d.iter().map(|v| [v.x, v.y, v.z][c]).collect() };
    let (ix, iy, iz) = (comp(&wi, 0), comp(&wi, 1), comp(&wi, 2));
    let (ox, oy, oz) = (comp(&wo, 0), comp(&wo, 1), comp(&wo, 2));
    let mut out = vec![0.0f32; n];
    ok(unsafe {
        rad_material_eval_batch_soa(
            &plastic,
            ix.as_ptr(),
            iy.as_ptr(),
            iz.as_ptr(),
            ox.as_ptr(),
            oy.as_ptr(),
            oz.as_ptr(),
            out.as_mut_ptr(),
            n,
        )
    });
    for k in 0..n {
        assert_eq!(out[k].to_bits(), plastic.eval(wi[k], wo[k]).to_bits(), "k={k}");
    }
}

#[test]
fn a_plastic_keeps_energy_and_its_reciprocal_form_is_reciprocal() {
    let (top, base) = (
        c_ggx(0.1, RAD_FRESNEL_DIELECTRIC, 1.5, 0.0),
        c_plugin(rad_brdf_eon, 1.0, 0.5),
    );
    let energy = c_coated(&top, &base, 1.0, 1.5);
    let mut reciprocal = RadMaterial::default();
    ok(unsafe { rad_material_coated_reciprocal(&top, &base, 1.0, 1.5, &mut reciprocal) });
    assert_eq!((energy.reciprocal, reciprocal.reciprocal), (0, 1));
    let d = directions(40, 0.2);
    for &a in &d {
        for &b in &d {
            let (x, y) = (reciprocal.eval(a, b), reciprocal.eval(b, a));
            assert!((x - y).abs() <= 1e-5 * x.abs().max(1e-3), "{x} vs {y}");
        }
    }
    // Albedo by its own sampler (the estimator is unbiased): ≤ 1 within 4 standard errors.
    for (plastic, theta) in [energy, reciprocal]
        .into_iter()
        .flat_map(|m| [0.0f32, 1.0, 1.4].map(|t| (m, t)))
    {
        let wo = RadVec3 {
            x: theta.sin(),
            y: 0.0,
            z: theta.cos(),
        };
        let n = 20_000;
        let w: Vec<f64> = us(n)
            .into_iter()
            .map(|u| f64::from(plastic.sample(wo, u).weight[0]))
            .collect();
        let mean = w.iter().sum::<f64>() / n as f64;
        let var = w.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1) as f64;
        let se = (var / n as f64).sqrt();
        assert!(mean <= 1.0 + 4.0 * se, "θo = {theta}: {mean} ± {se}");
        assert!(mean > 0.8, "a white plastic keeps most of the light: {mean}");
    }
}

#[test]
fn new_constructors_reject_bad_parameters_with_a_status() {
    let mut b = RadBrdf::default();
    unsafe {
        assert_eq!(rad_brdf_eon(0.5, 1.5, &mut b), RadStatus::OutOfRange);
        assert_eq!(rad_brdf_eon(1.2, 0.5, &mut b), RadStatus::OutOfRange);
        assert_eq!(rad_brdf_eon(f32::NAN, 0.5, &mut b), RadStatus::NotFinite);
        assert_eq!(rad_brdf_fon(0.5, -0.1, &mut b), RadStatus::OutOfRange);
        assert_eq!(rad_brdf_oren_nayar(0.5, 2.0, &mut b), RadStatus::OutOfRange);
        // ρ = 1 at σ = 0.2 rad reflects more than 1 at grazing view.
        assert_eq!(rad_brdf_oren_nayar(1.0, 0.2, &mut b), RadStatus::Constraint);
        assert_eq!(rad_brdf_sheen(0.5, 0.01, &mut b), RadStatus::OutOfRange);
        assert_eq!(rad_brdf_sheen(1.5, 0.5, &mut b), RadStatus::OutOfRange);
        assert_eq!(rad_brdf_sheen(0.5, f32::INFINITY, &mut b), RadStatus::NotFinite);
        let mf = |f, a, k, out: &mut RadBrdf| rad_brdf_microfacet(0, 0.3, 0, f, a, k, out);
        assert_eq!(mf(RAD_FRESNEL_F82, 1.2, 0.5, &mut b), RadStatus::OutOfRange);
        assert_eq!(mf(RAD_FRESNEL_F82, 0.5, -0.5, &mut b), RadStatus::OutOfRange);
        for bad in [0.0, 11.0, 1.5, -1.0, 1e10] {
            assert_eq!(
                mf(RAD_FRESNEL_METAL, bad, 0.0, &mut b),
                RadStatus::UnknownKind,
                "{bad}"
            );
        }
        assert_eq!(mf(RAD_FRESNEL_METAL, f32::NAN, 0.0, &mut b), RadStatus::NotFinite);
        assert_eq!(rad_brdf_eon(0.5, 0.5, null_mut()), RadStatus::NullPointer);
    }
    assert_eq!(b, RadBrdf::default(), "output untouched on error");
}

#[test]
fn material_constructors_reject_bad_parameters_and_lobes() {
    let eon = c_plugin(rad_brdf_eon, 0.8, 0.5);
    let top = c_ggx(0.1, RAD_FRESNEL_DIELECTRIC, 1.5, 0.0);
    let mut broken = eon;
    broken.params[1] = 7.0;
    let mut m = RadMaterial::default();
    unsafe {
        assert_eq!(rad_material_mix(1.5, &eon, &top, &mut m), RadStatus::OutOfRange);
        assert_eq!(rad_material_mix(-0.1, &eon, &top, &mut m), RadStatus::OutOfRange);
        assert_eq!(
            rad_material_mix(f32::NAN, &eon, &top, &mut m),
            RadStatus::NotFinite
        );
        assert_eq!(
            rad_material_coated(&top, &eon, 1.5, 1.5, &mut m),
            RadStatus::OutOfRange
        );
        assert_eq!(
            rad_material_coated(&top, &eon, -0.5, 1.5, &mut m),
            RadStatus::OutOfRange
        );
        assert_eq!(
            rad_material_coated(&top, &eon, 0.5, 0.9, &mut m),
            RadStatus::OutOfRange
        );
        assert_eq!(
            rad_material_coated(&top, &eon, f32::NAN, 1.5, &mut m),
            RadStatus::NotFinite
        );
        assert_eq!(
            rad_material_coated(&top, &eon, 0.5, f32::INFINITY, &mut m),
            RadStatus::NotFinite
        );
        assert_eq!(
            rad_material_coated(&top, &broken, 1.0, 1.5, &mut m),
            RadStatus::OutOfRange
        );
        assert_eq!(rad_material_sum(&broken, &eon, &mut m), RadStatus::OutOfRange);
        assert_eq!(
            rad_material_sum(&RadBrdf::default(), &eon, &mut m),
            RadStatus::BadHandle
        );
        assert_eq!(rad_material_brdf(&broken, &mut m), RadStatus::OutOfRange);
        assert_eq!(rad_material_sum(null(), &eon, &mut m), RadStatus::NullPointer);
        assert_eq!(
            rad_material_coated(&top, null(), 1.0, 1.5, &mut m),
            RadStatus::NullPointer
        );
        assert_eq!(rad_material_sum(&eon, &eon, null_mut()), RadStatus::NullPointer);
    }
    assert_eq!(m, RadMaterial::default(), "output untouched on error");
}

#[test]
fn scribbled_materials_are_reported() {
    let plastic = c_coated(
        &c_ggx(0.1, RAD_FRESNEL_DIELECTRIC, 1.5, 0.0),
        &c_plugin(rad_brdf_eon, 0.8, 0.5),
        1.0,
        1.5,
    );
    let (wi, wo) = (directions(3, 0.2)[2], directions(3, 0.5)[2]);
    let status = |m: &RadMaterial| {
        let mut f = 0.0;
        unsafe { rad_material_eval(m, wi, wo, &mut f) }
    };
    assert_eq!(status(&plastic), RadStatus::Ok);
    assert_eq!(status(&RadMaterial::default()), RadStatus::BadHandle);
    type Scribble = fn(&mut RadMaterial);
    let cases: [(&str, Scribble, RadStatus); 6] = [
        ("kind", |m| m.kind = 99, RadStatus::BadHandle),
        ("layering", |m| m.reciprocal = 2, RadStatus::BadHandle),
        ("coat ior", |m| m.coat_ior = 0.0, RadStatus::OutOfRange),
        ("coat colour", |m| m.coat_color = f32::NAN, RadStatus::NotFinite),
        ("lobe", |m| m.lobes[1].params[0] = 3.0, RadStatus::OutOfRange),
        (
            "metal id on a non-metal",
            |m| m.lobes[0].metal = RAD_METAL_AU,
            RadStatus::BadHandle,
        ),
    ];
    for (what, scribble, want) in cases {
        let mut m = plastic;
        scribble(&mut m);
        assert_eq!(status(&m), want, "{what}");
    }
    // A one-lobe material with a second lobe.
    let mut one = RadMaterial::default();
    ok(unsafe { rad_material_brdf(&plastic.lobes[1], &mut one) });
    assert_eq!(status(&one), RadStatus::Ok);
    one.lobes[1] = plastic.lobes[0];
    assert_eq!(status(&one), RadStatus::BadHandle);
    // Batch calls: the same pointer checks as the RadBrdf calls.
    let d = directions(8, 0.0);
    let mut out = [0.0f32; 8];
    unsafe {
        assert_eq!(
            rad_material_eval_batch(&plastic, d.as_ptr(), d.as_ptr(), d.as_ptr() as *mut f32, 8),
            RadStatus::Overlap
        );
        assert_eq!(
            rad_material_pdf_batch(&plastic, null(), d.as_ptr(), out.as_mut_ptr(), 8),
            RadStatus::NullPointer
        );
        assert_eq!(
            rad_material_eval_batch(&plastic, null(), null(), null_mut(), 0),
            RadStatus::Ok
        );
        assert_eq!(
            rad_material_sample_batch(&RadMaterial::default(), d.as_ptr(), out.as_ptr(), null_mut(), 0),
            RadStatus::BadHandle
        );
        assert_eq!(
            rad_material_eval(null(), wi, wo, out.as_mut_ptr()),
            RadStatus::NullPointer
        );
    }
}

fn c_openpbr(p: &RadOpenPbrParams) -> RadOpenPbr {
    let mut m = RadOpenPbr::default();
    ok(unsafe { rad_openpbr_new(p, &mut m) });
    m
}

fn c_defaults() -> RadOpenPbrParams {
    // Start from garbage: the call writes every field.
    let mut p = RadOpenPbrParams {
        base_color: [f32::NAN; 3],
        ..RadOpenPbrParams::default()
    };
    ok(unsafe { rad_openpbr_default_params(&mut p) });
    p
}

/// Parameter sets that turn each layer on (as the Rust unit tests do).
fn openpbr_variety() -> Vec<RadOpenPbrParams> {
    let d = c_defaults();
    vec![
        d,
        RadOpenPbrParams {
            base_metalness: 0.4,
            base_diffuse_roughness: 0.7,
            specular_roughness: 0.1,
            ..d
        },
        // A coated metal.
        RadOpenPbrParams {
            base_metalness: 1.0,
            base_color: [0.9; 3],
            specular_color: [0.8; 3],
            coat_weight: 1.0,
            coat_roughness: 0.2,
            coat_color: [0.7; 3],
            ..d
        },
        RadOpenPbrParams {
            fuzz_weight: 0.8,
            fuzz_roughness: 0.4,
            fuzz_color: [0.9; 3],
            coat_weight: 0.5,
            ..d
        },
        // Mirrors (roughness 0 raised to the floor) and fuzz roughness 0
        // (raised to 0.07).
        RadOpenPbrParams {
            specular_roughness: 0.0,
            coat_roughness: 0.0,
            coat_weight: 0.3,
            fuzz_weight: 1.0,
            fuzz_roughness: 0.0,
            specular_weight: 0.5,
            ..d
        },
        // Every layer, away from the defaults.
        RadOpenPbrParams {
            base_weight: 0.7,
            base_color: [0.5; 3],
            base_metalness: 0.5,
            base_diffuse_roughness: 1.0,
            specular_weight: 0.8,
            specular_color: [0.9; 3],
            specular_roughness: 0.6,
            specular_ior: 2.2,
            coat_weight: 0.6,
            coat_color: [0.3; 3],
            coat_roughness: 0.4,
            coat_ior: 1.3,
            coat_darkening: 0.4,
            fuzz_weight: 0.4,
            fuzz_color: [0.6; 3],
            fuzz_roughness: 0.9,
            reciprocal: 0,
        },
        // The reciprocal layering, every layer on.
        RadOpenPbrParams {
            base_metalness: 0.3,
            coat_weight: 0.7,
            coat_color: [0.6; 3],
            coat_roughness: 0.3,
            coat_darkening: 0.0,
            fuzz_weight: 0.5,
            reciprocal: 1,
            ..d
        },
    ]
}

#[test]
fn openpbr_defaults_are_openpbrs() {
    let p = c_defaults();
    let want = RadOpenPbrParams {
        base_weight: 1.0,
        base_color: [0.8; 3],
        base_metalness: 0.0,
        base_diffuse_roughness: 0.0,
        specular_weight: 1.0,
        specular_color: [1.0; 3],
        specular_roughness: 0.3,
        specular_ior: 1.5,
        coat_weight: 0.0,
        coat_color: [1.0; 3],
        coat_roughness: 0.0,
        coat_ior: 1.6,
        coat_darkening: 1.0,
        fuzz_weight: 0.0,
        fuzz_color: [1.0; 3],
        fuzz_roughness: 0.5,
        reciprocal: 0,
    };
    assert_eq!(p, want);
    assert_eq!(OpenPbrParams::<f32>::from(p), OpenPbrParams::default());
    assert_eq!(
        unsafe { rad_openpbr_default_params(null_mut()) },
        RadStatus::NullPointer
    );
}

#[test]
fn openpbr_equals_the_rust_plugin_bit_for_bit() {
    for (k, p) in openpbr_variety().into_iter().enumerate() {
        let c = c_openpbr(&p);
        let layering = if p.reciprocal == 1 {
            Layering::Reciprocal
        } else {
            Layering::EnergyConserving
        };
        let r = OpenPbr::with_layering(OpenPbrParams::from(p), layering).unwrap();
        assert_eq!(c.kind, RAD_OPENPBR_REFLECTION);
        assert_eq!(c.params, p);
        assert_eq!(r.layering(), layering);
        check_equal(&format!("openpbr {k}"), &c, &r);
    }
}

#[test]
fn openpbr_soa_batch_equals_single_calls() {
    let m = c_openpbr(&openpbr_variety()[5]);
    let n = 77;
    let (wi, wo) = (directions(n, 0.1), directions(n, 0.6));
    let comp = |d: &[RadVec3], c: usize| -> Vec<f32> { d.iter().map(|v| [v.x, v.y, v.z][c]).collect() };
    let (ix, iy, iz) = (comp(&wi, 0), comp(&wi, 1), comp(&wi, 2));
    let (ox, oy, oz) = (comp(&wo, 0), comp(&wo, 1), comp(&wo, 2));
    let mut out = vec![0.0f32; n];
    ok(unsafe {
        rad_openpbr_eval_batch_soa(
            &m,
            ix.as_ptr(),
            iy.as_ptr(),
            iz.as_ptr(),
            ox.as_ptr(),
            oy.as_ptr(),
            oz.as_ptr(),
            out.as_mut_ptr(),
            n,
        )
    });
    for k in 0..n {
        assert_eq!(out[k].to_bits(), m.eval(wi[k], wo[k]).to_bits(), "k={k}");
    }
}

/// Every field of `RadOpenPbrParams`, by name, for the checks below.
type Field = fn(&mut RadOpenPbrParams) -> &mut f32;

fn openpbr_fields() -> [(&'static str, Field); 16] {
    [
        ("base_weight", |p| &mut p.base_weight),
        ("base_color", |p| &mut p.base_color[1]),
        ("base_metalness", |p| &mut p.base_metalness),
        ("base_diffuse_roughness", |p| &mut p.base_diffuse_roughness),
        ("specular_weight", |p| &mut p.specular_weight),
        ("specular_color", |p| &mut p.specular_color[1]),
        ("specular_roughness", |p| &mut p.specular_roughness),
        ("specular_ior", |p| &mut p.specular_ior),
        ("coat_weight", |p| &mut p.coat_weight),
        ("coat_color", |p| &mut p.coat_color[1]),
        ("coat_roughness", |p| &mut p.coat_roughness),
        ("coat_ior", |p| &mut p.coat_ior),
        ("coat_darkening", |p| &mut p.coat_darkening),
        ("fuzz_weight", |p| &mut p.fuzz_weight),
        ("fuzz_color", |p| &mut p.fuzz_color[1]),
        ("fuzz_roughness", |p| &mut p.fuzz_roughness),
    ]
}

#[test]
fn openpbr_rejects_bad_parameters_with_a_status() {
    let d = c_defaults();
    let mut m = RadOpenPbr::default();
    for (name, field) in openpbr_fields() {
        let ior = name.ends_with("_ior");
        let (low, high) = if ior { (0.99, 1001.0) } else { (-0.01, 1.01) };
        for (bad, want) in [
            (low, RadStatus::OutOfRange),
            (high, RadStatus::OutOfRange),
            (f32::NAN, RadStatus::NotFinite),
            (f32::INFINITY, RadStatus::NotFinite),
            (f32::NEG_INFINITY, RadStatus::NotFinite),
        ] {
            let mut p = d;
            *field(&mut p) = bad;
            assert_eq!(unsafe { rad_openpbr_new(&p, &mut m) }, want, "{name} = {bad}");
        }
        // The ends of the domain are accepted.
        let mut p = d;
        *field(&mut p) = if ior { 1000.0 } else { 1.0 };
        let mut good = RadOpenPbr::default();
        assert_eq!(unsafe { rad_openpbr_new(&p, &mut good) }, RadStatus::Ok, "{name}");
    }
    // The layering flag: 0 or 1; checked after every float.
    for (reciprocal, want) in [
        (1, RadStatus::Ok),
        (2, RadStatus::OutOfRange),
        (u32::MAX, RadStatus::OutOfRange),
    ] {
        let mut good = RadOpenPbr::default();
        let p = RadOpenPbrParams { reciprocal, ..d };
        assert_eq!(
            unsafe { rad_openpbr_new(&p, &mut good) },
            want,
            "reciprocal = {reciprocal}"
        );
        let p = RadOpenPbrParams {
            reciprocal,
            fuzz_roughness: f32::NAN,
            ..d
        };
        assert_eq!(
            unsafe { rad_openpbr_new(&p, &mut good) },
            RadStatus::NotFinite,
            "reciprocal = {reciprocal}, fuzz_roughness NaN"
        );
    }
    unsafe {
        assert_eq!(rad_openpbr_new(null(), &mut m), RadStatus::NullPointer);
        assert_eq!(rad_openpbr_new(&d, null_mut()), RadStatus::NullPointer);
    }
    assert_eq!(m, RadOpenPbr::default(), "output untouched on error");
}

#[test]
fn scribbled_openpbr_handles_are_reported() {
    let good = c_openpbr(&openpbr_variety()[3]);
    let (wi, wo) = (directions(3, 0.2)[2], directions(3, 0.5)[2]);
    let status = |m: &RadOpenPbr| {
        let mut f = 0.0;
        unsafe { rad_openpbr_eval(m, wi, wo, &mut f) }
    };
    assert_eq!(status(&good), RadStatus::Ok);
    assert_eq!(status(&RadOpenPbr::default()), RadStatus::BadHandle);
    type Scribble = fn(&mut RadOpenPbr);
    let cases: [(&str, Scribble, RadStatus); 6] = [
        ("kind", |m| m.kind = 2, RadStatus::BadHandle),
        ("coat ior", |m| m.params.coat_ior = 0.0, RadStatus::OutOfRange),
        (
            "base colour",
            |m| m.params.base_color = [1.5; 3],
            RadStatus::OutOfRange,
        ),
        (
            "fuzz weight",
            |m| m.params.fuzz_weight = f32::NAN,
            RadStatus::NotFinite,
        ),
        (
            "specular ior",
            |m| m.params.specular_ior = f32::INFINITY,
            RadStatus::NotFinite,
        ),
        ("reciprocal", |m| m.params.reciprocal = 7, RadStatus::OutOfRange),
    ];
    let d = directions(8, 0.0);
    let u = [0.5f32; 16];
    let mut out = [0.0f32; 8];
    let mut samples = [RadBrdfSample::default(); 8];
    for (what, scribble, want) in cases {
        let mut m = good;
        scribble(&mut m);
        assert_eq!(status(&m), want, "{what}");
        unsafe {
            let mut f = 0.0;
            assert_eq!(rad_openpbr_pdf(&m, wi, wo, &mut f), want, "{what} pdf");
            let mut s = RadBrdfSample::default();
            assert_eq!(
                rad_openpbr_sample(&m, wo, 0.3, 0.6, &mut s),
                want,
                "{what} sample"
            );
            assert_eq!(
                rad_openpbr_eval_batch(&m, d.as_ptr(), d.as_ptr(), out.as_mut_ptr(), 8),
                want,
                "{what} eval_batch"
            );
            assert_eq!(
                rad_openpbr_pdf_batch(&m, d.as_ptr(), d.as_ptr(), out.as_mut_ptr(), 8),
                want,
                "{what} pdf_batch"
            );
            assert_eq!(
                rad_openpbr_sample_batch(&m, d.as_ptr(), u.as_ptr(), samples.as_mut_ptr(), 8),
                want,
                "{what} sample_batch"
            );
        }
    }
    // Pointer checks as for the other handles.
    unsafe {
        assert_eq!(
            rad_openpbr_eval_batch(&good, d.as_ptr(), d.as_ptr(), d.as_ptr() as *mut f32, 8),
            RadStatus::Overlap
        );
        assert_eq!(
            rad_openpbr_pdf_batch(&good, null(), d.as_ptr(), out.as_mut_ptr(), 8),
            RadStatus::NullPointer
        );
        assert_eq!(
            rad_openpbr_eval_batch(&good, null(), null(), null_mut(), 0),
            RadStatus::Ok
        );
        assert_eq!(
            rad_openpbr_eval(null(), wi, wo, out.as_mut_ptr()),
            RadStatus::NullPointer
        );
        assert_eq!(
            rad_openpbr_eval(&good, wi, wo, null_mut()),
            RadStatus::NullPointer
        );
        let misaligned = (&good as *const RadOpenPbr)
            .cast::<u8>()
            .wrapping_add(1)
            .cast::<RadOpenPbr>();
        assert_eq!(
            rad_openpbr_eval(misaligned, wi, wo, out.as_mut_ptr()),
            RadStatus::Misaligned
        );
    }
}

// ---- Colour: the `_rgb` calls equal the Rust `Vec3` plugins and composites bit for bit. ----

/// A handle's RGB calls, for the shared checks.
trait CHandleRgb {
    fn eval_rgb(&self, wi: RadVec3, wo: RadVec3) -> [f32; 3];
    fn pdf_rgb(&self, wi: RadVec3, wo: RadVec3) -> f32;
    fn sample_rgb(&self, wo: RadVec3, u: [f32; 2]) -> RadBrdfSample;
    fn eval_batch_rgb(&self, wi: &[RadVec3], wo: &[RadVec3]) -> Vec<f32>;
    fn pdf_batch_rgb(&self, wi: &[RadVec3], wo: &[RadVec3]) -> Vec<f32>;
    fn sample_batch_rgb(&self, wo: &[RadVec3], u: &[[f32; 2]]) -> Vec<RadBrdfSample>;
}

macro_rules! c_handle_rgb {
    ($t:ty, $eval:ident, $pdf:ident, $sample:ident, $eb:ident, $pb:ident, $sb:ident) => {
        impl CHandleRgb for $t {
            fn eval_rgb(&self, wi: RadVec3, wo: RadVec3) -> [f32; 3] {
                let mut f = [f32::NAN; 3];
                ok(unsafe { $eval(self, wi, wo, f.as_mut_ptr()) });
                f
            }
            fn pdf_rgb(&self, wi: RadVec3, wo: RadVec3) -> f32 {
                let mut p = f32::NAN;
                ok(unsafe { $pdf(self, wi, wo, &mut p) });
                p
            }
            fn sample_rgb(&self, wo: RadVec3, u: [f32; 2]) -> RadBrdfSample {
                let mut s = RadBrdfSample::default();
                ok(unsafe { $sample(self, wo, u[0], u[1], &mut s) });
                s
            }
            fn eval_batch_rgb(&self, wi: &[RadVec3], wo: &[RadVec3]) -> Vec<f32> {
                let mut out = vec![f32::NAN; 3 * wi.len()];
                ok(unsafe { $eb(self, wi.as_ptr(), wo.as_ptr(), out.as_mut_ptr(), wi.len()) });
                out
            }
            fn pdf_batch_rgb(&self, wi: &[RadVec3], wo: &[RadVec3]) -> Vec<f32> {
                let mut out = vec![f32::NAN; wi.len()];
                ok(unsafe { $pb(self, wi.as_ptr(), wo.as_ptr(), out.as_mut_ptr(), wi.len()) });
                out
            }
            fn sample_batch_rgb(&self, wo: &[RadVec3], u: &[[f32; 2]]) -> Vec<RadBrdfSample> {
                let mut out = vec![RadBrdfSample::default(); wo.len()];
                let u = u.as_ptr().cast::<f32>();
                ok(unsafe { $sb(self, wo.as_ptr(), u, out.as_mut_ptr(), wo.len()) });
                out
            }
        }
    };
}

c_handle_rgb!(
    RadBrdf,
    rad_brdf_eval_rgb,
    rad_brdf_pdf_rgb,
    rad_brdf_sample_rgb,
    rad_brdf_eval_batch_rgb,
    rad_brdf_pdf_batch_rgb,
    rad_brdf_sample_batch_rgb
);
c_handle_rgb!(
    RadMaterial,
    rad_material_eval_rgb,
    rad_material_pdf_rgb,
    rad_material_sample_rgb,
    rad_material_eval_batch_rgb,
    rad_material_pdf_batch_rgb,
    rad_material_sample_batch_rgb
);
c_handle_rgb!(
    RadOpenPbr,
    rad_openpbr_eval_rgb,
    rad_openpbr_pdf_rgb,
    rad_openpbr_sample_rgb,
    rad_openpbr_eval_batch_rgb,
    rad_openpbr_pdf_batch_rgb,
    rad_openpbr_sample_batch_rgb
);

fn same_sample_rgb(c: RadBrdfSample, r: Option<BrdfSample<Vec3>>) -> bool {
    match r {
        None => c == RadBrdfSample::default(),
        Some(r) => {
            let bits = |v: [f32; 3]| v.map(f32::to_bits);
            bits([c.wi.x, c.wi.y, c.wi.z]) == bits(r.wi.to_array())
                && c.pdf.to_bits() == r.pdf.to_bits()
                && bits(c.weight) == bits(r.weight.to_array())
        }
    }
}

/// `c` through the RGB calls and `r` (the Rust `Vec3` plugin or composite) give the same bits for eval, pdf and
/// sample, single and batched; a sample's pdf is `pdf_rgb` at its direction, bit for bit.
fn check_equal_rgb(name: &str, c: &impl CHandleRgb, r: &impl Brdf<Spectrum = Vec3>) {
    let n = 203;
    let (wi, wo, u) = (directions(n, 0.13), directions(n, 0.71), us(n));
    let (eb, pb, sb) = (
        c.eval_batch_rgb(&wi, &wo),
        c.pdf_batch_rgb(&wi, &wo),
        c.sample_batch_rgb(&wo, &u),
    );
    for k in 0..n {
        let (a, b) = (Vec3::from(wi[k]), Vec3::from(wo[k]));
        let want = r.eval(a, b).to_array().map(f32::to_bits);
        assert_eq!(
            c.eval_rgb(wi[k], wo[k]).map(f32::to_bits),
            want,
            "{name} eval k={k}"
        );
        assert_eq!(
            [eb[3 * k], eb[3 * k + 1], eb[3 * k + 2]].map(f32::to_bits),
            want,
            "{name} batch k={k}"
        );
        assert_eq!(
            c.pdf_rgb(wi[k], wo[k]).to_bits(),
            r.pdf(a, b).to_bits(),
            "{name} pdf k={k}"
        );
        assert_eq!(pb[k].to_bits(), r.pdf(a, b).to_bits(), "{name} pdf batch k={k}");
        let s = c.sample_rgb(wo[k], u[k]);
        assert!(
            same_sample_rgb(s, r.sample(b, u[k])),
            "{name} sample k={k}: {s:?}"
        );
        assert_eq!(sb[k], s, "{name} sample batch k={k}");
        if s.pdf > 0.0 {
            assert_eq!(
                c.pdf_rgb(s.wi, wo[k]).to_bits(),
                s.pdf.to_bits(),
                "{name} pdf(sample) k={k}"
            );
        }
    }
}

fn c_rgb(
    f: unsafe extern "C" fn(*const f32, f32, *mut RadBrdf) -> RadStatus,
    c: [f32; 3],
    p: f32,
) -> RadBrdf {
    let mut h = RadBrdf::default();
    ok(unsafe { f(c.as_ptr(), p, &mut h) });
    h
}

/// The RGB plugins: coloured lobes from the `_rgb` constructors and a named metal equal the Rust `Vec3` plugins
/// (gold: `Conductor::<Vec3>::metal`, red above blue); a Lambertian is ρ/π per channel and its luminance in
/// the monochrome calls.
#[test]
fn rgb_plugins_equal_the_rust_plugins_bit_for_bit() {
    let orange = [0.8f32, 0.4, 0.1];
    let mut lam = RadBrdf::default();
    ok(unsafe { rad_brdf_lambertian_rgb(orange.as_ptr(), &mut lam) });
    check_equal_rgb(
        "lambertian",
        &lam,
        &Lambertian::new(Vec3::from_array(orange)).unwrap(),
    );
    let (wi, wo) = (directions(8, 0.3)[3], directions(8, 0.9)[5]);
    assert_eq!(lam.eval_rgb(wi, wo), orange.map(|c| c / PI));
    let mut mono = f32::NAN;
    ok(unsafe { rad_brdf_eval(&lam, wi, wo, &mut mono) });
    assert_eq!(mono, (0.2126 * 0.8 + 0.7152 * 0.4 + 0.0722 * 0.1) / PI);
    let rho = Vec3::new(0.2, 0.5, 0.7);
    check_equal_rgb(
        "eon",
        &c_rgb(rad_brdf_eon_rgb, rho.to_array(), 0.5),
        &Eon::new(rho, 0.5).unwrap(),
    );
    check_equal_rgb(
        "fon",
        &c_rgb(rad_brdf_fon_rgb, rho.to_array(), 0.8),
        &Fon::new(rho, 0.8).unwrap(),
    );
    check_equal_rgb(
        "oren-nayar",
        &c_rgb(rad_brdf_oren_nayar_rgb, rho.to_array(), 0.3),
        &OrenNayar::new(rho, 0.3).unwrap(),
    );
    check_equal_rgb(
        "sheen",
        &c_rgb(rad_brdf_sheen_rgb, rho.to_array(), 0.4),
        &Sheen::new(rho, 0.4).unwrap(),
    );
    for m in Metal::ALL {
        let id = [
            Metal::Au,
            Metal::Ag,
            Metal::Cu,
            Metal::Al,
            Metal::Cr,
            Metal::Fe,
            Metal::Ni,
            Metal::Ti,
            Metal::Pt,
        ]
        .iter()
        .position(|&x| x == m)
        .map_or(RAD_METAL_BRASS, |i| i as u32 + 1);
        let c = c_ggx(0.3, RAD_FRESNEL_METAL, id as f32, 0.0);
        let r =
            Microfacet::<Ggx, HeightCorrelated, _>::new(Ggx::new(0.3).unwrap(), Conductor::<Vec3>::metal(m));
        check_equal_rgb(m.name(), &c, &r);
    }
    let gold = c_ggx(0.3, RAD_FRESNEL_METAL, RAD_METAL_AU as f32, 0.0);
    let n = RadVec3 {
        x: 0.0,
        y: 0.0,
        z: 1.0,
    };
    let f = gold.eval_rgb(n, n);
    assert!(f[0] > f[1] && f[1] > f[2], "{f:?}");
}

/// A grey handle (every scalar constructor) gives the monochrome value on each RGB channel, bit for bit.
#[test]
fn grey_handles_give_the_monochrome_values_per_channel() {
    let plugins = [
        c_plugin(rad_brdf_eon, 0.7, 0.5),
        c_plugin(rad_brdf_fon, 0.7, 0.5),
        c_plugin(rad_brdf_sheen, 0.8, 0.3),
        c_ggx(0.3, RAD_FRESNEL_DIELECTRIC, 1.5, 0.0),
        c_ggx(0.2, RAD_FRESNEL_SCHLICK, 0.04, 0.0),
        c_ggx(0.4, RAD_FRESNEL_CONDUCTOR, 0.2, 3.9),
        c_ggx(0.5, RAD_FRESNEL_F82, 0.9, 0.7),
        c_ggx(0.5, RAD_FRESNEL_NONE, 0.0, 0.0),
    ];
    let (wi, wo) = (directions(61, 0.2), directions(61, 0.6));
    for h in &plugins {
        for k in 0..wi.len() {
            let mut m = f32::NAN;
            ok(unsafe { rad_brdf_eval(h, wi[k], wo[k], &mut m) });
            assert_eq!(
                h.eval_rgb(wi[k], wo[k]).map(f32::to_bits),
                [m.to_bits(); 3],
                "{h:?} k={k}"
            );
        }
    }
    let coat = c_ggx(0.1, RAD_FRESNEL_DIELECTRIC, 1.5, 0.0);
    let m = c_coated(&coat, &plugins[0], 0.6, 1.5);
    for k in 0..wi.len() {
        let mut v = f32::NAN;
        ok(unsafe { rad_material_eval(&m, wi[k], wo[k], &mut v) });
        assert_eq!(
            m.eval_rgb(wi[k], wo[k]).map(f32::to_bits),
            [v.to_bits(); 3],
            "coated k={k}"
        );
    }
}

/// RGB materials equal the Rust `Vec3` composites bit for bit (pick probabilities from the lobes' RGB albedos).
#[test]
fn rgb_materials_equal_the_rust_composites_bit_for_bit() {
    let rho = Vec3::new(0.7, 0.3, 0.1);
    let base = c_rgb(rad_brdf_eon_rgb, rho.to_array(), 0.4);
    let coat = c_ggx(0.1, RAD_FRESNEL_DIELECTRIC, 1.5, 0.0);
    let gold = c_ggx(0.3, RAD_FRESNEL_METAL, RAD_METAL_AU as f32, 0.0);
    let r_base = Eon::new(rho, 0.4).unwrap();
    let r_coat = Microfacet::<Ggx, HeightCorrelated, _>::new(
        Ggx::new(0.1).unwrap(),
        radiometry_brdfs::microfacet::Achromatic::<_, Vec3>::new(Dielectric::new(1.5).unwrap()),
    );
    let r_gold = Microfacet::<Ggx, HeightCorrelated, _>::new(
        Ggx::new(0.3).unwrap(),
        Conductor::<Vec3>::metal(Metal::Au),
    );
    let plastic = c_coated(&coat, &base, 0.8, 1.6);
    check_equal_rgb(
        "red plastic",
        &plastic,
        &Coated::new(r_coat, r_base)
            .absorbing(Vec3::splat(0.8), 1.6)
            .unwrap(),
    );
    let mut mix = RadMaterial::default();
    ok(unsafe { rad_material_mix(0.3, &gold, &base, &mut mix) });
    check_equal_rgb("mix", &mix, &Mix::new(0.3, r_gold, r_base).unwrap());
    let mut sum = RadMaterial::default();
    ok(unsafe { rad_material_sum(&coat, &gold, &mut sum) });
    check_equal_rgb("sum", &sum, &Sum::new(r_coat, r_gold));
    let mut reciprocal = RadMaterial::default();
    ok(unsafe { rad_material_coated_reciprocal(&coat, &gold, 1.0, 1.5, &mut reciprocal) });
    check_equal_rgb(
        "reciprocal coated gold",
        &reciprocal,
        &Coated::new(r_coat, r_gold).with_layering(Layering::Reciprocal),
    );
}

/// The target: `openpbr(base_color=rgb(0.8, 0.1, 0.1))` through the C API equals `OpenPbr<Vec3>` bit for
/// bit; every colour of the parameters reaches its channel.
#[test]
fn rgb_openpbr_equals_the_rust_plugin_bit_for_bit() {
    let red = RadOpenPbrParams {
        base_color: [0.8, 0.1, 0.1],
        ..c_defaults()
    };
    let want = OpenPbrParams::<Vec3> {
        base_color: Vec3::new(0.8, 0.1, 0.1),
        ..OpenPbrParams::default()
    };
    assert_eq!(OpenPbrParams::<Vec3>::from(red), want);
    check_equal_rgb("red openpbr", &c_openpbr(&red), &OpenPbr::new(want).unwrap());
    let all = RadOpenPbrParams {
        base_color: [0.9, 0.6, 0.2],
        base_metalness: 0.6,
        specular_color: [1.0, 0.9, 0.8],
        coat_weight: 0.8,
        coat_color: [0.9, 0.95, 0.7],
        fuzz_weight: 0.4,
        fuzz_color: [0.3, 0.3, 1.0],
        reciprocal: 1,
        ..c_defaults()
    };
    let p = OpenPbrParams::<Vec3>::from(all);
    assert_eq!(
        (p.base_color, p.specular_color, p.coat_color, p.fuzz_color),
        (
            Vec3::new(0.9, 0.6, 0.2),
            Vec3::new(1.0, 0.9, 0.8),
            Vec3::new(0.9, 0.95, 0.7),
            Vec3::new(0.3, 0.3, 1.0)
        )
    );
    check_equal_rgb(
        "openpbr, every layer",
        &c_openpbr(&all),
        &OpenPbr::with_layering(p, Layering::Reciprocal).unwrap(),
    );
    // The monochrome calls use each colour's luminance.
    let mono = OpenPbrParams::<f32>::from(red);
    assert_eq!(mono.base_color, 0.2126 * 0.8 + 0.7152 * 0.1 + 0.0722 * 0.1);
}

/// Bad colours, pointers and buffers of the RGB calls are statuses.
#[test]
fn rgb_calls_report_bad_input() {
    let mut h = RadBrdf::default();
    for (c, want) in [
        ([0.5, f32::NAN, 0.5], RadStatus::NotFinite),
        ([0.5, 1.2, 0.5], RadStatus::OutOfRange),
        ([-0.1, 0.5, 0.5], RadStatus::OutOfRange),
    ] {
        assert_eq!(
            unsafe { rad_brdf_lambertian_rgb(c.as_ptr(), &mut h) },
            want,
            "{c:?}"
        );
    }
    assert_eq!(
        unsafe { rad_brdf_lambertian_rgb(null(), &mut h) },
        RadStatus::NullPointer
    );
    // An Oren–Nayar channel above the energy bound.
    assert_eq!(
        unsafe { rad_brdf_oren_nayar_rgb([0.5, 1.0, 0.5].as_ptr(), 0.3, &mut h) },
        RadStatus::Constraint
    );
    assert_eq!(h, RadBrdf::default(), "unchanged on error");
    let lam = c_rgb(rad_brdf_eon_rgb, [0.2, 0.4, 0.6], 0.5);
    let w = directions(4, 0.1);
    assert_eq!(
        unsafe { rad_brdf_eval_rgb(&lam, w[0], w[1], null_mut()) },
        RadStatus::NullPointer
    );
    assert_eq!(
        unsafe { rad_brdf_eval_rgb(null(), w[0], w[1], [0.0f32; 3].as_mut_ptr()) },
        RadStatus::NullPointer
    );
    // The output of 3n floats may not overlap the inputs (here: out over wi).
    let mut buf = vec![0.0f32; 3 * 4 * 2];
    let wi = buf.as_ptr().cast::<RadVec3>();
    let s = unsafe { rad_brdf_eval_batch_rgb(&lam, wi, w.as_ptr(), buf.as_mut_ptr(), 4) };
    assert_eq!(s, RadStatus::Overlap);
    // 3n overflows.
    let s =
        unsafe { rad_brdf_eval_batch_rgb(&lam, w.as_ptr(), w.as_ptr(), buf.as_mut_ptr(), usize::MAX / 2) };
    assert!(s == RadStatus::TooLong, "{s:?}");
    // A scribbled colour is reported by the RGB calls.
    let mut bad = lam;
    bad.rgb[0][2] = 2.0;
    let mut f = [0.0f32; 3];
    assert_eq!(
        unsafe { rad_brdf_eval_rgb(&bad, w[0], w[1], f.as_mut_ptr()) },
        RadStatus::OutOfRange
    );
}

/// Coloured Fresnel parameters: Schlick `f0[3]`, a conductor's `η[3]`, `k[3]` and F82-tint `f0[3]`, `f82[3]` equal
/// the Rust `Vec3` Fresnel terms bit for bit; other Fresnel kinds and bad channels are statuses.
#[test]
fn rgb_fresnel_parameters_equal_the_rust_plugins() {
    let mk = |fresnel: u32, a: [f32; 3], b: Option<[f32; 3]>| {
        let mut h = RadBrdf::default();
        let bp = b.as_ref().map_or(null(), |b| b.as_ptr());
        let s = unsafe {
            rad_brdf_microfacet_rgb(
                RAD_DISTRIBUTION_GGX,
                0.25,
                RAD_SHADOWING_HEIGHT_CORRELATED,
                fresnel,
                a.as_ptr(),
                bp,
                &mut h,
            )
        };
        (s, h)
    };
    let g = || Ggx::new(0.25).unwrap();
    let (s, h) = mk(RAD_FRESNEL_SCHLICK, [0.95, 0.64, 0.54], None);
    ok(s);
    let f0 = Vec3::new(0.95, 0.64, 0.54);
    let r = Microfacet::<Ggx, HeightCorrelated, _>::new(g(), radiometry_brdfs::Schlick::new(f0).unwrap());
    check_equal_rgb("schlick rgb", &h, &r);
    let (eta, k) = ([0.2f32, 0.92, 1.1], [3.9f32, 2.45, 2.14]);
    let (s, h) = mk(RAD_FRESNEL_CONDUCTOR, eta, Some(k));
    ok(s);
    let c = Conductor::new(Vec3::from_array(eta), Vec3::from_array(k)).unwrap();
    check_equal_rgb(
        "conductor rgb",
        &h,
        &Microfacet::<Ggx, HeightCorrelated, _>::new(g(), c),
    );
    // The monochrome calls: the luminance of η and of k.
    let lum = |v: [f32; 3]| 0.2126 * v[0] + 0.7152 * v[1] + 0.0722 * v[2];
    assert_eq!(h.params, [0.25, lum(eta), lum(k)]);
    let (t0, t82) = ([0.9f32, 0.7, 0.3], [0.8f32, 0.9, 1.0]);
    let (s, h) = mk(RAD_FRESNEL_F82, t0, Some(t82));
    ok(s);
    let f = F82Tint::new(Vec3::from_array(t0), Vec3::from_array(t82)).unwrap();
    check_equal_rgb(
        "f82 rgb",
        &h,
        &Microfacet::<Ggx, HeightCorrelated, _>::new(g(), f),
    );
    for fresnel in [RAD_FRESNEL_NONE, RAD_FRESNEL_DIELECTRIC, RAD_FRESNEL_METAL, 99] {
        assert_eq!(
            mk(fresnel, [0.5; 3], Some([0.5; 3])).0,
            RadStatus::UnknownKind,
            "{fresnel}"
        );
    }
    assert_eq!(
        mk(RAD_FRESNEL_SCHLICK, [0.5, 1.5, 0.5], None).0,
        RadStatus::OutOfRange
    );
    assert_eq!(
        mk(RAD_FRESNEL_CONDUCTOR, [0.5; 3], None).0,
        RadStatus::NullPointer
    );
    assert_eq!(
        mk(RAD_FRESNEL_F82, [0.5, f32::NAN, 0.5], Some([1.0; 3])).0,
        RadStatus::NotFinite
    );
}

/// The SoA RGB batches equal the AoS RGB batches bit for bit, for a plugin, a material and OpenPBR; outputs that
/// overlap an input or each other are `RAD_STATUS_OVERLAP`.
#[test]
fn rgb_soa_batches_equal_the_aos_batches() {
    let n = 150;
    let (wi, wo) = (directions(n, 0.21), directions(n, 0.47));
    let comp = |v: &[RadVec3], f: fn(&RadVec3) -> f32| v.iter().map(f).collect::<Vec<f32>>();
    let (ix, iy, iz) = (comp(&wi, |v| v.x), comp(&wi, |v| v.y), comp(&wi, |v| v.z));
    let (ox, oy, oz) = (comp(&wo, |v| v.x), comp(&wo, |v| v.y), comp(&wo, |v| v.z));
    type Soa<H> = unsafe extern "C" fn(
        *const H,
        *const f32,
        *const f32,
        *const f32,
        *const f32,
        *const f32,
        *const f32,
        *mut f32,
        *mut f32,
        *mut f32,
        usize,
    ) -> RadStatus;
    fn check<H: CHandleRgb>(
        name: &str,
        h: &H,
        soa: Soa<H>,
        inputs: [&[f32]; 6],
        wi: &[RadVec3],
        wo: &[RadVec3],
    ) {
        let n = wi.len();
        let (mut r, mut g, mut b) = (vec![f32::NAN; n], vec![f32::NAN; n], vec![f32::NAN; n]);
        let [ix, iy, iz, ox, oy, oz] = inputs.map(|s| s.as_ptr());
        ok(unsafe {
            soa(
                h,
                ix,
                iy,
                iz,
                ox,
                oy,
                oz,
                r.as_mut_ptr(),
                g.as_mut_ptr(),
                b.as_mut_ptr(),
                n,
            )
        });
        let aos = h.eval_batch_rgb(wi, wo);
        for k in 0..n {
            let got = [r[k], g[k], b[k]].map(f32::to_bits);
            assert_eq!(
                got,
                [aos[3 * k], aos[3 * k + 1], aos[3 * k + 2]].map(f32::to_bits),
                "{name} k={k}"
            );
        }
        let s = unsafe {
            soa(
                h,
                ix,
                iy,
                iz,
                ox,
                oy,
                oz,
                r.as_mut_ptr(),
                r.as_mut_ptr(),
                b.as_mut_ptr(),
                n,
            )
        };
        assert_eq!(s, RadStatus::Overlap, "{name}: out_g over out_r");
        let s = unsafe {
            soa(
                h,
                ix,
                iy,
                iz,
                ox,
                oy,
                oz,
                r.as_mut_ptr(),
                g.as_mut_ptr(),
                ix as *mut f32,
                n,
            )
        };
        assert_eq!(s, RadStatus::Overlap, "{name}: out_b over wi_x");
    }
    let inputs: [&[f32]; 6] = [&ix, &iy, &iz, &ox, &oy, &oz];
    let gold = c_ggx(0.3, RAD_FRESNEL_METAL, RAD_METAL_AU as f32, 0.0);
    check("gold", &gold, rad_brdf_eval_batch_soa_rgb, inputs, &wi, &wo);
    let base = c_rgb(rad_brdf_eon_rgb, [0.7, 0.3, 0.1], 0.4);
    let coat = c_ggx(0.1, RAD_FRESNEL_DIELECTRIC, 1.5, 0.0);
    check(
        "plastic",
        &c_coated(&coat, &base, 0.9, 1.5),
        rad_material_eval_batch_soa_rgb,
        inputs,
        &wi,
        &wo,
    );
    let red = RadOpenPbrParams {
        base_color: [0.8, 0.1, 0.1],
        ..c_defaults()
    };
    check(
        "openpbr",
        &c_openpbr(&red),
        rad_openpbr_eval_batch_soa_rgb,
        inputs,
        &wi,
        &wo,
    );
}
