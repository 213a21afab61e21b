# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""Helpers shared by the tests (import as `vdtest`)."""
from __future__ import annotations

from collections.abc import Callable
import os
from pathlib import Path
import subprocess
import sys
import time


def tree_snapshot(root: Path) -> dict[str, bytes]:
    """Every file under ``root`` with its bytes: to prove nothing was written."""
    return {str(p.relative_to(root)): p.read_bytes() for p in sorted(root.rglob('*'))
            if p.is_file()}


#: s: the longest a test waits for something that must happen (DDS discovery, a message, a
#: process's start or end). Not a performance bound: a loaded machine makes these waits
#: slower, never failed; only a hang (something that will never happen) meets this guard.
HANG_GUARD = 600.0


def wait_for(nodes, predicate: Callable[[], bool]) -> bool:
    """Spin ``nodes`` until ``predicate()`` holds (False only after HANG_GUARD s: a hang)."""
    return spin_until(nodes, predicate, HANG_GUARD)


def spin_until(nodes, predicate: Callable[[], bool], timeout: float = 10.0) -> bool:
    """
    Spin ``nodes`` until ``predicate()`` holds or ``timeout`` seconds pass.

    For something that must happen use :func:`wait_for`; a ``timeout`` here is for letting
    a fixed time pass (``lambda: False``) or for asserting that nothing happens.
    """
    from rclpy.executors import SingleThreadedExecutor

    executor = SingleThreadedExecutor()
    for node in nodes:
        executor.add_node(node)
    deadline = time.monotonic() + timeout
    try:
        while time.monotonic() < deadline:
            if predicate():
                return True
            executor.spin_once(timeout_sec=0.05)
        return predicate()
    finally:
        for node in nodes:
            executor.remove_node(node)
        executor.shutdown()


def replace_once(path: Path, old: str, new: str) -> None:
    """Edit a test's copy of a data file: ``old`` must occur exactly once."""
    text = path.read_text(encoding='utf-8')
    assert text.count(old) == 1, old
    path.write_text(text.replace(old, new), encoding='utf-8')



def line_no(path: Path, start: str) -> int:
    """1-based number of the first line of ``path`` that starts with ``start``."""
    lines = path.read_text(encoding='utf-8').splitlines()
    return next(n for n, line in enumerate(lines, start=1) if line.startswith(start))


def run_uncompiled(source: str, function: str, argument: Path, tmp_path: Path) -> dict:
    """
    Run ``function(argument)`` of ``source`` in a child with VD_NO_JIT=1 (arrays by name).

    ``source`` defines ``function`` and imports numpy as np; the child checks that nothing
    is compiled and returns the function's dict of arrays through an .npz file.
    """
    import numpy as np

    out = tmp_path / 'uncompiled.npz'
    code = (source + '\nimport sys\nfrom vd_solvers import compiled\n'
            'assert not compiled.ENABLED\n'
            f'np.savez(sys.argv[2], **{function}(sys.argv[1]))\n')
    env = dict(os.environ, VD_NO_JIT='1')
    env['PYTHONPATH'] = os.pathsep.join(
        [str(Path(p).resolve()) for p in sys.path if p] + [env.get('PYTHONPATH', '')])
    subprocess.run([sys.executable, '-c', code, str(argument), str(out)], env=env, check=True)
    with np.load(out) as data:
        return {k: data[k] for k in data.files}
