"""What every scene builder shares: the parameter checks and the shape of a checked quantity."""

from __future__ import annotations

from typing import Any

from flutterfriction.errors import ParameterError
from flutterfriction.models.ziegler import ZieglerPendulum


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
