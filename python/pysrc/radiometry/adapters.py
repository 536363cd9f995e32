"""Standard integration libraries as user integrators for
``radiometry.tradeoff(integrators={...})``, so that the project's integrators
and the usual peers appear side by side in one report::

    from radiometry import adapters
    rows = radiometry.tradeoff(quick=True, integrators={
        "scipy-nquad": adapters.scipy_nquad(),
        "scipy-cubature-gk21": adapters.scipy_cubature("gk21"),
        "vegas": adapters.vegas_(),
        "qmcpy": adapters.qmcpy_(),
    })
    # or every peer that is installed: integrators=adapters.peers()

Each factory imports its library when called (``ImportError`` if it is
missing; ``pip install radiometry[peers]`` installs them all) and returns a
function ``fn(integrand, budget=None, tol=None)`` following the contract of
``radiometry.tradeoff``: it returns the library's value, its claimed error
and, where the library offers one, a status, or ``None`` for a budget below
the library's smallest run. The evaluation counts are the harness's, never the
library's. ``warped=True`` integrates the case's warped square (through its
sampling map) instead of the plain hemisphere square.
"""

import math
import warnings

import numpy as np

__all__ = ["peers", "qmcpy_", "scipy_cubature", "scipy_nquad", "vegas_"]

# QUADPACK refuses a run with epsabs <= 0 and epsrel < max(50 eps, 5e-29)
# (ier = 6); this is the smallest relative tolerance it accepts, which makes
# a fixed-budget run refine until its subdivision limit.
_QUADPACK_MIN_EPSREL = 50.0 * np.finfo(float).eps


def _side(integrand, warped):
    """The plain or warped square of ``integrand`` (``None``: no sampling map)."""
    return integrand.warped if warped else integrand.plain


def _mark(fn, name, deterministic):
    fn.__name__ = fn.__qualname__ = name.replace("-", "_")
    fn.default_name = name
    fn.deterministic = deterministic
    return fn


