"""Interleaved comparison of robosuite 1.5.2's GymWrapper with robosuite-rs (Rust and
Python) on one task: each round runs the three measurements back to back, each in its own
process, and the ratios are medians of the per-round ratios, so that the speed drift of a
shared machine between minutes cancels. Run through scripts/bench_vs_robosuite.sh, which
makes the robosuite virtualenv and builds the Rust benchmark.

    python3 scripts/compare_with_robosuite.py --robosuite-python PY [--rs-python PY]
        [--task Lift] [--seconds 10] [--rounds 5] [--json out.json]

Only the standard library: it runs with any python3.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
RUST_BENCH = os.path.join(ROOT, "target", "release", "examples", "benchmark")


def run_json(cmd: list[str], env: dict[str, str] | None = None) -> dict:
    """Runs ``cmd`` and parses the last line of its output as JSON."""
    out = subprocess.run(cmd, check=True, capture_output=True, text=True, env=env).stdout
    return json.loads(out.strip().splitlines()[-1])


def robosuite_rate(python: str, task: str, seconds: float) -> dict:
    env = dict(os.environ, MUJOCO_GL="disable")
    script = os.path.join(ROOT, "scripts", "bench_robosuite.py")
    return run_json([python, script, "--task", task, "--seconds", str(seconds)], env)


def rust_rates(task: str, seconds: float) -> dict:
    with tempfile.NamedTemporaryFile(suffix=".json") as f:
        subprocess.run(
            [RUST_BENCH, "--task", task, "--seconds", str(seconds), "--only", "steps", "--json", f.name],
            check=True,
            capture_output=True,
        )
        return json.load(open(f.name))["tasks"][0]


def python_rate(python: str, task: str, seconds: float) -> dict:
    script = os.path.join(ROOT, "python", "scripts", "bench.py")
    return run_json([python, script, "--task", task, "--seconds", str(seconds), "--only", "gym", "--json"])


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--robosuite-python", required=True, help="python of the robosuite venv")
    parser.add_argument("--rs-python", help="python with robosuite_rs installed (.venv)")
    parser.add_argument("--task", default="Lift")
    parser.add_argument("--seconds", type=float, default=10.0)
    parser.add_argument("--rounds", type=int, default=5)
    parser.add_argument("--json", help="also write the figures here")
    args = parser.parse_args()

    rows = []
    for r in range(args.rounds):
        row = {"robosuite": robosuite_rate(args.robosuite_python, args.task, args.seconds)["steps_per_s"]}
        rust = rust_rates(args.task, args.seconds)
        row["rust_env"] = rust["steps_per_s"]
        row["rust_gym"] = rust["gym_wrapper_steps_per_s"]
        if args.rs_python:
            row["python_gym"] = python_rate(args.rs_python, args.task, args.seconds)["gym_wrapper_steps_per_s"]
        rows.append(row)
        print(
            f"round {r + 1}/{args.rounds}: "
            + ", ".join(f"{k} {v:.0f}" for k, v in row.items())
            + " steps/s",
            file=sys.stderr,
        )

    names = {
        "rust_env": "robosuite-rs env, Rust",
        "rust_gym": "robosuite-rs GymWrapper, Rust",
        "python_gym": "robosuite-rs GymWrapper, Python",
    }
    summary = {
        "task": args.task,
        "seconds": args.seconds,
        "rounds": rows,
        "robosuite_steps_per_s": statistics.median(r["robosuite"] for r in rows),
    }
    print(f"{args.task}, {args.rounds} interleaved rounds of {args.seconds:.0f} s (medians):")
    print(f"  {'robosuite 1.5.2 GymWrapper (Python)':<36} {summary['robosuite_steps_per_s']:8.0f} steps/s")
    for key, name in names.items():
        if key not in rows[0]:
            continue
        rate = statistics.median(r[key] for r in rows)
        ratios = [r[key] / r["robosuite"] for r in rows]
        summary[f"{key}_steps_per_s"] = rate
        summary[f"{key}_ratio"] = statistics.median(ratios)
        print(
            f"  {name:<36} {rate:8.0f} steps/s, {statistics.median(ratios):5.1f}x robosuite "
            f"(rounds: {min(ratios):.1f}-{max(ratios):.1f}x)"
        )
    if args.json:
        with open(args.json, "w") as f:
            json.dump(summary, f, indent=2)


if __name__ == "__main__":
    main()
