"""Times Mitsuba 3's ``roughconductor`` BSDF (Beckmann and GGX, alpha 0.3) on
one CPU thread, for a side-by-side reading with ``radiometry bench``'s rows
``beckmann-hc-a0.3`` and ``ggx-hc-a0.3`` (``eval_batch_soa``, ``sample_batch``)
at the same n:

    python3 -m venv target/mitsuba-venv
    target/mitsuba-venv/bin/pip install mitsuba numpy
    target/mitsuba-venv/bin/python tools/scripts/mitsuba_bsdf_rate.py            # n = 2^20
    RUSTFLAGS="-C target-cpu=native" cargo run --release -p radiometry-cli -- bench --only beckmann-hc-a0.3
    RUSTFLAGS="-C target-cpu=native" cargo run --release -p radiometry-cli -- bench --only ggx-hc-a0.3

Dr.Jit's LLVM backend loads the system's libLLVM: LLVM 19 works (Debian:
``apt-get install libllvm19``), LLVM 15 fails with "Cannot select: fmaximum";
``DRJIT_LIBLLVM_PATH`` picks a library. Its kernels use the
CPU's own vector width (16 lanes with AVX-512), so compare with a
``-C target-cpu=native`` build of the bench.

What is timed, per (distribution, path): ``bsdf.eval(ctx, si, wo)`` (the value
is f_r cos(theta) in RGB) or ``bsdf.sample(ctx, si, u0, (u1, u2))`` (direction,
pdf and RGB weight evaluated) on n direction pairs drawn like the bench's
``random`` set (theta uniform in [0, 1.55) rad, phi uniform, fixed seed;
``si.wi`` is the bench's ``wo``), from the call until the results are in
memory (``dr.eval`` + ``dr.sync_thread``). Two modes: ``traced`` re-traces the
Python call each time (the compiled kernel comes from Dr.Jit's cache), as a
Python caller runs it; ``frozen`` replays the recorded kernel launch
(``dr.freeze``): the kernel alone. Inputs are evaluated before timing; each
measurement is preceded by warm-up calls (JIT compilation excluded) and is the
best (fastest) of ``--rounds`` calls. ``cpu/wall`` is the process CPU time
over the wall time of the timed calls: at most 1 on one thread (below 1 while
other load takes the core), above 1 only if more threads computed.

Differences from the plugin rows (F = 1): ``material='none'`` is Mitsuba's
perfect mirror (eta = 0, k = 1), whose conductor Fresnel term is exactly 1 at
every angle (checked below) but is still computed; the shadowing is Smith's
separable G1(wi) G1(wo), with Walter et al.'s rational approximation of
Beckmann's G1 (the plugin row is height-correlated with the exact Lambda);
the output is three channels (the plugin rows write one f32).
"""

import argparse
import os
import sys
import time

import drjit as dr
import mitsuba as mi
import numpy as np


def directions(rng, n):
    """n unit vectors, theta uniform in [0, 1.55), phi uniform in [0, 2 pi)."""
    theta = rng.random(n) * 1.55
    phi = rng.random(n) * 2.0 * np.pi
    s = np.sin(theta)
    xyz = np.stack([s * np.cos(phi), s * np.sin(phi), np.cos(theta)]).astype(np.float32)
    return mi.Vector3f(xyz[0], xyz[1], xyz[2])


def best_of(call, rounds, warmup):
    """Best wall time of `rounds` calls after `warmup` calls, and the CPU/wall ratio of the timed calls."""
    for _ in range(warmup):
        dr.eval(call())
        dr.sync_thread()
    best, wall, cpu = float("inf"), 0.0, 0.0
    for _ in range(rounds):
        c0, t0 = time.process_time(), time.perf_counter()
        out = call()
        dr.eval(out)
        dr.sync_thread()
        t, c = time.perf_counter() - t0, time.process_time() - c0
        del out
        best, wall, cpu = min(best, t), wall + t, cpu + c
    return best, cpu / wall


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--n", type=int, default=1 << 20, help="direction pairs per call (default 2^20)")
    p.add_argument("--rounds", type=int, default=20, help="timed calls per measurement (best kept)")
    p.add_argument("--warmup", type=int, default=3, help="untimed calls before each measurement")
    p.add_argument("--alpha", type=float, default=0.3)
    p.add_argument("--threads", type=int, default=1, help="Dr.Jit CPU threads (1: the calling thread only)")
    p.add_argument("--variant", default="llvm_ad_rgb")
    p.add_argument("--seed", type=int, default=28)
    a = p.parse_args()

    dr.set_thread_count(a.threads)
    mi.set_variant(a.variant)
    rng = np.random.default_rng(a.seed)
    n = a.n
    wi, wo = directions(rng, n), directions(rng, n)
    u0 = mi.Float(rng.random(n).astype(np.float32))
    u12 = mi.Point2f(rng.random(n).astype(np.float32), rng.random(n).astype(np.float32))
    dr.eval(wi, wo, u0, u12)
    ctx = mi.BSDFContext()

    cos = mi.Float(np.linspace(0.0, 1.0, 100001).astype(np.float32))
    fresnel = mi.fresnel_conductor(cos, mi.Complex2f(0.0, 1.0))
    print(
        f"mitsuba {mi.__version__}, drjit {dr.__version__}, LLVM {'.'.join(map(str, dr.detail.llvm_version()))}, "
        f"variant {a.variant}, threads {dr.thread_count()}, n {n}, alpha {a.alpha}, best of {a.rounds} "
        f"after {a.warmup} warm-up calls; load average {' '.join(f'{x:.2f}' for x in os.getloadavg())}"
    )
    print(
        f"material 'none' (eta 0, k 1): conductor Fresnel over cos in [0, 1]: "
        f"min {dr.min(fresnel)[0]:.9g}, max {dr.max(fresnel)[0]:.9g}"
    )
    print(f"{'bsdf':<24} {'path':<7} {'mode':<7} {'n':>8} {'m_per_s':>9} {'ns_per_elem':>11} {'cpu/wall':>8}")

    for distribution in ("beckmann", "ggx"):
        bsdf = mi.load_dict(
            {"type": "roughconductor", "distribution": distribution, "alpha": a.alpha, "material": "none"}
        )

        def eval_(si_wi, w):
            si = dr.zeros(mi.SurfaceInteraction3f)
            si.wi = si_wi
            return bsdf.eval(ctx, si, w)

        def sample(si_wi, s0, s12):
            si = dr.zeros(mi.SurfaceInteraction3f)
            si.wi = si_wi
            bs, weight = bsdf.sample(ctx, si, s0, s12)
            return bs.wo, bs.pdf, weight

        frozen_eval, frozen_sample = dr.freeze(eval_), dr.freeze(sample)
        runs = [
            ("eval", "traced", lambda: eval_(wo, wi)),
            ("eval", "frozen", lambda: frozen_eval(wo, wi)),
            ("sample", "traced", lambda: sample(wo, u0, u12)),
            ("sample", "frozen", lambda: frozen_sample(wo, u0, u12)),
        ]
        for path, mode, call in runs:
            t, ratio = best_of(call, a.rounds, a.warmup)
            m_per_s = n / t * 1e-6
            name = f"roughconductor-{distribution}"
            print(f"{name:<24} {path:<7} {mode:<7} {n:>8} {m_per_s:>9.1f} {1e3 / m_per_s:>11.2f} {ratio:>8.2f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
