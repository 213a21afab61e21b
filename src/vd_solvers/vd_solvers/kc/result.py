# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""The result of one K&C event: per-step channels and their exact rates at design."""
from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field

import numpy as np

from .model import Axle


def _empty() -> Mapping[str, np.ndarray]:
    return {}


@dataclass(frozen=True)
class EventResult:
    """
    One event's per-step channels and the parameters it ran with (SI).

    ``channels``: name -> array with the step first (see :mod:`.channels`).
    ``sweep``: the swept quantity (``pad_travel``, ``lateral_force`` ...) and
    ``sweep_unit`` its SI unit. ``design``: every channel at the design state
    (the swept quantity zero), without the step axis. ``rate_up`` and
    ``rate_down``: the exact derivative of every channel with respect to the
    swept quantity at design (implicit function theorem on the converged
    tangent, :func:`.solver.sensitivity`), for the load increasing and
    decreasing from design. They are equal unless the event's load path
    changes at design (the longitudinal event brakes at the contact point and
    drives at the wheel centre) or an element's curve has a kink exactly at
    the design state.
    """

    event: str
    axle: Axle
    label: str
    params: Mapping[str, float]
    channels: Mapping[str, np.ndarray]
    sweep: str = ''
    sweep_unit: str = ''
    design: Mapping[str, np.ndarray] = field(default_factory=_empty)
    rate_up: Mapping[str, np.ndarray] = field(default_factory=_empty)
    rate_down: Mapping[str, np.ndarray] = field(default_factory=_empty)

    @property
    def steps(self) -> int:
        """Return the number of steps."""
        return int(self.channels['wheel_travel'].shape[0])
