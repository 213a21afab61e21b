# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""The time one identification takes: the sample plan (samples/identify_sedan.yaml)."""
from __future__ import annotations

from pathlib import Path
import time
from typing import Any

from ament_index_python.packages import get_package_share_directory

from vd_events.measured.identify import identify, load_identify_plan


def sample_plan() -> Path:
    """Return the installed sample identification plan."""
    return Path(get_package_share_directory('vd_events')) / 'samples' / 'identify_sedan.yaml'


def bench_identify() -> dict[str, Any]:
    """
    Identify the sample plan once (nothing written): wall time with and without set-up.

    Set-up is the base configuration's K&C and steering ratio (the bicycle's axle
    properties); the fit is the least squares, its Jacobian at the solution, before/after
    and the cross-validation's correlation.
    """
    plan = load_identify_plan(sample_plan())
    started = time.perf_counter()
    result = identify(plan)
    total = time.perf_counter() - started
    return {'total_s': total, 'fit_s': result.seconds, 'evaluations': result.evaluations,
            'model': plan.model, 'parameters': len(plan.parameters),
            'residuals': result.points}


__all__ = ['bench_identify', 'sample_plan']
