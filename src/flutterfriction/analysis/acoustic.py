"""Analysis of the acoustic tensor (chapter §3.3–3.5): classification of a direction, the
maximum of the localization modulus over all directions, and flutter intervals found by brute
force (the independent twins of the isotropic closed forms in :mod:`..models.solid`)."""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from fractions import Fraction

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.optimize import brentq, minimize

from flutterfriction.analysis.stability import Regime
from flutterfriction.errors import (
    NORMAL_MIN,
    ConvergenceError,
    ParameterError,
    check_finite_array,
    check_finite_reals,
    check_integer,
    check_real,
    shown_beside,
)
from flutterfriction.models.solid import (
    AMBIGUOUS_RTOL,
    acoustic_vectors,
    check_elasticity,
    check_flow_tensor,
    elastic_acoustic_tensor,
    exact_flutter_factors,
    voigt_to_tensor,
)


def cubic_discriminant(A: NDArray) -> NDArray:
    """Discriminant of ``det(A - eta I)`` from the invariants of ``A`` (..., 3, 3): positive for
    three distinct real eigenvalues, negative for a complex-conjugate pair (flutter), zero at a
    coalescence. No eigenvalue is computed."""
    A = np.asarray(A)
    if A.dtype.kind not in "iuf":  # (an audit: a complex stack raised numpy's TypeError)
        raise ParameterError(f"A must be a stack of real 3x3 matrices, got dtype {A.dtype}")
    A = A.astype(float, copy=False)  # (no copy of the flutter map's ~1e6 tensors)
    if A.ndim < 2 or A.shape[-2:] != (3, 3) or not np.all(np.isfinite(A)):
        # (an outside review: NaN matrices gave NaN, and has_complex_pair "no pair")
        raise ParameterError(f"A must be a stack of finite 3x3 matrices, got shape {A.shape}"
                             + ("" if np.all(np.isfinite(A)) else " with NaN or inf"))
    # The invariants from the entries (elementwise over the stack: ~5x faster than a stacked
    # matrix product and LU determinant on the flutter map's ~1e6 tensors); i2 as the sum of
    # the principal minors, free of the cancellation in (i1^2 - tr A^2) / 2.
    # (the entries as contiguous rows, one copy: the arithmetic on strided views took ~1.35x
    # longer, measured)
    a11, a12, a13, a21, a22, a23, a31, a32, a33 = np.ascontiguousarray(
        np.moveaxis(A.reshape(*A.shape[:-2], 9), -1, 0))
    i1 = a11 + a22 + a33
    i2 = a11 * a22 + a11 * a33 + a22 * a33 - a12 * a21 - a13 * a31 - a23 * a32
    i3 = (a11 * (a22 * a33 - a23 * a32) - a12 * (a21 * a33 - a23 * a31)
          + a13 * (a21 * a32 - a22 * a31))
    # eta^3 - i1 eta^2 + i2 eta - i3: the discriminant of a x^3 + b x^2 + c x + d,
    # 18abcd - 4b^3 d + b^2 c^2 - 4ac^3 - 27a^2 d^2, at a = 1, b = -i1, c = i2, d = -i3; the
    # cubes as products (numpy's float power by 3 calls pow: the whole took 3x longer, 1.6 of
    # the quick flutter map's 2 s, measured; the values agree to ~1e-16 relative)
    i1_2, i2_2 = i1 * i1, i2 * i2
    return (18 * i1 * i2 * i3 - 4 * (i1_2 * i1) * i3 + i1_2 * i2_2 - 4 * (i2_2 * i2)
            - 27 * (i3 * i3))


def flutters_somewhere(E: NDArray, P: ArrayLike, Q: ArrayLike, directions: NDArray,
                       g_values: NDArray, rtol: float = 1e-12) -> NDArray:
    """For each direction, whether ``A(n; g)`` has a complex pair for some ``g`` of
    ``g_values`` (vectorised brute force, no eigenvalue computed).

    The discriminant is taken of the deviator ``B = A - (tr A / 3) I`` (the same: a shift
    moves every root alike) and counts as negative below ``-rtol ||B||^6``. Why: the roots'
    spread, not their size, sets a discriminant, so on ``A`` itself a robust complex pair
    next to a close third root was lost in the round-off of ``(tr A / 3)^6`` (an outside
    audit: with the flutter map's anisotropy 0.05, a pair with ``|Im c^2| = 1.2e-3 |c^2|``
    had a discriminant of 1.7e-13 of that scale, below the former threshold 1e-9, and the
    fractions of fluttering directions were under-counted by up to 2.5x). Measured on the
    flutter map's tensors (6561 directions x 200 moduli): at an exact coalescence (isotropic
    elasticity) ``|disc(B)| <= 4e-16 ||B||^6``; every fluttering tensor has
    ``disc(B) < -1.3e-6 ||B||^6``; ``rtol`` = 1e-12 sits between, and the counts equal those
    of the eigenvalues (a pair with ``|Im| > 1e-7 |c^2|``) at every anisotropy."""
    rtol = _check_rtol(rtol)
    # (an audit: directions=None raised numpy's TypeError; acoustic_tensors checks the rest)
    n = check_finite_array("directions", directions, _shape(directions), "finite numbers")
    # in blocks of directions: the tensors of the whole map (6561 x 200) would take 94 MB, and
    # the deviator as much again
    return np.concatenate([
        np.any(has_complex_pair(_unit_acoustic_tensors(E, P, Q, n[i:i + 256], g_values)[0],
                                rtol), axis=1)
        for i in range(0, len(n), 256)]) if len(n) else np.zeros(0, dtype=bool)


def _shape(value: object) -> tuple[int, ...]:
    """The shape of ``value`` (any), for :func:`check_finite_array` to check the entries; a
    ragged nesting has none and is refused there."""
    try:
        return np.shape(value)
    except ValueError:
        return (-1,)


def _stack_inputs(E: NDArray, P: ArrayLike, Q: ArrayLike, directions: NDArray
                  ) -> tuple[NDArray, NDArray, NDArray, NDArray]:
    """``E``, ``P``, ``Q`` and the directions (m, 3) of the vectorised functions, checked: finite,
    of their shapes, no zero direction (an audit: NaN in, NaN out; a LinAlgError for n = 0)."""
    E = check_elasticity(E)
    P, Q = check_flow_tensor("P", P), check_flow_tensor("Q", Q)
    n = check_finite_array("directions", directions, _shape(directions), "finite numbers")
    if n.ndim != 2 or n.shape[1] != 3:
        raise ParameterError(f"directions must be an array of shape (m, 3), got shape {n.shape}")
    if np.any(np.all(n == 0.0, axis=1)):
        raise ParameterError("directions must be non-zero vectors (propagation directions)")
    return E, P, Q, n


def _exponent(A: NDArray) -> int:
    """``e`` with ``max |A| = m 2^e``, ``m`` in [1/2, 1) (0 for a zero array): dividing by
    ``2^e`` is exact, so the scaled computations below give the same bits at ordinary scales."""
    return math.frexp(float(np.max(np.abs(A))))[1]


