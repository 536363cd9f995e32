//! Integrators on a directional-albedo integrand with any finite parameters
//! and budgets up to 4096: a result (value and error) is finite and non-negative, or a typed
//! error; never a panic.
#![no_main]
mod common;
use common::Floats;
use libfuzzer_sys::fuzz_target;
use radiometry::Integrator;
use radiometry::integrator::{
    Adaptive, DirectionalAlbedo, GaussLegendre, MonteCarlo, PointSet, Strategy, WarpedGaussLegendre,
};
use radiometry_brdfs::*;

fn run<I: Integrator>(i: &I, g: &impl radiometry::Integrand<Spectrum = f32>, budget: u32) {
    if let Ok(e) = i.integrate(g, budget) {
        assert!(
            e.value.is_finite() && e.value >= 0.0 && e.error.is_finite() && e.error >= 0.0,
            "{e:?}"
        );
    }
}

fuzz_target!(|data: &[u8]| {
    let mut f = Floats(data);
    let which = f.byte();
    let budget = (f.byte() as u32) << (f.byte() % 5);
    let Ok(d) = Ggx::new(f.f32()) else { return };
    let g = DirectionalAlbedo {
        brdf: Microfacet::<_, HeightCorrelated, _>::new(d, NoFresnel),
        wo: f.vec3(),
    };
    match which % 5 {
        0 => run(&GaussLegendre::new(), &g, budget),
        1 => run(&WarpedGaussLegendre::new(), &g, budget),
        2 => {
            if let Ok(a) = Adaptive::new(1e-5, 0.0) {
                run(&a.warped(), &g, budget)
            }
        }
        3 => run(
            &MonteCarlo::new(Strategy::Integrand, PointSet::Sobol, f.byte() as u64),
            &g,
            budget,
        ),
        _ => run(
            &MonteCarlo::new(
                Strategy::Mis(radiometry::integrator::Heuristic::Power),
                PointSet::Prng,
                3,
            ),
            &g,
            budget,
        ),
    }
});
