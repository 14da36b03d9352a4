"""The ``flutterfriction`` command: the stable surface for users and external checks.

``flutterfriction ziegler --l1 L1 --l2 L2 --d D --h H --m1 M1 --m2 M2 --m3 M3 --k1 K1 --k2 K2
[--c1 0 --c2 0] [--json]`` prints the critical follower loads (flutter ``P_flu``, divergence
``P_div``) for the given hinge viscosities, the same without viscosity (``P_flu_undamped``,
``P_div_undamped``) and the dead loads (``H_cr``, ``H_sup``, unaffected by viscosity) in newtons.
``flutterfriction rod --mass-ratio MU --eta ETA --gamma GAMMA [--json]`` prints the
dimensionless flutter and divergence loads ``p_flu``, ``p_div`` (eq. 106; ``null`` when there is
none, as for the Beck rod) and the pulsation ``omega_flu``; with SI parameters
(``--length --B --rho [--D --kappa --tip-mass]``) it also prints ``P_flu_N``, ``P_div_N``.

``flutterfriction acoustic --lam L --mu M --P p11,p22,p33,p23,p13,p12 --Q q11,... --n n1,n2,n3
[--g G] [--json]`` analyses the acoustic tensor of nonassociative elastoplasticity (§3.5,
isotropic elasticity, unit density): ``g_localization`` (eq. 185), ``flutter_interval``
(eq. 188 corrected, or null) and, with ``--g``, the ``eigenvalues`` as ``[re, im]`` pairs.

Bad input: one line naming the parameter on stderr, exit code 2, no traceback.
"""

from __future__ import annotations

import argparse
import json
import math
import sys
from collections.abc import Sequence

from flutterfriction.errors import ConvergenceError, ParameterError, check_nonnegative

ZIEGLER_PARAMS = {
    "l1": "length of rod AB [m], > 0",
    "l2": "length of rod BC [m], > 0",
    "d": "position of m1 on AB from A [m], 0 < d <= l1",
    "h": "position of m3 on BC from B [m], 0 <= h <= l2",
    "m1": "mass at D [kg], > 0",
    "m2": "mass at the loaded end C [kg], > 0",
    "m3": "mass at E [kg], >= 0",
    "k1": "rotational spring at A [N m/rad], > 0",
    "k2": "rotational spring at B [N m/rad], > 0",
}


class _Parser(argparse.ArgumentParser):
    def error(self, message: str) -> None:  # one line, exit code 2 (argparse's convention)
        self.exit(2, f"{self.prog}: error: {message}\n")


def _number(text: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"not a number: {text!r}") from None
    if not math.isfinite(value):
        raise argparse.ArgumentTypeError(f"must be finite, got {text!r}")
    return value


def _add_pendulum_arguments(parser: argparse.ArgumentParser) -> None:
    """The SI parameters of a Ziegler pendulum (shared by `ziegler` and `limit-cycle ziegler`)."""
    for name, text in ZIEGLER_PARAMS.items():
        parser.add_argument(f"--{name}", type=_number, required=True, help=text)


