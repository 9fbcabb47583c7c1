"""The model level: a beam from arrays of section properties, its full and reduced models, and
their equations of motion evaluated at a state (NumPy in, NumPy out), for your own integrator
or linearization.

    python examples/python/model_level.py
"""

from __future__ import annotations

import numpy as np

import flexwing

# A tapered beam with torsion: properties at stations x (m), linear in between.
x = np.array([0.0, 0.5, 1.0])
beam = flexwing.Beam(
    length=1.0,
    elements=20,
    x=x,
    EI=np.array([80.0, 50.0, 30.0]),  # N m^2
    GJ=np.array([10.0, 8.0, 6.0]),  # N m^2
    mass_per_length=0.2,  # kg/m
    polar_inertia=1e-3,  # kg m
    polar_inertia_about="mass-centre",
    d0=0.01,  # m, mass centre ahead of the elastic axis
)
full = flexwing.FullModel(beam)
print(beam, full)
K = full.stiffness_matrix()  # N m/rad
print("K diagonal (N m/rad):", np.round(np.diag(K)[:4], 2), "...")

# The equations under a dead tip force of 10 N scaled by 0.5, at a random state (explicit seed).
load = {"type": "point-force", "span": 1.0, "direction": "dead", "fy": 10.0}
eom = full.equations([load], scales=[0.5])
rng = np.random.default_rng(1)
y = eom.state(rng.normal(scale=0.05, size=full.n_dofs), np.zeros(full.n_dofs))
dydt = eom.rhs(0.0, y)
J = eom.jacobian(0.0, y)
kinetic, strain = eom.energies(y)
print(f"|dy/dt| = {np.linalg.norm(dydt):.4f}, Jacobian {J.shape}, strain energy {strain:.4e} J")

# The Jacobian against central differences of the right-hand side.
h = 1e-6
fd = np.column_stack([(eom.rhs(0.0, y + h * e) - eom.rhs(0.0, y - h * e)) / (2 * h) for e in np.eye(y.size)])
print(f"Jacobian vs finite differences: {np.abs(J - fd).max():.2e}")

# A reduced model on the first 4 modes, and its linearization about the undeformed state.
reduced = full.reduced(4)
r_eom = reduced.equations([load], scales=[0.0])
A = r_eom.jacobian(0.0, np.zeros(2 * reduced.n_dofs))
omega = np.sort(np.abs(np.linalg.eigvals(A).imag))[::2]
print("reduced-model frequencies from its Jacobian (Hz):", np.round(omega / (2 * np.pi), 4))
print("full-model modes (Hz):                         ", np.round(full.modes(4).frequency_hz, 4))
