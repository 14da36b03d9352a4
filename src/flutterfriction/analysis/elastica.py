"""Statics of the clamped elastica (chapter §2.5–2.6, Fig. 9): an inextensible, unshearable
Euler–Bernoulli rod of length ``l`` and bending stiffness ``B``, clamped at ``s = 0``
(eq. 96), loaded at ``s = l`` by the dead force ``P = -P1 e1 - P2 e2`` and along its axis by the
dead, uniform load ``q = q1 e1 + q2 e2`` per unit length. Geometrically exact, SI units.

The equations (eqs. 64, 77, 80, 83 with ``D = 0``, and 97):

- kinematics ``x' = t = cos(theta) e1 + sin(theta) e2`` (eq. 64), ``x(0) = 0``, ``theta(0) = 0``;
- equilibrium ``a' + q = 0`` (eq. 77) with ``a(l) = P`` (eq. 97), so that
  ``a(s) = P + (l - s) q`` is the resultant of the loads beyond the cut ``s``;
- ``M' = T = a . m`` (eqs. 73, 80) with ``m = sin(theta) e1 - cos(theta) e2`` (eq. 71);
- ``M = B theta'`` (eq. 83) and ``M(l) = 0`` (eq. 97).

Together they are eq. (91) at rest: ``B theta'' + (P1 - (l-s) q1) sin(theta)
- (P2 - (l-s) q2) cos(theta) = 0`` (eq. 92 when ``q = 0``).

Three solvers, independent of each other:

- :func:`solve_shooting` (primary): the one unknown is the end rotation ``theta(l)``;
  ``theta, M`` and the positions are integrated from the free end to the clamp (DOP853,
  dimensionless, ``rtol = 1e-12``) and Newton, with the exact derivative from the variational
  equations, makes ``theta(0) = 0``. The loads are applied in steps from zero, following the
  loading path from the straight rod: a step is halved until its equilibrium is stable
  (:func:`stability_eigenvalue`, the second variation of the energy) and Newton's correction
  small. Past the Euler load with a small transverse load the path turns sharply, and equal
  steps landed on the unstable nearly straight equilibrium or on the stable one of the other
  side (outside audits). Where the path is lost, the stable equilibrium on its side is sought
  among all roots in ``theta(l)``.
- :func:`solve_collocation`: ``scipy.integrate.solve_bvp`` on the six states
  ``x1, x2, theta, M, a1, a2`` (the internal force is a state here, eq. 77), continued in the
  load from the straight rod as well; an unstable result is refused
  (:class:`~flutterfriction.errors.ConvergenceError`), never returned.
- :func:`tip_force_closed_form`: a tip force of fixed direction only (``q = 0``): the classical
  solution by elliptic integrals (eq. 92 is the pendulum equation in ``s``), exact up to the
  one root for the end rotation, found by Brent's method to round-off.

:func:`linear_tip_deflection` is the linear (small-deflection) cantilever, eq. (95) at rest
without axial loads: ``u2(l) = -P2 l^3/(3B) + q2 l^4/(8B)``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.integrate import solve_bvp, solve_ivp
from scipy.optimize import brentq
from scipy.special import ellipeinc, ellipj, ellipkinc, ellipkm1

from flutterfriction.errors import (
    ConvergenceError,
    ParameterError,
    check_finite_result,
    check_integer,
    check_positive,
    check_real,
    named_parameters,
)

#: Gauss–Legendre rule used for every integral along the rod (per subinterval): the integrands
#: are smooth (analytic in s), so 24 nodes on each of 16 subintervals integrate them to
#: round-off.
_GL_NODES, _GL_WEIGHTS = np.polynomial.legendre.leggauss(24)
_GL_PANELS = 16


@named_parameters
@dataclass(frozen=True)
class ElasticaLoads:
    """The loads of Fig. 9, dead (fixed in direction and size) [N, N/m].

    Parameters
    ----------
    P1, P2 : float
        The end force ``P = -P1 e1 - P2 e2`` (eq. 97; ``P1 > 0`` compresses the straight rod,
        ``P2 > 0`` pushes the end towards ``-e2``) [N].
    q1, q2 : float
        The uniform load per unit length ``q = q1 e1 + q2 e2`` (eq. 89) [N/m].
    """

    P1: float = 0.0
    P2: float = 0.0
    q1: float = 0.0
    q2: float = 0.0

    def __post_init__(self) -> None:
        for f in fields(self):
            object.__setattr__(self, f.name, check_real(f.name, getattr(self, f.name)))

    def scaled(self, factor: float) -> ElasticaLoads:
        """Every load times ``factor``."""
        return ElasticaLoads(*(factor * getattr(self, f.name) for f in fields(self)))

    def tip_force(self) -> NDArray:
        """``P`` as a vector [N]."""
        return np.array([-self.P1, -self.P2])

    def distributed(self) -> NDArray:
        """``q`` as a vector [N/m]."""
        return np.array([self.q1, self.q2])


def _check_rod(length: object, B: object) -> tuple[float, float]:
    return check_positive("length", length, "m"), check_positive("B", B, "N m^2")


def _arclengths(s: ArrayLike, length: float, name: str = "s") -> NDArray:
    """``s`` as an array of arc lengths on the rod, refused (naming it) unless finite and in
    ``[0, l]``: the solutions' dense outputs would extrapolate silently beyond the rod."""
    s = np.asarray(s, dtype=float)
    if not np.all(np.isfinite(s)) or (s.size and (s.min() < -1e-12 * length
                                                  or s.max() > length * (1 + 1e-12))):
        raise ParameterError(f"{name} must be finite arc lengths in [0, l] = [0, {length:g}] m")
    return s


def internal_force(s: ArrayLike, length: float, loads: ElasticaLoads) -> NDArray:
    """``a(s) = P + (l - s) q`` [N], shape ``(..., 2)``: eq. (77) integrated from ``a(l) = P``
    (eq. 97), the resultant of the loads on the part beyond the cut (eq. 74)."""
    s = _arclengths(s, check_positive("length", length, "m"))
    return loads.tip_force() + (length - s)[..., None] * loads.distributed()


