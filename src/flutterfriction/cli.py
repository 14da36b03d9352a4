"""The ``flutterfriction`` command: the stable surface for users and external checks.

``flutterfriction ziegler --l1 L1 --l2 L2 --d D --h H --m1 M1 --m2 M2 --m3 M3 --k1 K1 --k2 K2
[--c1 0 --c2 0] [--json]`` prints the critical follower loads (flutter ``P_flu``, divergence
``P_div``) for the given hinge viscosities, the same without viscosity (``P_flu_undamped``,
``P_div_undamped``) and the dead loads (``H_cr``, ``H_sup``, unaffected by viscosity) in newtons.
``flutterfriction rod --mass-ratio MU --eta ETA --gamma GAMMA [--json]`` prints the
dimensionless flutter and divergence loads ``p_flu``, ``p_div`` (eq. 106; ``null`` when there is
none, as for the Beck rod) and the pulsation ``omega_flu``; with SI parameters
(``--length --B --rho [--D --kappa --tip-mass]``) it also prints ``P_flu_N``, ``P_div_N``,
``Omega_flu_rad_s``, ``Omega_div_rad_s`` and ``time_scale_s``.

``flutterfriction acoustic --lam L --mu M --P p11,p22,p33,p23,p13,p12 --Q q11,... --n n1,n2,n3
[--g G] [--json]`` analyses the acoustic tensor of nonassociative elastoplasticity (§3.5,
isotropic elasticity, unit density): ``g_localization`` (eq. 185), ``flutter_interval``
(eq. 188 corrected, or null) and, with ``--g``, the ``eigenvalues`` as ``[re, im]`` pairs.
Vectors are numbers separated by spaces or commas, negative entries as typed
(``--P -1 0.5 0.5 0 0 0.8``); any scale is handled, results beyond 1e+-300 are refused.

``flutterfriction limit-cycle beck [--P 5.5 ...] [--t-max T] [--quiet] [--json]`` integrates the
nonlinear Beck rod to its limit cycle, after checking the load against the damped flutter load
of the linearised rod; progress goes to stderr unless ``--quiet``.

Bad input: one line naming the parameter on stderr, exit code 2, no traceback. ``--json``
prints strict JSON (a NaN or infinity would be an internal error, exit 1, never printed).
"""

from __future__ import annotations

import argparse
import contextlib
import json
import math
import re
import sys
from collections.abc import Iterable, Iterator, Sequence
from typing import Any

from flutterfriction.errors import (
    PLAIN_INTEGER,
    PLAIN_NUMBER,
    ConvergenceError,
    ParameterError,
    check_nonnegative,
    underflows,
)
from flutterfriction.models.rod import (
    CYCLE_ATTRACTION_SCALES,
    CYCLE_GAMMA_MAX,
    CYCLE_LOAD_MAX,
    CYCLE_T_MAX_DEFAULT_SCALES,
    CYCLE_T_MAX_SCALES,
    CYCLE_TIP_MASS_RATIO_MAX,
    GROUP_RANGES,
)
from flutterfriction.parameters import LIST_119, LIST_119_LOAD
from flutterfriction.threads import one_blas_thread

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


#: Ranges of `limit-cycle beck` (refused outside, before any integration): beyond them the
#: integration could run for hours or lose accuracy (absolute tolerances in SI units).
BECK_ELEMENTS = (1, 16)  # the chapter's meshes go to 16 (beck_limit_cycle scene)
BECK_LOAD_MAX = CYCLE_LOAD_MAX  # P / P_flu (models.rod)
BECK_ETA_MAX = 1.0  # as `rod`
BECK_GAMMA_MAX, BECK_TIP_MASS_RATIO_MAX = CYCLE_GAMMA_MAX, CYCLE_TIP_MASS_RATIO_MAX
#: The approach to the cycle is governed by the dissipation: measured on list (119) at 5.5 N
#: (4 elements, from the straight rod), converged at 14.6 s for eta = 1.36e-3, 35.6 s for
#: 5.75e-4 and 69.9 s for 2.9e-4 (tol 1e-5; 6, 11, 23 s of wall time): t ~ 0.13 T/eta,
#: T = l^2 sqrt(rho/B). BECK_ETA_MIN keeps a converging run within about a minute of wall
#: time (1300 T, ~200 s simulated for list 119); the audit's eta ~ 1e-7 ran past two minutes.
BECK_ATTRACTION_SCALES = CYCLE_ATTRACTION_SCALES  # t_need ~ BECK_ATTRACTION_SCALES T / eta
BECK_ETA_MIN = 1e-4
BECK_RANGES = {"length": (1e-6, 1e6, "m"), "B": (1e-12, 1e12, "N m^2"),
               "rho": (1e-12, 1e12, "kg/m")}
