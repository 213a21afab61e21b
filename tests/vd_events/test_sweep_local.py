# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Sweeps and optimisation with an in-process evaluator (the solvers' own K&C core).

The evaluator applies each run's overrides to the configuration and calls
``run_kc_event``, exactly what the K&C solver node does with a goal; the ROS
distribution is tested in tests/integration/test_sweep_ros.py.
"""
from __future__ import annotations

import csv
import json
from pathlib import Path

from numpy.testing import assert_allclose
import pytest

from vd_data_server.errors import DataError
from vd_data_server.master import parse_set, with_overrides
from vd_data_server.study import load_study
from vd_events.cli import main as cli
from vd_events.reports.sweep import write_outputs
from vd_events.sweeps.optimize import check_plan, optimize
from vd_events.sweeps.plan import convert, load_plan
from vd_events.sweeps.sweep import RUNS_FILE, sweep
from vd_solvers.kc.from_config import bar_stiffness, run_kc_event
from vdtest import tree_snapshot


def kc_run(study, configuration, overrides, event, axle, parameters):
    config = with_overrides(study.configurations[configuration], parse_set(overrides))
    return run_kc_event(config, event, axle, list(parameters))


class Local:
    """An evaluator computing each request in this process, counting the runs."""

    def __init__(self, study, stop_after: int | None = None) -> None:
        self.study, self.calls, self.stop_after = study, 0, stop_after

    def __call__(self, requests, done) -> None:
        for r in requests:
            if self.stop_after is not None and self.calls >= self.stop_after:
                raise KeyboardInterrupt
            self.calls += 1
            outcome = kc_run(self.study, r.configuration, r.overrides, r.event, r.axle,
                             r.parameters)
            assert outcome.data_hash == r.data_hash
            done(r, outcome, None, 'local')


BAR_PLAN = """\
name: bar
master: {master}
configuration: baseline
design: full_factorial
factors:
  bar_radius: {{key: front_stabilizer.bar_radius, unit: mm, values: [11, 12, 13]}}
runs:
  - {{event: opposite_wheel_travel, axle: front, parameters: [steps=11]}}
responses:
  roll_stiffness: {{metric: roll_stiffness, event: opposite_wheel_travel, unit: N*m/rad}}
  roll_stiffness_bar: {{metric: roll_stiffness_bar, event: opposite_wheel_travel,
                        unit: N*m/rad}}
  roll_stiffness_no_bar: {{metric: roll_stiffness_no_bar, event: opposite_wheel_travel,
                           unit: N*m/rad}}
