"""The one list of scenes: what each computes, which figures draw it, with their chapter captions.

Everything that names scenes is derived from :data:`SCENES`: the workflow's solve and plot jobs
(``workflow/rules/scenes.smk``), the notebooks' inputs, the report's sections and captions, the
reproducibility check's list of figures that draw wall times, and the configuration check's
list of scene sections. Adding a scene is one :class:`Scene` entry here plus its functions
(``tests/test_registry.py`` proves it on a toy scene).

Entries hold the scenes' functions themselves (real imports) and the figures' plot functions
by import path (imported when drawn: reading the registry, which every ``snakemake`` call does,
imports no matplotlib). A workflow job does not import this module: it receives its function's
import path (:func:`flutterfriction.sources.import_path`) and imports that module only, so a
solve job does not pay for matplotlib or for every other scene's solvers.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from types import MappingProxyType
from typing import Any

from flutterfriction import scenes as _scenes
from flutterfriction.errors import ParameterError
from flutterfriction.scenes import (
    apparatus,
    rod,
    rod_statics,
    sketches,
    solids,
    ziegler,
    ziegler_damped,
    ziegler_nonlinear,
)
from flutterfriction.scenes import beck_branch as branch
from flutterfriction.scenes.sweep import Sweep
from flutterfriction.sources import import_path, module_file, resolve

#: The chapter's parts, in its order: the report's sections and the notebooks (same names).
PARTS = ("ziegler", "ziegler_paradox", "rods", "limit_cycles", "solids")


@dataclass(frozen=True)
class FigureSpec:
    """One figure: the function drawing it from its scene's data, and its caption (the
    chapter's, or what it shows beyond the chapter).

    ``function`` is the function itself or, for the package's figures, its import path
    (``"flutterfriction.plotting.rod:plot_fig11"``): the registry then does not import the
    plotting code (matplotlib), so the workflow's start-up, which reads the registry on every
    ``snakemake`` call, does not pay for it. :attr:`plot` imports it on first use."""

    function: Callable[[dict[str, Any]], Any] | str
    caption: str

    @property
    def plot(self) -> Callable[[dict[str, Any]], Any]:
        return resolve(self.function) if isinstance(self.function, str) else self.function

    @property
    def path(self) -> str:
        """The plot function's import path (without importing it)."""
        return self.function if isinstance(self.function, str) else import_path(self.function)

    @property
    def module(self) -> str:
        """The plot function's module (without importing it)."""
        return self.path.partition(":")[0]


@dataclass(frozen=True)
class Scene:
    """One computation and the figures drawn from its data.

    Attributes
    ----------
    name
        The scene's name: ``results/data/<name>.json`` and its section of
        ``workflow/config.yaml``.
    compute
        ``compute(params) -> dict``: the scene's data from its parameters (SI units).
    part
        The chapter part it belongs to (one of :data:`PARTS`): its notebook and report section.
    figures
        Figure name -> :class:`FigureSpec`, drawn from this scene's data (empty for tables,
        errata and statements, which the check and the notebooks show).
    sweep
        For a bifurcation diagram or a map: its points scatter over several jobs.
    slow
        Tens of seconds or more: started first, and given a longer cluster runtime.
    draws_wall_times
        Its figures draw measured wall times, so they differ from run to run (the data do not).
    check
        ``check(params)``: raises :class:`~flutterfriction.errors.ParameterError` for
        parameters ``compute`` would refuse only after costly work (a load outside the
        interval where a cycle exists, a motion too long to integrate); the workflow's
        configuration check calls it before any job, ``compute`` itself first thing.
    """

    name: str
    compute: Callable[[dict[str, Any]], dict[str, Any]]
    part: str
    figures: Mapping[str, FigureSpec] = field(default_factory=dict)
    sweep: Sweep | None = None
    slow: bool = False
    draws_wall_times: bool = False
    check: Callable[[dict[str, Any]], None] | None = None


def _fig(plot: str, caption: str) -> FigureSpec:
    """A figure of the package: ``plot`` is ``"<plotting module>:<function>"``."""
    return FigureSpec(f"flutterfriction.plotting.{plot}", caption)


