"""Nonassociative elastoplasticity and the acoustic tensor (chapter §3.2–3.5).

Fourth-order tensors are numpy arrays of shape (3, 3, 3, 3) acting on symmetric second-order
tensors by double contraction, ``E[A]_ij = E_ijkl A_kl``. General forms use ``einsum`` and any
elasticity tensor; the isotropic closed forms (eqs. 178–194) are their twins.
"""

from __future__ import annotations

import math
from fractions import Fraction

import numpy as np
from numpy.typing import ArrayLike, NDArray

from flutterfriction.errors import (
    ParameterError,
    check_finite_array,
    check_finite_result,
    check_positive,
    check_real,
)

I3 = np.eye(3)


def isotropic_elasticity(lam: float, mu: float) -> NDArray:
    """``E = lam I (x) I + 2 mu II^sym``; positive definite iff mu > 0 and 3 lam + 2 mu > 0."""
    lam, mu = _isotropic(lam, mu)
    with np.errstate(over="ignore", invalid="ignore"):  # an overflow is refused just below
        E = (lam * np.einsum("ij,kl->ijkl", I3, I3)
             + mu * (np.einsum("ik,jl->ijkl", I3, I3) + np.einsum("il,jk->ijkl", I3, I3)))
    return check_finite_result(
        E, f"E with lam = {lam:g}, mu = {mu:g} overflows the double range: rescale the moduli")



def random_elasticity_perturbation(rng: np.random.Generator) -> NDArray:
    """A random fourth-order tensor with major and minor symmetries and unit norm (from a
    random symmetric 6x6 matrix in Mandel notation): a generic elastic anisotropy."""
    B = rng.normal(size=(6, 6))
    B = (B + B.T) / 2
    pairs = [(0, 0), (1, 1), (2, 2), (1, 2), (0, 2), (0, 1)]
    weight = [1.0, 1.0, 1.0, math.sqrt(2), math.sqrt(2), math.sqrt(2)]
    T = np.zeros((3, 3, 3, 3))
    for a, (i, j) in enumerate(pairs):
        for b, (k, l) in enumerate(pairs):
            v = B[a, b] / (weight[a] * weight[b])
            for r, s in {(i, j), (j, i)}:
                for t, u in {(k, l), (l, k)}:
                    T[r, s, t, u] = v
    return T / np.linalg.norm(T)


def mandel_matrix(E: NDArray) -> NDArray:
    """The 6x6 Mandel matrix of a fourth-order tensor with minor symmetries (its eigenvalues
    are the tensor's on symmetric second-order tensors: positive definite elasticity has all
    of them > 0)."""
    i, j = _MANDEL_PAIRS[:, :1], _MANDEL_PAIRS[:, 1:]
    w = _MANDEL_WEIGHTS
    return E[i, j, i.T, j.T] * w[:, None] * w[None, :]  # (E w_a) w_b, as it was written


_MANDEL_PAIRS = np.array([(0, 0), (1, 1), (2, 2), (1, 2), (0, 2), (0, 1)])
_MANDEL_WEIGHTS = np.array([1.0, 1.0, 1.0, math.sqrt(2), math.sqrt(2), math.sqrt(2)])


def apply(E: NDArray, A: ArrayLike) -> NDArray:
    """``E[A]``."""
    return np.einsum("ijkl,kl->ij", E, np.asarray(A, dtype=float))


def apply_transpose(E: NDArray, A: ArrayLike) -> NDArray:
    """``E^T[A]`` (major transpose)."""
    return np.einsum("ijkl,ij->kl", E, np.asarray(A, dtype=float))


def check_symmetric(name: str, A: ArrayLike) -> NDArray:
    A = np.asarray(A, dtype=float)
    if A.shape != (3, 3) or not np.all(np.isfinite(A)):
        raise ParameterError(f"{name} must be a finite 3x3 tensor")
    if not np.allclose(A, A.T, atol=1e-12 * max(1.0, np.abs(A).max())):
        raise ParameterError(f"{name} must be symmetric")
    return 0.5 * (A + A.T)


def check_direction(n: ArrayLike, normalise: bool = False) -> NDArray:
    n = np.asarray(n, dtype=float)
    if n.shape != (3,) or not np.all(np.isfinite(n)):
        raise ParameterError("n must be 3 finite numbers")
    n_max = float(np.abs(n).max())
    if n_max == 0:
        raise ParameterError("n must be non-zero (a unit vector)")
    m = n / n_max  # scaled first: |n| of huge or tiny entries neither overflows nor underflows
    norm_m = float(np.linalg.norm(m))
    if not normalise and abs(n_max * norm_m - 1) > 1e-9:
        raise ParameterError(f"n must be a unit vector, |n| = {n_max * norm_m:.6g}")
    return m / norm_m


