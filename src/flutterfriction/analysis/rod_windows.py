"""Repairs of the FE twin's regime boundaries on the exact eq. (118): where the twin's error
(~1e-3 relative) changes the order of two nearby changes of regime, or closes a window that
eq. (118) still has open. Each repair takes the exact boundaries found so far and returns
them corrected (:func:`flutterfriction.analysis.rod.critical_loads` applies them in turn):

- a narrow window, or a boundary whose two-variable Newton fails: the zeros of its pair's
  gap (:func:`_boundaries_by_gap`);
- two ends of different pairs that come out reversed (:func:`_drop_reversed_windows`);
- a window between two changes that change no regime on the twin
  (:func:`_windows_between_two_pairs`);
- a boundary with another pair's silent change next to it (:func:`_changes_next_to_boundaries`);
- a window where the twin only nearly changes regime (:func:`_windows_at_near_misses`).

Each was found by an outside review, named in its docstring with the rod where it mattered.
"""

from __future__ import annotations

import math

import numpy as np

from flutterfriction.analysis.rod_exact import (
    _closest_pair_index,
    _damped_divergence,
    _damped_flutter,
    _exact_regime,
    _undamped_double_root,
)
from flutterfriction.analysis.rod_gap import gap_roots
from flutterfriction.analysis.rod_scan import (
    LAST_INTERVAL_RTOL,
    _Boundary,
    _fe_boundary,
    _FEScan,
)
from flutterfriction.analysis.stability import Regime
from flutterfriction.errors import ConvergenceError
from flutterfriction.models.rod import RodGroups

#: Half-width of the search for a failed boundary's exact zeros of its pair's gap, relative
#: to p: 2.6x the FE twin's largest measured boundary error (7.6e-4, see SCAN_BEYOND).
GAP_SEARCH_RTOL = 2e-3
#: A near miss of the FE twin (see :attr:`_FEScan.near_misses`) is "close" below this value of
#: its indicator (measured: 1e-5 at tan(alpha) = 0.982349, where eq. 118 has a window 0.018
#: wide; ordinary extrema 7e-4 and above) and then probed at these relative offsets.
NEAR_MISS_CLOSE, NEAR_MISS_PROBES = 1e-3, (1e-4, 3e-4, 1e-3)


def _exact_boundary(g: RodGroups, b: _Boundary) -> tuple[float, float]:
    if not g.damped:
        p, mu = _undamped_double_root(g, b.p, b.guess)
        return p, float(np.sqrt(abs(mu)))
    if b.kind == "crossing":
        return _damped_flutter(g, b.p, b.guess)
    return _damped_divergence(g, b.p, b.guess)


def _same_pair_near(a: _Boundary, b: _Boundary) -> bool:
    """Two FE coalescences (double real roots) within ``2 GAP_SEARCH_RTOL p`` of each other
    whose double roots are within 5 %: the two ends of one pair's narrow window."""
    return (a.kind == b.kind == "coalescence" and b.p - a.p <= 2 * GAP_SEARCH_RTOL * max(
        1.0, a.p)
            and abs(b.guess - a.guess) <= 0.05 * max(1.0, abs(a.guess)))


def _boundaries_by_gap(g: RodGroups, bounds: list[_Boundary], i: int, error: Exception
                       ) -> tuple[list[_Boundary], int]:
    """The exact boundaries replacing FE coalescence ``i`` (whose two-variable Newton
    failed) and the FE boundaries of the same pair next to it, from the zeros of the pair's
    gap (:func:`flutterfriction.analysis.rod_gap.gap_roots`) within
    :data:`GAP_SEARCH_RTOL` of them; and how many FE boundaries they replace.

    Where a window opens or closes along tan(alpha), the two-variable Newton on (p, mu) (or
    (p, omega~), damped) meets
    a singular Jacobian (the two ends merge) and the coarse twin's window is not eq. (118)'s;
    the gap's zeros stay simple. As many zeros as FE boundaries: those, with the twin's
    regimes; none where the twin's window has no exact counterpart (the regimes on both
    sides agree): the twin's window is dropped. Anything else re-raises ``error``."""
    first = bounds[i]
    radius = GAP_SEARCH_RTOL * max(1.0, first.p)
    cluster = [first]
    for b in bounds[i + 1:]:
        if not _same_pair_near(cluster[-1], b):
            break
        cluster.append(b)
    # undamped in mu = omega~^2 (omega = sqrt|mu|); damped in omega~ (its double real root)
    variable = "omega" if g.damped else "mu"
    try:
        roots = gap_roots(g, max(0.0, first.p - radius), cluster[-1].p + radius, first.guess,
                          variable=variable)
    except ConvergenceError:
        raise error from None
    if len(roots) == len(cluster):
        return [_Boundary(p, mu if g.damped else math.sqrt(abs(mu)), b.before, b.after,
                          "coalescence", mu)
                for (p, mu), b in zip(roots, cluster, strict=True)], len(cluster)
    if not roots and cluster[0].before == cluster[-1].after and len(cluster) % 2 == 0:
        return [], len(cluster)
    raise error