_ENTRIES = [
    # §2.1–2.3 The Ziegler double pendulum
    Scene("fig01", sketches.fig01, "ziegler", {"fig01": _fig(
        "sketches:plot_fig01",
        "Fig. 1: a follower load on two rigid bars (exact kinematics) and on a clamped rod "
        "(small displacements), the states of their closed loops 1→2→3 and 1→2→3→4→1, and the "
        "work on each leg by quadrature: positive net work, zero on the rigid rotation and on "
        "the legs the caption names.")}, check=sketches.check_fig01),
    Scene("fig02", ziegler.fig02, "ziegler", {"fig02": _fig(
        "ziegler:plot_fig02",
        "Fig. 2: the Ziegler double pendulum (drawn by the same code as Fig. 4).")}),
    Scene("fig03", ziegler.fig03, "ziegler", {"fig03": _fig(
        "ziegler:plot_fig03",
        "Fig. 3: the line β1 − γβ2 and the parabola (β1 − γβ2)² − 4ka of eq. (34) for list "
        "(47), with the stable, flutter and divergence intervals.")}),
    Scene("fig04", ziegler.fig04, "ziegler", {"fig04": _fig(
        "ziegler:plot_fig04",
        "Fig. 4: configurations every 0.04 s of the linear motion, flutter (P = 6.8 N, 0.44 s) "
        "and divergence (P = 15.4 N, 0.2 s), from the exact matrix exponential.")},
          check=ziegler.check_fig04),
    Scene("eq25", ziegler.eq25, "ziegler", {"eq25": _fig(
        "ziegler:plot_eq25",
        "ω² against the dead load: H_cr = (3 − √5)/2 K/L ≈ 0.382 K/L (eq. 25).")}),
    Scene("eq46", ziegler.follower_load_scene, "ziegler", {"eq46": _fig(
        "ziegler:plot_eq46",
        "Re, Im ω² against the follower load: flutter at 2 K/L, divergence at 4 K/L "
        "(eq. 46).")}),
    Scene("eq47", ziegler.follower_load_scene, "ziegler", {"eq47": _fig(
        "ziegler:plot_eq47",
        "The same for the device of list (47): P_flu = 4.8038 N, P_div = 8.8042 N.")}),
    Scene("eq48", ziegler.follower_load_scene, "ziegler", {"eq48": _fig(
        "ziegler:plot_eq48",
        "The same for the mass distribution of eq. (48): 17/8 and 25/8 K/L.")}),
    Scene("errata_ziegler", ziegler.errata, "ziegler"),
    # §2.2, 2.4, 2.10 Viscosity and the Ziegler paradox
    Scene("fig05", ziegler_damped.fig05, "ziegler_paradox", {"fig05": _fig(
        "ziegler_damped:plot_fig05",
        "Fig. 5: Re and Im of ω̃ against γ, undamped and for ε = 0.1, 0.5 (eq. 51): flutter "
        "at 2, 1.338, 1.458 K/L.")}, check=ziegler_damped.check_fig05),
    Scene("paradox_limit", ziegler_damped.paradox_limit, "ziegler_paradox", {
        "paradox_limit": _fig(
            "ziegler_damped:plot_paradox_limit",
            "The damped flutter load as ε → 0 (log axis): it tends to 4/3 K/L, not to the "
            "undamped 2 K/L.")}, check=ziegler_damped.check_paradox_limit),
    Scene("fig18", apparatus.fig18, "ziegler_paradox", {"fig18": _fig(
        "apparatus:plot_fig18",
        "Fig. 18: the wheel at the pendulum's end on the sliding plate (top view, list (47) "
        "deflected: the force stays along BC) and the pendulum as a lever (side view, forces to "
        "scale): moment balance W a = R (b − μ r), P = μ R, checked against the lever's "
        "equilibrium as a linear system; μ, a, r are our choice. Red spirals: hinge springs; "
        "blue discs: masses.")}),
    Scene("fig19_theory", ziegler_damped.fig19_theory, "ziegler_paradox", {
        "fig19_theory": _fig(
            "ziegler_damped:plot_fig19_theory",
            "Fig. 19's theoretical bars for list (47), and the hinge viscosity inferred from "
            "the quoted ratios 0.70 and 1.49.")}, check=ziegler_damped.check_fig19_theory),
    Scene("paradox_map", ziegler_damped.paradox_map, "ziegler_paradox", {"paradox_map": _fig(
        "ziegler_damped:plot_paradox_map",
        "Beyond the chapter: vanishing-viscosity over undamped flutter load against c1/c2 and "
        "the mass distribution, with the curve where the paradox vanishes.")},
          check=ziegler_damped.check_paradox_map),
    Scene("damped_dead_load", ziegler_damped.damped_dead_load, "ziegler_paradox",
          check=ziegler_damped.check_damped_dead_load),
    Scene("errata_damped", ziegler_damped.errata_damped, "ziegler_paradox",
          check=ziegler_damped.check_errata_damped),
    # §2.5–2.8 The Beck and Pflüger rods
    Scene("elastica", rod_statics.elastica, "rods", {
        "fig06": _fig("rod_statics:plot_fig06",
                      "Fig. 6: the kinematics of an inextensible rod, drawn on the computed "
                      "elastica of Fig. 9: the point x0 e1 of the straight reference, its image "
                      "x = g(x0), the displacement u = x − x0 e1 (eq. 55), the tangent t, m and "
                      "n (eqs. 63, 69, 71), the rotation θ(s) and the arc length s = x0; "
                      "eqs. (65)–(66) and the curve's length from its positions checked."),
        "fig07": _fig("rod_statics:plot_fig07",
                      "Fig. 7: the computed rod ideally cut at s = l/2: the force a(s) and the "
                      "moment M(s) on the left part, −a(s) and −M(s) on the right (drawn apart "
                      "along t); M = Bθ' at every cut equals the moment of the loads beyond it "
                      "(eq. 89)."),
        "fig08": _fig("rod_statics:plot_fig08",
                      "Fig. 8: a part [s1, s2] of the computed rod as a free body under the "
                      "distributed load q, with a(s2), M(s2) and −a(s1), −M(s1): the force and "
                      "moment balances (eq. 74) and eq. (87) hold to round-off; N, T and M "
                      "along the rod."),
        "fig09": _fig("rod_statics:plot_fig09",
                      "Fig. 9: the clamped elastica of list (119) under the end forces P1, P2 "
                      "and the forces per unit length q1, q2 (geometrically exact, shooting "
                      "and collocation); the end forces alone against the closed form by "
                      "elliptic integrals; small loads approach the linear cantilever as the "
                      "load squared.")}, check=rod_statics.check_elastica),
    Scene("fig10", sketches.fig10, "rods", {"fig10": _fig(
        "sketches:plot_fig10",
        "Fig. 10: the Beck and the Pflüger (tan α = 1) rods with their modes at the exact "
        "critical loads of eq. (118) (Beck flutter p = 20.05; Pflüger flutter 16.21, divergence "
        "34.46), from the null vector of the boundary matrix; markers: the 32-element twin.")}),
    Scene("fig11", rod.fig11, "rods", {"fig11": _fig(
        "rod:plot_fig11",
        "Fig. 11: Re and Im of ω̃ against p for the Beck rod, without and with internal "
        "damping (list 119): flutter at p = 20.05 and 10.94.")}, check=rod.check_fig11),
    Scene("fig12", rod.fig12, "rods", {"fig12": _fig(
        "rod:plot_fig12",
        "Fig. 12: the Pflüger rod, side by side at the caption's tan α = 1 (flutter 16.21 / 7.91, "
        "divergence 34.46 / 34.86) and at the tip-mass ratio tan α = 1.5608 that reproduces the "
        "quoted 16.51 / 7.78 and 30.22 / 30.52 (the erratum).")}, check=rod.check_fig12),
    Scene("rod_fe_convergence", rod.rod_fe_convergence, "rods", {"rod_fe_convergence": _fig(
        "rod:plot_fe_convergence",
        "The finite-element twin: error of the flutter load and pulsation against elements "
        "(rate h⁴) and against run time.")}, slow=True, draws_wall_times=True),
    Scene("rod_stability_map", rod.rod_stability_map, "rods", {"rod_stability_map": _fig(
        "rod:plot_stability_map",
        "Beyond the chapter: flutter and divergence loads against the tip-mass ratio, "
        "undamped and with vanishing internal damping.")}, sweep=rod.ROD_STABILITY_MAP),
    Scene("errata_rods", rod.errata_rods, "rods", check=rod.check_errata_rods),
    Scene("self_adjoint", rod.self_adjoint, "rods"),
    # §2.9–2.11 Nonlinear dynamics and limit cycles
    Scene("fig13", ziegler_nonlinear.fig13, "limit_cycles", {"fig13": _fig(
        "ziegler_nonlinear:plot_fig13",
        "Fig. 13: the viscous Ziegler pendulum at P = 1.5 P*_flu reaching a stable limit cycle "
        "(α1 against α2).")}, check=ziegler_nonlinear.check_section29),
    Scene("fig14", ziegler_nonlinear.fig14, "limit_cycles", {"fig14": _fig(
        "ziegler_nonlinear:plot_fig14",
        "Fig. 14: angular velocities against rotations on the way to the limit cycle.")},
          check=ziegler_nonlinear.check_section29),
    Scene("beck_limit_cycle", rod.beck_limit_cycle, "limit_cycles", {
        "fig15": _fig("rod:plot_fig15",
                      "Fig. 15: the nonlinear Beck rod of list (119) at P = 5.5 N: the tip's "
                      "trajectory as flutter grows from the straight rod (a 1 mm flutter mode) "
                      "into the limit cycle (periodic-orbit Newton)."),
        "fig16": _fig("rod:plot_fig16", "Fig. 16: tip velocities against tip displacements."),
        "fig17": _fig("rod:plot_fig17",
                      "Fig. 17: the tip's lateral against axial velocity.")}, slow=True,
          check=rod.check_beck_limit_cycle),
    Scene("fig20", ziegler_nonlinear.fig20, "limit_cycles", {"fig20": _fig(
        "ziegler_nonlinear:plot_fig20",
        "Fig. 20: transverse acceleration of the loaded end, linear (blows up) against "
        "nonlinear (limit cycle), 6 s and a 1.5 s detail.")},
          check=ziegler_nonlinear.check_fig20),
    Scene("fig21", ziegler_nonlinear.fig21, "limit_cycles", {"fig21": _fig(
        "ziegler_nonlinear:plot_fig21",
        "Fig. 21: the path of the loaded end and the scratch it leaves on the moving "
        "plate.")}, check=ziegler_nonlinear.check_fig21),
    Scene("limit_cycle_amplitude", ziegler_nonlinear.limit_cycle_amplitude, "limit_cycles", {
        "limit_cycle_amplitude": _fig(
            "ziegler_nonlinear:plot_limit_cycle_amplitude",
            "Beyond the chapter: the pendulum's bifurcation diagram (amplitude ∝ √(P − P_flu), "
            "period → 2π/Ω_flu): a supercritical Hopf bifurcation.")},
          sweep=ziegler_nonlinear.LIMIT_CYCLE_AMPLITUDE,
          check=ziegler_nonlinear.check_limit_cycle_amplitude),
    Scene("beck_linearisation", rod.beck_linearisation, "limit_cycles", {
        "beck_linearisation": _fig(
            "rod:plot_beck_linearisation",
            "The nonlinear rod model linearised converges to the exact theory at h⁴: flutter "
            "loads, growth rate and frequency at 5.5 N.")}),
    Scene("beck_hopf", rod.beck_hopf, "limit_cycles", {"beck_hopf": _fig(
        "rod:plot_beck_hopf",
        "Beyond the chapter: the rod's limit cycles from the damped flutter load by "
        "periodic-orbit continuation, and their Floquet multipliers against the normal form: "
        "a supercritical Hopf bifurcation.")}, slow=True, check=rod.check_beck_hopf),
    Scene("beck_branch", branch.beck_branch, "limit_cycles", {"beck_branch": _fig(
        "beck_branch:plot_beck_branch",
        "Beyond the chapter: the rod's whole branch of limit cycles, from the Hopf point "
        "through the 5.5 N cycle of Figs. 15–17 to 7 N: tip amplitude and period against the "
        "load, stability from the Floquet multipliers, the onset normal form."),
        "beck_branch_shapes": _fig(
            "beck_branch:plot_beck_branch_shapes",
            "Beyond the chapter: the rod over one period of cycles of that branch (the "
            "amplitude's first maximum and the following minimum, the chapter's 5.5 N cycle, "
            "the last), its centre line at twelve instants coloured by the time through the "
            "period: the same swing at the amplitude's maximum and minimum, only smaller; past "
            "the dip the rod curls and its tip sweeps backwards.")}, slow=True,
          check=branch.check_beck_branch),
    Scene("beck_work_precision", rod.beck_work_precision, "limit_cycles", {
        "beck_work_precision": _fig(
            "rod:plot_beck_work_precision",
            "Work-precision of the rod's integrators on the cycle's return map: errors of "
            "period and tip amplitude over one period (LSODA, BDF, Radau, generalized-α).")},
          slow=True, draws_wall_times=True, check=rod.check_beck_work_precision),
    Scene("pendulum_work_precision", ziegler_nonlinear.pendulum_work_precision, "limit_cycles",
          slow=True, check=ziegler_nonlinear.check_pendulum_work_precision),
    # §3 Frictional solids
    Scene("fig22", solids.fig22, "solids", {"fig22": _fig(
        "solids:plot_fig22",
        "Fig. 22: one force path computed exactly through stick, slip, unloading and reverse "
        "slip (eq. 140), drawn three ways: two bricks after the first slip (point 3 of the "
        "path; N, T, the contact reaction on the friction cone, the upper brick shifted by the "
        "slip, to scale with a 0.5 m bar); the "
        "spring–slider model of §3.1 and its p_T–u_T response (slip onset at |p_T| = μ p_N, "
        "unloaded to p_T = 0 at u_T = u_T^s); the Coulomb cone with the normal a and the slip "
        "direction b.")}, check=solids.check_fig22),
    Scene("acoustic_eigenvalues", solids.acoustic_eigenvalues, "solids", {
        "acoustic_eigenvalues": _fig(
            "solids:plot_acoustic_eigenvalues",
            "Eigenvalues of the acoustic tensor against the plastic modulus g for a "
            "nonassociative case: the complex (flutter) pair between g1 and g2.")},
          check=solids.check_acoustic_eigenvalues),
    Scene("localization_directions", solids.localization_directions, "solids", {
        "localization_directions": _fig(
            "solids:plot_localization_directions",
            "The localization modulus over band directions, its maximum over the sphere, "
            "against Rudnicki and Rice (1975).")},
          check=solids.check_localization_directions),
    Scene("flutter_map", solids.flutter_map, "solids", {"flutter_map": _fig(
        "solids:plot_flutter_map",
        "Which directions flutter against g; and flutter triggered by a small elastic "
        "anisotropy at the coalescence of three eigenvalues.")},
          check=solids.check_flutter_map),
    Scene("fig23", sketches.fig23, "solids", {"fig23": _fig(
        "sketches:plot_fig23",
        "Fig. 23: twinning shear u = |x·f2| f1 (eq. 169) drawn on a lattice: the displacement "
        "is continuous across the plane f1, its gradient jumps by the rank-one 2 f1⊗f2 "
        "(eq. 171).")}),
    Scene("solids_statements", solids.solids_statements, "solids"),
    Scene("errata_solids", solids.errata_solids, "solids", check=solids.check_errata_solids),
]

