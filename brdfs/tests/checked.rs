//! The checked paths a layer takes ([`Brdf::eval_checked`], [`Brdf::pdf_checked`],
//! [`Brdf::albedo_checked`]): a layer tests its directions once
//! ([`radiometry::frame::is_checked`]: unit to within `4ε` and above the horizon) and then calls
//! its lobes without their own tests. These hold the shortcut to the general path:
//!
//! * `hooks_return_the_general_bits`: for every lobe that overrides a hook (the microfacet lobes
//!   with each distribution, shadowing and Fresnel term, prepared and not; EON, FON,
//!   Oren–Nayar), the hook returns what `eval`, `pdf` and the clamped `directional_albedo`
//!   return, bit for bit, at random checked directions (a hook that skipped a step of the
//!   general path — a normalisation, a clamp, the prepared read — fails here);
//! * `composites_are_unchanged`: `Coated`, `Mix`, `Sum` and `Scaled` (alone and nested) over lobes
//!   with the hooks give the bits of the same composite over the same lobes behind a wrapper
//!   that hides the hooks (the defaults, i.e. the general path), for `eval`, `pdf`, `sample` (and
//!   a `Coated`'s prepared view), at checked directions, at directions a rounding off unit
//!   length, well off it, below the horizon and not finite;
//! * `composite_formulas_hold_at_checked_directions`: the composites' own checked paths (the
//!   shortcut each takes before it calls its lobes) against their documented formulas written
//!   here from the lobes' public calls — `Mix` `sat(w f_A + (1 − w) f_B)`, `Sum` `sat(f_A + f_B)`,
//!   `Scaled` `s f`, `Coated` `sat(f_T + (1 − E_T(ωo)) f_B)`, and each mixture density `p pdf_A +
//!   (1 − p) pdf_B` with the composite's public pick probability — bit for bit.

use radiometry::compose::{Coated, Mix, Scaled, Sum};
use radiometry::frame::is_checked;
use radiometry::glam::Vec3;
use radiometry::{Albedo, Brdf, BrdfSample, Spectrum};
use radiometry_brdfs::microfacet::{
    Beckmann, Conductor, Dielectric, Ggx, HeightCorrelated, Microfacet, NoFresnel, Schlick, Separable,
};
use radiometry_brdfs::{Eon, Fon, OrenNayar};

/// xorshift64 uniforms in `[0, 1)`.
fn uniforms(mut s: u64) -> impl FnMut() -> f32 {
    move || {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        ((s >> 40) as f32) / (1u64 << 24) as f32
    }
}

/// A direction of the upper hemisphere from two uniforms (`cos θ ∈ [10⁻³, 1]`), grazing ones
/// included.
fn upper(u: &mut impl FnMut() -> f32) -> Vec3 {
    let z = u().max(1e-3);
    let phi = core::f32::consts::TAU * u();
    let r = (1.0 - z * z).max(0.0).sqrt();
    Vec3::new(r * phi.cos(), r * phi.sin(), z)
}

fn bits<S: Spectrum>(s: S) -> Vec<u32> {
    (0..S::CHANNELS).map(|c| s.channel(c).to_bits()).collect()
}

fn clamped<S: Spectrum>(a: Albedo<S>) -> S {
    a.value
        .map(|v| if v.is_finite() { v.clamp(0.0, 1.0) } else { 0.0 })
}

/// Asserts the three hooks of `b` equal the general calls at `n` random checked pairs.
fn assert_hooks<B: Brdf>(name: &str, b: &B, seed: u64, n: usize) {
    let mut u = uniforms(seed);
    let mut checked = 0;
    for _ in 0..n {
        let (wi, wo) = (upper(&mut u), upper(&mut u));
        if !(is_checked(wi) && is_checked(wo)) {
            continue;
        }
        checked += 1;
        assert_eq!(
            bits(b.eval_checked(wi, wo)),
            bits(b.eval(wi, wo)),
            "{name} eval at {wi} {wo}"
        );
        assert_eq!(
            b.pdf_checked(wi, wo).to_bits(),
            b.pdf(wi, wo).to_bits(),
            "{name} pdf at {wi} {wo}"
        );
        assert_eq!(
            bits(b.albedo_checked(wo)),
            bits(clamped(b.directional_albedo(wo))),
            "{name} albedo at {wo}"
        );
    }
    // Nearly every random direction of `upper` is unit to within 4ε.
    assert!(
        checked > n * 9 / 10,
        "{name}: only {checked} of {n} pairs checked"
    );
}

