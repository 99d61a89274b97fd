"""Shared fixtures: small horizons keep the suite fast."""

from __future__ import annotations

import warnings
from collections.abc import Iterator

import pytest

import robosuite_rs as suite
from robosuite_rs.wrappers import GymWrapper

QUIET = {"has_renderer": False, "has_offscreen_renderer": False, "use_camera_obs": False}


@pytest.fixture
def env() -> Iterator[suite.RobosuiteEnv]:
    e = suite.make("Lift", robots="Panda", horizon=20, **QUIET)
    yield e
    e.close()


@pytest.fixture
def gym_env(env: suite.RobosuiteEnv) -> Iterator[GymWrapper]:
    g = GymWrapper(env)
    yield g
    g.close()


UNBOUNDED_OBS_WARNINGS = (
    "A Box observation space minimum value is -infinity",
    "A Box observation space maximum value is infinity",
)


def unexpected(caught: list[warnings.WarningMessage], allowed: tuple[str, ...] = UNBOUNDED_OBS_WARNINGS) -> list[str]:
    """The messages of the caught warnings that are not in ``allowed``."""
    return [str(w.message) for w in caught if not any(a in str(w.message) for a in allowed)]
