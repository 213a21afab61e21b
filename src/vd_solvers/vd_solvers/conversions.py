# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
EventOutcome <-> vd_interfaces messages: the one conversion module of the results.

* :func:`outcome_to_msg` / :func:`outcome_from_msg`: EventResult (metrics, channels, notes);
  the report, ``vd run --json``, the capability study and the demo read results through
  :func:`outcome_from_msg`, from rclpy messages or from bag messages (rosbags) alike.
* :func:`outcome_states`: the per-step typed state of a result (``KcState``,
  ``AnalyticalState``, ``VehicleState``), whose fields are the channels, and
  :func:`states_channels`, its inverse.
* The bag's time axis: :func:`step_offsets` (simulated time, or :data:`PSEUDO_STEP`
  per step of a quasi-static sweep) and :class:`TimeAxis` (run stamps that never overlap).

A field a model does not compute is NaN in the message; :func:`states_channels`
leaves out the channels that are NaN at every step.
"""
from __future__ import annotations

from collections.abc import Mapping, Sequence
import copy
import math
import threading

from builtin_interfaces.msg import Time
from geometry_msgs.msg import Point, TransformStamped, Vector3
from nav_msgs.msg import Odometry
import numpy as np
from rclpy.serialization import serialize_message

from tf2_msgs.msg import TFMessage
from vd_data_server.ros.names import BODY_FRAME, ODOM_FRAME
from vd_interfaces.msg import (
    AnalyticalState,
    Bushing,
    EventResult,
    KcState,
    KcWheel,
    NamedScalar,
    Provenance,
    VehicleState,
    VehicleWheel,
)
from vd_interfaces.msg import Channel as ChannelMsg
from vd_solvers import __version__
from vd_solvers.families import FAMILIES, ODOMETRY_TOPIC, TF_TOPIC, message_family
from vd_solvers.results import Channel, EventOutcome, Metric

#: pseudo-time per step of a quasi-static event (K&C sweeps, steady-state sweeps), s
PSEUDO_STEP = 1e-3
#: least gap between two runs on one time axis, s
RUN_GAP = 1e-3

_NS = 1_000_000_000
SIDES = ('left', 'right')
XYZ = ('x', 'y', 'z')

# --- K&C ----------------------------------------------------------------------
#: KcState field (axle-level) -> SI unit; channel name = field name
KC_AXLE_FIELDS = {
    'applied_force': 'N', 'applied_moment': 'N*m', 'track': 'm',
    'steering_wheel_angle': 'rad', 'rack_travel': 'm', 'rack_force': 'N', 'arb_twist': 'rad',
    'arb_torque': 'N*m', 'elastic_energy': 'J', 'constraint_residual': 'm',
    'force_residual': 'N', 'iterations': '-', 'roll_centre_height': 'm',
    'roll_centre_lateral': 'm',
}
#: KcWheel scalar field -> SI unit; channel ``<field>_<side>``
KC_WHEEL_FIELDS = {
    'wheel_travel': 'm', 'pad_travel': 'm', 'toe': 'rad', 'camber': 'rad',
    'steer_angle': 'rad', 'caster': 'rad', 'kingpin_inclination': 'rad', 'scrub_radius': 'm',
    'mechanical_trail': 'm', 'pad_force': 'N', 'spring_length': 'm', 'spring_force': 'N',
    'damper_length': 'm', 'bump_stop_force': 'N', 'bump_stop_deflection': 'm',
    'rebound_stop_force': 'N', 'rebound_stop_deflection': 'm', 'arb_arm_angle': 'rad',
    'droplink_force': 'N', 'fvsa_length': 'm', 'svsa_length': 'm', 'svsa_angle': 'rad',
}
#: KcWheel Point/Vector3 field -> SI unit; channel ``<field>_<x|y|z>_<side>``
KC_WHEEL_VECTORS = {
    'wheel_centre': 'm', 'contact_point': 'm', 'steering_axis_ground': 'm',
    'front_view_instant_centre': 'm', 'side_view_instant_centre': 'm',
    'contact_force': 'N', 'centre_force': 'N', 'contact_moment': 'N*m',
}
#: the KC_WHEEL_VECTORS that are points (geometry_msgs/Point; the others are Vector3)
KC_WHEEL_POINTS = ('wheel_centre', 'contact_point', 'steering_axis_ground',
                   'front_view_instant_centre', 'side_view_instant_centre')
#: Bushing Vector3 field -> (channel prefix, component names, SI unit); channel
#: ``<prefix>.<bushing>.<component>_<side>``
KC_BUSHING_FIELDS = {
    'force': ('bushing_force', XYZ, 'N'),
    'torque': ('bushing_force', ('rx', 'ry', 'rz'), 'N*m'),
    'deflection': ('bushing_deflection', XYZ, 'm'),
    'rotation': ('bushing_deflection', ('rx', 'ry', 'rz'), 'rad'),
}

# --- analytical ---------------------------------------------------------------
#: AnalyticalState field -> SI unit; channel name = field name
ANALYTICAL_FIELDS = {
    'time': 's', 'lateral_acceleration': 'm/s^2', 'speed': 'm/s', 'steer_angle': 'rad',
    'yaw_rate': 'rad/s', 'sideslip': 'rad', 'lateral_velocity': 'm/s',
    'slip_angle_front': 'rad', 'slip_angle_rear': 'rad', 'slip_angle_difference': 'rad',
    'roll_angle': 'rad', 'lateral_force_front_axle': 'N', 'lateral_force_rear_axle': 'N',
    'wheel_load_front_left': 'N', 'wheel_load_front_right': 'N', 'wheel_load_rear_left': 'N',
    'wheel_load_rear_right': 'N',
}

# --- full vehicle -------------------------------------------------------------
#: VehicleState field -> SI unit; channel name = field name
VEHICLE_FIELDS = {
    'time': 's', 'x': 'm', 'y': 'm', 'yaw': 'rad', 'roll': 'rad', 'pitch': 'rad',
    'yaw_rate': 'rad/s', 'speed': 'm/s', 'sideslip': 'rad', 'lateral_acceleration': 'm/s^2',
    'longitudinal_acceleration': 'm/s^2', 'steering_wheel_angle': 'rad', 'wheel_torque': 'N*m',
}
#: VehicleWheel field -> (channel prefix, SI unit); channel ``<prefix>_<wheel>``
WHEEL_FIELDS = {
    'load': ('wheel_load', 'N'), 'travel': ('wheel_travel', 'm'),
    'steer': ('wheel_steer', 'rad'), 'steer_angle': ('steer_angle', 'rad'),
    'slip_angle': ('slip_angle', 'rad'), 'slip_ratio': ('slip_ratio', '-'),
    'inclination': ('inclination', 'rad'), 'force_x': ('tire_force_x', 'N'),
    'force_y': ('tire_force_y', 'N'), 'aligning_moment': ('aligning_moment', 'N*m'),
}
VEHICLE_WHEELS = ('front_left', 'front_right', 'rear_left', 'rear_right')


# --- EventResult ----------------------------------------------------------------


def outcome_to_msg(outcome: EventOutcome, stamp=None):
    """vd_interfaces/EventResult of ``outcome`` (stamped ``stamp`` if given)."""
    msg = EventResult(event=outcome.event, configuration=outcome.configuration,
                      model=outcome.model, fidelity=outcome.fidelity, axle=outcome.axle,
                      data_hash=outcome.data_hash, notes=list(outcome.notes))
    msg.metrics = [NamedScalar(name=k, value=float(m.value), unit=m.unit, source=m.source)
                   for k, m in outcome.metrics.items()]
    msg.channels = [ChannelMsg(name=k, unit=c.unit, values=[float(v) for v in c.values])
                    for k, c in outcome.channels.items()]
    if stamp is not None:
        msg.stamp = stamp
    return msg


def outcome_from_msg(msg) -> EventOutcome:
    """
    Return the EventOutcome of an EventResult.

    ``msg`` is an rclpy message or one read from a bag (``vd_events.bags.bag.read_bag``),
    whose fields are the same.
    """
    return EventOutcome(
        event=msg.event, configuration=msg.configuration, model=msg.model,
        fidelity=msg.fidelity, axle=msg.axle, data_hash=msg.data_hash,
        metrics={m.name: Metric(float(m.value), m.unit, m.source) for m in msg.metrics},
        channels={c.name: Channel(c.unit, np.asarray(c.values, dtype=float))
                  for c in msg.channels},
        notes=tuple(msg.notes))


def provenance_to_msg(outcome: EventOutcome, stamp, master_file: str = '',
                      groups: Sequence = ()):
    """
    vd_interfaces/Provenance of a run of ``outcome``, stamped ``stamp``.

    ``groups``: the GroupStatus of the configuration's input groups (with the run's
    overrides, ``vd_solvers.solve.provenance_groups``); none for imported measurements.
    """
    return Provenance(stamp=stamp, configuration=outcome.configuration,
                      master_file=master_file, data_hash=outcome.data_hash,
                      model=outcome.model, fidelity=outcome.fidelity, event=outcome.event,
                      software_version=__version__, groups=list(groups))


# --- the time axis --------------------------------------------------------------


def step_offsets(outcome: EventOutcome) -> np.ndarray:
    """
    Return the seconds from the run's stamp to each step.

    The simulated time of a time-domain event (a ``time`` channel), ``step *
    PSEUDO_STEP`` for a quasi-static one.
    """
    if 'time' in outcome.channels:
        return np.asarray(outcome.channels['time'].values, dtype=float)
    return np.arange(outcome.n_steps) * PSEUDO_STEP


def stamp_ns(stamp) -> int:
    """Nanoseconds of a builtin_interfaces/Time."""
    return int(stamp.sec) * _NS + int(stamp.nanosec)


def time_msg(ns: int):
    """builtin_interfaces/Time of ``ns`` nanoseconds."""
    return Time(sec=int(ns) // _NS, nanosec=int(ns) % _NS)


def offset_stamp(stamp, seconds: float):
    """``stamp`` (builtin_interfaces/Time) plus ``seconds``."""
    return time_msg(stamp_ns(stamp) + int(round(seconds * 1e9)))


class TimeAxis:
    """
    Run stamps on one strictly increasing time axis (one per process).

    A run starts at the wall-clock time it is published, or :data:`RUN_GAP` after the
    end of the previous run's axis if that is later (a 3 s step steer solved in 0.1 s
    must not overlap the next run), so several runs recorded in one bag keep strictly
    increasing stamps on every topic.
    """

    def __init__(self) -> None:
        self._end = -1
        self._lock = threading.Lock()

    def claim(self, now_ns: int, span: float) -> int:
        """Return the start (ns) of a run spanning ``span`` seconds, requested at ``now_ns``."""
        with self._lock:
            start = max(int(now_ns), self._end + int(RUN_GAP * 1e9))
            self._end = start + int(round(span * 1e9))
            return start

    def end(self) -> int:
        """Return the end (ns) of the latest run on this axis (-1: none yet)."""
        with self._lock:
            return self._end


#: the process's time axis (every solver node and the capability study share it)
TIME_AXIS = TimeAxis()


def run_stamp(outcome: EventOutcome, now_ns: int):
    """Claim the stamp (builtin_interfaces/Time) of a run of ``outcome`` on TIME_AXIS."""
    offsets = step_offsets(outcome)
    span = float(offsets[-1]) if offsets.size else 0.0
    return time_msg(TIME_AXIS.claim(now_ns, span))


def end_stamp(outcome: EventOutcome, stamp):
    """Return the stamp of a run's last step (where its EventResult goes on the axis)."""
    offsets = step_offsets(outcome)
    return offset_stamp(stamp, float(offsets[-1]) if offsets.size else 0.0)


