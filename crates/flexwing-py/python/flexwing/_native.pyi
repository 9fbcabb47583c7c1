"""Type stubs of flexwing._native, the Rust half of the package (import ``flexwing``).

Units are SI: m, rad, s, N, N m (moments), N m² (EI, GJ), kg/m, kg m, J. Arrays going in may be
any array-like of real numbers (lists, float32/integer arrays, C- or F-ordered or strided views):
they are converted to float64 and copied. Arrays coming out are new C-ordered float64 arrays.
Bad input raises ``ArgumentTypeError`` (a ``TypeError``) or ``InputError`` (a ``ValueError``)
naming the argument; the reference is docs/python.md.
"""

from __future__ import annotations

import os
from typing import Any, Callable, Dict, Iterable, List, Literal, Mapping, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

from ._aero_results import AeroDynamicResult, AeroStaticResult, FlutterResult, GustFamilyResult
from ._chain3d_results import (
    Chain3dAeroStaticResult,
    Chain3dDynamicResult,
    Chain3dFlutterResult,
    Chain3dModesResult,
    Chain3dStaticResult,
    Chain3dStudyResult,
)
from ._linear import LinearizeResult, TurbulenceResult
from ._results import Batch, DynamicResult, ModesResult, StaticResult

__version__: str

ArrayLike = npt.ArrayLike
Vector = npt.NDArray[np.float64]
Matrix = npt.NDArray[np.float64]
#: A load of the model level: the keys of a ``[[loads]]`` table without ``time``/``active``,
#: e.g. ``{"type": "point-force", "span": 1.0, "direction": "dead", "fy": 10.0}`` (N).
Load = Mapping[str, Any]
#: ``callback(done, label)``: ``done`` the fraction of the analysis (0 to 1), ``label`` the model
#: running (``"full"``, ``"reduced-r2"``, …).
ProgressCallback = Callable[[float, str], Any]
AnalysisName = Literal["modes", "static", "dynamic", "flutter", "linearize", "study", "gust", "turbulence"]

