# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
The URDF of a configuration, read back by an independent parser (Pinocchio's).

Its wheel centres are the hard points' and lie the geometry group's wheelbase and tracks
apart; its mass is the configuration's; the wheel frames vd puts on /tf (``transform``)
are the ones Pinocchio's forward kinematics of the URDF gives at the same joint positions.
"""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np
from numpy.testing import assert_allclose
import pinocchio as pin
import pytest

from vd_data_server.study import load_study
from vd_solvers.vehicle.description import describe, joint_positions, transform

STUDIES = Path(__file__).resolve().parents[3] / 'src' / 'vd_data_server' / 'data' / 'studies'
WHEELS = ('front_left', 'front_right', 'rear_left', 'rear_right')
STEER, TRAVEL = (-0.6, 0.6), (-0.1, 0.1)


@pytest.fixture(scope='module', params=['sedan.yaml', 'hmmwv.yaml'])
def config(request):
    study = load_study(STUDIES / request.param)
    return study.configurations[study.configuration_names[0]]


@pytest.fixture(scope='module')
def robot(config):
    text = describe(config, STEER, TRAVEL).urdf()
    model = pin.buildModelFromXML(text)
    return text, model


def _placement(model, frame: str, q) -> pin.SE3:
    data = model.createData()
    pin.framesForwardKinematics(model, data, q)
    return data.oMf[model.getFrameId(frame)]


def test_the_urdf_parses_with_the_joints_of_the_multibody_model(robot):
    _, model = robot
    names = list(model.names)[1:]
    assert names == ['front_left_travel', 'front_left_steer', 'front_left_spin',
                     'front_right_travel', 'front_right_steer', 'front_right_spin',
                     'rear_left_travel', 'rear_left_spin', 'rear_right_travel',
                     'rear_right_spin']


def test_the_wheel_centres_are_the_hard_points_a_wheelbase_and_a_track_apart(config, robot):
    _, model = robot
    q = pin.neutral(model)
    centres = {w: _placement(model, f'{w}_wheel', q).translation for w in WHEELS}
    for axle in ('front', 'rear'):
        x, y, z = config.group(f'{axle}_hardpoints').point('points.wheel_centre')
        assert_allclose(centres[f'{axle}_left'], [x, abs(y), z], atol=1e-12)
        assert_allclose(centres[f'{axle}_right'], [x, -abs(y), z], atol=1e-12)  # mirrored
    geometry = config.group('geometry')
    assert centres['front_left'][0] - centres['rear_left'][0] == pytest.approx(
        geometry.scalar('wheelbase'), abs=1e-9)
    for axle in ('front', 'rear'):
        track = centres[f'{axle}_left'][1] - centres[f'{axle}_right'][1]
        assert track == pytest.approx(geometry.scalar(f'track_{axle}'), abs=1e-9)


def test_the_urdf_carries_the_configuration_mass(config, robot):
    _, model = robot
    mass = config.group('mass')
    total = mass.scalar('sprung_mass') + 2.0 * (mass.scalar('unsprung_mass_front')
                                                + mass.scalar('unsprung_mass_rear'))
    assert sum(i.mass for i in model.inertias) == pytest.approx(total, rel=1e-12)
    com = pin.centerOfMass(model, model.createData(), pin.neutral(model))
    # the sprung CoG pulled towards the wheel centres by the unsprung masses
    cog = np.array(mass.point('sprung_cog'))
    assert np.linalg.norm(com - cog) < np.linalg.norm(cog)


def test_the_wheel_frames_on_tf_are_the_urdf_kinematics(config, robot):
    _, model = robot
    description = describe(config, STEER, TRAVEL)
    # a state: travel, steer, spin per wheel, as the multibody model's q holds them
    q_vehicle = np.zeros(7 + 8)
    for w in range(4):
        q_vehicle[7 + 2 * w] = 0.01 * (w + 1)  # travel, m
        q_vehicle[8 + 2 * w] = 0.7 * (w + 1)  # spin, rad
    steer = np.array([0.1, 0.08, 0.0, 0.0])
    values = dict(zip((j.name for j in description.moving),
                      joint_positions(description, q_vehicle, steer)))
    q = pin.neutral(model)
    for j, name in enumerate(model.names[1:], start=1):
        joint = model.joints[j]
        if joint.nq == 2:  # continuous: cos, sin
            q[joint.idx_q:joint.idx_q + 2] = (math.cos(values[name]), math.sin(values[name]))
        else:
            q[joint.idx_q] = values[name]
    for wheel in WHEELS:
        chain = [j for j in description.joints if j.child.startswith(wheel)]
        pose = pin.SE3.Identity()
        for joint in chain:
            (x, y, z), (qx, qy, qz, qw) = transform(joint, values[joint.name])
            pose = pose * pin.SE3(pin.Quaternion(qw, qx, qy, qz).matrix(), np.array([x, y, z]))
        expected = _placement(model, f'{wheel}_wheel', q)
        assert_allclose(pose.translation, expected.translation, atol=1e-12)
        assert_allclose(pose.rotation, expected.rotation, atol=1e-12)