# --- per-step states --------------------------------------------------------------


def start_stamp(outcome: EventOutcome, end):
    """Return a run's stamp from the stamp of its last step (the inverse of end_stamp)."""
    offsets = step_offsets(outcome)
    return time_msg(stamp_ns(end) - (int(round(float(offsets[-1]) * 1e9)) if offsets.size
                                     else 0))


def outcome_states(outcome: EventOutcome, stamp) -> list:
    """
    Return the typed per-step states of ``outcome``.

    KcState (family ``kc``: the K&C model, rig measurements), VehicleState (``vehicle``:
    the full vehicle, vehicle-test logs), AnalyticalState (the others), stamped ``stamp`` +
    :func:`step_offsets`.
    """
    family = message_family(outcome.model)
    if family == 'kc':
        return outcome_kc_states(outcome, stamp)
    if family == 'vehicle':
        return outcome_vehicle_states(outcome, stamp)
    return outcome_analytical_states(outcome, stamp)


#: the full vehicle's pose channels: a vehicle outcome with them has odometry and TF
POSE_CHANNELS = ('x', 'y', 'yaw')


def outcome_messages(outcome: EventOutcome, stamp, frame_prefix: str = '') -> list:
    """
    Return (topic, message) of everything one run publishes but its provenance.

    In publishing order: the TF of the run (the full vehicle's pose, the K&C wheels) and the
    vehicle's odometry, one per step; the typed states, one per step; the EventResult,
    stamped at the last step. Topics are relative to the namespace (``/tf`` absolute); every
    frame carries ``frame_prefix`` (several vehicles on one TF tree). The one definition of
    a run's messages: the solver nodes publish them, the recorder writes them to the bag
    from the EventResult alone, and ``vd import`` writes them for measured data.
    """
    family = FAMILIES[message_family(outcome.model)]
    out: list = []
    if family.name == 'vehicle' and all(
            k in outcome.channels and np.isfinite(outcome.channels[k].values).all()
            for k in POSE_CHANNELS):
        odometry = outcome_odometry(outcome, stamp)
        for msg in odometry:
            msg.header.frame_id = frame_prefix + msg.header.frame_id
            msg.child_frame_id = frame_prefix + msg.child_frame_id
        out += [(TF_TOPIC, m) for m in _odometry_transforms(odometry)]
        out += [(ODOMETRY_TOPIC, m) for m in odometry]
    elif family.name == 'kc':
        out += [(TF_TOPIC, m) for m in outcome_kc_transforms(outcome, stamp, frame_prefix)]
    for state in outcome_states(outcome, stamp):
        state.header.frame_id = frame_prefix + state.header.frame_id
        out.append((family.state_topic, state))
    out.append((family.result_topic, outcome_to_msg(outcome, end_stamp(outcome, stamp))))
    return out


