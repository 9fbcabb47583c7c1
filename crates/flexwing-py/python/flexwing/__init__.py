"""flexwing: geometrically non-linear structural dynamics of very flexible wings and their
non-linear reduced-order models, from Python.

The case level (the case file's keys, as in ``docs/case-file.md``)::

    import flexwing
    case = flexwing.Case.load("examples/paper_sine.toml")
    result = case.dynamics()                      # full and reduced models
    run = result.run("reduced-r2")
    run.t, run.tip_y                              # NumPy arrays (s, m)

The aeroelastic analyses of a case with ``[aero]``::

    case = flexwing.Case.load("examples/patil_flutter.toml")
    f = case.flutter()                            # V-g/V-ω, flutter and divergence speeds
    f.full.flutter_speed, f.full.divergence_speed
    f.full.eigenvalues.damping_ratio              # (branches, speeds)

and ``case.statics()`` / ``case.dynamics()`` on such a case give the static aeroelastic
equilibria and the gust response.

The batch level: ``flexwing.solve_many(cases, "static")`` returns each case's status, result
and error as data (the unit of work of a Dask sweep, see ``examples/python/sweep_dask.py``).

Every result converts with ``to_pandas()`` and ``to_xarray()`` (and a batch with
``Batch.to_pandas(index=…)``), draws with ``plot()`` and shows as a table in a notebook; a tqdm
bar is ``progress=flexwing.tqdm_progress()``. pandas, xarray, matplotlib and tqdm are optional
extras (``pip install "flexwing[pandas,xarray,plot,tqdm]"``).

The model level: ``Beam``, ``FullModel``, ``ReducedModel``; ``model.equations(loads)`` for
the right-hand side, Jacobian and energies at a state; ``model.stepper(loads)`` to advance a
run one interval at a time with the loads set between calls.

Errors are ``FlexwingError`` and its subclasses (``InputError``, ``CaseFileError``,
``ArgumentTypeError``, ``SolverError``, ``ReentrancyError``, ``InternalError``). Units are
SI. The API reference is
``docs/python.md``.
"""

from ._errors import (
    ArgumentTypeError,
    CaseFileError,
    FlexwingError,
    InputError,
    InternalError,
    ReentrancyError,
    SolverError,
)
from ._native import (
    AeroStepper,
    Beam,
    Case,
    Equations,
    FullModel,
    ReducedModel,
    Stepper,
    __version__,
    solve_many,
)
from ._aero_results import (
    AeroDynamicResult,
    AeroDynamicRun,
    AeroStaticResult,
    AeroStaticRun,
    FlutterResult,
    FlutterRun,
    GustFamilyResult,
    GustFamilyRun,
    Stability,
)
from ._chain3d_results import (
    Chain3dAeroStaticResult,
    Chain3dDynamicResult,
    Chain3dDynamicRun,
    Chain3dFlutterResult,
    Chain3dModesResult,
    Chain3dStaticResult,
    Chain3dStudyResult,
)
from ._files import load_npz
from ._linear import LinearizeResult, LinearModel, TurbulenceResult, TurbulenceRun
from ._progress import tqdm_progress
from ._results import (
    Batch,
    BatchItem,
    DynamicResult,
    DynamicRun,
    ModesResult,
    StaticResult,
    StaticRun,
)

__all__ = [
    "Case",
    "Beam",
    "FullModel",
    "ReducedModel",
    "Equations",
    "Stepper",
    "AeroStepper",
    "solve_many",
    "solve",
    "ModesResult",
    "StaticRun",
    "StaticResult",
    "DynamicRun",
    "DynamicResult",
    "AeroStaticRun",
    "AeroStaticResult",
    "FlutterRun",
    "FlutterResult",
    "GustFamilyRun",
    "GustFamilyResult",
    "Stability",
    "AeroDynamicRun",
    "AeroDynamicResult",
    "LinearModel",
    "LinearizeResult",
    "TurbulenceRun",
    "TurbulenceResult",
    "Chain3dModesResult",
    "Chain3dStaticResult",
    "Chain3dAeroStaticResult",
    "Chain3dFlutterResult",
    "Chain3dStudyResult",
    "Chain3dDynamicResult",
    "Chain3dDynamicRun",
    "BatchItem",
    "Batch",
    "tqdm_progress",
    "load_npz",
    "FlexwingError",
    "InputError",
    "CaseFileError",
    "ArgumentTypeError",
    "SolverError",
    "ReentrancyError",
    "InternalError",
    "__version__",
]


def solve(case, analysis="static", index=None):
    """Solve one case as ``solve_many`` does: a :class:`BatchItem` with its status, result and
    error as data (never raises for the case's own failure). The function a Dask
    ``client.map`` maps over cases: ``client.map(flexwing.solve, cases, ["static"] * n,
    range(n))`` numbers them. ``index``: the item's ``index`` (the case's position in the
    caller's sweep), ``None`` if not given."""
    if index is None:
        item = solve_many([case], analysis)[0]
        item.index = None
        return item
    return solve_many([case], analysis, start=index)[0]
