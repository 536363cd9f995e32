//! The integrands of the report's cases as NumPy functions on the unit
//! square, for integrators written in Python (`radiometry.CaseIntegrand`,
//! and the counting `radiometry.Integrand` the harness of
//! `radiometry.tradeoff(integrators={...})` hands to them).
//!
//! Two parameterisations of each case, both with the Jacobian folded in so
//! that the integral over `[0, 1)²` is the case's value:
//!
//! * **plain** — the hemisphere in `(μ, b)`: `μ = cos θi = x₀`, `φ = 2π x₁`,
//!   `dω = 2π dμ db`; the value is `2π g(ω)` with `g = f_r(ωi, ωo) cos θi`
//!   (albedo cases) or `f_r L cos θi 1_cap(ωi)` with `L = 1` (product cases),
//!   exactly as the built-in plain rules evaluate it
//!   (`radiometry::integrator` `hemisphere_values`);
//! * **warped** — the integrand pulled back through the case's sampling map:
//!   `x ↦ g(ω)/p(ω)` at `ω = sample(x)` (0 where the map gives no direction),
//!   as the built-in warped rules evaluate it (`warped_values`): the BRDF's
//!   own `Brdf::sample` for albedo cases, uniform over the cap's solid angle
//!   (`CapSampled` with `CapStrategy::Light`) for product cases.
//!
//! Points are `f64`; the BRDF is evaluated in `f32` (directions rounded as
//! the built-in rules round them), the values are returned in `f64`.

use numpy::{PyArray1, PyArray2, PyArrayMethods, PyUntypedArrayMethods};
use pyo3::create_exception;
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyType;
use radiometry::glam::Vec3;
use radiometry::integrator::{DirectionalAlbedo, Integrand, IntegrandSample};
use radiometry::light::{Cap, CapSampled, CapStrategy};
use radiometry_spec as spec;
use radiometry_tools::model::{self, AnyBrdf};
use radiometry_tools::reference;
use radiometry_tools::tradeoff::{self as report, product};
use std::collections::HashMap;
use std::f64::consts::TAU;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Mutex, OnceLock};

create_exception!(
    radiometry,
    EvaluationLimitError,
    PyRuntimeError,
    "A run of a user integrator asked for more integrand evaluations than the harness allows (`Integrand.max_evaluations`)."
);

/// Arrays with at least this many rows are evaluated with the GIL released.
const DETACH_ROWS: usize = 1024;

/// Points per batch call of the BRDF (the integrators' chunk size).
const CHUNK: usize = radiometry::integrator::CHUNK;

/// A case of the report, with its BRDF built.
enum Kind {
    Albedo { wo: Vec3 },
    Product { wo: Vec3, cap: Cap<f32> },
}

/// The data shared by a case's integrand objects.
pub struct CaseData {
    name: String,
    spec: String,
    kind: Kind,
    brdf: AnyBrdf,
    /// θo in degrees (product cases: of `ωo`).
    theta_o: f64,
}

/// Names of the albedo cases, then the product cases, of the full suites
/// (`quick`: of the CI-sized suites).
pub fn names(quick: bool) -> Vec<String> {
    report::suite(quick)
        .into_iter()
        .map(|c| c.name)
        .chain(product::suite(quick).into_iter().map(|c| c.name))
        .collect()
}

fn build(spec_text: &str) -> PyResult<AnyBrdf> {
    let parsed = spec::parse_brdf(spec_text).map_err(|e| PyValueError::new_err(e.to_string()))?;
    model::build_brdf(spec_text, &parsed).map_err(|e| PyValueError::new_err(e.to_string()))
}

fn v3(a: [f64; 3]) -> Vec3 {
    Vec3::new(a[0] as f32, a[1] as f32, a[2] as f32)
}

