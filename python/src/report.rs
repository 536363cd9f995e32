//! `radiometry._native.tradeoff`: the accuracy-vs-time report of the CLI,
//! returned as rows, with the rows of user integrators (measured by the
//! Python harness, `radiometry/_harness.py`) merged in. The user-facing
//! `radiometry.tradeoff` (in `radiometry/__init__.py`) wraps it.

use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use radiometry_tools::model;
use radiometry_tools::tradeoff::{self as report, ExternalRow};
use std::path::{Path, PathBuf};

/// The absolute tolerance the to-tolerance suite asks for, for a case
/// whose reference is ``reference``, at relative tolerance ``rel_tol`` (one
/// of ``TOL_TARGETS``).
#[pyfunction(name = "tolerance_for")]
pub fn py_tolerance_for(reference: f64, rel_tol: f64) -> f64 {
    report::tolerance_for(reference, rel_tol)
}

/// The output folder of a report run without ``out``: a folder under the
/// system temp dir, one per process.
#[pyfunction]
pub fn default_out() -> PathBuf {
    std::env::temp_dir().join(format!("radiometry-tradeoff-{}", std::process::id()))
}

/// One row of the harness, a dict with the fields of [`ExternalRow`].
fn external_row(d: &Bound<'_, PyAny>) -> PyResult<ExternalRow> {
    let d = d
        .cast::<PyDict>()
        .map_err(|_| PyValueError::new_err("an external row must be a dict"))?;
    // `get!(key, Type)`: the field, converted, or a ValueError naming it.
    macro_rules! get {
        ($k:expr, $t:ty) => {
            d.get_item($k)?
                .ok_or_else(|| PyValueError::new_err(format!("external row without `{}`", $k)))?
                .extract::<$t>()
                .map_err(|e| PyValueError::new_err(format!("external row field `{}`: {e}", $k)))?
        };
    }
    let text = |k: &str| -> PyResult<String> {
        let s: String = get!(k, String);
        if s.contains([',', '\n', '\r']) {
            return Err(PyValueError::new_err(format!(
                "external row field `{k}` = {s:?} contains a comma or a line break"
            )));
        }
        Ok(s)
    };
    let row = ExternalRow {
        case: text("case")?,
        integrator: text("integrator")?,
        deterministic: get!("deterministic", bool),
        budget: get!("budget", Option<u32>),
        tol: get!("tol", Option<f64>),
        evaluations: get!("evaluations", u64),
        estimate: get!("estimate", f64),
        error_estimate: get!("error_estimate", f64),
        resolved: get!("resolved", bool),
        status_reason: text("status_reason")?,
        stopped: text("stopped")?,
        seconds: get!("seconds", f64),
    };
    if row.budget.is_some() == row.tol.is_some() {
        return Err(PyValueError::new_err(format!(
            "external row of `{}` on `{}`: give exactly one of `budget` and `tol`",
            row.integrator, row.case
        )));
    }
    for (k, v) in [
        ("estimate", row.estimate),
        ("error_estimate", row.error_estimate),
        ("seconds", row.seconds),
        ("tol", row.tol.unwrap_or(1.0)),
    ] {
        if !v.is_finite() {
            return Err(PyValueError::new_err(format!(
                "external row of `{}` on `{}`: `{k}` = {v} is not finite",
                row.integrator, row.case
            )));
        }
    }
    Ok(row)
}

/// The rows of a CSV written by the report, as dicts keyed by its header
/// (integers and floats as numbers, other fields as strings); `[]` when
/// the file is absent.
fn read_rows<'py>(py: Python<'py>, path: &Path) -> PyResult<Vec<Bound<'py, PyDict>>> {
    if !path.exists() {
        return Ok(Vec::new());
    }
    let csv = std::fs::read_to_string(path)
        .map_err(|e| PyRuntimeError::new_err(format!("cannot read {}: {e}", path.display())))?;
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().unwrap_or_default().split(',').collect();
    let mut rows = Vec::new();
    for line in lines.filter(|l| !l.is_empty()) {
        let d = PyDict::new(py);
        for (k, v) in header.iter().zip(line.split(',')) {
            if let Ok(i) = v.parse::<i64>() {
                d.set_item(k, i)?;
            } else if let Ok(x) = v.parse::<f64>() {
                d.set_item(k, x)?;
            } else {
                d.set_item(k, v)?;
            }
        }
        rows.push(d);
    }
    Ok(rows)
}

/// Runs the report of ``radiometry tradeoff`` and returns ``{"budget":
/// rows of tradeoff.csv, "tolerance": rows of tolerance.csv, "out": the
/// output folder}`` (rows: lists of dicts keyed by the CSV columns). ``external``: rows of user
/// integrators measured by the harness (dicts with the fields of the Rust
/// ``ExternalRow``), merged into the tables by case name, and written to
/// ``peers_csv`` (the peers file ``radiometry tradeoff --peers`` reads) when
/// given. The GIL is released while it runs. Use ``radiometry.tradeoff``.
#[pyfunction]
#[pyo3(signature = (quick = true, out = None, threads = None, seed = model::DEFAULT_SEED, progress = false, cases = None, integrators = None, external = None, peers_csv = None))]
#[allow(clippy::too_many_arguments)]
pub fn tradeoff<'py>(
    py: Python<'py>,
    quick: bool,
    out: Option<PathBuf>,
    threads: Option<usize>,
    seed: u64,
    progress: bool,
    cases: Option<Vec<String>>,
    integrators: Option<Vec<String>>,
    external: Option<Vec<Bound<'py, PyAny>>>,
    peers_csv: Option<PathBuf>,
) -> PyResult<Bound<'py, PyDict>> {
    let out = out.unwrap_or_else(default_out);
    if threads == Some(0) {
        return Err(PyValueError::new_err("threads must be ≥ 1"));
    }
    let threads = threads.unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get()));
    let external = external
        .unwrap_or_default()
        .iter()
        .map(external_row)
        .collect::<PyResult<Vec<_>>>()?;
    if let Some(p) = &peers_csv {
        std::fs::write(p, report::external::to_csv(&external))
            .map_err(|e| PyRuntimeError::new_err(format!("cannot write {}: {e}", p.display())))?;
    }
    let opt = report::Options {
        quick,
        out: out.clone(),
        threads,
        seed,
        progress,
        cases: cases.unwrap_or_default(),
        integrators: integrators.unwrap_or_default(),
        external,
        honesty: 0,
    };
    py.detach(|| report::run(&opt)).map_err(PyRuntimeError::new_err)?;
    let d = PyDict::new(py);
    d.set_item("budget", read_rows(py, &out.join("tradeoff.csv"))?)?;
    d.set_item("tolerance", read_rows(py, &out.join("tolerance.csv"))?)?;
    d.set_item("out", out.to_string_lossy())?;
    Ok(d)
}