BECK_TOL = 1e-5  # the cycle's convergence tolerance (relative)
#: Largest estimated wall time of a `limit-cycle beck` run [s] (the help's promise: about a
#: minute, 100 s at most); a run estimated above it is refused before integrating. The
#: estimate (:func:`beck_cost_estimate`) is a model, not a clock: the same input gives the
#: same verdict on every machine.
BECK_BUDGET_S = 100.0
#: The model's constants, measured on list (119) (LSODA at rtol 1e-8, one BLAS thread, whole
#: runs): right-hand sides per time scale T ~720 n^0.44 on n elements (8480 a simulated second
#: on 4, 14600 on 16 elements at 5.5 N = 1.86 P_flu, eta = 1.36e-3); their cost with the
#: Jacobians and LU factors ~40 + 0.6 n^2 us (51 us on 4, 140-240 us on 16 elements); more
#: steps at higher loads, (P/1.86 P_flu)^1.1 (13800 a second at 3 P_flu), and below
#: eta = 1e-3, (1e-3/eta)^max(0.1, 0.23 (P/P_flu - 1.45)) (9450 a second at eta = 3e-4,
#: 1.86 P_flu; 30700 at eta = 1e-4, 3 P_flu: the outside audit's run); and the tip's history
#: (100 points a period, each found by a scan over the integration's pieces of 4 periods)
#: 2.4e-3 s a period plus 7e-5 s a period squared (0.8 s after 107 periods, 13 s after 498;
#: 200 s after 1346 on a loaded machine). Whole runs against the estimate: 8.4 s (est. 8.5),
#: 14 s at 3 P_flu (est. 13), 46 s at eta = 3e-4 (est. 73), 34 s on 16 elements (est. 47),
#: 72 s at 3 P_flu on 16 elements (est. 79), 442 s for the audit's run (est. 623: refused).
BECK_COST_RHS_PER_SCALE, BECK_COST_RHS_EXPONENT = 720.0, 0.44
BECK_COST_US_PER_RHS, BECK_COST_US_PER_RHS_N2 = 40.0, 0.6
BECK_COST_REF_LOAD_FACTOR, BECK_COST_LOAD_EXPONENT = 1.86, 1.1
BECK_COST_ETA_KNEE = 1e-3
BECK_COST_HISTORY_S, BECK_COST_HISTORY_S2 = 2.4e-3, 7e-5


#: How far [decades] a group's logarithm (a sum of logarithms, a few ulps off) may pass a range
#: bound before the CLI refuses it from the logarithm alone (see `_rod`).
LOG_SLACK = 1e-12


class _Parser(argparse.ArgumentParser):
    def __init__(self, *args: Any, **kwargs: Any) -> None:
        # No abbreviated options: `rod --p 10` was taken as --p-max 10, silently, where --P is
        # a load in the other commands (an outside audit)
        kwargs.setdefault("allow_abbrev", False)
        super().__init__(*args, **kwargs)

    def error(self, message: str) -> None:  # one line, exit code 2 (argparse's convention)
        self.exit(2, f"{self.prog}: error: {message}\n")


# Numbers as the options take them: errors.PLAIN_NUMBER / PLAIN_INTEGER (what float() accepts
# beyond them, such as 1_000 or full-width digits, is refused: a value is what it reads as).
_NON_FINITE = re.compile(r"[+-]?(?:inf|infinity|nan)", re.IGNORECASE)


def _number(text: str) -> float:
    word = text.strip()
    if _NON_FINITE.fullmatch(word):
        raise argparse.ArgumentTypeError(f"must be finite, got {text!r}")
    if not PLAIN_NUMBER.fullmatch(word):
        hint = " (no '_' digit separators: write the digits only)" if "_" in word else ""
        raise argparse.ArgumentTypeError(
            f"not a number: {text!r}{hint}; give a plain decimal number such as 0.5, -3 or "
            f"1.5e-3")
    value = float(word)
    if not math.isfinite(value):
        raise argparse.ArgumentTypeError(f"must be finite, got {text!r}")
    if underflows(word):
        raise argparse.ArgumentTypeError(f"{text!r} underflows to 0 in double precision "
                                         "(below 2.5e-324): give a value in the "
                                         "parameter's range")
    return value + 0.0  # -0 is 0 (it was echoed as -0.0; an outside audit)


def _integer(text: str) -> int:
    word = text.strip()
    if not PLAIN_INTEGER.fullmatch(word):
        hint = " (no '_' digit separators: write the digits only)" if "_" in word else ""
        raise argparse.ArgumentTypeError(f"not an integer: {text[:40]!r}{hint}")
    if len(word.lstrip("+-")) > 18:  # (5000 digits: Python's own conversion limit, echoed)
        raise argparse.ArgumentTypeError(f"an integer of {len(word.lstrip('+-'))} digits is "
                                         "beyond any allowed range")
    return int(word)


def _fields(text: str) -> list[str]:
    """The numbers of one command-line word, separated by commas (spaces around them allowed)
    or spaces; an empty field (``1,,0``, a leading or trailing comma) is kept, as ``""``."""
    return re.split(r"\s*,\s*|\s+", text.strip())


def _add_pendulum_arguments(parser: argparse.ArgumentParser) -> None:
    """The SI parameters of a Ziegler pendulum (shared by `ziegler` and `limit-cycle ziegler`)."""
    for name, text in ZIEGLER_PARAMS.items():
        parser.add_argument(f"--{name}", type=_number, required=True, help=text)


