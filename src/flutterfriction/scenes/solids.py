"""Scenes of chapter §3: Fig. 22 (Coulomb contact), the eigenvalues of the acoustic tensor,
localization directions (checked against Rudnicki and Rice 1975), flutter maps, the statements
of §3.5 shown numerically, and the evidence for the errata of §3."""

from __future__ import annotations

import math
from typing import Any, NamedTuple

import numpy as np

from flutterfriction.analysis import acoustic as ac
from flutterfriction.errors import ParameterError, check_positive, check_real
from flutterfriction.models import solid as so
from flutterfriction.models.contact import CoulombContact, integrate_path
from flutterfriction.scenes.common import n_points, quantity, take


def _tensor(name: str, t: Any) -> np.ndarray:
    """The flow mode ``P`` or yield gradient ``Q`` as given (Voigt or 3x3), not rescaled: the
    plastic modulus g of eq. (152) is defined with them, and scaling P, Q by a, b scales every
    critical g (g1, g2, the localization modulus) by a b, so a silent normalisation would
    report other moduli than the listed parameters give (the CLI and the notebooks use them as
    given too)."""
    t = np.asarray(t, dtype=float)
    if t.shape == (6,):
        t = so.voigt_to_tensor(t)
    t = so.check_symmetric(name, t)
    if not np.any(t):
        raise ParameterError(f"{name} must be non-zero (a flow mode / yield gradient)")
    return t


def _direction_in_plane(theta: np.ndarray) -> np.ndarray:
    """Unit vectors in the (e1, e3) principal plane at angle theta from e1, shape (m, 3)."""
    return np.stack([np.cos(theta), np.zeros_like(theta), np.sin(theta)], axis=-1)


# ---------------------------------------------------------------------- Fig. 22
def check_fig22(params: dict[str, Any]) -> None:
    """Fig. 22's contact and path as :func:`fig22` refuses them (the configuration check: the
    scene itself, exact and ~ms; an outside audit's path refused only in its job)."""
    import copy

    fig22(copy.deepcopy(params))


def fig22(params: dict[str, Any]) -> dict[str, Any]:
    """The Coulomb cone, the normal a and the slip direction b, and a computed force path."""
    take(params, {"k_N", "k_T", "mu", "path"})
    c = CoulombContact(params["k_N"], params["k_T"], params["mu"])
    try:
        r = integrate_path(c, params["path"])
    except ParameterError as exc:  # the model's word for the path is "vertices"
        message = str(exc)
        raise ParameterError("path" + message.removeprefix("vertices")
                             if message.startswith("vertices") else message) from None
    if "slip" not in r.branch:
        raise ParameterError("path never reaches the Coulomb cone |p_T| = mu p_N: Fig. 22 needs "
                             "stick, slip and unloading")
    slip_pt = r.p[r.branch.index("slip")]
    C = c.slip_operator(slip_pt)
    sgn = float(np.sign(slip_pt[1])) or 1.0  # the side of the cone slipped on (eq. 136)
    closed = np.array([[c.k_N, 0.0], [c.mu * c.k_N * sgn, 0.0]])
    # Prager's consistency (eq. 137) of eq. (143)'s generic operator on every slip piece: the
    # force rate it gives is tangent to the cone, a . C du = 0, relative to |E du| (the path
    # itself slips with its closed form, on the cone by construction)
    consistency = max(
        abs(c.gradient(r.p[i], side) @ c.slip_operator(r.p[i], side) @ (r.u[i] - r.u[i - 1]))
        / float(np.linalg.norm(c.elastic_matrix() @ (r.u[i] - r.u[i - 1])))
        for i, b in enumerate(r.branch) if b == "slip"
        for side in [float(np.sign(r.p[i][1])) or 1.0])
    onset = r.branch.index("slip") - 1  # the recorded point where the first slip piece starts
    residual = _unloaded_point(r, onset)
    return {
        "mu": c.mu, "k_N": c.k_N, "k_T": c.k_T, "u": r.u.tolist(), "p": r.p.tolist(),
        "slip": r.slip.tolist(), "branch": r.branch, "slip_point": slip_pt.tolist(),
        "slip_point_index": r.branch.index("slip"), "onset_index": onset,
        "residual": residual,
        "a": c.gradient(slip_pt).tolist(), "b": c.slip_direction(slip_pt).tolist(),
        "quantities": {
            "slip_onset_force": quantity(abs(float(r.p[onset, 1])),
                                         c.mu * c.k_N * float(r.u[onset, 0] - r.u[0, 0]),
                                         "|p_T| where the path first reaches the cone (exact "
                                         "splitting of eq. 140)",
                                         "mu k_N u_N there: mu N with N from the elastic normal "
                                         "spring (eq. 129)", "N"),
            "residual_displacement": quantity(residual["u_T"] - float(r.u[0, 1]),
                                              residual["slip"],
                                              "u_T where p_T returns to 0 on unloading "
                                              "(interpolated on the stick piece)",
                                              "accumulated slip u_T^s (sum of the slip "
                                              "multipliers, eq. 135)", "m"),
            "slip_operator_C21": quantity(float(C[1, 0]), float(closed[1, 0]),
                                           "eq. (143) from E, a, b", "closed form mu k_N sgn p_T",
                                           "N/m"),
            "slip_operator_asymmetry": quantity(float(C[1, 0] - C[0, 1]), c.mu * c.k_N * sgn,
                                                 "C21 - C12 of eq. (143)", "mu k_N sgn p_T",
                                                 "N/m"),
            "slip_consistency": quantity(float(consistency), 0.0,
                                         "max |a . C du| / |E du| on the slip pieces, C of "
                                         "eq. (143) from E, a, b", "zero (eq. 137)", ""),
        }}


