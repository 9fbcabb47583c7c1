"""The aeroelastic analyses against the CLI: the example cases with [aero] run through
`flexwing flutter|static|dynamic --json` and through Python must give the same numbers. Both
build the plan of the same case file with the case crate and run `flexwing::analysis::aero` (same
release build), so they agree to the last bit in practice; the tolerance (1e-12 relative, as
test_against_cli.py) only allows for a different summation order if the builds ever differ.
Counters, labels, branch and mode numbers must be equal exactly. The CSV files the CLI writes
beside its JSON carry what the JSON leaves out (tip x, dynamic pressure, divergence pressure,
node shapes): those are compared too (the CSV writer prints the shortest round-trip form of each
number, so they parse back exactly)."""

from __future__ import annotations

import csv

import numpy as np
import pytest

import flexwing

from conftest import example, run_cli

RTOL = 1e-12
ATOL = 1e-14


def close(a, b):
    np.testing.assert_allclose(np.asarray(a, dtype=float), np.asarray(b, dtype=float), rtol=RTOL, atol=ATOL)


def rows(path, model):
    with open(path, newline="") as f:
        return [r for r in csv.DictReader(f) if r["model"] == model]


def column(rs, key):
    """A CSV column as floats; an empty field (a non-finite number, or none) as inf."""
    return [float(r[key]) if r[key] != "" else np.inf for r in rs]


def same_stability(s: flexwing.Stability, expected):
    close(s.speeds, expected["speeds_m_s"])
    branches = expected["branches"]
    assert list(s.mode) == [b["mode"] for b in branches]
    close(s.wet_frequency, [b["wet_frequency_rad_s"] for b in branches])
    close(s.real, [b["real_1_s"] for b in branches])
    close(s.imag, [b["omega_rad_s"] for b in branches])
    close(s.damping_ratio, [b["damping_ratio"] for b in branches])
    assert list(s.uncertain) == [b["uncertain"] for b in branches]
    flutter = expected["flutter"]
    if flutter is None:
        assert s.flutter_speed is None and s.flutter_frequency is None and s.flutter_branch is None
    else:
        close(s.flutter_speed, flutter["speed_m_s"])
        close(s.flutter_frequency, flutter["frequency_rad_s"])
        assert s.flutter_branch == flutter["branch"]
    crossings = expected["crossings"]
    assert s.crossings["kind"] == [c["kind"] for c in crossings]
    close(s.crossings["speed"], [c["speed_m_s"] for c in crossings])
    close(s.crossings["frequency"], [c["frequency_rad_s"] for c in crossings])
    assert list(s.crossings["branch"]) == [c["branch"] for c in crossings]
    assert list(s.crossings["mode"]) == [c["mode"] for c in crossings]
    assert s.unstable_at_start == expected["unstable_at_start"]


@pytest.mark.parametrize("name", ["patil_flutter.toml", "section_flutter.toml"])
def test_flutter_matches_the_cli(cli, tmp_path, name):
    expected = run_cli(cli, "flutter", example(name), tmp_path)
    result = flexwing.Case.load(example(name)).flutter(check=False)
    assert result.status == expected["status"]
    close(result.speeds, expected["speeds_m_s"])
    assert [r.label for r in result.runs] == [m["label"] for m in expected["models"]]
    for run, model in zip(result.runs, expected["models"]):
        assert run.dofs == model["dofs"] and run.modes == model["modes"]
        assert run.status == model["status"]
        assert run.message == model["error"]
        if model["divergence"] is None:
            assert run.divergence_speed is None
            assert run.divergence_basis is None and run.divergence_within_sweep is None
        else:
            close(run.divergence_speed, model["divergence"]["speed_m_s"])
            close(run.divergence_dynamic_pressure, model["divergence"]["dynamic_pressure_pa"])
            assert run.divergence_basis == model["divergence"]["basis"]
            assert run.divergence_within_sweep == model["divergence"]["within_sweep"]
        same_stability(run.eigenvalues, model["eigenvalues"])
        assert run.flutter_speed == run.eigenvalues.flutter_speed
        if model["pk"] is None:
            assert run.pk is None
        else:
            same_stability(run.pk, model["pk"])
        eq = run.equilibria
        points = model["equilibria"]
        assert (eq.status == "complete") == model["equilibria_complete"]
        close(eq.speed, [p["speed_m_s"] for p in points])
        close(eq.tip_y, [p["tip_y_m"] for p in points])
        close(eq.tip_twist, [p["tip_twist_rad"] for p in points])
        close(eq.lift, [p["lift_n"] for p in points])
        close(eq.root_bending_moment, [p["root_bending_moment_n_m"] for p in points])
        rs = rows(tmp_path / "flutter_equilibria.csv", run.label)
        close(eq.tip_x, column(rs, "tip_x_m"))
        close(eq.dynamic_pressure, column(rs, "dynamic_pressure_pa"))
        assert eq.divergence_pressure == [
            None if r["divergence_pressure_pa"] == "" else float(r["divergence_pressure_pa"]) for r in rs
        ]
        nodes = rows(tmp_path / "flutter_nodes.csv", run.label)
        close(eq.y.ravel(), column(nodes, "y_m"))
        close(eq.twist.ravel(), column(nodes, "twist_rad"))


