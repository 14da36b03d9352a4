"""Figures of §2.9–2.11 for the Ziegler pendulum: Figs. 13, 14, 20, 21."""

from __future__ import annotations

from typing import Any

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.collections import LineCollection
from matplotlib.figure import Figure

from flutterfriction.plotting import (
    list47_viscous,
    own_parameters_note,
    pendulum_text,
    wrap_items,
)


def time_coloured(ax, x, y, t, lw=0.8):
    pts = np.array([x, y]).T.reshape(-1, 1, 2)
    lc = LineCollection(np.concatenate([pts[:-1], pts[1:]], axis=1), cmap="viridis", lw=lw)
    lc.set_array(np.asarray(t)[:-1])
    ax.add_collection(lc)
    ax.autoscale()
    return lc


#: The transient ends when the peaks of alpha1 first come within this fraction of the cycle's
#: amplitude (the limit cycle's, from the data).
TRANSIENT_TOL = 0.01


def _transient_end(t: np.ndarray, a1: np.ndarray, amplitude: float) -> int:
    """Index of the first peak of alpha1 within ``TRANSIENT_TOL`` of the cycle's amplitude."""
    peaks = np.flatnonzero((a1[1:-1] > a1[:-2]) & (a1[1:-1] >= a1[2:])) + 1
    close = peaks[a1[peaks] >= (1.0 - TRANSIENT_TOL) * amplitude]
    return int(close[0]) if close.size else len(t) - 1


def _transient_and_cycle(ax, x, y, t, k: int, t_end: float, cycle_label: bool):
    """The transient (t < t_end) coloured by time, the motion on the cycle after it in black."""
    norm = plt.Normalize(0.0, t_end)
    pts = np.array([x[: k + 1], y[: k + 1]]).T.reshape(-1, 1, 2)
    lc = LineCollection(np.concatenate([pts[:-1], pts[1:]], axis=1), cmap="viridis", lw=0.8,
                        norm=norm)
    lc.set_array(np.asarray(t)[:k])
    ax.add_collection(lc)
    ax.plot(x[k:], y[k:], color="k", lw=1.3,
            label=(f"limit cycle, t ≥ {t_end:.1f} s (to {t[-1]:.0f} s)" if cycle_label
                   else None))
    ax.autoscale()
    return lc


def _section29_text(data: dict[str, Any]) -> str:
    """The pendulum and the start of Figs. 13-14 (the §2.9 list and imperfection)."""
    params = data.get("params", {})
    # on lines of ~70 characters, so that the title can be read at 8 points in a figure
    # 4.8 in wide (one 120-character line needed 6 points: a figure review)
    text = wrap_items(pendulum_text(params.get("pendulum")), 70)
    if "alpha0_deg" in params:
        text += f";\nfrom rest at α1 = α2 = {params['alpha0_deg']:g}°"
    return text


def _load_text(data: dict[str, Any]) -> str:
    """The load as a multiple of P*_flu, and where P*_flu comes from."""
    star = data["P_star_flu"]
    source = ("eq. 54" if data.get("P_star_is_eq54", True)
              else "the exact damped flutter load; eq. 54 is the symmetric pendulum's")
    return f"P = {data['P']:.4g} N = {data['P'] / star:.3g} $P^*_{{flu}}$ ({source})"


def plot_fig13(data: dict[str, Any]) -> Figure:
    """Fig. 13: trajectory in the alpha1-alpha2 plane reaching a stable limit cycle."""
    a1, a2 = np.degrees(data["alpha"])
    t = np.array(data["t"])
    k = _transient_end(t, a1, np.degrees(data["limit_cycle"]["alpha1_amplitude_rad"]))
    fig, ax = plt.subplots(figsize=(4.8, 4.6), layout="constrained")
    lc = _transient_and_cycle(ax, a1, a2, t, k, t[k], True)
    fig.colorbar(lc, ax=ax, label=f"time t [s] along the transient (to {t[k]:.1f} s)")
    T = data["limit_cycle"]["period_s"]
    ax.set_xlabel(r"$\alpha_1$ [deg]")
    ax.set_ylabel(r"$\alpha_2$ [deg]")
    ax.legend(loc="upper left", fontsize=7, title="transient: until the α1 peaks\nare within "
              f"{100 * TRANSIENT_TOL:g} % of the cycle's", title_fontsize=6.5)
    ax.set_title(f"Fig. 13: {_load_text(data)}; limit cycle, "
                 f"period {T:.4f} s\n{_section29_text(data)}", fontsize=8)
    return fig


