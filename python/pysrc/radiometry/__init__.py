"""Radiometry and BRDFs from Rust.

BRDF eval/pdf/sample on NumPy arrays (``Brdf``), directional albedo with
quadrature and Monte Carlo integrators, irradiance from light specs, and the
accuracy-vs-time report of ``radiometry tradeoff`` (``tradeoff``), into which
integrators written in Python can be brought (``tradeoff(integrators={...})``,
``radiometry.adapters`` for SciPy, vegas and qmcpy).

>>> import numpy as np, radiometry
>>> ggx = radiometry.Brdf("ggx(alpha=1)")
>>> ggx.albedo(0.0)["value"]            # 1 - ln 2 = 0.3069
>>> f = ggx.eval(np.array([[0, 0, 1.0]]), np.array([[0, 0, 1.0]]))   # 1/(4 pi)

The compiled part is ``radiometry._native`` (PyO3); this package re-exports it.
"""

from . import _native
from ._native import (
    BRDF_SPEC_HELP,
    DEFAULT_SEED,
    FULL_BUDGETS,
    LIGHT_SPEC_HELP,
    QUICK_BUDGETS,
    TOL_TARGETS,
    Brdf,
    CaseIntegrand,
    EvaluationLimitError,
    Integrand,
    __version__,
    case_names,
    integrators,
    irradiance,
    report_methods,
    tolerance_for,
)
from ._harness import (
    DEFAULT_MAX_EVALUATIONS,
    IntegratorError,
    TradeoffRows,
    measure,
    tradeoff,
)
from . import adapters

__all__ = [
    "BRDF_SPEC_HELP",
    "DEFAULT_MAX_EVALUATIONS",
    "DEFAULT_SEED",
    "FULL_BUDGETS",
    "LIGHT_SPEC_HELP",
    "QUICK_BUDGETS",
    "TOL_TARGETS",
    "Brdf",
    "CaseIntegrand",
    "EvaluationLimitError",
    "Integrand",
    "IntegratorError",
    "TradeoffRows",
    "adapters",
    "case_names",
    "integrators",
    "irradiance",
    "measure",
    "report_methods",
    "tolerance_for",
    "tradeoff",
]
