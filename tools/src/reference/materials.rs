//! `f64` references for layered materials: `coated(TOP, BASE)` over the
//! lobes a material is made of, each re-implemented here from its source —
//! never calling the plugins, the combinators or the integrators under test.
//!
//! * [`Lobe::Eon`]: the energy-preserving Oren–Nayar BRDF (Portsmouth, Kutz &
//!   Hill, "EON: A practical energy-preserving rough diffuse BRDF", JCGT
//!   14(1), 2025, Listing 1 with `exact = true`): Fujii's
//!   `f_FON = (ρ/π) A (1 + σ s/t)` plus the multiple-scattering lobe
//!   `f_ms = (ρ_ms/π)(1 − E_FON(μi))(1 − E_FON(μo))/(1 − Ē_FON)`.
//! * [`Lobe::Ggx`]: GGX `D` (Walter et al. 2007, eq. 33) with the
//!   height-correlated Smith `G2 = 1/(1 + Λi + Λo)` (Heitz 2014, eq. 99) and
//!   an exact Fresnel factor at `ωi·h`: [`dielectric_fresnel`] (the Fresnel
//!   equations with Snell's law) or the conductor form of
//!   [`RefModel::conductor_fresnel`].
//! * [`Layer`]: the energy-conserving albedo scaling documented on
//!   `radiometry::compose::Coated` (clear coat, no absorption; OpenPBR's
//!   "non-reciprocal albedo scaling"):
//!
//!   ```text
//!   f(ωi, ωo) = f_T(ωi, ωo) + (1 − E_T(μo)) f_B(ωi, ωo)
//!   ```
//!
//! `E_T` is part of the layer's definition: `Coated` reads its top's
//! *reported* albedo. For a microfacet top the reference takes that value as
//! data (the library's global tables read at `μo`, [`library_albedo`]), as
//! the `Tabulated` references take the measured values — the report judges
//! the integrators on the layer the library evaluates. For other tops, and in
//! [`Prepared::with_tolerances`], the top's **true** albedo is tabulated by
//! this module's own quadrature at 128 nodes `μ_k = (k/127)²` and read
//! linearly in `√μ`.
//!
//! Each table is computed once per process ([`prepared`]) and shared by the
//! cases that use it; its quadrature evaluations are not counted in a case's
//! [`Reference::evaluations`].

use super::{RefModel, Reference, cap_radiance_of, integrate_2d, pole_albedo, sph};
use radiometry::Brdf;
use radiometry_brdfs::{Conductor, Dielectric, Ggx, HeightCorrelated, Microfacet};
use std::f64::consts::PI;
use std::sync::{Mutex, OnceLock};

/// Number of nodes of the top's albedo table.
pub const NODES: usize = 128;

/// Smallest node `μ` (the horizon itself is not a node).
pub const MIN_NODE_MU: f64 = 1e-6;

/// The node `μ_k = max((k/127)², 10⁻⁶)`.
pub fn node_mu(k: usize) -> f64 {
    let x = k as f64 / (NODES - 1) as f64;
    (x * x).max(MIN_NODE_MU)
}

/// Exact Fresnel reflectance of an interface with relative index `eta`
/// for unpolarised light at incidence cosine `c` (Born & Wolf, *Principles of
/// Optics*, §1.5.2: `r_s = (c − η c_t)/(c + η c_t)`, `r_p = (η c − c_t)/(η c +
/// c_t)`, `c_t = √(1 − (1 − c²)/η²)` by Snell's law; `F = (r_s² + r_p²)/2`;
/// 1 under total internal reflection).
pub fn dielectric_fresnel(eta: f64, c: f64) -> f64 {
    let c = c.clamp(0.0, 1.0);
    let sin2_t = (1.0 - c * c) / (eta * eta);
    if sin2_t >= 1.0 {
        return 1.0;
    }
    let ct = (1.0 - sin2_t).sqrt();
    let (ds, dp) = (c + eta * ct, eta * c + ct);
    if ds <= 0.0 || dp <= 0.0 {
        return 1.0;
    }
    let rs = (c - eta * ct) / ds;
    let rp = (eta * c - ct) / dp;
    0.5 * (rs * rs + rp * rp)
}

/// A Fresnel factor.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Fresnel {
    /// [`dielectric_fresnel`] with relative index `eta`.
    Dielectric {
        /// Relative index of refraction.
        eta: f64,
    },
    /// [`RefModel::conductor_fresnel`] with complex index `eta + i k`.
    Conductor {
        /// Real part of the index.
        eta: f64,
        /// Extinction coefficient.
        k: f64,
    },
}

impl Fresnel {
    /// `F(c)` at incidence cosine `c`.
    pub fn eval(&self, c: f64) -> f64 {
        match *self {
            Fresnel::Dielectric { eta } => dielectric_fresnel(eta, c),
            Fresnel::Conductor { eta, k } => RefModel::conductor_fresnel(eta, k, c.clamp(0.0, 1.0)),
        }
    }
}

/// `c₁ = 1/2 − 2/(3π)` of FON/EON (Portsmouth et al. 2025, Listing 1).
const EON_C1: f64 = 0.5 - 2.0 / (3.0 * PI);
/// `c₂ = 2/3 − 28/(15π)`: `Ē_FON = A (1 + c₂σ)` (ibid.).
const EON_C2: f64 = 2.0 / 3.0 - 28.0 / (15.0 * PI);

