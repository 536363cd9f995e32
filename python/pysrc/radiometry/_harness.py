"""The harness that runs integrators written in Python through the suites of
``radiometry tradeoff`` (``radiometry.tradeoff(integrators={...})``), locally
or as tasks on a Dask cluster, and hands their rows to the Rust report.

The harness measures; the report judges: it counts evaluations and wall time
itself and passes value, claimed error and status on unchanged; the Rust
report adds the reference, the true error and the summary.
"""

import hashlib
import math
import os
import sys
import time
import warnings
from concurrent.futures import ThreadPoolExecutor

from . import _native

#: The most integrand evaluations one run of a user integrator may spend
#: (2^23, twice the cap of the built-in tolerance driver, so that QUADPACK's
#: default ``limit=50`` nested twice, at most (21 * 99)^2 = 4.3 M points,
#: fits). A run that asks for more gets ``radiometry.EvaluationLimitError``
#: from the integrand and is listed in ``TradeoffRows.skipped``, no row.
DEFAULT_MAX_EVALUATIONS = 1 << 23

#: The fields of a harness row (those of the Rust ``tradeoff::ExternalRow``).
ROW_FIELDS = (
    "case",
    "integrator",
    "deterministic",
    "budget",
    "tol",
    "evaluations",
    "estimate",
    "error_estimate",
    "resolved",
    "status_reason",
    "stopped",
    "seconds",
)


class IntegratorError(RuntimeError):
    """A user integrator raised, or returned something outside the contract
    of ``radiometry.tradeoff`` (the message names the integrator, the case and
    the budget or tolerance; the original exception is the ``__cause__``)."""


class TradeoffRows(list):
    """What ``radiometry.tradeoff`` returns: a list of the rows of
    ``tradeoff.csv`` (dicts keyed by its columns), as before, with

    * ``tolerance``: the rows of ``tolerance.csv`` (the to-tolerance suite;
      empty when the report writes none),
    * ``external``: the rows the harness measured for the user integrators
      (dicts with the fields of ``ROW_FIELDS``; ``budget`` or ``tol`` set),
    * ``skipped``: runs of user integrators that wrote no row, as text
      (a declined budget or tolerance, an evaluation limit),
    * ``out``: the folder with the CSVs, ``summary.md`` and the plots.
    """

    def __init__(self, rows=(), tolerance=(), external=(), skipped=(), out=None):
        super().__init__(rows)
        self.tolerance = list(tolerance)
        self.external = list(external)
        self.skipped = list(skipped)
        self.out = out


def _clean(text):
    """Free text for a CSV field: no commas, no line breaks."""
    return " ".join(str(text).replace(",", ";").split())


def _seed_for(seed, case, name, budget, rel_tol):
    """A 63-bit seed fixed by (report seed, case, integrator, budget or
    tolerance): the same on every machine and in every process."""
    key = f"{seed}|{case}|{name}|{budget}|{rel_tol!r}".encode()
    return int.from_bytes(hashlib.blake2b(key, digest_size=8).digest(), "little") >> 1


def _where(name, case, budget, tol):
    at = f"budget {budget}" if budget is not None else f"tol {tol:.3g}"
    return f"integrator `{name}` on case `{case}` at {at}"


def _number(x, what, where):
    try:
        v = float(x)
    except (TypeError, ValueError) as e:
        raise IntegratorError(f"{where}: the {what} {x!r} is not a number") from e
    return v


def _status(s, where):
    """``(resolved, reason)`` from a returned status."""
    if s is None or s is True:
        return True, ""
    if s is False:
        return False, "integrator-flag"
    if isinstance(s, str):
        t = s.strip()
        if t == "resolved":
            return True, ""
        if t == "unresolved":
            return False, "integrator-flag"
        if t.startswith("unresolved:"):
            return False, _clean(t[len("unresolved:") :].strip()) or "integrator-flag"
    raise IntegratorError(
        f"{where}: status {s!r} is not one of True, False, 'resolved', 'unresolved' "
        "or 'unresolved: <reason>'"
    )


