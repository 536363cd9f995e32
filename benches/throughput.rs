//! Throughput of BRDF evaluation and sampling (criterion), and of the Monte
//! Carlo point sets.
//!
//! `cargo bench -p radiometry-benches --bench throughput` — reports time per batch of 4096
//! evaluations / samples for each plugin, scalar `eval` vs `eval_batch`, and
//! per 4096 points for the Sobol, PCG32 and Fibonacci point sets (`points/`).
//!
//! With the vector `eval_batch` kernels of `radiometry-brdfs` (feature
//! `simd`; GGX and Beckmann with either Smith `G2` and any Fresnel,
//! Lambertian, modified Phong, Blinn–Phong; see `radiometry_brdfs::simd`),
//! enable this package's `simd` feature:
//!
//! ```text
//! cargo bench -p radiometry-benches --bench throughput --features simd
//! # only the eval / eval_batch groups, AVX where the CPU has it:
//! RUSTFLAGS="-C target-cpu=native" cargo bench -p radiometry-benches --bench throughput \
//!     --features simd -- 'brdf/eval'
//! ```
//!
//! The `rough/` group times every path of the rough diffuse plugins (EON,
//! FON, the classic Oren–Nayar): the scalar loops `eval`, `pdf`, `sample`
//! (into an output slice, as a renderer writes them) against `eval_batch`,
//! `eval_batch_soa`, `pdf_batch`, `sample_batch`, on the pairs above and, for
//! EON, with one `ωo` for the whole batch (`eon-s0.5-one-wo`: an
//! integrator's nodes; the kernel computes `ωo`'s factor once):
//!
//! ```text
//! cargo bench -p radiometry-benches --bench throughput --features simd -- 'rough/'
//! ```
//!
//! Without `target-cpu` flags the kernels' `wide::f32x8` runs as two SSE2
//! halves on x86_64; with AVX-512 they use `wide::f32x16`. `radiometry bench`
//! (the CLI) reports the same paths against reference kernels.

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use radiometry::batch::Vec3Soa;
use radiometry::glam::Vec3;
use radiometry::{Brdf, frame::spherical_direction};
use radiometry_brdfs::{
    Beckmann, BlinnPhong, Eon, Fon, Ggx, HeightCorrelated, Lambertian, Microfacet, ModifiedPhong, NoFresnel,
    OrenNayar, Schlick, Separable,
};
use std::hint::black_box;

const N: usize = 4096;

/// Deterministic direction pairs spread over the upper hemisphere
/// (golden-ratio sequences; no RNG dependency).
fn directions() -> (Vec<Vec3>, Vec<Vec3>, Vec<[f32; 2]>) {
    let g = 0.618_034_f32;
    let mut wi = Vec::with_capacity(N);
    let mut wo = Vec::with_capacity(N);
    let mut u = Vec::with_capacity(N);
    for k in 0..N {
        let a = (k as f32 * g).fract();
        let b = (k as f32 * g * g).fract();
        let c = (k as f32 * 0.7548777).fract();
        let d = (k as f32 * 0.5698403).fract();
        wi.push(spherical_direction(a * 1.55, b * core::f32::consts::TAU));
        wo.push(spherical_direction(c * 1.55, d * core::f32::consts::TAU));
        u.push([a, d]);
    }
    (wi, wo, u)
}

fn bench_brdf<B: Brdf>(c: &mut Criterion, name: &str, brdf: B)
where
    B::Spectrum: Default + Copy,
{
    let (wi, wo, u) = directions();
    let mut group = c.benchmark_group("brdf");
    group.throughput(Throughput::Elements(N as u64));
    group.bench_function(BenchmarkId::new("eval", name), |bch| {
        bch.iter(|| {
            let mut acc = B::Spectrum::default();
            for k in 0..N {
                acc += brdf.eval(black_box(wi[k]), black_box(wo[k]));
            }
            acc
        })
    });
    let mut out = vec![B::Spectrum::default(); N];
    group.bench_function(BenchmarkId::new("eval_batch", name), |bch| {
        bch.iter(|| {
            brdf.eval_batch(black_box(&wi), black_box(&wo), &mut out);
            out[N - 1]
        })
    });
    group.bench_function(BenchmarkId::new("sample", name), |bch| {
        bch.iter(|| {
            let mut acc = 0.0f32;
            for k in 0..N {
                if let Some(s) = brdf.sample(black_box(wo[k]), black_box(u[k])) {
                    acc += s.pdf;
                }
            }
            acc
        })
    });
    group.finish();
}

fn plugins(c: &mut Criterion) {
    bench_brdf(c, "lambertian", Lambertian::new(0.5f32).unwrap());
    bench_brdf(
        c,
        "modified-phong-n100",
        ModifiedPhong::new(0.3f32, 0.7f32, 100.0).unwrap(),
    );
    bench_brdf(
        c,
        "blinn-phong-n100",
        BlinnPhong::new(0.3f32, 0.7f32, 100.0).unwrap(),
    );
    bench_brdf(
        c,
        "ggx-hc-a0.3",
        Microfacet::<_, HeightCorrelated, _>::new(Ggx::new(0.3).unwrap(), NoFresnel),
    );
    bench_brdf(
        c,
        "ggx-sep-schlick-a0.3",
        Microfacet::<_, Separable, _>::new(Ggx::new(0.3).unwrap(), Schlick::new(0.04f32).unwrap()),
    );
    bench_brdf(
        c,
        "beckmann-hc-a0.3",
        Microfacet::<_, HeightCorrelated, _>::new(Beckmann::new(0.3).unwrap(), NoFresnel),
    );
}

