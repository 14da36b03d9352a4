"""The clamped elastica of Fig. 9 (§2.5–2.6) and the balances of Figs. 6–8: the geometrically
exact solvers against the closed form by elliptic integrals, the linear cantilever and the
third-order perturbation; bad input refused before any work."""

from __future__ import annotations

import math

import numpy as np
import pytest
from conftest import ROOT

from flutterfriction.analysis import elastica as el
from flutterfriction.errors import ParameterError
from flutterfriction.parameters import LIST_119

L, B = LIST_119["length"], LIST_119["B"]
FIG09 = {"rod": dict(LIST_119), "P1": 0.2, "P2": 0.5, "q1": -1.0, "q2": -2.0,
         "n_points": 41}


@pytest.mark.parametrize(("P1", "P2"), [(0.0, 0.8), (0.2, 0.5), (-0.4, 0.6), (0.3, -0.5),
                                        (0.0, 3.0)])
def test_end_force_shooting_matches_the_elliptic_closed_form(P1, P2):
    """A fixed end force of any direction: tip and whole curve to ~1e-12 (the brief's 1e-8)."""
    sol = el.solve_shooting(L, B, el.ElasticaLoads(P1=P1, P2=P2))
    cf = el.tip_force_closed_form(L, B, P1, P2)
    s = np.linspace(0.0, L, 101)
    assert np.max(np.abs(sol.position(s) - cf.position(s))) / L < 1e-11
    assert np.max(np.abs(sol.theta(s) - cf.theta(s))) < 1e-11
    assert sol.tip_rotation == pytest.approx(cf.tip_rotation, rel=1e-12, abs=1e-13)
    assert abs(cf.theta(0.0)[0]) < 1e-14 and np.allclose(cf.position(0.0), 0.0, atol=1e-15)
    # the end turns towards the force, never past it
    phi = math.atan2(-P2, -P1)
    assert abs(math.remainder(cf.tip_rotation - phi, 2 * math.pi)) < abs(
        math.remainder(phi, 2 * math.pi))


def test_closed_form_is_the_classical_cantilever():
    """P1 = 0: sqrt(F/B) l = K(k) - F(varphi0, k), k^2 = (1 + sin alpha)/2, sin varphi0 =
    1/(k sqrt 2) (Bisshopp and Drucker 1945), independently of our parametrisation."""
    from scipy.special import ellipk, ellipkinc

    F = 0.8
    cf = el.tip_force_closed_form(L, B, 0.0, F)
    alpha = -cf.tip_rotation
    k2 = (1 + math.sin(alpha)) / 2
    varphi0 = math.asin(1 / math.sqrt(2 * k2))
    assert ellipk(k2) - ellipkinc(varphi0, k2) == pytest.approx(math.sqrt(F / B) * L,
                                                                 rel=1e-13)


def test_collocation_agrees_with_shooting_under_all_four_loads():
    loads = el.ElasticaLoads(P1=0.2, P2=0.5, q1=-1.0, q2=-2.0)
    a = el.solve_shooting(L, B, loads)
    b = el.solve_collocation(L, B, loads)
    s = np.linspace(0.0, L, 51)
    assert np.max(np.abs(a.position(s) - b.position(s))) / L < 1e-10
    assert np.max(np.abs(a.moment(s) - b.moment(s))) < 1e-10
    assert np.max(np.abs(a.force(s) - b.force(s))) < 1e-13  # a' = -q: linear, collocated exactly
    assert a.clamp_residual < 1e-13
    # a visibly large deflection: the end turns by more than 60 degrees
    assert a.tip_rotation < -math.radians(60)


