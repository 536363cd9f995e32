//! The rendered picture: linear radiance per pixel, the tone curve to 8 bits,
//! and (with the `plot` feature) PNG and SVG output.
//!
//! **Tone curve** ([`tone_map`]): the radiance times the exposure, `x`, goes
//! through the extended Reinhard curve `t(x) = x (1 + x/W²) / (1 + x)`
//! (Reinhard et al. 2002, "Photographic tone reproduction for digital
//! images", eq. 4) with white point `W = `[`WHITE_POINT`] (radiance `W` maps
//! to 1; above it the output clips to white), then the sRGB transfer function
//! (IEC 61966-2-1: `12.92 t` for `t ≤ 0.0031308`, else `1.055 t^(1/2.4) −
//! 0.055`), then rounds to 8 bits. The curve is monotonic, so equal radiances
//! give equal bytes (the white furnace stays invisible after tone mapping).
//!
//! **Files.** PNG: 8-bit greyscale, encoded by the `png` crate, with a
//! `Description` text chunk (the command line or spec that made it). SVG: one
//! `<image>` element holding that PNG as a base64 `data:` URI (a few kB larger
//! than the PNG; every browser and vector editor shows it), with a `<title>`.

#[cfg(feature = "plot")]
use std::path::Path;

/// The radiance that the tone curve maps to white (exposure 1).
pub const WHITE_POINT: f32 = 4.0;

/// Radiance `l` × `exposure` to an 8-bit sRGB-encoded value (module docs).
/// NaN and negative input give 0.
pub fn tone_map(l: f32, exposure: f32) -> u8 {
    let x = l * exposure;
    if x.is_nan() || x <= 0.0 {
        return 0;
    }
    let w2 = WHITE_POINT * WHITE_POINT;
    let t = if x >= WHITE_POINT {
        1.0
    } else {
        (x * (1.0 + x / w2) / (1.0 + x)).min(1.0)
    };
    let e = if t <= 0.003_130_8 {
        12.92 * t
    } else {
        1.055 * t.powf(1.0 / 2.4) - 0.055
    };
    (e * 255.0 + 0.5).clamp(0.0, 255.0) as u8
}

/// Output file format.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// 8-bit greyscale PNG.
    Png,
    /// SVG wrapping the PNG (base64).
    Svg,
}

impl Format {
    /// `Svg` for a path ending in `.svg` (any case), `Png` otherwise.
    pub fn from_path(p: &std::path::Path) -> Format {
        match p.extension().and_then(|e| e.to_str()) {
            Some(e) if e.eq_ignore_ascii_case("svg") => Format::Svg,
            _ => Format::Png,
        }
    }
}

/// A rendered square picture: linear radiance and ball coverage per pixel,
/// row-major from the top-left corner.
#[derive(Clone, Debug, PartialEq)]
pub struct Image {
    size: u32,
    radiance: Vec<f32>,
    coverage: Vec<f32>,
}

impl Image {
    pub(super) fn new(size: u32, radiance: Vec<f32>, coverage: Vec<f32>) -> Self {
        Image {
            size,
            radiance,
            coverage,
        }
    }

    /// Width and height in pixels.
    pub fn size(&self) -> u32 {
        self.size
    }

    /// Linear radiance of every pixel (row-major, `size²` values): the mean
    /// over the pixel's camera samples.
    pub fn radiance(&self) -> &[f32] {
        &self.radiance
    }

    /// The fraction of each pixel's camera samples that hit the ball (1 inside
    /// the silhouette, 0 on the background, between on the edge).
    pub fn coverage(&self) -> &[f32] {
        &self.coverage
    }

    /// Radiance of pixel `(x, y)` (`y` down), or `None` outside the image.
    pub fn get(&self, x: u32, y: u32) -> Option<f32> {
        (x < self.size && y < self.size).then(|| self.radiance[(y * self.size + x) as usize])
    }

    /// The 8-bit tone-mapped pixels ([`tone_map`]), row-major.
    pub fn to_gray8(&self, exposure: f32) -> Vec<u8> {
        self.radiance.iter().map(|&l| tone_map(l, exposure)).collect()
    }

    /// The picture as a PNG file's bytes (8-bit greyscale), with `description`
    /// in a `Description` text chunk when it is not empty.
    #[cfg(feature = "plot")]
    pub fn encode_png(&self, exposure: f32, description: &str) -> std::io::Result<Vec<u8>> {
        encode_png8(
            self.size,
            self.size,
            png::ColorType::Grayscale,
            &self.to_gray8(exposure),
            description,
        )
    }

