"""EventOutcome <-> vd_interfaces messages (EventResult, Sample)."""
from __future__ import annotations

import numpy as np

from vd_data_server.names import BODY_FRAME, ODOM_FRAME
from vd_interfaces.msg import Channel as ChannelMsg
from vd_interfaces.msg import EventResult, NamedScalar, Sample
from vd_solvers.results import Channel, EventOutcome, Metric


def outcome_to_msg(outcome: EventOutcome, stamp=None) -> EventResult:
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


def outcome_from_msg(msg: EventResult) -> EventOutcome:
    return EventOutcome(
        event=msg.event, configuration=msg.configuration, model=msg.model,
        fidelity=msg.fidelity, axle=msg.axle, data_hash=msg.data_hash,
        metrics={m.name: Metric(float(m.value), m.unit, m.source) for m in msg.metrics},
        channels={c.name: Channel(c.unit, np.asarray(c.values, dtype=float))
                  for c in msg.channels},
        notes=tuple(msg.notes))


def _offset(stamp, seconds: float):
    """``stamp`` (builtin_interfaces/Time) plus ``seconds``."""
    from builtin_interfaces.msg import Time

    total = stamp.sec * 1_000_000_000 + stamp.nanosec + int(round(seconds * 1e9))
    return Time(sec=total // 1_000_000_000, nanosec=total % 1_000_000_000)


def outcome_samples(outcome: EventOutcome, stamp=None) -> list[Sample]:
    """
    One Sample per step (channel names in every message, for plotting tools).

    With ``stamp``, headers are stamped: ``stamp`` + the step's ``time`` channel in a
    time-domain event, ``stamp`` itself otherwise.
    """
    names = [k for k, c in outcome.channels.items() if len(c.values) == outcome.n_steps]
    columns = np.column_stack([outcome.channels[k].values for k in names]) if names else None
    time = outcome.channels['time'].values if 'time' in outcome.channels else None
    samples = []
    for step in range(outcome.n_steps):
        sample = Sample(event=outcome.event, configuration=outcome.configuration,
                        model=outcome.model, step=step, names=names,
                        values=[float(v) for v in columns[step]] if columns is not None else [])
        sample.header.frame_id = BODY_FRAME
        if stamp is not None:
            sample.header.stamp = stamp if time is None else _offset(stamp, float(time[step]))
        samples.append(sample)
    return samples


#: VehicleState field -> channel; the wheels' fields take the channel + _<wheel> suffix
VEHICLE_FIELDS = ('time', 'x', 'y', 'yaw', 'roll', 'pitch', 'yaw_rate', 'speed', 'sideslip',
                  'lateral_acceleration', 'longitudinal_acceleration', 'steering_wheel_angle',
                  'wheel_torque')
WHEEL_FIELDS = {'load': 'wheel_load', 'travel': 'wheel_travel', 'steer': 'wheel_steer',
                'slip_angle': 'slip_angle', 'slip_ratio': 'slip_ratio',
                'inclination': 'inclination', 'force_x': 'tire_force_x',
                'force_y': 'tire_force_y', 'aligning_moment': 'aligning_moment'}


def outcome_vehicle_states(outcome: EventOutcome, stamp) -> list:
    """
    vd_interfaces/VehicleState per step of a full-vehicle outcome, stamped ``stamp`` +
    simulated time, frame ``odom``.
    """
    from vd_interfaces.msg import VehicleState, VehicleWheel

    ch = {k: c.values for k, c in outcome.channels.items()}
    out = []
    for i, t in enumerate(ch['time']):
        msg = VehicleState(event=outcome.event, configuration=outcome.configuration,
                           model=outcome.model, step=i)
        msg.header.stamp = _offset(stamp, float(t))
        msg.header.frame_id = ODOM_FRAME
        for name in VEHICLE_FIELDS:
            setattr(msg, name, float(ch[name][i]))
        for wheel in ('front_left', 'front_right', 'rear_left', 'rear_right'):
            setattr(msg, wheel, VehicleWheel(**{f: float(ch[f'{c}_{wheel}'][i])
                                                for f, c in WHEEL_FIELDS.items()}))
        out.append(msg)
    return out


def outcome_transforms(outcome: EventOutcome, stamp) -> list:
    """
    tf2_msgs/TFMessage per step of a full-vehicle outcome: the transform ``odom`` ->
    ``base_link`` (REP 105), the same pose as :func:`outcome_odometry`.
    """
    from geometry_msgs.msg import TransformStamped

    from tf2_msgs.msg import TFMessage

    out = []
    for odom in outcome_odometry(outcome, stamp):
        t = TransformStamped()
        t.header = odom.header
        t.child_frame_id = odom.child_frame_id
        p = odom.pose.pose.position
        t.transform.translation.x, t.transform.translation.y, t.transform.translation.z = p.x, p.y, p.z
        t.transform.rotation = odom.pose.pose.orientation
        out.append(TFMessage(transforms=[t]))
    return out


def outcome_odometry(outcome: EventOutcome, stamp) -> list:
    """
    nav_msgs/Odometry per step of a full-vehicle outcome (channels x, y, yaw, roll,
    pitch, speed, sideslip, yaw_rate): frame ``odom``, child ``base_link`` (REP 105),
    stamped ``stamp`` + simulated time. Height is not a channel: z = 0.
    """
    import math

    from nav_msgs.msg import Odometry

    ch = {k: c.values for k, c in outcome.channels.items()}
    out = []
    for i, t in enumerate(ch['time']):
        msg = Odometry()
        msg.header.stamp = _offset(stamp, float(t))
        msg.header.frame_id = ODOM_FRAME
        msg.child_frame_id = BODY_FRAME
        msg.pose.pose.position.x = float(ch['x'][i])
        msg.pose.pose.position.y = float(ch['y'][i])
        roll, pitch, yaw = float(ch['roll'][i]), float(ch['pitch'][i]), float(ch['yaw'][i])
        cr, sr = math.cos(roll / 2), math.sin(roll / 2)
        cp, sp = math.cos(pitch / 2), math.sin(pitch / 2)
        cy, sy = math.cos(yaw / 2), math.sin(yaw / 2)
        q = msg.pose.pose.orientation  # z-y-x (yaw, pitch, roll) Euler angles
        q.w = cr * cp * cy + sr * sp * sy
        q.x = sr * cp * cy - cr * sp * sy
        q.y = cr * sp * cy + sr * cp * sy
        q.z = cr * cp * sy - sr * sp * cy
        beta = float(ch['sideslip'][i])
        speed = float(ch['speed'][i])
        # twist in the child frame (base_link); the yaw-plane velocity of the CoG
        msg.twist.twist.linear.x = speed * math.cos(beta)
        msg.twist.twist.linear.y = speed * math.sin(beta)
        msg.twist.twist.angular.z = float(ch['yaw_rate'][i])
        out.append(msg)
    return out
