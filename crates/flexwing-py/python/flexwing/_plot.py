"""``result.plot()``: a quick look at a result with matplotlib (the optional ``plot`` extra,
``pip install "flexwing[plot]"``), built once from the fields the result classes declare
(``_base.py``): every run of a result is one line, labelled with the model.

* modes: the mode shapes ``dy`` (and ``twist`` with torsion) along the span;
* statics: the deformed shapes at the last point, and the tip against the sweep's scale;
* dynamics (structural or aeroelastic): the tip deflection (and the lift, aeroelastic; the
  tip's z, the 3-D chain) in time;
* static aeroelastic sweeps: the tip twist and deflection against the speed;
* flutter: the V-g and V-ω diagrams of one model's branches, the flutter speed marked;
* gust families: each output's largest (solid) and smallest (dashed) change against the gust
  gradient distance H, one panel per output (the twist and torque only with torsion).

Each returns the matplotlib ``Figure`` (its axes in ``figure.axes``); ``ax=`` draws a
one-panel plot into the caller's axes instead. Nothing is shown or saved: call
``figure.savefig(...)`` or let a notebook display it.
"""

from __future__ import annotations

from typing import Any, Optional

import numpy as np

from ._frames import UNITS


def pyplot():
    """matplotlib.pyplot, or ImportError naming the extra."""
    try:
        import matplotlib.pyplot as plt
    except ImportError as e:
        raise ImportError(
            'plot() needs matplotlib, an optional dependency of flexwing: pip install "flexwing[plot]" '
            "(or pip install matplotlib)"
        ) from e
    return plt


def _label(name: str) -> str:
    unit = UNITS.get(name)
    return f"{name} ({unit})" if unit and unit != "1" else name


def _axes(plt, ax, panels: int):
    if ax is not None:
        return ax.figure, [ax] * panels
    fig, axes = plt.subplots(panels, 1, figsize=(7, 3.2 * panels), squeeze=False, layout="constrained")
    return fig, list(axes[:, 0])


def plot(obj, ax=None, **kwargs) -> Any:
    """Dispatch on the kind of result (see the module's documentation)."""
    plt = pyplot()
    if hasattr(obj, "runs"):
        return _runs(plt, obj, ax, **kwargs)
    if hasattr(obj, "damping_ratio"):
        return _stability(plt, obj, ax, title=kwargs.get("title"))
    if hasattr(obj, "dx"):
        return _modes(plt, obj, ax)
    if getattr(obj, "_axis", None):
        return _runs(plt, _Single(obj), ax, **kwargs)
    if hasattr(obj, "result") and obj.result is not None:
        return plot(obj.result, ax, **kwargs)
    raise TypeError(f"{type(obj).__name__} has no plot")


class _Single:
    """One run shown as a result of one run."""

    def __init__(self, run):
        self.runs = [run]
        self.status = run.status


def _modes(plt, m, ax):
    torsion = bool(np.any(m.twist))
    fig, axes = _axes(plt, ax, 2 if torsion else 1)
    for k in range(len(m.mode)):
        label = f"mode {m.mode[k]}: {m.frequency_hz[k]:.4g} Hz"
        axes[0].plot(m.x, m.dy[k], label=label)
        if torsion:
            axes[1].plot(m.x, m.twist[k], label=label)
    axes[0].set_ylabel("dy (m, mass-normalized)")
    if torsion:
        axes[1].set_ylabel("twist (rad, mass-normalized)")
    axes[-1].set_xlabel(_label("x"))
    axes[0].legend(fontsize="small", loc="upper left", bbox_to_anchor=(1.01, 1.0))
    axes[0].set_title("natural modes")
    return fig


