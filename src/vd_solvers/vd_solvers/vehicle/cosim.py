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

from .drivers import wheel_torques
from .dynamics import PREVIOUS_ROWS, record_row
from .model import STEP, VehicleModel, WheelState
from .simulation import PER_WHEEL, TRACE

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
    """The vehicle state advanced one step at a time (module doc). Not thread-safe."""

    def __init__(self, model: VehicleModel, h: float = STEP, initial_speed: float = 0.0,
                 drive_front: float = 0.5, brake_front: float = 0.65) -> None:
        if not (math.isfinite(h) and 1e-4 <= h <= 0.02):
            raise SolverError(f'lock-step size must lie in [0.0001, 0.02] s, got {h!r}')
        self.model = model
        self.h = h
        self.drive_front, self.brake_front = drive_front, brake_front
        self.initial_speed = initial_speed
        self.max_angle = steering_lock(model)
        self.q, self.v = model.initial_state(initial_speed)
        self.slip = np.zeros((2, 4))
        self.previous: np.ndarray | None = None  # the last step's wheel rows PREVIOUS_ROWS
        self.step = 0
        self._cog = np.array(model.config.group('mass').point('sprung_cog'), dtype=float)
        self._last_swa = 0.0
        self._last_torque = 0.0
        self._state: dict[str, float] | None = None  # the current state's row, once built
        self.wheel: WheelState | None = None
        # the wheel quantities at the initial state, for the first published state
        _, self.wheel, _ = self.model.forces(self.q, self.v, 0.0, np.zeros(4), self.slip,
                                             None, h)

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
        q = self.q.copy()
        q[0], q[1] = x, y
        q[3:7] = pin.Quaternion(pin.rpy.rpyToMatrix(roll, pitch, yaw)).coeffs()
        self.q = q
        self._state = None

    @property
    def time(self) -> float:
        """Simulation time of the current state, s (step * h, no accumulated rounding)."""
        return self.step * self.h

    def advance(self, command: Command) -> None:
        """Apply ``command`` over one step (refused with CommandError, state unchanged)."""
        check_command(command, self.max_angle)
        model = self.model
        spin = np.ascontiguousarray(self.v[7::2])
        torques = (wheel_torques(float(command.drive_torque), self.drive_front,
                                 self.brake_front, spin)
                   + wheel_torques(-float(command.brake_torque), self.drive_front,
                                   self.brake_front, spin))
        q, v, slip, wheel = model.step(self.q, self.v, command.steering_wheel_angle, torques,
                                       self.slip, self.previous, self.h)
        before = self.state()
        self._state = None
        if not (np.all(np.isfinite(q)) and np.all(np.isfinite(v))):
            raise SolverError(f"{model.label('lockstep', self.time + self.h)}: the state "
                              'became non-finite')
        self.q, self.v, self.slip = q, v, slip
        self.previous = wheel[PREVIOUS_ROWS]
        self.wheel = WheelState(*wheel)
        self.step += 1
        self._last_swa = command.steering_wheel_angle
        self._last_torque = command.drive_torque - command.brake_torque
        after = self._row()
        # lateral and longitudinal acceleration of the CoG over the step (horizontal, yaw axes)
        ax = (after['cog_velocity_x'] - before['cog_velocity_x']) / self.h
        ay = (after['cog_velocity_y'] - before['cog_velocity_y']) / self.h
        c, s = math.cos(after['yaw']), math.sin(after['yaw'])
        after['longitudinal_acceleration'] = ax * c + ay * s
        after['lateral_acceleration'] = -ax * s + ay * c
        self._state = after

    def state(self) -> dict[str, float]:
        """Return the TRACE quantities of the current state, plus the accelerations (SI)."""
        if self._state is None:
            row = self._row()
            row['longitudinal_acceleration'] = row['lateral_acceleration'] = 0.0
            self._state = row
        return dict(self._state)

    def _row(self) -> dict[str, float]:
        assert self.wheel is not None
        row = record_row(self.q, self.v, self.time, float(self._last_swa), np.array(self.wheel),
                         self._cog, float(self._last_torque))
        return dict(zip(TRACE, row.tolist()))

    def wheels(self) -> dict[str, np.ndarray]:
        """Return the per-wheel quantities of the last step (PER_WHEEL, arrays FL FR RL RR)."""
        w = self.wheel
        assert w is not None
        return dict(zip(PER_WHEEL, (w.fz, w.travel, w.alpha, w.kappa, w.gamma, w.fx, w.fy,
                                    w.steer, w.mz)))


__all__ = ['Command', 'CommandError', 'Stepper', 'check_command', 'steering_lock',
           'STEERING_ANGLE', 'STEERING_TORQUE']
