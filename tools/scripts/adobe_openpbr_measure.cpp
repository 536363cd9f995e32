// adobe_openpbr_measure.cpp — a measurement harness (our own code) around Adobe's OpenPBR BSDF
// (https://github.com/adobe/openpbr-bsdf, header-only, Apache-2.0). Nothing of Adobe's is copied
// here: the harness only #includes `openpbr.h` from a checkout given with `-I`.
//
// What it computes, per case of the conformance set below (OpenPBR Surface 1.1 parameter names;
// every parameter not listed stays at `openpbr_make_default_resolved_inputs()`), in the local frame
// of the default `geometry_basis` (normal +Z), ωo = (sin θo, 0, cos θo):
//
//   * albedo     E(θo) per channel at θo ∈ {0,15,30,45,60,75,85}°: the mean of Adobe's own sample
//                weights (`openpbr_sample`'s weight = f·|cos θi|/pdf over every lobe, summed
//                diffuse + specular; a failed sample, pdf = 0, counts 0) over N = 2^22 samples:
//                (u1, u2) on a 2048×2048 grid jittered inside each cell, u3 uniform iid.
//   * albedo_se  the standard error from 64 independent batches: batch b = 8·(i mod 8) + (j mod 8)
//                of cell (i, j), so every batch spans the square and the batches are independent
//                (own jitter and u3); SE = sd(batch means)/√64. Conservative: the spread of the
//                batch means also holds the (deterministic) differences between the interleaved
//                sub-grids.
//   * albedo_quadrature / albedo_quadrature_err   (cases whose lobes are all rough, i.e. not
//                `coat-r0-over-grey-diffuse`) ∫ openpbr_eval dω by tensor Gauss–Legendre in
//                (μi, φi), φi ∈ [0, π] doubled (the BSDF is isotropic and ωo lies in the xz plane),
//                panels graded geometrically towards the mirror direction (μo, π), towards φ = 0
//                and towards μ = 1, with n = 8, 16, 32 nodes per panel; the value is n = 32 and the
//                error |Q32 − Q16|.
//   * values     f_r = openpbr_eval/cos θi per channel at (θi, θo, Δφ) triples, φo = 0, φi = Δφ.
//   * variance   at θo ∈ {0, 45, 75}°: the per-sample variance (n − 1 denominator) and the mean of the
//                channel-average weight (w_r+w_g+w_b)/3 over 2^20 iid uniform (u1,u2,u3), fixed seed.
//   * timing     (`timing` mode) ns per call of prepare, eval, sample, pdf and of a whole hit
//                (prepare + eval + sample + pdf at the sampled direction), one thread, 2^20 calls per
//                repetition, 15 repetitions, timed by the thread's CPU time (CLOCK_THREAD_CPUTIME_ID:
//                time the core spends on other processes is not counted; median and min reported,
//                wall-clock median alongside), inputs precomputed, results summed into a volatile sink.
//
// The two builds: default = Adobe's energy-conserving layering (one-sided coat and fuzz);
// -DOPENPBR_RECIPROCAL_COAT_AND_FUZZ=1 = reciprocal coat (the fuzz stays one-sided).
//
// Build (GLM 0.9.9 headers from Debian's libglm-dev; ADOBE = a checkout of adobe/openpbr-bsdf):
//   g++ -std=c++17 -O2 -I "$ADOBE" tools/scripts/adobe_openpbr_measure.cpp -o /tmp/adobe_energy
//   g++ -std=c++17 -O2 -DOPENPBR_RECIPROCAL_COAT_AND_FUZZ=1 -I "$ADOBE" \
//       tools/scripts/adobe_openpbr_measure.cpp -o /tmp/adobe_reciprocal
// Run (one JSON object per line on stdout):
//   /tmp/adobe_energy list                 # the case names, one per line
//   /tmp/adobe_energy case NAME            # every measurement of one case (≈ 10–40 s)
//   /tmp/adobe_energy timing               # the timing block (≈ 1 min)
// The driver tools/scripts/adobe_openpbr_measure.py builds both, runs everything (nice -n 10, one
// thread) and writes brdfs/tests/data/openpbr_adobe.json.

#include <glm/glm.hpp>

#include "openpbr.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <string>
#include <vector>

