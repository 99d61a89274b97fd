"""robosuite's observables (``robosuite.utils.observables``): a sensor, read at its own
sampling rate, optionally delayed, corrupted and filtered.

An env (:class:`robosuite_rs.RobosuiteEnv`) keeps one :class:`Observable` per observation
key in ``env._observables`` and, as robosuite 1.5.2 does, calls ``update`` on every one of
them after every physics substep (``timestep`` = the model timestep). An observable samples
once per sampling period: on the first substep of the period that is not earlier than the
period's length minus the current delay — with robosuite's defaults (sampling rate = the
control frequency, no delay) that is the last substep of every env step — and ``force``
samples at once (as ``env.reset()`` and ``env._get_observations(force_update=True)`` do).
A sample is ``filter(corrupter(sensor(obs_cache)))``; a one-element vector becomes a
scalar; the value is also put into ``obs_cache`` under the observable's name, where later
observables' sensors can read it.

Beyond robosuite, bad input is refused with a ``ValueError`` that names the observable: a
sensor that raises or changes its output shape, a corrupter or filter that turns finite
numbers into NaN/inf, a sampling rate that is not a positive finite number.

After ``robosuite_rs.install_as_robosuite()`` this module is ``robosuite.utils.observables``.
"""

from __future__ import annotations

import math
import numbers
from typing import Any, Callable

import numpy as np

__all__ = [
    "sensor",
    "Observable",
    "ObservableError",
    "create_deterministic_corrupter",
    "create_uniform_noise_corrupter",
    "create_gaussian_noise_corrupter",
    "create_deterministic_delayer",
    "create_uniform_sampled_delayer",
    "create_gaussian_sampled_delayer",
    "NO_CORRUPTION",
    "NO_FILTER",
    "NO_DELAY",
]


class ObservableError(ValueError, AssertionError):
    """Refused observable input where robosuite asserts (an unknown or duplicate observable
    name, a negative delay): a ``ValueError`` that is also the ``AssertionError`` robosuite
    raises there."""


def sensor(modality: str) -> Callable[[Callable[..., Any]], Callable[..., Any]]:
    """Marks ``func(obs_cache) -> value`` as a sensor of ``modality`` (sets
    ``func.__modality__``). The function must also work when ``obs_cache`` is empty."""

    def mark(func: Callable[..., Any]) -> Callable[..., Any]:
        func.__modality__ = modality
        return func

    return mark


# --- corrupters and delayers ---------------------------------------------------------
def create_deterministic_corrupter(corruption: Any, low: float = -np.inf, high: float = np.inf) -> Callable[[Any], np.ndarray]:
    """A corrupter adding ``corruption`` to every value, then clipping to ``[low, high]``."""

    def corrupt(inp: Any) -> np.ndarray:
        return np.clip(np.array(inp) + corruption, low, high)

    return corrupt


def create_uniform_noise_corrupter(min_noise: float, max_noise: float, low: float = -np.inf, high: float = np.inf) -> Callable[[Any], np.ndarray]:
    """A corrupter adding noise drawn uniformly from ``[min_noise, max_noise)`` (one
    ``np.random.random_sample`` draw per value), then clipping to ``[low, high]``."""

    def corrupt(inp: Any) -> np.ndarray:
        value = np.array(inp)
        noise = min_noise + (max_noise - min_noise) * np.random.random_sample(value.shape)
        return np.clip(value + noise, low, high)

    return corrupt


def create_gaussian_noise_corrupter(mean: float, std: float, low: float = -np.inf, high: float = np.inf) -> Callable[[Any], np.ndarray]:
    """A corrupter adding Gaussian noise ``mean + std * np.random.randn(...)`` per value,
    then clipping to ``[low, high]``."""

    def corrupt(inp: Any) -> np.ndarray:
        value = np.array(inp)
        noise = mean + std * np.random.randn(*value.shape)
        return np.clip(value + noise, low, high)

    return corrupt


def create_deterministic_delayer(delay: float) -> Callable[[], float]:
    """A delayer always giving ``delay`` seconds.

    Raises:
        ObservableError: for a negative delay.
    """
    if not delay >= 0:
        raise ObservableError(f"a delay must be non-negative, got {delay!r}")
    return lambda: delay


def create_uniform_sampled_delayer(min_delay: float, max_delay: float) -> Callable[[], float]:
    """A delayer drawing uniformly between ``min_delay`` and ``max_delay`` seconds (one
    ``np.random.random`` draw per delay).

    Raises:
        ObservableError: for a negative bound.
    """
    if not min(min_delay, max_delay) >= 0:
        raise ObservableError(f"delays must be non-negative, got {min_delay!r} and {max_delay!r}")
    return lambda: min_delay + (max_delay - min_delay) * np.random.random()


def create_gaussian_sampled_delayer(mean: float, std: float) -> Callable[[], float]:
    """A delayer drawing ``mean + std * np.random.randn()``, rounded to a whole number and
    floored at 0 — robosuite 1.5.2's delayer, which rounds to whole seconds.

    Raises:
        ObservableError: for a negative mean.
    """
    if not mean >= 0:
        raise ObservableError(f"the mean delay must be non-negative, got {mean!r}")
    return lambda: max(0.0, int(np.round(mean + std * np.random.randn())))