def build_parser() -> argparse.ArgumentParser:
    parser = _Parser(prog="flutterfriction",
                     description="Flutter from friction: reproducible stability analyses.")
    sub = parser.add_subparsers(dest="command", required=True, parser_class=_Parser)
    z = sub.add_parser(
        "ziegler", help="critical loads of a Ziegler double pendulum (SI units)",
        description="Critical loads of the Ziegler double pendulum (chapter §2.1-2.3): flutter "
                    "and divergence under a follower load, buckling under a dead load.")
    _add_pendulum_arguments(z)
    z.add_argument("--c1", type=_number, default=0.0,
                   help="hinge viscosity at A [N m s/rad], >= 0 (default 0)")
    z.add_argument("--c2", type=_number, default=0.0,
                   help="hinge viscosity at B [N m s/rad], >= 0 (default 0)")
    z.add_argument("--json", action="store_true", help="print one JSON object")
    r = sub.add_parser(
        "rod", help="critical loads of a Beck/Pflüger rod (dimensionless or SI)",
        description="Flutter and divergence loads of a cantilever with a tangential follower "
                    "force (chapter §2.7), from the exact characteristic function, eq. (118). "
                    "Give either the dimensionless groups of eq. (106) or SI parameters.")
    r.add_argument("--mass-ratio", type=_number, default=None,
                   help="tip-mass ratio M/(rho l) = tan(alpha), >= 0 (dimensionless mode)")
    r.add_argument("--eta", type=_number, default=None, help="internal viscosity, >= 0")
    r.add_argument("--gamma", type=_number, default=None, help="external damping, >= 0")
    r.add_argument("--length", type=_number, default=None, help="rod length [m], > 0 (SI mode)")
    r.add_argument("--B", type=_number, default=None, help="bending stiffness [N m^2], > 0")
    r.add_argument("--rho", type=_number, default=None, help="mass per length [kg/m], > 0")
    r.add_argument("--D", type=_number, default=None, help="Kelvin-Voigt viscosity [N m^2 s]")
    r.add_argument("--kappa", type=_number, default=None, help="external damping [N s/m^2]")
    r.add_argument("--tip-mass", type=_number, default=None, help="tip mass [kg], >= 0")
    r.add_argument("--p-max", type=_number, default=80.0,
                   help="largest dimensionless load searched (default 80)")
    r.add_argument("--json", action="store_true", help="print one JSON object")
    a = sub.add_parser(
        "acoustic", help="acoustic tensor of nonassociative elastoplasticity (§3.5)",
        description="Localization modulus, flutter interval and eigenvalues of the acoustic "
                    "tensor A(n) for isotropic elasticity (Lame constants), unit density, flow "
                    "mode P and yield gradient Q (symmetric, Voigt order 11,22,33,23,13,12).")
    a.add_argument("--lam", type=_number, required=True, help="Lame constant lambda [Pa]")
    a.add_argument("--mu", type=_number, required=True, help="shear modulus mu [Pa], > 0")
    a.add_argument("--P", type=_vector(6), required=True, help="p11,p22,p33,p23,p13,p12")
    a.add_argument("--Q", type=_vector(6), required=True, help="q11,q22,q33,q23,q13,q12")
    a.add_argument("--n", type=_vector(3), required=True, help="unit propagation direction")
    a.add_argument("--g", type=_number, default=None, help="plastic modulus g [Pa], != 0")
    a.add_argument("--json", action="store_true", help="print one JSON object")
    lc = sub.add_parser("limit-cycle", help="limit cycles of the nonlinear dynamics (§2.9)")
    lcs = lc.add_subparsers(dest="system", required=True, parser_class=_Parser)
    lz = lcs.add_parser(
        "ziegler", help="limit cycle of the Ziegler pendulum, eq. (10) with viscous hinges",
        description="Integrates eq. (10) from alpha1 = alpha2 = ALPHA0 until successive "
                    "crossings of the Poincare section agree to 1e-8, then confirms the orbit "
                    "by shooting. SI units.")
    _add_pendulum_arguments(lz)
    lz.add_argument("--c1", type=_number, required=True, help="hinge viscosity at A, > 0")
    lz.add_argument("--c2", type=_number, required=True, help="hinge viscosity at B, > 0")
    lz.add_argument("--P", type=_number, required=True, help="follower load [N]")
    lz.add_argument("--alpha0-deg", type=_number, default=0.1,
                    help="initial rotations alpha1 = alpha2 [deg] (default 0.1)")
    lz.add_argument("--json", action="store_true", help="print one JSON object")
    lb = lcs.add_parser(
        "beck", help="limit cycle of the nonlinear Beck rod (defaults: list (119))",
        description="Geometrically exact inextensible rod with a tangential follower force and "
                    "Kelvin-Voigt viscosity (P2 elements for the rotation), integrated until "
                    "the cycle on the Poincare section converges. SI units.")
    for name, default, text in (("P", 5.5, "follower load [N]"), ("length", 0.35, "[m]"),
                                ("B", 0.0332, "bending stiffness [N m^2]"),
                                ("rho", 0.0546, "mass per length [kg/m]"),
                                ("D", 7.078e-6, "Kelvin-Voigt viscosity [N m^2 s]"),
                                ("kappa", 0.0, "external damping [N s/m^2]"),
                                ("tip-mass", 0.0, "tip mass [kg]")):
        lb.add_argument(f"--{name}", type=_number, default=default,
                        help=f"{text} (default {default})")
    lb.add_argument("--elements", type=int, default=4, help="P2 elements (default 4)")
    lb.add_argument("--json", action="store_true", help="print one JSON object")
    return parser


