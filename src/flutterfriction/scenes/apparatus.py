"""Scene of chapter §2.10: the apparatus of Fig. 18 (a follower force from sliding friction)
and its lever calibration W -> R -> P, from the statics of the lever (closed-form moment
balance, checked against the lever's equilibrium solved as a linear system of forces)."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from flutterfriction.analysis.statics import planar_equilibrium
from flutterfriction.closed_forms.ziegler import critical_loads_closed_form
from flutterfriction.errors import ParameterError, check_positive, check_real
from flutterfriction.models.apparatus import FrictionLever, follower_direction
from flutterfriction.scenes.common import n_points, pendulum_of, quantity, take


def _lever_equilibrium(lever: FrictionLever, W: float) -> dict[str, float]:
    """Hinge reactions and contact force for the weight ``W`` from the three equilibrium
    equations of the lever as a linear system (no closed form used)."""
    pts = lever.points()
    Ox, Oy, R = planar_equilibrium(
        known=[(pts["H"], (0.0, -W))],
        unknown=[(pts["O"], (1.0, 0.0)), (pts["O"], (0.0, 1.0)),
                 (pts["K"], lever.contact_direction())])
    return {"O_x": float(Ox), "O_y": float(Oy), "R": float(R), "P": float(lever.mu * R)}


def fig18(params: dict[str, Any]) -> dict[str, Any]:
    """Fig. 18: the pendulum with its wheel on the sliding plate (top view, a deflected
    configuration: the transmitted force stays along BC), the lever calibration (side view,
    forces to scale at ``W_drawn``) and the calibration line P(W)."""
    take(params, {"pendulum", "mu", "weight_arm", "wheel_radius", "W_max", "W_drawn",
                  "alpha_deg", "plate_speed", "n_points"})
    pend = pendulum_of(params)
    lever = FrictionLever(pend.l1 + pend.l2, params.get("weight_arm", 0.15),
                          params.get("wheel_radius", 0.02), params.get("mu", 0.25))
    W_max = check_positive("W_max", params.get("W_max", 60.0), "N")
    W_drawn = check_positive("W_drawn", params.get("W_drawn", 30.0), "N")
    V = check_positive("plate_speed", params.get("plate_speed", 0.05), "m/s")
    alpha = params.get("alpha_deg", [6.0, -10.0])
    if not isinstance(alpha, list | tuple) or len(alpha) != 2:
        raise ParameterError(f"alpha_deg must be two angles [alpha1, alpha2] in deg, got "
                             f"{alpha!r}")
    a1, a2 = (math.radians(check_real("alpha_deg", x)) for x in alpha)
    if max(abs(a1), abs(a2)) >= math.pi / 4:
        raise ParameterError(f"alpha_deg must lie in (-45, 45) deg (a drawn configuration of "
                             f"the sliding wheel), got {alpha!r}")

    # -- calibration line: closed form and the linear system at every W
    W = np.linspace(0.0, W_max, n_points(params, 61))
    ratio = lever.follower_ratio()
    P_closed = ratio * W
    P_system = np.array([_lever_equilibrium(lever, w)["P"] for w in W])
    drawn = _lever_equilibrium(lever, W_drawn)
    if pend.c1 == 0 and pend.c2 == 0:
        crit = critical_loads_closed_form(pend)
    else:  # a pendulum with hinge viscosity flutters at its damped load (§2.8)
        from flutterfriction.analysis.ziegler import critical_loads

        crit = critical_loads(pend)

    # -- top view: the pendulum deflected, the plate sliding towards A
    pos = pend.positions(a1, a2)
    v_plate = np.array([-V, 0.0])
    t_force = follower_direction(pos["B"], pos["C"], v_plate)
    P_drawn = lever.follower_force(W_drawn)
    bc = (pos["C"] - pos["B"]) / np.linalg.norm(pos["C"] - pos["B"])
    transverse = float(abs(bc[0] * t_force[1] - bc[1] * t_force[0]))

    q = {
        "follower_ratio": quantity(ratio, drawn["P"] / W_drawn,
                                   "moment balance about the fulcrum, mu a / (b - mu r)",
                                   "equilibrium of the lever (3 forces) as a linear system",
                                   ""),
        "follower_force_at_W_drawn": quantity(P_drawn, drawn["P"],
                                              "closed form mu a W / (b - mu r)",
                                              "linear system: mu R", "N"),
        "calibration_max_deviation": quantity(
            float(np.max(np.abs(P_system - P_closed))), 0.0,
            "max over the W grid of |P (linear system) - (P/W) W|",
            "zero: P is proportional to W", "N"),
    }
    return {
        "mu": lever.mu, "a": lever.weight_arm, "b": lever.length, "r": lever.wheel_radius,
        "l1": pend.l1,
        "W": W.tolist(), "P": P_closed.tolist(), "P_system": P_system.tolist(),
        "ratio": ratio, "ratio_without_offset": lever.follower_ratio_without_offset(),
        "W_drawn": W_drawn, "forces_drawn": drawn,
        "side_points": {k: v.tolist() for k, v in lever.points().items()},
        "top": {"points": {k: v.tolist() for k, v in pos.items()},
                "masses": {"m1": pend.m1, "m2": pend.m2, "m3": pend.m3},
                "alpha_deg": [math.degrees(a1), math.degrees(a2)],
                "plate_velocity": v_plate.tolist(), "force_direction": t_force.tolist(),
                "force_transverse_to_BC": transverse, "P": P_drawn},
        "critical": {"P_flu": crit.P_flu, "P_div": crit.P_div,
                     "W_flu": crit.P_flu / ratio, "W_div": crit.P_div / ratio},
        "quantities": q,
    }
