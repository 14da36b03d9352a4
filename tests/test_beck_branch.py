"""The rod's branch of limit cycles with a load stop (scene ``beck_branch``)."""

from __future__ import annotations

import numpy as np
import pytest
from conftest import ROOT

from flutterfriction.analysis.rod_cycles import cycle_branch
from flutterfriction.errors import ParameterError
from flutterfriction.models.rod import Rod

ROD119 = Rod(length=0.35, B=0.0332, rho=0.0546, D=7.078e-6)


@pytest.fixture(scope="module")
def short_branch():
    """2 elements (damped flutter load 2.9458 N) from A = 1 cm to 2.955 N, landing on 2.952 N."""
    return cycle_branch(ROD119, n_elements=2, A_first=0.01, A_max=0.3, rtol=1e-9,
                        max_points=12, P_max=2.955, land_at=(2.952,), newton_tol=1e-5,
                        ds_first=0.05, ds_max=0.3, error_target=5e-3)


@pytest.mark.slow
def test_short_branch_lands_on_the_requested_loads(short_branch):
    b = short_branch
    assert b.stopped_by == "P_max"
    P = np.array(b.P)
    assert np.all(np.diff(P) > 0)  # supercritical: the load grows along the branch
    assert np.all(P > b.P_flu)
    landed = [P[k] for k in b.landed]
    # Landing is exact: the load condition is linear, so Newton meets it to rounding.
    assert landed == pytest.approx([2.952, 2.955], rel=1e-12, abs=0)
    assert P[-1] == pytest.approx(2.955, rel=1e-12)


@pytest.mark.slow
def test_short_branch_cycles_are_stable_and_grow(short_branch):
    b = short_branch
    mu = np.array(b.max_floquet_modulus)
    assert np.all(mu < 1.0)
    assert np.all(1.0 - mu > 1e-6)  # near the onset 1 - mu ~ 1e-5, not a rounding artefact
    assert np.all(np.diff(b.A) > 0)  # near the onset the amplitude grows with the load
    # The tip rotation comes from the same variational solve's orbit: positive, and of the
    # size the 2-element branch of the exploratory run gave (0.0448 rad at A = 1 cm).
    assert b.tip_rotation_amplitude[0] == pytest.approx(0.0448, rel=2e-2)
    assert all(r > 0 for r in b.tip_rotation_amplitude)


def test_load_stop_must_lie_above_the_flutter_load():
    with pytest.raises(ParameterError, match="P_max must exceed the flutter load"):
        cycle_branch(ROD119, n_elements=2, P_max=2.0)


def test_unknown_parametrisation_is_refused():
    from flutterfriction.analysis.rod_cycles import CycleContinuation

    cont = CycleContinuation(ROD119, n_elements=2)
    with pytest.raises(ParameterError, match="parametrisation"):
        cont.advance("natural")


def test_scene_refuses_unknown_parameters():
    from flutterfriction.scenes.beck_branch import beck_branch

    with pytest.raises(ParameterError, match="unknown scene parameter"):
        beck_branch({"rod": {"length": 0.35, "B": 0.0332, "rho": 0.0546, "D": 7.078e-6},
                     "P_maximum": 7.0})


def test_plot_draws_stability_and_the_chapter_cycle():
    from flutterfriction.plotting.beck_branch import plot_beck_branch

    P = np.linspace(2.97, 7.0, 9)
    data = {"P_N": P.tolist(), "tip_amplitude_m": (0.1 * np.sqrt(P - 2.96)).tolist(),
            "period_s": np.linspace(0.18, 0.136, 9).tolist(),
            "max_floquet_modulus": [0.99] * 8 + [1.01], "P_flu_model": 2.9645,
            "cycle_index": 4, "n_elements": 4}
    fig = plot_beck_branch(data)
    labels = [t.get_text() for ax in fig.axes for t in ax.get_legend().get_texts()]
    assert any("unstable" in s for s in labels) and any("Figs. 15" in s for s in labels)
    assert all(ax.get_xlabel() and ax.get_ylabel() for ax in fig.axes)


