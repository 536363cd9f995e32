"""Bring your own integrator: the quick accuracy-vs-time report with SciPy's
``integrate.nquad`` (QUADPACK, nested adaptive Gauss-Kronrod on the plain
(mu, phi) square) run beside the built-in integrators, on the same cases,
budgets and tolerances, into the same CSVs and summary.

    pip install ./python scipy          # or: pip install "./python[peers]"
    python python/examples/byo_integrator.py [OUT_DIR [CASE_SUBSTRING ...]]

(CI runs it on two cases: ``... target/tradeoff-byo-ci ggx-a0.3-to60 lambertian``.)

Prints the report's summary (as ``radiometry tradeoff --quick``), then, per
case and relative tolerance of the to-tolerance suite, the evaluations nquad
spent beside the built-in default's, with the true errors.
"""

import sys

import radiometry
from radiometry import adapters


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else None
    cases = sys.argv[2:] or None
    rows = radiometry.tradeoff(quick=True, out=out, cases=cases, integrators={"scipy-nquad": adapters.scipy_nquad()})
    mine = [r for r in rows if r["integrator"] == "scipy-nquad"]
    print(f"\nscipy-nquad: {len(mine)} fixed-budget rows in {rows.out}/tradeoff.csv "
          f"(budgets below 441 = 21 x 21 declined: {len(rows.skipped)} runs)")
    tol = rows.tolerance
    if not tol:
        print("(this build's report writes no tolerance.csv; harness rows:)")
        for r in rows.external:
            if r["tol"] is not None:
                print(f"  {r['case']:28} tol {r['tol']:.1e}: {r['evaluations']:9,} evaluations, {r['stopped']}")
        return 0 if mine else 1
    builtin = "auto" if any(r["integrator"] == "auto" for r in tol) else "adaptive-warped"
    by = {(r["case"], r["integrator"], r["rel_tol"]): r for r in tol}
    print(f"\nTo tolerance: evaluations (true relative error), scipy-nquad vs {builtin}")
    print(f"{'case':28} {'rel tol':>8} {'scipy-nquad':>24} {builtin:>24}")
    for case, integ, rel in sorted({k for k in by if k[1] == "scipy-nquad"}, key=lambda k: (k[0], -k[2])):
        cells = []
        for name in ("scipy-nquad", builtin):
            r = by.get((case, name, rel))
            cells.append("-" if r is None else f"{r['evaluations']:,} ({r['rel_error']:.1e})")
        print(f"{case:28} {rel:8.0e} {cells[0]:>24} {cells[1]:>24}")
    return 0 if mine else 1


if __name__ == "__main__":
    sys.exit(main())
