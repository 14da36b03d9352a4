"""Figures of §3: Fig. 22, the acoustic eigenvalues, localization directions, flutter maps."""

from __future__ import annotations

from typing import Any

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.axes import Axes
from matplotlib.figure import Figure
from matplotlib.lines import Line2D
from matplotlib.patches import Patch, Polygon, Rectangle

from flutterfriction.plotting import REGIME_COLOURS

#: Label offsets [points] tried in turn for a path's point (:func:`place_point_labels`):
#: above-right, below-right, above, below, above-left, below-left, right, left.
_LABEL_OFFSETS = ((4, 4), (5, -11), (-3, 6), (-3, -13), (-10, 4), (-10, -11), (6, -3),
                  (-12, -3))


def _label_points(ax: Axes, xy: np.ndarray) -> None:
    """One label per distinct point of the path ("2, 3" where it stops at the same place
    twice), above-right of it; :func:`place_point_labels` moves them clear of the lines once
    the figure is laid out."""
    groups: dict[tuple[float, float], list[int]] = {}
    for k, (x, y) in enumerate(np.asarray(xy, dtype=float)):
        groups.setdefault((round(float(x), 9), round(float(y), 9)), []).append(k)
    for (x, y), ks in groups.items():
        t = ax.annotate(", ".join(map(str, ks)), (x, y), xytext=_LABEL_OFFSETS[0],
                        textcoords="offset points", fontsize=7)
        t.point_label = True


def place_point_labels(fig: Figure) -> None:
    """Each point label of :func:`_label_points` at the first of :data:`_LABEL_OFFSETS` where
    its box (grown by 2 px) meets no line or marker of its axes and no other text (nor a label
    placed before it), lies inside the axes and is nearer its own point than any other
    labelled point, else where it breaks these least: measured on the laid-out figure (a
    review saw Fig. 22's 6 on a segment of the path). Call after the layout."""
    renderer = fig.canvas.get_renderer()
    for ax in fig.axes:
        samples = []
        for line in ax.get_lines():
            xy = np.asarray(line.get_xydata(), dtype=float)
            xy = xy[np.all(np.isfinite(xy), axis=1)]
            if line.get_linestyle() not in ("None", "", " ") and len(xy) >= 2:
                s = np.linspace(0.0, 1.0, 60)[None, :, None]
                pts = (xy[:-1, None, :] + s * (xy[1:, None, :] - xy[:-1, None, :])).reshape(-1, 2)
                samples.append(ax.transData.transform(pts))
            if line.get_marker() not in ("None", "", " ", None) and len(xy):
                # a marker: its centre and a ring at its radius
                r = 0.5 * line.get_markersize() * fig.dpi / 72.0 + 1.0
                ring = r * np.array([[np.cos(a), np.sin(a)]
                                     for a in np.linspace(0, 2 * np.pi, 32, endpoint=False)])
                centres = ax.transData.transform(xy)
                samples.append((centres[:, None, :] + np.vstack([[0, 0], ring])[None]
                                ).reshape(-1, 2))
        pts = np.vstack(samples) if samples else np.empty((0, 2))
        labels = [t for t in ax.texts if getattr(t, "point_label", False)]
        # the other texts, and the point labels already placed (not those still to move)
        others = [o.get_window_extent(renderer) for o in ax.texts
                  if not getattr(o, "point_label", False)]
        frame = ax.get_window_extent(renderer)
        anchors = ax.transData.transform([t.xy for t in labels])
        for i, t in enumerate(labels):

            def hits(off, t=t, i=i, others=tuple(others), pts=pts, frame=frame,
                     anchors=anchors) -> tuple[int, int]:
                t.xyann = off
                box = t.get_window_extent(renderer).padded(2.0)
                inside = ((pts[:, 0] > box.x0) & (pts[:, 0] < box.x1)
                          & (pts[:, 1] > box.y0) & (pts[:, 1] < box.y1))
                # read as another point's (its centre nearer another point: a review saw 7
                # between 7 and 6), or on the frame (4 on the right spine)
                centre = np.array([0.5 * (box.x0 + box.x1), 0.5 * (box.y0 + box.y1)])
                d = np.linalg.norm(anchors - centre, axis=1)
                misread = int(np.argmin(d)) != i
                framed = not (frame.x0 <= box.x0 and box.x1 <= frame.x1
                              and frame.y0 <= box.y0 and box.y1 <= frame.y1)
                return (int(inside.sum()) + 1000 * (misread + framed),
                        sum(box.overlaps(o) for o in others))

            scores = [hits(off) for off in _LABEL_OFFSETS]
            clear = [k for k, sc in enumerate(scores) if sc == (0, 0)]
            best = clear[0] if clear else min(range(len(scores)), key=lambda k: scores[k])
            t.xyann = _LABEL_OFFSETS[best]
            others.append(t.get_window_extent(renderer))


