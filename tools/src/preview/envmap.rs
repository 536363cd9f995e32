//! Equirectangular environment maps for the colour preview: the sky (and
//! ground) of [`super::colour::render_rgb_env`] read from a picture instead of
//! the uniform sky — `radiometry preview … --env FILE.hdr`.
//!
//! **Mapping.** World `+Y` is up; the camera looks along `−Z`. A direction
//! `ω` reads the texel at `u = ½ + atan2(ω_x, −ω_z)/(2π)` (columns, left to
//! right; the image centre lies straight ahead of the camera, behind the
//! ball) and `v = acos(ω_y)/π` (rows, top = up), bilinearly interpolated,
//! wrapping in `u`. The texel values, times a scale, are linear RGB
//! radiances.
//!
//! **Estimator.** The preview's: one light sample and one BRDF sample,
//! combined by the power heuristic. The light sample is the sun's cone or,
//! with an [`EnvSampler`], a direction drawn from the map in proportion to
//! texel luminance times `sin θ` (a piecewise-constant 2D distribution:
//! a row by its marginal, a column by its conditional, uniform inside the
//! texel; density `p_texel W H / (2π² sin θ)`, Pharr, Jakob & Humphreys,
//! *Physically Based Rendering*, 4th ed., §12.5.2), so small bright
//! sources in the map are found.
//!
//! **Files** (feature `hdr`): Radiance RGBE `.hdr` pictures, decoded by the
//! `image` crate's HDR decoder (image-rs), at most [`MAX_TEXELS`] texels.

use super::PreviewError;
use radiometry::glam::Vec3;
use std::f32::consts::{PI, TAU};

/// Largest number of texels of a map (8192 × 4096: 384 MiB of `f32` RGB).
pub const MAX_TEXELS: usize = 8192 * 4096;

/// A linear RGB equirectangular map (module docs).
#[derive(Clone, Debug, PartialEq)]
pub struct EnvMap {
    width: usize,
    height: usize,
    rgb: Vec<[f32; 3]>,
}

impl EnvMap {
    /// A map of `width × height` texels, row-major from the top-left;
    /// every component finite and ≥ 0, `width, height ≥ 1`, at most
    /// [`MAX_TEXELS`].
    pub fn from_rgb(width: usize, height: usize, rgb: Vec<[f32; 3]>) -> Result<Self, PreviewError> {
        let n = width.saturating_mul(height);
        if width == 0 || height == 0 || n > MAX_TEXELS || rgb.len() != n {
            return Err(PreviewError::EnvMap(format!(
                "{width} × {height} texels with {} values (need 1 ≤ width × height ≤ {MAX_TEXELS})",
                rgb.len()
            )));
        }
        if let Some(bad) = rgb.iter().flatten().find(|v| !(v.is_finite() && **v >= 0.0)) {
            return Err(PreviewError::EnvMap(format!(
                "texel component {bad} is not finite and ≥ 0"
            )));
        }
        Ok(EnvMap { width, height, rgb })
    }

    /// Reads a Radiance `.hdr` (RGBE) file.
    #[cfg(feature = "hdr")]
    pub fn read_hdr(path: &std::path::Path) -> Result<Self, PreviewError> {
        use image::ImageDecoder as _;
        let bad = |e: String| PreviewError::EnvMap(format!("{}: {e}", path.display()));
        let file = std::fs::File::open(path).map_err(|e| bad(e.to_string()))?;
        let dec = image::codecs::hdr::HdrDecoder::new(std::io::BufReader::new(file))
            .map_err(|e| bad(e.to_string()))?;
        let (w, h) = dec.dimensions();
        let (w, h) = (w as usize, h as usize);
        if w == 0 || h == 0 || w.saturating_mul(h) > MAX_TEXELS {
            return Err(bad(format!(
                "{w} × {h} texels: need 1 ≤ width × height ≤ {MAX_TEXELS}"
            )));
        }
        let img = image::DynamicImage::from_decoder(dec)
            .map_err(|e| bad(e.to_string()))?
            .into_rgb32f();
        let rgb = img
            .pixels()
            .map(|p| p.0.map(|v| if v.is_finite() { v.max(0.0) } else { 0.0 }))
            .collect();
        EnvMap::from_rgb(w, h, rgb)
    }