def _nonzero_direction(n: ArrayLike) -> NDArray:
    """The propagation direction: a unit vector (eqs. 161, 179 and 185 hold for ``|n| = 1``;
    an outside audit found ``n = (2, 0, 0)`` accepted and the isotropic forms then answering
    divergence for a stable direction). Refused unless ``|n| = 1`` to 1e-9; returned
    normalised, so that the last ulps of a computed direction do not matter."""
    n = check_finite_array("n", n, (3,))
    if not np.any(n):
        raise ParameterError("n must be a non-zero vector (a propagation direction)")
    return check_direction(n)


def check_elasticity(E: ArrayLike) -> NDArray:
    """``E`` (eq. 146) as a finite (3, 3, 3, 3) array with the minor symmetries (it maps
    symmetric strains to symmetric stresses) and positive definite on symmetric tensors (the
    symmetric part of its Mandel matrix; for isotropy mu > 0 and 3 lam + 2 mu > 0, as
    :func:`isotropic_elasticity` requires), each to 1e-12 of its largest entry; refused in one
    line otherwise (an outside audit: ``-E`` was accepted). The major symmetry is not asked
    (§3.3 assumes it only where it says so). Returned unchanged."""
    E = check_finite_array("E", E, (3, 3, 3, 3))
    key = E.tobytes()
    if key in _ELASTICITY_CHECKED:  # (a scan validates the same E at every step)
        return E
    scale = float(np.max(np.abs(E)))
    if scale == 0.0:
        raise ParameterError("E must be a non-zero elasticity tensor")
    tol = 1e-12 * scale
    if (np.max(np.abs(E - E.transpose(1, 0, 2, 3))) > tol
            or np.max(np.abs(E - E.transpose(0, 1, 3, 2))) > tol):
        raise ParameterError("E must have the minor symmetries E_ijkl = E_jikl = E_ijlk (it "
                             "maps symmetric strains to symmetric stresses, eq. 146)")
    M = mandel_matrix(E / scale)
    smallest = float(np.linalg.eigvalsh(0.5 * (M + M.T))[0])
    if not smallest > 1e-12:
        raise ParameterError(f"E must be positive definite on symmetric tensors (smallest "
                             f"eigenvalue of its Mandel matrix {smallest * scale:.3g})")
    if len(_ELASTICITY_CHECKED) >= 64:
        _ELASTICITY_CHECKED.clear()
    _ELASTICITY_CHECKED.add(key)
    return E


#: The bytes of the last elasticity tensors :func:`check_elasticity` accepted (at most 64): a
#: scan that validates the same E at every step checks it once (acoustic_eigenvalues: 801 g
#: values, max_localization_modulus: thousands of directions; ~0.1 s each otherwise, measured).
_ELASTICITY_CHECKED: set[bytes] = set()


def check_flow_tensor(name: str, A: ArrayLike) -> NDArray:
    """A flow-rule tensor ``P`` (eq. 147) or ``Q`` (the yield function's gradient, eq. 149):
    a finite, symmetric 3x3 array (to 1e-12 of its largest entry; an outside audit: a
    non-symmetric ``P`` was accepted). Returned unchanged."""
    A = check_finite_array(name, A, (3, 3))
    if np.max(np.abs(A - A.T)) > 1e-12 * float(np.max(np.abs(A))):
        raise ParameterError(f"{name} must be a symmetric second-order tensor (§3.2)")
    return A


def _tensors(P: ArrayLike, Q: ArrayLike) -> tuple[NDArray, NDArray]:
    """The flow-rule tensors ``P``, ``Q`` as finite symmetric 3x3 arrays (refused, naming
    them)."""
    return check_flow_tensor("P", P), check_flow_tensor("Q", Q)


def _modulus(g: object) -> float:
    """The plastic modulus of eq. (152), "assumed strictly positive" (§3.3) and a normal double
    (it divides; an outside review: g = -1 was accepted where the command line refuses it,
    g = 1e-320 put an infinity into the tensor)."""
    g = check_real("g", g)
    if not g > 0:
        raise ParameterError(f"g must be > 0 (the plastic modulus of eq. 152, assumed strictly "
                             f"positive in §3.3), got {g!r}")
    return check_positive("g", g)


