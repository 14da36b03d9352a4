"""Fuzzing the `flutterfriction` command (issue 12): every command over decades of every
parameter (1e-300..1e300, 0, negative, non-numbers). Each call either exits 0 with strict JSON
or exits 2 with one line on stderr naming a parameter; never a traceback, never NaN or
Infinity in the output. Where an independent computation exists the values are checked too
(the acoustic tensor's exact scaling laws, numpy's eigenvalues).

Bounded: small example counts and inputs whose computations are fast; the limit-cycle commands
are driven only up to their up-front checks (the integrators are replaced by a stub that
records acceptance), so no call integrates anything."""

from __future__ import annotations

import contextlib
import io
import json
import math
import os

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

from flutterfriction.cli import main

#: FLUTTERFRICTION_FUZZ_EXAMPLES=2000 for a long, randomised hunt; by default a fixed, quick set.
_EXAMPLES = os.environ.get("FLUTTERFRICTION_FUZZ_EXAMPLES")
FUZZ = settings(max_examples=int(_EXAMPLES or 60), deadline=None, derandomize=not _EXAMPLES,
                suppress_health_check=[HealthCheck.too_slow], database=None)

#: Values of every decade and the awkward ones, as a user would type them.
SPECIAL = ["0", "-0", "nan", "NaN", "inf", "-inf", "1e400", "-1e400", "5e-324", "1e-320",
           "1.7976931348623157e308", "abc", "", "1,2", "0x10"]


@st.composite
def decade(draw) -> str:
    if draw(st.integers(0, 4)) == 0:
        return draw(st.sampled_from(SPECIAL))
    sign = draw(st.sampled_from(["", "-"]))
    mantissa = draw(st.sampled_from(["1", "2.5", "7.3"]))
    return f"{sign}{mantissa}e{draw(st.integers(-300, 300))}"


def _run(argv: list[str]) -> tuple[int, str, str]:
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        try:
            code = main(argv)
        except SystemExit as exc:  # argparse's own errors and --help
            code = exc.code
    return code, out.getvalue(), err.getvalue()


def _strict_json(text: str):
    return json.loads(text, parse_constant=lambda c: pytest.fail(f"non-strict JSON {c!r}"))


def _check(argv: list[str]) -> dict | None:
    """The contract; returns the parsed result when the call succeeded."""
    code, out, err = _run(argv)
    assert "Traceback" not in err, (argv, err)
    if code == 0:
        return _strict_json(out)
    assert code == 2, (argv, code, err)
    assert out == "", (argv, out)
    lines = err.strip().splitlines()
    assert len(lines) == 1, (argv, err)
    names = {a.split("=")[0].lstrip("-") for a in argv if a.startswith("--")} - {"json"}
    assert any(name in lines[0] or name.replace("-", "_") in lines[0] for name in names), (
        argv, err)
    return None


def _argv(command: list[str], params: dict[str, str]) -> list[str]:
    """Options as ``--name=value`` (so that a value such as ``-1e-3`` or ``""`` stays a value),
    or as two words when the value is a plain number (the form users type)."""
    out = list(command)
    for k, v in params.items():
        out += [f"--{k}", v] if v and v[0] not in "-" else [f"--{k}={v}"]
    return [*out, "--json"]


# ---------------------------------------------------------------------- acoustic
BASE = {"lam": "1", "mu": "1", "P": "1,-0.5,-0.5,0,0,0.8", "Q": "0.6,-0.3,-0.3,0,0,-0.8",
        "n": "1,0,0", "g": "0.5"}


@st.composite
def acoustic_params(draw) -> dict[str, str]:
    params = dict(BASE)
    for name in draw(st.sets(st.sampled_from(sorted(BASE)), min_size=1, max_size=3)):
        if name in ("P", "Q", "n"):
            size = 3 if name == "n" else 6
            params[name] = ",".join(draw(st.lists(decade(), min_size=size, max_size=size)))
            if draw(st.booleans()):  # sometimes one entry only is extreme
                entries = BASE[name].split(",")
                entries[draw(st.integers(0, size - 1))] = draw(decade())
                params[name] = ",".join(entries)
        else:
            params[name] = draw(decade())
    return params


def _regime_of(eigenvalues: list[list[float]]) -> str:
    eta = np.array([complex(a, b) for a, b in eigenvalues])
    scale = np.abs(eta).max()
    if np.any(np.abs(eta.imag) > 1e-10 * scale):
        return "flutter"
    return "divergence" if np.any(eta.real < -1e-10 * scale) else "stable"


