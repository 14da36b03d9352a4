"""All figure functions by scene name (the plot rule looks a scene up here)."""

from flutterfriction.plotting import (
    rod,
    solids,
    ziegler,
    ziegler_damped,
    ziegler_nonlinear,
)

PLOTS = {**ziegler.PLOTS, **ziegler_damped.PLOTS, **rod.PLOTS, **solids.PLOTS,
         **ziegler_nonlinear.PLOTS}
