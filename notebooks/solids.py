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
# # Flutter in frictional solids (chapter §3)
#
# Executed by the workflow into `results/reports/solids.html` from `results/data/` and
# `results/figures/`. Every number is also in `results/checks/summary.md`.

# %%
import json
from pathlib import Path

import numpy as np
from IPython.display import Image, Markdown, display

from flutterfriction.models import solid as so
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
# ## §3.1 Coulomb friction is a nonassociative "plasticity"
#
# The two-spring model of Fig. 22 obeys the incrementally nonlinear rate equations (140)–(141):
# stick inside the cone $|p_T| < \mu p_N$, slip on it when $\mathbf a\cdot\mathbf E\dot{\mathbf u} > 0$.
# Along a piecewise-linear displacement path the response is piecewise linear, so we integrate
# it exactly, splitting each segment where the force reaches the cone. The slip direction
# $\mathbf b$ is not normal to the cone: the slip operator (143) is unsymmetric.

# %%
show("fig22", width=520)
d = scene("fig22")
display(Markdown(
    f"Branches along the path: {', '.join(d['branch'][1:])}. Slip operator at the slip point: "
    f"C21 - C12 = {d['quantities']['slip_operator_asymmetry']['value']} N/m = mu k_N sgn p_T; "
    f"Prager's consistency (eq. 137) while slipping, max |a . C du| / |E du|: "
    f"{d['quantities']['slip_consistency']['value']:.1e}."))

# %% [markdown]
# ## §3.2–3.4 The acoustic tensor and localization
#
# With the plastic branch $\mathcal C = \mathcal E - \mathcal E[\mathbf P]\otimes\mathcal E^T[\mathbf Q]/g$
# (eq. 153) the acoustic tensor is eq. (161); localization in a band of normal $\mathbf n$
# happens at $g = g^E_{cr}(\mathbf n)$ (eq. 166). For a Drucker–Prager material the maximum over
# all directions (a global search on a Fibonacci grid of the half sphere, then Nelder–Mead)
# reproduces the closed-form critical hardening of Rudnicki and Rice (1975),
# $h_{cr}/G = \frac{1+\nu}{9(1-\nu)}(\beta-\mu)^2 - \frac{1+\nu}{2}(N + \frac{\beta+\mu}{3})^2$.

# %%
show("localization_directions")
q = scene("localization_directions")["quantities"]["h_cr"]
display(Markdown(f"$h_{{cr}}$: search {q['value']:.15f}, Rudnicki–Rice {q['independent']:.15f}"))

# %% [markdown]
# ## §3.5 Flutter
#
# For isotropic elasticity the eigenvalues are $\mu$ and the roots of eq. (184); flutter (a
# complex pair of eigenvalues $\eta = \rho c^2$) happens iff $N = (\mathbf n\cdot\mathbf p)(\mathbf n\cdot\mathbf q) > 0$,
# $N - \mathbf p\cdot\mathbf q > 0$ and $g_1 < g < g_2$ with
# $g_{1,2} = (\sqrt{N} \mp \sqrt{N - \mathbf p\cdot\mathbf q})^2/(\lambda+\mu)$.
# **Erratum**: eq. (188) prints $(\mathbf n\cdot\mathbf p)(\mathbf n\cdot\mathbf p)$ in the second
# root; the roots of the discriminant (186) in $1/g$ give $(\mathbf n\cdot\mathbf p)(\mathbf n\cdot\mathbf q)$,
# and a brute-force scan of the discriminant of $\det(\mathbf A - \eta\mathbf I)$ confirms it:

# %%
e = scene("errata_solids")["errata"]
display(Markdown("| | printed | corrected | brute force |\n|---|---|---|---|\n" + "\n".join(
    f"| {k} | {'none' if v['printed'] is None else format(v['printed'], '.10g')} "
    f"| {v['corrected']:.10g} | {v['independent']:.10g} |"
    for k, v in e.items())))
show("acoustic_eigenvalues")

# %% [markdown]
# The statements of §3.5, checked on 2000 random samples (seeded):

# %%
display(Markdown(quantities_table(scene("solids_statements")["quantities"], digits=4)))

# %% [markdown]
# ### Which directions flutter, and anisotropy
#
# (a) For the nonassociative case, the band of $g$ in which each direction of a principal
# plane flutters, above the localization modulus as the theory requires. (b) A
# deviatoric-associative Drucker–Prager material at the coalescence modulus (194) cannot flutter
# with isotropic elasticity; adding a generic elastic anisotropy (a random tensor with the
# major and minor symmetries, size ε relative to μ) of ε ≳ 0.05 (none at 0.02 on this grid)
# makes a thin set of directions near the coalescence direction flutter (0.06–0.27 % of the
# patch); (c) that set grows with ε (Bigoni and Loret 1999).

# %%
show("flutter_map", width=900)
an = scene("flutter_map")["anisotropy"]
display(Markdown("| ε | % of the ±20° patch that flutters |\n|---|---|\n" + "\n".join(
    f"| {e} | {100 * f:.3f} |" for e, f in zip(an["eps"], an["fraction_flutter"], strict=True))))

# %% [markdown]
# ## Your own material
# `flutterfriction acoustic --lam L --mu M --P ... --Q ... --n ... --g G --json`; here the
# parameters of the figures above (P, Q as given: eq. 152 defines g with them, so these are the
# checked $g_1$, $g_2$ and $g^E_{cr}$):

# %%
# the parameters the figure was drawn with (the workflow's data: your own, if you set them)
ae = scene("acoustic_eigenvalues")["params"]
P, Q = so.voigt_to_tensor(ae["P"]), so.voigt_to_tensor(ae["Q"])
n = np.array(ae["n"], dtype=float)
lam, mu = ae["lam"], ae["mu"]
display(Markdown(f"λ = {lam:g}, μ = {mu:g}: flutter interval "
                 f"{so.flutter_interval_isotropic(lam, mu, P, Q, n)}, "
                 f"g_localization {so.localization_modulus_isotropic(lam, mu, P, Q, n):.6f}"))


# %% [markdown]
# ## Your parameters
#
# The note at the top lists the scenes of this notebook that ran with other physical
# parameters than the chapter's (`workflow/config.yaml`), if any.

# %%
NOTE.update(Markdown(own_parameters_note(READ)))
display(Markdown(own_parameters_summary(READ)))