/// `G(μ) = sin θ (θ − sin θ cos θ) + (2/3)(tan θ (1 − sin³θ) − sin θ)`
/// (Portsmouth et al. 2025, Listing 1, `E_FON_exact`), with `tan θ (1 − sin³θ)`
/// written as `sin θ cos θ (1 + sin θ + sin²θ)/(1 + sin θ)` (from `1 − sin θ =
/// cos²θ/(1 + sin θ)`), finite at the horizon.
fn eon_g(mu: f64) -> f64 {
    let mu = mu.clamp(0.0, 1.0);
    let s = ((1.0 - mu) * (1.0 + mu)).sqrt();
    let theta = mu.acos();
    s * (theta - s * mu) + (2.0 / 3.0) * (s * mu * (1.0 + s + s * s) / (1.0 + s) - s)
}

/// FON's exact directional albedo at `ρ = 1`: `E_FON(μ) = A (1 + σ G(μ)/π)`,
/// `A = 1/(1 + c₁σ)` (ibid.).
pub fn fon_albedo(mu: f64, sigma: f64) -> f64 {
    (1.0 + sigma * eon_g(mu) / PI) / (1.0 + EON_C1 * sigma)
}

/// EON's multiple-scattering albedo `ρ_ms = ρ² Ē/(1 − ρ(1 − Ē))`,
/// `Ē = A (1 + c₂σ)`, and `Ē` itself (ibid.).
fn eon_rho_ms(rho: f64, sigma: f64) -> (f64, f64) {
    let e_avg = (1.0 + EON_C2 * sigma) / (1.0 + EON_C1 * sigma);
    (rho * rho * e_avg / (1.0 - rho * (1.0 - e_avg)), e_avg)
}

/// EON's exact directional albedo, `ρ E_FON(μo) + ρ_ms (1 − E_FON(μo))`
/// (Portsmouth et al. 2025, §4) — for the tests; the references integrate
/// the BRDF itself.
pub fn eon_albedo(rho: f64, sigma: f64, mu_o: f64) -> f64 {
    let e = fon_albedo(mu_o, sigma);
    rho * e + eon_rho_ms(rho, sigma).0 * (1.0 - e)
}

/// `(A, B)` of the qualitative Oren–Nayar model for `σ` in radians:
/// `A = 1 − σ²/(2(σ² + 0.33))`, `B = 0.45σ²/(σ² + 0.09)` (Oren & Nayar 1994,
/// the qualitative model).
pub fn qon_coefficients(sigma_rad: f64) -> (f64, f64) {
    let s2 = sigma_rad * sigma_rad;
    (1.0 - s2 / (2.0 * (s2 + 0.33)), 0.45 * s2 / (s2 + 0.09))
}

/// The qualitative Oren–Nayar model's directional albedo at `ρ = 1`,
/// `A + B H(μ)`, `H(μ) = (G(μ) + (2/3) sin θ)/π`, derived here from FON's
/// closed form: FON's single-scattering term integrates `s/t` over both
/// signs of `s = sin θi sin θo cos Δφ` (with `t = 1` where `s ≤ 0`), the
/// qualitative model only `max(0, s)/t`. Over `s ≤ 0` (`t = 1`),
/// `(1/π)∫ s μi dωi = −(1/π) sin θo ∫₀¹ √(1 − μ²) μ dμ ∫_{π/2}^{3π/2} |cos φ|
/// dφ … = −(2/3) sin θo/π`, so `(1/π)∫ max(0, s)/t μi dωi = G(μo)/π + (2/3)
/// sin θo/π` where `G/π` is FON's (Portsmouth et al. 2025, `E_FON_exact`).
pub fn qon_albedo(mu: f64, sigma_rad: f64) -> f64 {
    let (a, b) = qon_coefficients(sigma_rad);
    let mu = mu.clamp(0.0, 1.0);
    let s = ((1.0 - mu) * (1.0 + mu)).sqrt();
    a + b * (eon_g(mu) + 2.0 / 3.0 * s) / PI
}

/// One lobe of a layered material.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Lobe {
    /// `f = 0` (an ideal, non-reflecting top).
    Black,
    /// `f = ρ/π`.
    Lambertian {
        /// Albedo ρ.
        rho: f64,
    },
    /// Fujii's improved Oren–Nayar, single scattering only (the first
    /// term of EON): `f = (ρ/π) A (1 + σ s/t)`, `A = 1/(1 + c₁σ)`, `s = ωi·ωo
    /// − μi μo`, `t = max(μi, μo)` where `s > 0`, else 1 (Portsmouth et al.
    /// 2025, Listing 1, `f_EON`'s single-scattering term).
    Fon {
        /// ρ.
        rho: f64,
        /// Dimensionless roughness σ ∈ [0, 1].
        sigma: f64,
    },
    /// The classic "qualitative" Oren–Nayar model (Oren & Nayar 1994; as
    /// pbrt-v3 writes it): `f = (ρ/π)(A + B max(0, cos Δφ) sin α tan β)`,
    /// `α = max(θi, θo)`, `β = min(θi, θo)`, `A = 1 − σ²/(2(σ² + 0.33))`,
    /// `B = 0.45σ²/(σ² + 0.09)`, σ in radians — evaluated here in its
    /// trigonometric form, as the paper writes it.
    OrenNayar {
        /// ρ.
        rho: f64,
        /// σ, the facet slope's standard deviation in radians.
        sigma_rad: f64,
    },
    /// EON with albedo colour `ρ` and dimensionless roughness `σ ∈ [0, 1]`.
    Eon {
        /// ρ.
        rho: f64,
        /// σ.
        sigma: f64,
    },
    /// GGX `F D G2/(4 μi μo)`, height-correlated `G2`.
    Ggx {
        /// Roughness α.
        alpha: f64,
        /// Fresnel factor at `ωi·h`.
        fresnel: Fresnel,
    },
}

