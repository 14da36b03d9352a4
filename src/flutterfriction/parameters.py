"""The chapter's parameter lists, defined once (SI units).

Everything that uses them reads them from here: the workflow configuration names them
(``pendulum: list47``, resolved by :func:`flutterfriction.config.expand_parameter_lists`), the
CLI's defaults, the stress tests, the test suite, the notebooks and the report's table of
parameter lists.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from types import MappingProxyType
from typing import Any


@dataclass(frozen=True)
class ParameterList:
    """One list of the chapter: its values, what kind of system they describe, where it is."""

    name: str  # as written in workflow/config.yaml
    kind: str  # "pendulum" (ZieglerPendulum), "rod" (Rod) or "solid"
    source: str  # where the chapter gives it
    values: Mapping[str, Any]
    note: str = ""


def _frozen(**values: Any) -> Mapping[str, Any]:
    return MappingProxyType(values)


#: List (47), §2.3: the device of §2.10, l = 3d = 3h = 100 mm, m1 = 12 m2 = 4 m3 = 552 g,
#: k1 = k2 = 0.189 N m.
LIST_47 = _frozen(l1=0.1, l2=0.1, d=0.1 / 3, h=0.1 / 3, m1=0.552, m2=0.046, m3=0.138,
                  k1=0.189, k2=0.189)
#: Hinge viscosity of the device (Fig. 19; inferred from the quoted ratios 0.70 and 1.49).
SEC_210_VISCOSITY = 0.006
#: List (47) with the hinge viscosity c1 = c2 = 0.006 N m s (§2.10, Figs. 19–21).
LIST_47_VISCOUS = _frozen(**LIST_47, c1=SEC_210_VISCOSITY, c2=SEC_210_VISCOSITY)
#: §2.9, Figs. 13–14: l1 = l2 = 0.1 m, d = l1, m1 = m2 = 0.2 kg, m3 = 0, k1 = k2 = 0.189 N m,
#: c1 = c2 = 0.006 N m s.
SEC_29 = _frozen(l1=0.1, l2=0.1, d=0.1, h=0.0, m1=0.2, m2=0.2, m3=0.0, k1=0.189, k2=0.189,
                 c1=0.006, c2=0.006)
#: List (119), §2.7: l = 0.350 m, rho = 0.0546 kg/m, B = 0.0332 N m², D = 7.078e-6 N m² s
#: (Kelvin–Voigt); P = 5.5 N is the load of Figs. 15–17.
LIST_119 = _frozen(length=0.35, B=0.0332, rho=0.0546, D=7.078e-6)
LIST_119_LOAD = 5.5
#: §3.3–3.5 (our choice: the chapter gives no numbers): isotropic elasticity with Lamé
#: constants lam = mu = 1 Pa and unit density, and a nonassociative flow rule whose deviatoric
#: parts differ (P, Q in Voigt order 11, 22, 33, 23, 13, 12).
SEC_35 = _frozen(lam=1.0, mu=1.0, P=(1.0, -0.5, -0.5, 0.0, 0.0, 0.8),
                 Q=(0.6, -0.3, -0.3, 0.0, 0.0, -0.8))

LISTS: Mapping[str, ParameterList] = MappingProxyType({p.name: p for p in (
    ParameterList("list47", "pendulum", "list (47), §2.3", LIST_47),
    ParameterList("list47_viscous", "pendulum", "list (47) with c1 = c2 = 0.006 N m s, §2.10",
                  LIST_47_VISCOUS,
                  "the viscosity is §2.9's 0.006 N m s; Fig. 19's quoted ratios 0.70, 1.49 "
                  "give 0.00625, 0.00605 (within their two digits)"),
    ParameterList("sec29", "pendulum", "§2.9, Figs. 13–14", SEC_29),
    ParameterList("list119", "rod", "list (119), §2.7", LIST_119,
                  "P = 5.5 N for Figs. 15–17"),
    ParameterList("sec35", "solid", "§3.3–3.5 (our choice)", SEC_35,
                  "the chapter gives no numbers for the acoustic-tensor examples"),
)})

#: Configuration keys that may name a list, and the kind of list they take.
NAMED_KEYS = MappingProxyType({"pendulum": "pendulum", "cycle_pendulum": "pendulum",
                               "rod": "rod"})


def parameter_list(name: str, kind: str | None = None) -> dict[str, Any]:
    """A fresh dict of the list ``name`` (of the given ``kind``), or a one-line error naming
    the lists there are."""
    from flutterfriction.errors import ParameterError

    known = sorted(n for n, p in LISTS.items() if kind is None or p.kind == kind)
    if name not in known:
        raise ParameterError(f"unknown parameter list {name!r}; known {kind or ''} lists: "
                             f"{known}")
    return {k: list(v) if isinstance(v, tuple) else v for k, v in LISTS[name].values.items()}
