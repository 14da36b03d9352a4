"""Exceptions and input validation shared by every entry point."""

from __future__ import annotations

import functools
import inspect
import math
import re
import sys
from numbers import Real
from typing import Any

#: A number as typed by a user (CLI options, nested config values): plain decimal, optionally
#: with an exponent (``-1``, ``0.5``, ``.5``, ``1.5e-3``); Python's ``float`` accepts more
#: (``1_000``, ``infinity``), which a typo can produce.
PLAIN_NUMBER = re.compile(r"[+-]?(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[eE][+-]?[0-9]+)?")
PLAIN_INTEGER = re.compile(r"[+-]?[0-9]+")


def underflows(word: str) -> bool:
    """Whether the decimal ``word`` (:data:`PLAIN_NUMBER`) has a non-zero significand yet
    rounds to 0.0 in double precision (below 2.5e-324): ``float`` takes ``1e-400`` as 0 with
    no word, and a damping of 1e-400 computed as none is the chapter's paradox turned into a
    silent wrong answer (an outside review: the undamped 2.0 for the damped limit 4/3)."""
    significand = re.split(r"[eE]", word.strip(), maxsplit=1)[0]
    return bool(re.search(r"[1-9]", significand)) and float(word) == 0.0


def shown_beside(value: float, bounds: tuple[float, ...], spec: str = "g") -> str:
    """``value`` formatted with ``spec`` for a refusal's "got ...", with all its digits
    (``repr``) where the short form would read as one of the ``bounds`` it violates (outside
    reviews: "got 1" for eta = 1.0000001 against 1; "det M/(M11 M22) = 1e-12 must be
    >= 1e-12" for 9.99999999999e-13)."""
    short = format(value, spec)
    if any(short == format(b, spec) or float(short) == b for b in bounds):
        return repr(float(value))
    return short


class ParameterError(ValueError):
    """A parameter is outside its allowed range; the message names the parameter."""


class ConvergenceError(RuntimeError):
    """A solver did not reach its tolerance; raised instead of returning a wrong root or NaN."""


class SignatureError(ParameterError, TypeError):
    """A model built with an unknown, missing or repeated parameter: a :class:`ParameterError`
    (one line naming it and the allowed names, as every entry point refuses bad input) and a
    ``TypeError`` (what Python raises for a wrong call, which callers may expect)."""


def named_parameters(cls: type) -> type:
    """Class decorator for a model dataclass: its ``__init__`` refuses an unknown, missing or
    repeated parameter, or too many positional ones, with a :class:`SignatureError` naming
    them and the allowed names, before the dataclass's own checks (an outside review: an
    unknown keyword of ``ZieglerPendulum`` or ``Rod`` was the dataclass's bare TypeError)."""
    init = cls.__init__
    params = [p for p in inspect.signature(init).parameters.values() if p.name != "self"]
    names = [p.name for p in params]
    required = [p.name for p in params if p.default is inspect.Parameter.empty]

    @functools.wraps(init)
    def __init__(self: Any, *args: Any, **kwargs: Any) -> None:
        where = cls.__name__
        unknown = sorted(set(kwargs) - set(names))
        if unknown:
            raise SignatureError(f"{where}: unknown parameter(s) {unknown}; allowed: {names}")
        if len(args) > len(names):
            raise SignatureError(f"{where} takes at most {len(names)} parameters {names}, "
                                 f"got {len(args)} positional")
        twice = sorted(set(names[:len(args)]) & set(kwargs))
        if twice:
            raise SignatureError(f"{where}: parameter(s) {twice} given twice (by position "
                                 f"and by name); order: {names}")
        given = set(names[:len(args)]) | set(kwargs)
        missing = [n for n in required if n not in given]
        if missing:
            raise SignatureError(f"{where}: missing parameter(s) {missing}; required: "
                                 f"{required}, optional: {[n for n in names if n not in required]}")
        init(self, *args, **kwargs)

    cls.__init__ = __init__
    return cls


def check_real(name: str, value: object) -> float:
    """Return ``value`` as a finite float, or raise :class:`ParameterError` naming ``name``.
    A real number, or a 0-d numpy array of one (as numpy's reductions return)."""
    if type(value).__name__ == "ndarray" and getattr(value, "ndim", None) == 0 \
            and value.dtype.kind in "iuf":
        value = value.item()
    if isinstance(value, bool) or not isinstance(value, Real):
        raise ParameterError(f"{name} must be a real number, got {value!r}")
    try:
        x = float(value)
    except OverflowError:  # an int beyond the double range, e.g. 10**400
        raise ParameterError(f"{name} must be finite (within the double range, |x| < "
                             f"1.8e308), got an integer of {len(str(abs(value)))} digits"
                             ) from None
    if not math.isfinite(x):
        raise ParameterError(f"{name} must be finite, got {value!r}")
    return x


#: The smallest normal double: a nonzero value below it (subnormal) has lost digits already
#: (an outside audit: c = 1e-316 gave a flutter load 2.5e-6 off, silently).
NORMAL_MIN = sys.float_info.min