"""


@pytest.fixture
def bar_plan(tmp_path, sedan_master):
    path = tmp_path / 'bar.yaml'
    path.write_text(BAR_PLAN.format(master=sedan_master))
    return path


def test_bar_sweep_main_effect_and_cache(tmp_path, bar_plan):
    plan = load_plan(bar_plan)
    study = load_study(plan.master)
    out = tmp_path / 'out'
    local = Local(study)
    result = sweep(plan, study, local, out, bags=False)
    write_outputs(result, out)
    assert local.calls == 3 and result.computed == 3 and not any(result.errors)
    total, bar, no_bar = result.responses.T
    # the bar does not change the rest of the axle, and the axle adds the bar's part
    assert_allclose(no_bar, no_bar[0], rtol=1e-9)
    assert_allclose(total, bar + no_bar, rtol=1e-9)
    # the bar's share follows its torsional rate G*pi*r^4/(2L): through the same linkage,
    # the roll stiffness it adds at the axle is proportional to that rate (to 0.2 %: the
    # bushings in series with the bar take a little more of a stiffer bar's share; seen
    # here as 1.1e-3 low at 13 mm and 0.8e-3 high at 11 mm)
    group = study.configurations['baseline'].group('front_stabilizer')
    rates = [bar_stiffness(group) * (r / 12.0) ** 4 for r in (11.0, 12.0, 13.0)]
    assert_allclose(bar / bar[1], [k / rates[1] for k in rates], rtol=2e-3)
    # the sweep's response equals the single run of the same configuration
    single = kc_run(study, 'baseline', ['front_stabilizer.bar_radius=13 mm'],
                    'opposite_wheel_travel', 'front', ['steps=11'])
    metric = single.metrics['roll_stiffness']
    assert_allclose(total[2], convert(metric.value, metric.unit, 'N*m/rad'), rtol=1e-12)
    # the table holds every point
    rows = list(csv.reader((out / 'table.csv').open()))
    assert rows[0] == ['point', 'bar_radius [mm]', 'roll_stiffness [N*m/rad]',
                       'roll_stiffness_bar [N*m/rad]', 'roll_stiffness_no_bar [N*m/rad]',
                       'error']
    assert [float(r[1]) for r in rows[1:]] == [11.0, 12.0, 13.0]
    assert_allclose([float(r[2]) for r in rows[1:]], total, rtol=1e-15)
    assert (out / 'sweep.html').is_file() and (out / 'main_effects.png').is_file()
    summary = json.loads((out / 'summary.json').read_text())
    # one factor: it explains all of the (monotonic, nearly linear) variation
    assert summary['sensitivity']['roll_stiffness']['first_order']['bar_radius'] == \
        pytest.approx(1.0)
    # identical runs are not computed twice: a second sweep computes nothing
    again = sweep(plan, study, local, out, bags=False)
    assert local.calls == 3 and again.computed == 0 and again.cached == 3
    assert_allclose(again.responses, result.responses, rtol=0)


def test_interrupted_sweep_keeps_finished_runs(tmp_path, bar_plan):
    plan = load_plan(bar_plan)
    study = load_study(plan.master)
    out = tmp_path / 'out'
    with pytest.raises(KeyboardInterrupt):
        sweep(plan, study, Local(study, stop_after=2), out, bags=False)
    assert len((out / RUNS_FILE).read_text().splitlines()) == 2
    assert not (out / 'table.csv').exists()
    rest = Local(study)
    result = sweep(plan, study, rest, out, bags=False)
    assert rest.calls == 1 and result.cached == 2 and not any(result.errors)


def test_sweep_writes_a_bag_per_run(tmp_path, bar_plan):
    from vd_events.bags.bag import read_bag

    plan = load_plan(bar_plan)
    study = load_study(plan.master)
    out = tmp_path / 'out'
    sweep(plan, study, Local(study), out)
    bags = sorted((out / 'bags').iterdir())
    assert len(bags) == 3
    topics = [m.topic for m in read_bag(bags[0])]
    assert topics == ['/vd/kc/result']


OPT_PLAN = """\
name: bump
master: {master}
configuration: baseline
factors:
  tierod_z: {{key: front_hardpoints.points.tierod_inner.z, unit: mm, range: [320, 360]}}
runs:
  - {{event: parallel_wheel_travel, axle: front, parameters: [steps=21]}}
responses:
  bump_steer: {{metric: bump_steer, event: parallel_wheel_travel, unit: deg/m,
               target: 0 deg/m +- 0.2 deg/m}}