impl CaseData {
    /// The case called `name` (either suite, full or quick).
    pub fn new(name: &str) -> PyResult<CaseData> {
        if let Some(c) = report::suite(false).into_iter().find(|c| c.name == name) {
            let t = c.theta_o.to_radians();
            return Ok(CaseData {
                name: c.name,
                brdf: build(&c.spec)?,
                spec: c.spec,
                // As the report's `measure` builds ωo.
                kind: Kind::Albedo {
                    wo: Vec3::new(t.sin() as f32, 0.0, t.cos() as f32),
                },
                theta_o: c.theta_o,
            });
        }
        if let Some(c) = product::suite(false).into_iter().find(|c| c.name == name) {
            return Ok(CaseData {
                brdf: build(&c.spec)?,
                kind: Kind::Product {
                    wo: v3(c.wo),
                    cap: product::cap_of(&c),
                },
                theta_o: c.wo[2].clamp(-1.0, 1.0).acos().to_degrees(),
                name: c.name,
                spec: c.spec,
            });
        }
        Err(PyValueError::new_err(format!(
            "unknown case `{name}`; the cases are radiometry.case_names(): {}",
            names(false).join(", ")
        )))
    }

    /// `out[k]` = the plain-square value at `p[k]` (see the module docs).
    fn plain(&self, p: &[[f64; 2]], out: &mut [f64]) {
        match self.kind {
            Kind::Albedo { wo } => plain_values(&DirectionalAlbedo { brdf: &self.brdf, wo }, p, out),
            Kind::Product { wo, cap } => {
                plain_values(&CapSampled::new(&self.brdf, wo, &cap, CapStrategy::Light), p, out)
            }
        }
    }

    /// `out[k]` = the warped-square value at `p[k]` (see the module docs).
    fn warped(&self, p: &[[f64; 2]], out: &mut [f64]) {
        match self.kind {
            Kind::Albedo { wo } => warped_values(&DirectionalAlbedo { brdf: &self.brdf, wo }, p, out),
            Kind::Product { wo, cap } => {
                warped_values(&CapSampled::new(&self.brdf, wo, &cap, CapStrategy::Light), p, out)
            }
        }
    }

    /// Every case of the suites offers a sampling map.
    fn has_warped(&self) -> bool {
        match self.kind {
            Kind::Albedo { wo } => DirectionalAlbedo { brdf: &self.brdf, wo }.has_sampling_map(),
            Kind::Product { wo, cap } => {
                CapSampled::new(&self.brdf, wo, &cap, CapStrategy::Light).has_sampling_map()
            }
        }
    }

    /// The report's `f64` reference of the case, computed once per process.
    fn reference(&self) -> PyResult<reference::Reference> {
        static CACHE: OnceLock<Mutex<HashMap<String, reference::Reference>>> = OnceLock::new();
        let cache = CACHE.get_or_init(Default::default);
        if let Some(r) = cache.lock().expect("no poison").get(&self.name) {
            return Ok(*r);
        }
        let r = report::case_reference(&self.name).map_err(PyRuntimeError::new_err)?;
        cache.lock().expect("no poison").insert(self.name.clone(), r);
        Ok(r)
    }
}

/// Direction for `cos θ = μ`, azimuth `φ` (as the built-in plain rules:
/// `radiometry::integrator` `direction`, PBRT 4th ed. §3.8.3).
#[inline]
fn direction(mu: f64, phi: f64) -> Vec3 {
    let mu = mu.clamp(0.0, 1.0);
    let s = (1.0 - mu * mu).max(0.0).sqrt();
    let (sp, cp) = phi.sin_cos();
    Vec3::new((s * cp) as f32, (s * sp) as f32, mu as f32)
}

fn plain_values<I: Integrand<Spectrum = f32>>(g: &I, p: &[[f64; 2]], out: &mut [f64]) {
    let mut dirs = [Vec3::ZERO; CHUNK];
    let mut vals = [0.0f32; CHUNK];
    for (p, out) in p.chunks(CHUNK).zip(out.chunks_mut(CHUNK)) {
        let n = p.len();
        for (d, &[a, b]) in dirs[..n].iter_mut().zip(p) {
            *d = direction(a, TAU * b);
        }
        g.eval_batch(&dirs[..n], &mut vals[..n]);
        for (o, &v) in out.iter_mut().zip(&vals[..n]) {
            *o = v as f64 * TAU;
        }
    }
}

