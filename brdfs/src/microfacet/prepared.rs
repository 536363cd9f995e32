//! What a [`Microfacet`](super::Microfacet) lobe keeps of its directional
//! albedo's table reads once [prepared](radiometry::Brdf::with_prepared_albedo):
//! the roughness and index cells and their interpolation weights, so that a
//! read at `ωo` is the one-dimensional interpolation in `μo` that is left.
//! They live in the lobe's [`Dielectric`](super::Dielectric) term (the one
//! Fresnel term the ratio tables read), so that no other lobe grows.

use super::fresnel_table::{DielectricAlbedoReader, RatioCells, dielectric_error};

/// The cells of a GGX (height-correlated `G2`) dielectric lobe's albedo
/// `E_F(μ) = E₁(μ) R(μ)` at roughness `alpha`, with the error the full read
/// states there ([`dielectric_error`]); a lobe whose roughness is no longer
/// `alpha` does not use them.
#[derive(Clone, Copy, Debug)]
pub struct DielectricCells {
    pub(crate) alpha: f32,
    pub(crate) error: f32,
    /// [`dielectric_average`](super::fresnel_table::dielectric_average) at
    /// `(α, η)`, read with the same cells.
    pub(crate) average: f32,
    pub(crate) reader: DielectricAlbedoReader,
}

impl DielectricCells {
    /// The cells of `E_F(·, α, η)`.
    #[inline]
    pub(crate) fn new(alpha: f32, eta: f32) -> Self {
        Self::new_in(RatioCells::new(alpha, eta), alpha, eta)
    }

    /// [`new`](Self::new) from the ratio table's cells of `(α, η)`
    /// computed once, bit for bit.
    #[inline(always)]
    pub(crate) fn new_in(cells: RatioCells, alpha: f32, eta: f32) -> Self {
        let (reader, average) = DielectricAlbedoReader::with_average_in(cells, alpha, eta);
        Self {
            alpha,
            error: dielectric_error(alpha, eta),
            average,
            reader,
        }
    }

    /// These cells if they were built for roughness `alpha`.
    #[inline(always)]
    pub(crate) fn for_alpha(&self, alpha: f32) -> Option<&Self> {
        (self.alpha == alpha).then_some(self)
    }
}

#[cfg(test)]
mod tests {
    extern crate std;

    use super::super::{
        Beckmann, Dielectric, Fresnel, Ggx, HeightCorrelated, Microfacet, MicrofacetDistribution, NoFresnel,
        Schlick, Separable, ShadowingMasking,
    };
    use crate::Eon;
    use crate::test_stream::uniforms;
    use radiometry::compose::Coated;
    use radiometry::glam::Vec3;
    use radiometry::{Brdf, Spectrum};

    /// The largest difference between a prepared lobe's albedo and the full
    /// read's, per channel, that the layer test allows: the readers' own
    /// bound against the plain reads (the prepared read is in fact the same
    /// arithmetic, and [`prepared_albedo_equals_the_full_read`] asserts
    /// equality).
    const ROUNDING: f32 = 2e-6;

    /// A direction at `μ = cos θ` and azimuth `φ` (unit to rounding).
    fn dir(mu: f32, phi: f32) -> Vec3 {
        let s = radiometry::math::sqrtf((1.0 - mu * mu).max(0.0));
        Vec3::new(s * libm::cosf(phi), s * libm::sinf(phi), mu)
    }

    /// `prepared` reads what `full` reads at `wo`: the same value per
    /// channel (the same operations on the same table entries, the roughness
    /// and index work done once), the same stated error and kind.
    fn assert_same_albedo<D, G, F>(full: &Microfacet<D, G, F>, wo: Vec3, what: &str)
    where
        D: MicrofacetDistribution + Copy,
        G: ShadowingMasking,
        F: Fresnel + Copy,
    {
        let prepared = full.with_prepared_albedo();
        let (a, b) = (full.directional_albedo(wo), prepared.directional_albedo(wo));
        for c in 0..F::Spectrum::CHANNELS {
            let (x, y) = (a.value.channel(c), b.value.channel(c));
            assert!(
                x == y,
                "{what} α {} ωo {wo}: full {x}, prepared {y}",
                full.distribution.alpha()
            );
        }
        assert_eq!((a.error, a.is_bound), (b.error, b.is_bound), "{what} ωo {wo}");
    }

