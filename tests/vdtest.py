"""Helpers shared by the tests (import as `vdtest`)."""
from __future__ import annotations

import time
from collections.abc import Callable
from pathlib import Path


def tree_snapshot(root: Path) -> dict[str, bytes]:
    """Every file under ``root`` with its bytes: to prove nothing was written."""
    return {str(p.relative_to(root)): p.read_bytes() for p in sorted(root.rglob("*"))
            if p.is_file()}


def spin_until(nodes, predicate: Callable[[], bool], timeout: float = 10.0) -> bool:
    """Spin ``nodes`` until ``predicate()`` holds or ``timeout`` seconds pass."""
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
