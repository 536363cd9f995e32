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
//! **Estimator.** The preview's: one light sample (the sun's cone, or a
//! cosine-weighted direction, which now reads the map) and one BRDF sample,
//! combined by the power heuristic — unbiased for any map, though without
//! importance sampling of the map itself a small, very bright source in it
//! (an unclipped sun) is found only by chance: keep the sun in the
//! preview's own sun cap (`--sun-…`) and a map without it.
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
