//! The batch methods of an [`Integrand`] against its scalar methods, bit
//! for bit, over ragged lengths (used by `integrators.rs` and
//! `illumination.rs`).

use radiometry::Spectrum;
use radiometry::glam::Vec3;
use radiometry::integrator::{Integrand, IntegrandSample};

/// Directions of every kind an integrand may see in a batch: upper
/// hemisphere, horizon, below it, non-unit.
pub fn batch_dirs(n: usize) -> Vec<Vec3> {
    (0..n)
        .map(|k| {
            let t = k as f32 * 0.7548777;
            let z = 1.1 * (t.fract() - 0.05);
            let phi = core::f32::consts::TAU * (k as f32 * 0.5698403).fract();
            let s = (1.0 - z * z).max(0.0).sqrt();
            let w = Vec3::new(s * phi.cos(), s * phi.sin(), z);
            if k % 29 == 3 { Vec3::new(w.x, w.y, 0.0) } else { w }
        })
        .collect()
}

/// Unit-square points (a 2-D Kronecker sequence).
pub fn batch_us(n: usize) -> Vec<[f32; 2]> {
    (0..n)
        .map(|k| [(k as f32 * 0.7548777).fract(), (k as f32 * 0.5698403).fract()])
        .collect()
}

/// `eval_batch`/`sample_batch`/`pdf_batch` of `g` agree bit for bit with the
/// scalar methods for ragged lengths (across chunk boundaries), and zero
/// the extra output elements (the batch length rule,
/// `radiometry::batch::zero_tail`), whatever they held.
pub fn assert_batches_match_scalar<I: Integrand>(name: &str, g: &I)
where
    I::Spectrum: core::fmt::Debug,
{
    let bits = |s: I::Spectrum| -> Vec<u32> {
        (0..<I::Spectrum as Spectrum>::CHANNELS)
            .map(|i| Spectrum::channel(&s, i).to_bits())
            .collect()
    };
    let marker = <I::Spectrum as Spectrum>::splat(-7.0);
    for n in [0usize, 1, 7, 63, 64, 65, 130, 200] {
        let w = batch_dirs(n);
        let mut out = vec![marker; n + 3];
        g.eval_batch(&w, &mut out);
        for k in 0..n {
            assert_eq!(
                bits(out[k]),
                bits(g.eval(w[k])),
                "{name} eval n={n} k={k} w={:?}",
                w[k]
            );
        }
        assert!(
            out[n..].iter().all(|&v| v == <I::Spectrum as Spectrum>::zero()),
            "{name} eval tail"
        );
        let mut pdf = vec![-7.0f32; n + 3];
        g.pdf_batch(&w, &mut pdf);
        for k in 0..n {
            assert_eq!(pdf[k].to_bits(), g.pdf(w[k]).to_bits(), "{name} pdf n={n} k={k}");
        }
        assert!(pdf[n..].iter().all(|&v| v == 0.0), "{name} pdf tail");
        // Output shorter than the input: only `out.len()` elements.
        let mut short = vec![marker; n / 2];
        g.eval_batch(&w, &mut short);
        for k in 0..n / 2 {
            assert_eq!(
                bits(short[k]),
                bits(g.eval(w[k])),
                "{name} short eval n={n} k={k}"
            );
        }
        let u = batch_us(n);
        let mut s = vec![None; n + 3];
        s[n..].fill(Some(IntegrandSample {
            w: Vec3::X,
            pdf: -7.0,
            value: marker,
        }));
        g.sample_batch(&u, &mut s);
        for k in 0..n {
            let (a, b) = (s[k], g.sample(u[k]));
            assert_eq!(a.is_some(), b.is_some(), "{name} sample n={n} k={k}");
            if let (Some(a), Some(b)) = (a, b) {
                assert_eq!(a.w.to_array().map(f32::to_bits), b.w.to_array().map(f32::to_bits));
                assert_eq!(a.pdf.to_bits(), b.pdf.to_bits(), "{name} sample pdf n={n} k={k}");
                assert_eq!(bits(a.value), bits(b.value), "{name} sample value n={n} k={k}");
            }
        }
        assert!(s[n..].iter().all(|x| x.is_none()), "{name} sample tail");
    }
}
