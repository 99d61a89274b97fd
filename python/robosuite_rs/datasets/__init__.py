"""Demonstrations and datasets: robosuite's ``demo.hdf5``, its playback, robomimic's layout
and robomimic's ``dataset_states_to_obs.py`` on the Rust core.

Needs h5py (``pip install robosuite-rs[datasets]``).

* :func:`gather_demonstrations_as_hdf5`: robosuite's function of
  ``scripts/collect_human_demonstrations.py``: the episodes a
  :class:`~robosuite_rs.wrappers.DataCollectionWrapper` wrote, as one ``demo.hdf5``.
* :func:`playback`: robosuite's ``playback_demonstrations_from_hdf5.py`` without a viewer:
  each demo's scene reloaded from its ``model_file``, then its states set one by one, or
  its actions stepped open loop from its first state with the per-step divergence from the
  stored states.
* :func:`convert_to_robomimic`: robomimic's ``convert_robosuite.py`` (``env_args``,
  ``num_samples``, ``total``, a ``mask/train`` / ``mask/valid`` split) into a new file.
* :func:`states_to_obs`: robomimic's ``dataset_states_to_obs.py`` (same arguments, same
  output), on several worker threads; also ``python -m robosuite_rs.datasets
  states-to-obs ...``.

Inputs are opened read-only and never modified. Outputs are written under a temporary name
next to the destination and renamed when complete, so a failed run leaves no file that looks
finished; an existing output is refused unless ``overwrite=True`` (``--overwrite``).
Malformed input raises :class:`DatasetError` naming the file, the demo and the key.
"""

from __future__ import annotations

import contextlib
import datetime
import json
import os
import sys
import time
from copy import deepcopy
from dataclasses import dataclass, field
from glob import glob
from typing import Any, Callable, Iterator, Sequence

import numpy as np

__all__ = [
    "DatasetError",
    "gather_demonstrations_as_hdf5",
    "playback",
    "PlaybackResult",
    "convert_to_robomimic",
    "states_to_obs",
    "StatesToObsResult",
]


#: Whether :func:`states_to_obs` observes each trajectory's states in one native call
#: (the result is the same either way; the per-state Python loop is robomimic's own).
NATIVE_LOOP = True


class DatasetError(ValueError):
    """A dataset that does not fit: the message names the file, the demo and the key."""


def _h5py() -> Any:
    try:
        import h5py
    except ImportError as e:  # pragma: no cover - depends on the installation
        raise ImportError(
            "robosuite_rs.datasets needs h5py: pip install 'robosuite-rs[datasets]' (or pip install h5py)"
        ) from e
    return h5py


def _open_input(path: str | os.PathLike[str]) -> Any:
    """``path`` opened read-only, with a ``data`` group."""
    h5py = _h5py()
    path = os.fspath(path)
    if not os.path.exists(path):
        raise FileNotFoundError(f"{path}: no such dataset file")
    try:
        f = h5py.File(path, "r")
    except OSError as e:
        raise DatasetError(f"{path}: not a readable HDF5 file ({e})") from None
    if "data" not in f:
        f.close()
        raise DatasetError(f"{path}: no 'data' group (not a robosuite / robomimic dataset)")
    return f


def _attr_str(value: Any) -> str:
    if isinstance(value, bytes):
        return value.decode()
    if isinstance(value, np.ndarray) and value.shape == ():
        return _attr_str(value[()])
    return str(value)


def _sorted_demos(f: Any) -> list[str]:
    """The demos under ``data`` in increasing number order (robomimic's order)."""
    demos = list(f["data"].keys())
    try:
        return sorted(demos, key=lambda d: int(d[5:]))
    except ValueError:
        return sorted(demos)


def _read(f: Any, path: str, key: str) -> np.ndarray:
    if key not in f[path]:
        raise DatasetError(f"{f.filename}: {path} has no '{key}' dataset")
    try:
        return f[f"{path}/{key}"][()]
    except Exception as e:  # noqa: BLE001 - h5py raises OSError / KeyError / RuntimeError
        raise DatasetError(f"{f.filename}: {path}/{key} cannot be read ({e})") from None


def _model_file(f: Any, demo: str) -> str:
    attrs = f[f"data/{demo}"].attrs
    if "model_file" not in attrs:
        raise DatasetError(f"{f.filename}: data/{demo} has no 'model_file' attribute (the episode's scene XML)")
    return _attr_str(attrs["model_file"])


def _ep_meta(f: Any, demo: str) -> str | None:
    attrs = f[f"data/{demo}"].attrs
    return _attr_str(attrs["ep_meta"]) if "ep_meta" in attrs else None


@contextlib.contextmanager
def _atomic_output(path: str, overwrite: bool, inputs: Sequence[str] = ()) -> Iterator[str]:
    """A temporary path next to ``path``, renamed to ``path`` when the block succeeds and
    removed when it fails."""
    path = os.path.abspath(path)
    for src in inputs:
        same = os.path.samefile(src, path) if os.path.exists(path) else os.path.abspath(src) == path
        if same:
            raise DatasetError(f"{path}: the output would replace the input")
    if os.path.exists(path) and not overwrite:
        raise FileExistsError(f"{path} exists; pass overwrite=True (--overwrite) to replace it")
    folder = os.path.dirname(path)
    if not os.path.isdir(folder):
        raise FileNotFoundError(f"{path}: the output folder {folder} does not exist")
    if not os.access(folder, os.W_OK):
        raise PermissionError(f"{path}: the output folder {folder} is not writable")
    tmp = os.path.join(folder, f".{os.path.basename(path)}.tmp-{os.getpid()}")
    try:
        yield tmp
        os.replace(tmp, path)
    finally:
        if os.path.exists(tmp):
            os.remove(tmp)


