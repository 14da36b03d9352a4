"""Numerical stability analysis of the Ziegler pendulum (chapter §2.2–2.3), from its matrices only.

These are the numerical twins of the closed forms in :mod:`flutterfriction.closed_forms.ziegler`:
nothing here uses the chapter's formulas (19)–(48).
"""

from __future__ import annotations

from dataclasses import asdict, dataclass

import numpy as np
import scipy.linalg as sla
from numpy.typing import ArrayLike, NDArray

from flutterfriction.analysis.damped import divergence_onset, flutter_onset
from flutterfriction.analysis.stability import (
    Regime,
    classify,
    coalescence_loads,
    first_order_matrix,
    state_eigenvalues,
    static_bifurcation_loads,
)
from flutterfriction.errors import ConvergenceError, check_real
from flutterfriction.models.ziegler import ZieglerPendulum


@dataclass(frozen=True)
class CriticalLoads:
    """Critical loads of the pendulum [N]; ``None`` when a load does not exist.

    ``P_flu``, ``P_div`` are for the pendulum's own hinge viscosities (damped flutter is the
    Hopf crossing, damped divergence the load where the unstable pair becomes real);
    ``P_flu_undamped``, ``P_div_undamped`` for viscosity absent "from the beginning". The dead
    loads ``H_cr``, ``H_sup`` are quasi-static and do not depend on viscosity (§2.2, after eq. 31).
    """

    P_flu: float | None
    P_div: float | None
    H_cr: float | None
    H_sup: float | None
    P_flu_undamped: float | None = None
    P_div_undamped: float | None = None

    def as_dict(self) -> dict[str, float | None]:
        return asdict(self)


def follower_critical_loads(pendulum: ZieglerPendulum, n_scan: int = 512,
                            max_doublings: int = 60) -> tuple[float, float]:
    """Flutter and divergence loads ``(P_flu, P_div)`` [N] under the follower load alone (H = 0).

    Both are coalescence points of the eigenvalues ``Omega^2`` of ``(K + P dG/dP, M)`` (eq. 14),
    found by :func:`~flutterfriction.analysis.stability.coalescence_loads`. The scan window
    starts at ``4 k2/l1`` and doubles until both coalescences are bracketed.
    """
    K, G1, M = (pendulum.stiffness_matrix(), pendulum.follower_load_matrix(),
                pendulum.mass_matrix())
    load_max = 4.0 * max(pendulum.k1, pendulum.k2) / pendulum.l1
    for _ in range(max_doublings):
        roots = coalescence_loads(K, G1, M, load_max, n_scan)
        if len(roots) >= 2:
            if len(roots) > 2:
                raise ConvergenceError(f"expected two coalescence loads, found {roots}")
            return roots[0], roots[1]
        load_max *= 2.0
    raise ConvergenceError(
        f"no flutter/divergence coalescence bracketed up to P = {load_max:g} N "
        f"(flutter interval narrower than the scan step?)")


def dead_critical_loads(pendulum: ZieglerPendulum) -> tuple[float, float]:
    """Buckling loads ``(H_cr, H_sup)`` [N] under the dead load alone (P = 0).

    Quasi-static bifurcations ``det(K + H dG/dH) = 0``, from the symmetric-definite generalised
    eigenproblem ``K a = H diag(l1, l2) a``.
    """
    loads = static_bifurcation_loads(pendulum.stiffness_matrix(), pendulum.dead_load_matrix())
    if loads.size != 2:
        raise ConvergenceError(f"expected two buckling loads, found {loads}")
    return float(loads[0]), float(loads[1])


def is_damped(pendulum: ZieglerPendulum) -> bool:
    return pendulum.c1 > 0 or pendulum.c2 > 0


def _damped_args(pendulum: ZieglerPendulum, dead: bool = False) -> tuple:
    K1 = pendulum.dead_load_matrix() if dead else pendulum.follower_load_matrix()
    return (pendulum.mass_matrix(), pendulum.viscosity_matrix(), pendulum.stiffness_matrix(), K1)


