"""Builds tools/scripts/adobe_openpbr_measure.cpp against a checkout of Adobe's OpenPBR BSDF
(https://github.com/adobe/openpbr-bsdf) in its two layering builds, runs every case of the
conformance set and the timing, and writes brdfs/tests/data/openpbr_adobe.json:

    git clone https://github.com/adobe/openpbr-bsdf /path/to/openpbr-bsdf   # header-only
    apt-get install libglm-dev g++                                            # GLM 0.9.9 headers
    python3 tools/scripts/adobe_openpbr_measure.py /path/to/openpbr-bsdf \
        [--build-dir /tmp/adobe_openpbr_build] [--out brdfs/tests/data/openpbr_adobe.json]

Every run is one thread under `nice -n 10`, one process per case and build (10-40 s each; the
whole set about 25 min on a 2-core AMD EPYC VM). Per-case results are cached as
BUILD_DIR/<build>/<case>.json, so an interrupted run resumes; delete the build directory to start
over. See the header of adobe_openpbr_measure.cpp for what each number is.
"""

import argparse
import json
import os
import shlex
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
SOURCE = os.path.join(HERE, "adobe_openpbr_measure.cpp")

BUILDS = {
    "energy": [],
    "reciprocal": ["-DOPENPBR_RECIPROCAL_COAT_AND_FUZZ=1"],
}

THETA_O = [0, 15, 30, 45, 60, 75, 85]
VALUE_TRIPLES = [[30, 45, 180], [45, 45, 180], [10, 60, 90], [60, 30, 0],
                 [20, 20, 180], [75, 20, 120], [50, 70, 180], [5, 5, 45]]
VARIANCE_THETA_O = [0, 45, 75]
PER_BUILD_KEYS = ["albedo", "albedo_se", "values", "variance", "mean_weight",
                  "albedo_quadrature", "albedo_quadrature_err", "sample_failures"]


def build_cmd(adobe, build, exe):
    return ["g++", "-std=c++17", "-O2", *BUILDS[build], "-I", adobe,
            os.path.relpath(SOURCE, REPO), "-o", exe]


def run(cmd, **kw):
    print("+", " ".join(shlex.quote(c) for c in cmd), file=sys.stderr, flush=True)
    return subprocess.run(cmd, check=True, cwd=REPO, **kw)


def cpu_model():
    name = "unknown"
    with open("/proc/cpuinfo") as f:
        for line in f:
            if line.startswith("model name"):
                name = line.split(":", 1)[1].strip()
                break
    lscpu = subprocess.run(["lscpu"], capture_output=True, text=True).stdout
    fields = dict(l.split(":", 1) for l in lscpu.splitlines() if ":" in l)
    fam, mod, hyp = (fields.get(k, "?").strip() for k in ("CPU family", "Model", "Hypervisor vendor"))
    return f"{name} (/proc/cpuinfo); lscpu: family {fam}, model {mod}, {os.cpu_count()} vCPU, hypervisor {hyp}"