def _unloaded_point(r: Any, onset: int) -> dict[str, float]:
    """Where the tangential force first returns to zero after the first slip (on a stick
    piece, so the spring is unstretched there: ``u_T = u_T^s``)."""
    for k in range(onset + 2, len(r.p)):
        p0, p1 = r.p[k - 1, 1], r.p[k, 1]
        if r.branch[k] == "stick" and p0 != 0.0 and p0 * p1 <= 0.0:
            s = p0 / (p0 - p1)
            u = r.u[k - 1] + s * (r.u[k] - r.u[k - 1])
            return {"u_N": float(u[0]), "u_T": float(u[1]), "slip": float(r.slip[k]),
                    "p_N": float(r.p[k - 1, 0] + s * (r.p[k, 0] - r.p[k - 1, 0])), "piece": k}
    raise ParameterError("path must slip and then unload the tangential force through "
                         "p_T = 0 (Fig. 22: stick, slip, unloading)")


# ---------------------------------------------------------------------- acoustic eigenvalues
def _nonassociative_case(params: dict[str, Any]):
    lam, mu = float(params["lam"]), check_positive("mu", params["mu"])
    P, Q = _tensor("P", params["P"]), _tensor("Q", params["Q"])
    n = so.check_direction(params["n"], normalise=True)
    so.isotropic_vectors(lam, mu, P, Q, n)  # (P, Q within the closed forms' range, named)
    return lam, mu, P, Q, n


