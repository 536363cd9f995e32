//! Generator of `brdfs/src/microfacet/fresnel_table_data.rs`: the global
//! energy tables of GGX (height-correlated Smith `G2`) with a Fresnel term,
//! from `f64` quadrature written here.
//!
//! # What is tabulated
//!
//! With `E₁(μ, α)` the albedo with `F = 1` (the Kulla–Conty table the crate
//! already ships) and the single-scattering albedo with a Fresnel factor
//!
//! ```text
//! E_F(μo, α) = ∫_H F(ωo·h) D(h) G2(ωi, ωo) / (4 μo) dωi
//!            = ∫∫_[0,1]² F(ωo·m(u)) G2(ωi(u), ωo) / G1(ωo) du      (VNDF map m(u), Heitz 2018)
//! ```
//!
//! the tables hold ratios `E_F / E₁` (an average of `F` over the lobe, in
//! `[0, 1]`, free of the grazing dip of `E₁`):
//!
//! * `DIELECTRIC_OUT[z][a][x]`: exact unpolarised dielectric Fresnel, `η > 1`
//!   (light arriving from the rarer side), `x = √μ`;
//! * `DIELECTRIC_IN[z][a][x]`: the same for `η < 1` (total internal reflection
//!   beyond the critical cosine `μc = √(1 − η²)`), with `x` split at `μc`:
//!   `x = ½ − ½√((μc − μ)/μc)` below, `x = ½ + ½√((μ − μc)/(1 − μc))` above
//!   (the Fresnel factor is linear in `√(μ − μc)` there);
//! * the averages `Ē(α, η) = 2∫₀¹ E_F(μ) μ dμ` of both (not ratios);
//! * the metal moments `M5 / E₁` and `M6 / E₁` with `F = (1 − c)⁵` and
//!   `F = c(1 − c)⁶`, `c = ωo·m`: every Fresnel term linear in these
//!   (Schlick, F82-tint) has an exact albedo per channel from them.
//!
//! Nodes: `x_j = j/32` (`j = 0..33`), `√α_k = 0.01 + 0.99 k/31` (`k = 0..32`),
//! `z_l = l/31` with `z = F0^¼`, `F0 = ((η − 1)/(η + 1))²` (`l = 0..32`).
//!
//! # Error
//!
//! Each entry is a product Gauss–Legendre rule (8 nodes per panel) on the
//! unit square of the VNDF map, computed with two panel counts (`η > 1` and
//! the moments: 16 × 16 and 32 × 32 panels; `η < 1`: 8 × 8 and 16 × 16); the
//! finer value is written and the largest difference of the two is stated in
//! the header.
//!
//! Run: `cargo run --release -p radiometry-tools --example energy_tables > brdfs/src/microfacet/fresnel_table_data.rs`

use radiometry_tools::energy_tables::*;

fn print_u16(name: &str, doc: &str, vals: &[f64]) {
    println!("{doc}");
    println!("pub(crate) static {name}: [u16; {}] = [", vals.len());
    for chunk in vals.chunks(16) {
        let s: Vec<String> = chunk
            .iter()
            .map(|v| format!("{}", (v.clamp(0.0, 1.0) * 65535.0).round() as u32))
            .collect();
        println!("    {},", s.join(", "));
    }
    println!("];");
}

fn print_f32(name: &str, doc: &str, vals: &[f64]) {
    println!("{doc}");
    println!("pub(crate) static {name}: [f32; {}] = [", vals.len());
    for chunk in vals.chunks(8) {
        let s: Vec<String> = chunk.iter().map(|v| format!("{v:.8}")).collect();
        println!("    {},", s.join(", "));
    }
    println!("];");
}