def test_small_loads_approach_the_linear_cantilever_as_load_squared():
    base = el.ElasticaLoads(P2=0.5, q2=-2.0)
    c1, c2, c3 = el.perturbation_tip_deflection(L, B, base)
    assert c1 == pytest.approx(el.linear_tip_deflection(L, B, base), rel=1e-14)
    assert c2 == 0.0  # transverse loads only: u2 is odd in the load
    rel = []
    for e in (1e-2, 1e-3):
        u = el.solve_shooting(L, B, base.scaled(e), load_steps=1).tip_displacement()[1]
        rel.append(u / el.linear_tip_deflection(L, B, base.scaled(e)) - 1.0)
    assert math.log10(rel[0] / rel[1]) == pytest.approx(2.0, abs=1e-3)
    assert rel[1] / 1e-6 == pytest.approx(c3 / c1, rel=1e-5)


def test_perturbation_series_with_axial_loads():
    """With P1, q1 the relative difference from the linear cantilever is first order (the
    beam-column coupling c2), and the third-order series is right to O(e^4)."""
    loads = el.ElasticaLoads(P1=0.2, P2=0.5, q1=-1.0, q2=-2.0)
    c1, c2, c3 = el.perturbation_tip_deflection(L, B, loads)
    assert c2 != 0.0
    for e in (1e-2, 1e-3):
        u = el.solve_shooting(L, B, loads.scaled(e), load_steps=1).tip_displacement()[1]
        series = c1 * e + c2 * e**2 + c3 * e**3
        assert abs(u - series) < 50 * abs(c1) * e**4 + 1e-15


def test_equilibrium_of_cuts_and_parts():
    loads = el.ElasticaLoads(P1=0.2, P2=0.5, q1=-1.0, q2=-2.0)
    for sol in (el.solve_shooting(L, B, loads), el.solve_collocation(L, B, loads)):
        for sc in (0.0, 0.3 * L, 0.77 * L):
            assert el.moment_of_loads_beyond(sol, sc) == pytest.approx(
                sol.moment(sc)[0], rel=1e-11, abs=1e-14)
        bal = el.part_balances(sol, 0.2 * L, 0.65 * L)
        assert abs(bal["force"]) < 1e-14
        assert abs(bal["moment"]) < 1e-11
        assert abs(bal["eq87"]) < 1e-11
        pr = el.projections(sol)
        assert pr["d"] == pytest.approx(pr["d_positions"], rel=1e-12)
        assert pr["h"] == pytest.approx(pr["h_positions"], rel=1e-12)


def test_eq100_the_follower_free_end_force():
    """Eq. (87) with q . t = 0 (end forces only): N + M^2/(2B) is constant, equal to its end
    value P . t(l) (eq. 97) along the whole rod."""
    sol = el.solve_shooting(L, B, el.ElasticaLoads(P1=0.3, P2=0.7))
    s = np.linspace(0.0, L, 41)
    N, _ = sol.normal_and_shear(s)
    inv = N + sol.moment(s) ** 2 / (2 * B)
    assert np.ptp(inv) < 1e-11


@pytest.mark.parametrize(("kwargs", "name"), [
    ({"length": float("nan")}, "length"), ({"B": -1.0}, "B"), ({"B": 0.0}, "B"),
    ({"length": "1"}, "length"), ({"load_steps": 0}, "load_steps"),
    ({"rtol": float("inf")}, "rtol")])
def test_bad_solver_input_is_refused(kwargs, name):
    args = {"length": L, "B": B, "loads": el.ElasticaLoads(P2=0.5)}
    extra = {k: kwargs.pop(k) for k in list(kwargs) if k in ("load_steps", "rtol")}
    args.update(kwargs)
    with pytest.raises(ParameterError, match=name):
        el.solve_shooting(**args, **extra)


@pytest.mark.parametrize("field", ["P1", "P2", "q1", "q2"])
def test_bad_loads_are_refused(field):
    with pytest.raises(ParameterError, match=field):
        el.ElasticaLoads(**{field: float("nan")})
    with pytest.raises(ParameterError, match=field):
        el.ElasticaLoads(**{field: True})


def test_axial_end_force_has_no_closed_form_here():
    with pytest.raises(ParameterError, match="axial"):
        el.tip_force_closed_form(L, B, 0.5, 0.0)
    with pytest.raises(ParameterError, match="B"):
        el.tip_force_closed_form(L, -B, 0.0, 0.5)


