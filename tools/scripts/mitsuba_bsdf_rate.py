"""Times Mitsuba 3 BSDFs on one CPU thread (by default ``roughconductor``,
Beckmann and GGX, alpha 0.3; with ``--bsdf`` also ``roughplastic`` and
``principled``), ``eval`` and ``sample`` on n = 2^20 direction pairs, for a
side-by-side reading with ``radiometry bench``'s rows at the same n:

    python3 -m venv target/mitsuba-venv
    target/mitsuba-venv/bin/pip install mitsuba numpy
    target/mitsuba-venv/bin/python tools/scripts/mitsuba_bsdf_rate.py            # n = 2^20
    RUSTFLAGS="-C target-cpu=native" cargo run --release -p radiometry-cli -- bench --only beckmann-hc-a0.3
    RUSTFLAGS="-C target-cpu=native" cargo run --release -p radiometry-cli -- bench --only ggx-hc-a0.3

    # the plastic and the Disney-style material, beside plastic-ggx0.1-eon and the openpbr rows:
    target/mitsuba-venv/bin/python tools/scripts/mitsuba_bsdf_rate.py --bsdf roughplastic --bsdf principled
    RUSTFLAGS="-C target-cpu=native" cargo run --release -p radiometry-cli -- bench --only plastic-ggx0.1-eon
    RUSTFLAGS="-C target-cpu=native" cargo run --release -p radiometry-cli -- bench --only openpbr

``--bsdf`` may be repeated or given a comma-separated list (``all`` names
every one); ``--json FILE`` also writes the header and rows as JSON (``-``:
to stdout, the table then goes to stderr); ``--rounds`` (alias
``--repeats``) sets how many timed calls each figure is the best of.

Dr.Jit's LLVM backend loads the system's libLLVM: LLVM 19 works (Debian:
``apt-get install libllvm19``), LLVM 15 fails with "Cannot select: fmaximum";
``DRJIT_LIBLLVM_PATH`` picks a library. Its kernels use the
CPU's own vector width (16 lanes with AVX-512), so compare with a
``-C target-cpu=native`` build of the bench.

What is timed, per (BSDF, path): ``bsdf.eval(ctx, si, wo)`` (the value
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
other load takes the core), above 1 only if more threads computed. Each
BSDF's parameters are printed as Mitsuba reports them (``mi.traverse``), and
an untimed check: the mean sample weight at normal incidence (a Monte Carlo
estimate of the directional albedo, red channel).

``roughconductor-beckmann``, ``roughconductor-ggx`` (beside the plugin rows
``beckmann-hc-a0.3``, ``ggx-hc-a0.3``; F = 1): ``material='none'`` is
Mitsuba's perfect mirror (eta = 0, k = 1), whose conductor Fresnel term is
exactly 1 at every angle (checked below) but is still computed; the shadowing
is Smith's separable G1(wi) G1(wo), with Walter et al.'s rational
approximation of Beckmann's G1 (the plugin rows are height-correlated with the
exact Lambda); the output is three channels (the plugin rows write one f32).

``roughplastic`` (beside ``plastic-ggx0.1-eon``, a coated GGX alpha 0.1
dielectric eta 1.5 over an EON diffuse rho 0.8 sigma 0.5; a different model):
GGX alpha 0.1 (visible-normal sampling), int_ior 1.5, ext_ior 1.0,
diffuse_reflectance 0.8 (uniform), nonlinear false. Per Mitsuba's
src/bsdfs/roughplastic.cpp (3.9.1), ``eval`` is a specular microfacet term
F(wi.h, eta) D(h) G1(wi) G1(wo) / (4 cos theta_i) (unpolarised dielectric
Fresnel, separable Smith G) plus a diffuse term
rho / (1 - Fdr) * T(cos theta_i) T(cos theta_o) cos theta_o / (pi eta^2):
T is the rough interface's single-scattering transmittance, tabulated at 64
cosines when the plugin is built (32 x 32 Gauss-Legendre nodes over sampled
visible normals) and read by linear interpolation (two gathers per
direction); 1 / (1 - Fdr) accounts for internal scattering (light the
interface reflects back onto the diffuse base, summed as a geometric series),
Fdr being the cosine-weighted mean internal rough reflectance (eta 1/eta,
computed once; with nonlinear false the factor does not depend on rho).
``sample`` picks the specular lobe with probability proportional to
(1 - T(cos theta_i)) w and the diffuse one to T(cos theta_i) (1 - w),
w = 1 / (1 + mean rho), samples visible GGX normals or a cosine-weighted
direction, then evaluates the mixture pdf and ``eval`` at the sampled
direction.

``principled`` (beside the ``openpbr`` rows; a different model and
parameters: OpenPBR's defaults are base_color 0.8, specular_roughness 0.3):
Mitsuba's ``principled`` plugin (Burley's Disney BRDF) at its defaults,
base_color 0.5, roughness 0.5, specular 0.5 (eta = 1.5), every other
parameter 0 (metallic, spec_trans, anisotropic, sheen, sheen_tint, clearcoat,
clearcoat_gloss, flatness, spec_tint), sampling rates 1. Absent lobes are
not traced, so ``eval`` is Burley's diffuse with retro-reflection,
base_color / pi (f_diff + f_retro) cos theta_o (Schlick weights), not scaled
by 1 - F, plus GGX alpha = roughness^2 = 0.25 with the exact dielectric
Fresnel and separable Smith G;
``sample`` picks diffuse or specular with probability 1/2 each (visible-normal
GGX or cosine-weighted), then evaluates pdf and ``eval`` at the sample.
"""

