"""Bring your own integrator: the case integrands as NumPy functions, the
harness of ``radiometry.tradeoff(integrators={...})``, the adapters for
SciPy, vegas and qmcpy, and the Dask path.

Independent checks: closed forms (1 - ln 2, the Lambertian weight 1),
``Brdf.eval`` / ``Brdf.sample`` with the geometry recomputed here in NumPy,
the report's f64 references, and the local run for the Dask one. A peer whose
package is missing is skipped (``pytest.importorskip``).
"""

import csv
import math
import os
import pickle
import subprocess
import warnings

import numpy as np
import pytest

import radiometry
from radiometry import adapters

LN2 = 1.0 - math.log(2.0)


def grid(n):
    """Midpoints of an n x n grid on the unit square, (n^2, 2) float64."""
    a = (np.arange(n) + 0.5) / n
    return np.stack(np.meshgrid(a, a, indexing="ij"), -1).reshape(-1, 2)


def directions(x):
    """The plain square's map, recomputed: mu = x0, phi = 2 pi x1."""
    mu, phi = x[:, 0], 2.0 * math.pi * x[:, 1]
    s = np.sqrt(np.maximum(0.0, 1.0 - mu * mu))
    return np.stack([s * np.cos(phi), s * np.sin(phi), mu], -1)


def wo_of(theta_deg):
    t = math.radians(theta_deg)
    return np.array([math.sin(t), 0.0, math.cos(t)])


# --- the case integrands ---------------------------------------------------


def test_case_names_cover_both_suites_and_quick_is_a_subset():
    full, quick = radiometry.case_names(), radiometry.case_names(quick=True)
    assert set(quick) < set(full) and len(set(full)) == len(full)
    kinds = {radiometry.CaseIntegrand(c).kind for c in quick}
    assert kinds == {"albedo", "product"}


def test_plain_and_warped_integrate_to_one_minus_ln2():
    # GGX alpha = 1 at normal incidence: albedo 1 - ln 2 (closed form).
    g = radiometry.CaseIntegrand("ggx-a1-to0")
    assert g.kind == "albedo" and g.theta_o == 0.0 and g.has_warped
    x = grid(600)
    plain, warped = g.plain(x), g.warped(x)
    assert plain.dtype == np.float64 and plain.shape == (len(x),)
    assert abs(plain.mean() - LN2) < 2e-6, plain.mean()
    assert abs(warped.mean() - LN2) < 2e-6, warped.mean()
    value, bound = g.reference()
    assert abs(value - LN2) < 1e-12 and bound < 1e-9


def test_plain_is_2pi_f_cos_pointwise_and_warped_is_the_sample_weight():
    case = radiometry.CaseIntegrand("ggx-a0.3-to60")
    brdf = radiometry.Brdf(case.spec)
    x = np.random.default_rng(3).random((5000, 2))
    wi = directions(x)
    wo = np.tile(wo_of(60.0), (len(x), 1))
    f = brdf.eval(wi.astype(np.float32), wo.astype(np.float32)).astype(np.float64)
    want = 2.0 * math.pi * f * x[:, 0]
    assert np.allclose(case.plain(x), want, rtol=2e-5, atol=1e-12)
    # The warped square: the weight f cos / pdf of the BRDF's own sample.
    _wi, pdf, weight = brdf.sample(wo.astype(np.float32), x.astype(np.float32))
    assert np.allclose(case.warped(x), np.where(pdf > 0, weight, 0.0), rtol=1e-5, atol=1e-7)
    # One point at a time gives the same values.
    for k in range(5):
        assert case.plain_at(*x[k]) == case.plain(x[k : k + 1])[0]
        assert case.warped_at(*x[k]) == case.warped(x[k : k + 1])[0]


def test_lambertian_warped_is_its_albedo_everywhere():
    # Cosine sampling of a white Lambertian: f cos / pdf = 1 at every u.
    w = radiometry.CaseIntegrand("lambertian-to60").warped(np.random.default_rng(4).random((4096, 2)))
    assert np.all(np.abs(w - 1.0) < 1e-6)


