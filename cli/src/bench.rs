//! `radiometry bench`: single-thread throughput of every BRDF plugin's hot
//! paths, each figure also given as a fraction of this CPU's limits measured
//! in the same run (the kernels of [`mod@reference`]).
//!
//! Every timed pass is an `#[inline(never)]` function whose arguments (the
//! BRDF, the input slices, the output slice) go through
//! [`std::hint::black_box`]; nothing is black-boxed per element, so the
//! loops are compiled as a renderer's loops would be. Outputs are written to
//! memory, so no work can be dropped as dead.

mod machine;
mod reference;
mod timing;

use machine::{Feature, cpu_model, profile, simd_features};
use timing::{
    InputSet, Inputs, MIN_REPS, REP_SLICES, measure, pass_eval, pass_eval_batch, pass_eval_batch_soa,
    pass_pdf, pass_pdf_batch, pass_sample, pass_sample_batch,
};

use crate::{Format, json_num};
use radiometry::compose::Coated;
use radiometry::glam::Vec3;
use radiometry::{Brdf, BrdfSample};
use radiometry_brdfs::{
    Beckmann, BlinnPhong, Conductor, Dielectric, Eon, Ggx, HeightCorrelated, Lambertian, Layering,
    Microfacet, ModifiedPhong, NoFresnel, OpenPbr, OpenPbrParams, Schlick, Separable,
};
use std::hint::black_box;
use std::io::IsTerminal;
use std::process::ExitCode;
use std::time::Duration;