impl Lobe {
    /// `f(ωi, ωo)`, zero when either direction is at or below the horizon.
    pub fn eval(&self, wi: [f64; 3], wo: [f64; 3]) -> f64 {
        let (mi, mo) = (wi[2], wo[2]);
        if mi <= 0.0 || mo <= 0.0 {
            return 0.0;
        }
        match *self {
            Lobe::Black => 0.0,
            Lobe::Lambertian { rho } => rho / PI,
            Lobe::Fon { rho, sigma } => {
                let a = 1.0 / (1.0 + EON_C1 * sigma);
                let s = wi[0] * wo[0] + wi[1] * wo[1];
                let s_over_t = if s > 0.0 { s / mi.max(mo) } else { s };
                rho / PI * a * (1.0 + sigma * s_over_t)
            }
            Lobe::OrenNayar { rho, sigma_rad } => {
                let (a, b) = qon_coefficients(sigma_rad);
                let (ti, to) = (mi.clamp(-1.0, 1.0).acos(), mo.clamp(-1.0, 1.0).acos());
                let (alpha, beta) = (ti.max(to), ti.min(to));
                let (pi_, po) = (wi[1].atan2(wi[0]), wo[1].atan2(wo[0]));
                let c = if ti == 0.0 || to == 0.0 {
                    0.0
                } else {
                    (pi_ - po).cos().max(0.0)
                };
                rho / PI * (a + b * c * alpha.sin() * beta.tan())
            }
            Lobe::Eon { rho, sigma } => {
                let a = 1.0 / (1.0 + EON_C1 * sigma);
                // s = ωi·ωo − μi μo, t = max(μi, μo) where s > 0.
                let s = wi[0] * wo[0] + wi[1] * wo[1];
                let s_over_t = if s > 0.0 { s / mi.max(mo) } else { s };
                let f_ss = rho / PI * a * (1.0 + sigma * s_over_t);
                let (rho_ms, e_avg) = eon_rho_ms(rho, sigma);
                let f_ms = if sigma > 0.0 {
                    rho_ms / PI * (1.0 - fon_albedo(mi, sigma)) * (1.0 - fon_albedo(mo, sigma))
                        / (1.0 - e_avg)
                } else {
                    0.0
                };
                f_ss + f_ms
            }
            Lobe::Ggx { alpha, fresnel } => {
                let h = [wi[0] + wo[0], wi[1] + wo[1], wi[2] + wo[2]];
                let len = (h[0] * h[0] + h[1] * h[1] + h[2] * h[2]).sqrt();
                if len <= 0.0 {
                    return 0.0;
                }
                let d = RefModel::d(true, alpha, h[2] / len);
                let g2 = 1.0 / (1.0 + RefModel::lambda(true, alpha, mi) + RefModel::lambda(true, alpha, mo));
                let c = (wi[0] * h[0] + wi[1] * h[1] + wi[2] * h[2]) / len;
                fresnel.eval(c) * d * g2 / (4.0 * mi * mo)
            }
        }
    }

    /// The lobe's directional albedo at `cos θo = mu_o` in closed form, where
    /// it has one (Lambertian `ρ`; FON `ρ E_FON`; EON `ρ E_FON + ρ_ms (1 −
    /// E_FON)`; the qualitative Oren–Nayar [`qon_albedo`]), with a bound of
    /// a few ulps; `None` for a microfacet lobe.
    pub fn closed_albedo(&self, mu_o: f64) -> Option<Reference> {
        let v = match *self {
            Lobe::Black => 0.0,
            Lobe::Lambertian { rho } => rho,
            Lobe::Fon { rho, sigma } => rho * fon_albedo(mu_o, sigma),
            Lobe::Eon { rho, sigma } => eon_albedo(rho, sigma, mu_o),
            Lobe::OrenNayar { rho, sigma_rad } => rho * qon_albedo(mu_o, sigma_rad),
            Lobe::Ggx { .. } => return None,
        };
        Some(Reference {
            value: v,
            bound: 64.0 * f64::EPSILON * v.abs(),
            evaluations: 0,
        })
    }

    /// A rough width (radians) of the lobe's peak about the mirror
    /// direction; `None` for a diffuse lobe.
    pub fn peak_width(&self) -> Option<f64> {
        match *self {
            Lobe::Ggx { alpha, .. } => Some(2.0 * alpha),
            _ => None,
        }
    }

    /// `∫ f(ωi, ωo) μi dωi` at `cos θo = mu_o` by nested adaptive
    /// Gauss–Kronrod, at relative tolerances `coarse` and `fine`, with the
    /// bound `|coarse − fine| + ε_fine` (as [`super::albedo`]).
    pub fn albedo(&self, mu_o: f64, coarse: f64, fine: f64) -> Reference {
        let mu_o = mu_o.clamp(0.0, 1.0);
        let theta_o = mu_o.acos();
        let wo = [theta_o.sin(), 0.0, mu_o];
        let mut evals = 0u64;
        let (c, (v, e)) = match self.peak_width() {
            _ if *self == Lobe::Black => (0.0, (0.0, 0.0)),
            Some(width) => {
                let f = |wi: [f64; 3], wo: [f64; 3]| self.eval(wi, wo);
                let (c, _) = pole_albedo(&f, theta_o, width, coarse, 0.0, &mut evals);
                (c, pole_albedo(&f, theta_o, width, fine, c, &mut evals))
            }
            None => {
                let g = |mu: f64, phi: f64| 2.0 * self.eval(sph(mu, phi), wo) * mu;
                // EON's kinks: s = 0 at φ = π/2, and μi = μo.
                let kink: &dyn Fn(f64) -> Option<f64> = &|_| (wo[0] > 0.0).then_some(PI / 2.0);
                let (c, _) = integrate_2d(&g, None, Some(kink), &[mu_o], coarse, 0.0, &mut evals);
                (
                    c,
                    integrate_2d(&g, None, Some(kink), &[mu_o], fine, c, &mut evals),
                )
            }
        };
        Reference {
            value: v,
            bound: (c - v).abs() + e + 4.0 * f64::EPSILON * v.abs(),
            evaluations: evals,
        }
    }
}

