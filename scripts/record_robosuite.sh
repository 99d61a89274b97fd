#!/usr/bin/env bash
# Records robosuite 1.5.2's own rollouts, scenes and placements as test fixtures
# (scripts/record_robosuite.py) in robosuite-env/tests/fixtures/robosuite/.
#
# Not part of CI: it installs robosuite 1.5.2 with mujoco 3.3.7 from PyPI into a scratch
# virtualenv (.bench-venv/robosuite by default; BENCH_VENV overrides), shared with
# scripts/bench_vs_robosuite.sh. Usage:
#   scripts/record_robosuite.sh [--resets N] [TASK ...]
set -euo pipefail
cd "$(dirname "$0")/.."
venv=${BENCH_VENV:-.bench-venv/robosuite}
if [ ! -x "$venv/bin/python" ]; then
    python3 -m venv "$venv"
    "$venv/bin/pip" install --quiet "robosuite==1.5.2" "mujoco==3.3.7" gymnasium h5py
fi
"$venv/bin/python" scripts/record_robosuite.py "$@"