class Case:
    """A flexwing case: the beam, the loads and the settings of its analyses, with the keys of
    the case file (docs/case-file.md). Immutable; pickles as its TOML text."""

    def __init__(self, data: Optional[Mapping[str, Any]] = None, /, **kwargs: Any) -> None:
        """A case from a dict with the case file's keys and/or keyword arguments (which
        override the dict's keys). Raises ``CaseFileError`` naming the key (``beam.section.EI``)."""
    @staticmethod
    def from_toml(text: str, file: Optional[str] = None) -> Case:
        """A case from TOML text; ``file`` names it in errors."""
    @staticmethod
    def load(path: Union[str, os.PathLike[str]]) -> Case:
        """Read the case file at ``path``."""
    @staticmethod
    def from_dict(data: Mapping[str, Any]) -> Case:
        """A case from a dict with the case file's keys (NumPy arrays and scalars accepted)."""
    def to_dict(self) -> Dict[str, Any]:
        """The case as a dict with the case file's keys (absent optional keys left out)."""
    def to_toml(self) -> str:
        """The case as TOML text."""
    def replace(self, changes: Mapping[str, Any]) -> Case:
        """A copy with the values at key paths changed: ``{"beam.section.EI": 60.0,
        "loads[0].fy": 12.0}``. Missing tables are created; errors name the path."""
    @property
    def title(self) -> Optional[str]:
        """The case's title, if any."""
    @property
    def aeroelastic(self) -> bool:
        """Whether the case has an ``[aero]`` table (``statics``/``dynamics`` are then
        aeroelastic, and ``flutter`` runs)."""
    @property
    def file(self) -> Optional[str]:
        """The file the case was read from, if any."""
    def model(self) -> FullModel:
        """The full model of ``[beam]``."""
    def modes(
        self, *, progress: Optional[ProgressCallback] = None, check: bool = True
    ) -> ModesResult:
        """The natural modes of ``[beam]`` (``[modes] count``, default 10), frequencies in rad/s
        and Hz; in vacuo (an ``[aero]`` table is not used, as ``flexwing modes``). ``check`` is
        accepted as by every analysis (a modal analysis completes or raises). Ctrl-C or a
        raising ``progress`` stops any analysis at its next check and raises that exception
        with the partial result as its ``result`` attribute."""
    def statics(
        self, *, progress: Optional[ProgressCallback] = None, check: bool = True
    ) -> Union[StaticResult, AeroStaticResult, Chain3dStaticResult, Chain3dAeroStaticResult]:
        """The non-linear statics of ``[[loads]]`` and ``[static]`` (sweeps, reduced models,
        loaded modes); with ``[aero]``, the static aeroelastic equilibria at
        ``aero.flight.speed`` or along ``[aero.sweep]`` and the divergence speed
        (``AeroStaticResult``; on the 3-D chain ``Chain3dStaticResult`` and
        ``Chain3dAeroStaticResult``). With ``check`` (default), a model that stopped raises
        ``SolverError`` carrying the partial result; else each run's ``status`` says so."""
    def dynamics(
        self, *, progress: Optional[ProgressCallback] = None, check: bool = True
    ) -> Union[DynamicResult, AeroDynamicResult, Chain3dDynamicResult]:
        """The non-linear dynamics of ``[[loads]]`` and ``[dynamic]`` (full, simplified and
        reduced models); with ``[aero]``, the aeroelastic response (``AeroDynamicResult``); on
        the 3-D chain (``beam.model = "chain3d"``), a ``Chain3dDynamicResult``;
        ``check`` as ``statics`` (a suspect energy balance raises too)."""
    def stepper(
        self,
        *,
        inputs: Optional[Sequence[str]] = None,
        outputs: Optional[Sequence[str]] = None,
        hold: str = "linear",
        model: int = 0,
    ) -> AeroStepper:
        """An ``AeroStepper`` of the case's aeroelastic response (``[aero]``, ``[dynamic]``):
        inputs (default ``root_angle`` (rad), ``speed`` (m/s), ``gust`` (m/s); also
        ``force[k]`` (N), ``torque[k]`` (N·m) at node k) set between calls of ``step``, outputs
        (default ``tip_x``, ``tip_y`` (m), ``tip_twist`` (rad), ``root_bending_moment``,
        ``root_torque`` (N·m), ``lift`` (N)) read after each."""
    def fmu(
        self,
        path: Union[str, "os.PathLike[str]"],
        *,
        inputs: Optional[Sequence[str]] = None,
        outputs: Optional[Sequence[str]] = None,
        hold: str = "zero",
        model: int = 0,
        library: Optional[Union[str, "os.PathLike[str]"]] = None,
    ) -> Dict[str, Any]:
        """Write a co-simulation FMU (FMI 2.0) of the case's aeroelastic response to ``path``
        (as ``flexwing fmu``): the stepper's inputs and outputs as FMI variables, the case in
        its resources, ``hold`` the start value of its ``hold`` parameter; ``library`` the
        compiled ``libflexwing_fmu.so`` (default ``FLEXWING_FMU_LIBRARY``). Returns ``path``,
        ``guid``, ``inputs``, ``outputs``, ``model``, ``hold``, ``platform``, ``bytes``."""
    def flutter(
        self, *, progress: Optional[ProgressCallback] = None, check: bool = True
    ) -> FlutterResult:
        """Flutter and divergence along ``[aero.sweep]`` (``[aero]``, ``[flutter]``): V-g/V-ω
        data (1/s, rad/s), flutter speeds (m/s) and frequencies (rad/s), divergence speeds,
        equilibria and the p-k check, per model. ``check`` raises if an eigen-analysis stopped
        before the last speed."""
    def gust_family(
        self, *, progress: Optional[ProgressCallback] = None, check: bool = True
    ) -> GustFamilyResult:
        """A discrete gust family as in CS 25.341(a) (``[gust_family]`` on ``[aero]`` and
        ``[dynamic]``): per model and gust gradient distance H (m), the design velocity (m/s)
        and the largest and smallest change of the tip deflection (m) and twist (rad), the root
        bending moment and torque (N m) and the lift (N) with their times (s), and each
        output's critical H. ``check`` as ``dynamics``."""
    def study(
        self, *, progress: Optional[ProgressCallback] = None, check: bool = True
    ) -> Chain3dStudyResult:
        """Flutter and divergence against a load level on the 3-D chain (``beam.model =
        "chain3d"``, ``[flutter.study]``): the tip deflection at rest (m), the flutter speed
        (m/s) and frequency (rad/s) and the divergence speed at every level, beside the
        undeformed wing's flutter speed. ``check`` raises if the study was cut short."""
    def linearize(
        self,
        *,
        speed: Optional[float] = None,
        inputs: Optional[Sequence[str]] = None,
        outputs: Optional[Sequence[str]] = None,
        states: Optional[Literal["velocities", "momenta"]] = None,
        progress: Optional[ProgressCallback] = None,
        check: bool = True,
    ) -> LinearizeResult:
        """Linear state-space models ``A, B, C, D`` (SI units, docs/control.md) about the static
        aeroelastic equilibrium at ``speed`` (m/s, default ``aero.flight.speed``) for the full
        and reduced models of ``[linearize]``; ``inputs``, ``outputs``, ``states`` override
        its keys. ``check`` raises ``SolverError`` past the divergence speed."""
    def turbulence(
        self,
        *,
        spectrum: Optional[Literal["von-karman", "dryden"]] = None,
        intensity: Optional[float] = None,
        scale_length: Optional[float] = None,
        frequencies: Optional[int] = None,
        min_frequency: Optional[float] = None,
        max_frequency: Optional[float] = None,
        progress: Optional[ProgressCallback] = None,
        check: bool = True,
    ) -> TurbulenceResult:
        """The power spectra (unit² per rad/s) and RMS of the outputs of the linear models of
        ``[linearize]`` in continuous turbulence (``[turbulence]``; the keywords override its
        keys, ``intensity`` in m/s, ``scale_length`` in m, frequencies in rad/s). ``check``
        raises ``SolverError`` if a model is past the flutter speed."""
    def run(
        self,
        analysis: AnalysisName,
        *,
        progress: Optional[ProgressCallback] = None,
        check: bool = True,
    ) -> Union[
        ModesResult,
        StaticResult,
        DynamicResult,
        AeroStaticResult,
        AeroDynamicResult,
        FlutterResult,
        GustFamilyResult,
        LinearizeResult,
        TurbulenceResult,
        Chain3dModesResult,
        Chain3dStaticResult,
        Chain3dAeroStaticResult,
        Chain3dFlutterResult,
        Chain3dStudyResult,
        Chain3dDynamicResult,
    ]:
        """Run the analysis named ``analysis`` (as the method of the same name)."""
    def __eq__(self, other: object) -> bool: ...
    def __reduce__(self) -> Tuple[Any, Tuple[str, Optional[str]]]: ...

