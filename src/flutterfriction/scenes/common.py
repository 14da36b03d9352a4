"""What every scene builder shares: the parameter checks and the shape of a checked quantity."""

from __future__ import annotations

import statistics
import time
from collections.abc import Callable
from typing import Any, TypeVar

from flutterfriction.errors import ParameterError
from flutterfriction.models.ziegler import ZieglerPendulum

T = TypeVar("T")

#: A run this long [s] is timed once: its wall time is then known to a few per cent by itself
#: (timer resolution, caches and the first call's warm-up matter for millisecond runs).
TIMED_ENOUGH_S = 0.25


def quantity(value: float | str, independent: float | str, method: str, independent_method: str,
             unit: str) -> dict[str, Any]:
    """One checked quantity of a scene: its value by the primary method and by an independent
    one, named (``workflow/reference.yaml`` compares them with the chapter's)."""
    return {"value": value, "independent": independent, "method": method,
            "independent_method": independent_method, "unit": unit}


def take(params: dict[str, Any], allowed: set[str]) -> dict[str, Any]:
    """``params`` if it has no key outside ``allowed`` (one line naming the unknown keys)."""
    unknown = sorted(set(params) - allowed)
    if unknown:
        raise ParameterError(f"unknown scene parameter(s) {unknown}; allowed: {sorted(allowed)}")
    return params


def pendulum_of(params: dict[str, Any]) -> ZieglerPendulum:
    """The scene's pendulum (its ``pendulum`` section)."""
    if "pendulum" not in params:
        raise ParameterError("scene parameters need a 'pendulum' section")
    return ZieglerPendulum.from_mapping(params["pendulum"])


def n_points(params: dict[str, Any], default: int = 401) -> int:
    """The number of points of a curve (``n_points``), an integer >= 11."""
    n = params.get("n_points", default)
    if isinstance(n, bool) or not isinstance(n, int) or n < 11:
        raise ParameterError(f"n_points must be an integer >= 11, got {n!r}")
    return n


def median_wall_time(fun: Callable[[], T], repeats: int) -> tuple[T, float]:
    """``(fun(), median wall time [s])`` of up to ``repeats`` runs of ``fun``: a run is repeated
    while the runs so far took less than :data:`TIMED_ENOUGH_S` together (as ``timeit``'s
    autorange), so a work-precision study repeats its short runs, whose times are noisy, and
    does not pay its longest runs three times over. Only the measured time depends on the
    clock: ``fun`` is deterministic and its value is the same on every run."""
    if repeats < 1:
        raise ParameterError(f"repeats must be >= 1, got {repeats}")
    times: list[float] = []
    while True:
        start = time.perf_counter()
        value = fun()
        times.append(time.perf_counter() - start)
        if len(times) >= repeats or sum(times) >= TIMED_ENOUGH_S:
            return value, float(statistics.median(times))