def _coulomb_panel(ax: Axes, data: dict[str, Any]) -> None:
    """The Coulomb cone in the (p_N, p_T) plane, a and b at a slip point, and a force path."""
    p = np.array(data["p"])
    mu = data["mu"]
    pn = np.linspace(0, 1.25 * p[:, 0].max(), 2)
    ax.fill_between(pn, -mu * pn, mu * pn, color="0.9", label="stick (inside the cone)")
    ax.plot(pn, mu * pn, "k", lw=1.2)
    ax.plot(pn, -mu * pn, "k", lw=1.2, label=r"Coulomb cone $|p_T| = \mu p_N$")
    _path_by_branch(ax, p[:, 0], p[:, 1], data["branch"], "computed path")
    ax.plot(p[:, 0], p[:, 1], "o", color="k", ms=3)
    _label_points(ax, p)
    s = np.array(data["slip_point"])
    L = 0.35 * p[:, 0].max()
    for vec, name, col, ha in ((data["a"], r"$\mathbf{a}$ (normal)", "C2", "right"),
                               (data["b"], r"$\mathbf{b}$ (slip)", "C1", "left")):
        v = np.array(vec) / np.linalg.norm(vec) * L
        ax.annotate("", s + v, s, arrowprops={"arrowstyle": "-|>", "color": col, "lw": 1.8})
        ax.annotate(name, s + 1.05 * v, color=col, fontsize=9, ha=ha, va="bottom")
    ax.set_ylim(p[:, 1].min() - 0.4 * L, max(p[:, 1].max(), s[1]) + 1.45 * L)
    # the cone drawn to the frame (the default margin left a white strip inside it; a review)
    ax.set_xlim(-0.05 * pn[-1], pn[-1])
    ax.set_xlabel(r"normal force $p_N$ [N]")
    ax.set_ylabel(r"tangential force $p_T$ [N]")
    ax.set_aspect("equal")
    # under the panel (inside, lower left, it covered point 7 and the 6-7 slip; a review)
    ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.16), fontsize=7, ncol=2)
    ax.set_title("(right) the Coulomb criterion:\na nonassociative 'flow rule' (b not parallel "
                 "to a);\npoints numbered along the path", fontsize=8)


STICK_SLIP = {"stick": "C0", "slip": "C3"}


def _path_by_branch(ax, x, y, branches, label: str) -> None:
    """The path's segments coloured by the branch each ends on (stick, slip), each branch in
    the legend once."""
    done = set()
    for k in range(1, len(x)):
        b = branches[k]
        ax.plot(x[k - 1:k + 1], y[k - 1:k + 1], "-", color=STICK_SLIP[b], lw=2.2,
                label=f"{label}: {b}" if b not in done else None)
        done.add(b)
_FORCE = {"N": "C2", "T": "C1", "reaction": "C4"}


def _arrow(ax: Axes, tail, head, colour: str, lw: float = 1.8) -> None:
    ax.annotate("", tuple(head), tuple(tail),
                arrowprops={"arrowstyle": "-|>", "color": colour, "lw": lw, "shrinkA": 0,
                            "shrinkB": 0, "mutation_scale": 12}, zorder=9)


def _zigzag(ax: Axes, start, end, n: int = 6, width: float = 0.18, **kw) -> None:
    """A coil spring from ``start`` to ``end`` (straight leads, ``n`` zigzags between)."""
    start, end = np.asarray(start, float), np.asarray(end, float)
    d = end - start
    t = d / np.linalg.norm(d)
    nrm = np.array([-t[1], t[0]])
    s = np.concatenate([[0.0, 0.15], np.linspace(0.15, 0.85, 2 * n + 1)[1:-1], [0.85, 1.0]])
    off = np.zeros_like(s)
    off[2:-2] = width * np.where(np.arange(len(s) - 4) % 2 == 0, 1.0, -1.0)
    pts = start + s[:, None] * d + off[:, None] * nrm
    ax.plot(*pts.T, **kw)


