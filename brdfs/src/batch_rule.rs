//! The batch length rule ([`radiometry::batch::zero_tail`]) for every
//! plugin, with and without the `simd` feature: mismatched lengths compute
//! the common prefix (equal to the scalar calls, bit for bit) and zero every
//! output past it, whatever `out` held before.

use crate::microfacet::{
    Beckmann, Ggx, HeightCorrelated, KullaConty, Microfacet, NoFresnel, Schlick, Separable,
};
use crate::tabulated::{RusinkiewiczGrid, Tabulated};
use crate::{BlinnPhong, Lambertian, ModifiedPhong};
use radiometry::batch::Vec3Soa;
use radiometry::glam::Vec3;
use radiometry::{Brdf, BrdfSample};
extern crate std;
use std::vec;
use std::vec::Vec;

fn dir(k: usize, salt: f32) -> Vec3 {
    let t = (k as f32 * 0.618_034 + salt).fract() * 1.5;
    let p = (k as f32 * 0.414_213_5 + salt).fract() * core::f32::consts::TAU;
    Vec3::new(t.sin() * p.cos(), t.sin() * p.sin(), t.cos())
}

fn check<B: Brdf<Spectrum = f32>>(name: &str, b: &B) {
    // Lengths around the vector width (8 or 16 lanes) and its tails.
    for (n_in, n_out) in [(0, 5), (3, 20), (17, 40), (37, 37), (40, 17), (9, 8)] {
        let wi: Vec<Vec3> = (0..n_in).map(|k| dir(k, 0.1)).collect();
        let wo: Vec<Vec3> = (0..n_in).map(|k| dir(k, 0.7)).collect();
        let u: Vec<[f32; 2]> = (0..n_in)
            .map(|k| [(k as f32 * 0.754_877_7).fract(), (k as f32 * 0.569_840_3).fract()])
            .collect();
        let n = n_in.min(n_out);
        let stale = BrdfSample {
            wi: Vec3::ONE,
            pdf: 7.0,
            weight: 7.0,
        };

        let mut out = vec![f32::NAN; n_out];
        b.eval_batch(&wi, &wo, &mut out);
        let mut out_pdf = vec![f32::NAN; n_out];
        b.pdf_batch(&wi, &wo, &mut out_pdf);
        let (ix, iy, iz): (Vec<f32>, Vec<f32>, Vec<f32>) = (
            wi.iter().map(|v| v.x).collect(),
            wi.iter().map(|v| v.y).collect(),
            wi.iter().map(|v| v.z).collect(),
        );
        let (ox, oy, oz): (Vec<f32>, Vec<f32>, Vec<f32>) = (
            wo.iter().map(|v| v.x).collect(),
            wo.iter().map(|v| v.y).collect(),
            wo.iter().map(|v| v.z).collect(),
        );
        let mut out_soa = vec![f32::NAN; n_out];
        b.eval_batch_soa(
            Vec3Soa::new(&ix, &iy, &iz),
            Vec3Soa::new(&ox, &oy, &oz),
            &mut out_soa,
        );
        let mut out_s = vec![Some(stale); n_out];
        b.sample_batch(&wo, &u, &mut out_s);
        for k in 0..n_out {
            if k < n {
                assert_eq!(
                    out[k].to_bits(),
                    b.eval(wi[k], wo[k]).to_bits(),
                    "{name} eval {k}"
                );
                assert_eq!(
                    out_soa[k].to_bits(),
                    b.eval(wi[k], wo[k]).to_bits(),
                    "{name} soa {k}"
                );
                assert_eq!(
                    out_pdf[k].to_bits(),
                    b.pdf(wi[k], wo[k]).to_bits(),
                    "{name} pdf {k}"
                );
                assert_eq!(out_s[k], b.sample(wo[k], u[k]), "{name} sample {k}");
            } else {
                assert_eq!(out[k], 0.0, "{name} eval tail {k} ({n_in} in, {n_out} out)");
                assert_eq!(out_soa[k], 0.0, "{name} soa tail {k}");
                assert_eq!(out_pdf[k], 0.0, "{name} pdf tail {k}");
                assert_eq!(out_s[k], None, "{name} sample tail {k}");
            }
        }
    }
}

#[test]
fn every_plugin_zeroes_the_tail_of_a_mismatched_batch() {
    check("lambertian", &Lambertian::new(0.7f32).unwrap());
    check("phong", &ModifiedPhong::new(0.2f32, 0.5, 40.0).unwrap());
    check("blinn-phong", &BlinnPhong::new(0.1f32, 0.6, 100.0).unwrap());
    check(
        "ggx",
        &Microfacet::<_, HeightCorrelated, _>::new(Ggx::new(0.3).unwrap(), NoFresnel),
    );
    check(
        "ggx-separable-schlick",
        &Microfacet::<_, Separable, _>::new(Ggx::new(0.1).unwrap(), Schlick::new(0.04).unwrap()),
    );
    check(
        "beckmann",
        &Microfacet::<_, HeightCorrelated, _>::new(Beckmann::new(0.2).unwrap(), NoFresnel),
    );
    let kc: KullaConty<Ggx> = KullaConty::new(Ggx::new(0.5).unwrap(), NoFresnel);
    check("kulla-conty", &kc);
    let grid = RusinkiewiczGrid::new(16, 16, 32).unwrap();
    let values: Vec<f32> = (0..grid.len())
        .map(|i| ((i * 7919) % 1000) as f32 * 1e-3)
        .collect();
    let mut buf = vec![0.0f32; Tabulated::<f32>::sampling_buffer_len(&grid)];
    let t = Tabulated::new(grid, &values)
        .unwrap()
        .with_sampling(&mut buf)
        .unwrap();
    check("tabulated", &t);
}
