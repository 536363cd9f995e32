//! Measures the excess `E(μ, α) − E_tab(μ, α)` of the exact single-scattering albedo (`F = 1`, by
//! `Adaptive::new(0, 0).warped()` at 10⁵ evaluations) over what `KullaConty::albedo` treats as kept
//! (the interpolated table plus `LOSS_MARGIN`), for all four `(D, G)` variants on 40 roughnesses
//! (log-spaced in `[10⁻⁴, 1]`) × 60 + 9 grazing cosines (down to `μ = 10⁻⁸`). A negative maximum means
//! the compensated BRDF never reflects more than it receives: this is the evidence behind
//! `LOSS_MARGIN`. Prints the largest and smallest excess per variant.
//!
//! Run: `cargo run --release -p radiometry-brdfs --features examples --example kulla_conty_excess` (≈ 2 min per variant).
use radiometry::glam::Vec3;
use radiometry::integrator::{Adaptive, DirectionalAlbedo, Integrator};
use radiometry_brdfs::microfacet::*;

fn e<D: MicrofacetDistribution + Copy, G: ShadowingMasking>(d: D, mu: f32) -> f64 {
    let b = Microfacet::<D, G, NoFresnel>::new(d, NoFresnel);
    let s = (1.0 - mu * mu).max(0.0).sqrt();
    let a = Adaptive::new(0.0, 0.0).expect("valid").warped();
    a.integrate(
        &DirectionalAlbedo {
            brdf: b,
            wo: Vec3::new(s, 0.0, mu),
        },
        100_000,
    )
    .expect("finite")
    .value
}

fn scan<D: MicrofacetDistribution + EnergyTable<G> + Copy, G: ShadowingMasking>(
    name: &str,
    make: impl Fn(f32) -> D,
) {
    let mus: Vec<f32> = (0..60)
        .map(|i| ((i as f32 + 0.37) / 60.0).powi(2))
        .chain([1e-8, 1e-7, 1e-6, 3e-6, 1e-5, 2e-5, 8e-5, 1.2e-4, 1.8e-4])
        .collect();
    let (mut hi, mut lo) = ((f64::MIN, 0.0, 0.0), (f64::MAX, 0.0, 0.0));
    for ai in 0..40 {
        let alpha = (1e-4f32 * 10f32.powf(4.0 * ai as f32 / 39.0)).min(1.0);
        let b = KullaConty::<D, G, NoFresnel>::new(make(alpha), NoFresnel);
        for &mu in &mus {
            let x = e::<D, G>(make(alpha), mu) - b.albedo(mu) as f64;
            if x > hi.0 {
                hi = (x, alpha, mu);
            }
            if x < lo.0 {
                lo = (x, alpha, mu);
            }
        }
    }
    println!(
        "{name}: largest excess {:.2e} (α = {}, μ = {:e}); smallest {:.2e} (α = {}, μ = {:e})",
        hi.0, hi.1, hi.2, lo.0, lo.1, lo.2
    );
}

fn main() {
    let ggx = |a: f32| Ggx::new(a).expect("alpha in range");
    let beck = |a: f32| Beckmann::new(a).expect("alpha in range");
    scan::<_, HeightCorrelated>("GGX, height-correlated", ggx);
    scan::<_, Separable>("GGX, separable", ggx);
    scan::<_, HeightCorrelated>("Beckmann, height-correlated", beck);
    scan::<_, Separable>("Beckmann, separable", beck);
}