def cap_geometry(name):
    """Axis, half-angle and wo of a product case, recomputed from its name
    (``ggx-{sun,lamp}-a{alpha}-el{elevation}-{mirror,off}``)."""
    parts = name.split("-")
    sigma = math.radians(0.27 if parts[1] == "sun" else 5.0)
    elev = float(parts[3][2:])
    ta = math.radians(90.0 - elev)
    p = math.pi + (math.radians(10.0) if parts[4] == "off" else 0.0)
    return (
        np.array([math.sin(ta), 0.0, math.cos(ta)]),
        sigma,
        np.array([math.sin(ta) * math.cos(p), math.sin(ta) * math.sin(p), math.cos(ta)]),
    )


@pytest.mark.parametrize("name", ["ggx-lamp-a0.5-el45-mirror", "ggx-lamp-a0.1-el2-off"])
def test_product_plain_is_the_masked_integrand_and_warped_integrates_to_the_reference(name):
    case = radiometry.CaseIntegrand(name)
    assert case.kind == "product"
    axis, sigma, wo = cap_geometry(name)
    brdf = radiometry.Brdf(case.spec)
    # Points concentrated around the cap, so that the mask is exercised.
    rng = np.random.default_rng(5)
    mu0 = axis[2]
    lo, hi = max(0.0, mu0 - 0.2), min(1.0, mu0 + 0.2)
    x = np.stack([rng.uniform(lo, hi, 20000), rng.uniform(-0.05, 0.05, 20000) % 1.0], -1)
    wi = directions(x)
    angle = np.arccos(np.clip(wi @ axis, -1.0, 1.0))
    inside, clear = angle <= sigma, np.abs(angle - sigma) > 1e-4
    assert inside.sum() > 500 and (~inside).sum() > 500
    f = brdf.eval(wi.astype(np.float32), np.tile(wo, (len(x), 1)).astype(np.float32)).astype(np.float64)
    want = 2.0 * math.pi * f * x[:, 0] * inside
    got = case.plain(x)
    assert np.allclose(got[clear], want[clear], rtol=2e-5, atol=1e-12)
    # Warped: uniform over the cap, so the mean over a grid is the radiance.
    ref, bound = case.reference()
    warped = case.warped(grid(400))
    assert abs(warped.mean() - ref) < 1e-4 * ref, (warped.mean(), ref)
    # Below the horizon (el2: part of the lamp is) the warped square is 0.
    if name.endswith("el2-off"):
        assert (warped == 0.0).mean() > 0.05


def test_points_in_any_layout_and_bad_points_raise():
    g = radiometry.CaseIntegrand("ggx-a0.3-to60")
    x = np.random.default_rng(6).random((300, 2))
    want = g.plain(x)
    assert np.array_equal(g.plain(np.asfortranarray(x)), want)  # column-major memory
    wide = np.zeros((300, 4))
    wide[:, ::2] = x
    assert np.array_equal(g.plain(wide[:, ::2]), want)  # strided
    assert np.array_equal(g.plain(x.tolist()), want)
    assert np.array_equal(g.plain(x.astype(np.float32)), g.plain(x.astype(np.float32).astype(np.float64)))
    assert g.plain(np.zeros((0, 2))).shape == (0,)
    for bad in [x[:, :1], np.zeros((3, 3)), x[0], np.array([[0.5, 1.5]]), np.array([[np.nan, 0.5]]), "x"]:
        with pytest.raises(ValueError):
            g.plain(bad)
        with pytest.raises(ValueError):
            g.warped(bad)
    with pytest.raises(ValueError, match="outside the unit square"):
        g.plain_at(-0.1, 0.5)
    with pytest.raises(ValueError, match="unknown case `nope`.*case_names"):
        radiometry.CaseIntegrand("nope")