/// `x ∈ [0, 1]` as the `f32` sample coordinate in `[0, 1)` the built-in
/// warped rules pass to the map.
#[inline]
fn to_unit_f32(x: f64) -> f32 {
    (x.clamp(0.0, 1.0) as f32).min(radiometry::math::ONE_MINUS_EPSILON)
}

fn warped_values<I: Integrand<Spectrum = f32>>(g: &I, p: &[[f64; 2]], out: &mut [f64]) {
    let mut us = [[0.0f32; 2]; CHUNK];
    let mut ss: [Option<IntegrandSample<f32>>; CHUNK] = [None; CHUNK];
    for (p, out) in p.chunks(CHUNK).zip(out.chunks_mut(CHUNK)) {
        let n = p.len();
        for (u, &[a, b]) in us[..n].iter_mut().zip(p) {
            *u = [to_unit_f32(a), to_unit_f32(b)];
        }
        g.sample_batch(&us[..n], &mut ss[..n]);
        for (o, s) in out.iter_mut().zip(&ss[..n]) {
            *o = match s {
                Some(s) if s.pdf > 0.0 => s.value as f64 / s.pdf as f64,
                _ => 0.0,
            };
        }
    }
}

/// `(N, 2)` points in `[0, 1]²` from any array-like, as `f64`.
fn points(obj: &Bound<'_, PyAny>) -> PyResult<Vec<[f64; 2]>> {
    let bad = |got: String| {
        PyValueError::new_err(format!(
            "points must be a float array of shape (N, 2) with values in [0, 1], got {got}"
        ))
    };
    let arr = match obj.cast::<PyArray2<f64>>() {
        Ok(a) => a.clone(),
        Err(_) => {
            let np = obj.py().import("numpy")?;
            let c = np
                .call_method1("asarray", (obj, "float64"))
                .map_err(|_| bad("something that is not a float array".into()))?;
            match c.cast_into::<PyArray2<f64>>() {
                Ok(a) => a,
                Err(e) => {
                    let shape: Vec<usize> = e.into_inner().getattr("shape")?.extract()?;
                    return Err(bad(format!("shape {shape:?}")));
                }
            }
        }
    };
    let ro = arr.readonly();
    if ro.shape()[1] != 2 {
        return Err(bad(format!("shape ({}, {})", ro.shape()[0], ro.shape()[1])));
    }
    // `as_slice` also accepts Fortran-ordered arrays (column-major memory),
    // so C order is checked first.
    let v: Vec<[f64; 2]> = match ro.as_slice().ok().filter(|_| ro.is_c_contiguous()) {
        Some(s) => s.chunks_exact(2).map(|c| [c[0], c[1]]).collect(),
        None => ro.as_array().rows().into_iter().map(|r| [r[0], r[1]]).collect(),
    };
    check_unit(&v)?;
    Ok(v)
}

fn check_unit(v: &[[f64; 2]]) -> PyResult<()> {
    if let Some(p) = v
        .iter()
        .find(|p| !(0.0..=1.0).contains(&p[0]) || !(0.0..=1.0).contains(&p[1]))
    {
        return Err(PyValueError::new_err(format!(
            "point ({}, {}) is outside the unit square [0, 1]² (or not a number)",
            p[0], p[1]
        )));
    }
    Ok(())
}

