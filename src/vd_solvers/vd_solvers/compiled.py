# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Compilation of the hot numerical paths (the full-vehicle forces, the Magic Formula, the maps).

The physics is written once, as plain functions on numpy arrays and floats; :func:`jit`
compiles them with numba (``nopython``, ``cache=True``: the machine code is cached beside
the sources and ``make setup`` builds it, see ``vd_solvers.warm``), with numpy's error model
(division by zero gives inf / nan as numpy does, no exception) and no fast-math, so compiled
and uncompiled evaluations agree to rounding.

``VD_NO_JIT=1`` in the environment (before the first import) runs the same functions as plain
Python (numba's ``NUMBA_DISABLE_JIT``): for a debugger, a profiler or coverage.
"""
from __future__ import annotations

from collections.abc import Callable
import os
from typing import Any, TypeVar, cast

if os.environ.get('VD_NO_JIT', '') not in ('', '0'):
    os.environ['NUMBA_DISABLE_JIT'] = '1'

import numba  # noqa: E402  (reads NUMBA_DISABLE_JIT when imported)

F = TypeVar('F', bound=Callable[..., Any])

#: True when the functions run compiled (VD_NO_JIT unset)
ENABLED: bool = os.environ.get('NUMBA_DISABLE_JIT', '') in ('', '0')


def jit(fn: F) -> F:
    """Compile ``fn`` (module doc); with VD_NO_JIT=1 it is returned as it is."""
    if not ENABLED:
        return fn
    return cast(F, numba.njit(cache=True, error_model='numpy')(fn))


__all__ = ['jit', 'ENABLED']
