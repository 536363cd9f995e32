/* Ambient-light sensor firmware path through the C API: calibrate under a
 * reference lamp, correct for the spectrum of the light being measured,
 * convert raw counts to lux. Checked against values computed here by hand.
 *
 * Build and run (from the repository root, after `cd ffi && cargo build --release`):
 *   cc -std=c99 -Wall -Wextra -Werror -O2 ffi/examples/als.c -Iffi/include \
 *      ffi/target/release/libradiometry_ffi.a -lm -o target/als-example && ./target/als-example
 * Prints one line per check and exits non-zero if any fails.
 */
#include "radiometry.h"

#include <math.h>
#include <stdio.h>

static int failures = 0;

static void check(const char *what, double got, double want, double rel_tol) {
    int ok = fabs(got - want) <= rel_tol * fabs(want) + 1e-12;
    printf("%-60s %.7g (expected %.7g) %s\n", what, got, want, ok ? "ok" : "FAIL");
    if (!ok) failures++;
}

static void check_status(const char *what, RadStatus got, RadStatus want) {
    int ok = got == want;
    printf("%-60s status %d \"%s\" %s\n", what, (int)got, rad_status_message((int)got), ok ? "ok" : "FAIL");
    if (!ok) failures++;
}

/* CIE 1924 photopic V(lambda) at 5 nm, 530-630 nm (CIE 015:2018 table). */
static const double V_START = 530.0;
static const double V_TABLE[21] = {0.862,  0.91485, 0.954, 0.9803, 0.99495, 1.0,   0.995,
                                   0.9786, 0.952,   0.9154, 0.870, 0.8163,  0.757, 0.6949,
                                   0.631,  0.5668,  0.503, 0.4412, 0.381,  0.321,  0.265};

static double v_of(double l) {
    double t = (l - V_START) / 5.0;
    int i = (int)t;
    if (i < 0 || i >= 20) return 0.0;
    return V_TABLE[i] + (V_TABLE[i + 1] - V_TABLE[i]) * (t - i);
}

/* A box spectrum tabulated at 10 nm from `start`: 0,1,1,1,0 (linear ramps). */
static double box_of(double start, double l) {
    double up = (l - start) / 10.0, down = (start + 40.0 - l) / 10.0;
    double b = up < down ? up : down;
    return b < 0.0 ? 0.0 : (b > 1.0 ? 1.0 : b);
}

/* Trapezoid rule at 1 nm of box(start) x V over 530-630 nm. */
static double box_v_integral(double start) {
    double sum = 0.0;
    for (int l = 530; l < 630; l++)
        sum += 0.5 * (box_of(start, l) * v_of(l) + box_of(start, l + 1) * v_of(l + 1));
    return sum;
}

