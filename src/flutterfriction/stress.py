"""Stress tests of numerical stability: each solver pushed where numerics break.

Every case states what was tried, what the right answer is (from an independent computation,
mostly 50-digit mpmath or exact rational arithmetic) and what the solver gave. The outcome is

- ``correct``: the answer agrees with the reference within the stated tolerance;
- ``refused``: the solver raised a clear :class:`ParameterError`/:class:`ConvergenceError`
  instead of answering (acceptable where no reliable answer exists);
- ``WRONG``: a silent wrong answer. The stress report must have none.

The cases run in seconds; ``tests/test_stress.py`` asserts that none is ``WRONG`` and the
workflow writes the report (``results/reports/stress.md``).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import asdict, dataclass
from typing import Any

import mpmath as mp
import numpy as np

from flutterfriction.errors import ConvergenceError, ParameterError
from flutterfriction.io import markdown_table
from flutterfriction.parameters import LIST_47

CORRECT, REFUSED, WRONG = "correct", "refused", "WRONG"
LIST47 = dict(LIST_47)  # list (47), defined once in flutterfriction.parameters


@dataclass
class StressResult:
    area: str
    case: str
    tried: str
    expected: str
    got: str
    outcome: str
    note: str = ""

    def as_dict(self) -> dict[str, str]:
        return asdict(self)


def _judge(area: str, case: str, tried: str, run: Callable[[], Any],
           expected: Callable[[], Any], agree: Callable[[Any, Any], bool],
           fmt: Callable[[Any], str] = str, note: str = "") -> StressResult:
    ref = expected()
    try:
        got = run()
    except (ParameterError, ConvergenceError) as exc:
        return StressResult(area, case, tried, fmt(ref), f"refused: {exc}", REFUSED, note)
    outcome = CORRECT if agree(got, ref) else WRONG
    return StressResult(area, case, tried, fmt(ref), fmt(got), outcome, note)


def _rel(a: float, b: float) -> float:
    return abs(float(a) - float(b)) / abs(float(b))


# ---------------------------------------------------------------------- pendulum, exact refs
def _mp_flutter_load(params: dict[str, float], dps: int = 50):
    """The 50-digit flutter load of the pendulum with these parameters [N]."""
    from flutterfriction.analysis.ziegler import flutter_load_multiprecision
    from flutterfriction.models.ziegler import ZieglerPendulum

    return flutter_load_multiprecision(ZieglerPendulum(**params), dps)


def exceptional_point_cases() -> list[StressResult]:
    """Loads within a relative ``delta`` of the flutter load (an exceptional point, where the
    eigenvalues are square-root sensitive): the regime from the eigenvalues against the sign of
    ``P - P_flu`` with P_flu in 50 digits."""
    from flutterfriction.analysis.ziegler import follower_critical_loads, regime
    from flutterfriction.models.ziegler import ZieglerPendulum

    p = ZieglerPendulum(**LIST47)
    P_mp = _mp_flutter_load(LIST47)
    out = [_judge("exceptional point", "flutter load of list (47)",
                  "coalescence load (Brent on the discriminant) vs 50-digit mpmath",
                  lambda: follower_critical_loads(p)[0], lambda: float(P_mp),
                  lambda g, r: _rel(g, r) < 1e-13, lambda x: f"{x:.15g} N")]
    for delta in (1e-4, 1e-8, 1e-12, 1e-14):
        for sign in (-1, 1):
            P = float(P_mp * (1 + sign * mp.mpf(delta)))
            truth = "flutter" if mp.mpf(P) > P_mp else "stable"
            out.append(_judge(
                "exceptional point", f"P = P_flu (1 {'+' if sign > 0 else '-'} {delta:g})",
                "regime from the eigenvalues of the first-order form",
                lambda P=P: str(regime(p, P)), lambda truth=truth: truth,
                lambda g, r: g == r,
                note="refusal expected where |P - P_flu| is below what double precision "
                     "resolves (the eigenvalues split like sqrt(delta))"))
    return out


def vanishing_viscosity_cases() -> list[StressResult]:
    """Hinge viscosity down to 1e-10 of the reference: exact Routh–Hurwitz against the closed
    form (eq. 54 generalised, exact in eps)."""
    from flutterfriction.analysis.ziegler import damped_flutter_load, regime
    from flutterfriction.closed_forms.ziegler_damped import damped_flutter_gamma_exact
    from flutterfriction.models.ziegler import ZieglerPendulum

    out = []
    for c in (1e-6, 1e-8, 1e-10):
        p = ZieglerPendulum(**LIST47, c1=c, c2=c)
        exact = damped_flutter_gamma_exact(p) * p.load_unit
        for method, tol in (("routh", 1e-12), ("eigenvalues", 1e-5)):
            out.append(_judge(
                "vanishing viscosity", f"c1 = c2 = {c:g} N m s, {method}",
                f"damped flutter load by {method}",
                lambda p=p, method=method: damped_flutter_load(p, method),
                lambda exact=exact: exact, lambda g, r, tol=tol: _rel(g, r) < tol,
                lambda x: f"{x:.13g} N",
                note="the eigenvalue crossing is expected to lose digits like 1e-16/eps"
                if method == "eigenvalues" else ""))
    # Soft first spring, heavy first mass, viscosity at the second hinge only (an outside
    # audit: in doubles k1/k2 + 1 lost the digits the flutter condition depends on, 34 % low).
    # With l1 = l2 = d = L, m3 = 0, c1 = 0 Hurwitz' Delta3 vanishes at
    # P = 2 k1 m2 / (L (m1 + 4 m2)) for any c2 (sympy, tests/test_damped.py).
    for m1, k1 in ((1e3, 2e-5), (1e5, 2e-7)):
        p = ZieglerPendulum(l1=0.1, l2=0.1, d=0.1, h=0.0, m1=m1, m2=0.1, m3=0.0, k1=k1,
                            k2=0.2, c1=0.0, c2=1e-4)
        out.append(_judge(
            "vanishing viscosity", f"k1/k2 = {k1 / 0.2:g}, m1/m2 = {m1 / 0.1:g}, c1 = 0, routh",
            "damped flutter load by routh (exact characteristic polynomial)",
            lambda p=p: damped_flutter_load(p, "routh"),
            lambda m1=m1, k1=k1: 2 * k1 * 0.1 / (0.1 * (m1 + 0.4)),
            lambda g, r: _rel(g, r) < 1e-13, lambda x: f"{x:.13g} N",
            note="reference: the closed form 2 k1 m2 / (L (m1 + 4 m2)) of this pendulum"))
    # The regime where the growth rate is far below the eigenvalues' resolution (an outside
    # audit: c = 1e-8 at P = 1.6 K/L, max Re s = 1.3e-9, was called stable).
    sym = ZieglerPendulum(l1=1.0, l2=1.0, d=1.0, h=0.0, m1=1.0, m2=1.0, m3=0.0, k1=1.0,
                          k2=1.0, c1=1e-8, c2=1e-8)
    for P in (1.3, 1.6, 5.0):
        out.append(_judge(
            "vanishing viscosity", f"symmetric pendulum, c = 1e-8, regime at P = {P:g} K/L",
            "regime(p, P) (exact Routh and Sturm root counts)",
            lambda P=P: str(regime(sym, P)), lambda P=P: _mp_regime(sym, P),
            lambda g, r: g == r, note="reference: the 60-digit roots of the characteristic "
            "polynomial (max Re s = -8.8e-11, 1.3e-9 and 1.9 at the three loads)"))
    return out


def _mp_regime(p: Any, P: float) -> str:
    """Stable / flutter / divergence from the 60-digit roots of ``det(M s^2 + C s + K + P G)``
    (the pendulum's SI matrices, each entry a double, taken exactly)."""
    with mp.workdps(60):
        M, C = mp.matrix(p.mass_matrix().tolist()), mp.matrix(p.viscosity_matrix().tolist())
        K = mp.matrix(p.stiffness_matrix().tolist()) + mp.mpf(P) * mp.matrix(
            p.follower_load_matrix().tolist())
        # the determinant's coefficients by interpolation at 5 points (60 digits)
        pts = [mp.mpf(k) for k in range(-2, 3)]
        vals = [mp.det(M * x**2 + C * x + K) for x in pts]
        coeffs = mp.lu_solve(mp.matrix([[x**j for j in range(4, -1, -1)] for x in pts]),
                             mp.matrix(vals))
        roots = mp.polyroots([coeffs[i] for i in range(5)], maxsteps=400, extraprec=400)
        unstable = [r for r in roots if mp.re(r) > 0]
        if not unstable:
            return "stable"
        return "divergence" if all(abs(mp.im(r)) < mp.mpf(10) ** -40 for r in unstable) \
            else "flutter"


def scale_cases() -> list[StressResult]:
    """The same device in millimetres and in kilometres (lengths x 1e-3 and 1e3, masses
    x 1e-6 and 1e6): the dimensionless flutter load ``P l2 / k2`` must not change."""
    from flutterfriction.analysis.ziegler import follower_critical_loads
    from flutterfriction.models.ziegler import ZieglerPendulum

    base = ZieglerPendulum(**LIST47)
    p_ref = follower_critical_loads(base)[0] * base.l2 / base.k2
    out = []
    for s_len, s_mass in ((1e-3, 1.0), (1e3, 1.0), (1.0, 1e-6), (1.0, 1e6), (1e-3, 1e-6)):
        q = dict(LIST47)
        for k in ("l1", "l2", "d", "h"):
            q[k] *= s_len
        for k in ("m1", "m2", "m3"):
            q[k] *= s_mass
        p = ZieglerPendulum(**q)
        out.append(_judge(
            "extreme scales", f"lengths x {s_len:g}, masses x {s_mass:g}",
            "dimensionless flutter load P l2/k2",
            lambda p=p: follower_critical_loads(p)[0] * p.l2 / p.k2, lambda: p_ref,
            lambda g, r: _rel(g, r) < 1e-12, lambda x: f"{x:.15g}"))
    return out


# ---------------------------------------------------------------------- rods
def _mp_eq118(p, w, ta, gam, eta):
    """Eq. (118) literally (lambda2^2 = minus the second root of eq. 112), in mpmath."""
    a = 1 + eta * w
    r = mp.sqrt(p**2 - 4 * a * (gam * w + w**2))
    L1 = (-p + r) / (2 * a)
    L2 = (p + r) / (2 * a)
    l1, l2 = mp.sqrt(L1), mp.sqrt(L2)
    return (a * (L1**2 + L2**2) + 2 * a * L1 * L2 * mp.cosh(l1) * mp.cos(l2)
            + a * L1 * L2 * (L2 - L1) * mp.sinh(l1) / l1 * mp.sin(l2) / l2
            - w**2 * ta * (L1 + L2) * (mp.sinh(l1) / l1 * mp.cos(l2)
                                       - mp.cosh(l1) * mp.sin(l2) / l2))


def rod_cases() -> list[StressResult]:
    """High modes and large loads, where eq. (118) overflows if evaluated as printed: the
    eigenvalues of the stable form, each polished as a root of the literal eq. (118) in
    40-digit mpmath."""
    from flutterfriction.analysis import rod as ar
    from flutterfriction.models.rod import RodGroups

    out = []
    for p, n_modes, g in ((10.0, 8, RodGroups()), (200.0, 4, RodGroups()),
                          (2000.0, 3, RodGroups(eta=1e-3)), (5.0, 6, RodGroups(tan_alpha=1.0))):
        def run(p=p, n_modes=n_modes, g=g):
            w = ar.eigenvalues(p, g, n_modes=n_modes)
            if not np.all(np.isfinite(w)):
                raise AssertionError("non-finite eigenvalue")  # a silent failure: judged WRONG
            return w

        def polish(w, p=p, g=g):
            with mp.workdps(40):
                return [complex(mp.findroot(lambda z: _mp_eq118(mp.mpf(p), z, g.tan_alpha,
                                                                g.gamma, g.eta),
                                            mp.mpc(x.real, x.imag))) for x in w]

        def agree(got, _ref, polish=polish):
            try:
                exact = polish(got)
            except (ZeroDivisionError, ValueError):
                return False
            return all(abs(a - b) <= 1e-9 * abs(b) for a, b in zip(got, exact, strict=True))

        out.append(_judge(
            "rod: high modes, large loads", f"p = {p:g}, {n_modes} modes, tan a = "
            f"{g.tan_alpha:g}, eta = {g.eta:g}",
            "eigenvalues of the stable eq. (118) vs roots of the literal eq. (118), 40 digits",
            run, lambda: "roots of eq. (118) in mpmath", agree,
            lambda x: x if isinstance(x, str) else f"{len(x)} finite roots, max |w| "
            f"{max(abs(v) for v in x):.4g}"))
    return out


#: The dense check's twin: 40 elements reduced (Galerkin) to their 24 lowest unloaded modes.
#: Its regime boundaries lie within 7.3e-5 (relative) of eq. (118)'s up to p = 400 at the 12
#: tip masses of :func:`rod_regime_cases` (measured; the unreduced 20-element mesh used before:
#: 1.2e-3, at 3x the cost), so the bands left out of the comparison are :data:`DENSE_BAND`.
DENSE_ELEMENTS, DENSE_MODES = 40, 24
#: Loads within ``rel * boundary + abs`` of a reported boundary are not compared: 5e-4 is the
#: dense twin's measured 7.3e-5 with a x7 margin; 0.02 (one fifth of the dense step) keeps a
#: boundary near p = 0 from comparing the grid point next to it.
DENSE_BAND = (5e-4, 0.02)


def _fe_regimes_dense(tan_alpha: float, p: np.ndarray, n_elements: int = DENSE_ELEMENTS,
                      n_modes: int = DENSE_MODES) -> list[str]:
    """Regime of the undamped FE twin at every load of ``p`` (no adaptivity, no exact solve):
    flutter where a pencil eigenvalue Omega^2 is complex, divergence where one is negative.
    The twin is Galerkin-reduced to its ``n_modes`` lowest unloaded modes (M-orthonormal); the
    regime scan of :func:`~flutterfriction.analysis.rod.critical_loads` it checks is not
    reduced and runs on other meshes (25 elements at p_max 400; its retry, 75)."""
    from flutterfriction.models.rod import RodGroups
    from flutterfriction.models.rod_fe import assemble

    fe = assemble(RodGroups(tan_alpha=tan_alpha), n_elements)
    L = np.linalg.cholesky(fe.M)
    Linv = np.linalg.solve(L, np.eye(L.shape[0]))
    A0, A1 = Linv @ fe.K_B @ Linv.T, Linv @ fe.load_matrix() @ Linv.T
    V = np.linalg.eigh(0.5 * (A0 + A0.T))[1][:, :n_modes]
    A0, A1 = V.T @ A0 @ V, V.T @ A1 @ V
    out = []
    for chunk in np.array_split(p, max(1, p.size // 500)):
        mu = np.linalg.eigvals(A0[None] + chunk[:, None, None] * A1[None])
        cx = np.abs(mu.imag) > 1e-6 * np.abs(mu)
        neg = ~cx & (mu.real < 0)
        out += ["flutter" if c else "divergence" if n else "stable"
                for c, n in zip(cx.any(-1), neg.any(-1), strict=True)]
    return out


def rod_regime_cases(p_max: float = 400.0, n_alpha: int = 12) -> list[StressResult]:
    """The Pflüger column's regime along the load axis, tan(alpha) in [0, 10] (a log-spaced
    set plus 0.59, 0.595, 0.6, where a 2.3-wide divergence window opens near p = 48), p up to
    400: every interval of :func:`critical_loads` against a dense, non-adaptive scan of the
    FE twin on another mesh (:func:`_fe_regimes_dense`, step 0.1 = the scan step / 2.5). Loads
    within :data:`DENSE_BAND` of a reported boundary (0.05 % + 0.02) are not compared.
    Also four damped rods against the full first-order FE spectrum
    (:func:`_damped_regime_disagreements`). The first disagreement is reported; also the first
    divergence load at tan(alpha) = 0.595 for p_max 50 ... 400 (47.7155, whatever p_max)."""
    from flutterfriction.analysis import rod as ar
    from flutterfriction.models.rod import RodGroups

    alphas = sorted({0.0, 0.59, 0.595, 0.6, *np.geomspace(0.01, 10.0, n_alpha - 4).tolist()})
    dense = np.arange(0.0, p_max, 0.1)[1:]
    bad: list[str] = []
    n_intervals = 0
    solved = {}
    for ta in alphas:
        try:
            c = solved[ta] = ar.critical_loads(RodGroups(tan_alpha=ta), p_max=p_max)
        except (ParameterError, ConvergenceError) as exc:
            bad.append(f"tan a = {ta:.4g}: refused ({exc})")
            continue
        n_intervals += len(c.intervals)
        edges = np.array([iv["p_from"] for iv in c.intervals[1:]])
        claimed = np.empty(dense.size, dtype=object)
        for iv in c.intervals:
            claimed[(dense >= iv["p_from"]) & (dense <= iv["p_to"])] = iv["regime"]
        fe = np.array(_fe_regimes_dense(ta, dense), dtype=object)
        near = np.zeros(dense.size, dtype=bool)
        for e in edges:
            near |= np.abs(dense - e) <= DENSE_BAND[0] * e + DENSE_BAND[1]
        wrong = (claimed != fe) & ~near
        if np.any(wrong):
            i = int(np.argmax(wrong))
            bad.append(f"tan a = {ta:.4g}: p = {dense[i]:.2f} is {claimed[i]}, the dense "
                       f"scan says {fe[i]}")
    bad += _damped_regime_disagreements()
    # (the scan above already solved p_max: not twice)
    firsts = {pm: (solved[0.595] if pm == p_max and 0.595 in solved else
                   ar.critical_loads(RodGroups(tan_alpha=0.595), p_max=pm)).p_div
              for pm in (50.0, 80.0, 200.0, 400.0)}
    out = [StressResult(
        "rod: regimes along p", f"{len(alphas)} tip masses tan a in [0, 10], p <= {p_max:g}; "
        "4 damped rods, p <= 200",
        "every stable/flutter/divergence interval (FE-bracketed, eq. 118 Newton) vs a dense "
        f"non-adaptive FE scan ({DENSE_ELEMENTS} elements reduced to {DENSE_MODES} modes, "
        "dp = 0.1)",
        f"the same regime at every load outside the boundaries' {100 * DENSE_BAND[0]:g} % + "
        f"{DENSE_BAND[1]:g} bands (4 damped rods: 0.5 % + 0.02)",
        f"{n_intervals} intervals; " + ("all agree" if not bad else "; ".join(bad[:3])),
        CORRECT if not bad else (REFUSED if all(": refused (" in b for b in bad) else WRONG))]
    out.append(_judge(
        "rod: regimes along p", "tan a = 0.595, first divergence load for p_max 50/80/200/400",
        "critical_loads(p_max).p_div (the 2.3-wide window at 47.7-50.0 must not be skipped)",
        lambda: firsts, lambda: 47.71549336756,
        lambda g, r: all(v is not None and abs(v - r) < 1e-9 * r for v in g.values()),
        lambda x: x if isinstance(x, str | float) else ", ".join(
            f"{k:g}: {v:.10g}" for k, v in x.items()) if isinstance(x, dict) else f"{x:.10g}",
        note="reference: the undamped double root of eq. (118) (Newton, 1e-13), "
             "tests/test_rod.py checks it against 30-digit mpmath"))
    return out


def _damped_regime_disagreements(p_max: float = 200.0) -> list[str]:
    """Damped rods (flutter: a pair crossing the imaginary axis; divergence: the unstable pair
    merging on the real axis): the intervals against the full first-order FE spectrum (20
    elements, no modal reduction) on a grid of step 0.2, with bands of 0.5 % + 0.02 (the
    unreduced 20-element twin's error; the undamped check's are :data:`DENSE_BAND`)."""
    from flutterfriction.analysis import rod as ar
    from flutterfriction.models.rod import RodGroups
    from flutterfriction.models.rod_fe import assemble

    out = []
    for kw in (dict(tan_alpha=0.595, eta=1e-3), dict(tan_alpha=1.0, eta=1e-2, gamma=0.1),
               dict(tan_alpha=10.0, eta=1e-3), dict(tan_alpha=0.3, gamma=1.0)):
        g = RodGroups(**kw)
        try:
            c = ar.critical_loads(g, p_max=p_max)
        except (ParameterError, ConvergenceError) as exc:
            out.append(f"{kw}: refused ({exc})")
            continue
        fe = assemble(g, 20)
        n = fe.M.shape[0]
        # the first-order form in the coordinates L^T q (M = L L^T): the same spectrum as
        # with M^-1 K, M^-1 C (to 4e-15 relative, measured), and 30 % cheaper to solve
        Linv = np.linalg.inv(np.linalg.cholesky(fe.M))
        K_B, Q, C = (Linv @ X @ Linv.T for X in (fe.K_B, fe.load_matrix(), fe.C))
        p = np.arange(0.2, p_max, 0.2)
        A = np.zeros((p.size, 2 * n, 2 * n))
        A[:, :n, n:] = np.eye(n)
        A[:, n:, :n] = -K_B[None] - p[:, None, None] * Q[None]
        A[:, n:, n:] = -C
        s = np.linalg.eigvals(A)
        unstable = s.real > 0
        cx = np.abs(s.imag) > 1e-6 * np.abs(s)
        dense = np.where((unstable & cx).any(-1), "flutter",
                         np.where(unstable.any(-1), "divergence", "stable"))
        claimed = np.empty(p.size, dtype=object)
        near = np.zeros(p.size, dtype=bool)
        for iv in c.intervals:
            claimed[(p >= iv["p_from"]) & (p <= iv["p_to"])] = iv["regime"]
            if iv["p_from"] > 0:
                near |= np.abs(p - iv["p_from"]) <= 0.005 * iv["p_from"] + 0.02
        wrong = (claimed != dense) & ~near
        if np.any(wrong):
            i = int(np.argmax(wrong))
            out.append(f"{kw}: p = {p[i]:.1f} is {claimed[i]}, the dense scan says {dense[i]}")
    return out


def _fe_vanishing_damping_limit(tan_alpha: float, n_elements: int = 48) -> float:
    """The damped flutter load's eta -> 0 limit on the FE twin, by first-order perturbation of
    the undamped modes: with left/right eigenvectors u, z of the reduced pencil, a real mode's
    growth rate is ``-eta (u^T C1 z)/(2 u^T z)`` (C1 = the Kelvin-Voigt matrix per unit eta);
    the limit is the first load where one becomes positive (Brent on the largest)."""
    import scipy.linalg as sla
    from scipy.optimize import brentq

    from flutterfriction.models.rod import RodGroups
    from flutterfriction.models.rod_fe import assemble

    fe = assemble(RodGroups(tan_alpha=tan_alpha, eta=1.0), n_elements)
    L = np.linalg.cholesky(fe.M)
    Linv = np.linalg.solve(L, np.eye(L.shape[0]))
    A0, A1, C1 = (Linv @ X @ Linv.T for X in (fe.K_B, fe.load_matrix(), fe.C))

    def growth(p: float) -> float:
        mu, U, Z = sla.eig(A0 + p * A1, left=True, right=True)
        low = np.argsort(np.abs(mu))[:6]
        rates = [-(U[:, k].conj() @ C1 @ Z[:, k]).real / (2 * (U[:, k].conj() @ Z[:, k]).real)
                 for k in low if abs(mu[k].imag) <= 1e-9 * abs(mu[k])]
        return float(max(rates))

    grid = np.arange(0.1, 40.0, 0.1)
    # up to the first positive growth rate only (the grid beyond it cannot change the result)
    i = next(k for k, p in enumerate(grid) if growth(p) > 0)
    return float(brentq(growth, grid[i - 1], grid[i], xtol=1e-14))


def _vanishing_damping_limit(tan_alpha: float) -> float:
    """:func:`_fe_vanishing_damping_limit` on 32 and 48 elements, Richardson-extrapolated with
    the cubic elements' h^4 rate (tests/test_rod.py::test_fe_converges_at_fourth_order)."""
    p32, p48 = (_fe_vanishing_damping_limit(tan_alpha, n) for n in (32, 48))
    return p48 + (p48 - p32) / ((48 / 32) ** 4 - 1)


def rod_vanishing_viscosity_cases() -> list[StressResult]:
    """Kelvin-Voigt viscosity eta from 1e-6 down to 1e-30 (the chapter's paradox, §2.7: the
    damped flutter load tends to a limit below the undamped one, 10.94 for Beck instead of
    20.05): the exact flutter load against the limit on the FE twin from first-order
    perturbation theory (32 and 48 elements, Richardson-extrapolated). Tolerance 1e-8
    relative: the unextrapolated 48-element limit is within 1.4e-8 (tan a = 1, 100) and 2e-9
    (Beck) of the exact one and the h^4 extrapolation gains >= 10x; the distance of the
    eta = 1e-6 load to the limit is O(eta) (< 2e-10 relative, measured)."""
    from flutterfriction.analysis import rod as ar
    from flutterfriction.models.rod import RodGroups

    out = []
    for ta in (0.0, 1.0, 100.0):
        limit = _vanishing_damping_limit(ta)
        for eta in (1e-6, 1e-10, 1e-14, 1e-20, 1e-30):
            out.append(_judge(
                "rod: vanishing viscosity", f"tan a = {ta:g}, eta = {eta:g}",
                "exact damped flutter load (eq. 118, Newton on Re f and Im f / eta)",
                lambda ta=ta, eta=eta: ar.critical_loads(RodGroups(tan_alpha=ta, eta=eta)).p_flu,
                lambda limit=limit: limit, lambda g, r: g is not None and _rel(g, r) < 1e-8,
                lambda x: "none" if x is None else f"{x:.12g}",
                note="eta -> 0 limit from FE perturbation theory"))
    return out


def acoustic_cases() -> list[StressResult]:
    """Flutter of the acoustic tensor far below the elastic scale: with P, Q scaled by s the
    flutter interval of g scales by s^2. The discriminant route (a quartic in 1/g) against the
    corrected closed form eq. (188)."""
    from flutterfriction.analysis.acoustic import flutter_interval_bruteforce
    from flutterfriction.models import solid as so

    lam, mu = 1.0, 1.0
    P = np.array([[-0.6, -0.1, 0.1], [-0.1, 0.8, -0.5], [0.1, -0.5, 0.3]])
    Q = np.array([[0.4, 0.1, 0.2], [0.1, 0.3, 0.0], [0.2, 0.0, 0.0]])
    n = np.array([0.6, 0.8, 0.0])
    E = so.isotropic_elasticity(lam, mu)
    out = []
    for s in (1.0, 1e-3, 1e-6):
        closed = so.flutter_interval_isotropic(lam, mu, s * P, s * Q, n)

        def run(s=s, closed=closed):
            return flutter_interval_bruteforce(E, s * P, s * Q, n, g_max=10 * closed[1],
                                               decades=16)

        out.append(_judge(
            "acoustic tensor",
            # its own test tensors, not §3.5's case (a reader took its interval for the figure's)
            f"a test P, Q (not §3.5's), n = (0.6, 0.8, 0), scaled x {s:g} (g interval x "
            f"{s * s:g})",
            "flutter interval from the discriminant, a quartic in 1/g",
            run, lambda closed=closed: [closed],
            lambda g, r: len(g) == 1 and all(_rel(a, b) < 1e-9 for a, b in zip(g[0], r[0],
                                                                               strict=True)),
            lambda x: "; ".join(f"[{a:.10g}, {b:.10g}]" for a, b in x)))
    return out


def long_integration_cases() -> list[StressResult]:
    """The §2.9 pendulum on its limit cycle for 200 more periods: the cycle must stay put
    (drift of amplitude and period below 1e-7), i.e. no secular accumulation of error."""
    from flutterfriction.analysis import dynamics as dy
    from flutterfriction.closed_forms.ziegler_damped import eq54_flutter_gamma, viscosity_groups
    from flutterfriction.models.ziegler import ZieglerPendulum

    p = ZieglerPendulum(l1=0.1, l2=0.1, d=0.1, h=0.0, m1=0.2, m2=0.2, m3=0.0, k1=0.189,
                        k2=0.189, c1=0.006, c2=0.006)
    eps, _ = viscosity_groups(p)
    P = 1.5 * eq54_flutter_gamma(eps) * p.load_unit
    lc = dy.limit_cycle(p, P, [0.1, 0.1, 0.0, 0.0], tol=1e-9)

    def run():
        x = np.array(lc.section_state)
        sol = dy.simulate(p, P, x, 200 * lc.period_s)
        later = dy.limit_cycle(p, P, sol.y[:, -1], tol=1e-9)
        return later.alpha1_amplitude_rad, later.period_s

    below = _judge("long integration", "limit cycle asked for at 0.9 P_flu (none exists)",
                   "Poincaré-section search for 100 s",
                   lambda: dy.limit_cycle(p, 0.9 * P / 1.5, [0.1, 0.1, 0.0, 0.0], t_max=100.0),
                   lambda: "no cycle: refusal", lambda g, r: False,
                   lambda x: x if isinstance(x, str) else f"a cycle of amplitude "
                   f"{x.alpha1_amplitude_rad:.3g} rad")
    return [below, _judge("long integration", "200 periods on the §2.9 cycle (DOP853, rtol 1e-11)",
                   "amplitude and period after 200 periods vs at the start",
                   run, lambda: (lc.alpha1_amplitude_rad, lc.period_s),
                   lambda g, r: _rel(g[0], r[0]) < 1e-7 and _rel(g[1], r[1]) < 1e-7,
                   lambda x: f"alpha1 {x[0]:.10f} rad, T {x[1]:.10f} s")]


def random_pendulum_cases(n: int = 40, seed: int = 20261122) -> list[StressResult]:
    """Random devices (masses, lengths, stiffnesses over four decades each): the numerical
    flutter load against 50-digit mpmath; the worst case is reported."""
    from flutterfriction.analysis.ziegler import follower_critical_loads
    from flutterfriction.models.ziegler import ZieglerPendulum

    rng = np.random.default_rng(seed)
    worst, worst_case, refused = 0.0, "", 0
    for _ in range(n):
        l1, l2 = 10 ** rng.uniform(-2, 2, 2)
        q = {"l1": l1, "l2": l2, "d": l1 * rng.uniform(0.05, 1.0),
             "h": l2 * rng.uniform(0.0, 1.0), "m1": 10 ** rng.uniform(-2, 2),
             "m2": 10 ** rng.uniform(-2, 2), "m3": 10 ** rng.uniform(-2, 2),
             "k1": 10 ** rng.uniform(-2, 2), "k2": 10 ** rng.uniform(-2, 2)}
        try:
            got = follower_critical_loads(ZieglerPendulum(**q))[0]
        except (ParameterError, ConvergenceError):
            refused += 1
            continue
        err = _rel(got, float(_mp_flutter_load(q)))
        if err > worst:
            worst, worst_case = err, ", ".join(f"{k}={v:.3g}" for k, v in q.items())
    outcome = CORRECT if worst < 1e-10 else WRONG
    return [StressResult("random parameters", f"{n} random pendulums (seed {seed})",
                         "numerical flutter load vs 50-digit mpmath from the matrices",
                         "relative error < 1e-10", f"worst {worst:.2g} ({worst_case}); "
                         f"{refused} refused", outcome)]


def bad_input_cases() -> list[StressResult]:
    """Inputs with no meaning must be refused with a message naming the parameter."""
    from flutterfriction.analysis.acoustic import flutter_interval_bruteforce
    from flutterfriction.models.rod import Rod
    from flutterfriction.models.ziegler import ZieglerPendulum

    def pendulum(**over):
        return lambda: ZieglerPendulum(**{**LIST47, **over})

    tries = [("pendulum m1 = NaN", pendulum(m1=math.nan), "m1"),
             ("pendulum k2 = -1", pendulum(k2=-1.0), "k2"),
             ("pendulum d > l1", pendulum(d=0.2), "d"),
             ("rod length = 0", lambda: Rod(length=0.0, B=1.0, rho=1.0), "length"),
             ("rod B = inf", lambda: Rod(length=1.0, B=math.inf, rho=1.0), "B"),
             ("acoustic scan with g_max = NaN",
              lambda: flutter_interval_bruteforce(np.eye(9).reshape(3, 3, 3, 3),
                                                  np.eye(3), np.eye(3), [1.0, 0, 0], math.nan),
              "g_max")]
    out = []
    for case, make, name in tries:
        try:
            make()
        except ParameterError as exc:
            ok = name in str(exc)
            out.append(StressResult("bad input", case, "construct / call", f"refusal naming "
                                    f"{name!r}", f"refused: {exc}", REFUSED if ok else WRONG))
            continue
        out.append(StressResult("bad input", case, "construct / call",
                                f"refusal naming {name!r}", "accepted", WRONG))
    return out


def paradox_limit_cases() -> list[StressResult]:
    """The Ziegler paradox as the viscosity vanishes (issue 12): the eq. (54) pendulum (l1 = l2,
    k1 = k2, m1 = m2, d = l1, m3 = 0, c1 = c2) with relative viscosity eps = c/(L sqrt(K m))
    down to 1e-30. The damped flutter load must tend to 4/3 K/L (eq. 54: 4/3 + eps^2/2), the
    damped divergence load to the undamped 4 K/L (eq. 48 with its divergence twin; measured
    slope 4 eps: 4.0004 at eps = 1e-4, 4.00000004 at 1e-8), never "unstable at zero load"."""
    from flutterfriction.analysis.ziegler import damped_divergence_load, damped_flutter_load
    from flutterfriction.closed_forms.ziegler import two_mass_gammas
    from flutterfriction.closed_forms.ziegler_damped import eq54_flutter_gamma
    from flutterfriction.models.ziegler import ZieglerPendulum

    base = {"l1": 1.0, "l2": 1.0, "d": 1.0, "h": 0.0, "m1": 1.0, "m2": 1.0, "m3": 0.0,
            "k1": 1.0, "k2": 1.0}
    p_div0 = two_mass_gammas(1.0, 1.0, 1.0, 1.0)[1]
    out = []
    for eps in (1e-10, 1e-20, 1e-30):
        p = ZieglerPendulum(**base, c1=eps, c2=eps)
        # Routh's verdict is exact for the float coefficients; their rounding (a few eps in
        # p2 = 6 + eps^2 - 2 gamma) moves the load by a few ulps: 1e-14 leaves a margin.
        out.append(_judge("vanishing viscosity", f"eq. (54) pendulum, eps = {eps:g}, flutter",
                          "damped flutter load (exact Routh-Hurwitz) vs eq. (54)",
                          lambda p=p: damped_flutter_load(p, "routh"),
                          lambda eps=eps: eq54_flutter_gamma(eps),
                          lambda g, r: _rel(g, r) < 1e-14, lambda x: f"{x:.16g} K/L"))
        out.append(_judge("vanishing viscosity", f"eq. (54) pendulum, eps = {eps:g}, divergence",
                          "damped divergence load (exact algebraic, scan from Routh's P_flu) vs "
                          "the undamped 4 K/L",
                          lambda p=p: damped_divergence_load(p),
                          lambda: p_div0,
                          lambda g, r, eps=eps: abs(g - r) <= 1e-14 * r + 5 * eps,
                          lambda x: f"{x:.16g} K/L",
                          note="tolerance 5 eps: the load's measured slope in eps is 4"))
        out.append(_judge("vanishing viscosity", f"eq. (54) pendulum, eps = {eps:g}, eigenvalues",
                          "damped flutter load from the eigenvalue crossing",
                          lambda p=p: damped_flutter_load(p, "eigenvalues"),
                          lambda eps=eps: eq54_flutter_gamma(eps),
                          lambda g, r: _rel(g, r) < 1e-4, lambda x: f"{x:.16g} K/L",
                          note="refusal expected: Re s ~ eps is below the eigenvalues' "
                               "round-off (1e-16 of |s|)"))
    return out


def ziegler_extreme_input_cases() -> list[StressResult]:
    """Issue 12: parameters far outside the pendulum's numerical range must be refused quickly
    with a message naming them (they used to hang or raise OverflowError/LinAlgError), and a
    device scaled as a whole (every parameter x 1e150) must give the base loads (the
    dimensionless groups do not change)."""
    from flutterfriction.analysis.ziegler import critical_loads
    from flutterfriction.models.ziegler import ZieglerPendulum

    base = dict(LIST47)
    tries = [("m1 = 1e300", {"m1": 1e300}, "m1"), ("k1 = 1e300", {"k1": 1e300}, "k1"),
             ("k1 = 1e-300", {"k1": 1e-300}, "k1"), ("k2 = 1e-300", {"k2": 1e-300}, "k2"),
             ("m3 = 1e300", {"m3": 1e300}, "m3"), ("l1 = 1e300", {"l1": 1e300}, "l1"),
             ("l2 = 1e-300 (h = 1e-300)", {"l2": 1e-300, "h": 1e-300}, "l2"),
             ("m1/m2 = 2e13", {"m1": 0.046 * 2e13}, "m1"),
             ("k1/k2 = 5e-16", {"k1": 0.189 * 5e-16}, "k1"),
             ("c1 = 1e-200 N m s", {"c1": 1e-200}, "c1"),
             ("m1 d^2 -> 0 with m3 = 0", {"m3": 0.0, "d": 1e-12}, "d")]
    out = []
    for case, over, name in tries:
        def run(over=over):
            return critical_loads(ZieglerPendulum(**{**base, **over}))

        r = _judge("extreme input", case, "critical_loads", run,
                   lambda name=name: f"refusal naming {name!r}", lambda g, r: False,
                   lambda x: x if isinstance(x, str) else "loads returned")
        if r.outcome == REFUSED and name not in r.got:
            r.outcome = WRONG
        out.append(r)
    ref = critical_loads(ZieglerPendulum(**base))
    big = ZieglerPendulum(**{k: v * 1e150 for k, v in base.items()})
    out.append(_judge("extreme input", "every parameter x 1e150",
                      "critical loads vs the base device (same groups, same load unit)",
                      lambda: critical_loads(big), lambda: ref,
                      lambda g, r: all(_rel(getattr(g, k), getattr(r, k)) < 1e-13
                                       for k in ("P_flu", "P_div", "H_cr", "H_sup")),
                      lambda x: f"P_flu {x.P_flu:.15g} N, H_cr {x.H_cr:.15g} N",
                      note="1e-13: the two runs round the groups differently (measured 0 to "
                           "a few ulps)"))
    return out


def _mp_double_root(tan_alpha: float, p0: complex, mu0: complex) -> tuple[complex, complex]:
    """The double root ``f = df/dmu = 0`` of the undamped eq. (118) (``mu = omega~^2``)
    nearest ``(p0, mu0)`` at 40 digits, complex in general: mpmath's Newton in two complex
    variables. Where no window is open the nearest double roots are a complex-conjugate pair
    of loads; a window opens where they meet on the real axis."""
    with mp.workdps(40):
        def G(p, mu):
            return _mp_eq118(p, mp.sqrt(mu), mp.mpf(tan_alpha), 0, 0)

        sol = mp.findroot(lambda p, mu: [G(p, mu), mp.diff(lambda m: G(p, m), mu)],
                          (mp.mpc(p0), mp.mpc(mu0)), tol=1e-30)
        return complex(sol[0]), complex(sol[1])


def rod_window_cases() -> list[StressResult]:
    """Regime windows at their opening or closing along tan(alpha) (the undamped Pflüger
    column), where a window's two ends merge and the two-variable Newton on eq. (118) is
    singular: the window's ends (or its absence) against eq. (118)'s double roots at 40
    digits, started off the real axis so that they may land on it or not."""
    from flutterfriction.analysis import rod as ar
    from flutterfriction.models.rod import RodGroups

    out = []
    for ta, p_max, lo, hi, starts, what in (
            (0.59325019, 60.0, 48.6, 49.1, [(48.8518, 170.26)],
             "2e-8 before the first divergence window opens"),
            (0.5932502125, 60.0, 48.6, 49.1, [(48.8513, 170.256), (48.8522, 170.264)],
             "3e-10 after it opens (0.0009 wide)"),
            (0.9823492, 80.0, 69.3, 70.0, [(69.6632, 552.36), (69.6740, 552.65)],
             "a flutter window 0.011 wide, about to close"),
            (0.2265, 300.0, 273.0, 273.5, [(273.195, 5534.0), (273.327, 14908.0)],
             "a divergence window between two pairs, missed by the FE twin")):
        def run(ta=ta, p_max=p_max, lo=lo, hi=hi):
            c = ar.critical_loads(RodGroups(tan_alpha=ta), p_max=p_max)
            return [iv["p_from"] for iv in c.intervals if lo < iv["p_from"] < hi]

        def ref(ta=ta, starts=starts):
            return [_mp_double_root(ta, complex(p, 1e-3), complex(mu, 1e-3))[0]
                    for p, mu in starts]

        def agree(got, exact):
            real = [p.real for p in exact if abs(p.imag) <= 1e-20 * abs(p)]
            if len(real) != len(exact):  # no window: no boundary reported there
                return not got and len(real) == 0
            return len(got) == len(real) and all(abs(a - b) <= 1e-10 * b
                                                 for a, b in zip(got, real, strict=True))

        out.append(_judge(
            "rod: window at its opening", f"tan a = {ta:.10g}, p_max {p_max:g}: {what}",
            "boundaries of critical_loads near the window vs eq. (118)'s double roots "
            "(40 digits; a complex load: no window)", run, ref, agree,
            lambda x: ", ".join(f"{complex(v).real:.10g}" + (
                f" {complex(v).imag:+.2g}i" if abs(complex(v).imag) > 1e-20 * abs(v) else "")
                for v in x) or "no boundary"))
    return out


ALL_CASES: dict[str, Callable[[], list[StressResult]]] = {
    "exceptional point": exceptional_point_cases,
    "vanishing viscosity": vanishing_viscosity_cases,
    "extreme scales": scale_cases,
    "rod": rod_cases,
    "rod: regimes along p": rod_regime_cases,
    "rod: window at its opening": rod_window_cases,
    "rod: vanishing viscosity": rod_vanishing_viscosity_cases,
    "acoustic tensor": acoustic_cases,
    "long integration": long_integration_cases,
    "random parameters": random_pendulum_cases,
    "bad input": bad_input_cases,
    "vanishing viscosity (paradox limit)": paradox_limit_cases,
    "extreme pendulum input": ziegler_extreme_input_cases,
}


#: The areas that take tens of seconds (the rod's regime scan over p and tan(alpha): 23 of
#: the stress job's 29 CPU-s, and its vanishing viscosity: 4; measured 2026-12-06): the
#: workflow runs them with ``stress: full`` in its config, the slow tests always; the quick
#: preset, the default paper run (``stress: standard``) and the fast tests leave them out.
SLOW_AREAS = ("rod: regimes along p", "rod: vanishing viscosity")
#: What the quick preset (a 30-second smoke run) leaves out: the slow areas and the long
#: integration (200 periods on the pendulum's cycle, and its refused search for a cycle below
#: the flutter load: 1.3 of quick's 2.1 CPU-s of stress tests; measured) and the rod's windows
#: at their opening (40-digit double roots, ~1 CPU-s).
QUICK_SKIPPED_AREAS = (*SLOW_AREAS, "long integration", "rod: window at its opening")
#: The workflow's ``stress`` setting: ``standard`` leaves out :data:`SLOW_AREAS` (the paper
#: run) or :data:`QUICK_SKIPPED_AREAS` (the quick preset); ``full`` runs every area.
STRESS_LEVELS = ("standard", "full")


def skipped_areas(fidelity: str, level: str | None = None) -> tuple[str, ...]:
    """The areas the workflow's stress job leaves out at ``fidelity`` ("quick" or "paper")
    and stress ``level`` (:data:`STRESS_LEVELS`; ``None``, the setting not given: the first,
    "standard")."""
    level = STRESS_LEVELS[0] if level is None else level
    if level not in STRESS_LEVELS:
        raise ParameterError(f"stress must be one of {list(STRESS_LEVELS)}, got {level!r}")
    if level == "full":
        return ()
    return QUICK_SKIPPED_AREAS if fidelity == "quick" else SLOW_AREAS


def run_all(skip: tuple[str, ...] = ()) -> list[StressResult]:
    """Every case of every area except those in ``skip``."""
    unknown = sorted(set(skip) - set(ALL_CASES))
    if unknown:
        raise ParameterError(f"unknown stress areas {unknown}; areas: {sorted(ALL_CASES)}")
    return [r for area, make in ALL_CASES.items() if area not in skip for r in make()]


def stress_markdown(results: list[StressResult], skipped: tuple[str, ...] = ()) -> str:
    n_wrong = sum(r.outcome == WRONG for r in results)
    lines = ["# Stress tests of numerical stability", "",
             f"{len(results)} cases: {sum(r.outcome == CORRECT for r in results)} correct, "
             f"{sum(r.outcome == REFUSED for r in results)} refused clearly, "
             f"**{n_wrong} silent wrong answers**.", ""]
    if skipped:
        lines += [f"Not run here: {', '.join(skipped)} (`--config stress=full` runs every area; "
                  "tests/test_stress.py runs each, the slow ones under `-m slow`).", ""]
    lines += markdown_table(["area", "case", "tried", "expected", "got", "outcome"],
                            [[r.area, r.case, r.tried, r.expected, r.got, r.outcome]
                             for r in results])
    return "\n".join(lines) + "\n"
