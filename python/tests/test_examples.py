"""The robosuite GymWrapper usage examples run unchanged except for their imports."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"


@pytest.mark.parametrize("script", ["random_actions.py", "training_loop.py"])
def test_example_runs(script: str) -> None:
    result = subprocess.run([sys.executable, str(EXAMPLES / script)], capture_output=True, text=True, timeout=300)
    assert result.returncode == 0, result.stderr
    if script == "random_actions.py":
        assert "Observation space: Box(-inf, inf, (60,), float32)" in result.stdout
        assert "Initial observation shape: (60,)" in result.stdout
    else:
        assert result.stdout.count("length=200") == 10