@FUZZ
@given(acoustic_params())
def test_acoustic_decades(params):
    result = _check(_argv(["acoustic"], params))
    if result is not None:
        assert set(result) >= {"g_localization", "flutter_interval", "eigenvalues", "regime"}
        assert result["regime"] == _regime_of(result["eigenvalues"])
        interval = result["flutter_interval"]
        if interval is not None:
            assert 0 <= interval[0] <= interval[1]


@FUZZ
@given(acoustic_params(), st.sampled_from(["P", "Q", "n"]))
def test_acoustic_vectors_as_separate_words(params, name):
    """The same call with a vector given as separate words (negative first entries included)
    gives the same answer as the comma form."""
    argv = _argv(["acoustic"], params)
    words = params[name].split(",")
    assume(all(words))
    spaced = ["acoustic"]
    for k, v in params.items():
        spaced += [f"--{k}", *v.split(",")] if k == name else [f"--{k}={v}"]
    spaced.append("--json")
    assert _run(spaced)[:2] == _run(argv)[:2]


WORDS = ["--lam", "--mu", "--P", "--Q", "--n", "--g", "--json", "--l", "--P=", "-1", "1", "0",
         "0.5", "-1e-3", "1e-300", "-1,0.5", "1,0,0", "-1,0.5,0.5,0,0,0.8", "nan", "-inf", "x",
         "--", "-", ",", "1,,2", "--g=-0.5"]


@FUZZ
@given(st.lists(st.sampled_from(WORDS), max_size=24))
def test_acoustic_any_words(words):
    """Whatever words follow `acoustic`: exit 0 or 2, never a traceback; JSON when asked."""
    argv = ["acoustic", "--lam", "1", "--mu", "1", *words]
    code, out, err = _run(argv)
    assert "Traceback" not in err and code in (0, 2), (argv, code, err)
    if code == 2:
        assert out == "" and len(err.strip().splitlines()) == 1, (argv, err)
    elif "--json" in words:
        _strict_json(out)


# (normal doubles: the acoustic entry refuses a subnormal one)
finite = st.floats(-2.0, 2.0, allow_nan=False, allow_subnormal=False)


@st.composite
def moderate_acoustic(draw):
    mu = draw(st.floats(0.1, 10.0))
    ratio = draw(st.floats(-0.65, 10.0))
    # lam = 0 or normal, also scaled by 2^-300 (a subnormal lam is refused, as any parameter)
    assume(ratio == 0 or abs(ratio) >= 1e-100)
    lam = mu * ratio
    P = draw(st.lists(finite, min_size=6, max_size=6))
    Q = draw(st.lists(finite, min_size=6, max_size=6))
    n = draw(st.lists(st.floats(-1.0, 1.0, allow_subnormal=False), min_size=3, max_size=3))
    assume(max(map(abs, n)) > 1e-3 and max(map(abs, P)) > 1e-3 and max(map(abs, Q)) > 1e-3)
    g = 10 ** draw(st.floats(-3.0, 3.0))  # g > 0 (eq. 152; a negative g is refused)
    return lam, mu, P, Q, n, g


def _acoustic(lam, mu, P, Q, n, g):
    return _run(["acoustic", f"--lam={lam!r}", f"--mu={mu!r}",
                 "--P=" + ",".join(map(repr, P)), "--Q=" + ",".join(map(repr, Q)),
                 "--n=" + ",".join(map(repr, n)), f"--g={g!r}", "--json"])


@FUZZ
@given(moderate_acoustic(), st.integers(-1000, 1000), st.integers(-1000, 1000),
       st.integers(-1000, 1000))
