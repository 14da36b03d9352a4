"""Figures of §3: Fig. 22, the acoustic eigenvalues, localization directions, flutter maps."""

from __future__ import annotations

from typing import Any

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.figure import Figure

from flutterfriction.plotting import REGIME_COLOURS


def plot_fig22(data: dict[str, Any]) -> Figure:
    """The Coulomb cone in the (p_N, p_T) plane, a and b at a slip point, and a force path."""
    p = np.array(data["p"])
    mu = data["mu"]
    fig, ax = plt.subplots(figsize=(5.2, 4.2))
    pn = np.linspace(0, 1.25 * p[:, 0].max(), 2)
    ax.fill_between(pn, -mu * pn, mu * pn, color="0.9", label="stick (inside the cone)")
    ax.plot(pn, mu * pn, "k", lw=1.2)
    ax.plot(pn, -mu * pn, "k", lw=1.2, label=r"Coulomb cone $|p_T| = \mu p_N$")
    colours = {"stick": "C0", "slip": "C3"}
    done = set()
    for k in range(1, len(p)):
        b = data["branch"][k]
        ax.plot(p[k - 1:k + 1, 0], p[k - 1:k + 1, 1], "-", color=colours[b], lw=2.2,
                label=f"computed path: {b}" if b not in done else None)
        done.add(b)
    ax.plot(p[:, 0], p[:, 1], "o", color="k", ms=3)
    # One label per distinct point ("2, 3" where the path stops at the same force twice),
    # coincident ones below-right of the point, inside the cone, clear of the path.
    groups: dict[tuple[float, float], list[int]] = {}
    for k, (x, y) in enumerate(p):
        groups.setdefault((round(float(x), 9), round(float(y), 9)), []).append(k)
    for (x, y), ks in groups.items():
        ax.annotate(", ".join(map(str, ks)), (x, y), xytext=(4, 4) if len(ks) == 1 else (5, -11),
                    textcoords="offset points", fontsize=7)
    s = np.array(data["slip_point"])
    L = 0.35 * p[:, 0].max()
    for vec, name, col, ha in ((data["a"], r"$\mathbf{a}$ (normal)", "C2", "right"),
                               (data["b"], r"$\mathbf{b}$ (slip)", "C1", "left")):
        v = np.array(vec) / np.linalg.norm(vec) * L
        ax.annotate("", s + v, s, arrowprops={"arrowstyle": "-|>", "color": col, "lw": 1.8})
        ax.annotate(name, s + 1.05 * v, color=col, fontsize=9, ha=ha, va="bottom")
    ax.set_ylim(p[:, 1].min() - 0.4 * L, max(p[:, 1].max(), s[1]) + 1.45 * L)
    ax.set_xlabel(r"normal force $p_N$ [N]")
    ax.set_ylabel(r"tangential force $p_T$ [N]")
    ax.set_aspect("equal")
    ax.legend(loc="lower left", fontsize=7)
    ax.set_title("Fig. 22: Coulomb friction, a nonassociative 'flow rule' (b not parallel to a)",
                 fontsize=8)
    return fig


def plot_acoustic_eigenvalues(data: dict[str, Any]) -> Figure:
    """Re and Im of the eigenvalues of A(n) against g, with g_cr^E, g1, g2."""
    g = np.array(data["g"])
    g1, g2 = data["flutter_interval"]
    fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(5.6, 4.8), sharex=True,
                                   gridspec_kw={"height_ratios": [3, 2]})
    for ax in (ax1, ax2):
        ax.axvspan(g1, g2, color=REGIME_COLOURS["flutter"], lw=0, label="flutter (g1, g2)")
        ax.set_xscale("log")
    for i, (re, im) in enumerate(zip(data["re"], data["im"], strict=True)):
        ax1.plot(g, re, color=f"C{i}", lw=1.4)
        ax2.plot(g, im, color=f"C{i}", lw=1.4, label=f"eigenvalue {i + 1} of A(n)")
    ax1.axhline(data["mu"], color="k", ls=":", lw=0.8)
    ax1.annotate(rf"$\mu$ = {data['mu']:g}", (g[0], data["mu"]), xytext=(0, 3),
                 textcoords="offset points", ha="left", va="bottom", fontsize=7)
    ax1.axhline(0, color="k", lw=0.6)
    for val, name, ha in ((g1, "$g_1$", "right"), (g2, "$g_2$", "left")):
        ax1.axvline(val, color="k", ls="--", lw=0.8)
        ax1.annotate(f"{name} = {val:.4g}", (val, 1.0), xycoords=("data", "axes fraction"),
                     xytext=(0, 2), textcoords="offset points", va="bottom", ha=ha, fontsize=7)
    gE = data["g_localization"]
    ax1.set_title(f"Eigenvalues of A(n) (eq. 179), nonassociative case; "
                  f"$g^E_{{cr}}(n)$ = {gE:.4g} < 0: localization not reached for g > 0",
                  fontsize=8, pad=14)
    ax1.set_yscale("symlog", linthresh=1.0)
    ax1.set_ylabel(r"Re $c^2$ [Pa]")
    ax2.set_ylabel(r"Im $c^2$ [Pa]")
    ax2.set_xlabel("plastic modulus g [Pa]")
    # In the empty Re < 0 band (no eigenvalue goes there for g > 0).
    ax1.legend(*ax2.get_legend_handles_labels(), fontsize=7, loc="lower right", ncol=2)
    return fig