def _identity_corruption(inp: Any) -> Any:
    return inp


def _identity_filter(inp: Any) -> Any:
    return inp


def _no_delay() -> float:
    return 0.0


#: The default corrupter (the value unchanged).
NO_CORRUPTION: Callable[[Any], Any] = _identity_corruption
#: The default filter (the value unchanged).
NO_FILTER: Callable[[Any], Any] = _identity_filter
#: The default delayer (no delay).
NO_DELAY: Callable[[], float] = _no_delay


def _sampling_timestep(name: str, rate: Any) -> float:
    """``1 / rate`` for a positive finite rate, else ``ValueError``."""
    if isinstance(rate, (bool, np.bool_)) or not isinstance(rate, numbers.Real):
        raise ValueError(f"observable {name!r}: sampling_rate must be a positive number (Hz), got {rate!r}")
    if not (math.isfinite(rate) and rate > 0):
        raise ValueError(f"observable {name!r}: sampling_rate must be a positive finite number (Hz), got {rate!r}")
    return 1.0 / rate


def _non_finite(value: np.ndarray) -> bool:
    return value.dtype.kind in "fc" and not bool(np.isfinite(value).all())


class Observable:
    """One observation: ``sensor`` read at ``sampling_rate`` Hz, delayed by ``delayer()``
    seconds, then ``corrupter`` and ``filter`` (``None``: unchanged, no delay).

    ``enabled``: whether ``update`` samples it at all; ``active``: whether ``obs`` (and the
    env's observations) return its value.

    Raises:
        ValueError: when ``sensor`` has no modality (see :func:`sensor`) or fails on an
            empty ``obs_cache``, or for a sampling rate that is not a positive finite number.
    """

    def __init__(
        self,
        name: str,
        sensor: Callable[[dict[str, Any]], Any],
        corrupter: Callable[[Any], Any] | None = None,
        filter: Callable[[Any], Any] | None = None,
        delayer: Callable[[], float] | None = None,
        sampling_rate: float = 20,
        enabled: bool = True,
        active: bool = True,
    ) -> None:
        self.name = name
        self._sensor = sensor
        self._corrupter = NO_CORRUPTION if corrupter is None else corrupter
        self._filter = NO_FILTER if filter is None else filter
        self._delayer = NO_DELAY if delayer is None else delayer
        self._sampling_timestep = _sampling_timestep(name, sampling_rate)
        self._enabled = enabled
        self._active = active
        self._is_number = False
        self._data_shape: tuple[int, ...] = (1,)
        self._check_sensor_validity()
        self._time_since_last_sample = 0.0
        self._current_delay = self._delayer()
        self._current_observed_value: Any = self._zero()
        self._sampled = False

    @classmethod
    def _prebuilt(
        cls,
        name: str,
        sensor: Callable[[dict[str, Any]], Any],
        sampling_rate: float,
        shape: tuple[int, ...],
        enabled: bool,
        active: bool,
    ) -> "Observable":
        """An observable whose sensor's output shape is known (the env's own observables),
        made without reading the sensor."""
        self = cls.__new__(cls)
        self.name = name
        self._sensor = sensor
        self._corrupter = NO_CORRUPTION
        self._filter = NO_FILTER
        self._delayer = NO_DELAY
        self._sampling_timestep = _sampling_timestep(name, sampling_rate)
        self._enabled = enabled
        self._active = active
        self._set_shape(shape)
        self._time_since_last_sample = 0.0
        self._current_delay = self._delayer()
        self._current_observed_value = self._zero()
        self._sampled = False
        return self

    def _set_shape(self, shape: tuple[int, ...]) -> None:
        self._data_shape = tuple(shape)
        self._is_number = self._data_shape == (1,)

    def _zero(self) -> Any:
        return 0 if self._is_number else np.zeros(self._data_shape)

    # --- sampling --------------------------------------------------------------------
    def _due(self, timestep: float) -> bool:
        """Whether the next ``update(timestep, ...)`` (not forced) will sample."""
        if not self._enabled or self._sampled:
            return False
        t = self._time_since_last_sample + timestep
        return self._sampling_timestep - self._current_delay >= t or t >= self._sampling_timestep

    def _read(self, obs_cache: dict[str, Any]) -> None:
        """One sample: ``filter(corrupter(sensor(obs_cache)))`` into the current value and
        ``obs_cache``."""
        try:
            raw = self._sensor(obs_cache)
        except Exception as e:
            raise ValueError(f"observable {self.name!r}: its sensor raised {type(e).__name__}: {e}") from e
        raw_array = raw if isinstance(raw, np.ndarray) else np.asarray(raw)
        if raw_array.shape != self._data_shape:
            raise ValueError(
                f"observable {self.name!r}: its sensor returned shape {raw_array.shape}, "
                f"expected {self._data_shape} (the shape it gave when it was set)"
            )
        if self._corrupter is NO_CORRUPTION and self._filter is NO_FILTER:
            value = np.array(raw)
        else:
            value = self._process(raw, raw_array)
        if value.ndim == 1 and value.shape[0] == 1:
            value = value[0]
        self._current_observed_value = value
        obs_cache[self.name] = np.array(value)

    def _process(self, raw: Any, raw_array: np.ndarray) -> np.ndarray:
        """``filter(corrupter(raw))`` as an array, refusing NaN/inf made from finite values."""
        step = "corrupter"
        try:
            value = self._corrupter(raw)
            step = "filter"
            value = np.array(self._filter(value))
        except Exception as e:
            raise ValueError(f"observable {self.name!r}: its {step} raised {type(e).__name__}: {e}") from e
        if _non_finite(value) and not _non_finite(raw_array):
            raise ValueError(
                f"observable {self.name!r}: its corrupter/filter turned finite sensor values into "
                f"NaN or inf ({value!r})"
            )
        return value

    def update(self, timestep: float, obs_cache: dict[str, Any], force: bool = False) -> None:
        """Advances this observable's clock by ``timestep`` seconds and samples it if due
        (or if ``force``); a disabled observable does nothing. ``obs_cache`` gets the
        sampled value under this observable's name.

        Raises:
            ValueError: naming this observable, when its sensor raises or changes its
                output shape, or its corrupter or filter raises or turns finite values into
                NaN/inf.
        """
        if not self._enabled:
            return
        self._time_since_last_sample += timestep
        period = self._sampling_timestep
        if force or (not self._sampled and period - self._current_delay >= self._time_since_last_sample):
            self._read(obs_cache)
            self._sampled = True
            self._current_delay = self._delayer()
        if self._time_since_last_sample >= period:
            if not self._sampled:
                print(
                    f"Warning: sampling rate for observable {self.name} is either too low or delay is too high. "
                    f"Please adjust one (or both)"
                )
                self._read(obs_cache)
                self._current_delay = self._delayer()
            self._time_since_last_sample %= period
            self._sampled = False

    def reset(self) -> None:
        """Restarts the clock, draws a new delay and zeroes the value (the sensor,
        corrupter, filter and delayer stay)."""
        self._time_since_last_sample = 0.0
        self._current_delay = self._delayer()
        self._current_observed_value = self._zero()

    # --- settings --------------------------------------------------------------------
    def is_enabled(self) -> bool:
        """Whether ``update`` samples this observable."""
        return self._enabled

    def is_active(self) -> bool:
        """Whether ``obs`` returns the value (else ``None``)."""
        return self._active

    def set_enabled(self, enabled: bool) -> None:
        """Enables or disables sampling; either way the observable is :meth:`reset`."""
        self._enabled = enabled
        self.reset()

    def set_active(self, active: bool) -> None:
        """Sets whether ``obs`` returns the value."""
        self._active = active

    def set_sensor(self, sensor: Callable[[dict[str, Any]], Any]) -> None:
        """Replaces the sensor (checked as in the constructor; its output shape on an empty
        ``obs_cache`` becomes this observable's shape).

        Raises:
            ValueError: for a sensor without a modality or failing on an empty cache (the
                observable keeps its former sensor).
        """
        previous = self._sensor
        self._sensor = sensor
        try:
            self._check_sensor_validity()
        except ValueError:
            self._sensor = previous
            raise

    def set_corrupter(self, corrupter: Callable[[Any], Any] | None) -> None:
        """Replaces the corrupter (``None``: no corruption)."""
        self._corrupter = NO_CORRUPTION if corrupter is None else corrupter

    def set_filter(self, filter: Callable[[Any], Any] | None) -> None:
        """Replaces the filter (``None``: no filter)."""
        self._filter = NO_FILTER if filter is None else filter

    def set_delayer(self, delayer: Callable[[], float] | None) -> None:
        """Replaces the delayer (``None``: no delay); the current delay stays until the
        next sample or reset."""
        self._delayer = NO_DELAY if delayer is None else delayer

    def set_sampling_rate(self, rate: float) -> None:
        """Sets the sampling rate (Hz).

        Raises:
            ValueError: for a rate that is not a positive finite number (nothing changes).
        """
        self._sampling_timestep = _sampling_timestep(self.name, rate)

    def _check_sensor_validity(self) -> None:
        """Checks that the sensor has a modality and works on an empty cache; records its
        output shape."""
        try:
            _ = self.modality
            shape = np.array(self._sensor({})).shape
        except Exception as e:
            raise ValueError(
                f"Current sensor for observable {self.name} is invalid: {type(e).__name__}: {e}"
            ) from e
        self._set_shape(shape)

    # --- values ----------------------------------------------------------------------
    @property
    def obs(self) -> Any:
        """The last sampled value (``None`` when inactive)."""
        return self._current_observed_value if self._active else None

    @property
    def modality(self) -> str:
        """The sensor's modality."""
        return self._sensor.__modality__

    def __repr__(self) -> str:
        rate = 1.0 / self._sampling_timestep
        return (
            f"<Observable {self.name!r} modality={getattr(self._sensor, '__modality__', None)!r} "
            f"rate={rate:g}Hz enabled={self._enabled} active={self._active}>"
        )
