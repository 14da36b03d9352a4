"""Critical loads and regime intervals of the Beck/Pflüger rod (chapter §2.7), exact on the
characteristic function eq. (118), and its eigenvalue branches (Figs. 11, 12).

:func:`critical_loads` runs three steps, each in its own module:

1. the FE twin's regime scan along the load brackets every change of regime
   (:mod:`flutterfriction.analysis.rod_scan`);
2. each change is solved exactly on eq. (118) by Newton on the critical condition itself
   (:mod:`flutterfriction.analysis.rod_exact`), and the boundaries are repaired where the
   twin's error changed their order or closed a window
   (:mod:`flutterfriction.analysis.rod_windows`);
3. the regime of every interval is checked on eq. (118)'s exact roots.

:func:`fe_critical_loads` is the FE model's own answer, the independent method.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass

import numpy as np
from numpy.typing import NDArray
from scipy.optimize import linear_sum_assignment

from flutterfriction.analysis.rod_exact import (
    MAX_ELEMENTS,
    _check_mesh,
    _damped_divergence,
    _damped_flutter,
    _damping,
    _exact_regime,
    _undamped_double_root,
    check_groups,
    coupled_roots,
    eigenvalues,
    eigenvalues_along,
    fe_eigenvalues,
    refine_eigenvalues,
)
from flutterfriction.analysis.rod_scan import (
    LAST_INTERVAL_RTOL,
    P_MAX_LIMIT,
    SCAN_BEYOND,
    SCAN_POINTS_MAX,
    SCAN_STEP,
    _Boundary,
    _fe_scan,
    _modes_coupled,
    _scan_elements,
)
from flutterfriction.analysis.rod_windows import (
    GAP_SEARCH_RTOL,
    NEAR_MISS_CLOSE,
    NEAR_MISS_PROBES,
    _boundaries_by_gap,
    _changes_next_to_boundaries,
    _drop_reversed_windows,
    _exact_boundary,
    _same_pair_near,
    _windows_at_near_misses,
    _windows_between_two_pairs,
)
from flutterfriction.analysis.stability import Regime
from flutterfriction.errors import (
    ConvergenceError,
    ParameterError,
    check_finite_reals,
    check_positive,
    check_real,
)
from flutterfriction.models.rod import GROUP_RANGES, Rod, RodGroups

#: The rod solver's public names (the helpers of eq. 118 and the scan's range live in
#: rod_exact and rod_scan; they are public here too, where the callers have always found them).
__all__ = [
    "DAMPING_FLOOR", "GROUP_RANGES", "LAST_INTERVAL_RTOL", "MAX_BRANCH_LOADS", "MAX_ELEMENTS",
    "P_MAX_LIMIT", "REGIME_CHECK_POINTS", "SCAN_STEP", "RodCriticalLoads", "branches",
    "check_groups", "continue_critical_loads", "critical_loads", "eigenvalues",
    "eigenvalues_along", "fastest_mode",
    "fe_critical_loads", "fe_eigenvalues", "refine_eigenvalues",
]


@dataclass(frozen=True)
class RodCriticalLoads:
    """Dimensionless critical loads ``p = P l^2/B`` and pulsations ``omega~`` (eq. 106, 108);
    ``None`` where the load does not exist in the searched range (Beck: no divergence). From
    :func:`continue_critical_loads` ``None`` means only "not followed": the previous rod had
    no such load, and one may have appeared (``intervals`` is then ``None`` too).

    ``p_flu``/``p_div`` are the starts of the first flutter/divergence intervals; ``intervals``
    lists every regime interval on [0, p_max] as ``{"regime", "p_from", "p_to"}`` (``None``
    from :func:`continue_critical_loads`, which follows two loads only)."""

    p_flu: float | None
    omega_flu: float | None  # Im omega~ at flutter (the oscillation's pulsation)
    p_div: float | None
    omega_div: float | None  # Re omega~ of the double real root at divergence
    intervals: list[dict] | None = None

    def as_dict(self) -> dict:
        return asdict(self)


#: Damping (max(eta, gamma)) below which the FE bracketing scan is run at this damping instead
#: (same eta:gamma ratio; the exact Newton solves and the final regime checks use the true
#: one). Where it comes from: the FE eigensolver resolves growth rates down to
#: ~1e3 eps max|s| ~ 1e-9; at 1e-6 the growth rates of the low modes (~1e-6 |s1|, |s1| >= 1e-2)
#: are >= 10x above that. Below it the loads are within O(1e-6) of their vanishing-damping
#: limits, a start Newton converges from.
DAMPING_FLOOR = 1e-6
#: Where each interval's claimed regime is checked against the exact roots of eq. (118), as
#: fractions of the interval (the midpoint first, as before; then both sides).
REGIME_CHECK_POINTS = (0.5, 0.125, 0.25, 0.375, 0.625, 0.75, 0.875)


def _intervals(boundaries: list, first: Regime, p_max: float) -> list[dict]:
    out, start, regime = [], 0.0, first
    for b in boundaries:
        out.append({"regime": str(regime), "p_from": start, "p_to": b.p})
        start, regime = b.p, b.after
    out.append({"regime": str(regime), "p_from": start, "p_to": float(p_max)})
    return out


def _check_p_max(p_max: float) -> float:
    p_max = check_positive("p_max", p_max)
    if p_max > P_MAX_LIMIT:
        raise ParameterError(f"p_max must be in (0, {P_MAX_LIMIT:g}] (the regime scan's range, "
                             f"see analysis.rod.P_MAX_LIMIT), got {p_max!r}")
    return p_max


def _check_step(step: float, p_max: float) -> float:
    step = check_positive("step", step)
    # (the points' count to 1e-12: 30/0.0003 is 100000.00000000001 in doubles, and an outside
    # audit saw "step must be in [0.0003, ...], got 0.0003")
    if step > SCAN_STEP or p_max / step > SCAN_POINTS_MAX * (1.0 + 1e-12):
        raise ParameterError(f"step must be in [p_max/{SCAN_POINTS_MAX:g}, {SCAN_STEP:g}] = "
                             f"[{p_max / SCAN_POINTS_MAX:g}, {SCAN_STEP:g}] (the scan's "
                             f"guarantee and size), got {step!r}")
    return step


def _loads_from(intervals: list[dict], omegas: dict[float, float]) -> dict:
    out: dict = {"p_flu": None, "omega_flu": None, "p_div": None, "omega_div": None}
    for iv in intervals:
        if iv["p_from"] == 0.0:
            continue
        if iv["regime"] == Regime.FLUTTER and out["p_flu"] is None:
            out.update(p_flu=iv["p_from"], omega_flu=omegas[iv["p_from"]])
        if iv["regime"] == Regime.DIVERGENCE and out["p_div"] is None:
            out.update(p_div=iv["p_from"], omega_div=omegas[iv["p_from"]])
    return out


def fe_critical_loads(g: RodGroups, n_elements: int, p_max: float = 80.0,
                      step: float = SCAN_STEP) -> RodCriticalLoads:
    """Critical loads and regime intervals of the FE model (the independent method).

    The FE spectrum's signature (undamped: complex and negative ``Omega^2`` of the pencil,
    eq. 14 form; damped: unstable complex and real roots ``s``) is scanned on [0, p_max] with a
    step <= ``step``, every change is bisected and polished with Brent's method (coalescence:
    a pair's squared difference; damped flutter: the pair's growth rate), and windows between
    two scan points are caught by minimising the indicators of
    :class:`~flutterfriction.analysis.rod_scan._FEScan`. Damped: the scan runs on the modal
    reduction to the modes the load couples and each boundary is polished on the full model.
    Parameters as :func:`critical_loads` (``n_elements`` required); the loads are the FE
    model's, not eq. (118)'s.

    Accuracy of a damped flutter load: it is where a growth rate of order ``eta`` crosses
    zero. Located on the first-order spectrum, whose round-off grows with the stiffest element
    mode, it stalled at that round-off: 2.3e-6 relative at ``eta = 1e-6`` on 80 elements, and
    at list (119)'s ``eta = 1.36e-3`` (Beck rod) 3e-9 on 48 elements, 1.3e-7 on 96, 1.8e-6 on
    128 (an outside audit): a finer mesh was less accurate. Each crossing is therefore
    polished by Newton on the quadratic eigenproblem
    (:func:`~flutterfriction.analysis.damped.polish_flutter_crossing`), whose own round-off is
    ~1e-10 at 48 elements and up to ~1e-8 at 96-128 (an outside audit: 3-8e-9). Measured
    against the exact load: tan(alpha) 0, 1, 4.59, p_max 40, ``eta`` 1e-6 ... 1e-4: 4.8e-7
    on 20 elements, 3.0e-8 on 40, <= 1.6e-9 on 80 (the mesh's h^4 error); list (119): 7e-10
    on 48 elements, <= 3.4e-9 on 64-128; the Beck rod with ``gamma = 1e-6`` (a crossing just
    past a coalescence): h^4 from 1.3e-7 on 48 elements to 8e-9 on 96. Where Newton cannot
    confirm the crossing the spectrum's load stands, with its round-off. For small damping
    use :func:`critical_loads` (exact at any damping); this function is its independent
    check."""
    p_max = _check_p_max(p_max)
    step = _check_step(step, p_max)
    check_groups(g)
    _check_mesh(n_elements)  # (500 elements scanned for minutes; an outside audit)
    if g.damped and _damping(g) < DAMPING_FLOOR:
        # Below the floor the crossing's growth rate is round-off of the FE spectrum (measured
        # by an outside audit: 9.808 for the exact 10.93885 at eta = 1e-12, no convergence with
        # the mesh, and no end at eta = 1e-20): refused, never answered.
        raise ParameterError(
            f"fe_critical_loads: the damping max(eta, gamma) = {_damping(g):.3g} must be 0 or "
            f">= {DAMPING_FLOOR:g} (below, the FE spectrum cannot resolve the crossing); "
            f"critical_loads solves eq. (118) exactly at any damping")
    # Damped: scanned on the modal reduction (fast), each boundary polished on the full model.
    n_modes = _modes_coupled(p_max) if g.damped else None
    _, first, bounds = _fe_scan(g, n_elements, p_max, step, n_modes, polish_full=True)
    intervals = _intervals(bounds, first, p_max)
    out = _loads_from(intervals, {b.p: b.omega for b in bounds})
    return RodCriticalLoads(**out, intervals=intervals)


def critical_loads(g: RodGroups, p_max: float = 80.0, n_elements: int | None = None,
                   step: float = SCAN_STEP) -> RodCriticalLoads:
    """Exact critical loads (eq. 118) to ~1e-13 and every regime interval on [0, p_max].

    The regime changes are bracketed on the FE twin (:func:`fe_critical_loads`; scan step
    <= ``step`` whatever ``p_max``, ``n_elements`` default :func:`_scan_elements`) and each is
    solved exactly by Newton on eq. (118) (double root, eqs. 117-118 with df/domega~ = 0, or a
    root on the imaginary axis). Below :data:`DAMPING_FLOOR` the FE scan runs at that damping
    and Newton at the true one. Finally the regime of every interval is checked on the exact
    roots at its midpoint; any disagreement raises :class:`ConvergenceError`.

    Guarantee: every regime interval wider than ``step`` (0.25 by default, whatever
    ``p_max``) is found with both its ends (it contains a scan point). Narrower ones are found
    when an indicator of :class:`~flutterfriction.analysis.rod_scan._FEScan` has a sampled
    local minimum at a neighbouring scan point (always, if the coalescing pair's gap varies
    on a scale longer than ``step``;
    measured: the divergence window opening at tan(alpha) = 0.593251 is found from 0.07
    wide, on 12 and on 40 elements). The scan runs to ``p_max (1 + SCAN_BEYOND)``, so a
    boundary just below ``p_max`` whose FE twin lies just beyond it is kept (unless it lies
    within ``LAST_INTERVAL_RTOL p_max`` of ``p_max``: then the regime below it is reported up
    to ``p_max``). A narrow window of a pair coalescing on the real axis (undamped, in
    ``mu = omega~^2``; damped, a divergence window's double real ``omega~``; its two FE ends
    within ``2 GAP_SEARCH_RTOL p`` of each other), and any such boundary whose two-variable
    Newton fails, are solved instead as the zeros of the coalescing pair's gap
    (:mod:`flutterfriction.analysis.rod_gap`; one variable, simple zeros): next to a window's
    opening or closing along tan(alpha) the two ends merge, the Newton on (p, mu) meets a
    singular Jacobian (it failed, or converged to the other end: an outside review,
    tan(alpha) = 0.55278551 at p ~ 641.39; refused at 0.59325 with eta = 1e-6), and the
    coarse twin's window is not eq. (118)'s (the gap then has no zero: the twin's window is
    dropped). Undamped, a window the FE twin has
    already closed (at tan(alpha) = 0.98229-0.98235 a flutter window near p = 69.7, 12
    elements; an outside audit) leaves the twin a near miss, an indicator's extremum without
    a change of signature: where it comes within :data:`NEAR_MISS_CLOSE` of coalescing, the
    pair's gap is followed there too and a window it finds is added; the exact regime is
    also checked at every near miss (and at :data:`NEAR_MISS_PROBES` on either side), and a
    disagreement, or no verdict there, sends the scan to the finer twin below, and a second
    failure is refused. Undamped, a divergence window bounded by two different pairs (one
    turning real, the other complex) that the twin misses, its two changes falling in the
    other order or within one scan step (an outside review: tan(alpha) = 0.2265, [273.1953,
    273.3266]), is found by solving every two such nearby coalescences on eq. (118) and
    checking the regime between; two such ends reversed on eq. (118) drop the twin's window
    (tan(alpha) = 0.2595186 near p = 111.6706 was refused); damped, the same with a pair's
    crossing of the imaginary axis as one end (tan(alpha) = 0.2769, eta = 1e-5,
    gamma = 0.05: divergence on [108.1197, 108.1375] was missed); and a boundary with
    another pair's silent change next to it is moved to where eq. (118) has the first of the
    two (tan(alpha) = 0.7141, eta = 1e-2, gamma = 1: flutter from 250.0586, reported from
    250.0927). The twin's changes and near misses beyond ``p_max`` (up to
    ``p_max (1 + SCAN_BEYOND)``) count too, and a window open at ``p_max`` ends there
    (tan(alpha) = 0.3014: divergence on [785.2847, 785.3162] was missed for p_max
    785.32-785.6; 0.982349: flutter on [69.6591, 69.6781] for p_max 69.665-69.68); the
    exact regime at a load decides a pair by its gap also where a root's Newton left its
    guess's basin (two FE guesses of a pair the twin has real and eq. 118 complex converge
    to one real root). Measured at p_max 80, without a
    refusal: the first divergence window
    of the Pflüger column on a 1e-10 grid of tan(alpha) through its opening at 0.5932502122
    (0.0009 wide 3e-10 past it), the flutter window near p = 69.7 on a 1e-7 grid through its
    closing at ~0.9823494 (0.011 wide at 0.9823492); damped (eta = 1.48e-4, gamma = 0.225)
    a flutter window near p = 208.4 down to 0.012 wide at tan(alpha) = 1.528407, where the
    FE twin's stays ~1 wide (refused before from 1.5284); the ends agree with eq. (118)'s
    double roots at 40 digits to 1e-12 (``tests/test_rod.py``). Not guaranteed, then: a window
    narrower than its gap's round-off resolves (refused, naming the load).

    Parameters
    ----------
    g : RodGroups
        ``tan(alpha)``, ``eta``, ``gamma`` of eq. (106), within :data:`GROUP_RANGES`.
    p_max : float
        Largest load ``p = P l^2/B`` searched, in (0, :data:`P_MAX_LIMIT`].
    n_elements : int, optional
        FE elements of the bracketing scan: default, and at least, :func:`_scan_elements`
        (``max(12, ceil(1.25 sqrt(p_max)))``: a coarser twin dropped whole intervals without
        a refusal; an outside audit), at most :data:`MAX_ELEMENTS`. The scan's cost grows as
        ``n_elements^3 p_max / step``: measured (2026-12-06, one core) 24 s for 200 elements
        to p = 80 and 230 s for 200 elements to p = 1000; the default mesh 0.1-0.2 s to
        p = 80, 2.5-5 s to p = 1000.
    step : float
        Largest step of the scan, in [p_max/:data:`SCAN_POINTS_MAX`, :data:`SCAN_STEP`]
        (p_max/1e5 to 0.25); the cost grows as ``1/step``.

    Returns
    -------
    RodCriticalLoads
        First flutter and divergence loads (``None`` if absent up to ``p_max``), their
        pulsations, and ``intervals``: every ``{"regime", "p_from", "p_to"}`` on [0, p_max].

    Raises
    ------
    ParameterError
        A parameter outside its range (the message names it and the range).
    ConvergenceError
        A Newton solve failed or the exact regime check contradicts the FE bracketing.
    """
    p_max = _check_p_max(p_max)
    step = _check_step(step, p_max)
    check_groups(g)
    if n_elements is not None:  # (10**9 asked numpy for 7.5 GB; an outside audit)
        _check_mesh(n_elements)
        least = _scan_elements(p_max)
        if n_elements < least:
            # a coarser twin's boundaries lie farther from eq. (118)'s than the scan's margins
            # (SCAN_BEYOND, the near-miss checks) are measured for: an outside audit found
            # whole intervals dropped without a refusal (tan(alpha) = 0.595, p_max = 100 on 3
            # elements: first divergence at 85.23 instead of 47.72)
            raise ParameterError(
                f"n_elements must be >= {least} for p_max = {p_max:g} (the default mesh, "
                f"max(12, ceil(1.25 sqrt(p_max))): the scan's accuracy is measured on meshes "
                f"no coarser), got {n_elements}")
    n_el = _scan_elements(p_max) if n_elements is None else n_elements
    delta = _damping(g)
    g_scan = g
    if g.damped and delta < DAMPING_FLOOR:
        k = DAMPING_FLOOR / delta
        g_scan = RodGroups(tan_alpha=g.tan_alpha, eta=g.eta * k, gamma=g.gamma * k)
    # Damped: the scan on the lowest modes only (see _FEScan), enough of them to hold every
    # mode the load couples (wavenumber^2 <= 3 p_max + 40, as in _exact_regime) plus 4.
    n_modes = None
    if g.damped:
        n_modes = _modes_coupled(p_max)
        n_el = max(n_el, n_modes)
    try:
        # (a failed Newton on a boundary only the extended scan sees: skipped where no finer
        # retry follows, else the retry decides, as for any failure)
        return _solve_on(g, g_scan, n_el, p_max, step, n_modes,
                         skip_failed_beyond=n_elements is not None)
    except ConvergenceError as first_error:
        if n_elements is not None:
            raise
        # Once on a 3x finer twin: a window that opens or closes within the coarse twin's
        # error (~1e-5 in tan(alpha) at p ~ 50 on 12 elements) has no exact double roots
        # where the coarse twin puts them. A second failure is reported as the first.
        # Unreduced: a Galerkin reduction of the finer twin (tried for speed: p_max 1000 at
        # tan(alpha) = 0.59325019, 51 s -> 9 s with 80 modes, 17 s with 120) opened windows
        # late, and a narrow one just past its opening was answered "no window", silently
        # (outside reviews: 40 elements to 24 modes at 0.59325025, p ~ 48.8; 120 elements to
        # 120 modes at 0.552785507, p ~ 641.4, where the unreduced twin refuses).
        # Damped: on twice the modes too (an outside review: at tan(alpha) = 1.52753,
        # eta = 1.48e-4, gamma = 0.225 the 15-mode twin lost a flutter window 0.81 wide at
        # p = 208 for p_max 260-400, kept by 14, 22 or 30 modes: the near-miss check refused
        # it; with 2x the modes the retry finds it, as p_max 220 does)
        try:
            return _solve_on(g, g_scan, max(40, 3 * n_el), p_max, step,
                             None if n_modes is None else 2 * n_modes, skip_failed_beyond=True)
        except ConvergenceError:
            raise first_error from None


def _solve_on(g: RodGroups, g_scan: RodGroups, n_el: int, p_max: float, step: float,
              n_modes: int | None, skip_failed_beyond: bool = True) -> RodCriticalLoads:
    """:func:`critical_loads` with the FE twin on ``n_el`` elements (scan at ``g_scan``)."""
    # The FE twin is scanned a little beyond p_max: an exact boundary just below p_max whose FE
    # boundary falls just beyond it would otherwise be lost, and with it the last interval
    # (an outside audit: tan(alpha) = 0 at p_max = 20.05166 ended "stable" although the exact
    # flutter load is 20.05095; the FE twin's 20.0517 lay beyond p_max).
    scan, first, bounds = _fe_scan(g_scan, n_el, p_max * (1 + SCAN_BEYOND), step, n_modes)
    exact: list[_Boundary] = []
    i = 0
    while i < len(bounds):
        b = bounds[i]
        try:
            if i + 1 < len(bounds) and _same_pair_near(b, bounds[i + 1]):
                # a narrow window: next to its opening the two-variable Newton may converge
                # to the other end (an outside review: tan(alpha) = 0.55278551, p ~ 641.39,
                # both ends 641.3928; the window is [641.3783, 641.3928])
                raise ConvergenceError(f"a window narrower than {2 * GAP_SEARCH_RTOL:g} p "
                                       f"at p = {b.p:.10g}")
            p, omega = _exact_boundary(g, b)
            solved, i = [_Boundary(p, omega, b.before, b.after, b.kind, b.guess)], i + 1
        except ConvergenceError as exc:
            if b.p > p_max and skip_failed_beyond:  # only the extended scan sees it
                break
            if b.kind != "coalescence":  # (a damped crossing: no pair on the real axis)
                raise
            # a window opening or closing within the twin's error, solved on the pair's gap
            # (one variable, simple zeros) instead
            solved, used = _boundaries_by_gap(g, bounds, i, exc)
            i += used
        # Beyond the asked range (the FE boundary may lie on either side), or so close to
        # p_max that the last interval would be a sliver narrower than the regime check
        # resolves (its check points sit on the coalescence; an outside review: p_max = the
        # exact flutter load failed): the interval below it runs to p_max.
        beyond = [s for s in solved if s.p > p_max * (1 - LAST_INTERVAL_RTOL)]
        exact += [s for s in solved if s not in beyond]
        if beyond:
            break
    exact = _drop_reversed_windows(exact)
    exact = _windows_between_two_pairs(g, scan, exact, first, p_max)
    exact = _changes_next_to_boundaries(g, scan, exact, first, p_max)
    exact = _windows_at_near_misses(g, scan, exact, first, p_max)
    ps = [0.0, *[b.p for b in exact], p_max]
    if np.any(np.diff(ps) <= 0):
        raise ConvergenceError(f"the exact regime boundaries are not ordered: {ps[1:-1]} "
                               "(two changes of regime closer than the FE twin resolves)")
    intervals = _intervals(exact, first, p_max)
    for iv in intervals:
        # Not the midpoint alone: at tan(alpha) = 0 with a small external damping gamma only,
        # the scan missed the flutter from p = 20.05 and a midpoint of [0, 40] (p = 20) found
        # the claimed "stable" true (outside audit). Seven interior points of each interval.
        # A point next to a coalescence (Newton on nearly coincident roots) gives no verdict;
        # at least one of the seven must (a narrow interval's midpoint may be that close: an
        # outside review saw p_max 1e-6 ... 1.5e-5 above a boundary fail on it alone).
        first_error: ConvergenceError | None = None
        verdicts = 0
        width = iv["p_to"] - iv["p_from"]
        # and where the FE twin nearly changed regime: a window it has just closed may be
        # open on eq. (118) there (an outside audit: tan(alpha) = 0.98232, a flutter window
        # [69.574, 69.763] reported as divergence at p_max 80, found at p_max 300)
        near = [(p, v) for p, v in scan.near_misses
                if iv["p_from"] + 1e-6 * width < p < iv["p_to"] - 1e-6 * width]
        # Where the twin comes within NEAR_MISS_CLOSE of coalescing, the exact window (if any)
        # may lie beside the twin's near miss (by its error, ~0.02 at p ~ 70 on 13 elements):
        # probed at relative offsets NEAR_MISS_PROBES on either side too (an outside review:
        # tan(alpha) = 0.982349, window [69.6597, 69.6774], near miss at 69.6853).
        probes = [p * (1 + sign * r) for p, v in near if v < NEAR_MISS_CLOSE
                  for r in NEAR_MISS_PROBES for sign in (-1.0, 1.0)]
        probes = [p for p in probes if iv["p_from"] < p < iv["p_to"]]
        checks = [iv["p_from"] + frac * width for frac in REGIME_CHECK_POINTS]
        near_at = [p for p, _ in near]
        for k, mid in enumerate(checks + near_at + probes):
            why = ("a growth rate or a coalescing pair's gap below what eq. (118)'s roots "
                   "resolve")
            try:
                r = _exact_regime(mid, g)
            except ConvergenceError as exc:
                r, why = None, str(exc)
                first_error = first_error or exc
            if r is None:  # no verdict here (an outside review: it was counted as one)
                if k >= len(checks):
                    # No verdict at a near miss (eq. 118's roots nearly coincide there): a
                    # window may open or close within the twin's error. Unresolved: the finer
                    # twin decides, or it is refused (an outside review: left alone, windows
                    # up to 0.087 wide at tan(alpha) = 0.982343-0.982349 went unreported).
                    raise ConvergenceError(
                        f"no exact regime at p = {mid:.6g}, where the FE twin nearly changes "
                        f"regime (a window within its error): {why}")
                continue
            verdicts += 1
            if r != iv["regime"]:
                raise ConvergenceError(
                    f"regime check failed at p = {mid:.6g}: the exact roots of eq. (118) give "
                    f"{r}, the FE bracketing {iv['regime']} (a change of regime the scan "
                    "missed)")
        if not verdicts:
            raise first_error or ConvergenceError(
                f"no exact regime at any of the {len(checks)} check points of the "
                f"{iv['regime']} interval [{iv['p_from']:.10g}, {iv['p_to']:.10g}]")
    out = _loads_from(intervals, {b.p: b.omega for b in exact})
    return RodCriticalLoads(**out, intervals=intervals)


def continue_critical_loads(g: RodGroups, previous: RodCriticalLoads) -> RodCriticalLoads:
    """Critical loads of ``g`` by Newton from those of a nearby rod (continuation in a
    parameter): milliseconds, no FE guess. Raises :class:`ConvergenceError` if Newton fails.

    Local: it follows the loads ``previous`` has and cannot see a new one appear. A divergence
    load absent from ``previous`` is ``None`` here even where ``g`` has one (an outside audit:
    tan(alpha) 0.5 -> 0.7 gave ``p_div = None`` for 40.4658), and a window opening below the
    followed load is missed: use :func:`critical_loads` (every interval) where the regime
    structure may change, as the stability map does."""
    check_groups(g)
    if not isinstance(previous, RodCriticalLoads):
        raise ParameterError(f"previous must be the RodCriticalLoads of a nearby rod, got "
                             f"{type(previous).__name__}")
    if previous.p_flu is None:
        raise ConvergenceError("continuation needs a previous flutter load")
    out = {"p_flu": None, "omega_flu": None, "p_div": None, "omega_div": None}
    if not g.damped:
        p, mu = _undamped_double_root(g, previous.p_flu, -previous.omega_flu**2)
        out.update(p_flu=p, omega_flu=float(np.sqrt(-mu)))
        if previous.p_div is not None:
            p, mu = _undamped_double_root(g, previous.p_div, previous.omega_div**2)
            out.update(p_div=p, omega_div=float(np.sqrt(mu)))
    else:
        out["p_flu"], out["omega_flu"] = _damped_flutter(g, previous.p_flu, previous.omega_flu)
        if previous.p_div is not None:
            out["p_div"], out["omega_div"] = _damped_divergence(g, previous.p_div,
                                                                previous.omega_div)
    if out["omega_flu"] is not None and not out["omega_flu"] > 0:
        raise ConvergenceError("continuation reached a flutter point with zero pulsation")
    return RodCriticalLoads(**out)


#: Most loads :func:`branches` continues along, in one call (~1 ms a load: a minute or two).
MAX_BRANCH_LOADS = 100_000


def branches(g: RodGroups, p_values: NDArray, n_modes: int = 2,
             n_elements: int = 16) -> NDArray:
    """Eigenvalue branches ``omega~(p)`` continued along ``p_values``, shape (len(p), 2 n_modes).

    Predictor: linear extrapolation of each branch from the two previous loads. Corrector:
    Newton on the exact eq. (118). To never jump between branches, the corrected roots are
    matched one-to-one (Hungarian assignment on the distance to the predictions) with the FE
    roots refined on eq. (118) at the same load, which are the complete set of the
    ``2 n_modes`` roots of smallest modulus.
    """
    p_values = np.atleast_1d(check_finite_reals("p_values", p_values))
    if p_values.ndim != 1 or p_values.size == 0:
        raise ParameterError(f"p_values must be a non-empty 1-d array of loads, got shape "
                             f"{p_values.shape}")
    steps = np.diff(p_values)
    if steps.size and not (np.all(steps > 0) or np.all(steps < 0)):
        # the predictor extrapolates along the loads (an outside audit: a repeated load
        # divided by zero and ended in a numpy error)
        raise ParameterError("p_values must be strictly increasing or strictly decreasing "
                             "loads (a branch is followed along them)")
    if p_values.size > MAX_BRANCH_LOADS:  # (1e7 loads ran for minutes; an outside audit)
        raise ParameterError(f"p_values must hold at most {MAX_BRANCH_LOADS} loads (~1 ms "
                             f"each), got {p_values.size}")
    # (the loads, the mesh and the groups are checked by eigenvalues_along)
    truths = eigenvalues_along(p_values, g, n_modes, n_elements)
    out = np.empty((p_values.size, 2 * n_modes), dtype=complex)
    for i, p in enumerate(p_values):
        truth = truths[i]
        if i == 0:
            out[i] = truth
            continue
        pred = out[i - 1] if i == 1 else out[i - 1] + (out[i - 1] - out[i - 2]) * (
            (p - p_values[i - 1]) / (p_values[i - 1] - p_values[i - 2]))
        cost = np.abs(pred[:, None] - truth[None, :])
        rows, cols = linear_sum_assignment(cost)
        out[i, rows] = truth[cols]
        _orient_splits(out[i], pred)
    return out


def _orient_splits(roots: NDArray, pred: NDArray) -> None:
    """Where two branches have just split from a double root (their predictions nearly
    coincide, so that swapping them costs < 10 % of their separation), order them by one rule,
    in place. A split has no continuation to follow; without a rule the colours of Fig. 12's
    branches after the flutter coalescence were set by round-off and differed between its two
    columns. In the upper half-plane and on the real axis the lower-indexed branch takes the
    root of larger real part (of larger imaginary part where the real parts agree to 1e-9 of
    the separation: a split along the imaginary axis). In the lower half-plane each branch
    takes the conjugate of its partner's root (the branches are ordered by imaginary part at
    p = 0, so the partner of column j is column ``size - 1 - j``), which keeps every mode's
    two branches conjugate (the rule itself, applied there, sent the other mode right: a
    review). Branches crossing without meeting are not ambiguous (a swap costs twice their
    separation) and keep their continuation."""
    n = roots.size
    pairs = []
    for j in range(n):
        for k in range(j + 1, n):
            a, b = roots[j], roots[k]
            gap = abs(a - b)
            kept = abs(pred[j] - a) + abs(pred[k] - b)
            swapped = abs(pred[j] - b) + abs(pred[k] - a)
            if gap > 0.0 and swapped - kept < 0.1 * gap:
                pairs.append((j, k))
    lower = [(j, k) for j, k in pairs if roots[j].imag < 0 and roots[k].imag < 0
             and min(abs(roots[j].imag), abs(roots[k].imag)) > 1e-9 * abs(roots[j] - roots[k])]
    for j, k in pairs:
        if (j, k) in lower:
            continue
        a, b = roots[j], roots[k]
        by_real = abs(b.real - a.real) > 1e-9 * abs(a - b)
        if (b.real > a.real) if by_real else (b.imag > a.imag):
            roots[j], roots[k] = b, a
    for j, k in lower:
        cj, ck = np.conj(roots[n - 1 - j]), np.conj(roots[n - 1 - k])
        if abs(roots[k] - cj) + abs(roots[j] - ck) < abs(roots[j] - cj) + abs(roots[k] - ck):
            roots[j], roots[k] = roots[k], roots[j]


def fastest_mode(rod: Rod, P: float) -> complex:
    """The exact eigenvalue (eq. 118) with the largest real part at the load ``P`` [N], in
    1/s, among the roots of every mode the load couples
    (:func:`~flutterfriction.analysis.rod_exact.coupled_roots`: wavenumber^2 up to
    3|p| + 40; the three lowest mode pairs of before missed the fastest from p ~ 100, an
    outside audit: the Beck rod at p = 124 growing at 46.05, reported 0): its real part the
    growth rate, its imaginary part the pulsation [rad/s]. ``P`` a real number within the
    solver's range, ``|P| <= P_MAX_LIMIT B/l^2`` (an outside audit: True was taken as 1 N,
    and 1e308 N was refused as "p must be finite, got inf", its overflowed dimensionless
    value)."""
    P = check_real("P", P)
    bound = P_MAX_LIMIT * rod.load_unit
    if not abs(P) <= bound:
        raise ParameterError(f"P must be in [-{bound:.6g}, {bound:.6g}] N ({P_MAX_LIMIT:g} "
                             f"B/l^2, the rod solver's range), got {P!r}")
    w = coupled_roots(P / rod.load_unit, rod.groups()) / rod.time_scale
    return complex(w[np.argmax(w.real)])
