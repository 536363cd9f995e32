//! χ² goodness-of-fit test of a BRDF sampler against its own density, as pbrt-v4 and Mitsuba 3 do
//! (histogram of ~10⁶ samples against the integrated pdf, cells with expected count < 5 pooled), with
//! two refinements:
//!
//! * the histogram lives in a frame whose pole is chosen by the caller (usually the mirror direction of
//!   `wo`), with `n_fine` bins of `cos θ'` over the cap `[1 − cap, 1]` and `n_coarse` over the rest of the
//!   sphere, times `n_phi` bins of `φ'`, so that sharp lobes are spread over many cells;
//! * the "no sample" outcome (`sample` returned `None`) is one more cell whose expected count is
//!   `N (1 − ∫_{H+} pdf)`, which checks that the density integrates to the probability of producing a
//!   sample (1, or the documented mass for visible-normal sampling).
//!
//! Expected counts come from the adaptive `f64` quadrature of [`super::quad`], per cell, with the
//! horizon clipped in closed form. The statistic `Σ (O − E)² / E` over `k` pooled cells has `k − 1`
//! degrees of freedom (Pearson 1900), and its p-value is the χ² survival function of [`super::special`].
//!
//! The same pass checks every sample: direction finite, unit and strictly above the horizon, pdf finite
//! and > 0, `pdf(wi, wo)` equal to the returned pdf, and `weight = f cos θi / pdf`.

use super::quad::{Adaptive, Integral, PoleFrame, Tol};
use super::rng::Rng;
use super::special::chi2_sf;
use radiometry::glam::{DVec3, Vec3};
use radiometry::{Brdf, Spectrum};
use std::f64::consts::TAU;

/// Configuration of one χ² test.
#[derive(Clone, Copy, Debug)]
pub struct ChiSquare {
    /// Number of `sample` calls.
    pub samples: u32,
    /// Pole of the histogram frame (need not be unit).
    pub pole: DVec3,
    /// Extent `1 − cos θ'` of the finely binned cap around the pole (`≥ 2` bins the whole sphere finely).
    pub cap: f64,
    /// Bins of `cos θ'` in the cap.
    pub n_fine: usize,
    /// Bins of `cos θ'` outside the cap.
    pub n_coarse: usize,
    /// Bins of `φ'`.
    pub n_phi: usize,
    /// Seed of the sample points.
    pub seed: u64,
}

impl ChiSquare {
    /// 10⁶ samples, pole at the mirror direction of `wo`, cap sized for a lobe of angular width `w`
    /// (radians; the cap is `1 − cos(4w)`, at least the whole hemisphere when `w` is large).
    pub fn for_lobe(wo: Vec3, w: f64, seed: u64) -> Self {
        let r = DVec3::new(-wo.x as f64, -wo.y as f64, wo.z as f64);
        let cap = if 4.0 * w >= std::f64::consts::PI {
            2.0
        } else {
            1.0 - (4.0 * w).cos()
        };
        ChiSquare {
            samples: 1_000_000,
            pole: r,
            cap,
            n_fine: 20,
            n_coarse: if cap >= 2.0 { 0 } else { 10 },
            n_phi: 40,
            seed,
        }
    }
}

/// Outcome of one χ² test.
#[derive(Clone, Debug, Default)]
pub struct ChiSquareOutcome {
    /// Pearson statistic after pooling.
    pub statistic: f64,
    /// Degrees of freedom.
    pub dof: usize,
    /// p-value (χ² survival function); 0 if a sample fell where the pdf integrates to exactly 0.
    pub p_value: f64,
    /// `∫_{H+} pdf(ω, wo) dω` by quadrature.
    pub mass: Integral,
    /// Observed `None` results.
    pub none_observed: u64,
    /// Expected `None` results, `N (1 − mass)`.
    pub none_expected: f64,
    /// Samples violating the sample contract (non-finite, not unit, not above the horizon, pdf ≤ 0).
    pub bad_samples: u64,
    /// First violating sample, for the report.
    pub first_bad: Option<String>,
    /// Samples in cells whose integrated pdf is exactly 0.
    pub zero_pdf_hits: u64,
    /// Worst `|pdf(wi) − returned pdf| / returned pdf`.
    pub worst_pdf_rel: f64,
    /// Worst `|weight − f cos/pdf| / max(weight, f cos/pdf)` over channels.
    pub worst_weight_rel: f64,
    /// The cells contributing most to the statistic: (description, observed, expected).
    pub top_cells: Vec<(String, f64, f64)>,
    /// What the quadrature's stated error can add to the statistic, `Σ (N err)² / max(E, 5)` over the
    /// cells; [`passes`](Self::passes) requires it `≤ 1`, so a count is never trusted beyond what the
    /// quadrature resolved.
    pub quadrature_chi2: f64,
}

