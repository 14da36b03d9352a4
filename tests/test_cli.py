"""The `flutterfriction` command: JSON surface, exit codes, one-line errors."""

from __future__ import annotations

import json
import re
import subprocess
import sys

import pytest
from conftest import LIST47

from flutterfriction.analysis.ziegler import critical_loads
from flutterfriction.cli import main
from flutterfriction.models.ziegler import ZieglerPendulum


def _args(**over):
    params = {**LIST47, **over}
    return ["ziegler", *[f"--{k}={v}" for k, v in params.items()]]


def test_json_output(capsys):
    assert main([*_args(), "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    expected = critical_loads(ZieglerPendulum(**LIST47))
    for key in ("P_flu", "P_div", "H_cr", "H_sup"):
        assert out[key] == pytest.approx(getattr(expected, key), rel=1e-14)
    assert out["P_flu"] == pytest.approx(4.8038120088, rel=1e-10)


def test_viscous_hinges(capsys):
    """Issue 3: with c1 = c2 = 0.006 N m s (§2.9) the loads are the damped ones (Fig. 19)."""
    assert main([*_args(c1=0.006, c2=0.006), "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["P_flu_undamped"] == pytest.approx(4.8038120088, rel=1e-10)
    assert out["P_div_undamped"] == pytest.approx(8.8041879912, rel=1e-10)
    assert out["P_flu"] / out["P_flu_undamped"] == pytest.approx(0.70, abs=0.005)
    assert out["P_div"] / out["P_div_undamped"] == pytest.approx(1.49, abs=0.005)
    assert out["H_cr"] == pytest.approx(critical_loads(ZieglerPendulum(**LIST47)).H_cr)


def test_text_output(capsys):
    assert main(_args()) == 0
    out = capsys.readouterr().out
    assert "P_flu" in out and "4.803812009 N" in out


@pytest.mark.parametrize(("over", "name"), [
    ({"m1": -1}, "m1"), ({"k2": 0}, "k2"), ({"l1": "nan"}, "l1"), ({"l2": "inf"}, "l2"),
    ({"d": 0.5}, "d"), ({"h": 0.5}, "h"), ({"m3": "abc"}, "m3"), ({"c1": -0.1}, "c1"),
])
def test_bad_input_exits_2_naming_the_parameter(capsys, over, name):
    with pytest.raises(SystemExit) as exc:
        code = main(_args(**over))
        raise SystemExit(code)
    assert exc.value.code == 2
    err = capsys.readouterr().err
    assert name in err and "Traceback" not in err
    assert len(err.strip().splitlines()) == 1


def test_missing_argument_exits_2(capsys):
    with pytest.raises(SystemExit) as exc:
        main(["ziegler", "--l1", "0.1"])
    assert exc.value.code == 2
    assert "--k2" in capsys.readouterr().err


def test_console_script_runs_as_a_process():
    """The installed entry point, end to end, as an external checker would call it."""
    proc = subprocess.run([sys.executable, "-m", "flutterfriction.cli", *_args(m1=-1)],
                          capture_output=True, text=True)
    assert proc.returncode == 2
    assert "m1" in proc.stderr and "Traceback" not in proc.stderr
    proc = subprocess.run([sys.executable, "-m", "flutterfriction.cli", *_args(), "--json"],
                          capture_output=True, text=True, check=True)
    assert set(json.loads(proc.stdout)) >= {"P_flu", "P_div", "H_cr", "H_sup"}


@pytest.mark.parametrize("module", ["flutterfriction", "flutterfriction.cli"])
def test_python_dash_m_runs_the_command_line(module):
    """``python -m flutterfriction`` as well as the module (an outside audit found the package
    without a __main__: exit 1, "No module named flutterfriction.__main__")."""
    proc = subprocess.run([sys.executable, "-m", module, "--help"], capture_output=True,
                          text=True)
    assert proc.returncode == 0 and "ziegler" in proc.stdout
    proc = subprocess.run([sys.executable, "-m", module, *_args(m1=-1)], capture_output=True,
                          text=True)
    assert proc.returncode == 2 and "m1" in proc.stderr and "Traceback" not in proc.stderr


def test_rod_json(capsys):
    assert main(["rod", "--mass-ratio", "0", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["p_flu"] == pytest.approx(20.0509536190, rel=1e-10)
    assert out["p_div"] is None and out["omega_flu"] > 0


def test_rod_si(capsys):
    args = ["rod", "--length", "0.35", "--B", "0.0332", "--rho", "0.0546", "--D", "7.078e-6",
            "--json"]
    assert main(args) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["p_flu"] == pytest.approx(10.9393514864, rel=1e-9)
    assert out["P_flu_N"] == pytest.approx(out["p_flu"] * 0.0332 / 0.35**2)
    # the pulsation in rad/s (an outside audit: SI mode gave it only per time scale)
    T = 0.35**2 * (0.0546 / 0.0332) ** 0.5
    assert out["time_scale_s"] == pytest.approx(T, rel=1e-14)
    assert out["Omega_flu_rad_s"] == pytest.approx(out["omega_flu"] / T, rel=1e-14)
    assert out["Omega_div_rad_s"] is None


@pytest.mark.parametrize(("args", "name"), [
    (["--mass-ratio", "-1"], "--mass-ratio"), (["--eta", "nan"], "--eta"),
    (["--length", "1", "--B", "1"], "--rho"), (["--mass-ratio", "1", "--length", "1"], "either"),
    (["--length", "-1", "--B", "1", "--rho", "1"], "length")])
def test_rod_bad_input(capsys, args, name):
    with pytest.raises(SystemExit) as exc:
        raise SystemExit(main(["rod", *args]))
    assert exc.value.code == 2
    err = capsys.readouterr().err
    assert name in err and "Traceback" not in err


def test_acoustic_json(capsys):
    args = ["acoustic", "--lam", "1", "--mu", "1", "--P", "1,-0.5,-0.5,0,0,0.8",
            "--Q", "0.6,-0.3,-0.3,0,0,-0.8", "--n", "1,0,0", "--g", "0.5", "--json"]
    assert main(args) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["flutter_interval"][0] < 0.5 < out["flutter_interval"][1]
    assert any(abs(im) > 0 for _, im in out["eigenvalues"])  # inside the interval: flutter
    assert "g_localization" in out


@pytest.mark.parametrize(("extra", "name"), [(["--n", "0,0,0"], "--n"),
                                             (["--n", "1,0"], "--n"),
                                             (["--n", "1,0,0", "--g", "0"], "--g")])
def test_acoustic_bad_input(capsys, extra, name):
    args = ["acoustic", "--lam", "1", "--mu", "1", "--P", "1,0,0,0,0,0", "--Q", "1,0,0,0,0,0",
            *extra]
    with pytest.raises(SystemExit) as exc:
        raise SystemExit(main(args))
    assert exc.value.code == 2
    err = capsys.readouterr().err
    assert name in err and "Traceback" not in err


def test_limit_cycle_cli(capsys):
    args = ["limit-cycle", "ziegler", "--l1", "0.1", "--l2", "0.1", "--d", "0.1", "--h", "0",
            "--m1", "0.2", "--m2", "0.2", "--m3", "0", "--k1", "0.189", "--k2", "0.189",
            "--c1", "0.006", "--c2", "0.006", "--P", "3.915", "--json"]
    assert main(args) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["period_s"] == pytest.approx(0.9658, rel=1e-3)
    assert out["period_s"] == pytest.approx(out["shooting_check"]["period_s"], rel=1e-8)
    assert set(out) >= {"alpha1_amplitude_rad", "alpha2_amplitude_rad", "period_s"}


@pytest.mark.parametrize(("args", "name"), [(["--elements", "0"], "--elements"),
                                            (["--P", "-1"], "--P"), (["--B", "0"], "B")])
def test_limit_cycle_beck_bad_input(capsys, args, name):
    with pytest.raises(SystemExit) as exc:
        raise SystemExit(main(["limit-cycle", "beck", *args]))
    assert exc.value.code == 2
    err = capsys.readouterr().err
    assert name in err and "Traceback" not in err


def test_acoustic_regime(capsys):
    args = ["acoustic", "--lam", "1", "--mu", "1", "--P", "1,-0.5,-0.5,0,0,0.8",
            "--Q", "0.6,-0.3,-0.3,0,0,-0.8", "--n", "1,0,0", "--g", "0.5", "--json"]
    assert main(args) == 0
    assert json.loads(capsys.readouterr().out)["regime"] == "flutter"


# ---------------------------------------------------------------- issue 12: vectors, scale, beck
ACOUSTIC = ["acoustic", "--lam", "1", "--mu", "1", "--Q=0.6,-0.3,-0.3,0,0,-0.8", "--n", "1,0,0",
            "--g", "0.5", "--json"]


def _run(capsys, args):
    code = main(args)
    captured = capsys.readouterr()
    return code, captured.out, captured.err


def _strict(text):
    return json.loads(text, parse_constant=lambda c: pytest.fail(f"non-strict JSON: {c}"))


@pytest.mark.parametrize("P", [
    ["--P", "-1,0.5,0.5,0,0,0.8"], ["--P", "-1", "0.5", "0.5", "0", "0", "0.8"],
    ["--P=-1,0.5,0.5,0,0,0.8"], ["--P", "-1e0", "5e-1,0.5", "0", "-0", "0.8"],
    ["--P", "-1, 0.5, 0.5, 0, 0, 0.8"], ["--P=-1", "0.5", "0.5", "0", "0", "0.8"]])
def test_negative_vector_entries_as_typed(capsys, P):
    """Issue 12, item 4: a vector may start with a negative number, comma- or space-separated."""
    code, out, _ = _run(capsys, [*ACOUSTIC, *P])
    assert code == 0
    code_ref, ref, _ = _run(capsys, [*ACOUSTIC, "--P=-1,0.5,0.5,0,0,0.8"])
    assert _strict(out) == _strict(ref)


def test_negative_vector_entries_every_vector_option(capsys):
    args = ["acoustic", "--lam", "-0.1", "--mu", "1", "--P", "-1", "0.5", "0.5", "0", "0", "0.8",
            "--Q", "-0.6", "0.3", "0.3", "0", "0", "-0.8", "--n", "-1", "-1e-1", "0", "--g",
            "2e-1", "--json"]  # (a negative --g is refused: eq. 152, g > 0)
    code, out, _ = _run(capsys, args)
    assert code == 0
    assert _strict(out)["notes"]  # n was normalised


def test_positive_comma_form_still_works(capsys):
    code, out, _ = _run(capsys, [*ACOUSTIC, "--P", "1,-0.5,-0.5,0,0,0.8"])
    assert code == 0 and _strict(out)["regime"] == "flutter"


@pytest.mark.parametrize(("P", "text"), [(["--P", "-1", "0.5"], "needs 6 numbers"),
                                         (["--P", "-1,0.5,0.5,0,0,0.8,1"], "needs 6 numbers"),
                                         # a 7th word (was "unrecognized arguments: 7")
                                         (["--P", "1", "-0.5", "-0.5", "0", "0", "0.8", "7"],
                                          "needs 6 numbers .* got 7"),
                                         (["--P", "nan,0,0,0,0,0"], "finite")])
def test_vector_count_and_values_checked(capsys, P, text):
    code, _, err = _run_exit(capsys, [*ACOUSTIC, *P])
    assert code == 2 and "--P" in err and re.search(text, err) and "Traceback" not in err


def _run_exit(capsys, args):
    try:
        code = main(args)
    except SystemExit as exc:  # argparse's errors
        code = exc.code
    captured = capsys.readouterr()
    return code, captured.out, captured.err


def test_help_says_how_to_give_vectors(capsys):
    code, out, _ = _run_exit(capsys, ["acoustic", "--help"])
    assert code == 0
    assert "spaces or commas" in out and "--P -1 0.5 0.5 0 0 0.8" in " ".join(out.split())


def test_acoustic_huge_direction_is_normalised(capsys):
    """Issue 12, item 5: |n| overflowed and n became zero (g_loc 0, "stable")."""
    base = [a for a in ACOUSTIC if a not in ("--n", "1,0,0")]
    P = "--P=1,-0.5,-0.5,0,0,0.8"
    code, out, _ = _run(capsys, [*base, P, "--n", "1e300,1e300,0"])
    assert code == 0
    huge = _strict(out)
    code, out, _ = _run(capsys, [*base, P, "--n", "1,1,0"])
    unit = _strict(out)
    assert huge["g_localization"] == pytest.approx(unit["g_localization"], rel=1e-14)
    assert huge["g_localization"] != 0
    assert _flat(huge["eigenvalues"]) == pytest.approx(_flat(unit["eigenvalues"]), rel=1e-14)


def _flat(pairs):
    return [x for pair in pairs for x in pair]


def test_acoustic_tiny_g_keeps_the_finite_eigenvalue(capsys):
    """Issue 12: at g = 1e-100 the finite root (33 here) came out as 0 (cancellation)."""
    args = [a if a != "0.5" else "1e-100" for a in ACOUSTIC]
    code, out, _ = _run(capsys, [*args, "--P=1,-0.5,-0.5,0,0,0.8"])
    assert code == 0
    eta = sorted(re for re, _ in _strict(out)["eigenvalues"])
    assert eta[0] == pytest.approx(1.0) and eta[1] == pytest.approx(33.0, rel=1e-12)
    assert eta[2] == pytest.approx(1.6e99, rel=1e-12)


@pytest.mark.parametrize(("over", "name"), [
    ({"--g": "1e-300"}, "--g"), ({"--g": "1e-320"}, "--g"), ({"--lam": "1e300"}, "--lam"),
    ({"--mu": "1e300"}, "--mu"), ({"--mu": "1e-300"}, "--lam"), ({"--mu": "1e-320"}, "--mu"),
    ({"--lam": "-1e300"}, "--lam"), ({"--mu": "2e300", "--lam": "0"}, "--mu"),
    ({"--P": "1e300,-0.5e300,-0.5e300,0,0,0.8e300"}, "--P"),
    ({"--P": "1e-200,0,0,0,0,0", "--Q": "1e-200,0,0,0,0,0"}, "--Q"),
])
def test_acoustic_out_of_range_refused(capsys, over, name):
    """Issue 12: tracebacks, NaN and -Infinity next to "stable" before; now one line, exit 2."""
    args = {"--lam": "1", "--mu": "1", "--P": "1,-0.5,-0.5,0,0,0.8",
            "--Q": "0.6,-0.3,-0.3,0,0,-0.8", "--n": "1,0,0", "--g": "0.5"} | over
    argv = ["acoustic", *[f"{k}={v}" for k, v in args.items()], "--json"]
    code, out, err = _run_exit(capsys, argv)
    assert code == 2 and out == ""
    assert name in err and "Traceback" not in err and len(err.strip().splitlines()) == 1


@pytest.mark.parametrize("scale", [1e-250, 1e-30, 1e30, 1e250])
def test_acoustic_scale_invariance(capsys, scale):
    """lam, mu and g times s: moduli and eigenvalues times s; P times s, g times s: moduli times
    s, eigenvalues unchanged (eqs. 179-188 are homogeneous)."""
    P, Q, n = "1,-0.5,-0.5,0,0,0.8", "0.6,-0.3,-0.3,0,0,-0.8", "0.9,0.1,-0.2"

    def run(lam, mu, P, g):
        code, out, _ = _run(capsys, ["acoustic", f"--lam={lam!r}", f"--mu={mu!r}", f"--P={P}",
                                     f"--Q={Q}", f"--n={n}", f"--g={g!r}", "--json"])
        assert code == 0
        return _strict(out)

    ref = run(1.0, 1.0, P, 0.5)
    big = run(scale, scale, P, 0.5 * scale)
    assert big["g_localization"] == pytest.approx(scale * ref["g_localization"], rel=1e-12)
    assert big["flutter_interval"] == pytest.approx([scale * g for g in ref["flutter_interval"]],
                                                    rel=1e-12)
    assert _flat(big["eigenvalues"]) == pytest.approx(
        [scale * x for x in _flat(ref["eigenvalues"])], rel=1e-12)
    assert big["regime"] == ref["regime"]
    Ps = ",".join(repr(scale * float(x)) for x in P.split(","))
    bigP = run(1.0, 1.0, Ps, 0.5 * scale)
    assert bigP["g_localization"] == pytest.approx(scale * ref["g_localization"], rel=1e-12)
    assert _flat(bigP["eigenvalues"]) == pytest.approx(_flat(ref["eigenvalues"]), rel=1e-12)


def test_acoustic_agrees_with_the_tensor(capsys):
    """The scaled closed forms against numpy's eigenvalues of A(n), eq. (179)."""
    import numpy as np

    from flutterfriction.models import solid as so

    rng = np.random.default_rng(12)
    for _ in range(20):
        mu = float(rng.uniform(0.2, 3))
        lam = float(mu * rng.uniform(-0.6, 4))
        P, Q, n = rng.normal(size=6), rng.normal(size=6), rng.normal(size=3)
        g = float(rng.choice([-1, 1]) * 10 ** rng.uniform(-2, 2))
        g = abs(g)  # g > 0 (eq. 152; a negative g is refused), the same random stream
        code, out, _ = _run(capsys, ["acoustic", f"--lam={lam!r}", f"--mu={mu!r}",
                                     "--P=" + ",".join(map(str, P)),
                                     "--Q=" + ",".join(map(str, Q)),
                                     "--n=" + ",".join(map(str, n)), f"--g={g!r}", "--json"])
        assert code == 0
        res = _strict(out)
        nu = n / np.linalg.norm(n)
        A = so.acoustic_tensor_isotropic(lam, mu, so.voigt_to_tensor(P), so.voigt_to_tensor(Q),
                                         g, nu)
        expected = np.sort_complex(np.linalg.eigvals(A))
        got = np.sort_complex(np.array([complex(a, b) for a, b in res["eigenvalues"]]))
        assert np.abs(got - expected).max() <= 1e-10 * np.abs(expected).max()
        assert res["g_localization"] == pytest.approx(so.localization_modulus_isotropic(
            lam, mu, so.voigt_to_tensor(P), so.voigt_to_tensor(Q), nu), rel=1e-9, abs=1e-12)


def test_non_finite_result_is_an_error_not_printed(capsys, monkeypatch):
    """Strict JSON: a NaN reaching the output is reported (exit 1), never printed."""
    import flutterfriction.cli as cli

    monkeypatch.setattr(cli, "_acoustic", lambda args: {"g_localization": float("nan")})
    code, out, err = _run(capsys, [*ACOUSTIC, "--P=1,0,0,0,0,0"])
    assert code == 1 and out == "" and "not finite" in err and "g_localization" in err
    with pytest.raises(ValueError):
        cli._print({"x": float("inf")}, as_json=True)


@pytest.mark.parametrize("args", [
    ["rod", "--p", "10", "--mass-ratio", "1"],  # read as --p-max 10, silently (--P: a load)
    ["rod", "--mass-r", "1"],
    ["rod", "--mass-ratio", "1", "--js"],
])
def test_an_abbreviated_option_is_refused(capsys, args):
    """Outside audit: argparse took unique prefixes (`rod --p 10` for --p-max 10)."""
    code, out, err = _run_exit(capsys, args)
    assert code == 2 and out == "" and "unrecognized arguments" in err
    assert len(err.strip().splitlines()) == 1


def test_an_si_rod_at_the_mass_ratio_bound_is_decided_on_the_ratio_not_its_logarithm(capsys):
    """Outside audit: log10 M - log10 rho - log10 l = 4.000000000000001 refused a rod whose
    M/(rho l) is 9999.999999999998 (in [0, 1e4]); one above the bound names its value."""
    si = ["rod", "--length", "4.435087177140663", "--B", "1", "--rho", "5.008541189680321"]
    code, out, err = _run(capsys, [*si, "--tip-mass", "222133.16806532035", "--p-max", "20",
                                   "--json"])
    assert code == 0 and _strict(out)["groups"]["tan_alpha"] == pytest.approx(1e4, rel=1e-15)
    code, out, err = _run_exit(capsys, [*si, "--tip-mass", "222133.2", "--p-max", "20"])
    assert code == 2 and out == ""
    assert ("--tip-mass (with --length, --B, --rho): tan_alpha = M/(rho l) = 10000.00144 "
            "must be in [0, 10000]") in err


@pytest.mark.parametrize(("args", "name", "text"), [
    (["--D", "0"], "--D", "> 0"), (["--P", "1e6"], "--P", "flutter load"),
    (["--elements", "200"], "--elements", "1..16"), (["--P", "2"], "--P", "stable"),
    (["--t-max", "1e9"], "--t-max", "time scales"), (["--length", "1e300"], "--length", "1e+06"),
    (["--D", "1e3"], "--D", "eta"), (["--tip-mass", "1e300"], "--tip-mass", "100"),
    (["--kappa", "-1e-3"], "--kappa", ">= 0"), (["--B", "1e-300"], "--B", "1e-12"),
    (["--P", "3.0"], "--P", "2.96454"), (["--P", "3.3"], "--P", "--t-max >="),
    # outside audit: a tiny viscosity ran past 2 minutes (--D 1e-9) or was diagnosed as "does
    # not flutter" (--D 1e-20, a long soft rod); a slow approach blamed --P for --t-max
    (["--D", "1e-9"], "--D", "[0.0001, 1]"), (["--D", "1e-20"], "--D", "[0.0001, 1]"),
    (["--length", "1e6", "--B", "1e12", "--rho", "1e-12"], "--D", "[0.0001, 1]"),
    (["--D", "1.5e-6"], "--t-max", "--t-max >= 71"),
    (["--P", "3.0", "--t-max", "0.001"], "--t-max", "--t-max >="),
])
def test_limit_cycle_beck_refused_up_front(capsys, args, name, text):
    """Issue 12: --D 0, --P 1e6, --elements 200 hung; --P 3.0 said the motion decays (it grows,
    slowly). Now refused at once, naming the parameter and its range."""
    code, out, err = _run_exit(capsys, ["limit-cycle", "beck", *args, "--json"])
    assert code == 2 and out == ""
    assert name in err and text in err and "Traceback" not in err
    assert len(err.strip().splitlines()) == 1


def _fake_cycle(monkeypatch, calls, fail=False):
    import flutterfriction.analysis.rod_dynamics as rd
    from flutterfriction.errors import ConvergenceError

    class Cycle:
        transient_s, wall_s = 1.0, 0.1

        def as_dict(self):
            return {"tip_amplitude_m": 0.25, "period_s": 0.136}

    def fake(rod, P, **kw):
        calls.append(kw)
        kw["progress"]("rod, 4 elements, P = 5.5 N: t = 0.385 s, tail 1e-3")
        if fail:
            raise ConvergenceError("no rod limit cycle converged to 1e-05 within 31 s (P = 5.5 N;"
                                   " below the flutter load the motion decays)")
        return Cycle()

    monkeypatch.setattr(rd, "beck_limit_cycle", fake)


def test_limit_cycle_beck_progress_on_stderr(capsys, monkeypatch):
    """Issue 12: progress (what is integrated, simulated time, convergence) on stderr; stdout
    stays one strict JSON object; --quiet silences it."""
    calls = []
    _fake_cycle(monkeypatch, calls)
    code, out, err = _run(capsys, ["limit-cycle", "beck", "--json"])
    assert code == 0
    res = _strict(out)
    assert res["flutter_load_damped_N"] == pytest.approx(2.9645354, rel=1e-6)
    assert res["tip_amplitude_m"] == 0.25 and res["t_max_s"] == pytest.approx(31.419, rel=1e-4)
    assert "flutter load" in err and "t = 0.385 s" in err and "converged" in err
    assert calls[0]["t_max"] == pytest.approx(res["t_max_s"]) and calls[0]["tol"] == 1e-5
    code, out, err = _run(capsys, ["limit-cycle", "beck", "--quiet", "--json"])
    assert code == 0 and err == "" and _strict(out)["period_s"] == 0.136


def test_limit_cycle_beck_timeout_message_is_true(capsys, monkeypatch):
    """Above the flutter load the motion does not decay: the message says the approach is slow
    and what to give instead."""
    _fake_cycle(monkeypatch, [], fail=True)
    code, out, err = _run(capsys, ["limit-cycle", "beck", "--quiet", "--P", "4.5", "--json"])
    assert code == 1 and out == ""
    assert "decays" not in err and "--t-max" in err and "above the damped flutter load" in err


def test_version(capsys):
    from flutterfriction import __version__
    from flutterfriction.cli import main

    with pytest.raises(SystemExit) as exc:
        main(["--version"])
    assert exc.value.code == 0
    assert capsys.readouterr().out.strip() == f"flutterfriction {__version__}"


@pytest.mark.parametrize(("si", "load_unit", "time_scale"), [
    (["--length", "1", "--B", "1e-200", "--rho", "1e200"], 1e-200, 1e200),  # rho/B overflows
    (["--length", "1e-160", "--B", "1e-20", "--rho", "1e30"], 1e300, 1e-295),  # l^2 subnormal
])
def test_rod_si_units_at_the_ends_of_the_range(capsys, si, load_unit, time_scale):
    """Outside audit: rho/B = 1e400 overflowed into an internal error after half the text was
    printed, and l^2 = 1e-320 (a subnormal) gave P_flu_N wrong by 1e-5, silently. The SI units
    are now formed without overflow or underflow (models.rod.power_product)."""
    code, out, err = _run(capsys, ["rod", *si, "--json"])
    assert code == 0 and err == ""
    r = _strict(out)
    assert r["P_flu_N"] == pytest.approx(r["p_flu"] * load_unit, rel=1e-14)
    assert r["p_flu"] == pytest.approx(20.0509536, rel=1e-8)  # the Beck rod
    assert r["time_scale_s"] == pytest.approx(time_scale, rel=1e-14)
    code, out, err = _run(capsys, ["rod", *si])
    assert code == 0 and out.startswith("stable     p in [0, 20.05095362]")


@pytest.mark.parametrize("args", [
    [*_args(), "--k2", "1"],
    ["rod", "--mass-ratio", "1", "--mass-ratio", "2"],
    [*ACOUSTIC, "--n", "0", "1", "0"],
])
def test_an_option_given_twice_is_refused(capsys, args):
    """Outside audit: argparse kept the last of two values silently (--k2 0.189 ... --k2 1)."""
    code, out, err = _run_exit(capsys, args)
    assert code == 2 and out == "" and "given more than once" in err
    assert len(err.strip().splitlines()) == 1


@pytest.mark.parametrize(("args", "name", "text"), [
    # an empty field was dropped (--n 1,,0,0 read as 1 0 0)
    (["acoustic", "--lam", "1", "--mu", "1", "--P=-1,0.5,0.5,0,0,0.8",
      "--Q=0.6,-0.3,-0.3,0,0,-0.8", "--n", "1,,0,0", "--json"], "--n",
     "empty entry in '1,,0,0' (two commas in a row, or a leading or trailing comma): give 3 "
     "numbers separated by commas or spaces"),
    # a trailing comma gave argparse's "expected at least one argument"
    ([*ACOUSTIC, "--P", "-1,0.5,0.5,0,0,0.8,"], "--P", "empty entry in '-1,0.5,0.5,0,0,0.8,'"),
    ([*ACOUSTIC, "--P", ",-1,0.5,0.5,0,0,0.8"], "--P", "empty entry"),
    # Python's float() reads 1_000 as 1000: refused, plain decimal numbers only
    (_args(k1="1_000"), "--k1", "not a number: '1_000' (no '_' digit separators"),
    (["ziegler", *_args()[1:-1], "--k2", "-1_000"], "--k2", "not a number: '-1_000'"),
    (_args(k1="１"), "--k1", "not a number"),  # a full-width digit
    (["limit-cycle", "beck", "--elements", "1_6"], "--elements", "not an integer: '1_6'"),
])
def test_numbers_are_plain_and_lists_have_no_empty_entries(capsys, args, name, text):
    """Outside audit: `--n 1,,0,0` was accepted as 1 0 0, a trailing comma said "expected at
    least one argument", `--k1 1_000` was accepted as 1000."""
    code, out, err = _run_exit(capsys, args)
    assert code == 2 and out == "" and "Traceback" not in err
    assert f"argument {name}: {text}" in err and len(err.strip().splitlines()) == 1


def test_exponents_and_signs_still_read(capsys):
    code, out, _ = _run(capsys, [*_args(k1="1.89E-1", k2="+0.189"), "--json"])
    assert code == 0
    assert _strict(out)["P_flu"] == pytest.approx(4.8038120088, rel=1e-10)


def _no_integration(monkeypatch):
    import flutterfriction.analysis.rod_dynamics as rd

    class Accepted(Exception):
        pass

    def stub(rod, P, **kw):
        raise Accepted(kw)

    monkeypatch.setattr(rd, "beck_limit_cycle", stub)
    return Accepted


def test_limit_cycle_beck_refuses_a_run_beyond_its_cost_budget(capsys, monkeypatch):
    """Outside audit: `--D 5.3e-7 --t-max 314 --P 8.89` (eta = 1e-4, 3 P_flu, each inside its
    range) ran for 7 minutes (127 s simulated, 3.9 million right-hand sides, 1346 periods of
    history); the help promised about a minute. Refused up front, naming the options."""
    _no_integration(monkeypatch)
    code, out, err = _run_exit(capsys, ["limit-cycle", "beck", "--D", "5.3e-7", "--t-max",
                                        "314", "--P", "8.89", "--quiet", "--json"])
    assert code == 2 and out == "" and len(err.strip().splitlines()) == 1
    assert err.startswith("flutterfriction: error: --D, --P, --elements: this run is estimated "
                          "at 623 s of wall time, beyond the 100 s promised (201 s simulated")
    assert "give a larger --D" in err and "a lower --P (down to 1.86 P_flu = 5.514 N)" in err


@pytest.mark.parametrize(("args", "estimate"), [
    ([], 8.4),  # measured 8.4 s
    (["--elements", "16"], 47.4),  # the default t-max (31.4 s) on 16 elements: measured 34 s
    (["--P", "8.89"], 12.7),  # measured 14 s
    (["--D", "1.565e-6", "--t-max", "80"], 73.2),  # eta = 3e-4: measured 46 s
])
def test_limit_cycle_beck_accepts_runs_within_the_budget(capsys, monkeypatch, args, estimate):
    from flutterfriction import cli

    accepted = _no_integration(monkeypatch)
    seen = []
    real = cli.beck_cost_estimate
    monkeypatch.setattr(cli, "beck_cost_estimate", lambda *a: seen.append(real(*a)) or seen[-1])
    with pytest.raises(accepted):
        main(["limit-cycle", "beck", *args, "--quiet", "--json"])
    assert seen == [pytest.approx(estimate, abs=0.05)]


def test_the_cost_estimate_is_deterministic(monkeypatch):
    """From simulated time, periods, elements, eta and P only: no clock enters."""
    import time

    from flutterfriction.cli import BECK_BUDGET_S, beck_cost_estimate

    audit = (1279.29, 2060.84, 4, 1.0162e-4, 2.9989)
    first = beck_cost_estimate(*audit)
    for name in ("time", "perf_counter", "monotonic", "process_time"):
        monkeypatch.setattr(time, name, lambda: pytest.fail("the clock was read"))
    assert beck_cost_estimate(*audit) == first == pytest.approx(623.3, abs=0.05)
    assert first > BECK_BUDGET_S >= beck_cost_estimate(95.79, 158.96, 16, 1.357e-3, 1.855)


def test_acoustic_near_incompressible_limit_is_accurate_or_refused(capsys):
    """An outside audit: at lam/mu = 1e20 an eigenvalue came out with the wrong sign (k =
    (lam' + 1)/(lam' + 2) rounds at eps lam/mu). lam/mu is now limited to 1e8, where A =
    diag(mu, mu, lam + 2 mu - 0.6/g) for n = e3 is reproduced to 2e-9 (measured 1e-9)."""
    args = ["acoustic", "--mu", "1", "--P", "1,-0.5,-0.5,0,0,0.8", "--Q",
            "0.6,-0.3,-0.3,0,0,-0.8", "--n", "0,0,1", "--g", "1e-9", "--json"]
    assert main([*args, "--lam", "1e8"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["g_localization"] == pytest.approx(0.6 / (1e8 + 2), rel=2e-9)
    eig = sorted(e[0] for e in out["eigenvalues"])
    assert eig[1:] == pytest.approx([1.0, 1.0], rel=2e-9)
    assert eig[0] == pytest.approx(1e8 + 2 - 0.6e9, rel=1e-9)
    assert main([*args, "--lam", "1e9"]) == 2
    assert "lam/mu <= 1e+08" in capsys.readouterr().err


def test_model_errors_name_the_option_and_the_rod_help_states_the_group_ranges(capsys):
    from flutterfriction.cli import main

    for args, option in ((["--D", "-1"], "--D"), (["--tip-mass", "-1"], "--tip-mass")):
        assert main(["rod", "--length", "1", "--B", "1", "--rho", "1", *args]) == 2
        assert capsys.readouterr().err.startswith(f"flutterfriction: error: {option} must be ")
    # and the pendulum's (an outside audit: "l1 must be > 0 m" for --l1, "= 1e5.03")
    pendulum = ["--l2", "0.1", "--d", "0.0333", "--h", "0.0333", "--m1", "0.552", "--m2",
                "0.046", "--m3", "0.138", "--k1", "0.189", "--k2", "0.189"]
    assert main(["ziegler", "--l1", "-1", *pendulum]) == 2
    assert capsys.readouterr().err.startswith("flutterfriction: error: --l1 must be > 0 m")
    assert main(["ziegler", "--l1", "0.1", *pendulum, "--c1", "1000", "--c2", "0"]) == 2
    err = capsys.readouterr().err
    assert err.startswith("flutterfriction: error: --c1: the relative viscosity")
    assert "= 10^5.03 must be" in err
    with pytest.raises(SystemExit):
        main(["rod", "--help"])
    out = " ".join(capsys.readouterr().out.split())
    assert "tan(alpha), in [0, 10000]" in out and "internal viscosity, 0 or in [1e-100, 1]" in out


def test_the_command_line_computes_with_one_blas_thread(monkeypatch, capsys):
    """Outside audit: `rod --mass-ratio 0.5932505 --p-max 300` took 7.6 s with OpenBLAS's
    default threads on two cores, 1.1 s with one (the matrices are small; threads spin). The
    command runs with one BLAS thread unless the environment sets a count."""
    from threadpoolctl import threadpool_info, threadpool_limits

    import flutterfriction.cli as cli
    from flutterfriction.threads import THREAD_VARIABLES

    def blas_threads() -> set[int]:
        return {i["num_threads"] for i in threadpool_info() if i["user_api"] == "blas"}

    seen = []
    monkeypatch.setattr(cli, "_rod", lambda args: seen.append(blas_threads()) or {"p": 1.0})
    for name in THREAD_VARIABLES:
        monkeypatch.delenv(name, raising=False)
    with threadpool_limits(limits=2, user_api="blas"):
        if blas_threads() != {2}:
            pytest.skip("this machine's BLAS runs one thread only")
        assert cli.main(["rod", "--mass-ratio", "0", "--json"]) == 0
        monkeypatch.setenv("OPENBLAS_NUM_THREADS", "0")  # OpenBLAS's "default": no choice
        assert cli.main(["rod", "--mass-ratio", "0", "--json"]) == 0
        monkeypatch.setenv("OPENBLAS_NUM_THREADS", "2")  # the user's choice is kept
        assert cli.main(["rod", "--mass-ratio", "0", "--json"]) == 0
    assert seen == [{1}, {1}, {2}]


def test_a_full_disk_is_one_line_and_minus_zero_is_zero(capsys):
    """An outside audit: `> /dev/full` ended in an OSError traceback; `--h -0` was echoed as
    -0.0."""
    import os

    if not os.path.exists("/dev/full"):
        pytest.skip("no /dev/full here")
    with open("/dev/full", "w") as full:
        proc = subprocess.run([sys.executable, "-m", "flutterfriction", *_args(), "--json"],
                              stdout=full, stderr=subprocess.PIPE, text=True)
    assert proc.returncode == 1
    assert proc.stderr.strip() == ("flutterfriction: error: cannot write the result: No space "
                                   "left on device")
    code, out, _ = _run(capsys, [*_args(h="-0"), "--json"])
    assert code == 0 and '"h": 0.0' in out


@pytest.mark.parametrize(("over", "text"), [
    ({"k1": "1e308"}, "--k1, --k2: the ratio k1/k2"),
    ({"k2": "1e-300"}, "--k1, --k2: the ratio k1/k2"),
    ({"m1": "-0.3"}, "--m1 must be > 0 kg"),
])
def test_a_models_refusal_names_every_option_it_is_about(capsys, over, text):
    """Outside audit: a pair was named "--k1, k2" (the second without its dashes)."""
    code, out, err = _run_exit(capsys, _args(**over))
    assert code == 2 and out == "" and text in err and len(err.strip().splitlines()) == 1