def _isotropic(lam: object, mu: object) -> tuple[float, float]:
    """``(lam, mu)`` of a positive definite isotropic elasticity (mu > 0, 3 lam + 2 mu > 0)."""
    lam, mu = check_real("lam", lam), check_positive("mu", mu)
    if 3 * lam + 2 * mu <= 0:
        raise ParameterError(f"lam must be > -2 mu/3 = {-2 * mu / 3:g} for a positive definite "
                             f"isotropic elasticity, got {lam!r}")
    return lam, mu


def voigt_to_tensor(v: ArrayLike) -> NDArray:
    """``(a11, a22, a33, a23, a13, a12)`` to the symmetric 3x3 tensor."""
    a = np.asarray(v, dtype=float)
    if a.shape != (6,) or not np.all(np.isfinite(a)):
        raise ParameterError("a Voigt tensor needs 6 finite components a11,a22,a33,a23,a13,a12")
    return np.array([[a[0], a[5], a[4]], [a[5], a[1], a[3]], [a[4], a[3], a[2]]])


# ---------------------------------------------------------------------- §3.2
def drucker_prager_tensors(sigma: ArrayLike, friction_angle: float,
                           dilatancy_angle: float) -> tuple[NDArray, NDArray]:
    """``(P, Q)`` of eqs. (154)–(155): ``P = cos(chi) S^ + sqrt3 sin(chi)/3 I``,
    ``Q = cos(phi) S^ + sqrt3 sin(phi)/3 I`` with ``S^ = dev(sigma)/|dev(sigma)|``; ``phi``
    the friction (pressure-sensitivity) angle and ``chi`` the dilatancy angle, radians. Both
    tensors have unit norm. Deviatoric associativity: their deviatoric parts are aligned."""
    sigma = check_symmetric("sigma", sigma)
    phi = check_real("friction_angle", friction_angle)
    chi = check_real("dilatancy_angle", dilatancy_angle)
    for name, angle in (("friction_angle", phi), ("dilatancy_angle", chi)):
        if not abs(angle) <= math.pi / 2:  # (an outside audit: 1e10 and 4 rad were accepted)
            raise ParameterError(f"{name} must lie in [-pi/2, pi/2] rad, got {angle!r}")
    dev = sigma - I3 * np.trace(sigma) / 3
    norm = np.linalg.norm(dev)
    if norm == 0:
        raise ParameterError("sigma must have a non-zero deviator (Drucker-Prager's S^)")
    S = dev / norm
    P = math.cos(chi) * S + math.sqrt(3) * math.sin(chi) / 3 * I3
    Q = math.cos(phi) * S + math.sqrt(3) * math.sin(phi) / 3 * I3
    return P, Q


def plastic_modulus(H: float, E: NDArray, P: ArrayLike, Q: ArrayLike) -> float:
    """``g = H + Q . E[P]`` (eq. 152)."""
    E = check_elasticity(E)
    P, Q = _tensors(P, Q)
    return float(check_real("H", H) + np.einsum("ij,ij->", Q, apply(E, P)))


def elastoplastic_tangent(E: NDArray, P: ArrayLike, Q: ArrayLike, g: float) -> NDArray:
    """``C = E - E[P] (x) E^T[Q] / g`` (eq. 153), the plastic branch."""
    g = _modulus(g)
    with np.errstate(over="ignore", invalid="ignore"):  # an overflow is refused just below
        C = E - np.einsum("ij,kl->ijkl", apply(E, P), apply_transpose(E, Q)) / g
    return check_finite_result(
        C, f"the tangent with g = {g:g} overflows the double range: |g| is too small for the "
        f"scale of E[P] and E[Q]")


# ---------------------------------------------------------------------- §3.3–3.4
def elastic_acoustic_tensor(E: NDArray, n: ArrayLike, rho: float = 1.0) -> NDArray:
    """``A_el(n)`` of eq. (162): ``(A_el)_ik = E_ijkl n_j n_l / rho``."""
    E, n = check_elasticity(E), _nonzero_direction(n)
    return np.einsum("ijkl,j,l->ik", E, n, n) / check_positive("rho", rho)


def acoustic_vectors(E: NDArray, P: ArrayLike, Q: ArrayLike, n: ArrayLike) -> tuple:
    """``p = E[P] n`` and ``q = E^T[Q] n`` (eq. 165)."""
    E, n = check_elasticity(E), _nonzero_direction(n)
    P, Q = _tensors(P, Q)
    return apply(E, P) @ n, apply_transpose(E, Q) @ n