/// Evaluates `side` of `case` at `x` ((N, 2) → (N,) float64).
fn eval_array<'py>(
    py: Python<'py>,
    case: &CaseData,
    warped: bool,
    x: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyArray1<f64>>> {
    let p = points(x)?;
    let run = |p: &[[f64; 2]]| {
        let mut out = vec![0.0; p.len()];
        if warped {
            case.warped(p, &mut out)
        } else {
            case.plain(p, &mut out)
        }
        out
    };
    let out = if p.len() >= DETACH_ROWS {
        py.detach(|| run(&p))
    } else {
        run(&p)
    };
    Ok(PyArray1::from_vec(py, out))
}

fn eval_point(case: &CaseData, warped: bool, a: f64, b: f64) -> PyResult<f64> {
    let p = [[a, b]];
    check_unit(&p)?;
    let mut out = [0.0];
    if warped {
        case.warped(&p, &mut out)
    } else {
        case.plain(&p, &mut out)
    }
    Ok(out[0])
}

/// The integrand of a case of ``radiometry tradeoff`` (a name from
/// ``radiometry.case_names()``) as NumPy functions on the unit square, with
/// the Jacobian folded in so that the integral over [0, 1)² is the case's
/// value (a directional albedo, or the radiance reflected from a cap light):
///
/// * ``plain(x)``: the hemisphere square, ``μ = cos θi = x[:, 0]``,
///   ``φ = 2π x[:, 1]``, value ``2π f_r(ωi, ωo) cos θi`` (albedo cases) or
///   ``2π f_r L cos θi [ωi in the cap]`` with ``L = 1`` (product cases);
/// * ``warped(x)``: pulled back through the case's sampling map, value
///   ``f_r cos θi / pdf`` of the direction the map gives (0 where it gives
///   none): the BRDF's own ``sample`` for albedo cases, uniform over the
///   cap's solid angle for product cases.
///
/// ``x``: an (N, 2) float array with values in [0, 1]; returns (N,) float64.
/// ``plain_at(a, b)`` / ``warped_at(a, b)`` evaluate one point. Large arrays
/// are evaluated with the GIL released. No counting here: the harness of
/// ``radiometry.tradeoff`` hands user integrators a counting
/// ``radiometry.Integrand`` built from it. Picklable (by name).
///
/// >>> g = radiometry.CaseIntegrand("ggx-a0.3-to60")
/// >>> x = np.random.default_rng(1).random((100_000, 2))
/// >>> g.warped(x).mean()      # ≈ the albedo
#[pyclass(frozen, module = "radiometry")]
pub struct CaseIntegrand {
    data: Arc<CaseData>,
}

#[pymethods]
impl CaseIntegrand {
    #[new]
    fn new(name: &str) -> PyResult<Self> {
        Ok(CaseIntegrand {
            data: Arc::new(CaseData::new(name)?),
        })
    }

    /// The case name.
    #[getter]
    fn name(&self) -> &str {
        &self.data.name
    }

    /// ``"albedo"`` or ``"product"``.
    #[getter]
    fn kind(&self) -> &'static str {
        match self.data.kind {
            Kind::Albedo { .. } => "albedo",
            Kind::Product { .. } => "product",
        }
    }

    /// The BRDF spec of the case.
    #[getter]
    fn spec(&self) -> &str {
        &self.data.spec
    }

    /// θo in degrees.
    #[getter]
    fn theta_o(&self) -> f64 {
        self.data.theta_o
    }

    /// Whether the case has a sampling map (``warped``); every case of the
    /// suites has one.
    #[getter]
    fn has_warped(&self) -> bool {
        self.data.has_warped()
    }

    /// The plain-square values at ``x`` ((N, 2) → (N,) float64).
    fn plain<'py>(&self, py: Python<'py>, x: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyArray1<f64>>> {
        eval_array(py, &self.data, false, x)
    }

    /// The warped-square values at ``x`` ((N, 2) → (N,) float64).
    fn warped<'py>(&self, py: Python<'py>, x: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyArray1<f64>>> {
        eval_array(py, &self.data, true, x)
    }

    /// ``plain`` at the point ``(a, b)``.
    fn plain_at(&self, a: f64, b: f64) -> PyResult<f64> {
        eval_point(&self.data, false, a, b)
    }

    /// ``warped`` at the point ``(a, b)``.
    fn warped_at(&self, a: f64, b: f64) -> PyResult<f64> {
        eval_point(&self.data, true, a, b)
    }

    /// The report's f64 reference of the case: ``(value, bound)``, ``bound``
    /// its error bound. Computed once per process (seconds for
    /// the hardest cases), with the GIL released.
    fn reference<'py>(&self, py: Python<'py>) -> PyResult<(f64, f64)> {
        let data = self.data.clone();
        let r = py.detach(move || data.reference())?;
        Ok((r.value, r.bound))
    }

    fn __repr__(&self) -> String {
        format!("CaseIntegrand({:?})", self.data.name)
    }

    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> (Bound<'py, PyType>, (String,)) {
        (slf.get_type(), (slf.get().data.name.clone(),))
    }
}