    /// Width in texels.
    pub fn width(&self) -> usize {
        self.width
    }

    /// Height in texels.
    pub fn height(&self) -> usize {
        self.height
    }

    /// The texels (row-major).
    pub fn texels(&self) -> &[[f32; 3]] {
        &self.rgb
    }

    fn texel(&self, x: usize, y: usize) -> [f32; 3] {
        self.rgb
            .get(y.min(self.height - 1) * self.width + x % self.width)
            .copied()
            .unwrap_or([0.0; 3])
    }

    /// The radiance from world direction `w` (unit; module docs), bilinear.
    pub fn radiance(&self, w: Vec3) -> [f32; 3] {
        if !w.is_finite() {
            return [0.0; 3];
        }
        let u = 0.5 + w.x.atan2(-w.z) / TAU;
        let v = w.y.clamp(-1.0, 1.0).acos() / PI;
        // Texel centres at (i + ½)/width.
        let x = u * self.width as f32 - 0.5;
        let y = (v * self.height as f32 - 0.5).clamp(0.0, (self.height - 1) as f32);
        let (x0, y0) = (x.floor(), y.floor());
        let (tx, ty) = (x - x0, y - y0);
        let xi = (x0 as i64).rem_euclid(self.width as i64) as usize;
        let yi = y0 as usize;
        let (a, b) = (self.texel(xi, yi), self.texel(xi + 1, yi));
        let (c, d) = (self.texel(xi, yi + 1), self.texel(xi + 1, yi + 1));
        std::array::from_fn(|k| {
            let top = a[k] + tx * (b[k] - a[k]);
            let bottom = c[k] + tx * (d[k] - c[k]);
            top + ty * (bottom - top)
        })
    }

    /// The mean radiance over the sphere (texels weighted by their solid
    /// angle, `∝ sin θ`), per channel.
    pub fn mean(&self) -> [f32; 3] {
        let mut s = [0.0f64; 3];
        let mut wsum = 0.0f64;
        for y in 0..self.height {
            let w = ((y as f64 + 0.5) / self.height as f64 * std::f64::consts::PI).sin();
            for x in 0..self.width {
                let t = self.texel(x, y);
                for k in 0..3 {
                    s[k] += w * t[k] as f64;
                }
                wsum += w;
            }
        }
        s.map(|v| (v / wsum) as f32)
    }
}

/// Importance sampling of an [`EnvMap`] (module docs).
#[derive(Clone, Debug, PartialEq)]
pub struct EnvSampler {
    width: usize,
    height: usize,
    /// `marginal[y]`: the cumulative weight of rows `0..y` (length `height + 1`).
    marginal: Vec<f64>,
    /// Per row, the cumulative weight of its texels (`width + 1` each).
    conditional: Vec<f64>,
    total: f64,
}

impl EnvSampler {
    /// The distribution of `map` (luminance `0.2126 R + 0.7152 G + 0.0722 B`
    /// times `sin θ` per texel); `None` when the map is black.
    pub fn new(map: &EnvMap) -> Option<Self> {
        let (w, h) = (map.width, map.height);
        let mut conditional = Vec::with_capacity(h * (w + 1));
        let mut marginal = Vec::with_capacity(h + 1);
        marginal.push(0.0);
        let mut total = 0.0f64;
        for y in 0..h {
            let sin_t = ((y as f64 + 0.5) / h as f64 * std::f64::consts::PI).sin();
            let mut acc = 0.0f64;
            conditional.push(0.0);
            for x in 0..w {
                let t = map.texel(x, y);
                let lum = 0.2126 * t[0] as f64 + 0.7152 * t[1] as f64 + 0.0722 * t[2] as f64;
                acc += lum.max(0.0) * sin_t;
                conditional.push(acc);
            }
            total += acc;
            marginal.push(total);
        }
        (total > 0.0 && total.is_finite()).then_some(EnvSampler {
            width: w,
            height: h,
            marginal,
            conditional,
            total,
        })
    }

    /// The index `i` with `cdf[i] ≤ x < cdf[i + 1]` among `cdf[..n + 1]`,
    /// skipping empty bins.
    fn find(cdf: &[f64], x: f64) -> usize {
        let n = cdf.len().saturating_sub(1);
        cdf.partition_point(|&c| c <= x)
            .saturating_sub(1)
            .min(n.saturating_sub(1))
    }

