"""The finite-element twin's regime scan along the load (chapter §2.7): where the FE model of
the rod (:mod:`flutterfriction.models.rod_fe`) changes regime, each change bracketed and
polished to the twin's own boundary (:class:`_Boundary`), its kind (a coalescence or a
crossing of the imaginary axis) and its pair's double root or pulsation: the starts of the
exact solves on eq. (118) (:mod:`flutterfriction.analysis.rod_exact`).

The scan's own record is kept for the exact repairs
(:mod:`flutterfriction.analysis.rod_windows`): the changes of the twin's spectrum that change
no regime (``silent_events``) and its near misses (an indicator's extremum next to zero
without a change of signature), where eq. (118) may have a window the twin's error closed.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray
from scipy.optimize import brentq, minimize_scalar

from flutterfriction.analysis.damped import polish_flutter_crossing
from flutterfriction.analysis.stability import Regime
from flutterfriction.errors import ConvergenceError
from flutterfriction.models.rod import RodGroups
from flutterfriction.models.rod_fe import assemble

#: Largest step of the regime scan along the load axis, independent of ``p_max``. Where the
#: number comes from: a regime interval wider than the step contains a scan point, so its
#: regime differs from a neighbour's and both its ends are bracketed and refined. 0.25 is
#: 1/9 of the narrowest interval the chapter's rods show at list (119) (the 2.3-wide divergence
#: window at tan(alpha) = 0.595) and keeps the scan at 1600 FE spectra for p_max = 400.
SCAN_STEP = 0.25
#: The bracketing scan runs to ``p_max (1 + SCAN_BEYOND)``: the FE twin's boundaries differ
#: from eq. (118)'s by <= 7.6e-4 relative (measured over 284 tip masses tan(alpha) in [0, 50],
#: p_max <= 400, on the default meshes), so an exact boundary below p_max is bracketed even
#: when the twin's lies beyond it (x13 margin; a mesh given by hand may need more).
SCAN_BEYOND = 0.01
#: A change of regime within ``LAST_INTERVAL_RTOL p_max`` below ``p_max`` is not reported: the
#: last interval would be narrower than the exact regime check resolves (its check points sit
#: on the coalescence, where Newton on eq. (118) meets nearly coincident roots; measured by
#: outside reviews: widths of 1e-8 p_max and below failed, and the midpoint alone failed up
#: to 1.5e-5 before the other check points could answer for it).
LAST_INTERVAL_RTOL = 1e-6
#: Largest load of the scan. Where it comes from: the FE mesh grows like sqrt(p_max)
#: (:func:`_scan_elements`) and the scan like p_max; at 1000 the scan takes ~2 s (25 x 40
#: elements) and the modes involved (k ~ sqrt(p) ~ 32) are still resolved to < 1e-3 by the
#: FE twin that brackets the exact Newton solves. Above it the regime count grows without
#: bound (every pair of modes flutters, then diverges) and we refuse.
P_MAX_LIMIT = 1000.0
#: Most scan points (p_max / step): ~1.2 ms each at p_max = 1000 (40 elements), so at most
#: ~2 min; 25 times the default density at any p_max.
SCAN_POINTS_MAX = 100_000
#: Relative imaginary part above which an FE eigenvalue counts as complex (and a pencil
#: eigenvalue ``Omega^2`` as a flutter pair): near a coalescence the pair splits like
#: ``sqrt(p - p_c)``, so this locates the FE coalescence to ~1e-12 relative, while round-off
#: (~1e-16 ||A||, enlarged to ~1e-8 at a defective pair) stays far below.
_COMPLEX_RTOL = 1e-6
#: Bisection width of the FE brackets, relative to p: Brent then polishes the boundary to
#: machine precision in a few steps (a smooth function with one simple zero in the bracket).
_BRACKET_RTOL = 1e-7
#: Loads per batched eigenvalue call of the scan (memory: ~26 MB at 40 elements).
_SCAN_BLOCK = 500


@dataclass(frozen=True)
class _Event:
    """A change of the FE spectrum's signature between ``a`` and ``b`` (width <= tolerance)."""

    a: float
    b: float
    before: tuple
    after: tuple


