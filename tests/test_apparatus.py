"""Fig. 18: the lever calibration W -> R -> P (moment balance against the lever's equilibrium as a
linear system), the follower direction of the wheel, bad input refused, and the figure draws."""

from __future__ import annotations

import numpy as np
import pytest

from flutterfriction.analysis.statics import planar_equilibrium
from flutterfriction.errors import ParameterError
from flutterfriction.models.apparatus import FrictionLever, follower_direction
from flutterfriction.parameters import LIST_47
from flutterfriction.scenes.apparatus import fig18


@pytest.fixture(scope="module")
def data():
    return fig18({"pendulum": dict(LIST_47), "mu": 0.25, "weight_arm": 0.15,
                  "wheel_radius": 0.02, "W_max": 60.0, "W_drawn": 30.0, "n_points": 21})


def test_the_calibration_slope_is_the_moment_balance(data):
    # mu a / (b - mu r) = 0.25 * 0.15 / (0.2 - 0.005) = 5/26, by hand
    assert data["ratio"] == pytest.approx(5 / 26, rel=1e-14)
    assert data["ratio_without_offset"] == pytest.approx(0.25 * 0.15 / 0.2, rel=1e-14)
    F = data["forces_drawn"]
    assert F["R"] == pytest.approx(300 / 13, rel=1e-13)
    assert F["P"] == pytest.approx(75 / 13, rel=1e-13)
    # the fulcrum takes the friction (x) and what the contact does not carry of W (y)
    assert F["O_x"] == pytest.approx(F["P"], rel=1e-13)
    assert F["O_y"] == pytest.approx(30.0 - F["R"], rel=1e-13)
    assert np.max(np.abs(np.array(data["P_system"]) - np.array(data["P"]))) < 1e-12
    for q in data["quantities"].values():
        assert q["value"] == pytest.approx(q["independent"], rel=1e-12, abs=1e-12)


def test_the_friction_moment_presses_the_wheel_on():
    """With the contact below the fulcrum the friction towards A adds to W's moment: R grows
    with r, and at r = 0 the lever ratio is a / b."""
    flat = FrictionLever(0.2, 0.1, 0.0, 0.3)
    assert flat.contact_ratio() == pytest.approx(0.5, rel=1e-15)
    ratios = [FrictionLever(0.2, 0.1, r, 0.3).contact_ratio() for r in (0.0, 0.01, 0.05)]
    assert ratios == sorted(ratios) and ratios[0] < ratios[-1]


def test_planar_equilibrium_balances_forces_and_moments():
    rng = np.random.default_rng(3)
    known = [(rng.normal(size=2), rng.normal(size=2)) for _ in range(3)]
    unknown = [((0.0, 0.0), (1.0, 0.0)), ((0.0, 0.0), (0.0, 1.0)), ((1.0, -0.2), (-0.3, 1.0))]
    x = planar_equilibrium(known, unknown)
    forces = [(np.array(r), np.array(f)) for r, f in known]
    forces += [(np.array(r), xk * np.array(d)) for xk, (r, d) in zip(x, unknown, strict=True)]
    total = sum(f for _, f in forces)
    moment = sum(r[0] * f[1] - r[1] * f[0] for r, f in forces)
    assert np.abs(total).max() < 1e-12 and abs(moment) < 1e-12


def test_a_mechanism_or_a_wrong_count_is_refused():
    with pytest.raises(ParameterError, match="3 unknown"):
        planar_equilibrium([], [((0, 0), (1, 0))])
    with pytest.raises(ParameterError, match="singular"):  # three parallel forces
        planar_equilibrium([((1, 0), (0, -1))],
                           [((0, 0), (0, 1)), ((1, 0), (0, 1)), ((2, 0), (0, 1))])