class Beam:
    """A cantilever cut into rigid elements, with its section properties over the span."""

    def __init__(
        self,
        *,
        length: float,
        EI: Union[float, ArrayLike],
        mass_per_length: Union[float, ArrayLike],
        elements: Optional[int] = None,
        stations: Optional[ArrayLike] = None,
        x: Optional[ArrayLike] = None,
        GJ: Union[float, ArrayLike, None] = None,
        polar_inertia: Union[float, ArrayLike, None] = None,
        polar_inertia_about: Optional[Literal["mass-centre", "elastic-axis"]] = None,
        d0: Union[float, ArrayLike, None] = None,
        calibration: Optional[Literal["tip-load", "uniform"]] = None,
        element_inertia: Optional[Literal["point-mass", "bar"]] = None,
        rotary_inertia: Union[float, ArrayLike, None] = None,
    ) -> None:
        """``length`` (m); ``elements`` (equal elements) or ``stations`` (node positions, m,
        0 … length); ``EI`` (N m²) and ``mass_per_length`` (kg/m); for torsion ``GJ`` (N m²),
        ``polar_inertia`` (kg m), ``polar_inertia_about``, ``d0`` (m, mass-centre offset). Each
        property a number or an array of values at the stations ``x`` (m, piecewise linear).
        ``calibration``: ``"tip-load"`` (default) or ``"uniform"``. Rotary inertia in bending:
        ``element_inertia`` ``"point-mass"`` (default, the paper's) or ``"bar"`` (each element a
        rigid bar, m ℓ²/12: for long chains), and ``rotary_inertia`` (kg m, the section's ρI,
        a property)."""
    @staticmethod
    def from_dict(table: Mapping[str, Any]) -> Beam:
        """A beam from a ``[beam]`` table (a dict with the case file's keys)."""
    def to_dict(self) -> Dict[str, Any]:
        """The beam as a ``[beam]`` table."""
    @property
    def length(self) -> float:
        """Span L (m)."""
    @property
    def n_elements(self) -> int:
        """Number of elements n."""
    @property
    def has_torsion(self) -> bool:
        """Whether the beam has torsion coordinates."""
    @property
    def nodes(self) -> Vector:
        """Node stations x_0 = 0 … x_n = L (m), ``(n + 1,)``."""
    @property
    def lengths(self) -> Vector:
        """Element lengths (m), ``(n,)``."""
    @property
    def masses(self) -> Vector:
        """Element masses (kg), ``(n,)``."""
    @property
    def offsets(self) -> Vector:
        """Element mass-centre offsets d0 (m), ``(n,)``."""
    @property
    def inertias(self) -> Vector:
        """Element polar inertias about their mass centres (kg m²), ``(n,)``."""
    @property
    def bending_inertias(self) -> Vector:
        """Element rotary inertias in bending about their midpoints (kg m²), ``(n,)``; zeros for
        point masses."""
    @property
    def bending_stiffness(self) -> Vector:
        """Bending spring stiffnesses (N m/rad), ``(n,)``, joint i at node i."""
    @property
    def torsion_stiffness(self) -> Optional[Vector]:
        """Torsion spring stiffnesses (N m/rad), ``(n,)``, or None without torsion."""
    def __reduce__(self) -> Tuple[Any, Tuple[Any, ...]]: ...

