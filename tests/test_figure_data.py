"""The data the figures of issue 13 draw beyond the checked quantities: Fig. 12 at the caption's
tan(alpha) = 1 beside the fitted value, Fig. 4's dense exact solution; and that the figures
draw from it."""

from __future__ import annotations

import numpy as np
import pytest

from flutterfriction.parameters import LIST_47, LIST_119


@pytest.fixture(scope="module")
def fig12_data():
    from flutterfriction.scenes.rod import fig12

    return fig12({"rod": dict(LIST_119), "tan_alpha": 1.5608, "p_max": 35.0, "n_modes": 2,
                  "fe_elements": 8, "n_points": 41})


def test_fig12_keeps_the_fitted_case_and_adds_the_stated_one(fig12_data):
    d = fig12_data
    # The keys workflow/reference.yaml reads stay where they were (the fitted tan alpha).
    assert d["cases"]["undamped"]["critical"]["p_flu"] == pytest.approx(16.51, abs=0.005)
    assert d["cases"]["damped"]["critical"]["p_div"] == pytest.approx(30.52, abs=0.005)
    assert {"undamped_p_flu", "undamped_p_div", "damped_p_flu", "damped_p_div"} <= set(
        d["quantities"])
    st = d["stated"]
    assert st["tan_alpha"] == 1.0
    crit = {k: st["cases"][k]["critical"] for k in ("undamped", "damped")}
    # The figure as printed (tan alpha = 1): 16.21 / 34.46, damped 7.91 / 34.86.
    assert round(crit["undamped"]["p_flu"], 2) == 16.21
    assert round(crit["undamped"]["p_div"], 2) == 34.46
    assert round(crit["damped"]["p_flu"], 2) == 7.91
    assert round(crit["damped"]["p_div"], 2) == 34.86
    # Its load range reaches past both of its divergence loads.
    assert st["p"][-1] > max(crit["undamped"]["p_div"], crit["damped"]["p_div"])
    assert np.array(st["cases"]["damped"]["re"]).shape == (4, len(st["p"]))


def test_fig12_draws_both_cases(fig12_data):
    import matplotlib.pyplot as plt

    from flutterfriction.plotting.rod import plot_fig12

    fig = plot_fig12(fig12_data)
    text = fig._suptitle.get_text()
    assert "16.21 / 34.46" in text and "16.51 / 30.22" in text
    assert len(fig.axes) >= 8
    plt.close(fig)


def test_fig04_dense_solution_passes_through_the_frames():
    from flutterfriction.scenes.ziegler import fig04

    d = fig04({"pendulum": dict(LIST_47), "dt": 0.04,
               "cases": {"flutter": {"P": 6.8, "duration": 0.44, "alpha0_deg": 0.5}}})
    c = d["cases"]["flutter"]
    t, a = np.array(c["t_dense"]), np.array(c["alpha_dense"])
    idx = [int(np.argmin(np.abs(t - ti))) for ti in c["times"]]
    np.testing.assert_allclose(a[idx], np.array(c["alpha"]), rtol=1e-9, atol=1e-12)


def test_branch_panels_draw_a_rod_without_flutter():
    """A user's own rod may have no flutter load (or none in the drawn range): the regime
    shading and the inset crashed on p_flu = None (a review)."""
    import matplotlib.pyplot as plt
    import numpy as np

    from flutterfriction.plotting.rod import _draw_branch_case

    p = np.linspace(0.0, 10.0, 11)
    roots = np.array([[-2.0], [-1.0], [1.0], [2.0]]) * np.ones((1, p.size))
    for crit in ({"p_flu": None, "p_div": None}, {"p_flu": None, "p_div": 5.0},
                 {"p_flu": 40.0, "p_div": None}):
        fig, (a, b) = plt.subplots(2)
        case = {"critical": crit, "re": np.zeros_like(roots).tolist(), "im": roots.tolist()}
        _draw_branch_case(a, b, p, case, "damped", zoom=True)
        shaded = [patch for patch in a.patches]
        assert len(shaded) == 1 + (crit["p_div"] is not None)
        plt.close(fig)