def _ground(ax: Axes, x0: float, x1: float, y: float, h: float = 0.25) -> None:
    ax.plot([x0, x1], [y, y], color="k", lw=1.2)
    for x in np.arange(x0 + 0.1, x1, 0.3):
        ax.plot([x, x - h], [y, y - h], color="k", lw=0.6)


def _bricks_panel(ax: Axes, data: dict[str, Any]) -> None:
    """Two bricks in contact after the path's first slip (its first recorded slip point): N, T,
    the contact reaction on the friction cone, and the upper brick shifted by the slip (to the
    scale of the bricks, with a scale bar)."""
    k = data["slip_point_index"]
    N, T = data["p"][k]
    mu, slip = data["mu"], data["slip"][k] - data["slip"][0]
    L, H, f = 4.0, 1.6, 0.7  # brick length and height [m], arrow length per newton [m/N]
    ax.add_patch(Rectangle((-L / 2, -H), L, H, fc="#d9a07a", ec="k", lw=1.0))
    ax.add_patch(Rectangle((-L / 2, 0.0), L, H, fill=False, ec="0.45", lw=0.9, ls="--"))
    ax.add_patch(Rectangle((-L / 2 + slip, 0.0), L, H, fc="#e8c0a0", ec="k", lw=1.0,
                           alpha=0.9))
    _ground(ax, -L / 2 - 0.3, L / 2 + 0.3, -H)
    xc = slip
    cone = np.array([[xc - mu * 1.5 * H, 1.5 * H], [xc, 0.0], [xc + mu * 1.5 * H, 1.5 * H]])
    ax.add_patch(Polygon(cone, closed=True, fc="0.85", ec="0.3", lw=0.8, ls=":", alpha=0.6,
                         zorder=3))
    _arrow(ax, (xc, H + N * f), (xc, H), _FORCE["N"])
    _arrow(ax, (L / 2 + slip, 0.5 * H), (L / 2 + slip + T * f, 0.5 * H), _FORCE["T"])
    _arrow(ax, (xc, 0.0), (xc - np.sign(T) * abs(T) * f, N * f), _FORCE["reaction"])
    ax.annotate(f"$N = p_N$ = {N:.2f} N", (xc, H + N * f), xytext=(5, -2),
                textcoords="offset points", fontsize=8, color=_FORCE["N"], va="top")
    ax.annotate(f"$T = p_T$ = {T:.2f} N", (L / 2 + slip, 0.5 * H), xytext=(2, 6),
                textcoords="offset points", fontsize=8, color=_FORCE["T"], ha="left",
                va="bottom")
    ax.text(0.5, 0.02, f"friction limit |T| ≤ μN: T = {abs(T):.2f} N = μN = {mu * N:.2f} N,\n"
            f"so the upper brick slips: $u_T^s$ = {slip:.2f} m (drawn to scale)",
            transform=ax.transAxes, ha="center", va="bottom", fontsize=8)
    handles = [Line2D([], [], color=_FORCE["N"], lw=1.8, label="normal force N"),
               Line2D([], [], color=_FORCE["T"], lw=1.8, label="tangential force T"),
               Line2D([], [], color=_FORCE["reaction"], lw=1.8,
                      label="contact reaction (−T, N): on the cone"),
               Patch(fc="0.85", ec="0.3", ls=":", label=f"friction cone, half-angle "
                     f"arctan μ = {np.degrees(np.arctan(mu)):.1f}°"),
               Line2D([], [], color="0.45", ls="--", lw=0.9, label="upper brick before slip")]
    ax.legend(handles=handles, loc="upper left", fontsize=7)
    bar, xb, yb = 0.5, L / 2 + slip + 0.9, -0.6 * H  # length scale bar [m]
    ax.plot([xb, xb + bar], [yb, yb], color="k", lw=2, solid_capstyle="butt")
    for x in (xb, xb + bar):
        ax.plot([x, x], [yb - 0.08, yb + 0.08], color="k", lw=1)
    ax.annotate(f"{bar:g} m", (xb + bar / 2, yb), xytext=(0, 3), textcoords="offset points",
                ha="center", va="bottom", fontsize=8)
    ax.set_xlim(-L / 2 - 0.5, L / 2 + slip + 2.4)
    ax.set_ylim(-H - 1.9, H + N * f + 3.4)  # (room above the N arrow for the legend)
    ax.set_aspect("equal")
    ax.set_axis_off()
    ax.set_title(f"(left) two 'bricks' in contact,\nafter the first slip (point {k} of the path)",
                 fontsize=8)