def test_acoustic_scaling_laws(base, km, ka, kb):
    """lam, mu times m; P times a; Q times b; g times m a b (powers of two: exact): A(n) is m
    A(n), so the eigenvalues are m times the unscaled ones and the moduli m a b times (to
    rounding: the scaled quantities lam/mu, P/max|P|, ... are the same floats). Every scaled
    call within 2^+-300 (1e+-90) of the base must succeed; beyond, refusal is allowed."""
    lam, mu, P, Q, n, g = base
    code, out, err = _acoustic(lam, mu, P, Q, n, g)
    assert code == 0, err
    ref = _strict_json(out)

    def scale(x: float, k: int) -> float:
        try:
            return math.ldexp(x, k)
        except OverflowError:
            return math.inf

    scaled = (scale(lam, km), scale(mu, km), [scale(x, ka) for x in P],
              [scale(x, kb) for x in Q], n, scale(g, km + ka + kb))
    assume(all(math.isfinite(x) for x in (scaled[0], scaled[1], *scaled[2], *scaled[3],
                                          scaled[5])))
    code, out, err = _acoustic(*scaled)
    assert "Traceback" not in err
    if max(abs(km), abs(ka), abs(kb)) <= 300:  # 2^300 = 2e90
        assert code == 0, err
    if code == 2:
        return
    assert code == 0, err
    # Compared only where the scaled inputs are exact (no subnormal or zero rounding).
    pairs = [(scaled[0], lam, km), (scaled[1], mu, km), (scaled[5], g, km + ka + kb),
             *((x, y, ka) for x, y in zip(scaled[2], P, strict=True)),
             *((x, y, kb) for x, y in zip(scaled[3], Q, strict=True))]
    if any(scale(new, -k) != old for new, old, k in pairs):
        return
    got = _strict_json(out)
    assert got["regime"] == ref["regime"]
    kmab = km + ka + kb
    assert got["g_localization"] == pytest.approx(scale(ref["g_localization"], kmab),
                                                  rel=1e-13, abs=1e-300)
    if ref["flutter_interval"] is None:
        assert got["flutter_interval"] is None
    else:
        assert got["flutter_interval"] == pytest.approx(
            [scale(y, kmab) for y in ref["flutter_interval"]], rel=1e-13, abs=1e-300)
    flat = [x for pair in got["eigenvalues"] for x in pair]
    ref_flat = [scale(x, km) for pair in ref["eigenvalues"] for x in pair]
    assert flat == pytest.approx(ref_flat, rel=1e-13, abs=1e-300)


@FUZZ
@given(moderate_acoustic())
def test_acoustic_against_numpy(base):
    """The scaled closed forms against numpy's eigenvalues of the tensor of eq. (179)."""
    from flutterfriction.models import solid as so

    lam, mu, P, Q, n, g = base
    code, out, err = _acoustic(lam, mu, P, Q, n, g)
    assert code == 0, err
    res = _strict_json(out)
    nu = np.array(n) / np.linalg.norm(n)
    A = so.acoustic_tensor_isotropic(lam, mu, so.voigt_to_tensor(P), so.voigt_to_tensor(Q), g,
                                     nu)
    expected = np.linalg.eigvals(A)
    got = np.array([complex(x, y) for x, y in res["eigenvalues"]])
    scale = np.abs(expected).max()
    # each computed eigenvalue is near one of numpy's (near a double root both are only
    # accurate to sqrt(eps))
    for z in got:
        assert np.min(np.abs(expected - z)) <= 1e-6 * scale, (got, expected)
    assert np.prod(got).real == pytest.approx(np.linalg.det(A), rel=1e-8, abs=1e-10 * scale**3)


# ---------------------------------------------------------------------- ziegler, rod
ZIEGLER = {"l1": "0.1", "l2": "0.1", "d": "0.0333", "h": "0.0333", "m1": "0.552",
           "m2": "0.046", "m3": "0.138", "k1": "0.189", "k2": "0.189", "c1": "0", "c2": "0"}


@FUZZ
@given(st.dictionaries(st.sampled_from(sorted(ZIEGLER)), decade(), min_size=1, max_size=2))
def test_ziegler_decades(over):
    result = _check(_argv(["ziegler"], ZIEGLER | over))
    if result is not None:
        for key in ("P_flu", "P_div", "H_cr", "H_sup"):
            assert result[key] is None or result[key] > 0


#: Found by long randomised runs of test_ziegler_decades.
ZIEGLER_FOUND = [{"k2": "1e3", "l1": "1e3"}, {"l1": "7.3e4"}]


@pytest.mark.parametrize("over", ZIEGLER_FOUND, ids=str)
def test_ziegler_found_cases(over):
    _check(_argv(["ziegler"], ZIEGLER | over))


ROD_SI = {"length": "0.35", "B": "0.0332", "rho": "0.0546", "D": "7.078e-6", "kappa": "0",
          "tip-mass": "0"}


def _rod_dimensionless(over):
    result = _check(_argv(["rod"], over))
    if result is not None:
        assert result["p_flu"] is None or result["p_flu"] > 0


@FUZZ
@given(st.dictionaries(st.sampled_from(["mass-ratio", "p-max"]), decade(), min_size=1,
                       max_size=2))
