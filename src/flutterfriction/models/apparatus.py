"""The apparatus of Fig. 18 (chapter §2.10): a follower force from sliding Coulomb friction.

A freely rotating wheel of negligible mass is mounted at the loaded end C of the Ziegler double
pendulum with its axle along the rod BC, and pressed against a plate sliding towards the hinge
A. The wheel rolls freely in the direction normal to BC, so the plate can only transmit the
friction force along BC: ``P = mu R``, coaxial with BC (a follower force), ``R`` the contact
force.

The contact force is calibrated (Fig. 18, lower part) by using the straight pendulum itself as
a lever in its vertical plane: a fulcrum at A, a weight ``W`` hanging at ``a`` from A, the
wheel's axle at ``b = l1 + l2`` from A on the same axis and its contact with the plate a wheel
radius ``r`` below that axis. The chapter gives no lever arms and no friction coefficient:
``a``, ``r`` and ``mu`` are parameters. Moment balance about the fulcrum (the friction force
``mu R`` acts ``r`` below it, towards A, and presses the wheel on: a self-energising lever),

    W a = R b - mu R r   =>   R = W a / (b - mu r),   P = mu R = mu a W / (b - mu r),

and ``b - mu r > 0`` is required (otherwise the lever wedges: no finite W gives equilibrium
with sliding). The lever's own weight is not modelled (taken as balanced).

Coordinates of the side view: x along the rod from the fulcrum towards C, y upwards, the
fulcrum at the origin; the plate's surface is the line y = -r.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction

import numpy as np
from numpy.typing import NDArray

from flutterfriction.errors import (
    ParameterError,
    check_finite_array,
    check_nonnegative,
    check_positive,
    named_parameters,
)


@named_parameters
@dataclass(frozen=True)
class FrictionLever:
    """The pendulum as a lever pressing its wheel on the sliding plate (Fig. 18, lower part).

    Parameters
    ----------
    length : float
        ``b``: fulcrum (at A) to the wheel's axle at C, ``l1 + l2`` [m], > 0.
    weight_arm : float
        ``a``: fulcrum to the line of the hanging weight ``W`` [m], > 0.
    wheel_radius : float
        ``r``: the contact with the plate lies ``r`` below the lever's axis [m], >= 0.
    mu : float
        Coulomb friction coefficient of the wheel on the plate, > 0 (dimensionless).
    """

    length: float
    weight_arm: float
    wheel_radius: float
    mu: float

    def __post_init__(self) -> None:
        object.__setattr__(self, "length", check_positive("length", self.length, "m"))
        object.__setattr__(self, "weight_arm",
                           check_positive("weight_arm", self.weight_arm, "m"))
        object.__setattr__(self, "wheel_radius",
                           check_nonnegative("wheel_radius", self.wheel_radius, "m"))
        object.__setattr__(self, "mu", check_positive("mu", self.mu))
        if self.lever_arm() <= 0:
            raise ParameterError(
                f"mu * wheel_radius = {self.mu * self.wheel_radius!r} m must be < length = "
                f"{self.length!r} m: otherwise the friction's moment wedges the lever")
        if not math.isfinite(self.follower_ratio()):  # (an outside audit: inf returned)
            raise ParameterError(
                f"weight_arm / (length - mu * wheel_radius) = P / (mu W) is beyond the double "
                f"range (weight_arm = {self.weight_arm!r} m, length - mu * wheel_radius = "
                f"{self.lever_arm()!r} m)")

    # ------------------------------------------------------------------ closed form
    def lever_arm(self) -> float:
        """``b - mu r`` [m], in exact arithmetic rounded once: near wedging ``mu r`` rounded
        first would cancel against ``b`` (an outside audit: 1.1 % off at b - mu r ~ 1e-15 b)."""
        return float(Fraction(self.length) - Fraction(self.mu) * Fraction(self.wheel_radius))

    def contact_ratio(self) -> float:
        """``R / W = a / (b - mu r)`` (moment balance about the fulcrum)."""
        return self.weight_arm / self.lever_arm()

    def follower_ratio(self) -> float:
        """``P / W = mu a / (b - mu r)``: the slope of the calibration line."""
        return self.mu * self.contact_ratio()

    def follower_ratio_without_offset(self) -> float:
        """``mu a / b``: the slope if the friction's moment about the fulcrum is neglected."""
        return self.mu * self.weight_arm / self.length

    def follower_force(self, W: float) -> float:
        """``P = mu a W / (b - mu r)`` [N] for the hanging weight ``W`` [N] >= 0."""
        P = self.follower_ratio() * check_nonnegative("W", W, "N")
        if not math.isfinite(P):
            raise ParameterError(f"W = {W!r} N gives a follower force beyond the double range")
        return P

    # ------------------------------------------------------------------ the forces
    def points(self) -> dict[str, NDArray]:
        """Side-view points [m]: fulcrum ``O``, weight's hook ``H``, wheel's axle ``C`` and the
        contact ``K`` with the plate."""
        return {"O": np.zeros(2), "H": np.array([self.weight_arm, 0.0]),
                "C": np.array([self.length, 0.0]),
                "K": np.array([self.length, -self.wheel_radius])}

    def contact_direction(self) -> NDArray:
        """The plate's force on the wheel per unit normal force: ``(-mu, 1)`` (normal ``R``
        upwards plus sliding friction ``mu R`` towards the fulcrum, the plate moving that way)."""
        return np.array([-self.mu, 1.0])


def follower_direction(B: NDArray, C: NDArray, plate_velocity: NDArray) -> NDArray:
    """Unit direction of the force the sliding plate transmits to the wheel at C (top view).

    The wheel's axle lies along BC: it rolls freely normal to BC, so only the sliding along BC
    is resisted, by the Coulomb force ``mu R`` opposite to the wheel's sliding relative to the
    plate, i.e. along the plate's velocity component on BC (the wheel's own velocity
    neglected). With the plate moving towards A this is the follower force, from C to B."""
    B, C, v = (check_finite_array(name, x, (2,), "a finite point or vector (x, y)")
               for name, x in (("B", B), ("C", C), ("plate_velocity", plate_velocity)))
    t = C - B
    norm = float(np.linalg.norm(t))
    if not 0 < norm < math.inf:  # (an outside audit: B == C gave [nan, nan])
        raise ParameterError(f"B and C must be distinct points, a finite distance apart "
                             f"(|BC| = {norm:g} m)")
    t /= norm
    s = float(v @ t)
    if s == 0.0:
        raise ParameterError("the plate must slide along BC (its velocity is normal to BC)")
    return np.sign(s) * t