#: ``2^k`` of the moduli's scale (``|E| |P| |Q|``) is kept within [RANGE_MIN, RANGE_MAX]:
#: log2 of 1e300 is 996.6.
_SCALE_EXPONENT_MAX = 996


def _unit_inputs(E: NDArray, P: NDArray, Q: NDArray) -> tuple[NDArray, NDArray, NDArray,
                                                               int, int]:
    """``E``, ``P``, ``Q`` divided by powers of two near their largest entries, and the
    exponents ``kE`` (``A_el`` scales as ``2^kE``) and ``k`` (the moduli ``g``, which scale as
    ``|E| |P| |Q|``, as ``2^k``). Every function of this section is homogeneous in them, and in
    these units their products stay in range: an outside audit found, at ``P, Q x 1e160``, the
    localization moduli NaN and ``-inf`` with no warning, and the brute-force interval empty
    at ``E x 1e-100`` (its quartic's coefficients underflowed) and a LinAlgError at ``1e40``.
    Refused where the moduli's scale itself leaves [1e-300, 1e300]."""
    kE, kP, kQ = _exponent(E), _exponent(P), _exponent(Q)
    k = kE + kP + kQ
    if abs(k) > _SCALE_EXPONENT_MAX:
        raise ParameterError(
            f"E, P and Q put the plastic moduli's scale |E| |P| |Q| ~ "
            f"1e{round(k * math.log10(2.0))} outside "
            f"[{RANGE_MIN:g}, {RANGE_MAX:g}] (the double range of the moduli g): rescale them")
    return np.ldexp(E, -kE), np.ldexp(P, -kP), np.ldexp(Q, -kQ), kE, k


def _in_range(name: str, x: NDArray, k: int) -> NDArray:
    """``x 2^k``, refused (naming ``name``) where it overflows."""
    with np.errstate(over="ignore"):
        out = np.ldexp(x, k)
    if not np.all(np.isfinite(out)):
        raise ParameterError(f"{name} leave the double range at these E, P, Q: rescale them")
    return out


def _unit_acoustic_tensors(E: NDArray, P: ArrayLike, Q: ArrayLike, directions: NDArray,
                           g_values: NDArray) -> tuple[NDArray, int]:
    """:func:`acoustic_tensors` in units of ``2^kE`` (``A_el``'s scale), and ``kE``."""
    E, P, Q, n = _stack_inputs(E, P, Q, directions)
    g = check_finite_array("g_values", g_values, _shape(g_values), "finite numbers")
    if g.ndim != 1 or np.any(g == 0.0):
        raise ParameterError(f"g_values must be a 1-d array of non-zero moduli (A has "
                             f"p (x) q / g), got shape {g.shape}"
                             + (", a zero" if np.any(g == 0.0) else ""))
    E, P, Q, kE, k = _unit_inputs(E, P, Q)
    Ael = np.einsum("ijkl,mj,ml->mik", E, n, n)
    p = np.einsum("ij,mj->mi", np.einsum("ijkl,kl->ij", E, P), n)
    q = np.einsum("kl,ml->mk", np.einsum("ijkl,ij->kl", E, Q), n)
    mg, eg = np.frexp(g)  # 2^k / g without forming 1/g (g may be subnormal)
    with np.errstate(over="ignore"):
        ratio = np.ldexp(1.0 / mg, k - eg)
    pq = np.einsum("mi,mk->mik", p, q)
    # A is finite where the update is: |p (x) q| |2^k/g| bounded (checked on the factors, not
    # on the whole stack of tensors)
    if not (np.all(np.isfinite(ratio))
            and float(np.max(np.abs(pq), initial=0.0)) * float(np.max(np.abs(ratio))) < 1e300):
        raise ParameterError("g_values: the acoustic tensors A = A_el - p (x) q / g leave the "
                             "double range (a modulus g too small for these E, P, Q)")
    return Ael[:, None] - pq[:, None] * ratio[None, :, None, None], kE


def acoustic_tensors(E: NDArray, P: ArrayLike, Q: ArrayLike, directions: NDArray,
                     g_values: NDArray) -> NDArray:
    """The acoustic tensors ``A(n; g)`` of eq. (163) (rho = 1) for every direction and every
    ``g``, shape (directions, g values, 3, 3), vectorised. ``g_values``: a 1-d array of finite,
    non-zero moduli."""
    A, kE = _unit_acoustic_tensors(E, P, Q, directions, g_values)
    return _in_range("the acoustic tensors", A, kE)


def _check_rtol(rtol: object) -> float:
    """A relative threshold in [0, 1) (an outside audit: -1 called a real spectrum complex,
    NaN a complex one real)."""
    rtol = check_real("rtol", rtol)
    if not 0.0 <= rtol < 1.0:
        raise ParameterError(f"rtol must be in [0, 1), got {rtol!r}")
    return rtol


def _real_stack(name: str, A: object) -> NDArray:
    """``A`` as a new float array of finite real 3x3 matrices (..., 3, 3): numbers only (an
    outside audit's ``"1"`` entries were read as 1.0)."""
    B = check_finite_reals(name, A)
    if B.ndim < 2 or B.shape[-2:] != (3, 3):
        raise ParameterError(f"{name} must be real 3x3 matrices (shape (..., 3, 3)), got shape "
                             f"{B.shape}")
    return B


def has_complex_pair(A: NDArray, rtol: float = 1e-12) -> NDArray:
    """Whether each real 3x3 matrix of the stack ``A`` (..., 3, 3) has a complex-conjugate
    pair of eigenvalues: the discriminant of its deviator below ``-rtol ||B||^6`` (see
    :func:`flutters_somewhere` for why the deviator and for the measured margins)."""
    rtol = _check_rtol(rtol)
    B = _real_stack("A", A)  # a copy, shifted in place
    t = np.trace(B, axis1=-2, axis2=-1) / 3
    for i in range(3):
        B[..., i, i] -= t
    with np.errstate(over="ignore", under="ignore"):
        scale = np.einsum("...ij,...ij->...", B, B) ** 3
    # A matrix whose ||B||^6 leaves the normal range (an outside audit's scales: it overflowed
    # from entries ~1e51) is divided by a power of two near its largest entry: exact, and only
    # those matrices (the others keep their bits; the pass over all of them cost the flutter
    # map ~0.3 s, measured)
    odd = ~((scale > 1e-250) & (scale < 1e250))
    if np.any(odd):
        _, e = np.frexp(np.max(np.abs(B[odd]), axis=(-2, -1)))
        B[odd] = np.ldexp(B[odd], -e[..., None, None])
        scale[odd] = np.einsum("...ij,...ij->...", B[odd], B[odd]) ** 3
    return cubic_discriminant(B) < -rtol * scale


def classify_acoustic(A: NDArray, rtol: float = 1e-10, imag_rtol: float = 1e-7) -> Regime:
    """§3.3 (Rice 1977): stable when all ``c^2`` are positive, flutter when two are complex
    conjugate, divergence when one is real and negative (tolerances: see
    :func:`classify_eigenvalues`)."""
    A = check_finite_array("A", A, (3, 3), "a finite 3x3 matrix")
    return classify_eigenvalues(np.linalg.eigvals(A), rtol, imag_rtol)