#: Scene name -> :class:`Scene`, in the chapter's order (read-only).
SCENES: Mapping[str, Scene] = MappingProxyType({s.name: s for s in _ENTRIES})


def figures() -> dict[str, tuple[Scene, FigureSpec]]:
    """Figure name -> (the scene whose data it draws, its spec), in the chapter's order."""
    return {f: (s, spec) for s in SCENES.values() for f, spec in s.figures.items()}


def scenes_of(part: str) -> list[Scene]:
    """The scenes of one chapter part (one notebook, one report section)."""
    return [s for s in SCENES.values() if s.part == part]


def _defined(spec: FigureSpec) -> bool:
    """The figure's plot function exists: callable, or (an import path, checked without
    importing the plotting code) a module of the package with a top-level ``def`` of it."""
    if not isinstance(spec.function, str):
        return callable(spec.function)
    module, _, name = spec.function.partition(":")
    path = module_file(module)
    return bool(name) and path is not None and f"\ndef {name}(" in path.read_text("utf-8")


def check_registry(scenes: Mapping[str, Scene] = SCENES) -> list[str]:
    """Problems of a registry, one line each (names unique across scenes and figures, parts
    known, sweeps and figures well formed); empty when sound."""
    problems = []
    seen_figures: dict[str, str] = {}
    for name, s in scenes.items():
        if s.name != name:
            problems.append(f"scene {name!r} is registered under another name ({s.name!r})")
        if s.part not in PARTS:
            problems.append(f"scene {name!r}: unknown part {s.part!r}; parts: {list(PARTS)}")
        if not callable(s.compute):
            problems.append(f"scene {name!r}: compute is not callable")
        for f, spec in s.figures.items():
            if f in seen_figures:
                problems.append(f"figure {f!r} is drawn by {seen_figures[f]!r} and {name!r}")
            seen_figures[f] = name
            if f in scenes and f != name:
                problems.append(f"figure {f!r} of {name!r} has the name of another scene")
            if not _defined(spec) or not spec.caption:
                problems.append(f"figure {f!r}: a plot function and a caption are required")
    return problems