def _slider_sketch(ax: Axes, data: dict[str, Any]) -> None:
    """The model of §3.1: a point mass on a rigid plane, a normal spring k_N pressing it with
    p_N and a tangential spring k_T pulled with p_T; the mass slips by u_T^s."""
    ax.set_axis_off()
    _ground(ax, -0.6, 5.2, 0.0, h=0.2)
    x_m, w = 0.4, 0.7
    ax.add_patch(Rectangle((x_m, 0.0), w, w, fc="0.35", ec="k", lw=1.0, zorder=4))
    top = (x_m + w / 2, w + 1.6)
    _zigzag(ax, (x_m + w / 2, w), top, color="k", lw=1.0)
    ax.plot([top[0] - 0.3, top[0] + 0.3], [top[1], top[1]], color="k", lw=2)
    _arrow(ax, (top[0], top[1] + 0.7), top, _FORCE["N"])
    end = (x_m + w + 2.0, w / 2)
    _zigzag(ax, (x_m + w, w / 2), end, color="k", lw=1.0)
    ax.plot([end[0], end[0]], [end[1] - 0.25, end[1] + 0.25], color="k", lw=2)
    _arrow(ax, end, (end[0] + 0.8, end[1]), _FORCE["T"])
    ax.annotate(r"$k_N$", (top[0] + 0.25, w + 0.8), fontsize=9, va="center")
    ax.annotate(r"$p_N$, $u_N$ (elastic)", (top[0] + 0.12, top[1] + 0.45), fontsize=8,
                color=_FORCE["N"], va="center")
    ax.annotate(r"$k_T$", (x_m + w + 1.0, w / 2 + 0.3), fontsize=9, ha="center", va="bottom")
    ax.annotate(r"$p_T$, $u_T = p_T/k_T + u_T^s$", (end[0] - 0.1, end[1] + 0.35), fontsize=8,
                color=_FORCE["T"], va="bottom", ha="left")
    ax.annotate(rf"Coulomb friction μ = {data['mu']:g}: slip $u_T^s$ when $|p_T| = \mu p_N$",
                (x_m, 0.0), xytext=(0, -16), textcoords="offset points", fontsize=8,
                va="top")
    ax.set_xlim(-0.7, 5.6)
    ax.set_ylim(-1.0, 3.2)
    ax.set_aspect("equal")
    ax.set_title(rf"(centre) the model: springs $k_N$ = {data['k_N']:g} N/m, "
                 rf"$k_T$ = {data['k_T']:g} N/m on a point mass", fontsize=8)


def _slider_response(ax: Axes, data: dict[str, Any]) -> None:
    """p_T against u_T along the computed path: stick lines of slope k_T, slip on the moving
    limit mu p_N, unloading; the slip onset and the residual displacement."""
    u, p = np.array(data["u"]), np.array(data["p"])
    mu = data["mu"]
    ax.plot(u[:, 1], mu * p[:, 0], "--", color="0.5", lw=1.0,
            label=r"friction limits $\pm\mu p_N$ along the path")
    ax.plot(u[:, 1], -mu * p[:, 0], "--", color="0.5", lw=1.0)
    _path_by_branch(ax, u[:, 1], p[:, 1], data["branch"], "computed")
    ax.plot(u[:, 1], p[:, 1], "o", color="k", ms=3)
    _label_points(ax, np.column_stack([u[:, 1], p[:, 1]]))
    i = data["onset_index"]
    ax.plot(u[i, 1], p[i, 1], "s", mfc="none", mec="C2", ms=9, mew=1.5,
            label=rf"slip onset: $|p_T| = \mu p_N$ = {abs(p[i, 1]):.2f} N")
    res = data["residual"]
    ax.plot(res["u_T"], 0.0, "D", mfc="none", mec="C4", ms=8, mew=1.5,
            label=rf"unloaded, $p_T$ = 0: $u_T = u_T^s$ = {res['slip']:.2f} m")
    ax.axhline(0, color="k", lw=0.6)
    top = mu * p[:, 0].max()
    ax.set_ylim(-1.15 * top, 1.35 * top)
    ax.set_xlabel(r"tangential displacement $u_T$ [m]")
    ax.set_ylabel(r"tangential force $p_T$ [N]")
    # under the panel (inside, in the figure's 10.6 in, it covered the path and the axis label)
    ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.2), fontsize=7, ncol=2)
    ax.set_title("its response along the path: stick, slip, unloading, reverse slip",
                 fontsize=8)