import argparse
import json
import os
import sys
import time

import drjit as dr
import mitsuba as mi
import numpy as np

DEFAULT_BSDFS = ("roughconductor-beckmann", "roughconductor-ggx")


def bsdf_dicts(a):
    """The ``mi.load_dict`` dictionary of every BSDF this script knows, by name."""
    return {
        "roughconductor-beckmann": {
            "type": "roughconductor", "distribution": "beckmann", "alpha": a.alpha, "material": "none",
        },
        "roughconductor-ggx": {
            "type": "roughconductor", "distribution": "ggx", "alpha": a.alpha, "material": "none",
        },
        "roughplastic": {
            "type": "roughplastic", "distribution": "ggx", "alpha": 0.1, "int_ior": 1.5, "ext_ior": 1.0,
            "diffuse_reflectance": 0.8, "nonlinear": False,
        },
        "principled": {"type": "principled"},
    }


def selected_bsdfs(values, known):
    """The names asked for by the ``--bsdf`` values (repeatable, comma lists, ``all``), in order."""
    if not values:
        return list(DEFAULT_BSDFS)
    names = []
    for v in values:
        for name in (s.strip() for s in v.split(",")):
            if not name:
                continue
            for n in known if name == "all" else [name]:
                if n not in known:
                    raise SystemExit(f"unknown --bsdf {n!r}; known: {', '.join(known)}, all")
                if n not in names:
                    names.append(n)
    return names


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


def calls(bsdf, ctx):
    """``eval`` and ``sample`` of `bsdf` as functions of the arrays alone (`bsdf` and `ctx` are closure
    variables, which ``dr.freeze`` traverses)."""

    def eval_(si_wi, w):
        si = dr.zeros(mi.SurfaceInteraction3f)
        si.wi = si_wi
        return bsdf.eval(ctx, si, w)

    def sample(si_wi, s0, s12):
        si = dr.zeros(mi.SurfaceInteraction3f)
        si.wi = si_wi
        bs, weight = bsdf.sample(ctx, si, s0, s12)
        return bs.wo, bs.pdf, weight

    return eval_, sample


def traversed(bsdf):
    """The BSDF's parameters as Mitsuba reports them (``mi.traverse``), scalars where they are one value."""
    params = mi.traverse(bsdf)
    out = {}
    for key in params.keys():
        v = params[key]
        try:
            arr = np.array(v, dtype=np.float64).ravel()
            out[key] = float(arr[0]) if arr.size == 1 else [float(x) for x in arr]
        except (TypeError, ValueError):
            out[key] = str(v)
    return out


