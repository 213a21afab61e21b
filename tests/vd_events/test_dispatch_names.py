# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""Solver instance names: what the dispatcher counts as one instance of a family."""
from __future__ import annotations

import pytest

from vd_events.dispatch import instance_names, parse_instance, parse_solvers, solver_command
from vd_events.runner import RunError


def test_instance_names_keep_the_default_first():
    assert instance_names('kc', 3) == ['kc_solver', 'kc_solver_2', 'kc_solver_3']
    assert instance_names('steady_state', 1) == ['analytical_solver']


def test_parse_instance():
    """Check the two action forms of vd_solvers.families.Family.action, in any namespace."""
    nodes = {'/vd/kc_solver', '/vd/kc_solver_2', '/car2/kc_solver_b', '/vd/data_server'}
    # the default instance serves the family's action
    assert parse_instance('/vd/kc/run_event', nodes) == ('/vd/kc_solver', 'kc')
    # other instances serve <family>/<node>/run_event in their namespace
    assert parse_instance('/vd/kc/kc_solver_2/run_event', nodes) == ('/vd/kc_solver_2', 'kc')
    assert parse_instance('/car2/kc/kc_solver_b/run_event', nodes) == ('/car2/kc_solver_b', 'kc')
    # a node not in the graph (gone), an unknown family, another action
    assert parse_instance('/car2/kc/run_event', nodes) is None
    assert parse_instance('/vd/kc/kc_solver_9/run_event', nodes) is None
    assert parse_instance('/vd/tyre/kc_solver/run_event', nodes) is None
    assert parse_instance('/vd/kc/kc_solver/other', nodes) is None


def test_solver_command_renames_all_but_the_default():
    """Check that only the extra instances get a node name of their own."""
    assert not any(a.startswith('__node:=') for a in solver_command('kc', 'kc_solver'))
    command = solver_command('kc', 'kc_solver_2')
    assert command[command.index('__node:=kc_solver_2') - 1] == '-r'
    assert command[command.index('__ns:=/vd') - 1] == '-r'


def test_parse_solvers():
    assert parse_solvers('kc=2, analytical=1') == {'kc': 2, 'steady_state': 1}
    assert parse_solvers('') == {}
    with pytest.raises(RunError, match=r"--solvers: expected FAMILY=N with FAMILY one of kc, "
                       r"analytical, vehicle, found 'tires=2'"):
        parse_solvers('tires=2')
