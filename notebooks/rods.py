# ---
# jupyter:
#   jupytext:
#     text_representation:
#       extension: .py
#       format_name: percent
#   kernelspec:
#     display_name: Python 3
#     language: python
#     name: python3
# ---

# %% [markdown]
# # The Beck and Pflüger rods (chapter §2.5–2.8)
#
# Executed by the workflow into `results/reports/rods.html` from `results/data/` and
# `results/figures/`. Every number is also in `results/checks/summary.md`.

# %%
import json
import math
from pathlib import Path

from IPython.display import Image, Markdown, display

from flutterfriction.analysis.rod import critical_loads
from flutterfriction.models.rod import Rod, RodGroups
from flutterfriction.notebook_export import quantities_table
from flutterfriction.parameters import LIST_119
from flutterfriction.reference import own_parameters_note, own_parameters_summary

DATA, FIGS = Path("results/data"), Path("results/figures")


READ = {}  # scene -> the parameters its data was computed with
# a note, shown here, on scenes computed with your own parameters (filled by the last cell)
NOTE = display(Markdown(""), display_id=True)


def scene(name):
    data = json.loads((DATA / f"{name}.json").read_text())
    READ[name] = data.get("params")  # for the note on your own parameters (top)
    return data


def show(name, width=1000):
    display(Image(filename=str(FIGS / f"{name}.png"), width=width))


# %% [markdown]
# ## Figs. 6–9: the clamped elastica (§2.5–2.6)
#
# The chapter's sketches of the rod's kinematics, of the internal action at a cut and of the
# equilibrium of a part are drawn on one computed rod: the clamped elastica of Fig. 9, with $l$
# and $B$ of list (119), under the dead end force $\mathbf{P} = -P_1\mathbf{e}_1 -
# P_2\mathbf{e}_2$ and the uniform load $\mathbf{q} = q_1\mathbf{e}_1 + q_2\mathbf{e}_2$ (our
# values: the chapter gives none). At rest, eq. (91) is
# $B\theta'' + (P_1 - (l-s)q_1)\sin\theta - (P_2 - (l-s)q_2)\cos\theta = 0$ with
# $\theta(0) = 0$, $\theta'(l) = 0$. It is solved twice, by shooting on the end rotation
# $\theta(l)$ (Newton with the variational equations, loads applied in steps from the straight
# rod) and by collocation; with the end forces alone, eq. (92) is the pendulum equation in $s$
# and its classical solution by elliptic integrals is the third, closed-form check. For small
# loads the relative difference from the linear cantilever is $c\,\epsilon^2$, with $c$ from
# the perturbation of eq. (91) to third order.

# %%
el = scene("elastica")
loads, tip = el["loads"], el["tip_forces_only"]
display(Markdown(
    f"Loads: $P_1$ = {loads['P1']:g} N, $P_2$ = {loads['P2']:g} N, $q_1$ = {loads['q1']:g} N/m, "
    f"$q_2$ = {loads['q2']:g} N/m. The end turns by {math.degrees(el['tip_rotation']):.2f}°; "
    f"with the end forces alone by {math.degrees(tip['tip_rotation']):.2f}° (elliptic modulus "
    f"$k$ = {tip['modulus_k']:.6f}), where shooting and the closed form differ by at most "
    f"{tip['curve_error']:.1e} $l$ along the rod. Small loads: measured order "
    f"{el['linear_limit']['order']:.5f}, $c$ = {el['linear_limit']['coefficient']:.10f}."))
show("fig09")
show("fig06")
show("fig07")
show("fig08")
# residuals (quoted value 0: two round-offs): their absolute difference, not a relative one
display(Markdown(quantities_table(
    el["quantities"], digits=10,
    absolute=("part_eq87", "part_force_balance", "part_moment_balance",
              "tip_force_curve_error"))))

