//! Independent high-accuracy references for directional albedos, in `f64`.
//!
//! Nothing here uses the integrators or the BRDF plugins under test: the
//! BRDF models are re-implemented in `f64` from their papers, and the
//! integral is computed by nested, globally adaptive Gauss–Kronrod (7, 15)
//! quadrature (Kronrod 1965; the error indicator `|K15 − G7|` per interval,
//! as in QUADPACK, Piessens et al. 1983) with break points at the specular
//! peak.
//!
//! `ρ(ωo) = ∫_H f_r(ωi, ωo) cos θi dωi = 2 ∫_0^1 ∫_0^π f_r(ωi(μ, φ), ωo) μ dφ dμ`
//! with `μ = cos θi` (`dω = dμ dφ`) and `ωo` in the `φ = 0` half-plane: the
//! integrand of an isotropic BRDF is even in `φ`, so `φ ∈ [0, π]` is doubled.
//!
//! Each reference is computed at two relative tolerances, `10⁻⁸` (coarse) and
//! `10⁻¹²` (fine); the reported bound is `|R_coarse − R_fine| + ε_fine`, where
//! `ε_fine` is the summed Kronrod error indicator of the fine run's outer
//! rule. The inner rules work to a tenth of the tolerance, relative to their
//! own value or (fine run) to the coarse total, whichever is looser
//! (`inner_abs_tol`). A rule also stops when 512 bisections did not halve its
//! summed error indicator (the indicators have reached the roundoff noise of
//! the `f64` integrand; see [`adaptive`]) and reports that sum as its error.
//! (A fine tolerance of `10⁻¹¹` would be cheaper but misses a feature of
//! Beckmann α = 0.05 at θo = 89.9° that the coarse run misses too, so the
//! bound would understate its error 38×.)

mod gauss_kronrod;
pub mod materials;
pub use gauss_kronrod::adaptive;

use std::f64::consts::{FRAC_PI_2, PI};

/// A BRDF model in `f64` for the reference computation.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum RefModel {
    /// `f = ρ/π`.
    Lambertian {
        /// Albedo.
        albedo: f64,
    },
    /// Modified Phong (Lafortune & Willems 1994, "Using the modified Phong
    /// reflectance model for physically based rendering", CW197):
    /// `f = kd/π + ks (n+2)/(2π) max(0, cos α)^n`, α between ωi and the
    /// mirror direction of ωo about the normal.
    Phong {
        /// Exponent n.
        n: f64,
        /// Specular coefficient.
        ks: f64,
        /// Diffuse coefficient.
        kd: f64,
    },
    /// Microfacet reflection with `F = 1` (Walter et al. 2007, "Microfacet
    /// models for refraction through rough surfaces", EGSR, eq. 20):
    /// `f = D(h) G2(ωi, ωo) / (4 cos θi cos θo)`.
    Microfacet {
        /// `true`: GGX (Walter eq. 33); `false`: Beckmann (Walter eq. 25).
        ggx: bool,
        /// Roughness α.
        alpha: f64,
        /// `true`: height-correlated Smith `G2 = 1/(1+Λi+Λo)` (Heitz 2014,
        /// "Understanding the masking-shadowing function", JCGT 3(2), eq. 99);
        /// `false`: separable `G1(ωi) G1(ωo)`.
        height_correlated: bool,
        /// Conductor Fresnel `F(ωi·h)` with complex index `η + i k`
        /// ([`RefModel::conductor_fresnel`]); `None`: `F = 1`.
        conductor: Option<(f64, f64)>,
    },
    /// A layered material, `coated(TOP, BASE)`: the albedo-scaled layering
    /// of `radiometry::compose::Coated` with the top's *true* directional
    /// albedo tabulated at its nodes (see [`materials`]).
    Coated(materials::Layer),
    /// A weighted sum of lobes `Σ w_k f_k` — one lobe (weights `(1, 0)`),
    /// `a + b` (`(1, 1)`) or `mix(w, a, b)` (`(w, 1 − w)`) — each lobe
    /// re-implemented in [`materials::Lobe`]. The albedo is the weighted sum
    /// of the lobes' albedos: the closed forms where a lobe has one
    /// ([`materials::Lobe::closed_albedo`]), else the lobe's own quadrature.
    Lobes([(f64, materials::Lobe); 2]),
    /// The spec's own BRDF values (the plugin's `eval` at `f32` directions,
    /// the inputs the integrators hand it), integrated in `f64` by nested
    /// adaptive Gauss–Kronrod split at `μ = μo`, at `mu_break`, at `φ = π/2`
    /// and about the mirror direction ([`plugin_albedo`],
    /// [`plugin_cap_radiance`]): for models with no closed form and no
    /// re-implementation here (sheen's fitted `Λ`, OpenPBR's layering). It
    /// never calls a sampling map or an integrator of the library.
    PluginEval {
        /// The spec of the BRDF (a valid spec of the grammar).
        spec: &'static str,
        /// A rough width (radians) of the narrowest peak about the mirror
        /// direction, `None` for none.
        peak: Option<f64>,
        /// A further break point in `μ = cos θi` (where the BRDF has a kink).
        mu_break: Option<f64>,
    },
}

fn sph(mu: f64, phi: f64) -> [f64; 3] {
    let s = (1.0 - mu * mu).max(0.0).sqrt();
    [s * phi.cos(), s * phi.sin(), mu]
}

impl RefModel {
    /// Microfacet normal distribution `D(m)` for `cos θm = c > 0`:
    /// GGX `α² / (π (c²(α²−1)+1)²)` (Walter eq. 33), Beckmann
    /// `exp(−tan²θm/α²) / (π α² c⁴)` (Walter eq. 25).
    fn d(ggx: bool, a: f64, c: f64) -> f64 {
        if c <= 0.0 {
            return 0.0;
        }
        let c2 = c * c;
        if ggx {
            let t = c2 * (a * a - 1.0) + 1.0;
            a * a / (PI * t * t)
        } else {
            let tan2 = (1.0 - c2).max(0.0) / c2;
            (-tan2 / (a * a)).exp() / (PI * a * a * c2 * c2)
        }
    }

    /// Smith Λ for direction with `cos θ = c ∈ (0, 1]`: GGX
    /// `(−1 + √(1 + α² tan²θ))/2` (Heitz 2014 eq. 86), Beckmann
    /// `(erf(a) − 1)/2 + exp(−a²)/(2a√π)`, `a = 1/(α tan θ)` (Heitz 2014 eq. 84;
    /// written with erfc to avoid cancellation).
    fn lambda(ggx: bool, a: f64, c: f64) -> f64 {
        let s2 = (1.0 - c * c).max(0.0);
        if s2 == 0.0 {
            return 0.0;
        }
        let tan2 = s2 / (c * c);
        if ggx {
            let x = a * a * tan2;
            // (√(1+x) − 1)/2 written without cancellation.
            0.5 * x / ((1.0 + x).sqrt() + 1.0)
        } else {
            let aa = 1.0 / (a * tan2.sqrt());
            if aa > 26.0 {
                return 0.0;
            }
            0.5 * ((-aa * aa).exp() / (aa * PI.sqrt()) - libm::erfc(aa))
        }
    }

