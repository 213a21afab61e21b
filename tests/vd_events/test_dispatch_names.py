"""Solver instance names: what the dispatcher counts as one instance of a family."""
from __future__ import annotations

import pytest

from vd_events.dispatch import instance_names, parse_instance, parse_solvers, solver_command
from vd_events.runner import RunError


def test_instance_names_keep_the_default_first():
    assert instance_names('kc', 3) == ['kc_solver', 'kc_solver_2', 'kc_solver_3']
    assert instance_names('steady_state', 1) == ['analytical_solver']


def test_parse_instance():
    nodes = {'/kc_solver', '/kc_solver_2', '/vd/kc_solver_b', '/data_server'}
    assert parse_instance('/kc_solver_2/kc/run_event', nodes) == ('/kc_solver_2', 'kc')
    assert parse_instance('/vd/kc_solver_b/kc/run_event', nodes) == ('/vd/kc_solver_b', 'kc')
    # the family's shared action is not an instance ('/vd' is a namespace, not a node)
    assert parse_instance('/vd/kc/run_event', nodes) is None
    # a node not in the graph (gone), an unknown family, another action
    assert parse_instance('/kc_solver_9/kc/run_event', nodes) is None
    assert parse_instance('/kc_solver/tyre/run_event', nodes) is None
    assert parse_instance('/kc_solver/kc/other', nodes) is None


def test_solver_command_renames_all_but_the_default():
    assert '-r' not in solver_command('kc', 'kc_solver')
    assert solver_command('kc', 'kc_solver_2')[-2:] == ['-r', '__node:=kc_solver_2']


def test_parse_solvers():
    assert parse_solvers('kc=2, analytical=1') == {'kc': 2, 'steady_state': 1}
    assert parse_solvers('') == {}
    with pytest.raises(RunError, match=r"--solvers: expected FAMILY=N with FAMILY one of kc, "
                       r"analytical, vehicle, found 'tires=2'"):
        parse_solvers('tires=2')
