//! Sums of lights: references, slices, arrays and tuples, all without allocation.

use super::{Light, PartVisitor};
use crate::integrator::IntegrateError;
use crate::spectrum::Spectrum;
use glam::Vec3;

impl<L: Light + ?Sized> Light for &L {
    type Spectrum = L::Spectrum;
    fn radiance(&self, w: Vec3) -> Self::Spectrum {
        (**self).radiance(w)
    }
    fn has_delta(&self) -> bool {
        (**self).has_delta()
    }
    fn closed_form_irradiance(&self) -> Option<Self::Spectrum> {
        (**self).closed_form_irradiance()
    }
    fn for_each_part(&self, f: &mut PartVisitor<'_, Self::Spectrum>) -> Result<(), IntegrateError> {
        (**self).for_each_part(f)
    }
}

/// A homogeneous sum of lights (e.g. several suns). Empty: no light.
impl<L: Light> Light for [L] {
    type Spectrum = L::Spectrum;
    fn radiance(&self, w: Vec3) -> Self::Spectrum {
        self.iter()
            .fold(L::Spectrum::zero(), |acc, l| acc + l.radiance(w))
    }
    fn has_delta(&self) -> bool {
        self.iter().any(|l| l.has_delta())
    }
    fn closed_form_irradiance(&self) -> Option<Self::Spectrum> {
        self.iter().try_fold(L::Spectrum::zero(), |acc, l| {
            Some(acc + l.closed_form_irradiance()?)
        })
    }
    fn for_each_part(&self, f: &mut PartVisitor<'_, Self::Spectrum>) -> Result<(), IntegrateError> {
        for l in self {
            l.for_each_part(f)?;
        }
        Ok(())
    }
}

impl<L: Light, const N: usize> Light for [L; N] {
    type Spectrum = L::Spectrum;
    fn radiance(&self, w: Vec3) -> Self::Spectrum {
        self.as_slice().radiance(w)
    }
    fn has_delta(&self) -> bool {
        self.as_slice().has_delta()
    }
    fn closed_form_irradiance(&self) -> Option<Self::Spectrum> {
        self.as_slice().closed_form_irradiance()
    }
    fn for_each_part(&self, f: &mut PartVisitor<'_, Self::Spectrum>) -> Result<(), IntegrateError> {
        self.as_slice().for_each_part(f)
    }
}

macro_rules! tuple_light {
    ($first:ident $(, $rest:ident)*) => {
        /// A heterogeneous sum of lights with the same spectrum.
        impl<$first: Light, $($rest: Light<Spectrum = $first::Spectrum>),*> Light for ($first, $($rest,)*) {
            type Spectrum = $first::Spectrum;
            #[allow(non_snake_case)]
            fn radiance(&self, w: Vec3) -> Self::Spectrum {
                let ($first, $($rest,)*) = self;
                $first.radiance(w) $(+ $rest.radiance(w))*
            }
            #[allow(non_snake_case)]
            fn has_delta(&self) -> bool {
                let ($first, $($rest,)*) = self;
                $first.has_delta() $(|| $rest.has_delta())*
            }
            #[allow(non_snake_case, clippy::needless_question_mark)]
            fn closed_form_irradiance(&self) -> Option<Self::Spectrum> {
                let ($first, $($rest,)*) = self;
                Some($first.closed_form_irradiance()? $(+ $rest.closed_form_irradiance()?)*)
            }
            #[allow(non_snake_case)]
            fn for_each_part(
                &self,
                f: &mut PartVisitor<'_, Self::Spectrum>,
            ) -> Result<(), IntegrateError> {
                let ($first, $($rest,)*) = self;
                $first.for_each_part(f)?;
                $($rest.for_each_part(f)?;)*
                Ok(())
            }
        }
    };
}

tuple_light!(A);
tuple_light!(A, B);
tuple_light!(A, B, C);
tuple_light!(A, B, C, D);
tuple_light!(A, B, C, D, E);
tuple_light!(A, B, C, D, E, F);
