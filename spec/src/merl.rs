//! MERL `.binary` BRDF files: reader, writer, and tabulation of analytic
//! BRDFs on the Rusinkiewicz grid.
//!
//! # Format (Matusik, Pfister, Brand & McMillan 2003, "A Data-Driven Reflectance Model")
//!
//! ```text
//! i32 LE  n_theta_h, n_theta_d, n_phi_d          (90, 90, 180 for MERL data)
//! f64 LE  red[n], green[n], blue[n]              n = n_theta_h · n_theta_d · n_phi_d
//! ```
//!
//! each block in the flat order of [`RusinkiewiczGrid::index`] (φd fastest).
//! Stored values are `f_r / scale` with the per-channel scales
//! [`SCALES`] = (1/1500, 1.15/1500, 1.66/1500): [`read`] multiplies by them,
//! [`write()`] divides. Any positive dimensions that form a valid
//! [`RusinkiewiczGrid`] are accepted (the MERL layout is the standard case).
//!
//! # Missing values
//!
//! Negative entries mark missing measurements (in MERL data, mostly
//! configurations below the horizon). [`read`] replaces each by **0** and
//! counts them ([`MerlTable::missing`]); 0 is also what a BRDF is below the
//! horizon, and it keeps the table a valid input of
//! [`Tabulated::new`](radiometry_brdfs::tabulated::Tabulated::new). NaN or
//! infinite entries are an error ([`MerlError::NotFinite`]), never replaced.
//!
//! # Example
//!
//! ```
//! use radiometry_brdfs::{Ggx, HeightCorrelated, Microfacet, NoFresnel};
//! use radiometry_brdfs::tabulated::RusinkiewiczGrid;
//! use radiometry_spec::merl;
//!
//! let ggx = Microfacet::<_, HeightCorrelated, _>::new(Ggx::new(0.3)?, NoFresnel);
//! let grid = RusinkiewiczGrid::new(16, 16, 8)?;
//! let table = merl::tabulate(&ggx, grid)?;
//! let bytes = merl::to_bytes(&table);
//! let back = merl::from_bytes(&bytes)?;
//! assert_eq!(back.values, table.values);
//! assert!(merl::from_bytes(&bytes[..100]).is_err());
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use radiometry::Brdf;
use radiometry::Spectrum;
use radiometry::glam::Vec3;
use radiometry_brdfs::tabulated::{RusinkiewiczGrid, TabulatedError};
use std::collections::HashMap;
use std::fmt;
use std::path::{Path, PathBuf};
use std::sync::{Mutex, OnceLock};

/// Per-channel scales of MERL files: a stored value times its channel's
/// scale is `f_r` [sr⁻¹] (red, green, blue).
pub const SCALES: [f64; 3] = [1.0 / 1500.0, 1.15 / 1500.0, 1.66 / 1500.0];

/// Bytes of the header (three `i32`).
pub const HEADER_BYTES: usize = 12;

/// An RGB table on a Rusinkiewicz grid, in `f_r` units [sr⁻¹].
#[derive(Clone, Debug, PartialEq)]
pub struct MerlTable {
    /// The grid (from the file header).
    pub grid: RusinkiewiczGrid,
    /// One RGB value per grid node, flat order of [`RusinkiewiczGrid::index`].
    pub values: Vec<Vec3>,
    /// Negative (missing) entries replaced by 0, over all three channels.
    pub missing: usize,
}