/// `coated(TOP, BASE)` with a clear coat (`coat_color = 1`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Layer {
    /// The top lobe (its albedo is tabulated).
    pub top: Lobe,
    /// The base lobe.
    pub base: Lobe,
}

/// A [`Layer`] with its table of the top's true albedo.
#[derive(Clone, Debug)]
pub struct Prepared {
    /// The layer.
    pub layer: Layer,
    /// The top's albedo at [`node_mu`]`(k)`, clamped to `[0, 1]`.
    pub table: [f64; NODES],
    /// The largest error bound of a table entry.
    pub table_bound: f64,
    /// Whether `E_T` is the library's reported albedo, read at `μo`
    /// ([`library_albedo`]) rather than the table.
    pub library: bool,
    /// Integrand evaluations spent on the table.
    pub evaluations: u64,
}

/// The albedo `radiometry::compose::Coated` reads for a GGX top at `μ`
/// (its reported `directional_albedo`, from the crate's global tables), as
/// data; `None` for other tops.
pub fn library_albedo(top: &Lobe, mu: f64) -> Option<f64> {
    let Lobe::Ggx { alpha, fresnel } = *top else {
        return None;
    };
    let ggx = Ggx::new(alpha as f32).ok()?;
    let mu = mu.clamp(0.0, 1.0) as f32;
    let wo = radiometry::glam::Vec3::new((1.0 - mu * mu).max(0.0).sqrt(), 0.0, mu);
    let e = match fresnel {
        Fresnel::Dielectric { eta } => {
            Microfacet::<_, HeightCorrelated, _>::new(ggx, Dielectric::new(eta as f32).ok()?)
                .directional_albedo(wo)
                .value
        }
        Fresnel::Conductor { eta, k } => {
            Microfacet::<_, HeightCorrelated, _>::new(ggx, Conductor::new(eta as f32, k as f32).ok()?)
                .directional_albedo(wo)
                .value
        }
    };
    Some(f64::from(e).clamp(0.0, 1.0))
}

/// [`library_albedo`] at the 128 nodes.
pub fn library_table(top: &Lobe) -> Option<[f64; NODES]> {
    let mut t = [0.0; NODES];
    for (k, e) in t.iter_mut().enumerate() {
        *e = library_albedo(top, node_mu(k))?;
    }
    Some(t)
}

impl Prepared {
    /// The layer as the library defines it: the table `Coated` reads
    /// ([`library_table`], exact data: bound 0) for a GGX top, else the top's
    /// albedo by quadrature with the references' tolerances (`10⁻⁸`, then
    /// `10⁻¹²`).
    pub fn new(layer: Layer) -> Prepared {
        match library_table(&layer.top) {
            Some(table) => Prepared {
                library: true,
                ..Prepared::from_table(layer, table, 0.0, 0)
            },
            None => Prepared::with_tolerances(layer, 1e-8, 1e-12),
        }
    }

    /// A layer over a given table (each value clamped to `[0, 1]`) whose
    /// entries are within `table_bound` of what they stand for.
    pub fn from_table(layer: Layer, table: [f64; NODES], table_bound: f64, evaluations: u64) -> Prepared {
        let table = table.map(|e| if e.is_finite() { e.clamp(0.0, 1.0) } else { 0.0 });

        Prepared {
            layer,
            table,
            table_bound,
            library: false,
            evaluations,
        }
    }

    /// Tabulates the top's albedo at relative tolerances `coarse`, `fine`.
    pub fn with_tolerances(layer: Layer, coarse: f64, fine: f64) -> Prepared {
        let mut table = [0.0; NODES];
        let (mut table_bound, mut evaluations) = (0.0f64, 0u64);
        for (k, e) in table.iter_mut().enumerate() {
            let r = layer.top.albedo(node_mu(k), coarse, fine);
            *e = if r.value.is_finite() {
                r.value.clamp(0.0, 1.0)
            } else {
                0.0
            };
            table_bound = table_bound.max(r.bound);
            evaluations += r.evaluations;
        }
        Prepared::from_table(layer, table, table_bound, evaluations)
    }

    /// The top's albedo as the layer reads it at `μ`: the library's value
    /// ([`library_albedo`]) or the table linear in `√μ`.
    pub fn top_albedo(&self, mu: f64) -> f64 {
        if self.library
            && let Some(e) = library_albedo(&self.layer.top, mu)
        {
            return e;
        }
        let x = mu.clamp(0.0, 1.0).sqrt() * (NODES - 1) as f64;
        let i = (x as usize).min(NODES - 2);
        let (a, b) = (self.table[i], self.table[i + 1]);
        a + (x - i as f64) * (b - a)
    }

