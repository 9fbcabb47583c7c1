"""Trailing-edge control surfaces from Python (docs/aeroelastic-model.md §3b): the effectiveness
of a full-span aileron on a uniform clamped wing against the closed form of the torsion ODE,
computed here, at second order in the element count; the hinge moments as arrays; bad surfaces
named by their case-file key.

Closed form (steady strip theory): GJ ψ'' + q c e c_lα ψ = −q (c e c_lδ + c² c_mδ) δ,
ψ(0) = ψ'(L) = 0, gives the lift relative to the rigid wing
η = 1 + (e c_lδ + c c_mδ)/(e c_lδ) (tan λL/(λL) − 1), λ² = q c e c_lα/GJ, with Glauert's
c_lδ = 2(π − θ + sin θ), c_mδ = −½ sin θ (1 − cos θ) (about the quarter chord), cos θ = 1 − 2 x_h."""

from __future__ import annotations

import copy

import numpy as np
import pytest

import flexwing
from flexwing import CaseFileError

L, C, GJ, RHO, X_EA, X_H, DELTA = 16.0, 1.0, 1.0e4, 0.0889, 0.35, 0.8, 1e-4


def wing(n, surfaces, speeds):
    return {
        "beam": {
            "length": L,
            "elements": n,
            "section": {
                "EI": 2.0e4,
                "GJ": GJ,
                "mass_per_length": 0.75,
                "polar_inertia": 0.1,
                "polar_inertia_about": "mass-centre",
            },
        },
        "aero": {
            "chord": C,
            "elastic_axis": X_EA,
            "density": RHO,
            "aerodynamics": {"model": "steady"},
            "surfaces": surfaces,
            "sweep": {"speeds": speeds},
        },
    }


def glauert():
    theta = np.arccos(1.0 - 2.0 * X_H)
    return 2.0 * (np.pi - theta + np.sin(theta)), -0.5 * np.sin(theta) * (1.0 - np.cos(theta))


def test_full_span_aileron_effectiveness_converges_to_the_torsion_ode():
    """Errors of η at U = 15, 20 m/s: measured 2.5e-2 → 1.5e-3 from n = 8 to 32 in the library
    test (aero_surfaces.rs); here n = 16 and 32: the ratio of the errors must show second order
    (between 1.8 and 2.2) and n = 32 lie within 2e-3."""
    cld, cmd = glauert()
    e, cla = (X_EA - 0.25) * C, 2.0 * np.pi
    speeds = [15.0, 20.0]
    aileron = [{"name": "aileron", "from": 0.0, "to": L, "hinge": X_H, "deflection": DELTA}]
    errors = []
    for n in (16, 32):
        run = flexwing.Case(wing(n, aileron, speeds)).statics().full
        assert run.hinge_moments.shape == (len(speeds), 1)
        err = 0.0
        for k, u in enumerate(speeds):
            q = 0.5 * RHO * u * u
            x = np.sqrt(q * C * e * cla / GJ) * L
            eta = 1.0 + (e * cld + C * cmd) / (e * cld) * (np.tan(x) / x - 1.0)
            err = max(err, abs(run.lift[k] / (q * C * cld * DELTA * L) - eta))
        errors.append(err)
    order = np.log2(errors[0] / errors[1])
    assert 1.8 < order < 2.2, (errors, order)
    assert errors[1] < 2e-3, errors


def test_hinge_moments_follow_the_surfaces():
    """Two surfaces, the inboard one undeflected: hinge moments `(points, 2)` in the order of
    `aerodynamics["surfaces"]`. With the elastic axis at 35 % the aileron's moment twists the
    wing nose-down (e c_lδ + c c_mδ < 0), root to tip: the aileron's hinge moment is negative (its
    lift pushes the trailing edge up) and grows less than q (4× from 10 to 20 m/s) as the twist
    unloads it; the flap's, from that nose-down angle of attack alone (c_hα < 0), is positive."""
    surfaces = [
        {"name": "flap", "from": 0.0, "to": 8.0, "hinge": 0.75},
        {"name": "aileron", "from": 12.0, "to": 16.0, "hinge": X_H, "deflection": 0.01},
    ]
    result = flexwing.Case(wing(16, surfaces, [10.0, 20.0])).statics()
    names = [s["name"] for s in result.aerodynamics["surfaces"]]
    assert names == ["flap", "aileron"]
    h = result.full.hinge_moments
    assert h.shape == (2, 2)
    assert h[0, 1] < 0 and 4.0 * h[0, 1] < h[1, 1] < h[0, 1]
    assert np.all(h[:, 0] > 0)
    assert not result.full.extra


@pytest.mark.parametrize(
    "key, value, field",
    [
        ("hinge", 1.0, "aero.surfaces[0].hinge"),
        ("to", 17.0, "aero.surfaces[0].to"),
        ("from", -1.0, "aero.surfaces[0].from"),
    ],
)
def test_bad_surfaces_name_the_key(key, value, field):
    surface = {"name": "aileron", "from": 12.0, "to": 16.0, "hinge": X_H}
    surface[key] = value
    with pytest.raises(CaseFileError) as info:
        flexwing.Case(wing(8, [surface], [10.0])).statics()
    assert info.value.field == field
    assert "\n" not in str(info.value)
