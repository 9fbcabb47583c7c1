"""The linear state-space models of ``Case.linearize()`` (docs/control.md): per model
``x' = A x + B u``, ``y = C x + D u`` on perturbations about the static aeroelastic
equilibrium, with the names and units of its states, inputs and outputs, as ``flexwing
linearize`` writes them to ``linear_LABEL.mat`` and ``.npz``.

``to_control()`` needs python-control (``pip install control``), ``to_scipy()`` SciPy; the
frequency response is NumPy's own (one complex solve per frequency).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Dict, List, Optional, Sequence, Union

import numpy as np

from ._base import _Run, _Runs, _summary

__all__ = ["LinearModel", "LinearizeResult"]


def _index(names: List[str], which: Union[None, str, int, Sequence], what: str) -> List[int]:
    if which is None:
        return list(range(len(names)))
    if isinstance(which, (str, int)):
        which = [which]
    out = []
    for w in which:
        if isinstance(w, str):
            if w not in names:
                raise KeyError(f"{what}: unknown name {w!r}; the model's are {', '.join(names)}")
            out.append(names.index(w))
        else:
            out.append(int(w))
    return out


@dataclass(eq=False, repr=False)
class LinearModel(_Run):
    """The linear model of one model (full or reduced) about the equilibrium.

    Attributes:
        label, kind, modes, dofs: as :class:`FlutterRun` (``"full"``, ``"reduced-r4"``…).
        aero_states: number of aerodynamic (lag) states.
        basis: ``"velocities"`` (coordinates, rates, lag states) or ``"momenta"``.
        A, B, C, D: the matrices (``None`` if the model stopped: no stable equilibrium).
        state_names, state_units, input_names, input_units, output_names, output_units:
            lists of strings (``"theta[1]"``, ``"rad"``; ``"gust"``, ``"m/s"``; ``"lift"``,
            ``"N"``).
        x0, u0, y0: the state, inputs and outputs at the equilibrium.
        poles: the eigenvalues of ``A`` (1/s, complex), by decreasing real part.
        wall_time_s: wall time of the linearization (s); status, stop, message, notes: as
            every run.
    """

    label: str
    kind: str
    modes: Optional[List[int]]
    dofs: int
    aero_states: int
    wall_time_s: float
    status: str
    stop: Optional[Dict[str, Any]]
    message: Optional[str]
    notes: List[Dict[str, Any]]
    basis: str
    A: Optional[np.ndarray]
    B: Optional[np.ndarray]
    C: Optional[np.ndarray]
    D: Optional[np.ndarray]
    state_names: Optional[List[str]]
    state_units: Optional[List[str]]
    input_names: Optional[List[str]]
    input_units: Optional[List[str]]
    output_names: Optional[List[str]]
    output_units: Optional[List[str]]
    x0: Optional[np.ndarray]
    u0: Optional[np.ndarray]
    y0: Optional[np.ndarray]
    poles: np.ndarray
    extra: Dict[str, Any] = field(default_factory=dict)

    def _matrices(self):
        if self.A is None:
            raise ValueError(f"{self.label}: no linear model ({self.message})")
        return self.A, self.B, self.C, self.D

    def to_scipy(self):
        """The model as ``scipy.signal.StateSpace`` (continuous time; no names: SciPy keeps
        none, they are ``state_names``, ``input_names``, ``output_names``)."""
        from scipy import signal

        return signal.StateSpace(*self._matrices())

    def to_control(self):
        """The model as python-control's ``StateSpace`` (``control.ss``) with the names of its
        states, inputs and outputs (``sys.input_labels``…), e.g.
        ``control.bode_plot(model.to_control()["tip_y", "gust"])``."""
        import control

        a, b, c, d = self._matrices()
        return control.ss(
            a,
            b,
            c,
            d,
            states=list(self.state_names),
            inputs=list(self.input_names),
            outputs=list(self.output_names),
            name=self.label,
        )

    def frequency_response(self, omega, inputs=None, outputs=None) -> np.ndarray:
        """``G(iω) = C (iω I − A)⁻¹ B + D`` at the angular frequencies ``omega`` (rad/s), an
        array ``(len(omega), outputs, inputs)`` in the outputs' units per the inputs' units;
        ``inputs`` and ``outputs`` pick names or indices (default: all)."""
        a, b, c, d = self._matrices()
        cols = _index(self.input_names, inputs, "inputs")
        rows = _index(self.output_names, outputs, "outputs")
        b, c, d = b[:, cols], c[rows, :], d[np.ix_(rows, cols)]
        omega = np.atleast_1d(np.asarray(omega, dtype=float))
        eye = np.eye(a.shape[0])
        out = np.empty((omega.size, len(rows), len(cols)), dtype=complex)
        for k, w in enumerate(omega):
            out[k] = c @ np.linalg.solve(1j * w * eye - a, b) + d
        return out

    def static_gain(self, inputs=None, outputs=None) -> np.ndarray:
        """``G(0) = D − C A⁻¹ B``: the steady output per unit steady input."""
        return self.frequency_response([0.0], inputs, outputs)[0].real

    def __repr__(self) -> str:
        n = None if self.A is None else self.A.shape[0]
        return _summary(self, ["label", "status", "basis"]) [:-1] + f", states={n})"


@dataclass(eq=False, repr=False)
class LinearizeResult(_Runs):
    """The linear models of a case (``Case.linearize()``).

    Attributes:
        runs: one :class:`LinearModel` per model, full model first.
        speed: the equilibrium's free-stream speed (m/s); root_angle (rad); gravity (m/s² or
            ``None``).
        aerodynamics: as ``AeroStaticResult.aerodynamics``.
        status: ``"complete"`` if every model was linearized, else ``"stopped"``.
        rust_time_s: wall time of the analysis on the Rust side (s).
    """

    _kind = "linearize"
    _nested = {"runs": LinearModel}

    runs: List[LinearModel]
    speed: float
    root_angle: float
    gravity: Optional[float]
    aerodynamics: Dict[str, Any]
    status: str
    rust_time_s: float
    extra: Dict[str, Any] = field(default_factory=dict)


@dataclass(eq=False, repr=False)
class TurbulenceRun(_Run):
    """The response of one model's outputs to continuous turbulence, through its linear model
    (docs/control.md, "Continuous turbulence").

    Attributes:
        label, kind, modes: as :class:`LinearModel`.
        status, stop, message, notes: as every run; a model past the flutter speed stops (no
            stationary response) and has empty arrays; ``notes`` name the outputs whose
            variance diverges with the cut-off.
        outputs, output_units: the outputs' names and units (``[linearize] outputs``).
        frequency: the frequencies ω (rad/s), ``(F,)``.
        gust_psd: the gust velocity's one-sided spectrum Φ_w(ω) (m²/s² per rad/s), ``(F,)``.
        psd: the outputs' spectra Φ_y(ω) = |H_y(iω)|² Φ_w(ω) (unit² per rad/s), ``(F, O)``.
        rms: each output's RMS (its unit), ``(O,)``: the variance below, on and above the grid;
            where it diverges, the part below ``max_frequency``.
        variance_error: the estimated error of each variance (unit²), ``(O,)``.
        tail_variance: the variance above ``max_frequency`` included (unit²; NaN where it
            diverges), ``(O,)``.
        tail_slope: the exponent p of Φ_y ∝ ω^p beyond every pole, ``(O,)``.
        diverges: per output, whether its variance diverges (p ≥ −1).
        gust_rms: the gust's RMS over the same grid and tails (m/s; σ_w up to the quadrature).
        wall_time_s: wall time of the spectra, the linearization apart (s).
    """

    _axis = "frequency"
    _coord = "frequency"
    _columns = ("frequency", "gust_psd")
    _grids = {"psd": "output"}
    _grid_labels = {"output": "outputs"}

    label: str
    kind: str
    modes: Optional[List[int]]
    status: str
    stop: Optional[Dict[str, Any]]
    message: Optional[str]
    notes: List[Dict[str, Any]]
    outputs: List[str]
    output_units: List[str]
    frequency: np.ndarray
    gust_psd: np.ndarray
    psd: np.ndarray
    rms: np.ndarray
    variance_error: np.ndarray
    tail_variance: np.ndarray
    tail_slope: np.ndarray
    diverges: List[bool]
    gust_rms: Optional[float]
    wall_time_s: float
    extra: Dict[str, Any] = field(default_factory=dict)

    def __repr__(self) -> str:
        return _summary(self, ["label", "status"]) + f" [{len(self.frequency)} frequencies]"


@dataclass(eq=False, repr=False)
class TurbulenceResult(_Runs):
    """What a turbulence analysis produced (``Case.turbulence()``, as ``flexwing turbulence``).

    Attributes:
        runs: one :class:`TurbulenceRun` per model, full model first.
        spectrum: ``"von-karman"`` or ``"dryden"``; intensity: σ_w (m/s); scale_length: L (m).
        speed: the free-stream speed (m/s).
        frequencies, min_frequency, max_frequency: the grid (count, rad/s).
        aerodynamics: as ``AeroStaticResult.aerodynamics``.
        status: the worst of the runs' statuses.
        rust_time_s: wall time of the analysis on the Rust side (s).
    """

    _kind = "turbulence"
    _nested = {"runs": TurbulenceRun}

    runs: List[TurbulenceRun]
    spectrum: str
    intensity: float
    scale_length: float
    speed: float
    frequencies: int
    min_frequency: float
    max_frequency: float
    aerodynamics: Dict[str, Any]
    status: str
    rust_time_s: float
    extra: Dict[str, Any] = field(default_factory=dict)
