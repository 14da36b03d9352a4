"""Exceptions and input validation shared by every entry point."""

from __future__ import annotations

import math
from numbers import Real


class ParameterError(ValueError):
    """A parameter is outside its allowed range; the message names the parameter."""


class ConvergenceError(RuntimeError):
    """A solver did not reach its tolerance; raised instead of returning a wrong root or NaN."""


def check_real(name: str, value: object) -> float:
    """Return ``value`` as a finite float, or raise :class:`ParameterError` naming ``name``."""
    if isinstance(value, bool) or not isinstance(value, Real):
        raise ParameterError(f"{name} must be a real number, got {value!r}")
    x = float(value)
    if not math.isfinite(x):
        raise ParameterError(f"{name} must be finite, got {value!r}")
    return x


def check_positive(name: str, value: object, unit: str = "") -> float:
    """Finite and strictly positive (allowed range: (0, inf))."""
    x = check_real(name, value)
    if x <= 0.0:
        raise ParameterError(f"{name} must be > 0{_unit(unit)}, got {x!r}")
    return x


def check_nonnegative(name: str, value: object, unit: str = "") -> float:
    """Finite and non-negative (allowed range: [0, inf))."""
    x = check_real(name, value)
    if x < 0.0:
        raise ParameterError(f"{name} must be >= 0{_unit(unit)}, got {x!r}")
    return x


def _unit(unit: str) -> str:
    return f" {unit}" if unit else ""