    /// `t(μ) = 1 − E_T(μ)`.
    pub fn through(&self, mu: f64) -> f64 {
        (1.0 - self.top_albedo(mu)).clamp(0.0, 1.0)
    }

    /// `f(ωi, ωo) = f_T + t(μo) f_B`.
    pub fn eval(&self, wi: [f64; 3], wo: [f64; 3]) -> f64 {
        if wi[2] <= 0.0 || wo[2] <= 0.0 {
            return 0.0;
        }
        self.layer.top.eval(wi, wo) + self.base_term(wi, wo)
    }

    /// `t(μo) f_B`.
    fn base_term(&self, wi: [f64; 3], wo: [f64; 3]) -> f64 {
        if wi[2] <= 0.0 || wo[2] <= 0.0 {
            return 0.0;
        }
        let fb = self.layer.base.eval(wi, wo);
        if fb == 0.0 {
            return 0.0;
        }
        self.through(wo[2]) * fb
    }

    /// Relative effect on the base term of every table entry being off by
    /// up to [`Prepared::table_bound`]: `β/(1 − E_max)`.
    fn table_effect(&self) -> f64 {
        let e_max = self.table.iter().fold(0.0f64, |m, &e| m.max(e));
        self.table_bound / (1.0 - e_max).max(1e-3)
    }
}

/// The [`Prepared`] table of `layer`, computed once per process (threads
/// asking for the same layer wait for the first one's table).
pub fn prepared(layer: &Layer) -> &'static Prepared {
    type Cache = Mutex<Vec<(Layer, &'static OnceLock<Prepared>)>>;
    static CACHE: OnceLock<Cache> = OnceLock::new();
    let cell = {
        let mut cache = CACHE.get_or_init(Default::default).lock().expect("no poison");
        match cache.iter().find(|(l, _)| l == layer) {
            Some(&(_, cell)) => cell,
            None => {
                let cell: &'static OnceLock<Prepared> = Box::leak(Box::new(OnceLock::new()));
                cache.push((*layer, cell));
                cell
            }
        }
    };
    cell.get_or_init(|| Prepared::new(*layer))
}

/// The directional albedo of `layer` at `θo` (radians): the top's
/// `∫ f_T μi dωi` in polar coordinates about the mirror direction plus the
/// base term's integral over `(μ, φ)` with break points at `μo` and at `φ = π/2`
/// (EON's kinks); bound: the sum of both bounds plus the effect of the
/// table's own bound.
pub fn albedo(layer: &Layer, theta_o: f64) -> Reference {
    albedo_with(prepared(layer), theta_o, 1e-8, 1e-12)
}

/// [`albedo`] with a given table and tolerances.
pub fn albedo_with(p: &Prepared, theta_o: f64, coarse: f64, fine: f64) -> Reference {
    let wo = [theta_o.sin(), 0.0, theta_o.cos()];
    let mu_o = wo[2];
    let top = p.layer.top.albedo(mu_o, coarse, fine);
    let g = |mu: f64, phi: f64| 2.0 * p.base_term(sph(mu, phi), wo) * mu;
    let peak = p.layer.base.peak_width().map(|w| (mu_o, w));
    let kink: &dyn Fn(f64) -> Option<f64> = &|_| (wo[0] > 0.0).then_some(PI / 2.0);
    let breaks = vec![mu_o];
    let mut evals = top.evaluations;
    let (c, _) = integrate_2d(&g, peak, Some(kink), &breaks, coarse, 0.0, &mut evals);
    let (v, e) = integrate_2d(&g, peak, Some(kink), &breaks, fine, c, &mut evals);
    let base_bound = (c - v).abs() + e + p.table_effect() * v.abs();
    Reference {
        value: top.value + v,
        bound: top.bound + base_bound + 4.0 * f64::EPSILON * (top.value + v).abs(),
        evaluations: evals,
    }
}

/// The reflected radiance of `layer` under a uniform cap light of radiance
/// 1 (as [`super::cap_radiance`]) — the energy-conserving layer's base term
/// depends on `ωo` alone, so no break points in `cos θi` are needed; the
/// table's effect is added to the bound relative to the whole value.
pub fn cap_radiance(layer: &Layer, wo: [f64; 3], axis: [f64; 3], sigma: f64) -> Reference {
    cap_radiance_with(prepared(layer), wo, axis, sigma)
}

/// [`cap_radiance`] with a given table.
pub fn cap_radiance_with(p: &Prepared, wo: [f64; 3], axis: [f64; 3], sigma: f64) -> Reference {
    let f = |wi: [f64; 3]| p.eval(wi, wo);
    let layer = p.layer;
    let lobe = match (layer.top.peak_width(), layer.base.peak_width()) {
        (Some(a), Some(b)) => Some(a.min(b)),
        (a, b) => a.or(b),
    };
    let r = cap_radiance_of(&f, lobe, &[], wo, axis, sigma);
    Reference {
        bound: r.bound + p.table_effect() * r.value.abs(),
        ..r
    }
}

/// `2∫₀¹ g(μ) μ dμ` by adaptive Gauss–Kronrod (tests).
#[cfg(test)]
fn cosine_average(g: impl Fn(f64) -> f64, breaks: &[f64]) -> f64 {
    super::adaptive(|mu| 2.0 * g(mu) * mu, 0.0, 1.0, breaks, 1e-300, 1e-13, 4000).0
}

#[cfg(test)]
mod tests {
    use super::*;

    const GLASS: Fresnel = Fresnel::Dielectric { eta: 1.5 };

