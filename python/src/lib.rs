//! Python module `radiometry` (PyO3, abi3 for CPython ≥ 3.9): BRDF plugins on
//! NumPy arrays, directional albedo with every integrator of the report,
//! irradiance from light specs, the accuracy-vs-time report itself, and the
//! report's integrands as NumPy functions for integrators written in Python.
//!
//! This crate is the native part, `radiometry._native`; the package
//! `radiometry` (`pysrc/radiometry/`, maturin's mixed layout) re-exports it
//! and adds the Python parts: the harness that runs user integrators through
//! the report (locally or on a Dask cluster) and the adapters for SciPy,
//! vegas and qmcpy.
//!
//! ```python
//! import numpy as np, radiometry
//! ggx = radiometry.Brdf("ggx(alpha=1)")
//! ggx.albedo(0.0)["value"]            # 1 - ln 2 = 0.3069
//! f = ggx.eval(np.array([[0, 0, 1.0]]), np.array([[0, 0, 1.0]]))   # 1/(4π)
//! ```
//!
//! Built with maturin (`pip install ./python`). Not a member of the main Cargo
//! workspace: an `extension-module` cdylib leaves the libpython symbols to the
//! interpreter, so `cargo test --workspace` would have to link test binaries
//! without them, and the build script needs a Python interpreter — the main
//! workspace stays pure Rust.
#![forbid(unsafe_code)]

mod arrays;
mod brdf;
mod cases;
mod report;

use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use radiometry::Integrator as _;
use radiometry_spec as spec;
use radiometry_tools::model;

/// The integrator names accepted by ``Brdf.albedo(..., integrator=...)``,
/// deterministic rules first (as ``radiometry integrators``).
#[pyfunction]
fn integrators() -> Vec<&'static str> {
    model::all_integrators(model::DEFAULT_SEED, 0.0)
        .iter()
        .map(|i| i.name())
        .collect()
}

/// Every built-in method name of ``radiometry tradeoff``: the albedo
/// integrators (``integrators()``), then the product-suite methods. A user
/// integrator may not take one of these names.
#[pyfunction]
fn report_methods() -> Vec<String> {
    use radiometry_tools::tradeoff::product;
    integrators()
        .into_iter()
        .map(String::from)
        .chain(product::methods(model::DEFAULT_SEED).iter().map(|m| m.name()))
        .collect()
}

/// Irradiance E on a surface with normal +Z from a light spec (a ``+``-sum of
/// ``sky(...)``, ``directional(...)``, ``cap(...)``; angles in degrees), in
/// closed form — the value ``radiometry irradiance`` prints.
#[pyfunction]
fn irradiance(light_spec: &str) -> PyResult<f64> {
    let lights = spec::parse_lights(light_spec).map_err(|e| PyValueError::new_err(e.to_string()))?;
    Ok(lights.iter().map(|l| model::irradiance_of(l).1 as f64).sum())
}

#[pymodule]
#[pyo3(name = "_native")]
fn radiometry_module(m: &Bound<'_, PyModule>) -> PyResult<()> {
    use radiometry_tools::tradeoff as t;
    m.add_class::<brdf::Brdf>()?;
    m.add_class::<cases::CaseIntegrand>()?;
    m.add_class::<cases::CountingIntegrand>()?;
    m.add_class::<cases::CountedSide>()?;
    m.add(
        "EvaluationLimitError",
        m.py().get_type::<cases::EvaluationLimitError>(),
    )?;
    m.add_function(wrap_pyfunction!(integrators, m)?)?;
    m.add_function(wrap_pyfunction!(irradiance, m)?)?;
    m.add_function(wrap_pyfunction!(report_methods, m)?)?;
    m.add_function(wrap_pyfunction!(report::tradeoff, m)?)?;
    m.add_function(wrap_pyfunction!(report::py_tolerance_for, m)?)?;
    m.add_function(wrap_pyfunction!(report::default_out, m)?)?;
    m.add_function(wrap_pyfunction!(cases::case_names, m)?)?;
    m.add("QUICK_BUDGETS", t::QUICK_BUDGETS.to_vec())?;
    m.add("FULL_BUDGETS", t::FULL_BUDGETS.to_vec())?;
    m.add("TOL_TARGETS", t::TOL_TARGETS.to_vec())?;
    m.add("BRDF_SPEC_HELP", spec::BRDF_SPEC_HELP)?;
    m.add("LIGHT_SPEC_HELP", spec::LIGHT_SPEC_HELP)?;
    m.add("DEFAULT_SEED", model::DEFAULT_SEED)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
