"""The triangular-interpolant workbench from Python.

Fit triangular surface interpolants (Mann's modified Shirman–Séquin scheme and the others of
the workbench's registry) through meshes given as numpy arrays, read their control nets,
reports and G1 measurements, and tessellate them with exact curvature::

    import triwb
    V, F = triwb.read_mesh("bunny.ply")
    fit = triwb.fit(V, F, curves="optimized")
    fit.report["g1"]["exterior_max"]       # radians, as the command line reports it
    t = fit.tessellate(8)                  # V, F, normals, K, H, k1, k2, d1, d2
    fit.to_mesh("bunny.glb")

Every call runs the same library job as the command line (``experiments fit``), with the GIL
released; errors are :class:`WorkbenchError` (the job failed) and :class:`UsageError` (a
``ValueError``: a bad name, value or array), carrying the command line's messages.
``triwb.sweep`` runs the ``sweep`` experiment's grid on Dask.
"""

from ._triwb import (  # noqa: F401
    Fit,
    MeshData,
    UsageError,
    WorkbenchError,
    __version__,
    capsule,
    curve,
    curve_methods,
    curves,
    datasets,
    estimate,
    estimators,
    fit,
    octa,
    read_mesh,
    ring,
    schemes,
    solvers,
    sphere,
    write_mesh,
)

__all__ = [
    "Fit",
    "MeshData",
    "UsageError",
    "WorkbenchError",
    "__version__",
    "capsule",
    "curve",
    "curve_methods",
    "curves",
    "datasets",
    "estimate",
    "estimators",
    "fit",
    "octa",
    "read_mesh",
    "ring",
    "schemes",
    "solvers",
    "sphere",
    "write_mesh",
]