#: Most directions :func:`fibonacci_sphere` makes: its arrays take ~72 bytes a direction
#: (72 MB here), and the spacing of 1e6 points on the half sphere, ~2.5e-3 rad, is far finer
#: than the Nelder-Mead refinement of :func:`max_localization_modulus` needs (default 4000).
FIBONACCI_MAX = 1_000_000


def fibonacci_sphere(n: int) -> NDArray:
    """``n`` nearly uniform unit vectors on the upper half sphere (``n`` and ``-n`` are the
    same band direction), shape (n, 3); ``n`` in [1, :data:`FIBONACCI_MAX`]."""
    n = check_integer("n", n, 1, FIBONACCI_MAX)
    k = np.arange(n) + 0.5
    z = k / n  # z in (0, 1]: the half sphere
    phi = np.pi * (1 + 5**0.5) * k
    r = np.sqrt(1 - z**2)
    return np.stack([r * np.cos(phi), r * np.sin(phi), z], axis=-1)


def localization_moduli(E: NDArray, P: ArrayLike, Q: ArrayLike, directions: NDArray) -> NDArray:
    """``g_cr^E(n)`` of eq. (166) for many directions at once (vectorised), rho = 1."""
    E, P, Q, n = _stack_inputs(E, P, Q, directions)
    E, P, Q, _, k = _unit_inputs(E, P, Q)  # g scales as |E| |P| |Q| = 2^k
    return _in_range("the localization moduli g_cr^E", _unit_moduli(E, P, Q, n), k)


def _unit_moduli(E: NDArray, P: NDArray, Q: NDArray, n: NDArray) -> NDArray:
    """:func:`localization_moduli` of inputs already checked and in units of order one."""
    Ael = np.einsum("ijkl,mj,ml->mik", E, n, n)
    EP = np.einsum("ijkl,kl->ij", E, P)
    EQt = np.einsum("ijkl,ij->kl", E, Q)
    p = np.einsum("ij,mj->mi", EP, n)
    q = np.einsum("kl,ml->mk", EQt, n)
    try:
        g = np.einsum("mi,mi->m", q, np.linalg.solve(Ael, p[..., None])[..., 0])
    except np.linalg.LinAlgError:
        raise ParameterError("E must give a non-singular elastic acoustic tensor A_el(n) for "
                             "every direction (eq. 166 needs its inverse)") from None
    if not np.all(np.isfinite(g)):  # an A_el(n) singular to round-off: LAPACK gave inf/NaN
        raise ParameterError("E must give a non-singular elastic acoustic tensor A_el(n) for "
                             "every direction (eq. 166 needs its inverse)")
    return g


def _angles_to_n(x: NDArray) -> NDArray:
    th, ph = x
    return np.array([np.sin(th) * np.cos(ph), np.sin(th) * np.sin(ph), np.cos(th)])


def max_localization_modulus(E: NDArray, P: ArrayLike, Q: ArrayLike,
                             n_search: int = 4000) -> tuple[float, NDArray]:
    """``max_n g_cr^E(n)`` and the maximising direction: a global search on a Fibonacci grid,
    then Nelder–Mead refinement from the best few grid points (the modulus often has several
    symmetric maxima). ``n_search`` in [1, :data:`FIBONACCI_MAX`]."""
    grid = fibonacci_sphere(check_integer("n_search", n_search, 1, FIBONACCI_MAX))
    E, P, Q, _ = _stack_inputs(E, P, Q, grid[:1])
    E, P, Q, _, k = _unit_inputs(E, P, Q)  # searched in units of 2^k, scaled back at the end
    vals = _unit_moduli(E, P, Q, grid)
    best_val, best_n = -np.inf, grid[0]
    for i in np.argsort(vals)[-5:]:
        n0 = grid[i]
        x0 = np.array([np.arccos(np.clip(n0[2], -1, 1)), np.arctan2(n0[1], n0[0])])
        res = minimize(lambda x: -_unit_moduli(E, P, Q, _angles_to_n(x)[None])[0], x0,
                       method="Nelder-Mead", options={"xatol": 1e-12, "fatol": 1e-15,
                                                      "maxiter": 4000})
        if -res.fun > best_val:
            best_val, best_n = -res.fun, _angles_to_n(res.x)
    return float(_in_range("the localization modulus", np.float64(best_val), k)), best_n


def discriminant_polynomial(E: NDArray, P: ArrayLike, Q: ArrayLike, n: ArrayLike
                            ) -> np.polynomial.Polynomial:
    """The cubic discriminant of ``A(n; g) = A_el - p (x) q / g`` (eq. 161) as a polynomial in
    ``x = 1/g``. ``A`` is a rank-one update of ``A_el``, so its invariants are affine in ``x``:
    ``I1 = tr A_el - x p.q``, ``I2 = I2_el - x (tr A_el p.q - q.A_el p)``,
    ``I3 = det A_el - x q.adj(A_el) p`` (matrix determinant lemma), and the discriminant is a
    quartic in ``x``. Its coefficients are formed once, so no cancellation grows with ``x``,
    which is what limits evaluating the discriminant from the invariants at each ``g``."""
    from numpy.polynomial import Polynomial

    n = np.asarray(n, dtype=float)
    Ael = elastic_acoustic_tensor(E, n)
    p, q = acoustic_vectors(E, P, Q, n)
    t, pq = float(np.trace(Ael)), float(p @ q)
    i2_el = 0.5 * (t**2 - float(np.trace(Ael @ Ael)))
    adj = np.linalg.det(Ael) * np.linalg.inv(Ael)
    i1 = Polynomial([t, -pq])
    i2 = Polynomial([i2_el, -(t * pq - float(q @ Ael @ p))])
    i3 = Polynomial([float(np.linalg.det(Ael)), -float(q @ adj @ p)])
    b, c, d = -i1, i2, -i3  # eta^3 + b eta^2 + c eta + d
    return 18 * b * c * d - 4 * b**3 * d + b**2 * c**2 - 4 * c**3 - 27 * d**2


def _secular_terms(Ael: NDArray, p: NDArray, q: NDArray, ael_norm: float
                   ) -> tuple[NDArray, NDArray] | None:
    """The poles ``a_k`` and weights ``s_k`` of the secular equation of ``A_el - x p (x) q``:
    ``1 = x sum_k s_k/(a_k - eta)``, from ``q^T (A_el - eta I)^-1 p`` with
    ``A_el = V diag(a) V^-1``, so ``s_k = (V^T q)_k (V^-1 p)_k`` (``V`` orthogonal, by
    ``eigh``, where ``A_el`` is symmetric: E with the major symmetry; complex conjugate
    pairs where a non-symmetric ``A_el`` has them); ``None`` where its eigenvectors are
    singular to working precision (cond > 1e8: no diagonal form to trust)."""
    eps = float(np.finfo(float).eps)
    if float(np.max(np.abs(Ael - Ael.T))) <= 8 * eps * ael_norm:
        a, V = np.linalg.eigh(Ael)
        return a, (V.T @ p) * (V.T @ q)
    a, V = np.linalg.eig(Ael)
    if np.linalg.cond(V) > 1e8:
        return None
    if not np.any(np.imag(a)):
        a, V = np.real(a), np.real(V)
    # complex poles (A_el itself has a complex pair: flutter at every large g) come in
    # conjugate pairs with conjugate weights: the sums stay real on the real eta axis
    return a, (V.T @ q) * np.linalg.solve(V, p)