    /// A world direction for `u ∈ [0, 1)²`.
    pub fn sample(&self, u: [f32; 2]) -> Vec3 {
        let y = Self::find(&self.marginal, u[0] as f64 * self.total);
        let (r0, r1) = (self.marginal[y], self.marginal[y + 1]);
        let dv = if r1 > r0 {
            ((u[0] as f64 * self.total - r0) / (r1 - r0)).clamp(0.0, 1.0)
        } else {
            0.5
        };
        let row = &self.conditional[y * (self.width + 1)..(y + 1) * (self.width + 1)];
        let row_total = row[self.width];
        let x = Self::find(row, u[1] as f64 * row_total);
        let du = if row[x + 1] > row[x] {
            ((u[1] as f64 * row_total - row[x]) / (row[x + 1] - row[x])).clamp(0.0, 1.0)
        } else {
            0.5
        };
        let uu = (x as f64 + du) / self.width as f64;
        let vv = (y as f64 + dv) / self.height as f64;
        let theta = vv * std::f64::consts::PI;
        let phi = (uu - 0.5) * std::f64::consts::TAU;
        let (st, ct) = theta.sin_cos();
        Vec3::new((st * phi.sin()) as f32, ct as f32, (-st * phi.cos()) as f32).normalize_or_zero()
    }