# ----------------------------------------------------------------------------- robosuite


def gather_demonstrations_as_hdf5(
    directory: str | os.PathLike[str], out_dir: str | os.PathLike[str], env_info: str | dict[str, Any]
) -> str:
    """robosuite's ``gather_demonstrations_as_hdf5``: the episodes in ``directory`` (as
    :class:`~robosuite_rs.wrappers.DataCollectionWrapper` or robosuite's wrapper writes them)
    into ``<out_dir>/demo.hdf5``; returns its path.

    Layout (robosuite's): group ``data`` with attributes ``date`` (``M-D-YYYY``), ``time``
    (``H:M:S``), ``repository_version`` (the robosuite API version, ``1.5.2``), ``env`` (the
    task name the episodes' npz files carry) and ``env_info`` (``env_info``: a JSON string,
    or a dict, stored as JSON); per successful episode ``demo_N`` (N from 1) with attribute
    ``model_file`` (the episode's ``model.xml``) and datasets ``states`` (every collected
    state but the last) and ``actions``. Unsuccessful episodes are left out, as robosuite
    does. Beyond robosuite 1.5.2: an episode's ``ep_meta.json`` is stored as attribute
    ``ep_meta`` (a JSON string, as robomimic reads it), and episodes are taken in the order
    of their folder names (their start times) rather than in ``os.listdir`` order.

    As robosuite, an existing ``demo.hdf5`` is replaced (collection scripts gather after
    every episode); it is written under a temporary name and renamed when complete.

    Raises:
        FileNotFoundError: for a missing ``directory``.
        DatasetError: for an episode whose files do not fit (named with the file).
    """
    h5py = _h5py()
    from ..compat import ROBOSUITE_API_VERSION

    directory = os.fspath(directory)
    if not os.path.isdir(directory):
        raise FileNotFoundError(f"{directory}: no such folder of episodes")
    if not isinstance(env_info, str):
        env_info = json.dumps(env_info)
    hdf5_path = os.path.join(os.fspath(out_dir), "demo.hdf5")
    with _atomic_output(hdf5_path, overwrite=True) as tmp, h5py.File(tmp, "w") as f:
        grp = f.create_group("data")
        num_eps = 0
        env_name = None
        for ep_directory in sorted(os.listdir(directory)):
            states: list[np.ndarray] = []
            actions: list[np.ndarray] = []
            success = False
            for state_file in sorted(glob(os.path.join(directory, ep_directory, "state_*.npz"))):
                try:
                    dic = np.load(state_file, allow_pickle=True)
                    env_name = str(dic["env"])
                    states.extend(dic["states"])
                    for ai in dic["action_infos"]:
                        actions.append(ai["actions"])
                    success = success or bool(dic["successful"])
                except Exception as e:  # noqa: BLE001 - a damaged npz: name it
                    raise DatasetError(f"{state_file}: not an episode file of DataCollectionWrapper ({e})") from None
            if len(states) == 0:
                continue
            if not success:
                print("Demonstration is unsuccessful and has NOT been saved")
                continue
            print("Demonstration is successful and has been saved")
            del states[-1]  # the state after the last action
            if len(states) != len(actions):
                raise DatasetError(
                    f"{os.path.join(directory, ep_directory)}: {len(states)} states for {len(actions)} actions"
                )
            num_eps += 1
            ep_grp = grp.create_group(f"demo_{num_eps}")
            with open(os.path.join(directory, ep_directory, "model.xml")) as xf:
                ep_grp.attrs["model_file"] = xf.read()
            meta_path = os.path.join(directory, ep_directory, "ep_meta.json")
            if os.path.exists(meta_path):
                with open(meta_path) as mf:
                    ep_grp.attrs["ep_meta"] = mf.read()
            ep_grp.create_dataset("states", data=np.array(states))
            ep_grp.create_dataset("actions", data=np.array(actions))
        if env_name is None:
            raise DatasetError(f"{directory}: no episodes (ep_*/state_*.npz) to gather")
        now = datetime.datetime.now()
        grp.attrs["date"] = f"{now.month}-{now.day}-{now.year}"
        grp.attrs["time"] = f"{now.hour}:{now.minute}:{now.second}"
        grp.attrs["repository_version"] = ROBOSUITE_API_VERSION
        grp.attrs["env"] = env_name
        grp.attrs["env_info"] = env_info
    return hdf5_path


def _env_meta(f: Any) -> dict[str, Any]:
    """robomimic's env metadata of a dataset: ``data.attrs["env_args"]``, or for a file of
    robosuite's (before ``convert_robosuite.py``) the same made from ``env`` and
    ``env_info``."""
    attrs = f["data"].attrs
    try:
        if "env_args" in attrs:
            meta = json.loads(_attr_str(attrs["env_args"]))
        elif "env_info" in attrs:
            env_info = json.loads(_attr_str(attrs["env_info"]))
            meta = {
                "type": 1,
                "env_name": _attr_str(attrs["env"]) if "env" in attrs else env_info.get("env_name"),
                "env_version": _attr_str(attrs.get("repository_version", "")),
                "env_kwargs": env_info,
            }
        else:
            raise DatasetError(f"{f.filename}: data has neither an 'env_args' nor an 'env_info' attribute")
    except json.JSONDecodeError as e:
        raise DatasetError(f"{f.filename}: data's env_args / env_info attribute is not JSON ({e})") from None
    if not isinstance(meta, dict) or not isinstance(meta.get("env_kwargs"), dict) or not meta.get("env_name"):
        raise DatasetError(f"{f.filename}: data's env_args needs 'env_name' and an 'env_kwargs' object")
    return meta