    /// `f_r(ωi, ωo)` for unit directions in the local frame.
    pub fn eval(&self, wi: [f64; 3], wo: [f64; 3]) -> f64 {
        if wi[2] <= 0.0 || wo[2] <= 0.0 {
            return 0.0;
        }
        match *self {
            RefModel::Coated(layer) => materials::prepared(&layer).eval(wi, wo),
            RefModel::Lobes(lobes) => lobes.iter().map(|(w, l)| w * l.eval(wi, wo)).sum(),
            RefModel::PluginEval { spec, .. } => plugin_eval(spec, wi, wo),
            RefModel::Lambertian { albedo } => albedo / PI,
            RefModel::Phong { n, ks, kd } => {
                let r = [-wo[0], -wo[1], wo[2]];
                let ca = (wi[0] * r[0] + wi[1] * r[1] + wi[2] * r[2]).clamp(0.0, 1.0);
                kd / PI + ks * (n + 2.0) / (2.0 * PI) * ca.powf(n)
            }
            RefModel::Microfacet {
                ggx,
                alpha,
                height_correlated,
                conductor,
            } => {
                let h = [wi[0] + wo[0], wi[1] + wo[1], wi[2] + wo[2]];
                let len = (h[0] * h[0] + h[1] * h[1] + h[2] * h[2]).sqrt();
                if len <= 0.0 {
                    return 0.0;
                }
                let d = Self::d(ggx, alpha, h[2] / len);
                let li = Self::lambda(ggx, alpha, wi[2]);
                let lo = Self::lambda(ggx, alpha, wo[2]);
                let g2 = if height_correlated {
                    1.0 / (1.0 + li + lo)
                } else {
                    1.0 / ((1.0 + li) * (1.0 + lo))
                };
                let f = match conductor {
                    Some((eta, k)) => {
                        let c = (wi[0] * h[0] + wi[1] * h[1] + wi[2] * h[2]) / len;
                        Self::conductor_fresnel(eta, k, c.clamp(0.0, 1.0))
                    }
                    None => 1.0,
                };
                f * d * g2 / (4.0 * wi[2] * wo[2])
            }
        }
    }

    /// Unpolarised Fresnel reflectance of a conductor with complex index
    /// `η + i k` at incidence cosine `c`, in the real form of Born & Wolf
    /// (*Principles of Optics*, 7th ed., §14.4.1; as written out in Pharr,
    /// Jakob & Humphreys, *PBR* 3rd ed., §8.2.1):
    /// `a² + b² = √((η² − k² − s²)² + 4η²k²)`, `a = √((a² + b² + η² − k² − s²)/2)`,
    /// `Rs = (a² + b² − 2ac + c²)/(a² + b² + 2ac + c²)`,
    /// `Rp = Rs (c²(a² + b²) − 2acs² + s⁴)/(c²(a² + b²) + 2acs² + s⁴)`,
    /// `F = (Rs + Rp)/2`, with `s² = 1 − c²`.
    pub fn conductor_fresnel(eta: f64, k: f64, c: f64) -> f64 {
        let s2 = 1.0 - c * c;
        let t = eta * eta - k * k - s2;
        let a2b2 = (t * t + 4.0 * eta * eta * k * k).sqrt();
        let a = ((a2b2 + t) / 2.0).max(0.0).sqrt();
        let rs = (a2b2 - 2.0 * a * c + c * c) / (a2b2 + 2.0 * a * c + c * c);
        let rp =
            rs * (c * c * a2b2 - 2.0 * a * c * s2 + s2 * s2) / (c * c * a2b2 + 2.0 * a * c * s2 + s2 * s2);
        0.5 * (rs + rp)
    }

    /// Where the integrand `f cos θi` peaks (in `μ = cos θi`) for `ωo` at
    /// `cos θo = mu_o`, and a rough lobe width in radians; `None` for a
    /// diffuse model.
    fn peak(&self, mu_o: f64) -> Option<(f64, f64)> {
        match *self {
            RefModel::Lambertian { .. } => None,
            RefModel::Phong { n, .. } => Some((mu_o, (1.0 / (n + 1.0)).sqrt())),
            RefModel::Microfacet { alpha, .. } => Some((mu_o, 2.0 * alpha)),
            RefModel::Coated(layer) => layer.top.peak_width().map(|w| (mu_o, w)),
            RefModel::Lobes(lobes) => lobes_peak(&lobes).map(|w| (mu_o, w)),
            RefModel::PluginEval { peak, .. } => peak.map(|w| (mu_o, w)),
        }
    }
}

/// Break points clustered geometrically around `x0` at distances
/// `w·4^k` (k = −3..2) and `x0` itself.
fn cluster(x0: f64, w: f64) -> Vec<f64> {
    let mut v = vec![x0];
    for k in -3..=2 {
        let d = w * 4f64.powi(k);
        v.push(x0 - d);
        v.push(x0 + d);
    }
    v
}

/// A reference value with its error bound.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Reference {
    /// The albedo.
    pub value: f64,
    /// Bound on `|value − truth|`: `|R_coarse − R_fine| + ε_fine`.
    pub bound: f64,
    /// Integrand evaluations spent (both runs).
    pub evaluations: u64,
}

/// The absolute tolerance of an inner integral of a nested rule whose outer
/// integral is `≈ scale` (the coarse run's value; `0` in the coarse run
/// itself) and whose inner values are summed with total weight `≤
/// outer_weight`: `0.1 · tol · |scale| / outer_weight`, so all inner errors
/// together stay below `tol/10` of the total. The inner rule still stops
/// earlier at its relative tolerance (`tol/10`); this only spares it from
/// resolving small inner integrals (the tails of a lobe) to `10⁻¹³` of
/// their own value.
fn inner_abs_tol(tol: f64, scale: f64, outer_weight: f64) -> f64 {
    (0.1 * tol * scale.abs() / outer_weight).max(1e-300)
}

/// `∫∫ g(μ, φ) dφ dμ` over `μ ∈ [0,1]`, `φ ∈ [0,π]` at relative tolerance
/// `tol`, with break points around `(mu_peak, π)` of width `width`.
fn integrate_2d(
    g: &dyn Fn(f64, f64) -> f64,
    peak: Option<(f64, f64)>,
    kink: Option<&dyn Fn(f64) -> Option<f64>>,
    extra_mu_breaks: &[f64],
    tol: f64,
    scale: f64,
    evals: &mut u64,
) -> (f64, f64) {
    let (mut mu_breaks, phi_breaks) = match peak {
        Some((mu0, w)) => (
            cluster(mu0, w * (1.0 - mu0 * mu0).max(1e-12).sqrt().max(w)),
            cluster(PI, w),
        ),
        None => (vec![], vec![]),
    };
    mu_breaks.extend_from_slice(extra_mu_breaks);
    let mut count = 0u64;
    let mut inner_err_sum = 0.0;
    let (v, e) = adaptive(
        |mu| {
            let mut breaks = phi_breaks.clone();
            if let Some(k) = kink.and_then(|k| k(mu)) {
                breaks.push(k);
            }
            let (iv, ie) = adaptive(
                |phi| {
                    count += 1;
                    g(mu, phi)
                },
                0.0,
                PI,
                &breaks,
                inner_abs_tol(tol, scale, 1.0),
                tol * 0.1,
                4000,
            );
            inner_err_sum += ie;
            iv
        },
        0.0,
        1.0,
        &mu_breaks,
        1e-300,
        tol,
        4000,
    );
    *evals += count;
    let _ = inner_err_sum;
    (v, e)
}

