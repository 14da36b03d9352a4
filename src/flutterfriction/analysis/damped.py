"""Critical loads of damped systems ``M q'' + C q' + (K0 + p K1) q = 0`` (chapter §2.2, §2.4).

With damping, flutter is the load where a pair of eigenvalues ``s`` crosses the imaginary axis
(Hopf), and divergence the load where the unstable pair meets on the positive real axis and
becomes real. Each is found two independent ways:

- ``method="eigenvalues"``: the spectrum of the first-order form. Flutter: Brent's method on
  ``max Re s(p)``, smooth at a simple crossing. Divergence: Brent's method on the discriminant
  ``prod (s_i - s_j)^2`` of the spectrum, across the flutter/divergence change of regime.
- ``method="routh"`` (flutter) / ``"algebraic"`` (divergence): the characteristic polynomial
  only (:mod:`.polynomial`, no eigenvalues). Flutter: bisection to machine precision on the
  exact Routh–Hurwitz verdict (:mod:`.routh`). Divergence: regimes from exact Routh and Sturm
  root counts, refined with Brent's method on the resultant ``Res(p, p')``.

Both scan ``[start, load_max]`` first and double the window until the change is bracketed.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from fractions import Fraction

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.optimize import brentq

from flutterfriction.analysis.polynomial import (
    all_exact,
    characteristic_polynomial,
    discriminant_from_coefficients,
    regime_from_coefficients,
)
from flutterfriction.analysis.routh import routh_hurwitz
from flutterfriction.analysis.stability import Regime, classify, classify_rows, discriminant
from flutterfriction.errors import (
    ConvergenceError,
    ParameterError,
    check_finite_array,
    check_integer,
    check_real,
)

Matrix = NDArray[np.float64]


def state_matrices(M: Matrix, C: Matrix, K0: Matrix, K1: Matrix, loads: ArrayLike) -> NDArray:
    """The first-order form's matrices ``[[0, I], [-M^-1 (K0 + P K1), -M^-1 C]]`` for many
    loads, shape (m, 2n, 2n)."""
    p = np.atleast_1d(np.asarray(loads, dtype=float))
    n = M.shape[0]
    Minv = np.linalg.inv(M)
    A = np.zeros((p.size, 2 * n, 2 * n))
    A[:, :n, n:] = np.eye(n)
    A[:, n:, :n] = -(Minv @ K0)[None] - p[:, None, None] * (Minv @ K1)[None]
    A[:, n:, n:] = -Minv @ C
    return A


def state_spectra(M: Matrix, C: Matrix, K0: Matrix, K1: Matrix, loads: ArrayLike) -> NDArray:
    """Spectra of the first-order form for many loads in one batched call, shape (m, 2n)."""
    return np.linalg.eigvals(state_matrices(M, C, K0, K1, loads))


class _System:
    """The damped system; given exact matrices (every entry a fraction or an integer, n <= 2;
    otherwise doubles), its
    characteristic polynomial is exact at every load (a float load is a rational), so the
    Routh, Sturm and Hurwitz verdicts are exact for the system itself, not only for rounded
    coefficients; the eigenvalue methods use the matrices rounded to doubles."""

    def __init__(self, M: ArrayLike, C: ArrayLike, K0: ArrayLike, K1: ArrayLike) -> None:
        given = [np.asarray(x) for x in (M, C, K0, K1)]
        n = given[0].shape[0] if given[0].ndim == 2 else 0
        # (an outside audit: NaN or singular M, mismatched shapes gave numpy's tracebacks)
        try:
            self.M, self.C, self.K0, self.K1 = (
                check_finite_array(name, x.astype(float) if x.dtype == object else x, (n, n),
                                   "a finite square matrix of M's shape")
                for name, x in zip(("M", "C", "K0", "K1"), given, strict=True))
        except ParameterError:
            raise
        except (TypeError, ValueError):  # entries that are not numbers
            raise ParameterError("M, C, K0, K1 must be real square matrices of one shape") \
                from None
        try:  # singular exactly (a rank test would refuse valid masses spanning 1e18)
            if n == 0:
                raise np.linalg.LinAlgError
            np.linalg.solve(self.M, np.eye(n))
        except np.linalg.LinAlgError:
            raise ParameterError("M must be a nonsingular square matrix (the mass matrix)") \
                from None
        if not np.any(self.C):
            raise ParameterError("C must be non-zero: use the coalescence solver when undamped")
        self.in_load = None
        if all_exact(*given) and given[0].shape[0] <= 2:
            # Each coefficient is a polynomial of degree <= 2 in the load (a 2x2 determinant
            # of entries linear in it): its three exact coefficients, from the exact
            # polynomial at loads 0, 1, 2 (~3x cheaper per load than expanding the
            # determinant in fractions).
            M_, C_, K0_, K1_ = given
            c0, c1, c2 = (characteristic_polynomial(M_, C_, K0_ + Fraction(k) * K1_)
                          for k in (0, 1, 2))
            quadratic = (c2 - 2 * c1 + c0) / 2
            terms = (c0, c1 - c0 - quadratic, quadratic)
            # in integers over one common denominator: a load n/d (every double is one) then
            # costs three integer products per coefficient
            den = math.lcm(*(x.denominator for t in terms for x in t))
            self.in_load = (den, [[x.numerator * (den // x.denominator) for x in t]
                                  for t in terms])

    def spectra(self, loads: ArrayLike) -> NDArray:
        return state_spectra(self.M, self.C, self.K0, self.K1, loads)

    def coefficients(self, load: float) -> NDArray:
        if self.in_load is not None:
            n, d = float(load).as_integer_ratio()
            den, (a0, a1, a2) = self.in_load
            scale = den * d * d
            return np.array([Fraction(x * d * d + y * n * d + z * n * n, scale)
                             for x, y, z in zip(a0, a1, a2, strict=True)], dtype=object)
        return characteristic_polynomial(self.M, self.C, self.K0 + load * self.K1)

    def regime_eigen(self, load: float) -> Regime:
        return classify(self.spectra([load])[0])

    def regime_algebraic(self, load: float) -> Regime | None:
        try:
            return regime_from_coefficients(self.coefficients(load))
        except ConvergenceError:  # exactly on a boundary: no verdict at this load
            return None


def _scan(regime_of: Callable[[float], Regime | None], target: Callable[[Regime], bool],
          start: float, load_max: float, n_scan: int, max_doublings: int,
          regimes_of: Callable[[NDArray], list[Regime | None]] | None = None,
          past: str = "unstable") -> tuple[float, float]:
    """First bracket ``[a, b]`` with ``not target(regime(a))`` and ``target(regime(b))``.
    ``regimes_of``: the same verdicts for a whole grid at once (one batched eigenvalue call),
    else ``regime_of`` point by point (the exact verdicts stop at the first target)."""
    # (an outside audit: started beyond the onset, the exact verdicts returned the start
    # load plus a rounding error as the onset)
    r0 = regime_of(start)
    if r0 is not None and target(r0):
        raise ConvergenceError(f"already {past} at the start load {start:g}: the onset lies "
                               f"below it")
    lo = start
    hi = load_max
    for _ in range(max_doublings):
        if not hi < _LOAD_LIMIT:
            break
        previous = lo
        grid = np.linspace(lo, hi, n_scan + 1)[1:]
        verdicts = regimes_of(grid) if regimes_of is not None else None
        for i, p in enumerate(grid):
            r = verdicts[i] if verdicts is not None else regime_of(float(p))
            if r is None:
                continue
            if target(r):
                return previous, float(p)
            previous = float(p)
        lo, hi = hi, 2 * hi
    raise ConvergenceError(f"no change of regime found up to load {lo:g}")


#: The scans stop doubling their window here (before the double range ends).
_LOAD_LIMIT = 1e300


def _check_scan(start: float, load_max: float, n_scan: int, max_doublings: int
                ) -> tuple[float, float, int, int]:
    """The scan's arguments, refused by name before any work (an outside audit: load_max = -1
    returned -1.8e16, n_scan = 0 said "already unstable")."""
    start = check_real("start", start)
    load_max = check_real("load_max", load_max)
    if not start < load_max < _LOAD_LIMIT:
        raise ParameterError(f"load_max must be in (start, {_LOAD_LIMIT:g}) = ({start:g}, "
                             f"{_LOAD_LIMIT:g}), got {load_max:g}")
    return (start, load_max, check_integer("n_scan", n_scan, 1, 100_000),
            check_integer("max_doublings", max_doublings, 1, 2000))


def _bisect(is_after: Callable[[float], bool], a: float, b: float) -> float:
    """Bisection to adjacent floats: the transition of a boolean verdict, to machine precision."""
    for _ in range(200):
        mid = 0.5 * (a + b)
        if mid <= a or mid >= b:
            return b
        if is_after(mid):
            b = mid
        else:
            a = mid
    return b


def flutter_onset(M: ArrayLike, C: ArrayLike, K0: ArrayLike, K1: ArrayLike, *,
                  method: str = "eigenvalues", start: float = 0.0, load_max: float = 1.0,
                  n_scan: int = 256, max_doublings: int = 60) -> float:
    """Smallest load above ``start`` where the damped system loses stability (the window
    ``(start, load_max]`` scanned in ``n_scan`` steps, then doubled at most ``max_doublings``
    times; ConvergenceError if the system is unstable at ``start`` or none is found)."""
    start, load_max, n_scan, max_doublings = _check_scan(start, load_max, n_scan, max_doublings)
    sys_ = _System(M, C, K0, K1)
    if method == "eigenvalues":
        def growth(p: float) -> float:
            return float(sys_.spectra([p])[0].real.max())

        # Bracket on the raw sign of max Re s (a tolerance-based classification would bias the
        # bracket when fast, strongly damped modes set the spectral scale), then Brent.
        lo, hi = start, load_max
        for _ in range(max_doublings):
            if not hi < _LOAD_LIMIT:
                break
            grid = np.linspace(lo, hi, n_scan + 1)
            g = sys_.spectra(grid).real.max(axis=1)
            up = np.nonzero(g > 0)[0]
            if up.size:
                i = int(up[0])
                if i == 0:
                    s0 = sys_.spectra([grid[0]])[0]
                    # Round-off of a computed eigenvalue: a modest multiple of eps ||A||, with
                    # ||A|| >= max|s|; 1000 eps max|s| is the level below which Re s carries no
                    # sign (as in :func:`~.stability.classify`).
                    if g[0] <= 1000 * np.finfo(float).eps * float(np.max(np.abs(s0))):
                        raise ConvergenceError(
                            f"the growth rate at the start load {lo:g} is at round-off level "
                            f"(max Re s = {g[0]:.3g}, max |s| = {np.max(np.abs(s0)):.3g}): the "
                            f"damping is too small for the eigenvalue crossing to resolve; use "
                            f"the exact Routh-Hurwitz method")
                    raise ConvergenceError(f"already unstable at the start load {lo:g}")
                return float(brentq(growth, grid[i - 1], grid[i],
                                    xtol=4 * np.finfo(float).eps * abs(grid[i])))
            lo, hi = hi, 2 * hi
        raise ConvergenceError(f"no loss of stability found up to load {lo:g}")
    if method == "routh":
        def unstable(p: float) -> bool:
            return not routh_hurwitz(sys_.coefficients(p)).stable

        a, b = _scan(lambda p: Regime.FLUTTER if unstable(p) else Regime.STABLE,
                     lambda r: r != Regime.STABLE, start, load_max, n_scan, max_doublings)
        return _bisect(unstable, a, b)
    raise ParameterError(f"method must be 'eigenvalues' or 'routh', got {method!r}")


#: Relative Newton step below which :func:`polish_flutter_onset` accepts a stalled iteration
#: (100x below its 1e-6 acceptance window; the measured round-off of the steps is <= 2e-9).
_POLISH_STALL = 1e-8


def polish_flutter_onset(M: ArrayLike, C: ArrayLike, K0: ArrayLike, K1: ArrayLike,
                         load: float, max_iterations: int = 12) -> float:
    """The flutter load near ``load``: :func:`polish_flutter_crossing`'s load."""
    return polish_flutter_crossing(M, C, K0, K1, load, max_iterations)[0]


