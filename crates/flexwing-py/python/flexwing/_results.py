"""The results of the structural analyses (modes, statics, dynamics) and of a batch: plain
Python objects holding NumPy arrays (the base classes and how they are built: ``_base.py``).

Units are SI throughout: m, rad, s, N, J. Arrays over points or output times have that axis
first; node arrays have one column per node ``0 … n`` (0 = clamp).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Dict, List, Optional

import numpy as np

__all__ = [
    "ModesResult",
    "StaticRun",
    "StaticResult",
    "DynamicRun",
    "DynamicResult",
    "BatchItem",
    "Batch",
]


from ._base import _Result, _Run, _Runs, _summary
from ._files import _ModeFiles, _NodeFiles, _StaticFiles


@dataclass(eq=False, repr=False)
class ModesResult(_ModeFiles, _Result):
    """Natural modes of the full model about its undeformed state, by increasing frequency.

    Attributes:
        mode: mode numbers, 1-based, shape ``(k,)``.
        omega: circular frequencies (rad/s), ``(k,)``.
        frequency_hz: frequencies (Hz), ``(k,)``.
        bending_energy_fraction: share of the strain energy in the bending springs (1: pure bending,
            0: pure torsion), ``(k,)``.
        x: node stations along the undeformed span (m), ``(n + 1,)``.
        dx, dy: nodal displacements along global x and y per unit modal amplitude, mass
            normalized (m), ``(k, n + 1)``.
        twist: nodal twist per unit modal amplitude (rad), ``(k, n + 1)``; zeros without torsion.
        n_elements, n_dofs: size of the model.
        rust_time_s: wall time of the analysis on the Rust side (s), the interpreter released:
            the call's time beyond it is the binding's (argument checks, NumPy conversion).
    """

    _kind = "modes"

    mode: np.ndarray
    omega: np.ndarray
    frequency_hz: np.ndarray
    bending_energy_fraction: np.ndarray
    x: np.ndarray
    dx: np.ndarray
    dy: np.ndarray
    twist: np.ndarray
    n_elements: int
    n_dofs: int
    rust_time_s: float
    extra: Dict[str, Any] = field(default_factory=dict)

    status = "complete"

    def __repr__(self) -> str:
        return f"ModesResult({len(self.omega)} modes, omega={np.round(self.omega, 4)!r} rad/s)"


@dataclass(eq=False, repr=False)
class StaticRun(_Run):
    """The equilibria of one model over the points of a static analysis (one point without a
    sweep), up to where it stopped.

    Attributes:
        label: ``"full"``, ``"reduced-r2"`` (first 2 modes), ``"reduced-modes-1-2-4"``.
        kind: ``"full"`` or ``"reduced"``.
        modes: the retained modes of a reduced model (1-based), or ``None``.
        dofs: number of coordinates of the model.
        wall_time_s: wall time of the solve over all points (s).
        status: ``"complete"`` or ``"stopped"`` (more values may follow).
        stop: where and why the run stopped (``None`` if complete): a dict with ``"reason"``,
            ``"message"`` and the values it stopped at.
        message: the stop's one-line message, or ``None``.
        scale: scale of the swept load at each converged point, ``(p,)`` (1 without a sweep).
        scales: scales of all loads at each point, ``(p, loads)``.
        tip_x, tip_y: tip position (m), ``(p,)``; tip_twist: tip twist (rad), ``(p,)``.
        x, y: node positions (m), ``(p, n + 1)``; twist: nodal twist (rad), ``(p, n + 1)``.
        q: joint rotations of the full model (rad), ``(p, dofs of the full model)``.
        tip_difference: distance of the tip from the full model's at each point (m), ``(p,)``;
            reduced models run with the full model only, else ``None``.
        stats: solver counters per point, each ``(p,)``: ``load_steps``, ``rejected_steps``,
            ``iterations``, ``residual_evaluations``, ``factorizations``, ``residual_norm``.
    """

    _axis = "point"
    _coord = None
    _columns = ("scale", "tip_x", "tip_y", "tip_twist", "tip_difference")
    _grids = {"x": "node", "y": "node", "twist": "node", "q": "dof", "scales": "load"}

    label: str
    kind: str
    modes: Optional[List[int]]
    dofs: int
    wall_time_s: float
    status: str
    stop: Optional[Dict[str, Any]]
    message: Optional[str]
    scale: np.ndarray
    scales: np.ndarray
    tip_x: np.ndarray
    tip_y: np.ndarray
    tip_twist: np.ndarray
    x: np.ndarray
    y: np.ndarray
    twist: np.ndarray
    q: np.ndarray
    tip_difference: Optional[np.ndarray]
    stats: Dict[str, np.ndarray]
    extra: Dict[str, Any] = field(default_factory=dict)

    def __repr__(self) -> str:
        return _summary(self, ["label", "status"]) + f" [{len(self.scale)} points]"


@dataclass(eq=False, repr=False)
class StaticResult(_StaticFiles, _Runs):
    """What a static analysis found.

    Attributes:
        runs: one :class:`StaticRun` per model, full model first.
        loaded_modes: modes about the full model's last equilibrium, if asked for and found: a
            dict of arrays ``mode``, ``omega`` (rad/s), ``frequency_hz``, ``unloaded_omega``
            (rad/s, the same-numbered mode about the undeformed state); else ``None``.
        loaded_modes_error: why the loaded modes failed (a dict as ``StaticRun.stop``), or
            ``None``.
        status: ``"complete"`` if every model reached every point and the loaded modes (if
            asked for) were found, else ``"stopped"``.
        sweep_load: the index of the swept load, or ``None``.
        rust_time_s: wall time of the analysis on the Rust side (s), plan and every model
            included (see ``ModesResult.rust_time_s``).
    """

    _kind = "static"
    _nested = {"runs": StaticRun}

    runs: List[StaticRun]
    loaded_modes: Optional[Dict[str, np.ndarray]]
    loaded_modes_error: Optional[Dict[str, Any]]
    status: str
    sweep_load: Optional[int]
    rust_time_s: float
    extra: Dict[str, Any] = field(default_factory=dict)


@dataclass(eq=False, repr=False)
class DynamicRun(_Run):
    """The simulation of one model, up to where it stopped.

    Attributes:
        label: ``"full"``, ``"simplified"``, ``"reduced-r2"``, ``"reduced-modes-1-2-4"``.
        kind: ``"full"``, ``"simplified"`` or ``"reduced"``.
        modes: the retained modes of a reduced model (1-based), or ``None``.
        dofs: number of coordinates.
        integrator: the integrator's case-file name (``"radau"``, ``"bdf"``, …).
        gyroscopic: ``"exact"``, ``"finite-difference"`` or ``"neglected"``.
        stats: integrator counters: ``steps``, ``rejected_steps``, ``newton_failures`` (of the
            rejected steps, those whose Newton iteration failed), ``rhs_evaluations``,
            ``jacobian_evaluations``, ``factorizations``, ``newton_iterations``.
        wall_time_s: wall time of the integration (s).
        status: ``"complete"``, ``"suspect"`` (every output time reached, but the energy
            balance error exceeded its limit: see ``energy_audit``) or ``"stopped"`` (more
            values may follow).
        stop: where and why the run stopped or is suspect (``None`` if complete): a dict with
            ``"reason"`` (``"energy-balance"`` for a suspect run, with ``"time"``,
            ``"max_error"``, ``"max_error_time"``, ``"limit"``), ``"message"``, ``"time"`` (s)
            and the solver's values.
        message: the stop's one-line message, or ``None``.
        t: output times reached (s), ``(T,)``.
        tip_x, tip_y: tip position (m), ``(T,)``; tip_twist: tip twist (rad), ``(T,)``.
        kinetic, strain, total: energies (J), ``(T,)``.
        work: work of the applied loads since t = 0 (J), ``(T,)``; dissipated: energy
            dissipated by the structural damping since t = 0 (J), ``(T,)``.
        balance_error: the energy balance ``(H − H(0) − W + D) / E`` at each output time,
            relative to the largest energy held or given so far (positive: energy created),
            ``(T,)``. For the simplified model (no balance by construction) it is the energy
            its equations create.
        energy_audit: what the energy audit found over the accepted steps (``None`` if the run
            did not start): a dict of ``balanced`` (whether the model has an energy balance:
            all but the simplified model), ``max_error`` (largest ``|H − H(0) − W + D| / E``)
            and ``max_error_time`` (s), ``limit`` (the tolerance it is held to: ``[dynamic]
            energy_tolerance`` or its default tied to ``rtol``; ``None`` for the simplified
            model), ``exceeded_time`` (s, the first time the error passed ``limit``: the run is
            then ``"suspect"``), ``runaway_limit`` and ``runaway_time`` (s, when the run was
            stopped for creating energy), ``reference_energy`` (J, the E above).
        snapshots: deformed shapes at the chosen output times: a dict of ``index`` ``(S,)``,
            ``t`` ``(S,)``, and ``x``, ``y`` (m), ``twist`` (rad), each ``(S, n + 1)``.
        comparison: differences from the first model's tip history (not for the first model):
            a dict with ``max_tip_difference`` (m), ``relative_x``, ``relative_y``; or ``None``.
        notes: what made the run slow that its status does not show, as the CLI's ``note:``
            lines: dicts with ``kind`` (``"newton-failures"``: ``failed``, ``steps``,
            ``advice``) and ``message``.
    """

    _axis = "time"
    _coord = "t"
    _columns = ("t", "tip_x", "tip_y", "tip_twist", "kinetic", "strain", "total", "work", "dissipated", "balance_error")
    _grids = {}

    label: str
    kind: str
    modes: Optional[List[int]]
    dofs: int
    integrator: str
    gyroscopic: str
    stats: Dict[str, int]
    wall_time_s: float
    status: str
    stop: Optional[Dict[str, Any]]
    message: Optional[str]
    t: np.ndarray
    tip_x: np.ndarray
    tip_y: np.ndarray
    tip_twist: np.ndarray
    kinetic: np.ndarray
    strain: np.ndarray
    total: np.ndarray
    work: np.ndarray
    dissipated: np.ndarray
    balance_error: np.ndarray
    energy_audit: Optional[Dict[str, Any]]
    snapshots: Dict[str, np.ndarray]
    comparison: Optional[Dict[str, Optional[float]]]
    notes: List[Dict[str, Any]]
    extra: Dict[str, Any] = field(default_factory=dict)

    def __repr__(self) -> str:
        return _summary(self, ["label", "status"]) + f" [{len(self.t)} output times]"


@dataclass(eq=False, repr=False)
class DynamicResult(_NodeFiles, _Runs):
    """What a dynamic analysis produced.

    Attributes:
        runs: one :class:`DynamicRun` per model: full, simplified, then the reduced models.
        status: ``"complete"`` if every model reached every output time with its energy
            balance within its limit; else ``"stopped"`` if a model stopped, else
            ``"suspect"``.
        end_time: the simulated time (s).
        rust_time_s: wall time of the analysis on the Rust side (s), plan, modes and every
            model included (see ``ModesResult.rust_time_s``).
    """

    _kind = "dynamic"
    _nested = {"runs": DynamicRun}

    runs: List[DynamicRun]
    status: str
    end_time: float
    rust_time_s: float
    extra: Dict[str, Any] = field(default_factory=dict)


@dataclass(eq=False, repr=False)
class BatchItem(_Result):
    """The outcome of one case of :func:`flexwing.solve_many`.

    Attributes:
        index: the case's position in the input plus ``solve_many``'s ``start``; for
            ``flexwing.solve`` the ``index`` given, else ``None``.
        status: ``"complete"``, ``"suspect"`` (every model ran to the end but one's energy
            balance exceeded its limit), ``"stopped"`` (a model stopped; ``result`` holds what
            it reached), ``"interrupted"`` (the batch was stopped while the case ran: Ctrl-C or
            a raising progress callback) or ``"error"`` (bad input or a failed set-up;
            ``result`` is ``None``).
        result: the analysis result (``ModesResult``, ``StaticResult``, ``DynamicResult``,
            ``AeroStaticResult``, ``AeroDynamicResult``, ``FlutterResult``), or ``None``.
        error: the exception the case would have raised (a :class:`flexwing.FlexwingError`),
            or ``None``; it pickles, so it travels back from workers.
        message: the error's one-line message, or ``None``.
        wall_time_s: wall time of the case (s), set-up included.
    """

    _kind = "batch"

    index: Optional[int]
    status: str
    result: Any
    error: Optional[BaseException]
    message: Optional[str]
    wall_time_s: float
    extra: Dict[str, Any] = field(default_factory=dict)

    @property
    def complete(self) -> bool:
        return self.status == "complete"

    def unwrap(self):
        """The result, or raise the case's error."""
        if self.error is not None:
            raise self.error
        return self.result

    def __repr__(self) -> str:
        return _summary(self, ["index", "status", "message"])