def _secular_end(x0: float, Ael: NDArray, p: NDArray, q: NDArray, a: NDArray,
                 s: NDArray, k: int = 0) -> float:
    """The coalescence of two eigenvalues of ``A_el - x p (x) q`` nearest ``x0``: Newton on
    ``S2(eta) = sum s_k/(a_k - eta)^2 = 0``, then ``x = 1 / sum s_k/(a_k - eta)`` (sums: no
    cancellation of large terms), started from each eigenvalue of A(x0) and each pair's mean
    (an isotropic A_el keeps one eigenvalue mu fixed, which may lie closer than the coalescing
    pair). The converged ``x`` nearest ``x0``; refused (:class:`ConvergenceError`) if none
    lands within 1e-3 of ``x0``, naming ``g = 2^k / x0`` (``k``: the moduli's unit,
    :func:`_unit_inputs`)."""
    eta_all = np.linalg.eigvals(Ael - x0 * np.outer(p, q)).real
    starts = [*eta_all, *(0.5 * (eta_all[i] + eta_all[j]) for i in range(eta_all.size)
                          for j in range(i + 1, eta_all.size))]
    keep = s != 0.0
    a, s = a[keep], s[keep]
    found = []
    for eta in starts:
        for _ in range(60):
            d = a - eta
            if np.any(d == 0.0):
                break
            with np.errstate(over="ignore", under="ignore"):  # (real for real eta: complex
                # poles and weights come in conjugate pairs)
                s2, s3 = float(np.sum(s / d**2).real), 2.0 * float(np.sum(s / d**3).real)
            if s3 == 0.0 or not (np.isfinite(s2) and np.isfinite(s3)):
                break
            step = s2 / s3
            eta -= step
            if np.any(a == eta):
                break
            # S2's terms cancel at its root: the step settles at ~1e-14 of the scale, not eps
            if abs(step) <= 1e-11 * max(abs(eta), float(np.max(np.abs(a)))):
                s1 = float(np.sum(s / (a - eta)).real)
                if s1 != 0.0 and abs(1.0 / s1 - x0) <= 1e-3 * abs(x0):
                    found.append(1.0 / s1)
                break
    if not found:
        raise ConvergenceError(f"the flutter interval's end near g = "
                               f"{float(np.ldexp(1 / x0, k)):.6g} was not "
                               "resolved (the secular equation's Newton did not confirm it); "
                               "use flutter_interval_isotropic (isotropic solids)")
    return min(found, key=lambda x: abs(x - x0))


def _coalescence_points(a: NDArray, s: NDArray, n_samples: int = 4001) -> list[float]:
    """Every ``x`` where two eigenvalues of ``diag(a) - x (V^T p)(V^T q)^T`` coalesce: the
    roots ``eta`` of ``S2(eta) = sum s_k/(a_k - eta)^2`` (sampled between and beyond the poles
    ``a_k``, equal ones merged, sign changes solved by Brent), mapped by
    ``x = 1/S1(eta)``, ``S1 = sum s_k/(a_k - eta)`` (the secular equation of the rank-one
    update: no cancellation of large coefficients)."""
    scale = float(np.max(np.abs(a))) or 1.0
    poles, weights = [], []
    for ak, sk in sorted(zip(a.tolist(), s.tolist(), strict=True),
                         key=lambda t: (t[0].real, t[0].imag, t[1].real, t[1].imag)):
        if poles and abs(ak - poles[-1]) <= 1e-12 * scale:
            weights[-1] += sk
        else:
            poles.append(ak)
            weights.append(sk)
    pa, ps = np.array(poles), np.array(weights)
    keep = ps != 0.0
    pa, ps = pa[keep], ps[keep]
    if pa.size < 2:
        return []

    def s2(eta: NDArray) -> NDArray:  # (real on the real axis: conjugate poles in pairs)
        return np.sum(ps[:, None] / (pa[:, None] - np.atleast_1d(eta)[None]) ** 2,
                      axis=0).real

    w = 0.5 * (1.0 - np.cos(np.pi * np.arange(1, n_samples) / n_samples))  # in (0, 1)
    ends = pa.real  # the samples crowd towards the poles (towards their real parts)
    pieces = [ends[0] - scale * w / (1.0 - w)]
    pieces += [lo + (hi - lo) * w for lo, hi in zip(ends[:-1], ends[1:], strict=True)]
    pieces += [ends[-1] + scale * w / (1.0 - w)]
    points = []
    with np.errstate(over="ignore", under="ignore", divide="ignore", invalid="ignore"):
        for eta in pieces:
            val = s2(eta)
            for i in np.nonzero(np.sign(val[:-1]) * np.sign(val[1:]) < 0)[0]:
                root = brentq(lambda e: float(s2(e)[0]), float(eta[i]), float(eta[i + 1]),
                              xtol=1e-300, rtol=1e-15, maxiter=500)
                s1 = float(np.sum(ps / (pa - root)).real)
                if s1 != 0.0 and np.isfinite(s1):
                    points.append(1.0 / s1)
    return points


#: The largest ``g`` of :func:`flutter_interval_bruteforce`, in units of the scale
#: ``|p| |q| / ||A_el||`` of the rank-one part ``p (x) q / g``. The isotropic ``A_el`` has the
#: double eigenvalue mu, so the quartic's two lowest coefficients vanish up to their round-off
#: (eps of their terms): its roots below ``x = 1/g ~ sqrt(eps)`` of the scale, ``g ~ 7e7``
#: times it, are noise. Measured (96 random isotropic solids with an interval, nu from -0.9 to
#: 0.4999): refusals (ConvergenceError) rise from 1 % at g_max = 1e2 times the scale through
#: 6 % at 1e4 to 30 % at 1e6 and 52 % from 1e8; none wrong. Every flutter interval ends below
#: :data:`G2_OVER_SCALE_MAX` times the scale, the workflow asks for 10 g2: 1e4 leaves a factor
#: of 40 above that.
G_MAX_OVER_SCALE = 1e4
#: Bound of ``g2 / (|p| |q| / ||A_el||)`` for isotropic elasticity: ``g2 = (sqrt N +
#: sqrt(N - p.q))^2 / (lam + mu) <= (1 + sqrt 2)^2 |p| |q| / (lam + mu)`` and ``||A_el|| /
#: (lam + mu) <= 4`` for ``lam > -2 mu / 3`` (Frobenius norm: up to sqrt 3 more); measured
#: largest 5.6.
G2_OVER_SCALE_MAX = 41.0


