//! Colour architectures: Bayer colour filter array with demosaicing
//! (bilinear and Malvar–He–Cutler), a 3-chip dichroic prism, a filter
//! wheel (time-multiplexed filters) and stacked layers (Foveon-like
//! depth-dependent absorption in silicon).
//!
//! Images are row-major caller buffers: `raw[y·w + x]` for a mosaic,
//! `rgb[y·w + x] = [R, G, B]` for colour; channel indices are 0 = R,
//! 1 = G, 2 = B. Borders are handled by mirror reflection without
//! repeating the edge sample (`−1 → 1`), which preserves the CFA phase.
//!
//! ```
//! use radiometry::sensor::color::{BayerPattern, demosaic_malvar, mosaic};
//! let (w, h) = (8, 6);
//! let grey = [[0.4f32; 3]; 48];
//! let mut raw = [0.0f32; 48];
//! mosaic(&grey, w, h, BayerPattern::Rggb, &mut raw).unwrap();
//! let mut out = [[0.0f32; 3]; 48];
//! demosaic_malvar(&raw, w, h, BayerPattern::Rggb, &mut out).unwrap();
//! assert!(out.iter().flatten().all(|&v| (v - 0.4).abs() < 1e-6));
//! ```

use super::SensorError;
use crate::spectral::{Irregular, SpectralCurve, integrate_fn};

/// The four phases of the Bayer (1976, US patent 3,971,065) colour filter
/// array, named by the colours of the top-left 2 × 2 block read row by
/// row.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum BayerPattern {
    /// R G / G B.
    Rggb,
    /// B G / G R.
    Bggr,
    /// G R / B G.
    Grbg,
    /// G B / R G.
    Gbrg,
}

impl BayerPattern {
    /// All four phases.
    pub const ALL: [BayerPattern; 4] = [Self::Rggb, Self::Bggr, Self::Grbg, Self::Gbrg];

    /// Channel (0 = R, 1 = G, 2 = B) of the filter over pixel `(x, y)`.
    ///
    /// ```
    /// use radiometry::sensor::color::BayerPattern;
    /// assert_eq!(BayerPattern::Rggb.channel_at(0, 0), 0);
    /// assert_eq!(BayerPattern::Rggb.channel_at(1, 1), 2);
    /// assert_eq!(BayerPattern::Gbrg.channel_at(0, 1), 0);
    /// ```
    pub fn channel_at(self, x: usize, y: usize) -> usize {
        let block = match self {
            Self::Rggb => [[0, 1], [1, 2]],
            Self::Bggr => [[2, 1], [1, 0]],
            Self::Grbg => [[1, 0], [2, 1]],
            Self::Gbrg => [[1, 2], [0, 1]],
        };
        block[y & 1][x & 1]
    }
}

fn check_dims(len_a: usize, len_b: usize, w: usize, h: usize) -> Result<usize, SensorError> {
    let n = w.checked_mul(h).ok_or(SensorError::BadBuffer)?;
    if w < 2 || h < 2 || len_a != n || len_b != n {
        return Err(SensorError::BadBuffer);
    }
    Ok(n)
}

/// Mirror reflection of index `i` into `0..n` (`n ≥ 2`) without
/// repeating the edge: `−1 → 1`, `n → n − 2`; period `2(n − 1)`.
#[inline]
fn reflect(i: isize, n: usize) -> usize {
    let p = 2 * (n as isize - 1);
    // `p ≥ 2` for `n ≥ 2`; `max(1)` keeps the remainder free of a panic path.
    let m = i.rem_euclid(p.max(1));
    (if m >= n as isize { p - m } else { m }) as usize
}

/// Samples a full-colour image through the CFA: `raw[i] = rgb[i][c(x,y)]`.
/// Errors with [`SensorError::BadBuffer`] unless both buffers hold
/// `w·h` pixels and `w, h ≥ 2`.
pub fn mosaic(
    rgb: &[[f32; 3]],
    w: usize,
    h: usize,
    pattern: BayerPattern,
    raw: &mut [f32],
) -> Result<(), SensorError> {
    check_dims(rgb.len(), raw.len(), w, h)?;
    // Row-major: pixel `y·w + x` (checked reads: no panic path).
    for (k, (r, px)) in raw.iter_mut().zip(rgb).enumerate() {
        let (x, y) = (k % w.max(1), k / w.max(1));
        *r = px.get(pattern.channel_at(x, y)).copied().unwrap_or(0.0);
    }
    Ok(())
}

