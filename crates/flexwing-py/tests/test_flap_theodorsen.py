"""The flap's frequency response against Theodorsen's closed form (NACA TR 496), written here:
a stiff wing (EI = GJ = 1e10 N·m², so that it barely moves and each strip is a typical section
at rest) with a full-span flap, hinge at 80 % of the chord, elastic axis at mid-chord (a = 0),
at k = 0.05, 0.1, 0.3, 0.6, 1.0. The linear model's lift and root torque to δ, δ̇, δ̈ combined
(`G_δ + iω G_δ̇ − ω² G_δ̈`, docs/control.md) against the span times Theodorsen's lift and moment
per unit span,

    L = −ρb²(U T4 δ̇ + b T1 δ̈) + 2πρUb C(k) Q
    M = −ρb²[(T4 + T10)U²δ + (T1 − T8 − (c−a)T4 + ½T11)Ub δ̇ − (T7 + (c−a)T1)b²δ̈]
        + 2πρUb²(a + ½) C(k) Q,      Q = U T10 δ/π + b T11 δ̇/(2π),

with each model's own C(k): Jones' two-term approximation for Wagner, Peters' finite-state
transfer function for Peters (both written here from their papers' constants), and Theodorsen's
exact C(k) = H₁⁽²⁾/(H₁⁽²⁾ + iH₀⁽²⁾) (SciPy's Hankel functions)."""

from __future__ import annotations

import math

import numpy as np
import pytest

import flexwing

from conftest import example

special = pytest.importorskip("scipy.special")

U, RHO, B, X_H, SPAN = 10.0, 0.0889, 0.5, 0.8, 16.0
K = [0.05, 0.1, 0.3, 0.6, 1.0]
NAMES = ["delta[flap]", "delta_rate[flap]", "delta_acceleration[flap]"]


def stiff_case(aerodynamics):
    d = flexwing.Case.load(example("patil_aileron.toml")).to_dict()
    d["aero"].pop("sweep")
    d["beam"]["section"].update({"EI": 1e10, "GJ": 1e10})
    d["aero"]["aerodynamics"] = aerodynamics
    d["aero"]["surfaces"] = [{"name": "flap", "from": 0.0, "to": SPAN, "hinge": X_H}]
    d["aero"]["flight"] = {"speed": U}
    return flexwing.Case(d)


def theodorsen(k, C, a=0.0):
    """Lift (N, up) and moment (N·m, nose-up about the elastic axis) of the whole span per unit
    δ̂ for δ = δ̂ e^{iωt}, with the lift deficiency `C`."""
    c = 2.0 * X_H - 1.0
    s, ac = math.sqrt(1.0 - c * c), math.acos(c)
    t1 = -s * (2.0 + c * c) / 3.0 + c * ac
    t4 = -ac + c * s
    t7 = -(1.0 / 8.0 + c * c) * ac + c * s * (7.0 + 2.0 * c * c) / 8.0
    t8 = -s * (2.0 * c * c + 1.0) / 3.0 + c * ac
    t10 = s + ac
    t11 = ac * (1.0 - 2.0 * c) + s * (2.0 - c)
    w = k * U / B
    d, dr, da = 1.0, 1j * w, -w * w
    q = U * t10 * d / math.pi + B * t11 * dr / (2.0 * math.pi)
    lift = -RHO * B**2 * (U * t4 * dr + B * t1 * da) + 2.0 * math.pi * RHO * U * B * C * q
    moment = -RHO * B**2 * (
        (t4 + t10) * U**2 * d
        + (t1 - t8 - (c - a) * t4 + 0.5 * t11) * U * B * dr
        - (t7 + (c - a) * t1) * B**2 * da
    ) + 2.0 * math.pi * RHO * U * B**2 * (a + 0.5) * C * q
    circulatory = 2.0 * math.pi * RHO * U * B * q * np.array([1.0, B * (a + 0.5)])
    return np.array([lift, moment]) * SPAN, np.abs(circulatory) * SPAN


def c_exact(k):
    h1, h0 = special.hankel2(1, k), special.hankel2(0, k)
    return h1 / (h1 + 1j * h0)


def c_jones(k):
    """R. T. Jones' approximation of Wagner's function (docs/aeroelastic-model.md §4)."""
    (a1, a2), (b1, b2), s = (0.165, 0.335), (0.0455, 0.3), 1j * k
    return 1.0 - a1 * s / (s + b1) - a2 * s / (s + b2)


def c_peters(k, n):
    """Peters' finite-state inflow, `1 − ½ s bᵀ(s A + I)⁻¹ c` at s = ik (Peters, Karunamoorthy &
    Cao 1995)."""
    idx = np.arange(1, n + 1)
    dmat = np.zeros((n, n))
    for i in range(n):
        if i > 0:
            dmat[i, i - 1] = 1.0 / (2 * idx[i])
        if i < n - 1:
            dmat[i, i + 1] = -1.0 / (2 * idx[i])
    bvec = np.array(
        [
            (-1) ** (m - 1) * math.factorial(n + m - 1) / (math.factorial(n - m - 1) * math.factorial(m) ** 2)
            if m < n
            else (-1) ** (n - 1)
            for m in idx
        ],
        dtype=float,
    )
    cvec = 2.0 / idx
    dvec = np.zeros(n)
    dvec[0] = 0.5
    amat = dmat + np.outer(dvec, bvec) + np.outer(cvec, dvec) + 0.5 * np.outer(cvec, bvec)
    s = 1j * k
    return 1.0 - 0.5 * s * bvec @ np.linalg.solve(s * amat + np.eye(n), cvec)


@pytest.mark.parametrize(
    "aerodynamics, own_c",
    [({"model": "wagner"}, c_jones), ({"model": "peters", "states": 8}, lambda k: c_peters(k, 8))],
)
def test_the_flap_frequency_response_is_theodorsens(aerodynamics, own_c):
    lin = stiff_case(aerodynamics).linearize(inputs=NAMES, outputs=["lift", "root_torque"]).runs[0]
    for k in K:
        w = k * U / B
        g = lin.frequency_response([w], NAMES, ["lift", "root_torque"])[0]
        got = g[:, 0] + 1j * w * g[:, 1] - w * w * g[:, 2]
        # With the model's own C(k) the closed form is the model's: what is left is the stiff
        # wing's own motion (twist ~ M L²/GJ ~ 1e-7 rad) and the strips' discretization of a
        # uniform load (none): 5e-5 of each load (measured ≤ 1.7e-5).
        own, _ = theodorsen(k, own_c(k))
        assert np.all(np.abs(got - own) < 5e-5 * np.abs(own)), (k, got, own)
        # Against Theodorsen's exact C(k) the difference is the circulatory part times the
        # model's error of C(k), |C_model − C|: bounded by it (and the 5e-5 above).
        exact, circulatory = theodorsen(k, c_exact(k))
        bound = circulatory * abs(own_c(k) - c_exact(k)) + 5e-5 * np.abs(exact)
        assert np.all(np.abs(got - exact) <= bound), (k, got, exact, bound)
    # One sign: a trailing-edge-down flap raises the lift (its static gain).
    assert np.real(lin.frequency_response([1e-6], NAMES, ["lift"])[0][0, 0]) > 0.0