def acoustic_tensor(E: NDArray, P: ArrayLike, Q: ArrayLike, g: float, n: ArrayLike,
                    rho: float = 1.0) -> NDArray:
    """``A(n) = A_el(n) - p (x) q / (rho g)`` (eq. 161), general elasticity."""
    g = _modulus(g)
    p, q = acoustic_vectors(E, P, Q, n)
    with np.errstate(over="ignore", invalid="ignore"):  # an overflow is refused just below
        A = elastic_acoustic_tensor(E, n, rho) - np.outer(p, q) / (rho * g)
    return check_finite_result(A, f"the acoustic tensor with g = {g:g} overflows the double "
                               f"range")


def localization_modulus(E: NDArray, P: ArrayLike, Q: ArrayLike, n: ArrayLike) -> float:
    """``g_cr^E(n) = q . A_el^{-1}(n) p`` (eq. 166), general elasticity, rho = 1."""
    p, q = acoustic_vectors(E, P, Q, n)
    return float(q @ np.linalg.solve(elastic_acoustic_tensor(E, n), p))


# ---------------------------------------------------------------------- §3.5, isotropic
def isotropic_vectors(lam: float, mu: float, P: ArrayLike, Q: ArrayLike,
                      n: ArrayLike) -> tuple[NDArray, NDArray]:
    """``q = lam tr(Q) n + 2 mu Q n``, ``p = lam tr(P) n + 2 mu P n`` (eq. 180); refused,
    naming P and Q, where their squares leave the double range (the closed forms form ``p.q``
    and ``|p|^2``; an outside audit: P = 1e300 gave a bare OverflowError "(34, 'Numerical
    result out of range')"). ``analysis.acoustic.isotropic_acoustic`` computes at any scale."""
    lam, mu = _isotropic(lam, mu)
    (P, Q), n = _tensors(P, Q), _nonzero_direction(n)
    with np.errstate(over="ignore", invalid="ignore"):
        p = lam * np.trace(P) * n + 2 * mu * P @ n
        q = lam * np.trace(Q) * n + 2 * mu * Q @ n
        squares = (p @ p, q @ q, p @ q)
    if not all(math.isfinite(float(x)) and abs(float(x)) < 1e300 for x in squares):
        raise ParameterError(
            f"P, Q: with lam = {lam:g}, mu = {mu:g} the vectors p = E[P] n, q = E[Q] n of eq. "
            f"(180) have squares beyond 1e300 (|p| = {float(np.max(np.abs(p))):.3g}, |q| = "
            f"{float(np.max(np.abs(q))):.3g}): scale P and Q down (every critical modulus g "
            f"scales with |P| |Q|)")
    return p, q


def acoustic_tensor_isotropic(lam: float, mu: float, P: ArrayLike, Q: ArrayLike, g: float,
                              n: ArrayLike) -> NDArray:
    """Eq. (179): ``(lam + mu) n (x) n + mu I - p (x) q / g``."""
    g = _modulus(g)
    n = _nonzero_direction(n)
    p, q = isotropic_vectors(lam, mu, P, Q, n)
    with np.errstate(over="ignore", invalid="ignore"):  # an overflow is refused just below
        A = (lam + mu) * np.outer(n, n) + mu * I3 - np.outer(p, q) / g
    return check_finite_result(A, f"the acoustic tensor with g = {g:g} overflows the double "
                               f"range; analysis.acoustic.isotropic_acoustic computes it scaled")