def plot_fig14(data: dict[str, Any]) -> Figure:
    """Fig. 14: angular velocities against rotations."""
    a = np.degrees(data["alpha"])
    w = np.degrees(data["alpha_dot"])
    t = np.array(data["t"])
    lcd = data["limit_cycle"]
    k = _transient_end(t, a[0], np.degrees(lcd["alpha1_amplitude_rad"]))
    fig, axes = plt.subplots(2, 1, figsize=(4.8, 6.4), layout="constrained")
    for i, ax in enumerate(axes):
        lc = _transient_and_cycle(ax, a[i], w[i], t, k, t[k], i == 0)
        ax.set_xlabel(rf"$\alpha_{i + 1}$ [deg]")
        ax.set_ylabel(rf"$\dot\alpha_{i + 1}$ [deg/s]")
    fig.colorbar(lc, ax=axes, label=f"time t [s] along the transient (to {t[k]:.1f} s)")
    fig.legend(loc="outside lower center", fontsize=7, frameon=False,
               title=f"transient: until the α1 peaks are within {100 * TRANSIENT_TOL:g} % of "
                     "the cycle's", title_fontsize=6.5)
    axes[0].set_title(f"Fig. 14: {_load_text(data)}; amplitudes "
                      f"{np.degrees(lcd['alpha1_amplitude_rad']):.2f}°, "
                      f"{np.degrees(lcd['alpha2_amplitude_rad']):.2f}°\n"
                      f"{_section29_text(data)}", fontsize=8)
    return fig


def plot_fig20(data: dict[str, Any]) -> Figure:
    """Fig. 20: transverse acceleration of the loaded end, 6 s and the first 1.5 s."""
    t = np.array(data["t"])
    acc = np.array(data["acc_nonlinear"])
    tl, al = np.array(data["t_linear"]), np.array(data["acc_linear"])
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(9.0, 3.4),
                                   gridspec_kw={"width_ratios": [2, 1]})
    lim = 1.45 * np.max(np.abs(acc))  # room for the legend above the peaks
    for ax, tmax in ((ax1, t[-1]), (ax2, tl[-1])):
        ax.plot(t[t <= tmax], acc[t <= tmax], color="C3", lw=0.8, label="nonlinear, eq. (10)")
        ax.plot(tl, al, color="C0", lw=0.8, label="linear, eqs. (11)+(26)")
        ax.set_ylim(-lim, lim)
        ax.set_xlim(0, tmax)
        ax.set_xlabel("t [s]")
    for ax in (ax1, ax2):
        ax.set_ylabel(r"transverse acceleration of C [m/s$^2$]")
    # one legend, in the detail's upper left: before the blow-up both curves are small there
    # (in the 6-s panel, above the cycle's peaks, it covered the linear solution's blow-up;
    # lower left, it hid the first peaks)
    ax2.legend(fontsize=7, loc="upper left")
    a0 = data.get("alpha0_deg", 0.5)  # (data from before the key was stored: the default)
    # one's own pendulum in short, its values on a line of their own (in the title's line
    # they widened the figure to the title's length)
    note = own_parameters_note(data, "pendulum", "list47_viscous", width=140)
    fig.suptitle(f"Fig. 20: {list47_viscous(data, short=True)}, P = {data['P']:.3f} N (middle "
                 f"of the flutter interval {data['P_flu']:.2f}–{data['P_div']:.2f} N), from "
                 f"α1 = α2 = {a0:g}° at rest\nsimulations only: the measured acceleration of "
                 "the printed figure (plate at 75 mm/s) is an experiment, not reproduced;\nthe "
                 "model's follower force does not depend on the plate's speed"
                 + (f"\n{note}" if note else ""), fontsize=8)
    ax1.set_title(f"the first {t[-1]:g} s (C: the pendulum's loaded end)", fontsize=8)
    ax2.set_title(f"detail: the first {tl[-1]:g} s\n(the linear solution is cut there)",
                  fontsize=8)
    fig.tight_layout()
    return fig