def _limit_cycle_beck(args: argparse.Namespace) -> dict:
    from flutterfriction.analysis.rod_dynamics import beck_limit_cycle
    from flutterfriction.models.rod import Rod

    rod = Rod(length=args.length, B=args.B, rho=args.rho, D=args.D, kappa=args.kappa,
              tip_mass=args.tip_mass)
    if args.elements < 1:
        raise ParameterError(f"--elements must be >= 1, got {args.elements}")
    if not args.P > 0:
        raise ParameterError(f"--P must be > 0, got {args.P}")
    return beck_limit_cycle(rod, args.P, n_elements=args.elements, method="LSODA", rtol=1e-8,
                            atol=1e-10, tol=1e-5, initial_tip_rotation=1.2).as_dict()


def _limit_cycle(args: argparse.Namespace) -> dict:
    import math

    from flutterfriction.analysis.dynamics import limit_cycle, shoot_periodic_orbit
    from flutterfriction.models.ziegler import ZieglerPendulum

    pendulum = ZieglerPendulum(**{k: getattr(args, k) for k in (*ZIEGLER_PARAMS, "c1", "c2")})
    if pendulum.c1 <= 0 and pendulum.c2 <= 0:
        raise ParameterError("--c1/--c2: a limit cycle needs hinge viscosity (> 0)")
    a0 = math.radians(args.alpha0_deg)
    cycle = limit_cycle(pendulum, args.P, [a0, a0, 0.0, 0.0])
    check = shoot_periodic_orbit(pendulum, args.P, cycle)
    return {"alpha1_amplitude_rad": cycle.alpha1_amplitude_rad,
            "alpha2_amplitude_rad": cycle.alpha2_amplitude_rad, "period_s": cycle.period_s,
            "transient_s": cycle.transient_s,
            "shooting_check": {"period_s": check.period_s,
                               "alpha1_amplitude_rad": check.alpha1_amplitude_rad}}


def _vector(size: int):
    def parse(text: str) -> list[float]:
        parts = text.split(",")
        if len(parts) != size:
            raise argparse.ArgumentTypeError(f"needs {size} comma-separated numbers, got {text!r}")
        return [_number(x) for x in parts]
    return parse


def _acoustic(args: argparse.Namespace) -> dict:
    import numpy as np

    from flutterfriction.models import solid as so

    so.isotropic_elasticity(args.lam, args.mu)  # validates lam, mu (positive definite)
    P = so.voigt_to_tensor(args.P)
    Q = so.voigt_to_tensor(args.Q)
    n = np.asarray(args.n, dtype=float)
    norm = float(np.linalg.norm(n))
    if norm == 0:
        raise ParameterError("--n must be a non-zero vector (a unit propagation direction)")
    notes = []
    if abs(norm - 1) > 1e-9:
        notes.append(f"n normalised from |n| = {norm:.6g}")
        n = n / norm
    out = {"g_localization": so.localization_modulus_isotropic(args.lam, args.mu, P, Q, n),
           "flutter_interval": None, "notes": notes}
    interval = so.flutter_interval_isotropic(args.lam, args.mu, P, Q, n)
    if interval is not None:
        out["flutter_interval"] = list(interval)
    if args.g is not None:
        if args.g == 0:
            raise ParameterError("--g must be non-zero (the plastic modulus divides)")
        from flutterfriction.analysis.acoustic import classify_acoustic

        eta = so.acoustic_eigenvalues_isotropic(args.lam, args.mu, P, Q, args.g, n)
        out["eigenvalues"] = [[float(z.real), float(z.imag)] for z in eta]
        out["regime"] = str(classify_acoustic(
            so.acoustic_tensor_isotropic(args.lam, args.mu, P, Q, args.g, n)))
    return out


