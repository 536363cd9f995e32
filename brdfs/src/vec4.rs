//! Four-lane helpers on `glam::Vec4` for scalar hot paths that work on a
//! few independent values at once (the three angles of the `Tabulated`
//! coordinates, the channels of a conductor's Fresnel term, OpenPBR's two
//! GGX roughnesses in `microfacet::ggx_pair`).

use radiometry::glam::Vec4;

/// The lane square roots of `x` (IEEE, correctly rounded: bit-identical to
/// `sqrtf` per lane): one vector instruction with the `simd` feature (via
/// `wide`; glam's `Vec4::sqrt` takes four scalar roots).
#[inline(always)]
pub(crate) fn sqrt4(x: Vec4) -> Vec4 {
    #[cfg(feature = "simd")]
    {
        let w = wide::f32x4::from(x.to_array()).sqrt();
        Vec4::from_array(w.to_array())
    }
    #[cfg(not(feature = "simd"))]
    x.sqrt()
}
