"""Eigenvalues and critical loads of the Beck/Pflüger rod from the exact characteristic function
(eq. 118), with finite-element initial guesses (:mod:`flutterfriction.models.rod_fe`).

Critical loads are solved as the conditions themselves, by Newton's method on two real
equations in two real unknowns:

- undamped (eta = gamma = 0), ``f`` depends on ``mu = omega~^2`` only; flutter and divergence are
  double roots in ``mu``: ``f = df/dmu = 0`` for ``(p, mu)`` (flutter: ``mu < 0`` merging
  oscillations; divergence: ``mu > 0``, the complex pair returning to the real axis);
- damped flutter: a root on the imaginary axis, ``f(p, i Omega) = 0`` for ``(p, Omega)``;
- damped divergence: a double real root, ``f = df/domega~ = 0`` for real ``(p, omega~)``.

Derivatives of ``f`` (analytic in ``p`` and ``omega~``) use a four-point complex difference
``f'(z) = [f(z+h) - f(z-h) - i f(z+ih) + i f(z-ih)] / (4h) + O(h^4)``.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import asdict, dataclass

import numpy as np
from numpy.typing import NDArray
from scipy.optimize import brentq, linear_sum_assignment, minimize_scalar

from flutterfriction.analysis.damped import polish_flutter_crossing
from flutterfriction.analysis.rod_gap import GAP_NOISE_FACTOR, gap_roots, pair_gap
from flutterfriction.analysis.stability import Regime, state_eigenvalues
from flutterfriction.errors import (
    ConvergenceError,
    ParameterError,
    check_integer,
    check_positive,
    check_real,
)
from flutterfriction.models.rod import GROUP_RANGES, RodGroups, characteristic_function
from flutterfriction.models.rod_fe import assemble


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


def _fixed_scale(p: float, w: complex, g: RodGroups) -> float:
    return float(np.real(characteristic_function(p, w, g, with_exponent=True)[1]))


def _f(p, w, g: RodGroups, sigma0: float):
    """``f exp(-sigma0)``: analytic in (p, w) since the scaling is a constant."""
    F, sigma = characteristic_function(p, w, g, with_exponent=True)
    return F * np.exp(sigma - sigma0)


def _with_derivative(fun: Callable, z, h):
    """``fun(z)`` and its derivative (four points, error O(h^4) for an analytic ``fun``), from
    one call of the vectorised ``fun`` on the five points: the arrays are short, so a call
    costs its overhead, and one call instead of five gives the same numbers 3x faster."""
    z = np.asarray(z)
    v = fun(np.stack([z, z + h, z - h, z + 1j * h, z - 1j * h]))
    return v[0], (v[1] - v[2] - 1j * v[3] + 1j * v[4]) / (4 * h)


def _newton2(residual: Callable[[NDArray], NDArray], x0: NDArray, tol: float = 1e-14,
             max_iter: int = 60) -> NDArray:
    """Newton's method for two real equations, Jacobian by central differences, with step
    halving when the residual does not decrease."""
    x = np.asarray(x0, dtype=float)
    r = residual(x)
    for _ in range(max_iter):
        J = np.empty((2, 2))
        for j in range(2):
            h = 1e-6 * max(1.0, abs(x[j]))
            e = np.zeros(2)
            e[j] = h
            J[:, j] = (residual(x + e) - residual(x - e)) / (2 * h)
        try:
            dx = np.linalg.solve(J, -r)
        except np.linalg.LinAlgError as exc:
            raise ConvergenceError("singular Jacobian in the critical-load Newton solve") from exc
        step = 1.0
        for _ in range(30):
            xn = x + step * dx
            rn = residual(xn)
            if np.linalg.norm(rn) < np.linalg.norm(r) or step < 1e-6:
                break
            step /= 2
        x, r = xn, rn
        if np.all(np.abs(step * dx) <= tol * np.maximum(1.0, np.abs(x))):
            return x
    raise ConvergenceError(f"Newton did not converge from {x0} (last {x}, residual {r})")


# ---------------------------------------------------------------------- eigenvalues at one p
def refine_eigenvalues(p: float, g: RodGroups, guesses: NDArray, tol: float = 1e-13,
                       max_iter: int = 50) -> NDArray:
    """Newton on the exact ``f(p, omega~) = 0`` from each guess (vectorised over guesses).

    A step onto the pole ``omega~ = -1/eta`` of eq. (113) or a flat point (``f' = 0``) is a
    :class:`ConvergenceError` at once, without numpy's warnings (the callers treat it as any
    failed Newton: an outside audit saw divide-by-zero warnings printed for answers that
    were right)."""
    w = np.asarray(guesses, dtype=complex).copy()
    h = 1e-4 * np.maximum(1.0, np.abs(w))
    # A root counts as converged once its step has met the tolerance: next to a double root
    # the steps of two nearly coincident roots jitter at ~1e-13 |w| (f' is small there), and
    # requiring every step small at the same iteration refused them (tan(alpha) = 0.5932505,
    # p = 48.85: every root converged alone; an outside audit). Elsewhere a converged step
    # stays converged, so the iterations and the roots are those of "all at once".
    met = np.zeros(w.shape, dtype=bool)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        sigma0 = np.real(characteristic_function(p, w, g, with_exponent=True)[1])
        for _ in range(max_iter):
            F, dF = _with_derivative(lambda z: _f(p, z, g, sigma0), w, h)
            step = F / dF
            if not np.all(np.isfinite(step)):
                break
            w = w - step
            met |= np.abs(step) <= tol * np.maximum(1.0, np.abs(w))
            if np.all(met):
                return w
    # one line a reader can act on (the guesses' array, printed whole, was a screenful)
    raise ConvergenceError(f"Newton on eq. (118) did not converge at p = {p:.10g} from "
                           f"{np.size(guesses)} guesses: nearly coincident roots (next to a "
                           f"double root, where a regime changes) or a flat point of eq. "
                           f"(118); a slightly different p_max or step moves the loads "
                           f"tried")


#: Largest FE mesh of the eigenvalue helpers (:func:`eigenvalues`, :func:`branches`,
#: :func:`fe_eigenvalues`): the figures use 16, the convergence study 48; beyond 200 the dense
#: eigensolver's cost (~n^3) is minutes per load and nothing gains.
MAX_ELEMENTS = 200


def _check_mesh(n_elements: object, n_modes: object = None) -> None:
    """Refuse a mesh or a mode count (at most n_elements) outside its range."""
    n_elements = check_integer("n_elements", n_elements, 1, MAX_ELEMENTS)
    if n_modes is not None:
        check_integer("n_modes", n_modes, 1, n_elements)


def _check_load(p: object, name: str = "p") -> float:
    """A finite load within the solver's range, |p| <= :data:`P_MAX_LIMIT`."""
    p = check_real(name, p)
    if abs(p) > P_MAX_LIMIT:
        raise ParameterError(f"{name} must be in [-{P_MAX_LIMIT:g}, {P_MAX_LIMIT:g}] (the rod "
                             f"solver's range, analysis.rod.P_MAX_LIMIT), got {p!r}")
    return p