def damped_flutter_load(pendulum: ZieglerPendulum, method: str = "routh") -> float:
    """Flutter load [N] with viscous hinges (eq. 27): the follower load at which a pair of
    eigenvalues crosses the imaginary axis. ``method``: ``"routh"`` (exact Routh–Hurwitz on the
    characteristic polynomial, the accurate one at small viscosity) or ``"eigenvalues"``."""
    return flutter_onset(*_damped_args(pendulum), method=method,
                         load_max=4 * max(pendulum.k1, pendulum.k2) / pendulum.l1)


def damped_divergence_load(pendulum: ZieglerPendulum, method: str = "eigenvalues") -> float:
    """Divergence load [N] with viscous hinges: the follower load at which the unstable pair
    becomes real. ``method``: ``"eigenvalues"`` or ``"algebraic"`` (Routh/Sturm root counts and
    the resultant of the characteristic polynomial)."""
    start = damped_flutter_load(pendulum, "eigenvalues" if method == "eigenvalues" else "routh")
    return divergence_onset(*_damped_args(pendulum), method=method, start=start,
                            load_max=2 * start)


def damped_dead_load_onset(pendulum: ZieglerPendulum, method: str = "routh") -> float:
    """First dead load [N] at which the damped pendulum loses stability (it is H_cr: §2.2)."""
    return flutter_onset(*_damped_args(pendulum, dead=True), method=method,
                         load_max=4 * max(pendulum.k1, pendulum.k2) / pendulum.l1)


def critical_loads(pendulum: ZieglerPendulum) -> CriticalLoads:
    """All critical loads of the pendulum, computed numerically from its matrices."""
    P_flu0, P_div0 = follower_critical_loads(pendulum)
    H_cr, H_sup = dead_critical_loads(pendulum)
    if is_damped(pendulum):
        P_flu, P_div = damped_flutter_load(pendulum), damped_divergence_load(pendulum)
    else:
        P_flu, P_div = P_flu0, P_div0
    return CriticalLoads(P_flu=P_flu, P_div=P_div, H_cr=H_cr, H_sup=H_sup,
                         P_flu_undamped=P_flu0, P_div_undamped=P_div0)


def spectrum(pendulum: ZieglerPendulum, P: float = 0.0, H: float = 0.0) -> NDArray:
    """Eigenvalues ``s = -i Omega`` [1/s] of the first-order form of eq. (11) plus eq. (26)."""
    K = pendulum.stiffness_matrix() + pendulum.geometric_matrix(P, H)
    return state_eigenvalues(pendulum.mass_matrix(), K, pendulum.viscosity_matrix())


def regime(pendulum: ZieglerPendulum, P: float = 0.0, H: float = 0.0) -> Regime:
    """Stable, flutter or divergence at the loads ``P``, ``H`` [N] (from the eigenvalues)."""
    return classify(spectrum(pendulum, P, H))


def linear_response(pendulum: ZieglerPendulum, P: float, H: float, state0: ArrayLike,
                    times: ArrayLike) -> NDArray:
    """Exact solution of the linear eqs. (11) + (26) at the given instants.

    ``x(t) = expm(A t) x0`` with the first-order matrix ``A``: no time stepping, so the drawn
    configurations carry no integration error.

    Parameters
    ----------
    state0 : array_like, shape (4,)
        ``[alpha1, alpha2, alpha1_dot, alpha2_dot]`` at t = 0 [rad, rad/s].
    times : array_like, shape (n,)
        Instants [s].

    Returns
    -------
    ndarray, shape (n, 4)
    """
    P = check_real("P", P)
    H = check_real("H", H)
    x0 = np.asarray(state0, dtype=float)
    if x0.shape != (4,) or not np.all(np.isfinite(x0)):
        raise ValueError(f"state0 must be 4 finite numbers, got {state0!r}")
    t = np.asarray(times, dtype=float)
    if not np.all(np.isfinite(t)):
        raise ValueError("times must be finite")
    A = first_order_matrix(pendulum.mass_matrix(),
                           pendulum.stiffness_matrix() + pendulum.geometric_matrix(P, H),
                           pendulum.viscosity_matrix())
    return np.array([sla.expm(A * ti) @ x0 for ti in t])
