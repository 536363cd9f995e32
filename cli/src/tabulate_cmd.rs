//! `radiometry tabulate SPEC --out FILE`: writes a MERL `.binary` file of an
//! analytic BRDF (optionally plus a Lambertian base), so that users can make
//! test files for `tabulated(file=…)`, `radiometry fit` and other MERL tools
//! (no measured data can be downloaded on the development machines).

use crate::model;
use crate::spec;
use radiometry::Brdf;
use radiometry::glam::Vec3;
use radiometry_brdfs::tabulated::RusinkiewiczGrid;
use radiometry_cli::merl;
use std::path::PathBuf;
use std::process::ExitCode;

/// Arguments of `radiometry tabulate`.
#[derive(clap::Args, Debug)]
pub struct TabulateArgs {
    /// BRDF spec to tabulate, e.g. `ggx(alpha=0.3)`, in RGB: a colour spec (an rgb() colour, a named metal)
    /// writes its channels, a grey spec the same values to all three.
    spec: String,
    /// Output file (MERL `.binary`: three i32 dims, then f64 red, green, blue blocks divided by the MERL
    /// scales 1/1500, 1.15/1500, 1.66/1500).
    #[arg(long)]
    out: PathBuf,
    /// Add a Lambertian base `ρ/π`: one albedo for all channels or `R,G,B` (each in [0, 1]).
    #[arg(long, value_delimiter = ',')]
    diffuse: Vec<f32>,
    /// Grid resolution `n_theta_h,n_theta_d,n_phi_d` (default: the MERL grid 90,90,180).
    #[arg(long, value_delimiter = ',', default_values_t = [90usize, 90, 180])]
    grid: Vec<usize>,
}

/// The spec's RGB BRDF plus `ρ/π`.
struct WithDiffuse<B> {
    brdf: B,
    rho_over_pi: Vec3,
}

impl<B: Brdf<Spectrum = Vec3>> Brdf for WithDiffuse<B> {
    type Spectrum = Vec3;
    fn eval(&self, wi: Vec3, wo: Vec3) -> Vec3 {
        let above = wi.z > 0.0 && wo.z > 0.0;
        self.brdf.eval(wi, wo) + if above { self.rho_over_pi } else { Vec3::ZERO }
    }
}

/// Runs `radiometry tabulate`.
pub fn run(a: TabulateArgs) -> ExitCode {
    let parsed = match spec::parse_brdf(&a.spec) {
        Ok(p) => p,
        Err(e) => return crate::spec_error(e),
    };
    // RGB: a grey spec's channels are its monochrome values, bit for bit.
    let brdf = match model::build_brdf_rgb(&a.spec, &parsed) {
        Ok(b) => b,
        Err(e) => return crate::spec_error(e),
    };
    let rho = match a.diffuse[..] {
        [] => Vec3::ZERO,
        [r] => Vec3::splat(r),
        [r, g, b] => Vec3::new(r, g, b),
        _ => return crate::usage_error("--diffuse takes one albedo or three (R,G,B)"),
    };
    if !(rho.is_finite() && rho.min_element() >= 0.0 && rho.max_element() <= 1.0) {
        return crate::usage_error(&format!("--diffuse {rho} must be in [0, 1]"));
    }
    let grid = match a.grid[..] {
        [h, d, p] => match RusinkiewiczGrid::new(h, d, p) {
            Ok(g) => g,
            Err(e) => return crate::usage_error(&format!("--grid: {e}")),
        },
        _ => return crate::usage_error("--grid takes three sizes: n_theta_h,n_theta_d,n_phi_d"),
    };
    let b = WithDiffuse {
        brdf,
        rho_over_pi: rho / std::f32::consts::PI,
    };
    let table = match merl::tabulate(&b, grid) {
        Ok(t) => t,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::from(1);
        }
    };
    if let Err(e) = merl::write(&a.out, &table) {
        eprintln!("error: {e}");
        return ExitCode::from(1);
    }
    let [h, d, p] = grid.dims();
    println!(
        "wrote {} ({h} x {d} x {p} nodes, {} bytes): {} + lambertian {rho}",
        a.out.display(),
        merl::HEADER_BYTES + 24 * grid.len(),
        a.spec
    );
    ExitCode::SUCCESS
}
