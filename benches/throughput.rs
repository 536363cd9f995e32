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
//! Without `target-cpu` flags the kernels' `wide::f32x8` runs as two SSE2
//! halves on x86_64; with AVX-512 they use `wide::f32x16`. `radiometry bench`
//! (the CLI) reports the same paths against reference kernels.

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use radiometry::glam::Vec3;
use radiometry::{Brdf, frame::spherical_direction};
use radiometry_brdfs::{
    Beckmann, BlinnPhong, Ggx, HeightCorrelated, Lambertian, Microfacet, ModifiedPhong, NoFresnel, Schlick,
    Separable,
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

criterion_group!(benches, plugins, point_sets);
criterion_main!(benches);