def _scan_elements(p_max: float) -> int:
    """FE elements of the bracketing scan: 12 up to p = 92, then 1.25 sqrt(p_max) (the modes
    involved at load p have wavenumber ~ sqrt(p), and cubic elements resolve them to
    ~(k h)^4)."""
    return max(12, int(math.ceil(1.25 * math.sqrt(p_max))))


class _FEScan:
    """Signature of the FE spectrum at a load and the indicators of hidden events.

    Undamped: the pencil eigenvalues ``mu = Omega^2`` (``Omega^2 < 0``: divergence, complex:
    flutter); signature ``(complex count, negative count)``. Damped: the first-order spectrum
    ``s``; signature ``(unstable complex count, unstable real count)``.
    """

    def __init__(self, g: RodGroups, n_elements: int, n_modes: int | None = None) -> None:
        self.damped = g.damped
        fe = assemble(g, n_elements)
        L = np.linalg.cholesky(fe.M)
        Linv = np.linalg.solve(L, np.eye(L.shape[0]))
        A0 = Linv @ fe.K_B @ Linv.T
        A1 = Linv @ fe.load_matrix() @ Linv.T
        C = Linv @ fe.C @ Linv.T
        if n_modes is not None and n_modes < A0.shape[0]:
            # Galerkin on the n_modes lowest unloaded modes (M-orthonormal): drops the stiff,
            # strongly damped FE modes that make the first-order eigensolver slow (a 2n x 2n
            # matrix spanning 1e8 in scale) and play no part in the low modes' regime.
            _, V = np.linalg.eigh(0.5 * (A0 + A0.T))
            V = V[:, :n_modes]
            A0, A1, C = (V.T @ X @ V for X in (A0, A1, C))
        if not self.damped:
            self.A0, self.A1 = A0, A1
        else:
            # the unreduced quadratic eigenproblem M s^2 + C s + K_B + p Q, for polishing a
            # crossing (better conditioned than the Cholesky-reduced one: measured, Newton
            # stalled at 2e-10 relative at 48 elements on the reduced, 1e-10 on these)
            self.quadratic = (fe.M, fe.C, fe.K_B, fe.load_matrix())
            n = A0.shape[0]
            self.B0 = np.zeros((2 * n, 2 * n))
            self.B0[:n, n:] = np.eye(n)
            self.B0[n:, :n] = -A0
            self.B0[n:, n:] = -C
            self.B1 = np.zeros((2 * n, 2 * n))
            self.B1[n:, :n] = -A1

    #: Changes of the FE signature that change no regime (:func:`_fe_scan` fills it).
    silent_events: tuple = ()
    #: Neighbouring pairs searched for hidden windows (undamped), see :func:`_modes_coupled`.
    coupled: int = 10**6
    #: ``(load, |indicator|)`` of the indicators' optimised extrema where the FE signature
    #: did not change (a near coalescence, or crossing): :func:`_events` fills it; the exact
    #: regime is checked there (a window the FE twin has just closed opens there on eq. 118).
    near_misses: tuple[tuple[float, float], ...] = ()

    def spectra(self, p: NDArray) -> NDArray:
        p = np.atleast_1d(np.asarray(p, dtype=float))
        if not self.damped:
            return np.linalg.eigvals(self.A0[None] + p[:, None, None] * self.A1[None])
        return np.linalg.eigvals(self.B0[None] + p[:, None, None] * self.B1[None])

    def _flags(self, z: NDArray) -> tuple[NDArray, NDArray]:
        """(complex, unstable) flags of the eigenvalues ``z`` (rows: loads)."""
        scale = np.max(np.abs(z), axis=-1, keepdims=True)
        cx = np.abs(z.imag) > _COMPLEX_RTOL * np.abs(z)
        if not self.damped:
            return cx, ~cx & (z.real < 0)
        # The raw sign, as the pendulum's flutter_onset: a relative threshold would be biased
        # by the stiff, strongly damped FE modes that set max|s| (1e7 at 48 elements).
        del scale
        return cx, z.real > 0

    def signatures(self, z: NDArray) -> list[tuple[int, int]]:
        cx, unstable = self._flags(z)
        if not self.damped:
            return list(zip(cx.sum(-1).tolist(), unstable.sum(-1).tolist(), strict=True))
        return list(zip((cx & unstable).sum(-1).tolist(), (~cx & unstable).sum(-1).tolist(),
                        strict=True))

    def regime(self, sig: tuple[int, int]) -> Regime:
        """Chapter §2.3/§2.7: flutter if an unstable root is complex, else divergence if an
        unstable root is real, else stable."""
        if sig[0]:
            return Regime.FLUTTER
        return Regime.DIVERGENCE if sig[1] else Regime.STABLE

    def indicators(self, z: NDArray) -> NDArray:
        """Smooth functions of the load that change sign at every change of regime, shape
        (k, loads); a hidden window between two scan points is a zero pair of one of them.

        For each pair of neighbours ``(z_k, z_k+1)`` in the spectrum sorted by real, then
        imaginary part, the normalised squared difference
        ``Re[(z_k+1 - z_k)^2] / (|z_k| + |z_k+1|)^2`` (a discriminant of the pair): positive
        for two real roots, negative for a complex-conjugate pair, analytic across their
        coalescence. Damped: only pairs with an unstable member (a coalescence in the left
        half-plane changes no regime; NaN elsewhere), and the largest growth rate
        ``max Re s / max|s|`` (a pair touching the imaginary axis)."""
        z = np.atleast_2d(z)
        order = np.lexsort((z.imag, z.real), axis=-1)
        zs = np.take_along_axis(z, order, axis=-1)
        a, b = zs[:, :-1], zs[:, 1:]
        q = ((b - a) ** 2).real / (np.abs(a) + np.abs(b) + 1e-300) ** 2
        if not self.damped:
            # Only pairs among the modes the load couples (the lowest Omega^2 first): higher
            # ones never meet below P_MAX_LIMIT, and their gaps' extrema cost Brent solves.
            return q[:, : self.coupled].T
        q = np.where((a.real > 0) | (b.real > 0), q, np.nan)
        growth = z.real.max(axis=-1) / np.max(np.abs(z), axis=-1)
        return np.vstack([q.T, growth[None]])