/// The directional albedo `ρ(θo)` of `model` (θo in radians) with an error
/// bound.
pub fn albedo(model: &RefModel, theta_o: f64) -> Reference {
    match *model {
        RefModel::Coated(ref layer) => return materials::albedo(layer, theta_o),
        RefModel::Lobes(lobes) => return lobes_albedo(&lobes, theta_o),
        RefModel::PluginEval { spec, peak, mu_break } => {
            let wo = f32_wo(theta_o);
            let brdf = plugin(spec);
            let f = |wi: [f64; 3]| eval_f32(brdf, wi, wo);
            return plugin_albedo(&f, theta_o, peak, mu_break, PLUGIN_TOLERANCES);
        }
        _ => {}
    }
    let wo = [theta_o.sin(), 0.0, theta_o.cos()];
    let mu_o = wo[2];
    let g = |mu: f64, phi: f64| 2.0 * model.eval(sph(mu, phi), wo) * mu;
    let peak = model.peak(mu_o);
    let mut evals = 0;
    // The modified Phong lobe max(0, cos α)^n has a kink (for small n) on the
    // curve ωi·r = 0, r = (−sin θo, 0, cos θo): cos φ = μ cos θo / (sin θ sin θo).
    // It is a break point of the inner integral, and μ = sin θo (where the
    // curve leaves the φ range) one of the outer.
    let (st, ct) = (theta_o.sin(), theta_o.cos());
    let phong_kink = move |mu: f64| {
        let s = (1.0 - mu * mu).max(0.0).sqrt();
        let c = mu * ct / (s * st);
        (s * st > 0.0 && c.abs() < 1.0).then(|| c.acos())
    };
    let is_phong = matches!(model, RefModel::Phong { .. });
    let kink: Option<&dyn Fn(f64) -> Option<f64>> = if is_phong { Some(&phong_kink) } else { None };
    let extra: Vec<f64> = if is_phong { vec![st] } else { vec![] };
    if let Some((_, width)) = peak {
        // Peaked models: polar coordinates about the mirror direction.
        let f = |wi: [f64; 3], wo: [f64; 3]| model.eval(wi, wo);
        let (coarse, _) = pole_albedo(&f, theta_o, width, 1e-8, 0.0, &mut evals);
        let (fine, e) = pole_albedo(&f, theta_o, width, 1e-12, coarse, &mut evals);
        return Reference {
            value: fine,
            bound: (coarse - fine).abs() + e + 4.0 * f64::EPSILON * fine.abs(),
            evaluations: evals,
        };
    }
    let (coarse, _) = integrate_2d(&g, peak, kink, &extra, 1e-8, 0.0, &mut evals);
    let (fine, e) = integrate_2d(&g, peak, kink, &extra, 1e-12, coarse, &mut evals);
    Reference {
        value: fine,
        bound: (coarse - fine).abs() + e + 4.0 * f64::EPSILON * fine.abs(),
        evaluations: evals,
    }
}

/// `ρ(θo)` in polar coordinates `(θ', φ')` about the mirror direction
/// `r = (−sin θo, 0, cos θo)` of `ωo`, where a narrow lobe is a smooth
/// function of `φ'` and a peak at `θ' ≈ 0` in `θ'` (resolved by geometric
/// break points `w/8, w/4, …`, `w` the lobe width):
/// `ω = cos θ' r + sin θ' (cos φ' t₁ + sin φ' t₂)`, `t₁ = (cos θo, 0, sin θo)`,
/// `t₂ = (0, 1, 0)`, `dω = sin θ' dθ' dφ'`. The horizon `ω_z = 0` bounds
/// `φ'`: visible where `cos φ' ≥ −cos θ' cos θo / (sin θ' sin θo)`, an
/// interval `[0, φ_max(θ')]` after folding the mirror symmetry `φ' ↔ −φ'`
/// (isotropic BRDF, `ωo` in the xz-plane). `φ_max` reaches `π` at
/// `θ' = π/2 − θo` and `0` at `θ' = π/2 + θo`: outer break points, as is
/// `θ' = π/2` (the modified-Phong kink `cos α = 0`).
fn pole_albedo(
    f: &dyn Fn([f64; 3], [f64; 3]) -> f64,
    theta_o: f64,
    width: f64,
    tol: f64,
    scale: f64,
    evals: &mut u64,
) -> (f64, f64) {
    let (st, ct) = theta_o.sin_cos();
    let wo = [st, 0.0, ct];
    let r = [-st, 0.0, ct];
    let t1 = [ct, 0.0, st];
    let mut breaks = Vec::new();
    let mut b = (width / 8.0).max(1e-9);
    while b < PI {
        breaks.push(b);
        b *= 2.0;
    }
    breaks.extend([FRAC_PI_2 - theta_o, FRAC_PI_2, FRAC_PI_2 + theta_o]);
    let mut count = 0u64;
    let (v, e) = adaptive(
        |tp| {
            let (sp, cp) = tp.sin_cos();
            if sp <= 0.0 {
                return 0.0;
            }
            let c_star = if st > 0.0 {
                -cp * ct / (sp * st)
            } else if cp * ct > 0.0 {
                -2.0
            } else {
                2.0
            };
            if c_star >= 1.0 {
                return 0.0;
            }
            let phi_max = if c_star <= -1.0 { PI } else { c_star.acos() };
            let (iv, _) = adaptive(
                |phi| {
                    count += 1;
                    let (s, c) = phi.sin_cos();
                    let w = [cp * r[0] + sp * c * t1[0], sp * s, cp * r[2] + sp * c * t1[2]];
                    if w[2] <= 0.0 { 0.0 } else { f(w, wo) * w[2] }
                },
                0.0,
                phi_max,
                &[],
                // The inner value is weighted by 2 sin θ' ≤ 2 over θ' ∈ [0, π].
                inner_abs_tol(tol, scale, 2.0 * PI),
                tol * 0.1,
                4000,
            );
            2.0 * sp * iv
        },
        0.0,
        PI,
        &breaks,
        1e-300,
        tol,
        4000,
    );
    *evals += count;
    (v, e)
}