def flutter_interval_bruteforce(E: NDArray, P: ArrayLike, Q: ArrayLike, n: ArrayLike,
                                g_max: float, decades: float = 8.0) -> list[tuple[float, float]]:
    """Intervals of ``g`` in ``[g_max 10^-decades, g_max]`` where the acoustic tensor (eq. 161)
    has complex eigenvalues, from the tensors alone (no closed form): the discriminant of the
    eigenvalue problem as a quartic in ``x = 1/g`` (:func:`discriminant_polynomial`): its sign
    changes between its critical points, solved by Brent, each end polished on the secular
    equation of the rank-one update (:func:`_secular_end`); with them every coalescence of the
    secular equation itself (:func:`_coalescence_points`: where the quartic's coefficients
    cancel, nu -> 1/2, a narrow interval has its ends only there). Each piece between ends is
    flutter where the eigenvalues of A itself have a complex pair above their round-off, and
    where they do not resolve it, by the quartic's sign, refused
    (:class:`ConvergenceError`) if that sign says flutter. An interval touching an end of the
    range is cut there. Measured on ~1000 random isotropic flutter cases (nu from -0.9 to
    0.49999, n also on the axes): none wrong, ends within 2e-11 of the closed form, ~6 %
    refused; 150 anisotropic cases agree with an eigenvalue scan (and 50-digit eigenvalues
    where the scan's threshold hesitated).

    ``g_max`` is at most :data:`G_MAX_OVER_SCALE` ``|p| |q| / ||A_el||`` (see there; an audit:
    g_max = 1e10 to 1e150 on the shipped case ended in a ConvergenceError, 1e200 in a
    ZeroDivisionError). A symmetric ``A`` (``A_el`` symmetric and ``p`` parallel to ``q``, e.g.
    ``P = Q`` with isotropic elasticity) has real eigenvalues: no interval (an audit: P = Q gave
    a ConvergenceError, and the closed forms a spurious interval 3e-8 wide, at a double root
    of the discriminant)."""
    # real numbers (an audit: g_max=None raised float()'s TypeError)
    g_max, decades = check_real("g_max", g_max), check_real("decades", decades)
    if not (np.isfinite(g_max) and g_max > 0):
        raise ParameterError(f"g_max must be finite and > 0, got {g_max}")
    if not (np.isfinite(decades) and 0.0 < decades <= 300.0):
        raise ParameterError(f"decades must be in (0, 300], got {decades}")
    lo, hi = 1.0 / g_max, 10.0**decades / g_max
    if not (lo <= 1e300 and hi <= 1e300):  # 1/g beyond the floats (an audit: a LinAlgError)
        raise ParameterError(f"g_max 10^-decades = {g_max:.3g} x 1e-{decades:g} must be >= "
                             "1e-300 (the range of 1/g)")
    # In units where E, P and Q are of order one (exact powers of two, :func:`_unit_inputs`):
    # x = 1/g below is 2^k / g, and the intervals are scaled back at the end.
    E = check_elasticity(E)
    P, Q = check_flow_tensor("P", P), check_flow_tensor("Q", Q)
    E, P, Q, _, k = _unit_inputs(E, P, Q)
    Ael = elastic_acoustic_tensor(E, np.asarray(n, dtype=float))
    p, q = acoustic_vectors(E, P, Q, np.asarray(n, dtype=float))
    eps = float(np.finfo(float).eps)
    pq_norm, ael_norm = float(np.linalg.norm(p) * np.linalg.norm(q)), float(np.linalg.norm(Ael))
    if float(np.linalg.norm(np.cross(p, q))) <= 8 * eps * pq_norm \
            and float(np.max(np.abs(Ael - Ael.T))) <= 8 * eps * ael_norm:
        return []  # A symmetric for every g (p (x) q symmetric, or zero): real eigenvalues
    with np.errstate(over="ignore"):
        g_top = float(np.ldexp(G_MAX_OVER_SCALE * pq_norm / ael_norm, k))
    if not g_max <= g_top:
        raise ParameterError(
            f"g_max must be <= {G_MAX_OVER_SCALE:g} |p| |q| / ||A_el|| = {g_top:.6g} here (beyond, "
            f"the discriminant's round-off decides; flutter intervals end below "
            f"{G2_OVER_SCALE_MAX:g} |p| |q| / ||A_el||), got {g_max!r}")
    lo, hi = float(np.ldexp(lo, k)), float(np.ldexp(hi, k))
    if not hi <= 1e300:
        raise ParameterError(
            f"g_max 10^-decades = {g_max:.3g} x 1e-{decades:g} must be >= 1e-300 |p| |q| / "
            f"||A_el|| = {float(np.ldexp(1e-300 * pq_norm / ael_norm, k)):.3g} here (the "
            f"range of 1/g in the moduli's scale)")
    disc = discriminant_polynomial(E, P, Q, n)
    ddisc = disc.deriv()

    def polish(x: float) -> float:  # Newton on the polynomial, kept only when it helps
        for _ in range(3):
            slope = float(ddisc(x))
            if slope == 0.0:
                break
            x_new = x - float(disc(x)) / slope
            if not abs(float(disc(x_new))) < abs(float(disc(x))):
                break
            x = x_new
        return x

    # The sign of the quartic is decided by its values at the range's ends and at its
    # critical points (the roots of its derivative: a narrow negative dip lies around one),
    # between which it is monotone: every sign change between two such samples brackets one
    # root, solved by Brent to round-off. (Candidate ends from the quartic's own roots alone
    # missed narrow intervals of nearly incompressible solids, whose close root pairs came out
    # as complex pairs or displaced: an outside audit, 18 of 102 random cases at nu = 0.4999.)
    samples = sorted({float(np.clip(r.real, lo, hi)) for r in ddisc.roots()}
                     | {float(np.clip(polish(r.real), lo, hi)) for r in disc.roots()}
                     | {lo, hi})
    values = [float(disc(x)) for x in samples]
    roots = []
    for i in range(len(samples) - 1):
        a, b, fa, fb = samples[i], samples[i + 1], values[i], values[i + 1]
        if fa == 0.0:
            roots.append(a)
        elif fa * fb < 0:
            roots.append(brentq(lambda x: float(disc(x)), a, b, xtol=1e-300, rtol=1e-15,
                                maxiter=500))
    # Each end polished on the secular equation, well conditioned where the quartic's
    # coefficients are not (nu = 0.4999 moved ends by 1e-4 in an outside audit): an end is
    # where two eigenvalues of A = A_el - x p (x) q coalesce: 1 = x sum s_k/(a_k - eta) and
    # sum s_k/(a_k - eta)^2 = 0 (poles and weights: _secular_terms, also without E's major
    # symmetry); where A_el's eigenvectors are singular the quartic's roots stand alone.
    secular = _secular_terms(Ael, p, q, ael_norm)
    if secular is not None:
        a_el, s_k = secular
        roots = [_secular_end(x, Ael, p, q, a_el, s_k, k) for x in roots]
        # ... and every coalescence of the secular equation itself: a dip narrower than the
        # quartic's round-off (nu -> 1/2: its terms cancel from ~1e21) has its ends there
        roots += [x for x in _coalescence_points(a_el, s_k) if lo < x < hi]
    cands: list[float] = []
    for x in sorted(set(roots) | {lo, hi}):  # one end where both routes found it
        if not cands or x > cands[-1] * (1.0 + 1e-9):
            cands.append(x)
    cands[-1] = max(cands[-1], hi)
    intervals: list[tuple[float, float]] = []
    for a, b in zip(cands[:-1], cands[1:], strict=True):
        if not b > a:
            continue
        x = float(np.sqrt(a) * np.sqrt(b))  # not sqrt(a b): that underflows below 1e-308
        negative = float(disc(x)) < 0
        # The eigenvalues of A itself confirm the sign wherever they resolve it (a complex
        # pair above their round-off, or three real ones further apart than it); a
        # contradiction means the coefficients' round-off decided: refused.
        eta = np.linalg.eigvals(Ael - x * np.outer(p, q))
        noise = 1e3 * np.finfo(float).eps * float(np.max(np.abs(eta)))
        gaps = np.abs(eta[:, None] - eta[None, :])[np.triu_indices(eta.size, 1)]
        resolved = float(np.max(np.abs(eta.imag))) > noise or (
            not np.any(eta.imag) and float(np.min(gaps)) > noise)
        if resolved:  # the eigenvalues of A decide where they resolve it
            negative = bool(float(np.max(np.abs(eta.imag))) > noise)
        elif negative:  # a flutter interval must show a complex pair
            raise ConvergenceError(
                f"the discriminant's sign at g = {float(np.ldexp(1 / x, k)):.6g} is not "
                "confirmed by the "
                "eigenvalues of A there (its coefficients' round-off decides it); use "
                "flutter_interval_isotropic (isotropic solids)")
        if negative:
            if intervals and intervals[-1][0] == 1.0 / a:  # adjacent pieces: one interval
                intervals[-1] = (1.0 / b, intervals[-1][1])
            else:
                intervals.append((1.0 / b, 1.0 / a))
    ends = _in_range("the flutter intervals' ends", np.array(intervals).reshape(-1, 2), k)
    return sorted((float(g1), float(g2)) for g1, g2 in ends)