def test_case_integrand_pickles_by_name():
    g = radiometry.CaseIntegrand("phong-n100-to60")
    h = pickle.loads(pickle.dumps(g))
    x = grid(20)
    assert h.name == g.name and np.array_equal(h.plain(x), g.plain(x))


def test_the_counting_integrand_counts_every_point_and_enforces_its_limit():
    g = radiometry.Integrand("ggx-a0.3-to60", max_evaluations=1000, seed=9)
    assert (g.case, g.kind, g.dim, g.seed, g.max_evaluations, g.evaluations) == ("ggx-a0.3-to60", "albedo", 2, 9, 1000, 0)
    g.plain(grid(10))
    g.warped(grid(20))
    g.plain.at(0.5, 0.5)
    assert g.evaluations == 100 + 400 + 1
    with pytest.raises(ValueError):
        g.plain(np.zeros((5, 3)))  # refused before counting
    assert g.evaluations == 501
    with pytest.raises(radiometry.EvaluationLimitError):
        g.warped(grid(30))


# --- the harness ------------------------------------------------------------


def midpoint(integrand, budget=None, tol=None):
    """A product midpoint rule on the warped square (fixed budgets only)."""
    if budget is None:
        return None
    n = int(math.isqrt(budget))
    v = integrand.warped(grid(n))
    return float(v.mean()), float(v.std() / n), "unresolved: no error estimate"


def test_harness_counts_what_is_evaluated_not_what_is_claimed():
    spent = []

    def fn(integrand, budget=None, tol=None):
        n = 7 if budget else 3
        a = integrand.plain(np.random.default_rng(1).random((n * 100, 2)))
        b = integrand.warped.at(0.25, 0.75)
        spent.append(n * 100 + 1)
        return {"value": a.mean() + 0 * b, "error": 1.0, "stopped": "my, reason"}

    rows, skipped = radiometry.measure({"mine": fn}, ["lambertian-to60"], budgets=[16, 64], tolerances=[1e-2])
    assert [r["evaluations"] for r in rows] == spent == [701, 701, 301]
    assert [r["budget"] for r in rows] == [16, 64, None]
    assert rows[2]["tol"] == pytest.approx(radiometry.tolerance_for(1.0, 1e-2), rel=1e-12)
    assert rows[2]["stopped"] == "my; reason" and rows[0]["stopped"] == ""  # no commas in the CSV
    assert all(set(r) == set(radiometry._harness.ROW_FIELDS) for r in rows) and not skipped


def test_harness_statuses_declines_and_seeds():
    seeds = []

    def fn(integrand, budget=None, tol=None):
        seeds.append(integrand.seed)
        v = integrand.plain(grid(8)).mean()
        if budget == 16:
            return None
        if budget == 64:
            return v, 0.1, "unresolved: too, coarse"
        if budget == 256:
            return v, 0.1, False
        return v, 1e-9  # tolerance runs: error <= tol, resolved

    rows, skipped = radiometry.measure({"s": fn}, ["ggx-a0.3-to60"], budgets=[16, 64, 256], tolerances=[1e-2])
    assert [s.endswith("at budget 16: declined") for s in skipped] == [True]
    assert [(r["resolved"], r["status_reason"]) for r in rows] == [
        (False, "too; coarse"), (False, "integrator-flag"), (True, "")]
    assert rows[-1]["stopped"] == "tolerance reached"
    # Seeds differ between runs and repeat between calls.
    first = list(seeds)
    radiometry.measure({"s": fn}, ["ggx-a0.3-to60"], budgets=[16, 64, 256], tolerances=[1e-2])
    assert seeds[len(first):] == first and len(set(first)) == len(first)