/// One side (plain or warped) of a counting [`Integrand`]: call it with an
/// (N, 2) array, or ``.at(a, b)`` for one point.
#[pyclass(frozen, module = "radiometry")]
pub struct CountedSide {
    owner: Py<CountingIntegrand>,
    warped: bool,
}

impl CountedSide {
    fn charge(&self, n: usize) -> PyResult<&CaseData> {
        let o = self.owner.get();
        let spent = o.count.fetch_add(n as u64, Ordering::Relaxed) + n as u64;
        if let Some(limit) = o.max_evaluations
            && spent > limit
        {
            return Err(EvaluationLimitError::new_err(format!(
                "{} evaluations asked for on `{}`, more than the harness allows ({limit})",
                spent, o.data.name
            )));
        }
        Ok(&o.data)
    }
}

#[pymethods]
impl CountedSide {
    fn __call__<'py>(&self, py: Python<'py>, x: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyArray1<f64>>> {
        // Shape and range are checked before the rows are charged.
        let p = points(x)?;
        let data = self.charge(p.len())?;
        let run = |p: &[[f64; 2]]| {
            let mut out = vec![0.0; p.len()];
            if self.warped {
                data.warped(p, &mut out)
            } else {
                data.plain(p, &mut out)
            }
            out
        };
        let out = if p.len() >= DETACH_ROWS {
            py.detach(|| run(&p))
        } else {
            run(&p)
        };
        Ok(PyArray1::from_vec(py, out))
    }

    /// The value at one point ``(a, b)`` (counts one evaluation).
    fn at(&self, a: f64, b: f64) -> PyResult<f64> {
        check_unit(&[[a, b]])?;
        let data = self.charge(1)?;
        eval_point(data, self.warped, a, b)
    }

    fn __repr__(&self) -> String {
        let o = self.owner.get();
        format!(
            "<{} side of the integrand of {:?}>",
            if self.warped { "warped" } else { "plain" },
            o.data.name
        )
    }
}

/// What a user integrator receives from ``radiometry.tradeoff``: the
/// integrand of one case, counting every point it is evaluated at.
///
/// * ``plain``: callable, ``plain(x)`` maps an (N, 2) float array in [0, 1]²
///   to (N,) float64; ``plain.at(a, b)`` evaluates one point (for scalar
///   libraries such as ``scipy.integrate.nquad``);
/// * ``warped``: the same through the case's sampling map, or ``None`` where
///   the case has none;
/// * ``evaluations``: points evaluated so far (plain and warped together);
/// * ``max_evaluations``: the most the harness allows in one run (a run that
///   asks for more raises ``radiometry.EvaluationLimitError`` inside the
///   integrator); adapters should keep their library's own limit below it;
/// * ``seed``: a seed for randomised integrators, fixed per (case,
///   integrator, budget or tolerance, report seed), so runs repeat exactly;
/// * ``case``, ``kind`` (``"albedo"`` / ``"product"``), ``spec``,
///   ``theta_o``, ``dim`` (= 2).
///
/// See ``radiometry.CaseIntegrand`` for the two parameterisations.
#[pyclass(frozen, module = "radiometry", name = "Integrand")]
pub struct CountingIntegrand {
    data: Arc<CaseData>,
    count: AtomicU64,
    max_evaluations: Option<u64>,
    seed: u64,
    sides: OnceLock<(Py<CountedSide>, Option<Py<CountedSide>>)>,
}

