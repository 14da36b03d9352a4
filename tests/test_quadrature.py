"""The vectorised adaptive quadrature (analysis.quadrature) against closed forms."""

import numpy as np
import pytest

from flutterfriction.analysis.quadrature import integrate_vectorised
from flutterfriction.errors import ConvergenceError, ParameterError


def test_smooth_vector_integrand_to_round_off():
    # int_0^2pi (cos^2 t, e^{sin t}) dt = (pi, 2 pi I0(1))
    from scipy.special import i0

    calls = []

    def f(t):
        calls.append(t.size)
        return np.array([np.cos(t) ** 2, np.exp(np.sin(t))])

    value, error = integrate_vectorised(f, 0.0, 2 * np.pi, epsrel=1e-12)
    assert value == pytest.approx([np.pi, 2 * np.pi * i0(1.0)], rel=1e-14)
    assert error < 1e-12 * np.linalg.norm(value)
    # 64 panels of 10 nodes, then their 128 halves: a smooth integrand closes in one pass
    assert sum(calls) == 64 * 10 * 3


def test_impulsive_peak_is_resolved():
    # a Lorentzian 1e4 times its background, width 1e-5 of the interval, off the panels'
    # symmetry points: int_0^1 = 1 + (atan((1 - c)/w) + atan(c/w))
    c, w = 0.3141592, 1e-5

    def f(t):
        return (1.0 + w / ((t - c) ** 2 + w**2))[None, :]

    exact = 1.0 + np.arctan((1 - c) / w) + np.arctan(c / w)
    value, _ = integrate_vectorised(f, 0.0, 1.0, epsrel=1e-10)
    assert value[0] == pytest.approx(exact, rel=1e-10)


def test_a_singular_integrand_is_refused_not_answered():
    with pytest.raises(ConvergenceError, match="bisections"):
        integrate_vectorised(lambda t: np.abs(t - 0.3) ** -0.9 * np.ones((1, t.size)),
                             0.0, 1.0, epsrel=1e-10, max_passes=20)


@pytest.mark.parametrize("a, b", [(1.0, 1.0), (1.0, 0.0), (0.0, np.inf), (np.nan, 1.0)])
def test_bad_interval_is_refused(a, b):
    with pytest.raises(ParameterError, match="interval"):
        integrate_vectorised(lambda t: t[None, :], a, b)


def test_a_tolerance_below_round_off_is_refused_without_exhausting_memory():
    # the error estimate cannot fall below ~1e-16 |I|: every panel stays open, and without a
    # bound their number would double every pass (2^40 panels)
    with pytest.raises(ConvergenceError, match="round-off"):
        integrate_vectorised(lambda t: np.exp(np.sin(40 * t))[None, :], 0.0, 1.0,
                             epsrel=1e-18)
