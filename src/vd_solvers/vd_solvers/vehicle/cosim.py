# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Lock-step co-simulation core: the full vehicle advanced one fixed step per command.

ROS-free; ``vehicle_solver`` in ``lockstep`` (or ``free``) mode wraps it. A
:class:`Stepper` holds the state at simulation time ``t = step * h``; :meth:`Stepper.advance`
applies one :class:`Command` over ``[t, t + h]`` with the same force evaluation, semi-implicit
Euler step and transient-slip update as :func:`.simulation.simulate`.

A command is checked before it is applied (:func:`check_command`): finite values, drive
and brake torques >= 0, the steering-wheel angle within the steering map, and steering
by angle (the model has no steering-system inertia, so a steering torque cannot be
applied and is refused). A refused command leaves the state unchanged.
"""
from __future__ import annotations

from dataclasses import dataclass
import math

import numpy as np
import pinocchio as pin

from vd_solvers.errors import SolverError

from .dynamics import ROW_SIZE, cosim_step, record_row
from .model import STEP, VehicleModel
from .simulation import PER_WHEEL, TRACE, WHEEL_ROW

#: the values of :attr:`Stepper.row`: the recorded channels, then the CoG's accelerations
STATE_KEYS = TRACE + ('longitudinal_acceleration', 'lateral_acceleration')
_VX, _VY, _YAW = (TRACE.index(k) for k in ('cog_velocity_x', 'cog_velocity_y', 'yaw'))

#: steering modes of a command (the VehicleCommand constants)
STEERING_ANGLE, STEERING_TORQUE = 0, 1


class CommandError(ValueError):
    """A command that cannot be applied (the message says why; the state is unchanged)."""


@dataclass(frozen=True)
class Command:
    """One step's command: steering-wheel angle (rad, + left), wheel torques (N*m, >= 0)."""

    steering_wheel_angle: float = 0.0
    drive_torque: float = 0.0
    brake_torque: float = 0.0
    steering_mode: int = STEERING_ANGLE
    steering_wheel_torque: float = 0.0


def check_command(command: Command, max_angle: float) -> None:
    """Raise CommandError when ``command`` cannot be applied (module doc)."""
    if command.steering_mode == STEERING_TORQUE:
        raise CommandError('steering by torque is not available: the vehicle model has no '
                           'steering-system inertia; command the steering-wheel angle '
                           '(steering_mode 0)')
    if command.steering_mode != STEERING_ANGLE:
        raise CommandError(f'unknown steering_mode {command.steering_mode} (0 angle, 1 torque)')
    for name in ('steering_wheel_angle', 'drive_torque', 'brake_torque'):
        value = getattr(command, name)
        if not math.isfinite(value):
            raise CommandError(f'{name} is not finite ({value})')
    if abs(command.steering_wheel_angle) > max_angle:
        raise CommandError(f'steering_wheel_angle {command.steering_wheel_angle:.4g} rad is '
                           f'beyond the steering lock of the model ({max_angle:.4g} rad)')
    for name in ('drive_torque', 'brake_torque'):
        if getattr(command, name) < 0.0:
            raise CommandError(f'{name} must be >= 0 N*m, got {getattr(command, name):.4g}')


def steering_lock(model: VehicleModel) -> float:
    """Return the steering-wheel angle at the end of the rack travel, rad (the map's ends)."""
    return float(min(-model.maps.steer_swa[0], model.maps.steer_swa[-1]))