def acoustic_eigenvalues_isotropic(lam: float, mu: float, P: ArrayLike, Q: ArrayLike,
                                   g: float, n: ArrayLike) -> NDArray:
    """``mu`` and the two roots of eq. (184) (complex when flutter), the real ones ascending;
    the smaller real root from the product ``c`` (no cancellation when one root dominates, as
    for small ``|g|``). For inputs at any scale see ``analysis.acoustic.isotropic_acoustic``."""
    g = _modulus(g)
    n = _nonzero_direction(n)
    p, q = isotropic_vectors(lam, mu, P, Q, n)
    b = float(lam + 3 * mu - p @ q / g)
    c = float((lam + 2 * mu) * (mu - p @ q / g) + (lam + mu) * (p @ n) * (q @ n) / g)
    # b^2 - 4c = (lam + mu)^2 (1 - g1/g)(1 - g2/g) with the interval of eq. (188), else
    # (lam + mu - (2N - p.q)/g)^2 - 4 N D / g^2 with N = (n.p)(n.q), D = N - p.q (a sum of
    # squares when N D <= 0): formed so, a double eigenvalue is no round-off pair 1 +- 1.5e-8 i
    # (an outside audit: P = Q, a symmetric A, was called flutter at its coalescence)
    a, x = lam + mu, 1.0 / g
    N, D = _flutter_factors(n, p, q)
    interval = flutter_interval_isotropic(lam, mu, P, Q, n)
    if interval is None:
        disc = max((a - x * (2 * N - float(p @ q))) ** 2 - 4 * x * x * N * D, 0.0)
    else:
        disc = a * a * (1 - x * interval[0]) * (1 - x * interval[1])
    if not (math.isfinite(b) and math.isfinite(c) and math.isfinite(disc)):
        # (an outside audit: g = 1e-200 put an infinity into the scene's data)
        raise ParameterError(f"g: |p.q|/g = {abs(float(p @ q)) / g:.3g} takes eq. (184) beyond "
                             f"the double range; analysis.acoustic.isotropic_acoustic computes "
                             f"it scaled, at any g")
    if disc < 0:
        root = 1j * math.sqrt(-disc)
        return np.array([mu, (b - root) / 2, (b + root) / 2])
    big = (b + math.copysign(math.sqrt(disc), b)) / 2
    small = c / big if big != 0 else 0.0
    return np.array([mu, min(small, big), max(small, big)], dtype=complex)


def localization_modulus_isotropic(lam: float, mu: float, P: ArrayLike, Q: ArrayLike,
                                   n: ArrayLike) -> float:
    """Eq. (185)."""
    n = _nonzero_direction(n)
    p, q = isotropic_vectors(lam, mu, P, Q, n)
    with np.errstate(over="ignore", invalid="ignore"):  # an overflow is refused just below
        g = float(-(lam + mu) / (mu * (lam + 2 * mu)) * (p @ n) * (q @ n) + p @ q / mu)
    # (an outside review: lam = 1e308 returned NaN)
    return check_finite_result(g, "eq. (185) overflows the double range here; "
                               "analysis.acoustic.isotropic_acoustic computes it scaled")


def flutter_interval_isotropic(lam: float, mu: float, P: ArrayLike, Q: ArrayLike,
                               n: ArrayLike) -> tuple[float, float] | None:
    """``(g1, g2)`` of eqs. (187)–(188), corrected: flutter iff ``N = (n.p)(n.q) > 0``,
    ``N - p.q > 0`` and ``g1 < g < g2`` with ``g = (sqrt N -/+ sqrt(N - p.q))^2/(lam + mu)``
    (``g1`` as ``(p.q)^2/((sqrt N + sqrt(N - p.q))^2 (lam + mu))`` with ``p.q`` exact where
    ``|p.q| < 1e-3 N``: the difference cancels there). (Eq. 188 as printed has ``(n.p)(n.p)``
    in the second root.) ``None`` when no flutter."""
    n = _nonzero_direction(n)
    p, q = isotropic_vectors(lam, mu, P, Q, n)
    N, D = _flutter_factors(n, p, q)
    pp, qq = float(np.linalg.norm(p)), float(np.linalg.norm(q))
    exact = None
    if abs(n @ p) <= AMBIGUOUS_RTOL * pp or abs(n @ q) <= AMBIGUOUS_RTOL * qq \
            or abs(D) <= AMBIGUOUS_RTOL * pp * qq:
        exact = mp, mq, D_exact = exact_flutter_factors(lam, mu, *_tensors(P, Q), n)
        if not (mp * mq > 0 and D_exact > 0):
            return None
        N, D = float(mp * mq), float(D_exact)
    if not (N > 0 and D > 0):
        return None
    r1, r2 = math.sqrt(N), math.sqrt(D)
    if abs(N - D) < 1e-3 * N:
        # g1 = (p.q)^2 / ((sqrt N + sqrt D)^2 (lam + mu)) with p.q = N - D exactly (rational
        # arithmetic): (sqrt N - sqrt D)^2 cancels here (an outside audit: p.q/N = 1e-12 gave
        # g1 2.2e-4 off), and so does p.q formed from the floats
        mp, mq, D_exact = exact or exact_flutter_factors(lam, mu, *_tensors(P, Q), n)
        pq = float(mp * mq - D_exact)
        return pq * pq / (r1 + r2) ** 2 / (lam + mu), (r1 + r2) ** 2 / (lam + mu)
    return (r1 - r2) ** 2 / (lam + mu), (r1 + r2) ** 2 / (lam + mu)


