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
    with pytest.raises(ParameterError, match="interval|finite"):
        integrate_vectorised(lambda t: t[None, :], a, b)


def test_a_tolerance_below_round_off_ends_without_exhausting_memory():
    # the error estimate cannot fall below ~1e-16 |I| on most panels: without the bound on open
    # panels their number would double every pass (2^40); the answer is refused or exact
    f = lambda t: np.exp(np.sin(40 * t))[None, :]  # noqa: E731
    from scipy.integrate import quad

    exact = quad(lambda t: np.exp(np.sin(40 * t)), 0.0, 1.0, epsabs=0, epsrel=1e-13,
                 limit=500)[0]
    try:
        value, _ = integrate_vectorised(f, 0.0, 1.0, epsrel=1e-18)
    except ConvergenceError as exc:
        assert "round-off" in str(exc)
    else:
        assert value[0] == pytest.approx(exact, rel=1e-13)


@pytest.mark.parametrize("scale", [1e-300, 1e-170, 1.0, 1e160, 1e300])
def test_magnitudes_near_the_float_range_neither_fool_nor_break_the_error_estimate(scale):
    """The error norms squared their entries: at 1e160 the estimate was inf and at 1e-170
    zero, and every panel closed on the first pass (a step read 6.66814e159, a 50 % wrong
    spike integral; an outside audit). At any scale a smooth integrand is exact and a step
    right to the tolerance, with a positive error bound."""
    value, _ = integrate_vectorised(lambda t: scale * np.exp(t)[None, :], 0.0, 1.0)
    assert value[0] == pytest.approx(scale * (np.e - 1), rel=1e-13)
    # a jump: its panel is bisected until its bound fits the tolerance, at any scale
    value, error = integrate_vectorised(lambda t: scale * (t > 1 / 3)[None, :], 0.0, 1.0)
    assert value[0] == pytest.approx(scale * 2 / 3, rel=1e-10)
    assert 0 < error <= 1e-10 * value[0]


def test_a_sharp_peak_is_refined_to_the_global_tolerance():
    """A panel's share of the tolerance was in proportion to its width, so a peak carrying
    most of the integral needed better than round-off and was refused (an outside audit:
    a Lorentzian of width 1e-7; sin t + 1e-8 over a period, whose integral is tiny)."""
    c, w = 0.3141592, 1e-7

    def f(t):
        return (w / ((t - c) ** 2 + w**2))[None, :]

    exact = np.arctan((1 - c) / w) + np.arctan(c / w)
    value, _ = integrate_vectorised(f, 0.0, 1.0, epsrel=1e-10)
    assert value[0] == pytest.approx(exact, rel=1e-10)
    value, _ = integrate_vectorised(lambda t: (np.sin(t) + 1e-8)[None, :], 0.0, 2 * np.pi,
                                    epsrel=1e-6)
    assert value[0] == pytest.approx(2 * np.pi * 1e-8, rel=1e-6)


@pytest.mark.parametrize("kwargs, match", [({"panels": 0}, "panels"), ({"epsrel": -1.0}, "eps"),
                                           ({"epsrel": 0.0}, "eps"),
                                           ({"epsrel": float("nan")}, "epsrel")])
def test_bad_settings_are_refused(kwargs, match):
    with pytest.raises(ParameterError, match=match):
        integrate_vectorised(lambda t: t[None, :], 0.0, 1.0, **kwargs)


def test_an_interval_wider_than_the_floats_is_refused():
    with pytest.raises(ParameterError, match="interval"):
        integrate_vectorised(lambda t: t[None, :], -1e308, 1e308)
