//! Every plugin (the rough diffuse lobes, sheen, a coated plastic and OpenPBR
//! included): any finite parameters (invalid ones must be rejected at
//! construction), any finite directions and samples: eval / pdf / sample are
//! finite and non-negative, and never panic; `sample_batch` equals `sample`
//! bit for bit.
#![no_main]
mod common;
use common::Floats;
use libfuzzer_sys::fuzz_target;
use radiometry::glam::Vec3;
use radiometry::{Brdf, BrdfSample, Spectrum};
use radiometry_brdfs::*;

fn check<B: Brdf>(b: &B, f: &mut Floats) {
    let wi = f.vec3();
    let wo = f.vec3();
    let v = b.eval(wi, wo);
    assert!(
        v.is_finite() && v.min_channel() >= 0.0,
        "eval {wi:?} {wo:?} -> {v:?}"
    );
    let p = b.pdf(wi, wo);
    assert!(p.is_finite() && p >= 0.0, "pdf {wi:?} {wo:?} -> {p}");
    let u = [f.unit(), f.unit()];
    if let Some(s) = b.sample(wo, u) {
        assert!(
            s.pdf.is_finite() && s.pdf > 0.0,
            "sample pdf {wo:?} {u:?} -> {s:?}"
        );
        assert!(
            s.weight.is_finite() && s.weight.min_channel() >= 0.0,
            "sample weight {wo:?} {u:?} -> {s:?}"
        );
        assert!(s.wi.is_finite());
    }
    // `sample_batch` (the vector kernels of the `simd` feature for GGX and
    // Beckmann) returns exactly what `sample` returns: one chunk of up to 16
    // lanes plus a tail, half the directions made unit (the kernels' hot
    // path), with the same `None` decisions and the same bits.
    let wos: [Vec3; 19] = core::array::from_fn(|k| {
        let w = f.vec3();
        if k % 2 == 0 { w.normalize_or(Vec3::Z) } else { w }
    });
    let us: [[f32; 2]; 19] = core::array::from_fn(|_| [f.unit(), f.unit()]);
    let mut out = [None; 19];
    b.sample_batch(&wos, &us, &mut out);
    for k in 0..19 {
        let s = b.sample(wos[k], us[k]);
        let bits = |s: Option<BrdfSample<B::Spectrum>>| {
            s.map(|s| {
                let mut v = [
                    s.wi.x.to_bits(),
                    s.wi.y.to_bits(),
                    s.wi.z.to_bits(),
                    s.pdf.to_bits(),
                ]
                .to_vec();
                v.extend((0..B::Spectrum::CHANNELS).map(|c| s.weight.channel(c).to_bits()));
                v
            })
        };
        assert!(
            bits(s) == bits(out[k]),
            "sample_batch {:?} {:?}: {:?} vs {s:?}",
            wos[k],
            us[k],
            out[k]
        );
    }
}