#if OPENPBR_RECIPROCAL_COAT_AND_FUZZ
static const char* const kBuild = "reciprocal";
#else
static const char* const kBuild = "energy";
#endif

// ---------------------------------------------------------------------------------------------
// The conformance set.
// ---------------------------------------------------------------------------------------------

struct Param
{
    const char* name;  // OpenPBR parameter name
    int n;             // 1 = scalar, 3 = colour
    float v[3];
};

struct Case
{
    const char* name;
    std::vector<Param> params;
    bool rough;  // every lobe rough: values and the quadrature cross-check are meaningful
};

static Param sc(const char* name, float v) { return Param{name, 1, {v, 0.0f, 0.0f}}; }
static Param rgb(const char* name, float r, float g, float b) { return Param{name, 3, {r, g, b}}; }
static Param grey(const char* name, float v) { return Param{name, 3, {v, v, v}}; }

static std::vector<Case> conformance_set()
{
    return {
        {"defaults", {}, true},
        {"white-plastic-r0.1", {grey("base_color", 1), sc("specular_roughness", 0.1f)}, true},
        {"white-diffuse", {grey("base_color", 1), sc("specular_weight", 0)}, true},
        {"coat-over-white-diffuse", {grey("base_color", 1), sc("specular_weight", 0), sc("coat_weight", 1), sc("coat_roughness", 0.1f)}, true},
        {"coat-over-white-plastic", {grey("base_color", 1), sc("coat_weight", 1), sc("coat_roughness", 0.1f)}, true},
        {"coat-over-white-metal", {sc("base_metalness", 1), grey("base_color", 1), sc("coat_weight", 1), sc("coat_roughness", 0.1f)}, true},
        {"coat-over-grey-diffuse", {grey("base_color", 0.5f), sc("specular_weight", 0), sc("coat_weight", 1), sc("coat_roughness", 0.1f)}, true},
        {"coat-r0-over-grey-diffuse", {grey("base_color", 0.5f), sc("specular_weight", 0), sc("coat_weight", 1), sc("coat_roughness", 0)}, false},
        {"white-fuzz-over-white",
         {grey("base_color", 1), sc("specular_weight", 0), sc("fuzz_weight", 1), grey("fuzz_color", 1), sc("fuzz_roughness", 0.5f)},
         true},
        {"all-layers-white",
         {grey("base_color", 1), sc("base_metalness", 0.5f), sc("specular_roughness", 0.3f), sc("coat_weight", 1), sc("coat_roughness", 0.2f),
          sc("fuzz_weight", 1), grey("fuzz_color", 1), sc("fuzz_roughness", 0.5f)},
         true},
        {"white-metal-r0.3", {sc("base_metalness", 1), grey("base_color", 1), sc("specular_roughness", 0.3f)}, true},
        {"white-metal-r0.8", {sc("base_metalness", 1), grey("base_color", 1), sc("specular_roughness", 0.8f)}, true},
        {"gold",
         {sc("base_metalness", 1), rgb("base_color", 1.0f, 0.78f, 0.34f), rgb("specular_color", 1.0f, 0.93f, 0.78f), sc("specular_roughness", 0.25f)},
         true},
        {"red-plastic", {rgb("base_color", 0.8f, 0.1f, 0.1f), sc("specular_roughness", 0.2f)}, true},
        {"half-metal", {sc("base_metalness", 0.5f), grey("base_color", 0.7f), sc("specular_roughness", 0.4f)}, true},
        {"tinted-coat-half",
         {sc("coat_weight", 0.5f), rgb("coat_color", 0.9f, 0.6f, 0.3f), sc("coat_roughness", 0.2f), sc("coat_ior", 1.5f)},
         true},
        {"ior-2.5-r0.5", {sc("specular_ior", 2.5f), sc("specular_roughness", 0.5f), grey("base_color", 0.6f)}, true},
        {"rough-diffuse-white", {grey("base_color", 1), sc("specular_weight", 0), sc("base_diffuse_roughness", 1)}, true},
        {"eon-plastic", {grey("base_color", 0.6f), sc("base_diffuse_roughness", 0.7f), sc("specular_roughness", 0.4f)}, true},
        {"red-fuzz-over-grey",
         {grey("base_color", 0.5f), sc("fuzz_weight", 1), rgb("fuzz_color", 0.9f, 0.3f, 0.3f), sc("fuzz_roughness", 0.3f)},
         true},
        {"specular-weight-0.5", {sc("specular_weight", 0.5f), rgb("specular_color", 0.8f, 0.9f, 1.0f)}, true},
        {"coat-1.3-over-1.8", {sc("specular_ior", 1.8f), sc("coat_weight", 1), sc("coat_ior", 1.3f), sc("coat_roughness", 0.2f)}, true},
        {"coat-2.0-over-1.5", {sc("coat_weight", 1), sc("coat_ior", 2.0f), sc("coat_roughness", 0.2f)}, true},
        {"coat-darkening-0", {grey("base_color", 0.5f), sc("coat_weight", 1), sc("coat_roughness", 0.2f), sc("coat_darkening", 0)}, true},
        {"coat-grey-0.5-plastic", {grey("base_color", 0.5f), sc("coat_weight", 1), sc("coat_roughness", 0.2f)}, true},
    };
}

