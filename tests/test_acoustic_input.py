"""The public functions of flutterfriction.analysis.acoustic refuse bad input in one line
(ParameterError naming the parameter and its range) before any work: an outside audit found
NaN answers, bare IndexError, LinAlgError, MemoryError and ZeroDivisionError, and a flutter
scan whose range beyond the double precision of its method ended in a ConvergenceError."""

from __future__ import annotations

import math
import re

import numpy as np
import pytest

from flutterfriction.analysis import acoustic as ac
from flutterfriction.analysis.stability import Regime
from flutterfriction.errors import ParameterError, check_finite_array
from flutterfriction.models import solid as so

E = so.isotropic_elasticity(1.0, 1.0)
# the shipped acoustic_eigenvalues case (workflow/config.yaml)
P = so.voigt_to_tensor([1.0, -0.5, -0.5, 0.0, 0.0, 0.8])
Q = so.voigt_to_tensor([0.6, -0.3, -0.3, 0.0, 0.0, -0.8])
SHIPPED_INTERVAL = (0.0012906584272531951, 4.958709341572748)  # eq. (188), corrected


@pytest.mark.parametrize("g_max", [1e7, 1e10, 1e150, 1e200])
def test_the_flutter_scan_refuses_a_g_max_beyond_its_numerical_range(g_max):
    """The audit (the acoustic_eigenvalues scene's g_max): 1e10 to 1e150 gave a
    ConvergenceError from inside, 1e200 a ZeroDivisionError in that error's own message. The
    range is g_max <= 1e4 |p| |q| / ||A_el|| (here |p| = 2.561, |q| = 2, ||A_el||_F = sqrt 11):
    beyond, the quartic's round-off decides."""
    scale = 2 * math.hypot(1.0, 0.8) * 2 * math.hypot(0.6, 0.8) / math.sqrt(11)
    assert ac.G_MAX_OVER_SCALE * scale == pytest.approx(15444.9, rel=1e-5)
    got = re.escape(repr(g_max))
    with pytest.raises(ParameterError, match=r"^g_max must be <= 10000 \|p\| \|q\| / "
                                             rf"\|\|A_el\|\| = 15444\.9 here .*, got {got}$"):
        ac.flutter_interval_bruteforce(E, P, Q, [1, 0, 0], g_max=g_max)
    for inside in (100.0, 15000.0):  # the shipped g_max, and near the bound: the same answer
        (found,) = ac.flutter_interval_bruteforce(E, P, Q, [1, 0, 0], g_max=inside)
        assert found == pytest.approx(SHIPPED_INTERVAL, rel=1e-12)


@pytest.mark.parametrize(("call", "match"), [
    (lambda: ac.localization_moduli(E, P, Q, np.full((2, 3), math.nan)), "directions "),
    (lambda: ac.localization_moduli(E, P, Q, np.zeros((2, 3))), "directions must be non-zero"),
    (lambda: ac.localization_moduli(E, P, Q, [1.0, 0.0, 0.0]), r"directions must be an array "
                                                               r"of shape \(m, 3\)"),
    (lambda: ac.localization_moduli(np.full((3, 3, 3, 3), math.nan), P, Q, [[1, 0, 0]]), "E "),
    (lambda: ac.acoustic_tensors(E, P, Q, [[1, 0, 0]], 0.0), "g_values "),
    (lambda: ac.acoustic_tensors(E, P, Q, [[1, 0, 0]], math.nan), "g_values "),
    (lambda: ac.acoustic_tensors(E, P, Q, [[1, 0, 0]], 1.0), "g_values must be a 1-d"),
    (lambda: ac.acoustic_tensors(E, P, Q, [[1, 0, 0]], [1.0, 0.0]), "g_values must be a 1-d"),
    (lambda: ac.max_localization_modulus(E, P, Q, 0), r"n_search must be an integer in "
                                                       r"\[1, 1000000\]"),
    (lambda: ac.classify_acoustic(np.full((3, 3), math.nan)), "A must be a finite 3x3"),
    (lambda: ac.classify_eigenvalues([math.nan, 1.0, 1.0]), "eta must be a non-empty 1-d"),
    (lambda: ac.classify_eigenvalues([]), "eta must be a non-empty 1-d"),
    (lambda: ac.fibonacci_sphere(-1), r"n must be an integer in \[1, 1000000\], got -1"),
    (lambda: ac.fibonacci_sphere(10**9), r"n must be an integer in \[1, 1000000\]"),
    (lambda: ac.fibonacci_sphere(4.0), r"n must be an integer"),
    (lambda: ac.isotropic_acoustic(1, 1, [1 + 1j, 0, 0, 0, 0, 0], [1, 0, 0, 0, 0, 0], [1, 0, 0]),
     r"P must be 6 finite numbers \(real numbers\)"),  # was a bare TypeError
    (lambda: ac.isotropic_acoustic(1, 1, [1, 0, 0, 0, 0, 0], ["1"] * 6, [1, 0, 0]),
     r"Q must be 6 finite numbers \(real numbers\)"),  # was read as numbers
])
def test_the_vectorised_helpers_refuse_bad_input_in_one_line(call, match):
    """The audit: NaN directions gave [nan, nan]; zero directions a LinAlgError; a scalar g an
    IndexError; n_search = 0 an IndexError; a NaN tensor a LinAlgError; eigenvalues with a NaN
    were classified STABLE; fibonacci_sphere(-1) returned nothing, (10**9) a MemoryError."""
    with pytest.raises(ParameterError, match=rf"^{match}"):
        call()