    /// The density [sr⁻¹] of [`EnvSampler::sample`] at world direction `w`.
    pub fn pdf(&self, w: Vec3) -> f32 {
        if !w.is_finite() {
            return 0.0;
        }
        let u = 0.5 + (w.x as f64).atan2(-(w.z as f64)) / std::f64::consts::TAU;
        let v = (w.y as f64).clamp(-1.0, 1.0).acos() / std::f64::consts::PI;
        let x = ((u * self.width as f64) as usize).min(self.width - 1);
        let y = ((v * self.height as f64) as usize).min(self.height - 1);
        let row = &self.conditional[y * (self.width + 1)..(y + 1) * (self.width + 1)];
        let p = (row[x + 1] - row[x]) / self.total;
        let sin_t = (v * std::f64::consts::PI).sin();
        if sin_t <= 0.0 {
            return 0.0;
        }
        let pdf = p * (self.width * self.height) as f64
            / (2.0 * std::f64::consts::PI * std::f64::consts::PI * sin_t);
        if pdf.is_finite() { pdf as f32 } else { 0.0 }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mapping_puts_up_at_the_top_and_the_front_at_the_centre() {
        // 4 × 2: top row red, bottom row blue; column 1..3 brighter in front.
        let mut rgb = vec![[1.0, 0.0, 0.0]; 4];
        rgb.extend(vec![[0.0, 0.0, 1.0]; 4]);
        let m = EnvMap::from_rgb(4, 2, rgb).unwrap();
        assert_eq!(m.radiance(Vec3::Y), [1.0, 0.0, 0.0]);
        assert_eq!(m.radiance(-Vec3::Y), [0.0, 0.0, 1.0]);
        let front = m.radiance(Vec3::new(0.0, 0.0, -1.0));
        assert!(
            (front[0] - 0.5).abs() < 1e-6 && (front[2] - 0.5).abs() < 1e-6,
            "{front:?}"
        );
        assert_eq!(m.radiance(Vec3::NAN), [0.0; 3]);
        let mean = m.mean();
        assert!((mean[0] - 0.5).abs() < 1e-6 && (mean[2] - 0.5).abs() < 1e-6);
    }

    #[test]
    fn the_sampler_draws_by_luminance_and_its_pdf_integrates_to_one() {
        // 16 × 8: dim everywhere, one bright texel.
        let mut rgb = vec![[0.1f32; 3]; 128];
        rgb[2 * 16 + 5] = [50.0, 40.0, 30.0];
        let m = EnvMap::from_rgb(16, 8, rgb).unwrap();
        let s = EnvSampler::new(&m).unwrap();
        // ∫ pdf dω = 1 (midpoint rule on a fine θ, φ grid).
        let (nt, np) = (400, 800);
        let mut integral = 0.0f64;
        for i in 0..nt {
            let t = (i as f64 + 0.5) / nt as f64 * std::f64::consts::PI;
            for j in 0..np {
                let p = (j as f64 + 0.5) / np as f64 * std::f64::consts::TAU;
                let w = Vec3::new(
                    (t.sin() * p.sin()) as f32,
                    t.cos() as f32,
                    (-t.sin() * p.cos()) as f32,
                );
                integral += s.pdf(w) as f64
                    * t.sin()
                    * (std::f64::consts::PI / nt as f64)
                    * (std::f64::consts::TAU / np as f64);
            }
        }
        assert!((integral - 1.0).abs() < 2e-3, "{integral}");
        // Samples land in the bright texel in proportion to its weight.
        let mut hits = 0;
        let n = 4000;
        for k in 0..n {
            let u = [
                ((k as f32) + 0.5) / n as f32,
                ((k * 7919 % n) as f32 + 0.5) / n as f32,
            ];
            let w = s.sample(u);
            assert!((w.length() - 1.0).abs() < 1e-4 && s.pdf(w) > 0.0);
            let px = 0.5 + w.x.atan2(-w.z) / TAU;
            let py = w.y.clamp(-1.0, 1.0).acos() / PI;
            if (px * 16.0) as usize == 5 && (py * 8.0) as usize == 2 {
                hits += 1;
            }
        }
        let sin2 = ((2.5f64 / 8.0) * std::f64::consts::PI).sin();
        let bright = (0.2126 * 50.0 + 0.7152 * 40.0 + 0.0722 * 30.0) * sin2;
        let expect = bright / s.total;
        let got = hits as f64 / n as f64;
        assert!((got - expect).abs() < 0.02, "{got} vs {expect}");
        assert!(EnvSampler::new(&EnvMap::from_rgb(2, 1, vec![[0.0; 3]; 2]).unwrap()).is_none());
    }

    #[test]
    fn bad_maps_are_typed_errors() {
        assert!(matches!(
            EnvMap::from_rgb(0, 1, vec![]),
            Err(PreviewError::EnvMap(_))
        ));
        assert!(matches!(
            EnvMap::from_rgb(2, 1, vec![[0.0; 3]]),
            Err(PreviewError::EnvMap(_))
        ));
        assert!(matches!(
            EnvMap::from_rgb(1, 1, vec![[f32::NAN, 0.0, 0.0]]),
            Err(PreviewError::EnvMap(_))
        ));
        assert!(matches!(
            EnvMap::from_rgb(1, 1, vec![[-1.0, 0.0, 0.0]]),
            Err(PreviewError::EnvMap(_))
        ));
    }

    #[cfg(feature = "hdr")]
    #[test]
    fn hdr_files_round_trip_within_rgbe_precision() {
        let dir = std::env::temp_dir().join(format!("radiometry-envmap-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("sky.hdr");
        let texels: Vec<image::Rgb<f32>> = (0..6 * 3)
            .map(|i| image::Rgb([0.1 * i as f32, 2.0, 0.25 + i as f32]))
            .collect();
        let f = std::fs::File::create(&path).unwrap();
        image::codecs::hdr::HdrEncoder::new(std::io::BufWriter::new(f))
            .encode(&texels, 6, 3)
            .unwrap();
        let m = EnvMap::read_hdr(&path).unwrap();
        assert_eq!((m.width(), m.height()), (6, 3));
        for (a, b) in m.texels().iter().zip(&texels) {
            // RGBE: an 8-bit mantissa per channel with a shared exponent.
            let tol = 0.01 * b.0.iter().fold(0.0f32, |m, v| m.max(*v)) + 1e-6;
            for (x, y) in a.iter().zip(b.0) {
                assert!((x - y).abs() <= tol, "{a:?} {b:?}");
            }
        }
        assert!(matches!(
            EnvMap::read_hdr(&dir.join("missing.hdr")),
            Err(PreviewError::EnvMap(_))
        ));
        std::fs::write(dir.join("junk.hdr"), b"not an hdr file").unwrap();
        assert!(matches!(
            EnvMap::read_hdr(&dir.join("junk.hdr")),
            Err(PreviewError::EnvMap(_))
        ));
        let _ = std::fs::remove_dir_all(dir);
    }
}