def build_parser() -> argparse.ArgumentParser:
    parser = _Parser(prog="flutterfriction",
                     description="Flutter from friction: reproducible stability analyses.")
    from flutterfriction import __version__

    parser.add_argument("--version", action="version", version=f"flutterfriction {__version__}")
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
    ranges = {k: f"in [0, {hi:g}]" if lo == 0 else f"0 or in [{lo:g}, {hi:g}]"
              for k, (lo, hi) in GROUP_RANGES.items()}
    r.add_argument("--mass-ratio", type=_number, default=None,
                   help=f"tip-mass ratio M/(rho l) = tan(alpha), {ranges['tan_alpha']} "
                        f"(dimensionless mode)")
    r.add_argument("--eta", type=_number, default=None,
                   help=f"internal viscosity, {ranges['eta']}")
    r.add_argument("--gamma", type=_number, default=None,
                   help=f"external damping, {ranges['gamma']}")
    r.add_argument("--length", type=_number, default=None, help="rod length [m], > 0 (SI mode)")
    r.add_argument("--B", type=_number, default=None, help="bending stiffness [N m^2], > 0")
    r.add_argument("--rho", type=_number, default=None, help="mass per length [kg/m], > 0")
    r.add_argument("--D", type=_number, default=None,
                   help="Kelvin-Voigt viscosity [N m^2 s], >= 0 (its group eta as --eta)")
    r.add_argument("--kappa", type=_number, default=None,
                   help="external damping [N s/m^2], >= 0 (its group gamma as --gamma)")
    r.add_argument("--tip-mass", type=_number, default=None, help="tip mass [kg], >= 0")
    r.add_argument("--p-max", type=_number, default=80.0,
                   help="largest dimensionless load searched, in (0, 1000] (default 80); "
                        "every stable/flutter/divergence interval up to it is reported "
                        "(--json key 'intervals')")
    r.add_argument("--json", action="store_true", help="print one JSON object")
    a = sub.add_parser(
        "acoustic", help="acoustic tensor of nonassociative elastoplasticity (§3.5)",
        description="Localization modulus, flutter interval and eigenvalues of the acoustic "
                    "tensor A(n) for isotropic elasticity (Lame constants), unit density, flow "
                    "mode P and yield gradient Q (symmetric, Voigt order 11,22,33,23,13,12). "
                    "Vectors are numbers separated by spaces or commas, negative entries as "
                    "typed: --P -1 0.5 0.5 0 0 0.8, --P -1,0.5,0.5,0,0,0.8 or "
                    "--P=-1,0.5,0.5,0,0,0.8. Computed in scaled quantities (lam/mu, P/max|P|, "
                    "Q/max|Q|): results must lie within [1e-300, 1e300] in magnitude, inputs "
                    "that would leave it are refused.")
    a.add_argument("--lam", type=_number, required=True,
                   help="Lame constant lambda [Pa], -2/3 < lam/mu <= 1e8, |lam| <= 1e300")
    a.add_argument("--mu", type=_number, required=True,
                   help="shear modulus mu [Pa], 1e-300 <= mu <= 1e300")
    vector = {"nargs": "+", "action": _VectorAction, "required": True}
    a.add_argument("--P", type=_vector(6), metavar="NUM", **vector,
                   help="flow mode: 6 numbers p11 p22 p33 p23 p13 p12 (spaces or commas)")
    a.add_argument("--Q", type=_vector(6), metavar="NUM", **vector,
                   help="yield gradient: 6 numbers q11 q22 q33 q23 q13 q12 (spaces or commas)")
    a.add_argument("--n", type=_vector(3), metavar="NUM", **vector,
                   help="propagation direction: 3 numbers n1 n2 n3, non-zero (normalised)")
    a.add_argument("--g", type=_number, default=None,
                   help="plastic modulus g [Pa], > 0 (eq. 152; a lower bound is stated if the "
                        "eigenvalues would exceed 1e300)")
    a.add_argument("--json", action="store_true", help="print one JSON object")
    lc = sub.add_parser("limit-cycle", help="limit cycles of the nonlinear dynamics (§2.9)")
    lcs = lc.add_subparsers(dest="system", required=True, parser_class=_Parser)
    lz = lcs.add_parser(
        "ziegler", help="limit cycle of the Ziegler pendulum, eq. (10) with viscous hinges",
        description="Integrates eq. (10) from alpha1 = alpha2 = ALPHA0 until successive "
                    "crossings of the Poincare section agree to 1e-8, then confirms the orbit "
                    "by shooting. SI units.")
    _add_pendulum_arguments(lz)
    lz.add_argument("--c1", type=_number, required=True,
                    help="hinge viscosity at A [N m s/rad], >= 0 (c1 or c2 > 0)")
    lz.add_argument("--c2", type=_number, required=True,
                    help="hinge viscosity at B [N m s/rad], >= 0 (c1 or c2 > 0)")
    lz.add_argument("--P", type=_number, required=True, help="follower load [N]")
    lz.add_argument("--alpha0-deg", type=_number, default=0.1,
                    help="initial rotations alpha1 = alpha2 [deg] (default 0.1)")
    lz.add_argument("--json", action="store_true", help="print one JSON object")
    lb = lcs.add_parser(
        "beck", help="limit cycle of the nonlinear Beck rod (defaults: list (119))",
        description="Geometrically exact inextensible rod with a tangential follower force and "
                    "Kelvin-Voigt viscosity (P2 elements for the rotation), integrated until "
                    "the cycle on the Poincare section converges (about 10 s for list (119), "
                    "at most a minute or two; progress on stderr unless --quiet). SI units. A "
                    "cycle exists only with viscosity (D > 0) and above the damped flutter "
                    "load P_flu of the linearised rod (2.9645 N for list (119), 4 elements), "
                    "computed first; loads too close to it, where the approach to the cycle "
                    "outlasts --t-max, are refused, and so is a run whose estimated wall time "
                    f"(from the simulated time, elements, eta and P; never the clock) exceeds "
                    f"{BECK_BUDGET_S:g} s.")
    for name, default, text in (
            ("P", LIST_119_LOAD, f"follower load [N], P_flu < P <= {BECK_LOAD_MAX:g} P_flu"),
            ("length", LIST_119["length"], "rod length l [m], 1e-6..1e6"),
            ("B", LIST_119["B"], "bending stiffness [N m^2], 1e-12..1e12"),
            ("rho", LIST_119["rho"], "mass per length [kg/m], 1e-12..1e12"),
            ("D", LIST_119["D"], f"Kelvin-Voigt viscosity [N m^2 s], > 0, with eta = "
                            f"D/(B l^2) sqrt(B/rho) in [{BECK_ETA_MIN:g}, {BECK_ETA_MAX:g}]"),
            ("kappa", 0.0, f"external damping [N s/m^2], >= 0, with gamma = kappa l^2/"
                           f"sqrt(rho B) <= {BECK_GAMMA_MAX:g}"),
            ("tip-mass", 0.0, f"tip mass [kg], 0..{BECK_TIP_MASS_RATIO_MAX:g} rho l")):
        lb.add_argument(f"--{name}", type=_number, default=default,
                        help=f"{text} (default {default})")
    lb.add_argument("--elements", type=_integer, default=4,
                    help=f"P2 elements, {BECK_ELEMENTS[0]}..{BECK_ELEMENTS[1]} (default 4)")
    lb.add_argument("--t-max", type=_number, default=None,
                    help=f"simulated time allowed for the cycle to converge [s], at most "
                         f"{CYCLE_T_MAX_SCALES:g} time scales l^2 sqrt(rho/B) (default "
                         f"{CYCLE_T_MAX_DEFAULT_SCALES:g} of them: 31.4 s for list (119))")
    lb.add_argument("--quiet", action="store_true",
                    help="no progress messages on stderr")
    lb.add_argument("--json", action="store_true", help="print one JSON object")
    return parser