def plot_fig21(data: dict[str, Any]) -> Figure:
    """Fig. 21: the path of the loaded end and the scratch it leaves on the moving plate."""
    C = np.array(data["C"]) * 1000
    S = np.array(data["scratch"]) * 1000
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(9.6, 4.4),
                                   gridspec_kw={"width_ratios": [1, 1.6]})
    lc = time_coloured(ax1, C[:, 0], C[:, 1], data["t"], lw=1.2)
    ax1.set_aspect("equal")
    fig.colorbar(lc, ax=ax1, label="time t [s]")
    ax1.set_title("path of the loaded end C in the fixed frame [mm]", fontsize=8)
    ax2.set_facecolor("0.15")
    ax2.plot(S[:, 0], S[:, 1], color="w", lw=1.4, label="scratch: C seen from the plate")
    ax2.set_aspect("equal")
    # the start (the path's first, dark part stays near the straight pendulum, under the
    # later loops: a marker says where it is; a figure review)
    for ax, Q in ((ax1, C), (ax2, S)):
        ax.plot(*Q[0], "o", ms=6, mfc="none", mec="C3", mew=1.4, zorder=4,
                label="start, t = 0 (straight pendulum)")
    # under the panel, on the panel's dark grey (the scratch's white line shows there; inside,
    # the legend covered a loop)
    ax2.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.14), ncol=2,
               facecolor="0.15", labelcolor="w", framealpha=1.0)
    ax2.set_title(f"the scratch on the plate (moving at {data['plate_speed'] * 1000:g} mm/s)",
                  fontsize=8)
    w0, T = data.get("omega0", 0.5), data.get("duration", 2.04)  # (older data: the defaults)
    note = own_parameters_note(data, "pendulum", "list47_viscous", width=140)
    fig.suptitle(f"Fig. 21: {list47_viscous(data, short=True)}, P = {data['P']:.3f} N (middle "
                 f"of the flutter interval), {T:g} s "
                 f"from α1 = α2 = 0 with angular velocities {w0:g} rad/s (computed)\n"
                 + ("largest rotations reached: |α1| = {:.0f}°, |α2| = {:.0f}°; ".format(
                     *data["alpha_max_deg"]) if "alpha_max_deg" in data else "")
                 + "the photo of the scratch and the camera's spots are an experiment, not "
                 "reproduced" + (f"\n{note}" if note else ""), fontsize=8)
    # the frame of eq. (1): origin at the clamp A, x along the straight pendulum
    ax1.set_xlabel("x (from the clamp A, along the straight pendulum) [mm]", fontsize=8)
    ax2.set_xlabel("x on the plate (sliding along −x at the plate's speed) [mm]", fontsize=8)
    for ax in (ax1, ax2):
        ax.set_ylabel("y [mm]")
    fig.tight_layout()
    return fig


def plot_limit_cycle_amplitude(data: dict[str, Any]) -> Figure:
    """Bifurcation diagram: amplitudes and period of the limit cycle against the load."""
    P = np.array(data["P"])
    Pf = data["P_flu"]
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(8.6, 3.9), layout="constrained")
    ax1.plot(P, np.degrees(data["alpha1_amplitude"]), "o-", ms=4, label=r"$\alpha_1$")
    ax1.plot(P, np.degrees(data["alpha2_amplitude"]), "s-", ms=4, label=r"$\alpha_2$")
    # The normal form through the first cycle, drawn over the whole load range (on top of the
    # markers) so that where the branch leaves it shows.
    Pfine = np.linspace(Pf, P[-1], 200)
    c = np.degrees(data["alpha1_amplitude"][0]) / np.sqrt(P[0] - Pf)
    ax1.plot(Pfine, c * np.sqrt(Pfine - Pf), "k:", lw=1.2, zorder=3,
             label=r"$\alpha_1 \propto \sqrt{P - P_{flu}}$ (normal form, through the first cycle)")
    ax1.plot([P[0] * 0.97, Pf], [0, 0], "k-", lw=2, label="stable equilibrium")
    ax1.axvline(Pf, color="k", ls="--", lw=0.8,
                label=rf"damped flutter load $P_{{flu}}$ = {Pf:.4g} N")
    ax1.set_xlabel("follower load P [N]")
    ax1.set_ylabel("limit-cycle amplitude [deg]")
    # under the panels: inside, it hid the alpha2 branch (a figure review); under the left
    # panel alone, it left the figure lopsided (an outside review)
    fig.legend(*ax1.get_legend_handles_labels(), fontsize=7, loc="outside lower center",
               ncol=3)
    q = data["quantities"]
    text = pendulum_text(data.get("params", {}).get("pendulum"))
    if text:
        fig.suptitle(f"The pendulum {text}", fontsize=7)
    ax1.set_title(rf"supercritical Hopf at $P_{{flu}}$ = {Pf:.4g} N" "\n(fitted exponent b of "
                  rf"$\alpha_1 \propto (P - P_{{flu}})^b$: "
                  f"{q['hopf_exponent']['value']:.3f})", fontsize=8)
    ax2.plot(P, data["period"], "o-", ms=4)
    ax2.axhline(2 * np.pi / data["omega_flu"], color="k", ls=":", lw=1,
                label=r"$2\pi/\Omega$ at the flutter load")
    ax2.set_xlabel("follower load P [N]")
    ax2.set_ylabel("period [s]")
    ax2.legend(fontsize=7)
    ax2.set_title("period of the limit cycle", fontsize=8)
    return fig
