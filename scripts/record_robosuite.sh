#!/usr/bin/env bash
# Records robosuite 1.5.2's own rollouts, scenes and placements as test fixtures
# (scripts/record_robosuite.py) in robosuite-env/tests/fixtures/robosuite/, then measures
# for each rollout what MuJoCo's version alone changes (scripts/mujoco_floor.py).
#
# Not part of CI. It makes two scratch virtualenvs from PyPI (BENCH_VENV, default
# .bench-venv/robosuite, shared with scripts/bench_vs_robosuite.sh: robosuite 1.5.2 with
# its MuJoCo 3.3.7; FLOOR_VENV, default .bench-venv/robosuite-mujoco317: robosuite 1.5.2 on
# MuJoCo 3.17.0, where three of robosuite's calls are adapted to MuJoCo's renamed Python
# API: joint types compared as integers, and mj_fullM's new argument order). Usage:
#   scripts/record_robosuite.sh [--resets N] [--robot NAME] [TASK ...]
#   (e.g. --robot SpotWithArm Lift writes Lift-SpotWithArm.json with its floors)
#   scripts/record_robosuite.sh --controllers [ROBOT ...]
# The second form records the controller fixtures (scripts/record_controllers.py, default
# robots Panda, Sawyer and UR5e) and their floors.
set -euo pipefail
cd "$(dirname "$0")/.."
venv=${BENCH_VENV:-.bench-venv/robosuite}
floor_venv=${FLOOR_VENV:-.bench-venv/robosuite-mujoco317}
if [ ! -x "$venv/bin/python" ]; then
    python3 -m venv "$venv"
    "$venv/bin/pip" install --quiet "robosuite==1.5.2" "mujoco==3.3.7" gymnasium h5py
fi
if [ ! -x "$floor_venv/bin/python" ]; then
    python3 -m venv "$floor_venv"
    "$floor_venv/bin/pip" install --quiet "robosuite==1.5.2" "mujoco==3.17.0"
    "$floor_venv/bin/python" - <<'PY'
import pathlib, robosuite
root = pathlib.Path(robosuite.__file__).parent
edits = {
    "utils/binding_utils.py": [
        ("joint_type = self.jnt_type[joint_id]", "joint_type = int(self.jnt_type[joint_id])"),
        ("if joint_type == mujoco.mjtJoint.mjJNT_FREE:", "if joint_type == int(mujoco.mjtJoint.mjJNT_FREE):"),
        ("elif joint_type == mujoco.mjtJoint.mjJNT_BALL:", "elif joint_type == int(mujoco.mjtJoint.mjJNT_BALL):"),
        ("assert joint_type in (mujoco.mjtJoint.mjJNT_HINGE, mujoco.mjtJoint.mjJNT_SLIDE)",
         "assert joint_type in (int(mujoco.mjtJoint.mjJNT_HINGE), int(mujoco.mjtJoint.mjJNT_SLIDE))"),
    ],
    "controllers/parts/controller.py": [
        ("mujoco.mj_fullM(self.sim.model._model, mass_matrix, self.sim.data.qM)",
         "mujoco.mj_fullM(self.sim.model._model, self.sim.data._data, mass_matrix)"),
    ],
}
for rel, pairs in edits.items():
    path = root / rel
    text = path.read_text()
    for old, new in pairs:
        text = text.replace(old, new)
    path.write_text(text)
PY
fi
if [ "${1:-}" = --controllers ]; then
    shift
    "$venv/bin/python" scripts/record_controllers.py "$@"
    "$floor_venv/bin/python" scripts/record_controllers.py --floor "$@"
    exit 0
fi
"$venv/bin/python" scripts/record_robosuite.py "$@"
# The fixtures just written (the task names among the arguments; every fixture if none).
robot=Panda
tasks=()
while [ $# -gt 0 ]; do
    case "$1" in
        --resets|--out) shift 2 ;;
        --robot) robot=$2; shift 2 ;;
        *) tasks+=("$1"); shift ;;
    esac
done
fixtures=()
for t in "${tasks[@]}"; do
    if [ "$robot" = Panda ]; then fixtures+=("$t"); else fixtures+=("$t-$robot"); fi
done
"$floor_venv/bin/python" scripts/mujoco_floor.py "${fixtures[@]}"