class FullModel:
    """The full model of a beam: n bending coordinates (joint rotations, rad), and n torsion
    coordinates with torsion."""

    def __init__(self, beam: Beam) -> None: ...
    @property
    def beam(self) -> Beam:
        """The beam."""
    @property
    def n_dofs(self) -> int:
        """Number of coordinates."""
    @property
    def n_elements(self) -> int:
        """Number of elements."""
    @property
    def has_torsion(self) -> bool:
        """Whether the model has torsion coordinates."""
    def stiffness_matrix(self) -> Matrix:
        """Stiffness matrix K (N m/rad), ``(n_dofs, n_dofs)``."""
    def mass_matrix(self, q: ArrayLike) -> Matrix:
        """Mass matrix M(q) (kg m²) at joint rotations q (rad), ``(n_dofs, n_dofs)``."""
    def shape(self, q: ArrayLike) -> Dict[str, Vector]:
        """The deformed shape at joint rotations q (rad): node arrays ``x``, ``y`` (m) and
        ``twist`` (rad), each ``(n + 1,)``."""
    def modes(self, count: Optional[int] = None) -> ModesResult:
        """The lowest ``count`` natural modes about the undeformed state (default
        ``min(10, n_dofs)``)."""
    def reduced(self, modes: Union[int, Sequence[int]]) -> ReducedModel:
        """The reduced model on ``modes``: an int r (the first r) or 1-based mode numbers."""
    def equations(
        self,
        loads: Optional[Sequence[Load]] = None,
        *,
        scales: Optional[ArrayLike] = None,
        gyroscopic: Optional[Literal["exact", "finite-difference", "neglected"]] = None,
        gyroscopic_step: Optional[float] = None,
        damping: Optional[Mapping[str, Any]] = None,
    ) -> Equations:
        """The equations of motion under ``loads`` (each scaled by ``scales``, default 1).
        ``damping``: ``{"type": "rayleigh", "alpha": 1/s, "beta": s}`` or ``{"type": "modal",
        "ratios": [...]}``."""
    def stepper(
        self,
        loads: Optional[Sequence[Load]] = None,
        *,
        x0: Optional[ArrayLike] = None,
        xdot0: Optional[ArrayLike] = None,
        t0: float = 0.0,
        scales: Optional[ArrayLike] = None,
        integrator: str = "auto",
        rtol: Optional[float] = None,
        atol: Optional[float] = None,
        max_steps: Optional[int] = None,
        max_step: Optional[float] = None,
        step: Optional[float] = None,
        max_order: Optional[int] = None,
        spectral_radius: Optional[float] = None,
        gyroscopic: Optional[Literal["exact", "finite-difference", "neglected"]] = None,
        gyroscopic_step: Optional[float] = None,
        damping: Optional[Mapping[str, Any]] = None,
        hold: Literal["linear", "zero"] = "linear",
    ) -> Stepper:
        """A stepper of the equations of motion under ``loads``, from the state (x0 rad, xdot0
        rad/s) at t0 (s); the integrator settings as ``[dynamic]`` of the case file."""
    def __reduce__(self) -> Tuple[Any, Tuple[Any, ...]]: ...

