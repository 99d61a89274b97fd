#!/usr/bin/env bash
# Measures robosuite 1.5.2's GymWrapper (Python, mujoco==3.3.7) and robosuite-rs on the
# same task in the same run, and prints both and their ratio; with the project's .venv
# (made by `make test`) it also measures robosuite_rs from Python (Lift).
#
# Not part of CI: it installs robosuite from PyPI into a scratch virtualenv
# (.bench-venv/robosuite by default). Usage:
#   scripts/bench_vs_robosuite.sh [TASK] [SECONDS]
set -euo pipefail
cd "$(dirname "$0")/.."
task=${1:-Lift}
seconds=${2:-15}
venv=${BENCH_VENV:-.bench-venv/robosuite}
if [ ! -x "$venv/bin/python" ]; then
    python3 -m venv "$venv"
    "$venv/bin/pip" install --quiet "robosuite==1.5.2" "mujoco==3.3.7" gymnasium h5py
fi
echo "robosuite 1.5.2 (Python GymWrapper):"
MUJOCO_GL=disable "$venv/bin/python" scripts/bench_robosuite.py --task "$task" --seconds "$seconds" > .bench-robosuite.json
cat .bench-robosuite.json
echo "robosuite-rs (Rust, one thread):"
cargo run --release -q -p examples --example benchmark -- --task "$task" --seconds "$seconds" --json .bench-rust.json > /dev/null
cat .bench-rust.json
python3 - <<'PY'
import json
py = json.load(open(".bench-robosuite.json"))
rs = json.load(open(".bench-rust.json"))
task = py["task"]
rust = next(t for t in rs["tasks"] if t["task"] == task)
print(f"{task}: robosuite {py['steps_per_s']:.0f} steps/s, robosuite-rs {rust['steps_per_s']:.0f} steps/s, "
      f"ratio {rust['steps_per_s'] / py['steps_per_s']:.1f}x; reset {py['reset_ms']:.1f} ms vs {rust['reset_us'] / 1000:.3f} ms")
PY
if [ -x .venv/bin/python ] && [ "$task" = Lift ]; then
    echo "robosuite_rs from Python (python/scripts/bench.py):"
    .venv/bin/python python/scripts/bench.py
fi
