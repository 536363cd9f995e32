/* Materials through the C API: a plastic (a GGX alpha = 0.1 dielectric coat of
 * index 1.5 over an EON rough diffuse base), a coated gold, a sum and a mix,
 * checked for reciprocity, energy, sampling consistency and against the
 * formulas of the sum and the mix; then OpenPBR Surface's reflection layer
 * (RadOpenPbr) with its defaults and as a coated metal.
 *
 * Build and run (from the repository root, after `cd ffi && cargo build --release`):
 *   cc -std=c99 -Wall -Wextra -Werror -O2 ffi/examples/material.c -Iffi/include \
 *      ffi/target/release/libradiometry_ffi.a -lm -o target/material-example && ./target/material-example
 * Prints one line per check and exits non-zero if any fails.
 */
#include "radiometry.h"

#include <math.h>
#include <stdio.h>

static int failures = 0;

static void check(const char *what, double got, double want, double rel_tol) {
    double err = fabs(got - want);
    int ok = err <= rel_tol * fabs(want) + 1e-12;
    printf("%-62s %.9g (expected %.9g) %s\n", what, got, want, ok ? "ok" : "FAIL");
    if (!ok) failures++;
}

static void check_le(const char *what, double got, double bound) {
    int ok = got <= bound;
    printf("%-62s %.6g (at most %.6g) %s\n", what, got, bound, ok ? "ok" : "FAIL");
    if (!ok) failures++;
}

static void check_ge(const char *what, double got, double bound) {
    int ok = got >= bound;
    printf("%-62s %.6g (at least %.6g) %s\n", what, got, bound, ok ? "ok" : "FAIL");
    if (!ok) failures++;
}

static void check_status(const char *what, RadStatus got, RadStatus want) {
    int ok = got == want;
    printf("%-62s status %d \"%s\" %s\n", what, (int)got, rad_status_message((int)got), ok ? "ok" : "FAIL");
    if (!ok) failures++;
}

static RadVec3 dir(double theta, double phi) {
    RadVec3 v = {(float)(sin(theta) * cos(phi)), (float)(sin(theta) * sin(phi)), (float)cos(theta)};
    return v;
}

static float eval(const RadMaterial *m, RadVec3 wi, RadVec3 wo) {
    float f = -1.0f;
    rad_material_eval(m, wi, wo, &f);
    return f;
}

/* The directional albedo at wo estimated from the material's own sampler:
 * the mean of the sample weights f cos / pdf over a stratified n x n grid of
 * (u0, u1), with its standard error. */
static void albedo(const RadMaterial *m, RadVec3 wo, int n, double *mean, double *se) {
    double s = 0.0, s2 = 0.0;
    for (int i = 0; i < n; i++) {
        for (int j = 0; j < n; j++) {
            RadBrdfSample smp;
            rad_material_sample(m, wo, (i + 0.5f) / n, (j + 0.5f) / n, &smp);
            s += smp.weight[0];
            s2 += (double)smp.weight[0] * smp.weight[0];
        }
    }
    double k = (double)n * n;
    *mean = s / k;
    *se = sqrt(fmax(s2 / k - *mean * *mean, 0.0) / (k - 1.0));
}

static float openpbr_eval(const RadOpenPbr *m, RadVec3 wi, RadVec3 wo) {
    float f = -1.0f;
    rad_openpbr_eval(m, wi, wo, &f);
    return f;
}

/* As albedo(), for an OpenPBR material. */
static void openpbr_albedo(const RadOpenPbr *m, RadVec3 wo, int n, double *mean, double *se) {
    double s = 0.0, s2 = 0.0;
    for (int i = 0; i < n; i++) {
        for (int j = 0; j < n; j++) {
            RadBrdfSample smp;
            rad_openpbr_sample(m, wo, (i + 0.5f) / n, (j + 0.5f) / n, &smp);
            s += smp.weight[0];
            s2 += (double)smp.weight[0] * smp.weight[0];
        }
    }
    double k = (double)n * n;
    *mean = s / k;
    *se = sqrt(fmax(s2 / k - *mean * *mean, 0.0) / (k - 1.0));
}