def plot_localization_directions(data: dict[str, Any]) -> Figure:
    """g_E(n) over the (sigma_1, sigma_3) plane and the maximum over the sphere."""
    th = np.degrees(data["theta"])
    fig, ax = plt.subplots(figsize=(5.4, 3.6))
    ax.plot(th, data["g_E"], color="C0",
            label=r"$g^E_{cr}(n)$, n in the $(\sigma_1,\sigma_3)$ plane")
    ax.axhline(data["g_max"], color="C3", ls="--", lw=1.0,
               label=f"max over the sphere = {data['g_max']:.6f}")
    ax.axvline(np.degrees(data["theta_max_in_plane"]), color="k", ls=":", lw=0.8)
    q = data["quantities"]["h_cr"]
    ax.set_title(f"Localization, Drucker–Prager: $h_{{cr}}$ = {q['value']:.6f} "
                 f"(Rudnicki–Rice: {q['independent']:.6f})", fontsize=8)
    ax.set_xlabel(r"angle of n from the $\sigma_1$ axis [deg]")
    ax.set_ylabel(r"$g^E_{cr}(n)$ [Pa]")
    ax.legend(fontsize=7)
    return fig


def plot_flutter_map(data: dict[str, Any]) -> Figure:
    """(a) flutter region over directions and g; (b) flutter triggered by elastic anisotropy,
    zoomed on the directions that flutter; (c) their fraction against the anisotropy."""
    th = np.degrees(data["theta"])
    fig, (ax1, ax2, ax3) = plt.subplots(1, 3, figsize=(12.6, 3.9),
                                        gridspec_kw={"width_ratios": [1.25, 1, 0.8]})
    g1 = np.array([np.nan if v is None else v for v in data["g1"]], float)
    g2 = np.array([np.nan if v is None else v for v in data["g2"]], float)
    ax1.fill_between(th, g1, g2, color=REGIME_COLOURS["flutter"], label="flutter")
    ax1.plot(th, g1, color="C1", lw=1)
    ax1.plot(th, g2, color="C1", lw=1, label=r"its bounds $g_1$, $g_2$")
    ax1.plot(th, data["g_localization"], color="C0", label=r"$g^E_{cr}(n)$ (localization)")
    ax1.set_yscale("symlog", linthresh=1e-3)
    ax1.set_xlabel(r"angle of n in the $(e_1, e_3)$ plane [deg]")
    ax1.set_ylabel("plastic modulus g [Pa]")
    ax1.set_title("(a) nonassociative case: directions that flutter", fontsize=8)
    ax1.legend(fontsize=7)
    an = data["anisotropy"]
    off = np.array(an["offsets_deg"])
    step = off[1] - off[0]
    maps = [np.array(m, dtype=bool) for m in an["maps"]]
    # Each direction (a cell of the tangent-plane grid around the coalescence direction n_C)
    # coloured by the smallest anisotropy at which it flutters.
    levels = [k for k, m in enumerate(maps) if m.any()]
    cmap = plt.get_cmap("autumn_r")
    shown = np.zeros_like(maps[0])
    for n, k in enumerate(levels):
        new_cells = maps[k] & ~shown
        shown |= maps[k]
        r, c = np.nonzero(new_cells)
        colour = cmap(0.35 + 0.65 * n / max(len(levels) - 1, 1))
        for rr, cc in zip(r, c, strict=True):
            ax2.add_patch(plt.Rectangle((off[cc] - step / 2, off[rr] - step / 2), step, step,
                                        color=colour, lw=0))
        ax2.plot([], [], "s", color=colour, ms=6, label=f"first flutters at ε = {an['eps'][k]:g}")
    ax2.plot(0, 0, "k+", ms=10, label=r"coalescence direction $n_C$")
    if shown.any():
        r, c = np.nonzero(shown)
        half = max(np.abs(off[r]).max(), np.abs(off[c]).max()) + 2.0
    else:
        half = off[-1]
    ax2.set_xlim(-half, half)
    ax2.set_ylim(-half, half)
    ax2.set_aspect("equal")
    ax2.set_xlabel(r"tilt of n from $n_C$ towards $t_1 = n_C \times e_3$ [deg]")
    ax2.set_ylabel(r"tilt towards $t_2 = n_C \times t_1$ [deg]")
    ax2.legend(fontsize=6.5, loc="upper left", title=f"cells: directions on a {step:g}° grid",
               title_fontsize=6.5)
    ax2.set_title("(b) Drucker–Prager at coalescence + anisotropy ε", fontsize=8)
    ax3.plot(an["eps"], np.array(an["fraction_flutter"]) * 100, "o-", ms=3.5, color="C3")
    ax3.set_xlabel("elastic anisotropy ε [-]")
    ax3.set_ylabel(f"directions that flutter [%] (of the ±{off[-1]:g}° patch)")
    ax3.set_title("(c) flutter appears with anisotropy", fontsize=8)
    fig.tight_layout()
    return fig