def _column(channels: Mapping[str, Channel], name: str, n: int) -> np.ndarray:
    c = channels.get(name)
    return np.full(n, np.nan) if c is None else np.asarray(c.values, dtype=float)


def _header(msg, stamp, offset: float, frame: str) -> None:
    msg.header.stamp = offset_stamp(stamp, float(offset))
    msg.header.frame_id = frame


def bushing_names(channels: Mapping[str, Channel]) -> list[str]:
    """Return the bushings of a K&C outcome, in channel order."""
    names = [k.split('.')[1] for k in channels if k.startswith('bushing_force.')]
    return list(dict.fromkeys(names))


def outcome_kc_states(outcome: EventOutcome, stamp) -> list:
    """vd_interfaces/KcState per step of a K&C outcome (pseudo-time, frame ``base_link``)."""
    ch, n = outcome.channels, outcome.n_steps
    axle = {f: _column(ch, f, n) for f in KC_AXLE_FIELDS}
    side_cols = []
    for side in SIDES:
        scal = {f: _column(ch, f'{f}_{side}', n) for f in KC_WHEEL_FIELDS}
        vec = {f: np.column_stack([_column(ch, f'{f}_{c}_{side}', n) for c in XYZ])
               for f in KC_WHEEL_VECTORS}
        bush = {b: {f: np.column_stack([_column(ch, f'{p}.{b}.{c}_{side}', n) for c in comps])
                    for f, (p, comps, _) in KC_BUSHING_FIELDS.items()}
                for b in bushing_names(ch)}
        side_cols.append((scal, vec, bush))
    out = []
    for i, offset in enumerate(step_offsets(outcome)):
        msg = KcState(event=outcome.event, configuration=outcome.configuration,
                      model=outcome.model, fidelity=outcome.fidelity, axle=outcome.axle, step=i)
        _header(msg, stamp, offset, BODY_FRAME)
        for f, col in axle.items():
            if f == 'iterations':
                msg.iterations = int(col[i]) if math.isfinite(col[i]) else 0
            else:
                setattr(msg, f, float(col[i]))
        for side, (scal, vec, bush) in zip(SIDES, side_cols):
            wheel = KcWheel(**{f: float(col[i]) for f, col in scal.items()})
            for f, col in vec.items():
                kind = Point if f in KC_WHEEL_POINTS else Vector3
                setattr(wheel, f, kind(x=float(col[i, 0]), y=float(col[i, 1]),
                                       z=float(col[i, 2])))
            wheel.bushings = [
                Bushing(name=b, **{f: Vector3(x=float(c[i, 0]), y=float(c[i, 1]),
                                              z=float(c[i, 2])) for f, c in cols.items()})
                for b, cols in bush.items()]
            setattr(msg, side, wheel)
        out.append(msg)
    return out