# ---------------------------------------------------------------------- the scene
def test_scene_quantities_and_bad_parameters():
    from flutterfriction.scenes.rod_statics import elastica

    d = elastica(FIG09)
    q = d["quantities"]
    for key in ("tip_deflection", "tip_rotation", "tip_force_deflection",
                "tip_force_rotation", "cut_moment", "projection_d", "projection_h"):
        assert q[key]["value"] == pytest.approx(q[key]["independent"], rel=1e-10), key
    assert q["arclength"]["value"] == pytest.approx(L, rel=1e-12)
    assert q["cut_force"]["value"] == pytest.approx(q["cut_force"]["independent"], rel=1e-14)
    for key in ("part_force_balance", "part_moment_balance", "part_eq87",
                "tip_force_curve_error"):
        assert abs(q[key]["value"]) < 1e-11 and abs(q[key]["independent"]) < 1e-11
    assert q["linear_limit_order"]["value"] == pytest.approx(2.0, abs=1e-3)
    assert len(d["s"]) == 41
    # the frame of Fig. 6: t, m orthonormal, m rotated -pi/2 from t (eq. 71), n = m here
    t, m, n = (np.array(d["point"][k]) for k in ("t", "m", "n"))
    assert t @ m == pytest.approx(0.0, abs=1e-15)
    assert t[0] * m[1] - t[1] * m[0] == pytest.approx(-1.0)
    assert np.allclose(n, m)
    for bad, name in (({"P2": 0.0}, "P2"), ({"cut": 1.5}, "cut"), ({"part": [0.6, 0.2]}, "part"),
                      ({"q1": float("nan")}, "q1"), ({"linear_factors": [0.1]}, "linear"),
                      ({"rod": {**LIST_119, "B": -1.0}}, "B"), ({"load": 1.0}, "unknown"),
                      ({"n_points": 5}, "n_points")):
        with pytest.raises(ParameterError, match=name):
            elastica({**FIG09, **bad})


@pytest.mark.slow  # > 4 s on a 2-core AMD EPYC host (2026-11-29)
def test_figures_6_to_9_draw():
    import io

    import matplotlib

    matplotlib.use("Agg")
    from flutterfriction.plotting import rod_statics as rp
    from flutterfriction.scenes.rod_statics import elastica

    d = elastica(FIG09)
    for f in ("06", "07", "08", "09"):
        fig = getattr(rp, f"plot_fig{f}")(d)
        assert fig._suptitle.get_text().startswith(f"Fig. {int(f)}")
        for ax in fig.axes:
            assert "[" in ax.get_xlabel() and "[" in ax.get_ylabel()
        fig.savefig(io.BytesIO(), format="png", dpi=40)


@pytest.mark.slow  # > 4 s on a 2-core AMD EPYC host (2026-11-29)
@pytest.mark.parametrize("loads", [{}, {"P2": -0.5, "q2": 2.0}, {"P2": 0.2, "q1": 0.0,
                                                                   "q2": 3.0}],
                         ids=["configured", "bending up", "S-shaped"])
def test_figures_6_to_9_pass_the_figure_check(loads):
    """No overlapping, clipped or covered text, units and legends everywhere, whichever side
    the rod bends to (the layout follows the computed shape)."""
    import matplotlib.pyplot as plt

    from flutterfriction.figure_check import check_figure
    from flutterfriction.plotting import rod_statics as rp
    from flutterfriction.scenes.rod_statics import elastica

    d = elastica({**FIG09, **loads})
    for f in ("06", "07", "08", "09"):
        fig = getattr(rp, f"plot_fig{f}")(d)
        assert check_figure(fig) == [], f
        plt.close(fig)


