#!/usr/bin/env bash
# Runs the Gymnasium-facing tests on the lowest and newest Gymnasium the package supports.
#
#   python/scripts/test_gym_versions.sh [VERSION...]   (default: 1.1.0 and the newest release)
#
# pyproject.toml declares gymnasium>=1.1 (1.1.0 is the first release with
# `gymnasium.vector.AutoresetMode`). For each VERSION this makes <repo>/.venv-gym-VERSION
# (python3 -m venv), installs gymnasium==VERSION (or the newest for "latest") with numpy,
# mujoco==3.17.0, pytest, pytest-xdist and hypothesis, points it at the extension that test.sh builds
# into python/robosuite_rs/ (an abi3 build: any CPython >= 3.10 loads it) and runs
# python/tests/test_ecosystem.py, test_cleanrl_port.py, test_vector.py and test_check_env.py
# (check_env on every registered id; not the every-robot sweeps, which test.sh runs) there.
set -euo pipefail
cd "$(dirname "$0")/../.."
ROOT="$(pwd)"
PYTHON="${PYTHON:-python3}"
VERSIONS=("$@")
[ ${#VERSIONS[@]} -gt 0 ] || VERSIONS=(1.1.0 latest)

ROBOSUITE_RS_BUILD_ONLY=1 bash "$ROOT/python/scripts/test.sh"

workers="${PYTEST_WORKERS:-$(nproc)}"
[ "$workers" -le 4 ] || workers=4
status=0
for version in "${VERSIONS[@]}"; do
    venv="$ROOT/.venv-gym-$version"
    [ -x "$venv/bin/python" ] || "$PYTHON" -m venv "$venv"
    spec="gymnasium==$version"
    [ "$version" = "latest" ] && spec="gymnasium"
    "$venv/bin/python" -m pip install --quiet --disable-pip-version-check --upgrade "$spec" numpy "mujoco==3.17.0" pytest pytest-xdist hypothesis
    site="$("$venv/bin/python" -c 'import sysconfig; print(sysconfig.get_paths()["purelib"])')"
    echo "$ROOT/python" > "$site/robosuite_rs_source.pth"
    installed="$("$venv/bin/python" -c 'import gymnasium; print(gymnasium.__version__)')"
    echo "test_gym_versions.sh: gymnasium $installed"
    "$venv/bin/python" -m pytest -q -p no:cacheprovider -n "$workers" --dist worksteal -k "not every_task_with_every" \
        "$ROOT/python/tests/test_ecosystem.py" "$ROOT/python/tests/test_cleanrl_port.py" \
        "$ROOT/python/tests/test_vector.py" "$ROOT/python/tests/test_check_env.py" \
        || status=$?
done
exit $status
