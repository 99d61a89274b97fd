"""Envs written in Rust and exported as ``gymnasium.Env`` by ``robosuite_py::export_env``.

``robosuite_rs`` is imported first: it loads MuJoCo (which ``make_lift_stack`` links) and
provides the ``gymnasium.Env`` shim the exported envs use.
"""

import robosuite_rs  # noqa: F401  (loads MuJoCo and the gymnasium shims)

from ._native import make_corridor, make_lift_stack

__all__ = ["make_corridor", "make_lift_stack"]
