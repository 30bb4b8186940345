"""bezjoin: smooth joins of Bezier curves, from Python, over the C ABI (ctypes).

Pure Python; no compiler at install. The shared library is found through
``BEZJOIN_LIBRARY``, then next to the package, then ``target/release/`` of
the repository holding the package (see :mod:`bezjoin._library`).

    >>> import bezjoin
    >>> with bezjoin.Curve([(0, 0), (1, 2), (3, 0)]) as c:
    ...     c.evaluate(0.5)
    (1.25, 1.0)
"""

from ._library import (
    ENVIRONMENT_VARIABLE,
    candidate_paths,
    find_library,
    library_path,
    library_version,
    status_name,
)
from ._connect import (
    AutoScaledConnection,
    BalancedConnection,
    GeometricConnection,
    connect,
    connect_auto_scale,
    connect_balanced_scale,
    connect_edges,
    connect_geometric,
    connect_points,
    connect_points_auto_scale,
)
from ._fillet import (
    DetailedRadiusFilletResult,
    DeviationFilletResult,
    FilletChainResult,
    FilletResult,
    Intersection,
    RadiusCornerReport,
    RadiusFilletChainResult,
    RadiusFilletResult,
    fillet,
    fillet_chain,
    fillet_deviation,
    fillet_radius,
    fillet_radius_chain,
    fillet_radius_detailed,
    fillet_vertex,
    intersect,
    intersect_detailed,
)
from ._lagrange import lagrange_spline, lagrange_spline_degree
from ._merge import ChainMergeResult, MergeResult, merge, merge_chain
from .curve import Curve
from .errors import STATUS_NAMES, BezjoinError, LibraryNotFoundError, UnsupportedGeometryError

__all__ = [
    "AutoScaledConnection",
    "BalancedConnection",
    "ENVIRONMENT_VARIABLE",
    "STATUS_NAMES",
    "BezjoinError",
    "ChainMergeResult",
    "Curve",
    "DetailedRadiusFilletResult",
    "DeviationFilletResult",
    "FilletChainResult",
    "FilletResult",
    "GeometricConnection",
    "Intersection",
    "LibraryNotFoundError",
    "MergeResult",
    "RadiusCornerReport",
    "RadiusFilletChainResult",
    "RadiusFilletResult",
    "UnsupportedGeometryError",
    "candidate_paths",
    "connect",
    "connect_auto_scale",
    "connect_balanced_scale",
    "connect_edges",
    "connect_geometric",
    "connect_points",
    "connect_points_auto_scale",
    "fillet",
    "fillet_chain",
    "fillet_deviation",
    "fillet_radius",
    "fillet_radius_chain",
    "fillet_radius_detailed",
    "fillet_vertex",
    "find_library",
    "intersect",
    "intersect_detailed",
    "lagrange_spline",
    "lagrange_spline_degree",
    "library_path",
    "library_version",
    "merge",
    "merge_chain",
    "status_name",
]
