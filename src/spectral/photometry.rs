//! Photometry and colorimetry: lux from spectral irradiance, CIE XYZ,
//! chromaticity, XYZ → linear sRGB.
//!
//! ```
//! use radiometry::spectral::{self, photometry, Scaled};
//! // 1 W/m² of 555 nm light is 683 lx.
//! assert!((photometry::illuminance_monochromatic(555.0, 1.0) - 683.0).abs() < 1e-3);
//! // D65 at 1 W m⁻² nm⁻¹ at 560 nm: 683 lm/W × Σ S(λ)V(λ)Δλ/100 ≈ 683 × 105.67 ≈ 72 200 lx.
//! let e = Scaled::new(spectral::d65(), 0.01);
//! let lux = photometry::illuminance_lux(&e);
//! assert!((lux - 72_174.0).abs() < 100.0);
//! ```

use super::{SpectralCurve, integrate_product, photopic_v, x_bar, y_bar, z_bar};

/// Maximum luminous efficacy of photopic vision, lm/W: the SI definition of
/// the candela fixes 683 lm/W at 540 × 10¹² Hz (≈ 555 nm)
/// (BIPM SI Brochure, 9th ed., 2019; CIE S 017 17-738).
pub const K_M: f32 = 683.0;

/// Step (nm) of the trapezoid rule used for photometric and colorimetric
/// integrals. 1 nm resolves the 5 nm CIE tables exactly at their nodes and
/// narrow-band sources to within their own tabulation.
pub const INTEGRATION_STEP_NM: f32 = 1.0;

/// Illuminance in lux from a spectral irradiance `E_e(λ)` in W·m⁻²·nm⁻¹:
/// `E_v = K_m ∫ E_e(λ) V(λ) dλ` (CIE S 017:2020 17-21-050; CIE 015:2018
/// eq. 7.1 with ȳ = V), integrated over 360–830 nm by the trapezoid rule at
/// [`INTEGRATION_STEP_NM`].
///
/// Domain: any curve. Negative spectral irradiance is integrated as given
/// (it can only arise from a caller's difference of spectra); non-finite
/// values read as 0 by the [`SpectralCurve`] contract.
pub fn illuminance_lux(spectral_irradiance: &impl SpectralCurve) -> f32 {
    K_M * integrate_product(spectral_irradiance, &photopic_v(), INTEGRATION_STEP_NM)
}

/// Illuminance in lux of monochromatic light of wavelength `lambda_nm`
/// and irradiance `irradiance_w_m2`: `E_v = K_m V(λ) E_e`.
/// Zero outside 360–830 nm and for a non-finite wavelength; a non-finite
/// irradiance gives 0; a finite result beyond the `f32` range saturates at
/// `±f32::MAX`.
pub fn illuminance_monochromatic(lambda_nm: f32, irradiance_w_m2: f32) -> f32 {
    if !irradiance_w_m2.is_finite() {
        return 0.0;
    }
    let v = K_M * photopic_v().value(lambda_nm) * irradiance_w_m2;
    v.clamp(-f32::MAX, f32::MAX)
}

/// Tristimulus integrals `(∫E x̄ dλ, ∫E ȳ dλ, ∫E z̄ dλ)` of a spectral
/// quantity (CIE 015:2018 eq. 7.1–7.3 without the normalising constant
/// `k`). Multiply by [`K_M`] for absolute photometric units (then Y is in
/// lux for an irradiance, cd/m² for a radiance), or divide by Y of the
/// white for relative colorimetry.
pub fn xyz(spectrum: &impl SpectralCurve) -> [f32; 3] {
    [
        integrate_product(spectrum, &x_bar(), INTEGRATION_STEP_NM),
        integrate_product(spectrum, &y_bar(), INTEGRATION_STEP_NM),
        integrate_product(spectrum, &z_bar(), INTEGRATION_STEP_NM),
    ]
}

/// Chromaticity coordinates `x = X/(X+Y+Z)`, `y = Y/(X+Y+Z)`
/// (CIE 015:2018 eq. 7.4). `None` when `X+Y+Z` is not a positive finite
/// number (no light, or invalid input).
pub fn chromaticity(xyz: [f32; 3]) -> Option<[f32; 2]> {
    let s = xyz[0] + xyz[1] + xyz[2];
    if !(s.is_finite() && s > 0.0) {
        return None;
    }
    Some([xyz[0] / s, xyz[1] / s])
}

/// The XYZ → linear sRGB matrix of IEC 61966-2-1:1999 eq. (5) (D65 white,
/// ITU-R BT.709 primaries), rows R, G, B.
pub const XYZ_TO_SRGB: [[f32; 3]; 3] = [
    [3.2406, -1.5372, -0.4986],
    [-0.9689, 1.8758, 0.0415],
    [0.0557, -0.2040, 1.0570],
];

/// Linear sRGB from CIE XYZ (Y of the white = 1): `RGB = M · XYZ` with
/// [`XYZ_TO_SRGB`]. No clipping to `[0, 1]`: out-of-gamut colours give
/// components outside it, which the caller may clip. Finite input gives
/// finite output: inputs near the `f32` limit are pre-scaled by 2⁻⁸ and
/// the result saturates at `±f32::MAX`; non-finite components give 0.
///
/// ```
/// use radiometry::spectral::xyz_to_linear_srgb;
/// let rgb = xyz_to_linear_srgb([0.9505, 1.0, 1.089]); // D65 white
/// assert!(rgb.iter().all(|c| (c - 1.0).abs() < 1e-3));
/// assert!(xyz_to_linear_srgb([f32::MAX; 3]).iter().all(|c| c.is_finite()));
/// ```
pub fn xyz_to_linear_srgb(xyz: [f32; 3]) -> [f32; 3] {
    let m = &XYZ_TO_SRGB;
    let xyz = xyz.map(|v| if v.is_finite() { v } else { 0.0 });
    let big = xyz.iter().any(|v| v.abs() > 1.0e36);
    let s = if big { 1.0 / 256.0 } else { 1.0 };
    core::array::from_fn(|r| {
        let v = (m[r][0] * (xyz[0] * s) + m[r][1] * (xyz[1] * s) + m[r][2] * (xyz[2] * s)) / s;
        v.clamp(-f32::MAX, f32::MAX)
    })
}