/// Bilinear demosaicing: each missing channel is the weighted mean of the
/// samples of that channel in the 3 × 3 neighbourhood with weights
/// `[1 2 1]ᵀ[1 2 1]` — i.e. the average of the 2 or 4 nearest samples of
/// that colour (e.g. Gunturk et al. 2005, "Demosaicking: color filter
/// array interpolation", IEEE Signal Proc. Mag. 22(1), §"Single-channel
/// interpolation"). Known samples are kept.
///
/// ```
/// use radiometry::sensor::color::{BayerPattern, demosaic_bilinear};
/// let raw = [0.5f32; 16];
/// let mut out = [[0.0f32; 3]; 16];
/// demosaic_bilinear(&raw, 4, 4, BayerPattern::Bggr, &mut out).unwrap();
/// assert_eq!(out[5], [0.5, 0.5, 0.5]);
/// ```
pub fn demosaic_bilinear(
    raw: &[f32],
    w: usize,
    h: usize,
    pattern: BayerPattern,
    out: &mut [[f32; 3]],
) -> Result<(), SensorError> {
    check_dims(raw.len(), out.len(), w, h)?;
    const K: [f32; 3] = [1.0, 2.0, 1.0];
    for y in 0..h {
        for x in 0..w {
            let own = pattern.channel_at(x, y);
            let mut num = [0.0f32; 3];
            let mut den = [0.0f32; 3];
            for (j, ky) in K.iter().enumerate() {
                let yy = reflect(y as isize + j as isize - 1, h);
                for (i, kx) in K.iter().enumerate() {
                    let xx = reflect(x as isize + i as isize - 1, w);
                    let c = pattern.channel_at(xx, yy);
                    if let (Some(n), Some(d), Some(&r)) =
                        (num.get_mut(c), den.get_mut(c), raw.get(yy * w + xx))
                    {
                        *n += ky * kx * r;
                        *d += ky * kx;
                    }
                }
            }
            let (Some(px), Some(&own_value)) = (out.get_mut(y * w + x), raw.get(y * w + x)) else {
                continue;
            };
            for (c, ((p, &n), &d)) in px.iter_mut().zip(&num).zip(&den).enumerate() {
                *p = if c == own {
                    own_value
                } else if d > 0.0 {
                    n / d
                } else {
                    0.0
                };
            }
        }
    }
    Ok(())
}

// Malvar–He–Cutler 2004, Fig. 2 filters (×1/8), indexed [dy + 2][dx + 2].
const MHC_G_AT_RB: [[f32; 5]; 5] = [
    [0.0, 0.0, -1.0, 0.0, 0.0],
    [0.0, 0.0, 2.0, 0.0, 0.0],
    [-1.0, 2.0, 4.0, 2.0, -1.0],
    [0.0, 0.0, 2.0, 0.0, 0.0],
    [0.0, 0.0, -1.0, 0.0, 0.0],
];
/// Chroma at a green pixel whose horizontal neighbours carry that chroma.
const MHC_ROW: [[f32; 5]; 5] = [
    [0.0, 0.0, 0.5, 0.0, 0.0],
    [0.0, -1.0, 0.0, -1.0, 0.0],
    [-1.0, 4.0, 5.0, 4.0, -1.0],
    [0.0, -1.0, 0.0, -1.0, 0.0],
    [0.0, 0.0, 0.5, 0.0, 0.0],
];
/// Chroma at a green pixel whose vertical neighbours carry that chroma.
const MHC_COL: [[f32; 5]; 5] = [
    [0.0, 0.0, -1.0, 0.0, 0.0],
    [0.0, -1.0, 4.0, -1.0, 0.0],
    [0.5, 0.0, 5.0, 0.0, 0.5],
    [0.0, -1.0, 4.0, -1.0, 0.0],
    [0.0, 0.0, -1.0, 0.0, 0.0],
];
/// R at a B pixel, or B at an R pixel.
const MHC_DIAG: [[f32; 5]; 5] = [
    [0.0, 0.0, -1.5, 0.0, 0.0],
    [0.0, 2.0, 0.0, 2.0, 0.0],
    [-1.5, 0.0, 6.0, 0.0, -1.5],
    [0.0, 2.0, 0.0, 2.0, 0.0],
    [0.0, 0.0, -1.5, 0.0, 0.0],
];