def plot_fig22(data: dict[str, Any]) -> Figure:
    """Fig. 22: two bricks in contact (left), the spring–slider model and its computed
    force–displacement response (centre), the Coulomb criterion with the same path (right)."""
    # 10.6 in wide: its texts legible with the figure 1200 px wide (at 14 in, 6.5-8 pt read
    # as 8-10 px; the figure check's `small` rule)
    fig = plt.figure(figsize=(10.6, 6.0))
    gs = fig.add_gridspec(2, 3, width_ratios=[1.0, 1.1, 1.15], height_ratios=[0.75, 1.0])
    _bricks_panel(fig.add_subplot(gs[:, 0]), data)
    _slider_sketch(fig.add_subplot(gs[0, 1]), data)
    _slider_response(fig.add_subplot(gs[1, 1]), data)
    _coulomb_panel(fig.add_subplot(gs[:, 2]), data)
    fig.suptitle("Fig. 22: contact with Coulomb friction, one computed path (numbered points) "
                 "in every panel", fontsize=10)
    fig.tight_layout()
    place_point_labels(fig)
    return fig


def _case_text(params: dict[str, Any]) -> str:
    """The nonassociative case a figure was computed for: elasticity, P, Q (Voigt order 11,
    22, 33, 23, 13, 12) and the direction n; empty without parameters."""
    if not {"lam", "mu", "P", "Q"} <= set(params):
        return ""
    def vec(v):
        return "(" + ", ".join(f"{x:g}" for x in v) + ")"
    text = (f"λ = {params['lam']:g} Pa, μ = {params['mu']:g} Pa, P = {vec(params['P'])}, "
            f"Q = {vec(params['Q'])} (Voigt 11, 22, 33, 23, 13, 12)")
    return text + (f", n = {vec(params['n'])}" if "n" in params else "")


def plot_acoustic_eigenvalues(data: dict[str, Any]) -> Figure:
    """Re and Im of the eigenvalues of A(n) against g, with g_cr^E, g1, g2."""
    g = np.array(data["g"])
    g1, g2 = data["flutter_interval"]
    fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(6.4, 5.4), sharex=True,
                                   gridspec_kw={"height_ratios": [3, 2]}, layout="constrained")
    for ax in (ax1, ax2):
        ax.axvspan(g1, g2, color=REGIME_COLOURS["flutter"], lw=0, label="flutter (g1, g2)")
        ax.set_xscale("log")
    for i, (re, im) in enumerate(zip(data["re"], data["im"], strict=True)):
        ax1.plot(g, re, color=f"C{i}", lw=1.4)
        ax2.plot(g, im, color=f"C{i}", lw=1.4, label=f"eigenvalue {i + 1} of A(n)")
    # A complex-conjugate pair has one real part: where two eigenvalues do (in the flutter
    # band), the first curve is drawn again dashed over the second (a figure review saw a
    # legend entry whose curve was hidden there).
    re_all, im_all = np.array(data["re"], float), np.array(data["im"], float)
    pair_colours = []
    for i in range(len(re_all)):
        for j in range(i + 1, len(re_all)):
            pair = (np.abs(im_all[i]) > 0) & np.isclose(re_all[i], re_all[j], rtol=1e-9, atol=0)
            if pair.any():
                ax1.plot(g, np.where(pair, re_all[i], np.nan), color=f"C{i}", lw=1.4,
                         ls=(0, (3, 3)), zorder=3)
                pair_colours.append(f"C{i}")
    ax1.axhline(data["mu"], color="k", ls=":", lw=0.8)
    ax1.annotate(rf"$\mu$ = {data['mu']:g}", (g[0], data["mu"]), xytext=(0, 3),
                 textcoords="offset points", ha="left", va="bottom", fontsize=7)
    ax1.axhline(0, color="k", lw=0.6)
    for val, name, ha in ((g1, "$g_1$", "right"), (g2, "$g_2$", "left")):
        ax1.axvline(val, color="k", ls="--", lw=0.8)
        ax1.annotate(f"{name} = {val:.4g}", (val, 1.0), xycoords=("data", "axes fraction"),
                     xytext=(0, 2), textcoords="offset points", va="bottom", ha=ha, fontsize=7)
    gE = data["g_localization"]
    ax1.set_title(f"Eigenvalues of A(n) (eq. 179); "
                  f"$g^E_{{cr}}(n)$ = {gE:.4g} < 0: no localization for g > 0",
                  fontsize=8, pad=14)
    ax1.set_yscale("symlog", linthresh=1.0)
    # eta, the eigenvalue of A(n) (eq. 183): rho c^2 of a plane wave, a stress (unit density)
    ax1.set_ylabel(r"Re $\eta = \rho c^2$ [Pa]")
    ax2.set_ylabel(r"Im $\eta$ [Pa]")
    ax2.set_xlabel("plastic modulus g [Pa]")
    # In the empty Re < 0 band (no eigenvalue goes there for g > 0).
    # Outside the band all three eigenvalues are real: their Im = 0 lines coincide and only
    # the last drawn shows, which the legend says (a figure review).
    handles, labels = ax2.get_legend_handles_labels()
    handles.append(Line2D([], [], ls="none"))
    labels.append(r"outside (g1, g2): all real, Im $\eta$ = 0")
    # the two other line styles on the Re panel, explained (a figure review)
    if pair_colours:
        handles.append(Line2D([], [], color=pair_colours[0], lw=1.4, ls=(0, (3, 3))))
        labels.append("complex pair: its common Re (dashed)")
    handles.append(Line2D([], [], color="k", ls=":", lw=0.8))
    labels.append(r"$\eta = \mu$ (eigenvalue 1 stays there)")
    ax1.legend(handles, labels, fontsize=7, loc="lower right", ncol=2)
    text = _case_text(data.get("params", {}))
    printed = data.get("flutter_interval_as_printed")
    if printed is not None:
        text += (f"\n$g_1$, $g_2$ from eq. (188) corrected; as printed it gives "
                 f"$g_1$ = {printed[0]:.4g} > $g_2$ = {printed[1]:.4g} (see the errata)")
    if text:
        fig.suptitle(text, fontsize=7)
    return fig


