//! Fitting an analytic microfacet BRDF to a tabulated (measured) isotropic
//! BRDF: the library behind `radiometry fit`.
//!
//! # Model
//! Per RGB channel `c`, with one roughness `α` shared by the channels,
//!
//! `f_c(ωi, ωo) = kd_c/π + D(h; α) G2(ωi, ωo; α) F_c(ωi·h) / (4 cos θi cos θo)`
//!
//! (Walter et al. 2007, "Microfacet models for refraction through rough
//! surfaces", eq. 20; `kd_c = 0` unless [`FitOptions::diffuse`]), where `D`
//! is GGX or Beckmann, `G2` the chosen Smith variant, and `F_c` Schlick's
//! approximation with `F0_c` or the exact conductor Fresnel with `η_c + i k_c`.
//! `D G2/(4 cos θi cos θo)` is the `radiometry-brdfs` plugin with `F = 1`,
//! so the fitted model is exactly what the printed specs build.
//!
//! # Metric
//! Over weighted samples `(ωi_j, ωo_j, f_table,j,c, w_j)` (missing channel
//! values excluded), with `μi = cos θi`, `μo = cos θo`:
//!
//! `E = Σ_c Σ_j w_j μi μo (ln(1 + μi f_table) − ln(1 + μi f_c))² / Σ_c Σ_j w_j μi μo`
//!
//! and the printed fit error is `√E`, the RMS log error. Why this metric:
//! `μi f` is the reflected radiance per unit of incident irradiance, and
//! `ln(1 + x)` is `≈ x` for small `x` (the diffuse and off-peak part, fitted
//! in absolute terms) and `≈ ln x` for large `x` (the peak, fitted in
//! relative terms), so the few peak values — which span orders of magnitude
//! and carry the largest measurement error — do not dominate the fit; this is
//! the log-compressed metric Löw et al. ("BRDF models for accurate and
//! efficient rendering of glossy surfaces", ACM TOG 31(1), 2012, § 6) fit
//! MERL data with. The `μi μo` weight makes `E` the mean squared error of
//! what a renderer integrates (the reflection equation weighs by `cos θi`, a
//! camera sees a patch with projected area `∝ cos θo`) and fades out the
//! grazing directions where measured data are least reliable. With `w_j` the
//! 4-D measure `dωi dωo` of sample `j`'s cell (what [`grid::samples`] assigns), `E` is
//! a Riemann sum of `∫∫ μi μo Δ² dωi dωo / ∫∫ μi μo dωi dωo`, independent
//! of the table's resolution and of subsampling.
//!
//! # Optimiser
//! Variable projection on the roughness: for a fixed `α`, `E` separates into
//! one small problem per channel in `(F0_c[, kd_c])` or `(r_c, t_c[, kd_c])` (a conductor
//! parametrisation by its normal-incidence reflectance `r` and a shape `t`),
//! solved by projected Levenberg–Marquardt (`fit/channel.rs`). The profile
//! `E*(ln α)` is scanned on [`ALPHA_GRID`] points from `α = 10⁻³` to `1`
//! (warm-starting each channel from the previous point; on every k-th sample
//! when there are more than [`SCAN_SAMPLES`], since the scan only brackets the
//! minimum), then minimised on all samples by
//! Brent's method (parabolic interpolation with golden-section fallback) in
//! the bracket around the best grid point to `|Δ ln α| ≲ 10⁻⁷`. About 45
//! roughness values are visited;
//! each costs one batch evaluation of the plugin over the samples and a few
//! passes per channel.
//!
//! ```
//! use radiometry::Brdf;
//! use radiometry::glam::Vec3;
//! use radiometry_tools::fit::{FitOptions, Sample, fit};
//! use radiometry_tools::model::build_brdf;
//! use radiometry_tools::spec::{Distribution, parse_brdf};
//!
//! // A table from GGX α = 0.4 with Schlick F0 = 0.5 in every channel.
//! let text = "ggx(alpha=0.4, fresnel=schlick(f0=0.5))";
//! let truth = build_brdf(text, &parse_brdf(text)?)?;
//! let mut samples = Vec::new();
//! for i in 0..12 {
//!     for j in 0..12 {
//!         for k in 0..12 {
//!             let (ti, to, phi) = (i as f32 * 0.13, j as f32 * 0.13, k as f32 * 0.26);
//!             let wi = Vec3::new(ti.sin(), 0.0, ti.cos());
//!             let wo = Vec3::new(to.sin() * phi.cos(), to.sin() * phi.sin(), to.cos());
//!             let v = truth.eval(wi, wo) as f64;
//!             samples.push(Sample { wi, wo, value: [v; 3], weight: 1.0 });
//!         }
//!     }
//! }
//! let f = fit(&samples, &FitOptions::new(Distribution::Ggx)).unwrap();
//! assert!((f.alpha / 0.4 - 1.0).abs() < 1e-3, "{}", f.alpha);
//! assert!(f.specs()[0].starts_with("ggx(alpha=0.4"), "{}", f.specs()[0]);
//! # Ok::<(), radiometry_tools::spec::SpecError>(())
//! ```

