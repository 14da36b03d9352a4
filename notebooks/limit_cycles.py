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
# # Beyond linearisation: limit cycles (chapter §2.9–2.11)
#
# Executed by the workflow into `results/reports/limit_cycles.html`: the viscous Ziegler
# pendulum (Figs. 13, 14, 20, 21) and the nonlinear Beck rod (Figs. 15–17, its Hopf bifurcation
# and its integrators).

# %%
import json
from pathlib import Path

import numpy as np
from IPython.display import Image, Markdown, display

from flutterfriction.io import merge_timings
from flutterfriction.notebook_export import quantities_table
from flutterfriction.reference import own_parameters_note, own_parameters_summary

DATA, FIGS = Path("results/data"), Path("results/figures")


READ = {}  # scene -> the parameters its data was computed with
# a note, shown here, on scenes computed with your own parameters (filled by the last cell)
NOTE = display(Markdown(""), display_id=True)


def scene(name):
    """A scene's data, with its wall-clock timings (kept in results/benchmarks/) merged back."""
    data = json.loads((DATA / f"{name}.json").read_text())
    READ[name] = data.get("params")  # for the note on your own parameters (top)
    timings = Path("results/benchmarks") / f"{name}.timings.json"
    return merge_timings(data, json.loads(timings.read_text()) or None)


def show(name, width=620):
    display(Image(filename=str(FIGS / f"{name}.png"), width=width))


# %% [markdown]
# ## §2.9 The viscous Ziegler pendulum reaches a stable limit cycle
#
# Eq. (10) with hinge viscosity is integrated (DOP853, rtol 1e-11) from
# $\alpha_1 = \alpha_2 = 0.1°$ at $P = 1.5 P^*_{flu}$ (eq. 54), for $l_1 = l_2 = 0.1$ m,
# $k_1 = k_2 = 0.189$ N m, $c_1 = c_2 = 0.006$ N m s, $m_1 = m_2 = 0.2$ kg, $m_3 = 0$, $d = l_1$.
# The limit cycle is detected on the Poincaré section $\dot\alpha_1 = 0$ (downwards): the run
# stops when successive crossings agree to 1e-8. A periodic-orbit solve by shooting (Newton on
# the flow map over one period, independent of the transient) confirms it. The figures draw
# the same motion sampled by LSODA (rtol 1e-11; within 1e-8 of DOP853 at rtol 1e-13).

# %%
d = scene("fig14")
lc = d["limit_cycle"]
display(Markdown(
    f"P*_flu = {d['P_star_flu']:.6f} N, P = {d['P']:.6f} N. Limit cycle: period "
    f"{lc['period_s']:.10f} s, amplitudes {lc['alpha1_amplitude_rad']:.10f} rad and "
    f"{lc['alpha2_amplitude_rad']:.10f} rad ({np.degrees(lc['alpha1_amplitude_rad']):.2f}°, "
    f"{np.degrees(lc['alpha2_amplitude_rad']):.2f}°), reached after {lc['transient_s']:.1f} s."))
display(Markdown(quantities_table(d["quantities"])))
show("fig13", width=480)
show("fig14", width=480)

# %% [markdown]
# ## §2.10 Fig. 20: linear against nonlinear
#
# The device of list (47) with the hinge viscosity that reproduces Fig. 19's ratios
# (c1 = c2 = 0.006 N m s). "A load in the middle of the flutter region" is taken as the
# midpoint of the flutter interval *of this viscous model* (from the damped flutter load to
# the damped divergence load), because that is the model whose flutter region the experiment
# probes; the midpoint of the undamped interval (6.8 N, the load of Fig. 4) would be the other
# reading. The linear solution grows without bound (cut at 1.5 s); the nonlinear one settles on
# a limit cycle.

# %%
d20 = scene("fig20")
display(Markdown(f"P = {d20['P']:.4f} N, the middle of [{d20['P_flu']:.4f}, {d20['P_div']:.4f}] N."))
show("fig20", width=900)

# %% [markdown]
# ## Fig. 21: the scratch
#
# From $\alpha = 0$ with angular velocities 0.5 rad/s, over 2.04 s, at the same load. The plate
# slides under the wheel (100 mm/s) so that the friction on the wheel points towards A; in the
# plate's frame the wheel therefore advances by $v t$ along $\mathbf e_1$.

# %%
show("fig21", width=900)