def parse_result(res, where, tol):
    """``(value, error, resolved, reason, stopped)`` from what a user
    integrator returned, or ``None`` (it declined the budget or tolerance).
    Raises ``IntegratorError`` outside the contract (see ``tradeoff``)."""
    if res is None:
        return None
    stopped = None
    if isinstance(res, dict):
        unknown = set(res) - {"value", "error", "status", "stopped"}
        if unknown or not {"value", "error"} <= set(res):
            raise IntegratorError(
                f"{where}: a dict result needs keys value, error (and optionally status, "
                f"stopped), got {sorted(res)}"
            )
        value, error, status = res["value"], res["error"], res.get("status")
        stopped = res.get("stopped")
    elif isinstance(res, (tuple, list)) and len(res) in (2, 3):
        value, error = res[0], res[1]
        status = res[2] if len(res) == 3 else None
    else:
        raise IntegratorError(
            f"{where}: expected (value, error), (value, error, status), a dict or None, "
            f"got {type(res).__name__} {res!r:.80}"
        )
    value = _number(value, "value", where)
    error = _number(error, "claimed error", where)
    if not math.isfinite(value):
        raise IntegratorError(f"{where}: returned the non-finite value {value}")
    if not (math.isfinite(error) and error >= 0.0):
        raise IntegratorError(
            f"{where}: returned the claimed error {error}: it must be finite and >= 0 "
            "(an integrator that cannot bound its error says so with status 'unresolved: <reason>')"
        )
    resolved, reason = _status(status, where)
    if tol is None:
        stopped = ""
    elif stopped is None:
        stopped = "tolerance reached" if error <= tol else "tolerance not reached"
    else:
        stopped = _clean(stopped)
    return value, error, resolved, reason, stopped


def run_one(fn, name, case, *, budget=None, tol=None, rel_tol=None, seed, max_evaluations):
    """One run of ``fn`` on ``case`` (a ``CaseIntegrand``): a harness row
    (dict of ``ROW_FIELDS``), or a string saying why there is none."""
    where = _where(name, case.name, budget, tol)
    g = _native.Integrand(
        case,
        max_evaluations=max_evaluations,
        seed=_seed_for(seed, case.name, name, budget, rel_tol),
    )
    t0 = time.perf_counter()
    try:
        res = fn(g, budget=budget, tol=tol)
    except _native.EvaluationLimitError as e:
        return f"{where}: {e}"
    except Exception as e:  # the user's code: re-raised with context
        raise IntegratorError(f"{where} raised {type(e).__name__}: {e}") from e
    seconds = time.perf_counter() - t0
    if g.evaluations > max_evaluations:
        # It caught the EvaluationLimitError and returned anyway.
        return f"{where}: {g.evaluations} evaluations asked for, more than the limit {max_evaluations}"
    parsed = parse_result(res, where, tol)
    if parsed is None:
        return f"{where}: declined"
    if g.evaluations == 0:
        raise IntegratorError(f"{where}: returned a value without evaluating the integrand")
    value, error, resolved, reason, stopped = parsed
    return {
        "case": case.name,
        "integrator": name,
        "deterministic": bool(getattr(fn, "deterministic", True)),
        "budget": budget,
        "tol": tol,
        "evaluations": g.evaluations,
        "estimate": value,
        "error_estimate": error,
        "resolved": resolved,
        "status_reason": reason,
        "stopped": stopped,
        "seconds": seconds,
    }


def case_tolerances(case_name, rel_tols):
    """``[(rel_tol, absolute tol)]`` of a case: the report's reference (an f64
    rule, computed once per process) times each relative tolerance."""
    if not rel_tols:
        return []
    ref, _bound = _native.CaseIntegrand(case_name).reference()
    return [(r, _native.tolerance_for(ref, r)) for r in rel_tols]


def run_task(case_name, name, fn, budgets, tolerances, seed, max_evaluations):
    """All runs of one integrator on one case: the budget ladder, then the
    tolerances (``[(rel_tol, tol)]``). Returns ``(rows, skipped)``. This is
    the unit of work of a Dask task (arguments and result are picklable;
    the integrand is rebuilt here from the case name)."""
    case = _native.CaseIntegrand(case_name)
    rows, skipped = [], []
    runs = [dict(budget=b) for b in budgets] + [dict(tol=t, rel_tol=r) for r, t in tolerances]
    for kw in runs:
        r = run_one(fn, name, case, seed=seed, max_evaluations=max_evaluations, **kw)
        (rows if isinstance(r, dict) else skipped).append(r)
    return rows, skipped


