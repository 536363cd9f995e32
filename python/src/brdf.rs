//! `radiometry.Brdf`: a plugin BRDF built from a spec string, evaluated on
//! NumPy arrays through the plugin's batch kernels with the GIL released.

use crate::arrays::{Input, same_rows};
use numpy::{PyArray1, PyArray2, PyArrayMethods};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use radiometry::glam::Vec3;
use radiometry::integrator::{DEFAULT_MAX_BUDGET, DirectionalAlbedo, Integrator, integrate_to_tolerance};
use radiometry::{Brdf as _, BrdfSample, Spectrum, WideSpectrum};
use radiometry_spec as spec;
use radiometry_tools::model::{self, AnyBrdf, AnyBrdfRgb};
use std::time::Instant;

/// A BRDF from a spec such as ``ggx(alpha=0.1, fresnel=schlick(f0=0.04))``
/// (the grammar of the ``radiometry`` command line; ``radiometry.BRDF_SPEC_HELP``).
/// Directions are in the local frame (normal +Z), pointing away from the surface.
///
/// Colour: a spec with an ``rgb(R, G, B)`` colour that is not grey, a named
/// metal (``conductor(metal=Au)``) or a MERL file is evaluated per channel
/// (linear sRGB; ``channels == 3``): ``eval`` returns shape (N, 3), ``sample``'s
/// weight (N, 3), ``albedo``'s value and error are lists of 3. A grey spec, or
/// any spec built with ``mono=True`` (each colour by its Rec. 709 luminance,
/// a metal by the luminance of its reflectance), has ``channels == 1`` and the
/// shapes (N,) and floats of a monochrome BRDF.
#[pyclass(frozen, module = "radiometry")]
pub struct Brdf {
    spec: String,
    brdf: Inner,
}

/// The run-time BRDF: monochrome (grey specs, ``mono=True``) or RGB.
enum Inner {
    Mono(AnyBrdf),
    Rgb(AnyBrdfRgb),
}

/// Runs `$body` with `$b` bound to the monochrome or the RGB BRDF.
macro_rules! with_brdf {
    ($inner:expr, $b:ident => $body:expr) => {
        match $inner {
            Inner::Mono($b) => $body,
            Inner::Rgb($b) => $body,
        }
    };
}

/// A spectrum's channels as `f32`s, appended to `out`.
fn push_channels<S: Spectrum>(out: &mut Vec<f32>, s: S) {
    out.extend((0..S::CHANNELS).map(|c| s.channel(c)));
}

/// `n` rows of `channels` values: shape (N,) for one channel, (N, C) otherwise.
fn rows_array<'py>(py: Python<'py>, v: Vec<f32>, n: usize, channels: usize) -> PyResult<Bound<'py, PyAny>> {
    let a = PyArray1::from_vec(py, v);
    if channels == 1 {
        Ok(a.into_any())
    } else {
        Ok(a.reshape([n, channels])?.into_any())
    }
}

/// A wide result: a float (one channel) or a list of the channels.
fn wide_py<'py, W: WideSpectrum>(py: Python<'py>, w: &W, channels: usize) -> PyResult<Bound<'py, PyAny>> {
    if channels == 1 {
        Ok(w.channel(0).into_pyobject(py)?.into_any())
    } else {
        let v: Vec<f64> = (0..channels).map(|c| w.channel(c)).collect();
        Ok(v.into_pyobject(py)?.into_any())
    }
}

/// `(θ, 0)` in degrees → unit direction, as the CLI's `dir`.
fn dir(theta_deg: f64) -> Vec3 {
    let t = theta_deg.to_radians();
    Vec3::new(t.sin() as f32, 0.0, t.cos() as f32)
}

#[pymethods]
impl Brdf {
    /// ``mono=True`` builds the monochrome BRDF (one channel) even for a
    /// colour spec.
    #[new]
    #[pyo3(signature = (spec, mono = false))]
    fn new(spec: &str, mono: bool) -> PyResult<Self> {
        let parsed = spec::parse_brdf(spec).map_err(|e| PyValueError::new_err(e.to_string()))?;
        let err = |e: spec::SpecError| PyValueError::new_err(e.to_string());
        let brdf = if mono || parsed.is_grey() {
            Inner::Mono(model::build_brdf(spec, &parsed).map_err(err)?)
        } else {
            Inner::Rgb(model::build_brdf_rgb(spec, &parsed).map_err(err)?)
        };
        Ok(Brdf {
            spec: spec.to_string(),
            brdf,
        })
    }

