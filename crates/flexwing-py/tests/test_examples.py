"""Every script of examples/python runs to the end and prints what it claims (the numbers it
prints are checked elsewhere: against the CLI in test_against_cli.py; here a few claims each
script makes are checked on its output). sweep_dask.py runs in test_dask.py. matplotlib is not
in the test requirements, so the plotting branches are skipped by the scripts themselves."""

from __future__ import annotations

import re
import subprocess
import sys

import pytest

from conftest import ROOT

SCRIPTS = ROOT / "examples" / "python"


def run(name, tmp_path):
    done = subprocess.run(
        [sys.executable, str(SCRIPTS / name)], capture_output=True, text=True, cwd=tmp_path, timeout=300
    )
    assert done.returncode == 0, done.stderr
    assert list(tmp_path.iterdir()) == [], "an example wrote to the working directory"
    return done.stdout


def test_every_script_is_tested():
    tested = {"modes.py", "statics.py", "dynamics.py", "model_level.py", "stepper.py", "sweep_dask.py", "flutter.py"}
    assert {p.name for p in SCRIPTS.glob("*.py")} == tested


def test_modes(tmp_path):
    out = run("modes.py", tmp_path)
    assert "mode  1:" in out and "tapered EI" in out


def test_statics(tmp_path):
    out = run("statics.py", tmp_path)
    assert out.count("largest tip distance") == 3


def test_dynamics(tmp_path):
    out = run("dynamics.py", tmp_path)
    assert all(f"reduced-r{r}" in out for r in range(1, 5))


def test_model_level(tmp_path):
    """The script's own checks: the Jacobian agrees with central differences (O(h²) truncation
    plus round-off ε|f|/h ≈ 1e-16 · 170 / 1e-6 ≈ 2e-8: bound 1e-6), and the reduced model's
    linearized frequencies are the full model's modes (the reduced model is exact about the
    undeformed state: equal to the 4 printed digits)."""
    out = run("model_level.py", tmp_path)
    err = float(re.search(r"finite differences: (\S+)", out).group(1))
    assert err < 1e-6
    reduced = re.search(r"from its Jacobian \(Hz\): \[(.*)\]", out).group(1).split()
    full = re.search(r"full-model modes \(Hz\): +\[(.*)\]", out).group(1).split()
    assert reduced == full


def test_stepper(tmp_path):
    """The controller brings the tip to 0.3 m within 1 mm after 2 s (damped at 5 %: the first
    mode's envelope e^(-0.05·2π·8.8·2) is below 1e-2; the integral action removes the rest)."""
    out = run("stepper.py", tmp_path)
    final = float(re.search(r"final tip y = (\S+) m", out).group(1))
    assert final == pytest.approx(0.3, abs=1e-3)


def test_flutter(tmp_path):
    """Patil's wing at n = 32: the full model's flutter speed (Peters 6) and p-k flutter speed
    equal the chain's references computed by independent scripts (32.1148 and 32.5080 m/s,
    quoted to 4 decimals: bound 2e-4 m/s, the rounding plus the 1e-7 relative refinement), the
    reduced model on 8 wet modes within 1e-3 relative of the full model (measured 5e-6). The
    elastic-axis sweep at n = 16: every divergence speed is below its closed form by the
    chain's discretization error, −1.028e-1/n² = −4.02e-4 relative whatever e (the discrete
    torsion eigenproblem scales with e as the continuous one); bound ±5e-5 around it."""
    out = run("flutter.py", tmp_path)
    rows = {m.group(1): [float(v) for v in m.group(3, 4, 5, 6)] for m in re.finditer(
        r"^(full|reduced-r\d+) +(\d+) +(\S+) +(\S+) +(\S+) +(\S+) +\S+ ms$", out, re.M)}
    assert set(rows) == {"full", "reduced-r4", "reduced-r8"}
    flutter, omega, pk = rows["full"][1], rows["full"][2], rows["full"][3]
    assert flutter == pytest.approx(32.1148, abs=2e-4)
    assert omega == pytest.approx(22.5188, abs=2e-3)
    assert pk == pytest.approx(32.5080, abs=2e-4)
    assert rows["reduced-r8"][1] == pytest.approx(flutter, rel=1e-3)
    sweep = re.findall(r"^ (0\.\d\d) +complete +(\S+) +(\S+) +(\S+) +(\S+)$", out, re.M)
    assert len(sweep) == 5
    for _, _, _, divergence, closed in sweep:
        assert float(divergence) / float(closed) - 1.0 == pytest.approx(-4.02e-4, abs=5e-5)