#[inline]
fn apply5(raw: &[f32], w: usize, h: usize, x: usize, y: usize, k: &[[f32; 5]; 5]) -> f32 {
    let mut s = 0.0f32;
    for (j, row) in k.iter().enumerate() {
        let yy = reflect(y as isize + j as isize - 2, h);
        for (i, &kv) in row.iter().enumerate() {
            // The index is in bounds for a `w × h` image (`reflect` maps into `0..w`, `0..h`);
            // the checked read keeps no panic path.
            if kv != 0.0
                && let Some(&r) = raw.get(yy * w + reflect(x as isize + i as isize - 2, w))
            {
                s += kv * r;
            }
        }
    }
    s * 0.125
}

/// Edge-aware linear demosaicing of Malvar, He & Cutler 2004
/// ("High-quality linear interpolation for demosaicing of Bayer-patterned
/// color images", Proc. IEEE ICASSP, vol. 3, pp. 485–488, Fig. 2): the
/// bilinear estimate corrected by the Laplacian of the known channel
/// (gains α = 1/2, β = 5/8, γ = 3/4), as 5 × 5 filters.
///
/// The output is not clipped: near strong edges it can overshoot the
/// input range slightly (callers clip for display). Uniform input gives
/// exactly uniform output (every filter sums to 1).
pub fn demosaic_malvar(
    raw: &[f32],
    w: usize,
    h: usize,
    pattern: BayerPattern,
    out: &mut [[f32; 3]],
) -> Result<(), SensorError> {
    check_dims(raw.len(), out.len(), w, h)?;
    // Row-major: pixel `k = y·w + x`; channels through `get_mut` (no panic path).
    for (k, (o, &v)) in out.iter_mut().zip(raw).enumerate() {
        let (x, y) = (k % w.max(1), k / w.max(1));
        let own = pattern.channel_at(x, y);
        let mut px = [0.0f32; 3];
        if let Some(p) = px.get_mut(own) {
            *p = v;
        }
        let (c0, k0, c1, k1) = if own == 1 {
            // Green: the chroma of the horizontal neighbours by rows, the other by columns.
            (
                pattern.channel_at(x + 1, y),
                &MHC_ROW,
                pattern.channel_at(x, y + 1),
                &MHC_COL,
            )
        } else {
            // Red or blue: green, and the opposite chroma (`2 − own`) diagonally.
            (1, &MHC_G_AT_RB, if own == 0 { 2 } else { 0 }, &MHC_DIAG)
        };
        if let Some(p) = px.get_mut(c0) {
            *p = apply5(raw, w, h, x, y, k0);
        }
        if let Some(p) = px.get_mut(c1) {
            *p = apply5(raw, w, h, x, y, k1);
        }
        *o = px;
    }
    Ok(())
}

/// False-colour energy of an image whose true content is achromatic:
/// `Σ_pixels Σ_c (c − m)²`, `m = (R + G + B)/3` — zero exactly when every
/// pixel is grey. Non-finite pixels are skipped.
pub fn false_colour_energy(rgb: &[[f32; 3]]) -> f32 {
    let mut e = 0.0f64;
    for p in rgb {
        if p.iter().all(|v| v.is_finite()) {
            let m = (p[0] as f64 + p[1] as f64 + p[2] as f64) / 3.0;
            e += p.iter().map(|&v| (v as f64 - m) * (v as f64 - m)).sum::<f64>();
        }
    }
    e as f32
}

/// A 3-chip camera's dichroic prism: a lossless band split into blue,
/// green and red at cut-on wavelengths `blue_green_nm < green_red_nm`,
/// with logistic edges of width `edge_nm` (ideal dichroic filters have
/// edges of a few nm; Hecht, *Optics*, 5th ed., §9.9 on multilayer
/// films):
///
/// `T_B = 1 − σ((λ − λ_bg)/w)`, `T_R = σ((λ − λ_gr)/w)`,
/// `T_G = 1 − T_B − T_R`, `σ(u) = 1/(1 + e^{−u})`,
///
/// so `T_R + T_G + T_B = 1` at every wavelength (energy conservation).
/// Each chip sees the whole image: no mosaic, no demosaicing, no false
/// colour.
///
/// ```
/// use radiometry::sensor::color::DichroicPrism;
/// let p = DichroicPrism::new(490.0, 590.0, 5.0).unwrap();
/// let t = p.transmittances(450.0);
/// assert!(t[2] > 0.99 && (t[0] + t[1] + t[2] - 1.0).abs() < 1e-6);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DichroicPrism {
    bg: f32,
    gr: f32,
    edge: f32,
}

