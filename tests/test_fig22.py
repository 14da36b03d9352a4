"""Fig. 22's three panels from one computed path: the slip onset at |p_T| = mu p_N, the residual
displacement after unloading equal to the slip, bad paths refused, and the figure draws."""

from __future__ import annotations

import numpy as np
import pytest

from flutterfriction.errors import ParameterError
from flutterfriction.scenes.solids import fig22

PATH = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.5], [1.5, 2.5], [1.5, 1.5], [1.2, -1.5]]


@pytest.fixture(scope="module")
def data():
    return fig22({"k_N": 2.0, "k_T": 1.0, "mu": 0.5, "path": PATH})


def test_slip_starts_at_mu_N_and_the_unloaded_spring_leaves_the_slip(data):
    q = data["quantities"]
    # by hand: mu k_N u_N = 0.5 * 2 * 1 = 1 N; slip 0.5 m + 0.5 m = 1 m
    assert q["slip_onset_force"]["value"] == pytest.approx(1.0, rel=1e-14)
    assert q["slip_onset_force"]["independent"] == pytest.approx(1.0, rel=1e-14)
    assert q["residual_displacement"]["value"] == pytest.approx(1.0, rel=1e-14)
    assert q["residual_displacement"]["independent"] == pytest.approx(1.0, rel=1e-14)
    i = data["onset_index"]
    assert data["branch"][i] == "stick" and data["branch"][i + 1] == "slip"
    assert data["slip"][i] == 0.0 and data["slip"][i + 1] == pytest.approx(0.5, rel=1e-14)
    res = data["residual"]
    assert data["branch"][res["piece"]] == "stick"
    # on the stick piece the tangential spring carries p_T = k_T (u_T - u_T^s): zero there
    assert data["k_T"] * (res["u_T"] - res["slip"]) == pytest.approx(0.0, abs=1e-14)


def test_the_residual_displacement_counts_from_the_paths_start():
    shifted = [[u_N, u_T + 0.3] for u_N, u_T in PATH]
    d = fig22({"k_N": 2.0, "k_T": 1.0, "mu": 0.5, "path": shifted})
    q = d["quantities"]["residual_displacement"]
    assert q["value"] == pytest.approx(q["independent"], rel=1e-13)
    assert d["residual"]["u_T"] == pytest.approx(1.3, rel=1e-13)


def test_the_onset_scales_with_the_normal_force():
    d = fig22({"k_N": 4.0, "k_T": 1.0, "mu": 0.3,
               "path": [[0, 0], [2.0, 0], [2.0, 5.0], [2.0, -1.0]]})
    q = d["quantities"]["slip_onset_force"]
    assert q["value"] == pytest.approx(0.3 * 4.0 * 2.0, rel=1e-14)
    assert q["value"] == pytest.approx(q["independent"], rel=1e-14)


@pytest.mark.parametrize("path, match", [
    ([[0, 0], [1, 0], [1, 0.2]], "never reaches"),          # stays inside the cone
    ([[0, 0], [1, 0], [1, 2.0]], "unload"),                  # slips but never unloads
    ([[0, 0], [1, 0], [-1, 0]], "p_N < 0"),                  # separates
    ([[0, 0], [1, 0], [1, 1], [-1, 0]], "p_N < 0"),         # separates while slipping
])
def test_paths_without_stick_slip_and_unloading_are_refused(path, match):
    with pytest.raises(ParameterError, match=match):
        fig22({"k_N": 2.0, "k_T": 1.0, "mu": 0.5, "path": path})


def test_bad_contact_parameters_are_refused():
    with pytest.raises(ParameterError, match="mu"):
        fig22({"k_N": 2.0, "k_T": 1.0, "mu": 0.0, "path": PATH})
    with pytest.raises(ParameterError, match="k_T"):
        fig22({"k_N": 2.0, "k_T": -1.0, "mu": 0.5, "path": PATH})


def test_fig22_draws_its_three_panels(data):
    import matplotlib.pyplot as plt

    from flutterfriction.plotting.solids import plot_fig22

    fig = plot_fig22(data)
    titles = [ax.get_title() for ax in fig.axes]
    assert any(t.startswith("(left)") for t in titles)
    assert any(t.startswith("(centre)") for t in titles)
    assert any(t.startswith("(right)") for t in titles)
    for ax in fig.axes:
        if ax.axison:
            assert "[" in ax.get_xlabel() and "[" in ax.get_ylabel()
    # the response panel draws the computed path itself
    resp = next(ax for ax in fig.axes if ax.get_xlabel().startswith("tangential displacement"))
    xs = np.concatenate([ln.get_xdata() for ln in resp.get_lines()
                         if ln.get_linestyle() == "-" and len(ln.get_xdata()) == 2])
    assert set(np.round(xs, 12)) <= {round(u[1], 12) for u in data["u"]}
    plt.close(fig)


def test_the_point_numbers_sit_clear_of_the_path(data):
    """Each point's number is drawn off the path's segments at that point (a review saw 6 on a
    segment of the response panel): no computed segment passes through a number's box."""
    import matplotlib.pyplot as plt

    from flutterfriction.plotting.solids import plot_fig22

    fig = plot_fig22(data)
    fig.canvas.draw()
    checked = 0
    for ax in fig.axes:
        numbers = [t for t in ax.texts if t.get_text().replace(", ", "").isdigit()]
        segments = [ln.get_xydata() for ln in ax.get_lines()
                    if ln.get_linestyle() == "-" and len(ln.get_xdata()) >= 2]
        for t in numbers:
            box = t.get_window_extent().padded(-0.5)
            for xy in segments:
                for a, b in zip(xy[:-1], xy[1:], strict=True):
                    s = np.linspace(0.0, 1.0, 200)[:, None]
                    pts = ax.transData.transform(a + s * (b - a))
                    inside = ((pts[:, 0] > box.x0) & (pts[:, 0] < box.x1)
                              & (pts[:, 1] > box.y0) & (pts[:, 1] < box.y1))
                    assert not inside.any(), (ax.get_title(), t.get_text())
            checked += 1
    assert checked >= 14  # both path panels: every distinct point of the path
    plt.close(fig)


@pytest.mark.parametrize(("k_N", "k_T", "u_T"), [(1e6, 1e-6, 1e-7), (1.0, 1.0, 1e-13)])
def test_a_return_to_the_apex_keeps_the_slip_it_drags(k_N, k_T, u_T):
    """An outside audit: unloading p_N to 0 with a small p_T = k_T u_T held, the cone shrinks
    to its apex and drags p_T to 0, which is slip u_T (u_T = p_T/k_T + slip, eq. 133). The
    cone reached p_T at t = 1 - 1e-19 of the segment, rounded to its end, and the snap onto
    the cone dropped p_T: slip 0 (k_N/k_T = 1e12), or 3e-4 off (k_N = k_T)."""
    from flutterfriction.models.contact import CoulombContact, integrate_path

    path = integrate_path(CoulombContact(k_N, k_T, 1.0), [(0, 0), (1, 0), (1, u_T), (0, u_T)])
    assert np.all(path.p[-1] == 0.0)
    assert path.slip[-1] == pytest.approx(u_T, rel=1e-12)
    assert path.u[:, 1] == pytest.approx(path.p[:, 1] / k_T + path.slip, rel=1e-12, abs=0)
