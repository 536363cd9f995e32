"""Tests of the Python module `radiometry`.

Reference values are closed forms written out here (1 - ln 2, rho/pi,
1/(4 pi alpha^2), pi L), the scalar Rust `eval` (bit for bit), and the
`radiometry` command-line binary when RADIOMETRY_CLI names it (CI sets it; a
set but missing path fails the tests that use it).
"""

import math
import os
import subprocess

import numpy as np
import pytest

import radiometry

SPECS = [
    "lambertian(albedo=0.7)",
    "phong(exponent=50, ks=0.6, kd=0.3)",
    "blinn-phong(exponent=200, ks=0.8, kd=0.1)",
    "ggx(alpha=0.3)",
    "ggx(alpha=0.05, g=separable, fresnel=conductor(eta=0.2, k=3.9))",
    "beckmann(alpha=0.5, fresnel=schlick(f0=0.04))",
    "beckmann(alpha=1, g=separable, fresnel=dielectric(eta=1.5))",
    "lambertian(albedo=0.3) + ggx(alpha=0.2, fresnel=schlick(f0=0.04))",
    "mix(0.4, ggx(alpha=0.1, fresnel=conductor(eta=0.2, k=3.9)), lambertian(albedo=0.9))",
    "coated(ggx(alpha=0.1, fresnel=dielectric(eta=1.5)), lambertian(albedo=0.8), coat_color=0.6)",
]


def cli():
    path = os.environ.get("RADIOMETRY_CLI")
    if not path:
        pytest.skip("RADIOMETRY_CLI not set (CI sets it to target/release/radiometry)")
    assert os.path.exists(path), f"RADIOMETRY_CLI={path} does not exist"
    return path