def _acoustic_range(params: dict[str, Any]):
    """The case and its range of g, refused before the scan: ``g_min >= g_max``, a g at which
    eq. (184) leaves the double range (an outside audit: g_min = 1e-200 put an infinity into
    the data), a ``g_max`` beyond the brute-force scan's range (:data:`~flutterfriction.
    analysis.acoustic.G_MAX_OVER_SCALE`; it failed in the job)."""
    take(params, {"lam", "mu", "P", "Q", "n", "g_min", "g_max", "n_points"})
    lam, mu, P, Q, n = _nonassociative_case(params)
    g_min = check_positive("g_min", params["g_min"], "Pa")
    g_max = check_positive("g_max", params["g_max"], "Pa")
    if not g_min < g_max:
        raise ParameterError(f"g_min must be < g_max = {g_max:g} Pa, got {g_min:g}")
    for name, value in (("g_min", g_min), ("g_max", g_max)):
        try:
            so.acoustic_eigenvalues_isotropic(lam, mu, P, Q, value, n)
        except ParameterError as exc:
            raise ParameterError(f"{name}: {str(exc).removeprefix('g: ')}") from None
    E = so.isotropic_elasticity(lam, mu)
    ac.flutter_interval_bruteforce(E, P, Q, n, g_max=g_max)  # (its range, naming g_max)
    # the figure shows the flutter interval: there must be one, inside [g_min, g_max] (an
    # outside audit: Q = P, or g_max below g1, failed in the job with no key named)
    interval = so.flutter_interval_isotropic(lam, mu, P, Q, n)
    if interval is None:
        raise ParameterError("P, Q, n: this case has no flutter interval (eq. 188, corrected), "
                             "which the figure shows: give a nonassociative case (Q not "
                             "parallel to P) with one")
    if not (g_min < interval[0] and interval[1] < g_max):
        raise ParameterError(f"g_min, g_max: [{g_min:g}, {g_max:g}] Pa must contain the flutter "
                             f"interval [{interval[0]:.6g}, {interval[1]:.6g}] Pa (eq. 188)")
    return lam, mu, P, Q, n, E, g_min, g_max


def check_acoustic_eigenvalues(params: dict[str, Any]) -> None:
    """The case and its range as :func:`acoustic_eigenvalues` refuses them (the configuration
    check)."""
    _acoustic_range(params)


def acoustic_eigenvalues(params: dict[str, Any]) -> dict[str, Any]:
    """Eigenvalues of A(n) against g for a nonassociative case: localization, coalescences and
    the complex (flutter) pair between g1 and g2 (eqs. 179–188)."""
    lam, mu, P, Q, n, E, g_min, g_max = _acoustic_range(params)
    g = np.geomspace(g_min, g_max, n_points(params))
    eta = np.array([np.sort_complex(np.linalg.eigvals(so.acoustic_tensor(E, P, Q, gi, n)))
                    for gi in g])
    closed = np.array([so.acoustic_eigenvalues_isotropic(lam, mu, P, Q, gi, n) for gi in g])
    interval = so.flutter_interval_isotropic(lam, mu, P, Q, n)
    brute = ac.flutter_interval_bruteforce(E, P, Q, n, g_max=float(g[-1]))
    if interval is None or len(brute) != 1:
        raise ParameterError("the configured case must have one flutter interval")
    gE = so.localization_modulus_isotropic(lam, mu, P, Q, n)
    return {
        "g": g.tolist(), "re": eta.real.T.tolist(), "im": eta.imag.T.tolist(), "mu": mu,
        "g_localization": gE, "flutter_interval": list(interval),
        # eq. (188) as printed (the erratum, stated on the figure); None if it has no interval
        "flutter_interval_as_printed": (
            None if (pr := so.flutter_interval_as_printed(lam, mu, P, Q, n)) is None
            else [float(x) for x in pr]),
        "max_closed_vs_eig": float(np.max(np.abs(np.sort_complex(closed) - eta))),
        "quantities": {
            "g1": quantity(interval[0], brute[0][0], "closed form eq. (188), corrected",
                            "brute force: discriminant of det(A - eta I) (Brent)", "Pa"),
            "g2": quantity(interval[1], brute[0][1], "closed form eq. (188), corrected",
                            "brute force: discriminant of det(A - eta I) (Brent)", "Pa"),
            "g_localization": quantity(gE, so.localization_modulus(E, P, Q, n),
                                        "closed form eq. (185)", "general eq. (166)", "Pa"),
        }}


# ---------------------------------------------------------------------- localization
#: The largest Drucker-Prager friction or dilatancy coefficient (mu = sqrt3 sin(phi)).
DP_COEFFICIENT_MAX = math.sqrt(3.0)