def gauss_integral(fun, a: float, b: float) -> NDArray:
    """``int_a^b fun(s) ds`` by composite Gauss–Legendre (``fun`` vectorised over ``s``,
    returning shape ``(n,)`` or ``(n, k)``)."""
    edges = np.linspace(a, b, _GL_PANELS + 1)
    half = 0.5 * np.diff(edges)
    mid = 0.5 * (edges[1:] + edges[:-1])
    s = (mid[:, None] + half[:, None] * _GL_NODES[None, :]).ravel()
    w = (half[:, None] * _GL_WEIGHTS[None, :]).ravel()
    vals = np.asarray(fun(s))
    return np.tensordot(w, vals, axes=(0, 0))


@dataclass(frozen=True)
class ElasticaSolution:
    """A computed equilibrium of the clamped elastica.

    ``state(s)`` returns ``theta`` [rad], ``M`` [N m], ``x1``, ``x2`` [m] at the arc lengths
    ``s`` [m] (rows), from the integrator's dense output (shooting) or the collocation
    polynomial (``solve_bvp``)."""

    length: float
    B: float
    loads: ElasticaLoads
    method: str
    _dense: Any  # s -> (theta, M, x1, x2), columns along s
    tip_rotation: float  # theta(l) [rad]
    clamp_residual: float  # |theta(0)| of the accepted solution [rad] (0 for collocation)
    iterations: int  # Newton iterations (shooting) or continuation steps (collocation)
    _force: Any = None  # s -> a(s) rows, when the internal force is a state (collocation)

    def state(self, s: ArrayLike) -> NDArray:
        s = np.atleast_1d(_arclengths(s, self.length))
        return np.asarray(self._dense(s)).T

    def theta(self, s: ArrayLike) -> NDArray:
        return self.state(s)[:, 0]

    def moment(self, s: ArrayLike) -> NDArray:
        """``M(s) = B theta'(s)`` [N m] (eq. 83)."""
        return self.state(s)[:, 1]

    def position(self, s: ArrayLike) -> NDArray:
        """``x(s)`` [m], rows ``(x1, x2)`` (eq. 56)."""
        return self.state(s)[:, 2:4]

    def force(self, s: ArrayLike) -> NDArray:
        """``a(s)`` [N], rows: the collocation's state where it is one, else eq. (77)
        integrated in closed form (:func:`internal_force`)."""
        s = np.atleast_1d(_arclengths(s, self.length))
        if self._force is not None:
            return np.asarray(self._force(s)).T
        return internal_force(s, self.length, self.loads)

    def normal_and_shear(self, s: ArrayLike) -> tuple[NDArray, NDArray]:
        """``N = a . t`` and ``T = a . m`` [N] (eq. 73)."""
        th = self.theta(s)
        a = self.force(s)
        t = np.column_stack([np.cos(th), np.sin(th)])
        m = np.column_stack([np.sin(th), -np.cos(th)])
        return np.sum(a * t, axis=1), np.sum(a * m, axis=1)

    def tip_displacement(self) -> NDArray:
        """``u(l) = x(l) - l e1`` [m] (eq. 55)."""
        return self.position(self.length)[0] - np.array([self.length, 0.0])


#: Elements of the stability check's discretisation (two meshes, Richardson-extrapolated:
#: linear elements with a lumped mass converge as h^2; the extrapolated eigenvalue's error is
#: below 1e-8 (l^2/B units) up to 50 Euler loads, measured against 8000 elements).
_STABILITY_ELEMENTS = (1000, 2000)


def stability_eigenvalue(sol: ElasticaSolution) -> float:
    """The lowest eigenvalue ``mu`` [-] of the second variation of the energy at the
    equilibrium ``sol``: positive for a stable equilibrium (a minimum), negative for an
    unstable one.

    The dead loads have the potential ``-int a(s) . t(theta(s)) ds`` (``a = P + (l - s) q``, the
    module docstring), so the energy is ``int [B theta'^2/2 - a . t] ds`` (its first variation
    is eq. 91) and its second variation ``int [B dtheta'^2 + N dtheta^2] ds`` with ``N = a . t``
    the normal force (eq. 73; compression ``N < 0``), ``dtheta(0) = 0``. ``mu`` is the lowest
    eigenvalue of ``-dtheta'' + N l^2/B dtheta = mu dtheta`` on ``xi = s/l`` in [0, 1] with
    ``dtheta'(1) = 0`` (natural), by linear elements (lumped) on two meshes, extrapolated. The
    straight rod under an end thrust ``P1`` gives ``mu = pi^2/4 - P1 l^2/B``: zero at the Euler
    load."""
    from scipy.linalg import eigh_tridiagonal

    l, B = sol.length, sol.B
    mus = []
    for n in _STABILITY_ELEMENTS:
        h = 1.0 / n
        xi = np.linspace(0.0, 1.0, n + 1)[1:]  # dtheta(0) = 0: the clamp's node is removed
        N = sol.normal_and_shear(xi * l)[0] * l * l / B
        w = np.full(n, h)
        w[-1] = h / 2  # lumped mass; the free end's node has half an element
        diag = np.full(n, 2.0 / h)
        diag[-1] = 1.0 / h
        diag = diag + N * w
        off = np.full(n - 1, -1.0 / h)
        # D^-1/2 (K + G) D^-1/2: a symmetric tridiagonal standard problem
        d = 1.0 / np.sqrt(w)
        mus.append(float(eigh_tridiagonal(diag * d * d, off * d[:-1] * d[1:], eigvals_only=True,
                                          select="i", select_range=(0, 0))[0]))
    return (4.0 * mus[1] - mus[0]) / 3.0


def _stability_tolerance(sol: ElasticaSolution) -> float:
    """What ``mu`` is resolved to: 1e-7 of the problem's scale (1 plus the largest ``|N|
    l^2/B``), above the discretisation's error (1e-8 up to 50 Euler loads, measured)."""
    s = np.linspace(0.0, sol.length, 201)
    return 1e-7 * (1.0 + float(np.max(np.abs(sol.normal_and_shear(s)[0]))) * sol.length**2
                   / sol.B)