def directions(n, seed, below=0.0):
    """Unit float32 directions, a fraction `below` of them under the horizon,
    some grazing."""
    rng = np.random.default_rng(seed)
    z = rng.uniform(-1.0, 1.0, n) if below > 0 else rng.uniform(0.0, 1.0, n)
    z[: n // 20] = rng.uniform(0.0, 1e-3, n // 20)  # grazing
    phi = rng.uniform(0.0, 2.0 * math.pi, n)
    r = np.sqrt(np.maximum(0.0, 1.0 - z * z))
    d = np.stack([r * np.cos(phi), r * np.sin(phi), z], axis=1)
    return d.astype(np.float32)


def bits(a):
    return np.asarray(a, dtype=np.float32).view(np.uint32)


@pytest.mark.parametrize("spec", SPECS)
def test_eval_is_bit_equal_to_scalar_eval_on_float32(spec):
    b = radiometry.Brdf(spec)
    n = 1003  # not a multiple of any vector width
    wi, wo = directions(n, 1, below=0.3), directions(n, 2)
    got = b.eval(wi, wo)
    assert got.dtype == np.float32 and got.shape == (n,)
    want = np.array([b.eval_one(wi[k], wo[k]) for k in range(n)], dtype=np.float32)
    assert np.array_equal(bits(got), bits(want))
    assert np.all(np.isfinite(got)) and np.all(got >= 0.0)
    assert np.all(got[wi[:, 2] < 0] == 0.0)


def rust_dir(theta_deg, phi_deg):
    """The CLI's `dir`: f64 sin/cos of the angles in radians, rounded to f32."""
    t, p = math.radians(theta_deg), math.radians(phi_deg)
    return np.array(
        [[math.sin(t) * math.cos(p), math.sin(t) * math.sin(p), math.cos(t)]]
    ).astype(np.float32)


@pytest.mark.parametrize("spec", SPECS)
def test_eval_equals_the_cli_bit_for_bit(spec):
    exe = cli()
    b = radiometry.Brdf(spec)
    for wi, wo in [("0,0", "0,0"), ("30,10", "45,190"), ("80,0", "10,180"), ("89.5,33", "60,-40")]:
        out = subprocess.run(
            [exe, "eval", spec, "--wi", wi, "--wo", wo], capture_output=True, text=True, check=True
        )
        want = np.float32(out.stdout.strip())
        ti, pi_ = map(float, wi.split(","))
        to, po = map(float, wo.split(","))
        got = b.eval(rust_dir(ti, pi_), rust_dir(to, po))[0]
        assert bits(got) == bits(want), (spec, wi, wo, got, want)


def test_closed_forms():
    n = np.array([[0.0, 0.0, 1.0]], dtype=np.float32)
    lam = radiometry.Brdf("lambertian(albedo=0.5)")
    assert abs(lam.eval(directions(10, 3), directions(10, 4)) - 0.5 / math.pi).max() < 1e-7
    for alpha in [0.1, 0.5, 1.0]:
        # h = n: D = 1/(pi a^2), G2 = F = 1 => f = 1/(4 pi a^2) (Walter et al. 2007).
        f = radiometry.Brdf(f"ggx(alpha={alpha})").eval(n, n)[0]
        want = 1.0 / (4.0 * math.pi * alpha * alpha)
        assert abs(f - want) < 2e-6 * want


def test_float64_input_is_rounded_to_float32_and_strided_input_works():
    b = radiometry.Brdf("ggx(alpha=0.2)")
    wi, wo = directions(257, 5), directions(257, 6)
    ref = b.eval(wi, wo)
    assert np.array_equal(bits(b.eval(wi.astype(np.float64), wo.astype(np.float64))), bits(ref))
    wide = np.zeros((257, 6), dtype=np.float32)
    wide[:, ::2] = wi  # a strided (non-contiguous) view
    assert np.array_equal(bits(b.eval(wide[:, ::2], wo)), bits(ref))
    assert np.array_equal(bits(b.eval(wi.tolist(), wo)), bits(ref))
    assert b.eval(np.zeros((0, 3), np.float32), np.zeros((0, 3), np.float32)).shape == (0,)


def test_fortran_ordered_arrays_are_read_by_rows():
    # A column-major (N, 3) array is contiguous too, but its memory is not
    # [x0, y0, z0, x1, ...]: it must be read by rows like any other layout.
    b = radiometry.Brdf("ggx(alpha=0.2)")
    wi, wo = directions(64, 11), directions(64, 12)
    ref = b.eval(wi, wo)
    assert np.array_equal(bits(b.eval(np.asfortranarray(wi), np.asfortranarray(wo))), bits(ref))
    assert np.array_equal(bits(b.eval(np.asfortranarray(wi.astype(np.float64)), wo)), bits(ref))
    u = np.random.default_rng(13).random((64, 2), dtype=np.float32)
    assert np.array_equal(bits(b.sample(wo, np.asfortranarray(u))[2]), bits(b.sample(wo, u)[2]))


@pytest.mark.parametrize("spec", SPECS)
def test_sampling_is_consistent_with_pdf_eval_and_albedo(spec):
    b = radiometry.Brdf(spec)
    n = 200_000
    theta_o = 35.0
    t = math.radians(theta_o)
    wo = np.tile(np.array([[math.sin(t), 0.0, math.cos(t)]], np.float32), (n, 1))
    u = np.random.default_rng(7).random((n, 2), dtype=np.float32)
    wi, pdf, weight = b.sample(wo, u)
    assert wi.shape == (n, 3) and pdf.dtype == np.float32 and weight.dtype == np.float32
    ok = pdf > 0
    assert ok.mean() > 0.5
    assert np.all(weight[~ok] == 0.0) and np.all(wi[~ok] == 0.0)
    # The returned pdf is the pdf of the returned direction; the weight is f cos / pdf.
    p = b.pdf(wi[ok], wo[ok])
    assert np.allclose(p, pdf[ok], rtol=1e-4, atol=0)
    f = b.eval(wi[ok], wo[ok])
    w = f.astype(np.float64) * wi[ok, 2] / pdf[ok]
    assert np.allclose(weight[ok], w, rtol=1e-4, atol=1e-7)
    # E[weight] = directional albedo (within 5 standard errors of the mean).
    mean = weight.astype(np.float64).mean()
    se = weight.astype(np.float64).std() / math.sqrt(n)
    rho = b.albedo(theta_o, tol=1e-7)["value"]
    assert abs(mean - rho) < 5 * se + 1e-6, (mean, se, rho)


def test_ggx_alpha_one_albedo_at_normal_incidence_is_one_minus_ln2():
    # Closed form: rho(0) = 1 - ln 2 for GGX alpha = 1, height-correlated,
    # no Fresnel.
    want = 1.0 - math.log(2.0)
    r = radiometry.Brdf("ggx(alpha=1)").albedo(0.0)
    assert set(r) >= {"value", "error", "evaluations", "seconds", "status", "status_reason"}
    assert abs(r["value"] - want) < 1e-6, r
    assert r["status"] == "resolved" and r["status_reason"] == ""
    assert r["evaluations"] > 0 and r["seconds"] >= 0.0
    r = radiometry.Brdf("ggx(alpha=1)").albedo(0.0, tol=1e-7)
    assert r["stopped"] == "tolerance reached" and abs(r["value"] - want) < 1e-6
    r = radiometry.Brdf("ggx(alpha=1)").albedo(0.0, integrator="mc-cosine-sobol", budget=1 << 16)
    assert abs(r["value"] - want) < 5 * r["error"] + 1e-6, r


@pytest.mark.parametrize(
    "spec,theta,integrator",
    [("ggx(alpha=1)", "0", "gauss-legendre"), ("phong(exponent=100000)", "30", "gauss-legendre"),
     ("ggx(alpha=0.001)", "60", "mc-uniform-prng")],
)
def test_albedo_equals_the_cli_json(spec, theta, integrator):
    import json

    out = subprocess.run(
        [cli(), "albedo", spec, "--theta-o", theta, "--integrator", integrator, "--budget", "1024", "--format", "json"],
        capture_output=True, text=True, check=True,
    )
    want = json.loads(out.stdout)
    got = radiometry.Brdf(spec).albedo(float(theta), integrator=integrator, budget=1024)
    for k in ["value", "error", "evaluations", "budget", "final_run_evaluations", "status", "status_reason"]:
        assert got[k] == want[k], (k, got[k], want[k])


def test_albedo_to_tolerance_equals_the_cli_json():
    # The defect of issue 24: GGX alpha = 0.01 at normal incidence, --tol 1e-6,
    # through the default integrator; the answer is judged by the report's f64
    # reference of the same case.
    import json

    spec = radiometry.CaseIntegrand("ggx-a0.01-to0").spec
    out = subprocess.run(
        [cli(), "albedo", spec, "--theta-o", "0", "--tol", "1e-6", "--format", "json"],
        capture_output=True, text=True, check=True,
    )
    want = json.loads(out.stdout)
    got = radiometry.Brdf(spec).albedo(0.0, tol=1e-6)
    for k in ["value", "error", "evaluations", "budget", "final_run_evaluations", "status", "stopped", "runs",
              "confirmation", "integrator", "tol", "max_budget"]:
        assert got[k] == want[k], (k, got[k], want[k])
    ref = radiometry.CaseIntegrand("ggx-a0.01-to0").reference()[0]
    assert got["stopped"] == "tolerance reached" and abs(got["value"] - ref) <= 1e-6, (got, ref)


def test_integrators_and_irradiance():
    names = radiometry.integrators()
    assert names[0] == "gauss-legendre"
    assert {"gauss-legendre-warped", "adaptive", "adaptive-warped", "mc-cosine-sobol"} <= set(names)
    assert len(set(names)) == len(names)
    assert abs(radiometry.irradiance("sky(radiance=1)") - math.pi) < 1e-6
    e = radiometry.irradiance("directional(theta=60, irradiance=2) + sky(radiance=0.5)")
    assert abs(e - (2.0 * 0.5 + 0.5 * math.pi)) < 1e-6


def test_integrators_match_the_cli():
    out = subprocess.run([cli(), "integrators"], capture_output=True, text=True, check=True)
    assert radiometry.integrators() == out.stdout.split()


BAD_SPECS = ["ggx(alpha=nan)", "ggx(alpha=0.1, g=sep)", "lambertian(albedo=1.5)", "phong(ks=1)", ""]


@pytest.mark.parametrize("spec", BAD_SPECS)
def test_bad_specs_raise_value_error_with_a_caret(spec):
    with pytest.raises(ValueError) as e:
        radiometry.Brdf(spec)
    assert "^" in str(e.value) and str(e.value).startswith("invalid spec:")


@pytest.mark.parametrize("spec", BAD_SPECS)
def test_bad_specs_give_the_cli_message(spec):
    out = subprocess.run([cli(), "eval", spec, "--wi", "0,0", "--wo", "0,0"], capture_output=True, text=True)
    assert out.returncode == 2
    with pytest.raises(ValueError) as e:
        radiometry.Brdf(spec)
    assert out.stderr.rstrip("\n") == "error: " + str(e.value)


def test_bad_arrays_and_arguments_raise_value_error():
    b = radiometry.Brdf("ggx(alpha=0.3)")
    d = directions(4, 8)
    for wi, wo in [
        (d[:, :2], d),  # (N, 2) instead of (N, 3)
        (d, d[:3]),  # row counts differ
        (d[0], d),  # 1-D
        (np.zeros((2, 3, 1)), d),  # 3-D
        ("not an array", d),
        (np.array([["a", "b", "c"]]), d[:1]),
    ]:
        with pytest.raises(ValueError):
            b.eval(wi, wo)
        with pytest.raises(ValueError):
            b.pdf(wi, wo)
    with pytest.raises(ValueError):
        b.sample(d, d)  # u must be (N, 2)
    with pytest.raises(ValueError, match=r"--theta-o 95 is outside \[0, 90\] degrees"):
        b.albedo(95.0)
    with pytest.raises(ValueError, match="unknown integrator `nope`"):
        b.albedo(0.0, integrator="nope")
    with pytest.raises(ValueError, match="must be a positive finite number"):
        b.albedo(0.0, tol=float("nan"))
    with pytest.raises(ValueError):
        b.albedo(0.0, budget=100, tol=1e-3)
    with pytest.raises(ValueError, match="invalid spec"):
        radiometry.irradiance("directional(theta=200)")
    # NaN directions are input, not parameters: finite output, no exception.
    nan = np.full((3, 3), np.nan, np.float32)
    assert np.all(np.isfinite(b.eval(nan, d[:3])))


def test_tradeoff_quick_returns_the_report_rows(tmp_path):
    rows = radiometry.tradeoff(quick=True, out=str(tmp_path), threads=2)
    assert {r["integrator"] for r in rows} >= set(radiometry.integrators())
    header = (tmp_path / "tradeoff.csv").read_text().splitlines()[0].split(",")
    assert len(rows) == len((tmp_path / "tradeoff.csv").read_text().splitlines()) - 1 > 0
    for r in rows:
        assert list(r) == header
        assert isinstance(r["case"], str) and isinstance(r["integrator"], str)
        assert r["status"] in ("resolved", "unresolved")
        assert isinstance(r["budget"], int) and isinstance(r["evaluations"], int)
        assert math.isfinite(r["estimate"]) and math.isfinite(r["reference"])
        assert abs(r["abs_error"] - abs(r["estimate"] - r["reference"])) <= 1e-9 * max(1.0, abs(r["reference"]))
    # The CLI's filters.
    few = radiometry.tradeoff(quick=True, out=str(tmp_path / "few"), threads=2, cases=["lambertian"], integrators=["adaptive"])
    assert few and all("lambertian" in r["case"] and "adaptive" in r["integrator"] for r in few)


# Colour: a spec with a non-grey rgb() colour, a named metal or a MERL file is evaluated per channel.

COLOUR_SPECS = [
    "lambertian(albedo=rgb(0.8, 0.4, 0.1))",
    "ggx(alpha=0.3, fresnel=conductor(metal=Au))",
    "openpbr(base_color=rgb(0.8, 0.1, 0.1))",
    "coated(ggx(alpha=0.1, fresnel=dielectric(eta=1.5)), eon(rho=rgb(0.2, 0.5, 0.7), sigma=0.3))",
    "mix(0.5, ggx(alpha=0.2, fresnel=conductor(metal=Cu)), lambertian(albedo=rgb(0.1, 0.2, 0.9)))",
]


@pytest.mark.parametrize("spec", COLOUR_SPECS)
def test_colour_eval_is_n_by_3_and_bit_equal_to_scalar_eval(spec):
    b = radiometry.Brdf(spec)
    assert b.channels == 3
    n = 1003
    wi, wo = directions(n, 21, below=0.3), directions(n, 22)
    got = b.eval(wi, wo)
    assert got.dtype == np.float32 and got.shape == (n, 3)
    want = np.array([b.eval_one(wi[k], wo[k]) for k in range(n)], dtype=np.float32)
    assert want.shape == (n, 3)
    assert np.array_equal(bits(got), bits(want))
    assert np.all(np.isfinite(got)) and np.all(got >= 0.0)
    assert np.all(got[wi[:, 2] < 0] == 0.0)
    # mono=True: one channel, the cheap path.
    m = radiometry.Brdf(spec, mono=True)
    assert m.channels == 1 and m.eval(wi, wo).shape == (n,)


def test_grey_specs_stay_one_channel():
    for spec in SPECS + ["lambertian(albedo=rgb(0.3, 0.3, 0.3))", "openpbr(base_color=0.5)"]:
        b = radiometry.Brdf(spec)
        assert b.channels == 1, spec
        assert b.eval(directions(4, 1), directions(4, 2)).shape == (4,)


def test_rgb_lambertian_closed_form_per_channel_and_mono_luminance():
    wi, wo = directions(50, 31), directions(50, 32)
    f = radiometry.Brdf("lambertian(albedo=rgb(0.8, 0.4, 0.1))").eval(wi, wo)
    for c, rho in enumerate([0.8, 0.4, 0.1]):
        assert np.abs(f[:, c] - rho / math.pi).max() < 1e-7
    m = radiometry.Brdf("lambertian(albedo=rgb(0.8, 0.4, 0.1))", mono=True).eval(wi, wo)
    lum = 0.2126 * 0.8 + 0.7152 * 0.4 + 0.0722 * 0.1
    assert np.abs(m - lum / math.pi).max() < 1e-7


def test_gold_red_above_blue_and_equal_to_the_cli():
    spec = "ggx(alpha=0.3, fresnel=conductor(metal=Au))"
    b = radiometry.Brdf(spec)
    f = b.eval(rust_dir(30, 0), rust_dir(30, 180))[0]
    assert f[0] > f[1] > f[2] > 0.0
    exe = cli()
    out = subprocess.run(
        [exe, "eval", spec, "--wi", "30,0", "--wo", "30,180"], capture_output=True, text=True, check=True
    )
    want = np.array([np.float32(t) for t in out.stdout.split()], dtype=np.float32)
    assert want.shape == (3,) and np.array_equal(bits(f), bits(want))


def test_colour_albedo_per_channel():
    b = radiometry.Brdf("lambertian(albedo=rgb(0.8, 0.4, 0.1))")
    r = b.albedo(40.0, tol=1e-6)
    assert r["channels"] == "linear-srgb"
    assert len(r["value"]) == 3 and len(r["error"]) == 3 and len(r["confirmation"]) == 3
    for got, want in zip(r["value"], [0.8, 0.4, 0.1]):
        assert abs(got - want) < 1e-5, r
    r = b.albedo(40.0)
    assert len(r["value"]) == 3 and r["status"] == "resolved"
    m = radiometry.Brdf("lambertian(albedo=rgb(0.8, 0.4, 0.1))", mono=True).albedo(40.0)
    assert isinstance(m["value"], float) and "channels" not in m


def test_colour_sampling_weight_is_per_channel_and_consistent():
    b = radiometry.Brdf("ggx(alpha=0.3, fresnel=conductor(metal=Cu))")
    n = 4096
    wo = directions(n, 41)
    u = np.random.default_rng(42).random((n, 2), dtype=np.float32)
    wi, pdf, weight = b.sample(wo, u)
    assert wi.shape == (n, 3) and pdf.shape == (n,) and weight.shape == (n, 3)
    ok = pdf > 0
    assert ok.mean() > 0.5 and np.all(weight[~ok] == 0.0)
    f = b.eval(wi[ok], wo[ok])
    w = f.astype(np.float64) * wi[ok, 2:3] / pdf[ok, None]
    assert np.allclose(weight[ok], w, rtol=1e-4, atol=1e-7)
    assert np.all(weight[ok, 0] > weight[ok, 2])  # copper: red above blue


def test_colour_batch_length_mismatch_is_a_value_error():
    b = radiometry.Brdf("ggx(alpha=0.3, fresnel=conductor(metal=Au))")
    with pytest.raises(ValueError, match="`wi` has 3 rows but `wo` has 2"):
        b.eval(directions(3, 1), directions(2, 2))
    with pytest.raises(ValueError, match="rows"):
        b.pdf(directions(3, 1), directions(2, 2))
    with pytest.raises(ValueError, match="rows"):
        b.sample(directions(3, 1), np.zeros((4, 2), np.float32))
    with pytest.raises(ValueError, match=r"shape \(N, 3\)"):
        b.eval(np.zeros((3, 2), np.float32), directions(3, 2))
