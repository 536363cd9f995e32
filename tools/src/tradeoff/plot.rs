//! Log-log SVG plots of the tradeoff report (plotters, SVG backend only).

use super::{Report, SuiteKind};
use plotters::prelude::*;
use std::path::Path;

/// Relative errors below this (including exact zeros) are drawn at it.
pub const ERROR_FLOOR: f64 = 1e-16;

/// Integrators drawn (all are in the CSV): every deterministic rule, each
/// Monte Carlo strategy with Sobol points, and plain PRNG cosine / integrand
/// sampling.
const SHOWN: [&str; 18] = [
    "gauss-legendre",
    "gauss-legendre-warped",
    "gauss-legendre-warped-split",
    "adaptive",
    "adaptive-warped",
    "mc-uniform-sobol",
    "mc-cosine-sobol",
    "mc-integrand-sobol",
    "mis-balance-sobol",
    "mis-power-sobol",
    "mc-cosine-prng",
    "mc-integrand-prng",
    // Product integrals (a lobe under a cap light).
    "cap-gauss-legendre",
    "cap-adaptive",
    "light-sampling-sobol",
    "brdf-sampling-sobol",
    "mis-light-brdf-sobol",
    "mis-light-brdf-prng",
];

struct Series {
    name: &'static str,
    /// (evaluations, seconds, worst relative error)
    points: Vec<(f64, f64, f64)>,
}

fn series(rep: &Report<'_>, cases: &[usize]) -> Vec<Series> {
    let mut out = Vec::new();
    for (ii, integ) in rep.integs.iter().enumerate() {
        let Some(&name) = SHOWN.iter().find(|&&n| n == integ.name()) else {
            continue;
        };
        let mut points = Vec::new();
        for &b in rep.budgets {
            let rows: Vec<_> = rep
                .rows
                .iter()
                .filter(|r| r.integ == ii && r.budget == b && cases.contains(&r.case))
                .collect();
            if rows.len() != cases.len() || rows.is_empty() {
                continue;
            }
            let ev = rows.iter().map(|r| r.evaluations as f64).fold(0.0, f64::max);
            let s = rows.iter().map(|r| r.seconds).fold(0.0, f64::max).max(1e-9);
            let e = rows
                .iter()
                .map(|r| rep.rel_error(r))
                .fold(0.0, f64::max)
                .max(ERROR_FLOOR);
            points.push((ev.max(1.0), s, e));
        }
        if !points.is_empty() {
            out.push(Series { name, points });
        }
    }
    out
}

fn draw(path: &Path, title: &str, x_label: &str, data: &[Series], use_time: bool) -> Result<(), String> {
    let xs = |p: &(f64, f64, f64)| if use_time { p.1 } else { p.0 };
    let (mut x0, mut x1, mut y0) = (f64::MAX, f64::MIN_POSITIVE, 1.0f64);
    let mut y1 = 1e-2f64;
    for s in data {
        for p in &s.points {
            x0 = x0.min(xs(p));
            x1 = x1.max(xs(p));
            y0 = y0.min(p.2);
            y1 = y1.max(p.2);
        }
    }
    if x0 > x1 {
        x0 = 1.0;
        x1 = 10.0;
    }
    let err = |e: &dyn std::fmt::Display| format!("plot {}: {e}", path.display());
    let root = SVGBackend::new(path, (900, 600)).into_drawing_area();
    root.fill(&WHITE).map_err(|e| err(&e))?;
    let mut chart = ChartBuilder::on(&root)
        .caption(title, ("sans-serif", 20))
        .margin(10)
        .x_label_area_size(40)
        .y_label_area_size(70)
        .build_cartesian_2d((x0 / 1.5..x1 * 1.5).log_scale(), (y0 / 3.0..y1 * 3.0).log_scale())
        .map_err(|e| err(&e))?;
    chart
        .configure_mesh()
        .x_desc(x_label)
        .y_desc("worst relative error (floored at 1e-16)")
        .x_label_formatter(&|v| format!("{v:.0e}"))
        .y_label_formatter(&|v| format!("{v:.0e}"))
        .draw()
        .map_err(|e| err(&e))?;
    for (k, s) in data.iter().enumerate() {
        let color = Palette99::pick(k).to_rgba();
        let style = ShapeStyle::from(&color).stroke_width(if k < 4 { 3 } else { 1 });
        chart
            .draw_series(LineSeries::new(s.points.iter().map(|p| (xs(p), p.2)), style))
            .map_err(|e| err(&e))?
            .label(s.name)
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], style));
        chart
            .draw_series(
                s.points
                    .iter()
                    .map(|p| Circle::new((xs(p), p.2), 3, color.filled())),
            )
            .map_err(|e| err(&e))?;
    }
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::LowerLeft)
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .draw()
        .map_err(|e| err(&e))?;
    root.present().map_err(|e| err(&e))?;
    Ok(())
}

/// Writes `error_vs_evaluations_<group>.svg` and `error_vs_time_<group>.svg`
/// for each case family, and for the hardest case (GGX α = 0.01 at 89.5°)
/// when it is in the suite.
pub fn write_plots(out: &Path, rep: &Report<'_>) -> Result<(), String> {
    let mut groups: Vec<(String, Vec<usize>)> = Vec::new();
    for (i, c) in rep.cases.iter().enumerate() {
        match groups.iter_mut().find(|g| g.0 == c.family) {
            Some(g) => g.1.push(i),
            None => groups.push((c.family.to_string(), vec![i])),
        }
    }
    if let Some(i) = rep.cases.iter().position(|c| c.name == "ggx-a0.01-to89.5") {
        groups.push(("ggx-a0.01-to89.5".into(), vec![i]));
    }
    for (g, idx) in &groups {
        let data = series(rep, idx);
        let title = match rep.kind {
            SuiteKind::Albedo => "Directional albedo",
            SuiteKind::Product => "Reflected radiance under a cap light",
        };
        let what = if idx.len() == 1 {
            g.clone()
        } else {
            format!("{g} (worst of {} cases)", idx.len())
        };
        draw(
            &out.join(format!("error_vs_evaluations_{g}.svg")),
            &format!("{title}, {what}: error vs evaluations"),
            "integrand evaluations",
            &data,
            false,
        )?;
        draw(
            &out.join(format!("error_vs_time_{g}.svg")),
            &format!("{title}, {what}: error vs wall time"),
            "wall time [s]",
            &data,
            true,
        )?;
    }
    Ok(())
}