static void set_param(OpenPBR_ResolvedInputs& in, const Param& p)
{
#define SCALAR(field)                                                                                                                                \
    if (std::strcmp(p.name, #field) == 0 && p.n == 1)                                                                                                \
    {                                                                                                                                                \
        in.field = p.v[0];                                                                                                                           \
        return;                                                                                                                                      \
    }
#define COLOUR(field)                                                                                                                                \
    if (std::strcmp(p.name, #field) == 0 && p.n == 3)                                                                                                \
    {                                                                                                                                                \
        in.field = vec3(p.v[0], p.v[1], p.v[2]);                                                                                                     \
        return;                                                                                                                                      \
    }
    SCALAR(base_weight)
    COLOUR(base_color)
    SCALAR(base_metalness)
    SCALAR(base_diffuse_roughness)
    SCALAR(specular_weight)
    COLOUR(specular_color)
    SCALAR(specular_roughness)
    SCALAR(specular_ior)
    SCALAR(coat_weight)
    COLOUR(coat_color)
    SCALAR(coat_roughness)
    SCALAR(coat_ior)
    SCALAR(coat_darkening)
    SCALAR(fuzz_weight)
    COLOUR(fuzz_color)
    SCALAR(fuzz_roughness)
#undef SCALAR
#undef COLOUR
    std::fprintf(stderr, "unknown parameter %s (n=%d)\n", p.name, p.n);
    std::exit(2);
}

static OpenPBR_ResolvedInputs inputs_of(const Case& c)
{
    OpenPBR_ResolvedInputs in = openpbr_make_default_resolved_inputs();
    for (const Param& p : c.params)
        set_param(in, p);
    return in;
}

static const double kPi = 3.14159265358979323846;
static const double kThetaO[] = {0, 15, 30, 45, 60, 75, 85};
static const int kNumThetaO = 7;
static const double kVarThetaO[] = {0, 45, 75};
static const int kNumVarThetaO = 3;
struct Triple
{
    double ti, to, dphi;
};
static const Triple kTriples[] = {{30, 45, 180}, {45, 45, 180}, {10, 60, 90}, {60, 30, 0}, {20, 20, 180}, {75, 20, 120}, {50, 70, 180}, {5, 5, 45}};
static const int kNumTriples = 8;

static vec3 dir_of(double theta_deg, double phi_deg)
{
    const double t = theta_deg * kPi / 180.0, p = phi_deg * kPi / 180.0;
    return vec3(float(std::sin(t) * std::cos(p)), float(std::sin(t) * std::sin(p)), float(std::cos(t)));
}

static OpenPBR_PreparedBsdf prepare(const OpenPBR_ResolvedInputs& in, const vec3 wo)
{
    return openpbr_prepare(in, vec3(1.0f), OpenPBR_BaseRgbWavelengths_nm, OpenPBR_VacuumIor, wo);
}

// ---------------------------------------------------------------------------------------------
// Random numbers: SplitMix64 seeding a xoshiro256** stream.
// ---------------------------------------------------------------------------------------------

static std::uint64_t splitmix64(std::uint64_t& x)
{
    std::uint64_t z = (x += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

struct Rng
{
    std::uint64_t s[4];
    explicit Rng(std::uint64_t seed)
    {
        for (auto& w : s)
            w = splitmix64(seed);
    }
    static std::uint64_t rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
    std::uint64_t next()
    {
        const std::uint64_t result = rotl(s[1] * 5, 7) * 9;
        const std::uint64_t t = s[1] << 17;
        s[2] ^= s[0];
        s[3] ^= s[1];
        s[1] ^= s[2];
        s[0] ^= s[3];
        s[2] ^= t;
        s[3] = rotl(s[3], 45);
        return result;
    }
    double uniform_double() { return double(next() >> 11) * 0x1.0p-53; }     // [0, 1)
    float uniform_float() { return float(next() >> 40) * 0x1.0p-24f; }       // [0, 1), 24 bits
};

static const float kBelowOne = 0x1.fffffep-1f;

static std::uint64_t seed_for(const char* case_name, int theta_index, std::uint64_t salt)
{
    std::uint64_t h = 1469598103934665603ull;  // FNV-1a of the name, then the indices
    for (const char* p = case_name; *p; ++p)
        h = (h ^ std::uint64_t(static_cast<unsigned char>(*p))) * 1099511628211ull;
    h = (h ^ std::uint64_t(theta_index)) * 1099511628211ull;
    h = (h ^ salt) * 1099511628211ull;
    return h;
}

// ---------------------------------------------------------------------------------------------
// Measurements.
// ---------------------------------------------------------------------------------------------

struct AlbedoResult
{
    double mean[3];
    double se[3];
    long failed;           // samples with pdf == 0
    long below_horizon;    // successful samples with ωi·n ≤ 0 and a non-zero weight
    long non_finite;       // weights that are NaN or ±inf (counted as 0)
};

static AlbedoResult albedo_mc(const Case& c, const OpenPBR_ResolvedInputs& in, int theta_index)
{
    const int kGrid = 2048, B = 8, NB = B * B;
    const OpenPBR_PreparedBsdf prep = prepare(in, dir_of(kThetaO[theta_index], 0.0));
    std::vector<double> batch_sum(3 * NB, 0.0);
    Rng rng(seed_for(c.name, theta_index, 0xA1BED0ull));
    AlbedoResult r{};
    for (int i = 0; i < kGrid; ++i)
    {
        for (int j = 0; j < kGrid; ++j)
        {
            const float u1 = std::min(float((i + rng.uniform_double()) / kGrid), kBelowOne);
            const float u2 = std::min(float((j + rng.uniform_double()) / kGrid), kBelowOne);
            const float u3 = rng.uniform_float();
            vec3 wi;
            OpenPBR_DiffuseSpecular w;
            float pdf;
            OpenPBR_BsdfLobeType type;
            openpbr_sample(prep, vec3(u1, u2, u3), wi, w, pdf, type);
            if (!(pdf > 0.0f))
            {
                ++r.failed;
                continue;
            }
            const vec3 ws = openpbr_get_sum_of_diffuse_specular(w);
            if (!std::isfinite(ws.x) || !std::isfinite(ws.y) || !std::isfinite(ws.z))
            {
                ++r.non_finite;
                continue;
            }
            if (wi.z <= 0.0f && (ws.x != 0.0f || ws.y != 0.0f || ws.z != 0.0f))
                ++r.below_horizon;
            const int b = (i % B) * B + (j % B);
            batch_sum[3 * b + 0] += ws.x;
            batch_sum[3 * b + 1] += ws.y;
            batch_sum[3 * b + 2] += ws.z;
        }
    }
    const double per_batch = double(kGrid) * kGrid / NB;
    for (int ch = 0; ch < 3; ++ch)
    {
        double m = 0.0;
        for (int b = 0; b < NB; ++b)
            m += batch_sum[3 * b + ch] / per_batch;
        m /= NB;
        double ss = 0.0;
        for (int b = 0; b < NB; ++b)
        {
            const double d = batch_sum[3 * b + ch] / per_batch - m;
            ss += d * d;
        }
        r.mean[ch] = m;
        r.se[ch] = std::sqrt(ss / (NB - 1) / NB);
    }
    return r;
}

// Gauss–Legendre nodes and weights on [-1, 1] (Newton on P_n, double).
static void gauss_legendre(int n, std::vector<double>& x, std::vector<double>& w)
{
    x.assign(n, 0.0);
    w.assign(n, 0.0);
    for (int i = 0; i < (n + 1) / 2; ++i)
    {
        double z = std::cos(kPi * (i + 0.75) / (n + 0.5));
        double dp = 0.0;
        for (int it = 0; it < 100; ++it)
        {
            double p0 = 1.0, p1 = z;
            for (int k = 2; k <= n; ++k)
            {
                const double p2 = ((2.0 * k - 1.0) * z * p1 - (k - 1.0) * p0) / k;
                p0 = p1;
                p1 = p2;
            }
            dp = n * (z * p1 - p0) / (z * z - 1.0);
            const double dz = p1 / dp;
            z -= dz;
            if (std::fabs(dz) < 1e-16)
                break;
        }
        {
            double p0 = 1.0, p1 = z;
            for (int k = 2; k <= n; ++k)
            {
                const double p2 = ((2.0 * k - 1.0) * z * p1 - (k - 1.0) * p0) / k;
                p0 = p1;
                p1 = p2;
            }
            dp = n * (z * p1 - p0) / (z * z - 1.0);
        }
        x[i] = -z;
        x[n - 1 - i] = z;
        w[i] = w[n - 1 - i] = 2.0 / ((1.0 - z * z) * dp * dp);
    }
}

static std::vector<double> breakpoints(double lo, double hi, const std::vector<double>& centres, const std::vector<double>& offsets)
{
    std::vector<double> b = {lo, hi};
    for (double c : centres)
    {
        if (c > lo && c < hi)
            b.push_back(c);
        for (double d : offsets)
        {
            if (c - d > lo && c - d < hi)
                b.push_back(c - d);
            if (c + d > lo && c + d < hi)
                b.push_back(c + d);
        }
    }
    std::sort(b.begin(), b.end());
    std::vector<double> out;
    for (double v : b)
        if (out.empty() || v - out.back() > 1e-9)
            out.push_back(v);
    if (out.back() != hi)
        out.back() = hi;
    return out;
}

static void albedo_quadrature_n(const OpenPBR_PreparedBsdf& prep, double mu_o, int n, double out[3], long& evals)
{
    const std::vector<double> graded = {1e-4, 3e-4, 1e-3, 3e-3, 1e-2, 3e-2, 0.1, 0.3};
    const std::vector<double> mu_b = breakpoints(0.0, 1.0, {mu_o, 1.0, 0.0}, graded);
    const std::vector<double> phi_b = breakpoints(0.0, kPi, {kPi, 0.0}, {1e-3, 3e-3, 1e-2, 3e-2, 0.1, 0.3, 1.0});
    std::vector<double> gx, gw;
    gauss_legendre(n, gx, gw);
    double acc[3] = {0, 0, 0};
    for (size_t a = 0; a + 1 < mu_b.size(); ++a)
    {
        const double m0 = mu_b[a], m1 = mu_b[a + 1], mh = 0.5 * (m1 - m0);
        for (int p = 0; p < n; ++p)
        {
            const double mu = m0 + mh * (gx[p] + 1.0);
            const double wm = mh * gw[p];
            const double s = std::sqrt(std::max(0.0, 1.0 - mu * mu));
            double row[3] = {0, 0, 0};
            for (size_t b = 0; b + 1 < phi_b.size(); ++b)
            {
                const double f0 = phi_b[b], f1 = phi_b[b + 1], fh = 0.5 * (f1 - f0);
                for (int q = 0; q < n; ++q)
                {
                    const double phi = f0 + fh * (gx[q] + 1.0);
                    const vec3 wi(float(s * std::cos(phi)), float(s * std::sin(phi)), float(mu));
                    const vec3 e = openpbr_get_sum_of_diffuse_specular(openpbr_eval(prep, wi));
                    ++evals;
                    row[0] += fh * gw[q] * e.x;
                    row[1] += fh * gw[q] * e.y;
                    row[2] += fh * gw[q] * e.z;
                }
            }
            for (int ch = 0; ch < 3; ++ch)
                acc[ch] += wm * row[ch];
        }
    }
    for (int ch = 0; ch < 3; ++ch)
        out[ch] = 2.0 * acc[ch];  // φ ∈ [0, π] doubled
}

static void json_triple(std::string& s, const double v[3])
{
    char buf[128];
    std::snprintf(buf, sizeof buf, "[%.7g,%.7g,%.7g]", v[0], v[1], v[2]);
    s += buf;
}

static void json_number(std::string& s, double v)
{
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.7g", v);
    s += buf;
}

static int run_case(const Case& c)
{
    const OpenPBR_ResolvedInputs in = inputs_of(c);
    std::string s = "{\"name\":\"";
    s += c.name;
    s += "\",\"build\":\"";
    s += kBuild;
    s += "\",\"params\":{";
    for (size_t k = 0; k < c.params.size(); ++k)
    {
        const Param& p = c.params[k];
        if (k)
            s += ",";
        s += "\"";
        s += p.name;
        s += "\":";
        if (p.n == 1)
            json_number(s, p.v[0]);
        else
        {
            const double v[3] = {p.v[0], p.v[1], p.v[2]};
            json_triple(s, v);
        }
    }
    s += "}";

    // Albedo by Adobe's sampler.
    AlbedoResult ar[kNumThetaO];
    for (int t = 0; t < kNumThetaO; ++t)
        ar[t] = albedo_mc(c, in, t);
    s += ",\"albedo\":[";
    for (int t = 0; t < kNumThetaO; ++t)
    {
        if (t)
            s += ",";
        json_triple(s, ar[t].mean);
    }
    s += "],\"albedo_se\":[";
    for (int t = 0; t < kNumThetaO; ++t)
    {
        if (t)
            s += ",";
        json_triple(s, ar[t].se);
    }
    s += "]";

    // Quadrature cross-check of ∫ eval.
    if (c.rough)
    {
        s += ",\"albedo_quadrature\":[";
        std::string err = ",\"albedo_quadrature_err\":[";
        long evals = 0;
        for (int t = 0; t < kNumThetaO; ++t)
        {
            const OpenPBR_PreparedBsdf prep = prepare(in, dir_of(kThetaO[t], 0.0));
            const double mu_o = std::cos(kThetaO[t] * kPi / 180.0);
            double q16[3], q32[3];
            long e16 = 0;
            albedo_quadrature_n(prep, mu_o, 16, q16, e16);
            albedo_quadrature_n(prep, mu_o, 32, q32, evals);
            const double d[3] = {std::fabs(q32[0] - q16[0]), std::fabs(q32[1] - q16[1]), std::fabs(q32[2] - q16[2])};
            if (t)
            {
                s += ",";
                err += ",";
            }
            json_triple(s, q32);
            json_triple(err, d);
        }
        s += "]";
        s += err;
        s += "],\"quadrature_evals_per_theta\":";
        json_number(s, double(evals / kNumThetaO));
    }
    else
    {
        s += ",\"albedo_quadrature\":null,\"albedo_quadrature_err\":null";
    }

    // BRDF values.
    if (c.rough)
    {
        s += ",\"values\":[";
        for (int k = 0; k < kNumTriples; ++k)
        {
            const Triple& tr = kTriples[k];
            const OpenPBR_PreparedBsdf prep = prepare(in, dir_of(tr.to, 0.0));
            const vec3 wi = dir_of(tr.ti, tr.dphi);
            const vec3 e = openpbr_get_sum_of_diffuse_specular(openpbr_eval(prep, wi));
            const double v[3] = {double(e.x) / wi.z, double(e.y) / wi.z, double(e.z) / wi.z};
            if (k)
                s += ",";
            json_triple(s, v);
        }
        s += "]";
    }
    else
    {
        s += ",\"values\":null";
    }

    // Sampling variance of the channel-average weight, iid uniforms.
    s += ",\"variance\":[";
    std::string mean_s = ",\"mean_weight\":[";
    for (int t = 0; t < kNumVarThetaO; ++t)
    {
        const OpenPBR_PreparedBsdf prep = prepare(in, dir_of(kVarThetaO[t], 0.0));
        Rng rng(seed_for(c.name, 100 + t, 0x5EEDull));
        const long N = 1L << 20;
        double mean = 0.0, m2 = 0.0;  // Welford
        for (long k = 0; k < N; ++k)
        {
            const float u1 = rng.uniform_float(), u2 = rng.uniform_float(), u3 = rng.uniform_float();
            vec3 wi;
            OpenPBR_DiffuseSpecular w;
            float pdf;
            OpenPBR_BsdfLobeType type;
            openpbr_sample(prep, vec3(u1, u2, u3), wi, w, pdf, type);
            double x = 0.0;
            if (pdf > 0.0f)
            {
                const vec3 ws = openpbr_get_sum_of_diffuse_specular(w);
                x = (double(ws.x) + ws.y + ws.z) / 3.0;
                if (!std::isfinite(x))
                    x = 0.0;
            }
            const double d = x - mean;
            mean += d / double(k + 1);
            m2 += d * (x - mean);
        }
        if (t)
        {
            s += ",";
            mean_s += ",";
        }
        json_number(s, m2 / double(N - 1));
        json_number(mean_s, mean);
    }
    s += "]";
    s += mean_s;
    s += "]";

    // Diagnostics of the albedo sampling.
    s += ",\"sample_failures\":[";
    for (int t = 0; t < kNumThetaO; ++t)
    {
        if (t)
            s += ",";
        json_number(s, double(ar[t].failed));
    }
    s += "],\"below_horizon_nonzero\":[";
    for (int t = 0; t < kNumThetaO; ++t)
    {
        if (t)
            s += ",";
        json_number(s, double(ar[t].below_horizon));
    }
    s += "],\"non_finite\":[";
    for (int t = 0; t < kNumThetaO; ++t)
    {
        if (t)
            s += ",";
        json_number(s, double(ar[t].non_finite));
    }
    s += "]}";
    std::printf("%s\n", s.c_str());
    return 0;
}

// ---------------------------------------------------------------------------------------------
// Timing.
// ---------------------------------------------------------------------------------------------

static volatile double g_sink = 0.0;

template <class T>
static inline void escape(T* p)
{
    asm volatile("" : : "g"(p) : "memory");
}

static vec3 random_hemisphere_dir(Rng& rng)
{
    // Cosine-weighted, as the directions a renderer hands a BSDF mostly are.
    const double u1 = rng.uniform_double(), u2 = rng.uniform_double();
    const double r = std::sqrt(u1), phi = 2.0 * kPi * u2;
    return vec3(float(r * std::cos(phi)), float(r * std::sin(phi)), float(std::sqrt(std::max(1e-6, 1.0 - u1))));
}

// Both clocks: the thread's CPU time (the figure: time when another process holds the core is not
// counted) and wall-clock time (for reference).
static double thread_cpu_ns()
{
    timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return double(ts.tv_sec) * 1e9 + double(ts.tv_nsec);
}

struct Timer
{
    std::chrono::steady_clock::time_point t0;
    double c0 = 0.0;
    void start()
    {
        c0 = thread_cpu_ns();
        t0 = std::chrono::steady_clock::now();
    }
    void stop(double& cpu_ns, double& wall_ns) const
    {
        const auto t1 = std::chrono::steady_clock::now();
        cpu_ns = thread_cpu_ns() - c0;
        wall_ns = std::chrono::duration<double, std::nano>(t1 - t0).count();
    }
};

static int run_timing()
{
    const int K = 4096;         // precomputed inputs, cycled
    const int NP = 64;          // prepared BSDFs cycled by eval/sample/pdf
    const long N = 1L << 20;    // calls per repetition (≥ 10^6)
    const int REPS = 15;
    std::vector<Case> cases = conformance_set();
    std::string s = "{\"build\":\"";
    s += kBuild;
    s += "\",\"calls_per_repetition\":";
    json_number(s, double(N));
    s += ",\"repetitions\":";
    json_number(s, REPS);
    s += ",\"cases\":{";
    bool first_case = true;
    for (const char* name : {"defaults", "all-layers-white"})
    {
        const Case* c = nullptr;
        for (const Case& cc : cases)
            if (std::strcmp(cc.name, name) == 0)
                c = &cc;
        const OpenPBR_ResolvedInputs in = inputs_of(*c);
        Rng rng(seed_for(name, 999, 0x71111ull));
        std::vector<vec3> views(K), lights(K), rands(K);
        for (int k = 0; k < K; ++k)
        {
            views[k] = random_hemisphere_dir(rng);
            lights[k] = random_hemisphere_dir(rng);
            rands[k] = vec3(rng.uniform_float(), rng.uniform_float(), rng.uniform_float());
        }
        std::vector<OpenPBR_PreparedBsdf> preps;
        for (int k = 0; k < NP; ++k)
            preps.push_back(prepare(in, views[k]));

        const char* ops[] = {"prepare", "eval", "sample", "pdf", "hit"};
        if (!first_case)
            s += ",";
        first_case = false;
        s += "\"";
        s += name;
        s += "\":{";
        for (int op = 0; op < 5; ++op)
        {
            std::vector<double> per_call, per_call_wall;
            for (int rep = 0; rep < REPS; ++rep)
            {
                double acc = 0.0;
                Timer tm;
                tm.start();
                switch (op)
                {
                case 0:
                    for (long i = 0; i < N; ++i)
                    {
                        OpenPBR_PreparedBsdf p = prepare(in, views[i & (K - 1)]);
                        escape(&p);
                        acc += p.fuzz_lobe.view_reflected;
                    }
                    break;
                case 1:
                    for (long i = 0; i < N; ++i)
                    {
                        const vec3 e = openpbr_get_sum_of_diffuse_specular(openpbr_eval(preps[i & (NP - 1)], lights[i & (K - 1)]));
                        acc += e.x + e.y + e.z;
                    }
                    break;
                case 2:
                    for (long i = 0; i < N; ++i)
                    {
                        vec3 wi;
                        OpenPBR_DiffuseSpecular w;
                        float pdf;
                        OpenPBR_BsdfLobeType type;
                        openpbr_sample(preps[i & (NP - 1)], rands[i & (K - 1)], wi, w, pdf, type);
                        if (pdf > 0.0f)
                        {
                            const vec3 ws = openpbr_get_sum_of_diffuse_specular(w);
                            acc += ws.x + ws.y + ws.z + wi.z;
                        }
                    }
                    break;
                case 3:
                    for (long i = 0; i < N; ++i)
                        acc += openpbr_pdf(preps[i & (NP - 1)], lights[i & (K - 1)]);
                    break;
                case 4:
                    for (long i = 0; i < N; ++i)
                    {
                        const OpenPBR_PreparedBsdf p = prepare(in, views[i & (K - 1)]);
                        const vec3 e = openpbr_get_sum_of_diffuse_specular(openpbr_eval(p, lights[(i + 1) & (K - 1)]));
                        vec3 wi;
                        OpenPBR_DiffuseSpecular w;
                        float pdf;
                        OpenPBR_BsdfLobeType type;
                        openpbr_sample(p, rands[i & (K - 1)], wi, w, pdf, type);
                        acc += e.x + e.y + e.z;
                        if (pdf > 0.0f)
                        {
                            const vec3 ws = openpbr_get_sum_of_diffuse_specular(w);
                            acc += ws.x + ws.y + ws.z + openpbr_pdf(p, wi);
                        }
                    }
                    break;
                }
                double cpu_ns, wall_ns;
                tm.stop(cpu_ns, wall_ns);
                g_sink = g_sink + acc;
                per_call.push_back(cpu_ns / double(N));
                per_call_wall.push_back(wall_ns / double(N));
            }
            std::sort(per_call.begin(), per_call.end());
            std::sort(per_call_wall.begin(), per_call_wall.end());
            if (op)
                s += ",";
            s += "\"";
            s += ops[op];
            s += "_ns\":{\"median\":";
            json_number(s, per_call[REPS / 2]);
            s += ",\"min\":";
            json_number(s, per_call[0]);
            s += ",\"wall_median\":";
            json_number(s, per_call_wall[REPS / 2]);
            s += "}";
        }
        s += "}";
    }
    s += "}}";
    std::printf("%s\n", s.c_str());
    return 0;
}

int main(int argc, char** argv)
{
    const std::vector<Case> cases = conformance_set();
    if (argc >= 2 && std::strcmp(argv[1], "list") == 0)
    {
        for (const Case& c : cases)
            std::printf("%s\n", c.name);
        return 0;
    }
    if (argc >= 3 && std::strcmp(argv[1], "case") == 0)
    {
        for (const Case& c : cases)
            if (std::strcmp(c.name, argv[2]) == 0)
                return run_case(c);
        std::fprintf(stderr, "no case %s\n", argv[2]);
        return 2;
    }
    if (argc >= 2 && std::strcmp(argv[1], "timing") == 0)
        return run_timing();
    std::fprintf(stderr, "usage: %s list | case NAME | timing\n", argv[0]);
    return 2;
}