def eigenvalues(p: float, g: RodGroups, n_modes: int = 3, n_elements: int = 16) -> NDArray:
    """The ``2 n_modes`` eigenvalues ``omega~`` of smallest modulus at load ``p``: FE guesses
    refined on the exact characteristic function; sorted by imaginary, then real part."""
    _check_mesh(n_elements, n_modes)
    fe = fe_eigenvalues(g, p, n_elements)
    guesses = fe[np.argsort(np.abs(fe))][: 2 * n_modes]
    w = refine_eigenvalues(p, g, guesses)
    return w[np.lexsort((w.real, w.imag))]


# ---------------------------------------------------------------------- critical loads
def _undamped_double_root(g: RodGroups, p0: float, mu0: float) -> tuple[float, float]:
    sigma0 = _fixed_scale(p0, np.sqrt(complex(mu0)), g)

    def G(p, mu):
        return _f(p, np.sqrt(mu + 0j), g, sigma0)

    def residual(x):
        p, mu = x
        h = 1e-3 * max(1.0, abs(mu))
        val, dval = _with_derivative(lambda m: G(p, m), mu + 0j, h)
        return np.array([np.real(val), np.real(dval)])

    p, mu = _newton2(residual, np.array([p0, mu0]))
    return float(p), float(mu)