def _localization_case(params: dict[str, Any]) -> tuple[float, float, np.ndarray, np.ndarray]:
    """``(G, nu, P, Q)`` of :func:`localization_directions`, checked."""
    G = check_positive("G", params["G"])
    nu = check_real("nu", params["nu"])
    if not -1 < nu < 0.5:
        raise ParameterError(f"nu must lie in (-1, 0.5), got {nu}")
    G, nu, P, Q = (G, nu, *_dp_state(params))
    try:  # the moduli's scale G^2 |P| |Q| in range (an outside audit: G = 1e300 Pa was
        # refused in the job only)
        ac.localization_moduli(so.isotropic_elasticity(2 * G * nu / (1 - 2 * nu), G), P, Q,
                               np.array([[1.0, 0.0, 0.0]]))
    except ParameterError as exc:
        raise ParameterError(f"G = {G:g} Pa: {exc}") from None
    return G, nu, P, Q


def check_localization_directions(params: dict[str, Any]) -> None:
    """The material and state as :func:`localization_directions` refuses them (the
    configuration check)."""
    _localization_case(params)


def _dp_state(params: dict[str, Any]):
    """Drucker–Prager in Rudnicki–Rice form: tension-positive stress with s_II / tau = N,
    Q = S^/sqrt2 + mu_f I/3, P = S^/sqrt2 + beta I/3 (so that H is R&R's h)."""
    N = float(params["N"])
    if not -1 / math.sqrt(3) - 1e-12 <= N <= 1 / math.sqrt(3) + 1e-12:
        raise ParameterError(f"N = s_II/tau must lie in [-1/sqrt3, 1/sqrt3], got {N}")
    for key in ("mu_f", "beta"):
        # Drucker-Prager's friction and dilatancy coefficients: 0 ... sqrt3 (sin of an angle
        # times sqrt3); an outside audit ran mu_f = -5 and beta = 1e300 (an OverflowError)
        value = check_real(key, params[key])
        if not 0.0 <= value <= DP_COEFFICIENT_MAX:
            raise ParameterError(f"{key} must lie in [0, sqrt3 = {DP_COEFFICIENT_MAX:.6g}] "
                                 f"(Drucker-Prager), got {value!r}")
    a = math.sqrt(max(0.0, (2 - 1.5 * N**2) / 2))
    s = np.diag([-N / 2 + a, N, -N / 2 - a])
    S = s / np.linalg.norm(s)
    P = S / math.sqrt(2) + float(params["beta"]) * np.eye(3) / 3
    Q = S / math.sqrt(2) + float(params["mu_f"]) * np.eye(3) / 3
    return P, Q


def rudnicki_rice_hcr(G: float, nu: float, beta: float, mu_f: float, N: float) -> float:
    """Rudnicki and Rice (1975): critical hardening modulus for localization of a
    Drucker–Prager material, ``h/G = (1+nu)/(9(1-nu)) (beta - mu)^2 - (1+nu)/2 (N + (beta+mu)/3)^2``
    (valid when the band normal lies in the plane of the extreme principal stresses)."""
    return G * ((1 + nu) / (9 * (1 - nu)) * (beta - mu_f) ** 2
                - (1 + nu) / 2 * (N + (beta + mu_f) / 3) ** 2)


def localization_directions(params: dict[str, Any]) -> dict[str, Any]:
    """g_E(n) over the directions of the (sigma_1, sigma_3) principal plane and its maximum over
    the whole sphere, against Rudnicki and Rice's closed form."""
    take(params, {"G", "nu", "beta", "mu_f", "N", "n_points", "n_search"})
    G, nu, P, Q = _localization_case(params)
    lam = 2 * G * nu / (1 - 2 * nu)
    E = so.isotropic_elasticity(lam, G)
    theta = np.linspace(0, np.pi, n_points(params))
    gE = ac.localization_moduli(E, P, Q, _direction_in_plane(theta))
    g_max, n_max = ac.max_localization_modulus(E, P, Q, int(params.get("n_search", 4000)))
    QEP = float(np.einsum("ij,ij->", Q, so.apply(E, P)))
    h_rr = rudnicki_rice_hcr(G, nu, params["beta"], params["mu_f"], params["N"])
    return {
        "theta": theta.tolist(), "g_E": gE.tolist(), "g_max": g_max, "n_max": n_max.tolist(),
        "theta_max_in_plane": float(theta[np.argmax(gE)]),
        "quantities": {"h_cr": quantity(g_max - QEP, h_rr,
                                         "max over the sphere of eq. (166) minus Q.E[P]",
                                         "Rudnicki and Rice (1975), closed form", "Pa")}}