def nquad_limit(budget):
    """The largest QUADPACK subdivision limit ``L`` whose nested worst case,
    ``(21 (2L - 1))^2`` evaluations (``2L - 1`` Gauss-Kronrod-21 panels on
    each axis), fits ``budget``; 0 when not even one panel per axis does."""
    return max(0, int((math.isqrt(budget) / 21 + 1) // 2))


def scipy_nquad(limit=50, warped=False):
    """``scipy.integrate.nquad`` (QUADPACK ``qags``, nested adaptive
    Gauss-Kronrod 21) on the plain square, ``x0 = mu`` inner, ``x1 = phi/2pi``
    outer, through ``integrand.plain.at`` (one point per call, as QUADPACK
    evaluates).

    * tolerance runs: ``epsabs = tol, epsrel = 0, limit = limit`` (SciPy's
      default 50) on both levels, as a SciPy user would run it; the value
      and error are nquad's (the error is the outer ``abserr``). Stopped:
      ``"tolerance reached"`` without a QUADPACK warning, ``"max budget
      reached"`` on the subdivision-limit warning, ``"roundoff detected"`` on
      the roundoff warning.
    * budget runs: ``limit = nquad_limit(budget)`` (so at most
      ``(21 (2L-1))^2 <= budget`` points; budgets below 441 are declined) and
      the smallest tolerance QUADPACK accepts, so it refines to its limit;
      limit and roundoff warnings are expected there and ignored.

    Status: unresolved (reason ``quadpack-bad-integrand`` /
    ``quadpack-divergent``) when QUADPACK warns of extremely bad integrand
    behaviour or divergence at any level.
    """
    from scipy.integrate import IntegrationWarning, nquad

    def run(integrand, budget=None, tol=None):
        side = _side(integrand, warped)
        if side is None:
            return None
        if tol is not None:
            opts = {"epsabs": tol, "epsrel": 0.0, "limit": limit}
        else:
            lim = nquad_limit(budget)
            if lim < 1:
                return None
            opts = {"epsabs": 0.0, "epsrel": _QUADPACK_MIN_EPSREL, "limit": lim}
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always", IntegrationWarning)
            value, error = nquad(side.at, [[0.0, 1.0], [0.0, 1.0]], opts=opts)
        said = " ".join(str(w.message) for w in caught if issubclass(w.category, IntegrationWarning))
        status = "resolved"
        if "bad integrand behavior" in said:
            status = "unresolved: quadpack-bad-integrand"
        elif "divergent" in said or "does not converge" in said:
            status = "unresolved: quadpack-divergent"
        out = {"value": value, "error": error, "status": status}
        if tol is not None:
            if "maximum number of subdivisions" in said:
                out["stopped"] = "max budget reached"
            elif "roundoff error" in said:
                out["stopped"] = "roundoff detected"
            else:
                out["stopped"] = "tolerance reached" if error <= tol else "tolerance not reached"
        return out

    return _mark(run, "scipy-nquad" + ("-warped" if warped else ""), True)


def _cubature_points_per_region(rule):
    """Points ``scipy.integrate.cubature`` spends per region with ``rule`` in
    two dimensions, measured on a test function (it evaluates the first
    region, then four per subdivision: ``P (1 + 4 s)`` for ``s >= 1``
    subdivisions)."""
    from scipy.integrate import cubature

    counts = []
    for s in (1, 2):
        n = [0]

        def f(x):
            n[0] += len(x)
            return np.exp(-40.0 * ((x[:, 0] - 0.3) ** 2 + (x[:, 1] - 0.6) ** 2))

        cubature(f, [0.0, 0.0], [1.0, 1.0], rule=rule, rtol=0.0, atol=0.0, max_subdivisions=s)
        counts.append(n[0])
    p, rem = divmod(counts[1] - counts[0], 4)
    if rem or counts[0] != 5 * p:
        raise RuntimeError(f"scipy.integrate.cubature({rule!r}) spends {counts} points: not P (1 + 4 s)")
    return p


def scipy_cubature(rule="gk21", warped=False):
    """``scipy.integrate.cubature`` (globally adaptive, the region with the
    largest error estimate split in four) with ``rule`` (``"gk21"``,
    ``"gk15"`` or ``"genz-malik"``) on the plain square, or on the warped one
    with ``warped=True``; vectorised, through ``integrand.plain`` (whole
    arrays of points).

    * tolerance runs: ``atol = tol, rtol = 0``, ``max_subdivisions`` as many
      as ``integrand.max_evaluations`` allows; stopped ``"tolerance
      reached"`` when the result's status is ``converged``, else ``"max
      budget reached"``.
    * budget runs: ``atol = rtol = 0`` and the most subdivisions that fit the
      budget (``P (1 + 4 s)`` points, ``P`` per region: 982 for gk21, 499
      for gk15, 47 for Genz-Malik in 2D, measured when the adapter is built);
      budgets below ``5 P`` are declined.

    The value and error are the result's ``estimate`` and ``error``.
    """
    from scipy.integrate import cubature

    per_region = _cubature_points_per_region(rule)

    def subdivisions(evals):
        return (evals // per_region - 1) // 4

    def run(integrand, budget=None, tol=None):
        side = _side(integrand, warped)
        if side is None:
            return None
        cap = budget if budget is not None else integrand.max_evaluations
        s = subdivisions(cap)
        if s < 1:
            return None
        atol = 0.0 if tol is None else tol
        r = cubature(side, [0.0, 0.0], [1.0, 1.0], rule=rule, rtol=0.0, atol=atol, max_subdivisions=s)
        out = {"value": float(r.estimate), "error": float(r.error)}
        if tol is not None:
            out["stopped"] = "tolerance reached" if r.status == "converged" else "max budget reached"
        return out

    name = f"scipy-cubature-{rule}" + ("-warped" if warped else "")
    run = _mark(run, name, True)
    run.points_per_region = per_region
    return run


def vegas_(nitn=5, warmup=5, min_neval=100, warped=False):
    """``vegas`` (Lepage's adaptive importance sampling, ``vegas.Integrator``
    on the unit square, batch integrand), seeded from ``integrand.seed``
    (numpy ``default_rng`` as its ``ran_array_generator``), so runs repeat.

    * budget runs: ``warmup`` adapting iterations (discarded) then ``nitn``
      iterations of ``neval = budget // (warmup + nitn)`` each (vegas spends
      at most ``neval`` per iteration); budgets with ``neval < min_neval``
      are declined.
    * tolerance runs: ``warmup`` iterations of 1,000 points, then runs of
      ``nitn`` iterations with ``atol = tol``, doubling ``neval`` from 1,000
      until the standard error is <= ``tol`` (stopped ``"tolerance
      reached"``) or the next run would pass ``integrand.max_evaluations``
      (``"max budget reached"``).

    Value and error: the weighted average of the final run's iterations and
    its standard error. Status: unresolved (``vegas-chi2-q``) when the
    iterations disagree (``Q < 0.01``, vegas's own consistency check).
    """
    import vegas

    def run(integrand, budget=None, tol=None):
        side = _side(integrand, warped)
        if side is None:
            return None
        rng = np.random.default_rng(integrand.seed)
        integ = vegas.Integrator([[0.0, 1.0], [0.0, 1.0]], ran_array_generator=rng.random)
        f = vegas.lbatchintegrand(lambda x: side(x))
        stopped = None
        if budget is not None:
            neval = budget // (warmup + nitn)
            if neval < min_neval:
                return None
            integ(f, nitn=warmup, neval=neval)
            r = integ(f, nitn=nitn, neval=neval)
        else:
            neval = 1000
            integ(f, nitn=warmup, neval=neval)
            while True:
                r = integ(f, nitn=nitn, neval=neval, atol=tol)
                if r.sdev <= tol:
                    stopped = "tolerance reached"
                    break
                neval *= 2
                if integrand.evaluations + nitn * neval > integrand.max_evaluations:
                    stopped = "max budget reached"
                    break
        status = "resolved" if r.Q >= 0.01 else "unresolved: vegas-chi2-q"
        out = {"value": r.mean, "error": r.sdev, "status": status}
        if stopped is not None:
            out["stopped"] = stopped
        return out

    return _mark(run, "vegas" + ("-warped" if warped else ""), False)


def qmcpy_(warped=False):
    """``qmcpy.CubQMCNetG`` (Hickernell and Jimenez Rugama's guaranteed
    automatic cubature on a digital net: a randomised Sobol' net, LMS and
    digital shift, seeded from ``integrand.seed``), through
    ``integrand.plain`` (whole arrays).

    * tolerance runs: ``abs_tol = tol, rel_tol = 0``, ``n_init = 256``,
      ``n_limit`` the largest power of two <= ``integrand.max_evaluations``;
      stopped ``"tolerance reached"`` when qmcpy's flag says so, else ``"max
      budget reached"``.
    * budget runs: ``n_init = n_limit =`` the largest power of two <=
      ``budget`` (its data bound after that many points); budgets below 256
      (qmcpy's smallest ``n_init``) are declined.

    Value and error: the ``solution`` and half the width of qmcpy's
    bounds (``comb_bound_diff / 2``).
    """
    import qmcpy as qp

    cub = getattr(qp, "CubQMCNetG", None) or qp.CubQMCSobolG

    def run(integrand, budget=None, tol=None):
        side = _side(integrand, warped)
        if side is None:
            return None
        cap = budget if budget is not None else integrand.max_evaluations
        n_limit = 1 << (int(cap).bit_length() - 1)
        if n_limit < 256:
            return None
        n_init = n_limit if budget is not None else 256
        sampler = qp.DigitalNetB2(2, seed=integrand.seed % (1 << 32))
        f = qp.CustomFun(qp.Uniform(sampler), g=lambda x: side(x))
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            sc = cub(f, abs_tol=tol if tol is not None else 1e-300, rel_tol=0.0, n_init=n_init, n_limit=n_limit)
            sol, data = sc.integrate()
        out = {"value": float(sol), "error": float(data.comb_bound_diff) / 2}
        if tol is not None:
            out["stopped"] = "tolerance reached" if bool(np.all(data.comb_flags)) else "max budget reached"
        return out

    return _mark(run, "qmcpy" + ("-warped" if warped else ""), False)


def peers(warped=False):
    """``{name: fn}`` of the adapters whose library is installed (SciPy's
    nquad and cubature with gk21 and Genz-Malik, vegas, qmcpy), ready for
    ``radiometry.tradeoff(integrators=adapters.peers())``."""
    out = {}
    for make in (
        lambda: scipy_nquad(warped=warped),
        lambda: scipy_cubature("gk21", warped=warped),
        lambda: scipy_cubature("genz-malik", warped=warped),
        lambda: vegas_(warped=warped),
        lambda: qmcpy_(warped=warped),
    ):
        try:
            fn = make()
        except ImportError:
            continue
        out[fn.default_name] = fn
    return out