def outcome_analytical_states(outcome: EventOutcome, stamp) -> list:
    """vd_interfaces/AnalyticalState per step of a bicycle or two-track outcome."""
    ch, n = outcome.channels, outcome.n_steps
    cols = {f: _column(ch, f, n) for f in ANALYTICAL_FIELDS}
    out = []
    for i, offset in enumerate(step_offsets(outcome)):
        msg = AnalyticalState(event=outcome.event, configuration=outcome.configuration,
                              model=outcome.model, step=i,
                              **{f: float(c[i]) for f, c in cols.items()})
        _header(msg, stamp, offset, BODY_FRAME)
        out.append(msg)
    return out


def outcome_vehicle_states(outcome: EventOutcome, stamp) -> list:
    """
    Return a vd_interfaces/VehicleState per step of a full-vehicle outcome.

    Stamped ``stamp`` + simulated time, frame ``odom``.
    """
    ch, n = outcome.channels, outcome.n_steps
    body = {f: _column(ch, f, n) for f in VEHICLE_FIELDS}
    wheels = {w: {f: _column(ch, f'{p}_{w}', n) for f, (p, _) in WHEEL_FIELDS.items()}
              for w in VEHICLE_WHEELS}
    out = []
    for i, offset in enumerate(step_offsets(outcome)):
        msg = VehicleState(event=outcome.event, configuration=outcome.configuration,
                           model=outcome.model, step=i,
                           **{f: float(c[i]) for f, c in body.items()})
        _header(msg, stamp, offset, ODOM_FRAME)
        for w, cols in wheels.items():
            setattr(msg, w, VehicleWheel(**{f: float(c[i]) for f, c in cols.items()}))
        out.append(msg)
    return out