def test_elastica_api_refuses_arc_lengths_off_the_rod_and_bad_iteration_counts():
    """Outside audit: the dense outputs extrapolated silently beyond the rod (theta(-1 m) =
    3773 rad), a part with s1 > s2 was accepted, NaN arc lengths gave NaN, and max_iter = 0 or
    load_steps = 0 raised UnboundLocalError or a bare AssertionError."""
    loads = el.ElasticaLoads(P1=-0.5, P2=0.3, q1=0.1, q2=0.2)
    sol = el.solve_shooting(0.35, 0.0332, loads)
    for call, match in [(lambda: sol.theta([-1.0]), "s must be finite arc lengths"),
                        (lambda: sol.position([10.0]), "s must be finite arc lengths"),
                        (lambda: el.moment_of_loads_beyond(sol, 2.0), "s_cut must"),
                        (lambda: el.moment_of_loads_beyond(sol, float("nan")), "s_cut must"),
                        (lambda: el.part_balances(sol, 0.3, 0.1), "needs s1 < s2"),
                        (lambda: el.internal_force([float("nan")], 0.35, loads), "s must"),
                        (lambda: el.solve_shooting(0.35, 0.0332, loads, max_iter=0),
                         "max_iter must"),
                        (lambda: el.solve_collocation(0.35, 0.0332, loads, load_steps=0),
                         "load_steps must")]:
        with pytest.raises(ParameterError, match=match):
            call()
    assert sol.theta([0.0, 0.35]).shape == (2,)  # the ends themselves are on the rod


@pytest.mark.slow  # 6-9 s on a slower host (2026-11-24): with the slow ones
def test_a_failed_elastica_scene_names_its_loads():
    """Outside audit: elastica.P1 = 100 N (150 Euler loads) failed with "solve_bvp failed ...
    mesh nodes", naming no parameter; the message now names the loads and the Euler load.
    (100 N is now beyond the scene's range, 200 B/l^2 = 54.2 N, refused up front; 30 N, 45
    Euler loads, is within it and still beyond what the continuation follows.)"""
    from flutterfriction.config import load_config, scene_params
    from flutterfriction.errors import ConvergenceError, ParameterError
    from flutterfriction.scenes.rod_statics import elastica

    params = scene_params(load_config(ROOT / "workflow" / "config.yaml"), "elastica")
    with pytest.raises(ConvergenceError, match=r"P1, P2, q1, q2 = 30 N.*Euler load"):
        elastica({**params, "P1": 30.0})
    with pytest.raises(ParameterError, match=r"^P1 must be within \+-200 B/l\^2 = \+-54\.2041 N"):
        elastica({**params, "P1": 100.0})


def test_linear_and_perturbation_deflections_refuse_overflow():
    """An outside audit: l = 1e300 m, B = 1e-300 N m^2 raised a bare OverflowError."""
    from flutterfriction.analysis import elastica as el
    from flutterfriction.errors import ParameterError

    loads = el.ElasticaLoads(P2=1e300)
    for f in (el.linear_tip_deflection, el.perturbation_tip_deflection):
        with pytest.raises(ParameterError, match="overflows the double range"):
            f(1e300, 1e-300, loads)
    # eq. (95): -P2 l^3 / (3 B)
    assert el.linear_tip_deflection(0.35, 0.0332, el.ElasticaLoads(P2=1.0)) == pytest.approx(
        -0.35**3 / (3 * 0.0332), rel=1e-15)


def test_the_stability_eigenvalue_of_the_straight_rod_is_eulers():
    """mu = pi^2/4 - P1 l^2/B for the straight rod under an end thrust (zero at the Euler
    load), to the extrapolated discretisation's 1e-8."""
    for P1 in (0.0, 0.5, 2.4):
        sol = el.solve_shooting(1.0, 1.0, el.ElasticaLoads(P1=P1))
        assert el.stability_eigenvalue(sol) == pytest.approx(math.pi**2 / 4 - P1, abs=1e-8)


