"""Shared fixtures and hypothesis strategies: random but physical pendulums."""

from __future__ import annotations

import os
from pathlib import Path

import pytest
from hypothesis import HealthCheck, settings
from hypothesis import strategies as st

from flutterfriction import ZieglerPendulum
from flutterfriction.parameters import LIST_47
from flutterfriction.threads import one_blas_thread

ROOT = Path(__file__).resolve().parents[1]


@pytest.fixture(autouse=True, scope="session")
def _one_blas_thread():
    """The tests compute as the command line and the workflow do: with one BLAS thread
    (flutterfriction.threads; the default threads made the small eigenproblems several times
    slower)."""
    with one_blas_thread():
        yield

# The README's test command is deterministic: hypothesis draws the same examples on every
# machine and run (derandomize), so a pass here is a pass on a fresh clone. Exploration with new
# random examples is a separate, explicit step: HYPOTHESIS_PROFILE=explore python -m pytest.
settings.register_profile("default", max_examples=200, deadline=None, derandomize=True,
                          suppress_health_check=[HealthCheck.too_slow])
settings.register_profile("ci", max_examples=300, deadline=None, derandomize=True,
                          suppress_health_check=[HealthCheck.too_slow])
settings.register_profile("explore", max_examples=2000, deadline=None,
                          suppress_health_check=[HealthCheck.too_slow])
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "ci" if os.environ.get("CI")
                                     else "default"))

LIST47 = dict(LIST_47)  # list (47): flutterfriction.parameters


def _logu(lo: float, hi: float) -> st.SearchStrategy[float]:
    """Log-uniform floats: ratios spanning several decades, as physical parameters do."""
    import math
    return st.floats(math.log(lo), math.log(hi)).map(math.exp)


@st.composite
def pendulums(draw, three_masses: bool = True) -> ZieglerPendulum:
    l1, l2 = draw(_logu(0.05, 2.0)), draw(_logu(0.05, 2.0))
    m3 = draw(st.one_of(st.just(0.0), _logu(0.01, 10.0))) if three_masses else 0.0
    return ZieglerPendulum(
        l1=l1, l2=l2, d=draw(st.floats(0.05, 1.0)) * l1,
        # (h = 0, or normal: the model refuses a subnormal double)
        h=draw(st.one_of(st.just(0.0), st.floats(1e-9, 1.0))) * l2,
        m1=draw(_logu(0.01, 10.0)), m2=draw(_logu(0.01, 10.0)), m3=m3,
        k1=draw(_logu(0.01, 10.0)), k2=draw(_logu(0.01, 10.0)))


@pytest.fixture
def list47() -> ZieglerPendulum:
    return ZieglerPendulum(**LIST47)