def _damped_flutter(g: RodGroups, p0: float, W0: float) -> tuple[float, float]:
    """Root ``omega~ = i Omega`` of eq. (118): ``Re f = 0`` and ``Im f / delta = 0`` with
    ``delta = max(eta, gamma)``. On the imaginary axis the imaginary parts of eq. (118)'s terms
    all carry a factor ``eta`` or ``gamma`` and are computed to relative precision, so the
    scaled equation keeps its digits as the damping vanishes (the chapter's paradox: the limit
    is not the undamped load) instead of drowning in the ``Re f`` round-off."""
    sigma0 = _fixed_scale(p0, 1j * W0, g)
    delta = max(g.eta, g.gamma)

    def residual(x):
        v = _f(x[0], 1j * x[1], g, sigma0)
        return np.array([np.real(v), np.imag(v) / delta])

    p, W = _newton2(residual, np.array([p0, abs(W0)]))
    return float(p), float(abs(W))


def _damped_divergence(g: RodGroups, p0: float, w0: float) -> tuple[float, float]:
    sigma0 = _fixed_scale(p0, w0, g)

    def residual(x):
        p, w = x
        h = 1e-3 * max(1.0, abs(w))
        val, dval = _with_derivative(lambda z: _f(p, z, g, sigma0), w + 0j, h)
        return np.array([np.real(val), np.real(dval)])

    p, w = _newton2(residual, np.array([p0, w0]))
    return float(p), float(w)


# ---------------------------------------------------------------------- regime scan along p
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
#: Half-width of the search for a failed boundary's exact zeros of its pair's gap, relative
#: to p: 2.6x the FE twin's largest measured boundary error (7.6e-4, see SCAN_BEYOND).
GAP_SEARCH_RTOL = 2e-3
#: A near miss of the FE twin (see :attr:`_FEScan.near_misses`) is "close" below this value of
#: its indicator (measured: 1e-5 at tan(alpha) = 0.982349, where eq. 118 has a window 0.018
#: wide; ordinary extrema 7e-4 and above) and then probed at these relative offsets.
NEAR_MISS_CLOSE, NEAR_MISS_PROBES = 1e-3, (1e-4, 3e-4, 1e-3)
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
#: Most scan points (p_max / step): ~1.2 ms each at p_max = 1000 (40 elements), so at most
#: ~2 min; 25 times the default density at any p_max.
SCAN_POINTS_MAX = 100_000


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


def _intervals(boundaries: list, first: Regime, p_max: float) -> list[dict]:
    out, start, regime = [], 0.0, first
    for b in boundaries:
        out.append({"regime": str(regime), "p_from": start, "p_to": b.p})
        start, regime = b.p, b.after
    out.append({"regime": str(regime), "p_from": start, "p_to": float(p_max)})
    return out


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


#: The groups' numerical range (eq. 106): ``(smallest positive, largest)``, 0 always allowed.
# GROUP_RANGES (the solver's numerical range of eq. 106's groups) lives with RodGroups.


def check_groups(g: RodGroups) -> RodGroups:
    """Refuse groups outside :data:`GROUP_RANGES` with a :class:`ParameterError` naming the
    group and its allowed range."""
    if not isinstance(g, RodGroups):
        raise ParameterError(f"g must be a RodGroups (eq. 106's groups), got {type(g).__name__}")
    for name, (low, high) in GROUP_RANGES.items():
        v = getattr(g, name)
        if v > high or 0 < v < low:
            allowed = f"in [0, {high:g}]" if low == 0 else f"0 or in [{low:g}, {high:g}]"
            # (all digits where %g would print a bound: "got 1" for eta = 1.0000001; an audit)
            shown = f"{v:g}" if float(f"{v:g}") not in (low, high) else repr(v)
            raise ParameterError(f"{name} must be {allowed} (the rod solver's numerical range,"
                                 f" analysis.rod.GROUP_RANGES), got {shown}")
    return g