@pytest.mark.parametrize(
    "result,match",
    [
        ((float("nan"), 0.1), "non-finite value"),
        ((1.0, float("inf")), "claimed error inf"),
        ((1.0, -1e-3), "claimed error -0.001"),
        ((1.0, 0.1, "fine"), "status 'fine'"),
        (("one", 0.1), "value 'one' is not a number"),
        (1.0, "expected \\(value, error\\)"),
        ({"value": 1.0}, "a dict result needs"),
    ],
)
def test_results_outside_the_contract_raise_integrator_error(result, match):
    def fn(integrand, budget=None, tol=None):
        integrand.plain.at(0.5, 0.5)
        return result

    with pytest.raises(radiometry.IntegratorError, match=match) as e:
        radiometry.measure({"bad": fn}, ["lambertian-to60"], budgets=[64])
    assert "`bad` on case `lambertian-to60` at budget 64" in str(e.value)


def test_an_exception_in_fn_is_raised_with_its_context():
    def fn(integrand, budget=None, tol=None):
        raise ZeroDivisionError("oops")

    with pytest.raises(radiometry.IntegratorError, match="raised ZeroDivisionError: oops") as e:
        radiometry.measure({"boom": fn}, ["phong-n100-to60"], tolerances=[1e-4])
    assert isinstance(e.value.__cause__, ZeroDivisionError) and "at tol" in str(e.value)


def test_a_value_without_evaluations_is_refused():
    with pytest.raises(radiometry.IntegratorError, match="without evaluating"):
        radiometry.measure({"lazy": lambda g, budget=None, tol=None: (1.0, 0.0)}, ["lambertian-to60"], budgets=[64])


def test_runs_past_the_evaluation_limit_write_no_row():
    def greedy(integrand, budget=None, tol=None):
        for _ in range(100):
            integrand.plain(grid(10))
        return 1.0, 0.0

    def sly(integrand, budget=None, tol=None):  # swallows the limit's exception
        try:
            greedy(integrand)
        except Exception:
            pass
        return 1.0, 0.0

    for fn in (greedy, sly):
        rows, skipped = radiometry.measure({"g": fn}, ["lambertian-to60"], budgets=[64], max_evaluations=5000)
        assert rows == [] and len(skipped) == 1 and "5000" in skipped[0]


def test_bad_tradeoff_arguments_raise_before_running(tmp_path):
    fn = midpoint
    with pytest.raises(ValueError, match="taken by a built-in"):
        radiometry.tradeoff(out=str(tmp_path), integrators={"adaptive-warped": fn})
    with pytest.raises(ValueError, match="without commas"):
        radiometry.tradeoff(out=str(tmp_path), integrators={"a,b": fn})
    with pytest.raises(TypeError, match="not callable"):
        radiometry.tradeoff(out=str(tmp_path), integrators={"x": 3})
    with pytest.raises(ValueError, match="leaves no case"):
        radiometry.tradeoff(out=str(tmp_path), integrators={"x": fn}, cases=["no-such-case"])
    with pytest.raises(ValueError, match="budget ladder"):
        radiometry.tradeoff(out=str(tmp_path), integrators={"x": fn}, budgets=[100])
    with pytest.raises(ValueError, match="TOL_TARGETS"):
        radiometry.tradeoff(out=str(tmp_path), integrators={"x": fn}, tolerances=[1e-3])
    with pytest.raises(TypeError, match="once"):
        radiometry.tradeoff(out=str(tmp_path), integrators=["adaptive"], builtins=["adaptive"])
    with pytest.raises(TypeError, match="Client"):
        radiometry.tradeoff(out=str(tmp_path), integrators={"x": fn}, client=object())


def grid_to_tol(integrand, budget=None, tol=None):
    """Tolerance runs only: a 128 x 128 midpoint grid on the warped square,
    claiming half the tolerance."""
    if tol is None:
        return None
    return float(integrand.warped(grid(128)).mean()), tol / 2