class ReducedModel:
    """The full model projected on some of its natural modes about the undeformed state: the
    coordinates are modal amplitudes η with q = Φ η; the geometry stays non-linear."""

    def __init__(self, full: FullModel, modes: Union[int, Sequence[int]]) -> None: ...
    @property
    def n_dofs(self) -> int:
        """Number of coordinates (retained modes)."""
    @property
    def modes(self) -> List[int]:
        """The retained modes, 1-based."""
    @property
    def full_model(self) -> FullModel:
        """The full model underneath."""
    @property
    def basis(self) -> Matrix:
        """The mass-normalized mode shapes Φ as columns, ``(full n_dofs, n_dofs)``."""
    def full_coordinates(self, x: ArrayLike) -> Vector:
        """Joint rotations q = Φ η (rad) of modal amplitudes x."""
    def reduce_coordinates(self, q: ArrayLike) -> Vector:
        """Modal amplitudes η = Φᵀ M(0) q of joint rotations q (rad)."""
    def stiffness_matrix(self) -> Matrix:
        """Reduced stiffness K_r = Φᵀ K Φ, ``(n_dofs, n_dofs)``."""
    def mass_matrix(self, x: ArrayLike) -> Matrix:
        """Reduced mass matrix M_r(η) = Φᵀ M(Φ η) Φ at modal amplitudes x."""
    def shape(self, x: ArrayLike) -> Dict[str, Vector]:
        """The deformed shape at modal amplitudes x (see ``FullModel.shape``)."""
    equations = FullModel.equations
    stepper = FullModel.stepper
    def __reduce__(self) -> Tuple[Any, Tuple[Any, ...]]: ...

class Equations:
    """The equations of motion of a full or reduced model under scaled loads, in first-order
    form dy/dt = f(t, y) with y = (x, p): coordinates x and conjugate momenta p."""

    @property
    def n_dofs(self) -> int:
        """Number of coordinates x (the state has twice as many values)."""
    @property
    def n_loads(self) -> int:
        """Number of loads."""
    @property
    def scales(self) -> Vector:
        """The load factors (one per load), held at every time until changed."""
    @scales.setter
    def scales(self, value: ArrayLike) -> None: ...
    def state(self, x: ArrayLike, xdot: ArrayLike) -> Vector:
        """The state y = (x, p) of coordinates x and velocities xdot, ``(2 n_dofs,)``."""
    def rhs(self, t: float, y: ArrayLike) -> Vector:
        """dy/dt at time t (s) and state y, ``(2 n_dofs,)``."""
    def jacobian(self, t: float, y: ArrayLike) -> Matrix:
        """The Jacobian ∂(dy/dt)/∂y at time t (s) and state y, ``(2 n_dofs, 2 n_dofs)``."""
    def energies(self, y: ArrayLike) -> Tuple[float, float]:
        """Energies of the state y: (kinetic, strain) (J)."""
    def velocities(self, y: ArrayLike) -> Vector:
        """Velocities ẋ = M(x)⁻¹ p of the state y."""
    def full_coordinates(self, x: ArrayLike) -> Vector:
        """Joint rotations q (rad) of the full model for coordinates x."""