fuzz_target!(|data: &[u8]| {
    let mut f = Floats(data);
    let which = f.byte();
    let (a, b, c) = (f.f32(), f.f32(), f.f32());
    match which % 19 {
        0 => {
            if let Ok(x) = Lambertian::new(a) {
                check(&x, &mut f)
            }
        }
        1 => {
            if let Ok(x) = ModifiedPhong::new(a, b, c) {
                check(&x, &mut f)
            }
        }
        2 => {
            if let Ok(x) = BlinnPhong::new(a, b, c) {
                check(&x, &mut f)
            }
        }
        3 => {
            if let Ok(d) = Ggx::new(a) {
                check(&Microfacet::<_, HeightCorrelated, _>::new(d, NoFresnel), &mut f)
            }
        }
        4 => {
            if let (Ok(d), Ok(fr)) = (Ggx::new(a), Conductor::new(b, c)) {
                check(&Microfacet::<_, Separable, _>::new(d, fr), &mut f)
            }
        }
        5 => {
            if let (Ok(d), Ok(fr)) = (Beckmann::new(a), Dielectric::new(b)) {
                check(&Microfacet::<_, HeightCorrelated, _>::new(d, fr), &mut f)
            }
        }
        6 => {
            if let (Ok(d), Ok(fr)) = (Beckmann::new(a), Schlick::new(b)) {
                check(&Microfacet::<_, Separable, _>::new(d, fr), &mut f)
            }
        }
        7 => {
            if let Ok(d) = Ggx::new(a) {
                check(&KullaConty::<_, HeightCorrelated, _>::new(d, NoFresnel), &mut f)
            }
        }
        8 => {
            if let (Ok(d), Ok(fr)) = (Ggx::new(a), Conductor::new(b, c)) {
                check(&KullaConty::<_, Separable, _>::new(d, fr), &mut f)
            }
        }
        9 => {
            if let (Ok(d), Ok(fr)) = (Beckmann::new(a), Dielectric::new(b)) {
                check(&KullaConty::<_, HeightCorrelated, _>::new(d, fr), &mut f)
            }
        }
        10 => {
            if let (Ok(d), Ok(fr)) = (Beckmann::new(a), Schlick::new(b)) {
                check(&KullaConty::<_, Separable, _>::new(d, fr), &mut f)
            }
        }
        13 => {
            if let Ok(x) = Eon::new(a, b) {
                check(&x, &mut f)
            }
        }
        14 => {
            if let Ok(x) = Fon::new(a, b) {
                check(&x, &mut f)
            }
        }
        15 => {
            if let Ok(x) = OrenNayar::new(a, b) {
                check(&x, &mut f)
            }
        }
        16 => {
            if let Ok(x) = Sheen::new(a, b) {
                check(&x, &mut f)
            }
        }
        17 => {
            // A plastic: a GGX dielectric coat over EON (radiometry::compose::Coated).
            if let (Ok(d), Ok(fr), Ok(base)) = (Ggx::new(a), Dielectric::new(b), Eon::new(c, f.unit())) {
                let coat = Microfacet::<_, HeightCorrelated, _>::new(d, fr);
                check(&radiometry::compose::Coated::new(coat, base), &mut f)
            }
        }
        18 => {
            // OpenPBR with fuzzed parameters (invalid ones rejected by the constructor).
            let p = OpenPbrParams::<f32> {
                base_color: a,
                base_metalness: f.unit(),
                base_diffuse_roughness: f.unit(),
                specular_roughness: b,
                specular_ior: c,
                specular_color: f.unit(),
                coat_weight: f.unit(),
                coat_roughness: f.unit(),
                coat_color: f.unit(),
                coat_ior: 1.0 + 2.0 * f.unit(),
                fuzz_weight: f.unit(),
                fuzz_roughness: f.unit(),
                ..OpenPbrParams::default()
            };
            if let Ok(x) = OpenPbr::new(p) {
                check(&x, &mut f)
            }
        }
        12 => {
            // Tabulated on a small grid of fuzzed size and (non-negative) values,
            // with half-vector sampling; the constructor rejects what it must.
            use radiometry_brdfs::tabulated::{RusinkiewiczGrid, Tabulated};
            let dims = [
                1 + f.byte() as usize % 6,
                1 + f.byte() as usize % 6,
                1 + f.byte() as usize % 6,
            ];
            let mut values = [0.0f32; 216];
            for v in values.iter_mut() {
                *v = f.unit() * 10.0;
            }
            let mut buf = [0.0f32; 21];
            if let Ok(g) = RusinkiewiczGrid::new(dims[0], dims[1], dims[2]) {
                if let Ok(t) = Tabulated::new(g, &values[..g.len()]) {
                    check(&t, &mut f);
                    let cw = f.unit();
                    if let Ok(t) = t.with_sampling_weight(&mut buf, cw) {
                        check(&t, &mut f);
                    }
                }
            }
        }
        _ => {
            if let Ok(d) = Ggx::new(a) {
                let w = f.vec3();
                let m = f.vec3();
                let vals = [d.d(m), d.g1(w), d.visible_pdf(w, m)];
                assert!(vals.iter().all(|v| v.is_finite() && *v >= 0.0), "{vals:?}");
                let s = d.sample_visible(w, [f.unit(), f.unit()]);
                assert!(s.is_finite());
            }
        }
    }
});