@pytest.mark.slow  # > 4 s on a 2-core AMD EPYC host (2026-11-29)
def test_past_the_euler_load_the_stable_bent_equilibrium_is_returned():
    """An outside audit: P1 just past the Euler load with a tiny P2 gave the unstable, nearly
    straight equilibrium bent against the push (theta(l) = +5.2e-6) from both solvers. Shooting
    now returns the stable one (the closed form's -0.0283, the post-buckling estimate
    -sqrt(8e-4)); collocation refuses instead of returning the unstable one."""
    from flutterfriction.errors import ConvergenceError

    euler = math.pi**2 / 4
    for P1, P2 in ((1.0001 * euler, 1e-9), (20 * euler, 1e-4 * euler)):
        loads = el.ElasticaLoads(P1=P1, P2=P2)
        sol = el.solve_shooting(1.0, 1.0, loads)
        closed = el.tip_force_closed_form(1.0, 1.0, P1, P2)
        assert sol.tip_rotation == pytest.approx(closed.tip_rotation, rel=1e-9)
        assert el.stability_eigenvalue(sol) > 0
    assert sol.tip_rotation < -3.1  # 20 Euler loads: the end turned nearly back on itself
    with pytest.raises(ConvergenceError, match="unstable equilibrium"):
        el.solve_collocation(1.0, 1.0, el.ElasticaLoads(P1=1.0001 * euler, P2=1e-9))
    with pytest.raises(ConvergenceError, match="either side"):
        el.solve_shooting(1.0, 1.0, el.ElasticaLoads(P1=2 * euler))


def test_a_wandering_newton_ends_in_the_stable_equilibrium_not_a_hang():
    """An outside audit's loads (3 Euler loads, distributed loads): Newton wandered to
    theta(l) ~ 1e7 rad and the integrations there took minutes. Now the stable equilibrium,
    which collocation (independent) confirms."""
    loads = el.ElasticaLoads(P1=3 * math.pi**2 / 4, P2=0.01, q1=2.0, q2=-1.0)
    sol = el.solve_shooting(1.0, 1.0, loads)
    assert el.stability_eigenvalue(sol) > 1.0
    colloc = el.solve_collocation(1.0, 1.0, loads)
    assert sol.tip_rotation == pytest.approx(colloc.tip_rotation, rel=1e-9)
    s = np.linspace(0.0, 1.0, 11)
    assert np.max(np.abs(sol.position(s) - colloc.position(s))) < 1e-9


@pytest.mark.slow  # 6-9 s on a slower host (2026-11-24): with the slow ones
def test_the_loading_path_is_followed_through_its_turn_to_the_right_side():
    """A second outside audit: with tip and distributed transverse loads of opposite signs
    the stable equilibrium on the wrong side was returned (+3.0423 rad; the auditor's own
    arc-length continuation of the loading path reaches -3.0578), and a pure transverse tip
    load P2 = 1000 B/l^2 (here -300) was refused (a fold test on an absolute 1e-8 and a
    residual below the integration's amplified round-off). The path is now followed with
    halved steps through the turn; the tip-load cases against the closed form (a transverse
    load at the solvers' range, LOAD_RANGE_MAX = 200 B/l^2: beyond it they refuse, see
    test_loads_beyond_the_solvers_range_are_refused_before_any_work)."""
    for loads, path in (((20.0, -0.35, 0.0, -1.0), -3.0578), ((8.0, -0.0035, 0.0, -0.01),
                                                                   -2.6509)):
        sol = el.solve_shooting(1.0, 1.0, el.ElasticaLoads(*loads))
        assert sol.tip_rotation == pytest.approx(path, abs=2e-4)
        assert el.stability_eigenvalue(sol) > 0
    for P1, P2 in ((0.0, -el.LOAD_RANGE_MAX), (8 * math.pi**2 / 4, 1e-6 * math.pi**2 / 4)):
        sol = el.solve_shooting(1.0, 1.0, el.ElasticaLoads(P1=P1, P2=P2))
        closed = el.tip_force_closed_form(1.0, 1.0, P1, P2)
        assert sol.tip_rotation == pytest.approx(closed.tip_rotation, rel=1e-9)