optimize: {{max_evaluations: 30, configuration: zero_bump_steer}}
"""


def test_optimize_reaches_the_target_and_writes_the_configuration(tmp_path, sedan_master,
                                                                   capsys):
    path = tmp_path / 'bump.yaml'
    path.write_text(OPT_PLAN.format(master=sedan_master))
    plan = load_plan(path, optimize=True)
    study = load_study(plan.master)
    out = tmp_path / 'out'
    result = optimize(plan, study, Local(study), out)
    assert result.best.met
    assert abs(result.best.responses[0]) <= 0.2
    assert (out / 'history.csv').is_file()
    written = result.master
    assert written == out / 'sedan.yaml'
    # the configuration written meets the target when rerun from the master file alone
    new = load_study(written)
    assert 'zero_bump_steer' in new.configurations
    config = new.configurations['zero_bump_steer']
    rerun = run_kc_event(config, 'parallel_wheel_travel', 'front', ['steps=21'])
    bump = rerun.metrics['bump_steer']
    assert abs(convert(bump.value, bump.unit, 'deg/m')) <= 0.2
    # and the feedback shows it MODIFIED, with the optimised hard point
    assert cli.main(['data', 'status', '--json', '--master', str(written)]) == 0
    status = json.loads(capsys.readouterr().out)
    row = next(s for s in status['status'] if s['configuration'] == 'zero_bump_steer'
               and s['group'] == 'front_hardpoints')
    assert row['state'] == 'MODIFIED'
    assert [k['key'] for k in row['modified_keys']] == ['points.tierod_inner']
    # the source master file is untouched, the other configurations are kept
    assert 'zero_bump_steer' not in load_study(sedan_master).configurations
    assert set(study.configuration_names) < set(new.configuration_names)
    # a second optimisation into the same folder would write the same name: refused
    with pytest.raises(DataError, match="configuration 'zero_bump_steer' already exists in"):
        check_plan(plan, study, out)


def test_optimize_refuses_an_existing_configuration(tmp_path, sedan_master, capsys):
    path = tmp_path / 'bump.yaml'
    text = OPT_PLAN.format(master=sedan_master).replace('zero_bump_steer', 'sport')
    text = text.replace('max_evaluations: 30,', f'max_evaluations: 30, write_master: '
                        f'{sedan_master},')
    path.write_text(text)
    before = sedan_master.read_text()
    assert cli.main(['optimize', str(path), '--out', str(tmp_path / 'out')]) == 2
    assert capsys.readouterr().err.strip() == (
        f"{path}: optimize.configuration: configuration 'sport' already exists in "
        f'{sedan_master} (choose another name: optimize.configuration)')
    assert sedan_master.read_text() == before and not (tmp_path / 'out').exists()


def test_plan_master_written_in_place_keeps_comments(tmp_path, sedan_master):
    from vd_events.sweeps.optimize import Evaluation, write_configuration

    path = tmp_path / 'bump.yaml'
    path.write_text(OPT_PLAN.format(master=sedan_master))
    plan = load_plan(path, optimize=True)
    study = load_study(sedan_master)
    best = Evaluation((341.5,), (0.0,), 0.0, True)
    write_configuration(plan, study, 'opt', best, sedan_master)
    text = sedan_master.read_text()
    assert text.startswith('# Sample study: a 1.7 t sedan')
    config = load_study(sedan_master).configurations['opt']
    assert config.group('front_hardpoints').values['points.tierod_inner'].si[2] == \
        pytest.approx(0.3415)


def test_plans_folder_file_is_valid():
    plan = load_plan(Path(__file__).resolve().parents[2] / 'src' / 'vd_events' / 'plans' /
                     'optimize_sedan.yaml', optimize=True)
    assert plan.optimize is not None and not plan.design


def test_configuration_written_beside_the_bundled_study(tmp_path):
    """The sample plans' master is the installed share (links to the sources): still loads."""
    from vd_events.sweeps.optimize import Evaluation, write_configuration

    plan = load_plan(Path(__file__).resolve().parents[2] / 'src' / 'vd_events' / 'plans' /
                     'optimize_sedan.yaml', optimize=True)
    study = load_study(plan.master)
    target = tmp_path / 'opt' / 'sedan.yaml'
    write_configuration(plan, study, 'front_kinematics', Evaluation((341.8, 189.5), (0.0, 60.0),
                                                                    0.0, True), target)
    new = load_study(target)
    points = new.configurations['front_kinematics'].group('front_hardpoints').values
    assert points['points.tierod_inner'].si[2] == pytest.approx(0.3418)
    assert points['points.lca_outer'].si[2] == pytest.approx(0.1895)
    assert new.configurations['baseline'].data_hash == study.configurations['baseline'].data_hash


def test_plan_write_master_outside_the_data_root_is_refused(tmp_path, sedan_master, capsys,
                                                            sample_root):
    """A plan file cannot make vd optimize write anywhere (/etc/...): only under the root."""
    path = tmp_path / 'bump.yaml'
    target = tmp_path / 'elsewhere' / 'sedan.yaml'
    target.parent.mkdir()
    path.write_text(OPT_PLAN.format(master=sedan_master).replace(
        'max_evaluations: 30,', f'max_evaluations: 30, write_master: {target},'))
    before = tree_snapshot(tmp_path)
    assert cli.main(['optimize', str(path), '--out', str(tmp_path / 'out')]) == 2
    assert capsys.readouterr().err.strip() == (
        f"{path}: optimize.write_master: {target} is outside the study's data root "
        f'{sample_root}: a plan writes master files only under it (name the file on the '
        'command line to write elsewhere: vd optimize --write-master PATH)')
    assert tree_snapshot(tmp_path) == before