# %% [markdown]
# The balances of Figs. 7–8 are the chapter's equilibrium equations applied to the computed
# shape: eq. (89), the moment of the loads beyond a cut, equals the constitutive $B\theta'$ at
# every cut; eq. (74) holds for the part $[s_1, s_2]$; and eq. (87),
# $(\mathcal{N} + \mathcal{M}^2/2B)' = -\mathbf{q}\cdot\mathbf{t}$, the identity behind
# eqs. (100)–(101), holds integrated over the part. (With the end forces alone,
# $\mathbf{q} = 0$, $\mathcal{N} + \mathcal{M}^2/2B$ is constant along the rod: the tests
# check it.)

# %% [markdown]
# ## The linearised problem (eqs. 105–118)
#
# Small vibrations of the cantilever (bending stiffness $B$, Kelvin–Voigt viscosity $D$, mass
# $\rho$ per length, external damping $\kappa$, tip mass $M$, tangential follower force $P$) obey
# eq. (105); with the groups of eq. (106), $p = Pl^2/B$, $\tan\alpha = M/(\rho l)$,
# $\eta = D\sqrt{B/\rho}/(Bl^2)$, $\gamma = \kappa l^2/\sqrt{\rho B}$, and
# $v = \tilde v(\xi) e^{\tilde\omega\tau}$, nontrivial solutions exist where the function $f$ of
# eq. (118) vanishes. Three remarks on how we evaluate it:
#
# - for $\sin(\lambda_2\xi)$ in eq. (114) to be a solution, $\lambda_2^2$ must be *minus* the
#   second root of eq. (112) in $\lambda^2$; with that reading, $f = \det(115)/(\lambda_1\lambda_2)$
#   exactly (checked at 30 digits in the tests);
# - written with $\cosh\lambda_1$, $\sinh\lambda_1/\lambda_1$, $\cos\lambda_2$,
#   $\sin\lambda_2/\lambda_2$, $f$ is an entire, symmetric function of the two roots: analytic in
#   $\tilde\omega$, regular as $\lambda_{1,2}\to 0$;
# - the hyperbolic and trigonometric factors are evaluated scaled by
#   $e^{-|\mathrm{Re}\,\lambda_1| - |\mathrm{Im}\,\lambda_2|}$, so nothing overflows.
#
# Critical loads are solved as conditions (Newton on two real equations): a double root in
# $\mu = \tilde\omega^2$ without damping, a root $\tilde\omega = i\Omega$ with damping (flutter),
# a double real root (divergence). Initial guesses come from finite elements (cubic Hermite,
# scikit-fem), which are also the independent check.

# %%
rod119 = Rod(**LIST_119)  # list (119): flutterfriction.parameters
g = rod119.groups()
display(Markdown(f"List (119): $\\eta$ = {g.eta:.6g}, load unit $B/l^2$ = {rod119.load_unit:.6g} N, "
                 f"time unit $T$ = {rod119.time_scale:.6g} s; $P$ = 5.5 N is $p$ = "
                 f"{5.5 / rod119.load_unit:.4f}."))

# %% [markdown]
# ## Fig. 11: the Beck rod
#
# Without damping flutter occurs at $p = 20.05$ (Beck 1952); with the internal damping of list
# (119) at $p = 10.94$: dissipation lowers the flutter load. There is no divergence.

# %%
show("fig11")
display(Markdown(quantities_table(scene("fig11")["quantities"], digits=8)))

# %% [markdown]
# ## Fig. 12: the Pflüger rod, and an erratum
#
# The chapter states $M/(\rho l) = \tan\alpha = 1$. With that value the exact characteristic
# function gives loads that differ from the quoted ones; the quoted ones are reproduced,
# all four to their printed digits, only in a narrow window of $\tan\alpha$:

# %%
e = scene("errata_rods")
rows = "\n".join(
    f"| {k} | {e['errata'][k]['independent']} | {e['at_stated'][k]:.4f} | "
    f"{e['at_alpha_1_rad'][k]:.4f} | {e['at_inferred'][k]:.4f} | "
    f"[{e['windows'][k][0]:.5f}, {e['windows'][k][1]:.5f}] |" for k in e["errata"])
display(Markdown(
    "| load | quoted | tan α = 1 (stated) | α = 1 rad (tan α = 1.5574) | inferred tan α | "
    "window of tan α |\n|---|---|---|---|---|---|\n" + rows))