def beck_cost_estimate(t_run_scales: float, periods: float, n_elements: int, eta: float,
                       load_factor: float) -> float:
    """Estimated wall time [s] of `limit-cycle beck` (see :data:`BECK_BUDGET_S` and the
    ``BECK_COST_*`` constants): ``t_run_scales`` time scales T simulated, ``periods`` cycle
    periods in them, on ``n_elements`` P2 elements at ``eta`` and P = ``load_factor`` P_flu.
    Deterministic: from simulated time, steps, elements, eta and P only, never the clock."""
    stiff = max(1.0, load_factor / BECK_COST_REF_LOAD_FACTOR) ** BECK_COST_LOAD_EXPONENT
    stiff *= max(1.0, BECK_COST_ETA_KNEE / eta) ** max(0.1, 0.23 * (load_factor - 1.45))
    rhs = t_run_scales * BECK_COST_RHS_PER_SCALE * n_elements ** BECK_COST_RHS_EXPONENT * stiff
    us_per_rhs = BECK_COST_US_PER_RHS + BECK_COST_US_PER_RHS_N2 * n_elements ** 2
    return (rhs * us_per_rhs * 1e-6 + BECK_COST_HISTORY_S * periods
            + BECK_COST_HISTORY_S2 * periods ** 2)


def _limit_cycle_beck(args: argparse.Namespace) -> dict:
    """Checks every parameter against the ranges of `BECK_*` and the load against the damped
    flutter load of the linearised rod (cheap: eigenvalues of a few small matrices) before
    integrating; progress on stderr unless ``--quiet``."""
    import time

    import numpy as np
    from scipy.optimize import brentq

    from flutterfriction.analysis.rod_cycles import linearised_flutter_load
    from flutterfriction.analysis.rod_dynamics import beck_limit_cycle, check_cycle_load
    from flutterfriction.models.rod import Rod
    from flutterfriction.models.rod_nonlinear import NonlinearRod

    lo, hi = BECK_ELEMENTS
    if not lo <= args.elements <= hi:
        raise ParameterError(f"--elements must be in {lo}..{hi}, got {args.elements}")
    for name, (a, b, unit) in BECK_RANGES.items():
        if not a <= getattr(args, name) <= b:
            raise ParameterError(f"--{name} must be in [{a:g}, {b:g}] {unit}, "
                                 f"got {getattr(args, name)!r}")
    if not args.D > 0:
        raise ParameterError(f"--D must be > 0 N m^2 s: without viscosity the rod's motion is "
                             f"reversible and has no attracting limit cycle, got {args.D!r}")
    for option, value in (("--kappa", args.kappa), ("--tip-mass", args.tip_mass)):
        if not value >= 0:
            raise ParameterError(f"{option} must be >= 0, got {value!r}")
    rod = Rod(length=args.length, B=args.B, rho=args.rho, D=args.D, kappa=args.kappa,
              tip_mass=args.tip_mass)
    T = rod.time_scale
    if not 1e-4 <= T <= 1e4:
        raise ParameterError(f"--length, --B, --rho: the time scale l^2 sqrt(rho/B) must be in "
                             f"[1e-4, 1e4] s (the integrator's absolute tolerances are in SI "
                             f"units), got {T:.3g} s")
    groups = rod.groups()  # eq. (106), formed without overflow or underflow
    for option, value, limit, text in (
            ("--D", groups.eta, BECK_ETA_MAX, "eta = D/(B l^2) sqrt(B/rho)"),
            ("--kappa", groups.gamma, BECK_GAMMA_MAX, "gamma = kappa l^2/sqrt(rho B)"),
            ("--tip-mass", groups.tan_alpha, BECK_TIP_MASS_RATIO_MAX, "M/(rho l)")):
        if not value <= limit:
            raise ParameterError(f"{option}: {text} must be <= {limit:g}, got {value:.4g}")
    if not groups.eta >= BECK_ETA_MIN:  # before the linearised rod: its onset is then unresolved
        raise ParameterError(
            f"--D: eta = D/(B l^2) sqrt(B/rho) must be in [{BECK_ETA_MIN:g}, {BECK_ETA_MAX:g}], "
            f"got {groups.eta:.4g}: the cycle attracts at a rate ~ eta (it needs ~"
            f"{BECK_ATTRACTION_SCALES:g}/eta time scales l^2 sqrt(rho/B), measured), beyond the "
            f"largest --t-max below {BECK_ETA_MIN:g}")
    t_limit = CYCLE_T_MAX_SCALES * T
    t_max = CYCLE_T_MAX_DEFAULT_SCALES * T if args.t_max is None else args.t_max
    if not 0 < t_max <= t_limit:
        raise ParameterError(f"--t-max must be in (0, {t_limit:.4g}] s ({CYCLE_T_MAX_SCALES:g} "
                             f"time scales l^2 sqrt(rho/B) = {T:.4g} s), got {t_max!r}")
    if not args.P > 0:
        raise ParameterError(f"--P must be > 0 N, got {args.P!r}")
    t_need_eta = BECK_ATTRACTION_SCALES * T / groups.eta
    if t_need_eta / 2 > t_max:
        raise ParameterError(
            f"--t-max = {t_max:.4g} s is too short for eta = {groups.eta:.3g}: the cycle attracts "
            f"at a rate ~ eta and needs roughly {t_need_eta:.3g} s of simulated time "
            f"({BECK_ATTRACTION_SCALES:g}/eta time scales, measured); give --t-max >= "
            f"{min(t_need_eta, t_limit):.3g} s (at most {t_limit:.4g} s) or a larger --D")

    M, C, K, K1 = NonlinearRod(rod, args.elements).linear_matrices()
    try:
        P_flu = linearised_flutter_load(rod, args.elements)
    except ParameterError as exc:
        raise ParameterError(f"--D, --kappa, --tip-mass: {exc}") from None
    check_cycle_load(rod, args.P, args.elements, "--P", P_flu)
    P_top = BECK_LOAD_MAX * P_flu
    Minv = np.linalg.inv(M)
    n = M.shape[0]

    def growth(P: float) -> float:  # max Re s of the linearised rod at load P [1/s]
        A = np.block([[np.zeros((n, n)), np.eye(n)], [-Minv @ (K + P * K1), -Minv @ C]])
        return float(np.linalg.eigvals(A).real.max())

    # Near a Hopf point the cycle attracts at about twice the linear growth rate sigma, so
    # converging from an O(1) distance to 1e-5 takes ~t_need = ln(1e4)/(2 sigma) (list 119 at
    # 3.3 N: t_need = 188 s, converged at 145 s); far from onset the approach is slower than
    # this. Refused when even half of it exceeds t_max: such a run could only fail.
    sigma = growth(args.P)
    above = 100 * (args.P / P_flu - 1)
    t_need = math.log(1e4) / (2 * sigma)
    if t_need / 2 > t_max:
        hints = []
        sigma_need = math.log(1e4) / (4 * t_max)
        if growth(P_top) > sigma_need:
            P_ok = brentq(lambda p: growth(p) - sigma_need, args.P, P_top, xtol=1e-6 * P_top)
            hints.append(f"--P >= {P_ok:.4g} N")
        if t_need <= t_limit:
            hints.append(f"--t-max >= {t_need:.3g} s")
        t_need_top = math.log(1e4) / (2 * growth(P_top))
        if not hints and t_need_top / 2 <= t_limit:  # the user's --t-max is the obstacle
            raise ParameterError(
                f"--t-max = {t_max:.4g} s is too short: at --P = {args.P:g} N the cycle needs "
                f"roughly {t_need:.3g} s of simulated time, and even at {BECK_LOAD_MAX:g} "
                f"P_flu = {P_top:.4g} N roughly {t_need_top:.3g} s; give a larger --t-max "
                f"(at most {t_limit:.4g} s) and, if that is not enough, a larger --P")
        if not hints:
            raise ParameterError(
                f"--P: this rod grows too slowly up to {BECK_LOAD_MAX:g} P_flu = {P_top:.4g} N "
                f"({growth(P_top):.3g} 1/s) for a cycle to converge within the largest "
                f"--t-max, {t_limit:.4g} s")
        raise ParameterError(
            f"--P = {args.P:g} N is only {above:.3g}% above the damped flutter load "
            f"{P_flu:.6g} N: the motion grows at {sigma:.3g} 1/s there, so the cycle needs "
            f"roughly {t_need:.3g} s of simulated time, far beyond --t-max = {t_max:.4g} s; "
            f"give {' or '.join(hints)}")

    # The cost, before integrating: the run lasts until the cycle converges (t_need, t_need_eta
    # above) or t_max, with a period of about the linear flutter mode's.
    t_run = min(t_max, max(t_need, t_need_eta))
    A = np.block([[np.zeros((n, n)), np.eye(n)], [-Minv @ (K + args.P * K1), -Minv @ C]])
    ev = np.linalg.eigvals(A)
    period = 2 * math.pi / max(abs(ev[np.argmax(ev.real)].imag), 1e-300)
    cost = beck_cost_estimate(t_run / T, t_run / period, args.elements, groups.eta,
                              args.P / P_flu)
    if cost > BECK_BUDGET_S:
        hints = {"--D": "a larger --D (eta: a faster approach, fewer steps)"}
        if args.P > BECK_COST_REF_LOAD_FACTOR * P_flu:
            hints["--P"] = (f"a lower --P (down to {BECK_COST_REF_LOAD_FACTOR:g} P_flu = "
                            f"{BECK_COST_REF_LOAD_FACTOR * P_flu:.4g} N)")
        if args.elements > 1:
            hints["--elements"] = "fewer --elements"
        raise ParameterError(
            f"{', '.join(hints)}: this run is estimated at {cost:.3g} s of wall time, beyond "
            f"the {BECK_BUDGET_S:g} s promised ({t_run:.3g} s simulated, ~{t_run / period:.3g} "
            f"periods, on {args.elements} elements at eta = {groups.eta:.3g} and P = "
            f"{args.P / P_flu:.3g} P_flu: small eta and high loads need more steps); give "
            f"{' or '.join(hints.values())}")

    say = _progress_printer(args.quiet)
    say(f"damped flutter load P_flu = {P_flu:.6g} N ({args.elements} P2 elements); "
        f"integrating the nonlinear rod at P = {args.P:g} N ({above:.3g}% above) until the "
        f"Poincare section converges to {BECK_TOL:g}, at most {t_max:.4g} s simulated")
    last = {"t": -math.inf}

    def progress(message: str) -> None:  # at most one line a second (each crossing is heard)
        now = time.monotonic()
        if now - last["t"] >= 1.0:
            last["t"] = now
            say(message)

    try:
        cycle = beck_limit_cycle(rod, args.P, n_elements=args.elements, method="LSODA",
                                 rtol=1e-8, atol=1e-10, tol=BECK_TOL, t_max=t_max,
                                 initial_tip_rotation=1.2, progress=progress)
    except ConvergenceError as exc:
        if not str(exc).startswith("no rod limit cycle converged"):
            raise
        raise ConvergenceError(
            f"no limit cycle converged to {BECK_TOL:g} within --t-max = {t_max:.4g} s of "
            f"simulated time: P = {args.P:g} N is {above:.3g}% above the damped flutter load "
            f"{P_flu:.6g} N, where the motion grows at {sigma:.3g} 1/s, and the approach to "
            f"the cycle is slow; give a larger --t-max (at most {t_limit:.4g} s) or a larger "
            f"--P") from None
    say(f"converged at t = {cycle.transient_s:.4g} s simulated ({cycle.wall_s:.3g} s)")
    return {**cycle.as_dict(), "P_N": args.P, "flutter_load_damped_N": P_flu,
            "t_max_s": t_max}


