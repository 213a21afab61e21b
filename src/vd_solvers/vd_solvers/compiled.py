# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Compilation of the hot numerical paths (the full-vehicle forces, the Magic Formula, the maps).

The physics is written once, as plain functions on numpy arrays and floats; :func:`jit`
compiles them with numba (``nopython``, ``cache=True``: the machine code is cached beside
the sources and ``make setup`` builds it, see ``vd_solvers.warm``), with numpy's error model
(division by zero gives inf / nan as numpy does, no exception) and no fast-math, so compiled
and uncompiled evaluations agree to rounding.

numba is imported, and a function's machine code loaded, at the first call of a compiled
function, not when a module defining one is imported: importing numba costs about half a
second of CPU, which a process that calls none (``vd data``, the reports) never pays. A
compiled function called from another is compiled (or loaded from the cache) when that one
is. The K&C solver compiles its per-evaluation loops over the primitives
(``kc.joints.primitives``, ``kc.system.second_order_sum``).

``VD_NO_JIT=1`` in the environment (before the first import) runs the same functions as plain
Python (numba's ``NUMBA_DISABLE_JIT``): for a debugger, a profiler or coverage.
"""
from __future__ import annotations

from collections.abc import Callable
import functools
import os
from typing import Any, TypeVar, cast

F = TypeVar('F', bound=Callable[..., Any])

#: True when the functions run compiled (VD_NO_JIT unset)
ENABLED: bool = (os.environ.get('VD_NO_JIT', '') in ('', '0')
                 and os.environ.get('NUMBA_DISABLE_JIT', '') in ('', '0'))


class Compiled:
    """
    A function compiled with numba at its first call (module doc).

    Called from Python it runs the compiled code; named inside another compiled function,
    numba types it as the numba dispatcher it stands for (``_numba_type_``), so compiled
    code calls compiled code directly. Other attributes (``signatures``, ...) are the
    dispatcher's; ``py_func`` is the function as written.
    """

    def __init__(self, fn: Callable[..., Any]) -> None:
        self.py_func = fn
        self._dispatcher: Any = None
        functools.update_wrapper(self, fn)

    @property
    def dispatcher(self) -> Any:
        """The numba dispatcher of the function (numba is imported here, once)."""
        if self._dispatcher is None:
            import numba

            self._dispatcher = numba.njit(cache=True, error_model='numpy')(self.py_func)
        return self._dispatcher

    @property
    def _numba_type_(self) -> Any:
        from numba.core import types

        return types.Dispatcher(self.dispatcher)

    def __call__(self, *args: Any, **kwargs: Any) -> Any:
        return self.dispatcher(*args, **kwargs)

    def __getattr__(self, name: str) -> Any:
        if name.startswith('__') or name in ('py_func', '_dispatcher'):
            raise AttributeError(name)
        return getattr(self.dispatcher, name)


def jit(fn: F) -> F:
    """Compile ``fn`` at its first call (module doc); with VD_NO_JIT=1 it is returned as it is."""
    if not ENABLED:
        return fn
    return cast(F, Compiled(fn))


__all__ = ['jit', 'Compiled', 'ENABLED']
