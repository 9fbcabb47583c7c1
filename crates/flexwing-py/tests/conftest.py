"""Shared fixtures: the repository's paths, the `flexwing` binary whose `--json` output the
bindings are compared with, and the paper's cases."""

from __future__ import annotations

import json
import os
import pathlib
import subprocess

import pytest

import flexwing

ROOT = pathlib.Path(__file__).resolve().parents[3]
EXAMPLES = ROOT / "examples"


def example(name: str) -> pathlib.Path:
    return EXAMPLES / name


@pytest.fixture(scope="session")
def cli() -> pathlib.Path:
    """The `flexwing` binary: $FLEXWING_CLI, else target/release/flexwing (./test.sh builds it
    and sets the variable). Missing is a failure, not a skip: the comparison is the point."""
    path = pathlib.Path(os.environ.get("FLEXWING_CLI", ROOT / "target" / "release" / "flexwing"))
    if not path.exists():
        pytest.fail(
            f"the flexwing binary {path} is missing: build it with "
            "`cargo build --release -p flexwing-cli` or set FLEXWING_CLI"
        )
    return path


def run_cli(cli: pathlib.Path, command: str, case: pathlib.Path, out: pathlib.Path) -> dict:
    """`flexwing COMMAND CASE --json --out OUT`, parsed."""
    done = subprocess.run(
        [str(cli), command, str(case), "--json", "--out", str(out)],
        capture_output=True,
        text=True,
        check=False,
    )
    assert done.returncode in (0, 1), done.stderr
    return json.loads(done.stdout)


@pytest.fixture(scope="session")
def sine_case() -> flexwing.Case:
    """The paper's case (b): examples/paper_sine.toml."""
    return flexwing.Case.load(example("paper_sine.toml"))


@pytest.fixture(scope="session")
def static_case() -> flexwing.Case:
    """The paper's two-load sweep (Figure 4): examples/paper_static.toml."""
    return flexwing.Case.load(example("paper_static.toml"))


def aileron_case(speed, deflection, dynamic=True, **section):
    """examples/patil_aileron.toml as a dict at one speed, Wagner's lag, the aileron at
    `deflection`; `section` overrides `[beam.section]` keys; with `[dynamic]` (rtol 1e-8)."""
    d = flexwing.Case.load(example("patil_aileron.toml")).to_dict()
    d["aero"].pop("sweep")
    d["beam"]["section"].update(section)
    d["aero"]["aerodynamics"] = {"model": "wagner"}
    d["aero"]["surfaces"][1]["deflection"] = deflection
    d["aero"]["flight"] = {"speed": speed}
    if dynamic:
        d["dynamic"] = {"end_time": 1.0, "output_step": 0.01, "rtol": 1e-8, "atol": 1e-10}
    return d
