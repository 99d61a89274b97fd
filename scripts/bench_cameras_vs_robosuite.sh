#!/usr/bin/env bash
# Camera env steps per second of Lift from Python: robosuite 1.5.2 (its virtualenv,
# MUJOCO_GL=egl) and robosuite-rs (the project's .venv, both render qualities), one camera
# and two, 84x84 and 256x256, each library in one process (scripts/bench_cameras.py), then
# a table. Not part of CI. Usage:
#   scripts/bench_cameras_vs_robosuite.sh [SECONDS]
# BENCH_VENV picks robosuite's virtualenv (default .bench-venv/robosuite, as
# scripts/bench_vs_robosuite.sh makes it); RS_PYTHON the robosuite-rs interpreter.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-8}
venv=${BENCH_VENV:-.bench-venv/robosuite}
rs_python=${RS_PYTHON:-.venv/bin/python}
out=$(mktemp)
trap 'rm -f "$out"' EXIT
MUJOCO_GL=egl "$venv/bin/python" scripts/bench_cameras.py --lib robosuite --seconds "$seconds" | tee -a "$out"
"$rs_python" scripts/bench_cameras.py --lib rs --seconds "$seconds" | tee -a "$out"
python3 - "$out" <<'EOF'
import json, sys
rows = [json.loads(l) for l in open(sys.argv[1]) if l.startswith("{")]
by = {(r["lib"], r["cameras"], r["size"], r["quality"]): r["steps_per_s"] for r in rows}
print()
print("| cameras | size | robosuite 1.5.2 | robosuite-rs, render_quality=\"robosuite\" | robosuite-rs, \"fast\" (default) |")
print("|---|---|---|---|---|")
for cams in sorted({r["cameras"] for r in rows}, key=len):
    for size in sorted({r["size"] for r in rows}):
        base = by.get(("robosuite", cams, size, "robosuite"))
        cells = []
        for q in ("robosuite", "fast"):
            v = by.get(("rs", cams, size, q))
            cells.append("—" if v is None else f"{v:.1f}" + (f" ({v / base:.1f}×)" if base else ""))
        print(f"| {cams} | {size}² | {'—' if base is None else f'{base:.1f}'} | {cells[0]} | {cells[1]} |")
EOF
