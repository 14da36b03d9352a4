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

from collections.abc import Callable
from dataclasses import asdict, dataclass

import numpy as np
from numpy.typing import NDArray
from scipy.optimize import linear_sum_assignment

from flutterfriction.analysis.damped import divergence_onset, flutter_onset
from flutterfriction.analysis.stability import (
    Regime,
    _refine_roots,
    classify,
    discriminant,
    pencil_eigenvalues,
)
from flutterfriction.errors import ConvergenceError
from flutterfriction.models.rod import RodGroups, characteristic_function
from flutterfriction.models.rod_fe import assemble, fe_eigenvalues


@dataclass(frozen=True)
class RodCriticalLoads:
    """Dimensionless critical loads ``p = P l^2/B`` and pulsations ``omega~`` (eq. 106, 108);
    ``None`` where the load does not exist in the searched range (Beck: no divergence)."""

    p_flu: float | None
    omega_flu: float | None  # Im omega~ at flutter (the oscillation's pulsation)
    p_div: float | None
    omega_div: float | None  # Re omega~ of the double real root at divergence

    def as_dict(self) -> dict:
        return asdict(self)


def _fixed_scale(p: float, w: complex, g: RodGroups) -> float:
    return float(np.real(characteristic_function(p, w, g, with_exponent=True)[1]))


def _f(p, w, g: RodGroups, sigma0: float):
    """``f exp(-sigma0)``: analytic in (p, w) since the scaling is a constant."""
    F, sigma = characteristic_function(p, w, g, with_exponent=True)
    return F * np.exp(sigma - sigma0)


def _d(fun: Callable, z, h: float):
    return (fun(z + h) - fun(z - h) - 1j * fun(z + 1j * h) + 1j * fun(z - 1j * h)) / (4 * h)


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
    """Newton on the exact ``f(p, omega~) = 0`` from each guess (vectorised over guesses)."""
    w = np.asarray(guesses, dtype=complex).copy()
    sigma0 = np.real(characteristic_function(p, w, g, with_exponent=True)[1])
    h = 1e-4 * np.maximum(1.0, np.abs(w))
    for _ in range(max_iter):
        F = _f(p, w, g, sigma0)
        dF = _d(lambda z: _f(p, z, g, sigma0), w, h)
        step = F / dF
        w = w - step
        if np.all(np.abs(step) <= tol * np.maximum(1.0, np.abs(w))):
            return w
    raise ConvergenceError(f"Newton on eq. (118) did not converge at p = {p} from {guesses}")


def eigenvalues(p: float, g: RodGroups, n_modes: int = 3, n_elements: int = 16) -> NDArray:
    """The ``2 n_modes`` eigenvalues ``omega~`` of smallest modulus at load ``p``: FE guesses
    refined on the exact characteristic function; sorted by imaginary, then real part."""
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
        val = G(p, mu)
        dval = _d(lambda m: G(p, m), mu + 0j, h)
        return np.array([np.real(val), np.real(dval)])

    p, mu = _newton2(residual, np.array([p0, mu0]))
    return float(p), float(mu)


def _damped_flutter(g: RodGroups, p0: float, W0: float) -> tuple[float, float]:
    sigma0 = _fixed_scale(p0, 1j * W0, g)

    def residual(x):
        v = _f(x[0], 1j * x[1], g, sigma0)
        return np.array([np.real(v), np.imag(v)])

    p, W = _newton2(residual, np.array([p0, abs(W0)]))
    return float(p), float(abs(W))


def _damped_divergence(g: RodGroups, p0: float, w0: float) -> tuple[float, float]:
    sigma0 = _fixed_scale(p0, w0, g)

    def residual(x):
        p, w = x
        h = 1e-3 * max(1.0, abs(w))
        val = _f(p, w + 0j, g, sigma0)
        dval = _d(lambda z: _f(p, z, g, sigma0), w + 0j, h)
        return np.array([np.real(val), np.real(dval)])

    p, w = _newton2(residual, np.array([p0, w0]))
    return float(p), float(w)


def _low_pencil(fe, p: NDArray, k: int = 6) -> NDArray:
    mu = pencil_eigenvalues(fe.K_B, fe.load_matrix(), fe.M, p)
    idx = np.argsort(np.abs(mu), axis=-1)[..., :k]
    return np.take_along_axis(mu, idx, axis=-1)