def _kept(columns: Mapping[str, tuple[str, Sequence[float]]]) -> dict[str, Channel]:
    out = {}
    for name, (unit, values) in columns.items():
        a = np.asarray(values, dtype=float)
        if a.size and not np.all(np.isnan(a)):
            out[name] = Channel(unit, a)
    return out


def states_channels(states: Sequence) -> dict[str, Channel]:
    """
    Return the channels of a run from its state messages (rclpy or bag messages).

    The inverse of :func:`outcome_states`, less the channels NaN at every step.
    """
    if not states:
        return {}
    first = states[0]
    cols: dict[str, tuple[str, list[float]]] = {}

    def add(name: str, unit: str, value: float) -> None:
        cols.setdefault(name, (unit, []))[1].append(float(value))

    if hasattr(first, 'left'):  # KcState
        for s in states:
            for f, unit in KC_AXLE_FIELDS.items():
                add(f, unit, getattr(s, f))
            for side in SIDES:
                wheel = getattr(s, side)
                for f, unit in KC_WHEEL_FIELDS.items():
                    add(f'{f}_{side}', unit, getattr(wheel, f))
                for f, unit in KC_WHEEL_VECTORS.items():
                    v = getattr(wheel, f)
                    for c in XYZ:
                        add(f'{f}_{c}_{side}', unit, getattr(v, c))
                for b in wheel.bushings:
                    for f, (prefix, comps, unit) in KC_BUSHING_FIELDS.items():
                        v = getattr(b, f)
                        for c, axis in zip(comps, XYZ):
                            add(f'{prefix}.{b.name}.{c}_{side}', unit, getattr(v, axis))
    elif hasattr(first, 'front_left'):  # VehicleState
        for s in states:
            for f, unit in VEHICLE_FIELDS.items():
                add(f, unit, getattr(s, f))
            for w in VEHICLE_WHEELS:
                wheel = getattr(s, w)
                for f, (prefix, unit) in WHEEL_FIELDS.items():
                    add(f'{prefix}_{w}', unit, getattr(wheel, f))
    else:  # AnalyticalState
        for s in states:
            for f, unit in ANALYTICAL_FIELDS.items():
                add(f, unit, getattr(s, f))
    return _kept(cols)


# --- odometry and TF of the full vehicle ---------------------------------------------