def _check_p_max(p_max: float) -> float:
    p_max = check_positive("p_max", p_max)
    if p_max > P_MAX_LIMIT:
        raise ParameterError(f"p_max must be in (0, {P_MAX_LIMIT:g}] (the regime scan's range, "
                             f"see analysis.rod.P_MAX_LIMIT), got {p_max!r}")
    return p_max


def _check_step(step: float, p_max: float) -> float:
    step = check_positive("step", step)
    if step > SCAN_STEP or p_max / step > SCAN_POINTS_MAX:
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
    two scan points are caught by minimising the indicators of :class:`_FEScan`. Damped: the
    scan runs on the modal reduction to the modes the load couples and each boundary is
    polished on the full model. Parameters as :func:`critical_loads` (``n_elements``
    required); the loads are the FE model's, not eq. (118)'s.

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


def _damping(g: RodGroups) -> float:
    return max(g.eta, g.gamma)


def _exact_boundary(g: RodGroups, b: _Boundary) -> tuple[float, float]:
    if not g.damped:
        p, mu = _undamped_double_root(g, b.p, b.guess)
        return p, float(np.sqrt(abs(mu)))
    if b.kind == "crossing":
        return _damped_flutter(g, b.p, b.guess)
    return _damped_divergence(g, b.p, b.guess)


def _exact_regime(p: float, g: RodGroups) -> Regime | None:
    """Regime from the exact roots of eq. (118) (FE guesses refined by Newton), ``None`` if a
    growth rate is below what the roots resolve. Modes with wavenumber^2 up to 3p + 40 (the
    load only couples modes with k^2 <~ p)."""
    n_modes = int(math.ceil(math.sqrt(3 * p + 40) / math.pi)) + 1
    if not g.damped:
        try:
            w = eigenvalues(p, g, n_modes=n_modes, n_elements=max(16, 3 * n_modes))
        except ConvergenceError:
            # two roots nearly coincide (next to a coalescence): the pair by its gap
            return _undamped_regime_by_gap(p, g, n_modes, max(16, 3 * n_modes))
    else:
        # The rightmost FE roots (with strong Kelvin-Voigt damping many overdamped roots lie
        # nearer the origin than an unstable pair) and those of smallest modulus (with tiny
        # damping the FE growth rates are round-off, ~1e-12, and "rightmost" is random).
        fe = fe_eigenvalues(g, p, max(16, 3 * n_modes))
        guesses = np.concatenate([fe[np.argsort(-fe.real)][: 2 * n_modes],
                                  fe[np.argsort(np.abs(fe))][: 2 * n_modes]])
        # Growth rates at round-off level start on the imaginary axis: Newton's first step
        # then gives Re omega~ = O(damping) to relative precision (from 1e-12 it would take
        # log2(log(1e-100)/log(1e-12)) ~ 3 steps more to fall to a damping of 1e-100).
        flat = np.abs(guesses.real) < 1e-8 * np.abs(guesses)
        guesses = np.unique(np.where(flat, 1j * guesses.imag, guesses))
        try:
            w = _damped_roots(p, g, guesses)
        except ConvergenceError:
            # two roots nearly coincide on the real axis (next to a divergence window's
            # end): the pair by its gap in omega~, the other roots alone
            w = _damped_roots_by_gap(p, g, guesses)
            if w is None:
                return None
    if not g.damped:
        mu = w**2
        cx = np.abs(mu.imag) > 1e-8 * np.abs(mu)
        if np.any(cx):
            return Regime.FLUTTER
        return Regime.DIVERGENCE if np.any(mu.real > 0) else Regime.STABLE
    # With damping the growth rates are resolved relative to the damping (the imaginary parts
    # of eq. 118's terms are O(damping) and carried with relative precision).
    tol = 1e-10 * np.abs(w) * min(1.0, _damping(g))
    unstable = w.real > tol
    if np.any(np.abs(w.real) <= tol):
        return None
    if np.any(unstable & (np.abs(w.imag) > 1e-8 * np.abs(w))):
        return Regime.FLUTTER
    return Regime.DIVERGENCE if np.any(unstable) else Regime.STABLE