    #[test]
    fn dielectric_fresnel_closed_forms() {
        // Normal incidence ((η − 1)/(η + 1))² = 0.04, grazing 1, and the
        // conductor form with k = 0 (another textbook form of the same
        // equations) at every angle.
        assert!((dielectric_fresnel(1.5, 1.0) - 0.04).abs() < 1e-15);
        assert_eq!(dielectric_fresnel(1.5, 0.0), 1.0);
        for i in 0..=50 {
            let c = i as f64 / 50.0;
            let (a, b) = (
                dielectric_fresnel(1.5, c),
                RefModel::conductor_fresnel(1.5, 0.0, c),
            );
            assert!((a - b).abs() < 1e-14, "c = {c}: {a} vs {b}");
        }
        // Brewster's angle: r_p = 0, so F = r_s²/2.
        let cb = 1.0 / (1.0f64 + 1.5 * 1.5).sqrt();
        let ct = (1.0 - (1.0 - cb * cb) / 2.25).sqrt();
        let rs = (cb - 1.5 * ct) / (cb + 1.5 * ct);
        assert!((dielectric_fresnel(1.5, cb) - 0.5 * rs * rs).abs() < 1e-15);
        // Total internal reflection inside the glass (η = 1/1.5).
        assert_eq!(dielectric_fresnel(1.0 / 1.5, 0.5), 1.0);
    }

    /// `Ē_FON = 2∫ E_FON μ dμ = A (1 + c₂σ)`: checks `G` and `c₂` against
    /// each other.
    #[test]
    fn fon_average_albedo_is_a_one_plus_c2_sigma() {
        for sigma in [0.25, 0.5, 1.0] {
            let q = cosine_average(|mu| fon_albedo(mu, sigma), &[]);
            let closed = (1.0 + EON_C2 * sigma) / (1.0 + EON_C1 * sigma);
            assert!((q - closed).abs() < 1e-12, "σ = {sigma}: {q} vs {closed}");
        }
        // E_FON = 1 at grazing (G(0) = π c₁ … the albedo of FON at the horizon).
        assert!((fon_albedo(0.0, 1.0) - 1.0).abs() < 1e-14);
        assert_eq!(fon_albedo(0.3, 0.0), 1.0);
    }

    /// The EON BRDF integrated by quadrature: its albedo is the closed form
    /// `ρ E_FON + ρ_ms (1 − E_FON)`, and 1 at `ρ = 1` (white furnace).
    #[test]
    fn eon_quadrature_matches_its_closed_form_and_the_furnace() {
        for (rho, sigma) in [(0.8, 0.5), (1.0, 0.5), (1.0, 1.0), (0.3, 1.0)] {
            for deg in [0.0f64, 60.0, 85.0] {
                let mu = deg.to_radians().cos();
                let r = Lobe::Eon { rho, sigma }.albedo(mu, 1e-7, 1e-11);
                let closed = eon_albedo(rho, sigma, mu);
                assert!(r.bound < 1e-9, "{rho} {sigma} {deg}: {r:?}");
                assert!(
                    (r.value - closed).abs() <= r.bound + 1e-12,
                    "{rho} {sigma} {deg}: {r:?} vs {closed}"
                );
                if rho == 1.0 {
                    assert!(
                        (r.value - 1.0).abs() <= r.bound + 1e-12,
                        "furnace {sigma} {deg}: {r:?}"
                    );
                }
            }
        }
    }

    /// FON's and the qualitative Oren–Nayar's closed-form albedos against
    /// the quadrature of their BRDFs (the Oren–Nayar one in its
    /// trigonometric form, so the `max(0, s)/t` rewriting is checked too),
    /// grazing views included.
    #[test]
    fn fon_and_oren_nayar_closed_forms_match_their_quadrature() {
        for deg in [0.0f64, 30.0, 60.0, 75.0, 85.0, 89.0] {
            let mu = deg.to_radians().cos();
            for lobe in [
                Lobe::Fon { rho: 0.8, sigma: 0.7 },
                Lobe::Fon { rho: 1.0, sigma: 1.0 },
                Lobe::OrenNayar {
                    rho: 0.8,
                    sigma_rad: 0.35,
                },
                Lobe::OrenNayar {
                    rho: 0.9,
                    sigma_rad: 1.5,
                },
            ] {
                let q = lobe.albedo(mu, 1e-7, 1e-11);
                let c = lobe.closed_albedo(mu).expect("closed form");
                assert!(q.bound < 1e-8, "{lobe:?} {deg}: {q:?}");
                assert!(
                    (q.value - c.value).abs() <= q.bound + c.bound + 1e-12,
                    "{lobe:?} {deg}: {q:?} vs {c:?}"
                );
            }
        }
        // Oren–Nayar at σ = 0 is Lambert; its grazing limit is ρ (A + B/2).
        assert!((qon_albedo(0.5, 0.0) - 1.0).abs() < 1e-15);
        let (a, b) = qon_coefficients(0.2);
        assert!((qon_albedo(0.0, 0.2) - (a + 0.5 * b)).abs() < 1e-12);
    }