def outcome_transforms(outcome: EventOutcome, stamp) -> list:
    """
    Return a tf2_msgs/TFMessage per step of a full-vehicle outcome.

    The transform ``odom`` -> ``base_link`` (REP 105), the same pose as
    :func:`outcome_odometry`.
    """
    return _odometry_transforms(outcome_odometry(outcome, stamp))


def _odometry_transforms(odometry: Sequence) -> list:
    """Return the TFMessage of each Odometry message: its frame -> its child frame."""
    out = []
    for odom in odometry:
        t = TransformStamped()
        t.header = odom.header
        t.child_frame_id = odom.child_frame_id
        p = odom.pose.pose.position
        t.transform.translation.x = p.x
        t.transform.translation.y = p.y
        t.transform.translation.z = p.z
        t.transform.rotation = odom.pose.pose.orientation
        out.append(TFMessage(transforms=[t]))
    return out


def quaternion(roll: float, pitch: float, yaw: float) -> tuple[float, float, float, float]:
    """Return the quaternion (x, y, z, w) of z-y-x (yaw, pitch, roll) Euler angles, rad."""
    cr, sr = math.cos(roll / 2), math.sin(roll / 2)
    cp, sp = math.cos(pitch / 2), math.sin(pitch / 2)
    cy, sy = math.cos(yaw / 2), math.sin(yaw / 2)
    return (sr * cp * cy - cr * sp * sy, cr * sp * cy + sr * cp * sy,
            cr * cp * sy - sr * sp * cy, cr * cp * cy + sr * sp * sy)


def set_quaternion(q, roll: float, pitch: float, yaw: float):
    """Fill the quaternion ``q`` (geometry_msgs) with z-y-x (yaw, pitch, roll) Euler angles."""
    q.x, q.y, q.z, q.w = quaternion(roll, pitch, yaw)
    return q


#: numpy type (little-endian, as the CDR_LE encapsulation says) of the fields that
#: :class:`InPlaceMessage` rewrites, by ROS type
IN_PLACE_TYPES = {'double': '<f8', 'int32': '<i4', 'uint32': '<u4'}


class InPlaceMessage:
    """
    A message serialised once, whose numeric fields are then rewritten in its bytes.

    A message published every step at a high rate costs more to build and to convert
    (Python attribute by attribute, then CDR) than to send. This one is serialised once,
    by rclpy, from ``template`` (strings, frames and the other fields stay as they are
    there); :meth:`slots` gives the byte positions of a group of fields, found by
    serialising the template with a distinct sentinel in each, so the layout is rclpy's
    own; ``Slots.write`` puts values there, and :meth:`data` is the serialised message,
    for ``Publisher.publish`` (which sends bytes as they are: no conversion, no
    serialisation). The fields are double, int32 or uint32 (IN_PLACE_TYPES), named by
    their dotted path (``pose.pose.position.x``). ``Slots.read`` takes the same fields
    out of a received message (a raw subscription's bytes) when no string comes before
    them: a header's stamp.
    """

    def __init__(self, template) -> None:
        self.template = copy.deepcopy(template)
        self._buffer = bytearray(serialize_message(self.template))
        if not self._buffer[1] & 1:
            raise ValueError(f'{type(template).__name__}: serialised big-endian, expected '
                             'CDR_LE')
        self._bytes = np.frombuffer(self._buffer, dtype=np.uint8)

    def slots(self, fields: Sequence[str]) -> Slots:
        """Return where ``fields`` (dotted paths, one ROS type) lie in the message's bytes."""
        kinds = {self._type_of(f) for f in fields}
        if len(kinds) != 1:
            raise ValueError(f'{type(self.template).__name__}: fields {", ".join(fields)} '
                             f'are not of one type ({", ".join(sorted(kinds))})')
        dtype = np.dtype(IN_PLACE_TYPES[kinds.pop()])
        probe = copy.deepcopy(self.template)
        sentinels = [self._sentinel(dtype, i) for i in range(len(fields))]
        for f, value in zip(fields, sentinels):
            self._set(probe, f, value)
        data = serialize_message(probe)
        if len(data) != len(self._buffer):
            raise ValueError(f'{type(self.template).__name__}: the serialised size depends on '
                             f'the values of {", ".join(fields)}')
        offsets = self._find(data, fields, sentinels, dtype)
        _lengthen_strings(probe)  # the offsets of fields after a string move with it
        fixed = offsets == self._find(serialize_message(probe), fields, sentinels, dtype)
        return Slots(self._bytes, np.array(offsets), dtype, fixed)

    def _find(self, data: bytes, fields: Sequence[str], sentinels: list,
              dtype: np.dtype) -> list[int]:
        offsets = []
        for f, value in zip(fields, sentinels):
            pattern = np.array([value], dtype=dtype).tobytes()
            at = data.find(pattern)
            if at < 0 or data.find(pattern, at + 1) >= 0:
                raise ValueError(f'{type(self.template).__name__}: field {f} not found once '
                                 'in the serialised message')
            offsets.append(at)
        return offsets

    def data(self) -> bytes:
        """Return the serialised message with the values written so far."""
        return bytes(self._buffer)

    def _type_of(self, path: str) -> str:
        msg, _, name = self._parent(self.template, path)
        kind = msg.get_fields_and_field_types().get(name)
        if kind not in IN_PLACE_TYPES:
            raise ValueError(f'{type(self.template).__name__}: field {path} is '
                             f'{kind or "not a field"}; in place: '
                             f'{", ".join(IN_PLACE_TYPES)}')
        return kind

    @staticmethod
    def _parent(msg, path: str):
        *parents, name = path.split('.')
        for p in parents:
            msg = getattr(msg, p)
        return msg, parents, name

    def _set(self, msg, path: str, value) -> None:
        parent, _, name = self._parent(msg, path)
        setattr(parent, name, value)

    @staticmethod
    def _sentinel(dtype: np.dtype, i: int):
        """Return the i-th value of a type whose bytes no ordinary message field holds."""
        if dtype.kind == 'f':
            return float(np.float64(-1.2345678901234567e-281) * (i + 1))
        return int(0x5A5A0000 + i) if dtype.kind == 'u' else int(0x3A5A0000 + i)


