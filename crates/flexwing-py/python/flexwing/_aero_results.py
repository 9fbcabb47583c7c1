"""The results of the aeroelastic analyses (docs/aeroelastic-model.md): static aeroelastic
equilibria and divergence (``Case.statics()`` on a case with ``[aero]``), flutter
(``Case.flutter()``), the aeroelastic response (``Case.dynamics()`` with ``[aero]``) and the
discrete gust family (``Case.gust_family()``). Plain
objects of NumPy arrays on the base classes of ``_base.py``: they pickle, print and convert to
dicts.

The numbers are those ``flexwing static``, ``flexwing flutter`` and ``flexwing dynamic`` print
and write for the same case file (the same plans and runs of ``flexwing::analysis::aero``).
Units are SI: m/s for speeds, rad/s for frequencies, 1/s for eigenvalues, Pa for dynamic
pressures, N for lift, N m for moments.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Dict, List, Optional

import numpy as np

from ._base import _Result, _Run, _Runs, _summary
from ._files import _NodeFiles

__all__ = [
    "AeroStaticRun",
    "AeroStaticResult",
    "Stability",
    "FlutterRun",
    "FlutterResult",
    "AeroDynamicRun",
    "AeroDynamicResult",
    "GustFamilyRun",
    "GustFamilyResult",
]

#: The outputs of a gust family, in order (the library's ``gust_family::OUTPUTS``).
GUST_OUTPUTS = ("tip_y", "tip_twist", "root_bending_moment", "root_torque", "lift")


@dataclass(eq=False, repr=False)
class AeroStaticRun(_Run):
    """The static aeroelastic equilibria of one model (steady strip theory) at the speeds of the
    analysis, up to where the sweep stopped, and the divergence speed where it found one.

    Attributes:
        label: ``"full"``, ``"reduced-r4"`` (first 4 wet modes), ``"reduced-modes-1-2-4"``.
        kind: ``"full"`` or ``"reduced"``.
        modes: the retained wet modes of a reduced model (1-based), or ``None``.
        dofs: number of coordinates of the model.
        wall_time_s: wall time of the sweep (s); ``None`` for the equilibria of a flutter run
            (timed with the run, ``FlutterRun.wall_time_s``).
        status: ``"complete"`` or ``"stopped"`` (past the divergence speed no stable
            equilibrium exists: the sweep stops there).
        stop: where and why it stopped (``None`` if complete): a dict with ``"reason"``
            (``"speed-point"``), ``"message"``, ``"point"``, ``"speed"`` (m/s), ``"error"``.
        message: the stop's one-line message, or ``None``.
        divergence_speed: the divergence speed (m/s) where the sweep brackets it (or, for
            equilibria that do not move the divergence pressure, from the frozen state), else
            ``None``.
        divergence_dynamic_pressure: its dynamic pressure (Pa), or ``None``.
        divergence_basis: how it was found: ``"bracketed"`` (a sign change of the frozen
            state's divergence pressure less the dynamic pressure between two speeds of the
            sweep, refined) or ``"undeformed"`` (every equilibrium undeformed: the linear
            divergence speed of the undeformed wing, wherever it lies); ``None`` if none.
        divergence_within_sweep: whether it lies within the speeds the sweep reached; an
            ``"undeformed"`` speed beyond them holds only while the wing stays undeformed (the
            CLI marks it ``*``); ``None`` if none.
        speed: free-stream speed at each equilibrium (m/s), ``(p,)``.
        dynamic_pressure: ``½ρU²`` (Pa), ``(p,)``.
        tip_x, tip_y: tip position (m), ``(p,)``; tip_twist: tip twist (rad, nose-up), ``(p,)``.
        lift: total aerodynamic force along the ground's vertical (N), ``(p,)``.
        root_bending_moment: the clamp spring's moment (N m), ``(p,)``.
        divergence_pressure: the dynamic pressure at which the equilibrium's frozen state
            diverges (Pa), a list of ``p`` values, ``None`` where no real mode diverges.
        x, y: node positions (m), ``(p, n + 1)``; twist: nodal twist (rad), ``(p, n + 1)``.
        q: joint rotations of the full model (rad), ``(p, dofs of the full model)``.
        hinge_moments: hinge moment of each control surface (N m, positive trailing edge down),
            ``(p, surfaces)`` in the order of ``aerodynamics["surfaces"]`` (``(p, 0)`` without
            surfaces).
        tip_difference: distance of the tip from the full model's at each speed (m), ``(p,)``;
            reduced models run with the full model only, else ``None``.
        stats: the static solver's counters per point, each ``(p,)`` (as ``StaticRun.stats``).
    """

    _axis = "speed"
    _coord = "speed"
    _columns = (
        "speed", "dynamic_pressure", "tip_x", "tip_y", "tip_twist", "lift", "root_bending_moment",
        "divergence_pressure", "tip_difference",
    )
    _grids = {"x": "node", "y": "node", "twist": "node", "q": "dof", "hinge_moments": "surface"}

    label: str
    kind: str
    modes: Optional[List[int]]
    dofs: int
    wall_time_s: Optional[float]
    status: str
    stop: Optional[Dict[str, Any]]
    message: Optional[str]
    divergence_speed: Optional[float]
    divergence_dynamic_pressure: Optional[float]
    divergence_basis: Optional[str]
    divergence_within_sweep: Optional[bool]
    speed: np.ndarray
    dynamic_pressure: np.ndarray
    tip_x: np.ndarray
    tip_y: np.ndarray
    tip_twist: np.ndarray
    lift: np.ndarray
    root_bending_moment: np.ndarray
    divergence_pressure: List[Optional[float]]
    x: np.ndarray
    y: np.ndarray
    twist: np.ndarray
    q: np.ndarray
    hinge_moments: np.ndarray
    tip_difference: Optional[np.ndarray]
    stats: Dict[str, np.ndarray]
    extra: Dict[str, Any] = field(default_factory=dict)

    def __repr__(self) -> str:
        return _summary(self, ["label", "status", "divergence_speed"]) + f" [{len(self.speed)} speeds]"


@dataclass(eq=False, repr=False)
class AeroStaticResult(_Runs):
    """What a static aeroelastic analysis found (``Case.statics()`` on a case with ``[aero]``).

    Attributes:
        runs: one :class:`AeroStaticRun` per model, full model first.
        speeds: the speeds asked for (m/s): ``aero.flight.speed`` or ``[aero.sweep]``.
        root_angle: root angle of attack (rad); gravity: ``aero.flight.gravity`` (m/s²) or
            ``None``.
        aerodynamics: ``{"model": "steady" | "quasi-steady" | "wagner" | "peters", "states":
            Peters' states per strip or None, "density": kg/m³}`` (the equilibria use steady
            strip theory whatever the model: a static equilibrium has no motion to lag).
        status: ``"complete"`` if every model reached every speed, else ``"stopped"``.
        rust_time_s: wall time of the analysis on the Rust side (s).
    """

    _kind = "aero-static"
    _nested = {"runs": AeroStaticRun}

    runs: List[AeroStaticRun]
    speeds: np.ndarray
    root_angle: float
    gravity: Optional[float]
    aerodynamics: Dict[str, Any]
    status: str
    rust_time_s: float
    extra: Dict[str, Any] = field(default_factory=dict)


@dataclass(eq=False, repr=False)
class Stability(_Result):
    """The eigen-analysis of one model along the speeds (the model's own aerodynamic lag), or
    the p-k check with Theodorsen's function: the tracked branches (V-g and V-ω data) and
    their crossings of the imaginary axis.

    Attributes:
        speeds: the speeds reached (m/s), ``(S,)``.
        mode: the wet mode each branch starts from at U = 0 (1-based by frequency), ``(B,)``.
        wet_frequency: its wet natural frequency at U = 0 (rad/s), ``(B,)``.
        real: ``σ = Re s`` per branch and speed (1/s; positive is unstable), ``(B, S)``.
        imag: ``ω = Im s`` (rad/s; 0 for a real, divergence-type root), ``(B, S)``.
        damping_ratio: ``ζ = −σ/|s|`` (V-g data), ``(B, S)``.
        uncertain: whether some step of a branch's tracking was accepted without passing the
            shape check (a coalescence), ``(B,)`` bool.
        flutter_speed, flutter_frequency: the lowest onset (m/s, rad/s; frequency 0 for
            dynamic divergence), or ``None`` when no branch becomes unstable in the sweep or
            one is unstable from its first speed (see ``unstable_at_start``).
        flutter_branch: the branch of that onset (index into the branch arrays), or ``None``.
        crossings: every crossing after the first speed, refined, by speed: a dict of
            ``kind`` (list of ``"onset"``/``"offset"``), ``speed`` (m/s), ``frequency``
            (rad/s), ``branch`` and ``mode`` (int), each of length C.
        unstable_at_start: branches (indices) already unstable at the first speed: no flutter
            speed exists within the sweep.
        stats: counters: ``linearizations``, ``newton_iterations``, ``halvings``, ``trials``
            (trial speeds of the branch tracking), ``static_solves``.
        wall_time_s: wall time of this eigen-analysis (s).
    """

    speeds: np.ndarray
    mode: np.ndarray
    wet_frequency: np.ndarray
    real: np.ndarray
    imag: np.ndarray
    damping_ratio: np.ndarray
    uncertain: np.ndarray
    flutter_speed: Optional[float]
    flutter_frequency: Optional[float]
    flutter_branch: Optional[int]
    crossings: Dict[str, Any]
    unstable_at_start: List[int]
    stats: Dict[str, int]
    wall_time_s: float
    extra: Dict[str, Any] = field(default_factory=dict)

    def __repr__(self) -> str:
        return (
            f"Stability({len(self.mode)} branches, {len(self.speeds)} speeds, "
            f"flutter_speed={self.flutter_speed!r})"
        )


@dataclass(eq=False, repr=False)
class FlutterRun(_Run):
    """The flutter analysis of one model: its static equilibria along the speeds, its
    eigen-analysis and, if asked (``[flutter] pk``), the p-k check.

    Attributes:
        label, kind, modes, dofs: as :class:`AeroStaticRun`.
        wall_time_s: wall time of the whole analysis of this model (s).
        status: ``"complete"`` if the eigen-analysis (and the p-k check) reached the last
            speed, else ``"stopped"``; the equilibria stopping past the divergence speed is
            expected and shows in ``equilibria.status`` only.
        stop, message: where and why it stopped (``None`` if complete); ``stop["reason"]`` is
            ``"flutter-equilibrium"`` or ``"flutter-branch-lost"``.
        other_stops: the p-k check's stop when the eigen-analysis stopped too (dicts).
        divergence_speed, divergence_dynamic_pressure: the static divergence speed (m/s) and
            pressure (Pa) found along the equilibria, or ``None``.
        divergence_basis, divergence_within_sweep: as :class:`AeroStaticRun`.
        flutter_speed, flutter_frequency: ``eigenvalues.flutter_speed`` (m/s) and
            ``eigenvalues.flutter_frequency`` (rad/s).
        eigenvalues: the model's own eigen-analysis, a :class:`Stability`.
        pk: the p-k check with Theodorsen's C(k), a :class:`Stability`, or ``None``.
        equilibria: the static equilibria along the speeds, an :class:`AeroStaticRun`.
        notes: what the numbers mean that the status does not show, as the CLI's ``note:``
            lines: dicts with ``kind`` (``"equilibria-stopped"`` with the ``stop``;
            ``"unstable-at-start"`` with ``pk``, ``mode``, ``wet_frequency``, ``speed``;
            ``"planar-deflection"`` with ``tip_deflection``, ``span``, ``speed``: the planar
            chain about a wing deflected by 2 % of the span or more) and ``message``.
    """

    _nested = {"eigenvalues": Stability, "pk": Stability, "equilibria": AeroStaticRun}
    # Its tables and datasets are those of its eigen-analysis (the V-g/V-ω data); the
    # equilibria and the p-k check have their own (run.equilibria.to_pandas(), run.pk…).
    _delegate = "eigenvalues"

    label: str
    kind: str
    modes: Optional[List[int]]
    dofs: int
    wall_time_s: float
    status: str
    stop: Optional[Dict[str, Any]]
    message: Optional[str]
    other_stops: List[Dict[str, Any]]
    divergence_speed: Optional[float]
    divergence_dynamic_pressure: Optional[float]
    divergence_basis: Optional[str]
    divergence_within_sweep: Optional[bool]
    flutter_speed: Optional[float]
    flutter_frequency: Optional[float]
    eigenvalues: Stability
    pk: Optional[Stability]
    equilibria: AeroStaticRun
    notes: List[Dict[str, Any]]
    extra: Dict[str, Any] = field(default_factory=dict)

    def __repr__(self) -> str:
        return _summary(self, ["label", "status", "flutter_speed", "divergence_speed"])


@dataclass(eq=False, repr=False)
class FlutterResult(_Runs):
    """What a flutter analysis found (``Case.flutter()``).

    Attributes:
        runs: one :class:`FlutterRun` per model, full model first.
        speeds: the speeds of ``[aero.sweep]`` (m/s).
        root_angle: root angle of attack (rad); gravity: m/s² or ``None``.
        aerodynamics: as ``AeroStaticResult.aerodynamics``.
        tolerance: relative tolerance of the flutter and divergence speeds.
        status: ``"complete"`` if every model's eigen-analysis reached the last speed, else
            ``"stopped"``.
        rust_time_s: wall time of the analysis on the Rust side (s).
    """

    _kind = "flutter"
    _nested = {"runs": FlutterRun}

    runs: List[FlutterRun]
    speeds: np.ndarray
    root_angle: float
    gravity: Optional[float]
    aerodynamics: Dict[str, Any]
    tolerance: float
    status: str
    rust_time_s: float
    extra: Dict[str, Any] = field(default_factory=dict)


@dataclass(eq=False, repr=False)
class AeroDynamicRun(_Run):
    """The aeroelastic response of one model, up to where it stopped.

    Attributes:
        label, kind, modes, dofs: as :class:`AeroStaticRun`.
        aero_states: number of aerodynamic (lag) states.
        integrator: the integrator's case-file name.
        stats: integrator counters (as ``DynamicRun.stats``).
        wall_time_s: wall time of the integration (s); ratio_to_first: over the first model's.
        status, stop, message: as ``DynamicRun`` (``stop["reason"]`` ``"initial-state"`` when
            the initial equilibrium was not found).
        t: output times reached (s), ``(T,)``.
        tip_x, tip_y: tip position (m); tip_twist: tip twist (rad, nose-up); each ``(T,)``.
        root_bending_moment: the clamp spring's moment (N m), ``(T,)``.
        lift: total aerodynamic force along the ground's vertical (N), ``(T,)``.
        speed: free-stream speed U(t) (m/s), ``(T,)``.
        kinetic: kinetic energy of the structure and the fluid's apparent mass (J); strain:
            strain energy (J); total: their sum; each ``(T,)``.
        work: work of the loads since t = 0 (J), ``(T,)``: the applied loads, gravity and the
            aerodynamic loads other than the apparent mass (circulatory, the non-circulatory
            velocity term, gust, changes of speed and root angle); dissipated: energy
            dissipated by the structural damping since t = 0 (J), ``(T,)``.
        balance_error: the energy balance ``(H − H(0) − W + D) / E`` at each output time, with
            ``H = total`` (the apparent mass included), relative to the largest energy held or
            given (positive: energy created), ``(T,)``.
        energy_audit: what the energy audit found over the accepted steps, as
            ``DynamicRun.energy_audit`` (``None`` if the run did not start). A run whose
            balance error exceeded ``limit`` is ``"suspect"``; one whose energy ran away is
            stopped (``stop["reason"] == "energy-runaway"``).
        snapshots: as ``DynamicRun.snapshots``.
        max_tip_difference: largest tip distance from the first model's (m), or ``None``.
        hinge_moments: hinge moment of each control surface (N m, positive trailing edge down:
            the deflection, flap-rate and circulatory terms, as the linear model's
            ``hinge_moment[NAME]``), ``(T, surfaces)`` in the order of
            ``aerodynamics["surfaces"]`` (``(T, 0)`` without surfaces).
    """

    _axis = "time"
    _coord = "t"
    _columns = (
        "t", "tip_x", "tip_y", "tip_twist", "root_bending_moment", "lift", "speed", "kinetic",
        "strain", "total", "work", "dissipated", "balance_error",
    )
    _grids = {"hinge_moments": "surface"}

    label: str
    kind: str
    modes: Optional[List[int]]
    dofs: int
    aero_states: int
    integrator: str
    stats: Dict[str, int]
    wall_time_s: float
    ratio_to_first: Optional[float]
    status: str
    stop: Optional[Dict[str, Any]]
    message: Optional[str]
    t: np.ndarray
    tip_x: np.ndarray
    tip_y: np.ndarray
    tip_twist: np.ndarray
    root_bending_moment: np.ndarray
    lift: np.ndarray
    speed: np.ndarray
    kinetic: np.ndarray
    strain: np.ndarray
    total: np.ndarray
    work: np.ndarray
    dissipated: np.ndarray
    balance_error: np.ndarray
    energy_audit: Optional[Dict[str, Any]]
    snapshots: Dict[str, np.ndarray]
    max_tip_difference: Optional[float]
    hinge_moments: np.ndarray
    extra: Dict[str, Any] = field(default_factory=dict)

    def __repr__(self) -> str:
        return _summary(self, ["label", "status"]) + f" [{len(self.t)} output times]"


@dataclass(eq=False, repr=False)
class AeroDynamicResult(_NodeFiles, _Runs):
    """What an aeroelastic response produced (``Case.dynamics()`` on a case with ``[aero]``).

    Attributes:
        runs: one :class:`AeroDynamicRun` per model: full, then the reduced models.
        status: ``"complete"`` if every model reached every output time with its energy balance
            within its limit, ``"suspect"`` if one's balance exceeded it, else ``"stopped"``.
        end_time: the simulated time (s).
        aerodynamics: as ``AeroStaticResult.aerodynamics``.
        start: ``"equilibrium"`` (the static aeroelastic equilibrium of the initial flight) or
            ``"rest"`` (undeformed).
        penetration: how the gust front meets each section, ``"uniform"`` or ``"kussner"``
            (``[aero.flight.gust] penetration``); None without a gust.
        rust_time_s: wall time of the analysis on the Rust side (s).
    """

    _kind = "aero-dynamic"
    _nested = {"runs": AeroDynamicRun}

    runs: List[AeroDynamicRun]
    status: str
    end_time: float
    aerodynamics: Dict[str, Any]
    start: str
    rust_time_s: float
    penetration: Optional[str] = None
    extra: Dict[str, Any] = field(default_factory=dict)


@dataclass(eq=False, repr=False)
class GustFamilyRun(_Run):
    """One model's responses to the gusts of a family (CS 25.341(a)), one value per gust
    gradient distance H in the order given.

    Attributes:
        label, kind, modes: as :class:`AeroDynamicRun`.
        status, stop, message: how the model's runs ended: its first run that stopped, else
            its first that is not complete, else ``"complete"``.
        gradient: the gust gradient distances H (m; the 1−cos wavelength is 2H), ``(G,)``.
        design_velocity: U_ds = U_ref F_g (H/350 ft)^(1/6) of each (m/s), ``(G,)``.
        tip_y_max, tip_y_max_time, tip_y_min, tip_y_min_time: the largest and smallest change
            of the tip deflection from the equilibrium (m) at the output times from the gust's
            start on, and their times (s), ``(G,)`` each. A change that never goes above
            (below) zero has the peak 0 at the start.
        tip_twist_max, tip_twist_max_time, tip_twist_min, tip_twist_min_time: the same of the
            tip twist (rad); zero without torsion.
        root_bending_moment_max, root_bending_moment_max_time, root_bending_moment_min,
            root_bending_moment_min_time: the same of the root bending moment (N m).
        root_torque_max, root_torque_max_time, root_torque_min, root_torque_min_time: the same
            of the root torque, the clamp's torsion spring moment (N m); zero without torsion.
        lift_max, lift_max_time, lift_min, lift_min_time: the same of the lift (N).
        steps: accepted integrator steps per gust, ``(G,)``.
        member_status: each gust's run status word, ``(G,)`` list.
        wall_time_s: wall time of the model's integrations over the family (s).
        critical: per output name, the member of largest peak magnitude among the complete
            runs — ``{"gradient", "design_velocity", "peak" (signed), "time"}`` — or None.
    """

    _axis = "gust"
    _coord = "gradient"
    _columns = (
        "gradient",
        "design_velocity",
        *(f"{o}_{w}" for o in GUST_OUTPUTS for w in ("max", "max_time", "min", "min_time")),
        "steps",
    )
    _grids = {}

    label: str
    kind: str
    modes: Optional[List[int]]
    status: str
    stop: Optional[Dict[str, Any]]
    message: Optional[str]
    gradient: np.ndarray
    design_velocity: np.ndarray
    tip_y_max: np.ndarray
    tip_y_max_time: np.ndarray
    tip_y_min: np.ndarray
    tip_y_min_time: np.ndarray
    tip_twist_max: np.ndarray
    tip_twist_max_time: np.ndarray
    tip_twist_min: np.ndarray
    tip_twist_min_time: np.ndarray
    root_bending_moment_max: np.ndarray
    root_bending_moment_max_time: np.ndarray
    root_bending_moment_min: np.ndarray
    root_bending_moment_min_time: np.ndarray
    root_torque_max: np.ndarray
    root_torque_max_time: np.ndarray
    root_torque_min: np.ndarray
    root_torque_min_time: np.ndarray
    lift_max: np.ndarray
    lift_max_time: np.ndarray
    lift_min: np.ndarray
    lift_min_time: np.ndarray
    steps: np.ndarray
    member_status: List[str]
    wall_time_s: float
    critical: Dict[str, Optional[Dict[str, float]]]
    extra: Dict[str, Any] = field(default_factory=dict)

    def __repr__(self) -> str:
        return _summary(self, ["label", "status"]) + f" [{len(self.gradient)} gusts]"


@dataclass(eq=False, repr=False)
class GustFamilyResult(_Runs):
    """What a discrete gust family produced (``Case.gust_family()``, as ``flexwing gust``).

    Attributes:
        runs: one :class:`GustFamilyRun` per model: full, then the reduced models.
        status: the worst of the runs' statuses.
        outputs: the output names, in order (``tip_y``, ``tip_twist``, ``root_bending_moment``,
            ``root_torque``, ``lift``).
        reference_velocity: U_ref (m/s, true air velocity); alleviation: F_g.
        start: the time each gust front reaches the wing (s); end_time: the simulated time (s).
        penetration: ``"uniform"`` or ``"kussner"``.
        aerodynamics: as ``AeroStaticResult.aerodynamics``.
        rust_time_s: wall time of the analysis on the Rust side (s).
    """

    _kind = "gust-family"
    _nested = {"runs": GustFamilyRun}

    runs: List[GustFamilyRun]
    status: str
    outputs: List[str]
    reference_velocity: float
    alleviation: float
    start: float
    penetration: str
    end_time: float
    aerodynamics: Dict[str, Any]
    rust_time_s: float
    extra: Dict[str, Any] = field(default_factory=dict)