    /// A non-reflecting top leaves the base as it is: `E_T = 0`, `t = 1`.
    #[test]
    fn black_top_over_a_base_is_the_base() {
        let layer = Layer {
            top: Lobe::Black,
            base: Lobe::Lambertian { rho: 0.7 },
        };
        let p = Prepared::with_tolerances(layer, 1e-7, 1e-10);
        assert!(p.table.iter().all(|&e| e == 0.0));
        for deg in [0.0f64, 60.0, 85.0] {
            let r = albedo_with(&p, deg.to_radians(), 1e-7, 1e-10);
            assert!(
                (r.value - 0.7).abs() <= r.bound + 1e-12 && r.bound < 1e-9,
                "{deg}: {r:?}"
            );
        }
        let base = Layer {
            top: Lobe::Black,
            base: Lobe::Eon { rho: 0.8, sigma: 0.5 },
        };
        let p = Prepared::with_tolerances(base, 1e-7, 1e-10);
        let r = albedo_with(&p, 1.0, 1e-7, 1e-10);
        let closed = eon_albedo(0.8, 0.5, 1f64.cos());
        assert!((r.value - closed).abs() <= r.bound + 1e-12, "{r:?} vs {closed}");
    }

    /// A top of constant albedo `c` (a Lambertian one): the base is scaled
    /// by `1 − c`: `E = c + (1 − c) E_B`.
    #[test]
    fn constant_top_scales_the_base_by_one_minus_its_albedo() {
        let layer = Layer {
            top: Lobe::Lambertian { rho: 0.2 },
            base: Lobe::Eon { rho: 0.8, sigma: 0.5 },
        };
        let p = Prepared::with_tolerances(layer, 1e-7, 1e-10);
        assert!(p.table.iter().all(|&e| (e - 0.2).abs() < 1e-12), "{:?}", p.table);
        for deg in [0.0f64, 70.0] {
            let mu = deg.to_radians().cos();
            let r = albedo_with(&p, deg.to_radians(), 1e-7, 1e-10);
            let closed = 0.2 + 0.8 * eon_albedo(0.8, 0.5, mu);
            assert!(
                (r.value - closed).abs() <= r.bound + 1e-11,
                "{deg}: {r:?} vs {closed}"
            );
        }
    }

    /// A clear dielectric coat over a white Lambertian base keeps all its
    /// energy: `E(μo) = E_T(μo) + (1 − Ê_T(μo))`, `Ê_T` the layer's reading of
    /// the top's albedo (the table, linear in `√μ`).
    #[test]
    fn clear_coat_over_white_lambertian_matches_the_closed_form() {
        let layer = Layer {
            top: Lobe::Ggx {
                alpha: 0.3,
                fresnel: GLASS,
            },
            base: Lobe::Lambertian { rho: 1.0 },
        };
        let p = Prepared::with_tolerances(layer, 1e-6, 1e-9);
        assert!(p.table_bound < 1e-8, "{}", p.table_bound);
        for deg in [0.0f64, 60.0, 85.0] {
            let mu = deg.to_radians().cos();
            let r = albedo_with(&p, deg.to_radians(), 1e-6, 1e-9);
            let e_t = layer.top.albedo(mu, 1e-6, 1e-9);
            let closed = e_t.value + (1.0 - p.top_albedo(mu));
            assert!(
                (r.value - closed).abs() <= r.bound + e_t.bound + 1e-12,
                "{deg}: {r:?} vs {closed}"
            );
            assert!((r.value - 1.0).abs() < 1e-3, "{deg}: {r:?}");
        }
    }

    /// The cap radiance of a layer: a black top over a Lambertian base under
    /// an unclipped cap is `ρ sin²σ cos θa` (Snyder 1996), also with the
    /// node levels as break points.
    #[test]
    fn cap_radiance_of_a_black_top_over_lambertian() {
        let layer = Layer {
            top: Lobe::Black,
            base: Lobe::Lambertian { rho: 0.6 },
        };
        for (theta_a, sigma) in [(45f64, 5f64), (80.0, 5.0), (60.0, 0.27)] {
            let (ta, s) = (theta_a.to_radians(), sigma.to_radians());
            let r = cap_radiance(
                &layer,
                [-0.3, 0.1, 0.948_683_298_050_513_8],
                [ta.sin(), 0.0, ta.cos()],
                s,
            );
            let exact = 0.6 * s.sin().powi(2) * ta.cos();
            assert!(
                (r.value - exact).abs() <= r.bound + 1e-13 * exact,
                "{theta_a}: {r:?} vs {exact}"
            );
        }
    }

    /// The reading of the table: linear in `√μ` between the nodes, exact at
    /// them.
    #[test]
    fn table_reading_is_the_linear_interpolant() {
        let mut p = Prepared::with_tolerances(
            Layer {
                top: Lobe::Black,
                base: Lobe::Black,
            },
            1e-6,
            1e-9,
        );
        for (k, e) in p.table.iter_mut().enumerate() {
            *e = ((k * 37) % 11) as f64 / 20.0;
        }
        let t = p.table;
        for k in 0..NODES - 1 {
            let mid = ((k as f64 + 0.5) / (NODES - 1) as f64).powi(2);
            assert!((p.top_albedo(mid) - 0.5 * (t[k] + t[k + 1])).abs() < 1e-12, "{k}");
            let at = ((k as f64) / (NODES - 1) as f64).powi(2);
            assert!((p.top_albedo(at) - t[k]).abs() < 1e-12, "{k}");
        }
    }
}

/// The plugins and this module's models agree pointwise — both implement
/// the same published formulas — and so do `Coated`'s layering rules and
/// [`Prepared::eval`] where the top states its albedo in closed form (an
/// EON top: table values within its stated `2·10⁻⁶`).
#[cfg(test)]
mod plugin_tests {
    use super::*;
    use radiometry::Brdf;
    use radiometry::glam::Vec3;
    use radiometry_spec::model::build_brdf;
    use radiometry_spec::parse_brdf;