def _dimensionless(length: float, B: float, loads: ElasticaLoads) -> tuple[NDArray, NDArray]:
    """``a(l) l^2/B`` and ``q l^3/B``: the loads in units of ``B/l^2`` and ``B/l^3``, refused
    (:class:`ParameterError`) outside the floating-point range (an outside audit's length of
    1e200 m raised a bare OverflowError)."""
    try:
        with np.errstate(over="ignore", invalid="ignore"):
            fP = loads.tip_force() * (length**2 / B)
            g = loads.distributed() * (length**3 / B)
    except OverflowError:
        fP = g = np.array([math.inf])
    if not (np.all(np.isfinite(fP)) and np.all(np.isfinite(g))):
        raise ParameterError(
            f"length = {length:g} m and B = {B:g} N m^2 put the loads in units of B/l^2 and "
            "B/l^3 (P l^2/B, q l^3/B) outside the floating-point range")
    return fP, g


def _shooting_rhs(xi: float, z: NDArray, fP: NDArray, g: NDArray) -> NDArray:
    """Dimensionless ``d/dxi`` of ``(theta, m, y1, y2, dtheta, dm)``, ``xi = s/l``,
    ``m = M l/B``, ``y = x/l``; the last two: the variational equations in ``theta(l)``."""
    th, m, _, _, dth, dm = z
    c, s = math.cos(th), math.sin(th)
    a1 = fP[0] + (1.0 - xi) * g[0]
    a2 = fP[1] + (1.0 - xi) * g[1]
    return np.array([m, a1 * s - a2 * c, c, s, dm, (a1 * c + a2 * s) * dth])


def _integrate_from_tip(theta_l: float, fP: NDArray, g: NDArray, rtol: float,
                        dense: bool = False):
    z0 = np.array([theta_l, 0.0, 0.0, 0.0, 1.0, 0.0])
    sol = solve_ivp(_shooting_rhs, (1.0, 0.0), z0, method="DOP853", rtol=rtol,
                    atol=rtol * 1e-2, args=(fP, g), dense_output=dense)
    if not sol.success:
        raise ConvergenceError(f"the elastica's integration failed: {sol.message}")
    return sol


def solve_shooting(length: float, B: float, loads: ElasticaLoads, *, load_steps: int = 8,
                   rtol: float = 1e-12, tol: float = 1e-13, max_iter: int = 30
                   ) -> ElasticaSolution:
    """The clamped elastica by shooting on the end rotation (module docstring).

    Parameters
    ----------
    length, B : float
        ``l`` [m] and the bending stiffness [N m^2], > 0.
    loads : ElasticaLoads
        ``P1, P2`` [N], ``q1, q2`` [N/m].
    load_steps : int
        The loads are applied from zero in steps of at most ``1/load_steps`` of them (Newton
        starts each from the extrapolation of the previous two), halved until each lands on a
        stable equilibrium near the prediction: the loading path is followed.
    rtol : float
        Relative tolerance of the integration (dimensionless; absolute ``rtol/100``).
    tol : float
        Newton stops when ``|theta(0)| <= tol`` [rad].

    Raises
    ------
    ParameterError
        Bad input, before any work; also a load beyond :data:`LOAD_RANGE_MAX` B/l^2 (B/l^3
        for ``q``; :func:`check_load_range`).
    ConvergenceError
        Newton fails or the branch folds (``d theta(0)/d theta(l)`` vanishes), and the search
        among all roots finds no stable equilibrium on the loads' side (or there is no side: no
        transverse load past the Euler load).
    """
    length, B = _check_rod(length, B)
    if not isinstance(loads, ElasticaLoads):
        raise ParameterError(f"loads must be ElasticaLoads, got {type(loads).__name__}")
    check_integer("load_steps", load_steps, 1)
    check_integer("max_iter", max_iter, 1)
    rtol = check_positive("rtol", rtol)
    tol = check_positive("tol", tol, "rad")
    fP1, g1 = _dimensionless(length, B, loads)
    check_load_range(length, B, loads)
    try:
        th, iterations = _follow_loading_path(length, B, loads, load_steps, rtol, tol,
                                              max_iter)
        return _shooting_solution(length, B, loads, th, rtol, iterations)
    except _PathLost as exc:
        # the stable equilibrium on the side the path last bent the rod to, among all roots
        failure, last = str(exc), exc.theta_l
    th = _stable_root(length, B, loads, fP1, g1, rtol, tol, max_iter, failure, last)
    return _shooting_solution(length, B, loads, th, rtol, 0)  # its stability checked there


class _PathLost(ConvergenceError):
    """The loading path could not be followed further; ``theta_l`` its last end rotation."""

    def __init__(self, message: str, theta_l: float) -> None:
        super().__init__(message)
        self.theta_l = theta_l


def _newton_on_theta(th: float, fP: NDArray, g: NDArray, rtol: float, tol: float,
                     max_iter: int) -> tuple[float, int]:
    """Newton on ``theta(0) = 0`` in the end rotation, from ``th``; raises on a fold, a
    wandering iterate (|theta(l)| > 4 pi: an outside audit saw 1e7 rad and integrations of
    minutes) or no convergence."""
    for k in range(1, max_iter + 1):
        z = _integrate_from_tip(th, fP, g, rtol).y[:, -1]
        r, dr = z[0], z[4]
        if not (np.isfinite(dr) and dr != 0.0):
            # (no threshold: far past the Euler load d theta(0)/d theta(l) is legitimately
            # ~exp(-sqrt(load)), and an absolute 1e-8 refused P2 = 1000 B/l^2; an audit)
            raise ConvergenceError(f"the elastica's branch folds (d theta(0)/d theta(l) = "
                                   f"{dr:.3g})")
        # converged: theta(0) within tol, or a correction of theta(l) below 1e-12 rad (far
        # past the Euler load theta(0) amplifies the integration's round-off by ~exp(k l), so
        # its own noise can exceed tol: P2 = 69 B/l^2 gave 4e-9 rad at dr = 1.8e3)
        if abs(r) <= tol or abs(r / dr) <= 1e-12:
            return th - r / dr, k
        # steps capped at 0.1 rad: near the loads' direction the residual is steep and full
        # steps overshot to another root (P2 = 69 B/l^2 from -1.56 to -0.83 rad; an audit)
        th -= float(np.clip(r / dr, -0.1, 0.1))
        if not abs(th) <= 4 * math.pi:
            raise ConvergenceError("Newton on theta(0) = 0 left |theta(l)| <= 4 pi")
    raise ConvergenceError(f"Newton on theta(0) = 0 did not converge (residual {r:.3g} rad)")