@pytest.mark.parametrize(("over", "match"), [
    ({"check_loads": [1.0]}, r"^check_loads: 1 N is outside the branch \(2\.94"),
    ({"P_max": 1.0}, r"^P_max = 1.0 N must be above the damped flutter load 2\.94"),
])
def test_loads_off_the_branch_are_refused_before_it_is_computed(over, match):
    """Outside audit: check_loads = [1.0] was refused only after the whole branch had been
    computed. Both are now refused after the linear flutter load alone (~0.1 s)."""
    from flutterfriction.config import load_config, scene_params
    from flutterfriction.scenes.beck_branch import beck_branch

    cfg = load_config(ROOT / "workflow" / "config.yaml")
    cfg["fidelity"] = "quick"
    with pytest.raises(ParameterError, match=match):
        beck_branch({**scene_params(cfg, "beck_branch"), **over})


def test_growth_rates_match_the_fe_twin_spectrum():
    """The growth-rate table the notebook shows (exact eq. 118) against the first-order FE
    spectrum on 24 elements, an independent route: measured agreement 6e-5 relative at 5.5 N
    (the FE twin's error grows with the load), <1e-5 near the onset; asserted 1e-3."""
    from flutterfriction.analysis.rod_exact import fe_eigenvalues
    from flutterfriction.scenes.beck_branch import GROWTH_RATE_FACTORS, growth_rates

    rod = ROD119
    rows = growth_rates(rod, 5.5)
    assert [r["load_ratio"] for r in rows[:-1]] == list(GROWTH_RATE_FACTORS)
    assert rows[-1]["P_N"] == pytest.approx(5.5, rel=1e-12)
    for r in rows:
        w = fe_eigenvalues(rod.groups(), r["P_N"] / rod.load_unit, 24) / rod.time_scale
        s = w[np.argmax(w.real)]
        assert s.real == pytest.approx(r["growth_rate"], rel=1e-3)
        assert abs(s.imag) == pytest.approx(r["frequency"], rel=1e-3)
    # above the damped flutter load the mode grows, faster with the load
    assert 0 < rows[0]["growth_rate"] < rows[1]["growth_rate"] < rows[-1]["growth_rate"]


def test_a_cycle_carried_to_the_same_mesh_is_the_same_cycle():
    """``cycle_on_finer_mesh`` (LSODA by odeint, the tip's rotation from its samples) given
    the mesh the cycle was found on, and a period 1e-4 off, returns that cycle after Newton
    steps: the same period and lateral tip amplitude, and the tip rotation of DOP853's dense
    orbit (an independent integrator and interpolant), to the integrators' tolerances (the
    finer meshes: the workflow's mesh checks, against their references). At A = 10 cm, where
    1 - mu = 3e-3 (near the onset, 1 - mu ~ 1e-5 amplifies the coarse cycle's residual into a
    3e-4 change of amplitude, measured, in any solver)."""
    from flutterfriction.analysis.rod_cycles import (
        cycle_on_finer_mesh,
        tip_rotation_amplitude,
        variational_flow,
    )
    from flutterfriction.models.rod_nonlinear import NonlinearRod

    b = cycle_branch(ROD119, n_elements=2, A_first=0.1, rtol=1e-10, max_points=2,
                     newton_tol=1e-7)
    coarse = NonlinearRod(ROD119, 2)
    y, T, P = np.asarray(b.states[0])[:-2], b.T[0], b.P[0]
    same = cycle_on_finer_mesh(coarse, y, T * (1 + 1e-4), P, NonlinearRod(ROD119, 2))
    assert same.newton_iterations > 1
    assert same.T == pytest.approx(T, rel=1e-7)
    assert same.A == pytest.approx(b.A[0], rel=1e-6)
    dense = variational_flow(coarse, y, T, P, rtol=1e-10, dense_output=True).orbit
    assert same.tip_rotation_amplitude == pytest.approx(
        tip_rotation_amplitude(coarse, dense, T), rel=1e-6)
    # a tolerance outside the integrators' range is refused before any work, by name
    with pytest.raises(ParameterError, match="rtol must be in"):
        cycle_on_finer_mesh(coarse, y, T, P, NonlinearRod(ROD119, 2), rtol=1e-17)
