# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Display units at the edges: the one table the CLI text, the demo and the report use.

Every value on the wire is SI (``rad/(m/s^2)``, ``m/s``, ``N*m/rad``, ...). For people,
:func:`display` converts a metric to the unit it is customarily quoted in (deg/g, km/h,
N*m/deg, mm for a scrub radius), with pint, from whatever unit string the value carries:
a value that arrives in another unit of the same quantity (``deg/m`` rather than
``rad/m``) is shown the same way. ``g`` in a unit string is standard gravity
(9.80665 m/s^2), never the gram.
"""
from __future__ import annotations

from functools import lru_cache
import math
import re
from typing import TYPE_CHECKING, NamedTuple, cast

from vd_data_server.units import ureg

if TYPE_CHECKING:
    import pint

#: SI unit -> display unit (pint expression; ``g`` = standard gravity)
DISPLAY_UNITS = {
    'rad': 'deg',
    'rad/(m/s^2)': 'deg/g',
    'm/s': 'km/h',
    'm/s^2': 'g',
    'rad/m': 'deg/m',
    'rad/N': 'deg/kN',
    'rad/(N*m)': 'deg/(kN*m)',
    'N*m/rad': 'N*m/deg',
    'N/m': 'N/mm',
    'rad/s': 'deg/s',
}
#: metrics shown in another unit than their SI unit's display unit
METRIC_UNITS = {
    'wheelbase': 'mm',  # capability table: wheelbase and track changes
    'track': 'mm',
    'scrub_radius': 'mm',
    'mechanical_trail': 'mm',
    'roll_centre_height_kinematic': 'mm',
    'roll_centre_height_force': 'mm',
    'roll_centre_height_front': 'mm',
    'roll_centre_height_rear': 'mm',
    'mean_fully_developed_deceleration': 'm/s^2',  # as UN R13-H quotes it
    'mean_deceleration': 'm/s^2',
    'mean_longitudinal_deceleration': 'm/s^2',
    'brake_pressure': 'bar',
}

_GRAVITY = re.compile(r'(?<![A-Za-z_])g(?![A-Za-z_0-9])')


class Headline(NamedTuple):
    """A metric shown first (CLI, report) and, if ``summary``, in the demo's lines."""

    name: str
    label: str
    fmt: str
    summary: bool = True


#: the metrics shown first, in this order, and how the demo's one-line summaries say them
HEADLINE = (
    Headline('understeer_gradient', 'K_us', '{:.3f}'),
    Headline('characteristic_speed', 'v_char', '{:.0f}'),
    Headline('critical_speed', 'v_crit', '{:.0f}'),
    Headline('max_lateral_acceleration', 'a_y,max', '{:.3f}'),
    Headline('understeer_gradient_linear', 'K_us,lin', '{:.3f}', summary=False),
    Headline('roll_gradient', 'roll', '{:.2f}'),
    Headline('sideslip_gradient', 'sideslip', '{:.2f}'),
    Headline('yaw_rate_response_time_90', 't90(r)', '{:.3f}'),
    Headline('yaw_rate_overshoot', 'overshoot(r)', '{:.1f}'),
    Headline('lateral_acceleration_response_time_90', 't90(a_y)', '{:.3f}', summary=False),
    Headline('natural_frequency', 'f_n', '{:.2f}'),
    Headline('damping_ratio', 'D', '{:.2f}', summary=False),
    Headline('yaw_rate_gain', 'r/delta', '{:.3g}', summary=False),
    Headline('bump_steer', 'bump steer', '{:.1f}'),
    Headline('camber_gain', 'camber gain', '{:.1f}'),
    Headline('wheel_rate', 'wheel rate', '{:.1f}'),
    Headline('roll_centre_height_kinematic', 'RC', '{:.0f}'),
    Headline('roll_stiffness', 'roll stiffness', '{:.0f}'),
    Headline('roll_steer', 'roll steer', '{:.3f}', summary=False),
    Headline('lateral_compliance_steer', 'lat. compl. steer', '{:.3f}'),
    Headline('lateral_compliance_camber', 'camber', '{:.3f}'),
    Headline('anti_squat', 'anti-squat', '{:.0f}'),
    Headline('steering_ratio', 'steering ratio', '{:.1f}'),
    Headline('ackermann', 'Ackermann', '{:.0f}'),
    # braking and acceleration (vd_solvers.vehicle.longitudinal_events)
    Headline('stopping_distance', 'stop', '{:.1f}'),
    Headline('mean_fully_developed_deceleration', 'MFDD', '{:.2f}'),
    Headline('locked_wheels', 'locked wheels', '{:.0f}'),
    Headline('max_pitch', 'pitch', '{:.2f}', summary=False),
    Headline('acceleration_time', 't_acc', '{:.2f}'),
    Headline('max_longitudinal_acceleration', 'a_x,max', '{:.3f}'),
    Headline('yaw_rate_ratio', 'r(t_n)/r_0', '{:.3f}'),
    Headline('lateral_acceleration_ratio', 'a_y(t_n)/a_y,0', '{:.3f}'),
    Headline('heading_deviation', 'heading dev.', '{:.2f}'),
    Headline('path_deviation', 'path dev.', '{:.2f}'),
    # ride, bump and lane change (vd_solvers.vehicle.ride_events)
    Headline('vertical_acceleration_rms_wk', 'a_w,z', '{:.3f}'),
    Headline('wheel_load_variation_front', 'dFz/Fz front', '{:.3f}'),
    Headline('peak_vertical_acceleration', 'a_z,peak', '{:.2f}'),
    Headline('settling_time', 'settling', '{:.2f}'),
    Headline('passed', 'cones passed', '{:.0f}'),
    Headline('smallest_margin', 'margin', '{:.2f}'),
)
HEADLINE_NAMES = tuple(h.name for h in HEADLINE)