def _follow_loading_path(length: float, B: float, loads: ElasticaLoads, load_steps: int,
                         rtol: float, tol: float, max_iter: int) -> tuple[float, int]:
    """The end rotation at the full loads, reached along the loading path from the straight
    rod: load factor steps of at most ``1/load_steps`` (Newton from the secant predictor), a
    step accepted only if its equilibrium is stable and Newton's correction is small against
    the predicted change (a quarter of it, plus 1e-6 rad), else halved. Past the Euler load
    with a small transverse load the path turns sharply, and equal steps landed on the
    unstable nearly straight equilibrium or jumped to the stable one on the other side
    (outside audits); halving follows the turn. Raises :class:`_PathLost` (with
    the last end rotation) below a step of 1e-9."""
    fP1, g1 = _dimensionless(length, B, loads)
    lam, th, prev = 0.0, 0.0, None
    h = 1.0 / load_steps
    iterations = 0
    while lam < 1.0:
        h = min(h, 1.0 - lam)
        pred = th + (th - prev[1]) * h / (lam - prev[0]) if prev is not None else th
        try:
            new, k = _newton_on_theta(pred, (lam + h) * fP1, (lam + h) * g1, rtol, tol,
                                      max_iter)
            iterations += k
            # the correction small against the predicted change: a jump to another branch
            # (the complementary stable one appears beside the path past the Euler load) is
            # not, whatever the step; a smooth path's is, once the step is small enough
            ok = abs(new - pred) <= 0.25 * abs(pred - th) + 1e-6
            if ok:
                sol = _shooting_solution(length, B, loads.scaled(lam + h), new, rtol, 0)
                ok = stability_eigenvalue(sol) >= -_stability_tolerance(sol)
        except ConvergenceError:
            ok = False
        if ok:
            prev, lam, th = (lam, th), lam + h, new
            h = min(2.0 * h, 1.0 / load_steps)
        else:
            h *= 0.5
            if h < 1e-9:
                raise _PathLost(f"the loading path was lost at load factor {lam:.9g} (no stable "
                                f"equilibrium within a step of 1e-9)", th)
    return th, iterations


def _shooting_solution(length: float, B: float, loads: ElasticaLoads, th: float, rtol: float,
                       iterations: int) -> ElasticaSolution:
    fP, g = _dimensionless(length, B, loads)
    sol = _integrate_from_tip(th, fP, g, rtol, dense=True)
    y0 = sol.y[2:4, -1]  # the clamp's position relative to the end

    def dense(s: NDArray) -> NDArray:
        z = sol.sol(s / length)
        return np.vstack([z[0], z[1] * B / length, (z[2] - y0[0]) * length,
                          (z[3] - y0[1]) * length])

    return ElasticaSolution(length, B, loads, "shooting (DOP853, Newton on theta(l))", dense,
                            float(th), float(abs(sol.y[0, -1])), iterations)


#: End rotations scanned for every equilibrium when the continuation lands on an unstable one
#: [rad]: two turns each way in steps of 1 degree; loads up to ``_SCAN_LIMIT`` B/l^2 (their
#: equilibria, ~sqrt(load)/pi per turn, are then several scan steps apart; the scan takes
#: ~1-4 s there, measured).
_SCAN = np.linspace(-4 * math.pi, 4 * math.pi, 1441)
_SCAN_LIMIT = 200.0
#: Largest load [B/l^2, or B/l^3 per unit length] the solvers and the elastica scene take:
#: the stable equilibrium's scan range. Beyond it the cost grows fast (a pulled rod with a
#: transverse load, P1 = -2 q2 l: 11 s at 200 B/l^2, 21 s at 300, 63 s at 400, minutes at
#: 1000, measured 2026-12-06; an outside audit's 1000 did not return in 60 s) and a lost
#: loading path could not be recovered; the worst of nine load directions at 200 took 11 s.
LOAD_RANGE_MAX = _SCAN_LIMIT


def check_load_range(length: float, B: float, loads: ElasticaLoads) -> None:
    """Refuse (:class:`ParameterError`, naming the load, its range in SI units and
    :data:`LOAD_RANGE_MAX`) a load beyond ``LOAD_RANGE_MAX`` B/l^2 (``P1, P2``) or B/l^3
    (``q1, q2``): outside the range the solvers are measured on."""
    unit = B / length**2
    for key, value, scale in (("P1", loads.P1, unit), ("P2", loads.P2, unit),
                              ("q1", loads.q1, unit / length), ("q2", loads.q2, unit / length)):
        if not abs(value) <= LOAD_RANGE_MAX * scale:
            raise ParameterError(
                f"{key} must be within +-{LOAD_RANGE_MAX:g} B/l^{2 if key[0] == 'P' else 3} "
                f"= +-{LOAD_RANGE_MAX * scale:.6g} {'N' if key[0] == 'P' else 'N/m'} for "
                f"this rod (the elastica solvers' range, analysis.elastica.LOAD_RANGE_MAX), "
                f"got {value!r}")
#: The loading path's last end rotation [rad] gives the side above this; below, the rod is in
#: its linear range, where the side is the linear response's (and the path's rotation may be
#: Newton's noise).
_SIDE_FROM_PATH = 1e-6