def _progress_printer(quiet: bool):
    def say(message: str) -> None:
        if not quiet:
            print(f"flutterfriction: {message}", file=sys.stderr, flush=True)
    return say


def _limit_cycle(args: argparse.Namespace) -> dict:
    """``limit-cycle ziegler``: refuses --alpha0-deg outside 0 < |alpha0| <= 180 and --P outside
    the damped flutter interval (P_flu, P_div) before any integration; near P_flu the cycle is
    continued from the linear flutter mode (see ``analysis.dynamics.ziegler_limit_cycle``)."""
    import math

    from flutterfriction.analysis.dynamics import ziegler_limit_cycle
    from flutterfriction.models.ziegler import ZieglerPendulum

    pendulum = ZieglerPendulum(**{k: getattr(args, k) for k in (*ZIEGLER_PARAMS, "c1", "c2")})
    if pendulum.c1 <= 0 and pendulum.c2 <= 0:
        raise ParameterError("--c1/--c2: a limit cycle needs hinge viscosity (> 0)")
    if not 0 < abs(args.alpha0_deg) <= 180:
        raise ParameterError(f"--alpha0-deg must be non-zero and within half a turn, "
                             f"0 < |alpha0| <= 180, got {args.alpha0_deg:g}")
    return ziegler_limit_cycle(pendulum, args.P, math.radians(args.alpha0_deg), P_name="--P",
                               alpha0_name="--alpha0-deg")


