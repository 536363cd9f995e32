//! NumPy input arrays of shape `(N, 3)` (directions) and `(N, 2)` (uniform
//! pairs), float32 or float64, viewed as Rust slices: a C-contiguous float32
//! array is borrowed without a copy (`bytemuck` cast of `[f32]` to `[Vec3]`);
//! anything else (float64, strided, a nested list) is converted once.

use numpy::{PyArray2, PyArrayMethods, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use radiometry::glam::Vec3;
use std::borrow::Cow;

/// A validated `(N, C)` float array, kept borrowed from Python.
pub enum Input<'py> {
    F32(PyReadonlyArray2<'py, f32>),
    F64(PyReadonlyArray2<'py, f64>),
}

fn shape_error(name: &str, cols: usize, got: &str) -> PyErr {
    PyValueError::new_err(format!(
        "`{name}` must be a float32 or float64 array of shape (N, {cols}), got {got}"
    ))
}

impl<'py> Input<'py> {
    /// Checks dtype and shape `(N, cols)`. Lists and other dtypes go through
    /// `numpy.asarray(obj, dtype=float64)`.
    pub fn new(obj: &Bound<'py, PyAny>, name: &str, cols: usize) -> PyResult<Self> {
        let input = if let Ok(a) = obj.cast::<PyArray2<f32>>() {
            Input::F32(a.readonly())
        } else if let Ok(a) = obj.cast::<PyArray2<f64>>() {
            Input::F64(a.readonly())
        } else {
            let np = obj.py().import("numpy")?;
            let converted = np
                .call_method1("asarray", (obj, "float64"))
                .map_err(|_| shape_error(name, cols, "something that is not a float array"))?;
            match converted.cast::<PyArray2<f64>>() {
                Ok(a) => Input::F64(a.readonly()),
                Err(_) => {
                    let shape: Vec<usize> = converted.getattr("shape")?.extract()?;
                    return Err(shape_error(name, cols, &format!("shape {shape:?}")));
                }
            }
        };
        let shape = match &input {
            Input::F32(a) => a.shape().to_vec(),
            Input::F64(a) => a.shape().to_vec(),
        };
        if shape[1] != cols {
            return Err(shape_error(
                name,
                cols,
                &format!("shape ({}, {})", shape[0], shape[1]),
            ));
        }
        Ok(input)
    }

    /// N.
    pub fn rows(&self) -> usize {
        match self {
            Input::F32(a) => a.shape()[0],
            Input::F64(a) => a.shape()[0],
        }
    }

    /// The rows as `[T]`, each from `cols` consecutive floats by `make`:
    /// borrowed (a `bytemuck` cast, no copy) when the array is float32 and
    /// C-contiguous, else converted in one pass (float64 rounded to nearest
    /// float32).
    fn rows_as<T: bytemuck::Pod, const C: usize>(&self, make: impl Fn([f32; C]) -> T) -> Cow<'_, [T]> {
        fn convert<X: Copy, T, const C: usize>(
            s: &[X],
            f: impl Fn(X) -> f32,
            make: impl Fn([f32; C]) -> T,
        ) -> Vec<T> {
            s.chunks_exact(C)
                .map(|c| make(core::array::from_fn(|i| f(c[i]))))
                .collect()
        }
        match self {
            // `as_slice` also accepts Fortran-ordered arrays (column-major
            // memory), so C order is checked first.
            Input::F32(a) => match a.as_slice().ok().filter(|_| a.is_c_contiguous()) {
                Some(s) => Cow::Borrowed(bytemuck::cast_slice(s)),
                None => {
                    let v: Vec<f32> = a.as_array().iter().copied().collect();
                    Cow::Owned(convert(&v, |x| x, make))
                }
            },
            Input::F64(a) => match a.as_slice().ok().filter(|_| a.is_c_contiguous()) {
                Some(s) => Cow::Owned(convert(s, |x| x as f32, make)),
                None => {
                    let v: Vec<f64> = a.as_array().iter().copied().collect();
                    Cow::Owned(convert(&v, |x| x as f32, make))
                }
            },
        }
    }

    /// The rows as directions (`cols = 3`).
    pub fn vec3(&self) -> Cow<'_, [Vec3]> {
        self.rows_as(Vec3::from_array)
    }

    /// The rows as pairs (`cols = 2`).
    pub fn pairs(&self) -> Cow<'_, [[f32; 2]]> {
        self.rows_as(|p: [f32; 2]| p)
    }
}

/// Checks that two inputs have the same number of rows.
pub fn same_rows(a: (&str, &Input<'_>), b: (&str, &Input<'_>)) -> PyResult<usize> {
    if a.1.rows() != b.1.rows() {
        return Err(PyValueError::new_err(format!(
            "`{}` has {} rows but `{}` has {}",
            a.0,
            a.1.rows(),
            b.0,
            b.1.rows()
        )));
    }
    Ok(a.1.rows())
}