def _stable_root(length: float, B: float, loads: ElasticaLoads, fP: NDArray, g: NDArray,
                 rtol: float, tol: float, max_iter: int, failure: str,
                 last: float = 0.0) -> float:
    """Where the loading path was lost (``last``: its last end rotation), the stable
    equilibrium it leads to: among every root of ``theta(0; theta(l)) = 0`` on :data:`_SCAN`
    (sign changes, then Newton), the stable ones on the side of ``last`` when the path had
    bent the rod (above :data:`_SIDE_FROM_PATH`), else on the side the transverse loads push
    it (the linear response at a load factor of 1e-6); of those, the least rotated. Refused: a
    perfect column (no transverse load) past its Euler load (two mirror-image equilibria), and
    a still straight rod under transverse loads pushing opposite ways (the side is their
    projection on the buckling mode, not computed here)."""
    # (the loads are within _SCAN_LIMIT: solve_shooting's check_load_range)
    side = math.copysign(1.0, last) if abs(last) > _SIDE_FROM_PATH else None
    if side is None:
        # Still nearly straight: the side the transverse loads push the rod to (Newton's
        # tolerance on theta(0) leaves theta(l) noise of either sign near the Euler load,
        # ~tol/|d theta(0)/d theta(l)|: P2 = 1e-13 B/l^2 at 1.2 Euler loads ended on the wrong
        # side; an absolute threshold on the linear response refused P2 = 1e-12 at the Euler
        # load as "no transverse load"; outside audits)
        if loads.P2 == 0.0 and loads.q2 == 0.0:
            raise ConvergenceError(
                f"{failure}; with no transverse load (P2 = q2 = 0) a rod past its Euler load "
                "may buckle to either side: give a transverse load to choose one")
        if (loads.P2 > 0.0 and loads.q2 > 0.0) or (loads.P2 < 0.0 and loads.q2 < 0.0):
            # The end force (-P2) and the distributed load (q2) push opposite ways: the side is
            # the sign of their projection on the buckling mode, not of the linear end
            # rotation (they differ for q2 l / P2 in ~(2.75, 3) at 20 Euler loads; an
            # outside review), and is not computed here
            raise ConvergenceError(
                f"{failure}; the transverse loads push opposite ways (P2 = {loads.P2:g} N, q2 "
                f"= {loads.q2:g} N/m) on a rod still straight, so the side it buckles to is "
                "not determined here: give larger transverse loads (the loading path then "
                "bends the rod before the Euler load) or one of them")
        # one transverse load, or both pushing the same way: the linear response's side
        z = _integrate_from_tip(0.0, 1e-6 * fP, 1e-6 * g, rtol).y[:, -1]
        start = -z[0] / z[4]  # the linear end rotation at a load factor of 1e-6
        if not (math.isfinite(start) and start != 0.0):
            raise ConvergenceError(
                f"{failure}; the transverse loads (P2 = {loads.P2:g} N, q2 = {loads.q2:g} "
                "N/m) are too small to choose the side in double precision")
        side = math.copysign(1.0, start)

    def residual(t: float) -> float:
        return float(_integrate_from_tip(t, fP, g, 1e-9).y[0, -1])

    r = [residual(t) for t in _SCAN]
    # Sign changes on the scan (a pair of roots closer than a degree, where theta(l) nears the
    # loads' direction far past the Euler load, can hide between two points: then no stable
    # root is found and the solver says so rather than return an unstable one)
    brackets = [(float(_SCAN[i]), float(_SCAN[i + 1]), r[i], r[i + 1])
                for i in range(len(_SCAN) - 1) if r[i] * r[i + 1] <= 0]
    candidates = []
    for a, b, ra, rb in brackets:
        th = brentq(residual, a, b, xtol=1e-12) if ra != rb else a
        try:  # polished at the full tolerance
            th, _ = _newton_on_theta(th, fP, g, rtol, tol, max_iter)
        except ConvergenceError:
            continue
        if th * side <= 0:
            continue
        cand = _shooting_solution(length, B, loads, th, rtol, 0)
        if stability_eigenvalue(cand) > _stability_tolerance(cand):
            candidates.append(th)
    if not candidates:
        raise ConvergenceError(
            f"{failure}, and no stable equilibrium bent the loads' way was found for "
            "|theta(l)| <= 4 pi")
    return min(candidates, key=abs)


def solve_collocation(length: float, B: float, loads: ElasticaLoads, *, load_steps: int = 4,
                      tol: float = 1e-10, max_nodes: int = 20000) -> ElasticaSolution:
    """The clamped elastica by collocation (``scipy.integrate.solve_bvp``) on the six states
    ``(y1, y2, theta, m, alpha1, alpha2) = (x/l, theta, M l/B, a l^2/B)`` in ``xi = s/l``:
    ``y' = t``, ``theta' = m``, ``m' = alpha . m_vec``, ``alpha' = -q l^3/B`` (eqs. 64, 83,
    80, 77), with ``y(0) = 0``, ``theta(0) = 0`` (eq. 96) and ``m(1) = 0``, ``alpha(1) = P
    l^2/B`` (eq. 97). Continued in ``load_steps`` equal load steps from the straight rod.
    Refuses (:class:`ParameterError`, before any work) bad input and a load beyond
    :data:`LOAD_RANGE_MAX` B/l^2 (B/l^3 for ``q``; :func:`check_load_range`)."""
    length, B = _check_rod(length, B)
    if not isinstance(loads, ElasticaLoads):
        raise ParameterError(f"loads must be ElasticaLoads, got {type(loads).__name__}")
    check_integer("load_steps", load_steps, 1)
    check_integer("max_nodes", max_nodes, 1)
    tol = check_positive("tol", tol)
    fP1, g1 = _dimensionless(length, B, loads)
    check_load_range(length, B, loads)

    def bc(za: NDArray, zb: NDArray, fP: NDArray) -> NDArray:
        return np.array([za[0], za[1], za[2], zb[3], zb[4] - fP[0], zb[5] - fP[1]])

    xi = np.linspace(0.0, 1.0, 41)
    z = np.zeros((6, xi.size))
    z[0] = xi
    sol = None
    for k in range(1, load_steps + 1):
        lam = k / load_steps
        fP, g = lam * fP1, lam * g1

        def rhs(x: NDArray, y: NDArray, g: NDArray = g) -> NDArray:
            c, s = np.cos(y[2]), np.sin(y[2])
            return np.vstack([c, s, y[3], y[4] * s - y[5] * c,
                              -g[0] * np.ones_like(x), -g[1] * np.ones_like(x)])

        # the intermediate loads only lead to the last: a loose tolerance is enough there
        t = tol if k == load_steps else max(tol, 1e-6)
        sol = solve_bvp(rhs, lambda za, zb, fP=fP: bc(za, zb, fP), xi, z, tol=t,
                        bc_tol=t, max_nodes=max_nodes)
        if sol.status != 0:
            raise ConvergenceError(f"solve_bvp failed at load factor {lam:g}: {sol.message}")
        xi, z = sol.x, sol.y
    assert sol is not None

    def dense(s: NDArray) -> NDArray:
        zz = sol.sol(s / length)
        return np.vstack([zz[2], zz[3] * B / length, zz[0] * length, zz[1] * length])

    def force(s: NDArray) -> NDArray:
        return sol.sol(s / length)[4:6] * B / length**2

    out = ElasticaSolution(length, B, loads, f"collocation (solve_bvp, tol {tol:g})", dense,
                           float(sol.sol(1.0)[2]), 0.0, load_steps, force)
    mu = stability_eigenvalue(out)
    if mu < -_stability_tolerance(out):
        raise ConvergenceError(
            f"collocation reached an unstable equilibrium (lowest eigenvalue of the second "
            f"variation {mu:.3g} l^2/B): past the Euler load the continuation from the straight "
            f"rod jumped to the nearly straight branch; solve_shooting finds the stable one")
    # Near a critical load the residual's tolerance buys an error ~ tol/mu in the solution
    # (an outside audit: P1 = 2.4674 B/l^2, 1e-6 below Euler's, mu = 1.2e-6: the tip rotation
    # 8e-4 off at tol 1e-10; at 1e-13, 1e-8): solved once more at tol mu 1e-8 (not below
    # 1e-13, solve_bvp's floor), and refused where even that leaves tol/mu above 1e-6.
    if tol / max(mu, 1e-300) > 1e-8 and tol > 1e-13:
        tight = max(1e-13, 1e-8 * mu)
        return _recollocated(length, B, loads, load_steps, tight, max_nodes)
    return out