#[test]
fn hooks_return_the_general_bits() {
    let n = 3_000;
    for (k, alpha) in [1e-4f32, 0.01, 0.1, 0.3, 0.8].into_iter().enumerate() {
        let seed = 0x9e37_79b9_7f4a_7c15 ^ k as u64;
        let g = Ggx::new(alpha).unwrap();
        let b = Beckmann::new(alpha).unwrap();
        let d = Dielectric::new(1.5).unwrap();
        let d_in = Dielectric::new(1.0 / 1.33).unwrap();
        let cu = Conductor::new(Vec3::new(0.27, 0.68, 1.32), Vec3::new(3.61, 2.62, 2.29)).unwrap();
        let sch = Schlick::new(Vec3::new(0.9, 0.6, 0.3)).unwrap();
        let top = Microfacet::<_, HeightCorrelated, _>::new(g, d);
        assert_hooks("ggx hc dielectric", &top, seed, n);
        assert_hooks(
            "ggx hc dielectric, prepared",
            &top.with_prepared_albedo(),
            seed,
            n,
        );
        let inside = Microfacet::<_, HeightCorrelated, _>::new(g, d_in);
        assert_hooks(
            "ggx hc dielectric η < 1, prepared",
            &inside.with_prepared_albedo(),
            seed,
            n,
        );
        assert_hooks(
            "ggx sep dielectric",
            &Microfacet::<_, Separable, _>::new(g, d),
            seed,
            n,
        );
        assert_hooks(
            "ggx hc none",
            &Microfacet::<_, HeightCorrelated, _>::new(g, NoFresnel),
            seed,
            n,
        );
        assert_hooks(
            "ggx hc conductor",
            &Microfacet::<_, HeightCorrelated, _>::new(g, cu),
            seed,
            n,
        );
        assert_hooks(
            "ggx hc schlick",
            &Microfacet::<_, HeightCorrelated, _>::new(g, sch),
            seed,
            n,
        );
        assert_hooks(
            "beckmann hc dielectric",
            &Microfacet::<_, HeightCorrelated, _>::new(b, d),
            seed,
            n,
        );
        assert_hooks(
            "beckmann sep none",
            &Microfacet::<_, Separable, _>::new(b, NoFresnel),
            seed,
            n,
        );
    }
    for (k, sigma) in [0.0f32, 0.3, 1.0].into_iter().enumerate() {
        let seed = 0x2545_f491_4f6c_dd1d ^ k as u64;
        assert_hooks("eon", &Eon::new(0.8f32, sigma).unwrap(), seed, n);
        assert_hooks(
            "eon rgb",
            &Eon::new(Vec3::new(0.9, 0.5, 0.1), sigma).unwrap(),
            seed,
            n,
        );
        assert_hooks("fon", &Fon::new(0.7f32, sigma).unwrap(), seed, n);
        assert_hooks("oren-nayar", &OrenNayar::new(0.6f32, sigma).unwrap(), seed, n);
    }
}

/// `B` behind the default hooks: every other method forwards (preparation and averages
/// included, so that a layer over it holds the same prepared top).
#[derive(Clone, Copy, Debug)]
struct Plain<B>(B);