    /// Cells built from the ratio table's cells computed once
    /// ([`DielectricCells::new_in`], as `OpenPbr` builds its dielectric
    /// lobes) are the cells [`DielectricCells::new`] builds — reader,
    /// average, error, roughness —, their roughness cell is the metal's
    /// Fresnel-moment cell, and the shared index cell's average at
    /// another roughness is [`dielectric_average`] there, bit for bit.
    #[test]
    fn cells_from_shared_cells_are_new() {
        use super::super::fresnel_table::{RatioCells, dielectric_average};
        let mut u = uniforms(0x5EED_CE11_0000_0002);
        for n in 0..4_000 {
            let alpha = match n % 10 {
                0 => 1e-4,
                1 => 1.0,
                _ => (u() * u()).max(1e-4),
            };
            let eta = match n % 5 {
                0 => 1.0,
                1 => 0.2 + 0.79 * u(),
                _ => 1.0 + 3.0 * u(),
            };
            let cells = RatioCells::new(alpha, eta);
            let (a, b) = (
                super::DielectricCells::new_in(cells, alpha, eta),
                super::DielectricCells::new(alpha, eta),
            );
            assert_eq!(a.reader, b.reader, "α {alpha} η {eta}");
            assert_eq!(
                (a.alpha.to_bits(), a.average.to_bits(), a.error.to_bits()),
                (b.alpha.to_bits(), b.average.to_bits(), b.error.to_bits()),
                "α {alpha} η {eta}"
            );
            assert_eq!(
                super::super::fresnel_table::MomentCell::at(cells.alpha),
                super::super::fresnel_table::MomentCell::new(alpha),
                "α {alpha}"
            );
            let other = (u() * u()).max(1e-4);
            for a2 in [crate::microfacet::MIN_ALPHA, other] {
                assert_eq!(
                    cells.average_at(a2).to_bits(),
                    dielectric_average(a2, eta).to_bits(),
                    "α' {a2} η {eta}"
                );
            }
        }
    }

    /// Prepared lobes against the full read on random `(α, η, μ)` (the
    /// dielectric ones read through their cells, the others are returned as
    /// they are):
    /// roughness from near-delta to 1 (and the table's own nodes and both
    /// ends), indices on both sides of 1, `μ` spread in `√μ` so grazing is
    /// covered, with non-unit and below-horizon directions.
    #[test]
    fn prepared_albedo_equals_the_full_read() {
        let mut u = uniforms(0x0051_7cc1_b727_220a);
        for n in 0..6_000 {
            let alpha = match n % 40 {
                0 => 1e-4,
                1 => 1.0,
                2 => 0.2,
                3 => super::super::alpha_node(1 + n % 30),
                _ => {
                    let s = u();
                    (s * s).max(1e-4)
                }
            };
            let eta = match n % 5 {
                0 => 1.0 + 1e-3,
                1 => 0.3 + 0.69 * u(),
                _ => 1.0 + 2.0 * u(),
            };
            let mu = match n % 13 {
                0 => 1.0,
                1 => 0.0,
                _ => {
                    let s = u();
                    s * s
                }
            };
            let wo = match n % 17 {
                0 => 3.0 * dir(mu, 6.0 * u()),
                1 => -dir(mu, 6.0 * u()),
                _ => dir(mu, 6.0 * u()),
            };
            let ggx = Ggx::new(alpha).unwrap();
            let beckmann = Beckmann::new(alpha).unwrap();
            let dielectric = Microfacet::<_, HeightCorrelated, _>::new(ggx, Dielectric::new(eta).unwrap());
            assert_same_albedo(&dielectric, wo, "GGX dielectric");
            let f0 = Vec3::new(u(), u(), u());
            let schlick = Microfacet::<_, HeightCorrelated, _>::new(ggx, Schlick::new(f0).unwrap());
            assert_same_albedo(&schlick, wo, "GGX Schlick RGB");
            assert_same_albedo(
                &Microfacet::<_, Separable, _>::new(ggx, NoFresnel),
                wo,
                "GGX separable F = 1",
            );
            assert_same_albedo(
                &Microfacet::<_, HeightCorrelated, _>::new(beckmann, NoFresnel),
                wo,
                "Beckmann F = 1",
            );
        }
    }