class Batch(list):
    """What :func:`flexwing.solve_many` returns: a list of :class:`BatchItem`, in input order,
    with the views of a sweep.

    ``to_pandas(index=None)``: one row per case — ``status``, ``message``, ``wall_time_s`` and
    the scalars of its result, flat (the result's ``status``; per model, prefixed with its label,
    its scalars and the last value of each of its columns: ``full.tip_y`` at the last point or
    output time, ``full.flutter_speed``, ``full.divergence_speed``; a modal analysis'
    ``frequency_hz[k]``), NaN where a case has none; rows indexed by ``case`` (the items'
    ``index``) or by ``index``: labels of the swept parameters, one per item (a list, a list of
    tuples, or a ``pandas.Index``/``MultiIndex`` such as ``MultiIndex.from_product([forces,
    stiffnesses], names=["F", "EI"])``). ``to_xarray(index=None)``: the same as a dataset
    whose dimensions are the index' levels (a product sweep becomes a grid ``F × EI``). Units
    in ``frame.attrs["units"]`` and on each variable."""

    def to_pandas(self, index=None):
        from . import _frames

        return _frames.batch_frame(self, index)

    def to_xarray(self, index=None):
        from . import _frames

        return _frames.batch_dataset(self, index)

    def _repr_html_(self) -> str:
        from . import _html

        return _html.batch_html(self)