/// The reflected radiance `L_r(ωo) = ∫_cap f_r(ωi, ωo) cos θi dωi` of a
/// uniform cap light of radiance 1, axis `axis` (unit) and half-angle
/// `sigma` (radians), clipped by the horizon, with an error bound (two
/// tolerances, as [`albedo`]).
///
/// Cap coordinates (independent of the library's `CapIntegrand`): `v = 1 −
/// cos α ∈ [0, 1 − cos σ]` (α from the axis) and `β ∈ [−π, π]` about it,
/// `dω = dv dβ`, `β = 0` toward the mirror direction `r` of `ωo`. Nested
/// adaptive Gauss–Kronrod: outer in β with break points clustered around
/// `β = 0`, inner in `v` with break points at the horizon crossing (`a_z cos α
/// + k sin α = 0`, `k` the z-component of the azimuth direction) and
/// clustered around the lobe peak `v_r`.
pub fn cap_radiance(model: &RefModel, wo: [f64; 3], axis: [f64; 3], sigma: f64) -> Reference {
    match *model {
        RefModel::Coated(ref layer) => materials::cap_radiance(layer, wo, axis, sigma),
        RefModel::PluginEval { spec, peak, mu_break } => {
            let brdf = plugin(spec);
            let wo32 = radiometry::glam::Vec3::new(wo[0] as f32, wo[1] as f32, wo[2] as f32);
            let f = |wi: [f64; 3]| eval_f32(brdf, wi, wo32);
            let levels: Vec<f64> = mu_break.into_iter().collect();
            plugin_cap_radiance(&f, peak, &levels, wo, axis, sigma, PLUGIN_TOLERANCES)
        }
        _ => {
            let f = |wi: [f64; 3]| model.eval(wi, wo);
            cap_radiance_of(&f, model.peak(wo[2]).map(|(_, w)| w), &[], wo, axis, sigma)
        }
    }
}

/// [`cap_radiance`] of the BRDF `f(ωi)` (at the given `ωo`) whose narrowest
/// lobe has width `lobe` (radians; `None`: no peak), with inner break points
/// also where `cos θi` crosses one of `mu_levels` (where `f` jumps).
fn cap_radiance_of(
    f: &dyn Fn([f64; 3]) -> f64,
    lobe: Option<f64>,
    mu_levels: &[f64],
    wo: [f64; 3],
    axis: [f64; 3],
    sigma: f64,
) -> Reference {
    cap_radiance_at(f, lobe, mu_levels, wo, axis, sigma, (1e-8, 1e-12), 4000)
}

