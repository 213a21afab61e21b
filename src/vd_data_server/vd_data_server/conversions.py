# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Conversions between the ROS-free data model and vd_interfaces messages.

``configuration_from_msg(configuration_to_msg(c)) == c`` for every resolved
configuration: values, units, display units and sources survive unchanged.
"""
from __future__ import annotations

from collections.abc import Iterable
from typing import cast

from vd_interfaces.msg import Configuration as ConfigurationMsg
from vd_interfaces.msg import (
    DataStatus,
    InputGroup,
    NamedCurve,
    NamedPoint,
    NamedScalar,
    NamedText,
)
from vd_interfaces.msg import GroupStatus as GroupStatusMsg
from vd_interfaces.msg import ModifiedKey as ModifiedKeyMsg

from .model import Configuration, GroupData, Value, ValueType
from .study import GroupStatus, Study


def value_to_fields(value: Value) -> NamedScalar | NamedCurve | NamedPoint | NamedText:
    if value.type == 'scalar':
        return NamedScalar(name=value.key, value=float(cast(float, value.si)), unit=value.unit,
                           display_unit=value.display_unit, source=value.source)
    if value.type == 'curve':
        xs, ys = cast(tuple[tuple[float, ...], tuple[float, ...]], value.si)
        return NamedCurve(name=value.key, x=list(xs), y=list(ys), x_unit=value.x_unit,
                          y_unit=value.unit, x_display_unit=value.x_display_unit,
                          y_display_unit=value.display_unit, source=value.source)
    if value.type in ('point', 'vector'):
        x, y, z = cast(tuple[float, float, float], value.si)
        return NamedPoint(name=value.key, kind=NamedPoint.POINT if value.type == 'point'
                          else NamedPoint.VECTOR, x=x, y=y, z=z, display_unit=value.display_unit,
                          source=value.source)
    return NamedText(name=value.key, value=str(value.si), source=value.source)


def group_to_msg(group: GroupData) -> InputGroup:
    msg = InputGroup(name=group.group, kind=group.kind, variant=group.variant, file=group.file,
                     description=group.description)
    for value in group.values.values():
        field = value_to_fields(value)
        {NamedScalar: msg.scalars, NamedCurve: msg.curves, NamedPoint: msg.points,
         NamedText: msg.texts}[type(field)].append(field)
    return msg


def configuration_to_msg(config: Configuration, stamp=None) -> ConfigurationMsg:
    msg = ConfigurationMsg(master_file=config.master_file, name=config.name,
                           description=config.description, data_hash=config.data_hash,
                           flexible=config.flexible,
                           flexible_components=list(config.flexible_components),
                           groups=[group_to_msg(g) for g in config.groups.values()],
                           file_hashes=[NamedText(name=k, value=v)
                                        for k, v in config.extra_hashes.items()])
    if stamp is not None:
        msg.stamp = stamp
    return msg


def group_from_msg(msg: InputGroup) -> GroupData:
    values: dict[str, Value] = {}
    for s in msg.scalars:
        values[s.name] = Value(s.name, 'scalar', float(s.value), s.unit,
                               display_unit=s.display_unit, source=s.source)
    for c in msg.curves:
        values[c.name] = Value(c.name, 'curve', (tuple(float(v) for v in c.x),
                                                  tuple(float(v) for v in c.y)), c.y_unit,
                               c.x_unit, c.y_display_unit, c.x_display_unit, c.source)
    for p in msg.points:
        kind: ValueType = 'point' if p.kind == NamedPoint.POINT else 'vector'
        values[p.name] = Value(p.name, kind, (float(p.x), float(p.y), float(p.z)),
                               'm' if kind == 'point' else '', display_unit=p.display_unit,
                               source=p.source)
    for t in msg.texts:
        values[t.name] = Value(t.name, 'text', t.value, source=t.source)
    return GroupData(group=msg.name, kind=msg.kind, variant=msg.variant, file=msg.file,
                     values=values, description=msg.description)


def configuration_from_msg(msg: ConfigurationMsg) -> Configuration:
    return Configuration(name=msg.name, master_file=msg.master_file, description=msg.description,
                         groups={g.name: group_from_msg(g) for g in msg.groups},
                         flexible=msg.flexible,
                         flexible_components=tuple(msg.flexible_components),
                         extra_hashes={t.name: t.value for t in msg.file_hashes})


def status_to_msg(entries: Iterable[GroupStatus]) -> list[GroupStatusMsg]:
    return [GroupStatusMsg(configuration=s.configuration, group=s.group, variant=s.variant,
                           state=GroupStatusMsg.MODIFIED if s.state == 'MODIFIED'
                           else GroupStatusMsg.UNCHANGED,
                           consistency=GroupStatusMsg.DIFFERS if s.consistency == 'DIFFERS'
                           else GroupStatusMsg.SAME,
                           modified_keys=[ModifiedKeyMsg(key=m.key, data_value=m.data_value,
                                                         master_value=m.master_value,
                                                         unit=m.unit)
                                          for m in s.modified_keys])
            for s in entries]


def study_to_status_msg(study: Study, errors: Iterable[str] = (), stamp=None) -> DataStatus:
    msg = DataStatus(master_file=str(study.master.path), data_root=str(study.master.data_root),
                     configurations=study.configuration_names, groups=list(study.groups),
                     status=status_to_msg(study.status), errors=list(errors))
    if stamp is not None:
        msg.stamp = stamp
    return msg
