"""The materials through the Python module: the rough diffuse lobes (EON, FON,
classic Oren-Nayar), sheen, the F82-tint and named-metal Fresnel terms, and
the compositions `A + B`, `mix(W, A, B)` and `coated(TOP, BASE)`.

Reference values: the `radiometry` command-line binary when RADIOMETRY_CLI
names it (bit for bit, as in test_radiometry.py), the scalar Rust `eval`, and
EON's white furnace (albedo 1 at rho = 1).
"""

import math
import subprocess

import numpy as np
import pytest

import radiometry
from test_radiometry import bits, cli, directions, rust_dir

MATERIALS = [
    "eon(rho=0.8, sigma=0.5)",
    "fon(rho=0.7, sigma=1)",
    "oren-nayar(rho=0.9, sigma_rad=0.35)",
    "sheen(color=0.8, roughness=0.3)",
    "ggx(alpha=0.3, fresnel=f82(f0=0.9, f82=0.7))",
    "ggx(alpha=0.2, fresnel=conductor(metal=Au))",
    "coated(ggx(alpha=0.1, fresnel=dielectric(eta=1.5)), eon(rho=0.8, sigma=0.5))",
    "coated(ggx(alpha=0.1, fresnel=dielectric(eta=1.5)), ggx(alpha=0.3, fresnel=conductor(metal=Cu)), "
    "coat_color=0.7, coat_ior=1.6)",
    "eon(rho=0.5, sigma=1) + sheen(color=1, roughness=0.5)",
    "mix(0.3, sheen(roughness=0.5), oren-nayar(rho=0.9, sigma_rad=0.35))",
    "coated(sheen(roughness=0.4), fon(rho=0.6, sigma=0.8))",
    "openpbr",
    "openpbr(base_color=rgb(0.8, 0.2, 0.1), base_metalness=0.5, coat_weight=1, coat_roughness=0.1, "
    "fuzz_weight=0.3, fuzz_color=rgb(0.9, 0.9, 1))",
]

COMPOSITES = [s for s in MATERIALS if s.startswith(("coated", "mix", "openpbr")) or " + " in s]


@pytest.mark.parametrize("spec", MATERIALS)
def test_material_eval_equals_the_cli_bit_for_bit(spec):
    exe = cli()

    b = radiometry.Brdf(spec)
    for wi, wo in [("0,0", "0,0"), ("30,10", "45,190"), ("80,0", "10,180"), ("89.5,33", "60,-40"), ("20,0", "20,180")]:
        out = subprocess.run(
            [exe, "eval", spec, "--wi", wi, "--wo", wo], capture_output=True, text=True, check=True
        )
        # One value, or R G B for a colour spec (a named metal, an rgb() colour).
        want = np.array([np.float32(t) for t in out.stdout.split()], dtype=np.float32)
        ti, pi_ = map(float, wi.split(","))
        to, po = map(float, wo.split(","))
        got = np.atleast_1d(b.eval(rust_dir(ti, pi_), rust_dir(to, po))[0])
        assert got.shape == want.shape == (b.channels,)
        assert np.array_equal(bits(got), bits(want)), (spec, wi, wo, got, want)


@pytest.mark.parametrize("spec", MATERIALS)
def test_material_batch_eval_is_bit_equal_to_scalar_eval(spec):
    b = radiometry.Brdf(spec)
    n = 517
    wi, wo = directions(n, 11, below=0.2), directions(n, 12)
    got = b.eval(wi, wo)
    want = np.array([b.eval_one(wi[k], wo[k]) for k in range(n)], dtype=np.float32)
    assert np.array_equal(bits(got), bits(want))
    assert np.all(np.isfinite(got)) and np.all(got >= 0.0)
    assert np.all(got[wi[:, 2] < 0] == 0.0)


