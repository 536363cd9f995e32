/* BRDF plugins through the C API, checked against closed forms written out here.
 *
 * Build and run (from the repository root, after `cd ffi && cargo build --release`):
 *   cc -std=c99 -Wall -Wextra -Werror -O2 ffi/examples/brdf.c -Iffi/include \
 *      ffi/target/release/libradiometry_ffi.a -lm -o target/brdf-example && ./target/brdf-example
 * Prints one line per check and exits non-zero if any fails.
 */
#include "radiometry.h"

#include <math.h>
#include <stdio.h>

static int failures = 0;

static void check(const char *what, double got, double want, double rel_tol) {
    double err = fabs(got - want);
    int ok = err <= rel_tol * fabs(want) + 1e-12;
    printf("%-58s %.9g (expected %.9g) %s\n", what, got, want, ok ? "ok" : "FAIL");
    if (!ok) failures++;
}

static void check_le(const char *what, double got, double bound) {
    int ok = got <= bound;
    printf("%-58s %.3g (at most %.3g) %s\n", what, got, bound, ok ? "ok" : "FAIL");
    if (!ok) failures++;
}

static void check_status(const char *what, RadStatus got, RadStatus want) {
    int ok = got == want;
    printf("%-58s status %d \"%s\" %s\n", what, (int)got, rad_status_message((int)got), ok ? "ok" : "FAIL");
    if (!ok) failures++;
}

static RadVec3 dir(double theta, double phi) {
    RadVec3 v = {(float)(sin(theta) * cos(phi)), (float)(sin(theta) * sin(phi)), (float)cos(theta)};
    return v;
}