/// Help text after the options (`radiometry bench --help`).
pub const AFTER_HELP: &str = "\
Plugins (F = 1 unless a Fresnel term is named):
  lambertian                   Lambertian, albedo 0.5 (f32)
  modified-phong-n100          ModifiedPhong kd 0.3, ks 0.7, n 100 (f32)
  blinn-phong-n100             BlinnPhong kd 0.3, ks 0.7, n 100 (f32)
  ggx-hc-a0.3                  Microfacet<Ggx, HeightCorrelated, NoFresnel>, α 0.3 (f32)
  ggx-sep-a0.3                 Microfacet<Ggx, Separable, NoFresnel>, α 0.3 (f32)
  ggx-hc-schlick-rgb-a0.3      Microfacet<Ggx, HeightCorrelated, Schlick<Vec3>>, f0 (1.0, 0.71, 0.29) (Vec3)
  ggx-hc-conductor-rgb-a0.3    Microfacet<Ggx, HeightCorrelated, Conductor<Vec3>>, gold η, k (Vec3)
  beckmann-hc-a0.3             Microfacet<Beckmann, HeightCorrelated, NoFresnel>, α 0.3 (f32)
  tabulated-merl-ggx-a0.3      Tabulated<f32>: ggx-hc-a0.3 tabulated on the MERL grid (90 x 90 x 180,
                               5.8 MB), trilinear, half-vector sampling (f32)
  tabulated-merl-rgb-ggx-a0.3  Tabulated<Vec3>: the same table in three channels (17.5 MB) (Vec3)
  eon-s0.5                     Eon, ρ 0.8, σ 0.5 (f32)
  ggx-hc-dielectric-a0.1       Microfacet<Ggx, HeightCorrelated, Dielectric>, α 0.1, η 1.5: the plastic's
                               top alone (f32)
  plastic-ggx0.1-eon           coated(GGX α 0.1 dielectric η 1.5, Eon ρ 0.8 σ 0.5): radiometry::compose::Coated (f32)
  openpbr-defaults             OpenPbr with OpenPBR Surface's default parameters (f32)
  openpbr-all-layers           OpenPbr, every layer on: metalness 0.5, coat 1 (r 0.2), fuzz 1 (f32)
  openpbr-defaults-reciprocal  the defaults in the reciprocal layering (Layering::Reciprocal) (f32)
  openpbr-all-layers-reciprocal
                               every layer on, reciprocal layering (f32)
  openpbr-defaults-rgb         OpenPbr<Vec3> with OpenPBR Surface's default parameters (Vec3)
  spec-openpbr-red-rgb         the spec grammar's RGB run-time BRDF (AnyBrdfRgb, one virtual call per
                               element or batch) of openpbr(base_color=rgb(0.8, 0.1, 0.1)) (Vec3)
  (the four f32 OpenPbr rows also time construct — OpenPbr::with_layering with a roughness from u per
  element — hit — construct + eval + sample + pdf at the sampled direction, a renderer's whole
  hit with textured parameters — and hit-prepared — the same hit through one OpenPbr::prepare view,
  as Adobe's prepare + eval + sample + pdf; the plastic's row construct for Coated::new, hit and
  hit-prepared through Coated::prepare as above, albedo-read, the top's albedo at ωo alone as the
  energy-conserving layer reads it at every eval of unit directions above the horizon (the checked
  read of the top Coated::new keeps, prepared by Brdf::with_prepared_albedo), albedo-full,
  directional_albedo of a top not prepared (its table cells located at every call), albedo-prepared, the bare DielectricAlbedoReader built once,
  albedo-batch, the prepared top's directional_albedo_batch over the n view directions, and
  eval-parts, a plain loop of the top's eval + the base's eval + that bare read, summed: the least
  an exact energy-conserving layer computes per eval; eval-batch-parts, the lobes' own batch kernels
  one after the other (both eval_batch + the top's directional_albedo_batch), and
  sample-batch-parts, the same for a sample batch (both lobes' albedo batches, the cheaper lobe's
  sample_batch, both eval_batch and pdf_batch at the drawn directions): the least the batches
  compute with these kernels; openpbr-defaults has the same two rows from its specular and EON
  lobes, with the specular albedo batch at ωi too, and eval-parts and sample-parts: plain loops of
  those two lobes' eval (and sample, pdf) with the specular layer's bare albedo reads at ωo and
  ωi, the diffuse term weighted by Kelemen's factor and the lobe picked in proportion to its
  albedo at ωo: the least the formula computes per eval and per sample)

Paths, each at n = 4096 (in cache) and n = 2^20 (streaming from memory; not with --quick):
  eval            for k { out[k] = brdf.eval(wi[k], wo[k]) }      the loop a renderer writes
  eval_batch      brdf.eval_batch(&wi, &wo, &mut out)              AoS &[Vec3]
  eval_batch_soa  brdf.eval_batch_soa(wi_soa, wo_soa, &mut out)    SoA, radiometry::batch::Vec3Soa
  pdf             for k { out[k] = brdf.pdf(wi[k], wo[k]) }
  pdf_batch       brdf.pdf_batch(&wi, &wo, &mut out)
  sample          for k { out[k] = brdf.sample(wo[k], u[k]) }      stores the Option<BrdfSample>
  sample_batch    brdf.sample_batch(&wo, &u, &mut out)             the same samples, batched
Inputs: deterministic direction pairs spread over the upper hemisphere (θ uniform in [0°, 88.8°),
φ uniform), u in [0,1)², in two sets timed one after the other at every n (column inputs):
  golden  golden-ratio (R2) sequences: neighbouring pairs alike, data-dependent branches regular
  random  the same distribution from a fixed-seed Pcg32, in no order (as a renderer's directions)
Every reference is timed on each set, and every ratio divides figures of the same set.

This CPU's limits, timed in the same process on the same inputs, each written in the formulation
with the fewest divisions and square roots known for it (un-normalised half vector; Heitz 2014,
Filament's V_SmithGGXCorrelated):
  reference-ggx-scalar  GGX α 0.3, height-correlated Smith, F = 1, as a plain scalar loop over
                        AoS Vec3 with no input checks but the horizon (a select):  h = wi + wo;
                        L = |h|²;  d = h_z²(α² − 1) + L;  r(z) = sqrt(z²(1 − α²) + α²);
                        f = (α²/2π) L² / (d² (z_o r(z_i) + z_i r(z_o)))   (1 division, 2 roots)
  reference-ggx-soa     the same formula over SoA &[f32] slices, a branch-free loop LLVM
                        auto-vectorises
  stream                out[k] = x_i + y_i + z_i + x_o + y_o + z_o over SoA slices
                        (reads 24 B, writes 4 B per element): the memory-stream bound
  reference-ggx-sample-scalar
                        GGX α 0.3 visible-normal sampling (spherical caps) with the sample's pdf
                        and weight, F = 1, as a plain scalar loop with no input checks: every
                        vector scaled by |stretched wo|, never normalised (2 divisions, 3 roots;
                        sin/cos by a branch-free polynomial)
  reference-ggx-sample-soa
                        the same sampler over SoA slices (wo, u in; wi, pdf, weight out), a
                        branch-free loop LLVM auto-vectorises

Plain loops of other plugins' own formulas (no input checks, libm for the special functions):
  reference-beckmann-scalar
                        Beckmann α 0.3, height-correlated Smith, F = 1, un-normalised h and
                        projected areas: D = exp(−tan²θh/α²) L²/(πα²h_z⁴), a = z/(α sin θ),
                        A = (z (1 + erf a) + α sin θ exp(−a²)/√π)/2,
                        f = D/(4 (z_o A_i + z_i A_o − z_i z_o))   (libm expf, erff)
  reference-tabulated-scalar
                        the tabulated-merl-ggx-a0.3 table looked up the textbook way: θh = acos h_z,
                        d = R_y(−θh) R_z(−φh) wi, θd = acos d_z, φd = atan2(d_y, d_x) folded into [0, π),
                        the MERL index mappings, trilinear interpolation
  reference-eon-scalar  EON ρ 0.8, σ 0.5 (Portsmouth, Kutz & Hill 2025, exact FON albedo):
                        f = (ρ/π) A (1 + σ s/t) + (ρ_ms/π) A σ (c₁ − G(μi)/π)(c₁ − G(μo)/π)/(c₁ − c₂),
                        G by libm acosf and two square roots per direction

Columns:
  m_per_s      million elements (pairs, or samples) per second, single thread
  ns_per_elem  1000 / m_per_s
  vs_ref       m_per_s / m_per_s of the reference at the same n and inputs: reference-ggx-scalar for eval
               and pdf, reference-ggx-soa for eval_batch, eval_batch_soa and pdf_batch,
               reference-ggx-sample-scalar for sample, reference-ggx-sample-soa for
               sample_batch; json key `ref` names it
  vs_stream    m_per_s / m_per_s of stream at the same n
  vs_own_ref   m_per_s / m_per_s of the plain loop of the plugin's own formula at the same n and
               inputs, where
               there is one: ggx-hc-a0.3 (eval; eval_batch and eval_batch_soa vs reference-ggx-soa;
               sample, sample_batch vs the sampler references), beckmann-hc-a0.3 (eval) and
               tabulated-merl-ggx-a0.3 (eval); json key `own_ref` names it
  inputs       the input set, golden or random

A line \"warning: <plugin> <path> runs at <r>x its scalar path <path>\" follows the table of an
(n, inputs) group for every batch path (eval_batch, eval_batch_soa vs eval; pdf_batch vs pdf;
sample_batch vs sample) below 0.95x its scalar loop (json: \"warnings\").

Timing: per measurement a warm-up, then repetitions of whole passes over the n elements (each
repetition about a tenth of the minimum time, at least one pass) until at least 50 ms
(--quick: 10 ms) in total and at least 3 repetitions; the figure is the BEST (fastest)
repetition. The references are timed before and after the plugins and the best
is kept. The machine's other load only slows runs down, so best-of is the least noisy estimate
of the achievable rate.

Build for meaningful numbers (release; the vector kernels of radiometry-brdfs; the CPU's
own vector width for them and for the auto-vectorised reference):
  RUSTFLAGS=\"-C target-cpu=native\" cargo run --release -p radiometry-cli --features simd -- bench
The header says which SIMD target features were compiled in and which the CPU has.";

/// `radiometry bench` options.
#[derive(clap::Args, Debug)]
pub struct BenchArgs {
    /// Only n = 4096, 10 ms per measurement (about 1 s in all; the full run takes about 20 s).
    #[arg(long)]
    quick: bool,
    /// Output format (json: {"header": {...}, "rows": [{plugin, path, n, inputs, m_per_s, ns_per_elem, vs_ref,
    /// vs_stream, ref, vs_own_ref, own_ref}], "warnings": [{plugin, path, scalar_path, n, inputs, vs_scalar}]}).
    #[arg(long, value_enum, default_value_t = Format::Text)]
    format: Format,
    /// Minimum timed milliseconds per measurement (overrides 50 / --quick 10; for tests).
    #[arg(long, hide = true)]
    min_time_ms: Option<f64>,
    /// Time only the plugins whose name contains this string (the references are always timed), e.g.
    /// `--only tabulated` to profile those rows.
    #[arg(long, value_name = "SUBSTRING")]
    only: Option<String>,
}

/// Whether a path is a batch call (compared with the SoA reference) rather
/// than a scalar loop (compared with the scalar reference).
fn is_batch(path: &str) -> bool {
    matches!(
        path,
        "eval_batch" | "eval_batch_soa" | "pdf_batch" | "sample_batch"
    )
}

const REF_SCALAR: &str = "reference-ggx-scalar";
const REF_SOA: &str = "reference-ggx-soa";
const REF_SAMPLE_SCALAR: &str = "reference-ggx-sample-scalar";
const REF_SAMPLE_SOA: &str = "reference-ggx-sample-soa";
const STREAM: &str = "stream";
const REF_BECKMANN_SCALAR: &str = "reference-beckmann-scalar";
const REF_TABULATED_SCALAR: &str = "reference-tabulated-scalar";
const REF_EON_SCALAR: &str = "reference-eon-scalar";
/// ρ and σ of the `eon-s0.5` plugin and its reference.
const EON_RHO: f32 = 0.8;
const EON_SIGMA: f32 = 0.5;

/// The plain loop of the plugin's own formula for `(plugin, path)`, if the
/// bench has one.
fn own_reference(plugin: &str, path: &str) -> Option<&'static str> {
    match (plugin, path) {
        ("ggx-hc-a0.3", "eval") => Some(REF_SCALAR),
        ("ggx-hc-a0.3", "eval_batch" | "eval_batch_soa") => Some(REF_SOA),
        ("ggx-hc-a0.3", "sample") => Some(REF_SAMPLE_SCALAR),
        ("ggx-hc-a0.3", "sample_batch") => Some(REF_SAMPLE_SOA),
        ("beckmann-hc-a0.3", "eval") => Some(REF_BECKMANN_SCALAR),
        ("tabulated-merl-ggx-a0.3", "eval") => Some(REF_TABULATED_SCALAR),
        ("eon-s0.5", "eval") => Some(REF_EON_SCALAR),
        _ => None,
    }
}
/// α of the reference GGX (that of the `ggx-hc-a0.3` plugin).
const REF_ALPHA: f32 = 0.3;

/// One measured figure.
#[derive(Clone, Debug)]
struct Row {
    plugin: &'static str,
    path: &'static str,
    n: usize,
    /// The input set ([`InputSet::name`]).
    inputs: &'static str,
    m_per_s: f64,
    /// The reference row `vs_ref` divides by (`None` for `stream`).
    reference: Option<&'static str>,
    vs_ref: Option<f64>,
    vs_stream: f64,
    /// The plain loop of the plugin's own formula `vs_own_ref` divides by.
    own_reference: Option<&'static str>,
    vs_own_ref: Option<f64>,
}

/// Measurements at one `n`.
struct Run<'a> {
    inputs: &'a Inputs,
    set: InputSet,
    /// Only the plugins whose name contains this.
    only: Option<&'a str>,
    n: usize,
    min_time: Duration,
    progress: bool,
    rows: Vec<Row>,
    /// Seconds per element of `reference-tabulated-scalar` (set by the
    /// `Tabulated` rows).
    tabulated_ref: f64,
}

impl Run<'_> {
    fn push(&mut self, plugin: &'static str, path: &'static str, secs_per_elem: f64) {
        self.rows.push(Row {
            plugin,
            path,
            n: self.n,
            inputs: self.set.name(),
            m_per_s: 1e-6 / secs_per_elem,
            reference: None,
            vs_ref: None,
            vs_stream: f64::NAN,
            own_reference: None,
            vs_own_ref: None,
        });
    }

    fn note(&self, what: &str) {
        if self.progress {
            eprint!(
                "\r\x1b[2Kbench: n = {}, {} inputs: {what}",
                self.n,
                self.set.name()
            );
        }
    }

    /// Seconds per element of the six reference kernels (eval scalar and
    /// SoA, stream, sample scalar and SoA, Beckmann scalar).
    fn references(&self) -> [f64; 7] {
        self.note("references");
        let (n, mt) = (self.n, self.min_time);
        let (wi, wo) = (self.inputs.wi(n), self.inputs.wo(n));
        let (si, so) = (self.inputs.wi_soa(n), self.inputs.wo_soa(n));
        let mut out = vec![0.0f32; n];
        let scalar = measure(n, mt, || {
            reference::ggx_scalar(
                black_box(REF_ALPHA),
                black_box(wi),
                black_box(wo),
                black_box(&mut out[..]),
            )
        });
        let soa = measure(n, mt, || {
            reference::ggx_soa(
                black_box(REF_ALPHA),
                black_box(si),
                black_box(so),
                black_box(&mut out[..]),
            )
        });
        let stream = measure(n, mt, || {
            reference::stream(black_box(si), black_box(so), black_box(&mut out[..]))
        });
        let u = &self.inputs.u[..n];
        let mut samples = vec![reference::RefSample::default(); n];
        let sample_scalar = measure(n, mt, || {
            reference::ggx_sample_scalar(
                black_box(REF_ALPHA),
                black_box(wo),
                black_box(u),
                black_box(&mut samples[..]),
            )
        });
        let (u0, u1) = self.inputs.u_soa(n);
        let mut o: [Vec<f32>; 5] = std::array::from_fn(|_| vec![0.0f32; n]);
        let sample_soa = measure(n, mt, || {
            let [x, y, z, pdf, weight] = &mut o;
            reference::ggx_sample_soa(
                black_box(REF_ALPHA),
                black_box(so),
                black_box(u0),
                black_box(u1),
                black_box(reference::SampleSoa { x, y, z, pdf, weight }),
            )
        });
        let beckmann = measure(n, mt, || {
            reference::beckmann_scalar(
                black_box(REF_ALPHA),
                black_box(wi),
                black_box(wo),
                black_box(&mut out[..]),
            )
        });
        let eon = measure(n, mt, || {
            reference::eon_scalar(
                black_box(EON_RHO),
                black_box(EON_SIGMA),
                black_box(wi),
                black_box(wo),
                black_box(&mut out[..]),
            )
        });
        black_box((&out, &samples, &o));
        [scalar, soa, stream, sample_scalar, sample_soa, beckmann, eon]
    }

    /// Times the seven paths of one plugin.
    fn plugin<B: Brdf>(&mut self, name: &'static str, brdf: &B) {
        if !self.wanted(name) {
            return;
        }
        self.note(name);
        let (n, mt, inputs) = (self.n, self.min_time, self.inputs);
        let (wi, wo, u) = (inputs.wi(n), inputs.wo(n), &inputs.u[..n]);
        let (si, so) = (inputs.wi_soa(n), inputs.wo_soa(n));
        let mut out = vec![B::Spectrum::default(); n];
        let mut out_f = vec![0.0f32; n];
        let mut out_s: Vec<Option<BrdfSample<B::Spectrum>>> = vec![None; n];
        let t = measure(n, mt, || {
            pass_eval(
                black_box(brdf),
                black_box(wi),
                black_box(wo),
                black_box(&mut out[..]),
            )
        });
        self.push(name, "eval", t);
        let t = measure(n, mt, || {
            pass_eval_batch(
                black_box(brdf),
                black_box(wi),
                black_box(wo),
                black_box(&mut out[..]),
            )
        });
        self.push(name, "eval_batch", t);
        let t = measure(n, mt, || {
            pass_eval_batch_soa(
                black_box(brdf),
                black_box(si),
                black_box(so),
                black_box(&mut out[..]),
            )
        });
        self.push(name, "eval_batch_soa", t);
        let t = measure(n, mt, || {
            pass_pdf(
                black_box(brdf),
                black_box(wi),
                black_box(wo),
                black_box(&mut out_f[..]),
            )
        });
        self.push(name, "pdf", t);
        let t = measure(n, mt, || {
            pass_pdf_batch(
                black_box(brdf),
                black_box(wi),
                black_box(wo),
                black_box(&mut out_f[..]),
            )
        });
        self.push(name, "pdf_batch", t);
        let t = measure(n, mt, || {
            pass_sample(
                black_box(brdf),
                black_box(wo),
                black_box(u),
                black_box(&mut out_s[..]),
            )
        });
        self.push(name, "sample", t);
        let t = measure(n, mt, || {
            pass_sample_batch(
                black_box(brdf),
                black_box(wo),
                black_box(u),
                black_box(&mut out_s[..]),
            )
        });
        self.push(name, "sample_batch", t);
        black_box((&out, &out_f, &out_s));
    }

    /// Whether `--only` selects the plugin `name`.
    fn wanted(&self, name: &str) -> bool {
        self.only.is_none_or(|s| name.contains(s))
    }

    /// Every plugin (see [`AFTER_HELP`] for the list).
    fn plugins(&mut self) {
        const BAD: &str = "bench plugin parameters are valid";
        let ggx = Ggx::new(0.3).expect(BAD);
        self.plugin("lambertian", &Lambertian::new(0.5f32).expect(BAD));
        self.plugin(
            "modified-phong-n100",
            &ModifiedPhong::new(0.3f32, 0.7, 100.0).expect(BAD),
        );
        self.plugin(
            "blinn-phong-n100",
            &BlinnPhong::new(0.3f32, 0.7, 100.0).expect(BAD),
        );
        self.plugin(
            "ggx-hc-a0.3",
            &Microfacet::<_, HeightCorrelated, _>::new(ggx, NoFresnel),
        );
        self.plugin(
            "ggx-sep-a0.3",
            &Microfacet::<_, Separable, _>::new(ggx, NoFresnel),
        );
        self.plugin(
            "ggx-hc-schlick-rgb-a0.3",
            &Microfacet::<_, HeightCorrelated, _>::new(
                ggx,
                Schlick::new(Vec3::new(1.0, 0.71, 0.29)).expect(BAD),
            ),
        );
        self.plugin(
            "ggx-hc-conductor-rgb-a0.3",
            &Microfacet::<_, HeightCorrelated, _>::new(
                ggx,
                Conductor::new(Vec3::new(0.143, 0.374, 1.442), Vec3::new(3.983, 2.385, 1.603)).expect(BAD),
            ),
        );
        self.plugin(
            "beckmann-hc-a0.3",
            &Microfacet::<_, HeightCorrelated, _>::new(Beckmann::new(0.3).expect(BAD), NoFresnel),
        );
        self.tabulated(ggx);
        let eon = Eon::new(EON_RHO, EON_SIGMA).expect(BAD);
        self.plugin("eon-s0.5", &eon);
        let plastic_top = Microfacet::<_, HeightCorrelated, _>::new(
            Ggx::new(0.1).expect(BAD),
            Dielectric::new(1.5).expect(BAD),
        );
        self.plugin("ggx-hc-dielectric-a0.1", &plastic_top);
        if self.wanted("plastic-ggx0.1-eon") {
            self.plugin("plastic-ggx0.1-eon", &Coated::new(plastic_top, eon));
        }
        if self.wanted("plastic-ggx0.1-eon") {
            let (n, mt, inputs) = (self.n, self.min_time, self.inputs);
            let u = &inputs.u[..n];
            let mut sink = 0.0f32;
            let t = measure(n, mt, || {
                for uk in u {
                    let coat = Microfacet::<_, HeightCorrelated, _>::new(
                        Ggx::new(0.01 + 0.5 * black_box(uk[0])).expect(BAD),
                        Dielectric::new(1.5).expect(BAD),
                    );
                    let c = Coated::new(coat, eon);
                    // The value escapes whole (no read of its albedos is timed).
                    sink += radiometry_brdfs::microfacet::MicrofacetDistribution::alpha(
                        &black_box(&c).top().distribution,
                    );
                }
            });
            black_box(sink);
            self.push("plastic-ggx0.1-eon", "construct", t);
            self.plastic_hit(eon);
        }
        let all_layers = OpenPbrParams::<f32> {
            base_metalness: 0.5,
            coat_weight: 1.0,
            coat_roughness: 0.2,
            fuzz_weight: 1.0,
            ..OpenPbrParams::default()
        };
        let (energy, reciprocal) = (Layering::EnergyConserving, Layering::Reciprocal);
        for (name, params, layering) in [
            ("openpbr-defaults", OpenPbrParams::<f32>::default(), energy),
            ("openpbr-all-layers", all_layers, energy),
            (
                "openpbr-defaults-reciprocal",
                OpenPbrParams::<f32>::default(),
                reciprocal,
            ),
            ("openpbr-all-layers-reciprocal", all_layers, reciprocal),
        ] {
            if self.wanted(name) {
                self.plugin(name, &OpenPbr::with_layering(params, layering).expect(BAD));
                self.material_hit(name, params, layering);
            }
        }
        if self.wanted("openpbr-defaults") {
            // The defaults' two lobes as `OpenPbr::new` builds them (specular
            // GGX α = 0.3² dielectric η = 1.5, its albedo prepared; EON ρ =
            // 0.8, σ = 0), for the bound of its batches.
            let spec = Microfacet::<_, HeightCorrelated, _>::new(
                Ggx::new(0.09).expect(BAD),
                radiometry_brdfs::microfacet::Achromatic::<_, f32>::new(Dielectric::new(1.5).expect(BAD)),
            )
            .with_prepared_albedo();
            let diffuse = Eon::new(0.8f32, 0.0).expect(BAD);
            self.batch_parts("openpbr-defaults", &spec, &diffuse, true);
            self.scalar_parts("openpbr-defaults", &spec, &diffuse, (0.09, 1.5));
        }
        // Colour: the typed OpenPbr<Vec3> and the spec grammar's RGB
        // run-time BRDF (a boxed trait object) of a red OpenPBR.
        if self.wanted("openpbr-defaults-rgb") {
            self.plugin(
                "openpbr-defaults-rgb",
                &OpenPbr::new(OpenPbrParams::<Vec3>::default()).expect(BAD),
            );
        }
        if self.wanted("spec-openpbr-red-rgb") {
            let text = "openpbr(base_color=rgb(0.8, 0.1, 0.1))";
            let parsed = crate::spec::parse_brdf(text).expect(BAD);
            let b = crate::model::build_brdf_rgb(text, &parsed).expect(BAD);
            self.plugin("spec-openpbr-red-rgb", &b);
        }
    }

    /// The construct and hit paths of an `OpenPbr` (see [`AFTER_HELP`]): a
    /// renderer that builds the material at every hit from textured
    /// parameters (here `specular_roughness` from `u[k][0]`).
    fn material_hit(&mut self, name: &'static str, params: OpenPbrParams<f32>, layering: Layering) {
        const BAD: &str = "bench plugin parameters are valid";
        let (n, mt, inputs) = (self.n, self.min_time, self.inputs);
        let (wi, wo, u) = (inputs.wi(n), inputs.wo(n), &inputs.u[..n]);
        let with = |k: usize| OpenPbrParams {
            specular_roughness: 0.1 + 0.5 * u.get(k).map_or(0.5, |x| x[0]),
            ..params
        };
        let mut sink = 0.0f32;
        let t = measure(n, mt, || {
            for k in 0..n {
                let m = OpenPbr::with_layering(black_box(with(k)), layering).expect(BAD);
                sink += black_box(&m).params().specular_roughness;
            }
        });
        self.push(name, "construct", t);
        let t = measure(n, mt, || {
            for k in 0..n {
                let m = OpenPbr::with_layering(black_box(with(k)), layering).expect(BAD);
                let (i, o) = (wi[k], wo[k]);
                sink += m.eval(i, o);
                if let Some(s) = m.sample(o, u[k]) {
                    sink += s.weight + m.pdf(s.wi, o);
                }
            }
        });
        self.push(name, "hit", t);
        // The same hit through one prepared view (`OpenPbr::prepare`), as a
        // renderer that shades a light sample and a BSDF sample at one hit
        // calls it, and as Adobe's `openpbr_prepare` is timed.
        let t = measure(n, mt, || {
            for k in 0..n {
                let m = OpenPbr::with_layering(black_box(with(k)), layering).expect(BAD);
                let view = m.prepare(wo[k]);
                sink += view.eval(wi[k]);
                if let Some(s) = view.sample(u[k]) {
                    sink += s.weight + view.pdf(s.wi);
                }
            }
        });
        self.push(name, "hit-prepared", t);
        black_box(sink);
    }

    /// The plastic's hit paths (see [`AFTER_HELP`]): built at every hit with
    /// the top's roughness from `u[k][0]`, then `eval` + `sample` + `pdf`
    /// through the `Brdf` calls (`hit`) and through one `Coated::prepare`
    /// view (`hit-prepared`); `albedo-read`, the top's albedo at `ωo` alone
    /// as the layer reads it at every `eval` (the checked read of its
    /// prepared top), `albedo-full`, `directional_albedo` of a top not
    /// prepared,
    /// `albedo-prepared`, the bare reader built once, `albedo-batch`, the
    /// prepared top's `directional_albedo_batch`, `eval-parts`, the
    /// plain loop of both lobes' `eval` and the bare read, and the batch
    /// bounds of [`batch_parts`](Self::batch_parts).
    fn plastic_hit(&mut self, eon: Eon<f32>) {
        const BAD: &str = "bench plugin parameters are valid";
        let (n, mt, inputs) = (self.n, self.min_time, self.inputs);
        let (wi, wo, u) = (inputs.wi(n), inputs.wo(n), &inputs.u[..n]);
        let build = |k: usize| {
            let a = 0.01 + 0.5 * u.get(k).map_or(0.5, |x| x[0]);
            let top = Microfacet::<_, HeightCorrelated, _>::new(
                Ggx::new(a).expect(BAD),
                Dielectric::new(1.5).expect(BAD),
            );
            Coated::new(top, eon)
        };
        let mut sink = 0.0f32;
        let t = measure(n, mt, || {
            for k in 0..n {
                let m = build(black_box(k));
                let (i, o) = (wi[k], wo[k]);
                sink += m.eval(i, o);
                if let Some(s) = m.sample(o, u[k]) {
                    sink += s.weight + m.pdf(s.wi, o);
                }
            }
        });
        self.push("plastic-ggx0.1-eon", "hit", t);
        let t = measure(n, mt, || {
            for k in 0..n {
                let m = build(black_box(k));
                let view = m.prepare(wo[k]);
                sink += view.eval(wi[k]);
                if let Some(s) = view.sample(u[k]) {
                    sink += s.weight + view.pdf(s.wi);
                }
            }
        });
        self.push("plastic-ggx0.1-eon", "hit-prepared", t);
        let top = Microfacet::<_, HeightCorrelated, _>::new(
            Ggx::new(0.1).expect(BAD),
            Dielectric::new(1.5).expect(BAD),
        );
        let layer = Coated::new(top, eon);
        // What the layer reads at every `eval` of a checked pair: the top's
        // checked read (`Brdf::albedo_checked`). `ωo` is taken as it lies in
        // the input: passed through `black_box`, the 12-byte direction is
        // stored in one pair of pieces and reloaded in another, a load the
        // store cannot forward to (a scratch loop read 41 ns that way against
        // 21 ns, the same read).
        let t = measure(n, mt, || {
            for &o in wo {
                sink += black_box(&layer).top().albedo_checked(o);
            }
        });
        self.push("plastic-ggx0.1-eon", "albedo-read", t);
        let t = measure(n, mt, || {
            for &o in wo {
                sink += black_box(&top).directional_albedo(o).value;
            }
        });
        self.push("plastic-ggx0.1-eon", "albedo-full", t);
        // The same read through a reader prepared once (OpenPbr keeps one per
        // layer): the least any layer that reads E_T(μo) per eval can pay.
        let reader = radiometry_brdfs::microfacet::fresnel_table::DielectricAlbedoReader::new(0.1, 1.5);
        let t = measure(n, mt, || {
            for &o in wo {
                sink += black_box(&reader).albedo(black_box(o).z);
            }
        });
        self.push("plastic-ggx0.1-eon", "albedo-prepared", t);
        // The same reads as one batch (`Brdf::directional_albedo_batch` of the
        // prepared top: with `simd`, in vector lanes from the reader's
        // combined rows, built once per call).
        let mut albedos = vec![0.0f32; wo.len()];
        let t = measure(n, mt, || {
            black_box(&layer)
                .top()
                .directional_albedo_batch(black_box(wo), &mut albedos);
            sink += albedos.first().copied().unwrap_or(0.0);
        });
        self.push("plastic-ggx0.1-eon", "albedo-batch", t);
        // The least an exact energy-conserving layer computes per `eval`: both
        // lobes' values and the top's albedo at ωo from the bare reader, summed
        // in one plain loop (no layering, no clamping): the bound of the
        // plastic's `eval` against its lobes' combined rate.
        let (top, base) = (layer.top(), layer.base());
        let t = measure(n, mt, || {
            for (&i, &o) in wi.iter().zip(wo) {
                sink +=
                    black_box(top).eval(i, o) + black_box(base).eval(i, o) + black_box(&reader).albedo(o.z);
            }
        });
        self.push("plastic-ggx0.1-eon", "eval-parts", t);
        self.batch_parts("plastic-ggx0.1-eon", layer.top(), layer.base(), false);
        black_box(sink);
    }

    /// The least a layered material's batches compute, from its two lobes'
    /// own batch kernels run one after the other over the n elements (no
    /// layering, no chunking), as rows `eval-batch-parts` and
    /// `sample-batch-parts` of `name`. `eval-batch-parts`: the top's and the
    /// base's `eval_batch` and the top's `directional_albedo_batch` at `ωo`
    /// (and at `ωi` where `read_i`: OpenPBR's diffuse term reads `E_s` at
    /// both). `sample-batch-parts`: both lobes' `directional_albedo_batch` at
    /// `ωo` (the picks), the cheaper lobe's `sample_batch` for every element
    /// (timed for each lobe, the faster kept), both lobes' `eval_batch` and
    /// `pdf_batch` at the drawn directions (and the top's albedo there where
    /// `read_i`). The bound of `eval_batch` and `sample_batch` against the
    /// lobes' kernels.
    fn batch_parts<T, B>(&mut self, name: &'static str, top: &T, base: &B, read_i: bool)
    where
        T: Brdf<Spectrum = f32>,
        B: Brdf<Spectrum = f32>,
    {
        let (n, mt, inputs) = (self.n, self.min_time, self.inputs);
        let (wi, wo, u) = (inputs.wi(n), inputs.wo(n), &inputs.u[..n]);
        let (mut a, mut b, mut c) = (vec![0.0f32; n], vec![0.0f32; n], vec![0.0f32; n]);
        let mut sink = 0.0f32;
        let t = measure(n, mt, || {
            black_box(top).eval_batch(wi, wo, &mut a);
            black_box(base).eval_batch(wi, wo, &mut b);
            black_box(top).directional_albedo_batch(wo, &mut c);
            sink += a.first().copied().unwrap_or(0.0) + b.first().copied().unwrap_or(0.0) + c[0];
            if read_i {
                black_box(top).directional_albedo_batch(wi, &mut c);
                sink += c[0];
            }
        });
        self.push(name, "eval-batch-parts", t);
        let mut drawn: Vec<Option<BrdfSample<f32>>> = vec![None; n];
        let draw_top = measure(n, mt, || {
            black_box(top).sample_batch(wo, u, &mut drawn);
            sink += drawn.first().copied().flatten().map_or(0.0, |s| s.pdf);
        });
        let draw_base = measure(n, mt, || {
            black_box(base).sample_batch(wo, u, &mut drawn);
            sink += drawn.first().copied().flatten().map_or(0.0, |s| s.pdf);
        });
        let draw = draw_top.min(draw_base);
        // The rest at the base's drawn directions (all above the horizon).
        base.sample_batch(wo, u, &mut drawn);
        let wi_s: Vec<Vec3> = drawn.iter().map(|s| s.map_or(Vec3::Z, |s| s.wi)).collect();
        let (mut d, mut e) = (vec![0.0f32; n], vec![0.0f32; n]);
        let rest = measure(n, mt, || {
            black_box(top).directional_albedo_batch(wo, &mut a);
            black_box(base).directional_albedo_batch(wo, &mut b);
            black_box(top).eval_batch(&wi_s, wo, &mut c);
            black_box(base).eval_batch(&wi_s, wo, &mut d);
            black_box(top).pdf_batch(&wi_s, wo, &mut e);
            black_box(base).pdf_batch(&wi_s, wo, &mut c);
            sink += a[0] + b[0] + d[0] + e[0] + c[0];
            if read_i {
                black_box(top).directional_albedo_batch(&wi_s, &mut c);
                sink += c[0];
            }
        });
        self.push(name, "sample-batch-parts", draw + rest);
        black_box(sink);
    }

    /// The least a dielectric layer over a diffuse lobe computes per call, as
    /// plain loops of the two lobes' public calls and the specular layer's
    /// bare albedo reader (`(α, η)` = `ae`), rows `eval-parts` and
    /// `sample-parts` of `name`. `eval-parts`: `f = f_s + f_d (1 − E_s(μi))
    /// (1 − E_s(μo))/(1 − Ē_s)` (Kelemen). `sample-parts`: the pick ∝ each
    /// lobe's albedo at `ωo` (`E_s(μo)` and `(1 − E_s(μo)) E_d(ωo)`), the
    /// picked lobe's own `sample`, then `f` and the mixture pdf at the drawn
    /// direction and the weight `f cos θi/pdf`. The bound of `eval` and
    /// `sample` against the formula itself.
    fn scalar_parts<T, B>(&mut self, name: &'static str, top: &T, base: &B, ae: (f32, f32))
    where
        T: Brdf<Spectrum = f32>,
        B: Brdf<Spectrum = f32>,
    {
        use radiometry_brdfs::microfacet::fresnel_table::{DielectricAlbedoReader, dielectric_average};
        let (n, mt, inputs) = (self.n, self.min_time, self.inputs);
        let (wi, wo, u) = (inputs.wi(n), inputs.wo(n), &inputs.u[..n]);
        let reader = DielectricAlbedoReader::new(ae.0, ae.1);
        let inv_avg = 1.0 / (1.0 - dielectric_average(ae.0, ae.1));
        let mut sink = 0.0f32;
        let t = measure(n, mt, || {
            for (&i, &o) in wi.iter().zip(wo) {
                let r = black_box(&reader);
                let (eo, ei) = (r.albedo(o.z), r.albedo(i.z));
                sink += black_box(top).eval(i, o)
                    + black_box(base).eval(i, o) * ((1.0 - ei) * (1.0 - eo) * inv_avg);
            }
        });
        self.push(name, "eval-parts", t);
        let t = measure(n, mt, || {
            for (&o, &[u0, u1]) in wo.iter().zip(u) {
                let (r, top, base) = (black_box(&reader), black_box(top), black_box(base));
                let eo = r.albedo(o.z);
                let diffuse = (1.0 - eo) * base.directional_albedo(o).value;
                let ps = eo / (eo + diffuse);
                let drawn = if u0 < ps {
                    top.sample(o, [u0 / ps, u1])
                } else {
                    base.sample(o, [((u0 - ps) / (1.0 - ps)).min(0.999_999_94), u1])
                };
                if let Some(i) = drawn.map(|s| s.wi) {
                    let ei = r.albedo(i.z);
                    let f = top.eval(i, o) + base.eval(i, o) * ((1.0 - ei) * (1.0 - eo) * inv_avg);
                    let pdf = ps * top.pdf(i, o) + (1.0 - ps) * base.pdf(i, o);
                    if pdf > 0.0 {
                        sink += f * (i.z / pdf);
                    }
                }
            }
        });
        self.push(name, "sample-parts", t);
        black_box(sink);
    }

    /// The `Tabulated` rows: GGX α 0.3 (the reference's formula) on the MERL grid.
    fn tabulated(&mut self, ggx: Ggx) {
        use radiometry_brdfs::tabulated::{RusinkiewiczGrid, Tabulated};
        if !self.wanted("tabulated-merl-ggx-a0.3") && !self.wanted("tabulated-merl-rgb-ggx-a0.3") {
            return;
        }
        const BAD: &str = "the MERL-grid table of a valid plugin is valid";
        let grid = RusinkiewiczGrid::MERL;
        let table =
            radiometry_cli::merl::tabulate(&Microfacet::<_, HeightCorrelated, _>::new(ggx, NoFresnel), grid)
                .expect(BAD);
        let mono: Vec<f32> = table.values.iter().map(|v| v.x).collect();
        let mut buf = vec![0.0f32; Tabulated::<f32>::sampling_buffer_len(&grid)];
        let mut buf_rgb = buf.clone();
        let t = Tabulated::new(grid, &mono)
            .and_then(|t| t.with_sampling(&mut buf))
            .expect(BAD);
        // The plain loop of the same lookup, before and after (best kept).
        let plain = reference::Table {
            values: &mono,
            dims: grid.dims(),
        };
        let before = self.tabulated_reference(plain);
        self.plugin("tabulated-merl-ggx-a0.3", &t);
        let after = self.tabulated_reference(plain);
        self.tabulated_ref = before.min(after);
        let t = Tabulated::new(grid, &table.values[..])
            .and_then(|t| t.with_sampling(&mut buf_rgb))
            .expect(BAD);
        self.plugin("tabulated-merl-rgb-ggx-a0.3", &t);
    }

    /// Seconds per element of [`reference::tabulated_scalar`] on `table`.
    fn tabulated_reference(&self, table: reference::Table<'_>) -> f64 {
        self.note("references");
        let (n, inputs) = (self.n, self.inputs);
        let mut out = vec![0.0f32; n];
        let t = measure(n, self.min_time, || {
            reference::tabulated_scalar(
                black_box(table),
                black_box(inputs.wi(n)),
                black_box(inputs.wo(n)),
                black_box(&mut out[..]),
            )
        });
        black_box(&out);
        t
    }

    /// References, plugins, references again (best of both kept); then the
    /// ratio columns.
    fn measure_all(mut self) -> Vec<Row> {
        let before = self.references();
        self.plugins();
        let after = self.references();
        let best = |k: usize| before[k].min(after[k]);
        let plugin_rows = std::mem::take(&mut self.rows);
        self.push(REF_SCALAR, "eval", best(0));
        self.push(REF_SOA, "eval_batch_soa", best(1));
        self.push(STREAM, "stream", best(2));
        self.push(REF_SAMPLE_SCALAR, "sample", best(3));
        self.push(REF_SAMPLE_SOA, "sample_batch", best(4));
        self.push(REF_BECKMANN_SCALAR, "eval", best(5));
        self.push(REF_EON_SCALAR, "eval", best(6));
        if !self.tabulated_ref.is_nan() {
            self.push(REF_TABULATED_SCALAR, "eval", self.tabulated_ref);
        }
        self.rows.extend(plugin_rows);
        let rate = |name: &str| {
            self.rows
                .iter()
                .find(|r| r.plugin == name)
                .map_or(f64::NAN, |r| r.m_per_s)
        };
        let (scalar, soa, stream) = (rate(REF_SCALAR), rate(REF_SOA), rate(STREAM));
        let (sample_scalar, sample_soa) = (rate(REF_SAMPLE_SCALAR), rate(REF_SAMPLE_SOA));
        let (beckmann, tabulated) = (rate(REF_BECKMANN_SCALAR), rate(REF_TABULATED_SCALAR));
        let eon = rate(REF_EON_SCALAR);
        let own_rates = |name: &str| match name {
            REF_SCALAR => scalar,
            REF_SOA => soa,
            REF_SAMPLE_SCALAR => sample_scalar,
            REF_SAMPLE_SOA => sample_soa,
            REF_BECKMANN_SCALAR => beckmann,
            REF_TABULATED_SCALAR => tabulated,
            REF_EON_SCALAR => eon,
            _ => f64::NAN,
        };
        for r in &mut self.rows {
            r.vs_stream = r.m_per_s / stream;
            if r.plugin != STREAM {
                let (name, m) = match r.path {
                    "sample" => (REF_SAMPLE_SCALAR, sample_scalar),
                    "sample_batch" => (REF_SAMPLE_SOA, sample_soa),
                    p if is_batch(p) => (REF_SOA, soa),
                    _ => (REF_SCALAR, scalar),
                };
                r.reference = Some(name);
                r.vs_ref = Some(r.m_per_s / m);
            }
            r.own_reference = own_reference(r.plugin, r.path);
            r.vs_own_ref = r.own_reference.map(|name| r.m_per_s / own_rates(name));
        }
        self.rows
    }
}

fn timing_text(min_time: Duration) -> String {
    format!(
        "best of the repetitions (each ~{} ms, >= 1 pass; >= {MIN_REPS} and >= {} ms per measurement, after a \
warm-up); single thread",
        min_time.as_secs_f64() * 1e3 / REP_SLICES as f64,
        min_time.as_secs_f64() * 1e3
    )
}

const RATIO_TEXT: &str = "vs_ref = m_per_s / reference-ggx-scalar (eval, pdf), / reference-ggx-soa (eval_batch, \
eval_batch_soa, pdf_batch), / reference-ggx-sample-scalar (sample) or / reference-ggx-sample-soa (sample_batch) at the \
same n; vs_stream = m_per_s / stream at the same n; vs_own_ref = m_per_s / the plain loop of the plugin's own formula \
(ggx-hc-a0.3, beckmann-hc-a0.3 eval, tabulated-merl-ggx-a0.3 eval, eon-s0.5 eval) at the same n; every ratio within one input set";

const INPUTS_TEXT: &str = "every n is timed on two input sets of the same distribution: golden (golden-ratio \
sequences, neighbouring pairs alike) and random (fixed-seed Pcg32 draws, in no order), each with its own references";

/// The batch paths and the scalar loop each is compared with.
const BATCH_VS_SCALAR: [(&str, &str); 4] = [
    ("eval_batch", "eval"),
    ("eval_batch_soa", "eval"),
    ("pdf_batch", "pdf"),
    ("sample_batch", "sample"),
];

/// A batch path is reported when it runs below this fraction of its scalar
/// path: best-of figures of the same code vary by a few per cent between
/// measurements on a shared machine, so a batch path that is the scalar loop
/// itself (a plugin without a kernel) must not be flagged by noise.
const WARN_BELOW: f64 = 0.95;

/// A batch path slower than its scalar path.
#[derive(Debug)]
struct SlowBatch {
    plugin: &'static str,
    path: &'static str,
    scalar_path: &'static str,
    n: usize,
    inputs: &'static str,
    /// Batch rate / scalar rate.
    ratio: f64,
}

impl SlowBatch {
    fn text(&self) -> String {
        format!(
            "warning: {} {} runs at {:.3}x its scalar path {} (n = {}, {} inputs)",
            self.plugin, self.path, self.ratio, self.scalar_path, self.n, self.inputs
        )
    }
}

/// Every batch row of `rows` below [`WARN_BELOW`] times the scalar row of
/// the same plugin, `n` and input set.
fn slow_batches(rows: &[Row]) -> Vec<SlowBatch> {
    let mut out = Vec::new();
    for r in rows {
        let Some(&(_, scalar_path)) = BATCH_VS_SCALAR.iter().find(|(b, _)| *b == r.path) else {
            continue;
        };
        let scalar = rows
            .iter()
            .find(|s| s.plugin == r.plugin && s.n == r.n && s.inputs == r.inputs && s.path == scalar_path);
        if let Some(s) = scalar {
            let ratio = r.m_per_s / s.m_per_s;
            if ratio < WARN_BELOW {
                out.push(SlowBatch {
                    plugin: r.plugin,
                    path: r.path,
                    scalar_path,
                    n: r.n,
                    inputs: r.inputs,
                    ratio,
                });
            }
        }
    }
    out
}

/// Runs the command.
pub fn run(args: BenchArgs) -> ExitCode {
    let min_ms = args.min_time_ms.unwrap_or(if args.quick { 10.0 } else { 50.0 });
    if !(min_ms.is_finite() && min_ms > 0.0 && min_ms <= 60_000.0) {
        eprintln!("error: --min-time-ms {min_ms} must be in (0, 60000]");
        return ExitCode::from(2);
    }
    let min_time = Duration::from_secs_f64(min_ms * 1e-3);
    let ns: &[usize] = if args.quick { &[4096] } else { &[4096, 1 << 20] };
    let n_max = *ns.iter().max().unwrap_or(&4096);
    let inputs = InputSet::ALL.map(|set| (set, Inputs::new(n_max, set)));
    let progress = std::io::stderr().is_terminal();
    let mut rows = Vec::new();
    for &n in ns {
        for (set, inputs) in &inputs {
            rows.extend(
                Run {
                    inputs,
                    set: *set,
                    only: args.only.as_deref(),
                    n,
                    min_time,
                    progress,
                    rows: Vec::new(),
                    tabulated_ref: f64::NAN,
                }
                .measure_all(),
            );
        }
    }
    let warnings = slow_batches(&rows);
    if progress {
        eprint!("\r\x1b[2K");
    }
    let cpu = cpu_model();
    let features = simd_features();
    let simd = cfg!(feature = "simd");
    let (prof, opt) = profile();
    let debug_assertions = cfg!(debug_assertions);
    match args.format {
        Format::Json => {
            let compiled: serde_json::Map<_, _> = features
                .iter()
                .map(|f| (f.name.to_string(), serde_json::Value::Bool(f.compiled)))
                .collect();
            let detected: serde_json::Map<_, _> = features
                .iter()
                .filter_map(|f| Some((f.name.to_string(), serde_json::Value::Bool(f.cpu?))))
                .collect();
            let rows: Vec<_> = rows
                .iter()
                .map(|r| {
                    serde_json::json!({
                        "plugin": r.plugin,
                        "path": r.path,
                        "n": r.n,
                        "inputs": r.inputs,
                        "m_per_s": json_num(r.m_per_s),
                        "ns_per_elem": json_num(1e3 / r.m_per_s),
                        "vs_ref": r.vs_ref.map(json_num),
                        "vs_stream": json_num(r.vs_stream),
                        "ref": r.reference,
                        "vs_own_ref": r.vs_own_ref.map(json_num),
                        "own_ref": r.own_reference,
                    })
                })
                .collect();
            let j = serde_json::json!({
                "header": {
                    "cpu": cpu,
                    "target_features": compiled,
                    "cpu_features": detected,
                    "simd_feature": simd,
                    "profile": prof,
                    "opt_level": opt,
                    "debug_assertions": debug_assertions,
                    "threads": 1,
                    "timing": timing_text(min_time),
                    "min_time_ms": json_num(min_ms),
                    "ratios": RATIO_TEXT,
                    "inputs": INPUTS_TEXT,
                },
                "rows": rows,
                "warnings": warnings.iter().map(|w| serde_json::json!({
                    "plugin": w.plugin,
                    "path": w.path,
                    "scalar_path": w.scalar_path,
                    "n": w.n,
                    "inputs": w.inputs,
                    "vs_scalar": json_num(w.ratio),
                })).collect::<Vec<_>>(),
            });
            println!("{j}");
        }
        Format::Text => {
            println!("radiometry bench: single-thread throughput of the BRDF plugins vs this CPU's limits");
            println!("cpu:      {cpu}");
            let list = |pick: fn(&Feature) -> bool| {
                let v: Vec<&str> = features.iter().filter(|f| pick(f)).map(|f| f.name).collect();
                if v.is_empty() {
                    "-".to_string()
                } else {
                    v.join(" ")
                }
            };
            println!(
                "features: compiled in: {}; not compiled in: {}; CPU has but not compiled in: {}",
                list(|f| f.compiled),
                list(|f| !f.compiled),
                list(|f| !f.compiled && f.cpu == Some(true)),
            );
            println!(
                "build:    radiometry-brdfs simd feature {}; profile {prof}, opt-level {opt}, debug-assertions {}",
                if simd { "on" } else { "off" },
                if debug_assertions { "on" } else { "off" },
            );
            if debug_assertions || prof != "release" {
                println!("          (not a release build: the figures are not representative)");
            }
            println!("timing:   {}", timing_text(min_time));
            println!("ratios:   {RATIO_TEXT}");
            println!("inputs:   {INPUTS_TEXT}");
            let mut group = None;
            let print_warnings = |n: usize, inputs: &str| {
                for w in warnings.iter().filter(|w| w.n == n && w.inputs == inputs) {
                    println!("{}", w.text());
                }
            };
            for r in &rows {
                if group != Some((r.n, r.inputs)) {
                    if let Some((n, inputs)) = group {
                        print_warnings(n, inputs);
                    }
                    println!();
                    println!(
                        "{:<26} {:<15} {:>8} {:>10} {:>11} {:>7} {:>9} {:>10}  inputs",
                        "plugin", "path", "n", "m_per_s", "ns_per_elem", "vs_ref", "vs_stream", "vs_own_ref"
                    );
                    group = Some((r.n, r.inputs));
                }
                let ratio = |v: Option<f64>| v.map_or("-".to_string(), |v| format!("{v:.3}"));
                println!(
                    "{:<26} {:<15} {:>8} {:>10.1} {:>11.2} {:>7} {:>9.3} {:>10}  {}",
                    r.plugin,
                    r.path,
                    r.n,
                    r.m_per_s,
                    1e3 / r.m_per_s,
                    ratio(r.vs_ref),
                    r.vs_stream,
                    ratio(r.vs_own_ref),
                    r.inputs
                );
            }
            if let Some((n, inputs)) = group {
                print_warnings(n, inputs);
            }
        }
    }
    ExitCode::SUCCESS
}

#[cfg(test)]
mod tests {
    use super::*;

    fn row(plugin: &'static str, path: &'static str, inputs: &'static str, m_per_s: f64) -> Row {
        Row {
            plugin,
            path,
            n: 4096,
            inputs,
            m_per_s,
            reference: None,
            vs_ref: None,
            vs_stream: f64::NAN,
            own_reference: None,
            vs_own_ref: None,
        }
    }

    /// A warning for each batch path below 0.95x the scalar path of the same
    /// plugin and input set, none at or above it.
    #[test]
    fn slow_batches_are_found() {
        let rows = [
            row("a", "eval", "golden", 10.0),
            row("a", "eval_batch", "golden", 9.0),
            row("a", "eval_batch_soa", "golden", 9.6),
            row("a", "eval", "random", 20.0),
            row("a", "eval_batch", "random", 9.6),
            row("a", "sample", "golden", 5.0),
            row("a", "sample_batch", "golden", 4.0),
            row("a", "pdf_batch", "golden", 1.0),
            row("b", "pdf", "golden", 5.0),
            row("b", "pdf_batch", "golden", 50.0),
        ];
        let w = slow_batches(&rows);
        let got: Vec<_> = w
            .iter()
            .map(|w| (w.plugin, w.path, w.inputs, w.scalar_path))
            .collect();
        assert_eq!(
            got,
            [
                ("a", "eval_batch", "golden", "eval"),
                ("a", "eval_batch", "random", "eval"),
                ("a", "sample_batch", "golden", "sample"),
            ]
        );
        assert!((w[1].ratio - 0.48).abs() < 1e-12);
        assert_eq!(
            w[0].text(),
            "warning: a eval_batch runs at 0.900x its scalar path eval (n = 4096, golden inputs)"
        );
    }
}