fn main() {
    let quick = std::env::args().any(|a| a == "--quick");
    let (pc, pf) = if quick { (4, 8) } else { (16, 32) };
    // Inside (η < 1): the finer rule of the pair.
    let pi = if quick { 8 } else { 32 };
    let mut worst_out = (0.0f64, String::new());
    let mut worst_in = (0.0f64, String::new());
    let mut out = vec![0.0; NZ * NA * NX];
    let mut inn = vec![0.0; NZ * NA * NX];
    let mut avg_out = vec![0.0; NZ * NA];
    let mut avg_in = vec![0.0; NZ * NA];
    let mut m5 = vec![0.0; NA * NX];
    let mut m6 = vec![0.0; NA * NX];
    let mut worst_m = 0.0f64;
    // Rows of α in parallel (two threads), each returning its slices.
    type Row = (
        Vec<f64>,
        Vec<f64>,
        Vec<f64>,
        Vec<f64>,
        Vec<f64>,
        Vec<f64>,
        (f64, String),
        (f64, String),
        f64,
    );
    let row = |k: usize| -> Row {
        let alpha = alpha_node(k);
        let mut out = vec![0.0; NZ * NX];
        let mut inn = vec![0.0; NZ * NX];
        let mut avg_out = vec![0.0; NZ];
        let mut avg_in = vec![0.0; NZ];
        let mut m5 = vec![0.0; NX];
        let mut m6 = vec![0.0; NX];
        let mut worst_out = (0.0f64, String::new());
        let mut worst_in = (0.0f64, String::new());
        let mut worst_m = 0.0f64;
        for j in 0..NX {
            let x = j as f64 / (NX - 1) as f64;
            let mu = (x * x).max(MU_FLOOR);
            let mom = |c: f64| {
                let q = 1.0 - c;
                let q5 = q * q * q * q * q;
                [q5, c * q5 * q, 1.0]
            };
            let f = integrate(alpha, mu, pf, mom);
            let c = integrate(alpha, mu, pc, mom);
            let r = |v: [f64; 3]| (v[0] / v[2], v[1] / v[2]);
            let (a5, a6) = r(f);
            let (b5, b6) = r(c);
            worst_m = worst_m.max((a5 - b5).abs()).max((a6 - b6).abs());
            m5[j] = a5;
            m6[j] = a6;
        }
        // Outside: the nodes of each μ serve every index.
        for j in 0..NX {
            let x = j as f64 / (NX - 1) as f64;
            let mu = (x * x).max(MU_FLOOR);
            let nf = nodes(alpha, mu, pf);
            let nc = nodes(alpha, mu, pc);
            for l in 0..NZ {
                let eo = eta_out(z_node(l));
                let f = ratio(pair_nodes(&nf, eo));
                let c = ratio(pair_nodes(&nc, eo));
                if (f - c).abs() > worst_out.0 {
                    worst_out = ((f - c).abs(), format!("α = {alpha:.6}, η = {eo:.6}, μ = {mu:.6}"));
                }
                out[l * NX + j] = f;
            }
        }
        let panels = if quick { 2 } else { 4 };
        let (gx, gw) = gl8();
        let mut avg_nodes = Vec::new();
        for p in 0..panels {
            for i in 0..8 {
                let mu = (p as f64 + gx[i]) / panels as f64;
                avg_nodes.push((mu, gw[i] / panels as f64, nodes(alpha, mu.max(MU_FLOOR), pi)));
            }
        }
        for l in 0..NZ {
            let eo = eta_out(z_node(l));
            avg_out[l] = avg_nodes
                .iter()
                .map(|(mu, w, n)| w * 2.0 * mu * pair_nodes(n, eo)[0])
                .sum();
        }
        // Inside: μ nodes depend on the index through μc.
        for l in 0..NZ {
            let ei = 1.0 / eta_out(z_node(l));
            let mc = (1.0 - ei * ei).max(0.0).sqrt();
            for j in 0..NX {
                let x = j as f64 / (NX - 1) as f64;
                let mu = mu_in(x, mc).max(MU_FLOOR);
                let f = ratio(pair_nodes(&nodes(alpha, mu, pi), ei));
                let c = ratio(pair_nodes(&nodes(alpha, mu, pi / 2), ei));
                if (f - c).abs() > worst_in.0 {
                    worst_in = ((f - c).abs(), format!("α = {alpha:.6}, η = {ei:.6}, μ = {mu:.6}"));
                }
                inn[l * NX + j] = f;
            }
            let mut lower = |t: f64| {
                let mu = mc * (1.0 - t * t);
                2.0 * mu * pair_nodes(&nodes(alpha, mu.max(MU_FLOOR), pi / 2), ei)[0] * 2.0 * t * mc
            };
            let mut upper = |t: f64| {
                let mu = mc + (1.0 - mc) * t * t;
                2.0 * mu * pair_nodes(&nodes(alpha, mu.max(MU_FLOOR), pi / 2), ei)[0] * 2.0 * t * (1.0 - mc)
            };
            avg_in[l] = gl_interval(0.0, 1.0, panels, &mut lower) + gl_interval(0.0, 1.0, panels, &mut upper);
        }
        eprintln!("row {k} of {NA} (α = {alpha:.5})");
        (out, inn, avg_out, avg_in, m5, m6, worst_out, worst_in, worst_m)
    };
    let rows: Vec<Row> = std::thread::scope(|s| {
        let even = s.spawn(|| (0..NA).step_by(2).map(row).collect::<Vec<_>>());
        let odd: Vec<Row> = (1..NA).step_by(2).map(row).collect();
        let even = even.join().expect("worker thread");
        let mut all = Vec::new();
        for (e, o) in even.into_iter().zip(odd) {
            all.push(e);
            all.push(o);
        }
        all
    });
    for (k, r) in rows.into_iter().enumerate() {
        let (o, i, ao, ai, a5, a6, wo, wi, wm) = r;
        for l in 0..NZ {
            for j in 0..NX {
                out[(l * NA + k) * NX + j] = o[l * NX + j];
                inn[(l * NA + k) * NX + j] = i[l * NX + j];
            }
            avg_out[l * NA + k] = ao[l];
            avg_in[l * NA + k] = ai[l];
        }
        for j in 0..NX {
            m5[k * NX + j] = a5[j];
            m6[k * NX + j] = a6[j];
        }
        if wo.0 > worst_out.0 {
            worst_out = wo;
        }
        if wi.0 > worst_in.0 {
            worst_in = wi;
        }
        worst_m = worst_m.max(wm);
    }
    println!(
        "//! Generated by `cargo run --release -p radiometry-tools --example energy_tables{}` (do not edit):",
        if quick { " -- --quick" } else { "" }
    );
    println!("//! the Fresnel-weighted albedo ratios of GGX (height-correlated G2), their averages and the");
    println!(
        "//! metal moments, on the grids of `fresnel_table.rs`. Each entry: product Gauss–Legendre on the"
    );
    println!(
        "//! VNDF square with {pf} × {pf} panels of 8 × 8 nodes ({pi} × {pi} for η < 1); largest difference"
    );
    println!("//! to half as many panels per side:");
    println!(
        "//! outside {:.1e} ({}), inside {:.1e} ({}), moments {:.1e}.",
        worst_out.0, worst_out.1, worst_in.0, worst_in.1, worst_m
    );
    println!("#![allow(clippy::excessive_precision, clippy::unreadable_literal)]");
    println!();
    print_u16(
        "DIELECTRIC_OUT",
        "/// `E_F/E₁` for `η > 1`, `[z][α][x]`, `x = √μ`, as `u16` of `65535 ×` the ratio.",
        &out,
    );
    print_u16(
        "DIELECTRIC_IN",
        "/// `E_F/E₁` for `η < 1`, `[z][α][x]`, `x` split at the critical cosine, as `u16`.",
        &inn,
    );
    print_f32(
        "AVERAGE_OUT",
        "/// `Ē = 2∫E_F μ dμ` for `η > 1`, `[z][α]`.",
        &avg_out,
    );
    print_f32(
        "AVERAGE_IN",
        "/// `Ē = 2∫E_F μ dμ` for `η < 1`, `[z][α]`.",
        &avg_in,
    );
    print_f32(
        "MOMENT5",
        "/// `M5/E₁` (`F = (1 − c)⁵`), `[α][x]`, `x = √μ`.",
        &m5,
    );
    print_f32(
        "MOMENT6",
        "/// `M6/E₁` (`F = c (1 − c)⁶`), `[α][x]`, `x = √μ`.",
        &m6,
    );
}