/// Why a MERL file cannot be read or written.
#[derive(Debug)]
#[non_exhaustive]
pub enum MerlError {
    /// Reading or writing the file failed.
    Io {
        /// The file.
        path: PathBuf,
        /// The I/O error.
        source: std::io::Error,
    },
    /// The data are shorter (or longer) than the header announces.
    Length {
        /// Bytes the header implies (`12 + 24 n`), or 12 when the header
        /// itself is incomplete.
        expected: usize,
        /// Bytes found.
        found: usize,
    },
    /// The header dimensions do not form a valid grid.
    Dims {
        /// The three header values.
        dims: [i32; 3],
        /// Why (the grid's error).
        source: Option<TabulatedError>,
    },
    /// A stored value is NaN or infinite.
    NotFinite {
        /// Channel (0 red, 1 green, 2 blue).
        channel: usize,
        /// Flat index in the channel block.
        index: usize,
    },
    /// A value is too large for `f32` after scaling, or (writer) not a
    /// finite non-negative number.
    OutOfRange {
        /// Channel.
        channel: usize,
        /// Flat index.
        index: usize,
        /// The value.
        value: f64,
    },
    /// The BRDF to tabulate has a channel count other than 1 or 3.
    Channels {
        /// `Spectrum::CHANNELS`.
        channels: usize,
    },
}

impl fmt::Display for MerlError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            MerlError::Io { path, source } => write!(f, "{}: {source}", path.display()),
            MerlError::Length { expected, found } if *expected == HEADER_BYTES => write!(
                f,
                "truncated MERL file: {found} bytes, shorter than the {HEADER_BYTES}-byte header"
            ),
            MerlError::Length { expected, found } => write!(
                f,
                "MERL file has {found} bytes, its header implies {expected} (12-byte header + 3 x 8 bytes per node)"
            ),
            MerlError::Dims {
                dims: [a, b, c],
                source,
            } => {
                write!(f, "MERL header dimensions {a} x {b} x {c} are invalid")?;
                if let Some(e) = source {
                    write!(f, ": {e}")?;
                }
                Ok(())
            }
            MerlError::NotFinite { channel, index } => {
                write!(f, "MERL value {index} of channel {channel} is not finite")
            }
            MerlError::OutOfRange {
                channel,
                index,
                value,
            } => {
                write!(
                    f,
                    "MERL value {index} of channel {channel} = {value:e} is out of range"
                )
            }
            MerlError::Channels { channels } => {
                write!(
                    f,
                    "cannot tabulate a {channels}-channel BRDF as RGB (1 or 3 channels)"
                )
            }
        }
    }
}

impl std::error::Error for MerlError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            MerlError::Io { source, .. } => Some(source),
            MerlError::Dims { source: Some(e), .. } => Some(e),
            _ => None,
        }
    }
}

/// Reads a MERL file (see the [module documentation](self)).
///
/// # Errors
/// [`MerlError::Io`] when the file cannot be read; otherwise those of
/// [`from_bytes`].
pub fn read(path: &Path) -> Result<MerlTable, MerlError> {
    let bytes = std::fs::read(path).map_err(|source| MerlError::Io {
        path: path.to_path_buf(),
        source,
    })?;
    from_bytes(&bytes)
}

