# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Property-based fuzzing of every input the data side reads.

Data files, raw YAML, master files, .tir files and edits. Property: either a clean
DataError or a valid result; never another exception (a traceback), a hang or a huge
message (issue 10).
"""
from __future__ import annotations

import math
from pathlib import Path
import shutil

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
import pytest
import yaml

from fuzzing import QUANTITIES, clean, mutate, no_hang
from vd_data_server.datafile import parse_group
from vd_data_server.errors import DataError
from vd_data_server.yamlio import loads

SAMPLE = Path(__file__).resolve().parents[2] / 'src' / 'vd_data_server' / 'data'
#: (group, file) of every sedan data file
FILES = sorted((p.parent.name, p) for p in (SAMPLE / 'sedan').glob('*/*.yaml'))


@pytest.fixture(scope='module')
def root(tmp_path_factory) -> Path:
    """
    Return one writable copy of the sample data for the whole module.

    Hypothesis reruns the test body many times; each example writes only its own
    fuzz files.
    """
    copy = tmp_path_factory.mktemp('fuzz') / 'data'
    shutil.copytree(SAMPLE, copy)
    return copy


@given(data=st.data(), which=st.sampled_from(FILES))
def test_mutated_data_files(data, which):
    group, path = which
    tree = yaml.safe_load(path.read_text())
    text = yaml.safe_dump(mutate(data, tree), allow_unicode=True)
    with no_hang():
        try:
            raw = loads(text, file='fuzz.yaml')
            result = parse_group(raw, display='fuzz.yaml', group=group, variant='X')
        except DataError as err:
            clean(err)
            return
    for value in result.values.values():
        if value.type == 'scalar':
            assert math.isfinite(value.si), value


@given(text=st.one_of(st.text(max_size=300), st.binary(max_size=300).map(
    lambda b: b.decode('latin-1'))))
def test_arbitrary_yaml_text(text):
    with no_hang():
        try:
            loads(text, file='fuzz.yaml')
        except DataError as err:
            clean(err)


@given(data=st.data())
def test_mutated_master_files(data, root):
    from vd_data_server.study import load_study

    tree = yaml.safe_load((root / 'studies' / 'sedan.yaml').read_text())
    master = root / 'studies' / 'fuzz.yaml'
    master.write_text(yaml.safe_dump(mutate(data, tree, rounds=4), allow_unicode=True))
    with no_hang():
        try:
            study = load_study(master)
        except DataError as err:
            clean(err)
            return
    for config in study.configurations.values():
        assert len(config.data_hash) == 16


TIR = (SAMPLE / 'tires' / 'Sedan_Pac02Tire.tir').read_text(encoding='latin-1').splitlines()
TOKENS = st.one_of(
    QUANTITIES, st.sampled_from(['0', '-1', '1e999', '-1e999', '1e-320', '1e300', "'PAC2002'",
                                 "''", "'", '[', '{a b}', '=', '$', 'nan', 'inf']),
    st.floats(allow_nan=False, allow_infinity=False).map(repr), st.text(max_size=12))


@given(data=st.data())
def test_mutated_tir_files(data):
    from vd_data_server.tir import parse_tir_text
    from vd_solvers.errors import SolverError
    from vd_solvers.tire.magic_formula import MagicFormula

    lines = list(TIR)
    for _ in range(data.draw(st.integers(1, 4))):
        index = data.draw(st.integers(0, len(lines) - 1))
        action = data.draw(st.sampled_from(['value', 'delete', 'insert', 'key']))
        if action == 'value' and '=' in lines[index]:
            key = lines[index].split('=')[0]
            lines[index] = f'{key}= {data.draw(TOKENS)}'
        elif action == 'delete':
            del lines[index]
        elif action == 'insert':
            lines.insert(index, data.draw(st.text(max_size=30)))
        else:
            key = data.draw(st.sampled_from(
                ['PKY2', 'FNOMIN', 'LFZO', 'PCY1', 'PDX1', 'LMUY', 'UNLOADED_RADIUS']))
            lines.insert(index, f'{key} = {data.draw(TOKENS)}')
    with no_hang():
        try:
            props = parse_tir_text('\n'.join(lines), 'fuzz.tir')
            tire = MagicFormula(props)
            fz = props.fnomin
            values = [float(tire.cornering_stiffness(fz)), float(tire.fy(fz, 0.05)),
                      float(tire.fx(fz, 0.05))]
        except (DataError, SolverError) as err:
            clean(err)
            return
    assert all(math.isfinite(v) for v in values), values


_SERVICE: dict = {}  # one loaded data service per data copy, reset for each example


@given(configuration=st.sampled_from(['baseline', 'sport', 'nope', '', '../x']),
       key=st.one_of(st.sampled_from(['front_spring.rate', 'mass.sprung_mass',
                                      'front_hardpoints.points.lca_outer.x',
                                      'front_tire.tir.LATERAL_COEFFICIENTS.PKY2',
                                      'front_alignment.camber', 'geometry.wheelbase']),
                     st.text(max_size=30)),
       value=st.one_of(QUANTITIES, st.text(max_size=30)))
def test_edit_requests(configuration, key, value, root):
    """What /vd/set_override hands the data server's core."""
    from vd_data_server.service import DataService

    if root not in _SERVICE:
        _SERVICE[root] = DataService(root / 'studies' / 'sedan.yaml')
        assert _SERVICE[root].load().errors == ()
        _SERVICE[root].base = _SERVICE[root].study
    service = _SERVICE[root]
    service.edits, service.study = {}, service.base  # as freshly loaded
    before = service.study
    with no_hang():
        try:
            service.set_override(configuration, key, value)
        except DataError as err:
            clean(err)
            assert service.study is before  # nothing changed
            return
    assert service.study.configurations[configuration].data_hash