    /// Worst relative difference `|plugin − model| / max(model, floor)` over
    /// a 30 × 30 grid of (θi, θo) with azimuths spread over the circle.
    fn worst(text: &str, model: &dyn Fn([f64; 3], [f64; 3]) -> f64, floor: f64) -> f64 {
        let b = build_brdf(text, &parse_brdf(text).unwrap()).unwrap();
        let mut worst = 0.0f64;
        for i in 0..30 {
            for j in 0..30 {
                let ti = ((i as f64 + 0.5) / 30.0 * 89.0).to_radians();
                let to = ((j as f64 + 0.5) / 30.0 * 89.0).to_radians();
                let dphi = (((i * 7 + j * 13) % 36) as f64 * 10.0 + 3.0).to_radians();
                let wi = [ti.sin(), 0.0, ti.cos()].map(|x| x as f32 as f64);
                let wo = [to.sin() * dphi.cos(), to.sin() * dphi.sin(), to.cos()].map(|x| x as f32 as f64);
                let want = model(wi, wo);
                let got = b.eval(
                    Vec3::new(wi[0] as f32, wi[1] as f32, wi[2] as f32),
                    Vec3::new(wo[0] as f32, wo[1] as f32, wo[2] as f32),
                ) as f64;
                let rel = (got - want).abs() / want.abs().max(floor);
                assert!(rel.is_finite(), "{text}: {got} vs {want}");
                worst = worst.max(rel);
            }
        }
        worst
    }

    #[test]
    fn lobes_match_the_plugins() {
        let glass = Fresnel::Dielectric { eta: 1.5 };
        let gold = Fresnel::Conductor {
            eta: 0.18104,
            k: 3.068099,
        };
        let cases: [(&str, Lobe); 9] = [
            ("eon(rho=0.8, sigma=0.5)", Lobe::Eon { rho: 0.8, sigma: 0.5 }),
            ("eon(rho=0.9, sigma=1)", Lobe::Eon { rho: 0.9, sigma: 1.0 }),
            ("fon(rho=0.8, sigma=0.7)", Lobe::Fon { rho: 0.8, sigma: 0.7 }),
            (
                "oren-nayar(rho=0.8, sigma_rad=0.35)",
                Lobe::OrenNayar {
                    rho: 0.8,
                    sigma_rad: 0.35,
                },
            ),
            (
                "oren-nayar(rho=0.9, sigma_rad=0.5)",
                Lobe::OrenNayar {
                    rho: 0.9,
                    sigma_rad: 0.5,
                },
            ),
            ("eon(rho=1, sigma=1)", Lobe::Eon { rho: 1.0, sigma: 1.0 }),
            (
                "ggx(alpha=0.1, fresnel=dielectric(eta=1.5))",
                Lobe::Ggx {
                    alpha: 0.1,
                    fresnel: glass,
                },
            ),
            (
                "ggx(alpha=0.05, fresnel=dielectric(eta=1.5))",
                Lobe::Ggx {
                    alpha: 0.05,
                    fresnel: glass,
                },
            ),
            (
                "ggx(alpha=0.3, fresnel=conductor(eta=0.18104, k=3.068099))",
                Lobe::Ggx {
                    alpha: 0.3,
                    fresnel: gold,
                },
            ),
        ];
        for (text, lobe) in cases {
            let w = worst(text, &|wi, wo| lobe.eval(wi, wo), 1e-3);
            assert!(w < 2e-5, "{text}: worst relative difference {w:e}");
        }
    }

    #[test]
    fn layering_rules_match_coated_with_a_closed_form_top() {
        let layer = Layer {
            top: Lobe::Eon { rho: 0.3, sigma: 1.0 },
            base: Lobe::Eon { rho: 0.8, sigma: 0.5 },
        };
        let p = Prepared::with_tolerances(layer, 1e-7, 1e-10);
        // The top's albedo varies with μ (so t(μ) < 1 away from E_min).
        let e_max = p.table.iter().fold(0.0f64, |m, &e| m.max(e));
        let e_min = p.table.iter().fold(1.0f64, |m, &e| m.min(e));
        assert!(e_max - e_min > 0.03, "{:?}", p.table);
        let text = "coated(eon(rho=0.3, sigma=1), eon(rho=0.8, sigma=0.5))";
        let w = worst(text, &|wi, wo| p.eval(wi, wo), 1e-3);
        assert!(w < 2e-5, "worst relative difference {w:e}");
    }
}

/// The report's references of the materials family are converged: the
/// bound of a full-tolerance reference is far below the `f32` evaluation
/// floor (`~10⁻⁷` relative) and the report's targets.
#[cfg(test)]
mod convergence_tests {
    use super::*;

    #[test]
    fn plastic_albedo_reference_bounds_its_error_tightly() {
        let layer = Layer {
            top: Lobe::Ggx {
                alpha: 0.1,
                fresnel: Fresnel::Dielectric { eta: 1.5 },
            },
            base: Lobe::Eon { rho: 0.8, sigma: 0.5 },
        };
        let r = albedo(&layer, 60f64.to_radians());
        assert!(r.value > 0.7 && r.value < 0.85, "{r:?}");
        assert!(r.bound < 1e-8 * r.value, "{r:?}");
        let p = prepared(&layer);
        assert!(p.table_bound < 1e-9, "{}", p.table_bound);
        // The same layer at looser tolerances lands within the bound of the
        // coarser run.
        let loose = albedo_with(p, 60f64.to_radians(), 1e-6, 1e-9);
        assert!((loose.value - r.value).abs() <= loose.bound, "{loose:?} vs {r:?}");
    }
}