def test_the_wheel_transmits_a_force_along_BC_whatever_the_plate_direction():
    B, C = np.zeros(2), np.array([np.cos(0.3), np.sin(0.3)])
    f = follower_direction(B, C, np.array([-0.05, 0.0]))
    assert f == pytest.approx(-C, abs=1e-15)  # from C towards B: compressive, coaxial
    with pytest.raises(ParameterError, match="slide along BC"):
        follower_direction(B, np.array([1.0, 0.0]), np.array([0.0, 1.0]))


def test_the_top_view_force_stays_on_BC(data):
    top = data["top"]
    assert top["force_transverse_to_BC"] < 1e-15
    B, C = (np.array(top["points"][k]) for k in "BC")
    assert np.dot(top["force_direction"], C - B) < 0  # pushes C towards B


@pytest.mark.parametrize("kwargs, match", [
    ({"length": 0.0, "weight_arm": 0.1, "wheel_radius": 0.0, "mu": 0.2}, "length"),
    ({"length": 0.2, "weight_arm": -0.1, "wheel_radius": 0.0, "mu": 0.2}, "weight_arm"),
    ({"length": 0.2, "weight_arm": 0.1, "wheel_radius": -0.01, "mu": 0.2}, "wheel_radius"),
    ({"length": 0.2, "weight_arm": 0.1, "wheel_radius": 0.01, "mu": 0.0}, "mu"),
    ({"length": 0.2, "weight_arm": 0.1, "wheel_radius": 0.5, "mu": 0.5}, "wedges"),
])
def test_bad_levers_are_refused(kwargs, match):
    with pytest.raises(ParameterError, match=match):
        FrictionLever(**kwargs)


@pytest.mark.parametrize("over, match", [
    ({"W_max": 0.0}, "W_max"), ({"W_drawn": -1.0}, "W_drawn"),
    ({"alpha_deg": [10.0]}, "alpha_deg"), ({"alpha_deg": [60.0, 0.0]}, "alpha_deg"),
    ({"plate_speed": 0.0}, "plate_speed"), ({"n_points": 3}, "n_points"),
    ({"lever": 1.0}, "unknown scene parameter"),
])
def test_bad_scene_parameters_are_refused(over, match):
    with pytest.raises(ParameterError, match=match):
        fig18({"pendulum": dict(LIST_47), **over})
    with pytest.raises(ParameterError, match="W"):
        FrictionLever(0.2, 0.1, 0.0, 0.2).follower_force(-1.0)


def test_fig18_draws(data):
    import matplotlib.pyplot as plt

    from flutterfriction.plotting.apparatus import plot_fig18

    fig = plot_fig18(data)
    assert len(fig.axes) >= 3
    for ax in fig.axes:
        if ax.get_visible() and ax.get_xlabel():
            assert "[" in ax.get_xlabel() and "[" in ax.get_ylabel()
    plt.close(fig)


def test_the_lever_near_wedging_and_beyond_the_double_range():
    """A second outside audit: b - mu r formed after rounding mu r was 1.1 % off where it is
    ~1e-15 b (now exact, rounded once: the value for these doubles, by Fractions); a lever
    whose P/W overflowed returned inf; B == C and a NaN plate velocity returned [nan, nan]."""
    from fractions import Fraction as F

    lever = FrictionLever(1.0, 0.5, 9.99999999999999, 0.1)
    exact = F(0.1) * F(0.5) / (F(1.0) - F(0.1) * F(9.99999999999999))
    assert lever.follower_ratio() == pytest.approx(float(exact), rel=1e-15)
    with pytest.raises(ParameterError, match="beyond the double range"):
        FrictionLever(1.0, 1e300, 1 - 1e-16, 1.0)
    with pytest.raises(ParameterError, match="^W = .* beyond the double range"):
        FrictionLever(1.0, 10.0, 0.0, 1.0).follower_force(1e308)
    with pytest.raises(ParameterError, match="^B and C must be distinct"):
        follower_direction(np.zeros(2), np.zeros(2), np.array([1.0, 0.0]))
    with pytest.raises(ParameterError, match="^plate_velocity must be"):
        follower_direction(np.zeros(2), np.ones(2), np.array([np.nan, 0.0]))