def _check_client(client):
    if not (hasattr(client, "submit") and hasattr(client, "gather")):
        raise TypeError(
            f"`client` must be a dask.distributed.Client (with submit and gather), got {type(client).__name__}"
        )


def measure(
    integrators,
    cases,
    *,
    budgets=(),
    tolerances=(),
    seed=_native.DEFAULT_SEED,
    max_evaluations=DEFAULT_MAX_EVALUATIONS,
    client=None,
    threads=None,
    progress=False,
):
    """Runs user integrators (a dict name -> fn, see ``tradeoff``) on the named
    cases over ``budgets`` and relative ``tolerances``, locally or on a Dask
    ``client`` (one task per case x integrator, after one reference task per
    case). Returns ``(rows, skipped)``: the harness rows in (case,
    integrator, budget, tolerance) order, identical for the local and the
    Dask run apart from ``seconds``, and the runs that wrote none."""
    named = list(integrators.items())
    cases = list(cases)
    tolerances = list(tolerances)
    if client is not None:
        _check_client(client)
        tols = {c: client.submit(case_tolerances, c, tolerances, pure=False) for c in cases}
        futures = [
            client.submit(run_task, c, n, fn, list(budgets), tols[c], seed, max_evaluations, pure=False)
            for c in cases
            for n, fn in named
        ]
        results = client.gather(futures)
    else:
        # The references (f64 rules in Rust, GIL released) in parallel.
        with ThreadPoolExecutor(max_workers=threads or 1) as ex:
            tols = dict(zip(cases, ex.map(lambda c: case_tolerances(c, tolerances), cases)))
        results = []
        for c in cases:
            for n, fn in named:
                if progress:
                    print(f"radiometry: {n} on {c}", file=sys.stderr, flush=True)
                results.append(run_task(c, n, fn, list(budgets), tols[c], seed, max_evaluations))
    rows = [r for rs, _ in results for r in rs]
    skipped = [s for _, ss in results for s in ss]
    return rows, skipped


def _split_integrators(integrators, builtins):
    """``(builtin filter, user dict)`` from the ``integrators`` and
    ``builtins`` arguments of ``tradeoff``."""
    if integrators is None:
        user, builtin_filter = {}, None
    elif isinstance(integrators, dict):
        user, builtin_filter = dict(integrators), None
    elif isinstance(integrators, str):
        raise TypeError("`integrators` must be a list of name substrings or a dict name -> fn, not a str")
    else:
        builtin_filter, user = list(integrators), {}
        if not all(isinstance(s, str) for s in builtin_filter):
            raise TypeError("`integrators` as a list filters the built-in integrators: give strings")
    if builtins is not None:
        if builtin_filter is not None:
            raise TypeError("give the built-in filter once: as `integrators=[...]` or as `builtins=[...]`")
        if isinstance(builtins, str) or not all(isinstance(s, str) for s in builtins):
            raise TypeError("`builtins` must be a list of name substrings")
        builtin_filter = list(builtins)
    reserved = set(_native.report_methods())
    for name, fn in user.items():
        if not isinstance(name, str) or not name or any(c in name for c in ",\n\r"):
            raise ValueError(f"user integrator name {name!r}: give a non-empty str without commas")
        if name in reserved:
            raise ValueError(f"user integrator name `{name}` is taken by a built-in method")
        if not callable(fn):
            raise TypeError(f"user integrator `{name}`: {fn!r} is not callable")
    return builtin_filter, user


def _select(names, filters):
    return [n for n in names if not filters or any(f in n for f in filters)]