def test_the_helpers_answer_good_input_up_to_their_stated_range():
    """The stated maximum of fibonacci_sphere (1e6 directions, ~72 MB) is answered; the
    helpers answer good input as before."""
    for size in (5, ac.FIBONACCI_MAX):
        grid = ac.fibonacci_sphere(size)
        assert grid.shape == (size, 3) and np.allclose(np.linalg.norm(grid, axis=1), 1.0)
        assert np.all(grid[:, 2] > 0)  # the upper half sphere
    # g_E = q . A_el^-1 p at n = e1 (eq. 166): the closed form eq. (185)
    assert ac.localization_moduli(E, P, Q, [[1.0, 0.0, 0.0]])[0] == pytest.approx(
        so.localization_modulus_isotropic(1.0, 1.0, P, Q, [1.0, 0.0, 0.0]), rel=1e-14)
    A = ac.acoustic_tensors(E, P, Q, [[1.0, 0.0, 0.0]], [1.0, 2.0])
    assert A.shape == (1, 2, 3, 3)
    assert np.allclose(A[0, 0], so.acoustic_tensor(E, P, Q, 1.0, [1, 0, 0]), rtol=1e-15)
    assert ac.classify_acoustic(A[0, 0]) == Regime.FLUTTER  # g = 1 lies in the interval
    assert ac.classify_eigenvalues(np.array([1.0, 2.0, 3.0])) == Regime.STABLE


@pytest.mark.parametrize("value", [
    np.array([1 + 2j, 0.0, 0.0]),  # the imaginary part was dropped
    ["1", "2", "3"],  # strings were read as numbers
    [True, 1.0, 1.0],  # a bool was read as 1
    np.array([True, False, True]),
    [[1.0, 2.0], [3.0]],  # ragged: a bare ValueError from numpy
    [10**400, 0, 0],  # an integer beyond the doubles: a bare OverflowError
])
def test_check_finite_array_takes_real_numbers_only(value):
    """The audit: errors.check_finite_array (P, Q, n everywhere) accepted a complex array with
    its imaginary part silently dropped, and strings and bools inside arrays."""
    with pytest.raises(ParameterError, match=r"^n must be a finite array of shape \(3,\)"):
        check_finite_array("n", value, (3,))
    assert check_finite_array("n", [1, 2.5, np.float32(3)], (3,)).tolist() == [1.0, 2.5, 3.0]


# ---------------------------------------------------------------- scale (an outside audit)
@pytest.mark.parametrize("s", [1e-100, 1e-60, 1e40, 1e100])
def test_the_general_functions_are_homogeneous_in_the_scale_of_E(s):
    """An outside audit: the brute-force interval came out empty at E x 1e-100 (its quartic's
    coefficients underflowed, no warning) and a LinAlgError at 1e40. Every function of the
    general anisotropic section is homogeneous: A_el scales as |E|, the moduli g as
    |E| |P| |Q|; they compute in units of powers of two near these, so the answers scale to
    round-off (measured <= 2e-15; asserted 1e-13)."""
    n = np.array([1.0, 0.0, 0.0])
    (interval,) = ac.flutter_interval_bruteforce(E * s, P, Q, n, g_max=100.0 * s)
    assert np.array(interval) / s == pytest.approx(SHIPPED_INTERVAL, rel=1e-13)
    dirs = np.array([[1.0, 0.0, 0.0], [0.6, 0.8, 0.0], [0.0, 0.6, 0.8]])
    g = ac.localization_moduli(E * s, P, Q, dirs)
    assert g / s == pytest.approx(ac.localization_moduli(E, P, Q, dirs), rel=1e-13)
    A = ac.acoustic_tensors(E * s, P, Q, dirs, np.array([0.5, 2.0]) * s)
    assert A / s == pytest.approx(ac.acoustic_tensors(E, P, Q, dirs, np.array([0.5, 2.0])),
                                  rel=1e-13, abs=1e-13)


