"""Figures of chapter §2.1–2.3: Fig. 2 (schematic), Fig. 3 (eq. 34), Fig. 4 (motions) and the
load–frequency diagrams of the critical-load scenes (eqs. 25, 46–48)."""

from __future__ import annotations

from typing import Any

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.figure import Figure
from matplotlib.patches import Arc

from flutterfriction.plotting import REGIME_COLOURS
from flutterfriction.plotting.pendulum import draw_pendulum


def _shade_regimes(ax, edges: list[float], names: list[str], x_max: float) -> None:
    bounds = [0.0, *edges, x_max]
    for lo, hi, name in zip(bounds[:-1], bounds[1:], names, strict=True):
        ax.axvspan(lo, hi, color=REGIME_COLOURS[name], alpha=0.8, lw=0, zorder=0)


def _q(data: dict[str, Any], key: str) -> float:
    return data["quantities"][key]["value"]


def plot_dead_load_spectrum(data: dict[str, Any], title: str) -> Figure:
    """omega^2 against eta = H l1/k2 with H_cr and H_sup (eqs. 19, 22, 25)."""
    c = data["curve"]
    eta = np.array(c["eta"])
    re = np.array(c["omega2_re"])
    closed = np.array(c["omega2_closed_form"])
    e_cr, e_sup = _q(data, "eta_cr"), _q(data, "eta_sup")
    fig, ax = plt.subplots(figsize=(5.2, 3.4))
    _shade_regimes(ax, [e_cr, e_sup], ["stable", "divergence", "divergence"], eta[-1])
    for i, branch in enumerate(re):
        ax.plot(eta, branch, color="C0", lw=1.6,
                label="eigenvalues of (K+G, M)" if i == 0 else None)
    step = max(1, len(eta) // 25)
    for i, branch in enumerate(closed):
        ax.plot(eta[::step], branch[::step], "o", ms=3, mfc="none", color="C1",
                label="closed form, eq. (19)" if i == 0 else None)
    ax.axhline(0, color="k", lw=0.8)
    for val, name in ((e_cr, r"$\eta_{cr}$"), (e_sup, r"$\eta_{sup}$")):
        ax.axvline(val, color="k", ls="--", lw=0.8)
        ax.annotate(f"{name} = {val:.4f}", (val, ax.get_ylim()[1]), rotation=90, va="top",
                    ha="right", fontsize=8)
    ax.set_xlim(eta[0], eta[-1])
    ax.set_xlabel(r"dead load $\eta = H l_1/k_2$")
    ax.set_ylabel(r"$\omega^2 = m_2 l_2^2\,\Omega^2/k_2$")
    ax.set_title(title)
    ax.legend(loc="lower left")
    return fig


def plot_follower_spectrum(data: dict[str, Any], title: str, in_newtons: bool = False) -> Figure:
    """Re and Im of omega^2 against the follower load, regimes shaded (eqs. 34, 39, 41)."""
    c = data["curve"]
    gamma = np.array(c["gamma"])
    unit = data["load_unit_N"] if in_newtons else 1.0
    x = gamma * unit
    g_flu, g_div = _q(data, "gamma_flu"), _q(data, "gamma_div")
    fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(5.2, 4.6), sharex=True,
                                   gridspec_kw={"height_ratios": [3, 2]})
    step = max(1, len(gamma) // 30)
    for ax, key, label in ((ax1, "re", r"Re $\omega^2$"), (ax2, "im", r"Im $\omega^2$")):
        _shade_regimes(ax, [g_flu * unit, g_div * unit], ["stable", "flutter", "divergence"],
                       x[-1])
        for i, branch in enumerate(np.array(c[f"omega2_{key}"])):
            ax.plot(x, branch, color="C0", lw=1.6,
                    label="eigenvalues of (K+G, M)" if i == 0 else None)
        for i, branch in enumerate(np.array(c[f"omega2_closed_form_{key}"])):
            ax.plot(x[::step], branch[::step], "o", ms=3, mfc="none", color="C1",
                    label="closed form, eq. (34)" if i == 0 else None)
        ax.axhline(0, color="k", lw=0.8)
        for val in (g_flu, g_div):
            ax.axvline(val * unit, color="k", ls="--", lw=0.8)
        ax.set_ylabel(label)
    fmt = ("{:.3f} N" if in_newtons else "{:.4f} K/L")
    ax1.annotate(r"$P_{flu}$ = " + fmt.format(g_flu * unit), (g_flu * unit, ax1.get_ylim()[1]),
                 rotation=90, va="top", ha="right", fontsize=8)
    ax1.annotate(r"$P_{div}$ = " + fmt.format(g_div * unit), (g_div * unit, ax1.get_ylim()[1]),
                 rotation=90, va="top", ha="right", fontsize=8)
    for name, xpos in (("stable", g_flu / 2), ("flutter", (g_flu + g_div) / 2),
                       ("divergence", (g_div + gamma[-1]) / 2)):
        ax2.annotate(name, (xpos * unit, 0.04), xycoords=("data", "axes fraction"),
                     ha="center", fontsize=8)
    ax1.legend(loc="lower left")
    ax1.set_title(title)
    ax2.set_xlim(x[0], x[-1])
    ax2.set_xlabel(r"follower load $P$ [N]" if in_newtons
                   else r"follower load $\gamma = P l_1/k_2$")
    return fig


def plot_fig03(data: dict[str, Any]) -> Figure:
    """Fig. 3: the line beta1 - gamma beta2 and the parabola (beta1 - gamma beta2)^2 - 4ka."""
    c = data["curve"]
    gamma = np.array(c["gamma"])
    line, parab = np.array(c["line"]), np.array(c["parabola"])
    g_flu, g_div = _q(data, "gamma_flu"), _q(data, "gamma_div")
    vertex = _q(data, "gamma_vertex")
    fig, ax = plt.subplots(figsize=(5.4, 3.8))
    _shade_regimes(ax, [g_flu, g_div], ["stable", "flutter", "divergence"], gamma[-1])
    ax.plot(gamma, line, color="C0", lw=1.8, label=r"$\beta_1 - \gamma\beta_2$")
    ax.plot(gamma, parab, color="C3", lw=1.8, label=r"$(\beta_1 - \gamma\beta_2)^2 - 4ka$")
    ax.axhline(0, color="k", lw=0.8)
    for val, name in ((g_flu, r"$\gamma_{flu}$"), (vertex, r"$\beta_1/\beta_2$"),
                      (g_div, r"$\gamma_{div}$")):
        ax.axvline(val, color="k", ls="--" if val != vertex else ":", lw=0.8)
        ax.annotate(f"{name} = {val:.3f}", (val, 0.98), xycoords=("data", "axes fraction"),
                    rotation=90, va="top", ha="right", fontsize=8)
    ymin = min(line.min(), parab.min())
    ax.set_ylim(1.15 * ymin, 1.2 * line.max())
    for name, xpos in (("stable", g_flu / 2), ("flutter", (g_flu + g_div) / 2),
                       ("divergence", (g_div + gamma[-1]) / 2)):
        ax.annotate(name, (xpos, 0.03), xycoords=("data", "axes fraction"), ha="center",
                    fontsize=8)
    ax.set_xlim(gamma[0], gamma[-1])
    ax.set_xlabel(r"$\gamma = P l_1/k_2$")
    ax.set_ylabel("dimensionless")
    unit = data["load_unit_N"]
    top = ax.secondary_xaxis("top", functions=(lambda g: g * unit, lambda P: P / unit))
    top.set_xlabel("P [N]")
    ax.legend(loc="lower left", bbox_to_anchor=(0.0, 0.1))
    co = data["coefficients"]
    ax.set_title(rf"Eq. (34) for list (47): $a$ = {co['a']:.4f}, $\beta_1$ = {co['beta1']:.4f}, "
                 rf"$\beta_2$ = {co['beta2']:.4f}", pad=28)
    return fig


def _upright(xy: np.ndarray) -> np.ndarray:
    """Model (e1 along the undeformed pendulum) to drawing coordinates with e1 pointing up."""
    xy = np.asarray(xy, dtype=float)
    return np.stack([-xy[..., 1], xy[..., 0]], axis=-1)


def plot_fig04(data: dict[str, Any]) -> Figure:
    """Fig. 4: configurations of the linear motion every dt, flutter (top), divergence (bottom).

    The pendulum is drawn upright (e1 pointing up, the load pushing down); angles are the
    linear solution's, drawn with the exact rigid-rod kinematics of eq. (1).
    """
    cases = data["cases"]
    n_max = max(len(c["times"]) for c in cases.values())
    extents = []
    for case in cases.values():
        xy = _upright(np.concatenate([np.array(v) for v in case["points"].values()]))
        extents.append((xy[:, 1].min(), xy[:, 1].max()))
    L = float(np.linalg.norm(np.array(next(iter(cases.values()))["points"]["C"][0])))
    heights = [hi - lo + 0.75 * L for lo, hi in extents]
    spacing = 0.9 * L
    width_in = 0.62 * n_max
    scale_in = width_in / (n_max * spacing)
    fig, axes = plt.subplots(len(cases), 1, figsize=(width_in, scale_in * sum(heights) + 0.8),
                             gridspec_kw={"height_ratios": heights})
    axes = np.atleast_1d(axes)
    for ax, (name, case), (lo, hi) in zip(axes, cases.items(), extents, strict=True):
        pts = {k: np.array(v) for k, v in case["points"].items()}
        for i, t in enumerate(case["times"]):
            frame = {k: v[i] for k, v in pts.items()}
            draw_pendulum(ax, frame, data["masses"], scale=0.55 * L, springs=False,
                          offset=(i * spacing, 0.0), transform=_upright)
            a1, a2 = np.degrees(case["alpha"][i])
            ax.annotate(f"{t:.2f} s", (i * spacing, hi + 0.12 * L), ha="center", fontsize=7)
            ax.annotate(f"{a1:+.1f}°\n{a2:+.1f}°", (i * spacing, lo - 0.3 * L), ha="center",
                        va="center", fontsize=6, color="0.35")
        ax.set_aspect("equal")
        ax.set_xlim(-0.5 * spacing, (n_max - 0.5) * spacing)
        ax.set_ylim(lo - 0.5 * L, hi + 0.25 * L)
        ax.set_axis_off()
        ax.set_title(f"{name}: P = {case['P']:g} N, a configuration every "
                     f"{case['times'][1] - case['times'][0]:.2f} s "
                     r"(below: $\alpha_1$, $\alpha_2$)", fontsize=8, loc="left")
    fig.suptitle("Linear eq. (11) solved exactly (matrix exponential), list (47)", fontsize=8,
                 y=1.0)
    return fig


def plot_fig02(data: dict[str, Any]) -> Figure:
    """Fig. 2: the Ziegler double pendulum with its springs, masses and the loads P and H."""
    pts = {k: np.array(v) for k, v in data["points"].items()}
    L = float(np.linalg.norm(pts["B"] - pts["A"]))
    fig, ax = plt.subplots(figsize=(5.6, 3.8))
    # The undeformed axis, and the rotations alpha1, alpha2 measured from e1.
    ax.plot([0, 2.25 * L], [0, 0], color="0.6", lw=0.8, ls="--")
    ax.plot([pts["B"][0], pts["B"][0] + 0.6 * L], [pts["B"][1]] * 2, color="0.6", lw=0.8,
            ls="--")
    for centre, angle, name in ((pts["A"], data["alpha1"], r"$\alpha_1$"),
                                (pts["B"], data["alpha2"], r"$\alpha_2$")):
        ax.add_patch(Arc(centre, 0.56 * L, 0.56 * L, theta1=0, theta2=np.degrees(angle), lw=0.8))
        mid = angle / 2
        ax.annotate(name, centre + 0.36 * L * np.array([np.cos(mid), np.sin(mid)]),
                    ha="center", va="center")
    draw_pendulum(ax, pts, data["masses"], scale=L, loads={"P": 0.45 * L, "H": 0.45 * L},
                  labels=True)
    for name, p, dxy in (("$k_1$", pts["A"], (0.14, -0.13)), ("$k_2$", pts["B"], (0.05, -0.16)),
                         ("$m_1$", pts["D"], (0.05, -0.17)), ("$m_2$", pts["C"], (0.13, -0.1)),
                         ("$m_3$", pts["E"], (0.15, -0.05))):
        ax.annotate(name, p + L * np.array(dxy), ha="center", va="center", color="0.2")
    o = np.array([1.6 * L, -0.4 * L])
    ax.annotate("", o + [0.3 * L, 0], o, arrowprops={"arrowstyle": "-|>", "lw": 0.8})
    ax.annotate("", o + [0, 0.3 * L], o, arrowprops={"arrowstyle": "-|>", "lw": 0.8})
    ax.annotate(r"$\mathbf{e}_1$", o + [0.33 * L, 0], va="center")
    ax.annotate(r"$\mathbf{e}_2$", o + [0, 0.33 * L], ha="center")
    ax.set_aspect("equal")
    top = max(p[1] for p in pts.values())
    ax.set_xlim(-0.35 * L, 2.45 * L)
    ax.set_ylim(-0.5 * L, top + 0.45 * L)
    ax.set_axis_off()
    ax.set_title("The Ziegler double pendulum (follower load P parallel to BC, dead load H "
                 "parallel to $\\mathbf{e}_1$)", fontsize=8)
    return fig


def plot_eq25(data: dict[str, Any]) -> Figure:
    return plot_dead_load_spectrum(
        data, r"Eq. (25): dead load on equal rods, $H_{cr}$ = (3-$\sqrt{5}$)/2 K/L")


def plot_eq46(data: dict[str, Any]) -> Figure:
    return plot_follower_spectrum(
        data, r"Eq. (46): $l_1=l_2=L$, $d=L$, $k_1=k_2=K$, $m_1=m_2$, $m_3=0$")


def plot_eq47(data: dict[str, Any]) -> Figure:
    return plot_follower_spectrum(data, "List (47): the device of §2.10", in_newtons=True)


def plot_eq48(data: dict[str, Any]) -> Figure:
    return plot_follower_spectrum(data, r"Eq. (48): as eq. (46) but $d = L/2$ ($y_1 = 1/2$)")
