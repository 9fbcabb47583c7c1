"""The results of the 3-D chain's analyses (``beam.model = "chain3d"``): the library's outcome
(``flexwing::analysis::chain3d``) with the names of the CLI's JSON, and NumPy arrays of the 3-D
data as properties: node positions ``x, y, z`` and each element's section rotation vector.

Units are SI: m, rad, s, N. Node arrays have ``n + 1`` rows (0 = clamp), element arrays ``n``;
the last axis of a position or rotation is ``(x, y, z)``.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Dict, List, Optional

import numpy as np

from ._base import _Result, _Run, _Runs, _summary

__all__ = [
    "Chain3dModesResult",
    "Chain3dStaticResult",
    "Chain3dAeroStaticResult",
    "Chain3dFlutterResult",
    "Chain3dStudyResult",
    "Chain3dDynamicRun",
    "Chain3dDynamicResult",
]


def _speed(point: Optional[Dict[str, Any]], key: str = "speed") -> float:
    return float("nan") if point is None else float(point[key])


@dataclass(eq=False, repr=False)
class Chain3dModesResult(_Result):
    """Natural modes of the 3-D chain about its undeformed state, by increasing frequency.

    Attributes:
        modes: one dict per mode: ``mode``, ``omega`` (rad/s), ``frequency_hz``,
            ``energy_fraction`` (``twist``, ``lag``, ``flap``: shares of the strain energy),
            ``displacement`` (node displacements per unit modal amplitude, mass normalized, m,
            ``(n + 1, 3)``), ``rotation`` (element rotations, rad, ``(n, 3)``).
        shape: the undeformed chain: ``span`` (m), ``position`` (m), ``rotation`` (rad).
        n_elements, n_dofs: size of the chain (``3 n`` coordinates).
        rust_time_s: wall time of the analysis on the Rust side (s).

    Properties ``omega`` ``(k,)``, ``position`` ``(n + 1, 3)``, ``displacement``
    ``(k, n + 1, 3)`` and ``rotation`` ``(k, n, 3)`` are NumPy arrays of the same data.
    """

    _kind = "chain3d-modes"

    modes: List[Dict[str, Any]]
    shape: Dict[str, Any]
    n_elements: int
    n_dofs: int
    rust_time_s: float
    extra: Dict[str, Any] = field(default_factory=dict)

    @property
    def omega(self) -> np.ndarray:
        """Circular frequencies (rad/s), ``(k,)``."""
        return np.array([m["omega"] for m in self.modes], dtype=float)

    @property
    def position(self) -> np.ndarray:
        """Undeformed node positions (m), ``(n + 1, 3)``."""
        return np.array(self.shape["position"], dtype=float)

    @property
    def displacement(self) -> np.ndarray:
        """Mode shapes: node displacements (m per unit modal amplitude), ``(k, n + 1, 3)``."""
        return np.array([m["displacement"] for m in self.modes], dtype=float)

    @property
    def rotation(self) -> np.ndarray:
        """Mode shapes: element rotations (rad per unit modal amplitude), ``(k, n, 3)``."""
        return np.array([m["rotation"] for m in self.modes], dtype=float)

    def write_vtk(self, folder) -> str:
        """Write the mode shapes to ``folder`` for ParaView, as ``flexwing modes --vtk`` does
        on the 3-D chain: ``modes_0000.vtu``, … (the undeformed nodes as points, point data
        ``displacement`` (m per unit modal amplitude: Warp By Vector) and ``rotation``) and
        ``modes.pvd`` whose times are the mode numbers. Returns the ``.pvd`` path."""
        from ._files import _spatial_vtk

        numbers = np.array([m["mode"] for m in self.modes], dtype=float)
        return _spatial_vtk(folder, "modes", numbers, self.displacement, self.rotation, self.position, modes=True)

    def __repr__(self) -> str:
        return _summary(self, ["n_elements", "n_dofs"]) + f" with {len(self.modes)} modes"


@dataclass(eq=False, repr=False)
class Chain3dStaticResult(_Result):
    """Non-linear static equilibria of the 3-D chain over the load sweep.

    Attributes:
        points: one dict per converged point: ``scale``, ``scales``, ``shape`` (``span``,
            ``position`` (m), ``rotation`` (rad)), ``q`` (joint rotations), ``stable``,
            ``stats``.
        status: how the sweep ended: ``status``, ``stop``, ``message``.
        loaded_modes: the modes about the last equilibrium (as ``Chain3dModesResult.modes``), or
            ``None``; loaded_modes_status: how their computation ended.
        dofs: coordinates of the chain; wall_time_s: wall time of the solve (s).
        reference: the undeformed node positions (m), ``(n + 1, 3)``.
        n_elements, n_dofs: size of the chain.
        rust_time_s: wall time of the analysis on the Rust side (s).

    Properties ``scale`` ``(p,)``, ``tip`` ``(p, 3)``, ``position`` ``(p, n + 1, 3)`` and
    ``rotation`` ``(p, n, 3)`` are NumPy arrays of the same data.
    """

    _kind = "chain3d-static"

    points: List[Dict[str, Any]]
    status: Dict[str, Any]
    loaded_modes: Optional[List[Dict[str, Any]]]
    loaded_modes_status: Dict[str, Any]
    dofs: int
    wall_time_s: float
    reference: List[List[float]]
    n_elements: int
    n_dofs: int
    rust_time_s: float
    extra: Dict[str, Any] = field(default_factory=dict)

    def write_vtk(self, folder) -> str:
        """Write the equilibria to ``folder`` for ParaView, as ``flexwing static --vtk`` does on
        the 3-D chain: ``static_full_0000.vtu``, … one per load step (points, lines,
        ``displacement``, ``rotation``, ``t``, ``n``, ``c`` as ``Chain3dDynamicResult.write_vtk``)
        and ``static_full.pvd`` whose times are the load scales (or 1, 2, … when they do not
        increase). Returns the ``.pvd`` path."""
        from ._files import _spatial_vtk, _step_times

        return _spatial_vtk(folder, "static_full", _step_times(self.scale), self.position, self.rotation,
                            self.reference)

    @property
    def scale(self) -> np.ndarray:
        """Scale of the swept load at each point, ``(p,)``."""
        return np.array([p["scale"] for p in self.points], dtype=float)

    @property
    def position(self) -> np.ndarray:
        """Node positions (m), ``(p, n + 1, 3)``."""
        return np.array([p["shape"]["position"] for p in self.points], dtype=float)

    @property
    def rotation(self) -> np.ndarray:
        """Element section rotation vectors (rad), ``(p, n, 3)``."""
        return np.array([p["shape"]["rotation"] for p in self.points], dtype=float)

    @property
    def tip(self) -> np.ndarray:
        """Tip positions (m), ``(p, 3)``."""
        return self.position[:, -1, :] if self.points else np.zeros((0, 3))

    def __repr__(self) -> str:
        return _summary(self, ["n_elements", "n_dofs"]) + f" with {len(self.points)} points"


class _Equilibria:
    """The arrays of a result's static aeroelastic ``equilibria`` and its ``divergence``."""

    @property
    def divergence_speed(self) -> float:
        """The divergence speed (m/s), NaN if none."""
        return _speed(self.divergence)

    @property
    def speed(self) -> np.ndarray:
        """The speeds of the equilibria (m/s), ``(k,)``."""
        return np.array([e["speed"] for e in self.equilibria], dtype=float)

    @property
    def tip(self) -> np.ndarray:
        """Tip displacements of the equilibria (m), ``(k, 3)``."""
        return np.array([e["tip"] for e in self.equilibria], dtype=float).reshape(-1, 3)

    @property
    def position(self) -> np.ndarray:
        """Node positions of the equilibria (m), ``(k, n + 1, 3)``."""
        return np.array([e["shape"]["position"] for e in self.equilibria], dtype=float)


