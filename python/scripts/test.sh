#!/usr/bin/env bash
# Builds the Python package robosuite_rs into a project-local virtualenv and runs its tests.
#
#   python/scripts/test.sh [pytest args...]
#
# Creates <repo>/.venv if missing (python3 -m venv), installs maturin, pytest, pytest-xdist,
# hypothesis, gymnasium, numpy, mujoco==3.17.0, moviepy (for RecordVideo), h5py
# (robosuite_rs.datasets) and opencv-python (the renderer="mujoco" viewer) into it, installs
# Xvfb (the viewer tests' virtual display) with apt-get when missing and possible, builds the extension in release mode with
# `maturin develop` (the same build `pip install .` runs), builds the example of a user's
# own module (python/examples/own_module) and runs pytest on python/tests.
# Environment: PYTHON (default python3) picks the interpreter the virtualenv is made from;
# CARGO_TARGET_DIR is honoured (default: <repo>/target, shared with cargo);
# ROBOSUITE_RS_BUILD_ONLY=1 builds the extension (into python/robosuite_rs/) and stops
# (test_rl.sh and test_gym_versions.sh reuse that build from their own virtualenvs).
set -euo pipefail
cd "$(dirname "$0")/../.."
ROOT="$(pwd)"
VENV="$ROOT/.venv"
PYTHON="${PYTHON:-python3}"
# One target folder for the extension and the example module (outside the workspace), so
# the example reuses the dependencies the extension built.
export CARGO_TARGET_DIR="${CARGO_TARGET_DIR:-$ROOT/target}"

if [ ! -x "$VENV/bin/python" ]; then
    echo "test.sh: creating $VENV"
    "$PYTHON" -m venv "$VENV" || {
        echo "test.sh: '$PYTHON -m venv' failed; install the venv module (Debian: apt-get install python3-venv)" >&2
        exit 1
    }
fi
PY="$VENV/bin/python"
# Quiet, idempotent: pip skips what is already installed.
"$PY" -m pip install --quiet --disable-pip-version-check "maturin>=1.9,<2" pytest "gymnasium>=1.1" numpy "mujoco==3.17.0" hypothesis moviepy pytest-xdist h5py opencv-python

start=$(date +%s)
"$VENV/bin/maturin" develop --release --quiet --manifest-path "$ROOT/python/native/Cargo.toml"
echo "test.sh: extension built in $(( $(date +%s) - start )) s"
if [ "${ROBOSUITE_RS_BUILD_ONLY:-0}" = "1" ]; then
    exit 0
fi
# Not fatal here: without Xvfb only the viewer tests fail, saying what to install.
sh "$ROOT/build-support/install-xvfb.sh" || true

# The example of a user's own pyo3 module (python/examples/own_module, which depends on the
# robosuite-rs package installed above), tested by tests/test_own_module.py;
# ROBOSUITE_RS_SKIP_OWN_MODULE=1 skips building it. It links the robosuite-py library the
# extension above built (same features, same lock file versions), so only its own crate
# compiles.
if [ "${ROBOSUITE_RS_SKIP_OWN_MODULE:-0}" != "1" ]; then
    start=$(date +%s)
    "$VENV/bin/maturin" develop --release --quiet --manifest-path "$ROOT/python/examples/own_module/Cargo.toml"
    echo "test.sh: example module built in $(( $(date +%s) - start )) s"
fi

# pytest-xdist: one worker per core, at most 4 (each worker holds its own compiled
# scenes, up to ~5 GiB at the end of the suite); PYTEST_WORKERS overrides (0: no workers).
workers="${PYTEST_WORKERS:-$(nproc)}"
[ "$workers" -le 4 ] || workers=4
start=$(date +%s)
status=0
"$PY" -m pytest -q -n "$workers" --dist worksteal "$ROOT/python/tests" "$@" || status=$?
echo "test.sh: pytest finished in $(( $(date +%s) - start )) s"
exit $status
