#!/usr/bin/env python3
"""JSON for recorded fixtures, laid out for review: one key per line, nested objects
indented, a list of numbers or strings on one line, a list of lists (a rollout's steps)
one inner list per line. The values are exactly ``json.dump``'s (Python's shortest
round-trip floats), so reformatting never changes a figure.

    from fixture_json import dump          # the recording scripts write with it
    python3 scripts/fixture_json.py FILE...  # rewrites existing fixtures in this layout
"""

from __future__ import annotations

import json
import sys
from typing import Any


def _scalar(v: Any) -> bool:
    return not isinstance(v, (dict, list))


def dumps(value: Any, indent: int = 0) -> str:
    """``value`` as JSON in the fixture layout."""
    pad, inner = " " * indent, " " * (indent + 1)
    if isinstance(value, dict):
        if not value:
            return "{}"
        items = [f"{inner}{json.dumps(k)}: {dumps(v, indent + 1)}" for k, v in value.items()]
        return "{\n" + ",\n".join(items) + "\n" + pad + "}"
    if isinstance(value, list):
        if all(_scalar(v) for v in value):
            return json.dumps(value, separators=(",", ":"))
        items = [inner + dumps(v, indent + 1) for v in value]
        return "[\n" + ",\n".join(items) + "\n" + pad + "]"
    return json.dumps(value)


def dump(value: Any, path: str) -> None:
    """Writes ``value`` to ``path`` in the fixture layout."""
    with open(path, "w") as f:
        f.write(dumps(value) + "\n")


if __name__ == "__main__":
    for path in sys.argv[1:]:
        with open(path) as f:
            data = json.load(f)
        dump(data, path)
        with open(path) as f:
            assert json.load(f) == data, path