/// Parses the bytes of a MERL file.
///
/// # Errors
/// [`MerlError::Length`] for a truncated file or trailing bytes,
/// [`MerlError::Dims`] for header dimensions that are not a valid grid,
/// [`MerlError::NotFinite`] for a NaN or infinite value,
/// [`MerlError::OutOfRange`] for a value that overflows `f32` after scaling.
pub fn from_bytes(bytes: &[u8]) -> Result<MerlTable, MerlError> {
    let header = bytes.get(..HEADER_BYTES).ok_or(MerlError::Length {
        expected: HEADER_BYTES,
        found: bytes.len(),
    })?;
    let mut dims = [0i32; 3];
    for (d, c) in dims.iter_mut().zip(header.chunks_exact(4)) {
        *d = i32::from_le_bytes([c[0], c[1], c[2], c[3]]);
    }
    let as_usize = |d: i32| usize::try_from(d).ok();
    let grid = match (as_usize(dims[0]), as_usize(dims[1]), as_usize(dims[2])) {
        (Some(a), Some(b), Some(c)) => RusinkiewiczGrid::new(a, b, c).map_err(|e| MerlError::Dims {
            dims,
            source: Some(e),
        })?,
        _ => return Err(MerlError::Dims { dims, source: None }),
    };
    let n = grid.len();
    let expected = HEADER_BYTES + 3 * 8 * n;
    if bytes.len() != expected {
        return Err(MerlError::Length {
            expected,
            found: bytes.len(),
        });
    }
    let mut values = vec![Vec3::ZERO; n];
    let mut missing = 0;
    let body = &bytes[HEADER_BYTES..];
    for (channel, block) in body.chunks_exact(8 * n).enumerate() {
        let scale = SCALES[channel];
        for (index, (c, v)) in block.chunks_exact(8).zip(values.iter_mut()).enumerate() {
            let raw = f64::from_le_bytes([c[0], c[1], c[2], c[3], c[4], c[5], c[6], c[7]]);
            if !raw.is_finite() {
                return Err(MerlError::NotFinite { channel, index });
            }
            let x = if raw < 0.0 {
                missing += 1;
                0.0
            } else {
                raw * scale
            };
            if x > radiometry_brdfs::tabulated::MAX_VALUE as f64 {
                return Err(MerlError::OutOfRange {
                    channel,
                    index,
                    value: raw,
                });
            }
            v[channel] = x as f32;
        }
    }
    Ok(MerlTable {
        grid,
        values,
        missing,
    })
}

/// The bytes of a MERL file holding `table` (values divided by [`SCALES`]).
pub fn to_bytes(table: &MerlTable) -> Vec<u8> {
    let n = table.values.len();
    let mut out = Vec::with_capacity(HEADER_BYTES + 24 * n);
    for d in table.grid.dims() {
        // Grid axes are ≤ 4096 (RusinkiewiczGrid::new), so they fit an i32.
        out.extend_from_slice(&(d as i32).to_le_bytes());
    }
    for (channel, scale) in SCALES.iter().enumerate() {
        for v in &table.values {
            out.extend_from_slice(&(v[channel] as f64 / scale).to_le_bytes());
        }
    }
    out
}

/// Writes `table` as a MERL file.
///
/// # Errors
/// [`MerlError::Io`] when the file cannot be written;
/// [`MerlError::Length`] when `table.values` does not match its grid.
pub fn write(path: &Path, table: &MerlTable) -> Result<(), MerlError> {
    if table.values.len() != table.grid.len() {
        return Err(MerlError::Length {
            expected: HEADER_BYTES + 24 * table.grid.len(),
            found: HEADER_BYTES + 24 * table.values.len(),
        });
    }
    std::fs::write(path, to_bytes(table)).map_err(|source| MerlError::Io {
        path: path.to_path_buf(),
        source,
    })
}

/// Tabulates `brdf` on `grid`: the value at node `(i, j, k)` is
/// `brdf.eval(ωi, ωo)` at [`RusinkiewiczGrid::node_directions`] (0 where a
/// direction is below the horizon, as every plugin returns there). A
/// monochrome BRDF is replicated to the three channels; an RGB BRDF keeps
/// its channels.
///
/// # Errors
/// [`MerlError::Channels`] for spectra with other channel counts,
/// [`MerlError::OutOfRange`] for a negative, non-finite or huge value
/// (a BRDF breaking its contract).
pub fn tabulate<B: Brdf>(brdf: &B, grid: RusinkiewiczGrid) -> Result<MerlTable, MerlError> {
    let channels = <B::Spectrum as Spectrum>::CHANNELS;
    if channels != 1 && channels != 3 {
        return Err(MerlError::Channels { channels });
    }
    let [nh, nd, np] = grid.dims();
    let mut values = vec![Vec3::ZERO; grid.len()];
    for i in 0..nh {
        for j in 0..nd {
            for k in 0..np {
                let (wi, wo) = grid.node_directions(i, j, k);
                let f = brdf.eval(wi, wo);
                let index = grid.index(i, j, k);
                let v = Vec3::from_array(std::array::from_fn(|c| f.channel(c.min(channels - 1))));
                for c in 0..3 {
                    let x = v[c];
                    if !(x.is_finite() && (0.0..=radiometry_brdfs::tabulated::MAX_VALUE).contains(&x)) {
                        return Err(MerlError::OutOfRange {
                            channel: c,
                            index,
                            value: x as f64,
                        });
                    }
                }
                values[index] = v;
            }
        }
    }
    Ok(MerlTable {
        grid,
        values,
        missing: 0,
    })
}

