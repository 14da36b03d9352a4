"""flutterfriction: a verified reproduction of *Flutter from friction in solids and structures*.

The package is split by concern:

- :mod:`flutterfriction.models`: mechanical systems as data and matrices (no solving),
- :mod:`flutterfriction.closed_forms`: the chapter's closed-form results, equation by equation,
- :mod:`flutterfriction.analysis`: numerical solvers that work on any model,
- :mod:`flutterfriction.plotting`: one function per figure, returning a matplotlib Figure,
- :mod:`flutterfriction.reference`: the tolerance check against ``workflow/reference.yaml``.
"""

from flutterfriction.errors import ConvergenceError, ParameterError
from flutterfriction.models.ziegler import ZieglerPendulum

__all__ = ["ConvergenceError", "ParameterError", "ZieglerPendulum"]
__version__ = "0.1.0"