impl ChiSquareOutcome {
    /// Whether the sampler passes at per-test significance `alpha` and the sample contract holds.
    pub fn passes(&self, alpha: f64) -> bool {
        self.p_value >= alpha
            && self.bad_samples == 0
            && self.zero_pdf_hits == 0
            && self.quadrature_chi2 <= 1.0
    }
}

fn cos_edges(cfg: &ChiSquare) -> Vec<f64> {
    let cap = cfg.cap.min(2.0);
    let c0 = 1.0 - cap;
    let mut e = Vec::new();
    if cap < 2.0 && cfg.n_coarse > 0 {
        for i in 0..cfg.n_coarse {
            e.push(-1.0 + (c0 + 1.0) * i as f64 / cfg.n_coarse as f64);
        }
    }
    for i in 0..cfg.n_fine {
        e.push(c0 + cap * i as f64 / cfg.n_fine as f64);
    }
    e.push(1.0);
    e
}

fn bin_of(edges: &[f64], c: f64) -> usize {
    // Last edge index i with edges[i] ≤ c, capped at the last bin.
    let n = edges.len() - 1;
    match edges.binary_search_by(|e| e.partial_cmp(&c).unwrap()) {
        Ok(i) => i.min(n - 1),
        Err(i) => i.saturating_sub(1).min(n - 1),
    }
}

/// Integrated pdf per cell (row-major: cos bin, φ bin), by adaptive quadrature in `(cos θ', φ')`
/// (`dω = d cos θ' dφ'`), horizon clipped exactly.
pub fn cell_masses(pdf: &mut impl FnMut(DVec3) -> f64, cfg: &ChiSquare) -> Vec<Integral> {
    let fr = PoleFrame::new(cfg.pole);
    let edges = cos_edges(cfg);
    let q = Adaptive::default();
    // Sized to the statistic: with 10⁶ samples a cell's count is off by at most 0.1 + 10⁻⁵ E, which moves
    // `Σ (O − E)²/E` (standard deviation √(2 dof) ≈ 30) by far less than one unit. `chi_square` checks
    // what the quadrature states against that bound (`quadrature_chi2`) before it trusts the counts.
    let tol = Tol {
        abs: 1e-7,
        rel: 1e-5,
        depth: 14,
    };
    let hb: Vec<f64> = fr.horizon_breaks().iter().map(|t| t.cos()).collect();
    let mut out = Vec::with_capacity((edges.len() - 1) * cfg.n_phi);
    for ci in 0..edges.len() - 1 {
        for pi in 0..cfg.n_phi {
            let p0 = TAU * pi as f64 / cfg.n_phi as f64;
            let p1 = TAU * (pi + 1) as f64 / cfg.n_phi as f64;
            let mut row = |c: f64| -> (f64, f64) {
                let s = (1.0 - c * c).max(0.0).sqrt();
                let mut acc = Integral::default();
                for (lo, hi) in fr.upper_phi(c, s, p0, p1) {
                    let t = Tol { abs: 1e-8, ..tol };
                    acc = acc + q.integrate(lo, hi, t, &mut |phi| (pdf(fr.dir(c, s, phi)), 0.0));
                }
                (acc.value, acc.err)
            };
            // Split the cos θ' bin at the horizon features of the rows (see `PoleFrame::horizon_breaks`).
            let (a, b) = (edges[ci], edges[ci + 1]);
            let mut br = vec![a];
            for c in &hb {
                if *c > a && *c < b {
                    br.push(*c);
                }
            }
            br.push(b);
            br.sort_by(|x, y| x.partial_cmp(y).unwrap());
            out.push(q.integrate_breaks(&br, tol, &mut row));
        }
    }
    out
}

fn to_f32(w: DVec3) -> Vec3 {
    Vec3::new(w.x as f32, w.y as f32, w.z as f32)
}