def test_user_rows_come_back_through_the_report(tmp_path):
    cases = ["lambertian-to60", "ggx-lamp-a0.01-el2-off"]
    rows = radiometry.tradeoff(
        quick=True,
        out=str(tmp_path),
        threads=2,
        cases=cases,
        integrators={"midpoint-warped": midpoint, "grid-to-tol": grid_to_tol},
        builtins=["adaptive-warped", "cap-adaptive"],
        tolerances=[1e-2],
    )
    # Fixed budgets: tradeoff.csv has the harness's rows, with the reference
    # and the true error added.
    mine = [r for r in rows if r["integrator"] == "midpoint-warped"]
    ext = [r for r in rows.external if r["budget"] is not None]
    assert len(mine) == len(ext) == len(cases) * len(radiometry.QUICK_BUDGETS)
    by_key = {(r["case"], r["budget"]): r for r in ext}
    for r in mine:
        e = by_key[(r["case"], r["budget"])]
        assert r["evaluations"] == e["evaluations"] == math.isqrt(r["budget"]) ** 2
        assert r["estimate"] == pytest.approx(e["estimate"], rel=1e-12)
        assert r["status"] == "unresolved" and r["status_reason"]
        assert r["abs_error"] == pytest.approx(abs(r["estimate"] - r["reference"]), rel=1e-9, abs=1e-15)
    # To tolerance: tolerance.csv has the harness's rows at the asked
    # absolute tolerance, its relative one, and the reference.
    tol = [r for r in rows.tolerance if r["integrator"] == "grid-to-tol"]
    assert sorted(r["case"] for r in tol) == sorted(cases)
    for r in tol:
        ref = radiometry.CaseIntegrand(r["case"]).reference()[0]
        assert r["reference"] == pytest.approx(ref, rel=1e-12)
        assert r["rel_tol"] == pytest.approx(1e-2) and r["tol"] == pytest.approx(radiometry.tolerance_for(ref, 1e-2))
        assert r["evaluations"] == 128 * 128 and r["error_estimate"] == pytest.approx(r["tol"] / 2)
        assert r["stopped"] == "tolerance reached" and r["status"] == "resolved"
        assert r["abs_error"] == pytest.approx(abs(r["estimate"] - ref), rel=1e-9, abs=1e-15)
    # The built-in filter applies to the built-ins only.
    assert {r["integrator"] for r in rows} == {"adaptive-warped", "cap-adaptive", "midpoint-warped"}
    assert {r["integrator"] for r in rows.tolerance} == {"adaptive-warped", "cap-adaptive", "grid-to-tol"}
    # Declined runs: listed, no row.
    assert len(rows.skipped) == len(cases) * (1 + len(radiometry.QUICK_BUDGETS))
    assert all(s.endswith("declined") for s in rows.skipped)
    assert rows.out == str(tmp_path) and (tmp_path / "summary.md").exists()
    assert "grid-to-tol" in (tmp_path / "summary.md").read_text()