    /// Values per evaluation: 1 (monochrome) or 3 (R, G, B, linear sRGB).
    #[getter]
    fn channels(&self) -> usize {
        match self.brdf {
            Inner::Mono(_) => 1,
            Inner::Rgb(_) => 3,
        }
    }

    /// The spec string it was built from.
    #[getter]
    fn spec(&self) -> &str {
        &self.spec
    }

    fn __repr__(&self) -> String {
        format!("Brdf({:?})", self.spec)
    }

    /// ``f_r(wi[k] → wo[k])`` in 1/sr for arrays of shape (N, 3) (float32 or
    /// float64; float64 is rounded to float32). Returns float32 of shape (N,)
    /// (one channel) or (N, 3) (R, G, B; see ``channels``). Arrays with
    /// different N are a ``ValueError``.
    fn eval<'py>(
        &self,
        py: Python<'py>,
        wi: &Bound<'py, PyAny>,
        wo: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let (wi, wo) = (Input::new(wi, "wi", 3)?, Input::new(wo, "wo", 3)?);
        let n = same_rows(("wi", &wi), ("wo", &wo))?;
        let (wi, wo) = (wi.vec3(), wo.vec3());
        let out = py.detach(|| with_brdf!(&self.brdf, b => eval_flat(b, &wi, &wo)));
        rows_array(py, out, n, self.channels())
    }

    /// The solid-angle density with which ``sample`` draws ``wi`` given ``wo``;
    /// arrays of shape (N, 3), float32 result of shape (N,).
    fn pdf<'py>(
        &self,
        py: Python<'py>,
        wi: &Bound<'py, PyAny>,
        wo: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyArray1<f32>>> {
        let (wi, wo) = (Input::new(wi, "wi", 3)?, Input::new(wo, "wo", 3)?);
        let n = same_rows(("wi", &wi), ("wo", &wo))?;
        let (wi, wo) = (wi.vec3(), wo.vec3());
        let out = py.detach(|| {
            let mut out = vec![0.0f32; n];
            with_brdf!(&self.brdf, b => b.pdf_batch(&wi, &wo, &mut out));
            out
        });
        Ok(PyArray1::from_vec(py, out))
    }

    /// Importance samples: ``wo`` of shape (N, 3), ``u`` uniform in [0, 1) of
    /// shape (N, 2). Returns ``(wi, pdf, weight)`` (float32, shapes (N, 3),
    /// (N,), and (N,) or (N, 3) as ``eval``) with ``weight = f_r cos θi /
    /// pdf``; ``pdf = 0`` (and ``wi = weight = 0``) where the plugin draws no
    /// sample (``wo`` below the horizon).
    #[allow(clippy::type_complexity)]
    fn sample<'py>(
        &self,
        py: Python<'py>,
        wo: &Bound<'py, PyAny>,
        u: &Bound<'py, PyAny>,
    ) -> PyResult<(
        Bound<'py, PyArray2<f32>>,
        Bound<'py, PyArray1<f32>>,
        Bound<'py, PyAny>,
    )> {
        let (wo, u) = (Input::new(wo, "wo", 3)?, Input::new(u, "u", 2)?);
        let n = same_rows(("wo", &wo), ("u", &u))?;
        let (wo, u) = (wo.vec3(), u.pairs());
        let (wi, pdf, weight) = py.detach(|| with_brdf!(&self.brdf, b => sample_flat(b, &wo, &u)));
        let wi = PyArray1::from_vec(py, wi).reshape([n, 3])?;
        let weight = rows_array(py, weight, n, self.channels())?;
        Ok((wi, PyArray1::from_vec(py, pdf), weight))
    }

    /// ``f_r(wi → wo)`` for one pair through the scalar ``Brdf::eval`` (each
    /// argument a sequence of 3 numbers, rounded to float32): a float, or a
    /// list of 3 (R, G, B) for a colour BRDF. For checks against the batch
    /// path.
    fn eval_one<'py>(&self, py: Python<'py>, wi: [f32; 3], wo: [f32; 3]) -> PyResult<Bound<'py, PyAny>> {
        let (wi, wo) = (Vec3::from_array(wi), Vec3::from_array(wo));
        match &self.brdf {
            Inner::Mono(b) => Ok(b.eval(wi, wo).into_pyobject(py)?.into_any()),
            Inner::Rgb(b) => Ok(b.eval(wi, wo).to_array().to_vec().into_pyobject(py)?.into_any()),
        }
    }

    /// Directional albedo ρ(θo) = ∫ f_r(ωi, ωo) cos θi dωi at ``theta_o_deg``
    /// ∈ [0, 90] with the named integrator (``radiometry.integrators()``; the
    /// default, as in the CLI, is ``auto``, which picks the parameterisation
    /// from the integrand and carries an a-posteriori error estimate), either
    /// one run with ``budget`` evaluations (default 4096) or, with ``tol``,
    /// refined until the estimate is resolved, its error ≤ tol and confirmed
    /// beyond one run (``integrate_to_tolerance``; at most 2^22 evaluations in
    /// the last run). Returns a dict like ``radiometry albedo --format json``:
    /// value, error (floats, or lists of 3 for a colour BRDF: per channel,
    /// and then ``channels`` is ``"linear-srgb"``), evaluations, seconds, integrator, budget,
    /// final_run_evaluations, status (``"resolved"`` or ``"unresolved"``: the
    /// estimate cannot be trusted) and status_reason (empty when resolved), and
    /// with ``tol``: stopped (``"tolerance reached"``, ``"max budget
    /// reached"``, ``"integrator cap reached"``, ``"out of reach"``), runs,
    /// confirmation (how far the answer moved from the run that confirmed it;
    /// ``None`` unless the tolerance was reached), tol, max_budget.
    #[pyo3(signature = (theta_o_deg, integrator = "auto", budget = None, tol = None, seed = model::DEFAULT_SEED))]
    fn albedo<'py>(
        &self,
        py: Python<'py>,
        theta_o_deg: f64,
        integrator: &str,
        budget: Option<u32>,
        tol: Option<f64>,
        seed: u64,
    ) -> PyResult<Bound<'py, PyDict>> {
        // The checks and messages of `radiometry albedo`.
        if !(0.0..=90.0).contains(&theta_o_deg) {
            return Err(PyValueError::new_err(format!(
                "--theta-o {theta_o_deg} is outside [0, 90] degrees"
            )));
        }
        if budget.is_some() && tol.is_some() {
            return Err(PyValueError::new_err("give either `budget` or `tol`, not both"));
        }
        if let Some(t) = tol
            && !(t.is_finite() && t > 0.0)
        {
            return Err(PyValueError::new_err(format!(
                "--tol {t} must be a positive finite number"
            )));
        }
        let Some(integ) = model::integrator_by_name(integrator, seed, tol.unwrap_or(0.0)) else {
            let names: Vec<_> = model::all_integrators(seed, 0.0)
                .iter()
                .map(|i| i.name())
                .collect();
            return Err(PyValueError::new_err(format!(
                "unknown integrator `{integrator}`; expected one of: {}",
                names.join(", ")
            )));
        };
        with_brdf!(&self.brdf, b => albedo_dict(py, b, &integ, theta_o_deg, budget, tol))
    }

    /// Seconds per call of the Rust batch path (`eval_batch`) on the same
    /// arrays, minimum over `repeats` calls, with no Python in the loop: the
    /// in-run reference for ``Brdf.eval``'s throughput (``python/bench.py``).
    #[pyo3(signature = (wi, wo, repeats = 5))]
    fn rust_eval_batch_seconds(
        &self,
        py: Python<'_>,
        wi: &Bound<'_, PyAny>,
        wo: &Bound<'_, PyAny>,
        repeats: usize,
    ) -> PyResult<f64> {
        let (wi, wo) = (Input::new(wi, "wi", 3)?, Input::new(wo, "wo", 3)?);
        let n = same_rows(("wi", &wi), ("wo", &wo))?;
        // Owned copies: the reference excludes the input conversion.
        let (wi, wo) = (wi.vec3().into_owned(), wo.vec3().into_owned());
        Ok(py.detach(|| with_brdf!(&self.brdf, b => eval_batch_seconds(b, &wi, &wo, n, repeats))))
    }
}