def _regime_below(boundaries: list[_Boundary], first: Regime, p: float) -> Regime:
    """The regime just below load ``p`` given the sorted ``boundaries`` and the regime at 0."""
    regime = first
    for b in boundaries:
        if b.p < p:
            regime = b.after
    return regime


def _drop_reversed_windows(exact: list[_Boundary]) -> list[_Boundary]:
    """``exact`` without the windows whose exact ends came out reversed: two changes of
    regime of different pairs (pair A turns real at ``a``, pair B complex at ``b``; the FE twin
    has ``a < b``, a window) whose exact loads are ``b < a``: on eq. (118) one of the pairs is
    complex at every load, so the regime outside the twin's window (the same on both sides)
    holds throughout (an outside review: tan(alpha) = 0.2595186 near p = 111.6706 was refused
    as "boundaries not ordered")."""
    out: list[_Boundary] = []
    for b in exact:
        if out and b.p <= out[-1].p and out[-1].before == b.after:
            out.pop()
            continue
        out.append(b)
    return out


def _windows_between_two_pairs(g: RodGroups, scan: _FEScan, exact: list[_Boundary],
                               first: Regime, p_max: float) -> list[_Boundary]:
    """``exact`` with the windows bounded by two different pairs that the FE twin misses.
    Pair A turning real at ``a`` and pair B turning complex at ``b`` change no regime on the
    twin when its ``b < a`` (one pair is always complex: flutter), while eq. (118) may have
    ``a < b`` and a divergence window between (an outside review: tan(alpha) = 0.2265,
    [273.1953, 273.3266] missed, the twin's error ~0.2 there). Damped, the same with B's
    crossing of the imaginary axis (an outside review: tan(alpha) = 0.2769, eta = 1e-5,
    gamma = 0.05, divergence on [108.1197, 108.1375] missed). Every two such silent changes
    of the twin within ``2 GAP_SEARCH_RTOL p`` of each other are solved on eq. (118) and the
    regime between their exact loads checked at its middle. Every change the scan saw counts,
    up to ``p_max (1 + SCAN_BEYOND)``: the twin's may lie beyond ``p_max`` where eq. (118)'s
    lie below it (an outside review: tan(alpha) = 0.3014, the window [785.2847, 785.3162]
    whose twin is at 785.64 was missed for p_max 785.32-785.6); a window open at ``p_max``
    changes the regime at its first end only."""
    events = list(scan.silent_events)
    top = p_max * (1 - LAST_INTERVAL_RTOL)
    out = list(exact)
    for e1, e2 in zip(events, events[1:], strict=False):
        if e2.a - e1.b > 2 * GAP_SEARCH_RTOL * max(1.0, e1.b):
            continue
        try:
            fe = [_fe_boundary(scan, e) for e in (e1, e2)]
            roots = sorted((*_exact_boundary(g, b), b) for b in fe)
        except ConvergenceError:
            continue  # (the regime checks below still see what lies there)
        (lo, w_lo, b_lo), (hi, w_hi, b_hi) = roots
        if not (0.0 < lo < hi and lo < top) or any(lo <= b.p <= hi for b in out):
            continue
        outside = _regime_below(out, first, lo)
        try:
            inside = _exact_regime(0.5 * (lo + min(hi, p_max)), g)
        except ConvergenceError:
            continue  # no verdict between them: as before, the interval checks decide
        if inside is None or inside == outside:
            continue
        out.append(_Boundary(lo, w_lo, outside, inside, b_lo.kind, b_lo.guess))
        if hi < top:  # (else the window is open at p_max)
            out.append(_Boundary(hi, w_hi, inside, outside, b_hi.kind, b_hi.guess))
        out.sort(key=lambda b: b.p)
    return out


def _changes_next_to_boundaries(g: RodGroups, scan: _FEScan, exact: list[_Boundary],
                                first: Regime, p_max: float) -> list[_Boundary]:
    """``exact`` with the change of regime moved or added where a silent change of the FE
    twin (another pair's, changing no regime there) lies next to a boundary and eq. (118) has
    the two in the other order. Pair B crossing at ``b`` (divergence -> flutter on the twin)
    and pair A turning complex at ``a``: with ``a < b`` on eq. (118) the flutter starts at
    ``a`` (an outside review: tan(alpha) = 0.7141, eta = 1e-2, gamma = 1, p_max 300 reported
    divergence up to 250.0927 where eq. 118 flutters from 250.0586; also tan(alpha) = 1.42,
    eta = 3e-3, gamma = 0.5 at p ~ 483.2, and undamped 0.252937 at p ~ 287.04). Each silent
    change within ``2 GAP_SEARCH_RTOL p`` of a boundary is solved on eq. (118), the regime
    between it and the boundary checked at the middle, and the boundaries on either side of
    that piece kept only where the regime changes."""
    out = list(exact)
    for e in scan.silent_events:  # (beyond p_max too: eq. 118's load may lie below it)
        radius = 2 * GAP_SEARCH_RTOL * max(1.0, e.a)
        near = [k for k, b in enumerate(out) if abs(b.p - e.a) <= radius]
        if len(near) != 1:
            continue  # none, or a cluster: the pairings above and the checks below decide
        k = near[0]
        b = out[k]
        try:
            fe = _fe_boundary(scan, e)
            s_p, s_omega = _exact_boundary(g, fe)
        except ConvergenceError:
            continue
        if not 0.0 < s_p < p_max * (1 - LAST_INTERVAL_RTOL) \
                or abs(s_p - b.p) <= 1e-9 * max(1.0, b.p):
            continue
        lo, hi = min(s_p, b.p), max(s_p, b.p)
        if any(lo < c.p < hi for c in out):
            continue
        try:
            middle = _exact_regime(0.5 * (lo + hi), g)
        except ConvergenceError:
            continue
        if middle is None:
            continue
        left, right = (b.before, b.after)
        if s_p < b.p:  # [s_p, b.p] was claimed b.before
            new = [_Boundary(s_p, s_omega, left, middle, fe.kind, fe.guess),
                   _Boundary(b.p, b.omega, middle, right, b.kind, b.guess)]
        else:  # [b.p, s_p] was claimed b.after
            new = [_Boundary(b.p, b.omega, left, middle, b.kind, b.guess),
                   _Boundary(s_p, s_omega, middle, right, fe.kind, fe.guess)]
        out[k:k + 1] = [c for c in new if c.before != c.after]
    return out