def read_csv(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def test_the_peers_file_gives_the_cli_report_the_same_rows(tmp_path):
    exe = os.environ.get("RADIOMETRY_CLI")
    if not exe:
        pytest.skip("RADIOMETRY_CLI not set (CI sets it to target/release/radiometry)")
    user = {"midpoint-warped": midpoint, "grid-to-tol": grid_to_tol}
    radiometry.tradeoff(
        quick=True, out=str(tmp_path / "py"), threads=2, cases=["lambertian-to60"],
        integrators=user, builtins=["adaptive-warped"], tolerances=[1e-2],
    )
    peers = tmp_path / "py" / "peers.csv"
    subprocess.run(
        [exe, "tradeoff", "--quick", "--out", str(tmp_path / "cli"), "--threads", "2", "--cases", "lambertian-to60",
         "--integrators", "adaptive-warped", "--peers", str(peers)],
        check=True, capture_output=True,
    )
    for name in ("tradeoff.csv", "tolerance.csv"):
        py, cl = read_csv(tmp_path / "py" / name), read_csv(tmp_path / "cli" / name)
        assert [r["integrator"] for r in py] == [r["integrator"] for r in cl]
        assert any(r["integrator"] in user for r in py)
        for a, b in zip(py, cl):
            if a["integrator"] in user:
                assert a == b  # the peers file carries every field, seconds included
            else:
                a.pop("seconds"), b.pop("seconds")
                assert a == b


def test_old_calls_return_a_list_of_rows(tmp_path):
    rows = radiometry.tradeoff(quick=True, out=str(tmp_path), threads=2, cases=["phong"], integrators=["gauss-legendre"])
    assert isinstance(rows, list) and rows and rows.external == [] and rows.skipped == []
    assert {r["integrator"] for r in rows} <= {"gauss-legendre", "gauss-legendre-warped", "gauss-legendre-warped-split"}


# --- the adapters -------------------------------------------------------------

SMOOTH = "ggx-a1-to0"  # albedo 1 - ln 2: smooth on both squares


def run_adapter(fn, case=SMOOTH, budgets=(), tolerances=()):
    rows, skipped = radiometry.measure({fn.default_name: fn}, [case], budgets=list(budgets), tolerances=list(tolerances))
    ref = radiometry.CaseIntegrand(case).reference()[0]
    return rows, skipped, ref


def test_scipy_nquad_budget_and_tolerance_runs():
    pytest.importorskip("scipy.integrate")
    fn = adapters.scipy_nquad()
    assert fn.deterministic and fn.default_name == "scipy-nquad"
    assert [adapters.nquad_limit(b) for b in (256, 441, 1024, 4096, 16384)] == [0, 1, 1, 2, 3]
    rows, skipped, ref = run_adapter(fn, budgets=[256, 1024, 4096, 16384], tolerances=[1e-2, 1e-6])
    assert len(skipped) == 1 and "budget 256: declined" in skipped[0]
    for r in rows:
        true = abs(r["estimate"] - ref)
        if r["budget"] is not None:
            # At most (21 (2L - 1))^2 points: the nested worst case of the limit.
            lim = adapters.nquad_limit(r["budget"])
            assert r["evaluations"] <= (21 * (2 * lim - 1)) ** 2 <= r["budget"]
        else:
            assert r["stopped"] == "tolerance reached" and true <= r["tol"], r
        assert r["resolved"] and true <= 10 * r["error_estimate"] + 1e-12, r
    # More budget, a smaller error.
    b = [r for r in rows if r["budget"]]
    assert abs(b[-1]["estimate"] - ref) < abs(b[0]["estimate"] - ref)


def test_scipy_nquad_reports_the_subdivision_limit_as_the_stop():
    pytest.importorskip("scipy.integrate")
    rows, _, ref = run_adapter(adapters.scipy_nquad(limit=2), case="ggx-a0.05-to60", tolerances=[1e-6])
    assert rows[0]["stopped"] == "max budget reached"


@pytest.mark.parametrize("rule,warped", [("gk21", False), ("genz-malik", False), ("genz-malik", True)])
def test_scipy_cubature(rule, warped):
    integrate = pytest.importorskip("scipy.integrate")
    if not hasattr(integrate, "cubature"):
        pytest.skip("scipy.integrate.cubature needs SciPy >= 1.15")
    fn = adapters.scipy_cubature(rule, warped=warped)
    p = fn.points_per_region
    assert p == {"gk21": 982, "genz-malik": 47}[rule]
    rows, skipped, ref = run_adapter(fn, budgets=[256, 4096, 16384], tolerances=[1e-4])
    for r in rows:
        true = abs(r["estimate"] - ref)
        if r["budget"] is not None:
            assert 5 * p <= r["evaluations"] <= r["budget"], r
        else:
            assert r["stopped"] == "tolerance reached" and true <= r["tol"], r
        assert true <= 10 * r["error_estimate"] + 1e-12, r
    assert len(skipped) == sum(b < 5 * p for b in (256, 4096, 16384))


def test_vegas_is_seeded_and_within_its_standard_errors():
    pytest.importorskip("vegas")
    fn = adapters.vegas_()
    assert not fn.deterministic
    rows, skipped, ref = run_adapter(fn, budgets=[64, 4096, 16384], tolerances=[1e-2])
    assert len(skipped) == 1 and "budget 64" in skipped[0]
    for r in rows:
        assert abs(r["estimate"] - ref) <= 5 * r["error_estimate"], r
        if r["budget"] is not None:
            assert r["evaluations"] <= r["budget"]
        else:
            assert r["stopped"] == "tolerance reached" and r["error_estimate"] <= r["tol"]
    again, _, _ = run_adapter(fn, budgets=[64, 4096, 16384], tolerances=[1e-2])
    assert [r["estimate"] for r in again] == [r["estimate"] for r in rows]


def test_qmcpy_budget_and_tolerance_runs():
    pytest.importorskip("qmcpy")
    fn = adapters.qmcpy_()
    rows, skipped, ref = run_adapter(fn, budgets=[64, 1024, 4096], tolerances=[1e-4])
    assert len(skipped) == 1 and "budget 64" in skipped[0]
    for r in rows:
        assert abs(r["estimate"] - ref) <= 10 * r["error_estimate"] + 1e-12, r
        if r["budget"] is not None:
            assert r["evaluations"] == r["budget"]
        else:
            assert r["stopped"] == "tolerance reached" and r["error_estimate"] <= r["tol"]
    again, _, _ = run_adapter(fn, budgets=[1024])
    assert again[0]["estimate"] == rows[0]["estimate"]


def test_peers_lists_the_installed_adapters():
    have = adapters.peers()
    for mod, names in [("scipy.integrate", ["scipy-nquad"]), ("vegas", ["vegas"]), ("qmcpy", ["qmcpy"])]:
        try:
            __import__(mod)
        except ImportError:
            assert not set(names) & set(have)
        else:
            assert set(names) <= set(have)
    assert all(fn.default_name == n for n, fn in have.items())


# --- Dask ---------------------------------------------------------------------


@pytest.fixture(scope="module")
def dask_client():
    distributed = pytest.importorskip("dask.distributed")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        cluster = distributed.LocalCluster(
            n_workers=2, threads_per_worker=1, processes=True, host="127.0.0.1", dashboard_address=None
        )
        client = distributed.Client(cluster)
    yield client
    client.close()
    cluster.close()


def without_seconds(rows):
    return [{k: v for k, v in r.items() if k != "seconds"} for r in rows]


def test_dask_returns_the_rows_of_the_local_run(dask_client, tmp_path):
    scale = 0.5
    integrators = {
        "midpoint-warped": midpoint,
        # A closure: shipped to the workers by cloudpickle.
        "closure": lambda g, budget=None, tol=None: (scale * 2 * g.plain(grid(16)).mean(), 0.1),
    }
    integrators.update({n: f for n, f in adapters.peers().items() if n in ("scipy-nquad", "vegas", "qmcpy")})
    kw = dict(
        quick=True,
        threads=2,
        cases=["lambertian-to60", "ggx-sun-a0.1-el45-mirror"],
        integrators=integrators,
        builtins=["gauss-legendre-warped-split", "cap-gauss-legendre"],
        budgets=[1024, 4096],
        tolerances=[1e-2, 1e-4],
    )
    local = radiometry.tradeoff(out=str(tmp_path / "local"), **kw)
    remote = radiometry.tradeoff(out=str(tmp_path / "dask"), client=dask_client, **kw)
    assert len(remote.external) == len(local.external) >= 2 * len(integrators)
    assert without_seconds(remote.external) == without_seconds(local.external)
    assert remote.skipped == local.skipped
    assert without_seconds(remote) == without_seconds(local)
    assert without_seconds(remote.tolerance) == without_seconds(local.tolerance)
    # Every user integrator has budget rows in the merged table.
    assert set(integrators) <= {r["integrator"] for r in remote}


def test_dask_raises_the_integrator_error_of_a_task(dask_client):
    def broken(integrand, budget=None, tol=None):
        integrand.plain.at(0.5, 0.5)
        return float("nan"), 0.0

    with pytest.raises(radiometry.IntegratorError, match="`broken` on case `lambertian-to60` at budget 64"):
        radiometry.measure({"broken": broken}, ["lambertian-to60"], budgets=[64], client=dask_client)