def _make(env_name: str, kwargs: dict[str, Any], where: str, scene_xml: str | None = None) -> Any:
    """``robosuite_rs.make(env_name, **kwargs)``; with ``scene_xml`` (a demo's scene, loaded
    next anyway) the env is built on that scene instead of composing and compiling its own,
    falling back to composing when the scene does not load."""
    import tempfile

    import robosuite_rs as suite

    if env_name not in suite.ALL_ENVIRONMENTS:
        raise DatasetError(f"{where}: unknown env {env_name!r} (robosuite_rs.ALL_ENVIRONMENTS lists the envs)")
    if scene_xml is not None:
        with tempfile.TemporaryDirectory() as folder:
            path = os.path.join(folder, "scene.xml")
            with open(path, "w", encoding="utf8") as f:
                f.write(scene_xml)
            try:
                return suite.make(env_name, **kwargs, model_xml=path)
            except (TypeError, ValueError, KeyError, RuntimeError):
                pass  # composed below: its error names the argument, the demo's names the scene
    try:
        return suite.make(env_name, **kwargs)
    except (TypeError, ValueError, KeyError, RuntimeError) as e:
        raise DatasetError(f"{where}: the env cannot be made from its arguments: {e}") from None


def _load_scene(env: Any, f: Any, demo: str) -> None:
    """The demo's scene into ``env`` as robomimic's ``reset_to`` and robosuite's playback do."""
    meta = _ep_meta(f, demo)
    env.set_ep_meta(json.loads(meta) if meta is not None else {})
    env.reset()
    try:
        env.reset_from_xml_string(env.edit_model_xml(_model_file(f, demo)))
    except DatasetError:
        raise
    except Exception as e:  # noqa: BLE001 - any failure of the XML is the finding
        raise DatasetError(f"{f.filename}: data/{demo} attribute model_file: the scene does not load ({e})") from None
    env.sim.reset()


def _check_states(env: Any, states: np.ndarray, where: str) -> None:
    m = env.sim.model
    need = 1 + int(m.nq) + int(m.nv)
    if states.ndim != 2 or states.shape[1] != need:
        raise DatasetError(
            f"{where}/states: shape {states.shape} does not fit the scene (rows of 1 + nq + nv = {need})"
        )


@dataclass
class PlaybackResult:
    """One demo played back: ``steps`` states set (or actions stepped); with actions,
    ``divergence[j]`` is ``‖states[j+1] − state after action j‖`` (robosuite's measure)
    and ``max_abs[j]`` its largest component, for every action but the last."""

    demo: str
    steps: int
    divergence: np.ndarray = field(default_factory=lambda: np.zeros(0))
    max_abs: np.ndarray = field(default_factory=lambda: np.zeros(0))


def playback(
    path: str | os.PathLike[str],
    use_actions: bool = False,
    demos: Sequence[str] | None = None,
    env: Any = None,
    callback: Callable[[Any, str, int], None] | None = None,
) -> dict[str, PlaybackResult]:
    """robosuite's ``playback_demonstrations_from_hdf5.py`` on every demo of ``path`` (or on
    ``demos``), without a viewer.

    The env is made as robosuite's script makes it (``robosuite_rs.make(**env_info,
    has_renderer=False, has_offscreen_renderer=False, ignore_done=True,
    use_camera_obs=False, reward_shaping=True, control_freq=20)``), unless ``env`` is given.
    Per demo: its ``ep_meta`` set, ``env.reset()``, ``reset_from_xml_string`` of its
    ``model_file``, ``env.sim.reset()``; then each stored state is set
    (``set_state_from_flattened`` + ``forward``), or with ``use_actions`` the first state is
    set and the actions are stepped open loop. ``callback(env, demo, t)`` runs after each
    state set / action stepped (to observe, render, record).

    Returns:
        demo name -> :class:`PlaybackResult` (with the divergence when ``use_actions``).

    Raises:
        DatasetError: for a file, demo, scene or state array that does not fit.
    """
    f = _open_input(path)
    try:
        if env is None:
            meta = _env_meta(f)
            kwargs = dict(meta["env_kwargs"])
            kwargs.pop("env_name", None)
            kwargs.update(
                has_renderer=False,
                has_offscreen_renderer=False,
                ignore_done=True,
                use_camera_obs=False,
                reward_shaping=True,
                control_freq=20,
            )
            env = _make(meta["env_name"], kwargs, f"{f.filename}: data attribute env_info")
        selected = _sorted_demos(f) if demos is None else list(demos)
        results: dict[str, PlaybackResult] = {}
        for ep in selected:
            where = f"{f.filename}: data/{ep}"
            if ep not in f["data"]:
                raise DatasetError(f"{where}: no such demo")
            states = _read(f, f"data/{ep}", "states")
            actions = _read(f, f"data/{ep}", "actions") if use_actions else None
            _load_scene(env, f, ep)
            _check_states(env, states, where)
            if not use_actions:
                for t, state in enumerate(states):
                    env.sim.set_state_from_flattened(state)
                    env.sim.forward()
                    if callback is not None:
                        callback(env, ep, t)
                results[ep] = PlaybackResult(ep, len(states))
                continue
            assert actions is not None
            if actions.ndim != 2 or actions.shape[1] != env.action_dim:
                raise DatasetError(f"{where}/actions: shape {actions.shape} does not fit the env (action_dim {env.action_dim})")
            env.sim.set_state_from_flattened(states[0])
            env.sim.forward()
            div, mx = [], []
            for j, action in enumerate(actions):
                env.step(action)
                if callback is not None:
                    callback(env, ep, j)
                if j < len(actions) - 1 and j + 1 < len(states):
                    diff = states[j + 1] - env.sim.get_state().flatten()
                    div.append(float(np.linalg.norm(diff)))
                    mx.append(float(np.abs(diff).max()))
            results[ep] = PlaybackResult(ep, len(actions), np.array(div), np.array(mx))
        return results
    finally:
        f.close()