/// Rec. 709 luminance weights of linear RGB: the monochrome value the
/// CLI's `tabulated(file=…)` BRDF uses, `Y = 0.2126 R + 0.7152 G + 0.0722 B`
/// (ITU-R BT.709-6, item 3.2).
pub const LUMINANCE: [f32; 3] = [0.2126, 0.7152, 0.0722];

/// The monochrome [`Tabulated`](radiometry_brdfs::tabulated::Tabulated)
/// BRDF (Rec. 709 luminance of the RGB table, [`LUMINANCE`]) of a MERL
/// file, with half-vector sampling: what `tabulated(file=PATH)` builds in
/// the monochrome run-time BRDF ([`build_brdf`](crate::build_brdf)).
///
/// The plugin borrows its table, and the CLI's type-erased BRDFs are
/// `'static`, so the table and sampling buffer are leaked (kept for the
/// process lifetime) and cached by (canonical path, size, modification
/// time): building the same unchanged file again reuses them, so the
/// memory held is bounded by the number of distinct files (≈ 5.8 MB for a
/// 90 × 90 × 180 table; ≈ 17 MB more for its RGB form,
/// [`load_tabulated_rgb`]).
///
/// # Errors
/// A message naming the file and the [`MerlError`] or
/// [`TabulatedError`] (missing file, truncated, bad dimensions, NaN).
pub fn load_tabulated(path: &str) -> Result<radiometry_brdfs::tabulated::Tabulated<'static, f32>, String> {
    static CACHE: Cache<f32> = OnceLock::new();
    load_cached(path, &CACHE, |v| {
        LUMINANCE[0] * v.x + LUMINANCE[1] * v.y + LUMINANCE[2] * v.z
    })
}

/// The RGB [`Tabulated`](radiometry_brdfs::tabulated::Tabulated) BRDF of a
/// MERL file (its three channels, in `f_r` units), with half-vector sampling
/// (whose density follows the channels' average): what `tabulated(file=PATH)`
/// builds in the RGB run-time BRDF
/// ([`build_brdf_rgb`](crate::model::build_brdf_rgb)). Leaked and cached as
/// [`load_tabulated`] (its own cache).
///
/// # Errors
/// As [`load_tabulated`].
pub fn load_tabulated_rgb(
    path: &str,
) -> Result<radiometry_brdfs::tabulated::Tabulated<'static, Vec3>, String> {
    static CACHE: Cache<Vec3> = OnceLock::new();
    load_cached(path, &CACHE, |v| v)
}

type CacheKey = (PathBuf, u64, Option<std::time::SystemTime>);
type Cache<S> = OnceLock<Mutex<HashMap<CacheKey, radiometry_brdfs::tabulated::Tabulated<'static, S>>>>;