class Stepper:
    """
    The vehicle state advanced one step at a time (module doc). Not thread-safe.

    The state lives in arrays updated in place by each step (one compiled call, no Python
    objects per step): ``q``, ``v``, :attr:`row` (STATE_KEYS) and :attr:`wheel_rows`
    (forces.WHEEL_ROWS x FL FR RL RR). Copy them to keep a step's values.
    """

    def __init__(self, model: VehicleModel, h: float = STEP, initial_speed: float = 0.0,
                 drive_front: float = 0.5, brake_front: float = 0.65) -> None:
        if not (math.isfinite(h) and 1e-4 <= h <= 0.02):
            raise SolverError(f'lock-step size must lie in [0.0001, 0.02] s, got {h!r}')
        self.model = model
        self.h = h
        self.drive_front, self.brake_front = drive_front, brake_front
        self.initial_speed = initial_speed
        self.max_angle = steering_lock(model)
        self.q, self.v = (np.array(a, dtype=float) for a in model.initial_state(initial_speed))
        self.slip = np.zeros((2, 4))
        self.step = 0
        self._cog = np.array(model.config.group('mass').point('sprung_cog'), dtype=float)
        # the last step's wheel rows dynamics.PREVIOUS_ROWS (none before the first step)
        self._previous = np.zeros((4, 4))
        self._has_previous = False
        # the wheel quantities at the initial state, for the first published state
        _, wheel, _ = self.model.forces(self.q, self.v, 0.0, np.zeros(4), self.slip, None, h)
        self.wheel_rows = np.ascontiguousarray(np.stack(wheel), dtype=float)
        self.row = np.zeros(len(STATE_KEYS))
        self._initial_row()

    def _initial_row(self) -> None:
        self.row[:ROW_SIZE] = record_row(self.q, self.v, self.time, 0.0, self.wheel_rows,
                                         self._cog, 0.0)
        self.row[ROW_SIZE:] = 0.0

    def place(self, x: float, y: float, yaw: float) -> None:
        """
        Put the vehicle at ``x``, ``y`` (m) heading ``yaw`` (rad) in the world; step 0 only.

        Roll and pitch, heights and the body-frame velocities stay (the state of a vehicle
        on a flat road does not depend on where it stands).
        """
        if self.step != 0:
            raise SolverError('the vehicle can be placed only before its first step')
        for name, value in (('x', x), ('y', y), ('yaw', yaw)):
            if not math.isfinite(value):
                raise SolverError(f'initial pose: {name} is not finite ({value})')
        roll, pitch, _ = pin.rpy.matrixToRpy(pin.Quaternion(self.q[3:7]).matrix())
        self.q[0], self.q[1] = x, y
        self.q[3:7] = pin.Quaternion(pin.rpy.rpyToMatrix(roll, pitch, yaw)).coeffs()
        self._initial_row()

    @property
    def time(self) -> float:
        """Simulation time of the current state, s (step * h, no accumulated rounding)."""
        return self.step * self.h

    def advance(self, command: Command) -> None:
        """Apply ``command`` over one step (refused with CommandError, state unchanged)."""
        check_command(command, self.max_angle)
        model, row = self.model, self.row
        vx, vy = row[_VX], row[_VY]
        if not cosim_step(self.q, self.v, self.slip, self._previous, self._has_previous,
                          self.wheel_rows, row, float(command.steering_wheel_angle),
                          float(command.drive_torque), float(command.brake_torque),
                          self.drive_front, self.brake_front, (self.step + 1) * self.h,
                          self.h, model.arrays, model.vx_floor, model.total_mass,
                          model.options.road, model.options.dampers, model.multibody,
                          self._cog):
            raise SolverError(f"{model.label('lockstep', self.time + self.h)}: the state "
                              'became non-finite')
        self._has_previous = True
        self.step += 1
        # lateral and longitudinal acceleration of the CoG over the step (horizontal, yaw axes)
        ax, ay = (row[_VX] - vx) / self.h, (row[_VY] - vy) / self.h
        c, s = math.cos(row[_YAW]), math.sin(row[_YAW])
        row[ROW_SIZE] = ax * c + ay * s
        row[ROW_SIZE + 1] = -ax * s + ay * c

    def state(self) -> dict[str, float]:
        """Return the STATE_KEYS of the current state (SI): TRACE, then the accelerations."""
        return dict(zip(STATE_KEYS, self.row.tolist()))

    def wheels(self) -> dict[str, np.ndarray]:
        """Return the per-wheel quantities of the last step (PER_WHEEL, arrays FL FR RL RR)."""
        return {key: self.wheel_rows[WHEEL_ROW[key]] for key in PER_WHEEL}


__all__ = ['Command', 'CommandError', 'Stepper', 'STATE_KEYS', 'check_command', 'steering_lock',
           'STEERING_ANGLE', 'STEERING_TORQUE']