def _recollocated(length: float, B: float, loads: ElasticaLoads, load_steps: int, tight: float,
                  max_nodes: int) -> ElasticaSolution:
    """:func:`solve_collocation` again at the tolerance ``tight`` (near a critical load),
    refused where the lowest eigenvalue ``mu`` still leaves ``tight/mu > 1e-6``."""
    out = solve_collocation(length, B, loads, load_steps=load_steps, tol=tight,
                            max_nodes=max_nodes)
    mu = stability_eigenvalue(out)
    if tight / max(mu, 1e-300) > 1e-6:
        raise ConvergenceError(
            f"collocation too close to a critical load (lowest eigenvalue of the second "
            f"variation {mu:.3g} l^2/B): its error ~ tol/mu exceeds 1e-6 even at tol "
            f"{tight:.1g}; solve_shooting resolves it")
    return out


# ---------------------------------------------------------------------- closed form
@dataclass(frozen=True)
class TipForceElastica:
    """The closed-form elastica under an end force of fixed direction (no distributed load).

    With ``P = R (cos phi, sin phi)`` and ``psi = theta - phi - pi``, eq. (92) reads
    ``B psi'' = -R sin(psi)``; its first integral with ``M(l) = 0`` is
    ``(B/2) psi'^2 = R (cos psi - cos psi_l)``. Writing ``sigma psi = hat_psi`` (``sigma`` the sign
    of ``psi(0)``) and ``sin(hat_psi/2) = k sin(varphi)``, ``k = sin(hat_psi_l / 2)``:
    ``sqrt(R/B) s = F(varphi, k) - F(varphi0, k)``, so ``varphi(s) = am(F(varphi0) + sqrt(R/B) s)``
    (Jacobi amplitude) and ``varphi(l) = pi/2`` fixes ``k``:
    ``sqrt(R/B) l = K(k) - F(varphi0, k)``. Along the rod
    ``t = -cos(hat_psi) e_P - sigma sin(hat_psi) e_P^perp`` with ``cos hat_psi = 1 - 2 k^2 sin^2
    varphi``, ``sin hat_psi = 2 k sin varphi dn``, which integrate to
    ``int cos hat_psi ds = sqrt(B/R) [2 E(varphi) - F(varphi)]`` and
    ``int sin hat_psi ds = -2 k sqrt(B/R) cos(varphi)``.
    """

    length: float
    B: float
    R: float  # |P| [N]
    phi: float  # direction of P [rad]
    sigma: float  # +1 or -1
    k: float  # elliptic modulus (m = k^2)
    varphi0: float  # amplitude at the clamp
    tip_rotation: float  # theta(l) [rad]

    def _check_modulus(self) -> None:
        """The shape needs Jacobi's elliptic functions at ``m = k^2``; within 1e-9 of 1 (a
        pulling force near the axis, or loads of ~60 B/l^2 and more) scipy's ``ellipj``
        switches to a first-order approximation and the shape loses digits (an outside review:
        theta(l) 1.2e-4 off at 60 B/l^2, 0.02 rad off the axis, while ``tip_rotation``, from
        the modulus alone, is right to 3e-15): refused there."""
        if 1.0 - self.k**2 < 1e-9:
            raise ConvergenceError(
                f"the closed form's shape needs elliptic functions at a modulus within "
                f"{1.0 - self.k**2:.1e} of 1, where they lose digits; tip_rotation is exact "
                "(use solve_shooting for the shape)")

    def _parts(self, s: NDArray) -> tuple[NDArray, NDArray]:
        self._check_modulus()
        m = self.k**2
        c = math.sqrt(self.B / self.R)
        u = ellipkinc(self.varphi0, m) + s / c
        _, _, _, varphi = ellipj(u, m)
        along = c * (2 * (ellipeinc(varphi, m) - ellipeinc(self.varphi0, m))
                     - (ellipkinc(varphi, m) - ellipkinc(self.varphi0, m)))
        across = -2 * self.k * c * (np.cos(varphi) - math.cos(self.varphi0))
        return along, across

    def position(self, s: ArrayLike) -> NDArray:
        """``x(s)`` [m], rows ``(x1, x2)``; ``s`` finite in ``[0, l]`` (it extrapolated, and
        NaN gave NaN; an outside audit)."""
        s = np.atleast_1d(_arclengths(s, self.length))
        along, across = self._parts(s)
        eP = np.array([math.cos(self.phi), math.sin(self.phi)])
        eQ = np.array([-math.sin(self.phi), math.cos(self.phi)])
        return -along[:, None] * eP - self.sigma * across[:, None] * eQ

    def theta(self, s: ArrayLike) -> NDArray:
        """``theta(s)`` [rad]; ``s`` finite in ``[0, l]``."""
        self._check_modulus()
        s = np.atleast_1d(_arclengths(s, self.length))
        m = self.k**2
        u = ellipkinc(self.varphi0, m) + s / math.sqrt(self.B / self.R)
        sn = ellipj(u, m)[0]
        # theta(s) - theta(0) = psi(s) - psi(0), and theta(0) = 0 (eq. 96)
        return self.sigma * (2 * np.arcsin(self.k * sn) - 2 * math.asin(self.k * math.sin(
            self.varphi0)))