def tradeoff(
    quick=True,
    out=None,
    threads=None,
    seed=_native.DEFAULT_SEED,
    progress=False,
    cases=None,
    integrators=None,
    *,
    builtins=None,
    budgets=None,
    tolerances=None,
    max_evaluations=DEFAULT_MAX_EVALUATIONS,
    client=None,
    peers_csv=None,
):
    """Runs the report of ``radiometry tradeoff`` (``quick``: the CI-sized
    suite), optionally with integrators written in Python beside the built-in
    ones, and returns its rows.

    Returns a ``TradeoffRows``: the list of the rows of ``tradeoff.csv``
    (dicts keyed by the CSV columns: case, integrator, budget, evaluations,
    estimate, reference, abs_error, rel_error, error_estimate, seconds,
    status, status_reason; numbers as numbers), as earlier versions did, with
    ``.tolerance`` (the rows of ``tolerance.csv``, the to-tolerance suite),
    ``.external`` (the rows the harness measured), ``.skipped`` and ``.out``.
    With user integrators the harness rows are also written as a peers file,
    ``peers_csv`` (default ``peers.csv`` in ``out``), which ``radiometry
    tradeoff --peers FILE`` merges into a report run from the command line.
    The CSVs, ``summary.md`` and the plots are written to ``out`` (default: a
    folder under the system temp dir); the summary is printed on stdout as by
    the CLI. ``cases``: keep only cases whose name contains one of these
    substrings (``radiometry.case_names()``; the CLI's ``--cases``). The Rust
    report runs on ``threads`` threads with the GIL released.

    ``integrators``: either a list of substrings, which keeps the built-in
    integrators whose name contains one (the CLI's ``--integrators``), or a
    dict ``{name: fn}`` of **user integrators**, run beside every built-in one
    (``builtins=[...]``: the substring filter of the built-in ones then).

    The user contract
    -----------------
    ``fn(integrand, budget=None, tol=None)`` is called once per run, with
    exactly one of

    * ``budget`` (int): a run of the fixed-budget ladder (``QUICK_BUDGETS`` or
      ``FULL_BUDGETS``; ``budgets=[...]`` picks a subset), aiming to spend
      about that many evaluations;
    * ``tol`` (float): a run of the to-tolerance suite, aiming at an absolute
      error <= ``tol``; ``tol = tolerance_for(reference, rel_tol)`` for each
      relative tolerance of ``TOL_TARGETS`` (``tolerances=[...]``: a subset).

    ``integrand`` (a ``radiometry.Integrand``) is the case's integrand on the
    unit square, the Jacobian folded in (the integral over [0, 1)^2 is the
    answer): ``integrand.plain(x)`` maps an (N, 2) float64 array to (N,)
    float64 on the hemisphere square (mu = cos theta_i, phi = 2 pi x1);
    ``integrand.warped(x)`` is the same pulled back through the case's
    sampling map (the BRDF's for albedo cases, uniform over the light's cap
    for product cases), or ``None``; ``.plain.at(a, b)`` and
    ``.warped.at(a, b)`` evaluate one point. Also ``integrand.seed`` (use it
    to seed a randomised method: rows then repeat exactly, also on Dask),
    ``integrand.max_evaluations``, ``case``, ``kind``, ``spec``,
    ``theta_o``. The **harness counts** every point evaluated (all calls,
    plain and warped), and times the call; nothing ``fn`` says about its
    own evaluation count is used.

    ``fn`` returns one of

    * ``(value, error)``: the estimate and its claimed error (>= 0; a
      standard error for Monte Carlo, a bound for quadrature), resolved;
    * ``(value, error, status)``: status ``"resolved"``, ``"unresolved"``,
      ``"unresolved: <reason>"`` (or ``True`` / ``False``) -- "unresolved"
      means "do not trust this error", as the built-in rows' status;
    * a dict with ``value``, ``error`` and optionally ``status`` and
      ``stopped`` (to-tolerance runs: why it stopped, e.g. ``"tolerance
      reached"``, ``"max budget reached"``; without it the harness writes
      ``"tolerance reached"`` when error <= tol, else ``"tolerance not
      reached"``);
    * ``None``: it declines this budget or tolerance (e.g. below its
      smallest rule): no row, listed in ``.skipped`` -- as a built-in
      integrator's refused budget.

    Set ``fn.deterministic = False`` on a randomised method (default True).

    Errors: an exception raised by ``fn``, a non-finite value, a non-finite
    or negative error, or a result outside this contract raises
    ``radiometry.IntegratorError`` naming the integrator, the case and the
    budget or tolerance (the original exception chained): a broken
    integrator stops the report rather than leaving a row that looks
    measured. A run that evaluates more than ``max_evaluations`` points
    (default ``DEFAULT_MAX_EVALUATIONS``) gets
    ``radiometry.EvaluationLimitError`` from the integrand and writes no
    row (listed in ``.skipped``). Unknown case names raise ``ValueError``.

    Example::

        import numpy as np
        import radiometry
        from radiometry import adapters

        def midpoint(integrand, budget=None, tol=None):
            if budget is None:
                return None                      # fixed budgets only
            n = int(budget ** 0.5)
            g = (np.arange(n) + 0.5) / n
            x = np.stack(np.meshgrid(g, g), -1).reshape(-1, 2)
            v = integrand.warped(x)
            return v.mean(), v.std() / n, "unresolved: no error estimate"

        rows = radiometry.tradeoff(quick=True, integrators={
            "midpoint-warped": midpoint,
            "scipy-nquad": adapters.scipy_nquad(),
        })
        nquad = [r for r in rows.tolerance if r["integrator"] == "scipy-nquad"]
        print(nquad[0]["evaluations"], nquad[0]["rel_error"])

    Dask
    ----
    ``client=dask.distributed.Client("tcp://scheduler:8786")`` (one line:
    pass the client of an existing cluster) runs the user integrators as
    tasks -- one task per case x integrator, after one reference task per
    case -- and returns the same rows as the local run (only ``seconds``
    differs): tasks carry case names and rebuild the integrands on the
    worker, ``fn`` is shipped with cloudpickle (closures and lambdas work),
    and randomised methods seeded from ``integrand.seed`` repeat exactly.
    The workers need ``radiometry`` (and the fn's libraries) installed. The
    built-in integrators and the report itself run locally (they are fast
    and multi-threaded). Dask rather than Ray: it is pure Python, installs
    with pip (``radiometry[dask]``), starts a loopback ``LocalCluster`` in a
    second for tests, and its ``distributed`` scheduler deploys where sweeps
    of this kind run -- SSH, HPC batch queues (dask-jobqueue: SLURM, PBS,
    SGE), Kubernetes -- without Ray's object store and daemons; the work is
    independent tasks with one dependency (the reference), which is what
    ``Client.submit`` does.
    """
    builtin_filter, user = _split_integrators(integrators, builtins)
    if client is not None:
        _check_client(client)
        if not user:
            raise ValueError("`client` runs user integrators: give `integrators={name: fn}`")
    ladder = list(_native.QUICK_BUDGETS if quick else _native.FULL_BUDGETS)
    if budgets is None:
        budgets = ladder
    elif not set(budgets) <= set(ladder):
        raise ValueError(f"`budgets` must be taken from the budget ladder {ladder}")
    if tolerances is None:
        tolerances = list(_native.TOL_TARGETS)
    elif not set(tolerances) <= set(_native.TOL_TARGETS):
        raise ValueError(f"`tolerances` must be taken from TOL_TARGETS {list(_native.TOL_TARGETS)}")
    if max_evaluations < 1:
        raise ValueError("`max_evaluations` must be >= 1")
    external, skipped = [], []
    if user:
        selected = _select(_native.case_names(quick), cases or [])
        if not selected:
            raise ValueError(f"the `cases` filter {cases!r} leaves no case (see radiometry.case_names())")
        external, skipped = measure(
            user,
            selected,
            budgets=sorted(budgets),
            tolerances=sorted(tolerances, reverse=True),
            seed=seed,
            max_evaluations=max_evaluations,
            client=client,
            threads=threads,
            progress=progress,
        )
        for s in skipped:
            if not s.endswith(": declined"):
                warnings.warn(f"radiometry.tradeoff: {s}", RuntimeWarning, stacklevel=2)
    if user and peers_csv is None:
        peers_csv = os.path.join(_native.default_out() if out is None else str(out), "peers.csv")
        os.makedirs(os.path.dirname(peers_csv), exist_ok=True)
    res = _native.tradeoff(
        quick=quick,
        out=None if out is None else str(out),
        threads=threads,
        seed=seed,
        progress=progress,
        cases=cases,
        integrators=builtin_filter,
        external=external,
        peers_csv=None if peers_csv is None else str(peers_csv),
    )
    return TradeoffRows(res["budget"], res["tolerance"], external, skipped, res["out"])