def _damped_roots(p: float, g: RodGroups, guesses: NDArray) -> NDArray:
    """The damped rod's roots ``omega~`` of eq. (118) from FE ``guesses``, each refined alone
    (those deep in the left half-plane may fail: they decide no regime)."""
    roots = []
    for z in guesses:
        try:
            roots.append(refine_eigenvalues(p, g, np.array([z]))[0])
        except ConvergenceError:
            # Newton may fail next to the pole omega~ = -1/eta of eq. (113) (overdamped
            # roots); a root that deep in the left half-plane (decay > 10 % of its
            # modulus, far beyond the FE twin's error) decides no regime.
            if not z.real < -0.1 * abs(z):
                raise
    w = np.array(roots, dtype=complex)
    # Two more Newton steps: the stopping test (step <= 1e-13 |w|) leaves an error up to
    # ~1e-16 |w|, above a growth rate O(damping) when the damping is tiny; each step
    # squares it, down to the relative precision Re omega~ is computed with (see
    # _damped_flutter). Not on the roots deep in the left half-plane: they decide nothing,
    # and a nearly coincident pair there (the mirror -omega~ of a nearly undamped pair next
    # to its coalescence) may jitter and fail (an outside review: tan(alpha) = 0.5932505,
    # eta = 1e-6, p = 48.8495).
    near = ~(w.real < -0.1 * np.abs(w))
    w[near] = refine_eigenvalues(p, g, refine_eigenvalues(p, g, w[near]))
    return w


def _closest_pair_index(z: NDArray) -> tuple[int, int]:
    """Indices of the two values of ``z`` nearest each other relative to their moduli."""
    d = np.abs(z[:, None] - z[None, :]) / (np.abs(z[:, None]) + np.abs(z[None, :]) + 1e-300)
    d[np.arange(z.size), np.arange(z.size)] = np.inf
    i, j = np.unravel_index(int(np.argmin(d)), d.shape)
    return int(i), int(j)


def _damped_roots_by_gap(p: float, g: RodGroups, guesses: NDArray) -> NDArray | None:
    """:func:`_damped_roots` where two roots nearly coincide and Newton on them fails: the
    pair of guesses nearest each other (on or about the real axis) from its gap in
    ``omega~`` (:func:`flutterfriction.analysis.rod_gap.pair_gap`: two real roots about its
    centre, or a complex pair), every other root alone; ``None`` (no verdict) where the gap
    is within its round-off."""
    # among the roots that decide the regime (a pair deep in the left half-plane, e.g. the
    # mirror -omega~ of a nearly undamped pair, is left to _damped_roots, which skips it)
    deciding = np.flatnonzero(~(guesses.real < -0.1 * np.abs(guesses)))
    if deciding.size < 2:
        raise ConvergenceError(f"no pair of roots of eq. (118) to decide at p = {p:.10g}")
    a, b = _closest_pair_index(guesses[deciding])
    i, j = int(deciding[a]), int(deciding[b])
    centre, gap, noise = pair_gap(p, g, float(0.5 * (guesses[i] + guesses[j]).real), "omega")
    if abs(gap) <= GAP_NOISE_FACTOR * noise:
        return None
    others = _damped_roots(p, g, np.delete(guesses, [i, j]))
    half = math.sqrt(abs(gap))
    pair = ([complex(centre - half), complex(centre + half)] if gap > 0 else
            [complex(centre, half), complex(centre, -half)])
    return np.concatenate([others, np.array(pair)])