int main(void) {
    /* 1. Calibration: the sensor reads 12016 counts (16 dark) at gain 1 and
     * 100 ms under a 500 lx illuminant-A lamp. */
    RadAlsCalibration cal;
    check_status("calibrate under A at 500 lx",
                 rad_als_from_reference(16.0f, 12016.0f, 1.0f, 0.1f, 500.0f, 65535, &cal), RAD_STATUS_OK);
    double lpc = 500.0 * 1.0 * 0.1 / 12000.0;
    check("lux per count/(g t) = 500 * 0.1 / 12000", cal.lux_per_count_s, lpc, 1e-6);

    /* 2. Readings at other settings: E = (counts - dark) lpc / (g t). */
    float lux = 0.0f;
    check_status("reading 3016 counts at gain 4, 25 ms", rad_als_lux(&cal, 3016, 4.0f, 0.025f, &lux), RAD_STATUS_OK);
    check("  lux = 3000 lpc / (4 * 0.025)", lux, 3000.0 * lpc / 0.1, 1e-5);
    check_status("reading 10 counts (below dark)", rad_als_lux(&cal, 10, 1.0f, 0.1f, &lux), RAD_STATUS_OK);
    check("  lux = 0", lux, 0.0, 0.0);
    check_status("reading at full scale", rad_als_lux(&cal, 65535, 1.0f, 0.1f, &lux), RAD_STATUS_SATURATED);
    check_status("gain 0", rad_als_lux(&cal, 100, 0.0f, 0.1f, &lux), RAD_STATUS_BAD_SETTING);
    check_status("integration time NaN", rad_als_lux(&cal, 100, 1.0f, NAN, &lux), RAD_STATUS_BAD_SETTING);

    /* 3. Spectral mismatch correction (CIE S 023):
     * F = [int E_X V / int E_X s] / [int E_A V / int E_A s].
     * A photopically matched detector (s = V) needs none: F = 1. */
    RadSpectrum v = {RAD_SPECTRUM_PHOTOPIC_V, 0, 0, 0, NULL, 0};
    RadSpectrum d65 = {RAD_SPECTRUM_D65, 0, 0, 0, NULL, 0};
    RadSpectrum lamp_a = {RAD_SPECTRUM_A, 0, 0, 0, NULL, 0};
    float f = 0.0f;
    check_status("F for s = V, D65 vs A", rad_spectral_correction(&v, &d65, &lamp_a, &f), RAD_STATUS_OK);
    check("  F = 1", f, 1.0, 1e-5);

    /* A flat detector (380-780 nm) under two box sources of equal area, X on
     * 530-570 nm and A on 580-620 nm: F = int X V / int A V, with V from the
     * CIE table above. */
    static const float flat[41] = {1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1,
                                   1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1};
    static const float box[5] = {0, 1, 1, 1, 0};
    RadSpectrum s_flat = {RAD_SPECTRUM_TABULATED, 0, 380.0f, 10.0f, flat, 41};
    RadSpectrum x_green = {RAD_SPECTRUM_TABULATED, 0, 530.0f, 10.0f, box, 5};
    RadSpectrum a_orange = {RAD_SPECTRUM_TABULATED, 0, 580.0f, 10.0f, box, 5};
    check_status("F for a flat detector, green vs orange box",
                 rad_spectral_correction(&s_flat, &x_green, &a_orange, &f), RAD_STATUS_OK);
    check("  F = int(green V) / int(orange V)", f, box_v_integral(530.0) / box_v_integral(580.0), 2e-3);

    /* 4. End to end: an ideal photopic sensor with k = 50 counts/s per unit of
     * int E V reads D65; with lux per count/(g t) = 683/k (K_m = 683 lm/W) the
     * reading is the illuminance 683 int E V that rad_source_lux computes. */
    uint32_t counts = 0;
    check_status("simulate counts under D65",
                 rad_als_simulate_counts(&v, &d65, 50.0f, 1.0f, 0.1f, 0.0f, 1u << 24, &counts), RAD_STATUS_OK);
    RadAlsCalibration ideal;
    rad_als_new(0.0f, 683.0f / 50.0f, 1.0f, 1u << 24, &ideal);
    float e_src = 0.0f;
    rad_source_lux(&d65, &e_src);
    rad_als_lux(&ideal, counts, 1.0f, 0.1f, &lux);
    check("  lux from counts = lux of the source", lux, e_src, 0.5 / counts + 1e-5);

    /* 5. Correction applied to a reading. */
    check_status("set correction 1.08", rad_als_set_spectral_correction(&cal, 1.08f), RAD_STATUS_OK);
    rad_als_lux(&cal, 3016, 4.0f, 0.025f, &lux);
    check("  lux = 1.08 * 3000 lpc / 0.1", lux, 1.08 * 3000.0 * lpc / 0.1, 1e-5);
    check_status("correction -1 rejected", rad_als_set_spectral_correction(&cal, -1.0f), RAD_STATUS_OUT_OF_RANGE);
    check_status("null calibration rejected", rad_als_lux(NULL, 100, 1.0f, 0.1f, &lux), RAD_STATUS_NULL_POINTER);

    /* 6. Irradiance closed forms: sky pi L, directional E cos(theta). */
    float e = 0.0f;
    rad_irradiance_sky(2.0f, &e);
    check("sky(radiance=2): E = 2 pi", e, 2.0 * 3.14159265358979, 1e-6);
    RadVec3 sun = {(float)sin(0.5), 0.0f, (float)cos(0.5)};
    rad_irradiance_directional(sun, 1000.0f, &e);
    check("directional(theta=0.5 rad, E=1000): E = 1000 cos 0.5", e, 1000.0 * cos(0.5), 1e-6);
    check_status("cap with half-angle 2 rad rejected", rad_irradiance_cap(sun, 2.0f, 1.0f, &e),
                 RAD_STATUS_OUT_OF_RANGE);

    if (failures) {
        printf("%d check(s) FAILED\n", failures);
        return 1;
    }
    printf("als.c: all checks passed\n");
    return 0;
}
