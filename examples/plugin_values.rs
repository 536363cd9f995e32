//! Prints, for every BRDF plugin, a few values of `f_r` and the directional
//! albedo `ρ(θo)` at several viewing angles.
//!
//! `cargo run --release --features examples --example plugin_values`

use radiometry::frame::spherical_direction;
use radiometry::integrator::{Adaptive, DirectionalAlbedo, Integrator};
use radiometry::{Brdf, Spectrum, WideSpectrum};
use radiometry_brdfs::{
    Beckmann, BlinnPhong, Conductor, Ggx, HeightCorrelated, Lambertian, Microfacet, ModifiedPhong, NoFresnel,
    Separable,
};

fn show<B: Brdf>(name: &str, brdf: B)
where
    B::Spectrum: Spectrum,
{
    let deg = core::f32::consts::PI / 180.0;
    let wo = spherical_direction(30.0 * deg, 0.0);
    let mirror = spherical_direction(30.0 * deg, core::f32::consts::PI);
    let side = spherical_direction(45.0 * deg, 0.5 * core::f32::consts::PI);
    print!(
        "{name:<34} f(mirror)={:>11.4e}  f(side)={:>10.4e}  ρ(θo):",
        brdf.eval(mirror, wo).average(),
        brdf.eval(side, wo).average()
    );
    let integrator = Adaptive::new(1e-7, 0.0).expect("valid tolerances").warped();
    for theta_o in [0.0f32, 30.0, 60.0, 85.0] {
        let g = DirectionalAlbedo {
            brdf: &brdf,
            wo: spherical_direction(theta_o * deg, 0.0),
        };
        match integrator.integrate(&g, 1 << 16) {
            Ok(e) => print!("  {theta_o:>2}°: {:.6}", e.value.max_channel()),
            Err(err) => print!("  {theta_o:>2}°: error ({err})"),
        }
    }
    println!();
}

fn main() -> Result<(), radiometry_brdfs::BrdfError> {
    show("lambertian(albedo=0.5)", Lambertian::new(0.5f32)?);
    show(
        "phong(kd=0, ks=1, n=100)",
        ModifiedPhong::new(0.0f32, 1.0, 100.0)?,
    );
    show(
        "blinn-phong(kd=0.2, ks=0.8, n=50)",
        BlinnPhong::new(0.2f32, 0.8, 50.0)?,
    );
    show(
        "ggx(α=0.3, height-correlated)",
        Microfacet::<_, HeightCorrelated, _>::new(Ggx::new(0.3)?, NoFresnel),
    );
    show(
        "ggx(α=0.3, separable)",
        Microfacet::<_, Separable, _>::new(Ggx::new(0.3)?, NoFresnel),
    );
    show(
        "beckmann(α=0.3, height-correlated)",
        Microfacet::<_, HeightCorrelated, _>::new(Beckmann::new(0.3)?, NoFresnel),
    );
    show(
        "ggx(α=0.1, gold conductor)",
        Microfacet::<_, HeightCorrelated, _>::new(Ggx::new(0.1)?, Conductor::new(0.2f32, 3.9)?),
    );
    Ok(())
}
