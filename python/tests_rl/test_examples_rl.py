"""The RL examples (python/examples) run, briefly, and report what they learned from."""

from __future__ import annotations

import csv
import subprocess
import sys
from pathlib import Path

import pytest

pytestmark = pytest.mark.rl

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"


def _run(*args: str) -> str:
    result = subprocess.run([sys.executable, *args], capture_output=True, text=True, timeout=600)
    assert result.returncode == 0, result.stdout[-2000:] + result.stderr[-4000:]
    return result.stdout


def test_sb3_example_writes_a_learning_curve(tmp_path: Path) -> None:
    out = tmp_path / "curve.png"
    stdout = _run(str(EXAMPLES / "sb3_ppo_lift.py"), "--timesteps", "2048", "--num-envs", "2", "--horizon", "50", "--out", str(out))
    assert "2048 env steps" in stdout
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    rows = list(csv.DictReader(out.with_suffix(".csv").open()))
    assert len(rows) == 2 * (1024 // 50)  # 2 envs x 1024 steps, 50-step episodes (SB3 resets at once)
    assert all(int(r["env_steps"]) <= 2048 for r in rows)


def test_cleanrl_example_trains() -> None:
    stdout = _run(str(EXAMPLES / "cleanrl_ppo_continuous.py"), "--total-timesteps", "512", "--num-steps", "128", "--update-epochs", "2")
    lines = [line for line in stdout.splitlines() if line.startswith("global_step=")]
    assert [line.split()[0] for line in lines] == ["global_step=256", "global_step=512"]
    # Horizon 100 and Gymnasium's NEXT_STEP autoreset: each env ends episodes at its steps 100 and 201.
    assert "episodes=4" in lines[-1]
    assert float(lines[-1].split("mean_return(last 10)=")[1].split()[0]) > 0  # shaped rewards


def test_rllib_example_runs_two_env_runners() -> None:
    stdout = _run(str(EXAMPLES / "rllib_ppo_lift.py"), "--iterations", "1", "--batch", "200", "--horizon", "25", "--env-runners", "2")
    assert "iteration 1: env steps" in stdout
