"""Contact with Coulomb friction (chapter §3.1, Fig. 22): a point mass held by a normal spring
``k_N`` and a tangential spring ``k_T``, sliding on a rigid plane with friction coefficient
``mu``; forces ``p = (p_N, p_T)`` (``p_N > 0`` compressive), displacements ``u = (u_N, u_T)``.

The rate equations (140)–(141) are piecewise linear in the rate: stick ``p_dot = E u_dot``
inside the Coulomb cone ``|p_T| < mu p_N`` (eq. 127–129) or when unloading from it, slip
``p_dot = C u_dot`` (eq. 143) on it. Along a piecewise-linear displacement path the response is
therefore integrated *exactly*, splitting each segment where the force reaches the cone.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from flutterfriction.errors import (
    ConvergenceError,
    ParameterError,
    check_finite_array,
    check_positive,
    named_parameters,
)


@named_parameters
@dataclass(frozen=True)
class CoulombContact:
    """Normal and tangential spring stiffnesses [N/m] and friction coefficient, all > 0."""

    k_N: float
    k_T: float
    mu: float

    def __post_init__(self) -> None:
        object.__setattr__(self, "k_N", check_positive("k_N", self.k_N, "N/m"))
        object.__setattr__(self, "k_T", check_positive("k_T", self.k_T, "N/m"))
        object.__setattr__(self, "mu", check_positive("mu", self.mu))

    def elastic_matrix(self) -> NDArray:
        """``E`` of eq. (129)."""
        return np.diag([self.k_N, self.k_T])

    def friction_function(self, p: ArrayLike) -> float:
        """``f = |p_T| - mu p_N`` (eq. 128)."""
        return self._friction(check_finite_array("p", p, (2,), "two finite numbers (p_N, p_T)"))

    def _friction(self, p: NDArray) -> float:
        """:meth:`friction_function` of a checked force (the path's inner loop)."""
        return abs(p[1]) - self.mu * p[0]

    @staticmethod
    def _side(p: ArrayLike, side: float | None) -> float:
        if side is not None:
            return 1.0 if side >= 0 else -1.0
        return float(np.sign(np.asarray(p, dtype=float)[1])) or 1.0

    def gradient(self, p: ArrayLike, side: float | None = None) -> NDArray:
        """``a = [-mu, sgn p_T]`` (eq. 131): normal to the Coulomb cone. At the apex
        (``p_T = 0``) the side of the cone must be given (``side`` = +1 or -1)."""
        return np.array([-self.mu, self._side(p, side)])

    def slip_direction(self, p: ArrayLike, side: float | None = None) -> NDArray:
        """``b = [0, sgn p_T]`` (eq. 136): not parallel to ``a``, the model is nonassociative."""
        return np.array([0.0, self._side(p, side)])

    def slip_operator(self, p: ArrayLike, side: float | None = None) -> NDArray:
        """``C = E - (E b) (x) (E a) / (a . E b)`` (eq. 143), unsymmetric."""
        E, a, b = self.elastic_matrix(), self.gradient(p, side), self.slip_direction(p, side)
        return E - np.outer(E @ b, E.T @ a) / (a @ E @ b)

    def cone_tolerance(self, p: NDArray) -> float:
        """Round-off of the friction function at ``p``: relative to its terms ``|p_T|`` and
        ``mu p_N`` only (with ``mu ~ 1e5`` a force on the cone missed it by 1e-7 and a stick
        step never advanced). No absolute floor and no ``p_N`` alone: a second outside audit
        found forces well inside the cone taken as on it, so a stick step slipped and ``p_T``
        froze (1 pN forces; ``mu = 1e-13``; ``mu = 1e-10`` 0.5 % inside the cone). Not the
        segment's increment either (it would take a stick start as on the cone); a piece that
        reaches the cone is put on it (:func:`integrate_path`)."""
        return 1e-12 * max(abs(p[1]), self.mu * abs(p[0]))

    def check_admissible(self, name: str, p: NDArray) -> None:
        """Refuse a force outside the model: tensile ``p_N < 0`` or outside the cone."""
        if p[0] < 0 or self._friction(p) > self.cone_tolerance(p):
            raise ParameterError(f"{name} = {p.tolist()} is outside the Coulomb cone "
                                 f"|p_T| <= mu p_N with p_N >= 0 (mu = {self.mu:g})")

    def rate(self, p: ArrayLike, u_dot: ArrayLike) -> NDArray:
        """``p_dot`` of eq. (140) at the force ``p`` for the displacement rate ``u_dot``."""
        p, u_dot = (check_finite_array(name, x, (2,), "two finite numbers (normal, tangential)")
                    for name, x in (("p", p), ("u_dot", u_dot)))
        self.check_admissible("p", p)  # (an outside audit: p_T = 5 mu p_N gave a rate)
        E = self.elastic_matrix()
        if p[0] <= 0 and (E @ u_dot)[0] < 0:
            raise ParameterError("u_dot separates the contact at p_N = 0 (p_N would turn "
                                 "tensile): not modelled (chapter §3.1: contact only), as "
                                 "integrate_path")
        if self._friction(p) < -self.cone_tolerance(p):
            return E @ u_dot
        # At the apex (p_T = 0) the side of the cone is the one the elastic trial rate leaves
        # by (an outside audit: the default side +1 let p_T = (0, 0) -> (0, -3) stick out of
        # the cone for u_dot = (0, -1), while (0, +1) slipped)
        side = (1.0 if (E @ u_dot)[1] >= 0 else -1.0) if p[1] == 0 else None
        a, b = self.gradient(p, side), self.slip_direction(p, side)
        lam = max(a @ E @ u_dot, 0.0) / (a @ E @ b)  # Macaulay bracket: slip only if > 0
        return E @ u_dot - lam * (E @ b)


@dataclass(frozen=True)
class ContactPath:
    """Forces along a displacement path, with the slip and the branch of each piece."""

    u: NDArray  # (n, 2) displacements at the recorded points
    p: NDArray  # (n, 2) forces
    slip: NDArray  # (n,) accumulated tangential slip u_T^s
    branch: list[str]  # for the piece ending at each point: "start", "stick" or "slip"


def integrate_path(contact: CoulombContact, vertices: ArrayLike,
                   p0: ArrayLike = (0.0, 0.0)) -> ContactPath:
    """Exact response to the piecewise-linear displacement path through ``vertices`` (m, 2).

    Within a segment the rate is constant; the branch changes only where the force reaches
    the cone (computed exactly), so every piece is linear. ``p0`` must be admissible
    (``p_N >= 0``, ``|p_T| <= mu p_N``).
    """
    try:
        V = np.asarray(vertices, dtype=float)
    except (ValueError, TypeError):  # strings, ragged nesting (an outside audit: a traceback)
        V = np.empty((0, 0))
    if V.ndim != 2 or V.shape[1] != 2 or len(V) < 2 or not np.all(np.isfinite(V)):
        raise ParameterError("vertices must be a finite (m >= 2, 2) array of (u_N, u_T)")
    p = check_finite_array("p0", p0, (2,), "two finite numbers (p_N, p_T)").copy()
    contact.check_admissible("p0", p)
    E = contact.elastic_matrix()
    # forces of every segment (and their sums along the path) within the double range: an
    # outside audit's 1e308 m overflowed in E du and was refused only as "no slip"
    with np.errstate(over="ignore", invalid="ignore"):
        reach = (float(np.abs(E).max()) * float(np.abs(np.diff(V, axis=0)).sum())
                 + float(np.abs(p).sum()))
    if not reach < 1e300:
        raise ParameterError(f"vertices: the path's forces (stiffness x displacements, "
                             f"~{reach:.3g} N) leave the double range; rescale the path")
    us, ps, slips, branches = [V[0].copy()], [p.copy()], [0.0], ["start"]
    slip = 0.0
    for u_a, u_b in zip(V[:-1], V[1:], strict=True):
        du = u_b - u_a
        t = 0.0
        pieces = 0
        while t < 1.0 - 1e-15:
            # within one linear segment the branch changes at most a few times (stick, cross
            # to the other side of the cone, slip): more means no progress (a bound, not a hang)
            pieces += 1
            if pieces > 8:
                raise ConvergenceError(
                    f"the contact path did not advance on the segment {u_a} -> {u_b} (the force "
                    f"{p} stays at the cone's edge to round-off)")
            tol = contact.cone_tolerance(p)
            p_start = p
            dp_trial = E @ du
            # The side of the cone: sgn p_T, or at the apex the direction of the trial rate.
            side = np.sign(p[1]) if abs(p[1]) > tol else (np.sign(dp_trial[1]) or 1.0)
            on_cone = contact._friction(p) >= -tol
            a, b = contact.gradient(p, side), contact.slip_direction(p, side)
            if on_cone and a @ dp_trial > 0:  # plastic loading: slip to the end of the segment
                lam = (a @ dp_trial) / (a @ E @ b) * (1.0 - t)
                # eq. (143) in closed form, C = [[k_N, 0], [mu k_N sgn p_T, 0]]: the force stays
                # on the cone by construction (its generic form's C22 = k_T - k_T k_T/k_T rounds
                # to ~eps k_T, which a long slip carried off a small cone; a review)
                p_N = p[0] + contact.k_N * du[0] * (1.0 - t)
                p = np.array([p_N, side * contact.mu * p_N])
                slip += lam * b[1]
                t = 1.0
                branch = "slip"
            else:  # stick: elastic until the force reaches the cone (either side) or the end
                dp = E @ du
                t_hit, hit_side = 1.0, None
                for s in (1.0, -1.0):  # f = s p_T - mu p_N reaches 0
                    rate = s * dp[1] - contact.mu * dp[0]
                    val = s * p[1] - contact.mu * p[0]
                    if rate > 0 and val < 0 and t + (-val / rate) <= t_hit:
                        t_hit, hit_side = t + (-val / rate), s
                t_new = min(t_hit, 1.0)
                p = p + dp * (t_new - t)
                if hit_side is not None:
                    # it reached the cone: put it there (its rounding, relative to the step,
                    # could leave it inside by more than the cone's round-off near the apex,
                    # and the next piece would not advance; a review)
                    on = hit_side * contact.mu * p[0]
                    if abs(p[0]) <= 1e-12 * (abs(p_start[0]) + abs(dp[0])):
                        # at the apex what it moves p_T by is slip, not round-off (the cone
                        # reached p_T at t = 1 - 1e-19, rounded to the segment's end, and
                        # dragged it to 0): kept so that u_T = p_T/k_T + slip (an outside
                        # audit: with k_N/k_T = 1e12 a 1e-7 m slip was lost)
                        slip += (p[1] - on) / contact.k_T
                    p[1] = on
                t = t_new
                branch = "stick"
            if p[0] < 0:  # on either branch: a slip through the apex separates too
                # unless it is a return to p_N = 0 rounded below it (the exact path touches
                # the apex and goes on; a review found such paths refused as separating)
                scale = 1e-12 * (abs(p_start[0]) + abs(contact.k_N * du[0]))
                if p[0] >= -scale and abs(p[1]) <= contact.mu * scale:
                    # the cone shrinks to its apex and drags p_T to 0: that is slip, p_T/k_T
                    # of it (dropped before, u_T = p_T/k_T + slip broke: with k_N/k_T = 1e12
                    # the whole 1e-7 m slip was lost; an outside audit)
                    slip += p[1] / contact.k_T
                    p = np.zeros(2)
                else:
                    raise ParameterError("the path separates the contact (p_N < 0): not "
                                         "modelled (chapter §3.1: contact only)")
            us.append(u_a + t * du)
            ps.append(p.copy())
            slips.append(slip)
            branches.append(branch)
    return ContactPath(u=np.array(us), p=np.array(ps), slip=np.array(slips), branch=branches)
