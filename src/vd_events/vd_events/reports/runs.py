# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
What the reports read from bags, and which plots each event gets.

:func:`load_runs` reads every EventResult of the bags (through
``vd_solvers.conversions.outcome_from_msg``) with its provenance, and the newest data
status; :func:`plots_for` says which channel pairs a group of runs is drawn as (the
thesis' Figs. 4.1.x-4.4.x); :func:`shown` and :func:`shown_unit` give a metric in its
display unit (``display.display``). The static report, the study report and the
comparison pages all take them from here.
"""
from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from vd_events.bags.bag import read_bag
from vd_events.errors import BagError
from vd_events.measured.align import reference_time
from vd_events.reports.display import display
from vd_events.studies.capability import TOPIC as CAPABILITY_TOPIC
from vd_events.studies.capability import Table as CapabilityTable
from vd_events.studies.capability import from_msg as capability_from_msg
from vd_solvers.constants import DEG, STANDARD_GRAVITY
from vd_solvers.conversions import outcome_from_msg
from vd_solvers.families import MEASURED_MODEL_FAMILY
from vd_solvers.results import EventOutcome
from vd_solvers.standards.fmvss126 import ProcessingError

#: plot scale factors from SI to the axes' units
TO_DEG = 1.0 / DEG
TO_G = 1.0 / STANDARD_GRAVITY


@dataclass(frozen=True)
class Axis:
    """One plot axis: a channel, its label (with the display unit) and the scale to it."""

    channel: str
    label: str
    scale: float = 1.0
    relative: bool = False  # plot the change from the step nearest the design (x = 0)
    #: the event whose manoeuvre instant is the origin (time axes of simulations and logs
    #: aligned: measured.align.reference_time); '' for none
    aligned: str = ''


#: event -> plots (x axis, y axis) of the analytical models; channels a run lacks are skipped
PLOTS: Mapping[str, Sequence[tuple[Axis, Axis]]] = {
    'handling_diagram': (
        (Axis('slip_angle_difference', 'front minus rear slip angle α_f − α_r [deg]', TO_DEG),
         Axis('lateral_acceleration', 'lateral acceleration [g]', TO_G)),
        (Axis('lateral_acceleration', 'lateral acceleration [g]', TO_G),
         Axis('steer_angle', 'road-wheel steer angle [deg]', TO_DEG)),
        (Axis('lateral_acceleration', 'lateral acceleration [g]', TO_G),
         Axis('roll_angle', 'roll angle [deg]', TO_DEG)),
        # the thesis' Figs. 4.1.1-4.1.2: axle lateral force over slip angle
        (Axis('slip_angle_front', 'front slip angle [deg]', TO_DEG),
         Axis('lateral_force_front_axle', 'front axle lateral force [kN]', 1e-3)),
        (Axis('slip_angle_rear', 'rear slip angle [deg]', TO_DEG),
         Axis('lateral_force_rear_axle', 'rear axle lateral force [kN]', 1e-3)),
    ),
    'steady_state_circular': (
        (Axis('lateral_acceleration', 'lateral acceleration [g]', TO_G),
         Axis('steer_angle', 'road-wheel steer angle [deg]', TO_DEG)),
        (Axis('lateral_acceleration', 'lateral acceleration [g]', TO_G),
         Axis('sideslip', 'sideslip angle [deg]', TO_DEG)),
        (Axis('lateral_acceleration', 'lateral acceleration [g]', TO_G),
         Axis('roll_angle', 'roll angle [deg]', TO_DEG)),
    ),
    'step_steer': (
        (Axis('time', 'time [s]'), Axis('yaw_rate', 'yaw rate [deg/s]', TO_DEG)),
        (Axis('time', 'time [s]'), Axis('lateral_acceleration', 'lateral acceleration [m/s²]')),
    ),
}
_TRAVEL = Axis('wheel_travel_left', 'vertical wheel travel, left [mm]', 1e3)
_OPPOSITE = Axis('wheel_travel_left', 'opposite wheel travel, left wheel [mm]', 1e3)
_FORCE = Axis('applied_force', 'applied force per wheel [kN]', 1e-3)
_TOE = Axis('toe_left', 'toe angle, left [deg]', TO_DEG)
_CAMBER = Axis('camber_left', 'camber angle, left [deg]', TO_DEG)
#: K&C plots (the thesis' Figs. 4.2.x-4.3.x)
KC_PLOTS: Mapping[str, Sequence[tuple[Axis, Axis]]] = {
    'parallel_wheel_travel': (
        (_TRAVEL, _TOE), (_TRAVEL, _CAMBER),
        (_TRAVEL, Axis('track', 'track change [mm]', 1e3, relative=True)),
        (_TRAVEL, Axis('contact_point_x_left', 'wheelbase change, left contact patch x [mm]',
                       1e3, relative=True)),
        (_TRAVEL, Axis('pad_force_left', 'wheel vertical load, left [N]')),
        (_TRAVEL, Axis('caster_left', 'caster, left [deg]', TO_DEG)),
    ),
    'opposite_wheel_travel': (
        (_OPPOSITE, _TOE), (_OPPOSITE, _CAMBER),
        (_OPPOSITE, Axis('pad_force_left', 'wheel vertical load, left [N]')),
    ),
    'lateral_force': (
        (_FORCE, _CAMBER), (_FORCE, _TOE),
        (_FORCE, Axis('pad_force_left', 'wheel vertical load, left [N]')),
        (_FORCE, Axis('contact_point_y_left', 'contact patch y change, left [mm]', 1e3,
                      relative=True)),
    ),
    'longitudinal_force': (
        (_FORCE, Axis('wheel_centre_x_left', 'wheel centre x change, left [mm]', 1e3,
                      relative=True)),
        (_FORCE, Axis('pad_force_left', 'wheel vertical load, left [N]')),
        (_FORCE, _TOE),
    ),
    'steering': (
        (Axis('steering_wheel_angle', 'steering-wheel angle [deg]', TO_DEG),
         Axis('steer_angle_left', 'road-wheel angle, left [deg]', TO_DEG)),
        (Axis('steering_wheel_angle', 'steering-wheel angle [deg]', TO_DEG),
         Axis('steer_angle_right', 'road-wheel angle, right [deg]', TO_DEG)),
        (Axis('rack_travel', 'rack travel [mm]', 1e3),
         Axis('rack_force', 'rack force [N]')),
    ),
}
_TIME = Axis('time', 'time [s]')
#: a step steer's time from its 50 % steering-wheel instant (ISO 7401), simulations and logs
_FROM_STEP = Axis('time', 'time from the 50 % steering-wheel instant [s]', aligned='step_steer')
_AY = Axis('lateral_acceleration', 'lateral acceleration [m/s²]')
#: full-vehicle plots; over time: the thesis' Figs. 4.4.1-4.4.3 (lateral acceleration,
#: roll and steering angle over time, configurations overlaid)
VEHICLE_PLOTS: Mapping[str, Sequence[tuple[Axis, Axis]]] = {
    'constant_radius_turn': (
        (_TIME, _AY),
        (_TIME, Axis('roll', 'roll angle [deg]', TO_DEG)),
        (_TIME, Axis('steering_wheel_angle', 'steering-wheel angle [deg]', TO_DEG)),
        (_AY, Axis('steering_wheel_angle', 'steering-wheel angle [deg]', TO_DEG)),
        (_AY, Axis('roll', 'roll angle [deg]', TO_DEG)),
        (_AY, Axis('sideslip', 'sideslip angle [deg]', TO_DEG)),
    ),
    'step_steer': (
        (_FROM_STEP, Axis('yaw_rate', 'yaw rate [deg/s]', TO_DEG)),
        (_FROM_STEP, _AY),
        (_FROM_STEP, Axis('roll', 'roll angle [deg]', TO_DEG)),
        (_FROM_STEP, Axis('steering_wheel_angle', 'steering-wheel angle [deg]', TO_DEG)),
    ),
    'straight_line_braking': (
        (_TIME, Axis('speed', 'speed [km/h]', 3.6)),
        (_TIME, Axis('longitudinal_acceleration', 'longitudinal acceleration [m/s²]')),
        (_TIME, Axis('pitch', 'pitch angle [deg]', TO_DEG)),
        (_TIME, Axis('brake_pressure_front_left', 'brake pressure, front left [bar]', 1e-5)),
        (_TIME, Axis('slip_ratio_front_left', 'slip ratio, front left [-]')),
    ),
    'brake_in_turn': (
        (_TIME, Axis('yaw_rate', 'yaw rate [deg/s]', TO_DEG)),
        (_TIME, _AY),
        (_TIME, Axis('speed', 'speed [km/h]', 3.6)),
        (Axis('x', 'x [m]'), Axis('y', 'y [m]')),
    ),
    'power_off_in_turn': (
        (_TIME, Axis('yaw_rate', 'yaw rate [deg/s]', TO_DEG)),
        (_TIME, _AY),
        (_TIME, Axis('speed', 'speed [km/h]', 3.6)),
        (Axis('x', 'x [m]'), Axis('y', 'y [m]')),
    ),
    'straight_line_acceleration': (
        (_TIME, Axis('speed', 'speed [km/h]', 3.6)),
        (_TIME, Axis('longitudinal_acceleration', 'longitudinal acceleration [m/s²]')),
        (_TIME, Axis('gear', 'gear [-]')),
        (_TIME, Axis('slip_ratio_front_left', 'slip ratio, front left [-]')),
    ),
    # a vehicle-test log and its replays (vd import / vd replay)
    'vehicle_test': tuple((_TIME, Axis(c, label, scale)) for c, label, scale in (
        ('yaw_rate', 'yaw rate [deg/s]', TO_DEG),
        ('lateral_acceleration', 'lateral acceleration [m/s²]', 1.0),
        ('sideslip', 'sideslip angle [deg]', TO_DEG), ('roll', 'roll angle [deg]', TO_DEG),
        ('steering_wheel_angle', 'steering-wheel angle [deg]', TO_DEG),
        ('speed', 'speed [km/h]', 3.6))),
}


@dataclass(frozen=True)
class Run:
    """One recorded result (read through ``conversions.outcome_from_msg``) and its bag."""

    bag: Path
    outcome: EventOutcome
    modified: list[str] = field(default_factory=list)

    def __getattr__(self, name: str):
        return getattr(self.outcome, name)  # event, configuration, model, axle, notes, ...

    @property
    def channels(self) -> dict[str, np.ndarray]:
        return {k: c.values for k, c in self.outcome.channels.items()}

    @property
    def units(self) -> dict[str, str]:
        return {k: c.unit for k, c in self.outcome.channels.items()}

    @property
    def label(self) -> str:
        flex = ', flexible' if self.fidelity == 'flexible' else ''
        return f'{self.configuration} ({self.model}{flex})'


def check_bags(bags: Sequence[Path]) -> None:
    """Raise BagError for a path that is not a finished bag."""
    for bag in bags:
        if not (Path(bag) / 'metadata.yaml').is_file():
            raise BagError(f'{bag}: not a finished rosbag2 bag (no metadata.yaml)')


def load_runs(bags: Sequence[Path]) -> tuple[list[Run], object | None]:
    """Every EventResult in the bags (as EventOutcomes), and the newest data status seen."""
    runs: list[Run] = []
    status = None
    for bag in bags:
        provenance: dict[str, list[str]] = {}
        results = []
        for item in read_bag(bag):
            msg = item.msg
            # topics of any namespace (/vd/data_status, /car2/data_status)
            if item.topic.endswith('/data_status'):
                status = msg
            elif item.topic.endswith('/provenance'):
                provenance[msg.configuration] = [
                    f'{g.group}.{k.key}: {k.data_value} → {k.master_value} {k.unit}'.strip()
                    for g in msg.groups for k in g.modified_keys]
            elif item.topic.endswith('/result'):
                results.append(outcome_from_msg(msg))
        runs += [Run(bag, o, provenance.get(o.configuration, [])) for o in results]
    return runs, status


def load_capability(bags: Sequence[Path]) -> list[CapabilityTable]:
    """Every capability table (vd capability) recorded in the bags."""
    return [capability_from_msg(item.msg) for bag in bags
            for item in read_bag(bag, {CAPABILITY_TOPIC})]


def family_of(model: str) -> str:
    """Return the family a run is drawn with: measured results overlay their simulations."""
    if model in ('bicycle', 'two_track'):
        return 'analytical'
    return MEASURED_MODEL_FAMILY.get(model, model)


def groups(runs: Sequence[Run]) -> dict[tuple[str, str, str], list[Run]]:
    """Return the runs by (event, axle, family): each group is one section of a report."""
    out: dict[tuple[str, str, str], list[Run]] = {}
    for run in runs:
        out.setdefault((run.event, run.axle, family_of(run.model)), []).append(run)
    return out


def plots_for(event: str, family: str, runs: Sequence[Run]) -> list[tuple[Axis, Axis, list]]:
    """
    Return the plots of a group: (x axis, y axis, the runs that have both channels).

    An event without plot definitions gets its first channel against the next six.
    """
    table = {'kc': KC_PLOTS, 'vehicle': VEHICLE_PLOTS}.get(family, PLOTS)
    pairs = table.get(event) or _generic_plots(runs[0])
    out = []
    for xa, ya in pairs:
        usable = [r for r in runs if xa.channel in r.channels and ya.channel in r.channels
                  and (not xa.aligned or origin(r, xa.aligned) is not None)]
        if usable:
            out.append((xa, ya, usable))
    return out


def _generic_plots(run: Run) -> Sequence[tuple[Axis, Axis]]:
    names = list(run.channels)
    if not names:
        return ()
    x = Axis(names[0], f'{names[0]} [{run.units[names[0]]}]')
    return tuple((x, Axis(n, f'{n} [{run.units[n]}]')) for n in names[1:7])


def origin(run: Run, event: str) -> float | None:
    """Return the manoeuvre instant of ``run`` (measured.align.reference_time), None if none."""
    ch = run.channels
    if 'time' not in ch or 'steering_wheel_angle' not in ch:
        return None
    try:
        return reference_time(event, ch['time'], ch['steering_wheel_angle'])
    except ProcessingError:
        return None


def curve(run: Run, xa: Axis, ya: Axis) -> tuple[np.ndarray, np.ndarray]:
    """Return the (x, y) a plot draws of ``run``, scaled to the axes' units."""
    x, y = run.channels[xa.channel], run.channels[ya.channel]
    if xa.aligned:
        x = x - (origin(run, xa.aligned) or 0.0)
    if ya.relative:
        y = y - y[int(np.argmin(np.abs(x)))]
    return x * xa.scale, y * ya.scale


def shown(run: Run, name: str) -> float:
    """Return a metric of ``run`` in its display unit (``display.display``)."""
    m = run.metrics[name]
    return display(m.value, m.unit, name)[0]


def shown_unit(runs: Sequence[Run], name: str) -> str:
    """Return the display unit of metric ``name`` (from the first run that has it)."""
    for run in runs:
        if name in run.metrics:
            m = run.metrics[name]
            return display(m.value, m.unit, name)[1]
    return ''


__all__ = ['Axis', 'Run', 'PLOTS', 'KC_PLOTS', 'VEHICLE_PLOTS', 'check_bags', 'load_runs',
           'load_capability', 'family_of', 'groups', 'plots_for', 'curve', 'origin', 'shown',
           'shown_unit']
