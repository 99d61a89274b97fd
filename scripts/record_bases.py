"""Records robosuite 1.5.2's scenes with each fixed base (`base_types`) on the tasks that
honour the argument (robosuite 1.5.2's Lift and Wipe pass "default" whatever is given):
body names and counts, geom count, the robot base's position and the total mass, for
robosuite-env/tests/it/task_options.rs.

    .bench-venv/robosuite/bin/python scripts/record_bases.py
"""

import json
from pathlib import Path

import numpy as np
import robosuite as suite

OUT = Path(__file__).resolve().parent.parent / "robosuite-env/tests/fixtures/bases.json"


def main() -> None:
    out = {"robosuite_version": suite.__version__, "scenes": []}
    for task in ["Stack", "Door"]:
        for base in ["NullMount", "RethinkMinimalMount", "RethinkMount"]:
            env = suite.make(task, robots="Panda", base_types=base, has_renderer=False,
                             has_offscreen_renderer=False, use_camera_obs=False)
            env.reset()
            m = env.sim.model
            out["scenes"].append({
                "task": task,
                "base": base,
                "ngeom": int(m.ngeom),
                "bodies": [m.body_id2name(i) for i in range(m.nbody)],
                "base_pos": env.sim.data.get_body_xpos("robot0_base").tolist(),
                "total_mass": float(m.body_mass.sum()),
            })
            env.close()
    OUT.write_text(json.dumps(out, indent=1) + "\n")
    print(f"wrote {OUT}")


if __name__ == "__main__":
    main()