def _rod(args: argparse.Namespace) -> dict:
    from flutterfriction.analysis.rod import critical_loads
    from flutterfriction.models.rod import Rod, RodGroups

    si = {k: getattr(args, k) for k in ("length", "B", "rho", "D", "kappa", "tip_mass")}
    dimless = {"tan_alpha": args.mass_ratio, "eta": args.eta, "gamma": args.gamma}
    given_si = {k for k, v in si.items() if v is not None}
    given_dl = {k for k, v in dimless.items() if v is not None}
    if given_si and given_dl:
        raise ParameterError("give either --mass-ratio/--eta/--gamma or SI parameters "
                             "(--length --B --rho ...), not both")
    rod = None
    if given_si:
        missing = [f"--{k}" for k in ("length", "B", "rho") if si[k] is None]
        if missing:
            raise ParameterError(f"SI mode needs {', '.join(missing)}")
        rod = Rod(**{k: v for k, v in si.items() if v is not None})
        groups = rod.groups()
    else:
        names = {"tan_alpha": "--mass-ratio", "eta": "--eta", "gamma": "--gamma"}
        groups = RodGroups(**{k: (0.0 if v is None else check_nonnegative(names[k], v))
                              for k, v in dimless.items()})
    if not args.p_max > 0:
        raise ParameterError(f"--p-max must be > 0, got {args.p_max}")
    loads = critical_loads(groups, p_max=args.p_max)
    out = {**loads.as_dict(), "groups": vars(groups)}
    if rod is not None:
        u = rod.load_unit
        out["P_flu_N"] = None if loads.p_flu is None else loads.p_flu * u
        out["P_div_N"] = None if loads.p_div is None else loads.p_div * u
        out["time_scale_s"] = rod.time_scale
    return out


def _ziegler(args: argparse.Namespace) -> dict:
    from flutterfriction.analysis.ziegler import critical_loads
    from flutterfriction.models.ziegler import ZieglerPendulum

    pendulum = ZieglerPendulum(**{k: getattr(args, k) for k in (*ZIEGLER_PARAMS, "c1", "c2")})
    return {**critical_loads(pendulum).as_dict(), "units": "N",
            "parameters": pendulum.as_dict()}


def main(argv: Sequence[str] | None = None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        if args.command == "limit-cycle" and args.system == "beck":
            result = _limit_cycle_beck(args)
        else:
            result = {"ziegler": _ziegler, "rod": _rod, "acoustic": _acoustic,
                      "limit-cycle": _limit_cycle}[args.command](args)
    except ParameterError as exc:
        print(f"flutterfriction: error: {exc}", file=sys.stderr)
        return 2
    except ConvergenceError as exc:
        print(f"flutterfriction: solver did not converge: {exc}", file=sys.stderr)
        return 1
    try:
        _print(result, args.json)
    except BrokenPipeError:  # e.g. piped into `head`: not an error of ours
        sys.stderr.close()
    return 0


def _print(result: dict, as_json: bool) -> None:
    if as_json:
        print(json.dumps(result))
    elif "g_localization" in result or "period_s" in result:  # acoustic, limit cycles
        for key, value in result.items():
            print(f"{key} = {value}")
    elif "p_flu" in result:
        for key in ("p_flu", "omega_flu", "p_div", "omega_div", "P_flu_N", "P_div_N"):
            if key in result:
                value = result[key]
                print(f"{key:9s} = {'none' if value is None else f'{value:.10g}'}")
    else:
        names = {"P_flu": "flutter load (follower, given viscosity)",
                 "P_div": "divergence load (follower, given viscosity)",
                 "P_flu_undamped": "flutter load, viscosity absent",
                 "P_div_undamped": "divergence load, viscosity absent",
                 "H_cr": "critical dead load (any viscosity)",
                 "H_sup": "second dead buckling load"}
        for key, label in names.items():
            value = result[key]
            print(f"{key:14s} = {'none' if value is None else f'{value:.10g} N':>18s}  {label}")


if __name__ == "__main__":
    sys.exit(main())
