"""Result types shared by the closed forms and the numerical analysis (neither imports the other
for them): the regime of the linearised motion and the pendulum's critical loads."""

from __future__ import annotations

from dataclasses import asdict, dataclass
from enum import StrEnum


class Regime(StrEnum):
    """Nature of the linearised motion about equilibrium (chapter §2.3)."""

    STABLE = "stable"
    FLUTTER = "flutter"
    DIVERGENCE = "divergence"


@dataclass(frozen=True)
class CriticalLoads:
    """Critical loads of the pendulum [N]; ``None`` when a load does not exist.

    ``P_flu``, ``P_div`` are for the pendulum's own hinge viscosities (damped flutter is the
    Hopf crossing, damped divergence the load where the unstable pair becomes real);
    ``P_flu_undamped``, ``P_div_undamped`` for viscosity absent "from the beginning". The dead
    loads ``H_cr``, ``H_sup`` are quasi-static and do not depend on viscosity (§2.2, after eq. 31).
    """

    P_flu: float | None
    P_div: float | None
    H_cr: float | None
    H_sup: float | None
    P_flu_undamped: float | None = None
    P_div_undamped: float | None = None

    def as_dict(self) -> dict[str, float | None]:
        return asdict(self)
