"""The parameters a figure or a notebook was computed with, in words: the chapter's list by
name ("list (47)") when they are its values, else "your own pendulum (l1 = ...)" with the values
(a figure of a researcher's own parameters must not say it is the chapter's). Text only, no
matplotlib: the notebooks' kernels use it too (importing it from the plotting package cost each
such kernel 0.3 CPU-s of matplotlib's imports, measured)."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

#: A pendulum's parameters in the order and units of list (47) (SI).
_PENDULUM_UNITS = (("l1", "m"), ("l2", "m"), ("d", "m"), ("h", "m"), ("m1", "kg"),
                   ("m2", "kg"), ("m3", "kg"), ("k1", "N m"), ("k2", "N m"), ("c1", "N m s"),
                   ("c2", "N m s"))


def pendulum_text(pendulum: dict[str, float] | None) -> str:
    """The pendulum a figure was computed for, in one short line (``l1 = l2 = 0.1 m, ...``;
    equal pairs written once); empty without parameters (data from before they were kept)."""
    if not pendulum:
        return ""
    parts, done = [], set()
    for name, unit in _PENDULUM_UNITS:
        if name in done or name not in pendulum:
            continue
        twin = {"l1": "l2", "m1": "m2", "k1": "k2", "c1": "c2"}.get(name)
        value = pendulum[name]
        if twin is not None and pendulum.get(twin) == value:
            parts.append(f"{name[0]}1 = {name[0]}2 = {value:g} {unit}")
            done.add(twin)
        else:
            parts.append(f"{name} = {value:g} {unit}")
    return ", ".join(parts)


def rod_text(rod: dict[str, float] | None) -> str:
    """The rod a figure was computed for, in one line with units (``length = 0.35 m,
    B = 0.0135 N m^2, ...``); empty without parameters."""
    from flutterfriction.models.rod import ROD_UNITS

    return ", ".join(f"{k} = {rod[k]:g} {unit}" for k, unit in ROD_UNITS.items()
                     if k in (rod or {}))


def wrap_items(text: str, width: int, sep: str = ", ") -> str:
    """``text``, a list of items joined by ``sep``, on lines of at most ``width`` characters
    broken between items only (never between a value and its unit); an item longer than
    ``width`` gets a line of its own."""
    lines: list[str] = []
    for item in text.split(sep):
        if lines and len(lines[-1]) + len(sep) + len(item) <= width:
            lines[-1] += sep + item
        else:
            lines.append(item)
    return (sep.rstrip() + "\n").join(lines)


def own_parameters_note(data: dict[str, Any], key: str, name: str, width: int = 150) -> str:
    """``""`` when the data's parameters ``key`` are the chapter's list ``name``, else
    "your own pendulum: l1 = ..." wrapped to lines of ``width`` characters: the values, once,
    for a figure that names them in short ("your own pendulum") where space is short (a title
    or a legend entry holding all of them broke Fig. 18's layout; an outside audit)."""
    import textwrap

    text = chapter_list(data, key, name, "")
    if not text:
        return ""
    kind, _, values = text.partition(" (")
    return textwrap.fill(f"{kind}: {values.removesuffix(')')}", width)


#: Longest line of a researcher's own parameters in a figure's text (characters).
OWN_VALUES_WIDTH = 60


def chapter_list(data: dict[str, Any], key: str, name: str, shown: str,
                 short: bool = False) -> str:
    """``shown`` (e.g. ``"list (47)"``) when the data's parameters ``key`` are the chapter's
    list ``name`` (:data:`flutterfriction.parameters.LISTS`), else ``"your own pendulum
    (l1 = ...)"``: a figure of a researcher's own parameters must not say it is the chapter's
    (an outside audit). Data without parameters (drawn by hand): ``shown``. ``short``: "your
    own pendulum" without the values (then :func:`own_parameters_note` gives them)."""
    from flutterfriction.parameters import LISTS, parameter_list

    used = (data.get("params") or {}).get(key)
    if not isinstance(used, dict):
        return shown
    ref = parameter_list(name)
    same = all(used.get(k) == v for k, v in ref.items()) and all(
        not used[k] for k in set(used) - set(ref))  # an extra key (tip mass, kappa) set to 0
    if same:
        return shown
    kind = LISTS[name].kind
    if short:
        return f"your own {kind}"
    values = pendulum_text(used) if kind == "pendulum" else rod_text(used)
    # on lines of at most OWN_VALUES_WIDTH characters: a title holding them in one line
    # widened its figure until the figure check's text sizes failed (an outside review:
    # Fig. 4 at 1585 px for one changed spring, 51 offences; beck_branch, beck_hopf)
    return f"your own {kind} ({wrap_items(values, OWN_VALUES_WIDTH)})"


def pendulum_case(data: dict[str, Any], holds: Callable[[Any], bool], stated: str,
                  short: bool = False) -> str:
    """``stated`` (the chapter's conditions of a figure, e.g. "l1 = l2 = L, ...") where the
    data's pendulum satisfies them (``holds`` of its groups, eq. 17), else "your own pendulum
    (l1 = ...)": a title must not claim the chapter's special case for a researcher's other
    pendulum (an outside review: eqs. 25, 46, 48, Fig. 5 and the paradox map did). ``short``:
    "your own pendulum" alone (:func:`own_parameters_note` gives the values)."""
    from flutterfriction.models.ziegler import ZieglerPendulum

    used = (data.get("params") or {}).get("pendulum")
    if not isinstance(used, dict) or holds(ZieglerPendulum(**used).groups()):
        return stated
    if short:
        return "your own pendulum"
    return f"your own pendulum ({wrap_items(pendulum_text(used), OWN_VALUES_WIDTH)})"


def list47(data: dict[str, Any], shown: str = "list (47)", short: bool = False) -> str:
    """:func:`chapter_list` for the pendulum of list (47)."""
    return chapter_list(data, "pendulum", "list47", shown, short)


def list47_viscous(data: dict[str, Any],
                   shown: str = "list (47), c1 = c2 = 0.006 N m s", short: bool = False) -> str:
    """:func:`chapter_list` for the viscous pendulum of §2.10."""
    return chapter_list(data, "pendulum", "list47_viscous", shown, short)


def list119(data: dict[str, Any], shown: str = "list (119)") -> str:
    """:func:`chapter_list` for the rod of list (119)."""
    return chapter_list(data, "rod", "list119", shown)