impl DichroicPrism {
    /// Cut wavelengths (nm) in increasing order and an edge width > 0.
    pub fn new(blue_green_nm: f32, green_red_nm: f32, edge_nm: f32) -> Result<Self, SensorError> {
        if !(blue_green_nm.is_finite() && green_red_nm.is_finite() && edge_nm.is_finite()) {
            return Err(SensorError::NotFinite);
        }
        if blue_green_nm >= green_red_nm || edge_nm <= 0.0 {
            return Err(SensorError::BadParameter(
                "need blue_green < green_red and edge > 0",
            ));
        }
        Ok(Self {
            bg: blue_green_nm,
            gr: green_red_nm,
            edge: edge_nm,
        })
    }

    /// `[T_R, T_G, T_B]` at `lambda_nm` (all 0 for NaN).
    pub fn transmittances(&self, lambda_nm: f32) -> [f32; 3] {
        if lambda_nm.is_nan() {
            return [0.0; 3];
        }
        let sig = |u: f32| 1.0 / (1.0 + libm::expf(-u.clamp(-80.0, 80.0)));
        let tb = 1.0 - sig((lambda_nm - self.bg) / self.edge);
        let tr = sig((lambda_nm - self.gr) / self.edge);
        [tr, (1.0 - tb - tr).max(0.0), tb]
    }

    /// Per-chip signal `S_c = ∫ E(λ) T_c(λ) q(λ) dλ` (trapezoid at 1 nm
    /// over `E`'s support ∩ `q`'s), `[R, G, B]`.
    pub fn split(&self, spectrum: &impl SpectralCurve, qe: &impl SpectralCurve) -> [f32; 3] {
        let (a0, a1) = spectrum.support();
        let (b0, b1) = qe.support();
        let (lo, hi) = (a0.max(b0), a1.min(b1));
        core::array::from_fn(|c| {
            integrate_fn(lo, hi, 1.0, |l| {
                let t = self.transmittances(l).get(c).copied().unwrap_or(0.0);
                spectrum.value(l) * qe.value(l) * t
            })
        })
    }
}

/// A filter wheel: `N` filters exposed one after another for `slot_s`
/// seconds each. Channel `k` integrates the scene over
/// `[k·slot, (k+1)·slot)`, so anything that moves between slots lands
/// at different places in different channels (colour misregistration).
///
/// ```
/// use radiometry::sensor::color::FilterWheel;
/// let wheel = FilterWheel::new(3, 0.01, 4).unwrap();
/// // A static grey scene: every channel reads it exactly.
/// let mut out = [0.0f32; 3 * 4 * 4];
/// wheel.capture(|_x, _y, _t, _k| 0.3, 4, 4, &mut out).unwrap();
/// assert!(out.iter().all(|&v| (v - 0.3).abs() < 1e-6));
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FilterWheel {
    filters: usize,
    slot_s: f32,
    samples_per_slot: u32,
}

impl FilterWheel {
    /// `filters ≥ 1`, `slot_s > 0`, `samples_per_slot ≥ 1` (midpoint
    /// samples in time per slot).
    pub fn new(filters: usize, slot_s: f32, samples_per_slot: u32) -> Result<Self, SensorError> {
        if !slot_s.is_finite() {
            return Err(SensorError::NotFinite);
        }
        if filters == 0 || slot_s <= 0.0 || samples_per_slot == 0 {
            return Err(SensorError::BadParameter(
                "filters, slot time and samples must be > 0",
            ));
        }
        if samples_per_slot > 1 << 20 {
            return Err(SensorError::BadParameter("at most 2²⁰ samples per slot"));
        }
        Ok(Self {
            filters,
            slot_s,
            samples_per_slot,
        })
    }

    /// Start time of filter `k`'s slot, s.
    pub fn slot_start(&self, k: usize) -> f32 {
        k as f32 * self.slot_s
    }

