"""One BLAS thread for this package's computations.

Every matrix here is small (a pendulum's 4x4, a rod's FE model up to a few hundred unknowns),
and on them BLAS threads only spin and contend: measured on a 2-core machine,
``flutterfriction rod --mass-ratio 0.5932505 --p-max 300`` took 7.6 s with OpenBLAS's default
threads and 1.1 s with one, and one damped rod spectrum 1.57 s against 6 ms. The workflow sets
``OPENBLAS_NUM_THREADS=1`` for its jobs (Snakefile); the command line and the tests limit the
already loaded BLAS with :func:`one_blas_thread`. A thread count the user set in the
environment is kept (0, OpenBLAS's "default", is no count).
"""

from __future__ import annotations

import contextlib
import os
from collections.abc import Iterator

#: Environment variables that set the BLAS thread count; any of them set means the user chose.
THREAD_VARIABLES = ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS")


@contextlib.contextmanager
def one_blas_thread() -> Iterator[None]:
    """Run the block with one BLAS thread (unless the environment sets a count)."""
    if any(os.environ.get(name, "").strip() not in ("", "0") for name in THREAD_VARIABLES):
        # (0 is OpenBLAS's "default", not a choice of one)
        yield
        return
    from threadpoolctl import threadpool_limits

    with threadpool_limits(limits=1, user_api="blas"):
        yield