def _vector(size: int):
    """Type of an option taking ``size`` numbers: each command-line word is a number or a list
    of numbers separated by commas (or spaces, when quoted); :class:`_VectorAction` gathers the
    words (``nargs="+"``) and checks the count."""
    def parse(text: str) -> list[float]:
        parts = _fields(text)
        if "" in parts:
            raise argparse.ArgumentTypeError(
                f"empty entry in {text!r} (two commas in a row, or a leading or trailing "
                f"comma): give {size} numbers separated by commas or spaces")
        return [_number(x) for x in parts]
    parse.vector_size = size
    parse.__name__ = f"{size} numbers"
    return parse


class _VectorAction(argparse.Action):
    def __call__(self, parser, namespace, values, option_string=None):
        flat = [x for word in values for x in word]
        size = self.type.vector_size
        if len(flat) != size:
            short = " (a word that is not a number ends the list)" if len(flat) < size else ""
            raise argparse.ArgumentError(
                self, f"needs {size} numbers (separated by spaces or commas), got "
                      f"{len(flat)}{short}")
        setattr(namespace, self.dest, flat)


def _words_of_numbers(word: str) -> int:
    """How many numbers ``word`` holds (``-1``, ``-1e-3``, ``-1,0.5``, ``nan``...), 0 if it is
    not a list of numbers. Loose on purpose: a word that only *looks* like numbers (``1_000``,
    ``-1,0.5,`` with an empty entry) is gathered too, so that the option's type refuses it by
    name rather than argparse taking ``-1,...`` for an unknown option."""
    parts = [x for x in _fields(word) if x]
    try:
        for x in parts:
            float(x)
    except ValueError:
        return 0
    return len(parts)


def _numeric_options(parser: argparse.ArgumentParser) -> dict[str, int]:
    """Option string -> how many numbers it takes (1 for ``_number``), for one (sub)parser."""
    out = {}
    for action in parser._actions:
        size = getattr(action.type, "vector_size", 1 if action.type is _number else 0)
        for option in action.option_strings if size else ():
            out[option] = size
    return out


def _subcommands(parser: argparse.ArgumentParser) -> dict[str, argparse.ArgumentParser]:
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            return dict(action.choices)
    return {}


def _numeric_argv(parser: argparse.ArgumentParser, argv: Sequence[str]) -> list[str]:
    """Joins each numeric option with the numbers that follow it (``--P -1 0.5 ...``,
    ``--P -1,0.5,...``, ``--lam -1e-3``) into one ``--P=-1,0.5,...`` word: argparse alone takes
    a word starting with ``-`` for an option unless it is a plain negative number like ``-1``.
    Only words that are numbers are gathered: as many as a scalar option takes, every one that
    follows a vector option (whose action checks the count)."""
    out: list[str] = []
    current, i, argv = parser, 0, list(argv)
    while i < len(argv):
        word = argv[i]
        i += 1
        if word == "--":
            out.extend(argv[i - 1:])
            break
        subs = _subcommands(current)
        if word in subs:
            current = subs[word]
            out.append(word)
            continue
        name, eq, value = word.partition("=")
        options = _numeric_options(current)
        size = options.get(name, 0) if name.startswith("--") else 0
        if not size:
            out.append(word)
            continue
        words = [value] if value else []  # "--P=" alone: the numbers follow
        count = _words_of_numbers(value) if value else 0
        # a vector option gathers every number that follows (its count is then checked: a 7th
        # number to --P was "unrecognized arguments: 7", naming no option; an outside audit)
        while (count < size or size > 1) and i < len(argv):
            k = _words_of_numbers(argv[i])
            if not k or (size == 1 and k > 1):
                break
            words.append(argv[i])
            count += k
            i += 1
        out.append(f"{name}={','.join(words)}" if words else word)
    return out