@dataclass(eq=False, repr=False)
class Chain3dAeroStaticResult(_Equilibria, _Result):
    """Static aeroelastic equilibria of the 3-D chain (``[aero]``, steady strip theory on the
    deformed geometry) at ``aero.flight.speed`` or along ``[aero.sweep]``, with the divergence
    speed.

    Attributes:
        equilibria: one dict per speed reached, as ``Chain3dFlutterResult.equilibria``: ``speed``
            (m/s), ``dynamic_pressure`` (Pa), ``tip`` (tip displacement, m), ``tip_twist``
            (rad), ``lift`` (N), ``strip_lift`` (each strip's vertical force, N),
            ``divergence_pressure`` (Pa), ``shape`` (``span``, ``position``, ``rotation``).
        strip_span: each strip's mid-station along the reference axis (m).
        divergence: the divergence point (``speed``, m/s) or ``None``.
        status: whether every speed was reached (``status``, ``stop``, ``message``; past the
            divergence speed the sweep stops).
        dofs: coordinates of the chain; wall_time_s: wall time of the analysis (s).
        n_elements, n_dofs: size of the chain.
        rust_time_s: wall time of the analysis on the Rust side (s).

    Properties ``divergence_speed`` (NaN when there is none), ``speed`` ``(k,)``, ``tip``
    ``(k, 3)``, ``tip_twist`` and ``lift`` ``(k,)``, ``strip_lift`` ``(k, strips)`` and
    ``position`` ``(k, n + 1, 3)``.
    """

    _kind = "chain3d-aero-static"

    equilibria: List[Dict[str, Any]]
    strip_span: List[float]
    divergence: Optional[Dict[str, Any]]
    status: Dict[str, Any]
    dofs: int
    wall_time_s: float
    n_elements: int
    n_dofs: int
    rust_time_s: float
    extra: Dict[str, Any] = field(default_factory=dict)

    @property
    def tip_twist(self) -> np.ndarray:
        """Tip twists of the equilibria (rad, nose-up), ``(k,)``."""
        return np.array([e["tip_twist"] for e in self.equilibria], dtype=float)

    @property
    def lift(self) -> np.ndarray:
        """Total vertical aerodynamic force of the equilibria (N), ``(k,)``."""
        return np.array([e["lift"] for e in self.equilibria], dtype=float)

    @property
    def strip_lift(self) -> np.ndarray:
        """Each strip's vertical aerodynamic force (N), ``(k, strips)``."""
        return np.array([e["strip_lift"] for e in self.equilibria], dtype=float).reshape(
            len(self.equilibria), len(self.strip_span)
        )

    def __repr__(self) -> str:
        return _summary(self, ["n_elements", "n_dofs"]) + f", divergence {self.divergence_speed:.4g} m/s"