# ---------------------------------------------------------------------- flutter maps
def flutter_map(params: dict[str, Any]) -> dict[str, Any]:
    """(a) Which directions in a principal plane flutter, against g, for the nonassociative case
    (closed form, verified by brute force at a few points); (b) a deviatoric-associative
    Drucker–Prager material at coalescence (no flutter with isotropic elasticity): the fraction
    of directions that flutter as a small elastic anisotropy grows (Bigoni and Loret 1999)."""
    take(params, {"plane_case", "anisotropy", "n_points"})
    pc = params["plane_case"]
    lam, mu, P, Q, _ = _nonassociative_case({**pc, "n": [1, 0, 0]})
    theta = np.linspace(0, np.pi, n_points(params))
    dirs = _direction_in_plane(theta)
    bounds = [so.flutter_interval_isotropic(lam, mu, P, Q, n) for n in dirs]
    gE = [so.localization_modulus_isotropic(lam, mu, P, Q, n) for n in dirs]
    E = so.isotropic_elasticity(lam, mu)
    checks = {}
    for i in np.linspace(0, len(theta) - 1, 7).astype(int)[1:-1]:
        if bounds[i] is not None:
            brute = ac.flutter_interval_bruteforce(E, P, Q, dirs[i], g_max=10 * bounds[i][1])
            checks[f"g2_theta{theta[i]:.3f}"] = quantity(
                bounds[i][1], brute[0][1], "closed form eq. (188), corrected", "brute force",
                "Pa")
    an = params["anisotropy"]
    a = anisotropy_setup(an)
    fractions, maps = [], []
    for eps in an["eps_values"]:
        flutters = ac.flutters_somewhere(a.E0 + float(eps) * a.T, a.P, a.Q, a.directions,
                                         a.g_values)
        fractions.append(float(np.mean(flutters)))
        maps.append(flutters.reshape(len(a.offsets_deg), len(a.offsets_deg)).astype(int)
                    .tolist())
    checks["isotropic_flutter_directions"] = quantity(
        int(round(fractions[0] * len(a.directions))), 0,
        "brute force near coalescence, eps = 0", "Loret et al. (1990): excluded", "")
    return {"theta": theta.tolist(),
            "g1": [None if b is None else b[0] for b in bounds],
            "g2": [None if b is None else b[1] for b in bounds], "g_localization": gE,
            "anisotropy": {"eps": an["eps_values"], "fraction_flutter": fractions,
                           "maps": maps, "offsets_deg": a.offsets_deg.tolist(),
                           "n_coalescence": a.n_coalescence.tolist(),
                           "g_coalescence": a.g_coalescence,
                           "g_range": [float(a.g_values[0]), float(a.g_values[-1])]},
            "quantities": checks}


class AnisotropySetup(NamedTuple):
    """The flutter map's (b)-(c) inputs (:func:`anisotropy_setup`)."""

    E0: np.ndarray  # isotropic elasticity
    T: np.ndarray  # the random anisotropy, times mu
    P: np.ndarray  # Drucker-Prager tensors
    Q: np.ndarray
    n_coalescence: np.ndarray  # direction and modulus of the coalescence (eq. 194)
    g_coalescence: float
    directions: np.ndarray  # the patch around n_coalescence
    offsets_deg: np.ndarray
    g_values: np.ndarray  # the moduli scanned, 0.8-1.2 g_coalescence