class AeroStepper:
    """An aeroelastic response advanced one communication interval per call, with named inputs
    set between calls and named outputs read after each (``Case.stepper``): the core of the
    co-simulation FMU (docs/python.md). Each call runs detached from the interpreter."""

    def step(self, dt: float, inputs: Optional[Mapping[str, float]] = None) -> float:
        """Advance by dt (s) with the inputs ``inputs`` (name → value, SI units; the others
        keep theirs). Returns the new time (s). ``InputError`` names a bad input or ``dt``;
        ``SolverError`` (``stop``) if the integration stops inside the interval; the stepper is
        then as before the call."""
    @property
    def t(self) -> float:
        """Time (s)."""
    @property
    def input_names(self) -> List[str]:
        """The input names, in order."""
    @property
    def output_names(self) -> List[str]:
        """The output names, in order."""
    @property
    def units(self) -> Dict[str, str]:
        """The SI unit of every input and output, by name."""
    @property
    def inputs(self) -> Dict[str, float]:
        """The inputs' values set (name → value, SI units)."""
    @property
    def outputs(self) -> Dict[str, float]:
        """The outputs at the current time (name → value, SI units: m, rad, N·m, N)."""
    @property
    def status(self) -> Dict[str, Any]:
        """``status`` (complete, suspect, stopped), ``stop`` and ``message``."""
    @property
    def energy_audit(self) -> Dict[str, Any]:
        """What the energy audit found since the start (as ``DynamicRun.energy_audit``)."""
    def energies(self) -> Dict[str, float]:
        """Energies at t (J): kinetic, strain, work and dissipated since the start."""
    @property
    def stats(self) -> Dict[str, Any]:
        """Integrator counters summed over the calls, ``calls``, ``rust_time_s`` (s)."""

class Stepper:
    """A dynamic run advanced one output interval per call, with the load factors set from
    Python between calls (coupling to a flight-dynamics or control model). Each call runs
    detached from the interpreter."""

    def step(self, dt: float, scales: Optional[ArrayLike] = None) -> float:
        """Advance by dt (s) to the load factors ``scales`` (default: the previous ones, held);
        ``hold="linear"`` ramps them over the interval, ``hold="zero"`` switches at once.
        Returns the new time (s). Raises ``SolverError`` (``stop["error"]["time"]``) if the
        integrator stops inside the interval, ``InputError`` (``dt``) for an interval below the
        time's resolution, ``KeyboardInterrupt`` on Ctrl-C; after any of these the stepper is as
        before the call (time, state, load factors)."""
    def set_state(self, x: ArrayLike, xdot: ArrayLike, t: Optional[float] = None) -> None:
        """Set the state from coordinates x and velocities xdot (and the time t, s)."""
    @property
    def t(self) -> float:
        """Time (s)."""
    @property
    def n_dofs(self) -> int:
        """Number of coordinates."""
    @property
    def scales(self) -> Vector:
        """The load factors in force."""
    @property
    def y(self) -> Vector:
        """The state y = (x, p)."""
    @property
    def x(self) -> Vector:
        """Coordinates x (rad, or modal amplitudes of a reduced model)."""
    @property
    def xdot(self) -> Vector:
        """Velocities ẋ."""
    @property
    def q(self) -> Vector:
        """Joint rotations q of the full model (rad)."""
    @property
    def tip(self) -> Tuple[float, float, float]:
        """Tip position and twist (x, y, twist) (m, m, rad)."""
    def energies(self) -> Tuple[float, float]:
        """Energies (kinetic, strain) (J)."""
    def shape(self) -> Dict[str, Vector]:
        """The deformed shape: node arrays ``x``, ``y`` (m) and ``twist`` (rad)."""
    @property
    def stats(self) -> Dict[str, Union[int, float]]:
        """Counters summed over the calls: the integrator's (``steps``, ``rejected_steps``,
        ``newton_failures``, ``rhs_evaluations``, ``jacobian_evaluations``, ``factorizations``,
        ``newton_iterations``), ``calls``, and ``rust_time_s`` (s spent in the library: setting
        the load factors and integrating)."""