/// `eval_batch` into a flat vector of `n · CHANNELS` floats.
fn eval_flat<S: Spectrum>(b: &AnyBrdf<S>, wi: &[Vec3], wo: &[Vec3]) -> Vec<f32> {
    let mut out = vec![S::zero(); wi.len()];
    b.eval_batch(wi, wo, &mut out);
    let mut flat = Vec::with_capacity(S::CHANNELS * out.len());
    for v in out {
        push_channels(&mut flat, v);
    }
    flat
}

/// `sample_batch` as flat `(wi, pdf, weight)` vectors (`weight`: `n · CHANNELS`).
fn sample_flat<S: Spectrum>(b: &AnyBrdf<S>, wo: &[Vec3], u: &[[f32; 2]]) -> (Vec<f32>, Vec<f32>, Vec<f32>) {
    let n = wo.len();
    let mut s: Vec<Option<BrdfSample<S>>> = vec![None; n];
    b.sample_batch(wo, u, &mut s);
    let mut wi = Vec::with_capacity(3 * n);
    let mut pdf = Vec::with_capacity(n);
    let mut weight = Vec::with_capacity(S::CHANNELS * n);
    for s in &s {
        match s {
            Some(s) => {
                wi.extend_from_slice(&s.wi.to_array());
                pdf.push(s.pdf);
                push_channels(&mut weight, s.weight);
            }
            None => {
                wi.extend_from_slice(&[0.0; 3]);
                pdf.push(0.0);
                push_channels(&mut weight, S::zero());
            }
        }
    }
    (wi, pdf, weight)
}