@dataclass(eq=False, repr=False)
class Chain3dFlutterResult(_Equilibria, _Result):
    """Flutter and divergence of the 3-D chain about its deformed equilibria along the speeds.

    Attributes:
        equilibria: one dict per speed reached: ``speed`` (m/s), ``dynamic_pressure`` (Pa),
            ``tip`` (tip displacement, m), ``tip_twist`` (rad), ``lift`` (N), ``strip_lift``
            (each strip's vertical force, N), ``divergence_pressure`` (Pa), ``shape``
            (``span``, ``position``, ``rotation``).
        divergence: the divergence point (``speed``, m/s) or ``None``.
        equilibria_status: how the equilibria ended (past divergence they stop).
        stability: the eigen-analysis: ``method``, ``speeds``, ``branches`` (``mode``,
            ``wet_frequency``, ``real``, ``imag``), ``flutter`` (``speed``, ``frequency``) or
            ``None``, ``unstable_at_start``, ``status``, ``wall_time_s``.
        pk: the p-k check (as ``stability``) or ``None``.
        notes: advice as data (equilibria that stopped, branches unstable from the start).
        dofs: coordinates of the chain; wall_time_s: wall time of the analysis (s).
        n_elements, n_dofs: size of the chain.
        rust_time_s: wall time of the analysis on the Rust side (s).

    Properties ``flutter_speed``, ``flutter_frequency``, ``divergence_speed`` (NaN when there is
    none), ``speed`` ``(k,)``, ``tip`` ``(k, 3)`` and ``position`` ``(k, n + 1, 3)``.
    """

    _kind = "chain3d-flutter"

    equilibria: List[Dict[str, Any]]
    divergence: Optional[Dict[str, Any]]
    equilibria_status: Dict[str, Any]
    stability: Dict[str, Any]
    pk: Optional[Dict[str, Any]]
    notes: List[Dict[str, Any]]
    dofs: int
    wall_time_s: float
    n_elements: int
    n_dofs: int
    rust_time_s: float
    extra: Dict[str, Any] = field(default_factory=dict)

    @property
    def flutter_speed(self) -> float:
        """The flutter speed of the eigen-analysis (m/s), NaN if none."""
        return _speed(self.stability["flutter"])

    @property
    def flutter_frequency(self) -> float:
        """The flutter frequency (rad/s), NaN if none."""
        return _speed(self.stability["flutter"], "frequency")

    def __repr__(self) -> str:
        return _summary(self, ["n_elements", "n_dofs"]) + f", flutter {self.flutter_speed:.4g} m/s"