# ---------------------------------------------------------------------- isotropic, any scale
#: Results and scales are kept within [RANGE_MIN, RANGE_MAX] (floats end at 1.8e308 and lose
#: precision below 2.2e-308); what would leave that range is refused, never rounded to 0/inf.
RANGE_MIN, RANGE_MAX = 1e-300, 1e300
#: Largest lam/mu. The products stay in range up to ~1e150, but k = (lam' + 1)/(lam' + 2) in
#: ``uv - k pn qn`` rounds at eps lam/mu (an outside audit: at lam/mu = 1e20 an eigenvalue
#: came out with the wrong sign, at 1e12 g_E was off by 6e-5): 1e8 keeps that error near
#: 1e-8 and is nu = 1/2 - 5e-9, beyond any solid (rubber: lam/mu ~ 5e3).
LAM_OVER_MU_MAX = 1e8


def classify_eigenvalues(eta: ArrayLike, rtol: float = 1e-10, imag_rtol: float = 1e-7
                         ) -> Regime:
    """:func:`classify_acoustic` from the eigenvalues themselves: flutter for a pair with
    ``|Im| > imag_rtol max|eta|``, divergence for a real part below ``-rtol max|eta|``.

    ``imag_rtol``: a double eigenvalue at a coalescence is a Jordan block, and round-off of
    ``eps`` in ``A`` moves it by ``~sqrt(eps) = 1.5e-8`` as a complex pair (an audit: P = Q,
    where A is symmetric, gave ``1 +- 1.49e-8 i`` from eq. 184 and regime flutter under the
    former 1e-10); 1e-7 sits above that. ``rtol``: a simple real eigenvalue moves by ``~eps``.
    Measured (3000 random isotropic solids): a symmetric A (P = Q) gives ``|Im| <= 1.2e-16``,
    but a strongly non-normal coalescence up to 6e-6, so no threshold decides every case:
    :func:`isotropic_acoustic` decides the pair from the factored discriminant instead."""
    for name, tol in (("rtol", rtol), ("imag_rtol", imag_rtol)):
        if not 0.0 <= check_real(name, tol) < 1.0:  # (an outside review: -inf, '1' accepted)
            raise ParameterError(f"{name} must be in [0, 1), got {tol!r}")
    eta = np.asarray(eta)
    if eta.ndim != 1 or eta.size == 0 or eta.dtype.kind not in "iufc" \
            or not np.all(np.isfinite(eta)):
        raise ParameterError(f"eta must be a non-empty 1-d array of finite (complex) "
                             f"eigenvalues, got {' '.join(repr(eta).split())[:80]}")
    eta = eta.astype(complex)
    scale = max(float(np.abs(eta).max()), np.finfo(float).tiny)
    if np.any(np.abs(eta.imag) > imag_rtol * scale):
        return Regime.FLUTTER
    if np.any(eta.real < -rtol * scale):
        return Regime.DIVERGENCE
    return Regime.STABLE


def _mul(*factors: float, divide: tuple[float, ...] = ()) -> tuple[float, int]:
    """``prod(factors) / prod(divide)`` as ``(mantissa, exponent)`` (base 2): no overflow or
    underflow in between, whatever the scales."""
    m, e = 1.0, 0
    for f in factors:
        fm, fe = math.frexp(f)
        m, k = math.frexp(m * fm)
        e += fe + k
    for d in divide:
        dm, de = math.frexp(d)
        m, k = math.frexp(m / dm)
        e += k - de
    return m, e


def _as_float(me: tuple[float, int]) -> float:
    """The float of :func:`_mul`'s pair, ``inf`` when it overflows."""
    m, e = me
    try:
        return math.ldexp(m, e)
    except OverflowError:
        return math.copysign(math.inf, m)


def _quadratic_roots(b: float, c: float, disc: Callable[[float], float] | None = None,
                     real: bool = False) -> tuple[complex, complex]:
    """Roots of ``eta^2 - b eta + c`` without overflow (scaled) or cancellation (the smaller
    real root from the product ``c``), ascending (by imaginary part when complex). The
    discriminant over ``m^2`` from ``disc(m)`` when given (a form without cancellation at a
    double root), clipped at 0 when ``real`` (known to be >= 0)."""
    m = max(abs(b), math.sqrt(abs(c)))
    if m == 0.0:
        return 0j, 0j
    bs, cs = b / m, c / m / m
    d = bs * bs - 4.0 * cs if disc is None else disc(m)
    if real:
        d = max(d, 0.0)
    if d < 0:
        re, im = m * bs / 2, m * math.sqrt(-d) / 2
        return complex(re, -im), complex(re, im)
    big = m * (bs + math.copysign(math.sqrt(d), bs)) / 2
    small = c / big if big != 0.0 else 0.0
    lo, hi = sorted((small, big))
    return complex(lo), complex(hi)