@pytest.mark.parametrize("spec", MATERIALS)
def test_material_sampling_is_consistent_with_pdf_eval_and_albedo(spec):
    b = radiometry.Brdf(spec)
    n = 40_000
    theta_o = 40.0
    t = math.radians(theta_o)
    wo = np.tile(np.array([[math.sin(t), 0.0, math.cos(t)]], np.float32), (n, 1))
    u = np.random.default_rng(5).random((n, 2), dtype=np.float32)
    wi, pdf, weight = b.sample(wo, u)
    ok = pdf > 0
    assert ok.mean() > 0.5
    assert np.all(weight[~ok] == 0.0) and np.all(wi[~ok] == 0.0)
    p = b.pdf(wi[ok], wo[ok])
    if spec in COMPOSITES:
        # A composite's pdf is the mixture density its sample returned, bit for bit.
        assert np.array_equal(bits(p), bits(pdf[ok]))
    else:
        assert np.allclose(p, pdf[ok], rtol=1e-5, atol=0)
    f = b.eval(wi[ok], wo[ok])
    # Colour specs: f and weight have a column per channel.
    cos_over_pdf = wi[ok, 2] / pdf[ok]
    if b.channels > 1:
        cos_over_pdf = cos_over_pdf[:, None]
    assert np.allclose(weight[ok], f.astype(np.float64) * cos_over_pdf, rtol=1e-4, atol=1e-7)
    # E[weight] = the directional albedo per channel (within 5 standard errors
    # of the mean and the albedo's own error estimate).
    w = weight.astype(np.float64)
    mean, se = np.atleast_1d(w.mean(axis=0)), np.atleast_1d(w.std(axis=0) / math.sqrt(n))
    a = b.albedo(theta_o)
    value, error = np.atleast_1d(a["value"]), np.atleast_1d(a["error"])
    assert np.all(np.abs(mean - value) < 5 * se + error + 1e-4), (mean, se, a)
    assert np.all(mean <= 1.0 + 5 * se)


@pytest.mark.parametrize("theta", [0.0, 45.0, 80.0, 89.0])
def test_eon_white_furnace(theta):
    a = radiometry.Brdf("eon(rho=1, sigma=0.7)").albedo(theta, tol=1e-6)
    assert abs(a["value"] - 1.0) < 1e-4, a


def test_a_mix_and_a_sum_are_their_formulas():
    wi, wo = directions(64, 21), directions(64, 22)
    sheen = radiometry.Brdf("sheen(roughness=0.5)").eval(wi, wo).astype(np.float64)
    eon = radiometry.Brdf("eon(rho=0.5, sigma=1)").eval(wi, wo).astype(np.float64)
    s = radiometry.Brdf("eon(rho=0.5, sigma=1) + sheen(roughness=0.5)").eval(wi, wo)
    m = radiometry.Brdf("mix(0.25, sheen(roughness=0.5), eon(rho=0.5, sigma=1))").eval(wi, wo)
    assert np.allclose(s, eon + sheen, rtol=1e-6, atol=0)
    assert np.allclose(m, 0.25 * sheen + 0.75 * eon, rtol=1e-6, atol=1e-9)


BAD_MATERIALS = [
    "eon(rho=0.5, sigma=1.5)",
    "eon(rho=0.5, sigma_rad=0.3)",
    "oren-nayar(rho=1, sigma_rad=0.2)",
    "sheen(roughness=0.01)",
    "ggx(alpha=0.1, fresnel=conductor(metal=steel))",
    "ggx(alpha=0.1, fresnel=f82(f0=1.2))",
    "mix(2, lambertian, lambertian)",
    "coated(lambertian, lambertian, coat_ior=0.5)",
    "openpbr(transmission_weight=1)",
    "openpbr(base_color=rgb(1, 2, 0))",
]


@pytest.mark.parametrize("spec", BAD_MATERIALS)
def test_bad_material_specs_give_the_cli_message(spec):

    out = subprocess.run([cli(), "eval", spec, "--wi", "0,0", "--wo", "0,0"], capture_output=True, text=True)
    assert out.returncode == 2
    with pytest.raises(ValueError) as e:
        radiometry.Brdf(spec)
    assert "^" in str(e.value)
    assert out.stderr.rstrip("\n") == "error: " + str(e.value)


def test_materialx_document_is_its_openpbr_spec(tmp_path):
    """An OpenPBR material read from a MaterialX document (the spec grammar's
    `openpbr(file=..., material=...)`) evaluates bit for bit as the
    equivalent `openpbr(...)` spec; an unknown material is a ValueError."""
    doc = tmp_path / "paint.mtlx"
    doc.write_text(
        '<?xml version="1.0"?><materialx version="1.39">'
        '<surfacematerial name="Paint" type="material">'
        '<input name="surfaceshader" type="surfaceshader" nodename="paint_s" /></surfacematerial>'
        '<open_pbr_surface name="paint_s" type="surfaceshader">'
        '<input name="base_color" type="color3" value="0.8, 0.05, 0.05" />'
        '<input name="coat_weight" type="float" value="0.5" />'
        "</open_pbr_surface></materialx>"
    )
    wi, wo = directions(64, 41), directions(64, 42)
    a = radiometry.Brdf(f'openpbr(file="{doc}", material="Paint")').eval(wi, wo)
    b = radiometry.Brdf("openpbr(base_color=rgb(0.8, 0.05, 0.05), coat_weight=0.5)").eval(wi, wo)
    assert a.shape == (64, 3)
    assert np.array_equal(bits(a), bits(b))
    with pytest.raises(ValueError, match="no material"):
        radiometry.Brdf(f'openpbr(file="{doc}", material="Chrome")')