# %% [markdown]
# ## §2.9 Figs. 15–17: the nonlinear Beck rod
#
# A geometrically exact, inextensible rod: the unknown is the rotation $\theta(s)$ on P2
# elements, the position is $\int_0^s(\cos\theta, \sin\theta)$, the tip carries the follower
# force $-P\mathbf t(l)$, and the Kelvin–Voigt moment $B\theta' + D\dot\theta'$ (eq. 83) gives
# the viscous term. Linearised about the straight rod it converges to the exact flutter loads of
# the rods report at the rate $h^4$ (undamped), so the nonlinear model starts from the right
# linear theory. At $P$ = 5.5 N (list 119) the rod reaches a limit cycle; the chapter notes that
# it is "a closed loop, which is rather flat and therefore hardly visible" (Fig. 15).
#
# Integrators: the Kelvin–Voigt modes make the system stiff (their decay rate grows like $N^4$),
# so an explicit method (DOP853) pays for the finer meshes in steps (it is the study's
# reference on 4 elements only), while LSODA (which switches to a stiff method), BDF, Radau and
# the generalized-α structural integrator (the ABAQUS-style choice) do not; their measured
# cost and accuracy, this run's, are in the work-precision section below.

# %%
show("beck_linearisation")
q = scene("beck_linearisation")["quantities"]
display(Markdown(f"At 5.5 N with 32 elements: growth rate {q['growth_rate']['value']:.8f} 1/s "
                 f"(exact {q['growth_rate']['independent']:.8f}), frequency "
                 f"{q['frequency']['value']:.8f} rad/s (exact {q['frequency']['independent']:.8f})."))

# %%
d = scene("beck_limit_cycle")
c, f = d["cycle"], d["cycle_fine"]
m1, m2 = d["meshes"][-2], d["meshes"][-1]
display(Markdown(
    f"The figures' transient runs on {d['history_mesh']} elements from the straight rod "
    f"perturbed by its flutter mode ({d['transient']['initial_amplitude_m'] * 1000:g} mm at the "
    "tip) and ends "
    f"{100 * d['transient']['final_distance']:.1f}% from the cycle, which periodic-orbit Newton "
    "(shooting, exact monodromy) converges; its Floquet multipliers lie inside the unit circle "
    f"(the slow one {d['transient']['slow_floquet_multiplier']:.4f}, the rate at which the "
    f"transient approaches: {d['transient']['contraction_per_period']:.4f} per period). Each "
    "finer mesh starts from the previous cycle, interpolated, and is converged by secant "
    "shooting. Mesh error against the finest mesh (relative): "
    + ", ".join(f"{n} elements {max(e.values()):.1e}" for n, e in d["mesh_error"].items())
    + ".\n\n"
    f"| | {m1} elements | {m2} elements |\n|---|---|---|\n"
    f"| tip amplitude [m] | {c['tip_amplitude_m']:.6f} | {f['tip_amplitude_m']:.6f} |\n"
    f"| period [s] | {c['period_s']:.6f} | {f['period_s']:.6f} |\n"
    f"| tip rotation amplitude [rad] | {c['tip_rotation_amplitude_rad']:.5f} | "
    f"{f['tip_rotation_amplitude_rad']:.5f} |\n"
    f"| work of P per period [J] | {c['work_follower_J']:.6f} | {f['work_follower_J']:.6f} |\n"
    f"| viscous dissipation per period [J] | {c['work_dissipated_J']:.6f} | "
    f"{f['work_dissipated_J']:.6f} |\n"
    f"| wall time [s] | {c['wall_s']:.1f} | {f['wall_s']:.1f} |"))
show("fig15")
show("fig16", width=480)
show("fig17", width=480)

# %% [markdown]
# ## Beyond the chapter: the bifurcation diagram of the pendulum
#
# Limit-cycle amplitude and period against the load, from the flutter load of §2.9 upwards.
# The amplitude grows like $\sqrt{P - P_{flu}}$ and the period starts at $2\pi/\Omega$ of the
# linear flutter mode; below $P_{flu}$ even a large initial amplitude decays: the Hopf
# bifurcation is supercritical (no hysteresis, no coexisting large cycle before flutter).

# %%
show("limit_cycle_amplitude", width=860)
display(Markdown(quantities_table(scene("limit_cycle_amplitude")["quantities"], digits=5)))

# %% [markdown]
# ### The rod's Hopf bifurcation
#
# For the rod of list (119) the diagram starts at the damped flutter load (P = 2.965 N,
# Kelvin–Voigt). There the linear growth rate of the flutter mode (exact theory, eq. 118) is
# tiny and rises steeply only towards the undamped Beck load, so a transient would need minutes
# of simulated time to settle near the onset (relaxation time ~1/(2 sigma)). Measured growth
# rates:

# %%
rows = [f"| {r['P_N']:.3f} | {r['load_ratio']:.3f} | {r['growth_rate']:.4f} | "
        f"{r['frequency']:.2f} |" for r in scene("beck_branch")["growth_rates"]]
display(Markdown("| P [N] | P / P_flu | growth rate [1/s] | frequency [rad/s] |\n|---|---|---|---|\n"
                 + "\n".join(rows)))

# %% [markdown]
# So the cycles are found without any transient, by periodic-orbit continuation: unknowns are
# the state on the Poincaré section, the period and the load; equations are periodicity, the
# section and a pseudo-arclength condition; the start is the linear flutter mode scaled to a tip
# amplitude of 1 cm. Newton's method uses the exact Jacobian: the flow's derivatives with
# respect to the state (the monodromy Φ) and to the load come from the variational equations
# Φ' = J(y(t)) Φ integrated with the orbit (J differentiated by hand, checked against complex
# steps), so it converges quadratically, and the converged cycle's Φ gives its Floquet
# multipliers with no further integration.
# The branch bends to higher loads with A ∝ √(P − P_flu), and every cycle's non-trivial
# multipliers lie inside the unit circle, the slow one as the normal form predicts,
# 1 − exp(−2σ(P)T) (their relative difference is in the table below): the Hopf bifurcation
# is supercritical.
# 1 − μ ≈ 1.7e-5 is ill-conditioned as an eigenvalue of Φ (it sits next to the trivial
# multiplier 1); it is computed as an eigenvalue of the return map on the section minus the
# identity, which has no trivial multiplier, and is then the same to 1e-8 at integrator
# tolerances 1e-8 to 1e-11. How far Φ maps the flow direction onto itself (`trivial_defect`
# in the data) is the accuracy check.

# %%
show("beck_hopf", width=860)
display(Markdown(quantities_table(scene("beck_hopf")["quantities"], digits=5)))

# %% [markdown]
# ### The whole branch: from the Hopf point to the chapter's cycle and beyond
#
# The same continuation, followed in the load up to 7 N (scene `beck_branch`, 4 P2 elements):
# a quadratic predictor through the last three cycles, a step sized by the predictor's measured
# error, chord corrections with the orbit alone before Newton's exact-Jacobian iterations, and
# pseudo-arclength in the scaled (A/0.3 m, P/P_flu) plane (measured: as robust as holding the
# load fixed, which the branch also allows since the load increases at every step, and 5–12%
# fewer variational integrations). The chapter's 5.5 N is landed on exactly. Every cycle's Floquet multipliers come from the monodromy of the Newton
# solve that accepted it.

# %%
bb = scene("beck_branch")
show("beck_branch", width=860)
cont = bb["continuation"]
P_b, A_b, T_b = (np.array(bb[k]) for k in ("P_N", "tip_amplitude_m", "period_s"))
k55 = bb["cycle_index"]
c4 = scene("beck_limit_cycle")["cycles"][str(bb["n_elements"])]
display(Markdown(
    f"{len(P_b)} cycles from {P_b[0]:.4f} N to {P_b[-1]:.4f} N "
    f"({bb['n_elements']} elements): {cont['integrations']} variational integrations, "
    f"{cont['orbit_integrations']} of the orbit alone (chord corrections), "
    f"{cont['rejected_steps']} rejected steps. "
    + ("The load increases at every step (smallest increment "
       f"{bb['min_dP']:.2e} N): no fold. " if bb["no_fold"] else "The load turns back: a fold. ")
    + f"Largest non-trivial Floquet modulus from 3 N to {P_b[-1]:g} N: "
    f"{bb['max_floquet_modulus_in_range']:.4f}"
    + (": every cycle is stable. " if bb["stable"] else ": unstable cycles exist. ")
    + f"At {P_b[k55]:g} N: A = {A_b[k55]:.5f} m, T = {T_b[k55]:.6f} s; the cycle of "
    f"`beck_limit_cycle` on the same mesh: {c4['tip_amplitude_m']:.5f} m, "
    f"{c4['period_s']:.6f} s."))
n_c, n_f = bb["n_elements"], bb["settings"]["check_elements"]
display(Markdown(f"| P [N] | A, {n_c} el. [m] | A, {n_f} el. [m] | T, {n_c} el. [s] | "
                 f"T, {n_f} el. [s] |\n"
                 "|---|---|---|---|---|\n" + "\n".join(
                     f"| {c['P_N']:g} | {c['coarse']['tip_amplitude_m']:.5f} | "
                     f"{c['fine']['tip_amplitude_m']:.5f} | {c['coarse']['period_s']:.6f} | "
                     f"{c['fine']['period_s']:.6f} |" for c in bb["mesh_checks"])))