/// Reads the MERL file at `path` (or takes it from `cache`), converts each
/// RGB entry with `convert`, leaks the values and the sampling buffer.
fn load_cached<S: Spectrum>(
    path: &str,
    cache: &'static Cache<S>,
    convert: impl Fn(Vec3) -> S,
) -> Result<radiometry_brdfs::tabulated::Tabulated<'static, S>, String> {
    use radiometry_brdfs::tabulated::Tabulated;
    let p = Path::new(path);
    let meta = std::fs::metadata(p).map_err(|e| format!("cannot read MERL file `{path}`: {e}"))?;
    let canonical = std::fs::canonicalize(p).unwrap_or_else(|_| p.to_path_buf());
    let key = (canonical, meta.len(), meta.modified().ok());
    let cache = cache.get_or_init(|| Mutex::new(HashMap::new()));
    if let Some(t) = cache.lock().ok().and_then(|c| c.get(&key).copied()) {
        return Ok(t);
    }
    let table = read(p).map_err(|e| format!("cannot read MERL file `{path}`: {e}"))?;
    let converted: Vec<S> = table.values.iter().map(|&v| convert(v)).collect();
    let values: &'static [S] = Vec::leak(converted);
    let buf: &'static mut [f32] = Vec::leak(vec![0.0f32; Tabulated::<S>::sampling_buffer_len(&table.grid)]);
    let t = Tabulated::new(table.grid, values)
        .and_then(|t| t.with_sampling(buf))
        .map_err(|e| format!("invalid table in `{path}`: {e}"))?;
    if let Ok(mut c) = cache.lock() {
        c.insert(key, t);
    }
    Ok(t)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn header(dims: [i32; 3]) -> Vec<u8> {
        dims.iter().flat_map(|d| d.to_le_bytes()).collect()
    }

    #[test]
    fn missing_values_become_zero_and_are_counted() {
        let mut b = header([2, 2, 2]);
        for c in 0..3 {
            for i in 0..8 {
                let v: f64 = if i == 3 {
                    -1.0
                } else {
                    1500.0 * (i as f64 + c as f64)
                };
                b.extend_from_slice(&v.to_le_bytes());
            }
        }
        let t = from_bytes(&b).unwrap();
        assert_eq!(t.missing, 3);
        assert_eq!(t.values[3], Vec3::ZERO);
        // value × scale: red 1500·5/1500 = 5, green 1500·6·1.15/1500, blue 1500·7·1.66/1500.
        assert_eq!(
            t.values[5],
            Vec3::new(5.0, (6.0f64 * 1.15) as f32, (7.0f64 * 1.66) as f32)
        );
    }

    #[test]
    fn malformed_files_are_typed_errors() {
        assert!(matches!(
            from_bytes(&[]),
            Err(MerlError::Length {
                expected: 12,
                found: 0
            })
        ));
        assert!(matches!(from_bytes(&[1, 2, 3]), Err(MerlError::Length { .. })));
        for dims in [[0, 90, 180], [-90, 90, 180], [90, 90, i32::MAX], [4097, 1, 1]] {
            let e = from_bytes(&header(dims)).unwrap_err();
            assert!(matches!(e, MerlError::Dims { .. }), "{dims:?}: {e}");
            assert!(e.to_string().contains("dimensions"), "{e}");
        }
        let mut b = header([1, 1, 2]);
        b.extend_from_slice(&[0u8; 47]);
        let e = from_bytes(&b).unwrap_err();
        assert!(
            matches!(
                e,
                MerlError::Length {
                    expected: 60,
                    found: 59
                }
            ),
            "{e}"
        );
        b.extend_from_slice(&[0u8; 2]);
        assert!(matches!(
            from_bytes(&b),
            Err(MerlError::Length {
                expected: 60,
                found: 61
            })
        ));
        for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            let mut b = header([1, 1, 2]);
            for i in 0..6 {
                b.extend_from_slice(&(if i == 4 { bad } else { 1.0 }).to_le_bytes());
            }
            let e = from_bytes(&b).unwrap_err();
            assert!(matches!(e, MerlError::NotFinite { channel: 2, index: 0 }), "{e}");
        }
        let mut b = header([1, 1, 1]);
        for v in [1e300f64, 1.0, 1.0] {
            b.extend_from_slice(&v.to_le_bytes());
        }
        assert!(matches!(from_bytes(&b), Err(MerlError::OutOfRange { .. })));
        let e = read(Path::new("/nonexistent/x.binary")).unwrap_err();
        assert!(matches!(e, MerlError::Io { .. }) && e.to_string().contains("/nonexistent/x.binary"));
    }
}
