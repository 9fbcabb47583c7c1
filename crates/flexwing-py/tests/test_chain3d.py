"""The 3-D chain (``beam.model = "chain3d"``) from Python against the CLI's JSON on the same
example files: both run the same plan through ``flexwing::analysis``, so the numbers agree to
round-off (1e-12 relative, as test_against_cli.py); what this checks is the binding: the names,
the array layouts (nodes × (x, y, z)), that nothing is dropped. The physics of these runs is
checked against the continuum rod and the closed forms by the CLI suite (``chain3d_cmd``) and the
library's ``aero3d_*``/``chain3d_*`` tests. Bad 3-D input raises an error naming the key."""

from __future__ import annotations

import numpy as np
import pytest

import flexwing

from conftest import example, run_cli

RTOL = 1e-12
ATOL = 1e-14


def close(a, b):
    np.testing.assert_allclose(np.asarray(a, dtype=float), np.asarray(b, dtype=float), rtol=RTOL, atol=ATOL)


def test_modes_match_the_cli(cli, tmp_path):
    expected = run_cli(cli, "modes", example("patil_3d_flutter.toml"), tmp_path)
    result = flexwing.Case.load(example("patil_3d_flutter.toml")).modes()
    assert isinstance(result, flexwing.Chain3dModesResult)
    assert (result.n_elements, result.n_dofs) == (expected["n_elements"], expected["n_dofs"]) == (32, 96)
    close(result.omega, [m["omega"] for m in expected["modes"]])
    close(result.displacement, [m["displacement"] for m in expected["modes"]])
    close(result.rotation, [m["rotation"] for m in expected["modes"]])
    close(result.position, expected["shape"]["position"])
    assert result.displacement.shape == (10, 33, 3)
    assert [m["energy_fraction"] for m in result.modes] == [m["energy_fraction"] for m in expected["modes"]]


def test_flutter_matches_the_cli(cli, tmp_path):
    expected = run_cli(cli, "flutter", example("patil_3d_flutter.toml"), tmp_path)
    result = flexwing.Case.load(example("patil_3d_flutter.toml")).flutter()
    assert isinstance(result, flexwing.Chain3dFlutterResult)
    assert expected["status"] == "complete"
    close(result.flutter_speed, expected["stability"]["flutter"]["speed"])
    close(result.flutter_frequency, expected["stability"]["flutter"]["frequency"])
    close(result.divergence_speed, expected["divergence"]["speed"])
    close(result.speed, [e["speed"] for e in expected["equilibria"]])
    close(result.tip, [e["tip"] for e in expected["equilibria"]])
    close(result.position, [e["shape"]["position"] for e in expected["equilibria"]])
    assert result.position.shape[1:] == (33, 3)
    for b, e in zip(result.stability["branches"], expected["stability"]["branches"]):
        assert b["mode"] == e["mode"]
        close(b["real"], e["real"])
        close(b["imag"], e["imag"])
    assert result.stability["status"] == expected["stability"]["status"]
    # 24 N tip force: the rod's 23.327657 m/s (chain3d_reference README §2), the n = 32 chain
    # 9.8e-3 m/s below it (CLI suite chain3d_cmd); the bound is that test's.
    assert abs(result.flutter_speed - 23.327657472220842) < 1.5e-2


def test_statics_match_the_cli(cli, tmp_path):
    expected = run_cli(cli, "static", example("swept_3d_wing.toml"), tmp_path)
    result = flexwing.Case.load(example("swept_3d_wing.toml")).statics()
    assert isinstance(result, flexwing.Chain3dStaticResult)
    close(result.scale, [p["scale"] for p in expected["points"]])
    close(result.position, [p["shape"]["position"] for p in expected["points"]])
    close(result.rotation, [p["shape"]["rotation"] for p in expected["points"]])
    assert result.tip.shape == (5, 3)
    assert len(result.loaded_modes) == len(expected["loaded_modes"]) == 4
    close([m["omega"] for m in result.loaded_modes], [m["omega"] for m in expected["loaded_modes"]])
    assert result.status["status"] == expected["status"] == "complete"


def test_study_matches_the_cli(cli, tmp_path):
    expected = run_cli(cli, "study", example("patil_3d_study.toml"), tmp_path)
    result = flexwing.Case.load(example("patil_3d_study.toml")).study()
    assert isinstance(result, flexwing.Chain3dStudyResult)
    assert result.parameter == expected["parameter"] == "tip-force"
    close(result.level, [p["level"] for p in expected["points"]])
    close(result.tip, [p["tip"] for p in expected["points"]])
    close(result.flutter_speed, [p["flutter"]["speed"] for p in expected["points"]])
    close(result.flutter_frequency, [p["flutter"]["frequency"] for p in expected["points"]])
    close(result.divergence_speed, [p["divergence"]["speed"] for p in expected["points"]])
    close(result.undeformed["speed"], expected["undeformed"]["speed"])
    # The fall of the flutter speed with the deflection, which the planar model misses.
    assert result.flutter_speed[-1] < 0.7 * result.undeformed["speed"]