    /// Captures `scene(x, y, t, k)` — the signal at pixel centre `(x, y)`
    /// (in pixels, `x + 0.5`), time `t`, through filter `k` — into
    /// `out[k·w·h + y·w + x]` as the time average over filter `k`'s slot
    /// (midpoint rule). Non-finite scene values read as 0.
    pub fn capture(
        &self,
        scene: impl Fn(f32, f32, f32, usize) -> f32,
        w: usize,
        h: usize,
        out: &mut [f32],
    ) -> Result<(), SensorError> {
        let n = w
            .checked_mul(h)
            .and_then(|n| n.checked_mul(self.filters))
            .ok_or(SensorError::BadBuffer)?;
        if w == 0 || h == 0 || out.len() != n {
            return Err(SensorError::BadBuffer);
        }
        let m = self.samples_per_slot;
        // `out[k·w·h + y·w + x]` in order (`w·h ≥ 1`): filter, row, column.
        let plane = (w * h).max(1);
        for (i, o) in out.iter_mut().enumerate() {
            let (k, p) = (i / plane, i % plane);
            let (x, y) = (p % w.max(1), p / w.max(1));
            let mut acc = 0.0f32;
            for s in 0..m {
                let t = self.slot_start(k) + (s as f32 + 0.5) / m as f32 * self.slot_s;
                let v = scene(x as f32 + 0.5, y as f32 + 0.5, t, k);
                if v.is_finite() {
                    acc += v;
                }
            }
            *o = acc / m as f32;
        }
        Ok(())
    }
}

/// Wavelengths (nm) of [`SILICON_ALPHA_PER_UM`].
pub const SILICON_LAMBDA_NM: [f32; 15] = [
    400.0, 450.0, 500.0, 550.0, 600.0, 650.0, 700.0, 750.0, 800.0, 850.0, 900.0, 950.0, 1000.0, 1050.0,
    1100.0,
];

/// Absorption coefficient α(λ) of intrinsic crystalline silicon at 300 K,
/// in µm⁻¹ (1 µm⁻¹ = 10⁴ cm⁻¹), at [`SILICON_LAMBDA_NM`]. Values of
/// Green & Keevers 1995 ("Optical properties of intrinsic silicon at
/// 300 K", Prog. Photovolt. 3, 189–192), rounded to 3 figures; Green 2008
/// ("Self-consistent optical parameters of intrinsic silicon at 300 K
/// including temperature coefficients", Sol. Energy Mater. Sol. Cells 92,
/// 1305–1310) revises them by a few per cent in this range.
pub const SILICON_ALPHA_PER_UM: [f32; 15] = [
    9.52, 2.55, 1.11, 0.640, 0.414, 0.281, 0.190, 0.130, 0.0850, 0.0535, 0.0306, 0.0157, 0.0064, 0.00163,
    0.00035,
];

/// α(λ) of silicon as a curve (µm⁻¹), linearly interpolated in λ, zero
/// outside 400–1100 nm (there the caller must supply data: silicon is
/// opaque below 400 nm and transparent beyond 1100 nm).
pub const fn silicon_absorption() -> Irregular<'static> {
    Irregular::from_valid_table(&SILICON_LAMBDA_NM, &SILICON_ALPHA_PER_UM)
}

/// Stacked photodiodes in one silicon column (Foveon X3-like): layer `i`
/// collects the photons absorbed between depths `z_{i−1}` and `z_i`
/// (`z_{−1} = 0`), by Beer–Lambert:
///
/// `f_i(λ) = exp(−α(λ) z_{i−1}) − exp(−α(λ) z_i)`,
///
/// with α of [`silicon_absorption`]. Short wavelengths are absorbed near
/// the surface, long ones deep, so the layers have blue-, green- and
/// red-peaked responses (Lyon & Hubel 2002, "Eyeing the camera: into the
/// next century", Proc. IS&T/SID CIC 10, pp. 349–355: junctions near
/// 0.2, 0.6 and 2 µm). What passes below the last layer is lost.
///
/// ```
/// use radiometry::sensor::color::StackedLayers;
/// let s = StackedLayers::foveon();
/// let blue = s.fractions(450.0);
/// let red = s.fractions(650.0);
/// assert!(blue[0] > blue[2] && red[2] > red[0]);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StackedLayers<const N: usize> {
    bottoms_um: [f32; N],
}