#: Smallest angle [rad] between a pulling end force and the rod's axis that the closed form
#: takes: the elliptic modulus tends to 1 there and the end rotation loses digits (measured
#: against shooting at 1e-13: relative error <= 1.5e-11 at 1e-2 rad for |P1| in [0.1, 30]
#: B/l^2; 6.7e-9 at 1e-3 rad, 1.5e-5 at 1e-6). A pushing force has no such loss (4e-13 at
#: P2/P1 = 1e-20, the shooting's own tolerance; exact against the beam-column's sec(kl) - 1).
#: This is the end rotation's accuracy; the shape (``theta(s)``, ``position``) is refused
#: where its elliptic functions lose digits (:meth:`TipForceElastica._check_modulus`).
TENSION_OFF_AXIS_MIN = 1e-2


def tip_force_closed_form(length: float, B: float, P1: float, P2: float) -> TipForceElastica:
    """The classical elastica of a cantilever under the end force ``P = -P1 e1 - P2 e2`` of
    fixed direction (eq. 92), by elliptic integrals (:class:`TipForceElastica`): the branch
    without inflection, connected to the straight rod. The end rotation is the root of
    ``K(k) - F(varphi0, k) = sqrt(R/B) l`` (Brent's method to round-off; ``K`` via
    ``ellipkm1`` to keep its digits as ``k -> 1``)."""
    length, B = _check_rod(length, B)
    P1, P2 = check_real("P1", P1), check_real("P2", P2)
    R = math.hypot(P1, P2)
    if R == 0.0:
        raise ParameterError("P1 and P2 are both zero: no end force")
    if P2 == 0.0:
        raise ParameterError("the end force is axial (P2 = 0): the closed form covers a "
                             "transverse component (the axial case is Euler's buckling)")
    phi = math.atan2(-P2, -P1)
    # psi at the clamp, -phi - pi modulo 2 pi, in (-pi, pi]: from the force's components
    # directly (-phi - pi lost the digits of a small transverse force: 4e-5 relative error in
    # the end rotation at P2/P1 = 1e-11)
    psi0 = math.atan2(-P2, P1)
    off_axis = math.atan2(abs(P2), abs(P1))  # the force's angle to the rod's axis
    if P1 < 0 and off_axis < TENSION_OFF_AXIS_MIN:
        raise ParameterError(
            f"a pulling end force (P1 < 0) must be at least {TENSION_OFF_AXIS_MIN:g} rad off "
            f"the rod's axis for the closed form (|P2/P1| >= {math.tan(TENSION_OFF_AXIS_MIN):.4g}"
            f"), got |P2/P1| = {abs(P2 / P1):.3g}: nearer, its elliptic modulus tends to 1 and "
            "it loses digits; solve_shooting covers it")
    sigma = math.copysign(1.0, psi0)
    h0 = abs(psi0)  # hat psi at the clamp, in (0, pi)
    target = math.sqrt(R / B) * length

    def arclength(hl: float) -> float:  # sqrt(R/B) l as a function of hat psi(l)
        k = math.sin(hl / 2)
        varphi0 = math.asin(min(1.0, math.sin(h0 / 2) / k))
        return float(ellipkm1(math.cos(hl / 2) ** 2) - ellipkinc(varphi0, k * k)) - target

    hi = math.pi - 1e-15
    if arclength(hi) <= 0:
        raise ConvergenceError("no end rotation below pi solves the elastica's length")
    try:  # to round-off relative to the clamp's angle (an absolute 1e-16 lost the digits
        # of small rotations: 1e-5 relative error at P2/P1 = 1e-11)
        hl = brentq(arclength, h0, hi, xtol=max(4 * np.finfo(float).eps * h0, 1e-300),
                    rtol=4 * np.finfo(float).eps, maxiter=200)
    except (RuntimeError, ValueError) as exc:
        raise ConvergenceError(f"the closed form's end rotation: {exc}") from None
    k = math.sin(hl / 2)
    varphi0 = math.asin(min(1.0, math.sin(h0 / 2) / k))
    return TipForceElastica(length, B, R, phi, sigma, k, varphi0, sigma * (hl - h0))


def linear_tip_deflection(length: float, B: float, loads: ElasticaLoads) -> float:
    """``u2(l)`` [m] of the linear Euler–Bernoulli cantilever (eq. 95 at rest, transverse
    loads): ``-P2 l^3/(3B) + q2 l^4/(8B)``. (The axial loads ``P1, q1`` enter eq. 95 only
    multiplied by the deflection: second order in the loads.)"""
    length, B = _check_rod(length, B)
    try:
        u = -loads.P2 * length**3 / (3 * B) + loads.q2 * length**4 / (8 * B)
    except OverflowError:
        u = math.inf
    return _finite_deflection(u, length, B)


def _finite_deflection(u: float, length: float, B: float) -> float:
    """``u`` if finite, else ParameterError: a deflection beyond the double range (an outside
    audit: l = 1e300, B = 1e-300 raised a bare OverflowError) is refused, naming the inputs."""
    return check_finite_result(u, f"the deflection of length = {length:g} m, B = {B:g} N m^2 "
                                  f"under these loads overflows the double range: rescale "
                                  f"the input")


def perturbation_tip_deflection(length: float, B: float, loads: ElasticaLoads
                                ) -> tuple[float, float, float]:
    """The coefficients ``(c1, c2, c3)`` [m] of ``u2(l) = c1 e + c2 e^2 + c3 e^3 + O(e^4)`` for
    the loads ``e * loads``: eq. (91) at rest expanded in the load factor ``e``.

    With ``xi = s/l``, ``alpha = (P1 - (l - s) q1) l^2/B``, ``f = (P2 - (l - s) q2) l^2/B``, eq.
    (91) is ``theta'' = e (-alpha sin(theta) + f cos(theta))``; with ``theta = e th1 + e^2 th2 +
    e^3 th3``: ``th1'' = f``, ``th2'' = -alpha th1``, ``th3'' = -alpha th2 - f th1^2/2``, each
    with ``th(0) = 0``, ``th'(1) = 0`` (eqs. 96-97), and ``u2(l) = l int_0^1 sin(theta) dxi``.
    Every term is a polynomial in ``xi``: integrated exactly (``numpy.polynomial``), so the
    coefficients are exact to round-off; ``c1`` is :func:`linear_tip_deflection`."""
    length, B = _check_rod(length, B)
    try:
        with np.errstate(over="ignore", invalid="ignore"):
            c = _perturbation_coefficients(length, B, loads)
    except OverflowError:
        c = (math.inf,) * 3
    for x in c:
        _finite_deflection(x, length, B)
    return c


