# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
The steering map of a configuration: road-wheel angles of both front wheels vs the wheel.

From the K&C ``steering`` event of the front axle (cached by data hash): the
steering-wheel angle sorted increasing, the road-wheel angles (rad, + left) of the left
and right wheel relative to straight ahead, and the steering ratio at the centre (slope
of the steering-wheel angle over the mean road-wheel angle through the five points
nearest the centre). The full vehicle steers with it, and the steady-state two-track
model takes its steering-wheel angle from it, so both rungs read one map.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from vd_data_server.model import Configuration
from vd_solvers.errors import SolverError
from vd_solvers.kc.cache import kc_result


@dataclass(frozen=True, eq=False)
class SteeringMap:
    """Road-wheel angles vs steering-wheel angle (SI, + left)."""

    swa: np.ndarray  # (n,) rad, increasing
    angles: np.ndarray  # (n, 2) rad, left and right road-wheel angle
    ratio: float  # -, at the centre
    source: str

    def road_wheel_angles(self, swa: float) -> tuple[float, float]:
        """Steer angles (rad, + left) of the left and right wheel at ``swa`` (rad)."""
        return (float(np.interp(swa, self.swa, self.angles[:, 0])),
                float(np.interp(swa, self.swa, self.angles[:, 1])))

    def steering_wheel_angle(self, mean_angle: float) -> float:
        """Steering-wheel angle (rad) at which the mean road-wheel angle is ``mean_angle``."""
        return float(np.interp(mean_angle, self.angles.mean(axis=1), self.swa))

    @property
    def lock(self) -> float:
        """Largest steering-wheel angle both ways, rad."""
        return float(min(-self.swa[0], self.swa[-1]))


def steering_map(config: Configuration, fidelity: str = 'rigid', steps: int = 41) -> SteeringMap:
    """Return the steering map of ``config`` (module doc)."""
    if 'steering' not in config.groups:
        raise SolverError(f"configuration '{config.name}': the steering map needs a steering "
                          'group')
    steer = kc_result(config, 'front', 'steering', fidelity, steps=steps)
    swa = steer.channels['steering_wheel_angle']
    order = np.argsort(swa)
    swa = swa[order]
    angles = steer.channels['steer_angle'][order]
    centre = int(np.argmin(np.abs(swa)))
    angles = angles - angles[centre]
    mean = angles.mean(axis=1)
    near = slice(max(centre - 2, 0), centre + 3)
    ratio = float(np.polyfit(mean[near], swa[near], 1)[0])
    source = (f'front: K&C steering ({fidelity}, data hash {config.data_hash}), ratio '
              f'{ratio:.1f} at the centre')
    return SteeringMap(swa, angles, ratio, source)


__all__ = ['SteeringMap', 'steering_map']