def _lengthen_strings(msg) -> None:
    """Add characters to every string field of ``msg`` and of the messages it holds."""
    for name, kind in msg.get_fields_and_field_types().items():
        value = getattr(msg, name)
        if kind == 'string':
            setattr(msg, name, value + 'abcde')
        elif hasattr(value, 'get_fields_and_field_types'):
            _lengthen_strings(value)


class Slots:
    """The byte positions of a group of fields of an :class:`InPlaceMessage`, one type."""

    def __init__(self, data: np.ndarray, offsets: np.ndarray, dtype: np.dtype,
                 fixed: bool) -> None:
        self._data = data
        self._index = (offsets[:, None] + np.arange(dtype.itemsize)).ravel()
        self._values = np.zeros(len(offsets), dtype=dtype)
        self._raw = self._values.view(np.uint8)
        self.fixed = fixed  # no string before the fields: the same offsets in every message

    def __len__(self) -> int:
        return len(self._values)

    def write(self, values) -> None:
        """Write ``values`` (one per field, in the order of the fields) into the message."""
        self._values[:] = values
        self._data[self._index] = self._raw

    def read(self, data: bytes) -> np.ndarray:
        """Return the fields' values in ``data``, a serialised message of the same type."""
        if not self.fixed:
            raise ValueError('fields after a string lie where its length puts them: '
                             'deserialise the message to read them')
        return np.frombuffer(data, dtype=np.uint8)[self._index].view(self._values.dtype)


def kc_wheel_frame(axle: str, side: str) -> str:
    """Return the TF frame of one K&C wheel: ``front_left_wheel`` ... ``rear_right_wheel``."""
    return f'{axle}_{side}_wheel'


#: the channels a K&C outcome needs for its wheel frames on /tf
KC_FRAME_CHANNELS = tuple(f'wheel_centre_{c}_{side}' for side in SIDES for c in XYZ)


def has_wheel_frames(channels: Mapping[str, Sequence[float] | np.ndarray]) -> bool:
    """Say whether a K&C outcome's channels (name -> values) give its wheels' TF frames."""
    return all(k in channels and np.isfinite(np.asarray(channels[k], dtype=float)).all()
               for k in KC_FRAME_CHANNELS)


