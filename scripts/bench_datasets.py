#!/usr/bin/env python3
"""states_to_obs throughput (low-dim) against robosuite 1.5.2's loop, on the recorded Lift
demonstrations (python/tests/fixtures/demonstrations/lift.hdf5) repeated ``--copies``
times, each copy with its cube scaled by 1 + 1e-4 * copy (so that no two demos share a
scene, as in a recorded dataset).

    .venv/bin/python scripts/bench_datasets.py                      # robosuite_rs.datasets.states_to_obs, 1 and N workers
    .bench-venv/robosuite/bin/python scripts/bench_datasets.py      # robosuite 1.5.2 (robomimic's per-demo sequence)

With robosuite_rs importable it runs ``states_to_obs(..., done_mode=2)`` with 1 worker and
with every core, each in a fresh process (``--full-compile``: every scene compiled in full,
as before scene patching); with robosuite 1.5.2 it runs what robomimic's ``dataset_states_to_obs.py``
does per demo (env.reset, reset_from_xml_string(model_file), sim.reset, then per state
set_state_from_flattened + forward + _get_observations(force_update=True) + reward +
_check_success; the hdf5 writing left out), in one process (robomimic's script). Prints
states/s over the whole run (env creation included) and over the demos alone.
"""
from __future__ import annotations

import argparse
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time

import h5py
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SRC = os.path.join(ROOT, "python", "tests", "fixtures", "demonstrations", "lift.hdf5")


def make_dataset(folder: str, copies: int) -> str:
    path = os.path.join(folder, "bench.hdf5")
    with h5py.File(SRC) as src, h5py.File(path, "w") as dst:
        data = dst.create_group("data")
        for k, v in src["data"].attrs.items():
            data.attrs[k] = v
        n = 0
        for c in range(copies):
            for ep in sorted(src["data"]):
                n += 1
                src.copy(f"data/{ep}", data, name=f"demo_{n}")
                if c > 0:  # each demo its own cube size (as in a real dataset): no scene repeats
                    g = data[f"demo_{n}"]
                    g.attrs["model_file"] = _resize_cube(str(g.attrs["model_file"]), 1.0 + 1e-4 * c)
    return path


def _resize_cube(xml: str, scale: float) -> str:
    def sub(m: re.Match) -> str:
        size = " ".join(f"{float(v) * scale:.7g}" for v in m.group(2).split())
        return f'{m.group(1)}"{size}"'

    return re.sub(r'(name="cube_g0(?:_vis)?" size=)"([^"]*)"', sub, xml)


def bench_robosuite(path: str) -> None:
    import robosuite

    t0 = time.perf_counter()
    with h5py.File(path) as f:
        info = json.loads(f["data"].attrs["env_info"])
        info.pop("env_name")
        env = robosuite.make(f["data"].attrs["env"], **info, has_renderer=False, has_offscreen_renderer=False,
                             ignore_done=True, use_object_obs=True, use_camera_obs=False, camera_depths=False,
                             reward_shaping=False)
        for name in env.observation_names:
            if "joint_pos" in name or "eef_vel" in name:
                env.modify_observable(name, "active", True)
        t1 = time.perf_counter()
        states_total = 0
        for ep in f["data"]:
            states = f[f"data/{ep}/states"][()]
            env.reset()
            env.reset_from_xml_string(env.edit_model_xml(f[f"data/{ep}"].attrs["model_file"]))
            env.sim.reset()
            for s in states:
                env.sim.set_state_from_flattened(s)
                env.sim.forward()
                env._get_observations(force_update=True)
                env.reward()
                env._check_success()
            states_total += len(states)
    t2 = time.perf_counter()
    print(f"robosuite {robosuite.__version__}: {states_total} states, "
          f"{states_total / (t2 - t0):.0f} states/s overall ({t2 - t0:.2f} s), "
          f"{states_total / (t2 - t1):.0f} states/s after env creation")


def bench_ours(path: str, workers: list[int], full_compile: bool) -> None:
    from robosuite_rs import _native
    from robosuite_rs import datasets as D

    # with scene patching off, every demo's scene is compiled in full (the cost before it)
    _native.set_scene_patching(not full_compile)
    for w in workers:
        r = D.states_to_obs(path, output_name=f"out{w}.hdf5", done_mode=2, num_workers=w, overwrite=True)
        print(f"robosuite_rs states_to_obs{' (full compiles)' if full_compile else ''}, "
              f"{r.num_workers} worker(s): {r.states} states, "
              f"{r.states / r.seconds:.0f} states/s overall ({r.seconds:.2f} s), "
              f"{r.states / (r.seconds - r.setup):.0f} states/s after the first env")


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--copies", type=int, default=4, help="how many times the two Lift demos are repeated")
    ap.add_argument("--full-compile", action="store_true",
                    help="robosuite_rs: compile every demo's scene in full (no patching of cached scenes)")
    ap.add_argument("--workers", type=int, default=None,
                    help="robosuite_rs: this many workers only (default: 1 and every core, each in a fresh process)")
    args = ap.parse_args()
    try:
        import robosuite_rs  # noqa: F401
    except ImportError:
        ours = False
    else:
        ours = True
    if ours and args.workers is None:
        # a fresh process per run: no scene compiled by an earlier run is cached
        for w in (1, len(os.sched_getaffinity(0))):
            cmd = [sys.executable, os.path.abspath(__file__), "--copies", str(args.copies), "--workers", str(w)]
            subprocess.run(cmd + (["--full-compile"] if args.full_compile else []), check=True)
        return
    folder = tempfile.mkdtemp()
    try:
        path = make_dataset(folder, args.copies)
        if ours:
            bench_ours(path, [args.workers], args.full_compile)
        else:
            bench_robosuite(path)
    finally:
        shutil.rmtree(folder)


if __name__ == "__main__":
    main()
