//! The parameter combinations of `tests/data/openpbr_adobe.json` as
//! `OpenPbrParams`, and the channel average of a material as a monochrome
//! BRDF: shared by the conformance test (`openpbr_conformance.rs`) and the
//! example that prints the docs' tables (`examples/openpbr_conformance_table.rs`),
//! each of which includes this file with `#[path]`.

use radiometry::glam::Vec3;
use radiometry::{Brdf, BrdfSample, Spectrum};
use radiometry_brdfs::openpbr::{OpenPbr, OpenPbrParams};
use serde_json::Value;

fn colour(v: &Value) -> Vec3 {
    match v {
        Value::Array(a) => Vec3::new(
            a[0].as_f64().unwrap() as f32,
            a[1].as_f64().unwrap() as f32,
            a[2].as_f64().unwrap() as f32,
        ),
        v => Vec3::splat(v.as_f64().unwrap() as f32),
    }
}

/// The combination's parameters (OpenPBR names; the rest at the defaults).
pub fn params(p: &Value) -> OpenPbrParams<Vec3> {
    let mut o = OpenPbrParams::<Vec3>::default();
    for (k, v) in p.as_object().unwrap() {
        let f = || v.as_f64().unwrap() as f32;
        match k.as_str() {
            "base_weight" => o.base_weight = f(),
            "base_color" => o.base_color = colour(v),
            "base_metalness" => o.base_metalness = f(),
            "base_diffuse_roughness" => o.base_diffuse_roughness = f(),
            "specular_weight" => o.specular_weight = f(),
            "specular_color" => o.specular_color = colour(v),
            "specular_roughness" => o.specular_roughness = f(),
            "specular_ior" => o.specular_ior = f(),
            "coat_weight" => o.coat_weight = f(),
            "coat_color" => o.coat_color = colour(v),
            "coat_roughness" => o.coat_roughness = f(),
            "coat_ior" => o.coat_ior = f(),
            "coat_darkening" => o.coat_darkening = f(),
            "fuzz_weight" => o.fuzz_weight = f(),
            "fuzz_color" => o.fuzz_color = colour(v),
            "fuzz_roughness" => o.fuzz_roughness = f(),
            other => panic!("parameter {other} not mapped"),
        }
    }
    o
}

/// The channel average of a material, as a monochrome BRDF to integrate.
pub struct Average<'a>(pub &'a OpenPbr<Vec3>);
impl Brdf for Average<'_> {
    type Spectrum = f32;
    fn eval(&self, wi: Vec3, wo: Vec3) -> f32 {
        self.0.eval(wi, wo).average()
    }
    fn sample(&self, wo: Vec3, u: [f32; 2]) -> Option<BrdfSample<f32>> {
        self.0.sample(wo, u).map(|s| BrdfSample {
            wi: s.wi,
            pdf: s.pdf,
            weight: s.weight.average(),
        })
    }
    fn pdf(&self, wi: Vec3, wo: Vec3) -> f32 {
        self.0.pdf(wi, wo)
    }
}

/// The mean of a JSON `[r, g, b]`.
pub fn avg3(v: &Value) -> f64 {
    let a = v.as_array().unwrap();
    a.iter().map(|x| x.as_f64().unwrap()).sum::<f64>() / 3.0
}

/// The per-sample variance (not clamped) of the channel-average sample
/// weight `f cos θi / pdf` at `wo` over `n` iid uniform samples of a fixed
/// seed, a failed sample counting 0 — how `energy.variance` of the data file
/// was measured on Adobe's side.
pub fn weight_variance(m: &OpenPbr<Vec3>, wo: Vec3, n: usize) -> f64 {
    let mut s = 0x853C_49E6_748F_EA9Bu64;
    let mut rnd = move || {
        s ^= s >> 12;
        s ^= s << 25;
        s ^= s >> 27;
        ((s.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 40) as f32) / (1u32 << 24) as f32
    };
    let v = m.prepare(wo);
    let (mut sum, mut sum2) = (0.0f64, 0.0f64);
    for _ in 0..n {
        let w = v
            .sample([rnd(), rnd()])
            .map_or(0.0, |x| f64::from(x.weight.average()));
        sum += w;
        sum2 += w * w;
    }
    let mean = sum / n as f64;
    sum2 / n as f64 - mean * mean
}