@pytest.mark.slow  # 6-9 s on a slower host (2026-11-24): with the slow ones
def test_an_end_force_near_the_axis_an_outside_audit_and_its_follow_up():
    """An outside audit and what checking it found:

    - the closed form refused a pushing force 1e-13 off axis as "axial (P2 = 0)", and was
      wrong to 4e-5 at P2/P1 = 1e-11 (its clamp angle computed as -phi - pi lost the digits;
      Brent's absolute 1e-16 tolerance the rest): now exact to round-off against the
      beam-column's theta(l) = -(P2/P1)(sec(k l) - 1) below the Euler load;
    - a pulling force near the axis loses digits in the elliptic form (1.5e-5 at 1e-6 rad):
      refused there, naming the limit; a raw RuntimeError of Brent's became a ConvergenceError;
    - shooting refused P2 = 1e-12 B/l^2 at the Euler load "with no transverse load", and at
      1.2 Euler loads returned the equilibrium on the WRONG side for P2 = 1e-13 (+1.2245 rad;
      Newton's noise near the bifurcation read as the loading path's side);
    - a length of 1e200 m raised a bare OverflowError."""
    from flutterfriction.errors import ConvergenceError, ParameterError

    for P2 in (1e-6, 1e-11, 1e-13, 1e-20, -1e-13):
        exact = -P2 * (1.0 / math.cos(1.0) - 1.0)  # P1 = B/l^2: k l = 1
        closed = el.tip_force_closed_form(1.0, 1.0, 1.0, P2).tip_rotation
        assert closed == pytest.approx(exact, rel=1e-13)
        shot = el.solve_shooting(1.0, 1.0, el.ElasticaLoads(P1=1.0, P2=P2)).tip_rotation
        assert shot == pytest.approx(exact, rel=1e-11)
    with pytest.raises(ParameterError, match="P1 < 0.*0.01 rad off"):
        el.tip_force_closed_form(1.0, 1.0, -1.0, 1e-6)
    assert el.tip_force_closed_form(1.0, 1.0, -1.0, 0.02).tip_rotation == pytest.approx(
        el.solve_shooting(1.0, 1.0, el.ElasticaLoads(P1=-1.0, P2=0.02)).tip_rotation,
        rel=1e-11)
    with pytest.raises(ConvergenceError, match="closed form's end rotation"):
        el.tip_force_closed_form(1.0, 1.0, 1.0, 1e-300)
    for P1, P2, at in ((2.47, 1e-12, -0.0917609577), (3.0, 1e-13, -1.2245236055),
                       (3.0, -1e-13, 1.2245236055), (3.0, 1e-20, -1.2245236055)):
        sol = el.solve_shooting(1.0, 1.0, el.ElasticaLoads(P1=P1, P2=P2))
        assert sol.tip_rotation == pytest.approx(at, rel=1e-9)
        assert sol.tip_rotation == pytest.approx(
            el.tip_force_closed_form(1.0, 1.0, P1, P2).tip_rotation, rel=1e-9)
    with pytest.raises(ParameterError, match="floating-point range"):
        el.solve_shooting(1e200, 1.0, el.ElasticaLoads(P2=1.0))
    # a review of the above: with tiny transverse loads pushing opposite ways the linear end
    # rotation's sign is not the buckling side (P1 = 20, q2 l/P2 = 2.9: the path, followed at
    # larger loads of the same ratio, ends at +3.0500; the linear rule gave -3.0500): refused
    sol = el.solve_shooting(1.0, 1.0, el.ElasticaLoads(P1=20.0, P2=1e-9, q2=2.9e-9))
    assert sol.tip_rotation == pytest.approx(3.050011, abs=1e-5)
    with pytest.raises(ConvergenceError, match="push opposite ways"):
        el.solve_shooting(1.0, 1.0, el.ElasticaLoads(P1=20.0, P2=1e-13, q2=2.9e-13))
    # the closed form's shape: refused where scipy's ellipj approximates (modulus within
    # 1e-9 of 1: theta(l) was 1.2e-4 off at 60 B/l^2, 0.02 rad off the axis) and off the rod
    big = el.tip_force_closed_form(1.0, 1.0, -60 * math.cos(0.02), 60 * math.sin(0.02))
    assert big.tip_rotation == pytest.approx(-0.0199827005244302, rel=1e-13)
    with pytest.raises(ConvergenceError, match="modulus within"):
        big.theta(1.0)
    with pytest.raises(ConvergenceError, match="modulus within"):
        big.position(0.5)
    small = el.tip_force_closed_form(1.0, 1.0, 1.0, 0.5)
    for s_bad in (1.5, math.nan, -0.1):
        with pytest.raises(ParameterError, match="arc lengths"):
            small.theta(s_bad)
        with pytest.raises(ParameterError, match="arc lengths"):
            small.position(s_bad)
    # (Brent's relative tolerance underflowed to 0 here: a bare ValueError; now floored)
    assert el.tip_force_closed_form(1.0, 1.0, 3.0, 1e-310).tip_rotation == pytest.approx(
        -1.2245236055, rel=1e-9)