impl<B: Brdf> Brdf for Plain<B> {
    type Spectrum = B::Spectrum;
    fn eval(&self, wi: Vec3, wo: Vec3) -> Self::Spectrum {
        self.0.eval(wi, wo)
    }
    fn sample(&self, wo: Vec3, u: [f32; 2]) -> Option<BrdfSample<Self::Spectrum>> {
        self.0.sample(wo, u)
    }
    fn pdf(&self, wi: Vec3, wo: Vec3) -> f32 {
        self.0.pdf(wi, wo)
    }
    fn sampling_components(&self) -> usize {
        self.0.sampling_components()
    }
    fn component_weight(&self, wo: Vec3, k: usize) -> f32 {
        self.0.component_weight(wo, k)
    }
    fn sample_component(&self, wo: Vec3, k: usize, u: [f32; 2]) -> Option<Vec3> {
        self.0.sample_component(wo, k, u)
    }
    fn directional_albedo(&self, wo: Vec3) -> Albedo<Self::Spectrum> {
        self.0.directional_albedo(wo)
    }
    fn average_albedo(&self) -> Self::Spectrum {
        self.0.average_albedo()
    }
    fn with_prepared_albedo(self) -> Self {
        Plain(self.0.with_prepared_albedo())
    }
}

fn sample_bits<S: Spectrum>(s: Option<BrdfSample<S>>) -> Option<(Vec<u32>, Vec<u32>, u32)> {
    s.map(|s| {
        let w = [s.wi.x, s.wi.y, s.wi.z].iter().map(|v| v.to_bits()).collect();
        (w, bits(s.weight), s.pdf.to_bits())
    })
}

/// A direction of one of the kinds a caller may pass (see the module docs).
fn any_direction(u: &mut impl FnMut() -> f32, kind: u32) -> Vec3 {
    let w = upper(u);
    match kind {
        0..=5 => w,
        6 => w * (1.0 + 3.0 * f32::EPSILON),
        7 => w * (1.0 + 1e-4),
        8 => w * 0.5,
        9 => w.with_z(-w.z),
        10 => Vec3::new(w.x, w.y, 0.0),
        _ => Vec3::new(f32::NAN, w.y, w.z),
    }
}

/// Asserts `fast` and `plain` (the same composite, its lobes behind [`Plain`]) agree bit for bit
/// on random input of every kind; `view` compares their prepared views where they have one.
fn assert_unchanged<F, P, S>(
    name: &str,
    fast: &F,
    plain: &P,
    seed: u64,
    view: impl Fn(Vec3, Vec3, [f32; 2]) -> [Option<Vec<u32>>; 3],
) where
    F: Brdf<Spectrum = S>,
    P: Brdf<Spectrum = S>,
    S: Spectrum,
{
    let mut u = uniforms(seed);
    let mut fast_paths = 0;
    for k in 0..4_000u32 {
        let (wi, wo) = (
            any_direction(&mut u, k % 12),
            any_direction(&mut u, (k / 12) % 12),
        );
        let uu = [u(), u()];
        fast_paths += usize::from(is_checked(wi) && is_checked(wo));
        let at = format!("{name} at {wi} {wo}");
        assert_eq!(bits(fast.eval(wi, wo)), bits(plain.eval(wi, wo)), "eval {at}");
        assert_eq!(
            fast.pdf(wi, wo).to_bits(),
            plain.pdf(wi, wo).to_bits(),
            "pdf {at}"
        );
        assert_eq!(
            sample_bits(fast.sample(wo, uu)),
            sample_bits(plain.sample(wo, uu)),
            "sample {at}"
        );
        let [a, b, c] = view(wi, wo, uu);
        assert!(a.is_none() || (a == b && b == c), "view {at}: {a:?} {b:?} {c:?}");
    }
    // About (6/12)² of the pairs take the checked path, the rest the general one.
    assert!(
        (700..1_300).contains(&fast_paths),
        "{name}: {fast_paths} checked pairs"
    );
}

