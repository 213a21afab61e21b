# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Fuzzed workbench edits: a message or a clean error, never a traceback or a hang.

A refused edit leaves the master file byte for byte as it was; an accepted one leaves a
master file that loads.
"""
from __future__ import annotations

from pathlib import Path
import shutil

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
import pytest

from fuzzing import QUANTITIES, clean, no_hang
from vd_data_server.errors import DataError, WorkbenchError
from vd_data_server.study import load_study
from vd_data_server.workbench.server import Workbench

SAMPLE = Path(__file__).resolve().parents[2] / 'src' / 'vd_data_server' / 'data'
TEXTS = st.one_of(st.text(max_size=20), st.integers(), st.none(), st.lists(st.text(max_size=3),
                                                                            max_size=2))


@pytest.fixture(scope='module')
def bench(tmp_path_factory) -> Workbench:
    root = tmp_path_factory.mktemp('fuzz-workbench') / 'data'
    shutil.copytree(SAMPLE, root)
    workbench = Workbench(root / 'studies' / 'sedan.yaml', edits=True)
    yield workbench
    workbench.stop()


@given(body=st.fixed_dictionaries({}, optional={
    'op': st.one_of(st.sampled_from(['variant', 'override', 'flexible', 'add']), TEXTS),
    'configuration': st.one_of(st.sampled_from(['baseline', 'sport', 'new_one', '', '../x']),
                               TEXTS),
    'group': st.one_of(st.sampled_from(['front_spring', 'rear_stabilizer', 'nope']), TEXTS),
    'key': st.one_of(st.sampled_from(['front_spring.rate', 'front_alignment.camber',
                                      'front_hardpoints.points.lca_outer.z', 'x.']), TEXTS),
    'value': st.one_of(st.sampled_from(['X', 'Y', 'on', 'off', 'lca, strut', '']), QUANTITIES,
                       TEXTS),
    'source': st.one_of(st.sampled_from(['', 'sport', 'nope']), TEXTS),
}))
@settings(suppress_health_check=[HealthCheck.function_scoped_fixture])
def test_edit_bodies(body, bench):
    master = bench.master_file
    original = master.read_bytes()
    try:
        with no_hang(30.0):
            try:
                message = bench.edit(body)
            except (DataError, WorkbenchError) as err:
                clean(err)
                assert master.read_bytes() == original
                return
        assert message.startswith(f"{body['configuration']}: ")
        load_study(master)
    finally:
        master.write_bytes(original)