def test_rod_undamped_decades(over):
    _rod_dimensionless(over)


@pytest.mark.slow  # > 4 s on a 2-core AMD EPYC host (2026-11-29)
@FUZZ
@given(st.dictionaries(st.sampled_from(["mass-ratio", "eta", "gamma", "p-max"]), decade(),
                       min_size=1, max_size=3).filter(lambda d: "eta" in d or "gamma" in d))
def test_rod_damped_decades(over):
    _rod_dimensionless(over)


#: Found by long randomised runs of test_rod_damped_decades (exit 1: eq. (118)'s Newton or the
#: exact regime check failing at small damping).
ROD_DAMPED_FOUND = [["--eta", "1e-2"], ["--gamma", "1e-5"], ["--eta", "1e-2", "--gamma", "1e-2"],
                    ["--gamma", "1e-30"], ["--mass-ratio", "0", "--gamma", "1e-5"]]


@pytest.mark.parametrize("args", ROD_DAMPED_FOUND, ids=" ".join)
def test_rod_damped_found_cases(args):
    _check(["rod", *args, "--json"])


@FUZZ
@given(st.dictionaries(st.sampled_from(sorted(ROD_SI)), decade(), min_size=1, max_size=2))
def test_rod_si_decades(over):
    result = _check(_argv(["rod"], ROD_SI | over))
    if result is not None and result.get("P_flu_N") is not None:
        assert result["P_flu_N"] > 0


# ---------------------------------------------------------------------- limit cycles, refusals
class _Accepted(Exception):
    """Raised by the stub integrators: the call passed every up-front check."""


BECK = {"P": "5.5", "length": "0.35", "B": "0.0332", "rho": "0.0546", "D": "7.078e-6",
        "kappa": "0", "tip-mass": "0", "elements": "4"}


@st.composite
def beck_params(draw):
    over = draw(st.dictionaries(st.sampled_from(sorted(BECK) + ["t-max"]), decade(),
                                min_size=1, max_size=2))
    if "elements" in over and draw(st.booleans()):
        over["elements"] = str(draw(st.integers(-5, 100)))
    return BECK | over


@FUZZ
@given(beck_params())
def test_limit_cycle_beck_refusals(params):
    """Every call is refused up front (exit 2, one line naming a parameter) or reaches the
    integrator with parameters inside the stated ranges and a cost estimate within the
    budget the help promises."""
    import flutterfriction.analysis.rod_dynamics as rd
    from flutterfriction import cli

    def stub(rod, P, **kw):
        raise _Accepted(rod, P, kw)

    estimates = []
    real = cli.beck_cost_estimate
    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(rd, "beck_limit_cycle", stub)
        mp.setattr(cli, "beck_cost_estimate", lambda *a: estimates.append(real(*a))
                   or estimates[-1])
        try:
            _check(_argv(["limit-cycle", "beck"], params) + ["--quiet"])
        except _Accepted as accepted:
            rod, P, kw = accepted.args
            assert len(estimates) == 1 and estimates[0] <= cli.BECK_BUDGET_S
            assert 1 <= kw["n_elements"] <= 16 and rod.D > 0
            assert 0 < kw["t_max"] <= 2000 * rod.time_scale
            assert 1e-6 <= rod.length <= 1e6 and 1e-12 <= rod.B <= 1e12
            assert 1e-12 <= rod.rho <= 1e12 and 0 < P < 1e3 * rod.load_unit


@settings(FUZZ, max_examples=int(_EXAMPLES or 30))  # each call solves for P_flu, P_div
@given(st.dictionaries(st.sampled_from(sorted(ZIEGLER) + ["P", "alpha0-deg"]), decade(),
                       min_size=1, max_size=2))
def test_limit_cycle_ziegler_refusals(over):
    """Up to the integrator only (a stub): refused with one line, or accepted."""
    import flutterfriction.analysis.dynamics as dyn

    def stub(*args, **kw):
        raise _Accepted(args)

    params = ZIEGLER | {"c1": "0.006", "c2": "0.006", "P": "3.915"} | over
    with pytest.MonkeyPatch.context() as mp:
        for name in ("limit_cycle", "shoot_periodic_orbit", "limit_cycle_by_continuation"):
            if hasattr(dyn, name):  # every integrator `limit-cycle ziegler` may call
                mp.setattr(dyn, name, stub)
        with contextlib.suppress(_Accepted):
            _check(_argv(["limit-cycle", "ziegler"], params))