/* OpenPBR Surface's reflection layer: the defaults and a coated metal. */
static void openpbr(void) {
    const double pi = 3.14159265358979323846;
    char line[128];
    RadOpenPbrParams p;
    check_status("rad_openpbr_default_params", rad_openpbr_default_params(&p), RAD_STATUS_OK);
    check("default base_color (grey)", p.base_color[0] + p.base_color[1] + p.base_color[2], 3 * 0.8f, 1e-7);
    check("default specular_roughness", p.specular_roughness, 0.3f, 0);
    check("default specular_ior", p.specular_ior, 1.5f, 0);
    check("default coat_weight, fuzz_weight (no coat, no fuzz)", p.coat_weight + p.fuzz_weight, 0.0, 0);
    check("default coat_ior", p.coat_ior, 1.6f, 0);
    check("default coat_darkening", p.coat_darkening, 1.0f, 0);
    check("default layering: energy-conserving (reciprocal = 0)", p.reciprocal, 0, 0);
    check("sizeof(RadOpenPbr) (plain data, no pointers)", (double)sizeof(RadOpenPbr), 104, 0);

    RadOpenPbr defaults;
    check_status("openpbr defaults (validates and stores the parameters)", rad_openpbr_new(&p, &defaults), RAD_STATUS_OK);
    RadVec3 wo = dir(0.5, 0.0);
    printf("openpbr defaults f(mirror of 28.6 deg) = %.6g 1/sr\n", openpbr_eval(&defaults, dir(0.5, pi), wo));
    printf("openpbr defaults f(80 deg, 28.6 deg)   = %.6g 1/sr\n", openpbr_eval(&defaults, dir(1.4, 2.0), wo));
    for (int t = 0; t < 3; t++) {
        double theta_deg = t == 0 ? 0.0 : t == 1 ? 45.0 : 80.0;
        double mean, se;
        openpbr_albedo(&defaults, dir(theta_deg * pi / 180.0, 0.0), 128, &mean, &se);
        snprintf(line, sizeof line, "openpbr defaults albedo at %2.0f deg (<= 1 + 4 se)", theta_deg);
        check_le(line, mean, 1.0 + 4.0 * se);
        check_ge("  ... a white-ish base reflects most of the light", mean, 0.5);
    }

    /* A coated metal: a gold-ish F82-tint metal under a clear, slightly
     * absorbing coat. */
    RadOpenPbrParams metal = p;
    metal.base_metalness = 1.0f;
    metal.base_color[0] = 0.95f;
    metal.base_color[1] = 0.8f;
    metal.base_color[2] = 0.4f;
    metal.specular_color[0] = metal.specular_color[1] = metal.specular_color[2] = 0.95f;
    metal.specular_roughness = 0.4f;
    metal.coat_weight = 1.0f;
    metal.coat_roughness = 0.1f;
    metal.coat_color[0] = metal.coat_color[1] = metal.coat_color[2] = 0.9f;
    RadOpenPbr coated_metal;
    check_status("openpbr coated metal", rad_openpbr_new(&metal, &coated_metal), RAD_STATUS_OK);
    double mean, se;
    openpbr_albedo(&coated_metal, wo, 128, &mean, &se);
    check_le("openpbr coated metal albedo at 28.6 deg (<= 1 + 4 se)", mean, 1.0 + 4.0 * se);
    check_ge("  ... and a metal reflects most of the light", mean, 0.6);

    /* Reciprocity (in the reciprocal layering) and exact sampling densities. */
    RadOpenPbrParams metal_rec = metal;
    metal_rec.reciprocal = 1;
    RadOpenPbr coated_metal_rec;
    check_status("openpbr coated metal, reciprocal layering", rad_openpbr_new(&metal_rec, &coated_metal_rec),
                 RAD_STATUS_OK);
    openpbr_albedo(&coated_metal_rec, wo, 128, &mean, &se);
    check_le("openpbr reciprocal coated metal albedo at 28.6 deg (<= 1 + 4 se)", mean, 1.0 + 4.0 * se);
    double worst = 0.0;
    for (int a = 0; a < 12; a++) {
        for (int b = 0; b < 12; b++) {
            RadVec3 x = dir(1.5 * a / 12.0 + 0.01, 0.7 * a), y = dir(1.5 * b / 12.0 + 0.02, -1.3 * b);
            double f1 = openpbr_eval(&coated_metal_rec, x, y), f2 = openpbr_eval(&coated_metal_rec, y, x);
            double d = fabs(f1 - f2) / fmax(fabs(f1), 1e-3);
            if (d > worst) worst = d;
        }
    }
    check_le("openpbr reciprocal coated metal reciprocity (worst relative)", worst, 1e-5);
    int exact = 1;
    for (int k = 0; k < 256; k++) {
        RadVec3 o = dir(1.5 * (k % 16) / 16.0, 0.3 * k);
        RadBrdfSample s;
        rad_openpbr_sample(&coated_metal, o, (k * 0.618034f) - (int)(k * 0.618034f),
                           (k * 0.7548777f) - (int)(k * 0.7548777f), &s);
        if (s.pdf == 0.0f) continue;
        float q = -1.0f;
        rad_openpbr_pdf(&coated_metal, s.wi, o, &q);
        if (q != s.pdf) exact = 0;
    }
    check("openpbr pdf(sample) == sample.pdf, bit for bit (1 = all)", exact, 1, 0);

    /* Colour: the coated metal's base colour per channel (the _rgb calls); the
     * RGB sample's pdf is rad_openpbr_pdf_rgb's, bit for bit. */
    float rgb[3];
    check_status("openpbr eval_rgb", rad_openpbr_eval_rgb(&coated_metal, dir(0.5, pi), wo, rgb), RAD_STATUS_OK);
    printf("openpbr coated metal f(mirror) R G B = %.6g %.6g %.6g 1/sr\n", rgb[0], rgb[1], rgb[2]);
    check_le("  ... a gold-ish base: blue below red", rgb[2] - rgb[0], 0.0);
    int exact_rgb = 1;
    for (int k = 0; k < 256; k++) {
        RadVec3 o = dir(1.5 * (k % 16) / 16.0, 0.3 * k);
        RadBrdfSample s;
        rad_openpbr_sample_rgb(&coated_metal, o, (k * 0.618034f) - (int)(k * 0.618034f),
                               (k * 0.7548777f) - (int)(k * 0.7548777f), &s);
        if (s.pdf == 0.0f) continue;
        float q = -1.0f;
        rad_openpbr_pdf_rgb(&coated_metal, s.wi, o, &q);
        if (q != s.pdf) exact_rgb = 0;
    }
    check("openpbr pdf_rgb(sample_rgb) == sample.pdf, bit for bit (1 = all)", exact_rgb, 1, 0);

    /* A batch equals single calls, bit for bit (and rebuilds the material once). */
    enum { N = 64 };
    RadVec3 wis[N], wos[N];
    float out[N];
    for (int k = 0; k < N; k++) {
        wis[k] = dir(1.5 * k / N, 0.37 * k);
        wos[k] = dir(1.5 * (N - k) / N, -0.11 * k);
    }
    check_status("openpbr eval_batch", rad_openpbr_eval_batch(&coated_metal, wis, wos, out, N), RAD_STATUS_OK);
    int same = 1;
    for (int k = 0; k < N; k++) {
        if (out[k] != openpbr_eval(&coated_metal, wis[k], wos[k])) same = 0;
    }
    check("openpbr eval_batch == eval, bit for bit (1 = all)", same, 1, 0);

    /* Bad input is a status. */
    RadOpenPbr bad;
    RadOpenPbrParams q = p;
    q.specular_ior = 0.5f;
    check_status("openpbr specular_ior = 0.5 rejected", rad_openpbr_new(&q, &bad), RAD_STATUS_OUT_OF_RANGE);
    q = p;
    q.base_color[1] = NAN;
    check_status("openpbr base_color = NaN rejected", rad_openpbr_new(&q, &bad), RAD_STATUS_NOT_FINITE);
    RadOpenPbr scribbled = coated_metal;
    scribbled.params.reciprocal = 7;
    float f = 0.0f;
    check_status("openpbr: a scribbled layering flag is reported", rad_openpbr_eval(&scribbled, wos[0], wo, &f),
                 RAD_STATUS_OUT_OF_RANGE);
    RadOpenPbr zeroed = {0};
    check_status("openpbr: zeroed handle rejected", rad_openpbr_eval(&zeroed, wos[0], wo, &f), RAD_STATUS_BAD_HANDLE);
}