/// [`assert_unchanged`] for `Coated::new(top, base)`, its prepared views included.
fn assert_layer_unchanged<T, B, S>(name: &str, top: T, base: B, seed: u64)
where
    T: Brdf<Spectrum = S> + Copy,
    B: Brdf<Spectrum = S> + Copy,
    S: Spectrum,
{
    let fast = Coated::new(top, base);
    let plain = Coated::new(Plain(top), Plain(base));
    assert_unchanged(name, &fast, &plain, seed, |wi, wo, uu| {
        let (vf, vp) = (fast.prepare(wo), plain.prepare(wo));
        let key = |e: S, p: f32, s: Option<BrdfSample<S>>| {
            let mut v = bits(e);
            v.push(p.to_bits());
            if let Some((w, x, q)) = sample_bits(s) {
                v.extend(w);
                v.extend(x);
                v.push(q);
            }
            v
        };
        let (a, b) = (
            key(vf.eval(wi), vf.pdf(wi), vf.sample(uu)),
            key(vp.eval(wi), vp.pdf(wi), vp.sample(uu)),
        );
        // The view against the plain call at its `ωo` (the docs' promise) and the two views.
        let c = key(fast.eval(wi, wo), fast.pdf(wi, wo), fast.sample(wo, uu));
        [Some(a), Some(b), Some(c)]
    });
}

fn no_view(_: Vec3, _: Vec3, _: [f32; 2]) -> [Option<Vec<u32>>; 3] {
    [None, None, None]
}

#[test]
fn composites_are_unchanged() {
    let g = |a: f32| Ggx::new(a).unwrap();
    let d = Dielectric::new(1.5).unwrap();
    let eon = Eon::new(0.8f32, 0.5).unwrap();
    let plastic_top = Microfacet::<_, HeightCorrelated, _>::new(g(0.1), d);
    assert_layer_unchanged("plastic", plastic_top, eon, 1);
    let rough_top = Microfacet::<_, HeightCorrelated, _>::new(g(0.5), d);
    assert_layer_unchanged("rough top over fon", rough_top, Fon::new(0.5f32, 1.0).unwrap(), 2);
    let beckmann_top = Microfacet::<_, Separable, _>::new(Beckmann::new(0.2).unwrap(), d);
    assert_layer_unchanged(
        "beckmann top",
        beckmann_top,
        OrenNayar::new(0.6f32, 0.2).unwrap(),
        3,
    );
    let metal = Microfacet::<_, HeightCorrelated, _>::new(
        g(0.3),
        Conductor::new(Vec3::new(0.27, 0.68, 1.32), Vec3::new(3.61, 2.62, 2.29)).unwrap(),
    );
    let clear_rgb =
        Microfacet::<_, HeightCorrelated, _>::new(g(0.05), Schlick::new(Vec3::splat(0.04)).unwrap());
    assert_layer_unchanged("rgb clear coat over metal", clear_rgb, metal, 4);

    // A coat mixed over its own substrate (a partial coat), the substrate a sum of two lobes,
    // and a scaled lobe; each against the same tree of plain lobes.
    let spec = Microfacet::<_, HeightCorrelated, _>::new(g(0.3), d);
    for w in [0.0f32, 0.4, 1.0] {
        let fast = Mix::new(w, Coated::new(plastic_top, eon), eon).unwrap();
        let plain = Mix::new(w, Plain(Coated::new(Plain(plastic_top), Plain(eon))), Plain(eon)).unwrap();
        assert_unchanged(&format!("partial coat w = {w}"), &fast, &plain, 5, no_view);
    }
    let fast = Sum::new(spec, Scaled::new(eon, 0.5).unwrap());
    let plain = Sum::new(Plain(spec), Plain(Scaled::new(Plain(eon), 0.5).unwrap()));
    assert_unchanged("sum of spec and scaled eon", &fast, &plain, 6, no_view);
    let fast = Coated::new(plastic_top, Sum::new(spec, Scaled::new(eon, 0.5).unwrap()));
    let plain = Coated::new(
        Plain(plastic_top),
        Plain(Sum::new(
            Plain(spec),
            Plain(Scaled::new(Plain(eon), 0.5).unwrap()),
        )),
    );
    assert_unchanged("coat over a sum", &fast, &plain, 7, no_view);
}