    /// A prepared lobe whose public fields are changed afterwards reads the
    /// tables of its new parameters (bit for bit the full read), never the
    /// stale cells; a prepared term moved into a lobe of another
    /// distribution is not read; and a prepared lobe is the same BRDF as the
    /// lobe it was prepared from.
    #[test]
    fn prepared_cells_follow_the_parameters() {
        let wo = dir(0.35, 0.4);
        let lobe =
            Microfacet::<_, HeightCorrelated, _>::new(Ggx::new(0.1).unwrap(), Dielectric::new(1.5).unwrap());
        let mut changed = lobe.with_prepared_albedo();
        changed.distribution = Ggx::new(0.5).unwrap();
        let fresh =
            Microfacet::<_, HeightCorrelated, _>::new(Ggx::new(0.5).unwrap(), Dielectric::new(1.5).unwrap());
        assert_eq!(changed.directional_albedo(wo), fresh.directional_albedo(wo));
        assert_ne!(changed.directional_albedo(wo), lobe.directional_albedo(wo));
        changed.fresnel = Dielectric::new(1.2).unwrap();
        let fresh =
            Microfacet::<_, HeightCorrelated, _>::new(Ggx::new(0.5).unwrap(), Dielectric::new(1.2).unwrap());
        assert_eq!(changed.directional_albedo(wo), fresh.directional_albedo(wo));
        // The cells of a GGX lobe in a Beckmann lobe of the same roughness.
        let mut beckmann = Microfacet::<_, HeightCorrelated, _>::new(
            Beckmann::new(0.1).unwrap(),
            Dielectric::new(1.5).unwrap(),
        );
        let full = beckmann.directional_albedo(wo);
        beckmann.fresnel = lobe.with_prepared_albedo().fresnel;
        assert!(beckmann.fresnel.albedo_cells(0.1).is_some());
        assert_eq!(beckmann.directional_albedo(wo), full);

        let prepared = lobe.with_prepared_albedo();
        assert_eq!(prepared, lobe);
        let mut u = uniforms(7);
        for _ in 0..500 {
            let (wi, wo) = (dir(u(), 6.0 * u()), dir(u(), 6.0 * u()));
            assert_eq!(prepared.eval(wi, wo).to_bits(), lobe.eval(wi, wo).to_bits());
            assert_eq!(prepared.pdf(wi, wo).to_bits(), lobe.pdf(wi, wo).to_bits());
            let v = [u(), u()];
            assert_eq!(prepared.sample(wo, v), lobe.sample(wo, v));
        }
    }

    /// The prepared cells keep a lobe a small plain value: the plastic's top
    /// (GGX, dielectric) fits in two cache lines (8 bytes before the cells
    /// existed); lobes without a dielectric term carry none.
    #[test]
    fn prepared_lobe_stays_small() {
        use core::mem::size_of;
        let top = size_of::<Microfacet<Ggx, HeightCorrelated, Dielectric>>();
        let reader = size_of::<super::DielectricCells>();
        std::eprintln!(
            "size_of: Microfacet<Ggx, HeightCorrelated, Dielectric> {top}, DielectricCells {reader}, \
             Coated<that, Eon<f32>> {}, OpenPbr<f32> {}, OpenPbr<Vec3> {}",
            size_of::<Coated<Microfacet<Ggx, HeightCorrelated, Dielectric>, Eon<f32>>>(),
            size_of::<crate::OpenPbr<f32>>(),
            size_of::<crate::OpenPbr<Vec3>>()
        );
        assert!(top <= 128, "{top} bytes");
        assert_eq!(size_of::<Microfacet<Ggx, HeightCorrelated, NoFresnel>>(), 4);
    }

    /// The plastic (`Coated::new` keeps its top prepared) against the
    /// layer's formula `f_T + (1 − E_T(μo)) f_B` with the top's full read:
    /// equal to the readers' rounding times `f_B`, on random pairs; and
    /// `pdf(sample) == sample.pdf` bit for bit.
    #[test]
    fn plastic_layer_is_unchanged_by_the_prepared_read() {
        let top =
            Microfacet::<_, HeightCorrelated, _>::new(Ggx::new(0.1).unwrap(), Dielectric::new(1.5).unwrap());
        let base = Eon::new(0.8f32, 0.5).unwrap();
        let plastic = Coated::new(top, base);
        let mut u = uniforms(0x00a1_1ed0);
        for _ in 0..5_000 {
            let (wi, wo) = (dir(u(), 6.0 * u()), dir(u(), 6.0 * u()));
            let (ft, fb) = (top.eval(wi, wo), base.eval(wi, wo));
            let et = top.directional_albedo(wo).value.clamp(0.0, 1.0);
            let want = ft + (1.0 - et) * fb;
            let got = plastic.eval(wi, wo);
            assert!(
                (got - want).abs() <= ROUNDING * fb + 2.0 * f32::EPSILON * want,
                "ωi {wi} ωo {wo}: {got} vs {want}"
            );
            if let Some(s) = plastic.sample(wo, [u(), u()]) {
                assert_eq!(plastic.pdf(s.wi, wo).to_bits(), s.pdf.to_bits());
            }
        }
    }
}