mod brent;
mod channel;
pub mod grid;
mod prepared;

use crate::model::build_brdf;
use crate::spec::{BrdfSpec, Distribution, FresnelSpec, G2Kind, MultipleScattering, SpecError};
use brent::brent;
use channel::ChannelProblem;
use prepared::Prepared;
use radiometry::Brdf;
use radiometry::glam::Vec3;
use std::fmt;

/// Absolute tolerance of the roughness search in `ln α`.
const T_TOL: f64 = 1e-7;

/// Most samples the coarse roughness scan uses (every k-th sample of a
/// larger set); Brent's search then runs on all samples.
pub const SCAN_SAMPLES: usize = 20_000;

/// Points of the coarse roughness scan, log-spaced over `α ∈ [10⁻³, 1]`.
pub const ALPHA_GRID: usize = 31;
/// Smallest roughness the fit considers (tables cannot resolve narrower
/// peaks than their angular spacing; the MERL grid's first `θh` node is
/// 0.011°).
pub const ALPHA_MIN: f64 = 1e-3;

/// One tabulated value: directions (local frame, normal `+Z`, pointing away
/// from the surface), the table's RGB value of `f_r` [1/sr] and the weight of
/// the sample in the metric (see the module doc). A channel value that is
/// negative or not finite is *missing* (the MERL convention) and ignored.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sample {
    /// Incident direction ωi.
    pub wi: Vec3,
    /// Outgoing direction ωo.
    pub wo: Vec3,
    /// `f_r` per RGB channel; negative or non-finite = missing.
    pub value: [f64; 3],
    /// Weight `w ≥ 0` (finite).
    pub weight: f64,
}

/// Fresnel model of the fit.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FresnelModel {
    /// Schlick's approximation, one `F0` per channel.
    Schlick,
    /// Exact conductor Fresnel, `η` and `k` per channel.
    Conductor,
}

/// What to fit.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct FitOptions {
    /// Microfacet distribution.
    pub distribution: Distribution,
    /// Smith shadowing–masking variant.
    pub g: G2Kind,
    /// Fresnel model.
    pub fresnel: FresnelModel,
    /// Add a Lambertian term `kd_c/π` per channel.
    pub diffuse: bool,
}

impl FitOptions {
    /// `distribution` with height-correlated Smith G2, Schlick Fresnel and no
    /// diffuse term.
    pub fn new(distribution: Distribution) -> Self {
        FitOptions {
            distribution,
            g: G2Kind::HeightCorrelated,
            fresnel: FresnelModel::Schlick,
            diffuse: false,
        }
    }
}

/// The fitted Fresnel parameters of one channel.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ChannelFresnel {
    /// Schlick `F0`.
    Schlick {
        /// Reflectance at normal incidence.
        f0: f64,
    },
    /// Conductor `η + i k`.
    Conductor {
        /// Real part of the index.
        eta: f64,
        /// Extinction coefficient.
        k: f64,
    },
}

impl ChannelFresnel {
    /// Reflectance at normal incidence: `F0`, or for a conductor
    /// `((η − 1)² + k²)/((η + 1)² + k²)` (Born & Wolf, § 14.2).
    pub fn f0(&self) -> f64 {
        match *self {
            ChannelFresnel::Schlick { f0 } => f0,
            ChannelFresnel::Conductor { eta, k } => {
                ((eta - 1.0).powi(2) + k * k) / ((eta + 1.0).powi(2) + k * k)
            }
        }
    }
}

/// The result of [`fit`].
#[derive(Clone, Debug, PartialEq)]
pub struct Fit {
    /// What was fitted.
    pub options: FitOptions,
    /// Roughness α (shared by the channels).
    pub alpha: f64,
    /// Fresnel parameters per channel.
    pub fresnel: [ChannelFresnel; 3],
    /// Diffuse albedo per channel (`0` without [`FitOptions::diffuse`]).
    pub kd: [f64; 3],
    /// The metric `E` (module doc) at the optimum.
    pub metric: f64,
    /// `E` of each channel alone (normalised by that channel's weights).
    pub channel_metric: [f64; 3],
    /// Samples used (above the horizon, positive weight, some channel present).
    pub samples: usize,
    /// Roughness values visited by the search.
    pub alpha_evaluations: usize,
    /// Levenberg–Marquardt iterations, summed over roughness values and channels.
    pub solver_iterations: usize,
}

