# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""Sweep plans: parsing, designs, and every class of bad plan refused before a run."""
from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from vd_data_server.errors import DataError
from vd_events.cli import main as cli
from vd_events.sweeps.plan import convert, load_plan, points

REPO = Path(__file__).resolve().parents[2]
SAMPLE_PLAN = REPO / 'src' / 'vd_events' / 'plans' / 'sweep_sedan.yaml'

GOOD = """\
name: t
master: {master}
configuration: baseline
design: {design}
{extra}
factors:
  tierod_z:
    key: front_hardpoints.points.tierod_inner.z
    unit: mm
    range: [326, 346]
{levels}
  bar_radius:
    key: front_stabilizer.bar_radius
    unit: mm
    range: [11 mm, 1.3 cm]
{levels}
runs:
  - {event: parallel_wheel_travel, axle: front, parameters: [steps=21]}
responses:
  bump_steer: {metric: bump_steer, event: parallel_wheel_travel, unit: deg/m,
               target: 0 deg/m +- 1 deg/m}
"""


def write(tmp_path: Path, text: str, master: Path) -> Path:
    path = tmp_path / 'plan.yaml'
    path.write_text(text.replace('{master}', str(master)))
    return path


def plan_text(design='full_factorial', extra='', levels='    levels: 3'):
    return GOOD.replace('{design}', design).replace('{extra}', extra).replace(
        '{levels}', levels)


def test_sample_plan_full_factorial():
    plan = load_plan(SAMPLE_PLAN)
    pts = points(plan)
    assert len(pts) == 9
    assert pts[0] == (326.0, 11.0) and pts[1] == (326.0, 12.0) and pts[-1] == (346.0, 13.0)
    tierod, bar = plan.factors
    assert tierod.override(336.0) == 'front_hardpoints.points.tierod_inner.z=336 mm'
    assert bar.base == pytest.approx(12.0)  # the data file's 12.0 mm, in the plan's unit
    assert [r.name for r in plan.responses] == ['bump_steer', 'roll_centre', 'roll_stiffness']
    assert plan.responses[2].run.event == 'opposite_wheel_travel'
    assert plan.responses[0].run.model == 'kc'


def test_value_units_convert_to_the_factor_unit(tmp_path, sedan_master):
    plan = load_plan(write(tmp_path, plan_text(), sedan_master))
    assert plan.factors[1].high == pytest.approx(13.0)  # '1.3 cm' in mm
    assert plan.responses[0].target.value == 0.0
    assert plan.responses[0].target.tolerance == 1.0


def test_latin_hypercube_one_sample_per_stratum(tmp_path, sedan_master):
    plan = load_plan(write(tmp_path, plan_text('latin_hypercube', 'samples: 10\nseed: 3', ''),
                           sedan_master))
    x = np.array(points(plan))
    assert x.shape == (10, 2)
    for j, f in enumerate(plan.factors):
        strata = np.floor((x[:, j] - f.low) / (f.high - f.low) * 10).astype(int)
        assert sorted(strata) == list(range(10))
    assert points(plan) == points(plan)  # the seed makes it reproducible


def test_sobol_points_in_range_and_balanced(tmp_path, sedan_master):
    plan = load_plan(write(tmp_path, plan_text('sobol', 'samples: 16', ''), sedan_master))
    x = np.array(points(plan))
    assert x.shape == (16, 2)
    for j, f in enumerate(plan.factors):
        assert np.all((x[:, j] >= f.low) & (x[:, j] <= f.high))
        # a (t, m, s)-net in base 2: each half of the range holds exactly half the points
        assert np.sum(x[:, j] < (f.low + f.high) / 2) == 8


def test_convert_tells_angles_apart():
    assert convert(1.0, 'rad/m', 'deg/m') == pytest.approx(57.29577951308232)
    assert convert(2.0, 'N*m/deg', 'N*m/rad') == pytest.approx(2.0 * 57.29577951308232)
    with pytest.raises(ValueError, match="unit 'deg/m' cannot be converted to '1/m'"):
        convert(1.0, 'deg/m', '1/m')