def test_write_master_named_on_the_command_line_may_lie_anywhere(tmp_path, sedan_master):
    from dataclasses import replace

    from vd_events.sweeps.plan import OptimizeSpec

    path = tmp_path / 'bump.yaml'
    path.write_text(OPT_PLAN.format(master=sedan_master))
    plan = load_plan(path, optimize=True)
    target = tmp_path / 'elsewhere' / 'sedan.yaml'
    plan = replace(plan, optimize=replace(plan.optimize or OptimizeSpec(), write_master=target,
                                          named_by_user=True))
    assert check_plan(plan, load_study(sedan_master), tmp_path / 'out') == 'zero_bump_steer'


@pytest.mark.parametrize('value', ['100000000000', '0', '4097'])
def test_max_evaluations_is_bounded(tmp_path, sedan_master, value):
    path = tmp_path / 'bump.yaml'
    path.write_text(OPT_PLAN.format(master=sedan_master).replace('max_evaluations: 30',
                                                                 f'max_evaluations: {value}'))
    with pytest.raises(DataError) as err:
        load_plan(path, optimize=True)
    assert str(err.value) == (f'{path}: optimize.max_evaluations: expected a whole number '
                              f'1..4096, found {value}')


def test_a_master_changed_during_the_optimisation_is_not_overwritten(tmp_path, sedan_master):
    from vd_data_server.masteredit import ConflictError, fingerprint
    from vd_events.sweeps.optimize import Evaluation, write_configuration

    path = tmp_path / 'bump.yaml'
    path.write_text(OPT_PLAN.format(master=sedan_master))
    plan = load_plan(path, optimize=True)
    study = load_study(sedan_master)
    read = fingerprint(sedan_master)
    edited = sedan_master.read_text().replace('# Sample study', '# Edited sample study', 1)
    sedan_master.write_text(edited)  # another editor, while the optimisation ran
    with pytest.raises(ConflictError) as err:
        write_configuration(plan, study, 'opt', Evaluation((341.5,), (0.0,), 0.0, True),
                            sedan_master, expected=read)
    assert str(err.value) == (f'{sedan_master}: changed on disk since the optimisation read '
                              "it: the configuration 'opt' is not written (the history is)")
    assert sedan_master.read_text() == edited


@pytest.mark.parametrize(('edit', 'message'), [
    (('metric: roll_stiffness_bar,', 'metric: roll_stifness_bar,'),
     "responses.roll_stiffness_bar.metric: run opposite_wheel_travel/front (kc) has no metric "
     "'roll_stifness_bar' (metrics: max_constraint_residual, max_force_residual, "
     'rigid_mass.lca, rigid_mass.strut, rigid_mass.tierod, rigid_mass.upright, roll_camber, '
     'roll_steer, roll_stiffness, roll_stiffness_bar, roll_stiffness_no_bar)'),
    (('unit: N*m/rad}\n  roll_stiffness_bar', 'unit: N/mm}\n  roll_stiffness_bar'),
     "responses.roll_stiffness.unit: unit 'N*m/rad' cannot be converted to 'N/mm' (metric "
     "'roll_stiffness' is in N*m/rad)"),
])
def test_a_response_the_runs_do_not_report_stops_the_sweep_after_one_point(
        tmp_path, sedan_master, edit, message):
    path = tmp_path / 'bar.yaml'
    path.write_text(BAR_PLAN.format(master=sedan_master).replace(*edit, 1))
    plan = load_plan(path)
    study = load_study(plan.master)
    local = Local(study)
    with pytest.raises(DataError) as err:
        sweep(plan, study, local, tmp_path / 'out', bags=False)
    assert str(err.value) == f'{path}: {message}'
    assert local.calls == 1  # the first point only, not the three of the sweep