def _regime_of(mu: NDArray) -> Regime:
    """Undamped regime of the roots ``mu = omega~^2``: flutter if one is complex, else
    divergence if one is positive (a real growing ``omega~``), else stable."""
    if np.any(np.abs(mu.imag) > 1e-8 * np.abs(mu)):
        return Regime.FLUTTER
    return Regime.DIVERGENCE if np.any(mu.real > 0) else Regime.STABLE


def _undamped_regime_by_gap(p: float, g: RodGroups, n_modes: int, n_el: int
                            ) -> Regime | None:
    """Undamped regime at ``p`` where roots of eq. (118) nearly coincide and Newton on them
    fails: every root is refined alone from its FE guess; one whose Newton fails is decided
    with its nearest neighbour by their gap (:func:`flutterfriction.analysis.rod_gap.
    pair_gap`: a complex pair if negative, else two real roots about its centre). Two such
    pairs at one load happen (an outside review: tan(alpha) = 0.2166, p = 847.08, mu ~ 20150
    and 75147). ``None`` (no verdict) where a gap is within
    :data:`~flutterfriction.analysis.rod_gap.GAP_NOISE_FACTOR` times its round-off."""
    mu = -_FEScan(g, n_el).spectra(np.array([p]))[0]  # the pencil's Omega^2 = -mu
    mu = mu[np.argsort(np.abs(mu))][:n_modes]
    roots: list[complex] = []
    pending = list(range(mu.size))
    while pending:
        k = pending.pop(0)
        try:
            roots.append(complex(refine_eigenvalues(p, g, np.array([np.sqrt(complex(mu[k]))]))
                                 [0] ** 2))
            continue
        except ConvergenceError:
            if not pending:
                raise
        j = min(pending, key=lambda q: abs(mu[q] - mu[k]))
        pending.remove(j)
        centre, gap, noise = pair_gap(p, g, float(0.5 * (mu[k] + mu[j]).real))
        if abs(gap) <= GAP_NOISE_FACTOR * noise:
            return None
        half = math.sqrt(abs(gap))
        roots += ([complex(centre, half), complex(centre, -half)] if gap < 0 else
                  [complex(centre - half), complex(centre + half)])
    return _regime_of(np.array(roots, dtype=complex))


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
    regime between their exact loads checked at its middle."""
    events = [e for e in scan.silent_events if e.a < p_max]
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
        if not 0.0 < lo < hi < p_max or any(lo <= b.p <= hi for b in out):
            continue
        outside = _regime_below(out, first, lo)
        try:
            inside = _exact_regime(0.5 * (lo + hi), g)
        except ConvergenceError:
            continue  # no verdict between them: as before, the interval checks decide
        if inside is None or inside == outside:
            continue
        out += [_Boundary(lo, w_lo, outside, inside, b_lo.kind, b_lo.guess),
                _Boundary(hi, w_hi, inside, outside, b_hi.kind, b_hi.guess)]
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
    for e in scan.silent_events:
        if not e.a < p_max:
            continue
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
        if not 0.0 < s_p < p_max or abs(s_p - b.p) <= 1e-9 * max(1.0, b.p):
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
    of it; two zeros are a window, its regime decided on eq. (118) at its middle."""
    out = list(exact)
    for p_nm, v in scan.near_misses:
        if v >= NEAR_MISS_CLOSE or p_nm >= p_max:
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
        radius = GAP_SEARCH_RTOL * max(1.0, p_nm)
        try:
            roots = gap_roots(g, max(0.0, p_nm - radius), min(p_max, p_nm + radius),
                              float(0.5 * (z[i] + z[j]).real),
                              variable="omega" if g.damped else "mu")
        except ConvergenceError:
            continue  # unresolved here: the near-miss regime check below decides, or refuses
        # (a zero that is a boundary already solved, within its round-off, is that one)
        roots = [(p, m) for p, m in roots
                 if all(abs(p - b.p) > 1e-9 * max(1.0, p) for b in out)]
        if not roots:
            continue
        if len(roots) != 2:
            raise ConvergenceError(f"{len(roots)} changes of regime of eq. (118) near "
                                   f"p = {p_nm:.6g}, where the FE twin has none")
        (p1, m1), (p2, m2) = roots
        if any(p1 < b.p < p2 for b in out):
            raise ConvergenceError(f"a window of eq. (118) near p = {p_nm:.6g} that the FE "
                                   "twin has closed straddles another change of regime")
        outside = _regime_below(out, first, p1)
        inside = _exact_regime(0.5 * (p1 + p2), g)
        if inside is None:
            raise ConvergenceError(f"no exact regime inside the window [{p1:.10g}, {p2:.10g}]"
                                   " of eq. (118) that the FE twin has closed")
        if inside == outside:  # another pair keeps the regime: no change
            continue
        w1, w2 = (m1, m2) if g.damped else (math.sqrt(abs(m1)), math.sqrt(abs(m2)))
        out += [_Boundary(p1, w1, outside, inside, "coalescence", m1),
                _Boundary(p2, w2, inside, outside, "coalescence", m2)]
        out.sort(key=lambda b: b.p)
    return out


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
    when an indicator of :class:`_FEScan` has a sampled local minimum at a neighbouring scan
    point (always, if the coalescing pair's gap varies on a scale longer than ``step``;
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
    250.0927). Measured at p_max 80, without a
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
        FE elements of the bracketing scan (default :func:`_scan_elements`).
    step : float
        Largest step of the scan, in (0, :data:`SCAN_STEP`] and >= p_max/1e6.

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
            try:
                r = _exact_regime(mid, g)
            except ConvergenceError as exc:
                if k >= len(checks):
                    # No verdict at a near miss (eq. 118's roots nearly coincide there): a
                    # window may open or close within the twin's error. Unresolved: the finer
                    # twin decides, or it is refused (an outside review: left alone, windows
                    # up to 0.087 wide at tan(alpha) = 0.982343-0.982349 went unreported).
                    raise ConvergenceError(
                        f"no exact regime at p = {mid:.6g}, where the FE twin nearly changes "
                        f"regime (a window within its error): {exc}") from None
                first_error = first_error or exc
                continue
            verdicts += 1
            if r is not None and r != iv["regime"]:
                raise ConvergenceError(
                    f"regime check failed at p = {mid:.6g}: the exact roots of eq. (118) give "
                    f"{r}, the FE bracketing {iv['regime']} (a change of regime the scan "
                    "missed)")
        if not verdicts:
            assert first_error is not None
            raise first_error
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