impl Fit {
    /// The RMS log error `√E`.
    pub fn rms_log_error(&self) -> f64 {
        self.metric.sqrt()
    }

    /// The normal-incidence reflectance of each channel.
    pub fn f0(&self) -> [f64; 3] {
        self.fresnel.map(|f| f.f0())
    }

    /// The parsed spec of channel `c` (`0, 1, 2` = R, G, B).
    pub fn brdf_spec(&self, c: usize) -> BrdfSpec {
        let fresnel = match self.fresnel[c] {
            ChannelFresnel::Schlick { f0 } => FresnelSpec::Schlick { f0: round6(f0) },
            ChannelFresnel::Conductor { eta, k } => FresnelSpec::Conductor {
                eta: round6(eta),
                k: round6(k),
            },
        };
        BrdfSpec::Microfacet {
            distribution: self.options.distribution,
            alpha: round6(self.alpha),
            g: self.options.g,
            fresnel,
            ms: MultipleScattering::Single,
            kd: round6(self.kd[c]),
        }
    }

    /// One spec string per channel (R, G, B) that `radiometry albedo` and
    /// `radiometry eval` accept (the spec grammar is monochrome), e.g.
    /// `ggx(alpha=0.3, fresnel=schlick(f0=0.9))`; numbers to 6 significant
    /// digits; `kd=` only with a diffuse term, `g=separable` only when fitted
    /// with it.
    pub fn specs(&self) -> [String; 3] {
        [0, 1, 2].map(|c| spec_string(&self.brdf_spec(c)))
    }
}

/// `x` rounded to 6 significant digits.
fn round6(x: f64) -> f64 {
    format!("{x:.5e}").parse().unwrap_or(x)
}

/// The spec text of a microfacet [`BrdfSpec`] (others: `Debug`).
fn spec_string(s: &BrdfSpec) -> String {
    let BrdfSpec::Microfacet {
        distribution,
        alpha,
        g,
        fresnel,
        kd,
        ..
    } = *s
    else {
        return format!("{s:?}");
    };
    let mut t = match distribution {
        Distribution::Ggx => format!("ggx(alpha={alpha}"),
        Distribution::Beckmann => format!("beckmann(alpha={alpha}"),
    };
    if g == G2Kind::Separable {
        t.push_str(", g=separable");
    }
    match fresnel {
        FresnelSpec::Schlick { f0 } => t.push_str(&format!(", fresnel=schlick(f0={f0})")),
        FresnelSpec::Conductor { eta, k } => t.push_str(&format!(", fresnel=conductor(eta={eta}, k={k})")),
        FresnelSpec::Dielectric { eta } => t.push_str(&format!(", fresnel=dielectric(eta={eta})")),
        FresnelSpec::Metal { metal } => t.push_str(&format!(", fresnel=conductor(metal={})", metal.name())),
        FresnelSpec::F82 { f0, f82 } => t.push_str(&format!(", fresnel=f82(f0={f0}, f82={f82})")),
        FresnelSpec::None => {}
    }
    if kd > 0.0 {
        t.push_str(&format!(", kd={kd}"));
    }
    t.push(')');
    t
}

/// Why a fit could not be made.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub enum FitError {
    /// No samples at all.
    Empty,
    /// Samples exist but none is usable (all below the horizon, zero weight,
    /// or every channel missing).
    NoValidSamples {
        /// Number of samples given.
        total: usize,
    },
    /// One channel is missing in every usable sample.
    EmptyChannel {
        /// The channel (0, 1, 2 = R, G, B).
        channel: usize,
    },
    /// A sample with a non-finite direction or a negative / non-finite weight.
    InvalidSample {
        /// Its index.
        index: usize,
        /// What is wrong.
        reason: &'static str,
    },
    /// A channel has fewer usable samples than the parameters that describe
    /// it (its Fresnel parameters and `kd`, plus the shared α): the fit would
    /// be underdetermined.
    TooFewSamples {
        /// The channel (0, 1, 2 = R, G, B).
        channel: usize,
        /// Its usable samples.
        samples: usize,
        /// Parameters to determine.
        parameters: usize,
    },
    /// A table's value array does not have one entry per grid node.
    TableSize {
        /// Grid nodes.
        expected: usize,
        /// Entries found.
        found: usize,
    },
    /// Building the model BRDF failed (an internal error).
    Model(SpecError),
}

