//! The slanted-edge picture of `radiometry sensor edge`: one black/white
//! edge target (ISO 12233-style) seen by the five colour architectures of the
//! course notes — Bayer CFA + bilinear demosaicing, Bayer + Malvar–He–Cutler,
//! a 3-chip dichroic prism, a filter wheel (time-multiplexed filters, here with
//! the edge moving during the capture) and stacked photodiodes (Foveon-like
//! depth-dependent absorption) — written side by side as SVG or PNG, each panel
//! under its label.

use radiometry::sensor::SensorError;
use radiometry::sensor::color::{
    BayerPattern, DichroicPrism, FilterWheel, StackedLayers, demosaic_bilinear, demosaic_malvar, mosaic,
    slanted_edge,
};
use radiometry::spectral::FnCurve;
use std::fmt::Write as _;
use std::path::Path;

/// Slope (pixels of x per pixel of y) of the slanted edge: about 5.7°
/// from vertical, as ISO 12233 slanted-edge charts use a few degrees.
pub const EDGE_SLOPE: f32 = 0.1;

/// Edge motion during a filter-wheel capture: pixels per filter slot (a slow
/// pan: 1 px while the wheel turns from one filter to the next).
pub const WHEEL_MOTION_PX_PER_SLOT: f32 = 1.0;

/// One reconstruction of the edge target.
pub struct Panel {
    /// Label drawn above the panel (also the text report's row name).
    pub label: &'static str,
    /// JSON key of its false-colour energy.
    pub key: &'static str,
    /// `n × n` linear RGB pixels.
    pub rgb: Vec<[f32; 3]>,
}

/// Renders the edge target (`n × n`) through every architecture.
pub fn render(n: usize, pattern: BayerPattern) -> Result<Vec<Panel>, SensorError> {
    let mut truth = vec![[0.0f32; 3]; n * n];
    let half = n as f32 / 2.0;
    let offset = half - EDGE_SLOPE * half;
    slanted_edge(n, n, EDGE_SLOPE, offset, &mut truth)?;

    // Bayer: one channel per pixel, the other two interpolated.
    let mut raw = vec![0.0f32; n * n];
    mosaic(&truth, n, n, pattern, &mut raw)?;
    let mut bilinear = vec![[0.0f32; 3]; n * n];
    demosaic_bilinear(&raw, n, n, pattern, &mut bilinear)?;
    let mut malvar = vec![[0.0f32; 3]; n * n];
    demosaic_malvar(&raw, n, n, pattern, &mut malvar)?;

    // 3-chip: each chip sees the whole image through its prism band; white-balanced on an
    // equal-energy white (chip c reads v·S_c, divided by S_c).
    let white = FnCurve::new(380.0, 780.0, |_| 1.0);
    let qe = FnCurve::new(380.0, 780.0, |_| 1.0);
    let prism = DichroicPrism::new(490.0, 590.0, 5.0)?;
    let s = prism.split(&white, &qe);
    let three_chip = truth
        .iter()
        .map(|p| core::array::from_fn(|c| p[c] * s[c] * (1.0 / s[c])))
        .collect();

    // Filter wheel: R, G, B exposed one after another; the edge moves
    // WHEEL_MOTION_PX_PER_SLOT px per slot, so each channel sees it elsewhere.
    // A pixel's value is the covered fraction of its row segment [x, x+1).
    let wheel = FilterWheel::new(3, 1.0, 8)?;
    let mut planes = vec![0.0f32; 3 * n * n];
    let scene = |x: f32, y: f32, t: f32, _k: usize| {
        let edge_x = EDGE_SLOPE * y + offset + WHEEL_MOTION_PX_PER_SLOT * t;
        (x + 0.5 - edge_x).clamp(0.0, 1.0)
    };
    wheel.capture(scene, n, n, &mut planes)?;
    let filter_wheel = (0..n * n)
        .map(|i| [planes[i], planes[n * n + i], planes[2 * n * n + i]])
        .collect();

    // Stacked layers: every layer sees every pixel (no mosaic, no motion); each
    // layer's response to the equal-energy white sets its white balance.
    let layers = StackedLayers::foveon();
    let r = layers.respond(&white);
    let stacked = truth
        .iter()
        .map(|p| core::array::from_fn(|c| p[c] * r[2 - c] / r[2 - c]))
        .collect();

    Ok(vec![
        Panel {
            label: "Bayer + bilinear",
            key: "bilinear",
            rgb: bilinear,
        },
        Panel {
            label: "Bayer + Malvar-He-Cutler",
            key: "malvar",
            rgb: malvar,
        },
        Panel {
            label: "3-chip prism",
            key: "three_chip",
            rgb: three_chip,
        },
        Panel {
            label: "Filter wheel (moving edge)",
            key: "filter_wheel",
            rgb: filter_wheel,
        },
        Panel {
            label: "Stacked (Foveon)",
            key: "stacked",
            rgb: stacked,
        },
    ])
}

/// sRGB encoding of a linear value clipped to [0, 1] (IEC 61966-2-1), as 8 bits.
fn srgb8(v: f32) -> u8 {
    let v = if v.is_finite() { v.clamp(0.0, 1.0) } else { 0.0 };
    let e = if v <= 0.003_130_8 {
        12.92 * v
    } else {
        1.055 * v.powf(1.0 / 2.4) - 0.055
    };
    (e * 255.0).round().clamp(0.0, 255.0) as u8
}

/// Layout: panels of `n·scale` pixels side by side, `GAP` apart, under a label band.
const GAP: usize = 16;
const LABEL_H: usize = 28;

