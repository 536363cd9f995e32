//! Bare-metal image for the footprint measurement (see Cargo.toml).
#![no_std]
#![no_main]

// Link the library in every image (it provides the panic handler).
use radiometry_ffi as _;

#[cfg(any(
    feature = "als",
    feature = "brdf",
    feature = "material",
    feature = "openpbr",
    feature = "others",
    feature = "rgb"
))]
use core::hint::black_box;

/// The reset entry: calls the measured functions with opaque arguments so
/// that nothing is constant-folded away, then parks.
#[unsafe(no_mangle)]
pub extern "C" fn _start() -> ! {
    #[cfg(feature = "als")]
    als();
    #[cfg(feature = "brdf")]
    brdf();
    #[cfg(feature = "material")]
    material();
    #[cfg(feature = "others")]
    others();
    #[cfg(feature = "openpbr")]
    openpbr();
    #[cfg(feature = "rgb")]
    rgb();
    loop {
        core::hint::spin_loop();
    }
}

#[cfg(feature = "als")]
fn als() {
    use radiometry_ffi::als::*;
    use radiometry_ffi::{RadAlsCalibration, RadStatus};
    let mut cal = RadAlsCalibration::default();
    let mut lux = 0.0f32;
    // SAFETY: valid, aligned, exclusive pointers to locals.
    unsafe {
        let s = rad_als_from_reference(
            black_box(16.0),
            black_box(12016.0),
            black_box(1.0),
            black_box(0.1),
            black_box(500.0),
            black_box(65535),
            &mut cal,
        );
        black_box(s);
        black_box(rad_als_set_spectral_correction(&mut cal, black_box(1.08)));
        let s: RadStatus = rad_als_lux(&cal, black_box(3016), black_box(4.0), black_box(0.025), &mut lux);
        black_box((s, lux));
    }
    #[cfg(feature = "correction")]
    {
        use radiometry_ffi::spectrum::*;
        let curve = |kind| radiometry_ffi::RadSpectrum {
            kind,
            temperature_k: 0.0,
            start_nm: 0.0,
            step_nm: 0.0,
            values: core::ptr::null(),
            len: 0,
        };
        let (s, x, a) = (
            black_box(curve(RAD_SPECTRUM_PHOTOPIC_V)),
            black_box(curve(RAD_SPECTRUM_D65)),
            black_box(curve(RAD_SPECTRUM_A)),
        );
        let mut f = 0.0f32;
        // SAFETY: valid pointers to locals.
        black_box(unsafe { rad_spectral_correction(&s, &x, &a, &mut f) });
        black_box(f);
    }
}

#[cfg(feature = "brdf")]
fn brdf() {
    use radiometry_ffi::brdf::*;
    use radiometry_ffi::{RadBrdf, RadBrdfSample, RadVec3};
    let mut b = RadBrdf::default();
    let v = |x: f32, y: f32, z: f32| black_box(RadVec3 { x, y, z });
    let (wi, wo) = (v(0.1, 0.2, 0.9), v(-0.3, 0.1, 0.8));
    let mut f = [0.0f32; 4];
    let mut s = [RadBrdfSample::default(); 4];
    let (wis, wos, u) = (black_box([wi; 4]), black_box([wo; 4]), black_box([0.5f32; 8]));
    let n = black_box(4usize);
    // SAFETY: valid, aligned, exclusive pointers to locals; `n` is their length.
    unsafe {
        black_box(rad_brdf_lambertian(black_box(0.5), &mut b));
        black_box(rad_brdf_phong(
            black_box(10.0),
            black_box(0.5),
            black_box(0.5),
            &mut b,
        ));
        black_box(rad_brdf_blinn_phong(
            black_box(10.0),
            black_box(0.5),
            black_box(0.5),
            &mut b,
        ));
        black_box(rad_brdf_microfacet(
            black_box(0),
            black_box(0.3),
            black_box(0),
            black_box(3),
            black_box(0.2),
            black_box(3.9),
            &mut b,
        ));
        black_box(rad_brdf_eon(black_box(0.8), black_box(0.5), &mut b));
        black_box(rad_brdf_fon(black_box(0.8), black_box(0.5), &mut b));
        black_box(rad_brdf_oren_nayar(black_box(0.8), black_box(0.5), &mut b));
        black_box(rad_brdf_sheen(black_box(0.8), black_box(0.5), &mut b));
        let b = black_box(b);
        black_box(rad_brdf_eval(&b, wi, wo, &mut f[0]));
        black_box(rad_brdf_pdf(&b, wi, wo, &mut f[1]));
        black_box(rad_brdf_sample(&b, wo, black_box(0.3), black_box(0.7), &mut s[0]));
        black_box(rad_brdf_eval_batch(
            &b,
            wis.as_ptr(),
            wos.as_ptr(),
            f.as_mut_ptr(),
            n,
        ));
        black_box(rad_brdf_pdf_batch(
            &b,
            wis.as_ptr(),
            wos.as_ptr(),
            f.as_mut_ptr(),
            n,
        ));
        black_box(rad_brdf_sample_batch(
            &b,
            wos.as_ptr(),
            u.as_ptr(),
            s.as_mut_ptr(),
            n,
        ));
        let c = black_box([0.5f32; 4]);
        black_box(rad_brdf_eval_batch_soa(
            &b,
            c.as_ptr(),
            c.as_ptr(),
            c.as_ptr(),
            c.as_ptr(),
            c.as_ptr(),
            c.as_ptr(),
            f.as_mut_ptr(),
            n,
        ));
    }
    black_box((f, s));
}