def _windows_at_near_misses(g: RodGroups, scan: _FEScan, exact: list[_Boundary],
                            first: Regime, p_max: float) -> list[_Boundary]:
    """``exact`` with the windows eq. (118) opens where the FE twin only nearly changed
    regime (its near misses closer than :data:`NEAR_MISS_CLOSE`): a window the twin has just
    closed along tan(alpha) (within its error) is still open on eq. (118) there. Each such
    near miss's pair (undamped in ``mu = omega~^2``; damped, the nearest pair on or right of
    the imaginary axis, in ``omega~``) is followed on its gap within :data:`GAP_SEARCH_RTOL`
    of it; two zeros are a window, its regime decided on eq. (118) at its middle. Near misses
    beyond ``p_max`` count (the scan's, up to ``p_max (1 + SCAN_BEYOND)``: eq. 118's window
    may lie below it), and one zero where the search reaches ``p_max`` is a window open
    there."""
    out = list(exact)
    top = p_max * (1 - LAST_INTERVAL_RTOL)
    for p_nm, v in scan.near_misses:
        radius = GAP_SEARCH_RTOL * max(1.0, p_nm)
        if v >= NEAR_MISS_CLOSE or p_nm - radius >= p_max:
            continue
        if not g.damped:
            z = -scan.spectra(np.array([p_nm]))[0]  # mu = -Omega^2, the pencil's
        else:  # omega~ of the first-order spectrum, on or right of the imaginary axis
            z = scan.spectra(np.array([p_nm]))[0]
            z = z[z.real > -1e-9 * np.max(np.abs(z))]
            if z.size < 2:
                continue
        i, j = _closest_pair_index(z)
        if abs(z[i] - z[j]) > 0.05 * (abs(z[i]) + abs(z[j])):
            continue  # no pair about to coalesce on the real axis here (the twin's error ~1e-3)
        try:
            roots = gap_roots(g, max(0.0, p_nm - radius), min(p_max, p_nm + radius),
                              float(0.5 * (z[i] + z[j]).real),
                              variable="omega" if g.damped else "mu")
        except ConvergenceError:
            continue  # unresolved here: the near-miss regime check below decides, or refuses
        # (a zero that is a boundary already solved, within its round-off, is that one; one
        # within LAST_INTERVAL_RTOL of p_max is not reported)
        roots = [(p, m) for p, m in roots if p < top
                 and all(abs(p - b.p) > 1e-9 * max(1.0, p) for b in out)]
        if not roots:
            continue
        open_at_top = len(roots) == 1 and p_nm + radius > top
        if len(roots) != 2 and not open_at_top:
            raise ConvergenceError(f"{len(roots)} changes of regime of eq. (118) near "
                                   f"p = {p_nm:.6g}, where the FE twin has none")
        (p1, m1), (p2, m2) = roots[0], roots[-1]
        end = p_max if open_at_top else p2
        if any(p1 < b.p < end for b in out):
            raise ConvergenceError(f"a window of eq. (118) near p = {p_nm:.6g} that the FE "
                                   "twin has closed straddles another change of regime")
        outside = _regime_below(out, first, p1)
        inside = _exact_regime(0.5 * (p1 + end), g)
        if inside is None:
            raise ConvergenceError(f"no exact regime inside the window [{p1:.10g}, {end:.10g}]"
                                   " of eq. (118) that the FE twin has closed")
        if inside == outside:  # another pair keeps the regime: no change
            continue
        w1, w2 = (m1, m2) if g.damped else (math.sqrt(abs(m1)), math.sqrt(abs(m2)))
        out.append(_Boundary(p1, w1, outside, inside, "coalescence", m1))
        if not open_at_top:
            out.append(_Boundary(p2, w2, inside, outside, "coalescence", m2))
        out.sort(key=lambda b: b.p)
    return out