/// [`cap_radiance_of`] at relative tolerances `(coarse, fine)` with at most
/// `max_intervals` intervals per adaptive rule.
#[allow(clippy::too_many_arguments)]
fn cap_radiance_at(
    f: &dyn Fn([f64; 3]) -> f64,
    lobe: Option<f64>,
    mu_levels: &[f64],
    wo: [f64; 3],
    axis: [f64; 3],
    sigma: f64,
    (coarse_tol, fine_tol): (f64, f64),
    max_intervals: usize,
) -> Reference {
    let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let norm = |a: [f64; 3]| {
        let l = dot(a, a).sqrt();
        [a[0] / l, a[1] / l, a[2] / l]
    };
    let cross = |a: [f64; 3], b: [f64; 3]| {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    };
    let a = norm(axis);
    let r = [-wo[0], -wo[1], wo[2]];
    // e1: r's component perpendicular to a (any perpendicular if r ∥ a).
    let ra = dot(r, a);
    let mut e1 = [r[0] - ra * a[0], r[1] - ra * a[1], r[2] - ra * a[2]];
    if dot(e1, e1) < 1e-24 {
        e1 = if a[0].abs() < 0.9 {
            cross(a, [1.0, 0.0, 0.0])
        } else {
            cross(a, [0.0, 1.0, 0.0])
        };
    }
    let e1 = norm(e1);
    let e2 = cross(a, e1);
    let v_sigma = 2.0 * (0.5 * sigma).sin().powi(2);
    let alpha_r = ra.clamp(-1.0, 1.0).acos();
    let v_r = 2.0 * (0.5 * alpha_r).sin().powi(2);
    let lobe = match lobe {
        Some(w) => w.max(1e-6),
        None => 1.0,
    };
    let dir = |v: f64, cb: f64, sb: f64| {
        let sa = (v * (2.0 - v)).max(0.0).sqrt();
        let ca = 1.0 - v;
        [
            ca * a[0] + sa * (cb * e1[0] + sb * e2[0]),
            ca * a[1] + sa * (cb * e1[1] + sb * e2[1]),
            ca * a[2] + sa * (cb * e1[2] + sb * e2[2]),
        ]
    };
    let v_breaks = cluster(v_r, lobe * alpha_r.sin().max(lobe) + lobe * lobe);
    let beta_breaks = cluster(0.0, (lobe / alpha_r.sin().max(lobe)).min(PI / 4.0));
    let mut evals = 0u64;
    let run = |tol: f64, scale: f64, evals: &mut u64| {
        let mut count = 0u64;
        let (v, e) = adaptive(
            |beta| {
                let (sb, cb) = beta.sin_cos();
                let k = cb * e1[2] + sb * e2[2];
                let mut breaks = v_breaks.clone();
                // Horizon: a_z cos α + k sin α = 0 at α_h ∈ (0, π).
                let ah = a[2].atan2(-k);
                let ah = if ah < 0.0 { ah + PI } else { ah };
                if ah > 0.0 && ah < sigma {
                    breaks.push(2.0 * (0.5 * ah).sin().powi(2));
                }
                // Levels of cos θi: a_z cos α + k sin α = R cos(α − δ) = μ.
                let (r, delta) = (a[2].hypot(k), k.atan2(a[2]));
                for &mu in mu_levels {
                    if mu.abs() >= r {
                        continue;
                    }
                    let g = (mu / r).acos();
                    for al in [delta - g, delta + g, delta - g + 2.0 * PI, delta + g - 2.0 * PI] {
                        if al > 0.0 && al < sigma {
                            breaks.push(2.0 * (0.5 * al).sin().powi(2));
                        }
                    }
                }
                adaptive(
                    |v| {
                        count += 1;
                        let w = dir(v, cb, sb);
                        if w[2] <= 0.0 { 0.0 } else { f(w) * w[2] }
                    },
                    0.0,
                    v_sigma,
                    &breaks,
                    inner_abs_tol(tol, scale, 2.0 * PI),
                    tol * 0.1,
                    max_intervals,
                )
                .0
            },
            -PI,
            PI,
            &beta_breaks,
            1e-300,
            tol,
            max_intervals,
        );
        *evals += count;
        (v, e)
    };
    let (coarse, _) = run(coarse_tol, 0.0, &mut evals);
    let (fine, e) = run(fine_tol, coarse, &mut evals);
    Reference {
        value: fine,
        bound: (coarse - fine).abs() + e + 4.0 * f64::EPSILON * fine.abs(),
        evaluations: evals,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lambertian_albedo_is_rho() {
        for t in [0.0f64, 60.0, 85.0, 89.5] {
            let r = albedo(&RefModel::Lambertian { albedo: 0.7 }, t.to_radians());
            assert!((r.value - 0.7).abs() < 1e-12, "{t}: {r:?}");
            assert!(r.bound < 1e-10);
        }
    }

    #[test]
    fn phong_lobe_albedo_at_normal_incidence_is_one() {
        // ∫ (n+2)/(2π) cos^n θ cos θ dω = 1 when the mirror direction is +Z.
        for n in [1.0, 10.0, 100.0, 1000.0] {
            let r = albedo(&RefModel::Phong { n, ks: 1.0, kd: 0.0 }, 0.0);
            assert!((r.value - 1.0).abs() < 1e-10, "n={n}: {r:?}");
            assert!(r.bound < 1e-8 && r.bound >= (r.value - 1.0).abs(), "n={n}: {r:?}");
        }
    }

    #[test]
    fn phong_albedo_off_normal_matches_1d_closed_form() {
        // For the lobe about the mirror direction r at angle θo from the
        // normal, ρ = (n+2)/(2π) ∫ cos^n α cos θi dω. In lobe-centred
        // coordinates (α, β), cos θi = cos α cos θo + sin α sin θo cos β, and
        // ∫ over β of the part above the horizon has a 1-D form we integrate
        // with a separate simple midpoint rule (independent code path).
        for (n, deg) in [(10.0, 60f64), (1.0, 60.0), (1.0, 85.0)] {
            let to: f64 = deg.to_radians();
            let m = 200_000;
            let mut sum = 0.0;
            for a in 0..m {
                let al = (a as f64 + 0.5) / m as f64 * (PI / 2.0);
                let (sa, ca) = al.sin_cos();
                // ∫_0^{2π} max(0, ca cos θo + sa sin θo cos β) dβ
                let p = ca * to.cos();
                let q = sa * to.sin();
                let inner = if q <= p.abs() {
                    if p > 0.0 { 2.0 * PI * p } else { 0.0 }
                } else {
                    let b0 = (-p / q).acos();
                    2.0 * (p * b0 + q * b0.sin())
                };
                sum += ca.powf(n) * sa * inner;
            }
            let closed = (n + 2.0) / (2.0 * PI) * sum * (PI / 2.0) / m as f64;
            let r = albedo(&RefModel::Phong { n, ks: 1.0, kd: 0.0 }, to);
            assert!(
                (r.value - closed).abs() < 1e-8,
                "n={n} θo={deg}: {} vs {closed}",
                r.value
            );
        }
    }

    #[test]
    fn ggx_alpha_one_normal_incidence_is_one_minus_ln2() {
        for hc in [true, false] {
            let m = RefModel::Microfacet {
                ggx: true,
                alpha: 1.0,
                height_correlated: hc,
                conductor: None,
            };
            let r = albedo(&m, 0.0);
            let exact = 1.0 - std::f64::consts::LN_2;
            assert!((r.value - exact).abs() < 1e-11, "{r:?} vs {exact}");
            assert!(r.bound >= (r.value - exact).abs());
        }
    }

    #[test]
    fn weak_white_furnace_of_d_and_lambda() {
        // ∫ G1(ωo) max(0, ωo·m) D(m) dm = cos θo (Heitz 2014 eq. 18): checks
        // D's normalisation and Λ at grazing angles, with the same quadrature.
        for ggx in [true, false] {
            for alpha in [0.01, 0.05, 0.3, 1.0] {
                for deg in [0.0f64, 60.0, 85.0, 89.5] {
                    let t = deg.to_radians();
                    let wo = [t.sin(), 0.0, t.cos()];
                    let g1 = 1.0 / (1.0 + RefModel::lambda(ggx, alpha, wo[2]));
                    let d = |mu: f64, phi: f64| {
                        let m = sph(mu, phi);
                        let dot = (m[0] * wo[0] + m[2] * wo[2]).max(0.0);
                        2.0 * g1 * dot * RefModel::d(ggx, alpha, mu)
                    };
                    // The kink of max(0, ωo·m) at cos φ = −μ cos θo/(sin θm sin θo)
                    // is a break point of the inner integral.
                    let (v, _) = adaptive(
                        |mu| {
                            let sm = (1.0 - mu * mu).max(0.0).sqrt();
                            let c = -mu * wo[2] / (sm * wo[0]).max(1e-300);
                            let kink = if c > -1.0 && c < 1.0 {
                                vec![c.acos()]
                            } else {
                                vec![]
                            };
                            adaptive(|phi| d(mu, phi), 0.0, PI, &kink, 1e-300, 1e-13, 4000).0
                        },
                        0.0,
                        1.0,
                        &cluster(1.0, alpha),
                        1e-300,
                        1e-11,
                        4000,
                    );
                    assert!(
                        (v - wo[2]).abs() < 1e-9 * wo[2].max(1e-3),
                        "ggx={ggx} α={alpha} θ={deg}: {v} vs {}",
                        wo[2]
                    );
                }
            }
        }
    }

    #[test]
    fn phong_n1_kink_is_resolved() {
        for deg in [60.0f64, 85.0, 89.5] {
            let r = albedo(
                &RefModel::Phong {
                    n: 1.0,
                    ks: 1.0,
                    kd: 0.0,
                },
                deg.to_radians(),
            );
            assert!(r.bound < 1e-8 * r.value, "θo={deg}: {r:?}");
        }
    }

    #[test]
    fn cap_radiance_of_a_lambertian_surface_is_the_cap_irradiance_over_pi() {
        // Unclipped cap at elevation e: E = π sin²σ cos θa (Snyder 1996), so
        // L_r = ρ E / π = sin²σ cos θa for ρ = 1.
        let m = RefModel::Lambertian { albedo: 1.0 };
        for (theta_a, sigma) in [(10f64, 0.27f64), (45.0, 5.0), (80.0, 5.0)] {
            let (ta, s) = (theta_a.to_radians(), sigma.to_radians());
            let r = cap_radiance(
                &m,
                [0.3, 0.1, 0.948_683_298_050_513_8],
                [ta.sin(), 0.0, ta.cos()],
                s,
            );
            let exact = s.sin().powi(2) * ta.cos();
            assert!(
                (r.value - exact).abs() <= 1e-12 * exact + r.bound,
                "{theta_a} {sigma}: {r:?} vs {exact}"
            );
            assert!(r.bound < 1e-9 * exact, "{r:?}");
        }
        // A cap with its axis on the horizon is half visible; by symmetry of
        // cos θ about the horizon plane, E = (σ − sin σ cos σ) (exact for
        // axis on the horizon: Snyder 1996, eq. for θa = 90°).
        let s = 0.3f64;
        let r = cap_radiance(&m, [0.0, 0.0, 1.0], [1.0, 0.0, 0.0], s);
        let exact = (s - s.sin() * s.cos()) / PI;
        assert!((r.value - exact).abs() <= 1e-10 * exact, "{r:?} vs {exact}");
    }

    #[test]
    fn conductor_fresnel_closed_forms() {
        // Normal incidence: ((η − 1)² + k²)/((η + 1)² + k²); grazing: 1;
        // k = 0 reduces to the dielectric Fresnel of Schlick's source
        // (η = 1.5 at normal incidence: 0.04).
        for (eta, k) in [(0.18104, 3.068099), (1.5, 0.0), (2.9, 3.0)] {
            let n = ((eta - 1.0) * (eta - 1.0) + k * k) / ((eta + 1.0) * (eta + 1.0) + k * k);
            assert!((RefModel::conductor_fresnel(eta, k, 1.0) - n).abs() < 1e-14);
            assert!((RefModel::conductor_fresnel(eta, k, 0.0) - 1.0).abs() < 1e-14);
        }
        assert!((RefModel::conductor_fresnel(1.5, 0.0, 1.0) - 0.04).abs() < 1e-15);
        // Dielectric at 45° (η = 1.5, Snell: sin θt = sin 45°/1.5):
        // Rs, Rp from the textbook amplitude formulas.
        let (ci, si) = (std::f64::consts::FRAC_1_SQRT_2, std::f64::consts::FRAC_1_SQRT_2);
        let st = si / 1.5;
        let ct = (1.0 - st * st).sqrt();
        let rs = ((ci - 1.5 * ct) / (ci + 1.5 * ct)).powi(2);
        let rp = ((1.5 * ci - ct) / (1.5 * ci + ct)).powi(2);
        assert!((RefModel::conductor_fresnel(1.5, 0.0, ci) - 0.5 * (rs + rp)).abs() < 1e-14);
    }

    #[test]
    fn hardest_case_has_a_small_bound() {
        let m = RefModel::Microfacet {
            ggx: true,
            alpha: 0.01,
            height_correlated: true,
            conductor: None,
        };
        let r = albedo(&m, 89.5f64.to_radians());
        assert!(r.value > 0.0 && r.value < 1.0, "{r:?}");
        assert!(r.bound < 1e-9 * r.value, "{r:?}");
    }
}

#[cfg(test)]
mod plugin_tests {
    use super::RefModel;
    use radiometry::Brdf;
    use radiometry::glam::Vec3;
    use radiometry_spec::model::build_brdf;
    use radiometry_spec::parse_brdf;

    /// The plugins and the independent f64 models agree pointwise (both
    /// implement the same published formulas).
    #[test]
    fn plugins_match_reference_models() {
        let cases: Vec<(String, RefModel)> = vec![
            (
                "lambertian(albedo=0.7)".into(),
                RefModel::Lambertian { albedo: 0.7 },
            ),
            (
                "phong(exponent=100, ks=0.6, kd=0.3)".into(),
                RefModel::Phong {
                    n: 100.0,
                    ks: 0.6,
                    kd: 0.3,
                },
            ),
            (
                "ggx(alpha=0.3)".into(),
                RefModel::Microfacet {
                    ggx: true,
                    alpha: 0.3,
                    height_correlated: true,
                    conductor: None,
                },
            ),
            (
                "ggx(alpha=0.05, g=separable)".into(),
                RefModel::Microfacet {
                    ggx: true,
                    alpha: 0.05,
                    height_correlated: false,
                    conductor: None,
                },
            ),
            (
                "beckmann(alpha=0.3)".into(),
                RefModel::Microfacet {
                    ggx: false,
                    alpha: 0.3,
                    height_correlated: true,
                    conductor: None,
                },
            ),
            (
                // Gold at 632.8 nm (Sopra library, via the Filmetrics database).
                "ggx(alpha=0.3, fresnel=conductor(eta=0.18104, k=3.068099))".into(),
                RefModel::Microfacet {
                    ggx: true,
                    alpha: 0.3,
                    height_correlated: true,
                    conductor: Some((0.18104, 3.068099)),
                },
            ),
            (
                "beckmann(alpha=1, g=separable)".into(),
                RefModel::Microfacet {
                    ggx: false,
                    alpha: 1.0,
                    height_correlated: false,
                    conductor: None,
                },
            ),
        ];
        let mut worst = 0.0f64;
        for (text, m) in &cases {
            let b = build_brdf(text, &parse_brdf(text).unwrap()).unwrap();
            for i in 0..40 {
                for j in 0..40 {
                    let ti = (i as f64 + 0.5) / 40.0 * 89.0;
                    let to = (j as f64 + 0.5) / 40.0 * 89.0;
                    let dphi = (i * 7 + j * 13) as f64 % 360.0;
                    let wi = [ti.to_radians().sin(), 0.0, ti.to_radians().cos()];
                    let (s, c) = dphi.to_radians().sin_cos();
                    let st = to.to_radians().sin();
                    let wo = [st * c, st * s, to.to_radians().cos()];
                    let want = m.eval(wi, wo);
                    let got = b.eval(
                        Vec3::new(wi[0] as f32, wi[1] as f32, wi[2] as f32),
                        Vec3::new(wo[0] as f32, wo[1] as f32, wo[2] as f32),
                    ) as f64;
                    let rel = (got - want).abs() / want.abs().max(1e-3);
                    worst = worst.max(rel);
                    assert!(rel < 1e-4, "{text} θi={ti} θo={to} Δφ={dphi}: {got} vs {want}");
                }
            }
        }
        eprintln!("worst relative plugin/reference-model difference: {worst:e}");
    }
}

/// Relative tolerances `(coarse, fine)` and the most intervals of the outer
/// (`μ`) and of each inner (`φ`, cap: `v`) adaptive rule of the
/// [`RefModel::PluginEval`] references. Their integrand is the plugin's
/// `f32` values, whose rounding (`≈ 10⁻⁷` relative per value) the rules
/// cannot resolve below, and OpenPBR's values carry kinks along the lines
/// of `μi` where its tables' cells meet (the base's `K(μi, μo)`): the outer
/// rule gets the intervals to resolve those, the inner ones (smooth but for
/// the mirror peak and `φ = π/2`, both break points) fewer. The interval
/// caps and the rules' stall test ([`adaptive`]) stop them, and the bound
/// (the two runs' difference plus the finer run's summed indicator) says how
/// far they got.
pub const PLUGIN_TOLERANCES: PluginTolerances = PluginTolerances {
    coarse: 1e-7,
    fine: 1e-8,
    outer_intervals: 400,
    inner_intervals: 50,
};

/// Settings of a quadrature of a plugin's values ([`PLUGIN_TOLERANCES`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PluginTolerances {
    /// Relative tolerance of the first run.
    pub coarse: f64,
    /// Relative tolerance of the second run.
    pub fine: f64,
    /// Most intervals of the outer rule.
    pub outer_intervals: usize,
    /// Most intervals of each inner rule.
    pub inner_intervals: usize,
}