def _acoustic(args: argparse.Namespace) -> dict:
    from flutterfriction.analysis.acoustic import isotropic_acoustic

    r = isotropic_acoustic(args.lam, args.mu, args.P, args.Q, args.n, args.g,
                           names={k: f"--{k}" for k in ("lam", "mu", "P", "Q", "n", "g")})
    out = {"g_localization": r.g_localization,
           "flutter_interval": None if r.flutter_interval is None else list(r.flutter_interval),
           "notes": list(r.notes)}
    if r.eigenvalues is not None:
        out["eigenvalues"] = [[z.real, z.imag] for z in r.eigenvalues]
        out["regime"] = str(r.regime)
    return out


def _rod(args: argparse.Namespace) -> dict:
    """Critical loads and regime intervals of a Beck/Pflüger rod (eqs. 106-118), refusing
    groups outside :data:`analysis.rod.GROUP_RANGES` and SI input whose groups or units leave
    the floating-point range (computed in logarithms, so that nothing overflows first)."""
    from flutterfriction.analysis.rod import GROUP_RANGES, P_MAX_LIMIT, check_groups, critical_loads
    from flutterfriction.models.rod import Rod, RodGroups

    si = {k: getattr(args, k) for k in ("length", "B", "rho", "D", "kappa", "tip_mass")}
    dimless = {"tan_alpha": args.mass_ratio, "eta": args.eta, "gamma": args.gamma}
    given_si = {k for k, v in si.items() if v is not None}
    given_dl = {k for k, v in dimless.items() if v is not None}
    if given_si and given_dl:
        raise ParameterError("give either --mass-ratio/--eta/--gamma or SI parameters "
                             "(--length --B --rho ...), not both")
    if not 0 < args.p_max <= P_MAX_LIMIT:
        raise ParameterError(f"--p-max must be in (0, {P_MAX_LIMIT:g}], got {args.p_max}")
    rod = None
    names = {"tan_alpha": "--mass-ratio", "eta": "--eta", "gamma": "--gamma"}
    if given_si:
        missing = [f"--{k}" for k in ("length", "B", "rho") if si[k] is None]
        if missing:
            raise ParameterError(f"SI mode needs {', '.join(missing)}")
        rod = Rod(**{k: v for k, v in si.items() if v is not None})  # finite, signs
        lg = {k: math.log10(getattr(rod, k)) if getattr(rod, k) > 0 else None
              for k in ("length", "B", "rho", "D", "kappa", "tip_mass")}
        ll, lB, lr = lg["length"], lg["B"], lg["rho"]
        # Eq. (106) in decimal logarithms: (option, group, text, log10 of the value or None).
        log_groups = (
            ("--D", "eta", "D/(B l^2) sqrt(B/rho)",
             None if lg["D"] is None else lg["D"] - 0.5 * lB - 2 * ll - 0.5 * lr),
            ("--kappa", "gamma", "kappa l^2/sqrt(rho B)",
             None if lg["kappa"] is None else lg["kappa"] + 2 * ll - 0.5 * lr - 0.5 * lB),
            ("--tip-mass", "tan_alpha", "M/(rho l)",
             None if lg["tip_mass"] is None else lg["tip_mass"] - lr - ll))
        # (a sum of logarithms is a few ulps off: at a bound, e.g. M/(rho l) exactly 10^4, it
        # read 10^4.000000000000001 and refused the bound itself; an outside audit. Within
        # LOG_SLACK of a bound the group formed directly is checked below instead.)
        for option, name, text, lv in log_groups:
            low, high = GROUP_RANGES[name]
            if lv is not None and (lv > math.log10(high) + LOG_SLACK
                                   or (low > 0 and lv < math.log10(low) - LOG_SLACK)):
                allowed = f"in [0, {high:g}]" if low == 0 else f"0 or in [{low:g}, {high:g}]"
                # (the value itself where a float holds it: "10^4" read as inside [0, 10000])
                value = f"{10.0**lv:.10g}" if abs(lv) < 300 else f"10^{lv:.6g}"
                raise ParameterError(f"{option} (with --length, --B, --rho): {name} = {text} = "
                                     f"{value} must be {allowed} (eq. 106)")
        # The SI units of the answer must be normal floats too (P = p B/l^2, t = T tau).
        for text, lv in (("the load unit B/l^2 [N]", lB - 2 * ll),
                         ("the time scale l^2 sqrt(rho/B) [s]", 2 * ll + 0.5 * (lr - lB))):
            if not -300 <= lv <= 300:
                raise ParameterError(f"--length, --B, --rho: {text} = 10^{lv:.4g} must be in "
                                     f"[1e-300, 1e300] (double precision)")
        groups = rod.groups()  # in range (above); formed without overflow or underflow
        try:  # exactly, at the bounds the logarithms could not decide
            check_groups(groups)
        except ParameterError as exc:
            name = str(exc).split(" ", 1)[0]
            option = {g: o for o, g, _, _ in log_groups}.get(name, name)
            raise ParameterError(f"{option} (with --length, --B, --rho): {exc}") from None
    else:
        groups = RodGroups(**{k: (0.0 if v is None else check_nonnegative(names[k], v))
                              for k, v in dimless.items()})
        try:
            check_groups(groups)
        except ParameterError as exc:
            name = str(exc).split(" ", 1)[0]
            raise ParameterError(f"{names.get(name, name)}: {exc}") from None
    loads = critical_loads(groups, p_max=args.p_max)
    out = {**loads.as_dict(), "groups": vars(groups)}
    if rod is not None:
        u = rod.load_unit
        out["P_flu_N"] = None if loads.p_flu is None else loads.p_flu * u
        out["P_div_N"] = None if loads.p_div is None else loads.p_div * u
        # the pulsations in rad/s: omega~ is per time scale l^2 sqrt(rho/B) (eq. 106)
        T = rod.time_scale
        out["Omega_flu_rad_s"] = None if loads.omega_flu is None else loads.omega_flu / T
        out["Omega_div_rad_s"] = None if loads.omega_div is None else loads.omega_div / T
        out["time_scale_s"] = T
    return out