def plot_localization_directions(data: dict[str, Any]) -> Figure:
    """g_E(n) over the (sigma_1, sigma_3) plane and the maximum over the sphere."""
    th = np.degrees(data["theta"])
    fig, ax = plt.subplots(figsize=(5.4, 3.6), layout="constrained")
    ax.plot(th, data["g_E"], color="C0",
            label=r"$g^E_{cr}(n)$, n in the $(\sigma_1,\sigma_3)$ plane")
    ax.axhline(data["g_max"], color="C3", ls="--", lw=1.0,
               label=f"max over the sphere = {data['g_max']:.6f} Pa")
    theta_max = np.degrees(data["theta_max_in_plane"])
    # the other maximum, the mirror band (n1 -> -n1), from the curve itself: both are marked
    # (a review saw one of two equal peaks marked)
    g_E = np.array(data["g_E"])
    other = th > 90.0 if theta_max < 90.0 else th < 90.0
    theta_other = th[other][np.argmax(g_E[other])] if other.any() else None
    ax.axvline(theta_max, color="k", ls=":", lw=0.8,
               label=f"directions of the maxima in the plane, {theta_max:.1f}°"
               + (f" and {theta_other:.1f}°" if theta_other is not None else ""))
    if theta_other is not None:
        ax.axvline(theta_other, color="k", ls=":", lw=0.8)
    q = data["quantities"]["h_cr"]
    pr = data["params"]
    ax.set_title(f"Localization, Drucker–Prager: G = {pr['G']:g} Pa, ν = {pr['nu']:g}, "
                 f"μ = {pr['mu_f']:g}, β = {pr['beta']:g}, N = {pr['N']:g}\n(N: intermediate "
                 "principal deviatoric stress / equivalent shear stress, Rudnicki–Rice)\n"
                 f"$h_{{cr}}$ = max $-$ Q:E[P] = {q['value']:.6f} Pa "
                 f"(Rudnicki–Rice: {q['independent']:.6f} Pa)", fontsize=8)
    ax.set_xlabel(r"angle of n from the $\sigma_1$ axis [deg]")
    ax.set_ylabel(r"$g^E_{cr}(n)$ [Pa]")
    # under the axes: inside, it hid the curve's rising branch (a figure review)
    # one entry a row: in two columns it was wider than the axes (a figure review)
    ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.17), ncol=1)
    return fig