def scene(name: str) -> Scene:
    """The registered scene ``name`` (a one-line error naming the known scenes otherwise)."""
    if name not in SCENES:
        raise ParameterError(f"unknown scene {name!r}; known scenes: {sorted(SCENES)}")
    return SCENES[name]


def sweep_of(name: str) -> Sweep:
    sweep = scene(name).sweep
    if sweep is None:
        raise ParameterError(f"{name!r} is not a sweep; sweeps: "
                             f"{sorted(k for k, s in SCENES.items() if s.sweep)}")
    return sweep


def _plain(value: Any) -> Any:
    """``value`` with numpy scalars and arrays as the Python numbers and lists a configuration
    file gives (a sweep's ``np.int64`` or ``np.linspace`` row is a user's natural input; the
    schema knows only JSON's types), tuples as lists, mappings copied; anything else as is
    (the schema then names it)."""
    import numpy as np

    if isinstance(value, dict):
        return {k: _plain(v) for k, v in value.items()}
    if isinstance(value, list | tuple):
        return [_plain(v) for v in value]
    if isinstance(value, np.ndarray):
        return _plain(value.tolist())
    if isinstance(value, np.generic):
        return value.item()
    return value


def checked_params(name: str, params: dict[str, Any]) -> dict[str, Any]:
    """``params`` of scene ``name`` with its chapter lists named (``rod: list119``) resolved,
    refused before any work as the workflow's configuration check refuses them
    (:func:`flutterfriction.config.scene_problems`: the schema's types and ranges, non-finite
    numbers, the geometry, the scene's own check): a :class:`ParameterError` naming every
    offending key in one line. Numpy scalars and arrays are taken as the Python numbers and
    lists they hold (:func:`_plain`)."""
    from flutterfriction.config import expand_parameter_lists, scene_problems

    sc = scene(name)
    if not isinstance(params, dict):
        raise ParameterError(f"scenes.{name}: the parameters must be a mapping, got "
                             f"{type(params).__name__}")
    holder = {"scenes": {name: _plain(params)}}
    problems = expand_parameter_lists(holder)
    params = holder["scenes"][name]
    problems = problems or scene_problems(name, params, sc.check)
    if problems:
        raise ParameterError("; ".join(p.removeprefix("config: ") for p in problems))
    return params


def build_scene(name: str, params: dict[str, Any]) -> dict[str, Any]:
    """Compute scene ``name`` from its parameters (checked first: :func:`checked_params`);
    the result records the parameters it used."""
    return _scenes.build_scene(name, checked_params(name, params), scene(name).compute)


def build_scene_part(name: str, params: dict[str, Any], part: int, n_parts: int
                     ) -> dict[str, Any]:
    """Block ``part`` of ``n_parts`` of the sweep scene ``name`` (its parameters checked
    first, as :func:`build_scene`'s)."""
    sweep = sweep_of(name)
    return _scenes.build_scene_part(name, checked_params(name, params), part, n_parts, sweep)


def combine_scene_parts(name: str, params: dict[str, Any], parts: list[dict[str, Any]]
                        ) -> dict[str, Any]:
    """The sweep scene ``name`` gathered from its parts (same data as :func:`build_scene`)."""
    return _scenes.combine_scene_parts(name, params, parts, sweep_of(name))