impl fmt::Display for FitError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            FitError::Empty => write!(f, "the table has no samples"),
            FitError::NoValidSamples { total } => write!(
                f,
                "none of the {total} samples is usable (all below the horizon, zero weight, or missing)"
            ),
            FitError::EmptyChannel { channel } => {
                write!(
                    f,
                    "channel {} is missing in every sample",
                    ["R", "G", "B"][*channel]
                )
            }
            FitError::InvalidSample { index, reason } => write!(f, "sample {index}: {reason}"),
            FitError::TooFewSamples {
                channel,
                samples,
                parameters,
            } => write!(
                f,
                "channel {} has {samples} usable samples for {parameters} parameters",
                ["R", "G", "B"][*channel]
            ),
            FitError::TableSize { expected, found } => {
                write!(f, "the table has {found} entries for a grid of {expected} nodes")
            }
            FitError::Model(e) => write!(f, "model: {e}"),
        }
    }
}

impl std::error::Error for FitError {}

/// `S_j = D G2/(4 μi μo)` of every prepared sample: the plugin with `F = 1`.
fn specular_factor(p: &Prepared, o: &FitOptions, alpha: f64) -> Result<Vec<f64>, FitError> {
    let spec = BrdfSpec::Microfacet {
        distribution: o.distribution,
        alpha,
        g: o.g,
        fresnel: FresnelSpec::None,
        ms: MultipleScattering::Single,
        kd: 0.0,
    };
    let b = build_brdf("fit", &spec).map_err(FitError::Model)?;
    let mut out = vec![0.0f32; p.len()];
    b.eval_batch(&p.wi, &p.wo, &mut out);
    Ok(out.into_iter().map(f64::from).collect())
}

/// Where the per-channel solvers start: parameters and Marquardt's `λ`
/// (warm starts carry both over from a neighbouring roughness).
#[derive(Clone)]
struct Warm {
    params: [Vec<f64>; 3],
    lambda: [f64; 3],
}

/// Per-channel optimum at one roughness.
struct Profile {
    cost: [f64; 3],
    warm: Warm,
    iterations: usize,
}

impl Profile {
    fn total(&self) -> f64 {
        self.cost.iter().sum()
    }
}

fn profile(p: &Prepared, o: &FitOptions, alpha: f64, start: &Warm) -> Result<Profile, FitError> {
    let s = specular_factor(p, o, alpha)?;
    let mut cost = [0.0; 3];
    let mut params: [Vec<f64>; 3] = Default::default();
    let mut lambda = [0.0; 3];
    let mut iterations = 0;
    for c in 0..3 {
        let prob = ChannelProblem {
            data: p,
            channel: c,
            s: &s,
            fresnel: o.fresnel,
            diffuse: o.diffuse,
        };
        let (x, e, it, l) = channel::minimize(&prob, &start.params[c], start.lambda[c]);
        cost[c] = e;
        params[c] = x;
        lambda[c] = l;
        iterations += it;
    }
    Ok(Profile {
        cost,
        warm: Warm { params, lambda },
        iterations,
    })
}

