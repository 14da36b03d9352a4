"""Figure of the Beck rod's branch of limit cycles (scene ``beck_branch``)."""

from __future__ import annotations

from typing import Any

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.collections import LineCollection
from matplotlib.figure import Figure

from flutterfriction.plotting import list119


def plot_beck_branch(data: dict[str, Any]) -> Figure:
    """Tip amplitude and period of the limit cycles against the follower load, from the Hopf
    point; stability from the Floquet multipliers; the onset normal form; the chapter's cycle
    (Figs. 15–17) marked."""
    P, A = np.array(data["P_N"]), np.array(data["tip_amplitude_m"])
    T = np.array(data["period_s"])
    mu = np.array(data["max_floquet_modulus"])
    stable = mu < 1.0
    P_flu = data["P_flu_model"]
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(9.5, 4.0), layout="constrained")
    for ax, Y, scale in ((ax1, A, 1e3), (ax2, T, 1e3)):
        ax.plot(P, Y * scale, "-", color="0.6", lw=1, zorder=1,
                label="the branch (continuation steps joined)")
        ax.plot(P[stable], Y[stable] * scale, "o", ms=3.5, color="C0", zorder=2,
                label=r"stable cycle (all non-trivial $|\mu| < 1$)")
        if (~stable).any():
            ax.plot(P[~stable], Y[~stable] * scale, "o", ms=4, mfc="none", color="C3",
                    zorder=2, label=r"unstable cycle ($|\mu| > 1$)")
        ax.axvline(P_flu, color="k", ls=":", lw=1,
                   label=f"damped flutter load (Hopf point), {P_flu:.3f} N")
        ax.set_xlabel("follower load P [N]")
    # Onset normal form through the second cycle, drawn up to where it leaves the branch.
    k = 1 if len(P) > 1 else 0
    c = A[k] / np.sqrt(P[k] - P_flu)
    dP = np.linspace(0.0, min(0.12, P.max() - P_flu), 100)
    ax1.plot(P_flu + dP, c * np.sqrt(dP) * 1e3, "C1--", lw=1.2,
             label=r"normal form $A = c\,\sqrt{P - P_{flu}}$")
    k_cycle = data.get("cycle_index")
    if k_cycle is not None:
        for ax, Y in ((ax1, A), (ax2, T)):
            ax.plot(P[k_cycle], Y[k_cycle] * 1e3, "*", ms=13, color="C2", mec="k", mew=0.6,
                    zorder=3, label=f"Figs. 15–17: P = {P[k_cycle]:g} N")
        # the branch's mesh named: Figs. 15-17's headers quote their own, finer cycle (a
        # review read 250.3 mm here against their 250.2 mm)
        n_el = data["n_elements"]
        ax1.annotate(f"{A[k_cycle] * 1e3:.1f} mm ({n_el} el.)", (P[k_cycle], A[k_cycle] * 1e3),
                     xytext=(0, -16), textcoords="offset points", ha="center", fontsize=7)
        ax2.annotate(f"{T[k_cycle] * 1e3:.2f} ms ({n_el} el.)", (P[k_cycle], T[k_cycle] * 1e3),
                     xytext=(4, -14), textcoords="offset points", ha="left", fontsize=7)
    checks = data.get("mesh_checks") or []
    if checks:
        n_fine = data["settings"]["check_elements"]
        for ax, key in ((ax1, "tip_amplitude_m"), (ax2, "period_s")):
            ax.plot([c["P_N"] for c in checks], [c["fine"][key] * 1e3 for c in checks], "s",
                    ms=7, mfc="none", mec="C3", mew=1.1, zorder=4,
                    label=f"mesh check: the cycle on {n_fine} P2 elements")
    ax1.set_ylabel("tip amplitude A [mm]\n(largest lateral displacement)")
    ax2.set_ylabel("period [ms]")
    ax1.legend(fontsize=7, loc="lower right")
    ax2.legend(fontsize=7, loc="upper right")
    fig.suptitle(f"Beck rod, {list119(data)}, {data['n_elements']} P2 elements: the branch of "
                 "limit cycles from the Hopf point (periodic-orbit continuation, Floquet "
                 "multipliers)", fontsize=9)
    return fig


def plot_beck_branch_shapes(data: dict[str, Any]) -> Figure:
    """The rod over one period of a few cycles of the branch (the amplitude's first maximum and
    the following minimum, the chapter's cycle, the last): its centre line at equally spaced
    instants, coloured by the time through the period; lateral against axial position."""
    shapes = data["shapes"]
    n = len(shapes)
    fig, axes = plt.subplots(1, n, figsize=(2.6 * n + 1.0, 2.9), layout="constrained",
                             sharey=True, squeeze=False)
    # one scale for all panels, the whole swing in view (a curled rod reaches further sideways
    # than it is long: data-limited shared axes cut its loops off)
    lateral = max(abs(v) for sh in shapes for _, z in sh["shapes"] for v in z) * 1e3 * 1.05
    axial = [min(min(x) for sh in shapes for x, _ in sh["shapes"]) * 1e3,
             max(max(x) for sh in shapes for x, _ in sh["shapes"]) * 1e3]
    pad = 0.05 * (axial[1] - axial[0])
    lines = None
    for ax, sh in zip(axes[0], shapes, strict=True):
        m = len(sh["shapes"])
        # one line per instant, coloured by t/T (a collection: the colour bar explains it)
        lines = LineCollection([np.column_stack([np.array(z) * 1e3, np.array(x) * 1e3])
                                for x, z in sh["shapes"]], cmap="viridis", lw=1,
                               norm=plt.Normalize(0.0, 1.0))
        lines.set_array(np.arange(m) / m)
        ax.add_collection(lines)
        ax.set_xlim(-lateral, lateral)
        ax.set_ylim(axial[0] - pad, axial[1] + pad)
        ax.set_title(f"{sh['label']}\nP = {sh['P_N']:.3f} N, A = "
                     f"{sh['tip_amplitude_m'] * 1e3:.0f} mm", fontsize=8)
        ax.set_xlabel("lateral position [mm]")
        ax.set_aspect("equal", adjustable="box")
    axes[0][0].set_ylabel("axial position from the clamp [mm]")
    fig.colorbar(lines, ax=axes[0].tolist(), shrink=0.8,
                 label="time through the period, t/T [-]")
    fig.suptitle(f"Beck rod, {list119(data)}, {data['n_elements']} P2 elements: the rod over "
                 "one period of cycles of the branch", fontsize=9)
    return fig


PLOTS = {"beck_branch": plot_beck_branch, "beck_branch_shapes": plot_beck_branch_shapes}
