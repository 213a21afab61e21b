# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
The robot description of a configuration: URDF, joint states and wheel frames.

ROS-free. What RViz, Foxglove and ``robot_state_publisher`` need to show the car, built
from the configuration alone (one source: the data the models read):

* links ``base_link`` (the vehicle frame of the data files: origin on the ground under
  the front axle centre, x forward, y left, z up), ``chassis`` (fixed to it: the sprung
  mass at its centre of gravity with its inertia, drawn as a box about the CoG as long as
  the wheelbase plus a tire diameter, as wide as the front track less a tire width and
  twice as tall as the CoG is above the wheel centres) and per
  wheel ``<wheel>_carrier`` (the wheel carrier), for the front wheels
  ``<wheel>_knuckle``, and ``<wheel>_wheel`` (the unsprung mass at the wheel centre with
  the wheel's spin inertia, drawn as a cylinder of the tire's unloaded radius and width);
* joints ``<wheel>_travel`` (prismatic along the body z axis at the design wheel centre
  from the hard points: the wheel travel, + bump), ``<wheel>_steer`` (front, revolute
  about z: the road-wheel heading, + left) and ``<wheel>_spin`` (continuous about y: the
  wheel's rotation, + rolling forward), in the order of the multibody model
  (:mod:`.model`: the carrier on a prismatic joint, the wheel on a revolute one).

The joints' origins carry no rotation, so a joint's transform is its origin plus its axis
times its position (prismatic) or a rotation about its axis (revolute): :func:`transform`
gives the wheel frames from the joint positions, the same definition the URDF states.
"""
from __future__ import annotations

from dataclasses import dataclass
import math
from typing import Literal
from xml.etree import ElementTree as ET

import numpy as np

from vd_data_server.model import Configuration
from vd_data_server.tire_group import tire_properties
from vd_solvers.tire.magic_formula import MagicFormula
from vd_solvers.vehicle_data import wheel_centres

from .maps import GRID_POINTS, WHEELS
from .model import SPIN_INERTIA_FACTOR, VehicleModel

ROOT = 'base_link'
CHASSIS = 'chassis'
#: m, the tire's section width when its .tir has no DIMENSION WIDTH
DEFAULT_TIRE_WIDTH = 0.2
JointKind = Literal['fixed', 'prismatic', 'revolute', 'continuous']


@dataclass(frozen=True)
class Link:
    """A link: mass (kg) at ``com`` (m, link frame), principal inertia (kg m^2), visual."""

    name: str
    mass: float = 0.0
    com: tuple[float, float, float] = (0.0, 0.0, 0.0)
    inertia: tuple[float, float, float] = (0.0, 0.0, 0.0)  # ixx, iyy, izz
    box: tuple[float, float, float] | None = None  # size x, y, z, centred at com
    cylinder: tuple[float, float] | None = None  # radius, width, axis y


@dataclass(frozen=True)
class Joint:
    """A joint: ``child`` in ``parent`` at ``origin`` (m), moving along/about ``axis``."""

    name: str
    kind: JointKind
    parent: str
    child: str
    origin: tuple[float, float, float]
    axis: tuple[float, float, float] = (0.0, 0.0, 1.0)
    limits: tuple[float, float] | None = None  # m or rad


@dataclass(frozen=True)
class Description:
    """The robot description of one configuration (module doc)."""

    name: str
    links: tuple[Link, ...]
    joints: tuple[Joint, ...]

    @property
    def moving(self) -> tuple[Joint, ...]:
        """The joints with a position (``joint_states``), in order."""
        return tuple(j for j in self.joints if j.kind != 'fixed')

    @property
    def fixed(self) -> tuple[Joint, ...]:
        """The fixed joints (``/tf_static``)."""
        return tuple(j for j in self.joints if j.kind == 'fixed')

    def urdf(self) -> str:
        """Return the URDF text."""
        robot = ET.Element('robot', name=self.name)
        for link in self.links:
            _link_xml(robot, link)
        for joint in self.joints:
            j = ET.SubElement(robot, 'joint', name=joint.name, type=joint.kind)
            ET.SubElement(j, 'parent', link=joint.parent)
            ET.SubElement(j, 'child', link=joint.child)
            ET.SubElement(j, 'origin', xyz=_vec(joint.origin), rpy='0 0 0')
            if joint.kind != 'fixed':
                ET.SubElement(j, 'axis', xyz=_vec(joint.axis))
            if joint.limits is not None:
                ET.SubElement(j, 'limit', lower=repr(joint.limits[0]),
                              upper=repr(joint.limits[1]), effort='0', velocity='0')
        ET.indent(robot)
        return '<?xml version="1.0"?>\n' + ET.tostring(robot, encoding='unicode') + '\n'


def _vec(v) -> str:
    return ' '.join(repr(float(x)) for x in v)


def _link_xml(robot: ET.Element, link: Link) -> None:
    element = ET.SubElement(robot, 'link', name=link.name)
    if link.mass > 0.0:
        inertial = ET.SubElement(element, 'inertial')
        ET.SubElement(inertial, 'origin', xyz=_vec(link.com), rpy='0 0 0')
        ET.SubElement(inertial, 'mass', value=repr(link.mass))
        ixx, iyy, izz = link.inertia
        ET.SubElement(inertial, 'inertia', ixx=repr(ixx), ixy='0', ixz='0', iyy=repr(iyy),
                      iyz='0', izz=repr(izz))
    if link.box is not None or link.cylinder is not None:
        visual = ET.SubElement(element, 'visual')
        geometry = ET.Element('geometry')
        if link.box is not None:
            ET.SubElement(visual, 'origin', xyz=_vec(link.com), rpy='0 0 0')
            ET.SubElement(geometry, 'box', size=_vec(link.box))
        elif link.cylinder is not None:  # a URDF cylinder's axis is z: turn it onto y
            ET.SubElement(visual, 'origin', xyz='0 0 0', rpy=_vec((math.pi / 2, 0.0, 0.0)))
            ET.SubElement(geometry, 'cylinder', radius=repr(link.cylinder[0]),
                          length=repr(link.cylinder[1]))
        visual.append(geometry)


def describe(config: Configuration, steer_limits: tuple[float, float],
             travel_limits: tuple[float, float]) -> Description:
    """
    Return the description of ``config`` (module doc).

    ``steer_limits``: the road-wheel angles at the ends of the rack travel, rad;
    ``travel_limits``: the wheel travel range, m (:func:`describe_model` takes both from
    the suspension maps).
    """
    mass = config.group('mass')
    centres = wheel_centres(config)
    tires = [MagicFormula(tire_properties(config.group(f'{axle}_tire')))
             for axle in ('front', 'front', 'rear', 'rear')]
    unsprung = [mass.scalar('unsprung_mass_front')] * 2 + [mass.scalar('unsprung_mass_rear')] * 2
    cog = _point(mass.point('sprung_cog'))
    front, rear = centres[0], centres[2]
    z_wheel = float(np.mean(centres[:, 2]))
    height = 2.0 * max(cog[2] - z_wheel, 0.1)
    r_front = tires[0].unloaded_radius
    body = Link(CHASSIS, float(mass.scalar('sprung_mass')), cog,
                (float(mass.scalar('sprung_inertia.ixx')),
                 float(mass.scalar('sprung_inertia.iyy')),
                 float(mass.scalar('sprung_inertia.izz'))),
                box=(float(front[0] - rear[0]) + 2.0 * r_front,
                     float(2.0 * abs(front[1])) - _width(tires[0]), height))
    links = [Link(ROOT), body]
    joints = [Joint('chassis_joint', 'fixed', ROOT, CHASSIS, (0.0, 0.0, 0.0))]
    for w, name in enumerate(WHEELS):
        tire = tires[w]
        carrier = f'{name}_carrier'
        links.append(Link(carrier))
        joints.append(Joint(f'{name}_travel', 'prismatic', ROOT, carrier,
                            _point(centres[w]), (0.0, 0.0, 1.0),
                            travel_limits))
        parent = carrier
        if name.startswith('front'):
            knuckle = f'{name}_knuckle'
            links.append(Link(knuckle))
            joints.append(Joint(f'{name}_steer', 'revolute', carrier, knuckle,
                                (0.0, 0.0, 0.0), (0.0, 0.0, 1.0), steer_limits))
            parent = knuckle
        r, m_u = tire.unloaded_radius, float(unsprung[w])
        # the spin inertia the multibody model's wheel carries
        i_spin = SPIN_INERTIA_FACTOR * m_u * r**2
        links.append(Link(f'{name}_wheel', m_u, (0.0, 0.0, 0.0),
                          (0.5 * i_spin, i_spin, 0.5 * i_spin),
                          cylinder=(r, _width(tire))))
        joints.append(Joint(f'{name}_spin', 'continuous', parent, f'{name}_wheel',
                            (0.0, 0.0, 0.0), (0.0, 1.0, 0.0)))
    return Description(config.name, tuple(links), tuple(joints))


def describe_model(model: VehicleModel) -> Description:
    """Return the description of ``model``'s configuration, limits from its maps."""
    maps = model.maps
    top = maps.travel0 + (GRID_POINTS - 1) * maps.travel_step
    return describe(model.config,
                    (float(np.min(maps.steer_angle)), float(np.max(maps.steer_angle))),
                    (float(np.max(maps.travel0)), float(np.min(top))))


def _point(p) -> tuple[float, float, float]:
    return float(p[0]), float(p[1]), float(p[2])


def _width(tire: MagicFormula) -> float:
    return float(tire.props.number('DIMENSION', 'WIDTH', DEFAULT_TIRE_WIDTH))


def transform(joint: Joint, position: float) -> tuple[tuple[float, float, float],
                                                      tuple[float, float, float, float]]:
    """Return the pose of ``joint.child`` in ``joint.parent``: translation, quaternion xyzw."""
    ox, oy, oz = joint.origin
    ax, ay, az = joint.axis
    if joint.kind == 'prismatic':
        return (ox + ax * position, oy + ay * position, oz + az * position), (0.0, 0.0, 0.0, 1.0)
    if joint.kind == 'fixed':
        return joint.origin, (0.0, 0.0, 0.0, 1.0)
    s = math.sin(0.5 * position)
    return joint.origin, (ax * s, ay * s, az * s, math.cos(0.5 * position))


def joint_positions(description: Description, q: np.ndarray, steer: np.ndarray
                    ) -> list[float]:
    """
    Return the positions of ``description.moving`` from the multibody state.

    ``q``: the configuration vector of :class:`.model.VehicleModel` (free flyer, then per
    wheel travel and spin); ``steer``: the road-wheel headings FL FR RL RR, rad.
    """
    values = {}
    for w, name in enumerate(WHEELS):
        values[f'{name}_travel'] = float(q[7 + 2 * w])
        values[f'{name}_spin'] = float(q[8 + 2 * w])
        values[f'{name}_steer'] = float(steer[w])
    return [values[j.name] for j in description.moving]


__all__ = ['CHASSIS', 'Description', 'Joint', 'Link', 'ROOT', 'describe', 'describe_model',
           'joint_positions', 'transform']