/// Fits the model of `options` to `samples` (see the module doc for the
/// model, the metric and the optimiser).
///
/// # Errors
/// [`FitError::Empty`], [`FitError::NoValidSamples`],
/// [`FitError::EmptyChannel`], [`FitError::InvalidSample`],
/// [`FitError::TooFewSamples`] for unusable input; never panics, and the
/// result's numbers are finite.
pub fn fit(samples: &[Sample], options: &FitOptions) -> Result<Fit, FitError> {
    let p = Prepared::new(samples)?;
    let o = options;
    let start = {
        let s = vec![0.0; p.len()];
        let prob = ChannelProblem {
            data: &p,
            channel: 0,
            s: &s,
            fresnel: o.fresnel,
            diffuse: o.diffuse,
        };
        let x = prob.start();
        // Each channel's problem has its own parameters plus the shared α.
        let needed = x.len() + 1;
        for c in 0..3 {
            let have = p.w[c].iter().filter(|&&w| w > 0.0).count();
            if have < needed {
                return Err(FitError::TooFewSamples {
                    channel: c,
                    samples: have,
                    parameters: needed,
                });
            }
        }
        Warm {
            params: [x.clone(), x.clone(), x],
            lambda: [channel::LAMBDA_START; 3],
        }
    };
    let (t_lo, t_hi) = (ALPHA_MIN.ln(), 0.0f64);
    let t_at = |i: usize| t_lo + (t_hi - t_lo) * i as f64 / (ALPHA_GRID - 1) as f64;
    let mut evaluations = 0;
    let mut iterations = 0;
    let mut best: Option<(f64, Profile)> = None;
    let mut warm = start;
    let mut best_i = 0;
    // The scan only brackets the minimum: a subset of at most SCAN_SAMPLES
    // (every k-th sample) does that at a fraction of the cost.
    let coarse_owned;
    let coarse = if p.len() > SCAN_SAMPLES {
        coarse_owned = p.every(p.len().div_ceil(SCAN_SAMPLES));
        &coarse_owned
    } else {
        &p
    };
    for i in 0..ALPHA_GRID {
        let t = t_at(i);
        let pr = profile(coarse, o, t.exp(), &warm)?;
        evaluations += 1;
        iterations += pr.iterations;
        warm = pr.warm.clone();
        if best.as_ref().is_none_or(|(_, b)| pr.total() < b.total()) {
            best = Some((t, pr));
            best_i = i;
        }
    }
    let (mut t_best, scan_best) = best.expect("ALPHA_GRID > 0");
    let mut pr_best = if std::ptr::eq(coarse, &p) {
        scan_best
    } else {
        evaluations += 1;
        let pr = profile(&p, o, t_best.exp(), &scan_best.warm)?;
        iterations += pr.iterations;
        pr
    };
    // Brent's minimisation on [t_{i−1}, t_{i+1}] (clamped to the grid).
    let (a, b) = (
        t_at(best_i.saturating_sub(1)),
        t_at((best_i + 1).min(ALPHA_GRID - 1)),
    );
    let warm = pr_best.warm.clone();
    let mut cache: Vec<(f64, Profile)> = Vec::new();
    let t_min = brent(a, b, t_best, pr_best.total(), T_TOL, |t| {
        evaluations += 1;
        let pr = profile(&p, o, t.exp(), &warm)?;
        iterations += pr.iterations;
        let e = pr.total();
        cache.push((t, pr));
        Ok(e)
    })?;
    if let Some(i) = cache.iter().position(|(t, _)| *t == t_min) {
        let (t, pr) = cache.swap_remove(i);
        if pr.total() < pr_best.total() {
            t_best = t;
            pr_best = pr;
        }
    }
    let alpha = t_best.exp().clamp(ALPHA_MIN, 1.0);
    let mut fresnel = [ChannelFresnel::Schlick { f0: 0.0 }; 3];
    let mut kd = [0.0; 3];
    for c in 0..3 {
        let x = &pr_best.warm.params[c];
        fresnel[c] = match o.fresnel {
            FresnelModel::Schlick => ChannelFresnel::Schlick { f0: x[0] },
            FresnelModel::Conductor => {
                let (eta, k) = channel::conductor_eta_k(x[0], x[1]);
                ChannelFresnel::Conductor { eta, k }
            }
        };
        if o.diffuse {
            kd[c] = *x.last().expect("diffuse adds a parameter");
        }
    }
    let wsum: [f64; 3] = [0, 1, 2].map(|c| p.w[c].iter().sum::<f64>());
    let total_w: f64 = wsum.iter().sum();
    let channel_metric = [0, 1, 2].map(|c| pr_best.cost[c] / wsum[c]);
    Ok(Fit {
        options: *o,
        alpha,
        fresnel,
        kd,
        metric: pr_best.total() / total_w,
        channel_metric,
        samples: p.len(),
        alpha_evaluations: evaluations,
        solver_iterations: iterations,
    })
}

/// The metric `E` (module doc) of three monochrome BRDFs (R, G, B) on
/// `samples` — e.g. the printed specs of a [`Fit`] built with
/// [`build_brdf`], to check that they reproduce the fitted model.
///
/// # Errors
/// As [`fit`] for unusable samples.
pub fn metric<B: Brdf<Spectrum = f32>>(samples: &[Sample], brdfs: [&B; 3]) -> Result<f64, FitError> {
    let p = Prepared::new(samples)?;
    let (mut num, mut den) = (0.0, 0.0);
    let mut f = vec![0.0f32; p.len()];
    for (c, b) in brdfs.iter().enumerate() {
        b.eval_batch(&p.wi, &p.wo, &mut f);
        for (j, &fj) in f.iter().enumerate() {
            let d = p.y[c][j] - (p.mu_i[j] * fj as f64).ln_1p();
            num += p.w[c][j] * d * d;
            den += p.w[c][j];
        }
    }
    Ok(num / den)
}
