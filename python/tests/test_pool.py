"""make_pool: EnvPool's asynchronous send/recv mode; every env follows the trajectory of a
single env with the same seed and actions, whichever batches it lands in."""

from __future__ import annotations

import numpy as np
import pytest

import robosuite_rs as suite
from robosuite_rs.wrappers import GymWrapper

from .conftest import QUIET


@pytest.mark.parametrize("pin_threads", [False, True])
def test_pool_envs_follow_their_own_trajectories(pin_threads: bool) -> None:
    n, batch, horizon, seed = 4, 2, 3, 50
    with suite.make_pool("Lift", n, batch, horizon=horizon, pin_threads=pin_threads, **QUIET) as pool:
        assert (pool.num_envs, pool.batch_size) == (n, batch)
        assert pool.observation_space.shape == (batch, 60)
        assert pool.action_space.shape == (batch, 7)
        singles = [GymWrapper(suite.make("Lift", horizon=horizon, **QUIET)) for _ in range(n)]
        expected = {i: (s.reset(seed=seed + i)[0], 0.0, False, False) for i, s in enumerate(singles)}
        ended = [False] * n
        autoresets = 0
        rng = np.random.default_rng(0)
        obs, info = pool.reset(seed=seed)
        rewards = np.zeros(batch)
        terms = truncs = np.zeros(batch, dtype=bool)
        for _ in range(16):
            ids = info["env_id"]
            assert len(set(ids.tolist())) == batch and obs.dtype == np.float32
            for k, i in enumerate(ids):
                o, r, te, tr = expected[i]
                np.testing.assert_array_equal(obs[k], o, err_msg=f"env {i}")
                assert (rewards[k], terms[k], truncs[k]) == (r, te, tr)
                ended[i] = te or tr
            actions = rng.uniform(-1, 1, size=(batch, 7)).astype(np.float32)
            for k, i in enumerate(ids):
                if ended[i]:
                    autoresets += 1
                    expected[i] = (singles[i].reset()[0], 0.0, False, False)
                else:
                    o, r, te, tr, _ = singles[i].step(actions[k])
                    expected[i] = (o, r, te, tr)
            obs, rewards, terms, truncs, info = pool.step(actions)
        assert autoresets > 0


def test_pool_reset_takes_a_seed_per_env() -> None:
    seeds = [11, 3]
    with suite.make_pool("Lift", 2, 2, horizon=5, **QUIET) as pool:
        obs, info = pool.reset(seed=seeds)
        for k, i in enumerate(info["env_id"]):
            single = GymWrapper(suite.make("Lift", horizon=5, **QUIET))
            np.testing.assert_array_equal(obs[k], single.reset(seed=seeds[i])[0])
        with pytest.raises(ValueError):
            pool.async_reset([1, 2, 3])


def test_pool_misuse_raises_and_sends_nothing() -> None:
    with pytest.raises(ValueError):
        suite.make_pool("Lift", 2, 3, **QUIET)
    pool = suite.make_pool("Lift", 3, 2, horizon=5, **QUIET)
    _, info = pool.reset(seed=0)
    ids = info["env_id"]
    pending = next(i for i in range(3) if i not in ids)
    zeros = np.zeros((2, 7), dtype=np.float32)
    with pytest.raises(ValueError):
        pool.send(zeros, [ids[0], pending])
    with pytest.raises(ValueError):
        pool.send(zeros, [ids[0], ids[0]])
    # A NaN row rejects the whole batch before anything is queued: the next good send
    # goes through and recv returns a full batch.
    nan = zeros.copy()
    nan[1, 0] = np.nan
    with pytest.raises(ValueError, match="not finite"):
        pool.send(nan, ids)
    pool.send(zeros, ids)
    obs, *_ = pool.recv()
    assert obs.shape == (2, 60)
    pool.close()
    pool.close()