def fe_critical_loads(g: RodGroups, n_elements: int, p_max: float = 80.0,
                      n_scan: int = 120) -> RodCriticalLoads:
    """Critical loads of the FE model (the independent method): the pendulum's solvers applied
    to the FE matrices. Undamped: coalescences of the lowest eigenvalues ``mu`` (Brent on their
    discriminant); damped: Re s crossing zero and the unstable pair becoming real."""
    fe = assemble(g, n_elements)
    K1 = fe.load_matrix()
    if not g.damped:
        def disc(p):
            return float(discriminant(_low_pencil(fe, np.array([p])))[0])

        grid = np.linspace(0.0, p_max, n_scan + 1)
        roots = _refine_roots(disc, grid, discriminant(_low_pencil(fe, grid)))
        out: dict = {"p_flu": None, "omega_flu": None, "p_div": None, "omega_div": None}
        for r in roots:
            after = classify(fe_eigenvalues(g, r * (1 + 1e-7), n_elements))
            if after == Regime.FLUTTER and out["p_flu"] is None:
                out["p_flu"] = r
            elif after == Regime.DIVERGENCE and out["p_div"] is None and out["p_flu"] is not None:
                out["p_div"] = r
        for key, sign in (("flu", 1.0), ("div", -1.0)):  # the pencil gives Omega^2 = -omega~^2
            if out[f"p_{key}"] is not None:
                # The double eigenvalue as the mean of the coalescing pair: well conditioned,
                # unlike either eigenvalue of a (nearly) defective pair.
                mu = np.sort_complex(_low_pencil(fe, np.array([out[f"p_{key}"]]))[0])
                i = int(np.argmin(np.abs(np.diff(mu))))
                out[f"omega_{key}"] = float(np.sqrt(sign * 0.5 * (mu[i] + mu[i + 1]).real))
        return RodCriticalLoads(**out)
    p_flu = flutter_onset(fe.M, fe.C, fe.K_B, K1, method="eigenvalues", load_max=p_max,
                          n_scan=64)
    s = fe_eigenvalues(g, p_flu, n_elements)
    omega_flu = float(np.abs(s[np.argmax(s.real)].imag))
    try:
        p_div = divergence_onset(fe.M, fe.C, fe.K_B, K1, method="eigenvalues", start=p_flu,
                                 load_max=p_max, n_scan=64, max_doublings=1)
        s = fe_eigenvalues(g, p_div, n_elements)
        omega_div = float(s[np.argmax(s.real)].real)
    except ConvergenceError:
        p_div = omega_div = None
    return RodCriticalLoads(p_flu=p_flu, omega_flu=omega_flu, p_div=p_div, omega_div=omega_div)


def critical_loads(g: RodGroups, p_max: float = 80.0, n_elements: int = 12) -> RodCriticalLoads:
    """Exact critical loads (eq. 118) to ~1e-13, Newton from FE guesses (``n_elements``)."""
    guess = fe_critical_loads(g, n_elements, p_max)
    if guess.p_flu is None:
        raise ConvergenceError(f"no flutter found for p <= {p_max}")
    if not g.damped:
        mu0 = -guess.omega_flu**2
        p_flu, mu_f = _undamped_double_root(g, guess.p_flu, mu0)
        out = {"p_flu": p_flu, "omega_flu": float(np.sqrt(-mu_f)), "p_div": None,
               "omega_div": None}
        if guess.p_div is not None:
            s = fe_eigenvalues(g, guess.p_div * (1 + 1e-6), n_elements)
            w0 = float(np.max(s.real))
            p_div, mu_d = _undamped_double_root(g, guess.p_div, w0**2)
            out.update(p_div=p_div, omega_div=float(np.sqrt(mu_d)))
        return RodCriticalLoads(**out)
    p_flu, W = _damped_flutter(g, guess.p_flu, guess.omega_flu)
    out = {"p_flu": p_flu, "omega_flu": W, "p_div": None, "omega_div": None}
    if guess.p_div is not None:
        p_div, w = _damped_divergence(g, guess.p_div, guess.omega_div)
        out.update(p_div=p_div, omega_div=w)
    return RodCriticalLoads(**out)


def continue_critical_loads(g: RodGroups, previous: RodCriticalLoads) -> RodCriticalLoads:
    """Critical loads of ``g`` by Newton from those of a nearby rod (continuation in a
    parameter): milliseconds, no FE guess. Raises :class:`ConvergenceError` if Newton fails."""
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
    return out