/// Seconds of the fastest of `repeats` `eval_batch` calls.
fn eval_batch_seconds<S: Spectrum>(
    b: &AnyBrdf<S>,
    wi: &[Vec3],
    wo: &[Vec3],
    n: usize,
    repeats: usize,
) -> f64 {
    let mut out = vec![S::zero(); n];
    let mut best = f64::INFINITY;
    for _ in 0..repeats.max(1) {
        let t0 = Instant::now();
        b.eval_batch(wi, wo, &mut out);
        best = best.min(t0.elapsed().as_secs_f64());
        std::hint::black_box(&out);
    }
    best
}

/// `Brdf.albedo` with the run-time BRDF chosen (monochrome or RGB).
fn albedo_dict<'py, S: Spectrum>(
    py: Python<'py>,
    brdf: &AnyBrdf<S>,
    integ: &model::AnyIntegrator,
    theta_o_deg: f64,
    budget: Option<u32>,
    tol: Option<f64>,
) -> PyResult<Bound<'py, PyDict>>
where
    S::Wide: Send,
{
    let g = DirectionalAlbedo {
        brdf,
        wo: dir(theta_o_deg),
    };
    let run = py.detach(|| {
        let t0 = Instant::now();
        let r = match tol {
            Some(t) => integrate_to_tolerance(integ, &g, t, 64, DEFAULT_MAX_BUDGET)
                .map(|o| (o.estimate, o.budget, Some(o), o.total_evaluations)),
            None => {
                let b = budget.unwrap_or(4096);
                integ.integrate(&g, b).map(|e| (e, b, None, e.evaluations))
            }
        };
        (r, t0.elapsed().as_secs_f64())
    });
    let ((est, used_budget, stopped, total), secs) = match run {
        (Ok(r), secs) => (r, secs),
        (Err(e), _) => return Err(PyValueError::new_err(format!("{}: {e}", integ.name()))),
    };
    let d = PyDict::new(py);
    let ch = S::CHANNELS;
    d.set_item("value", wide_py(py, &est.value, ch)?)?;
    d.set_item("error", wide_py(py, &est.error, ch)?)?;
    if ch > 1 {
        d.set_item("channels", "linear-srgb")?;
    }
    d.set_item("evaluations", total)?;
    d.set_item("seconds", secs)?;
    d.set_item("integrator", integ.name())?;
    d.set_item("budget", used_budget)?;
    d.set_item("final_run_evaluations", est.evaluations)?;
    d.set_item("status", est.status.as_str())?;
    d.set_item("status_reason", est.status.reason())?;
    if let Some(o) = stopped {
        d.set_item("stopped", o.stop.as_str())?;
        d.set_item("runs", o.runs)?;
        let c = o.confirmation.as_ref().map(|c| wide_py(py, c, ch)).transpose()?;
        d.set_item("confirmation", c)?;
        d.set_item("tol", tol.unwrap_or(0.0))?;
        d.set_item("max_budget", DEFAULT_MAX_BUDGET)?;
    }
    Ok(d)
}