def polish_flutter_crossing(M: ArrayLike, C: ArrayLike, K0: ArrayLike, K1: ArrayLike,
                            load: float, max_iterations: int = 12, rtol: float = 1e-6
                            ) -> tuple[float, float]:
    """The flutter load near ``load`` (e.g. :func:`flutter_onset`'s) and the pulsation ``w`` of
    the crossing pair there, to round-off of the matrices themselves: Newton on the quadratic
    eigenproblem at the crossing, ``(K0 + P K1 - w^2 M + i w C) x = 0`` with ``c^H x = 1``,
    unknowns ``x``, ``w``, ``P``.

    Why: :func:`flutter_onset` finds where the largest ``Re s`` of the first-order form
    changes sign, and a computed eigenvalue carries an absolute error ~eps ``max|s|``; with
    stiff, strongly damped modes (the rod's Kelvin–Voigt modes, ``max|s|`` ~1e7 at 32
    elements) that puts a round-off floor under the load (measured: 6e-9 relative at 32
    elements, 5e-8 at 48, moving with the scan's grid). The quadratic residual is exact to
    eps relative to its own terms: the polished load does not move with the grid (3e-13 at
    32 elements, 1e-12 at 48) and converges at h^4 where the raw one stalls. Where the
    residual's own round-off, eps |K| |x|, exceeds 1e-11 (the rod's FE twin: 1e-10 relative
    at 48 elements, up to 8e-9 at 96-128), Newton's steps stall there and the load is
    returned to that precision once a step no longer halves (below 1e-8 relative). Newton
    starts from the pair with the largest growth rate at ``load``. Refused
    (:class:`ConvergenceError`)
    if Newton does not converge, lands more than ``rtol`` (relative) away from ``load`` (a
    caller holding a bracket of the crossing may pass its width), or another pair is unstable
    at the result beyond round-off (1000 eps max|s|), or the crossing has no pulsation
    (``w <= 1e-10 max|s|``: a real root through zero, divergence)."""
    # bad input refused before any work (a review: C = 0 returned a point of the undamped
    # problem's curve of solutions, a NaN load a LinAlgError)
    if isinstance(rtol, bool) or not isinstance(rtol, int | float) or not 0 < rtol < 1:
        raise ParameterError(f"rtol must be a number in (0, 1), got {rtol!r}")
    load = check_real("load", load)
    shape = np.shape(M)
    if len(shape) != 2 or shape[0] != shape[1] or shape[0] == 0:
        raise ParameterError(f"M must be a non-empty square matrix, got shape {shape}")
    M, C, K0, K1 = (check_finite_array(name, X, shape, f"a finite array of M's shape {shape}")
                    for name, X in (("M", M), ("C", C), ("K0", K0), ("K1", K1)))
    if not np.any(C):
        raise ParameterError("C must be non-zero: an undamped system has no crossing to "
                             "polish (its flutter is a coalescence)")
    n = M.shape[0]

    def newton(w: float, x: NDArray) -> tuple[float, float]:
        c = x / np.vdot(x, x)  # normalisation c^H x = 1
        P = float(load)

        def step(x: NDArray, w: float, P: float) -> tuple[NDArray, float, float, float]:
            Q = K0 + P * K1 - w * w * M + 1j * w * C
            r = np.concatenate([Q @ x, [np.vdot(c, x) - 1.0]])
            J = np.zeros((n + 1, n + 2), dtype=complex)
            J[:n, :n], J[n, :n] = Q, c.conj()
            J[:n, n], J[:n, n + 1] = (-2 * w * M + 1j * C) @ x, K1 @ x
            # real unknowns (Re dx, Im dx, dw, dP) against real and imaginary residuals
            JR = np.block([[J[:, :n].real, -J[:, :n].imag, J[:, n:].real],
                           [J[:, :n].imag, J[:, :n].real, J[:, n:].imag]])
            d = np.linalg.solve(JR, -np.concatenate([r.real, r.imag]))
            return x + d[:n] + 1j * d[n:2 * n], w + d[2 * n], P + d[2 * n + 1], abs(d[2 * n + 1])

        previous = math.inf
        for _ in range(max_iterations):
            x, w, P, dP = step(x, w, P)
            if dP <= 1e-11 * abs(P):
                # converging quadratically: one more step reaches the residual's round-off
                # (a tighter test on dP alone can stall on that round-off, ~1e-15 relative)
                _, w, P, _ = step(x, w, P)
                return P, w
            if dP <= _POLISH_STALL * abs(P) and dP >= 0.5 * previous:
                # no longer converging: the steps are the residual's round-off, eps |K| |x|
                # (a fine FE mesh's stiffness; measured on the rod's FE twin: steps of 1e-11
                # relative at 32 elements, 1e-10 at 48 and 64, 1e-9 at 96 and 128, wandering
                # without end); any iterate is the load to that precision
                return P, w
            previous = dP
        raise ConvergenceError(f"polishing the flutter load {load:g}: Newton did not converge")

    ev, V = np.linalg.eig(state_matrices(M, C, K0, K1, load)[0])
    upper = np.flatnonzero(ev.imag > 0)
    if not upper.size:
        raise ConvergenceError(f"no oscillating pair at the flutter load {load:g}")
    # Candidates: the pairs with the largest growth rates at ``load`` (the crossing pair is
    # the largest above the crossing, but just below it a lightly damped pair may lie nearer
    # the axis: an outside review), each polished and accepted only if it is a crossing
    # within ``rtol`` of ``load`` where no other pair is unstable beyond round-off.
    # every candidate's reason, so that a refusal names the one that applies (a review: the
    # first candidate's "no crossing within rtol" hid the divergence's "no pulsation")
    reasons: list[str] = []
    for k in upper[np.argsort(-ev[upper].real)][:3]:
        try:
            P, w = newton(float(ev[k].imag), V[:n, k])
        except (ConvergenceError, np.linalg.LinAlgError) as exc:
            reasons.append(str(exc))
            continue
        if not abs(P - load) <= rtol * abs(load):
            reasons.append(
                f"polishing the flutter load {load:g}: no flutter crossing within {rtol:g} of it "
                f"(Newton reached {P:g})")
            continue
        at = state_spectra(M, C, K0, K1, P)[0]
        scale = np.abs(at).max()
        if abs(w) <= 1e-10 * scale:
            # a real root through 0 (divergence): the pair that met there is no oscillation
            # (an outside audit: a start just below a divergence returned w = 6e-32)
            reasons.append(
                f"polishing the flutter load {load:g}: the crossing at {P:g} has no pulsation "
                f"(w = {abs(w):.3g}): a divergence, not flutter")
            continue
        # the other roots, without the crossing pair itself: just past a coalescence its own
        # growth rate rises like sqrt(P - P_c), and the polished load's round-off (1e-8) gave
        # it Re s ~ 1e-3 (an outside audit: the Beck rod with external damping 1e-6)
        others = np.ones(at.size, dtype=bool)
        others[[np.argmin(np.abs(at - 1j * w)), np.argmin(np.abs(at + 1j * w))]] = False
        if at[others].real.max(initial=-np.inf) > 1000 * np.finfo(float).eps * scale:
            reasons.append(
                f"polishing the flutter load {load:g}: at {P:g} another pair is already "
                f"unstable (Re s = {at[others].real.max():.3g})")
            continue
        return P, abs(w)
    raise ConvergenceError("; ".join(dict.fromkeys(reasons)))