/// `NaN → 0`, `min(f32::MAX)` per channel (the composites' saturation).
fn sat<S: Spectrum>(v: S) -> S {
    v.map(|x| if x.is_nan() { 0.0 } else { x.min(f32::MAX) })
}

/// `p a + (1 − p) b`, 0 unless finite and positive.
fn mixture(p: f32, a: f32, b: f32) -> f32 {
    let v = p * a + (1.0 - p) * b;
    if v.is_finite() && v > 0.0 { v } else { 0.0 }
}

/// Asserts `eval` and `pdf` of `c` equal `eval_ref` and `pdf_ref` at random checked pairs.
fn assert_formula<C: Brdf>(
    name: &str,
    c: &C,
    seed: u64,
    eval_ref: impl Fn(Vec3, Vec3) -> C::Spectrum,
    pdf_ref: impl Fn(Vec3, Vec3) -> f32,
) {
    let mut u = uniforms(seed);
    for _ in 0..3_000 {
        let (wi, wo) = (upper(&mut u), upper(&mut u));
        if !(is_checked(wi) && is_checked(wo)) {
            continue;
        }
        assert_eq!(
            bits(c.eval(wi, wo)),
            bits(eval_ref(wi, wo)),
            "{name} eval at {wi} {wo}"
        );
        assert_eq!(
            c.pdf(wi, wo).to_bits(),
            pdf_ref(wi, wo).to_bits(),
            "{name} pdf at {wi} {wo}"
        );
    }
}

#[test]
fn composite_formulas_hold_at_checked_directions() {
    let d = Dielectric::new(1.5).unwrap();
    let eon = Eon::new(0.8f32, 0.5).unwrap();
    let spec = Microfacet::<_, HeightCorrelated, _>::new(Ggx::new(0.3).unwrap(), d);
    let layer = Coated::new(
        Microfacet::<_, HeightCorrelated, _>::new(Ggx::new(0.1).unwrap(), d),
        eon,
    );
    let (top, base) = (layer.top(), layer.base());
    assert_formula(
        "coated",
        &layer,
        11,
        |wi, wo| {
            let to = 1.0 - clamped(top.directional_albedo(wo));
            let (ft, fb) = (top.eval(wi, wo), base.eval(wi, wo));
            if fb == 0.0 { ft } else { sat(ft + to * fb) }
        },
        |wi, wo| mixture(layer.pick_probability(wo), top.pdf(wi, wo), base.pdf(wi, wo)),
    );
    for w in [0.0f32, 0.4, 1.0] {
        let m = Mix::new(w, layer, eon).unwrap();
        assert_formula(
            &format!("mix w = {w}"),
            &m,
            12,
            |wi, wo| match w {
                0.0 => eon.eval(wi, wo),
                1.0 => layer.eval(wi, wo),
                _ => sat(layer.eval(wi, wo) * w + eon.eval(wi, wo) * (1.0 - w)),
            },
            |wi, wo| {
                let pa = if w == 0.0 { 0.0 } else { layer.pdf(wi, wo) };
                let pb = if w == 1.0 { 0.0 } else { eon.pdf(wi, wo) };
                mixture(m.pick_probability(wo), pa, pb)
            },
        );
    }
    let scaled = Scaled::new(eon, 0.5).unwrap();
    assert_formula(
        "scaled",
        &scaled,
        13,
        |wi, wo| eon.eval(wi, wo) * 0.5,
        |wi, wo| eon.pdf(wi, wo),
    );
    let sum = Sum::new(spec, scaled);
    assert_formula(
        "sum",
        &sum,
        14,
        |wi, wo| sat(spec.eval(wi, wo) + scaled.eval(wi, wo)),
        |wi, wo| mixture(sum.pick_probability(wo), spec.pdf(wi, wo), scaled.pdf(wi, wo)),
    );
}