impl StackedLayers<3> {
    /// Three layers with bottoms at 0.2, 0.6 and 2.0 µm.
    pub fn foveon() -> Self {
        Self {
            bottoms_um: [0.2, 0.6, 2.0],
        }
    }
}

impl<const N: usize> StackedLayers<N> {
    /// Layer bottoms (µm), finite, positive and strictly increasing.
    pub fn new(bottoms_um: [f32; N]) -> Result<Self, SensorError> {
        if bottoms_um.iter().any(|z| !z.is_finite()) {
            return Err(SensorError::NotFinite);
        }
        let mut prev = 0.0;
        for &z in &bottoms_um {
            if z <= prev {
                return Err(SensorError::BadParameter(
                    "layer depths must be > 0 and increasing",
                ));
            }
            prev = z;
        }
        Ok(Self { bottoms_um })
    }

    /// Fraction of the photons entering the silicon at `lambda_nm` that
    /// are absorbed in each layer (all zero outside 400–1100 nm, where no
    /// α is tabulated, and for NaN).
    pub fn fractions(&self, lambda_nm: f32) -> [f32; N] {
        let a = silicon_absorption().value(lambda_nm);
        let mut top = 1.0f32;
        let mut out = [0.0f32; N];
        for (f, &z) in out.iter_mut().zip(&self.bottoms_um) {
            let below = libm::expf(-a * z);
            *f = if a > 0.0 { top - below } else { 0.0 };
            top = below;
        }
        out
    }

    /// Fraction transmitted below the last layer (1 where α is unknown).
    pub fn transmitted(&self, lambda_nm: f32) -> f32 {
        let a = silicon_absorption().value(lambda_nm);
        self.bottoms_um.last().map_or(1.0, |&z| libm::expf(-a * z))
    }

    /// Per-layer photo-electron rate for a spectral photon irradiance
    /// `φ(λ)` (photons·s⁻¹·m⁻²·nm⁻¹, or any consistent unit):
    /// `S_i = ∫ φ(λ) f_i(λ) dλ`, trapezoid at 1 nm over 400–1100 nm ∩ φ's
    /// support.
    pub fn respond(&self, photon_spectrum: &impl SpectralCurve) -> [f32; N] {
        let (a0, a1) = photon_spectrum.support();
        let (lo, hi) = (a0.max(400.0), a1.min(1100.0));
        core::array::from_fn(|i| {
            integrate_fn(lo, hi, 1.0, |l| {
                photon_spectrum.value(l) * self.fractions(l).get(i).copied().unwrap_or(0.0)
            })
        })
    }
}

/// Writes a black/white slanted-edge test chart (ISO 12233:2017-style
/// edge target) into `out` (`w·h` grey pixels, `[v, v, v]`): `v` is the
/// fraction of pixel `(x, y)` lying on the bright side of the line
/// `x = slope·y + offset` (pixel units, pixel `(x, y)` covering
/// `[x, x+1) × [y, y+1)`), estimated with 16 × 16 sub-samples. Used to
/// show demosaicing false colour: the true image is achromatic.
///
/// ```
/// use radiometry::sensor::color::slanted_edge;
/// let mut img = [[0.0f32; 3]; 8 * 4];
/// slanted_edge(8, 4, 0.0, 4.0, &mut img).unwrap();
/// assert_eq!(img[3], [0.0; 3]);
/// assert_eq!(img[4], [1.0; 3]);
/// ```
pub fn slanted_edge(
    w: usize,
    h: usize,
    slope: f32,
    offset: f32,
    out: &mut [[f32; 3]],
) -> Result<(), SensorError> {
    if !(slope.is_finite() && offset.is_finite()) {
        return Err(SensorError::NotFinite);
    }
    if w.checked_mul(h) != Some(out.len()) {
        return Err(SensorError::BadBuffer);
    }
    // Row-major: pixel `k = y·w + x` (no panic path).
    for (k, o) in out.iter_mut().enumerate() {
        let (x, y) = (k % w.max(1), k / w.max(1));
        let mut n = 0u32;
        for sy in 0..16 {
            for sx in 0..16 {
                let px = x as f32 + (sx as f32 + 0.5) / 16.0;
                let py = y as f32 + (sy as f32 + 0.5) / 16.0;
                if px > slope * py + offset {
                    n += 1;
                }
            }
        }
        *o = [n as f32 / 256.0; 3];
    }
    Ok(())
}
