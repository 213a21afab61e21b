# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Study plans: the plan file is checked against its spec (``study_plan.PLAN``).

Every bad plan is refused with the file, the key and (for mapping keys) the line, all
problems of the file at once, and nothing is written.
"""
from __future__ import annotations

from pathlib import Path

import pytest

from vd_data_server.errors import DataError
from vd_data_server.paths import default_master
from vd_data_server.study import load_study
from vd_events.studies.plan import expand, load_plan
from vdtest import line_no, tree_snapshot

GOOD = """name: small
runs:
  - event: handling_diagram
    models: [bicycle, two_track]
    configurations: [baseline]
  - event: parallel_wheel_travel
    models: [kc]
    axle: front
    fidelity: flexible
"""


def refused(tmp_path: Path, text: str) -> list[str]:
    """Return the error lines of loading a plan of ``text``; nothing is written."""
    plan = tmp_path / 'plan.yaml'
    plan.write_text(text)
    before = tree_snapshot(tmp_path)
    with pytest.raises(DataError) as info:
        load_plan(plan)
    assert tree_snapshot(tmp_path) == before
    return [line.replace(f'{plan}: ', '', 1) for line in str(info.value).splitlines()]


def test_a_good_plan_expands_to_one_run_per_model_and_configuration(tmp_path: Path) -> None:
    plan = tmp_path / 'plan.yaml'
    plan.write_text(GOOD)
    runs = expand(load_plan(plan), load_study(default_master()), tmp_path / 'bags')
    assert [(r.event, r.model, r.configuration, r.axle, r.fidelity) for r in runs] == [
        ('handling_diagram', 'bicycle', 'baseline', '', 'rigid'),
        ('handling_diagram', 'two_track', 'baseline', '', 'rigid'),
        ('parallel_wheel_travel', 'kc', 'baseline', 'front', 'flexible'),
        ('parallel_wheel_travel', 'kc', 'stiff_rear', 'front', 'flexible'),
        ('parallel_wheel_travel', 'kc', 'sport', 'front', 'flexible')]
    assert runs[2].bag == tmp_path / 'bags' / 'parallel_wheel_travel_front_kc_baseline_flexible'


def test_a_plan_that_is_no_mapping_is_refused(tmp_path: Path) -> None:
    assert refused(tmp_path, '- event: steering\n') == [
        "expected a mapping with 'name' and 'runs'"]


def test_unknown_keys_are_refused_with_their_lines(tmp_path: Path) -> None:
    text = GOOD.replace('name: small\n', 'name: small\nowner: chassis\n').replace(
        '    axle: front\n', '    axle: front\n    repeat: 3\n')
    plan = tmp_path / 'plan.yaml'
    plan.write_text(text)
    assert refused(tmp_path, text) == [
        f"owner: unknown key (expected one of: name, master, runs, measurements) "
        f"(line {line_no(plan, 'owner:')})",
        'runs[1].repeat: unknown key (expected one of: event, models, configurations, '
        f"parameters, overrides, axle, fidelity) (line {line_no(plan, '    repeat:')})"]


def test_the_plan_name_must_be_plain(tmp_path: Path) -> None:
    assert refused(tmp_path, GOOD.replace('name: small', 'name: ../small')) == [
        "name: invalid plan name (letters, digits, '_', '-', '.'), found '../small' (line 1)"]


def test_a_plan_needs_a_name_and_runs(tmp_path: Path) -> None:
    assert refused(tmp_path, 'master: sedan.yaml\n') == [
        'name: missing required key', 'runs: missing required key']


def test_runs_must_be_a_non_empty_list(tmp_path: Path) -> None:
    assert refused(tmp_path, 'name: small\nruns: []\n') == [
        'runs: expected a non-empty list of runs, found [] (line 2)']


def test_every_run_needs_an_event(tmp_path: Path) -> None:
    assert refused(tmp_path, 'name: small\nruns:\n  - models: [kc]\n  - steering\n') == [
        'runs[0].event: missing required key (line 2)',
        "runs[1]: expected a mapping, found str 'steering' (line 2)"]


def test_lists_of_texts_are_checked_item_by_item(tmp_path: Path) -> None:
    text = GOOD.replace('models: [bicycle, two_track]', 'models: [bicycle, 2]').replace(
        'configurations: [baseline]', 'configurations: baseline')
    assert refused(tmp_path, text) == [
        'runs[0].models[1]: expected a text, found int 2 (line 4)',
        "runs[0].configurations: expected 'all' or a list of names, found 'baseline' (line 5)"]


def test_the_master_must_be_a_path(tmp_path: Path) -> None:
    assert refused(tmp_path, GOOD.replace('name: small\n', 'name: small\nmaster: 3\n')) == [
        'master: expected a text, found int 3 (line 2)']