# ----------------------------------------------------------------------------- robomimic


def convert_to_robomimic(
    dataset: str | os.PathLike[str],
    output: str | os.PathLike[str] | None = None,
    *,
    val_ratio: float = 0.1,
    overwrite: bool = False,
) -> str:
    """robomimic's ``convert_robosuite.py`` (and its ``split_train_val_from_hdf5``) into a
    new file (robomimic edits the dataset in place; here the input is left as it is):
    ``data`` gains ``env_args`` (JSON, indent 4: ``type`` 1, ``env_name``, ``env_version``
    from ``repository_version``, ``env_kwargs`` = ``env_info``) and ``total``; each demo
    gains ``num_samples`` (its number of actions); ``mask/train`` and ``mask/valid`` list
    the demos (``int(val_ratio * n)`` validation demos chosen by ``np.random.shuffle``, as
    robomimic). ``output`` defaults to ``<dataset stem>_robomimic.hdf5`` next to it.
    Returns the output path. (robomimic's ``extract_action_dict`` and absolute actions are
    not added.)

    Raises:
        DatasetError, FileExistsError: as the module says.
    """
    h5py = _h5py()
    dataset = os.fspath(dataset)
    if output is None:
        output = os.path.splitext(dataset)[0] + "_robomimic.hdf5"
    output = os.fspath(output)
    src = _open_input(dataset)
    try:
        attrs = src["data"].attrs
        if "env_args" not in attrs and ("env" not in attrs or "env_info" not in attrs):
            raise DatasetError(f"{dataset}: data has neither env_args nor env and env_info attributes")
        demos = sorted(src["data"].keys())
        for ep in demos:
            _model_file(src, ep)
            if "actions" not in src[f"data/{ep}"]:
                raise DatasetError(f"{dataset}: data/{ep} has no 'actions' dataset")
        with _atomic_output(output, overwrite, [dataset]) as tmp:
            with h5py.File(tmp, "w") as f:
                for key in src:
                    src.copy(key, f)
                for k, v in src.attrs.items():
                    f.attrs[k] = v
                data = f["data"]
                if "env" in data.attrs and "env_info" in data.attrs:
                    env_meta = dict(
                        type=1,
                        env_name=_attr_str(data.attrs["env"]),
                        env_version=_attr_str(data.attrs.get("repository_version", "")),
                        env_kwargs=json.loads(_attr_str(data.attrs["env_info"])),
                    )
                    data.attrs["env_args"] = json.dumps(env_meta, indent=4)
                total = 0
                for ep in data:
                    n = int(data[f"{ep}/actions"].shape[0])
                    data[ep].attrs["num_samples"] = n
                    total += n
                data.attrs["total"] = total
                num_val = int(val_ratio * len(demos))
                mask = np.zeros(len(demos))
                mask[:num_val] = 1.0
                np.random.shuffle(mask)
                mask = mask.astype(int)
                for name, keys in (
                    ("train", [demos[i] for i in (1 - mask).nonzero()[0]]),
                    ("valid", [demos[i] for i in mask.nonzero()[0]]),
                ):
                    if f"mask/{name}" in f:
                        del f[f"mask/{name}"]
                    f[f"mask/{name}"] = np.array(keys, dtype="S")
    finally:
        src.close()
    return output


