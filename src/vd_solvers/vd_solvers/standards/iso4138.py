# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
ISO 4138:2021 steady-state circular driving, constant-radius method: gradients and validity.

On a quasi-steady run on a circle with slowly increasing speed -- simulated or measured --
with steering-wheel angle, lateral acceleration, yaw rate and speed (SI, ISO 8855):

* **Filtering**: 12-pole phaseless Butterworth at FILTER_CUTOFF (1 Hz) on every signal:
  the run is quasi-steady, so only the steady content is kept (vd's choice).
* **Direction**: a left circle has a positive lateral acceleration; signals are taken
  in the direction of the turn, so both directions give the same gradients.
* **Gradients** over the linear range LINEAR_RANGE of lateral acceleration (1..3 m/s^2,
  the range vd's constant radius turn event uses), least-squares slopes against the
  lateral acceleration: steering-wheel angle gradient d(delta_H)/d(a_y); with the
  overall steering ratio i_s the understeer gradient
  K = d(delta_H / i_s - L / R)/d(a_y) (ISO 4138 / SAE J266: the steer angle less the
  Ackermann angle; on a constant radius L / R is constant, so K = d(delta_H)/d(a_y) / i_s;
  with the wheelbase L given, the radius actually driven R = v / r is used); roll and
  sideslip gradients where logged.
* **Limit**: the largest lateral acceleration while the radius is held.
* **Validity**: the radius held (R = v / r within RADIUS_TOLERANCE of its median over the
  linear range: vd's tolerance); the data cover the linear range with increments of
  lateral acceleration no larger than 0.5 m/s^2 (ISO 4138:2021, 8.3).

Signals in SI. Results carry SI.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .fmvss126 import ProcessingError, lowpass

FILTER_CUTOFF = 1.0  # Hz
LINEAR_RANGE = (1.0, 3.0)  # m/s^2
MAX_INCREMENT = 0.5  # m/s^2 (ISO 4138:2021, 8.3)
RADIUS_TOLERANCE = 0.05  # of the median radius over the linear range (vd's)
MIN_SPEED = 3.0  # m/s: below, v / r is no radius


@dataclass(frozen=True)
class CircleGrade:
    """One constant-radius run: gradients (SI per m/s^2), limit and validity."""

    direction: int  # +1 left circle, -1 right
    radius: float  # m, median of v / r over the linear range
    steering_gradient: float  # rad/(m/s^2), steering-wheel angle
    understeer_gradient: float | None  # rad/(m/s^2), with the steering ratio
    roll_gradient: float | None  # rad/(m/s^2)
    sideslip_gradient: float | None  # rad/(m/s^2)
    max_lateral_acceleration: float  # m/s^2 while the radius is held
    radius_error: float  # max |R - radius| / radius over the linear range
    largest_increment: float  # m/s^2, the widest gap in the sorted lateral acceleration
    covered: tuple[float, float]  # m/s^2, lateral acceleration range of the run
    ackermann: str  # how the Ackermann term was taken

    @property
    def checks(self) -> dict[str, bool]:
        return {'radius_held': self.radius_error <= RADIUS_TOLERANCE,
                'linear_range_covered': (self.covered[0] <= LINEAR_RANGE[0] and
                                         self.covered[1] >= LINEAR_RANGE[1]),
                'increments': self.largest_increment <= MAX_INCREMENT}

    @property
    def valid(self) -> bool:
        return all(self.checks.values())

    def describe_checks(self) -> list[str]:
        c = self.checks
        word = {True: 'ok', False: 'FAILED'}
        return [f'radius {self.radius:.1f} m held within {100 * self.radius_error:.1f} % over '
                f'{LINEAR_RANGE[0]:g}..{LINEAR_RANGE[1]:g} m/s^2 (<= '
                f"{100 * RADIUS_TOLERANCE:g} %, vd): {word[c['radius_held']]}",
                f'lateral acceleration {self.covered[0]:.2f}..{self.covered[1]:.2f} m/s^2 '
                f'covers the linear range {LINEAR_RANGE[0]:g}..{LINEAR_RANGE[1]:g} m/s^2: '
                f"{word[c['linear_range_covered']]}",
                f'largest increment of lateral acceleration {self.largest_increment:.3f} m/s^2 '
                f"(<= {MAX_INCREMENT:g} m/s^2, ISO 4138 8.3): {word[c['increments']]}"]


def _slope(x: np.ndarray, y: np.ndarray) -> float:
    return float(np.polyfit(x, y, 1)[0])


def grade_circle(t, steering, lateral_acceleration, yaw_rate, speed, *, roll=None,
                 sideslip=None, steering_ratio: float | None = None,
                 wheelbase: float | None = None) -> CircleGrade:
    """Process one constant-radius run (module doc); ProcessingError names the problem."""
    t = np.asarray(t, dtype=float)
    named = {'steering': steering, 'lateral_acceleration': lateral_acceleration,
             'yaw_rate': yaw_rate, 'speed': speed, 'roll': roll, 'sideslip': sideslip}
    for name, x in named.items():
        if x is None:
            continue
        x = np.asarray(x, dtype=float)
        if x.shape != t.shape:
            raise ProcessingError(f'{name} has {x.size} samples, time has {t.size}')
        if not np.all(np.isfinite(x)):
            raise ProcessingError(f'{name} holds non-finite samples')
    for name, value in (('steering ratio', steering_ratio), ('wheelbase', wheelbase)):
        if value is not None and not value > 0.0:
            raise ProcessingError(f'the {name} must be positive, got {value!r}')
    f = {name: lowpass(t, np.asarray(x, dtype=float), FILTER_CUTOFF)
         for name, x in named.items() if x is not None}
    direction = 1 if float(np.mean(f['lateral_acceleration'])) >= 0.0 else -1
    ay = direction * f['lateral_acceleration']
    moving = f['speed'] > MIN_SPEED
    radius_all = np.full_like(t, np.inf)
    turning = moving & (np.abs(f['yaw_rate']) > 1e-6)
    radius_all[turning] = f['speed'][turning] / np.abs(f['yaw_rate'][turning])
    linear = moving & (ay >= LINEAR_RANGE[0]) & (ay <= LINEAR_RANGE[1])
    if np.count_nonzero(linear) < 3:
        raise ProcessingError(f'fewer than 3 samples with a lateral acceleration of '
                              f'{LINEAR_RANGE[0]:g}..{LINEAR_RANGE[1]:g} m/s^2 in the turn')
    radius = float(np.median(radius_all[linear]))
    error = np.abs(radius_all / radius - 1.0)
    radius_error = float(np.max(error[linear]))
    held = moving & (error <= RADIUS_TOLERANCE)
    steer = direction * f['steering']
    grad = _slope(ay[linear], steer[linear])
    understeer = None
    ackermann = 'no steering ratio: understeer gradient not computed'
    if steering_ratio is not None:
        if wheelbase is not None:
            curvature = np.abs(f['yaw_rate']) / np.maximum(f['speed'], MIN_SPEED)
            understeer = _slope(ay[linear], steer[linear] / steering_ratio
                                - wheelbase * curvature[linear])
            ackermann = f'Ackermann angle L r / v of the path driven (L = {wheelbase:g} m)'
        else:
            understeer = grad / steering_ratio
            ackermann = 'constant radius: the Ackermann angle L / R taken as constant'
    roll_grad = None if 'roll' not in f else _slope(ay[linear], direction * f['roll'][linear])
    beta_grad = None if 'sideslip' not in f else _slope(ay[linear],
                                                         direction * f['sideslip'][linear])
    ordered = np.sort(ay[moving])
    span = ordered[(ordered >= LINEAR_RANGE[0]) & (ordered <= LINEAR_RANGE[1])]
    edges = np.concatenate(([LINEAR_RANGE[0]], span, [LINEAR_RANGE[1]]))
    return CircleGrade(
        direction=direction, radius=radius, steering_gradient=grad,
        understeer_gradient=understeer, roll_gradient=roll_grad, sideslip_gradient=beta_grad,
        max_lateral_acceleration=float(np.max(ay[held])) if np.any(held) else float('nan'),
        radius_error=radius_error, largest_increment=float(np.max(np.diff(edges))),
        covered=(float(ordered[0]), float(ordered[-1])), ackermann=ackermann)


__all__ = ['CircleGrade', 'grade_circle', 'LINEAR_RANGE', 'RADIUS_TOLERANCE', 'MAX_INCREMENT']
