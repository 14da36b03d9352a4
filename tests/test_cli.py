"""The `flutterfriction` command: JSON surface, exit codes, one-line errors."""

from __future__ import annotations

import json
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