def anisotropy_setup(an: dict[str, Any]) -> AnisotropySetup:
    """The flutter map's (b)-(c) inputs from its ``anisotropy`` section: a deviatoric-
    associative Drucker-Prager material with isotropic elasticity, its coalescence, a random
    elastic anisotropy, the patch of directions and the moduli to scan."""
    take(an, {"lam", "mu", "sigma", "friction_deg", "dilatancy_deg", "seed", "eps_values",
              "patch_deg", "n_patch", "n_g"})
    lam2, mu2 = float(an["lam"]), check_positive("mu", an["mu"])
    E0 = so.isotropic_elasticity(lam2, mu2)
    Pd, Qd = so.drucker_prager_tensors(np.diag(an["sigma"]), math.radians(an["friction_deg"]),
                                       math.radians(an["dilatancy_deg"]))
    gC = so.coalescence_modulus(lam2, mu2, Pd, Qd)
    w, V = np.linalg.eigh(so.apply(E0, Pd))
    nC = V[:, int(np.argmax(w * np.einsum("ji,jk,ki->i", V, so.apply(E0, Qd), V)))]
    T = so.random_elasticity_perturbation(np.random.default_rng(int(an["seed"]))) * mu2
    dirs, offsets = _patch(nC, float(an["patch_deg"]), int(an["n_patch"]))
    return AnisotropySetup(E0, T, Pd, Qd, nC, gC, dirs, offsets,
                           gC * np.linspace(0.8, 1.2, int(an["n_g"])))


def _patch(nC: np.ndarray, half_deg: float, m: int) -> tuple[np.ndarray, np.ndarray]:
    """Directions within +/- half_deg of nC on an m x m grid of tangent-plane angles."""
    t1 = np.cross(nC, [0.0, 0.0, 1.0])
    if np.linalg.norm(t1) < 1e-6:
        t1 = np.cross(nC, [0.0, 1.0, 0.0])
    t1 /= np.linalg.norm(t1)
    t2 = np.cross(nC, t1)
    off = np.linspace(-half_deg, half_deg, m)
    X, Y = np.meshgrid(np.radians(off), np.radians(off))
    d = nC[None, None] + np.tan(X)[..., None] * t1 + np.tan(Y)[..., None] * t2
    d = d.reshape(-1, 3)
    return d / np.linalg.norm(d, axis=1)[:, None], off


# ---------------------------------------------------------------------- §3.5 statements
def _random_symmetric(rng: np.random.Generator) -> np.ndarray:
    A = rng.normal(size=(3, 3))
    return (A + A.T) / np.linalg.norm(A + A.T)


def solids_statements(params: dict[str, Any]) -> dict[str, Any]:
    """The statements of §3.5 on random samples (seeded): deviatoric associativity excludes
    flutter (eqs. 187, 191), flutter never at g <= g_cr^E(n), triple coalescence at mu (eq.
    190, 194)."""
    take(params, {"n_samples", "seed"})
    rng = np.random.default_rng(int(params.get("seed", 1)))
    n_samples = int(params.get("n_samples", 2000))
    min_191, worst_gap, n_flutter_cases = np.inf, np.inf, 0
    complex_found = 0
    for _ in range(n_samples):
        mu = rng.uniform(0.2, 3.0)
        lam = rng.uniform(-2 * mu / 3 + 0.05, 3.0)  # positive definite elasticity (§3.4)
        n = rng.normal(size=3)
        n /= np.linalg.norm(n)
        sigma = _random_symmetric(rng)
        P, Q = so.drucker_prager_tensors(sigma, rng.uniform(0, 0.8), rng.uniform(-0.5, 0.8))
        p, q = so.isotropic_vectors(lam, mu, P, Q, n)
        min_191 = min(min_191, (p @ q - (n @ p) * (n @ q)) / max(1.0, abs(p @ q)))
        g = rng.uniform(0.01, 5.0)
        if ac.cubic_discriminant(so.acoustic_tensor_isotropic(lam, mu, P, Q, g, n)) < -1e-9:
            complex_found += 1
        # General nonassociativity: flutter only above the localization modulus.
        P2, Q2 = _random_symmetric(rng), _random_symmetric(rng)
        iv = so.flutter_interval_isotropic(lam, mu, P2, Q2, n)
        if iv is not None:
            n_flutter_cases += 1
            gE = so.localization_modulus_isotropic(lam, mu, P2, Q2, n)
            worst_gap = min(worst_gap, (iv[0] - gE) / max(1.0, abs(gE)))
    # Triple coalescence (eqs. 190, 193, 194).
    lam, mu = 1.2, 0.8
    P, Q = so.drucker_prager_tensors(np.diag([1.0, -0.3, -0.7]), 0.5, 0.2)
    gC = so.coalescence_modulus(lam, mu, P, Q)
    w, V = np.linalg.eigh(so.apply(so.isotropic_elasticity(lam, mu), P))
    EQ = so.apply(so.isotropic_elasticity(lam, mu), Q)
    i = int(np.argmax(w * np.einsum("ji,jk,ki->i", V, EQ, V)))
    A = so.acoustic_tensor_isotropic(lam, mu, P, Q, gC, V[:, i])
    char = np.poly(A)  # compared with (eta - mu)^3
    triple = np.poly([mu, mu, mu])
    return {
        "n_samples": n_samples, "n_flutter_cases": n_flutter_cases,
        "quantities": {
            "deviatoric_associativity_no_flutter": quantity(
                "excluded" if complex_found == 0 else f"{complex_found} flutter",
                "excluded" if min_191 >= -1e-12 else "violated",
                "brute force: cubic discriminant of A at random g > 0",
                "eq. (191) >= 0 on the samples", ""),
            "flutter_above_localization": quantity(
                "always" if worst_gap >= -1e-10 else "violated",
                "always" if n_flutter_cases > 0 else "no flutter sampled",
                "g1 - g_cr^E(n) >= 0 on random nonassociative samples",
                "eq. (186): Delta >= 0 for g <= g_cr^E", ""),
            "triple_coalescence": quantity(
                float(np.max(np.abs(char - triple)) / mu**3), 0.0,
                "char. polynomial of A at g_cr^C (eq. 194), n an eigenvector of S^ (eq. 193)",
                "(eta - mu)^3", ""),
        }}