def confirm_onset(M: ArrayLike, C: ArrayLike, K0: ArrayLike, K1: ArrayLike, load: float,
                  kind: str, rel: float = 1e-6) -> float:
    """``load`` (an onset found from eigenvalues) if the exact verdicts of the characteristic
    polynomial agree that the regime changes within ``rel`` of it (Routh–Hurwitz for
    ``kind="flutter"``: stable just below, unstable just above; Routh/Sturm counts for
    ``kind="divergence"``: divergence just above, not just below); else ConvergenceError.

    Why: where the spectrum spans many decades (extreme length or stiffness ratios), the
    computed eigenvalues' round-off can move the crossing far from the true one without any
    sign (measured by an outside audit: 1.2e-5 to 0.67 relative errors). The exact verdicts on
    the polynomial do not depend on the eigenvalues (used for the pendulum's quartic; the
    rod's high-degree FE polynomials are checked against eq. 118 instead). ``rel`` = 1e-6 is
    ~1e4 times the eigenvalue methods' error where they are reliable (<= 1e-10 on the
    chapter's systems)."""
    load, rel = check_real("load", load), check_real("rel", rel)  # (not "coeffs": an audit)
    if not 0 < rel < 1:
        raise ParameterError(f"rel must be in (0, 1), got {rel!r}")
    sys_ = _System(M, C, K0, K1)
    below, above = load * (1 - rel), load * (1 + rel)
    if kind == "flutter":
        ok = (routh_hurwitz(sys_.coefficients(below)).stable
              and not routh_hurwitz(sys_.coefficients(above)).stable)
    elif kind == "divergence":
        r_below, r_above = sys_.regime_algebraic(below), sys_.regime_algebraic(above)
        ok = r_below != Regime.DIVERGENCE and r_above in (Regime.DIVERGENCE, None)
    else:
        raise ParameterError(f"kind must be 'flutter' or 'divergence', got {kind!r}")
    if not ok:
        raise ConvergenceError(
            f"the eigenvalue method's {kind} load {load:.10g} is not confirmed by the exact "
            f"verdicts of the characteristic polynomial within {rel:g} of it (round-off of "
            f"eigenvalues spanning many decades); use the exact method "
            f"({'routh' if kind == 'flutter' else 'algebraic'})")
    return load


