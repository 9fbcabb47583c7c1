"""Natural modes of the paper's Table 1 beam (examples/table1.toml), from Python.

    python examples/python/modes.py

Prints the frequencies (Hz) and the bending share of each mode; with matplotlib installed,
plots the first mode shapes (saved nowhere: shown in a window).
"""

from __future__ import annotations

import pathlib

import flexwing

HERE = pathlib.Path(__file__).resolve().parent
case = flexwing.Case.load(HERE.parent / "table1.toml")
result = case.modes()  # a ModesResult: arrays by increasing frequency
print(f"{case.title}: {result.n_elements} elements, {result.n_dofs} coordinates")
for k, f, b in zip(result.mode, result.frequency_hz, result.bending_energy_fraction):
    print(f"  mode {k:2d}: {f:10.4f} Hz  ({100 * b:5.1f} % bending)")

# The same from a beam built from arrays: 30 elements, EI falling linearly along the span.
beam = flexwing.Beam(length=1.0, elements=30, EI=[80.0, 20.0], x=[0.0, 1.0], mass_per_length=0.2)
tapered = flexwing.FullModel(beam).modes(count=3)
print("tapered EI 80 -> 20 N m^2:", ", ".join(f"{f:.3f} Hz" for f in tapered.frequency_hz))

try:
    import matplotlib.pyplot as plt
except ImportError:
    pass
else:
    for k in range(3):
        plt.plot(result.x, result.dy[k], label=f"mode {result.mode[k]}: {result.frequency_hz[k]:.2f} Hz")
    plt.xlabel("x (m)")
    plt.ylabel("dy (m, mass-normalized)")
    plt.legend()
    plt.show()