# ---------------------------------------------------------------------- errata of §3
def check_errata_solids(params: dict[str, Any]) -> None:
    """The case as :func:`errata_solids` needs it: with a flutter interval (eq. 188 corrected;
    an outside audit: Q = P, or n = e3, ended in a TypeError in the job)."""
    lam, mu, P, Q, n = _nonassociative_case(params)
    if so.flutter_interval_isotropic(lam, mu, P, Q, n) is None:
        raise ParameterError("P, Q, n: this case has no flutter interval (eq. 188, corrected), "
                             "so the erratum cannot be shown: give a nonassociative case with one")


def check_flutter_map(params: dict[str, Any]) -> None:
    """The plane case and the anisotropy section as :func:`flutter_map` refuses them (the
    configuration check; an outside audit: a stress without deviator failed in the job)."""
    _nonassociative_case({**params["plane_case"], "n": [1, 0, 0]})
    a = anisotropy_setup(params["anisotropy"])
    for eps in params["anisotropy"]["eps_values"]:
        # the perturbed elasticity must stay positive definite (an outside audit ran eps = 100)
        least = float(np.linalg.eigvalsh(so.mandel_matrix(a.E0 + float(eps) * a.T)).min())
        if not least > 0:
            raise ParameterError(f"anisotropy.eps_values: eps = {eps:g} makes the elasticity "
                                 f"E0 + eps T not positive definite (its least Mandel "
                                 f"eigenvalue {least:.3g} Pa)")


def errata_solids(params: dict[str, Any]) -> dict[str, Any]:
    """Eq. (188) as printed vs corrected vs brute force, for the nonassociative case."""
    take(params, {"lam", "mu", "P", "Q", "n"})
    check_errata_solids(params)
    lam, mu, P, Q, n = _nonassociative_case(params)
    E = so.isotropic_elasticity(lam, mu)
    corrected = so.flutter_interval_isotropic(lam, mu, P, Q, n)
    printed = so.flutter_interval_as_printed(lam, mu, P, Q, n)
    brute = ac.flutter_interval_bruteforce(E, P, Q, n, g_max=10 * corrected[1])
    if printed is None:  # the printed form gives no interval (null: the data is strict JSON)
        printed = (None, None)
    return {"errata": {
        f"eq188_g{k + 1}": {
            "quantity": f"g{k + 1} of eq. (188) [Pa]", "printed": printed[k],
            "corrected": corrected[k], "independent": brute[0][k],
            "independent_method": "brute force: sign changes of the discriminant of "
                                  "det(A(n) - eta I), Brent"} for k in range(2)}}