int main(void) {
    const double pi = 3.14159265358979323846;
    char line[128];

    /* The plastic: coat = GGX alpha 0.1 with the exact dielectric Fresnel of
     * eta = 1.5, base = EON (rho = 0.8, sigma = 0.5), a clear coat. */
    RadBrdf coat, eon;
    check_status("ggx(alpha=0.1, fresnel=dielectric(eta=1.5))",
                 rad_brdf_microfacet(RAD_DISTRIBUTION_GGX, 0.1f, RAD_SHADOWING_HEIGHT_CORRELATED,
                                     RAD_FRESNEL_DIELECTRIC, 1.5f, 0.0f, &coat),
                 RAD_STATUS_OK);
    check_status("eon(rho=0.8, sigma=0.5)", rad_brdf_eon(0.8f, 0.5f, &eon), RAD_STATUS_OK);
    RadMaterial plastic;
    check_status("coated(coat, eon) (stores the lobes and the coat parameters)",
                 rad_material_coated(&coat, &eon, 1.0f, 1.5f, &plastic), RAD_STATUS_OK);
    check("sizeof(RadMaterial) (plain data, no pointers)", (double)sizeof(RadMaterial), 132, 0);
    RadMaterial plastic_rec;
    check_status("coated_reciprocal(coat, eon)", rad_material_coated_reciprocal(&coat, &eon, 1.0f, 1.5f, &plastic_rec),
                 RAD_STATUS_OK);

    /* A few values: the highlight in the mirror direction, off-specular, grazing. */
    RadVec3 wo = dir(0.5, 0.0);
    printf("plastic f(mirror of 28.6 deg)      = %.6g 1/sr\n", eval(&plastic, dir(0.5, pi), wo));
    printf("plastic f(normal, 28.6 deg)        = %.6g 1/sr\n", eval(&plastic, dir(0.0, 0.0), wo));
    printf("plastic f(80 deg, 28.6 deg)        = %.6g 1/sr\n", eval(&plastic, dir(1.4, 2.0), wo));
    printf("plastic f(below the horizon)       = %.6g 1/sr\n", eval(&plastic, dir(2.0, 0.0), wo));

    /* Away from the highlight the coat adds almost nothing: the base, scaled by
     * what the coat lets through, is within a few percent of EON itself. */
    float fe = 0.0f;
    rad_brdf_eval(&eon, dir(1.0, 2.0), wo, &fe);
    double ratio = eval(&plastic, dir(1.0, 2.0), wo) / fe;
    check_le("plastic / eon off the highlight (coat lets through <= 1)", ratio, 1.0);
    check_ge("  ... and at least 0.85 of the base", ratio, 0.85);

    /* Reciprocity in the reciprocal layering: f(a, b) = f(b, a) over a grid
     * of directions. */
    double worst = 0.0;
    for (int a = 0; a < 12; a++) {
        for (int b = 0; b < 12; b++) {
            RadVec3 x = dir(1.5 * a / 12.0 + 0.01, 0.7 * a), y = dir(1.5 * b / 12.0 + 0.02, -1.3 * b);
            double f1 = eval(&plastic_rec, x, y), f2 = eval(&plastic_rec, y, x);
            double d = fabs(f1 - f2) / fmax(fabs(f1), 1e-3);
            if (d > worst) worst = d;
        }
    }
    check_le("reciprocal plastic: worst relative |f(a,b) - f(b,a)|", worst, 1e-5);

    /* Sampling: the sample's pdf is the material's pdf at the sampled
     * direction, exactly; the weight is f cos / pdf. */
    int exact = 1, n_samples = 0;
    double worst_w = 0.0;
    for (int k = 0; k < 256; k++) {
        RadVec3 o = dir(1.5 * (k % 16) / 16.0, 0.3 * k);
        RadBrdfSample s;
        rad_material_sample(&plastic, o, (k * 0.618034f) - (int)(k * 0.618034f), (k * 0.7548777f) - (int)(k * 0.7548777f),
                            &s);
        if (s.pdf == 0.0f) continue;
        n_samples++;
        float p = -1.0f;
        rad_material_pdf(&plastic, s.wi, o, &p);
        if (p != s.pdf) exact = 0;
        double w = eval(&plastic, s.wi, o) * s.wi.z / s.pdf;
        double d = fabs(w - s.weight[0]) / fmax(w, 1e-3);
        if (d > worst_w) worst_w = d;
    }
    check("plastic pdf(sample) == sample.pdf, bit for bit (1 = all)", exact, 1, 0);
    check_le("plastic sample weight vs f cos / pdf (worst relative)", worst_w, 1e-5);
    check_ge("plastic samples drawn of 256", n_samples, 200);

    /* Energy: with a white base (rho = 1) the albedo stays below 1 (within
     * 4 standard errors) and a clear coat keeps most of the light. */
    RadBrdf white_eon;
    RadMaterial white;
    rad_brdf_eon(1.0f, 0.5f, &white_eon);
    rad_material_coated(&coat, &white_eon, 1.0f, 1.5f, &white);
    for (int t = 0; t < 3; t++) {
        double theta_deg = t == 0 ? 0.0 : t == 1 ? 45.0 : 80.0;
        double mean, se;
        albedo(&white, dir(theta_deg * pi / 180.0, 0.0), 128, &mean, &se);
        snprintf(line, sizeof line, "white plastic albedo at %2.0f deg (<= 1 + 4 se = %.6f)", theta_deg, 1.0 + 4.0 * se);
        check_le(line, mean, 1.0 + 4.0 * se);
        check_ge("  ... and a clear coat keeps most of the light", mean, 0.9);
    }

    /* A coated gold: a dielectric coat over GGX alpha 0.3 with gold's measured
     * eta, k (reduced to one channel), through a tinted coat. */
    RadBrdf gold;
    check_status("ggx(alpha=0.3, fresnel=conductor(metal=Au))",
                 rad_brdf_microfacet(RAD_DISTRIBUTION_GGX, 0.3f, RAD_SHADOWING_HEIGHT_CORRELATED, RAD_FRESNEL_METAL,
                                     RAD_METAL_AU, 0.0f, &gold),
                 RAD_STATUS_OK);
    printf("gold eta, k (monochrome fit)       = %.6g, %.6g\n", gold.params[1], gold.params[2]);
    RadMaterial coated_gold;
    check_status("coated(coat, gold, coat_color=0.8)", rad_material_coated(&coat, &gold, 0.8f, 1.5f, &coated_gold),
                 RAD_STATUS_OK);
    double mean, se;
    albedo(&coated_gold, dir(0.5, 0.0), 128, &mean, &se);
    check_le("coated gold albedo at 28.6 deg (<= 1 + 4 se)", mean, 1.0 + 4.0 * se);

    /* Sum and mix against their formulas. */
    RadBrdf sheen;
    check_status("sheen(color=1, roughness=0.5)", rad_brdf_sheen(1.0f, 0.5f, &sheen), RAD_STATUS_OK);
    RadMaterial sum, mix;
    check_status("sum: eon + sheen", rad_material_sum(&eon, &sheen, &sum), RAD_STATUS_OK);
    check_status("mix(0.25, sheen, eon)", rad_material_mix(0.25f, &sheen, &eon, &mix), RAD_STATUS_OK);
    RadVec3 wi = dir(1.2, 2.5);
    float fs = 0.0f;
    rad_brdf_eval(&eon, wi, wo, &fe);
    rad_brdf_eval(&sheen, wi, wo, &fs);
    check("sum eval = f_eon + f_sheen", eval(&sum, wi, wo), (double)fe + fs, 1e-6);
    check("mix eval = 0.25 f_sheen + 0.75 f_eon", eval(&mix, wi, wo), 0.25 * fs + 0.75 * fe, 1e-6);

    /* Batches equal single calls, bit for bit. */
    enum { N = 100 };
    RadVec3 wis[N], wos[N];
    float out[N];
    for (int k = 0; k < N; k++) {
        wis[k] = dir(1.5 * k / N, 0.37 * k);
        wos[k] = dir(1.5 * (N - k) / N, -0.11 * k);
    }
    check_status("plastic eval_batch", rad_material_eval_batch(&plastic, wis, wos, out, N), RAD_STATUS_OK);
    int same = 1;
    for (int k = 0; k < N; k++) {
        if (out[k] != eval(&plastic, wis[k], wos[k])) same = 0;
    }
    check("plastic eval_batch == eval, bit for bit (1 = all)", same, 1, 0);

    /* Bad input is a status, never a crash. */
    RadMaterial bad;
    check_status("coat_ior = 0.5 rejected", rad_material_coated(&coat, &eon, 1.0f, 0.5f, &bad),
                 RAD_STATUS_OUT_OF_RANGE);
    check_status("mix weight 1.5 rejected", rad_material_mix(1.5f, &eon, &sheen, &bad), RAD_STATUS_OUT_OF_RANGE);
    check_status("unknown metal rejected",
                 rad_brdf_microfacet(RAD_DISTRIBUTION_GGX, 0.3f, 0, RAD_FRESNEL_METAL, 42.0f, 0.0f, &gold),
                 RAD_STATUS_UNKNOWN_KIND);
    check_status("oren-nayar(rho=1, sigma_rad=0.2) gains energy: rejected", rad_brdf_oren_nayar(1.0f, 0.2f, &eon),
                 RAD_STATUS_CONSTRAINT);
    RadMaterial scribbled = plastic;
    scribbled.reciprocal = 2;
    float f = 0.0f;
    check_status("a scribbled layering flag is reported", rad_material_eval(&scribbled, wi, wo, &f),
                 RAD_STATUS_BAD_HANDLE);
    RadMaterial zeroed = {0};
    check_status("zeroed material rejected", rad_material_eval(&zeroed, wi, wo, &f), RAD_STATUS_BAD_HANDLE);

    openpbr();

    if (failures) {
        printf("%d check(s) FAILED\n", failures);
        return 1;
    }
    printf("material.c: all checks passed\n");
    return 0;
}