class _RobomimicEnv:
    """robomimic's ``EnvRobosuite`` as ``dataset_states_to_obs.py`` uses it
    (``create_for_data_processing``, ``reset_to``, ``step``, ``get_observation``,
    ``get_reward``, ``is_success``, ``serialize``), on a ``robosuite_rs`` env."""

    def __init__(
        self,
        env_meta: dict[str, Any],
        camera_names: Sequence[str],
        camera_height: int,
        camera_width: int,
        reward_shaping: bool,
        use_depth_obs: bool,
        where: str,
        scene_xml: str | None = None,
    ) -> None:
        from ..compat import ROBOSUITE_API_VERSION

        kwargs = deepcopy(env_meta["env_kwargs"])
        for k in ("env_name", "camera_names", "camera_height", "camera_width", "reward_shaping",
                  "render", "render_offscreen", "use_image_obs", "use_depth_obs", "env_lang"):
            kwargs.pop(k, None)
        has_camera = len(camera_names) > 0
        kwargs["reward_shaping"] = reward_shaping
        if has_camera:
            kwargs["camera_names"] = list(camera_names)
            kwargs["camera_heights"] = camera_height
            kwargs["camera_widths"] = camera_width
        kwargs.update(
            has_renderer=False,
            has_offscreen_renderer=has_camera,
            ignore_done=True,
            use_object_obs=True,
            use_camera_obs=has_camera,
            camera_depths=use_depth_obs,
        )
        self.name = env_meta["env_name"]
        self.version = ROBOSUITE_API_VERSION
        self._init_kwargs = deepcopy(kwargs)
        self.image_keys = {f"{c}_image" for c in camera_names}
        self.depth_keys = {f"{c}_depth" for c in camera_names} if use_depth_obs else set()
        self.env = _make(self.name, kwargs, where, scene_xml)
        for ob_name in self.env.observation_names:
            if ("joint_pos" in ob_name) or ("eef_vel" in ob_name):
                self.env.modify_observable(observable_name=ob_name, attribute="active", modifier=True)

    def serialize(self) -> dict[str, Any]:
        return dict(env_name=self.name, env_version=self.version, type=1, env_kwargs=deepcopy(self._init_kwargs))

    def get_observation(self, di: Any = None, stacked: bool = False) -> dict[str, np.ndarray]:
        """robomimic's ``get_observation``; ``stacked``: ``di`` holds several states'
        values stacked on a first axis (``observe_states``)."""
        if di is None:
            di = self.env._get_observations(force_update=True)
        ret: dict[str, np.ndarray] = {}
        flip = (slice(None), slice(None, None, -1)) if stacked else (slice(None, None, -1),)
        for k in di:
            if k in self.image_keys:
                ret[k] = di[k][flip].copy()
            elif k in self.depth_keys:
                d = di[k][flip].copy()
                if len(d.shape) == 2 + stacked:
                    d = d[..., None]
                ret[k] = self._real_depth(d)
        if "object-state" in di:
            ret["object"] = np.array(di["object-state"])
        for robot in self.env.robots:
            pf = robot.robot_model.naming_prefix
            for k in di:
                if k.startswith(pf) and (k not in ret) and (not k.endswith("proprio-state")):
                    ret[k] = np.array(di[k])
        return ret

    def _real_depth(self, depth_map: np.ndarray) -> np.ndarray:
        m = self.env.sim.model
        extent = m.stat.extent
        far = m.vis.map.zfar * extent
        near = m.vis.map.znear * extent
        return near / (1.0 - depth_map * (1.0 - near / far))

    def camera_info(self, camera_names: Sequence[str], height: int, width: int) -> dict[str, Any] | None:
        """robomimic's ``get_camera_info``: per camera its intrinsics and extrinsics (eye-in-hand
        cameras relative to the end effector's control site)."""
        if not camera_names:
            return None
        sim = self.env.sim
        info = {}
        for cam in camera_names:
            cam_id = sim.model.camera_name2id(cam)
            fovy = sim.model.cam_fovy[cam_id]
            fl = 0.5 * height / np.tan(fovy * np.pi / 360)
            K = np.array([[fl, 0, width / 2], [0, fl, height / 2], [0, 0, 1]])
            R = np.eye(4)
            R[:3, :3] = np.array(sim.data.cam_xmat[cam_id]).reshape(3, 3)
            R[:3, 3] = np.array(sim.data.cam_xpos[cam_id])
            R = R @ np.array([[1.0, 0, 0, 0], [0, -1.0, 0, 0], [0, 0, -1.0, 0], [0, 0, 0, 1.0]])
            if "eye_in_hand" in cam:
                robot = self.env.robots[int(cam[5])]
                site = robot.composite_controller.part_controllers["right"].ref_name
                sid = sim.model.site_name2id(site)
                rot = np.array(sim.data.site_xmat[sid]).reshape(3, 3)
                pos = np.array(sim.data.site_xpos[sid])
                inv = np.eye(4)
                inv[:3, :3] = rot.T
                inv[:3, 3] = -rot.T.dot(pos)
                R = R.dot(inv)
            info[cam] = dict(intrinsics=K.tolist(), extrinsics=R.tolist())
        return info


@dataclass
class _Options:
    camera_names: tuple[str, ...]
    camera_height: int
    camera_width: int
    shaped: bool
    depth: bool
    done_mode: int