@dataclass(eq=False, repr=False)
class Chain3dStudyResult(_Result):
    """Flutter and divergence of the 3-D chain against a load level (``[flutter.study]``).

    Attributes:
        parameter: ``"tip-force"``, ``"gravity-factor"`` or ``"root-angle"``.
        points: one dict per level: ``level``, ``tip`` (tip displacement at rest, m),
            ``tip_twist`` (rad), ``tip_at_flutter`` (m, or ``None``), ``flutter`` (``speed``,
            ``frequency``) or ``None``, ``divergence`` (``speed``) or ``None``, ``status``.
        undeformed: the undeformed wing's flutter point (what the planar model gives at every
            level), or ``None``.
        status: whether every level ran (``status``, ``stop``, ``message``).
        wall_time_s: wall time of the study (s).
        n_elements, n_dofs: size of the chain.
        rust_time_s: wall time of the analysis on the Rust side (s).

    Properties ``level``, ``flutter_speed``, ``flutter_frequency``, ``divergence_speed``
    ``(L,)`` (NaN where there is none) and ``tip`` ``(L, 3)``.
    """

    _kind = "chain3d-study"

    parameter: str
    points: List[Dict[str, Any]]
    undeformed: Optional[Dict[str, Any]]
    status: Dict[str, Any]
    wall_time_s: float
    n_elements: int
    n_dofs: int
    rust_time_s: float
    extra: Dict[str, Any] = field(default_factory=dict)

    @property
    def level(self) -> np.ndarray:
        """The levels, ``(L,)``."""
        return np.array([p["level"] for p in self.points], dtype=float)

    @property
    def tip(self) -> np.ndarray:
        """Tip displacements at rest (m), ``(L, 3)``."""
        return np.array([p["tip"] for p in self.points], dtype=float).reshape(-1, 3)

    @property
    def flutter_speed(self) -> np.ndarray:
        """Flutter speeds (m/s), ``(L,)``."""
        return np.array([_speed(p["flutter"]) for p in self.points])

    @property
    def flutter_frequency(self) -> np.ndarray:
        """Flutter frequencies (rad/s), ``(L,)``."""
        return np.array([_speed(p["flutter"], "frequency") for p in self.points])

    @property
    def divergence_speed(self) -> np.ndarray:
        """Divergence speeds (m/s), ``(L,)``."""
        return np.array([_speed(p["divergence"]) for p in self.points])

    def __repr__(self) -> str:
        return _summary(self, ["parameter", "n_elements"]) + f" with {len(self.points)} levels"