def divergence_onset(M: ArrayLike, C: ArrayLike, K0: ArrayLike, K1: ArrayLike, *,
                     method: str = "eigenvalues", start: float = 0.0, load_max: float = 1.0,
                     n_scan: int = 256, max_doublings: int = 60) -> float:
    """Smallest load above ``start`` where the motion is divergence (unstable roots all real);
    the window as :func:`flutter_onset`'s (ConvergenceError if in divergence at ``start``)."""
    start, load_max, n_scan, max_doublings = _check_scan(start, load_max, n_scan, max_doublings)
    sys_ = _System(M, C, K0, K1)
    regimes_of = None
    if method == "eigenvalues":
        regime_of = sys_.regime_eigen

        def regimes_of(loads: NDArray) -> list[Regime | None]:
            return classify_rows(sys_.spectra(loads))

        def disc(p: float) -> float:
            # Only the eigenvalues nearest the unstable ones: a product over all pairs of a
            # large spectrum loses its digits to the far, well-separated ones.
            s = sys_.spectra([p])[0]
            near = s[np.argsort(np.abs(s - s[np.argmax(s.real)]))[:4]]
            return float(discriminant(near[None, :])[0])
    elif method == "algebraic":
        regime_of = sys_.regime_algebraic

        def disc(p: float) -> float:
            return discriminant_from_coefficients(sys_.coefficients(p))
    else:
        raise ParameterError(f"method must be 'eigenvalues' or 'algebraic', got {method!r}")
    a, b = _scan(regime_of, lambda r: r == Regime.DIVERGENCE, start, load_max, n_scan,
                 max_doublings, regimes_of=regimes_of, past="in divergence")
    # Narrow the bracket on the verdict first, so that it holds this one coalescence only.
    for _ in range(20):
        mid = 0.5 * (a + b)
        r = regime_of(mid)
        if r is None:
            break
        a, b = (a, mid) if r == Regime.DIVERGENCE else (mid, b)
    if disc(a) * disc(b) < 0:
        return float(brentq(disc, a, b, xtol=4 * np.finfo(float).eps * abs(b)))
    return _bisect(lambda p: regime_of(p) == Regime.DIVERGENCE, a, b)
