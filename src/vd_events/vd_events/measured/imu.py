# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
An IMU's lateral acceleration as the car's: moved to the centre of gravity, roll-corrected.

A body-fixed accelerometer measures the specific force at its own position along the
body's y axis. The car's lateral acceleration (ISO 8855: at the CoG, in the horizontal
plane) follows in two steps (49 CFR 571.126 S7.11.3 asks for both: "removing the effects
caused by vehicle body roll and by correcting for sensor placement via use of coordinate
transformation"):

1. **Sensor position** (rigid-body kinematics, e.g. Meriam & Kraige, Engineering
   Mechanics: Dynamics, relative acceleration in a rotating frame):
   a_P = a_G + w' x rho + w x (w x rho), with rho = (x_P, y_P, z_P) the IMU's position
   from the CoG in the body axes (x forward, y left, z up) and w = (p, 0, r) (roll rate,
   pitch neglected, yaw rate); its y component gives

       a_G,y = a_P,y - r' x_P + p' z_P + (p^2 + r^2) y_P

   with r' and p' differentiated from the logged yaw rate and roll angle (low-passed at
   DERIVATIVE_CUTOFF first, per gap-free segment).
2. **Roll** (ISO 8855 roll phi, positive left side up): the body's y axis is tilted by phi,
   so it reads a_y cos(phi) + g sin(phi) of a horizontal a_y without vertical
   acceleration; hence

       a_y = (a_G,y - g sin(phi)) / cos(phi).

Without a roll angle or an IMU position the signal is left as measured and the import
says so.
"""
from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from vd_events.measured.checks import segments
from vd_solvers.constants import STANDARD_GRAVITY as G
from vd_solvers.standards.fmvss126 import ProcessingError, lowpass

DERIVATIVE_CUTOFF = 6.0  # Hz (the FMVSS 126 response filter)


def _derivative(t: np.ndarray, x: np.ndarray, interval: float) -> np.ndarray:
    """dx/dt per gap-free segment, low-passed first where the segment is long enough."""
    out = np.zeros_like(x)
    for s in segments(t, interval):
        if s.stop - s.start < 3:
            continue
        xs = x[s]
        try:
            xs = lowpass(t[s], xs, DERIVATIVE_CUTOFF)
        except ProcessingError:
            pass  # a short or coarse segment: differentiated as logged
        out[s] = np.gradient(xs, t[s])
    return out


def to_cog(t: np.ndarray, ay_imu: np.ndarray, yaw_rate: np.ndarray, roll: np.ndarray | None,
           position: Sequence[float] | None, interval: float) -> np.ndarray:
    """Return the car's lateral acceleration from the IMU's (module doc); m/s^2."""
    ay = np.asarray(ay_imu, dtype=float).copy()
    p = np.zeros_like(ay) if roll is None else _derivative(t, roll, interval)
    if position is not None:
        xp, yp, zp = position
        r_dot = _derivative(t, yaw_rate, interval)
        p_dot = np.zeros_like(ay) if roll is None else _derivative(t, p, interval)
        ay = ay - r_dot * xp + p_dot * zp + (p ** 2 + yaw_rate ** 2) * yp
    if roll is not None:
        ay = (ay - G * np.sin(roll)) / np.cos(roll)
    return ay


__all__ = ['to_cog', 'DERIVATIVE_CUTOFF']
