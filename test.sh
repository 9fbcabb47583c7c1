#!/usr/bin/env bash
# The project's tests, in one command: the Rust workspace (`cargo test --workspace --exclude
# flexwing-py --release --lib --bins --tests`),
# then the Python package — built with maturin from the same release build and installed into a
# virtual environment (`.venv`, created if missing; `FLEXWING_VENV` picks another), where pytest
# runs its suite (crates/flexwing-py/tests) against the `flexwing` binary of the same build.
# Needs only Rust and Python ≥ 3.11 with its venv module (the pinned numpy needs 3.11; the
# package itself runs on ≥ 3.9); maturin, numpy, pytest, hypothesis, dask[distributed] and the
# optional extras the views use come from PyPI (crates/flexwing-py/requirements-test.txt).
#
#   ./test.sh                 everything
#   ./test.sh --python-only   the Python part alone (after a Rust build)
#   ./test.sh -- -k stepper   extra arguments after -- go to pytest
set -euo pipefail
cd "$(dirname "$0")"

rust=1
pytest_args=()
while [ $# -gt 0 ]; do
    case "$1" in
        --python-only) rust=0 ;;
        --) shift; pytest_args=("$@"); break ;;
        *) echo "test.sh: unknown argument $1 (use --python-only, or -- PYTEST-ARGS)" >&2; exit 2 ;;
    esac
    shift
done

if [ "$rust" = 1 ]; then
    # Libraries, binaries and test targets: the examples are left out (they hold no tests; .ci/run's
    # clippy --all-targets still compiles them) and there are no doctests. The bindings
    # (flexwing-py) are left out too: they have no Rust tests, and maturin below compiles them
    # (and pyo3, numpy) again for the extension module anyway — their test build took about
    # 2 min of unit time on a fresh clone (cargo --timings, loaded machine) for 0 tests.
    cargo test --workspace --exclude flexwing-py --release --lib --bins --tests
fi

venv="${FLEXWING_VENV:-.venv}"
python="${PYTHON:-python3}"
if [ ! -x "$venv/bin/python" ]; then
    echo "test.sh: creating the virtual environment $venv" >&2
    if ! "$python" -m venv "$venv"; then
        echo "test.sh: '$python -m venv' failed; install Python's venv module (Debian and" \
             "Ubuntu: apt-get install python3-venv) or set PYTHON to another Python 3" >&2
        exit 1
    fi
fi
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check \
    -r crates/flexwing-py/requirements-test.txt

# The wheel is built from the release build above: only pyo3 and the binding itself compile.
wheels=target/wheels
rm -f "$wheels"/flexwing-*.whl
"$venv/bin/maturin" build --release --quiet -m crates/flexwing-py/Cargo.toml -o "$wheels"
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check --force-reinstall \
    --no-deps "$wheels"/flexwing-*.whl

# The CLI whose --json output the bindings are compared with (built by cargo test above).
export FLEXWING_CLI="${FLEXWING_CLI:-$PWD/target/release/flexwing}"
if [ ! -x "$FLEXWING_CLI" ]; then
    cargo build --release -p flexwing-cli
fi
# The co-simulation FMU's library (crates/flexwing-fmu, a cdylib) that `flexwing fmu` and
# `Case.fmu` put into the FMUs test_fmu.py runs with FMPy.
export FLEXWING_FMU_LIBRARY="${FLEXWING_FMU_LIBRARY:-$PWD/target/release/libflexwing_fmu.so}"
if [ "$rust" = 1 ] || [ ! -f "$FLEXWING_FMU_LIBRARY" ]; then
    cargo build --release -p flexwing-fmu
fi
status=0
"$venv/bin/python" -m pytest crates/flexwing-py/tests "${pytest_args[@]}" || status=$?
if [ "$status" = 5 ]; then
    echo "test.sh: pytest collected no tests (exit status 5): the Python suite is missing" >&2
    exit 1
fi
exit "$status"