class _Extractor:
    """One env extracting trajectories (robomimic's ``extract_trajectory``)."""

    def __init__(self, env_meta: dict[str, Any], opts: _Options, where: str, scene_xml: str | None = None) -> None:
        self.opts = opts
        self.env = _RobomimicEnv(env_meta, opts.camera_names, opts.camera_height, opts.camera_width,
                                 opts.shaped, opts.depth, where, scene_xml)
        # whole trajectories through one native call (robosuite_rs.datasets.NATIVE_LOOP)
        self.native_loop = NATIVE_LOOP

    def reset_to(self, states: np.ndarray) -> dict[str, np.ndarray]:
        self.env.env.sim.set_state_from_flattened(states)
        self.env.env.sim.forward()
        return self.env.get_observation()

    def run(self, item: dict[str, Any]) -> dict[str, Any]:
        where = f"{item['file']}: data/{item['demo']}"
        try:
            return self._run(item, where)
        except DatasetError:
            raise
        except Exception as e:  # noqa: BLE001 - name the demo
            raise DatasetError(f"{where}: {type(e).__name__}: {e}") from None

    def _run(self, item: dict[str, Any], where: str) -> dict[str, Any]:
        env = self.env.env
        states, actions = item["states"], item["actions"]
        if states.ndim != 2 or actions.ndim != 2 or states.shape[0] != actions.shape[0]:
            raise DatasetError(f"{where}: states {states.shape} and actions {actions.shape} differ in length")
        if actions.shape[1] != env.action_dim:
            raise DatasetError(f"{where}/actions: shape {actions.shape} does not fit the env (action_dim {env.action_dim})")
        # reset_to({"model": ..., "ep_meta": ..., "states": states[0]})
        env.set_ep_meta(json.loads(item["ep_meta"]) if item["ep_meta"] is not None else {})
        env.reset()
        try:
            # reset_from_xml_string applies edit_model_xml itself (robomimic calls it first;
            # a second pass changes nothing)
            env.reset_from_xml_string(item["model_file"])
        except Exception as e:  # noqa: BLE001
            raise DatasetError(f"{where} attribute model_file: the scene does not load ({e})") from None
        env.sim.reset()
        _check_states(env, states, where)
        n = states.shape[0]
        if n > 1 and self.native_loop and env._obsv.as_made():
            return self._run_native(states, actions, where)
        obs = self.reset_to(states[0])
        camera_info = self.env.camera_info(self.opts.camera_names, self.opts.camera_height, self.opts.camera_width)
        obs_list, next_list, rewards, dones = [], [], [], []
        done_mode = self.opts.done_mode
        for t in range(1, n + 1):
            if t == n:
                di, _, _, _ = env.step(actions[t - 1])
                next_obs = self.env.get_observation(di)
            else:
                next_obs = self.reset_to(states[t])
            r = env.reward()
            done = False
            if done_mode in (1, 2):
                done = done or (t == n)
            if done_mode in (0, 2):
                done = done or bool(env._check_success())
            obs_list.append(obs)
            next_list.append(next_obs)
            rewards.append(r)
            dones.append(int(done))
            obs = deepcopy(next_obs)
        return {
            "obs": {k: np.array([o[k] for o in obs_list]) for k in obs_list[0]},
            "next_obs": {k: np.array([o[k] for o in next_list]) for k in next_list[0]},
            "rewards": np.array(rewards),
            "dones": np.array(dones),
            "camera_info": camera_info,
            "num_states": n,
        }

    def _run_native(self, states: np.ndarray, actions: np.ndarray, where: str) -> dict[str, Any]:
        """:meth:`_run`'s result with the states before the last observed natively in one
        call (``observe_states``: the same native calls, without the per-state Python); the
        observables' clocks are then moved as those forced updates move them, and the last
        state and the final step go through the env as robomimic's loop does."""
        env = self.env.env
        n = states.shape[0]
        camera_info = None
        if self.opts.camera_names:
            # robomimic reads the cameras' poses at states[0]
            env.sim.set_state_from_flattened(states[0])
            env.sim.forward()
            camera_info = self.env.camera_info(self.opts.camera_names, self.opts.camera_height, self.opts.camera_width)
        head, rewards_head, success_head = env._native.observe_states(np.ascontiguousarray(states[: n - 1]))
        env._obsv.skip_forced_updates(n - 1)
        first = self.env.get_observation(head, stacked=True)
        last = self.reset_to(states[n - 1])
        r_last = env.reward()
        success_last = bool(env._check_success())
        di, _, _, _ = env.step(actions[n - 1])
        final = self.env.get_observation(di)
        r_final = env.reward()
        success_final = bool(env._check_success())
        done_mode = self.opts.done_mode
        # transition t (1..n): obs = state t-1, next_obs = state t (the step after the last)
        # reward and success read at next_obs's state
        rewards = np.concatenate([rewards_head[1:], [r_last, r_final]])
        successes = np.concatenate([success_head[1:], [success_last, success_final]])
        dones = np.zeros(n, dtype=bool)
        if done_mode in (1, 2):
            dones[n - 1] = True
        if done_mode in (0, 2):
            dones |= successes
        obs = {k: np.concatenate([first[k], last[k][None]]) for k in first}
        next_obs = {k: np.concatenate([first[k][1:], last[k][None], final[k][None]]) for k in first}
        return {
            "obs": obs,
            "next_obs": next_obs,
            "rewards": rewards.astype(float),
            "dones": dones.astype(int),
            "camera_info": camera_info,
            "num_states": n,
        }


@dataclass
class StatesToObsResult:
    """What :func:`states_to_obs` wrote: the output path, the demos, the transitions
    (``total``), the states processed and the seconds it took (``seconds``; ``setup``: the
    part spent making the env(s) before the first demo)."""

    output: str
    demos: int
    total: int
    states: int
    seconds: float
    setup: float
    num_workers: int


def _default_workers() -> int:
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:  # pragma: no cover - not Linux
        return os.cpu_count() or 1


class _Progress:
    def __init__(self, total: int, enabled: bool) -> None:
        self.enabled = enabled
        self.total = total
        self.done = 0
        self.states = 0
        self.start = time.perf_counter()
        self.bar = None
        if enabled:
            try:
                from tqdm import tqdm

                self.bar = tqdm(total=total, unit="demo", file=sys.stderr)
            except ImportError:
                self.bar = None

    def update(self, states: int) -> None:
        self.done += 1
        self.states += states
        if not self.enabled:
            return
        if self.bar is not None:
            self.bar.update(1)
            return
        rate = self.states / max(time.perf_counter() - self.start, 1e-9)
        print(f"\rstates-to-obs: {self.done}/{self.total} demos, {self.states} states, {rate:.0f} states/s",
              end="" if self.done < self.total else "\n", file=sys.stderr, flush=True)

    def close(self) -> None:
        if self.bar is not None:
            self.bar.close()