for k, v in bb["quantities"].items():
    display(Markdown(f"- {k}: {v['value']} ({v['method']}); {v['independent']} "
                     f"({v['independent_method']})"))

# %% [markdown]
# The amplitude is not monotone: it grows like $\sqrt{P - P_{flu}}$, peaks near 3.2 N, falls
# to a minimum near 3.43 N and then grows again, while the load increases at every step and
# the period falls smoothly. The rod over one period at those loads (below) shows what
# changes and what does not: at the amplitude's peak and at its minimum the swing has the
# same shape (the tip rotation amplitude is 1.69-1.70 times A/l at both), only smaller; the
# multipliers stay inside the unit circle (the largest falls from 0.993 to 0.977 across the
# dip). Past the dip the swing grows and the rod curls: at 5.5 N the tip turns through
# ±1.42 rad and sweeps backwards (tip rotation 1.99 A/l), at 7 N through ±1.71 rad
# (2.25 A/l), with the amplitude nearly saturated. The dip is where the mesh matters most:
# 4 against 8 elements differ by 1.7% in amplitude at 3.5 N, against at most 0.08%
# (amplitude and period) at 5.5 and 7 N; the 2-element branch (the quick preset's mesh) has
# its peak and minimum at nearly the same loads (3.21 N, 3.45 N), so the dip is the
# model's, its depth a mesh-dependent detail.

# %%
show("beck_branch_shapes", width=900)
rot = np.array(bb["tip_rotation_amplitude_rad"])
display(Markdown("Tip rotation amplitude at those cycles: " + ", ".join(
    f"{sh['P_N']:.3f} N: {rot[sh['index']]:.3f} rad" for sh in bb["shapes"]) + "."))

# %% [markdown]
# ### Which integrator for the rod: work-precision
#
# What the cycle is measured by is the return map of the Poincaré section: from a state on the
# section near the cycle, one period is integrated to the next crossing, and the errors of the
# return time (the period) and of the tip amplitude are measured against a reference at rtol
# 1e-11 (DOP853 on 4 elements, accurate to ~1e-15 there; LSODA on 8, where explicit steps are
# limited by the Kelvin–Voigt stiffness). The adaptive stiff methods (LSODA, BDF, Radau, given
# the exact Jacobian) reach 1e-8 or better in about a second per period. The generalized-α
# structural integrator (fixed steps, ρ∞ = 0.8, the ABAQUS-style choice) is cheap per step and
# second order (in the form of Arnold and Brüls for a configuration-dependent mass matrix; the
# table below gives this run's errors and the observed orders), but at equal work it stays
# orders of magnitude less accurate than the adaptive methods here. Hence LSODA/BDF for the
# cycle.

# %%
show("beck_work_precision")
d = scene("beck_work_precision")
display(Markdown("| integrator family | best return-map error |\n|---|---|\n" + "\n".join(
    f"| {k} | {v:.2e} |" for k, v in d["best_error"].items())))
ga = sorted((r for r in d["runs"] if r["method"] == "generalized-alpha" and not r["failed"]),
            key=lambda r: (r["mesh"], -r["setting"]))


def observed_order(prev, r, key):
    """log(error ratio) / log(step ratio) against the previous (coarser) step of the mesh."""
    if prev is None or prev["mesh"] != r["mesh"]:
        return ""
    return f"{np.log(prev[key] / r[key]) / np.log(prev['setting'] / r['setting']):.2f}"


rows = [f"| {r['mesh']} | {r['setting'] * 1e3:g} | {r['period_error']:.2e} | "
        f"{observed_order(prev, r, 'period_error')} | {r['amplitude_error']:.2e} | "
        f"{observed_order(prev, r, 'amplitude_error')} |"
        for prev, r in zip([None, *ga[:-1]], ga, strict=True)]
display(Markdown("| elements | generalized-α step [ms] | period error | observed order | "
                 "amplitude error | observed order |\n|---|---|---|---|---|---|\n"
                 + "\n".join(rows)))


# %% [markdown]
# ## Your parameters
#
# The note at the top lists the scenes of this notebook that ran with other physical
# parameters than the chapter's (`workflow/config.yaml`), if any.

# %%
NOTE.update(Markdown(own_parameters_note(READ)))
display(Markdown(own_parameters_summary(READ)))