def _ziegler(args: argparse.Namespace) -> dict:
    from flutterfriction.analysis.ziegler import critical_loads
    from flutterfriction.models.ziegler import ZieglerPendulum

    pendulum = ZieglerPendulum(**{k: getattr(args, k) for k in (*ZIEGLER_PARAMS, "c1", "c2")})
    return {**critical_loads(pendulum).as_dict(), "units": "N",
            "parameters": pendulum.as_dict()}


def _refuse_repeated_options(parser: argparse.ArgumentParser, argv: Sequence[str]) -> None:
    """An option given twice (``--k2 0.189 ... --k2 1``) is refused, naming it: argparse would
    silently keep the last. (Abbreviations are refused by the parsers: allow_abbrev=False.)"""
    options: set[str] = set()
    stack = [parser]
    while stack:
        p = stack.pop()
        options |= {o for a in p._actions for o in a.option_strings if o.startswith("--")}
        stack += _subcommands(p).values()
    seen: set[str] = set()
    for word in argv:
        if word == "--":
            break
        if not word.startswith("--"):
            continue
        name = word.split("=", 1)[0]
        if name in seen:
            parser.error(f"{name} given more than once")
        seen.add(name)


@contextlib.contextmanager
def _as_options(names: Iterable[str]) -> Iterator[None]:
    """A model's :class:`ParameterError` about one of ``names`` (its message starts with the
    field's name, e.g. ``tip_mass must be >= 0 kg``) named as the option the user typed
    (``--tip-mass must be >= 0 kg``)."""
    try:
        yield
    except ParameterError as exc:
        message, fields = str(exc), set(names)
        # the leading names, "k1:" or a pair "k1, k2:" (an outside audit: "--k1, k2: ...")
        head = re.match(r"(\w+(?:, \w+)*)(?=[:\s])", message)
        keys = head.group(1).split(", ") if head else []
        if keys and all(k in fields for k in keys):
            named = ", ".join("--" + k.replace("_", "-") for k in keys)
            raise ParameterError(named + message[head.end():]) from None
        raise


def main(argv: Sequence[str] | None = None) -> int:
    parser = build_parser()
    words = _numeric_argv(parser, sys.argv[1:] if argv is None else argv)
    _refuse_repeated_options(parser, words)
    args = parser.parse_args(words)
    try:
        # a model's message about one of its fields names the option typed (--tip-mass)
        with _as_options(vars(args)), one_blas_thread():
            if args.command == "limit-cycle" and args.system == "beck":
                result = _limit_cycle_beck(args)
            else:
                result = {"ziegler": _ziegler, "rod": _rod, "acoustic": _acoustic,
                          "limit-cycle": _limit_cycle}[args.command](args)
    except ParameterError as exc:  # one line, whatever the message holds (e.g. an array)
        print(f"flutterfriction: error: {' '.join(str(exc).split())}", file=sys.stderr)
        return 2
    except ConvergenceError as exc:
        print(f"flutterfriction: solver did not converge: {' '.join(str(exc).split())}",
              file=sys.stderr)
        return 1
    where = _non_finite(result)
    if where is not None:  # a bug at the source: say so rather than print NaN or inf
        print(f"flutterfriction: internal error: {where} is not finite (not printed)",
              file=sys.stderr)
        return 1
    try:
        _print(result, args.json)
        sys.stdout.flush()  # a write error shows here, not at exit (with a traceback)
    except BrokenPipeError:  # e.g. piped into `head`: not an error of ours
        sys.stderr.close()
    except OSError as exc:  # e.g. a full disk (`> /dev/full`): one line, not a traceback
        print(f"flutterfriction: error: cannot write the result: {exc.strerror or exc}",
              file=sys.stderr)
        return 1
    return 0


def _non_finite(value: object, where: str = "result") -> str | None:
    """The path of the first NaN or infinity in ``value`` (dicts, lists, floats), or None."""
    if isinstance(value, dict):
        items = ((f"{where}[{k!r}]", v) for k, v in value.items())
    elif isinstance(value, (list, tuple)):
        items = ((f"{where}[{i}]", v) for i, v in enumerate(value))
    else:
        return None if not isinstance(value, float) or math.isfinite(value) else where
    for path, item in items:
        found = _non_finite(item, path)
        if found is not None:
            return found
    return None


def _print(result: dict, as_json: bool) -> None:
    if as_json:
        print(json.dumps(result, allow_nan=False))
    elif "g_localization" in result or "period_s" in result:  # acoustic, limit cycles
        for key, value in result.items():
            print(f"{key} = {value}")
    elif "p_flu" in result:  # the rod: the intervals first, one a line, then the loads
        for iv in result["intervals"]:
            print(f"{iv['regime']:10s} p in [{iv['p_from']:.10g}, {iv['p_to']:.10g}]")
        for key in ("p_flu", "omega_flu", "p_div", "omega_div", "P_flu_N", "P_div_N",
                    "Omega_flu_rad_s", "Omega_div_rad_s", "time_scale_s"):
            if key in result:
                value = result[key]
                print(f"{key:15s} = {'none' if value is None else f'{value:.10g}'}")
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