fn panel_scale(n: usize) -> usize {
    (256 / n).max(1)
}

/// Picture size `(w, h)` in pixels and the panel side.
fn layout(n: usize, panels: usize) -> (usize, usize, usize) {
    let side = n * panel_scale(n);
    (panels * side + (panels + 1) * GAP, side + LABEL_H + GAP, side)
}

/// SVG: one rectangle per pixel, text labels.
pub fn write_svg(path: &Path, n: usize, panels: &[Panel]) -> std::io::Result<()> {
    let s = panel_scale(n);
    let (w, h, side) = layout(n, panels.len());
    let mut o = String::new();
    let _ = writeln!(
        o,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" viewBox="0 0 {w} {h}" shape-rendering="crispEdges">"#
    );
    let _ = writeln!(o, r#"<rect width="{w}" height="{h}" fill="rgb(128,128,128)"/>"#);
    for (k, p) in panels.iter().enumerate() {
        let x0 = GAP + k * (side + GAP);
        let _ = writeln!(
            o,
            r#"<text x="{}" y="{}" font-family="sans-serif" font-size="14" text-anchor="middle" fill="black">{}</text>"#,
            x0 + side / 2,
            LABEL_H - 9,
            p.label
        );
        for y in 0..n {
            for x in 0..n {
                let c = p.rgb[y * n + x];
                let _ = writeln!(
                    o,
                    r#"<rect x="{}" y="{}" width="{s}" height="{s}" fill="rgb({},{},{})"/>"#,
                    x0 + x * s,
                    LABEL_H + y * s,
                    srgb8(c[0]),
                    srgb8(c[1]),
                    srgb8(c[2])
                );
            }
        }
    }
    o.push_str("</svg>\n");
    std::fs::write(path, o)
}

/// PNG (8-bit RGB, encoded by the `png` crate): the SVG's layout, labels drawn
/// with the 8 × 8 glyphs of the `font8x8` crate (all at one scale: ×2 when the
/// longest label fits).
pub fn write_png(path: &Path, n: usize, panels: &[Panel]) -> std::io::Result<()> {
    use font8x8::UnicodeFonts as _;
    let s = panel_scale(n);
    let (w, h, side) = layout(n, panels.len());
    let mut px = vec![128u8; 3 * w * h];
    let mut put = |x: usize, y: usize, c: [u8; 3]| {
        if x < w && y < h {
            px[3 * (y * w + x)..3 * (y * w + x) + 3].copy_from_slice(&c);
        }
    };
    // One glyph scale for every label (×2 only if the longest label fits).
    let longest = panels.iter().map(|p| p.label.chars().count()).max().unwrap_or(0);
    let fs = if longest * 16 <= side { 2 } else { 1 };
    for (k, p) in panels.iter().enumerate() {
        let x0 = GAP + k * (side + GAP);
        let chars = p.label.chars().count();
        let tx = (x0 + side / 2).saturating_sub(chars * 8 * fs / 2);
        let ty = (LABEL_H - 8 * fs) / 2;
        for (i, ch) in p.label.chars().enumerate() {
            let glyph = font8x8::BASIC_FONTS.get(ch).unwrap_or([0; 8]);
            for (r, bits) in glyph.iter().enumerate() {
                for col in 0..8 {
                    // font8x8: bit 0 is the leftmost column.
                    if bits & (1 << col) != 0 {
                        for dy in 0..fs {
                            for dx in 0..fs {
                                put(tx + (i * 8 + col) * fs + dx, ty + r * fs + dy, [0, 0, 0]);
                            }
                        }
                    }
                }
            }
        }
        for y in 0..n {
            for x in 0..n {
                let c = p.rgb[y * n + x];
                let c = [srgb8(c[0]), srgb8(c[1]), srgb8(c[2])];
                for dy in 0..s {
                    for dx in 0..s {
                        put(x0 + x * s + dx, LABEL_H + y * s + dy, c);
                    }
                }
            }
        }
    }
    let file = std::io::BufWriter::new(std::fs::File::create(path)?);
    let mut enc = png::Encoder::new(file, w as u32, h as u32);
    enc.set_color(png::ColorType::Rgb);
    enc.set_depth(png::BitDepth::Eight);
    let mut writer = enc.write_header().map_err(std::io::Error::other)?;
    writer.write_image_data(&px).map_err(std::io::Error::other)?;
    writer.finish().map_err(std::io::Error::other)
}

#[cfg(test)]
mod tests {
    use super::*;
    use radiometry::sensor::color::false_colour_energy;

    #[test]
    fn architectures_order_by_false_colour() {
        let panels = render(32, BayerPattern::Rggb).unwrap();
        let e: Vec<f32> = panels.iter().map(|p| false_colour_energy(&p.rgb)).collect();
        // Demosaicing and motion between filter slots produce false colour;
        // the prism and the stack see every colour at every pixel at once.
        assert!(e[0] > e[1] && e[1] > 0.0, "{e:?}");
        assert!(e[3] > 0.0, "moving edge through a filter wheel: {e:?}");
        assert!(e[2] < 1e-9 && e[4] < 1e-9, "{e:?}");
        // The wheel's channels are the edge shifted by 1 px per slot: the red
        // plane (slot 0, t in [0, 1)) leads the blue one (slot 2) by 2 px.
        let row = 16;
        let plane = |c: usize| -> f32 { (0..32).map(|x| panels[3].rgb[row * 32 + x][c]).sum() };
        assert!((plane(0) - plane(2) - 2.0 * WHEEL_MOTION_PX_PER_SLOT).abs() < 1e-3);
    }
}
