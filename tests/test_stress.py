"""The stress tests: no silent wrong answer anywhere, and the harness itself can fail."""

import pytest

from flutterfriction.errors import ConvergenceError
from flutterfriction.stress import (
    ALL_CASES,
    CORRECT,
    REFUSED,
    SLOW_AREAS,
    WRONG,
    _judge,
    stress_markdown,
)


# The slow areas (~40-120 s each) are marked slow.
@pytest.mark.parametrize("area", [pytest.param(a, marks=pytest.mark.slow) if a in SLOW_AREAS
                                  else a for a in sorted(ALL_CASES)])
def test_no_silent_wrong_answer(area):
    results = ALL_CASES[area]()
    assert results
    bad = [r for r in results if r.outcome not in (CORRECT, REFUSED)]
    assert not bad, stress_markdown(bad)


def test_the_harness_flags_a_wrong_answer_and_a_refusal():
    wrong = _judge("a", "b", "c", lambda: 1.0, lambda: 2.0, lambda g, r: abs(g - r) < 1e-9)
    assert wrong.outcome == WRONG

    def refuse():
        raise ConvergenceError("no root")

    refused = _judge("a", "b", "c", refuse, lambda: 2.0, lambda g, r: True)
    assert refused.outcome == REFUSED and "no root" in refused.got
    assert "1 silent wrong answers" in stress_markdown([wrong, refused])
