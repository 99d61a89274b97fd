"""Rust space descriptions become the matching gymnasium.spaces objects."""

from __future__ import annotations

import numpy as np
from gymnasium import spaces

from robosuite_rs.spaces import from_spec


def test_box_keeps_dtype_and_infinite_bounds() -> None:
    s = from_spec(("Box", np.array([-np.inf, 0.0]), np.array([np.inf, 1.0]), "float32"))
    assert isinstance(s, spaces.Box) and s.dtype == np.float32 and s.shape == (2,)
    assert s.low[0] == -np.inf and s.high[0] == np.inf and s.high[1] == 1.0
    assert not s.bounded_below[0] and s.bounded_below[1]


def test_integer_box_maps_infinity_to_dtype_limits() -> None:
    s = from_spec(("Box", np.array([-np.inf, 0.0]), np.array([np.inf, 5.0]), "int64"))
    assert s.dtype == np.int64 and s.low[1] == 0 and s.high[1] == 5
    assert s.low[0] == np.iinfo(np.int64).min and s.high[0] == np.iinfo(np.int64).max
    u8 = from_spec(("Box", np.zeros((2, 2)), np.full((2, 2), 255.0), "uint8"))
    assert u8.dtype == np.uint8 and u8.shape == (2, 2)


def test_discrete_multidiscrete_multibinary() -> None:
    assert from_spec(("Discrete", 5, -2)) == spaces.Discrete(5, start=-2)
    md = from_spec(("MultiDiscrete", np.array([3, 4]), np.array([0, 1])))
    assert md == spaces.MultiDiscrete([3, 4], start=[0, 1])
    assert from_spec(("MultiBinary", [4])) == spaces.MultiBinary(4)
    assert from_spec(("MultiBinary", [2, 3])) == spaces.MultiBinary([2, 3])


def test_dict_keeps_order_and_tuple_nests() -> None:
    spec = ("Dict", [("z", ("Discrete", 2, 0)), ("a", ("Tuple", [("Discrete", 3, 0), ("MultiBinary", [2])]))])
    s = from_spec(spec)
    assert isinstance(s, spaces.Dict) and list(s.spaces) == ["z", "a"]
    assert isinstance(s["a"], spaces.Tuple) and s["a"][0] == spaces.Discrete(3)
    assert s.sample() in s
