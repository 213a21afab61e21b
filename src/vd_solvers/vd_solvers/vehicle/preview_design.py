# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Gains of the optimal preview driver: discrete linear-quadratic control with the path ahead.

The plant is the linear single track of :func:`vd_solvers.analytical.bicycle.state_space`
(lateral velocity v at the CoG, yaw rate r; the configuration's effective axle cornering
stiffnesses) at forward speed V, put on a path of curvature kappa(s) and steered through
a first-order lag ``lag`` (the driver's neuromuscular and the steering system's lag, as in
Sharp, Casanova & Symonds, *A mathematical model for driver steering control, with
design, tuning and performance results*, Vehicle System Dynamics 33(5), 2000). States
x = (e, dpsi, v, r, delta)::

    e'     = V dpsi + v - c r          (1)  lateral offset of the reference point from
                                            the path, m, + left of it; c its distance
                                            behind the CoG
    dpsi'  = r - V kappa               (2)  yaw angle less the path's heading, rad
    (v, r)' = A (v, r) + B delta       (3)  the single track (Milliken ch. 5)
    delta' = (u - delta) / lag         (4)  road-wheel angle, rad; u the driver's command

Sampled every ``sample`` s with the command and the curvature held over the sample
(zero-order hold: x_{k+1} = F x_k + G u_k + W kappa_k). The driver sees the path's
curvature at the N + 1 stations V T j ahead, j = 0 … N (N = ``horizon`` / ``sample``):
the preview vector w_k, shifted by one station each sample with zero beyond the horizon
(w_{k+1} = D w_k, D nilpotent). The command minimises

    sum_k (e_k / error_scale)^2 + (u_k / steer_scale)^2

over the augmented system z = (x, w) (the discrete algebraic Riccati equation,
scipy.linalg.solve_discrete_are): u_k = -K_x x_k - K_w w_k. This is the discrete-time
optimal preview control of Tomizuka (*Optimal continuous finite preview problem*, IEEE
Trans. Automatic Control 20(3), 1975, in discrete form) as Sharp et al. (2000) and
Sharp & Valtetsiotis (*Optimal preview car steering control*, VSD 35 suppl., 2001)
apply it to the car: the feedback gains K_x are those of the infinite-horizon regulator
of the plant alone, the preview gains K_w decay along the horizon with the closed loop's
own poles, so a horizon longer than its slowest time constant makes the truncation
negligible. On a constant curvature the steady command is then the single track's
steady-state angle (L + K V^2) kappa with e = 0 and dpsi the reference point's slip angle.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.linalg import expm, solve_discrete_are

from vd_solvers.analytical.bicycle import state_space
from vd_solvers.analytical.params import VehicleParams
from vd_solvers.errors import SolverError

#: states of the plant (e, dpsi, v, r, delta)
STATES = 5


# Holds numpy arrays, whose element-wise == makes a generated __eq__ useless.
@dataclass(frozen=True, eq=False)
class PreviewGains:
    """
    The sampled plant and the optimal preview gains at one speed (module doc).

    ``plant``: F (5, 5), ``steer``: G (5,), ``path``: W (5,) (per 1/m of curvature);
    ``feedback``: K_x (5,) on (e m, dpsi rad, v m/s, r rad/s, delta rad); ``preview``: K_w
    (N + 1,) on the curvatures (1/m) at the stations ``spacing`` * j ahead (m); the
    command u = -K_x x - K_w w is a road-wheel angle, rad.
    """

    speed: float  # m/s
    sample: float  # s
    spacing: float  # m, V T
    plant: np.ndarray
    steer: np.ndarray
    path: np.ndarray
    feedback: np.ndarray
    preview: np.ndarray


def continuous_plant(p: VehicleParams, speed: float, behind: float, lag: float
                     ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """
    Return (A (5, 5), B (5,), E (5,)) of eqs. 1-4: x' = A x + B u + E kappa.

    ``behind``: the reference point's distance behind the CoG, m (c of eq. 1).
    """
    single = state_space(p, speed)
    a = np.zeros((STATES, STATES))
    a[0, 1], a[0, 2], a[0, 3] = speed, 1.0, -behind
    a[1, 3] = 1.0
    a[2:4, 2:4] = single.a
    a[2:4, 4] = single.b[:, 0]
    a[4, 4] = -1.0 / lag
    b = np.zeros(STATES)
    b[4] = 1.0 / lag
    e = np.zeros(STATES)
    e[1] = -speed
    return a, b, e


def preview_gains(p: VehicleParams, speed: float, behind: float, lag: float, sample: float,
                  horizon: float, error_scale: float, steer_scale: float) -> PreviewGains:
    """
    Return the optimal preview gains of the module doc at ``speed`` m/s.

    ``behind`` m (the reference point behind the CoG), ``lag`` s, ``sample`` s,
    ``horizon`` s of preview, ``error_scale`` m and ``steer_scale`` rad (road wheels): the
    lateral error and the command that cost alike. SolverError for settings out of range
    or when the Riccati equation has no stabilising solution.
    """
    if not (speed > 0.0 and lag > 0.0 and sample > 0.0 and horizon >= sample
            and error_scale > 0.0 and steer_scale > 0.0):
        raise SolverError(f'optimal preview driver: needs a positive speed ({speed!r} m/s), '
                          f'lag ({lag!r} s), sample ({sample!r} s), horizon ({horizon!r} s) '
                          'of at least one sample and positive cost scales')
    a, b, e = continuous_plant(p, speed, behind, lag)
    # zero-order hold of u and kappa over the sample: expm of the block matrix
    block = np.zeros((STATES + 2, STATES + 2))
    block[:STATES, :STATES] = a
    block[:STATES, STATES] = b
    block[:STATES, STATES + 1] = e
    held = expm(block * sample)
    plant, steer, path = held[:STATES, :STATES], held[:STATES, STATES], held[:STATES, STATES + 1]
    n = int(round(horizon / sample)) + 1
    size = STATES + n
    az = np.zeros((size, size))
    az[:STATES, :STATES] = plant
    az[:STATES, STATES] = path
    az[STATES:-1, STATES + 1:] = np.eye(n - 1)  # the preview shifts one station per sample
    bz = np.zeros((size, 1))
    bz[:STATES, 0] = steer
    q = np.zeros((size, size))
    q[0, 0] = 1.0 / error_scale**2
    r = np.array([[1.0 / steer_scale**2]])
    try:
        riccati = solve_discrete_are(az, bz, q, r)
    except (np.linalg.LinAlgError, ValueError) as err:
        raise SolverError(f'optimal preview driver: no stabilising gains at '
                          f'{speed * 3.6:.1f} km/h ({err})') from None
    gain = np.linalg.solve(r + bz.T @ riccati @ bz, bz.T @ riccati @ az)[0]
    if not np.all(np.isfinite(gain)):
        raise SolverError(f'optimal preview driver: no finite gains at {speed * 3.6:.1f} km/h')
    return PreviewGains(speed=speed, sample=sample, spacing=speed * sample, plant=plant,
                        steer=steer, path=path, feedback=gain[:STATES],
                        preview=gain[STATES:])


__all__ = ['STATES', 'PreviewGains', 'continuous_plant', 'preview_gains']