    /// The picture as an SVG document: the PNG of [`Image::encode_png`] in one
    /// `<image>` element (base64 `data:` URI), `title` as its `<title>`.
    #[cfg(feature = "plot")]
    pub fn to_svg(&self, exposure: f32, title: &str) -> std::io::Result<String> {
        let png = self.encode_png(exposure, title)?;
        Ok(svg_wrap(&png, self.size, self.size, title))
    }

    /// Writes the picture to `path` as `format` ([`Image::encode_png`] or
    /// [`Image::to_svg`]).
    #[cfg(feature = "plot")]
    pub fn write(
        &self,
        path: &Path,
        format: Format,
        exposure: f32,
        description: &str,
    ) -> std::io::Result<()> {
        match format {
            Format::Png => std::fs::write(path, self.encode_png(exposure, description)?),
            Format::Svg => std::fs::write(path, self.to_svg(exposure, description)?),
        }
    }
}

/// An 8-bit PNG of `width × height` pixels of `color` type, with
/// `description` in a `Description` text chunk when it is not empty.
#[cfg(feature = "plot")]
pub fn encode_png8(
    width: u32,
    height: u32,
    color: png::ColorType,
    data: &[u8],
    description: &str,
) -> std::io::Result<Vec<u8>> {
    let mut out = Vec::new();
    let mut enc = png::Encoder::new(&mut out, width, height);
    enc.set_color(color);
    enc.set_depth(png::BitDepth::Eight);
    if !description.is_empty() {
        enc.add_text_chunk("Description".into(), description.into())
            .map_err(std::io::Error::other)?;
    }
    let mut w = enc.write_header().map_err(std::io::Error::other)?;
    w.write_image_data(data).map_err(std::io::Error::other)?;
    w.finish().map_err(std::io::Error::other)?;
    Ok(out)
}

/// An SVG document showing `png` (`width × height`) in one `<image>`
/// element (base64 `data:` URI), `title` as its `<title>`.
#[cfg(feature = "plot")]
pub fn svg_wrap(png: &[u8], width: u32, height: u32, title: &str) -> String {
    format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" xmlns:xlink=\"http://www.w3.org/1999/xlink\" \
width=\"{width}\" height=\"{height}\" viewBox=\"0 0 {width} {height}\">\n<title>{}</title>\n\
<image width=\"{width}\" height=\"{height}\" style=\"image-rendering:pixelated\" \
xlink:href=\"data:image/png;base64,{}\"/>\n</svg>\n",
        xml_escape(title),
        base64(png)
    )
}

/// `&`, `<`, `>`, `"` as XML entities.
#[cfg(feature = "plot")]
fn xml_escape(s: &str) -> String {
    let mut o = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            '&' => o.push_str("&amp;"),
            '<' => o.push_str("&lt;"),
            '>' => o.push_str("&gt;"),
            '"' => o.push_str("&quot;"),
            c => o.push(c),
        }
    }
    o
}

/// Standard base64 with padding (RFC 4648 §4).
#[cfg(any(feature = "plot", test))]
fn base64(data: &[u8]) -> String {
    const A: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut o = String::with_capacity(data.len().div_ceil(3) * 4);
    for c in data.chunks(3) {
        let b = [c[0], *c.get(1).unwrap_or(&0), *c.get(2).unwrap_or(&0)];
        let v = (b[0] as u32) << 16 | (b[1] as u32) << 8 | b[2] as u32;
        for k in 0..4 {
            if k <= c.len() {
                o.push(A[(v >> (18 - 6 * k) & 63) as usize] as char);
            } else {
                o.push('=');
            }
        }
    }
    o
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn base64_matches_rfc4648_vectors() {
        for (i, o) in [
            ("", ""),
            ("f", "Zg=="),
            ("fo", "Zm8="),
            ("foo", "Zm9v"),
            ("foob", "Zm9vYg=="),
            ("fooba", "Zm9vYmE="),
            ("foobar", "Zm9vYmFy"),
        ] {
            assert_eq!(base64(i.as_bytes()), o);
        }
    }

    #[test]
    fn tone_curve_is_monotonic_and_pins_its_ends() {
        assert_eq!(tone_map(0.0, 1.0), 0);
        assert_eq!(tone_map(f32::NAN, 1.0), 0);
        assert_eq!(tone_map(-1.0, 1.0), 0);
        assert_eq!(tone_map(WHITE_POINT, 1.0), 255);
        assert_eq!(tone_map(1e30, 1.0), 255);
        let mut last = 0;
        for k in 0..=4000 {
            let b = tone_map(k as f32 * 1e-3, 1.0);
            assert!(b >= last);
            last = b;
        }
        // Reinhard at x = 1 with W = 4: 1·(1 + 1/16)/2 = 0.53125 → sRGB 0.7556 → 192.7 → 193.
        assert_eq!(tone_map(1.0, 1.0), 193);
    }
}
