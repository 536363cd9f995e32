//! Sums of lights: references, slices, arrays and tuples, all without allocation.

use super::*;

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
    fn irradiance_estimate<I: Integrator>(
        &self,
        integrator: &I,
        budget: u32,
    ) -> Result<WideEstimate<Self::Spectrum>, IntegrateError> {
        (**self).irradiance_estimate(integrator, budget)
    }
    fn reflected_radiance<B, I>(
        &self,
        brdf: &B,
        wo: Vec3,
        integrator: &I,
        budget: u32,
    ) -> Result<WideEstimate<Self::Spectrum>, IntegrateError>
    where
        B: Brdf<Spectrum = Self::Spectrum>,
        I: Integrator,
    {
        (**self).reflected_radiance(brdf, wo, integrator, budget)
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
    fn irradiance_estimate<I: Integrator>(
        &self,
        integrator: &I,
        budget: u32,
    ) -> Result<WideEstimate<Self::Spectrum>, IntegrateError> {
        let mut acc = zero_estimate::<L::Spectrum>();
        for l in self {
            acc = add_estimates(acc, l.irradiance_estimate(integrator, budget)?);
        }
        Ok(acc)
    }
    fn reflected_radiance<B, I>(
        &self,
        brdf: &B,
        wo: Vec3,
        integrator: &I,
        budget: u32,
    ) -> Result<WideEstimate<Self::Spectrum>, IntegrateError>
    where
        B: Brdf<Spectrum = Self::Spectrum>,
        I: Integrator,
    {
        let mut acc = zero_estimate::<L::Spectrum>();
        for l in self {
            acc = add_estimates(acc, l.reflected_radiance(brdf, wo, integrator, budget)?);
        }
        Ok(acc)
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
    fn irradiance_estimate<I: Integrator>(
        &self,
        integrator: &I,
        budget: u32,
    ) -> Result<WideEstimate<Self::Spectrum>, IntegrateError> {
        self.as_slice().irradiance_estimate(integrator, budget)
    }
    fn reflected_radiance<B, I>(
        &self,
        brdf: &B,
        wo: Vec3,
        integrator: &I,
        budget: u32,
    ) -> Result<WideEstimate<Self::Spectrum>, IntegrateError>
    where
        B: Brdf<Spectrum = Self::Spectrum>,
        I: Integrator,
    {
        self.as_slice().reflected_radiance(brdf, wo, integrator, budget)
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
            fn irradiance_estimate<I: Integrator>(
                &self,
                integrator: &I,
                budget: u32,
            ) -> Result<WideEstimate<Self::Spectrum>, IntegrateError> {
                let ($first, $($rest,)*) = self;
                let acc = $first.irradiance_estimate(integrator, budget)?;
                $(let acc = add_estimates(acc, $rest.irradiance_estimate(integrator, budget)?);)*
                Ok(acc)
            }
            #[allow(non_snake_case)]
            fn reflected_radiance<Br, I>(
                &self,
                brdf: &Br,
                wo: Vec3,
                integrator: &I,
                budget: u32,
            ) -> Result<WideEstimate<Self::Spectrum>, IntegrateError>
            where
                Br: Brdf<Spectrum = Self::Spectrum>,
                I: Integrator,
            {
                let ($first, $($rest,)*) = self;
                let acc = $first.reflected_radiance(brdf, wo, integrator, budget)?;
                $(let acc = add_estimates(acc, $rest.reflected_radiance(brdf, wo, integrator, budget)?);)*
                Ok(acc)
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
