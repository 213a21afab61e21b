# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Replay of measured inputs through the linear single track (bicycle model).

The model of :func:`.bicycle.state_space` (states lateral velocity v and yaw rate r)
with the forward speed u(t) and road-wheel angle delta(t) = delta_sw(t) / i_s of a log,
both linear between the logged samples; integrated with scipy's RK45 (``max_step`` the
log's sample interval) from straight running, and sampled at the log's times. Outputs:
yaw rate r, lateral acceleration a_y = v' + u r (with the direct feed-through of the
steer, as in ``state_space``), sideslip at the CoG beta = atan(v / u). The speed must
stay above MIN_SPEED: the linear single track has no meaning at walking pace.
"""
from __future__ import annotations

import numpy as np
from scipy.integrate import solve_ivp

from vd_solvers.analytical.bicycle import effective_cornering_stiffness, state_space
from vd_solvers.analytical.params import VehicleParams
from vd_solvers.errors import SolverError

MIN_SPEED = 3.0  # m/s


def replay_bicycle(p: VehicleParams, steering_ratio: float, time: np.ndarray,
                   swa: np.ndarray, speed: np.ndarray) -> dict[str, np.ndarray]:
    """SI channels of the single track driven by a log (module doc)."""
    t = np.asarray(time, dtype=float)
    t = t - t[0]
    u_log = np.asarray(speed, dtype=float)
    delta_log = np.asarray(swa, dtype=float) / steering_ratio
    slow = np.nonzero(u_log < MIN_SPEED)[0]
    if slow.size:
        raise SolverError(f'bicycle replay: the speed falls to {u_log[slow[0]]:.2f} m/s at '
                          f't = {t[slow[0]]:.2f} s (the linear model needs > {MIN_SPEED:g} m/s)')

    cornering = effective_cornering_stiffness(p)

    def rhs(s: float, x: np.ndarray) -> np.ndarray:
        ss = state_space(p, float(np.interp(s, t, u_log)), cornering)
        return ss.a @ x + ss.b[:, 0] * float(np.interp(s, t, delta_log))

    sol = solve_ivp(rhs, (0.0, float(t[-1])), np.zeros(2), t_eval=t,
                    max_step=float(np.min(np.diff(t))), rtol=1e-8, atol=1e-10)
    if not sol.success:
        raise SolverError(f'bicycle replay: integration failed: {sol.message}')
    v, r = sol.y
    a_y = np.empty_like(t)
    for i, (u, d) in enumerate(zip(u_log, delta_log)):
        ss = state_space(p, float(u), cornering)
        a_y[i] = float((ss.c[1] @ sol.y[:, i]) + ss.d[1, 0] * d)
    return {'time': t, 'yaw_rate': r, 'lateral_acceleration': a_y,
            'sideslip': np.arctan2(v, u_log), 'lateral_velocity': v, 'speed': u_log,
            'steering_wheel_angle': np.asarray(swa, dtype=float), 'steer_angle': delta_log}


__all__ = ['replay_bicycle', 'MIN_SPEED']