def cpu_model():
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return "unknown"


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--n", type=int, default=1 << 20, help="direction pairs per call (default 2^20)")
    p.add_argument(
        "--rounds", "--repeats", dest="rounds", type=int, default=20,
        help="timed calls per measurement (best kept; default 20)",
    )
    p.add_argument("--warmup", type=int, default=3, help="untimed calls before each measurement")
    p.add_argument("--alpha", type=float, default=0.3, help="roughconductor alpha (default 0.3)")
    p.add_argument(
        "--bsdf", action="append", metavar="NAME[,NAME...]",
        help="BSDFs to time, repeatable or comma-separated: roughconductor-beckmann, roughconductor-ggx, "
        "roughplastic, principled, all (default: the two roughconductors)",
    )
    p.add_argument("--json", metavar="FILE", help="also write the header and rows as JSON ('-': stdout)")
    p.add_argument("--threads", type=int, default=1, help="Dr.Jit CPU threads (1: the calling thread only)")
    p.add_argument("--variant", default="llvm_ad_rgb")
    p.add_argument("--seed", type=int, default=28)
    a = p.parse_args()

    dicts = bsdf_dicts(a)
    names = selected_bsdfs(a.bsdf, list(dicts))
    out = sys.stderr if a.json == "-" else sys.stdout

    def say(line=""):
        print(line, file=out, flush=True)

    dr.set_thread_count(a.threads)
    mi.set_variant(a.variant)
    rng = np.random.default_rng(a.seed)
    n = a.n
    wi, wo = directions(rng, n), directions(rng, n)
    u0 = mi.Float(rng.random(n).astype(np.float32))
    u12 = mi.Point2f(rng.random(n).astype(np.float32), rng.random(n).astype(np.float32))
    dr.eval(wi, wo, u0, u12)
    ctx = mi.BSDFContext()
    # The untimed albedo check: n samples at normal incidence.
    normal = mi.Vector3f(0.0, 0.0, 1.0)

    load = os.getloadavg()
    header = {
        "mitsuba": mi.__version__,
        "drjit": dr.__version__,
        "llvm": ".".join(map(str, dr.detail.llvm_version())),
        "variant": a.variant,
        "threads": dr.thread_count(),
        "cpu": cpu_model(),
        "n": n,
        "rounds": a.rounds,
        "warmup": a.warmup,
        "seed": a.seed,
        "load_average_start": [round(x, 2) for x in load],
    }
    say(
        f"mitsuba {header['mitsuba']}, drjit {header['drjit']}, LLVM {header['llvm']}, "
        f"variant {a.variant}, threads {header['threads']}, n {n}, best of {a.rounds} "
        f"after {a.warmup} warm-up calls; {header['cpu']}; load average {' '.join(f'{x:.2f}' for x in load)}"
    )
    if any(name.startswith("roughconductor") for name in names):
        cos = mi.Float(np.linspace(0.0, 1.0, 100001).astype(np.float32))
        fresnel = mi.fresnel_conductor(cos, mi.Complex2f(0.0, 1.0))
        say(
            f"material 'none' (eta 0, k 1): conductor Fresnel over cos in [0, 1]: "
            f"min {dr.min(fresnel)[0]:.9g}, max {dr.max(fresnel)[0]:.9g}"
        )

    bsdfs, info = {}, {}
    for name in names:
        bsdf = mi.load_dict(dicts[name])
        si = dr.zeros(mi.SurfaceInteraction3f)
        si.wi = normal
        _, weight = bsdf.sample(ctx, si, u0, u12)
        albedo = float(dr.mean(weight[0])[0])
        bsdfs[name] = bsdf
        info[name] = {"dict": dicts[name], "params": traversed(bsdf), "albedo_normal_mc": albedo}
        params = ", ".join(
            f"{k} {v:g}" if isinstance(v, float) else f"{k} {v}" for k, v in info[name]["params"].items()
        )
        given = ", ".join(f"{k} {v}" for k, v in dicts[name].items() if k != "type")
        given = f", {given}" if given else ", defaults"
        say(f"{name}: type {dicts[name]['type']}{given}; traverse: {params}")
        say(f"{name}: mean sample weight at normal incidence (albedo, red, n {n}): {albedo:.4f}")

    say(f"{'bsdf':<24} {'path':<7} {'mode':<7} {'n':>8} {'m_per_s':>9} {'ns_per_elem':>11} {'cpu/wall':>8}")
    rows = []
    for name in names:
        eval_, sample = calls(bsdfs[name], ctx)
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
            say(f"{name:<24} {path:<7} {mode:<7} {n:>8} {m_per_s:>9.1f} {1e3 / m_per_s:>11.2f} {ratio:>8.2f}")
            rows.append({
                "bsdf": name, "path": path, "mode": mode, "n": n, "m_per_s": m_per_s,
                "ns_per_elem": 1e3 / m_per_s, "cpu_per_wall": ratio,
            })

    load = os.getloadavg()
    header["load_average_end"] = [round(x, 2) for x in load]
    say(f"load average at the end {' '.join(f'{x:.2f}' for x in load)}")
    if a.json:
        doc = json.dumps({**header, "bsdfs": info, "rows": rows}, indent=2)
        if a.json == "-":
            print(doc)
        else:
            with open(a.json, "w") as f:
                f.write(doc + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