/// Runs the χ² test of `b.sample(wo, ·)` against `b.pdf(·, wo)`.
pub fn chi_square<B: Brdf + ?Sized>(b: &B, wo: Vec3, cfg: &ChiSquare) -> ChiSquareOutcome {
    let fr = PoleFrame::new(cfg.pole);
    let edges = cos_edges(cfg);
    let n_cells = (edges.len() - 1) * cfg.n_phi;
    let mut observed = vec![0u64; n_cells];
    let mut out = ChiSquareOutcome::default();
    let mut rng = Rng::new(cfg.seed);
    for _ in 0..cfg.samples {
        let u = [rng.f32(), rng.f32()];
        let Some(s) = b.sample(wo, u) else {
            out.none_observed += 1;
            continue;
        };
        let len = s.wi.length();
        let ok = s.wi.is_finite()
            && (len - 1.0).abs() < 1e-4
            && s.wi.z > 0.0
            && s.pdf.is_finite()
            && s.pdf > 0.0
            && s.weight.is_finite()
            && s.weight.min_channel() >= 0.0;
        if !ok {
            out.bad_samples += 1;
            if out.first_bad.is_none() {
                out.first_bad = Some(format!("u = {u:?}, wo = {wo:?}: {s:?}"));
            }
            continue;
        }
        let p2 = b.pdf(s.wi, wo);
        out.worst_pdf_rel = out.worst_pdf_rel.max(((p2 - s.pdf).abs() / s.pdf) as f64);
        let f = b.eval(s.wi, wo);
        for ch in 0..B::Spectrum::CHANNELS {
            let expect = f.channel(ch) as f64 * s.wi.z as f64 / s.pdf as f64;
            let got = s.weight.channel(ch) as f64;
            let den = expect.abs().max(got.abs());
            if den > 0.0 {
                out.worst_weight_rel = out.worst_weight_rel.max((expect - got).abs() / den);
            }
        }
        let w = DVec3::new(s.wi.x as f64, s.wi.y as f64, s.wi.z as f64).normalize();
        let (c, p) = fr.coords(w);
        let ci = bin_of(&edges, c);
        let pi = ((p / TAU * cfg.n_phi as f64) as usize).min(cfg.n_phi - 1);
        observed[ci * cfg.n_phi + pi] += 1;
    }

    let mut pdf = |w: DVec3| -> f64 {
        let v = b.pdf(to_f32(w), wo) as f64;
        if v.is_finite() { v } else { f64::NAN }
    };
    let masses = cell_masses(&mut pdf, cfg);
    let n = cfg.samples as f64;
    let mut mass = Integral::default();
    for m in &masses {
        mass = mass + *m;
    }
    out.mass = mass;
    out.quadrature_chi2 = masses
        .iter()
        .map(|m| (n * m.err).powi(2) / (n * m.value).max(5.0))
        .sum();
    out.none_expected = n * (1.0 - mass.value).max(0.0);

    // (label, observed, expected)
    let mut cells: Vec<(String, f64, f64)> = Vec::with_capacity(n_cells + 1);
    for (i, m) in masses.iter().enumerate() {
        let (ci, pi) = (i / cfg.n_phi, i % cfg.n_phi);
        let label = format!("cos θ' ∈ [{:.6}, {:.6}], φ' bin {pi}", edges[ci], edges[ci + 1]);
        if m.value <= 0.0 && observed[i] > 0 {
            out.zero_pdf_hits += observed[i];
        }
        cells.push((label, observed[i] as f64, n * m.value.max(0.0)));
    }
    cells.push((
        "None (no sample)".into(),
        out.none_observed as f64,
        out.none_expected,
    ));

    // Pool cells with expected count < 5 (in increasing order of expected count) until each pool
    // reaches 5; a final pool below 5 joins the smallest regular cell.
    cells.sort_by(|a, b| a.2.partial_cmp(&b.2).unwrap());
    let mut pooled: Vec<(String, f64, f64)> = Vec::new();
    let (mut po, mut pe, mut pn) = (0.0, 0.0, 0usize);
    for (label, o, e) in cells {
        if e < 5.0 {
            po += o;
            pe += e;
            pn += 1;
            if pe >= 5.0 {
                pooled.push((format!("pool of {pn} cells"), po, pe));
                (po, pe, pn) = (0.0, 0.0, 0);
            }
        } else {
            pooled.push((label, o, e));
        }
    }
    if pn > 0 {
        if let Some(first) = pooled.first_mut() {
            first.1 += po;
            first.2 += pe;
            first.0 = format!("{} + pool of {pn} cells", first.0);
        } else {
            pooled.push((format!("pool of {pn} cells"), po, pe));
        }
    }
    let mut contrib: Vec<(f64, usize)> = Vec::new();
    let mut stat = 0.0;
    for (i, (_, o, e)) in pooled.iter().enumerate() {
        let term = if *e > 0.0 {
            (o - e) * (o - e) / e
        } else if *o > 0.0 {
            f64::INFINITY
        } else {
            0.0
        };
        stat += term;
        contrib.push((term, i));
    }
    contrib.sort_by(|a, b| b.0.partial_cmp(&a.0).unwrap());
    out.top_cells = contrib.iter().take(5).map(|&(_, i)| pooled[i].clone()).collect();
    out.statistic = stat;
    out.dof = pooled.len().saturating_sub(1);
    out.p_value = if stat.is_finite() {
        chi2_sf(stat, out.dof)
    } else {
        0.0
    };
    if out.zero_pdf_hits > 0 {
        out.p_value = 0.0;
    }
    out
}