# ---------------------------------------------------------------------- branches (Figs. 11, 12)
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
    p_values = np.asarray(p_values, dtype=float)
    if p_values.ndim != 1 or p_values.size == 0:
        raise ParameterError(f"p_values must be a non-empty 1-d array of loads, got shape "
                             f"{p_values.shape}")
    if p_values.size > MAX_BRANCH_LOADS:  # (1e7 loads ran for minutes; an outside audit)
        raise ParameterError(f"p_values must hold at most {MAX_BRANCH_LOADS} loads (~1 ms "
                             f"each), got {p_values.size}")
    for p in p_values:
        _check_load(p, "p_values")
    _check_mesh(n_elements, n_modes)
    check_groups(g)
    out = np.empty((p_values.size, 2 * n_modes), dtype=complex)
    for i, p in enumerate(p_values):
        truth = eigenvalues(p, g, n_modes, n_elements)
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


def fe_eigenvalues(g: RodGroups, p: float, n_elements: int, follower: bool = True) -> NDArray:
    """All eigenvalues ``omega~`` of the discretised rod at load ``p`` (first-order form)."""
    p = _check_load(p)
    _check_mesh(n_elements)
    check_groups(g)
    fe = assemble(g, n_elements)
    return state_eigenvalues(fe.M, fe.K_B + p * fe.load_matrix(follower), fe.C)