display(Markdown(f"All four windows intersect in tan α ∈ [{e['common_window'][0]:.5f}, "
                 f"{e['common_window'][1]:.5f}]; the figure is drawn at tan α = "
                 f"{scene('fig12')['cases']['undamped']['groups']['tan_alpha']:.5g}. A "
                 "plausible origin is α = 1 rad instead of tan α = 1: it reproduces both flutter "
                 "loads to the printed digits, and the divergence loads to 0.06%."))

# %%
show("fig12")

# %% [markdown]
# Internal damping strongly lowers the flutter load and slightly raises the divergence load:
# the flutter region widens.
#
# ## Finite elements against the exact function
#
# The FE flutter load converges at the rate $h^4$ expected of cubic Hermite elements; with 32
# elements it is within ~1e-6 (relative) of the exact value, at a cost of a few tenths of a
# second (this run's errors and times are in the figure and the work-precision table). The
# damped flutter load converges at $h^4$ too: each crossing is polished by Newton on the
# quadratic eigenproblem (located on the first-order spectrum's growth rate alone, it stalled
# at that spectrum's round-off, ~4e-9, from 32 elements on).

# %%
show("rod_fe_convergence")
display(Markdown("| case | convergence rate | constant | exact p_flu |\n|---|---|---|---|\n"
                 + "\n".join(f"| {name} | {c['rate']:.3f} | {c['constant']:.3g} | "
                              f"{c['exact']['p_flu']:.10g} |"
                              for name, c in scene("rod_fe_convergence")["cases"].items())))

# %% [markdown]
# ## The whole family: from Beck to Pflüger
#
# Flutter and divergence loads against the tip-mass ratio. With vanishing internal damping the
# flutter load drops well below the undamped one for every mass ratio: the rod's Ziegler paradox.

# %%
show("rod_stability_map", width=620)

# %% [markdown]
# ## §2.8 Self-adjointness
#
# For a dead load the FE operator is symmetric and eq. (126) vanishes on any pair of test
# functions satisfying the boundary conditions (121): no flutter, and the Beck rod buckles at
# $p = \pi^2/4 \approx 2.467$. For the follower load neither holds.

# %%
s = scene("self_adjoint")
display(Markdown(
    f"- relative asymmetry of the FE stiffness at p = {s['p_test']}: dead {s['asymmetry']['dead']:.2e}, "
    f"follower {s['asymmetry']['follower']:.2e}\n"
    f"- eq. (126): dead {s['eq126']['dead']:.2e}, follower {s['eq126']['follower']:.6f}\n"
    f"- dead-load buckling: FE {s['quantities']['dead_load_buckling']['value']:.10f}, "
    f"$\\pi^2/4$ = {math.pi**2 / 4:.10f}"))

# %% [markdown]
# ## Your own rod
# `flutterfriction rod --mass-ratio MU --eta ETA --gamma GAMMA --json`, or SI parameters:

# %%
own = RodGroups(tan_alpha=0.5, eta=2e-3, gamma=0.05)
loads = critical_loads(own, p_max=80.0)
display(Markdown(
    f"A rod with tan α = M/(ρl) = {own.tan_alpha:g}, internal damping η = {own.eta:g} and "
    f"external damping γ = {own.gamma:g} (dimensionless groups of eq. 106), loads searched up "
    f"to p = 80: flutter at p = {loads.p_flu:.6g} (pulsation ω̃ = {loads.omega_flu:.6g}), "
    + ("no divergence" if loads.p_div is None else f"divergence at p = {loads.p_div:.6g}")
    + "; regimes: " + ", ".join(f"{i['regime']} {i['p_from']:.4g}–{i['p_to']:.4g}"
                                for i in loads.intervals) + "."))


# %% [markdown]
# ## Your parameters
#
# The note at the top lists the scenes of this notebook that ran with other physical
# parameters than the chapter's (`workflow/config.yaml`), if any.

# %%
NOTE.update(Markdown(own_parameters_note(READ)))
display(Markdown(own_parameters_summary(READ)))