@dataclass(eq=False, repr=False)
class Chain3dDynamicRun(_Run):
    """The simulation of one model of the 3-D chain, up to where it stopped (the planar
    :class:`flexwing.DynamicRun`'s fields, with the 3-D tip).

    Attributes:
        label, kind, modes, dofs, integrator, gyroscopic, stats, wall_time_s, status, stop,
            message, energy_audit, notes: as ``DynamicRun``'s.
        t: output times reached (s), ``(T,)``.
        tip_x, tip_y, tip_z: tip position (m), ``(T,)``.
        tip_rotation: the tip element's section rotation vector (rad, global components),
            ``(T, 3)``.
        kinetic, strain, total, work, dissipated (J), balance_error: as ``DynamicRun``'s.
        snapshots: one dict per snapshot: ``index``, ``t`` (s), ``shape`` (``span``,
            ``position`` (m), ``rotation`` (rad)).
        max_tip_difference: ``max_t |tip − tip_first|`` (m) from the first model, or ``None``.

    Properties ``snapshot_t`` ``(S,)``, ``position`` ``(S, n + 1, 3)`` and ``rotation``
    ``(S, n, 3)`` are NumPy arrays of the snapshots.
    """

    _axis = "time"
    _coord = "t"
    _columns = ("t", "tip_x", "tip_y", "tip_z", "kinetic", "strain", "total", "work", "dissipated", "balance_error")
    _grids = {"tip_rotation": "component"}

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
    tip_z: np.ndarray
    tip_rotation: np.ndarray
    kinetic: np.ndarray
    strain: np.ndarray
    total: np.ndarray
    work: np.ndarray
    dissipated: np.ndarray
    balance_error: np.ndarray
    energy_audit: Optional[Dict[str, Any]]
    snapshots: List[Dict[str, Any]]
    max_tip_difference: Optional[float]
    notes: List[Dict[str, Any]]
    extra: Dict[str, Any] = field(default_factory=dict)

    @property
    def snapshot_t(self) -> np.ndarray:
        """Times of the snapshots (s), ``(S,)``."""
        return np.array([s["t"] for s in self.snapshots], dtype=float)

    @property
    def position(self) -> np.ndarray:
        """Node positions at the snapshots (m), ``(S, n + 1, 3)``."""
        return np.array([s["shape"]["position"] for s in self.snapshots], dtype=float)

    @property
    def rotation(self) -> np.ndarray:
        """Element section rotation vectors at the snapshots (rad), ``(S, n, 3)``."""
        return np.array([s["shape"]["rotation"] for s in self.snapshots], dtype=float)

    def __repr__(self) -> str:
        return _summary(self, ["label", "status"]) + f" [{len(self.t)} output times]"


@dataclass(eq=False, repr=False)
class Chain3dDynamicResult(_Runs):
    """What a dynamic run of the 3-D chain produced.

    Attributes:
        runs: one :class:`Chain3dDynamicRun` per model: full, simplified, then the reduced
            models.
        status: the worst of the runs' (``"complete"``, ``"suspect"``, ``"stopped"``).
        end_time: the simulated time (s).
        reference: the undeformed node positions (m), ``(n + 1, 3)``.
        n_elements, n_dofs: size of the chain.
        rust_time_s: wall time of the analysis on the Rust side (s).
    """

    _kind = "chain3d-dynamic"
    _nested = {"runs": Chain3dDynamicRun}

    runs: List[Chain3dDynamicRun]
    status: str
    end_time: float
    reference: List[List[float]]
    n_elements: int
    n_dofs: int
    rust_time_s: float
    extra: Dict[str, Any] = field(default_factory=dict)

    def write_vtk(self, folder) -> List[str]:
        """Write every run's snapshots to ``folder`` for ParaView, as ``flexwing dynamic
        --vtk`` does on the 3-D chain: ``dynamic_LABEL_0000.vtu``, … (the nodes at their
        deformed positions, the elements as lines; point data ``displacement`` (m, from the
        undeformed nodes), the section ``rotation`` vector (rad) and the section axes ``t``,
        ``n``, ``c``; node ``k`` carries the element inboard of it, the root node the first
        element's) and ``dynamic_LABEL.pvd`` with the snapshot times. Returns the ``.pvd``
        paths."""
        from ._files import _spatial_vtk

        return [
            _spatial_vtk(folder, f"dynamic_{r.label}", r.snapshot_t, r.position, r.rotation, self.reference)
            for r in self.runs
            if r.snapshots
        ]