@given(argv=st.lists(st.one_of(st.sampled_from(
    ['data', 'status', 'show', 'check', 'run', 'study', 'report', '--json', '--master',
     '--set', '--param', '--model', '--axle', '--config', '--bag', '--fidelity', 'baseline',
     'handling_diagram', 'parallel_wheel_travel', 'kc', 'two_track', 'front', 'flexible',
     'front_spring.rate=3 N/mm', 'radius=nan m', 'steps=0', '/proc/x', '-', '--']),
    QUANTITIES, st.text(max_size=12)), max_size=8))
@settings(suppress_health_check=[HealthCheck.function_scoped_fixture])
def test_cli_arguments(argv, root, monkeypatch, capsys):
    """
    Check that any argument list gives a usage message, the command's clean error or success.

    The usage message comes from argparse (exit 2), the clean error exits 2 too. The
    runner is replaced: starting ROS graphs is not what is fuzzed here, the arguments'
    way to it is.
    """
    from vd_events.cli.main import main
    from vd_events.orchestration import inprocess, runner

    def no_graph(master, requests, progress=None, **kwargs):
        raise runner.RunError('validated; no run in the fuzz test')

    monkeypatch.setattr(inprocess, 'run_inprocess', no_graph)
    monkeypatch.setattr(runner, 'run_embedded', no_graph)
    monkeypatch.setattr(runner, 'run_distributed', no_graph)
    monkeypatch.chdir(root)
    with no_hang():
        try:
            rc = main(argv)
        except SystemExit as stop:  # argparse: usage error or --help
            rc = stop.code
    out, err = capsys.readouterr()
    assert rc in (0, 1, 2), (rc, out, err)
    assert 'Traceback' not in out + err


PLAN = Path(__file__).resolve().parents[2] / 'src' / 'vd_events' / 'plans' / 'demo.yaml'
_STUDY: dict = {}  # the sample study, loaded once per data copy


@given(data=st.data())
def test_mutated_study_plans(data, root):
    """
    Load a plan, expand it and validate every run.

    This is what `vd study` does before it starts anything.
    """
    from vd_data_server.study import load_study
    from vd_events.errors import BagError, RunError
    from vd_events.orchestration.runner import validate
    from vd_events.studies.plan import expand, load_plan

    tree = yaml.safe_load(PLAN.read_text())
    tree.pop('master', None)
    plan_file = root / 'fuzz_plan.yaml'
    plan_file.write_text(yaml.safe_dump(mutate(data, tree), allow_unicode=True))
    study = _STUDY.setdefault(root, load_study(root / 'studies' / 'sedan.yaml'))
    with no_hang():
        try:
            plan = load_plan(plan_file)
            for request in expand(plan, study, root / 'bags'):
                validate(study, request)
        except (DataError, RunError, BagError) as err:
            clean(err)