def states_to_obs(
    dataset: str | os.PathLike[str],
    output_name: str | None = None,
    n: int | None = None,
    shaped: bool = False,
    camera_names: Sequence[str] = (),
    camera_height: int = 84,
    camera_width: int = 84,
    depth: bool = False,
    done_mode: int = 0,
    copy_rewards: bool = False,
    copy_dones: bool = False,
    exclude_next_obs: bool = False,
    compress: bool = False,
    *,
    num_workers: int | None = None,
    overwrite: bool = False,
    progress: bool = False,
    ray_actors: int | None = None,
) -> StatesToObsResult:
    """robomimic's ``dataset_states_to_obs.py``: observations, rewards and dones computed from
    the stored states of ``dataset``, written in robomimic's layout.

    Arguments as robomimic's: ``output_name`` (a file name in the dataset's folder, or a path;
    default ``<stem>_ld.hdf5``, or ``<stem>_im<width>.hdf5`` with cameras), ``n`` (the first n
    demos), ``shaped`` (dense rewards), ``camera_names`` / ``camera_height`` /
    ``camera_width`` (``<cam>_image`` observations, uint8, flipped upright), ``depth``
    (``<cam>_depth``, metres), ``done_mode`` (0: done where s' succeeds; 1: at the end of
    each demo; 2: both), ``copy_rewards`` / ``copy_dones`` (taken from the dataset),
    ``exclude_next_obs``, ``compress`` (gzip). The output is robomimic's: ``data`` attrs
    ``total`` and ``env_args``; per demo (same names) ``actions``, ``states``, ``rewards``,
    ``dones``, ``obs/<key>``, ``next_obs/<key>`` (``actions_abs`` and ``action_dict/`` copied
    when present), attrs ``model_file``, ``ep_meta`` (when present), ``num_samples``,
    ``camera_info`` (with cameras); ``mask/`` copied. Observation keys are robomimic's
    (``object``, the ``robot0_*`` keys, the camera keys). Each demo is processed exactly as
    robomimic does (scene reloaded from ``model_file``, each state set and observed, the last
    ``next_obs`` by stepping the last action), so the values equal robomimic's on robosuite.

    ``num_workers`` (default: every core; capped at the number of demos) worker threads
    each hold one env and take demos as they come (the native work, scene loading included,
    runs without the GIL); the parent writes the results in demo
    order, so the output does not depend on ``num_workers``. A worker's error stops the run
    with that error (naming the demo). ``progress`` shows a bar on stderr (tqdm when
    installed, else a line of text).

    ``ray_actors``: the demos are processed by that many Ray actors instead (for datasets
    beyond one machine: each actor holds one env, on whichever node of the cluster Ray
    places it; ``ray.init()`` first, else a local Ray is started); this process writes the
    results in demo order as with threads, so the output is the same. Needs ``ray``.

    Returns:
        a :class:`StatesToObsResult`.

    Raises:
        DatasetError: for input that does not fit (file, demo and key named).
        FileExistsError: when the output exists and ``overwrite`` is false.
    """
    h5py = _h5py()
    t_start = time.perf_counter()
    dataset = os.fspath(dataset)
    if depth and len(camera_names) == 0:
        raise ValueError("must specify camera names if using depth")
    if done_mode not in (0, 1, 2):
        raise ValueError(f"done_mode must be 0, 1 or 2, got {done_mode}")
    f = _open_input(dataset)
    try:
        env_meta = _env_meta(f)
        demos = _sorted_demos(f)
        if n is not None:
            demos = demos[:n]
        if output_name is None:
            stem = os.path.basename(dataset)[:-5]
            output_name = stem + ("_ld.hdf5" if len(camera_names) == 0 else f"_im{camera_width}.hdf5")
        output_path = os.path.join(os.path.dirname(os.path.abspath(dataset)), output_name)
        opts = _Options(tuple(camera_names), int(camera_height), int(camera_width), bool(shaped), bool(depth), int(done_mode))
        where = f"{dataset}: data attribute env_args"

        # every demo's input read and checked up front (cheap): errors before any work
        items = []
        for ep in demos:
            g = f"data/{ep}"
            item = {
                "file": dataset,
                "demo": ep,
                "states": _read(f, g, "states"),
                "actions": _read(f, g, "actions"),
                "model_file": _model_file(f, ep),
                "ep_meta": _ep_meta(f, ep),
            }
            if copy_rewards and "rewards" not in f[g]:
                raise DatasetError(f"{dataset}: {g} has no 'rewards' dataset (copy_rewards)")
            if copy_dones and "dones" not in f[g]:
                raise DatasetError(f"{dataset}: {g} has no 'dones' dataset (copy_dones)")
            items.append(item)

        workers = _default_workers() if num_workers is None else int(num_workers)
        if workers < 1:
            raise ValueError(f"num_workers must be >= 1, got {num_workers}")
        workers = max(1, min(workers, len(items)))
        if ray_actors is not None:
            if int(ray_actors) < 1:
                raise ValueError(f"ray_actors must be >= 1, got {ray_actors}")
            ray_actors = workers = max(1, min(int(ray_actors), len(items)))
        # one env here: checks env_args and the cameras before any worker starts, gives
        # env_args for the output and serves as the only worker when there is one
        # built on the first demo's scene: it is loaded first anyway
        scene = items[0]["model_file"] if items else None
        local = _Extractor(env_meta, opts, where, scene)
        env_args = json.dumps(local.env.serialize(), indent=4)
        setup = time.perf_counter() - t_start

        with _atomic_output(output_path, overwrite, [dataset]) as tmp:
            bar = _Progress(len(items), progress)
            total_samples = 0
            total_states = 0
            with h5py.File(tmp, "w") as f_out:
                data_grp = f_out.create_group("data")
                results = (
                    _ray_results(items, env_meta, opts, where, ray_actors)
                    if ray_actors is not None
                    else _results(items, local, env_meta, opts, where, workers)
                )
                for item, traj in results:
                    ep = item["demo"]
                    g = f"data/{ep}"
                    if copy_rewards:
                        traj["rewards"] = f[f"{g}/rewards"][()]
                    if copy_dones:
                        traj["dones"] = f[f"{g}/dones"][()]
                    ep_grp = data_grp.create_group(ep)
                    ep_grp.create_dataset("actions", data=np.array(item["actions"]))
                    ep_grp.create_dataset("states", data=np.array(item["states"]))
                    ep_grp.create_dataset("rewards", data=np.array(traj["rewards"]))
                    ep_grp.create_dataset("dones", data=np.array(traj["dones"]))
                    if "actions_abs" in f[g]:
                        ep_grp.create_dataset("actions_abs", data=f[f"{g}/actions_abs"][()])
                    comp = {"compression": "gzip"} if compress else {}
                    for k in traj["obs"]:
                        ep_grp.create_dataset(f"obs/{k}", data=traj["obs"][k], **comp)
                        if not exclude_next_obs:
                            ep_grp.create_dataset(f"next_obs/{k}", data=traj["next_obs"][k], **comp)
                    if "action_dict" in f[g]:
                        for k in f[f"{g}/action_dict"]:
                            ep_grp.create_dataset(f"action_dict/{k}", data=np.array(f[f"{g}/action_dict/{k}"][()]))
                    ep_grp.attrs["model_file"] = item["model_file"]
                    if "ep_meta" in f[g].attrs:
                        ep_grp.attrs["ep_meta"] = f[g].attrs["ep_meta"]
                    ep_grp.attrs["num_samples"] = item["actions"].shape[0]
                    if traj["camera_info"] is not None:
                        ep_grp.attrs["camera_info"] = json.dumps(traj["camera_info"], indent=4)
                    total_samples += item["actions"].shape[0]
                    total_states += traj["num_states"]
                    bar.update(traj["num_states"])
                if "mask" in f:
                    f.copy("mask", f_out)
                data_grp.attrs["total"] = total_samples
                data_grp.attrs["env_args"] = env_args
            bar.close()
    finally:
        f.close()
    return StatesToObsResult(
        output=output_path,
        demos=len(items),
        total=total_samples,
        states=total_states,
        seconds=time.perf_counter() - t_start,
        setup=setup,
        num_workers=workers,
    )