def _perturbation_coefficients(length: float, B: float, loads: ElasticaLoads
                               ) -> tuple[float, float, float]:
    """The expansion of :func:`perturbation_tip_deflection` (checked inputs, unchecked result)."""
    Poly = np.polynomial.Polynomial
    one_minus_xi = Poly([1.0, -1.0])
    alpha = (loads.P1 - length * loads.q1 * one_minus_xi) * (length**2 / B)
    f = (loads.P2 - length * loads.q2 * one_minus_xi) * (length**2 / B)

    def clamped_free(rhs: np.polynomial.Polynomial) -> np.polynomial.Polynomial:
        # th'' = rhs, th(0) = 0, th'(1) = 0: th' = -int_xi^1 rhs, th = int_0^xi th'
        G = rhs.integ()
        return (G - G(1.0)).integ()

    th1 = clamped_free(f)
    th2 = clamped_free(-alpha * th1)
    th3 = clamped_free(-alpha * th2 - 0.5 * f * th1**2)

    def integral(p: np.polynomial.Polynomial) -> float:
        P = p.integ()
        return float(P(1.0) - P(0.0)) * length

    return integral(th1), integral(th2), integral(th3 - th1**3 / 6.0)


# ---------------------------------------------------------------------- balances (eq. 74, 87, 89)
def moment_of_loads_beyond(sol: ElasticaSolution, s_cut: float) -> float:
    """Eq. (89) at rest: the moment about ``x(s_cut)`` of the loads on the part beyond the cut,
    ``(x(l) - x_c) x P + int_{s_cut}^l (x(sigma) - x_c) x q dsigma`` [N m] (e3 component), by
    Gauss–Legendre quadrature over the computed deformed shape."""
    xc = sol.position(_arclengths(s_cut, sol.length, "s_cut"))[0]
    P, q = sol.loads.tip_force(), sol.loads.distributed()
    arm_P = sol.position(sol.length)[0] - xc
    integral = gauss_integral(lambda s: sol.position(s) - xc, s_cut, sol.length)
    return float(_cross(arm_P, P) + _cross(integral, q))


def part_balances(sol: ElasticaSolution, s1: float, s2: float) -> dict[str, float]:
    """The equilibrium of the part ``[s1, s2]`` (eq. 74) and eq. (87) on it, as residuals
    relative to the size of their largest term (dimensionless):

    - ``force``: ``|-a(s1) + a(s2) + int q ds| / max |term|`` (eq. 74_1);
    - ``moment``: ``[M + x x a]_{s1}^{s2} + int x x q ds`` (eq. 74_2, about the origin O);
    - ``eq87``: ``[N + M^2/(2B)]_{s1}^{s2} + int q . t ds`` (eq. 87), with
      ``int q . t ds`` by quadrature of ``q . t(theta(s))``.
    """
    s1, s2 = (float(_arclengths(x, sol.length, name)) for x, name in ((s1, "s1"), (s2, "s2")))
    if not s1 < s2:
        raise ParameterError(f"the part [s1, s2] needs s1 < s2, got [{s1:g}, {s2:g}]")
    q = sol.loads.distributed()
    a1, a2 = sol.force(s1)[0], sol.force(s2)[0]
    Q = gauss_integral(lambda s: np.broadcast_to(q, (np.size(s), 2)), s1, s2)
    force_terms = [np.linalg.norm(a1), np.linalg.norm(a2), np.linalg.norm(Q)]
    force = np.linalg.norm(-a1 + a2 + Q) / max(force_terms)
    M1, M2 = sol.moment([s1, s2])
    x1, x2 = sol.position([s1, s2])
    Xq = _cross(gauss_integral(sol.position, s1, s2), q)
    m_terms = [M1, M2, _cross(x1, a1), _cross(x2, a2), Xq]
    moment = (M2 + _cross(x2, a2) - M1 - _cross(x1, a1) + Xq) / max(map(abs, m_terms))
    (N1, N2), _ = sol.normal_and_shear([s1, s2])

    def q_dot_t(s: NDArray) -> NDArray:
        th = sol.theta(s)
        return q[0] * np.cos(th) + q[1] * np.sin(th)

    qt = float(gauss_integral(q_dot_t, s1, s2))
    e_terms = [N1, N2, M1**2 / (2 * sol.B), M2**2 / (2 * sol.B), qt]
    eq87 = (N2 + M2**2 / (2 * sol.B) - N1 - M1**2 / (2 * sol.B) + qt) / max(map(abs, e_terms))
    return {"force": float(force), "moment": float(moment), "eq87": float(eq87)}


def projections(sol: ElasticaSolution) -> dict[str, float]:
    """Eqs. (65)-(66): ``d = int cos(theta) ds`` and ``h = int sin(theta) ds`` by quadrature of
    the computed rotation, against ``l + u1(l) - u1(0)`` and ``u2(l) - u2(0)`` from the
    computed positions [m]."""
    th = sol.theta
    d = float(gauss_integral(lambda s: np.cos(th(s)), 0.0, sol.length))
    h = float(gauss_integral(lambda s: np.sin(th(s)), 0.0, sol.length))
    x0, xl = sol.position([0.0, sol.length])
    return {"d": d, "h": h, "d_positions": float(xl[0] - x0[0]),
            "h_positions": float(xl[1] - x0[1])}


def _cross(u: ArrayLike, v: ArrayLike) -> float:
    """``(u x v) . e3`` of two plane vectors."""
    u, v = np.asarray(u), np.asarray(v)
    return float(u[0] * v[1] - u[1] * v[0])


__all__ = ["ElasticaLoads", "ElasticaSolution", "TipForceElastica", "check_load_range",
           "gauss_integral",
           "internal_force", "linear_tip_deflection", "moment_of_loads_beyond",
           "perturbation_tip_deflection",
           "part_balances", "projections", "solve_collocation", "solve_shooting",
           "tip_force_closed_form"]