/// The run-time BRDF of a spec, built once per process (the references of
/// [`RefModel::PluginEval`] read its values only).
pub fn plugin(spec: &'static str) -> &'static crate::model::AnyBrdf {
    type Cache = std::sync::Mutex<Vec<(&'static str, &'static crate::model::AnyBrdf)>>;
    static CACHE: std::sync::OnceLock<Cache> = std::sync::OnceLock::new();
    let mut cache = CACHE.get_or_init(Default::default).lock().expect("no poison");
    if let Some(&(_, b)) = cache.iter().find(|(s, _)| *s == spec) {
        return b;
    }
    let parsed = crate::spec::parse_brdf(spec).unwrap_or_else(|e| panic!("reference spec `{spec}`: {e}"));
    let b =
        crate::model::build_brdf(spec, &parsed).unwrap_or_else(|e| panic!("reference spec `{spec}`: {e}"));
    let b: &'static crate::model::AnyBrdf = Box::leak(Box::new(b));
    cache.push((spec, b));
    b
}

/// `ωo` at `θo` as the report hands it to the integrators:
/// `(sin θo, 0, cos θo)` rounded to `f32`.
fn f32_wo(theta_o: f64) -> radiometry::glam::Vec3 {
    radiometry::glam::Vec3::new(theta_o.sin() as f32, 0.0, theta_o.cos() as f32)
}

/// The plugin's value at `ωi` (rounded to `f32`, normalised), 0 below the
/// horizon.
fn eval_f32(brdf: &crate::model::AnyBrdf, wi: [f64; 3], wo: radiometry::glam::Vec3) -> f64 {
    use radiometry::Brdf as _;
    let w = radiometry::glam::Vec3::new(wi[0] as f32, wi[1] as f32, wi[2] as f32);
    if w.z <= 0.0 {
        return 0.0;
    }
    f64::from(brdf.eval(w.normalize(), wo))
}

/// [`RefModel::eval`] of a [`RefModel::PluginEval`].
fn plugin_eval(spec: &'static str, wi: [f64; 3], wo: [f64; 3]) -> f64 {
    let wo = radiometry::glam::Vec3::new(wo[0] as f32, wo[1] as f32, wo[2] as f32);
    eval_f32(plugin(spec), wi, wo.normalize())
}

/// The narrowest peak width of a [`RefModel::Lobes`] (lobes of weight 0
/// left out).
fn lobes_peak(lobes: &[(f64, materials::Lobe); 2]) -> Option<f64> {
    lobes
        .iter()
        .filter(|(w, _)| *w != 0.0)
        .filter_map(|(_, l)| l.peak_width())
        .reduce(f64::min)
}

/// The albedo of `Σ w_k f_k`: `Σ w_k E_k`, each `E_k` in closed form where
/// the lobe has one, else by the lobe's own quadrature (tolerances `10⁻⁸`,
/// `10⁻¹²`); the bound is `Σ w_k β_k`.
fn lobes_albedo(lobes: &[(f64, materials::Lobe); 2], theta_o: f64) -> Reference {
    let mu_o = theta_o.cos();
    let mut r = Reference {
        value: 0.0,
        bound: 0.0,
        evaluations: 0,
    };
    for &(w, lobe) in lobes.iter().filter(|(w, _)| *w != 0.0) {
        let e = lobe
            .closed_albedo(mu_o)
            .unwrap_or_else(|| lobe.albedo(mu_o, 1e-8, 1e-12));
        r.value += w * e.value;
        r.bound += w.abs() * e.bound;
        r.evaluations += e.evaluations;
    }
    r.bound += 4.0 * f64::EPSILON * r.value.abs();
    r
}

/// `ρ = 2 ∫₀¹ ∫₀^π f(ω(μ, φ)) μ dφ dμ` of a BRDF given by its values `f`
/// (`ωo` in the `φ = 0` half-plane), nested adaptive Gauss–Kronrod split at
/// `μ = μo`, `mu_break`, `φ = π/2` (the rough diffuse lobes' `cos Δφ = 0`
/// kink) and clustered about the mirror direction `(μo, π)` (widths `4^k ·
/// w`, `w` the peak width or 0.02): two runs at the relative tolerances
/// `tol.0`, the bound their difference plus the finer run's summed indicator.
pub fn plugin_albedo(
    f: &dyn Fn([f64; 3]) -> f64,
    theta_o: f64,
    peak: Option<f64>,
    mu_break: Option<f64>,
    tol: PluginTolerances,
) -> Reference {
    let (coarse_tol, fine_tol) = (tol.coarse, tol.fine);
    let mu_o = theta_o.cos();
    let w = peak.unwrap_or(0.02);
    let mut mu_breaks = cluster(mu_o, w * (1.0 - mu_o * mu_o).max(1e-12).sqrt().max(w));
    mu_breaks.extend(mu_break);
    let phi_breaks = {
        let mut b = cluster(PI, w);
        b.push(FRAC_PI_2);
        b
    };
    let g = |mu: f64, phi: f64| 2.0 * f(sph(mu, phi)) * mu;
    let phi_at = |_mu: f64| phi_breaks.clone();
    let run = |rel: f64, scale: f64, evals: &mut u64| {
        nested_adaptive(
            &g,
            &mu_breaks,
            &phi_at,
            (rel, rel * 0.1),
            scale,
            (tol.outer_intervals, tol.inner_intervals),
            evals,
        )
    };
    let mut evals = 0;
    let (coarse, _) = run(coarse_tol, 0.0, &mut evals);
    let (fine, e) = run(fine_tol, coarse, &mut evals);
    Reference {
        value: fine,
        bound: (coarse - fine).abs() + e + 4.0 * f64::EPSILON * fine.abs(),
        evaluations: evals,
    }
}

/// The reflected radiance under a cap light (as [`cap_radiance`]) of a BRDF
/// given by its values `f`, at the tolerances and interval cap `tol`
/// (as [`plugin_albedo`]); `mu_levels`: where `f` has a kink in `cos θi`.
pub fn plugin_cap_radiance(
    f: &dyn Fn([f64; 3]) -> f64,
    peak: Option<f64>,
    mu_levels: &[f64],
    wo: [f64; 3],
    axis: [f64; 3],
    sigma: f64,
    tol: PluginTolerances,
) -> Reference {
    // The cap is small: both of its rules get the inner rules' intervals.
    cap_radiance_at(
        f,
        peak,
        mu_levels,
        wo,
        axis,
        sigma,
        (tol.coarse, tol.fine),
        tol.inner_intervals.max(100),
    )
}

/// The directional albedo at `θo` (radians) of an arbitrary BRDF given as
/// its values `f(ωi)` at the fixed `ωo = (sin θo, 0, cos θo)` — the
/// reference of the random-material honesty check
/// (`radiometry tradeoff --honesty N`), which judges the integrators on the
/// crate's own BRDF values.
///
/// `ρ = 2 ∫₀¹ ∫₀^π f(ω(μ, φ)) μ dφ dμ` (the BRDF is isotropic, so the
/// integrand is even in `φ`), nested globally adaptive Gauss–Kronrod in
/// `f64` ([`gauss_kronrod::adaptive`], written independently of the crate's
/// integrators), split where the lobes of the grammar are not smooth or
/// peak: `μ = μo` (the Oren–Nayar family's kink, the mirror direction's
/// polar angle), `φ = π/2` (their `cos Δφ = 0` kink), and clusters of break
/// points about the mirror direction `(μo, π)` at widths `4^k · 0.02`. Two
/// runs (relative tolerances `10⁻⁵` and `10⁻⁷`); the bound is their
/// difference plus the finer run's summed indicator.
pub fn albedo_of(f: &dyn Fn([f64; 3]) -> f64, theta_o: f64) -> Reference {
    let mu_o = theta_o.cos();
    let g = |mu: f64, phi: f64| 2.0 * f(sph(mu, phi)) * mu;
    let mut evals = 0;
    let mut mu_breaks = cluster(mu_o, 0.02);
    mu_breaks.push(mu_o);
    let right = |_mu: f64| Some(FRAC_PI_2);
    let (coarse, _) = integrate_split(&g, &mu_breaks, &right, 1e-5, 0.0, &mut evals);
    let (fine, e) = integrate_split(&g, &mu_breaks, &right, 1e-7, coarse, &mut evals);
    Reference {
        value: fine,
        bound: (coarse - fine).abs() + e + 4.0 * f64::EPSILON * fine.abs(),
        evaluations: evals,
    }
}

/// [`integrate_2d`] with the φ break points `π/2` and a cluster about `π`.
fn integrate_split(
    g: &dyn Fn(f64, f64) -> f64,
    mu_breaks: &[f64],
    kink: &dyn Fn(f64) -> Option<f64>,
    tol: f64,
    scale: f64,
    evals: &mut u64,
) -> (f64, f64) {
    let phi_breaks = cluster(PI, 0.02);
    let phi_at = |mu: f64| {
        let mut breaks = phi_breaks.clone();
        breaks.extend(kink(mu));
        breaks
    };
    nested_adaptive(
        g,
        mu_breaks,
        &phi_at,
        (tol, tol),
        scale,
        (SPLIT_MAX_INTERVALS, SPLIT_MAX_INTERVALS),
        evals,
    )
}

/// `∫₀¹ ∫₀^π g(μ, φ) dφ dμ` by nested globally adaptive Gauss–Kronrod: the
/// outer rule over `μ` split at `mu_breaks` (relative tolerance `rel.0`, no
/// absolute floor), at each of its nodes the inner rule over `φ` split at
/// `phi_breaks(μ)` (relative tolerance `rel.1`, absolute
/// [`inner_abs_tol`]`(rel.0, scale, 1)`); `intervals`: (outer, inner) caps.
/// Returns the value and the outer rule's error indicator, and adds the
/// evaluations of `g` to `evals`.
fn nested_adaptive(
    g: &dyn Fn(f64, f64) -> f64,
    mu_breaks: &[f64],
    phi_breaks: &dyn Fn(f64) -> Vec<f64>,
    rel: (f64, f64),
    scale: f64,
    intervals: (usize, usize),
    evals: &mut u64,
) -> (f64, f64) {
    let mut count = 0u64;
    let (v, e) = adaptive(
        |mu| {
            adaptive(
                |phi| {
                    count += 1;
                    g(mu, phi)
                },
                0.0,
                PI,
                &phi_breaks(mu),
                inner_abs_tol(rel.0, scale, 1.0),
                rel.1,
                intervals.1,
            )
            .0
        },
        0.0,
        1.0,
        mu_breaks,
        1e-300,
        rel.0,
        intervals.0,
    );
    *evals += count;
    (v, e)
}

/// Most intervals of each of [`integrate_split`]'s adaptive rules: the `f32`
/// values' rounding noise (`≈ 10⁻⁷` relative) stops the rules long before.
const SPLIT_MAX_INTERVALS: usize = 300;

/// The references of the materials family that are not layers: closed forms
/// and sums of lobes agree with an f64 quadrature of the plugins' own values
/// (two independent routes to the same number), and the quadrature of a
/// plugin's values converges (its bound is small and a looser run lands
/// within its own bound of it).
#[cfg(test)]
mod material_reference_tests {
    use super::*;
    use crate::tradeoff::materials;

    /// Every closed-form or lobe-sum reference of the suite equals the f64
    /// quadrature of its plugin's values to the `f32` evaluation floor.
    #[test]
    fn lobe_references_match_the_plugins_values() {
        for m in materials() {
            let RefModel::Lobes(_) = m.model else { continue };
            let spec: &'static str = Box::leak(m.spec.clone().into_boxed_str());
            let peak = m.model.peak(1.0).map(|(_, w)| w);
            for &deg in m.thetas {
                let t = deg.to_radians();
                let r = albedo(&m.model, t);
                assert!(r.bound < 1e-10 * r.value, "{} {deg}: {r:?}", m.name);
                let brdf = plugin(spec);
                let wo = f32_wo(t);
                let f = |wi: [f64; 3]| eval_f32(brdf, wi, wo);
                let q = plugin_albedo(&f, t, peak, None, PLUGIN_TOLERANCES);
                assert!(
                    (q.value - r.value).abs() <= q.bound + r.bound + 1e-6 * r.value,
                    "{} {deg}: plugin {q:?} vs reference {r:?}",
                    m.name
                );
            }
        }
    }

    /// The plugin-value references of the suite bound their error below
    /// `10⁻⁶` relative (the report's finest target), and a run at looser
    /// tolerances (`10⁻⁶`, `10⁻⁷`) lands within its own bound of them.
    #[test]
    fn plugin_value_references_converge() {
        for m in materials() {
            let RefModel::PluginEval { spec, peak, mu_break } = m.model else {
                continue;
            };
            for &deg in m.thetas {
                let t = deg.to_radians();
                let r = albedo(&m.model, t);
                assert!(r.bound < 1e-6 * r.value, "{} {deg}: {r:?}", m.name);
                let brdf = plugin(spec);
                let wo = f32_wo(t);
                let f = |wi: [f64; 3]| eval_f32(brdf, wi, wo);
                let loose = plugin_albedo(
                    &f,
                    t,
                    peak,
                    mu_break,
                    PluginTolerances {
                        coarse: 1e-6,
                        fine: 1e-7,
                        ..PLUGIN_TOLERANCES
                    },
                );
                assert!(
                    (loose.value - r.value).abs() <= loose.bound,
                    "{} {deg}: {loose:?} vs {r:?}",
                    m.name
                );
            }
        }
    }

    /// The quadrature of a plugin's values reproduces a closed form: EON's
    /// albedo (the plugin evaluates in `f32`, so to its rounding).
    #[test]
    fn plugin_value_quadrature_reproduces_eon_closed_form() {
        for deg in [0.0f64, 60.0, 85.0] {
            let t = deg.to_radians();
            let brdf = plugin("eon(rho=0.9, sigma=1)");
            let wo = f32_wo(t);
            let f = |wi: [f64; 3]| eval_f32(brdf, wi, wo);
            let q = plugin_albedo(&f, t, None, None, PLUGIN_TOLERANCES);
            let exact = materials::eon_albedo(0.9, 1.0, f64::from(wo.z) / f64::from(wo.length()));
            assert!(q.bound < 1e-7, "{deg}: {q:?}");
            assert!(
                (q.value - exact).abs() <= q.bound + 5e-7 * exact,
                "{deg}: {q:?} vs {exact}"
            );
        }
    }

    /// Under a lamp, the lobe-sum reference of the `mix` material equals the
    /// quadrature of the plugin's values over the cap.
    #[test]
    fn lobe_cap_reference_matches_the_plugins_values() {
        let m = materials().into_iter().find(|m| m.name == "mix").expect("mix");
        let spec: &'static str = Box::leak(m.spec.clone().into_boxed_str());
        let ta = 45f64.to_radians();
        let (wo, axis) = ([-ta.sin(), 0.0, ta.cos()], [ta.sin(), 0.0, ta.cos()]);
        let sigma = 5f64.to_radians();
        let r = cap_radiance(&m.model, wo, axis, sigma);
        let peak = m.model.peak(wo[2]).map(|(_, w)| w);
        let brdf = plugin(spec);
        let wo32 = radiometry::glam::Vec3::new(wo[0] as f32, wo[1] as f32, wo[2] as f32);
        let f = |wi: [f64; 3]| eval_f32(brdf, wi, wo32);
        let q = plugin_cap_radiance(&f, peak, &[], wo, axis, sigma, PLUGIN_TOLERANCES);
        assert!(r.bound < 1e-10 * r.value, "{r:?}");
        assert!(
            (q.value - r.value).abs() <= q.bound + r.bound + 2e-6 * r.value,
            "plugin {q:?} vs reference {r:?}"
        );
    }
}