def _results(
    items: list[dict[str, Any]],
    local: _Extractor,
    env_meta: dict[str, Any],
    opts: _Options,
    where: str,
    workers: int,
) -> Iterator[tuple[dict[str, Any], dict[str, Any]]]:
    """``(item, trajectory)`` in the order of ``items``: here with one worker, else from
    ``workers`` threads (the first uses ``local``, each other makes its own env; the native
    calls, scene loading, ``forward`` and observations, release the GIL), at most
    ``2 * workers`` demos in flight."""
    if workers == 1:
        for item in items:
            yield item, local.run(item)
        return
    import queue
    import threading
    from concurrent.futures import ThreadPoolExecutor

    spare: queue.SimpleQueue[_Extractor] = queue.SimpleQueue()
    spare.put(local)
    lock = threading.Lock()
    made = [1]

    def run(item: dict[str, Any]) -> dict[str, Any]:
        # an idle extractor, or a new one while fewer than ``workers`` exist
        try:
            ex = spare.get_nowait()
        except queue.Empty:
            with lock:
                make = made[0] < workers
                made[0] += make
            ex = _Extractor(env_meta, opts, where, item["model_file"]) if make else spare.get()
        try:
            return ex.run(item)
        finally:
            spare.put(ex)

    with ThreadPoolExecutor(workers, thread_name_prefix="states-to-obs") as pool:
        pending: list[Any] = []
        nxt = 0
        try:
            for i, item in enumerate(items):
                while nxt < len(items) and nxt < i + 2 * workers:
                    pending.append(pool.submit(run, items[nxt]))
                    nxt += 1
                yield item, pending[i].result()
                pending[i] = None
        except BaseException:
            for fut in pending:
                if fut is not None:
                    fut.cancel()
            pool.shutdown(wait=True, cancel_futures=True)
            raise


class _RayExtractor:
    """One Ray actor's :class:`_Extractor` (made on the actor's node)."""

    def __init__(self, env_meta: dict[str, Any], opts: _Options, where: str, scene_xml: str | None) -> None:
        self.ex = _Extractor(env_meta, opts, where, scene_xml)

    def run(self, item: dict[str, Any]) -> dict[str, Any]:
        return self.ex.run(item)


def _ray_results(
    items: list[dict[str, Any]],
    env_meta: dict[str, Any],
    opts: _Options,
    where: str,
    actors: int,
) -> Iterator[tuple[dict[str, Any], dict[str, Any]]]:
    """``(item, trajectory)`` in the order of ``items``, from ``actors`` Ray actors taking
    demos as they come (``ray.util.ActorPool``); an actor's error stops the run with it."""
    try:
        import ray
        from ray.util import ActorPool
    except ImportError:
        raise ImportError("ray_actors needs ray: pip install 'ray>=2.40'") from None
    if not ray.is_initialized():
        ray.init()
    remote = ray.remote(_RayExtractor)
    scene = items[0]["model_file"] if items else None
    handles = [remote.remote(env_meta, opts, where, scene) for _ in range(actors)]
    try:
        pool = ActorPool(handles)
        results = pool.map(lambda actor, item: actor.run.remote(item), items)
        for item in items:
            try:
                traj = next(results)
            except ray.exceptions.RayTaskError as e:
                cause = getattr(e, "cause", None)
                if isinstance(cause, (DatasetError, ValueError, RuntimeError)):
                    raise cause from None
                raise
            yield item, traj
    finally:
        for h in handles:
            ray.kill(h)
