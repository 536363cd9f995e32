"""Throughput of `Brdf.eval` on 10^6 directions against the Rust batch path
(`eval_batch` on the same data, timed inside the module with no Python in the
loop), in one process: the ratio is what calling from Python costs.

    python python/bench.py [N]

Prints, per BRDF: M evals/s of Brdf.eval with float32 input, with float64
input, of the Rust batch path, and the ratios (target for float32: <= 1.5).
"""

import sys
import time

import numpy as np

import radiometry


def best(f, repeats=7):
    t = float("inf")
    for _ in range(repeats):
        t0 = time.perf_counter()
        f()
        t = min(t, time.perf_counter() - t0)
    return t


def main():
    n = int(sys.argv[1]) if len(sys.argv) > 1 else 1_000_000
    rng = np.random.default_rng(1)

    def dirs():
        z = rng.uniform(0.0, 1.0, n)
        phi = rng.uniform(0.0, 2 * np.pi, n)
        r = np.sqrt(1 - z * z)
        return np.stack([r * np.cos(phi), r * np.sin(phi), z], axis=1).astype(np.float32)

    wi, wo = dirs(), dirs()
    wi64, wo64 = wi.astype(np.float64), wo.astype(np.float64)
    print(f"N = {n}, numpy {np.__version__}, radiometry {radiometry.__version__}")
    print(f"{'BRDF':<40} {'py f32 M/s':>11} {'py f64 M/s':>11} {'rust M/s':>9} {'f32 ratio':>9} {'f64 ratio':>9}")
    for spec in ["lambertian(albedo=0.5)", "phong(exponent=50, ks=0.6, kd=0.3)", "ggx(alpha=0.3)",
                 "beckmann(alpha=0.3, fresnel=schlick(f0=0.04))"]:
        b = radiometry.Brdf(spec)
        t32 = best(lambda: b.eval(wi, wo))
        t64 = best(lambda: b.eval(wi64, wo64))
        tr = b.rust_eval_batch_seconds(wi, wo, 7)
        print(f"{spec:<40} {n / t32 / 1e6:11.1f} {n / t64 / 1e6:11.1f} {n / tr / 1e6:9.1f} "
              f"{t32 / tr:9.2f} {t64 / tr:9.2f}")


if __name__ == "__main__":
    main()