def _flutter_factors(n: NDArray, p: NDArray, q: NDArray) -> tuple[float, float]:
    """``N = (n.p)(n.q)`` and ``D = N - p.q``, the latter as ``-(n x p).(n x q)`` (Binet-Cauchy,
    ``|n| = 1``): for ``P = Q`` exactly ``-|n x p|^2 <= 0``, where ``N - p.q`` formed directly
    left round-off of either sign and a spurious interval 3e-8 wide (an outside audit)."""
    return float((n @ p) * (n @ q)), -float(np.cross(n, p) @ np.cross(n, q))


#: Relative size below which the floating-point ``n.p``, ``n.q`` or ``N - p.q`` (against
#: ``|p|``, ``|q|``, ``|p||q|``) may carry the wrong sign: their round-off is a few eps
#: (~1e-15); the band is ~100 times wider. Inside it :func:`exact_flutter_factors` decides.
AMBIGUOUS_RTOL = 1e-12


def exact_flutter_factors(lam: float, mu: float, P: ArrayLike, Q: ArrayLike,
                          n: ArrayLike) -> tuple[Fraction, Fraction, Fraction]:
    """``(m.p, m.q, N - p.q)`` of eqs. (180), (187) for the unit direction ``m = n/|n|``,
    exactly: rational arithmetic on the float inputs (``n`` of any length). Where the floats
    cannot tell the sign (a direction along an eigenvector of ``P``, a nearly degenerate
    case), the interval's existence is decided here, not by round-off: ``N - p.q =
    -4 mu^2 (n x Pn).(n x Qn)/|n|^4`` (``n x p = 2 mu n x Pn``), ``m.p = lam trP + 2 mu
    n.Pn/|n|^2``."""
    F = Fraction
    nn = [F(float(x)) for x in np.asarray(n, dtype=float)]
    Pm, Qm = ([[F(float(x)) for x in row] for row in np.asarray(T, dtype=float)] for T in (P, Q))
    Pn, Qn = ([sum(T[i][j] * nn[j] for j in range(3)) for i in range(3)] for T in (Pm, Qm))
    n2 = sum(x * x for x in nn)

    def cross(a: list, b: list) -> list:
        return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]

    lam_f, mu_f = F(float(lam)), F(float(mu))
    mp = lam_f * (Pm[0][0] + Pm[1][1] + Pm[2][2]) + 2 * mu_f * sum(
        a * b for a, b in zip(nn, Pn, strict=True)) / n2
    mq = lam_f * (Qm[0][0] + Qm[1][1] + Qm[2][2]) + 2 * mu_f * sum(
        a * b for a, b in zip(nn, Qn, strict=True)) / n2
    D = -4 * mu_f * mu_f * sum(a * b for a, b in zip(cross(nn, Pn), cross(nn, Qn),
                                                     strict=True)) / (n2 * n2)
    return mp, mq, D


def flutter_interval_as_printed(lam: float, mu: float, P: ArrayLike, Q: ArrayLike,
                                n: ArrayLike) -> tuple[float, float] | None:
    """Eq. (188) exactly as printed (erratum evidence only): ``(n.p)(n.p)`` under the second
    root, and ``g1`` with the upper sign of the printed ``±``, so that ``g1 > g2`` (a reader's
    review: this had returned the roots in the corrected order, fixing half the misprint)."""
    n = _nonzero_direction(n)
    p, q = isotropic_vectors(lam, mu, P, Q, n)
    N, pq = (n @ p) * (n @ q), p @ q
    printed = (n @ p) * (n @ p) - pq
    if not (N > 0 and printed > 0):
        return None
    r1, r2 = math.sqrt(N), math.sqrt(printed)
    return (r1 + r2) ** 2 / (lam + mu), (r1 - r2) ** 2 / (lam + mu)


def coalescence_modulus(lam: float, mu: float, P: ArrayLike, Q: ArrayLike) -> float:
    """Eq. (194): ``max_i (E[P])_i (E[Q])_i / (lam + mu)`` over principal components, for
    coaxial ``P``, ``Q`` (deviatoric associativity)."""
    E = isotropic_elasticity(lam, mu)
    EP, EQ = (apply(E, T) for T in _tensors(P, Q))
    w, V = np.linalg.eigh(EP)
    eq = np.einsum("ji,jk,ki->i", V, EQ, V)  # components of E[Q] on E[P]'s principal axes
    return float(np.max(w * eq) / (lam + mu))