impl CountingIntegrand {
    fn sides<'a>(slf: &'a Bound<'_, Self>) -> PyResult<&'a (Py<CountedSide>, Option<Py<CountedSide>>)> {
        let me = slf.get();
        if let Some(s) = me.sides.get() {
            return Ok(s);
        }
        let py = slf.py();
        let plain = Py::new(
            py,
            CountedSide {
                owner: slf.clone().unbind(),
                warped: false,
            },
        )?;
        let warped = if me.data.has_warped() {
            Some(Py::new(
                py,
                CountedSide {
                    owner: slf.clone().unbind(),
                    warped: true,
                },
            )?)
        } else {
            None
        };
        let _ = me.sides.set((plain, warped));
        Ok(me.sides.get().expect("set above"))
    }
}

#[pymethods]
impl CountingIntegrand {
    /// ``Integrand(case, max_evaluations=None, seed=0)``: ``case`` a
    /// ``CaseIntegrand`` or a case name.
    #[new]
    #[pyo3(signature = (case, max_evaluations = None, seed = 0))]
    fn new(case: &Bound<'_, PyAny>, max_evaluations: Option<u64>, seed: u64) -> PyResult<Self> {
        let data = if let Ok(c) = case.cast::<CaseIntegrand>() {
            c.get().data.clone()
        } else {
            let name: String = case.extract().map_err(|_| {
                PyValueError::new_err("`case` must be a case name (str) or a radiometry.CaseIntegrand")
            })?;
            Arc::new(CaseData::new(&name)?)
        };
        Ok(CountingIntegrand {
            data,
            count: AtomicU64::new(0),
            max_evaluations,
            seed,
            sides: OnceLock::new(),
        })
    }

    #[getter]
    fn plain(slf: &Bound<'_, Self>) -> PyResult<Py<CountedSide>> {
        Ok(Self::sides(slf)?.0.clone_ref(slf.py()))
    }

    #[getter]
    fn warped(slf: &Bound<'_, Self>) -> PyResult<Option<Py<CountedSide>>> {
        Ok(Self::sides(slf)?.1.as_ref().map(|s| s.clone_ref(slf.py())))
    }

    #[getter]
    fn evaluations(&self) -> u64 {
        self.count.load(Ordering::Relaxed)
    }

    #[getter]
    fn max_evaluations(&self) -> Option<u64> {
        self.max_evaluations
    }

    #[getter]
    fn seed(&self) -> u64 {
        self.seed
    }

    #[getter]
    fn case(&self) -> &str {
        &self.data.name
    }

    #[getter]
    fn kind(&self) -> &'static str {
        match self.data.kind {
            Kind::Albedo { .. } => "albedo",
            Kind::Product { .. } => "product",
        }
    }

    #[getter]
    fn spec(&self) -> &str {
        &self.data.spec
    }

    #[getter]
    fn theta_o(&self) -> f64 {
        self.data.theta_o
    }

    #[getter]
    fn dim(&self) -> usize {
        2
    }

    fn __repr__(&self) -> String {
        format!(
            "Integrand({:?}, evaluations={})",
            self.data.name,
            self.count.load(Ordering::Relaxed)
        )
    }
}

/// The case names of ``radiometry tradeoff``: the albedo cases, then the
/// product cases (``quick``: the CI-sized suites).
#[pyfunction]
#[pyo3(signature = (quick = false))]
pub fn case_names(quick: bool) -> Vec<String> {
    names(quick)
}
