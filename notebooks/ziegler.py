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
# # The Ziegler double pendulum (chapter §2.1–2.3)
#
# This notebook is executed by the workflow (`snakemake -j2`) into `results/reports/ziegler.html`.
# It reads the data and figures the workflow computed (`results/data/*.json`,
# `results/figures/*.png`) and explains them, section by section, with the chapter's equation
# numbers. Every number shown here is also checked against the chapter in
# `results/checks/summary.md`.
#
# Run it by hand from the repository root after `snakemake -j2` (e.g. `jupytext --to ipynb`).

# %%
import json
from pathlib import Path

import numpy as np
from IPython.display import Image, Markdown, display

from flutterfriction import ZieglerPendulum
from flutterfriction.analysis.ziegler import critical_loads, regime, spectrum
from flutterfriction.closed_forms import ziegler as cf
from flutterfriction.parameter_text import chapter_list
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
# ## §2.1 The model
#
# Two rigid, massless rods AB ($l_1$) and BC ($l_2$) joined by rotational springs $k_1$ (at A)
# and $k_2$ (at B); masses $m_1$ at D (distance $d$ from A), $m_3$ at E (distance $h$ from B) and
# $m_2$ at the loaded end C. A follower force $P$ stays parallel to BC, a dead force $H$ stays
# parallel to $\mathbf{e}_1$ (Fig. 2). The Lagrangean parameters are the rod rotations
# $\alpha_1, \alpha_2$. The nonlinear equations of motion are eq. (10); linearised about the
# straight configuration they read $\mathbf{M}\ddot{\boldsymbol\alpha} + (\mathbf{K}+\mathbf{G})
# \boldsymbol\alpha = 0$ (eq. 11).
#
# Two misprints of §2.1 were found and are corrected in the code (evidence in the check
# summary): eq. (1) writes $d\sin\alpha_2$ for the vertical position of D (it is
# $d\sin\alpha_1$), and eq. (11) writes $G_{11} = -l_1(P-H)$ (it is $-l_1(P+H)$, as in eq. 13).

# %%
show("fig02")

# %%
# "list (47)" only when the data's pendulum is that list (else "your own pendulum (...)")
LIST47 = chapter_list(scene("eq47"), "pendulum", "list47", "list (47)")
p47 = ZieglerPendulum.from_mapping(scene("eq47")["params"]["pendulum"])
M, K = p47.mass_matrix(), p47.stiffness_matrix()
G = p47.geometric_matrix(P=1.0)
display(Markdown(
    f"For the device of {LIST47}: $\\mathbf{{M}}$ = {np.array2string(M, precision=5)} kg m², "
    f"$\\mathbf{{K}}$ = {np.array2string(K, precision=4)} N m, and the follower load enters "
    f"through the unsymmetric $\\mathbf{{G}}/P$ = {np.array2string(G, precision=3)} m."))

# %% [markdown]
# ## §2.2 Dead load: only divergence, at the quasi-static buckling loads
#
# With $P = 0$ the geometric matrix is symmetric, so $\Omega^2$ is always real (eq. 16). One
# root $\omega^2$ of eq. (19) vanishes at the buckling loads of eq. (22); for equal rods and
# springs $H_{cr} = (3-\sqrt5)/2\,K/L \approx 0.382\,K/L$ (eq. 25). The figure shows the
# eigenvalues of the pencil $(\mathbf{K}+\mathbf{G}, \mathbf{M})$ (lines) and the closed form
# (19) (circles).

# %%
show("eq25")
q = scene("eq25")["quantities"]
display(Markdown(
    f"$\\eta_{{cr}} = H_{{cr}} l_1/k_2$ = {q['eta_cr']['value']:.15f} (generalised eigenproblem) "
    f"and {q['eta_cr']['independent']:.15f} (eq. 22); $\\eta_{{sup}}$ = {q['eta_sup']['value']:.12f}."))

# %% [markdown]
# ## §2.3 Follower load: flutter, then divergence
#
# With $H = 0$ the two roots $\omega^2$ of eq. (34) are real and positive for small loads; they
# coalesce at the flutter load (eq. 39) and become complex conjugate (flutter: an oscillation of
# growing amplitude), and coalesce again on the negative axis at the divergence load (eq. 41).
# Numerically we find both loads as the exact zeros of the discriminant
# $(\mu_1-\mu_2)^2$ of the eigenvalues $\mu = \Omega^2$ of $(\mathbf{K}+\mathbf{G}(P),\mathbf{M})$,
# which is smooth in $P$; a threshold on the real part of the frequencies would be biased
# because near a coalescence $\mathrm{Re}\,\tilde\Omega \propto \sqrt{P-P_{flu}}$.
#
# Fig. 3 is the graphical form of eq. (34) for list (47): the parabola is negative (flutter)
# between $\gamma_{flu}$ and $\gamma_{div}$, and the line changes sign at $\beta_1/\beta_2$.

# %%
show("fig03")