/// Every scalar and batch path of one plugin, each writing its `n` results
/// to a slice (group `rough/`); `one_wo` repeats the first `ωo`.
fn bench_paths<B: Brdf>(c: &mut Criterion, name: &str, brdf: B, one_wo: bool)
where
    B::Spectrum: Default + Copy,
{
    let (wi, mut wo, u) = directions();
    if one_wo {
        wo = vec![wo[N / 3]; N];
    }
    let soa = |v: &[Vec3]| -> [Vec<f32>; 3] {
        [
            v.iter().map(|w| w.x).collect(),
            v.iter().map(|w| w.y).collect(),
            v.iter().map(|w| w.z).collect(),
        ]
    };
    let (si, so) = (soa(&wi), soa(&wo));
    let mut out = vec![B::Spectrum::default(); N];
    let mut out_f = vec![0.0f32; N];
    let mut out_s = vec![None; N];
    let mut g = c.benchmark_group("rough");
    g.throughput(Throughput::Elements(N as u64));
    g.bench_function(BenchmarkId::new("eval", name), |b| {
        b.iter(|| {
            for ((o, &a), &c) in out.iter_mut().zip(black_box(&wi)).zip(black_box(&wo)) {
                *o = brdf.eval(a, c);
            }
        })
    });
    g.bench_function(BenchmarkId::new("eval_batch", name), |b| {
        b.iter(|| brdf.eval_batch(black_box(&wi), black_box(&wo), &mut out))
    });
    g.bench_function(BenchmarkId::new("eval_batch_soa", name), |b| {
        b.iter(|| {
            let a = Vec3Soa::new(black_box(&si[0]), &si[1], &si[2]);
            let c = Vec3Soa::new(black_box(&so[0]), &so[1], &so[2]);
            brdf.eval_batch_soa(a, c, &mut out)
        })
    });
    g.bench_function(BenchmarkId::new("pdf", name), |b| {
        b.iter(|| {
            for ((o, &a), &c) in out_f.iter_mut().zip(black_box(&wi)).zip(black_box(&wo)) {
                *o = brdf.pdf(a, c);
            }
        })
    });
    g.bench_function(BenchmarkId::new("pdf_batch", name), |b| {
        b.iter(|| brdf.pdf_batch(black_box(&wi), black_box(&wo), &mut out_f))
    });
    g.bench_function(BenchmarkId::new("sample", name), |b| {
        b.iter(|| {
            for ((o, &w), &v) in out_s.iter_mut().zip(black_box(&wo)).zip(black_box(&u)) {
                *o = brdf.sample(w, v);
            }
        })
    });
    g.bench_function(BenchmarkId::new("sample_batch", name), |b| {
        b.iter(|| brdf.sample_batch(black_box(&wo), black_box(&u), &mut out_s))
    });
    g.finish();
}

/// The rough diffuse plugins at mid roughness, every path.
fn rough_diffuse(c: &mut Criterion) {
    bench_paths(c, "eon-s0.5", Eon::new(0.8f32, 0.5).unwrap(), false);
    bench_paths(c, "eon-s0.5-one-wo", Eon::new(0.8f32, 0.5).unwrap(), true);
    bench_paths(
        c,
        "eon-rgb-s0.5",
        Eon::new(Vec3::new(0.8, 0.5, 0.2), 0.5).unwrap(),
        false,
    );
    bench_paths(c, "fon-s0.5", Fon::new(0.8f32, 0.5).unwrap(), false);
    bench_paths(
        c,
        "oren-nayar-s0.5rad",
        OrenNayar::new(0.8f32, 0.5).unwrap(),
        false,
    );
}

/// The unit-square point sets of the Monte Carlo integrators, 4096 points
/// each: the crate's Owen-scrambled Sobol points (four dimensions per point,
/// the `MonteCarlo` path; one dimension pair), PCG32 and the shifted
/// Fibonacci lattice.
fn point_sets(c: &mut Criterion) {
    use radiometry::integrator::points::{fibonacci_point, sobol_point, sobol_point_pairs};
    use radiometry::rng::Pcg32;
    let mut g = c.benchmark_group("points");
    g.throughput(Throughput::Elements(N as u64));
    g.bench_function("sobol_point_pairs", |b| {
        b.iter(|| {
            let mut acc = 0.0f32;
            for i in 0..N as u32 {
                let [p, q] = sobol_point_pairs(black_box(i), 7);
                acc += p[0] + p[1] + q[0] + q[1];
            }
            acc
        })
    });
    g.bench_function("sobol_point", |b| {
        b.iter(|| {
            let mut acc = 0.0f32;
            for i in 0..N as u32 {
                let p = sobol_point(black_box(i), 3, 7);
                acc += p[0] + p[1];
            }
            acc
        })
    });
    g.bench_function("pcg32_pairs", |b| {
        b.iter(|| {
            let mut rng = Pcg32::with_stream(black_box(7), 0);
            let mut acc = 0.0f32;
            for _ in 0..N {
                acc += rng.next_f32() + rng.next_f32();
            }
            acc
        })
    });
    g.bench_function("fibonacci_point", |b| {
        b.iter(|| {
            let mut acc = 0.0f32;
            for i in 0..N as u32 {
                let p = fibonacci_point(black_box(i), N as u32, [0.25, 0.5]);
                acc += p[0] + p[1];
            }
            acc
        })
    });
    g.finish();
}

criterion_group!(benches, plugins, rough_diffuse, point_sets);
criterion_main!(benches);
