#!/usr/bin/env bash
# Compares robosuite 1.5.2's GymWrapper (Python, mujoco==3.3.7) with robosuite-rs from Rust
# and (with the project's .venv, made by `make test`) from Python, on one task, in
# interleaved rounds (scripts/compare_with_robosuite.py); prints medians and ratios.
#
# Not part of CI: it installs robosuite from PyPI into a scratch virtualenv
# (.bench-venv/robosuite by default; BENCH_VENV overrides). Usage:
#   scripts/bench_vs_robosuite.sh [TASK] [SECONDS] [ROUNDS]
set -euo pipefail
cd "$(dirname "$0")/.."
task=${1:-Lift}
seconds=${2:-10}
rounds=${3:-5}
venv=${BENCH_VENV:-.bench-venv/robosuite}
if [ ! -x "$venv/bin/python" ]; then
    python3 -m venv "$venv"
    "$venv/bin/pip" install --quiet "robosuite==1.5.2" "mujoco==3.3.7" gymnasium h5py
fi
cargo build --release -q -p tools --bin benchmark
rs_python=()
if [ -x .venv/bin/python ] && .venv/bin/python -c "import robosuite_rs" 2> /dev/null; then
    rs_python=(--rs-python .venv/bin/python)
fi
python3 scripts/compare_with_robosuite.py --robosuite-python "$venv/bin/python" "${rs_python[@]}" \
    --task "$task" --seconds "$seconds" --rounds "$rounds" --json .bench-vs-robosuite.json