int main(void) {
    const double pi = 3.14159265358979323846;
    RadVec3 n = {0.0f, 0.0f, 1.0f};
    float f = 0.0f;

    /* Lambertian: f = rho / pi everywhere above the horizon. */
    RadBrdf lambert;
    check_status("lambertian(albedo=0.5)", rad_brdf_lambertian(0.5f, &lambert), RAD_STATUS_OK);
    rad_brdf_eval(&lambert, dir(0.4, 0.3), dir(1.1, 2.0), &f);
    check("lambertian eval = 0.5/pi", f, 0.5 / pi, 1e-6);

    /* GGX at normal incidence: D(n) = 1/(pi a^2), G2 = 1, F = 1, so
     * f = D G2 F / (4 cos cos) = 1/(4 pi a^2) (Walter et al. 2007). */
    RadBrdf ggx;
    check_status("ggx(alpha=0.5)",
                 rad_brdf_microfacet(RAD_DISTRIBUTION_GGX, 0.5f, RAD_SHADOWING_HEIGHT_CORRELATED,
                                     RAD_FRESNEL_NONE, 0.0f, 0.0f, &ggx),
                 RAD_STATUS_OK);
    rad_brdf_eval(&ggx, n, n, &f);
    check("ggx eval(n, n) = 1/(4 pi 0.25)", f, 1.0 / (4.0 * pi * 0.25), 2e-6);

    /* Beckmann at normal incidence: D(n) = 1/(pi a^2) as well. */
    RadBrdf beckmann;
    rad_brdf_microfacet(RAD_DISTRIBUTION_BECKMANN, 0.3f, RAD_SHADOWING_SEPARABLE, RAD_FRESNEL_NONE, 0, 0,
                        &beckmann);
    rad_brdf_eval(&beckmann, n, n, &f);
    check("beckmann eval(n, n) = 1/(4 pi 0.09)", f, 1.0 / (4.0 * pi * 0.09), 2e-6);

    /* Schlick Fresnel at normal incidence multiplies by f0. */
    RadBrdf schlick;
    rad_brdf_microfacet(RAD_DISTRIBUTION_GGX, 0.5f, RAD_SHADOWING_HEIGHT_CORRELATED, RAD_FRESNEL_SCHLICK,
                        0.04f, 0.0f, &schlick);
    rad_brdf_eval(&schlick, n, n, &f);
    check("ggx+schlick(f0=0.04) eval(n, n) = 0.04/(4 pi 0.25)", f, 0.04 / (pi), 2e-6);

    /* Modified Phong in the mirror direction: kd/pi + ks (n+2)/(2 pi). */
    RadBrdf phong;
    check_status("phong(exponent=20, ks=0.6, kd=0.3)", rad_brdf_phong(20.0f, 0.6f, 0.3f, &phong), RAD_STATUS_OK);
    rad_brdf_eval(&phong, dir(0.5, 0.0), dir(0.5, pi), &f);
    check("phong eval(mirror) = kd/pi + ks (n+2)/(2pi)", f, 0.3 / pi + 0.6 * 22.0 / (2.0 * pi), 1e-5);

    /* Sampling: the sample's pdf is the pdf of its direction, its weight is
     * f cos(theta_i) / pdf. */
    RadVec3 wo = dir(0.7, 0.2);
    RadBrdfSample s;
    check_status("ggx sample", rad_brdf_sample(&ggx, wo, 0.3f, 0.8f, &s), RAD_STATUS_OK);
    float p = 0.0f;
    rad_brdf_pdf(&ggx, s.wi, wo, &p);
    check("ggx sample pdf = pdf(wi, wo)", s.pdf, p, 1e-5);
    rad_brdf_eval(&ggx, s.wi, wo, &f);
    check("ggx sample weight = f cos / pdf", s.weight[0], f * s.wi.z / s.pdf, 1e-5);
    check("  ... the same weight on every channel (a grey BRDF)", s.weight[2], s.weight[0], 0);

    /* Colour: an RGB albedo, and gold's measured eta, k per channel. */
    const float orange[3] = {0.8f, 0.4f, 0.1f};
    RadBrdf lam_rgb;
    check_status("lambertian_rgb(0.8, 0.4, 0.1)", rad_brdf_lambertian_rgb(orange, &lam_rgb), RAD_STATUS_OK);
    float rgb[3];
    RadBrdf bad_rgb;
    check_status("lambertian_rgb eval_rgb", rad_brdf_eval_rgb(&lam_rgb, n, dir(0.9, 1.0), rgb), RAD_STATUS_OK);
    check("  ... red = 0.8/pi", rgb[0], 0.8 / pi, 1e-6);
    check("  ... blue = 0.1/pi", rgb[2], 0.1 / pi, 1e-6);
    rad_brdf_eval(&lam_rgb, n, dir(0.9, 1.0), &f);
    check("  ... monochrome eval = Rec. 709 luminance/pi", f, (0.2126 * 0.8 + 0.7152 * 0.4 + 0.0722 * 0.1) / pi, 1e-6);
    RadBrdf gold;
    check_status("ggx(alpha=0.3, fresnel=conductor(metal=Au))",
                 rad_brdf_microfacet(RAD_DISTRIBUTION_GGX, 0.3f, RAD_SHADOWING_HEIGHT_CORRELATED, RAD_FRESNEL_METAL,
                                     RAD_METAL_AU, 0.0f, &gold),
                 RAD_STATUS_OK);
    rad_brdf_eval_rgb(&gold, dir(0.5236, 0.0), dir(0.5236, pi), rgb);
    printf("gold f(30 deg mirror) R G B = %.6g %.6g %.6g 1/sr\n", rgb[0], rgb[1], rgb[2]);
    check_le("  ... red above blue (gold): blue - red", rgb[2] - rgb[0], -0.3);
    /* An RGB conductor (eta, k per channel, as RGB renderers tabulate metals). */
    const float eta[3] = {0.2f, 0.92f, 1.1f}, k[3] = {3.9f, 2.45f, 2.14f};
    RadBrdf copperish;
    check_status("ggx rgb conductor", rad_brdf_microfacet_rgb(RAD_DISTRIBUTION_GGX, 0.3f, RAD_SHADOWING_HEIGHT_CORRELATED,
                                                               RAD_FRESNEL_CONDUCTOR, eta, k, &copperish),
                 RAD_STATUS_OK);
    rad_brdf_eval_rgb(&copperish, dir(0.5236, 0.0), dir(0.5236, pi), rgb);
    check_le("  ... red above blue: blue - red", rgb[2] - rgb[0], -0.05);
    check_status("ggx rgb dielectric rejected (rad_brdf_microfacet takes it)",
                 rad_brdf_microfacet_rgb(RAD_DISTRIBUTION_GGX, 0.3f, 0, RAD_FRESNEL_DIELECTRIC, eta, k, &bad_rgb),
                 RAD_STATUS_UNKNOWN_KIND);
    RadBrdfSample sc;
    check_status("gold sample_rgb", rad_brdf_sample_rgb(&gold, wo, 0.3f, 0.8f, &sc), RAD_STATUS_OK);
    rad_brdf_eval_rgb(&gold, sc.wi, wo, rgb);
    check("  ... weight (B) = f (B) cos / pdf", sc.weight[2], rgb[2] * sc.wi.z / sc.pdf, 1e-5);

    /* Batches equal single calls. */
    enum { N = 100 };
    RadVec3 wis[N], wos[N];
    float out[N];
    for (int k = 0; k < N; k++) {
        wis[k] = dir(1.5 * k / N, 0.37 * k);
        wos[k] = dir(1.5 * (N - k) / N, -0.11 * k);
    }
    check_status("ggx eval_batch", rad_brdf_eval_batch(&ggx, wis, wos, out, N), RAD_STATUS_OK);
    double worst = 0.0;
    for (int k = 0; k < N; k++) {
        rad_brdf_eval(&ggx, wis[k], wos[k], &f);
        double d = fabs(out[k] - f) / (fabs(f) > 1e-3 ? fabs(f) : 1e-3);
        if (d > worst) worst = d;
    }
    check_le("ggx eval_batch vs eval: worst relative difference", worst, 1e-6);

    /* Bad input is a status, never a crash. */
    RadBrdf bad;
    check_status("ggx(alpha=NaN) rejected",
                 rad_brdf_microfacet(RAD_DISTRIBUTION_GGX, NAN, 0, RAD_FRESNEL_NONE, 0, 0, &bad),
                 RAD_STATUS_NOT_FINITE);
    check_status("phong(kd + ks > 1) rejected", rad_brdf_phong(10.0f, 0.7f, 0.5f, &bad), RAD_STATUS_CONSTRAINT);
    check_status("unknown distribution rejected",
                 rad_brdf_microfacet(42, 0.3f, 0, RAD_FRESNEL_NONE, 0, 0, &bad), RAD_STATUS_UNKNOWN_KIND);
    RadBrdf zeroed = {0};
    check_status("zeroed handle rejected", rad_brdf_eval(&zeroed, n, n, &f), RAD_STATUS_BAD_HANDLE);
    check_status("null output rejected", rad_brdf_eval(&ggx, n, n, NULL), RAD_STATUS_NULL_POINTER);
    check_status("in-place batch rejected",
                 rad_brdf_eval_batch(&ggx, wis, wos, (float *)wis, N), RAD_STATUS_OVERLAP);

    if (failures) {
        printf("%d check(s) FAILED\n", failures);
        return 1;
    }
    printf("brdf.c: all checks passed\n");
    return 0;
}
