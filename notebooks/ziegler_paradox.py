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
# # Viscosity and the Ziegler paradox (chapter §2.2, §2.4, §2.10)
#
# Executed by the workflow into `results/reports/ziegler_paradox.html`, from the data in
# `results/data/` and the figures in `results/figures/`. Every number here is also in the
# check summary `results/checks/summary.md`, with its tolerance and its second method.

# %%
import json
from pathlib import Path

import sympy as sp
from IPython.display import Image, Markdown, display

from flutterfriction import ZieglerPendulum
from flutterfriction.analysis.polynomial import characteristic_polynomial
from flutterfriction.analysis.routh import robustly_stable, routh_hurwitz
from flutterfriction.analysis.ziegler import critical_loads, spectrum
from flutterfriction.closed_forms import ziegler_damped as cfd
from flutterfriction.notebook_export import quantities_table
from flutterfriction.reference import own_parameters_note, own_parameters_summary

DATA, FIGS = Path("results/data"), Path("results/figures")


READ = {}  # scene -> the parameters its data was computed with
# a note, shown here, on scenes computed with your own parameters (filled by the last cell)
NOTE = display(Markdown(""), display_id=True)


def scene(name):
    data = json.loads((DATA / f"{name}.json").read_text())
    READ[name] = data.get("params")  # for the note on your own parameters (top)
    return data


def show(name, width=620):
    display(Image(filename=str(FIGS / f"{name}.png"), width=width))


# %% [markdown]
# ## Viscous hinges (eq. 26) and the characteristic polynomial (eqs. 28–31)
#
# Viscous hinges add $\mathbf{C}\dot{\boldsymbol\alpha}$ with $\mathbf{C}$ of the same form as the
# stiffness matrix (eq. 26). With $\alpha_j = a_j e^{\tilde\Omega t}$ the characteristic equation
# is the quartic (30) in $\tilde\omega = \tilde\Omega\, l_2\sqrt{m_2/k_2}$, with the groups
# $c = c_1/c_2$, $\epsilon = c_2/(l_2\sqrt{k_2 m_2})$ (eq. 29). We do not copy its coefficients:
# sympy expands the determinant of the dimensionless matrices at first use.

# %%
p = cfd.symbolic_coefficients()
for i, expr in enumerate(p):
    display(Markdown(f"$p_{i} = {sp.latex(expr)}$"))

# %% [markdown]
# Setting $\gamma = 0$ gives the dead-load polynomial of eq. (31). Its printed $p_0$, $p_1$, $p_2$
# carry $\rho_2 y_2$ where the expansion has $\rho_2 y_2^2$ (and the printed $p_0$ is not
# $\det\hat{\mathbf M} = a$ of eq. 21). The misprints vanish when $m_3 = 0$ or $h \in \{0, l_2\}$,
# but not for the device of list (47):

# %%
e = scene("errata_damped")["errata"]
rows = "\n".join(f"| {k} | {v['printed']:.10f} | {v['corrected']:.10f} | {v['independent']:.10f} |"
                 for k, v in e.items())
display(Markdown("| coefficient | printed eq. (31) | sympy | from the matrices |\n|---|---|---|---|\n"
                 + rows))

# %% [markdown]
# $p_3$ and $p_4$ are right, and $p_4 = c(\eta)$ does not contain the viscosity: the quasi-static
# buckling loads (22) survive. Routh–Hurwitz and the eigenvalues both find the damped critical
# dead load at $H_{cr}$:

# %%
display(Markdown(quantities_table(scene("damped_dead_load")["quantities"], digits=10)))

# %% [markdown]
# ## The Ziegler paradox (§2.4)
#
# For the symmetric pendulum of eq. (46) with $c_1 = c_2$ the quartic is eq. (51) with
# coefficients (52) (confirmed by the derivation), and Routh–Hurwitz (53) gives the flutter load
# $P^*_{flu} = (4/3 + \epsilon^2/2)K/L$ (eq. 54). Fig. 5: the real and imaginary parts of
# $\tilde\omega$; flutter starts at $\gamma = 2$ without viscosity, at 1.338 and 1.458 with
# $\epsilon = 0.1$ and $0.5$.

# %%
show("fig05")
display(Markdown(quantities_table(scene("fig05")["quantities"], digits=10)))

# %% [markdown]
# As $\epsilon \to 0$ the flutter load tends to $4/3\,K/L$, not to the $2\,K/L$ of the pendulum
# without viscosity: the limit of the damped system is not the undamped system.

# %%
show("paradox_limit")

# %% [markdown]
# ### Routh–Hurwitz without round-off
#
# Near a stability boundary the real part of the critical eigenvalue is as small as the
# eigen-solver's round-off, so a sign read from floating-point eigenvalues can be wrong. Our
# criterion evaluates the Hurwitz determinants in exact rational arithmetic on the (float)
# coefficients, so its verdict is exact for those coefficients, and Kharitonov's theorem tells
# whether it survives a relative perturbation of the coefficients by a few ulps. Just below and
# just above the flutter load of the symmetric pendulum with $\epsilon = 10^{-3}$:

# %%
sym = ZieglerPendulum(l1=1.0, l2=1.0, d=1.0, h=0.0, m1=1.0, m2=1.0, m3=0.0, k1=1.0, k2=1.0,
                      c1=1e-3, c2=1e-3)
P_star = cfd.eq54_flutter_gamma(1e-3)
for rel in (-1e-12, 1e-12):
    P = P_star * (1 + rel)
    coeffs = characteristic_polynomial(sym.mass_matrix(), sym.viscosity_matrix(),
                                       sym.stiffness_matrix() + sym.geometric_matrix(P))
    rh = routh_hurwitz(coeffs)
    display(Markdown(
        f"P = P* (1 {rel:+.0e}): Routh–Hurwitz stable = {rh.stable} (robust to 8 ulps: "
        f"{robustly_stable(coeffs) if rh.stable else 'n/a'}); max Re s from eigenvalues = "
        f"{spectrum(sym, P).real.max():+.3e} 1/s"))

# %% [markdown]
# The eigenvalue crossing loses digits like $10^{-16}/\epsilon$ (the slope of $\mathrm{Re}\,s$
# at the crossing is proportional to $\epsilon$), while the exact criterion does not: for list
# (47) with $c_1 = c_2 = 10^{-7}$ N m s the Routh–Hurwitz flutter load agrees with a 50-digit
# evaluation of the closed form to $10^{-15}$, the eigenvalue crossing only to $10^{-11}$.
# Routh–Hurwitz is therefore our primary method for damped flutter, the eigenvalues the check.
#
# ### The paradox in closed form, for any pendulum
#
# Writing $p_1 = \epsilon q_1$ and $p_3 = \epsilon q_3$, the last Hurwitz condition is
# $\Delta_3 = \epsilon^2[q_1 q_3 p_2 - a q_3^2 - k q_1^2] > 0$ with $p_2 = \beta_1 - \gamma\beta_2
# + c\epsilon^2$, so
# $$\gamma^*_{flu} = \frac{\beta_1 + c\epsilon^2 - (a q_3^2 + k q_1^2)/(q_1 q_3)}{\beta_2}.$$
# Since $(a q_3^2 + k q_1^2)/(q_1 q_3) \ge 2\sqrt{ka}$, as $\epsilon \to 0$ this never exceeds
# the undamped flutter load $(\beta_1 - 2\sqrt{ka})/\beta_2$ (eq. 39), and equals it only when
# $q_1/q_3 = \sqrt{a/k}$. For the symmetric pendulum it is eq. (54). The map shows the ratio of
# the two loads over the damping distribution and the mass distribution, with the curve where
# the paradox disappears; the crosses were checked with Routh–Hurwitz at $\epsilon = 10^{-4}$.

# %%
show("paradox_map", width=860)
display(Markdown(quantities_table(scene("paradox_map")["quantities"], digits=10)))

# %% [markdown]
# ## Fig. 19: the experiment's theoretical bars (§2.10)
#
# The chapter states that for the device of list (47) the flutter load with viscosity is 0.70
# times, and the divergence load 1.49 times, the load without it, but not the hinge viscosity.
# With $c_1 = c_2 = c$ both ratios are functions of $c$: the flutter ratio 0.70 gives
# $c \approx 0.00625$ N m s, the divergence ratio 1.49 gives $c \approx 0.00605$ N m s, and the
# viscosity the chapter uses in §2.9, 0.006 N m s, reproduces both quoted ratios
# (0.696 and 1.486). The two-digit ratios allow $c \in [0.00595, 0.00654]$ and
# $[0.00599, 0.00611]$ N m s respectively; 0.006 lies in both.

# %%
show("fig19_theory", width=860)
display(Markdown(quantities_table(scene("fig19_theory")["quantities"], digits=6)))

# %% [markdown]
# ## Your own pendulum
# `flutterfriction ziegler ... --c1 C1 --c2 C2 --json` reports the damped loads as `P_flu`,
# `P_div` and the undamped ones as `P_flu_undamped`, `P_div_undamped`:

# %%
mine = ZieglerPendulum(l1=0.1, l2=0.1, d=0.05, h=0.0, m1=0.3, m2=0.1, m3=0.0, k1=0.4, k2=0.2,
                       c1=0.002, c2=0.004)
display(Markdown("| load | value [N] |\n|---|---|\n" + "\n".join(
    f"| {k} | {v:.6g} |" for k, v in critical_loads(mine).as_dict().items())))


# %% [markdown]
# ## Your parameters
#
# The note at the top lists the scenes of this notebook that ran with other physical
# parameters than the chapter's (`workflow/config.yaml`), if any.

# %%
NOTE.update(Markdown(own_parameters_note(READ)))
display(Markdown(own_parameters_summary(READ)))