@pytest.mark.parametrize(
    "change, key",
    [
        ({"section": {"EI_lag": 60.0}}, "beam.section.EI_lag"),
        ({"sweep": 0.1}, "beam.sweep"),
    ],
)
def test_a_3d_key_on_a_planar_case_names_the_key(change, key):
    beam = {"length": 1.0, "elements": 4, "section": {"EI": 50.0, "mass_per_length": 0.2}}
    for k, v in change.items():
        if isinstance(v, dict):
            beam[k] = {**beam[k], **v}
        else:
            beam[k] = v
    with pytest.raises(flexwing.InputError, match=key.replace(".", r"\.")):
        flexwing.Case(beam=beam).modes()


def test_bad_3d_values_name_the_key():
    text = example("swept_3d_wing.toml").read_text()
    with pytest.raises(flexwing.InputError, match=r"beam\.section\.EI_lag"):
        flexwing.Case.from_toml(text.replace("EI_lag = 60.0", "EI_lag = -60.0")).modes()
    with pytest.raises(flexwing.InputError, match=r"beam\.model"):
        flexwing.Case.load(example("patil_3d_flutter.toml")).dynamics()


def _steady_3d_case(tmp_path):
    """Patil's 3-D wing without its tip force, steady strip theory, root angle 1e-3, at 5 and
    10 m/s (the case of the CLI suite's closed-form test)."""
    text = example("patil_3d_flutter.toml").read_text()
    head = text.split("[flutter]")[0]
    beam, rest = head.split("[[loads]]")
    aero = rest.split("[aero]")[1]
    text = (
        (beam + "[aero]" + aero)
        .replace('{ model = "peters", states = 6 }', '{ model = "steady" }')
        .replace(
            "[aero.sweep]\nfrom = 2.0                 # m/s\nto = 40.0\nsteps = 20 ",
            "[aero.flight]\nroot_angle = 0.001\n\n[aero.sweep]\nfrom = 5.0\nto = 10.0\nsteps = 2 ",
        )
    )
    assert "root_angle = 0.001" in text
    path = tmp_path / "static3d.toml"
    path.write_text(text)
    return path


def test_aero_statics_match_the_cli_and_strip_theory(cli, tmp_path):
    case = _steady_3d_case(tmp_path)
    expected = run_cli(cli, "static", case, tmp_path / "out")
    result = flexwing.Case.load(case).statics()
    assert isinstance(result, flexwing.Chain3dAeroStaticResult)
    assert result.status["status"] == "complete"
    close(result.speed, [e["speed"] for e in expected["equilibria"]])
    close(result.tip, [e["tip"] for e in expected["equilibria"]])
    close(result.tip_twist, [e["tip_twist"] for e in expected["equilibria"]])
    close(result.lift, [e["lift"] for e in expected["equilibria"]])
    close(result.strip_lift, [e["strip_lift"] for e in expected["equilibria"]])
    close(result.strip_span, expected["strip_span"])
    close(result.position, [e["shape"]["position"] for e in expected["equilibria"]])
    assert result.strip_lift.shape == (2, 32) and result.position.shape == (2, 33, 3)
    # The total lift against steady strip theory's closed form q c c_lα α_r tan(λL)/λ of the
    # uniform wing in linear torsion: measured 2.9e-5 at 10 m/s, n = 32 (second order in n);
    # the bound is the CLI suite's (chain3d_cmd), twice that.
    q = 0.5 * 0.0889 * result.speed**2
    lam = np.sqrt(q * 2 * np.pi * 0.25 / 1e4)
    exact = q * 2 * np.pi * 1e-3 * np.tan(lam * 16.0) / lam
    np.testing.assert_allclose(result.lift, exact, rtol=6e-5)
    np.testing.assert_allclose(result.strip_lift.sum(axis=1), result.lift, rtol=1e-12)


def test_aero_statics_past_divergence_stop_with_the_rods_divergence():
    """Patil's wing under 24 N swept to 40 m/s: the sweep stops at 38 m/s (no stable
    equilibrium past the divergence), keeps the 18 equilibria before it, and gives the
    divergence speed within the CLI suite's bound of the continuum rod's (37.4357 m/s,
    chain3d_reference README §2; the chain's n = 32 error −3.6e-3 m/s); with check it raises
    SolverError. The notebook view shows the stop."""
    case = flexwing.Case.load(example("patil_3d_flutter.toml"))
    result = case.statics(check=False)
    assert isinstance(result, flexwing.Chain3dAeroStaticResult)
    assert result.status["status"] == "stopped" and "U = 38 m/s" in result.status["message"]
    assert len(result.equilibria) == 18 and result.speed[-1] == 36.0
    assert abs(result.divergence_speed - 37.43576864346924) < 5.5e-3
    assert "stopped" in result._repr_html_()
    with pytest.raises(flexwing.SolverError):
        case.statics()