#[cfg(feature = "material")]
fn material() {
    use radiometry_ffi::brdf::*;
    use radiometry_ffi::material::*;
    use radiometry_ffi::{RadBrdf, RadBrdfSample, RadMaterial, RadVec3};
    let (mut top, mut base) = (RadBrdf::default(), RadBrdf::default());
    let mut m = RadMaterial::default();
    let v = |x: f32, y: f32, z: f32| black_box(RadVec3 { x, y, z });
    let (wi, wo) = (v(0.1, 0.2, 0.9), v(-0.3, 0.1, 0.8));
    let mut f = [0.0f32; 4];
    let mut s = [RadBrdfSample::default(); 4];
    let (wis, wos, u) = (black_box([wi; 4]), black_box([wo; 4]), black_box([0.5f32; 8]));
    let n = black_box(4usize);
    // SAFETY: valid, aligned, exclusive pointers to locals; `n` is their length.
    unsafe {
        black_box(rad_brdf_microfacet(
            black_box(0),
            black_box(0.1),
            black_box(0),
            black_box(RAD_FRESNEL_METAL),
            black_box(1.0),
            black_box(0.0),
            &mut top,
        ));
        black_box(rad_brdf_microfacet(
            black_box(0),
            black_box(0.1),
            black_box(0),
            black_box(RAD_FRESNEL_F82),
            black_box(0.9),
            black_box(0.7),
            &mut top,
        ));
        black_box(rad_brdf_eon(black_box(0.8), black_box(0.5), &mut base));
        let (top, base) = (black_box(top), black_box(base));
        black_box(rad_material_brdf(&top, &mut m));
        black_box(rad_material_sum(&top, &base, &mut m));
        black_box(rad_material_mix(black_box(0.5), &top, &base, &mut m));
        black_box(rad_material_coated(
            &top,
            &base,
            black_box(1.0),
            black_box(1.5),
            &mut m,
        ));
        black_box(rad_material_coated_reciprocal(
            &top,
            &base,
            black_box(0.8),
            black_box(1.5),
            &mut m,
        ));
        let m = black_box(m);
        black_box(rad_material_eval(&m, wi, wo, &mut f[0]));
        black_box(rad_material_pdf(&m, wi, wo, &mut f[1]));
        black_box(rad_material_sample(
            &m,
            wo,
            black_box(0.3),
            black_box(0.7),
            &mut s[0],
        ));
        black_box(rad_material_eval_batch(
            &m,
            wis.as_ptr(),
            wos.as_ptr(),
            f.as_mut_ptr(),
            n,
        ));
        black_box(rad_material_pdf_batch(
            &m,
            wis.as_ptr(),
            wos.as_ptr(),
            f.as_mut_ptr(),
            n,
        ));
        black_box(rad_material_sample_batch(
            &m,
            wos.as_ptr(),
            u.as_ptr(),
            s.as_mut_ptr(),
            n,
        ));
        let c = black_box([0.5f32; 4]);
        black_box(rad_material_eval_batch_soa(
            &m,
            c.as_ptr(),
            c.as_ptr(),
            c.as_ptr(),
            c.as_ptr(),
            c.as_ptr(),
            c.as_ptr(),
            f.as_mut_ptr(),
            n,
        ));
    }
    black_box((f, s));
}

