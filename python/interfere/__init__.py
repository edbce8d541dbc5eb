"""interfere: exact, parallel clash detection for triangle meshes.

The compiled extension ``interfere._interfere`` holds everything; this package re-exports it.
numpy is required: point and index lists come back as numpy arrays (``HAVE_NUMPY`` is always
True, kept for older scripts). Type stubs ship with the package (``py.typed``). See docs/python.md.

    import interfere as itf
    a, b = itf.make_overlapping_spheres(20000)
    r = itf.clash(itf.make_model(a), itf.make_model(b))
    print(r.interference, len(r.pairs), r.regions[0].curve_length)
"""

try:
    import numpy as _numpy  # required: every point and index list is a numpy array
except ImportError as _e:  # pragma: no cover - exercised by the packaging test only
    raise ImportError(
        "interfere needs numpy, which could not be imported (" + str(_e) + "); install it: "
        "apt-get install python3-numpy, or pip install numpy"
    ) from _e
del _numpy

from ._interfere import bearing  # noqa: F401  (submodule: issue #4, docs/bearing.md)
from ._interfere import (  # noqa: F401
    HAVE_NUMPY,
    KIND_CROSS,
    KIND_TOUCH,
    ClashRegion,
    ClashResult,
    ClearancePair,
    DistanceResult,
    Error,
    InputError,
    MeshStats,
    Model,
    OutputError,
    Polyline,
    Transform,
    TriMesh,
    __version__,
    clash,
    distance,
    exact_fallback_count,
    make_box,
    make_model,
    make_overlapping_spheres,
    make_sphere,
    mesh_stats,
    read_mesh,
    submesh,
    transformed,
    weld_exact,
    write_mesh,
    write_polylines,
)

__all__ = [
    "HAVE_NUMPY",
    "KIND_CROSS",
    "KIND_TOUCH",
    "ClashRegion",
    "ClashResult",
    "ClearancePair",
    "DistanceResult",
    "Error",
    "InputError",
    "MeshStats",
    "Model",
    "OutputError",
    "Polyline",
    "Transform",
    "TriMesh",
    "__version__",
    "clash",
    "distance",
    "exact_fallback_count",
    "make_box",
    "make_model",
    "make_overlapping_spheres",
    "make_sphere",
    "mesh_stats",
    "read_mesh",
    "submesh",
    "transformed",
    "weld_exact",
    "write_mesh",
    "write_polylines",
]

from ._interfere import probe  # noqa: F401,E402  (issue #5: interfere.probe)
from ._interfere import cell  # noqa: F401,E402  (issue #28: interfere.cell)
# FEM models (docs/fem.md, "Python"): read_fem, generators, surface extraction, clash per step.
from ._interfere import (  # noqa: F401,E402
    FemMesh,
    clash_series,
    extract_surface,
    make_fem_box,
    make_fem_cylinder,
    make_fem_sphere,
    read_displacements_csv,
    read_fem,
)

__all__ += [
    "FemMesh",
    "clash_series",
    "extract_surface",
    "make_fem_box",
    "make_fem_cylinder",
    "make_fem_sphere",
    "read_displacements_csv",
    "read_fem",
]
# Simplification (issue #6) and, when built with OpenCASCADE, the CAD pipeline (docs/simplify.md).
from ._interfere import (  # noqa: F401,E402
    HAVE_CAD,
    SimplifyResult,
    count_self_intersections,
    distance_bound,
    hausdorff,
    read_error_bound,
    rebalanced_budgets,
    simplify,
    triangle_budgets,
    write_glb,
    write_tagged_mesh,
)

__all__ += ["HAVE_CAD", "SimplifyResult", "count_self_intersections", "distance_bound", "hausdorff",
            "read_error_bound", "rebalanced_budgets", "simplify", "triangle_budgets", "write_glb", "write_tagged_mesh"]
if HAVE_CAD:
    from ._interfere import assembly_clash, import_step, prepare_step, simplify_step, step_features  # noqa: F401,E402

    __all__ += ["assembly_clash", "import_step", "prepare_step", "simplify_step", "step_features"]
# Scenes (issue #24, docs/python.md "Scenes"): many bodies, clash tests, stable clash ids, baselines.
from ._interfere import Body, Clash, ClashReport, ClashTest, Scene  # noqa: F401,E402

__all__ += ["Body", "Clash", "ClashReport", "ClashTest", "Scene"]
