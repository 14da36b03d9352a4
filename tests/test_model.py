"""ZieglerPendulum: matrices, nonlinear equations and input validation."""

from __future__ import annotations

import math

import numpy as np
import pytest
from conftest import LIST47, pendulums
from hypothesis import given

from flutterfriction import ParameterError, ZieglerPendulum


@given(pendulums())
def test_matrices_have_the_stated_structure(p):
    """§2.1: M, K symmetric positive definite; G unsymmetric only through P."""
    for A in (p.mass_matrix(), p.stiffness_matrix()):
        assert np.allclose(A, A.T)
        assert np.all(np.linalg.eigvalsh(A) > 0)
    G_H = p.geometric_matrix(0.0, 1.0)
    assert np.allclose(G_H, G_H.T)
    G_P = p.geometric_matrix(1.0, 0.0)
    assert not np.allclose(G_P, G_P.T)


@given(pendulums())
def test_nonlinear_equations_linearise_to_eq11(p):
    """Central differences of eq. (10) at rest give -M^{-1}(K + G) and -M^{-1}C."""
    p = p.with_(c1=0.3 * p.k1, c2=0.1 * p.k2)
    P, H = 0.7 * p.load_unit, 0.2 * p.load_unit
    step = 1e-6
    J = np.column_stack([(p.equations_of_motion(step * e, P, H)
                          - p.equations_of_motion(-step * e, P, H)) / (2 * step)
                         for e in np.eye(4)])
    Minv = np.linalg.inv(p.mass_matrix())
    expected = np.block([[np.zeros((2, 2)), np.eye(2)],
                         [-Minv @ (p.stiffness_matrix() + p.geometric_matrix(P, H)),
                          -Minv @ p.viscosity_matrix()]])
    assert np.allclose(J, expected, rtol=1e-6, atol=1e-6 * np.abs(expected).max())


def test_positions_eq1(list47):
    pos = list47.positions(0.3, -0.2)
    assert np.allclose(pos["D"], list47.d * np.array([math.cos(0.3), math.sin(0.3)]))
    assert np.linalg.norm(pos["C"] - pos["B"]) == pytest.approx(list47.l2)
    assert np.linalg.norm(pos["E"] - pos["B"]) == pytest.approx(list47.h)


@pytest.mark.parametrize("name", ["l1", "l2", "d", "m1", "m2", "k1", "k2"])
@pytest.mark.parametrize("bad", [0.0, -1.0, math.nan, math.inf, -math.inf])
def test_positive_parameters_rejected(name, bad):
    with pytest.raises(ParameterError, match=name):
        ZieglerPendulum(**{**LIST47, name: bad})


@pytest.mark.parametrize("name", ["h", "m3", "c1", "c2"])
def test_nonnegative_parameters(name):
    ZieglerPendulum(**{**LIST47, name: 0.0})  # allowed
    with pytest.raises(ParameterError, match=name):
        ZieglerPendulum(**{**LIST47, name: -1e-9})


@pytest.mark.parametrize("bad", ["0.1", None, True, [0.1]])
def test_non_numbers_rejected(bad):
    with pytest.raises(ParameterError, match="l1"):
        ZieglerPendulum(**{**LIST47, "l1": bad})


def test_geometry_must_be_consistent():
    with pytest.raises(ParameterError, match="d must lie on rod AB"):
        ZieglerPendulum(**{**LIST47, "d": 0.11})
    with pytest.raises(ParameterError, match="h must lie on rod BC"):
        ZieglerPendulum(**{**LIST47, "h": 0.2})


def test_from_mapping_rejects_unknown_and_missing_keys():
    with pytest.raises(ParameterError, match="unknown pendulum parameter.*'mass'"):
        ZieglerPendulum.from_mapping({**LIST47, "mass": 1.0})
    with pytest.raises(ParameterError, match="missing.*'k2'"):
        ZieglerPendulum.from_mapping({k: v for k, v in LIST47.items() if k != "k2"})


def test_loads_must_be_finite(list47):
    with pytest.raises(ParameterError, match="P"):
        list47.geometric_matrix(P=math.nan)
    with pytest.raises(ParameterError, match="H"):
        list47.geometric_matrix(H=math.inf)


@pytest.mark.parametrize(("state", "P", "name"), [
    ([math.nan, 0, 0, 0], 1.0, "state"), ([0.1, 0, 0, 0], math.nan, "P"),
    ([0.1, 0, 0], 1.0, "state"), ([[0.1, 0.2], [0, 0]], 1.0, "state"),
])
def test_equations_of_motion_refuse_non_finite_or_misshapen_input(state, P, name):
    """Outside audit: a NaN state or load gave NaN accelerations silently, a 3-vector a raw
    unpacking error. (Integrators validate their start once and call it unchecked.)"""
    p = ZieglerPendulum(**LIST47)
    with pytest.raises(ParameterError, match=rf"^{name} "):
        p.equations_of_motion(state, P)
    unchecked = p.equations_of_motion([0.1, 0, 0, 0], 1.0, check=False)
    assert np.array_equal(unchecked, p.equations_of_motion([0.1, 0, 0, 0], 1.0))


def test_the_bound_right_hand_side_is_the_equations_of_motion():
    """ZieglerPendulum.motion_at (an integrator's right-hand side, constants bound once) gives
    the same numbers, bit for bit, as equations_of_motion for one state; for states (4, n), as
    a vectorized integrator passes them, the batched form's (numpy's sin and cos: to 1e-14,
    they may differ from math's by an ulp); a non-finite load is refused when it is bound."""
    p = ZieglerPendulum(**{**LIST47, "m3": 0.05, "h": 0.02, "c1": 0.003, "c2": 0.006})
    X = np.random.default_rng(7).normal(size=(4, 9))
    f = p.motion_at(2.3, 0.7)
    batched = p.equations_of_motion(X, 2.3, 0.7)
    for k in range(X.shape[1]):
        one = f(0.0, X[:, k])
        assert np.array_equal(one, p.equations_of_motion(X[:, k], 2.3, 0.7))
        assert np.allclose(one, batched[:, k], rtol=1e-14, atol=0.0)
    assert np.array_equal(f(0.0, X), batched)
    for bad in (math.nan, math.inf):
        with pytest.raises(ParameterError, match="^P "):
            p.motion_at(bad)
        with pytest.raises(ParameterError, match="^H "):
            p.motion_at(1.0, bad)