/// The C functions the other groups do not call: with `als`, `correction`, `brdf` and `material`, every exported function.
#[cfg(feature = "others")]
fn others() {
    use radiometry_ffi::als::*;
    use radiometry_ffi::irradiance::*;
    use radiometry_ffi::spectrum::*;
    use radiometry_ffi::{RadAlsCalibration, RadSpectrum, RadVec3, rad_status_message};
    let mut cal = RadAlsCalibration::default();
    let (mut f, mut n) = (0.0f32, 0u32);
    let values = black_box([0.1f32, 0.5, 0.9, 0.4]);
    let curve = |kind, values: &[f32]| RadSpectrum {
        kind,
        temperature_k: 5000.0,
        start_nm: 400.0,
        step_nm: 100.0,
        values: values.as_ptr(),
        len: values.len(),
    };
    let (tab, bb) = (
        black_box(curve(RAD_SPECTRUM_TABULATED, &values)),
        black_box(curve(RAD_SPECTRUM_BLACKBODY, &[])),
    );
    let axis = black_box(RadVec3 {
        x: 0.3,
        y: 0.0,
        z: 1.0,
    });
    // SAFETY: valid, aligned, exclusive pointers to locals; `values` outlives the spectra.
    unsafe {
        black_box(rad_als_new(
            black_box(16.0),
            black_box(0.04),
            black_box(1.0),
            black_box(65535),
            &mut cal,
        ));
        black_box(rad_source_lux(&bb, &mut f));
        black_box(rad_als_simulate_counts(
            &tab,
            &bb,
            black_box(1e3),
            black_box(1.0),
            black_box(0.1),
            black_box(16.0),
            black_box(65535),
            &mut n,
        ));
        black_box(rad_irradiance_sky(black_box(1e3), &mut f));
        black_box(rad_irradiance_directional(axis, black_box(10.0), &mut f));
        black_box(rad_irradiance_cap(
            axis,
            black_box(0.00465),
            black_box(2e7),
            &mut f,
        ));
    }
    black_box(rad_cap_solid_angle(black_box(0.3)));
    black_box(rad_status_message(black_box(3)));
    black_box((cal, f, n));
}

#[cfg(feature = "openpbr")]
fn openpbr() {
    use radiometry_ffi::openpbr::*;
    use radiometry_ffi::{RadBrdfSample, RadOpenPbr, RadOpenPbrParams, RadVec3};
    let mut p = RadOpenPbrParams::default();
    let mut m = RadOpenPbr::default();
    let v = |x: f32, y: f32, z: f32| black_box(RadVec3 { x, y, z });
    let (wi, wo) = (v(0.1, 0.2, 0.9), v(-0.3, 0.1, 0.8));
    let mut f = [0.0f32; 4];
    let mut s = [RadBrdfSample::default(); 4];
    let (wis, wos, u) = (black_box([wi; 4]), black_box([wo; 4]), black_box([0.5f32; 8]));
    let n = black_box(4usize);
    // SAFETY: valid, aligned, exclusive pointers to locals; `n` is their length.
    unsafe {
        black_box(rad_openpbr_default_params(&mut p));
        let p = black_box(p);
        black_box(rad_openpbr_new(&p, &mut m));
        let m = black_box(m);
        black_box(rad_openpbr_eval(&m, wi, wo, &mut f[0]));
        black_box(rad_openpbr_pdf(&m, wi, wo, &mut f[1]));
        black_box(rad_openpbr_sample(
            &m,
            wo,
            black_box(0.3),
            black_box(0.7),
            &mut s[0],
        ));
        black_box(rad_openpbr_eval_batch(
            &m,
            wis.as_ptr(),
            wos.as_ptr(),
            f.as_mut_ptr(),
            n,
        ));
        black_box(rad_openpbr_pdf_batch(
            &m,
            wis.as_ptr(),
            wos.as_ptr(),
            f.as_mut_ptr(),
            n,
        ));
        black_box(rad_openpbr_sample_batch(
            &m,
            wos.as_ptr(),
            u.as_ptr(),
            s.as_mut_ptr(),
            n,
        ));
        let c = black_box([0.5f32; 4]);
        black_box(rad_openpbr_eval_batch_soa(
            &m,
            c.as_ptr(),
            c.as_ptr(),
            c.as_ptr(),
            c.as_ptr(),
            c.as_ptr(),
            c.as_ptr(),
            f.as_mut_ptr(),
            n,
        ));
    }
    black_box((f, s));
}

