//! The footprint and soft-float images (`size.sh`): a bare cortex-m-rt image that calls a group of functions
//! with opaque arguments, chosen by features; without any feature it is the empty baseline.
//!
//! * `als`: counts → lux with calibration (`from_reference`, `with_spectral_correction`, `lux`);
//! * `ggx`: GGX (height-correlated Smith, no Fresnel) `eval`, `sample`, `pdf`;
//! * `f32-paths`: the `f32` paths that must not link a soft-float `f64` helper (CI fails on any): the ALS path,
//!   `eval`/`sample`/`pdf` of Lambertian, the Phong family and GGX microfacets (every Fresnel and Smith
//!   variant), `spherical_direction`, the closed-form irradiances of directional, sky and cap lights (an
//!   unclipped cap);
//! * `f64-known`: with `f32-paths`, the paths that still link `f64` helpers (listed in docs/firmware.md):
//!   Beckmann, Kulla–Conty, tabulated data, a horizon-clipped cap's projected solid angle.
//!
//! On the host the binary does nothing (it exists so that the firmware workspace builds natively too).
#![cfg_attr(target_os = "none", no_std, no_main)]

#[cfg(not(target_os = "none"))]
fn main() {}

#[cfg(target_os = "none")]
mod image {
    #[allow(unused_imports)]
    use core::hint::black_box;
    #[allow(unused_imports)]
    use radiometry::{Brdf, Spectrum, glam::Vec3};

    #[cortex_m_rt::entry]
    fn main() -> ! {
        #[cfg(any(feature = "als", feature = "f32-paths"))]
        als();
        #[cfg(any(feature = "ggx", feature = "f32-paths"))]
        {
            use radiometry_brdfs::{Ggx, HeightCorrelated, Microfacet, NoFresnel};
            if let Ok(d) = Ggx::new(black_box(0.3)) {
                exercise(&Microfacet::<_, HeightCorrelated, _>::new(d, NoFresnel));
            }
        }
        #[cfg(feature = "f32-paths")]
        f32_paths();
        loop {
            core::hint::spin_loop();
        }
    }

    #[panic_handler]
    fn panic(_: &core::panic::PanicInfo) -> ! {
        loop {
            core::hint::spin_loop();
        }
    }

    #[cfg(any(feature = "als", feature = "f32-paths"))]
    fn als() {
        use radiometry::sensor::als::AlsCalibration;
        if let Ok(c) = AlsCalibration::from_reference(
            black_box(16.0),
            black_box(12_016.0),
            black_box(1.0),
            black_box(0.1),
            black_box(500.0),
            black_box(65_535),
        ) && let Ok(c) = c.with_spectral_correction(black_box(1.08))
        {
            black_box(c.lux(black_box(3016), black_box(4.0), black_box(0.025)).ok());
        }
    }

    #[allow(dead_code)]
    fn exercise<B: Brdf>(b: &B) {
        let wo = black_box(Vec3::new(0.3, 0.1, 0.9));
        let wi = black_box(Vec3::new(-0.2, 0.4, 0.8));
        black_box(b.eval(wi, wo).average());
        black_box(b.pdf(wi, wo));
        black_box(
            b.sample(wo, black_box([0.25, 0.75]))
                .map(|s| (s.wi, s.pdf, s.weight.average())),
        );
    }

    #[cfg(feature = "f32-paths")]
    fn f32_paths() {
        use radiometry::light::{Cap, Directional, Light, UniformSky};
        #[cfg(feature = "f64-known")]
        use radiometry::radiometric::cap_projected_solid_angle;
        use radiometry::radiometric::{cap_irradiance, cap_solid_angle};
        use radiometry_brdfs::*;
        black_box(radiometry::frame::spherical_direction(
            black_box(0.5),
            black_box(2.0),
        ));
        black_box(cap_solid_angle(black_box(0.3)));
        #[cfg(feature = "f64-known")]
        black_box(cap_projected_solid_angle(black_box(0.2), black_box(0.4)));
        black_box(cap_irradiance(
            black_box(2.0e7f32),
            black_box(0.9),
            black_box(0.00465),
        ));
        if let (Ok(a), Ok(b), Ok(c)) = (
            Cap::new(black_box(Vec3::new(0.3, 0.0, 1.0)), black_box(0.00465), 2.0e7f32),
            UniformSky::new(black_box(1.0e3f32)),
            Directional::new(black_box(Vec3::new(0.0, 0.6, 0.8)), black_box(10.0f32)),
        ) {
            black_box((a, b, c).closed_form_irradiance());
        }
        if let Ok(b) = Lambertian::new(black_box(0.5f32)) {
            exercise(&b);
        }
        if let Ok(b) = ModifiedPhong::new(black_box(0.2f32), 0.7, 100.0) {
            exercise(&b);
        }
        if let Ok(b) = BlinnPhong::new(black_box(0.2f32), 0.7, 100.0) {
            exercise(&b);
        }
        if let Ok(d) = Ggx::new(black_box(0.3)) {
            if let Ok(f) = Conductor::new(0.2f32, 3.9) {
                exercise(&Microfacet::<_, Separable, _>::new(d, f));
                #[cfg(feature = "f64-known")]
                exercise(&KullaConty::<_, Separable, _>::new(d, f));
            }
            if let Ok(f) = Dielectric::new(1.5) {
                exercise(&Microfacet::<_, HeightCorrelated, _>::new(d, f));
            }
            #[cfg(feature = "f64-known")]
            exercise(&KullaConty::<_, HeightCorrelated, _>::new(d, NoFresnel));
        }
        #[cfg(feature = "f64-known")]
        if let Ok(d) = Beckmann::new(black_box(0.3)) {
            if let Ok(f) = Schlick::new(0.04f32) {
                exercise(&Microfacet::<_, HeightCorrelated, _>::new(d, f));
                exercise(&Microfacet::<_, Separable, _>::new(d, f));
                #[cfg(feature = "f64-known")]
                exercise(&KullaConty::<_, Separable, _>::new(d, f));
            }
            exercise(&KullaConty::<_, HeightCorrelated, _>::new(d, NoFresnel));
        }
        #[cfg(feature = "f64-known")]
        tabulated();
    }

    /// Measured data (libm `sincosf`/`sinf` in the Rusinkiewicz grid and the sampling guide: `f64` kernels).
    #[cfg(feature = "f64-known")]
    fn tabulated() {
        use radiometry_brdfs::tabulated::{RusinkiewiczGrid, Tabulated};
        let values = black_box([0.3f32; 4 * 4 * 4]);
        let mut buf = [0.0f32; 33];
        if let Ok(g) = RusinkiewiczGrid::new(black_box(4), 4, 4)
            && let Ok(t) = Tabulated::new(g, &values[..])
        {
            exercise(&t);
            if let Ok(t) = t.with_sampling(&mut buf[..]) {
                exercise(&t);
            }
        }
    }
}
