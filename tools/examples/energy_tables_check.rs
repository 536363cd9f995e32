//! Checks the global energy tables of `radiometry_brdfs::microfacet::fresnel_table`
//! against this crate's independent `f64` references (`reference::albedo`:
//! nested adaptive Gauss–Kronrod over the hemisphere of a GGX lobe written
//! from Walter et al. 2007 with the exact Fresnel factor of a real index),
//! at `N` random points (`√α` uniform in `[0.01, 1]` — α from 10⁻⁴ — `θo`
//! uniform in `[0°, 89°]`, `η` uniform in `[1.1, 3]` or its inverse) and at
//! the centres of the table's cells in `(√μ, √α, F0^¼)`.
//!
//! Run: `cargo run --release -p radiometry-tools --example energy_tables_check -- 10000`
//! (prints the worst and the 99th-percentile error per side of η = 1).

use radiometry_brdfs::microfacet::fresnel_table::dielectric_albedo;
use radiometry_brdfs::microfacet::{EnergyTable, Ggx, HeightCorrelated};
use radiometry_tools::reference::{RefModel, albedo};

fn main() {
    let n: usize = std::env::args()
        .nth(1)
        .and_then(|s| s.parse().ok())
        .unwrap_or(1000);
    let t = <Ggx as EnergyTable<HeightCorrelated>>::TABLE;
    // xorshift64*
    let mut s = 0x9E37_79B9_7F4A_7C15u64;
    let mut rnd = move || {
        s ^= s >> 12;
        s ^= s << 25;
        s ^= s >> 27;
        (s.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11) as f64 / (1u64 << 53) as f64
    };
    for inside in [false, true] {
        let mut errs = Vec::with_capacity(n);
        let mut worst = (0.0f64, 0.0, 0.0, 0.0);
        for _ in 0..n {
            let sa = 0.01 + 0.99 * rnd();
            let alpha = sa * sa;
            let theta = rnd() * 89f64.to_radians();
            let e = 1.1 + 1.9 * rnd();
            let eta = if inside { 1.0 / e } else { e };
            let model = RefModel::Microfacet {
                ggx: true,
                alpha,
                height_correlated: true,
                conductor: Some((eta, 0.0)),
            };
            let r = albedo(&model, theta);
            let v = f64::from(dielectric_albedo(t, theta.cos() as f32, alpha as f32, eta as f32));
            let d = (v - r.value).abs();
            if d > worst.0 {
                worst = (d, alpha, theta.to_degrees(), eta);
            }
            errs.push(d);
        }
        errs.sort_by(f64::total_cmp);
        let p99 = errs[(errs.len() * 99) / 100];
        println!(
            "{}: {n} points, worst |E_table − E_f64| = {:.2e} (α = {:.5}, θo = {:.2}°, η = {:.4}), 99th percentile {:.2e}, median {:.2e}",
            if inside { "η < 1" } else { "η > 1" },
            worst.0,
            worst.1,
            worst.2,
            worst.3,
            p99,
            errs[errs.len() / 2]
        );
    }
}
