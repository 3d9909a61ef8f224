"""symembed from Python: meshes as numpy arrays in, maps and errors out; experiments as the
command line runs them, and their results as numpy arrays.

    import symembed
    map_ab, result = symembed.match(VA, FA, VB, FB)            # every stage at its default
    map_ab, result = symembed.match(VA, FA, VB, FB, {"pipeline.refine.type": "zoomout"})
    a = symembed.Shape(VA, FA); b = symembed.Shape(VB, FB)     # per-shape stages once
    map_ab, result = symembed.match(a, b)
    errors = symembed.geodesic_errors(VB, FB, map_ab, gt_a, gt_b)
    thresholds, fraction, auc = symembed.error_curve(errors)
    out, ok = symembed.run("configs/quickstart.yaml", "results/q")
    results = symembed.load_results(out)
    symembed.stages()

The functions and classes of the C++ library are in the extension symembed._core (built by
CMake beside the binary, BUILD/python/symembed); docs/python.md is the guide.
"""

from ._core import (  # noqa: F401  (re-exported)
    ConfigError,
    Error,
    InternalError,
    InvalidInputError,
    IoError,
    MatchResult,
    Shape,
    SolverError,
    UsageError,
    error_curve,
    geodesic_errors,
    match,
    run,
    stages,
)
from .results import load_results  # noqa: F401

__all__ = [
    "ConfigError",
    "Error",
    "InternalError",
    "InvalidInputError",
    "IoError",
    "MatchResult",
    "Shape",
    "SolverError",
    "UsageError",
    "error_curve",
    "geodesic_errors",
    "load_results",
    "match",
    "run",
    "stages",
]