@dataclass(frozen=True)
class IsotropicAcoustic:
    """What :func:`isotropic_acoustic` finds; moduli in the units of ``mu``."""

    g_localization: float
    flutter_interval: tuple[float, float] | None
    eigenvalues: tuple[complex, complex, complex] | None = None
    regime: Regime | None = None
    notes: tuple[str, ...] = ()


def isotropic_acoustic(lam: float, mu: float, P: ArrayLike, Q: ArrayLike, n: ArrayLike,
                       g: float | None = None, names: dict[str, str] | None = None
                       ) -> IsotropicAcoustic:
    """The localization modulus (eq. 185), the flutter interval (eq. 188 corrected) and, with
    ``g``, the eigenvalues of ``A(n)`` (``mu`` and the roots of eq. 184) and their regime, for
    isotropic elasticity and unit density, at any scale of the inputs.

    Everything is computed in scaled quantities: ``lam' = lam/mu``, ``P^ = P/max|P|``,
    ``Q^ = Q/max|Q|``, ``n`` normalised after division by ``max|n|``; moduli come in units of
    ``S = mu max|P| max|Q|``, eigenvalues in units of ``mu``. The formulas are rearranged so
    that the ``lam'^2`` terms, which cancel in eqs. (185) and (188), are never formed:
    ``g^_E = r (lam' trP trQ + 2 trP qn + 2 trQ pn) + 4 (u.v - k pn qn)`` with ``u = P^ n``,
    ``v = Q^ n``, ``pn = n.u``, ``qn = n.v``, ``r = lam'/(lam'+2)``, ``k = (lam'+1)/(lam'+2)``,
    and ``N - p.q = 4 (pn qn - u.v)``; the smaller end of the flutter interval and the smaller
    real eigenvalue come from products, not differences. Inputs whose results would leave
    ``[1e-300, 1e300]`` are refused (:class:`ParameterError` naming the parameter and its
    range), so no result is ever rounded to 0, inf or NaN. ``names`` relabels the parameters
    in messages (e.g. ``{"lam": "--lam"}``)."""
    if names is not None and not (isinstance(names, dict) and all(
            isinstance(k, str) and isinstance(v, str) for k, v in names.items())):
        raise ParameterError(f"names must be a dict of parameter names to labels (str to str), "
                             f"got {names!r}")
    nm = {k: k for k in ("lam", "mu", "P", "Q", "n", "g")} | (names or {})
    if g is not None:
        g = check_real(nm["g"], g)
        if not g > 0:  # eq. (152): "assumed strictly positive"; the flutter interval is g > 0's
            raise ParameterError(f"{nm['g']} must be > 0 (the plastic modulus of eq. 152, "
                                 f"assumed strictly positive in §3.3), got {g!r}")
    lam = check_real(nm["lam"], lam)
    mu = check_real(nm["mu"], mu)
    if not RANGE_MIN <= mu <= RANGE_MAX:
        raise ParameterError(f"{nm['mu']} must be in [{RANGE_MIN:g}, {RANGE_MAX:g}], got {mu!r}")
    if not -RANGE_MAX <= lam <= RANGE_MAX:
        raise ParameterError(f"{nm['lam']} must be in [-1e+300, 1e+300], got {lam!r}")
    if 0.0 < abs(lam) < NORMAL_MIN:  # (an outside audit: lam = 1e-320 was taken, its digits lost)
        raise ParameterError(f"{nm['lam']} must be 0 or >= {NORMAL_MIN:.3g} in magnitude (a "
                             f"subnormal double has lost digits), got {lam!r}")
    lr = lam / mu  # finite: |lam| <= 1e300, mu >= 1e-300 gives at most 1e600 -> inf, refused
    if not (lr > -2.0 / 3.0 and lr <= LAM_OVER_MU_MAX):
        raise ParameterError(
            f"{nm['lam']} must satisfy -2/3 < lam/mu <= {LAM_OVER_MU_MAX:g} (positive definite "
            f"elasticity; beyond, the near-incompressible terms lose their digits), got "
            f"lam/mu = {shown_beside(lr, (-2.0 / 3.0, LAM_OVER_MU_MAX), '.6g')}")
    arrays = {}
    for key, value, size in (("P", P, 6), ("Q", Q, 6), ("n", n, 3)):
        # real numbers only (an audit: a complex entry raised a bare TypeError, a string or a
        # bool was read as a number)
        arrays[key] = check_finite_array(nm[key], value, (size,), f"{size} finite numbers")
        tiny = (arrays[key] != 0) & (np.abs(arrays[key]) < NORMAL_MIN)
        if tiny.any():  # (an outside audit: P = 1e-320 ... was read with its digits lost)
            raise ParameterError(f"{nm[key]}: each entry must be 0 or >= {NORMAL_MIN:.3g} in "
                                 f"magnitude (a subnormal double has lost digits), got "
                                 f"{float(arrays[key][tiny][0])!r}")
    nv = arrays["n"]
    n_max = float(np.abs(nv).max())
    if n_max == 0.0:
        raise ParameterError(f"{nm['n']} must be a non-zero vector (a propagation direction)")
    n_scaled = nv / n_max
    n_unit = n_scaled / float(np.linalg.norm(n_scaled))
    notes = []
    norm = _as_float(_mul(n_max, float(np.linalg.norm(n_scaled))))
    if abs(norm - 1.0) > 1e-9:
        notes.append(f"n normalised from |n| = {norm:.6g}")
    sP, sQ = (float(np.abs(arrays[k]).max()) for k in ("P", "Q"))
    Ph = voigt_to_tensor(arrays["P"] / sP) if sP > 0 else np.zeros((3, 3))
    Qh = voigt_to_tensor(arrays["Q"] / sQ) if sQ > 0 else np.zeros((3, 3))
    S = _as_float(_mul(mu, sP, sQ))  # 0 only when P or Q is 0 (no coupling): allowed
    if sP > 0 and sQ > 0 and not RANGE_MIN <= S <= RANGE_MAX:
        raise ParameterError(
            f"{nm['P']}, {nm['Q']}, {nm['mu']}: the moduli scale as mu max|P| max|Q| = "
            f"{_fmt(_mul(mu, sP, sQ))}, which must be 0 or in [{RANGE_MIN:g}, {RANGE_MAX:g}]")

    trP, trQ = float(np.trace(Ph)), float(np.trace(Qh))
    u, v = Ph @ n_unit, Qh @ n_unit
    pn, qn, uv = float(n_unit @ u), float(n_unit @ v), float(u @ v)
    p = lr * trP * n_unit + 2 * u  # eq. (180) over mu max|P|
    q = lr * trQ * n_unit + 2 * v
    p_n, q_n, pq = lr * trP + 2 * pn, lr * trQ + 2 * qn, float(p @ q)
    r, k = lr / (lr + 2), (lr + 1) / (lr + 2)
    gE = r * (lr * trP * trQ + 2 * trP * qn + 2 * trQ * pn) + 4 * (uv - k * pn * qn)
    # N - p.q = 4 (pn qn - u.v) with N = (n.p)(n.q), as -4 (n x u).(n x v) (Binet-Cauchy, |n| = 1):
    # for P = Q it is -4 |n x u|^2 <= 0 exactly, never the round-off of pn qn - u.v, which is
    # 0 when n is an eigenvector of P and made a spurious interval of width 3e-8 (an audit).
    cu, cv = np.cross(n_unit, u), np.cross(n_unit, v)
    D = -4 * float(cu @ cv)
    # Where N or D is within its round-off its sign is not the floats' to tell: a double root
    # of the discriminant touching 0 (no interval) or a genuine interval a few 1e-8 wide. There
    # they are computed exactly, in rationals of the inputs (models.solid.exact_flutter_factors;
    # the band: models.solid.AMBIGUOUS_RTOL, against |p|, |q|).
    band = AMBIGUOUS_RTOL
    pp, qq = float(np.linalg.norm(p)), float(np.linalg.norm(q))
    if sP > 0 and sQ > 0 and (abs(p_n) <= band * pp or abs(q_n) <= band * qq
                              or abs(D) <= band * pp * qq):
        mp, mq, D_exact = exact_flutter_factors(lam, mu, voigt_to_tensor(arrays["P"]),
                                                voigt_to_tensor(arrays["Q"]), nv)
        # in this function's units: n.p over mu max|P|, N - p.q over (mu max|P|)(mu max|Q|)
        p_n = float(mp / (Fraction(mu) * Fraction(sP)))
        q_n = float(mq / (Fraction(mu) * Fraction(sQ)))
        D = float(D_exact / (Fraction(mu) ** 2 * Fraction(sP) * Fraction(sQ)))
        sign_N, sign_D = (mp * mq > 0) - (mp * mq < 0), (D_exact > 0) - (D_exact < 0)
    else:
        sign_N, sign_D = (p_n * q_n > 0) - (p_n * q_n < 0), (D > 0) - (D < 0)

    def physical(x: float, what: str) -> float:
        value = _as_float(_mul(S, x))
        if not math.isfinite(value) or abs(value) > RANGE_MAX:
            raise ParameterError(
                f"{nm['P']}, {nm['Q']}, {nm['mu']}: {what} = {_fmt(_mul(S, x))} exceeds "
                f"{RANGE_MAX:g} in magnitude; mu max|P| max|Q| = {S:.3g} must be smaller here")
        return value

    g_loc = physical(gE, "g_localization")
    interval = None
    if sign_N > 0 and sign_D > 0 and D > 0:
        root_n = math.sqrt(abs(p_n)) * math.sqrt(abs(q_n))
        w = root_n + math.sqrt(D)
        g1 = (pq / w) ** 2 / (lr + 1)  # (sqrt N - sqrt(N - pq))^2 = (pq / (sqrt N + ...))^2
        g2 = w * w / (lr + 1)
        # g1 <= g2 exactly; rounding can swap them when N or N - p.q is tiny (width ~ eps)
        interval = tuple(sorted((physical(g1, "g1"), physical(g2, "g2"))))
    if g is None:
        return IsotropicAcoustic(g_loc, interval, notes=tuple(notes))

    # Eigenvalues over mu: 1 and the roots of eta^2 - b eta + c, with x = S/g,
    # b = lam' + 3 - x p.q and c = (lam' + 2)(1 - x g^_E) (= det A / mu^3).
    M = max(abs(pq), (lr + 2) * abs(gE))
    g_min = _as_float(_mul(max(mu, 1.0), S, M, divide=(RANGE_MAX,)))
    if not math.isfinite(g_min):
        raise ParameterError(
            f"{nm['P']}, {nm['Q']}, {nm['mu']}: no representable g keeps the eigenvalues (~ mu^2 "
            f"max|P| max|Q| / |g|) below {RANGE_MAX:g}; reduce mu, P or Q")
    if abs(g) < g_min:
        raise ParameterError(
            f"{nm['g']}: |g| must be >= {g_min:.3g} here (the eigenvalues, ~ mu^2 max|P| "
            f"max|Q| / |g|, must stay below {RANGE_MAX:g}), got {g!r}")
    x = _as_float(_mul(S, divide=(g,)))  # |x| M <= 1e300 / max(mu, 1); underflow to 0 is fine
    b = lr + 3 - x * pq
    c = (lr + 2) * (1 - x * gE)
    # b^2 - 4c = (lam' + 1 - x (2N - p.q))^2 - 4 x^2 N D = (lam' + 1)^2 (1 - x g1)(1 - x g2)
    # (scaled; N = p_n q_n, D = N - p.q): negative exactly between g1 and g2, >= 0 for every
    # g > 0 without an interval; computed so (a sum of squares when N D <= 0, as for P = Q), a
    # coalescence is no round-off pair 1 +- 1.5e-8 i (an audit) nor a split 1 +- 3e-8.
    if interval is None:
        def disc(m: float) -> float:
            # products in this order: (x/m)^2 alone overflows where x/m > 1e154 (mu = 1e154,
            # lam = 1: a fuzz case) while each factor times its small partner does not
            t = (lr + 1) / m - x / m * (2 * p_n * q_n - pq)
            return t * t - 4 * ((x / m) * p_n) * ((x / m) * q_n) * D
    else:
        def disc(m: float) -> float:
            return ((lr + 1) / m * (1 - x * g1)) * ((lr + 1) / m * (1 - x * g2))
    roots = _quadratic_roots(b, c, disc, real=interval is None)
    eta = (complex(mu), *(complex(z.real * mu, z.imag * mu) for z in roots))
    if not all(math.isfinite(z.real) and math.isfinite(z.imag) for z in eta):
        raise ParameterError(f"{nm['g']}: the eigenvalues leave the float range, |g| must be "
                             f"larger than {g!r}")
    if max(abs(z) for z in eta) > RANGE_MAX:  # the elastic part, ~ lam + 2 mu (an audit: 3e300)
        raise ParameterError(
            f"{nm['lam']}, {nm['mu']}: the eigenvalues (~ lam + 2 mu) must stay below "
            f"{RANGE_MAX:g} in magnitude, got {max(abs(z) for z in eta):.3g}")
    # the pair is complex exactly inside the interval (the factored discriminant): any
    # imaginary part is flutter, however narrow the interval (a threshold on |Im| called a
    # genuine pair 1 +- 9e-8 i stable; the review of this change). A real pair's smaller root
    # comes from the product c (its sign is that of g - g_loc, to rounding): any negative
    # root is divergence (a threshold of 1e-10 max|eta| called g up to 2 % below g_loc stable
    # at lam/mu = 1e8, and g_loc (1 - 1e-8) at lam/mu = 1; an outside audit)
    regime = classify_eigenvalues([1.0, *roots], rtol=0.0, imag_rtol=0.0)
    return IsotropicAcoustic(g_loc, interval, eta, regime, tuple(notes))


def _fmt(me: tuple[float, int]) -> str:
    """``m 2^e`` as a decimal string even beyond the float range."""
    m, e = me
    if m == 0:
        return "0"
    exp10 = math.log10(abs(m)) + e * math.log10(2.0)
    whole = math.floor(exp10)
    return f"{math.copysign(10 ** (exp10 - whole), m):.3g}e{whole:+d}"
