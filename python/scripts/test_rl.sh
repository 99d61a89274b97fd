#!/usr/bin/env bash
# The optional RL test group: Stable-Baselines3, Ray RLlib and the torch examples.
#
#   python/scripts/test_rl.sh [pytest args...]        (`make test-rl`)
#
# Builds the extension as test.sh does (into python/robosuite_rs/), makes <repo>/.venv-rl
# (python3 -m venv) with stable-baselines3, ray[rllib] (torch comes with SB3: a large
# download, ~3 GB with its CUDA wheels), matplotlib, pytest and the package's own
# dependencies, points it at the built package and runs python/tests_rl (pytest marker
# `rl`). Not part of `make test`. ROBOSUITE_RS_SETUP_ONLY=1 stops before pytest.
set -euo pipefail
cd "$(dirname "$0")/../.."
ROOT="$(pwd)"
VENV="$ROOT/.venv-rl"
PYTHON="${PYTHON:-python3}"

ROBOSUITE_RS_BUILD_ONLY=1 bash "$ROOT/python/scripts/test.sh"

[ -x "$VENV/bin/python" ] || "$PYTHON" -m venv "$VENV"
PY="$VENV/bin/python"
"$PY" -m pip install --quiet --disable-pip-version-check "stable-baselines3>=2.4" "ray[rllib]>=2.40" matplotlib h5py \
    pytest hypothesis "gymnasium>=1.1" numpy "mujoco==3.17.0"
site="$("$PY" -c 'import sysconfig; print(sysconfig.get_paths()["purelib"])')"
echo "$ROOT/python" > "$site/robosuite_rs_source.pth"
"$PY" -c 'import gymnasium, stable_baselines3, ray, torch; print(f"test_rl.sh: gymnasium {gymnasium.__version__}, SB3 {stable_baselines3.__version__}, ray {ray.__version__}, torch {torch.__version__}")'
[ "${ROBOSUITE_RS_SETUP_ONLY:-0}" = "1" ] && exit 0  # the venv only (make bench-sb3)

start=$(date +%s)
status=0
"$PY" -m pytest -q -p no:cacheprovider "$ROOT/python/tests_rl" "$@" || status=$?
echo "test_rl.sh: pytest finished in $(( $(date +%s) - start )) s"
exit $status
