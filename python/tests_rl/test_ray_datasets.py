"""robomimic's ``dataset_states_to_obs`` spread over Ray actors (``make test-rl``): on a
local Ray, ``states_to_obs(..., ray_actors=2)`` writes exactly what the threaded run writes,
and an actor's error stops the run with that error."""

from __future__ import annotations

import shutil
from collections.abc import Iterator
from pathlib import Path

import h5py
import numpy as np
import pytest

import ray
from robosuite_rs import datasets as D

pytestmark = pytest.mark.rl

FIXTURES = Path(__file__).resolve().parents[1] / "tests" / "fixtures" / "demonstrations"


@pytest.fixture(scope="module")
def local_ray() -> Iterator[None]:
    ray.init(num_cpus=2, include_dashboard=False, log_to_driver=False)
    yield
    ray.shutdown()


def _walk(g, out=None, prefix=""):
    out = {} if out is None else out
    for k in g:
        if isinstance(g[k], h5py.Dataset):
            out[prefix + k] = g[k][()]
        else:
            _walk(g[k], out, prefix + k + "/")
    return out


def test_ray_actors_write_what_threads_write(local_ray, tmp_path):
    shutil.copy(FIXTURES / "lift.hdf5", tmp_path)
    threads = D.states_to_obs(tmp_path / "lift.hdf5", output_name="threads.hdf5", done_mode=2, num_workers=1)
    actors = D.states_to_obs(tmp_path / "lift.hdf5", output_name="ray.hdf5", done_mode=2, ray_actors=2)
    assert actors.num_workers == 2 and actors.demos == threads.demos == 2
    with h5py.File(threads.output) as a, h5py.File(actors.output) as b:
        A, B = _walk(a), _walk(b)
        assert A.keys() == B.keys() and any(k.endswith("obs/object") for k in A)
        for k in A:
            np.testing.assert_array_equal(A[k], B[k], err_msg=k)
        assert dict(a["data"].attrs) == dict(b["data"].attrs)


def test_ray_actor_error_stops_the_run(local_ray, tmp_path):
    path = tmp_path / "lift.hdf5"
    shutil.copy(FIXTURES / "lift.hdf5", path)
    with h5py.File(path, "a") as f:
        del f["data/demo_2/actions"]
        f["data/demo_2/actions"] = np.zeros((3, 7))  # does not fit its states
    with pytest.raises(D.DatasetError, match="demo_2"):
        D.states_to_obs(path, output_name="bad.hdf5", done_mode=2, ray_actors=2)
    assert not (tmp_path / "bad.hdf5").exists()
    with pytest.raises(ValueError, match="ray_actors"):
        D.states_to_obs(path, output_name="bad.hdf5", ray_actors=0)