def solve_many(
    cases: Iterable[Union[Case, Mapping[str, Any]]],
    analysis: AnalysisName = "static",
    *,
    threads: int = 1,
    progress: Optional[Callable[[int, int], Any]] = None,
    start: int = 0,
) -> Batch:
    """Solve ``analysis`` for every case and return one ``BatchItem`` per case, in order (a
    ``Batch``: a list with ``to_pandas(index=…)`` and ``to_xarray(index=…)``), with
    its index (``start`` + position), status (``"complete"``, ``"suspect"``, ``"stopped"``,
    ``"interrupted"``, ``"error"``), result, error (as data) and wall time (s). No case's
    failure stops the others. ``threads``: worker threads of this process sharing the cases
    (the interpreter released); ``progress``: ``callback(done, total)`` on the calling thread,
    ``done`` counting up. A raising callback or Ctrl-C stops the batch and raises with the
    items so far as ``result``."""

def write_node_npz(
    path: str,
    fields: List[Tuple[str, str]],
    histories: List[Tuple[str, npt.NDArray[np.float64], npt.NDArray[np.int64], npt.NDArray[np.float64]]],
) -> None:
    """Write node histories to ``path`` (``.npz``, atomically) in the layout of ``flexwing
    dynamic --format npz``: ``fields`` the (name, unit) pairs of the last axis; each history
    (label, ``t`` ``(S,)``, ``index`` ``(S,)``, values ``(S, nodes, fields)``). Used by
    ``DynamicResult.save_npz``."""

def write_spatial_vtk(
    folder: Union[str, os.PathLike[str]],
    stem: str,
    times: npt.NDArray[np.float64],
    position: npt.NDArray[np.float64],
    rotation: npt.NDArray[np.float64],
    reference: npt.NDArray[np.float64],
    modes: bool = False,
) -> str:
    """Write frames of the 3-D chain to ``folder`` as ``STEM_0000.vtu``, … and ``STEM.pvd``
    (the CLI's writer) and return the ``.pvd``'s path. Per frame ``k``: ``times[k]``, the node
    positions ``position[k]`` ``(nodes, 3)`` (m; with ``modes``, a mode's nodal displacements
    drawn on ``reference``), the elements' section rotation vectors ``rotation[k]``
    ``(nodes − 1, 3)`` (rad); ``reference`` ``(nodes, 3)`` the undeformed nodes. Used by the
    3-D results' ``write_vtk``."""

def write_planar_vtk(
    folder: Union[str, os.PathLike[str]],
    stem: str,
    times: npt.NDArray[np.float64],
    x: npt.NDArray[np.float64],
    y: npt.NDArray[np.float64],
    twist: npt.NDArray[np.float64],
    stations: npt.NDArray[np.float64],
    modes: bool = False,
) -> str:
    """Write a planar chain's frames to ``folder`` as ``STEM_0000.vtu``, … and ``STEM.pvd``
    (VTK XML, ASCII; the CLI's writer) and return the ``.pvd``'s path. Per frame ``k``:
    ``times[k]``, the nodes ``x[k]``, ``y[k]`` (m; with ``modes``, a mode's nodal
    displacements drawn on the undeformed nodes), ``twist[k]`` (rad); ``stations`` the
    undeformed nodes (m). Used by ``write_vtk``."""
