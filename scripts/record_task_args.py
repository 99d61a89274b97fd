"""Records robosuite 1.5.2's task constructor arguments (those beyond its common env
arguments) with their defaults, for robosuite-env/tests/it/task_options.rs.

Run with robosuite 1.5.2 installed (the scratch venv of docs/fidelity.md):

    .bench-venv/robosuite/bin/python scripts/record_task_args.py
"""

import inspect
import json
from pathlib import Path

import robosuite
from robosuite.environments.manipulation.manipulation_env import ManipulationEnv
from robosuite.environments.manipulation.two_arm_env import TwoArmEnv

# Arguments robosuite declares on some task classes that are env-wide here (EnvConfig).
ENV_CONFIG = {"reward_scale", "reward_shaping", "use_object_obs"}

OUT = Path(__file__).resolve().parent.parent / "robosuite-env/tests/fixtures/task_args.json"


def common_args() -> set[str]:
    names = set()
    for cls in (ManipulationEnv, TwoArmEnv):
        names |= set(inspect.signature(cls.__init__).parameters)
    return names


def main() -> None:
    common = common_args()
    out = {"robosuite_version": robosuite.__version__, "tasks": {}}
    for name in sorted(robosuite.ALL_ENVIRONMENTS):
        cls = robosuite.environments.base.REGISTERED_ENVS[name]
        params = inspect.signature(cls.__init__).parameters
        args = {}
        for arg, p in params.items():
            if arg in common or arg in ENV_CONFIG or arg == "self" or p.kind is p.VAR_KEYWORD:
                continue
            default = p.default
            if isinstance(default, tuple):
                default = list(default)
            args[arg] = default
        out["tasks"][name] = args
    from robosuite.environments.manipulation.wipe import DEFAULT_WIPE_CONFIG

    out["wipe_default_config"] = {k: list(v) if isinstance(v, tuple) else v for k, v in DEFAULT_WIPE_CONFIG.items()}
    OUT.write_text(json.dumps(out, indent=2, sort_keys=True) + "\n")
    print(f"wrote {OUT}")


if __name__ == "__main__":
    main()