@pytest.mark.parametrize("t", [1e-150, 1e75, 1e140])
def test_the_localization_moduli_scale_with_P_and_Q(t):
    """The audit: P, Q x 1e160 gave the moduli NaN and the maximum -inf with no warning; at
    these scales (|E| |P| |Q| up to 1e280) each is t^2 times the unit case, and the flutter
    directions of a scan are the same."""
    dirs = np.array([[1.0, 0.0, 0.0], [0.6, 0.8, 0.0], [0.0, 0.6, 0.8]])
    g = ac.localization_moduli(E, P * t, Q * t, dirs) / t**2
    assert g == pytest.approx(ac.localization_moduli(E, P, Q, dirs), rel=1e-13)
    top, n_top = ac.max_localization_modulus(E, P * t, Q * t, n_search=50)
    top1, n1 = ac.max_localization_modulus(E, P, Q, n_search=50)
    assert top / t**2 == pytest.approx(top1, rel=1e-12)
    gs = np.array([0.01, 0.1, 1.0, 10.0])
    assert np.array_equal(ac.flutters_somewhere(E, P * t, Q * t, dirs, gs * t**2),
                          ac.flutters_somewhere(E, P, Q, dirs, gs))


@pytest.mark.parametrize("args", [(1e300, 1e300, 1.0), (1.0, 1e-200, 1e-200), (1.0, 1e160, 1e160)])
def test_moduli_whose_scale_leaves_the_double_range_are_refused(args):
    """|E| |P| |Q| beyond [1e-300, 1e300]: refused in one line naming E, P and Q, never a
    NaN, an infinity or an empty answer."""
    e, p, q = args
    dirs = np.array([[1.0, 0.0, 0.0]])
    for call in (lambda: ac.localization_moduli(E * e, P * p, Q * q, dirs),
                 lambda: ac.max_localization_modulus(E * e, P * p, Q * q, n_search=10),
                 lambda: ac.flutters_somewhere(E * e, P * p, Q * q, dirs, np.array([1.0])),
                 lambda: ac.flutter_interval_bruteforce(E * e, P * p, Q * q, dirs[0],
                                                        g_max=1e-290)):
        with pytest.raises(ParameterError, match=r"E, P and Q .*scale .*outside \[1e-300"):
            call()


def test_a_tensor_that_overflows_at_a_tiny_modulus_is_refused_naming_g_values():
    with pytest.raises(ParameterError, match=r"^g_values: .*double range"):
        ac.acoustic_tensors(E, P, Q, np.array([[1.0, 0.0, 0.0]]), np.array([1e-310]))


# ------------------------------------------------- physical tensors (an outside audit)
@pytest.mark.parametrize("bad, match", [
    (-E, r"E must be positive definite"),
    (so.isotropic_elasticity(1.0, 1.0) * 0.0, r"E must be a non-zero"),
    (np.eye(9).reshape(3, 3, 3, 3), r"E must have the minor symmetries"),
    (so.isotropic_elasticity(-0.5, 1.0) - 0.7 * np.einsum("ij,kl->ijkl", np.eye(3), np.eye(3)),
     r"E must be positive definite"),
])
def test_an_elasticity_that_is_not_one_is_refused(bad, match):
    """eq. (146): E maps symmetric strains to symmetric stresses (minor symmetries) and is
    positive definite (as isotropic_elasticity asks mu > 0, 3 lam + 2 mu > 0); the audit found
    -E accepted. The last case: lam = -1.2, mu = 1, 3 lam + 2 mu < 0."""
    dirs = np.array([[1.0, 0.0, 0.0]])
    for call in (lambda: ac.localization_moduli(bad, P, Q, dirs),
                 lambda: ac.flutter_interval_bruteforce(bad, P, Q, dirs[0], g_max=10.0),
                 lambda: so.acoustic_tensor(bad, P, Q, 1.0, dirs[0])):
        with pytest.raises(ParameterError, match=match):
            call()


def test_a_flow_tensor_that_is_not_symmetric_is_refused():
    """eq. (147): P is a symmetric second-order tensor, and so is Q (the gradient of f in the
    symmetric stress); the audit found a non-symmetric P accepted."""
    skew = P + np.array([[0.0, 0.1, 0.0], [-0.1, 0.0, 0.0], [0.0, 0.0, 0.0]])
    dirs = np.array([[1.0, 0.0, 0.0]])
    with pytest.raises(ParameterError, match=r"^P must be a symmetric"):
        ac.localization_moduli(E, skew, Q, dirs)
    with pytest.raises(ParameterError, match=r"^Q must be a symmetric"):
        ac.flutter_interval_bruteforce(E, P, skew, dirs[0], g_max=10.0)
    with pytest.raises(ParameterError, match=r"^P must be a symmetric"):
        so.plastic_modulus(0.0, E, skew, Q)