@pytest.mark.parametrize("name", ["patil_flutter.toml", "patil_gust.toml"])
def test_aero_statics_match_the_cli(cli, tmp_path, name):
    """patil_flutter.toml's sweep to 40 m/s stops past the divergence speed (37.15 m/s): the
    partial result and its stop are compared too; patil_gust.toml is one point at 25 m/s and a
    2° root angle."""
    expected = run_cli(cli, "static", example(name), tmp_path)
    result = flexwing.Case.load(example(name)).statics(check=False)
    assert isinstance(result, flexwing.AeroStaticResult)
    assert result.status == expected["status"]
    assert [r.label for r in result.runs] == [m["summary"]["model"] for m in expected["models"]]
    for run, model in zip(result.runs, expected["models"]):
        summary, points = model["summary"], model["points"]
        assert run.dofs == summary["dofs"]
        assert run.status == summary["status"]
        assert run.message == summary["error"]
        assert run.divergence_within_sweep == summary["divergence_within_sweep"]
        if summary["divergence_speed_m_s"] is None:
            assert run.divergence_speed is None
        else:
            close(run.divergence_speed, summary["divergence_speed_m_s"])
        close(run.speed, [p["speed_m_s"] for p in points])
        close(run.dynamic_pressure, [p["dynamic_pressure_pa"] for p in points])
        close(run.tip_x, [p["tip_x_m"] for p in points])
        close(run.tip_y, [p["tip_y_m"] for p in points])
        close(run.tip_twist, [p["tip_twist_rad"] for p in points])
        close(run.lift, [p["lift_n"] for p in points])
        close(run.root_bending_moment, [p["root_bending_moment_n_m"] for p in points])
        assert run.divergence_pressure == [p["divergence_pressure_pa"] for p in points]
        assert list(run.stats["iterations"]) == [p["iterations"] for p in points]
        nodes = rows(tmp_path / "static_nodes.csv", run.label)
        close(run.x.ravel(), column(nodes, "x_m"))
        close(run.y.ravel(), column(nodes, "y_m"))
        close(run.twist.ravel(), column(nodes, "twist_rad"))


def test_gust_response_matches_the_cli(cli, tmp_path):
    expected = run_cli(cli, "dynamic", example("patil_gust.toml"), tmp_path)
    result = flexwing.Case.load(example("patil_gust.toml")).dynamics(check=False)
    assert isinstance(result, flexwing.AeroDynamicResult)
    assert result.status == expected["status"]
    assert [r.label for r in result.runs] == [m["summary"]["model"] for m in expected["models"]]
    for run, model in zip(result.runs, expected["models"]):
        summary, samples = model["summary"], model["samples"]
        assert run.dofs == summary["dofs"] and run.aero_states == summary["aero_states"]
        assert run.integrator == summary["integrator"]
        for key in ["steps", "rejected_steps", "rhs_evaluations", "jacobian_evaluations", "factorizations"]:
            assert run.stats[key] == summary[key], key
        assert run.status == summary["status"]
        if summary["max_tip_difference_m"] is None:
            assert run.max_tip_difference is None
        else:
            close(run.max_tip_difference, summary["max_tip_difference_m"])
        for attr, key in [
            ("t", "t_s"),
            ("tip_x", "tip_x_m"),
            ("tip_y", "tip_y_m"),
            ("tip_twist", "tip_twist_rad"),
            ("root_bending_moment", "root_bending_moment_n_m"),
            ("lift", "lift_n"),
            ("speed", "speed_m_s"),
            ("kinetic", "kinetic_j"),
            ("strain", "strain_j"),
            ("work", "work_j"),
            ("dissipated", "dissipated_j"),
            ("balance_error", "energy_balance_error"),
        ]:
            close(getattr(run, attr), [s[key] for s in samples])
        # The energy audit: the library's data in both, and the CLI's summary columns.
        audit = run.energy_audit
        assert audit == model["energy_audit"]
        close(audit["max_error"], summary["energy_balance_max_error"])
        close(audit["limit"], summary["energy_balance_limit"])