def check_positive(name: str, value: object, unit: str = "") -> float:
    """Finite, strictly positive and a normal double (allowed range: [2.2e-308, inf))."""
    x = check_real(name, value)
    if x <= 0.0:
        raise ParameterError(f"{name} must be > 0{_unit(unit)}, got {x!r}")
    if x < NORMAL_MIN:
        raise ParameterError(f"{name} must be >= {NORMAL_MIN:.3g}{_unit(unit)} (a subnormal "
                             f"double has lost digits), got {x!r}")
    return x


def check_nonnegative(name: str, value: object, unit: str = "") -> float:
    """Finite, non-negative, 0 or a normal double (allowed: 0 or [2.2e-308, inf))."""
    x = check_real(name, value)
    if x < 0.0:
        raise ParameterError(f"{name} must be >= 0{_unit(unit)}, got {x!r}")
    if 0.0 < x < NORMAL_MIN:
        raise ParameterError(f"{name} must be 0 or >= {NORMAL_MIN:.3g}{_unit(unit)} (a "
                             f"subnormal double has lost digits), got {x!r}")
    return x + 0.0  # -0.0 read as 0.0 (it passes "x >= 0"; printed, it read "-0")


def check_integer(name: str, value: object, low: int, high: int | None = None) -> int:
    """An integer (not a bool, not 4.0 or "4") in ``[low, high]`` (``[low, inf)`` without
    ``high``), or a :class:`ParameterError` naming ``name`` and the range."""
    import numpy as np

    if isinstance(value, bool) or not isinstance(value, int | np.integer) or value < low \
            or (high is not None and value > high):
        allowed = f">= {low}" if high is None else f"in [{low}, {high}]"
        raise ParameterError(f"{name} must be an integer {allowed}, got {value!r}")
    return int(value)


def check_finite_array(name: str, value: object, shape: tuple[int, ...],
                       what: str | None = None) -> Any:
    """``value`` as a float array of ``shape`` with finite entries, or a
    :class:`ParameterError` ``"<name> must be <what>"`` (default: a finite array of the
    shape)."""
    import numpy as np

    must = f"{name} must be {what or f'a finite array of shape {shape}'}"

    def shown() -> str:  # one line, whatever the repr of an array holds (on a refusal only:
        return " ".join(repr(value).split())  # a repr per call cost seconds in the scans)
    try:
        raw = np.asarray(value)
    except (ValueError, TypeError):  # ragged nesting
        raise ParameterError(f"{must}, got {shown()[:80]}") from None
    # real numbers only: float() would drop an imaginary part and read "1" or True as numbers
    # (and numpy reads [True, 1] as integers)
    if raw.dtype.kind not in "iuf" or (not isinstance(value, np.ndarray) and any(
            isinstance(x, bool | np.bool_) for x in np.asarray(value, dtype=object).flat)):
        got = f"got {shown()}" if len(shown()) <= 80 else f"got dtype {raw.dtype}"
        raise ParameterError(f"{must} (real numbers), {got}")
    a = raw.astype(float)
    if a.shape != shape:
        got = f"got {shown()}" if a.size <= 6 else f"got shape {a.shape}"
        raise ParameterError(f"{must}, {got}")
    if not np.all(np.isfinite(a)):
        at = tuple(int(i) for i in np.argwhere(~np.isfinite(a))[0])
        got = f"got {shown()}" if a.size <= 6 else f"got {a[at]} at index {at}"
        raise ParameterError(f"{must}, {got}")
    return a


def check_finite_reals(name: str, value: object) -> Any:
    """``value`` (a number or an array of any shape) as floats, every entry real and finite, or
    a :class:`ParameterError` naming ``name`` (numpy reads "1" and True as numbers, and NaN
    went on into NaN results; outside reviews of the closed forms and the pendulum's
    kinematics). :func:`check_finite_array` where the shape is fixed."""
    import numpy as np

    if isinstance(value, str | bytes | bool | np.bool_) or value is None:
        raise ParameterError(f"{name} must be a real number or an array of them, finite; got "
                             f"{value!r}")
    try:
        raw = np.asarray(value)
    except (ValueError, TypeError):  # ragged nesting
        raise ParameterError(f"{name} must be a real number or an array of them, finite") \
            from None
    if raw.dtype.kind not in "iuf":
        raise ParameterError(f"{name} must be a real number or an array of them, finite; got "
                             f"dtype {raw.dtype}")
    a = raw.astype(float)
    if not np.all(np.isfinite(a)):
        raise ParameterError(f"{name} must be finite (no NaN or inf), got {value!r}")
    return a


def _unit(unit: str) -> str:
    return f" {unit}" if unit else ""


def check_finite_result(value: Any, why: str) -> Any:
    """``value`` if every entry is finite, else :class:`ParameterError` (``why``): a result that
    overflowed is refused, never returned as inf or NaN."""
    import numpy as np

    if not np.all(np.isfinite(value)):
        raise ParameterError(why)
    return value