# %%
for name, label in (("eq46", "eq. (46)"), ("eq47", LIST47), ("eq48", "eq. (48)")):
    q = scene(name)["quantities"]
    display(Markdown(
        f"**{label}**: $P_{{flu}}$ = {q['P_flu']['value']:.12g} N "
        f"(closed form {q['P_flu']['independent']:.12g}), "
        f"$P_{{div}}$ = {q['P_div']['value']:.12g} N "
        f"(closed form {q['P_div']['independent']:.12g}); in units of $k_2/l_1$: "
        f"$\\gamma_{{flu}}$ = {q['gamma_flu']['value']:.10g}, "
        f"$\\gamma_{{div}}$ = {q['gamma_div']['value']:.10g}."))
show("eq47")

# %% [markdown]
# The half-width of the flutter interval is $2\sqrt{k a}/\beta_2$; the text prints
# $2\sqrt{k}\,a/\beta_2$ in eqs. (37), (39), (41). The two agree only when $a = 1$, whatever $k$:
# for list (47) ($k = 1$, $a = 28/9$) the printed form would give 3.28 N and 10.33 N instead of
# the chapter's own 4.8 N and 8.8 N (Fig. 3 states both). Below, the check with $k_1 = 2k_2$:

# %%
e = scene("errata_ziegler")["errata"]
for key in ("eq39_flutter_sqrt_ka", "eq41_divergence_sqrt_ka"):
    x = e[key]
    display(Markdown(f"{x['quantity']} with $k_1 = 2k_2$: printed form {x['printed']:.6f}, "
                     f"corrected {x['corrected']:.10f}, eigenvalues {x['independent']:.10f}."))

# %% [markdown]
# ### The mass distribution matters (eqs. 42–48)
#
# With $m_3 = 0$ the flutter load is eq. (42); it is smallest when $\sqrt{k} = \lambda y
# \sqrt\rho$ (eq. 43), giving eqs. (44)–(46): $2K/L$ and $4K/L$ for the symmetric system. Moving
# $m_1$ to mid-rod ($y_1 = 1/2$) gives $(2 + 1/8)K/L$ and $25/8\,K/L$ (eq. 48), although nothing
# changes in a quasi-static analysis: *the quasi-static criterion cannot find flutter loads.*

# %%
show("eq48")

# %% [markdown]
# ### Fig. 4: flutter and divergence in time
#
# The linear equations (11) are solved exactly, $\mathbf{x}(t) = e^{\mathbf{A}t}\mathbf{x}_0$,
# at the drawn instants (no time stepping), from $\alpha_1 = \alpha_2 = \pm 0.5°$ at rest, for
# the chapter's $P$ = 6.8 N (flutter) and 15.4 N (divergence) of list (47); with your own
# pendulum or loads the cell below gives their regimes. The drawings use the exact rigid-rod
# kinematics with the linear solution's angles: past a few tens of degrees (20° after about
# 0.37 s in flutter, 0.15 s in divergence) the linear model is outside its range of validity,
# which is the point of §2.9.

# %%
show("fig04", width=900)
# the pendulum and the loads the figure was drawn with (the workflow's data)
f4 = scene("fig04")
p4 = ZieglerPendulum.from_mapping(f4["params"]["pendulum"])
for name, case in sorted(f4["cases"].items(), key=lambda kv: kv[0] != "flutter"):
    s = spectrum(p4, case["P"])
    display(Markdown(f"{name} case, P = {case['P']:g} N: {regime(p4, case['P'])} for "
                     f"{chapter_list(f4, 'pendulum', 'list47', 'list (47)')}; eigenvalues "
                     "$\\tilde\\Omega$ = "
                     + ", ".join(f"{z.real:+.3f}{z.imag:+.3f}i" for z in s) + " 1/s"))

# %% [markdown]
# ## Your own pendulum
#
# Everything above is a function of the SI parameters. For example, a pendulum with a stiffer
# first hinge and a heavier tip (also from the command line:
# `flutterfriction ziegler --l1 0.1 --l2 0.1 --d 0.05 --h 0 --m1 0.3 --m2 0.1 --m3 0 --k1 0.4 --k2 0.2 --json`):

# %%
mine = ZieglerPendulum(l1=0.1, l2=0.1, d=0.05, h=0.0, m1=0.3, m2=0.1, m3=0.0, k1=0.4, k2=0.2)
num, closed = critical_loads(mine), cf.critical_loads_closed_form(mine)
display(Markdown("| load | eigenvalues | closed form |\n|---|---|---|\n" + "\n".join(
    f"| {k} | {getattr(num, k):.10f} N | {getattr(closed, k):.10f} N |"
    for k in ("P_flu", "P_div", "H_cr", "H_sup"))))


# %% [markdown]
# ## Your parameters
#
# The note at the top lists the scenes of this notebook that ran with other physical
# parameters than the chapter's (`workflow/config.yaml`), if any.

# %%
NOTE.update(Markdown(own_parameters_note(READ)))
display(Markdown(own_parameters_summary(READ)))
