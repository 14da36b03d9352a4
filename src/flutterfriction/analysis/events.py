"""Poincaré-section events for scipy's ``solve_ivp`` that start on the section."""

from __future__ import annotations

from collections.abc import Callable

from numpy.typing import NDArray


def from_the_section(section: Callable[[float, NDArray], float], direction: float = -1.0,
                     t_start: float = 0.0) -> Callable[[float, NDArray], float]:
    """The event ``section(t, y)`` of an integration that starts on the section at
    ``t_start``: taken as exactly 0 there.

    The start state is a crossing found before (a shooting's section state, a previous run's
    event), so ``section`` is zero there only to rounding. scipy's event search compares the
    sign at the step's start computed from the state with the sign from the dense output at
    the same time; when that residue's sign is not reproduced it finds no sign change in the
    bracket it detected and raises ("f(a) and f(b) must have different signs"; seen with
    LSODA on the rod's section once the function's rounding changed). A start crossing is
    then found at ``t_start`` exactly (callers skip the first part of the period anyway)."""

    def event(t: float, y: NDArray) -> float:
        return 0.0 if t == t_start else section(t, y)

    event.direction = direction
    return event
