# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""Wall-clock timing for the benchmark suite (``vd bench``), never for pass/fail tests."""
from __future__ import annotations

from collections.abc import Callable
import statistics
import time
from typing import Any

#: repetitions of a timed call; the median is reported
REPEATS = 3


def median_time(fn: Callable[[], Any], repeats: int = REPEATS) -> float:
    """Median wall-clock seconds of ``repeats`` calls of ``fn``."""
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return statistics.median(times)


def median_cpu_time(fn: Callable[[], Any], repeats: int = REPEATS) -> float:
    """Median CPU seconds of this process over ``repeats`` calls of ``fn``."""
    times = []
    for _ in range(repeats):
        t0 = time.process_time()
        fn()
        times.append(time.process_time() - t0)
    return statistics.median(times)