def fmt(v, indent=0):
    """JSON with one key per line in every object, arrays of numbers compact."""
    pad = " " * indent
    if isinstance(v, dict):
        if not v or indent >= 4 and all(not isinstance(x, (dict, list)) for x in v.values()):
            return json.dumps(v, separators=(", ", ": "), ensure_ascii=False)
        items = [f'{pad}  {json.dumps(k)}: {fmt(x, indent + 2)}' for k, x in v.items()]
        return "{\n" + ",\n".join(items) + "\n" + pad + "}"
    if isinstance(v, list) and v and isinstance(v[0], dict):
        items = [pad + "  " + fmt(x, indent + 2) for x in v]
        return "[\n" + ",\n".join(items) + "\n" + pad + "]"
    return json.dumps(v, separators=(", ", ": "), ensure_ascii=False)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("adobe", help="checkout of adobe/openpbr-bsdf")
    ap.add_argument("--build-dir", default="/tmp/adobe_openpbr_build")
    ap.add_argument("--out", default=os.path.join(REPO, "brdfs", "tests", "data", "openpbr_adobe.json"))
    ap.add_argument("--only", nargs="*", help="case names (default: all)")
    args = ap.parse_args()
    adobe = os.path.abspath(args.adobe)
    commit = subprocess.run(["git", "-C", adobe, "rev-parse", "HEAD"], check=True,
                            capture_output=True, text=True).stdout.strip()

    exes = {}
    for build in BUILDS:
        os.makedirs(os.path.join(args.build_dir, build), exist_ok=True)
        exes[build] = os.path.join(args.build_dir, f"adobe_{build}")
        run(["nice", "-n", "10", *build_cmd(adobe, build, exes[build])])

    names = subprocess.run([exes["energy"], "list"], check=True, capture_output=True,
                           text=True).stdout.split()
    if args.only:
        names = [n for n in names if n in args.only]

    results = {b: {} for b in BUILDS}
    for name in names:
        for build in BUILDS:
            cache = os.path.join(args.build_dir, build, name + ".json")
            if not os.path.exists(cache):
                t0 = time.time()
                out = run(["nice", "-n", "10", exes[build], "case", name],
                          capture_output=True, text=True).stdout
                json.loads(out)
                with open(cache, "w") as f:
                    f.write(out)
                print(f"  {build} {name}: {time.time() - t0:.1f} s", file=sys.stderr, flush=True)
            with open(cache) as f:
                results[build][name] = json.load(f)

    timing = {}
    for build in BUILDS:
        cache = os.path.join(args.build_dir, build, "_timing.json")
        if not os.path.exists(cache):
            load = os.getloadavg()
            out = run(["nice", "-n", "10", exes[build], "timing"], capture_output=True, text=True).stdout
            t = json.loads(out)
            t["loadavg_before"] = [round(x, 2) for x in load]
            with open(cache, "w") as f:
                json.dump(t, f)
        with open(cache) as f:
            timing[build] = json.load(f)

    cases = []
    for name in names:
        e = results["energy"][name]
        case = {"name": name, "params": e["params"]}
        for build in BUILDS:
            r = results[build][name]
            assert r["params"] == e["params"]
            assert not any(r["below_horizon_nonzero"]) and not any(r["non_finite"]), (build, name)
            case[build] = {k: r[k] for k in PER_BUILD_KEYS}
        cases.append(case)

    tim = {
        "method": "ns per call, one thread, nice -n 10; 2^20 calls per repetition, 15 repetitions, "
                  "thread CPU time (CLOCK_THREAD_CPUTIME_ID), median and min, wall-clock median alongside; view/light directions cosine-distributed and random numbers "
                  "precomputed (4096 of each, cycled), eval/sample/pdf over 64 prepared BSDFs; "
                  "hit = prepare + eval + sample + pdf at the sampled direction; results summed into a "
                  "volatile sink, prepare's result also escaped with an empty asm",
        "calls_per_repetition": timing["energy"]["calls_per_repetition"],
        "repetitions": timing["energy"]["repetitions"],
    }
    for build in BUILDS:
        tim[build] = {"loadavg_before": timing[build]["loadavg_before"], **timing[build]["cases"]}

    cmd_build = ["g++ -std=c++17 -O2 " + " ".join(BUILDS[b] + [""]) + '-I "$ADOBE" '
                 f"tools/scripts/adobe_openpbr_measure.cpp -o /tmp/adobe_openpbr_build/adobe_{b}"
                 for b in BUILDS]
    doc = {
        "source": f"adobe/openpbr-bsdf {commit}",
        "command": (f"ADOBE=/path/to/openpbr-bsdf  # a checkout of {commit}\n"
                    'python3 tools/scripts/adobe_openpbr_measure.py "$ADOBE"\n'
                    "# which runs, from the repository root (g++ 12.2, GLM 0.9.9.8 from Debian libglm-dev):\n"
                    + "\n".join(f"nice -n 10 {c}" for c in cmd_build)
                    + "\nfor b in energy reciprocal; do for c in $(/tmp/adobe_openpbr_build/adobe_energy list); do "
                    "nice -n 10 /tmp/adobe_openpbr_build/adobe_$b case $c; done; "
                    "nice -n 10 /tmp/adobe_openpbr_build/adobe_$b timing; done"),
        "harness": "tools/scripts/adobe_openpbr_measure.cpp (+ adobe_openpbr_measure.py)",
        "cpu": cpu_model() + f" ({os.cpu_count()} vCPU, family/model from lscpu)",
        "frame": "normal +Z; wo = (sin θo, 0, cos θo); wi = (sin θi cos Δφ, sin θi sin Δφ, cos θi); "
                 "degrees throughout",
        "theta_o": THETA_O,
        "value_triples": VALUE_TRIPLES,
        "value_triples_are": "[θi, θo, Δφ] with φo = 0, φi = Δφ; values are f_r = openpbr_eval / cos θi",
        "variance_theta_o": VARIANCE_THETA_O,
        "estimators": {
            "albedo": "mean of openpbr_sample weights (diffuse + specular), 2^22 samples: (u1,u2) on a 2048x2048 "
                      "jittered grid, u3 iid; pdf = 0 counts 0",
            "albedo_se": "sd of 64 interleaved batch means / 8 (batch = 8(i mod 8) + (j mod 8) of cell (i,j)); "
                         "conservative",
            "albedo_quadrature": "integral of openpbr_eval over the hemisphere, tensor Gauss-Legendre in (mu_i, phi_i) "
                                 "on panels graded towards (mu_o, pi), phi=0 and mu=1, 32 nodes per panel; "
                                 "albedo_quadrature_err = |Q32 - Q16|; null where a lobe is near-delta",
            "variance": "per-sample variance of (w_r+w_g+w_b)/3 over 2^20 iid uniform (u1,u2,u3), fixed seed, "
                        "failed sample = 0; mean_weight is its mean",
            "sample_failures": "albedo samples (of 2^22) with pdf = 0",
        },
        "cases": cases,
        "timing": tim,
    }
    os.makedirs(os.path.dirname(os.path.abspath(args.out)), exist_ok=True)
    with open(args.out, "w") as f:
        f.write(fmt(doc) + "\n")
    print("wrote", args.out, file=sys.stderr)


if __name__ == "__main__":
    main()
