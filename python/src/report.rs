//! `radiometry.tradeoff`: the accuracy-vs-time report of the CLI, returned as
//! rows.

use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use radiometry_cli::model;
use radiometry_cli::tradeoff as report;
use std::path::PathBuf;

/// Runs the report of ``radiometry tradeoff`` (``quick``: the CI-sized suite)
/// and returns its ``tradeoff.csv`` as a list of dicts, one per row, keyed by
/// the CSV columns (case, integrator, budget, evaluations, estimate,
/// reference, abs_error, rel_error, error_estimate, seconds, ...): integers
/// and floats as numbers, names as strings. The CSV, plots and summary.md
/// are written to ``out`` (default: a folder under the system temp dir); the
/// summary table is printed on stdout as by the CLI. ``cases`` /
/// ``integrators``: keep only names containing one of these substrings (the
/// CLI's ``--cases`` / ``--integrators``). The GIL is released while it runs.
#[pyfunction]
#[pyo3(signature = (quick = true, out = None, threads = None, seed = model::DEFAULT_SEED, progress = false, cases = None, integrators = None))]
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
) -> PyResult<Vec<Bound<'py, PyDict>>> {
    let out = out
        .unwrap_or_else(|| std::env::temp_dir().join(format!("radiometry-tradeoff-{}", std::process::id())));
    if threads == Some(0) {
        return Err(PyValueError::new_err("threads must be ≥ 1"));
    }
    let threads = threads.unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get()));
    let opt = report::Options {
        quick,
        out: out.clone(),
        threads,
        seed,
        progress,
        cases: cases.unwrap_or_default(),
        integrators: integrators.unwrap_or_default(),
        external: Vec::new(),
    };
    py.detach(|| report::run(&opt)).map_err(PyRuntimeError::new_err)?;
    let path = out.join("tradeoff.csv");
    let csv = std::fs::read_to_string(&path)
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