/// The colour calls: the `_rgb` constructors and every `_rgb` call of plugins, materials and OpenPBR.
#[cfg(feature = "rgb")]
fn rgb() {
    use radiometry_ffi::brdf::*;
    use radiometry_ffi::material::*;
    use radiometry_ffi::openpbr::*;
    use radiometry_ffi::{RadBrdf, RadBrdfSample, RadMaterial, RadOpenPbr, RadOpenPbrParams, RadVec3};
    let (mut top, mut base) = (RadBrdf::default(), RadBrdf::default());
    let mut m = RadMaterial::default();
    let (mut p, mut o) = (RadOpenPbrParams::default(), RadOpenPbr::default());
    let v = |x: f32, y: f32, z: f32| black_box(RadVec3 { x, y, z });
    let (wi, wo) = (v(0.1, 0.2, 0.9), v(-0.3, 0.1, 0.8));
    let mut f = [0.0f32; 12];
    let mut s = [RadBrdfSample::default(); 4];
    let (wis, wos, u) = (black_box([wi; 4]), black_box([wo; 4]), black_box([0.5f32; 8]));
    let n = black_box(4usize);
    let c = black_box([0.8f32, 0.4, 0.1]);
    let d = black_box([0.5f32; 4]);
    // SAFETY: valid, aligned, exclusive pointers to locals; `n` is their length (3n floats for RGB values).
    unsafe {
        black_box(rad_brdf_lambertian_rgb(c.as_ptr(), &mut base));
        black_box(rad_brdf_fon_rgb(c.as_ptr(), black_box(0.5), &mut base));
        black_box(rad_brdf_oren_nayar_rgb(c.as_ptr(), black_box(0.5), &mut base));
        black_box(rad_brdf_sheen_rgb(c.as_ptr(), black_box(0.5), &mut base));
        black_box(rad_brdf_eon_rgb(c.as_ptr(), black_box(0.5), &mut base));
        black_box(rad_brdf_microfacet_rgb(
            black_box(0),
            black_box(0.1),
            black_box(0),
            black_box(RAD_FRESNEL_CONDUCTOR),
            c.as_ptr(),
            c.as_ptr(),
            &mut top,
        ));
        black_box(rad_brdf_microfacet(
            black_box(0),
            black_box(0.1),
            black_box(0),
            black_box(RAD_FRESNEL_METAL),
            black_box(1.0),
            black_box(0.0),
            &mut top,
        ));
        let (top, base) = (black_box(top), black_box(base));
        macro_rules! calls {
            ($h:expr, $e:ident, $p:ident, $s:ident, $eb:ident, $pb:ident, $sb:ident, $soa:ident) => {
                black_box($e($h, wi, wo, f.as_mut_ptr()));
                black_box($p($h, wi, wo, &mut f[3]));
                black_box($s($h, wo, black_box(0.3), black_box(0.7), &mut s[0]));
                black_box($eb($h, wis.as_ptr(), wos.as_ptr(), f.as_mut_ptr(), n));
                black_box($pb($h, wis.as_ptr(), wos.as_ptr(), f.as_mut_ptr(), n));
                black_box($sb($h, wos.as_ptr(), u.as_ptr(), s.as_mut_ptr(), n));
                let (r, rest) = f.split_at_mut(4);
                let (g, b) = rest.split_at_mut(4);
                black_box($soa(
                    $h,
                    d.as_ptr(),
                    d.as_ptr(),
                    d.as_ptr(),
                    d.as_ptr(),
                    d.as_ptr(),
                    d.as_ptr(),
                    r.as_mut_ptr(),
                    g.as_mut_ptr(),
                    b.as_mut_ptr(),
                    n,
                ));
            };
        }
        calls!(
            &top,
            rad_brdf_eval_rgb,
            rad_brdf_pdf_rgb,
            rad_brdf_sample_rgb,
            rad_brdf_eval_batch_rgb,
            rad_brdf_pdf_batch_rgb,
            rad_brdf_sample_batch_rgb,
            rad_brdf_eval_batch_soa_rgb
        );
        black_box(rad_material_coated(
            &top,
            &base,
            black_box(0.8),
            black_box(1.5),
            &mut m,
        ));
        let m = black_box(m);
        calls!(
            &m,
            rad_material_eval_rgb,
            rad_material_pdf_rgb,
            rad_material_sample_rgb,
            rad_material_eval_batch_rgb,
            rad_material_pdf_batch_rgb,
            rad_material_sample_batch_rgb,
            rad_material_eval_batch_soa_rgb
        );
        black_box(rad_openpbr_default_params(&mut p));
        black_box(rad_openpbr_new(&black_box(p), &mut o));
        let o = black_box(o);
        calls!(
            &o,
            rad_openpbr_eval_rgb,
            rad_openpbr_pdf_rgb,
            rad_openpbr_sample_rgb,
            rad_openpbr_eval_batch_rgb,
            rad_openpbr_pdf_batch_rgb,
            rad_openpbr_sample_batch_rgb,
            rad_openpbr_eval_batch_soa_rgb
        );
    }
    black_box((f, s));
}