def test_a_researchers_own_parameters_are_named_wrapped_and_with_units():
    """An outside review: one changed spring put all of a pendulum's values on Fig. 4's title
    line (the figure 1585 px wide, 51 text-size offences: the run failed), rods' values had no
    units, and Fig. 5, eqs. (25), (46), (48) and the paradox map kept the chapter's special
    case in their titles for another pendulum."""
    from flutterfriction.plotting import OWN_VALUES_WIDTH, chapter_list, pendulum_case

    rod = {"length": 0.5, "B": 0.05, "rho": 0.08, "D": 2e-5}
    text = chapter_list({"params": {"rod": rod}}, "rod", "list119", "list (119)")
    assert text.startswith("your own rod (length = 0.5 m, B = 0.05 N m^2, rho = 0.08 kg/m,")
    assert "D = 2e-05 N m^2 s" in text
    assert all(len(line) <= OWN_VALUES_WIDTH + len("your own rod (") for line in
               text.splitlines())
    symmetric = {"l1": 1.0, "l2": 1.0, "d": 1.0, "h": 0.0, "m1": 1.0, "m2": 1.0, "m3": 0.0,
                 "k1": 1.0, "k2": 1.0}
    mine = dict(symmetric, l1=0.15, d=0.1)
    assert pendulum_case({"params": {"pendulum": symmetric}}, lambda g: g.symmetric,
                         "eq. 46") == "eq. 46"
    assert pendulum_case({"params": {"pendulum": mine}}, lambda g: g.symmetric,
                         "eq. 46").startswith("your own pendulum (l1 = 0.15 m, l2 = 1 m")


def test_fig05_draws_the_vanishing_viscosity_limit_where_it_can_be_seen():
    """The eps -> 0 line (4/3) lay < 1 px from eps = 0.1's flutter line (1.338) in the upper
    panels and could not be seen (an outside review): it is drawn in the zoom only, and the
    legend above the panels names it."""
    import copy

    import matplotlib.pyplot as plt
    from conftest import ROOT

    from flutterfriction.config import load_config, scene_params
    from flutterfriction.plotting.ziegler_damped import plot_fig05
    from flutterfriction.registry import build_scene

    config = copy.deepcopy(load_config(ROOT / "workflow" / "config.yaml")) | {"fidelity": "quick"}
    data = build_scene("fig05", scene_params(config, "fig05"))
    fig = plot_fig05(data)
    limit = data["gamma_flu_limit"]

    def at_limit(ax):
        return [ln for ln in ax.get_lines() if len(ln.get_xdata()) == 2
                and np.allclose(ln.get_xdata(), limit)]

    ax_re, ax_im, ax_z = fig.axes[:3]
    assert not at_limit(ax_re) and not at_limit(ax_im)
    assert len(at_limit(ax_z)) == 1
    assert any("the Ziegler paradox" in t.get_text() for t in ax_re.get_legend().get_texts())
    plt.close(fig)


def test_the_stability_map_shows_the_whole_searched_load_range():
    """The divergence window's end left the axes where it passed p = 65 (cut there before): the
    map is drawn to the searched p = 80, its x scale stated."""
    import matplotlib.pyplot as plt

    from flutterfriction.plotting.rod import plot_stability_map

    r = [0.0, 0.5, 0.7, 1.0, 2.0]
    data = {"mass_ratio": r,
            "undamped": {"p_flu": [20.05, 16.06, 16.08, 16.21, 16.7],
                         "p_div": [None, None, 40.0, 34.46, 28.6],
                         "p_div_end": [None, None, 70.0, None, None]},
            "vanishing_damping": {"p_flu": [10.94, 8.5, 8.2, 7.9, 7.7],
                                  "p_div": [None, None, 40.0, 34.46, 28.6]}}
    fig = plot_stability_map(data)
    ax = fig.axes[0]
    assert ax.get_ylim() == (0.0, 80.0)
    assert "linear scale below" in ax.get_xlabel()
    plt.close(fig)