def test_collocation_near_the_euler_load_tightens_its_tolerance():
    """An outside audit: 1e-6 below Euler's load (P1 = 2.4674 B/l^2, a transverse 1e-9) the
    lowest eigenvalue of the second variation is 1.2e-6 and solve_bvp's residual tolerance
    1e-10 left the tip rotation 8e-4 off (4.01931e-4 for 4.0225903e-4, the audit's own
    shooting at rtol 1e-13 from two starts). Solved again at tol mu 1e-8 (floor 1e-13): to
    1e-7 of the shooting solution."""
    from flutterfriction.analysis import elastica as el

    loads = el.ElasticaLoads(2.4674, 0.0, 0.0, 1e-9)
    colloc = el.solve_collocation(1.0, 1.0, loads)
    assert colloc.tip_rotation == pytest.approx(4.0225903e-4, rel=1e-7)
    assert "tol 1e-13" in colloc.method


def test_loads_beyond_the_solvers_range_are_refused_before_any_work():
    """An outside audit: P1 = -1000 B/l^2 (pulling) with q2 = 500 B/l^3 did not return from
    solve_shooting in 60 s (measured after: the loading path advances, each integration
    slower as the load grows: 11 s at 200 B/l^2, 63 s at 400, minutes at 1000). Both solvers
    now refuse a load beyond LOAD_RANGE_MAX (B/l^2, B/l^3 for q) at once, naming it and its
    range in SI units for the rod; at the range's end they solve (the slow test above)."""
    import time

    from flutterfriction.errors import ParameterError

    length, B = 2.0, 3.0  # unit B/l^2 = 0.75 N, B/l^3 = 0.375 N/m
    cases = ((el.ElasticaLoads(-1000.0 * 0.75, 0.0, 0.0, 500.0 * 0.375), "P1", "150"),
             (el.ElasticaLoads(0.0, 200.001 * 0.75, 0.0, 0.0), "P2", "150"),
             (el.ElasticaLoads(0.0, 1.0, -201.0 * 0.375, 0.0), "q1", "75"),
             (el.ElasticaLoads(0.0, 1.0, 0.0, -250.0 * 0.375), "q2", "75"))
    for loads, key, bound in cases:
        for solve in (el.solve_shooting, el.solve_collocation):
            t = time.process_time()
            with pytest.raises(ParameterError, match=rf"{key} must be within \+-200 B/l\^"
                                                     rf"[23] = \+-{bound} N"):
                solve(length, B, loads)
            assert time.process_time() - t < 1.0  # before any work (~1 ms)
    el.check_load_range(length, B, el.ElasticaLoads(-200 * 0.75, 200 * 0.75, 200 * 0.375,
                                                    -200 * 0.375))  # the ends are in range