def plot_flutter_map(data: dict[str, Any]) -> Figure:
    """(a) flutter region over directions and g; (b) flutter triggered by elastic anisotropy,
    zoomed on the directions that flutter; (c) their fraction against the anisotropy."""
    th = np.degrees(data["theta"])
    # 11.4 in wide, texts >= 7 pt: legible with the figure 1200 px wide (the figure check)
    fig, (ax1, ax2, ax3) = plt.subplots(1, 3, figsize=(11.4, 3.9), layout="constrained",
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
    ax1.set_title("(a) nonassociative case: directions that flutter\n"
                  "($g_1$, $g_2$ from eq. (188) corrected)", fontsize=8)
    ax1.legend(fontsize=7)
    an = data["anisotropy"]
    off = np.array(an["offsets_deg"])
    step = off[1] - off[0]
    maps = [np.array(m, dtype=bool) for m in an["maps"]]
    # Each direction (a cell of the tangent-plane grid around the coalescence direction n_C)
    # coloured by the smallest anisotropy at which it flutters.
    levels = [k for k, m in enumerate(maps) if m.any()]
    # Distinct colours, one per anisotropy level (a sequential map made neighbours alike).
    palette = ["#d62728", "#1f77b4", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b", "#e377c2"]
    shown = np.zeros_like(maps[0])
    for n, k in enumerate(levels):
        new_cells = maps[k] & ~shown
        shown |= maps[k]
        r, c = np.nonzero(new_cells)
        colour = palette[n % len(palette)]
        for rr, cc in zip(r, c, strict=True):
            ax2.add_patch(plt.Rectangle((off[cc] - step / 2, off[rr] - step / 2), step, step,
                                        color=colour, lw=0))
        ax2.plot([], [], "s", color=colour, ms=6, label=f"ε = {an['eps'][k]:g}")
    ax2.set_axisbelow(True)  # the grid under the cells (it crossed them)
    # an open ring, not a cross: the cross hid the cell at n_C itself (an outside review)
    ax2.plot(0, 0, "o", mfc="none", mec="k", mew=0.9, ms=9,
             label=r"coalescence direction $n_C$")
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
    # (a cell's colour: the smallest ε at which it flutters; it need not at every larger ε,
    # so the colours do not add up to (c)'s count; a review)
    ax2.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.2), ncol=2,
               title=f"cells ({step:g}° grid), by the smallest ε at which they flutter",
               title_fontsize=7)
    seed = data.get("params", {}).get("anisotropy", {}).get("seed")
    # (the zoom on the flutter cells of the ±off[-1] patch that (c) counts: said, as a review
    # read the two as contradicting each other)
    ax2.set_title("(b) Drucker–Prager at coalescence, elastic anisotropy ε\n(random "
                  "perturbation" + (f", seed {seed}" if seed is not None else "")
                  + f"); zoomed on the flutter cells\nof the ±{off[-1]:g}° patch that (c) counts",
                  fontsize=8)
    ax3.plot(an["eps"], np.array(an["fraction_flutter"]) * 100, "o-", ms=3.5, color="C3")
    ax3.set_xlabel("elastic anisotropy ε [-]")
    ax3.set_ylabel("directions that flutter [%]")
    ax3.set_title(f"(c) flutter appears with anisotropy\n(share of the ±{off[-1]:g}° patch)",
                  fontsize=8)
    params = data.get("params", {})
    lines = []
    text = _case_text(params.get("plane_case", {}))
    if text:
        lines.append(f"(a): {text}, n in the $(e_1, e_3)$ plane")
    dp = params.get("anisotropy", {})
    if {"lam", "mu", "sigma", "friction_deg", "dilatancy_deg"} <= set(dp):
        # (b), (c) have their own material (a fresh-eyes review: only (a)'s was given)
        sig = ", ".join(f"{x:g}" for x in dp["sigma"])
        lines.append(f"(b), (c): Drucker–Prager, λ = {dp['lam']:g} Pa, μ = {dp['mu']:g} Pa, "
                     f"stress diag({sig}) Pa, friction angle {dp['friction_deg']:g}°, "
                     f"dilatancy angle {dp['dilatancy_deg']:g}°")
    if lines:
        fig.suptitle("\n".join(lines), fontsize=7.5)
    return fig