BAD = [
    ('unknown top-level key',
     lambda t: t.replace('design:', 'desing: x\ndesign:'),
     'plan.yaml: desing: unknown key (expected one of: name, description, master, '
     'configuration, design, samples, seed, factors, runs, responses, pareto, optimize)'),
    ('unknown factor key',
     lambda t: t.replace('    unit: mm\n    range: [326', '    unti: mm\n    range: [326'),
     'plan.yaml: factors.tierod_z.unti: unknown key (expected one of: key, unit, range, '
     'values, levels, start)'),
    ('unknown override key',
     lambda t: t.replace('tierod_inner.z', 'tierod_innr.z'),
     "plan.yaml: factors.tierod_z.key: key 'points.tierod_innr.z' does not exist in group "
     "'front_hardpoints' (sedan/front_hardpoints/X.yaml); keys: points.arb_link_lower"),
    ('unit of the wrong dimension',
     lambda t: t.replace('    unit: mm\n    range: [326', '    unit: deg\n    range: [326'),
     "plan.yaml: factors.tierod_z.unit: unit 'deg' is not a length unit (expected e.g. 'm'), "
     'as front_hardpoints.points.tierod_inner.z is'),
    ('a value in a unit of the wrong dimension',
     lambda t: t.replace('[11 mm, 1.3 cm]', '[11 mm, 13 N]'),
     "plan.yaml: factors.bar_radius.range[1]: unit 'N' cannot be converted to 'mm' (the unit "
     'of this value)'),
    ('empty range',
     lambda t: t.replace('[326, 346]', '[346, 346]'),
     'plan.yaml: factors.tierod_z.range: empty range [346, 346] (low must be below high)'),
    ('empty list of levels',
     lambda t: t.replace('    range: [326, 346]\n    levels: 3', '    values: []'),
     'plan.yaml: factors.tierod_z.values: empty list of values'),
    ('more levels than the design allows',
     lambda t: t.replace('levels: 3', 'levels: 40', 1),
     'plan.yaml: factors.tierod_z.levels: 40 levels, more than the limit of 21 of a full '
     'factorial design'),
    ('response metric of a run not in the plan',
     lambda t: t.replace('event: parallel_wheel_travel, unit', 'event: lateral_force, unit'),
     "plan.yaml: responses.bump_steer.event: no run of the plan matches event 'lateral_force' "
     '(runs: parallel_wheel_travel/front (kc))'),
    ('target in a unit of the wrong dimension',
     lambda t: t.replace('0 deg/m +- 1 deg/m', '0 mm +- 1 deg/m'),
     "plan.yaml: responses.bump_steer.target: unit 'mm' cannot be converted to 'deg/m'"),
]


@pytest.mark.parametrize('case,edit,message', BAD, ids=[b[0] for b in BAD])
def test_bad_plan_refused_before_any_run(tmp_path, sedan_master, capsys, case, edit, message):
    path = write(tmp_path, edit(plan_text()), sedan_master)
    with pytest.raises(DataError) as err:
        load_plan(path)
    assert str(err.value).startswith(str(tmp_path / message.split(': ', 1)[0]) + ': '
                                     + message.split(': ', 1)[1])
    out = tmp_path / 'out'
    assert cli.main(['sweep', str(path), '--out', str(out)]) == 2
    assert capsys.readouterr().err.strip().startswith(str(tmp_path / 'plan.yaml'))
    assert not out.exists()


def test_sobol_needs_a_power_of_two(tmp_path, sedan_master):
    path = write(tmp_path, plan_text('sobol', 'samples: 12', ''), sedan_master)
    with pytest.raises(DataError, match=r'samples: 12 samples: a Sobol sequence is balanced only '
                       r'for a power of 2 \(e.g. 8 or 16\)'):
        load_plan(path)


def test_sampled_design_refuses_levels(tmp_path, sedan_master):
    path = write(tmp_path, plan_text('latin_hypercube', 'samples: 8'), sedan_master)
    with pytest.raises(DataError, match="factors.tierod_z.levels: design 'latin_hypercube' "
                       'takes .samples. for the whole plan'):
        load_plan(path)


def test_point_out_of_the_key_range_refused(tmp_path, sedan_master, capsys):
    text = plan_text().replace('[11 mm, 1.3 cm]', '[-1 mm, 1.3 cm]')
    path = write(tmp_path, text, sedan_master)
    out = tmp_path / 'out'
    assert cli.main(['sweep', str(path), '--out', str(out)]) == 2
    err = capsys.readouterr().err
    assert err.startswith(f'{path}: point 0 (tierod_z=326 mm, bar_radius=-1 mm), run '
                          'parallel_wheel_travel/front (kc): ')
    assert 'bar_radius' in err and 'positive' in err
    assert not out.exists()


def test_bad_solvers_option(tmp_path, capsys):
    out = tmp_path / 'out'
    assert cli.main(['sweep', str(SAMPLE_PLAN), '--solvers', 'kc=0', '--out', str(out)]) == 2
    assert capsys.readouterr().err.strip() == ("--solvers: expected a positive number of "
                                               "instances, found 'kc=0'")
    assert not out.exists()