def _events(scan: _FEScan, p_max: float, step: float) -> list[_Event]:
    """Every change of the FE signature in [0, p_max]: bracketed on a uniform scan (step
    <= ``step``), each bracket bisected to ``_BRACKET_RTOL``; between two scan points with the
    same signature, every positive sampled local minimum and negative local maximum of an
    indicator (:meth:`_FEScan.indicators`) is optimised (bounded Brent) and a signature change
    at the optimum splits the interval (a window narrower than the step)."""
    n = max(2, int(math.ceil(p_max / step)))
    scan.coupled = _modes_coupled(p_max)
    grid = np.linspace(0.0, p_max, n + 1)
    # in blocks of loads: the stacked matrices of one call took 472 MB at p_max = 1000 and
    # the default step (an outside audit's step 1e-3 asked numpy for 48 GB)
    sigs: list[tuple] = []
    blocks = []
    for part in np.array_split(grid, -(-grid.size // _SCAN_BLOCK)):
        z = scan.spectra(part)
        sigs += scan.signatures(z)
        blocks.append(scan.indicators(z))
    ind = np.hstack(blocks)

    def sig_at(p: float) -> tuple:
        return scan.signatures(scan.spectra(np.array([p])))[0]

    def bisect(a: float, b: float, sa: tuple, sb: tuple, depth: int = 0) -> list[_Event]:
        if b - a <= _BRACKET_RTOL * max(1.0, b) or depth > 80:
            return [_Event(a, b, sa, sb)]
        m = 0.5 * (a + b)
        sm = sig_at(m)
        out = []
        if sm != sa:
            out += bisect(a, m, sa, sm, depth + 1)
        if sm != sb:
            out += bisect(m, b, sm, sb, depth + 1)
        return out

    events: list[_Event] = []
    near: list[tuple[float, float]] = []
    for i in range(n):
        if sigs[i] != sigs[i + 1]:
            events += bisect(grid[i], grid[i + 1], sigs[i], sigs[i + 1])
    # Hidden windows: a positive local minimum or a negative local maximum of an indicator
    # (with the same signature on both sides) is optimised on its two neighbouring steps
    # (bounded Brent, smooth function); if it crosses zero, the optimum splits the interval.
    idx = np.arange(n + 1)
    lo_i, hi_i = np.maximum(idx - 1, 0), np.minimum(idx + 1, n)
    same = np.array([sigs[lo_i[i]] == sigs[i] == sigs[hi_i[i]] for i in idx])
    v, vl, vh = ind, ind[:, lo_i], ind[:, hi_i]
    with np.errstate(invalid="ignore"):
        ok = same[None] & np.isfinite(v) & np.isfinite(vl) & np.isfinite(vh)
        # two real roots approaching (a hidden complex window?) / a complex pair approaching
        # the real axis (a hidden real window?)
        up = ok & (v > 0) & (v <= vl) & (v <= vh) & ((v < vl) | (v < vh))
        down = ok & (v < 0) & (v >= vl) & (v >= vh) & ((v > vl) | (v > vh))
    # Two events within one step (pair B turning complex, then pair A real, say): the
    # signature is the same at both scan points but an indicator changes sign between them.
    # Each sign change is solved (Brent) and the signature probed between the zeros; a
    # different one there is bisected on both sides (an outside review: tan(alpha) = 0.2265
    # has such a pair within 0.25 at p ~ 273.4 on 22 elements, and eq. 118 a window there).
    with np.errstate(invalid="ignore"):
        flips = (np.isfinite(ind[:, :-1]) & np.isfinite(ind[:, 1:])
                 & (ind[:, :-1] * ind[:, 1:] < 0))
    for i in np.flatnonzero(flips.any(axis=0)):
        if sigs[i] != sigs[i + 1]:
            continue  # bracketed above
        a, b = float(grid[i]), float(grid[i + 1])
        zeros = []
        for row in np.flatnonzero(flips[:, i]):
            def ind_at(p: float, row: int = int(row)) -> float:
                return float(scan.indicators(scan.spectra(np.array([p])))[row, 0])

            fa, fb = ind_at(a), ind_at(b)
            if np.isfinite(fa) and np.isfinite(fb) and fa * fb < 0:
                zeros.append(float(brentq(ind_at, a, b, xtol=_BRACKET_RTOL * max(1.0, b))))
        zeros = sorted(zeros)
        for z0, z1 in zip(zeros, zeros[1:], strict=False):
            mid = 0.5 * (z0 + z1)
            s_mid = sig_at(mid)
            if s_mid != sigs[i]:
                events += bisect(a, mid, sigs[i], s_mid)
                events += bisect(mid, b, s_mid, sigs[i + 1])
                break
    for row, i in zip(*np.nonzero(up | down), strict=True):
        sign = 1.0 if up[row, i] else -1.0
        a, b = float(grid[lo_i[i]]), float(grid[hi_i[i]])
        s_out = sigs[lo_i[i]]

        def fun(p: float, row: int = int(row), sign: float = sign) -> float:
            val = scan.indicators(scan.spectra(np.array([p])))[row, 0]
            return float(sign * val) if np.isfinite(val) else math.inf

        res = minimize_scalar(fun, bounds=(a, b), method="bounded",
                              options={"xatol": _BRACKET_RTOL * max(1.0, b)})
        s_min = sig_at(float(res.x))
        if s_min != s_out:
            events += bisect(a, float(res.x), s_out, s_min)
            events += bisect(float(res.x), b, s_min, s_out)
        elif np.isfinite(res.fun):
            near.append((float(res.x), abs(float(res.fun))))
    events.sort(key=lambda e: e.a)
    scan.near_misses = tuple(sorted(near))
    return events


@dataclass(frozen=True)
class _Boundary:
    """A change of regime at load ``p``: ``kind`` "coalescence" (a double root, ``omega`` its
    real or imaginary part) or "crossing" (a pair on the imaginary axis, ``omega = Im``)."""

    p: float
    omega: float
    before: Regime
    after: Regime
    kind: str
    guess: float  # Newton's start: omega~^2 (undamped), Im (crossing) or Re (damped double)


def _dedupe(events: list[_Event]) -> list[_Event]:
    out: list[_Event] = []
    for e in events:
        if out and e.a <= out[-1].b + 2 * _BRACKET_RTOL * max(1.0, e.b) \
                and (e.before, e.after) == (out[-1].before, out[-1].after):
            continue
        out.append(e)
    return out


def _closest_pair(z: NDArray, mask: NDArray | None = None) -> tuple[complex, complex]:
    zz = z if mask is None else z[mask]
    if zz.size < 2:
        raise ConvergenceError("no coalescing pair found at a change of regime")
    d = np.abs(zz[:, None] - zz[None, :])
    d[np.arange(zz.size), np.arange(zz.size)] = np.inf
    i, j = np.unravel_index(int(np.argmin(d)), d.shape)
    return complex(zz[i]), complex(zz[j])


def _fe_boundary(scan: _FEScan, e: _Event, polish: _FEScan | None = None) -> _Boundary:
    """The FE boundary of an event, polished with Brent's method on the smooth function that
    changes sign there (a pair's squared difference, or a pair's growth rate). With
    ``polish`` (the full FE model when ``scan`` is its modal reduction) the function is
    evaluated on ``polish``, in a bracket grown around the event until it changes sign."""
    before, after = scan.regime(e.before), scan.regime(e.after)
    m = 0.5 * (e.a + e.b)
    z = scan.spectra(np.array([m]))[0]
    model = scan if polish is None else polish
    d_uc, d_ur = e.after[0] - e.before[0], e.after[1] - e.before[1]
    if scan.damped and d_ur == 0:  # a pair crossing the imaginary axis (Hopf)
        cand = z[z.imag > 0]
        # The pair whose growth rate changes sign across the bracket; the one nearest the axis
        # at the midpoint only where none is found. (Nearest alone picked a high mode when the
        # crossing is abrupt: tan(alpha) = 0 with a tiny mass-proportional damping gamma puts
        # every mode at Re s = -gamma/2 while the flutter pair, just past its coalescence, is
        # already far right: outside audit, guesses of 290-708 for a pulsation of 11.)
        za, zb = scan.spectra(np.array([e.a, e.b]))
        flips = [c for c in cand
                 if za[np.argmin(np.abs(za - c))].real * zb[np.argmin(np.abs(zb - c))].real <= 0]
        pool = np.array(flips) if flips else cand
        z0 = complex(pool[np.argmin(np.abs(pool.real))])

        def fun(p: float) -> float:
            s = model.spectra(np.array([p]))[0]
            return float(s[np.argmin(np.abs(s - z0))].real)

        kind = "crossing"
    elif not scan.damped or d_uc == -d_ur:  # two roots merging on the real axis
        mask = None if not scan.damped else z.real > -1e-9 * np.max(np.abs(z))
        z1, z2 = _closest_pair(z, mask)
        z0 = 0.5 * (z1 + z2)

        def fun(p: float) -> float:
            s = model.spectra(np.array([p]))[0]
            near = s[np.argsort(np.abs(s - z0))[:2]]
            return float((((near[0] - near[1]) / abs(z0)) ** 2).real)

        kind = "coalescence"
    else:
        raise ConvergenceError(f"unexpected change of the FE spectrum near p = {m:.6g} "
                               f"({e.before} -> {e.after}): not a coalescence nor a crossing")
    a, b = e.a, e.b
    fa, fb = fun(a), fun(b)
    if polish is not None:  # the reduced model's bracket, grown on the full model
        w = 1e-3 * max(1.0, m)
        for _ in range(12):
            a, b = max(0.0, m - w), m + w
            fa, fb = fun(a), fun(b)
            if fa * fb < 0:
                break
            w *= 3
        else:
            raise ConvergenceError(f"the full FE model has no change of regime near p = {m:.6g}"
                                   " where its modal reduction has one")
    p = m
    if fa * fb < 0:
        p = float(brentq(fun, a, b, xtol=4 * np.finfo(float).eps * max(1.0, b)))
    crossing = None
    if kind == "crossing" and polish is not None:
        # Brent's root of a growth rate computed from the first-order spectrum stalls at that
        # spectrum's round-off, eps max|s| (the stiff Kelvin-Voigt modes): 3.6e-9 relative at
        # 48 elements (list 119's damping), where the mesh's error is 6e-10. Newton on the
        # quadratic eigenproblem has a floor 30x lower (~1e-10 at 48 elements;
        # analysis.damped.polish_flutter_crossing). It refuses a start it cannot confirm, and
        # Brent's load stands then.
        try:
            # accepted anywhere in the bracket where the growth rate changes sign (the raw
            # load's error reaches 2.3e-6 at eta = 1e-6: beyond polishing's default window;
            # the bracket may reach down to p = 0, a window of 100 %: capped, then checked)
            crossing = polish_flutter_crossing(
                *model.quadratic, p, rtol=min(0.5, max(b - p, p - a) / max(p, 1e-300)))
            if a <= crossing[0] <= b:
                p = crossing[0]
            else:
                crossing = None
        except ConvergenceError:
            pass
    s = model.spectra(np.array([p]))[0]
    if kind == "crossing":
        near = s[np.argmin(np.abs(s - z0))]
        # (Newton's pulsation where polished: the spectrum's carries its round-off too)
        omega = guess = abs(near.imag) if crossing is None else crossing[1]
    else:
        near = s[np.argsort(np.abs(s - z0))[:2]]
        # The double root as the pair's mean: well conditioned, unlike either root of a
        # (nearly) defective pair. Pencil: Omega^2 = -omega~^2.
        zm = complex(0.5 * (near[0] + near[1]))
        omega = math.sqrt(abs(zm.real)) if not scan.damped else zm.real
        guess = -zm.real if not scan.damped else zm.real
    return _Boundary(p, float(omega), before, after, kind, float(guess))


def _modes_coupled(p_max: float) -> int:
    """Modes the load couples up to ``p_max`` (wavenumber^2 <= 3 p_max + 40; a mode of
    wavenumber k feels the load when k^2 <~ p), plus 4 for the Galerkin reduction's accuracy."""
    return int(math.ceil(math.sqrt(3 * p_max + 40) / math.pi)) + 5


def _fe_scan(g: RodGroups, n_elements: int, p_max: float, step: float,
             n_modes: int | None = None, polish_full: bool = False
             ) -> tuple[_FEScan, Regime, list[_Boundary]]:
    scan = _FEScan(g, n_elements, n_modes)
    full = _FEScan(g, n_elements) if polish_full and n_modes is not None else None
    events = _dedupe(_events(scan, p_max, step))
    first = scan.regime(scan.signatures(scan.spectra(np.array([0.0])))[0])
    bounds = [_fe_boundary(scan, e, full) for e in events
              if scan.regime(e.before) != scan.regime(e.after)]
    # pairs coalescing without a change of regime (another pair keeps it): two of them close
    # together may bound a window on eq. (118) that the twin's error closed
    scan.silent_events = tuple(e for e in events if scan.regime(e.before) == scan.regime(e.after))
    return scan, first, bounds