def outcome_kc_transforms(outcome: EventOutcome, stamp, prefix: str = '') -> list:
    """
    Return a tf2_msgs/TFMessage per step of a K&C outcome: where its two wheels are.

    The transforms ``base_link`` -> ``<axle>_left_wheel`` and ``<axle>_right_wheel``
    (frames with ``prefix``), stamped like the KcStates: origin at the wheel centre, x
    along the wheel heading, y along the spin axis pointing left, z up in the wheel plane;
    the rotation is yaw = steer angle (= -s toe) then roll = -s camber about the new x
    (s = +1 left, -1 right; toe positive in, camber positive top outward, ISO 8855). The
    body is fixed on the rig, so base_link is the frame of the K&C points (docs/kc.md).
    Empty when the outcome has no wheel centres (a measured rig file without them).
    """
    ch, n = outcome.channels, outcome.n_steps
    if not has_wheel_frames({k: c.values for k, c in ch.items()}):
        return []
    sides = []
    for side, sign in zip(SIDES, (1.0, -1.0)):
        centre = np.column_stack([_column(ch, f'wheel_centre_{c}_{side}', n) for c in XYZ])
        toe, camber = _column(ch, f'toe_{side}', n), _column(ch, f'camber_{side}', n)
        # a rig file may lack the angles: the wheel keeps the body's orientation
        yaw = np.nan_to_num(-sign * toe)
        roll = np.nan_to_num(-sign * camber)
        sides.append((prefix + kc_wheel_frame(outcome.axle, side), centre, roll, yaw))
    out = []
    for i, offset in enumerate(step_offsets(outcome)):
        transforms = []
        for frame, centre, roll, yaw in sides:
            t = TransformStamped()
            _header(t, stamp, offset, prefix + BODY_FRAME)
            t.child_frame_id = frame
            t.transform.translation.x, t.transform.translation.y, t.transform.translation.z = (
                float(v) for v in centre[i])
            set_quaternion(t.transform.rotation, float(roll[i]), 0.0, float(yaw[i]))
            transforms.append(t)
        out.append(TFMessage(transforms=transforms))
    return out


#: REP 145's convention for a covariance nobody estimated: -1 in its first element
UNKNOWN_COVARIANCE = -1.0


def covariance_unknown(msg):
    """
    Mark the pose and twist covariance of a nav_msgs/Odometry as not estimated; return it.

    The model gives a state, not an estimate with an uncertainty: an all-zero covariance
    would claim the pose is known exactly, so the first element is -1 (REP 145: "a
    covariance matrix with -1 in its first element is unknown"), the rest 0.
    """
    msg.pose.covariance[0] = UNKNOWN_COVARIANCE
    msg.twist.covariance[0] = UNKNOWN_COVARIANCE
    return msg


def outcome_odometry(outcome: EventOutcome, stamp) -> list:
    """
    Return a nav_msgs/Odometry per step of a full-vehicle outcome.

    From the channels x, y, yaw, roll, pitch, speed, sideslip, yaw_rate: frame ``odom``,
    child ``base_link`` (REP 105), stamped ``stamp`` + simulated time. Height is not a
    channel: z = 0. A channel not measured (absent or NaN: roll, pitch, sideslip of a
    vehicle-test log without them) is 0 in the pose and the twist.
    """
    n = outcome.n_steps
    ch = {k: np.nan_to_num(_column(outcome.channels, k, n)) for k in
          ('x', 'y', 'yaw', 'roll', 'pitch', 'speed', 'sideslip', 'yaw_rate')}
    ch['time'] = _column(outcome.channels, 'time', n)
    out = []
    for i, t in enumerate(ch['time']):
        msg = Odometry()
        msg.header.stamp = offset_stamp(stamp, float(t))
        msg.header.frame_id = ODOM_FRAME
        msg.child_frame_id = BODY_FRAME
        msg.pose.pose.position.x = float(ch['x'][i])
        msg.pose.pose.position.y = float(ch['y'][i])
        set_quaternion(msg.pose.pose.orientation, float(ch['roll'][i]),
                       float(ch['pitch'][i]), float(ch['yaw'][i]))
        beta = float(ch['sideslip'][i])
        speed = float(ch['speed'][i])
        # twist in the child frame (base_link); the yaw-plane velocity of the CoG
        msg.twist.twist.linear.x = speed * math.cos(beta)
        msg.twist.twist.linear.y = speed * math.sin(beta)
        msg.twist.twist.angular.z = float(ch['yaw_rate'][i])
        out.append(covariance_unknown(msg))
    return out