def _runs(plt, result, ax, model: Optional[str] = None, **_):
    runs = result.runs
    if not runs:
        raise ValueError("the result has no runs to plot")
    first = runs[0]
    axis = getattr(first, "_axis", None)
    if getattr(first, "_delegate", None):  # flutter
        run = first if model is None else next(r for r in runs if r.label == model)
        return _stability(plt, run.eigenvalues, ax, title=f"{run.label}: V-g and V-ω", marked=run.flutter_speed)
    if axis == "point":
        many = any(len(r.scale) > 1 for r in runs)
        fig, axes = _axes(plt, ax, 2 if many else 1)
        for r in runs:
            if len(r.scale):
                axes[0].plot(r.x[-1], r.y[-1], marker=".", label=r.label)
            if many:
                axes[1].plot(r.scale, r.tip_y, marker=".", label=r.label)
        axes[0].set_xlabel(_label("x"))
        axes[0].set_ylabel(_label("y"))
        axes[0].set_aspect("equal", adjustable="datalim")
        axes[0].set_title("deformed shape at the last point")
        if many:
            axes[1].set_xlabel("scale of the swept load")
            axes[1].set_ylabel(_label("tip_y"))
    elif axis == "time":
        # The second panel: the lift of an aeroelastic run, the tip's z of the 3-D chain's.
        second = "lift" if hasattr(first, "lift") else "tip_z" if hasattr(first, "tip_z") else None
        fig, axes = _axes(plt, ax, 2 if second else 1)
        for r in runs:
            axes[0].plot(r.t, r.tip_y, label=r.label)
            if second:
                axes[-1].plot(r.t, getattr(r, second), label=r.label)
        axes[0].set_ylabel(_label("tip_y"))
        if second:
            axes[-1].set_ylabel(_label(second))
        axes[-1].set_xlabel(_label("t"))
        axes[0].set_title("tip deflection")
    elif axis == "speed":
        fig, axes = _axes(plt, ax, 2)
        for r in runs:
            axes[0].plot(r.speed, r.tip_twist, marker=".", label=r.label)
            axes[1].plot(r.speed, r.tip_y, marker=".", label=r.label)
        axes[0].set_ylabel(_label("tip_twist"))
        axes[1].set_ylabel(_label("tip_y"))
        axes[-1].set_xlabel(_label("speed"))
        axes[0].set_title("static aeroelastic equilibria")
    elif axis == "gust":
        names = [o for o in ("tip_y", "tip_twist", "root_bending_moment", "root_torque", "lift")
                 if any(np.any(getattr(r, f"{o}_max")) or np.any(getattr(r, f"{o}_min")) for r in runs)]
        fig, axes = _axes(plt, ax, len(names))
        for k, r in enumerate(runs):
            colour = f"C{k}"
            for a, o in zip(axes, names):
                a.plot(r.gradient, getattr(r, f"{o}_max"), color=colour, marker=".", label=f"{r.label} max")
                a.plot(r.gradient, getattr(r, f"{o}_min"), color=colour, linestyle="--", label=f"{r.label} min")
        for a, o in zip(axes, names):
            a.set_ylabel(f"peak change of {_label(o)}")
        axes[-1].set_xlabel("gust gradient distance H (m)")
        axes[0].set_title("discrete gusts (CS 25.341(a))")
    elif axis == "frequency":
        names = next((r.outputs for r in runs if len(r.frequency)), [])
        fig, axes = _axes(plt, ax, max(len(names), 1))
        for r in runs:
            for j, a in enumerate(axes[: len(names)]):
                if len(r.frequency):
                    a.loglog(r.frequency, r.psd[:, j], label=f"{r.label}: RMS {r.rms[j]:.4g}")
        for a, name, unit in zip(axes, names, next((r.output_units for r in runs if len(r.frequency)), [])):
            a.set_ylabel(f"Φ of {name} ({unit}²/(rad/s))")
        axes[-1].set_xlabel("ω (rad/s)")
        axes[0].set_title("output spectra in turbulence")
    else:
        raise TypeError(f"{type(first).__name__} has no plot")
    for a in set(axes):
        a.grid(True, alpha=0.3)
        a.legend(fontsize="small")
    return fig


def _stability(plt, s, ax, title=None, marked=None):
    fig, axes = _axes(plt, ax, 1 if ax is not None else 2)
    speeds = np.asarray(s.speeds)
    for b in range(len(s.mode)):
        label = f"branch {b} (mode {s.mode[b]})"
        axes[0].plot(speeds, s.damping_ratio[b], label=label)
        if ax is None:
            axes[1].plot(speeds, s.imag[b], label=label)
    axes[0].axhline(0.0, color="black", linewidth=0.8)
    axes[0].set_ylabel("damping ratio ζ = −σ/|s|")
    if ax is None:
        axes[1].set_ylabel("frequency ω = Im s (rad/s)")
    flutter = marked if marked is not None else s.flutter_speed
    for a in set(axes):
        if flutter is not None:
            a.axvline(flutter, color="red", linestyle="--", linewidth=1, label=f"flutter {flutter:.4g} m/s")
        a.grid(True, alpha=0.3)
    axes[-1].set_xlabel(_label("speed"))
    axes[0].legend(fontsize="small")
    axes[0].set_title(title or "V-g and V-ω")
    return fig