@lru_cache(maxsize=256)
def _unit(text: str) -> pint.Unit | None:
    try:
        return ureg().parse_units(_GRAVITY.sub('g_0', text)) if text else None
    except Exception:  # noqa: BLE001 - not a pint unit ('-', '%'-like labels): shown as is
        return None


def _radians(unit: pint.Unit) -> float:
    return cast(float, dict(ureg().Quantity(1.0, unit).to_root_units().unit_items()).get(
        'radian', 0))


@lru_cache(maxsize=256)
def display_unit(unit: str, name: str = '') -> str:
    """Return the unit a metric ``name`` in ``unit`` is shown in (``unit`` itself if none)."""
    if name in METRIC_UNITS:
        return METRIC_UNITS[name]
    if unit in DISPLAY_UNITS:
        return DISPLAY_UNITS[unit]
    src = _unit(unit)
    if src is None:
        return unit
    for si, shown in DISPLAY_UNITS.items():  # another unit of a quantity in the table
        dst = _unit(si)
        assert dst is not None  # every unit of the table is a pint unit
        if src.dimensionality == dst.dimensionality and _radians(src) == _radians(dst):
            return shown
    return unit


def display(value: float, unit: str, name: str = '') -> tuple[float, str]:
    """``value`` in ``unit`` converted to its display unit: (number, unit label)."""
    shown = display_unit(unit, name)
    if shown == unit or not math.isfinite(value):
        return float(value), shown
    src, dst = _unit(unit), _unit(shown)
    if src is None or dst is None:
        return float(value), unit
    from pint.errors import DimensionalityError

    try:
        return float(ureg().Quantity(float(value), src).to(dst).magnitude), shown
    except DimensionalityError:
        return float(value), unit


def summary(metrics) -> str:
    """Say a run in one line, as the demo does: ``K_us 2.196 deg/g, v_char 96 km/h, ...``."""
    parts = []
    for h in HEADLINE:
        m = metrics.get(h.name)
        if h.summary and m is not None:
            value, unit = display(m['value'] if isinstance(m, dict) else m.value,
                                  m['unit'] if isinstance(m, dict) else m.unit, h.name)
            suffix = '' if unit in ('', '-') else ' ' + unit
            parts.append(f'{h.label} {h.fmt.format(value)}{suffix}')
    return ', '.join(parts)
