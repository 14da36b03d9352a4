"""Eq. (10) and (11) derived from scratch with sympy (Lagrange's equations), independently of
the chapter's printed equations; this is the evidence for the errata of eqs. (1) and (11)."""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp

from flutterfriction import ZieglerPendulum

t = sp.symbols("t")
m1, m2, m3, d, h, l1, l2, k1, k2, c1, c2, P, H = sp.symbols(
    "m1 m2 m3 d h l1 l2 k1 k2 c1 c2 P H", positive=True)
a1, a2 = sp.Function("a1")(t), sp.Function("a2")(t)


def lagrange_equations(printed_eq1: bool = False) -> list[sp.Expr]:
    """Residuals of d/dt dL/dq' - dL/dq + dR/dq' - Q = 0 for q = alpha1, alpha2."""
    D = sp.Matrix([d * sp.cos(a1), d * sp.sin(a2 if printed_eq1 else a1)])
    E = sp.Matrix([l1 * sp.cos(a1) + h * sp.cos(a2), l1 * sp.sin(a1) + h * sp.sin(a2)])
    C = sp.Matrix([l1 * sp.cos(a1) + l2 * sp.cos(a2), l1 * sp.sin(a1) + l2 * sp.sin(a2)])
    T = sum(m * X.diff(t).dot(X.diff(t)) for m, X in ((m1, D), (m2, C), (m3, E))) / 2
    V = k1 * a1**2 / 2 + k2 * (a2 - a1) ** 2 / 2
    R = c1 * a1.diff(t) ** 2 / 2 + c2 * (a2.diff(t) - a1.diff(t)) ** 2 / 2  # Rayleigh, eq. (26)
    F = -P * sp.Matrix([sp.cos(a2), sp.sin(a2)]) - H * sp.Matrix([1, 0])  # eq. (2)
    L = T - V
    return [sp.diff(L.diff(q.diff(t)), t) - L.diff(q) + R.diff(q.diff(t)) - F.dot(C.diff(q))
            for q in (a1, a2)]


@pytest.fixture(scope="module")
def equations():
    return lagrange_equations()


def _values(p: ZieglerPendulum, Pv: float, Hv: float) -> dict:
    return {m1: p.m1, m2: p.m2, m3: p.m3, d: p.d, h: p.h, l1: p.l1, l2: p.l2, k1: p.k1,
            k2: p.k2, c1: p.c1, c2: p.c2, P: Pv, H: Hv}


def test_nonlinear_equations_of_motion_match_lagrange(equations):
    """The model's eq. (10) (plus viscosity) solves the Lagrange equations at random states."""
    p = ZieglerPendulum(l1=0.3, l2=0.2, d=0.1, h=0.07, m1=0.5, m2=0.2, m3=0.3, k1=1.3, k2=0.7,
                        c1=0.02, c2=0.05)
    rng = np.random.default_rng(1)
    q1, q2, w1, w2, ac1, ac2 = sp.symbols("q1 q2 w1 w2 ac1 ac2")
    subs_fn = {a1.diff(t, 2): ac1, a2.diff(t, 2): ac2}
    exprs = [e.subs(subs_fn).subs({a1.diff(t): w1, a2.diff(t): w2}).subs({a1: q1, a2: q2})
             .subs(_values(p, 2.3, 0.9)) for e in equations]
    f = sp.lambdify((q1, q2, w1, w2, ac1, ac2), exprs)
    for _ in range(20):
        state = rng.uniform(-2, 2, 4)
        acc = p.equations_of_motion(state, P=2.3, H=0.9)[2:]
        assert np.allclose(f(*state, *acc), 0.0, atol=1e-12)


def test_linearisation_gives_eq13_not_printed_eq11(equations):
    """Linearised Lagrange equations: M of eq. (11) and K + G of eq. (13), G11 = -l1 (P + H)."""
    x1, x2 = sp.symbols("x1 x2")
    static = [e.subs({a1.diff(t, 2): 0, a2.diff(t, 2): 0, a1.diff(t): 0, a2.diff(t): 0})
              .subs({a1: x1, a2: x2}) for e in equations]
    KG = sp.Matrix([[sp.diff(e, x).subs({x1: 0, x2: 0}) for x in (x1, x2)] for e in static])
    assert sp.simplify(KG - sp.Matrix([[k1 + k2 - l1 * (P + H), -k2 + P * l1],
                                       [-k2, k2 - H * l2]])) == sp.zeros(2, 2)
    assert sp.simplify(KG[0, 0] - (k1 + k2 - l1 * (P - H))) != 0  # printed eq. (11)
    p = ZieglerPendulum(l1=0.3, l2=0.2, d=0.1, h=0.07, m1=0.5, m2=0.2, m3=0.3, k1=1.3, k2=0.7)
    num = np.array(KG.subs(_values(p, 2.3, 0.9)), dtype=float)
    assert np.allclose(num, p.stiffness_matrix() + p.geometric_matrix(2.3, 0.9), rtol=1e-14)


def _mass_matrix(eqs: list[sp.Expr]) -> sp.Matrix:
    acc = (a1.diff(t, 2), a2.diff(t, 2))
    return sp.Matrix([[sp.diff(e, a).subs({a1: 0, a2: 0}) for a in acc] for e in eqs])


def test_mass_matrix_needs_corrected_eq1(equations):
    """With eq. (1) as printed (d sin alpha2), m1 d^2 moves from M11 to M22: not eq. (11)."""
    eq11 = sp.Matrix([[m1 * d**2 + (m2 + m3) * l1**2, (m2 * l2 + m3 * h) * l1],
                      [(m2 * l2 + m3 * h) * l1, m2 * l2**2 + m3 * h**2]])
    assert sp.simplify(_mass_matrix(equations) - eq11) == sp.zeros(2, 2)
    printed = _mass_matrix(lagrange_equations(printed_eq1=True))
    assert sp.simplify(printed - eq11) != sp.zeros(2, 2)
    assert sp.simplify(printed[1, 1] - eq11[1, 1] - m1 * d**2) == 0


def test_closed_form_characteristic_polynomial():
    """Eqs. (18)–(21) and (33)–(35): the dimensionless determinant, expanded by sympy."""
    r1, r2, y1, y2, lam, k, w2, eta, gam = sp.symbols("rho1 rho2 y1 y2 lam k w2 eta gamma")
    A = (r1 * y1**2 + r2 + 1) * lam**2
    B = lam * (1 + r2 * y2)
    Cc = 1 + r2 * y2**2
    a = lam**2 * (y1**2 * r1 + (1 - y2) ** 2 * r2 + y1**2 * y2**2 * r1 * r2)
    b1 = lam * (2 + 2 * y2 * r2 + lam * (1 + y1**2 * r1 + r2)) + (k + 1) * (1 + r2 * y2**2)
    d2 = 1 + lam * (1 + y1**2 * r1 + r2) + r2 * y2**2
    b2 = 1 + lam + y2**2 * r2 + y2 * lam * r2
    dead = sp.Matrix([[A * w2 - 1 - k + eta, B * w2 + 1], [B * w2 + 1, Cc * w2 - 1 + eta / lam]])
    c_eta = eta**2 / lam - eta * (1 + 1 / lam + k / lam) + k
    assert sp.expand(dead.det() - (a * w2**2 - (b1 - eta * d2) * w2 + c_eta)) == 0
    fol = sp.Matrix([[A * w2 - 1 - k + gam, B * w2 + 1 - gam], [B * w2 + 1, Cc * w2 - 1]])
    assert sp.expand(fol.det() - (a * w2**2 - (b1 - gam * b2) * w2 + k)) == 0
