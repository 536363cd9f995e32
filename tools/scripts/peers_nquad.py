"""Measures SciPy's ``integrate.nquad`` (QUADPACK nested adaptive
Gauss-Kronrod on the plain (mu, phi) square) on the GGX albedo cases of the
report's to-tolerance suite, through the Python harness (the project's own
f32 integrands, evaluations counted by the harness), and writes the rows as a
peers file for ``radiometry tradeoff --peers FILE``:

    pip install ./python scipy
    python tools/scripts/peers_nquad.py cli/results/peers-scipy-nquad.csv
    cargo run --release -p radiometry-cli -- tradeoff --peers cli/results/peers-scipy-nquad.csv

The summary's "auto vs scipy-nquad" table compares, per GGX case at relative
tolerance 1e-6, auto's evaluations with nquad's cheapest run (any tolerance of
the suite) that is at least as accurate.
"""

import sys

import scipy

import radiometry
from radiometry import adapters


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "peers-scipy-nquad.csv"
    rows = radiometry.tradeoff(
        quick=False,
        cases=["ggx-a"],
        builtins=["auto"],
        budgets=[],
        integrators={"scipy-nquad": adapters.scipy_nquad()},
        peers_csv=out,
    )
    print(f"scipy {scipy.__version__}: {len(rows.external)} nquad rows written to {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
