# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Hostile input at the CLI boundary.

Each class of bad input gives one clean message, exit code 2 and changes nothing
(issue 10, causes 3, 4, 7, 8, 9).
"""
from __future__ import annotations

from pathlib import Path

import pytest

from vd_events.cli.main import main
from vdtest import line_no, replace_once, tree_snapshot

BIG = '9' * 400


def run(capsys: pytest.CaptureFixture[str], *argv: str) -> tuple[int, str, str]:
    rc = main(list(argv))
    out, err = capsys.readouterr()
    return rc, out, err


def check(capsys, sample_root: Path, sedan_master: Path, expected: str, *argv: str) -> None:
    """``vd data check`` (or ``argv``) exits 2 with exactly ``expected``, writes nothing."""
    before = tree_snapshot(sample_root)
    rc, out, err = run(capsys, *(argv or ('data', 'check', '--master', str(sedan_master))))
    assert (rc, out) == (2, '')
    assert err.strip() == expected
    assert tree_snapshot(sample_root) == before


SPRING = 'sedan/front_spring/X.yaml'


@pytest.mark.parametrize(('value', 'message'), [
    (BIG, 'number too large (400 digits)'),
    ("'30 N/(mm*0)'", "invalid unit 'N/(mm*0)'"),
    ("'30 N/0'", "invalid unit 'N/0'"),
    ("''", "expected a number with a unit, found ''"),
    ("'nan N/mm'", "value must be finite, found 'nan N/mm'"),
    ('1.0e+999', 'value must be finite, found inf'),
])
def test_numbers_and_units_that_broke_the_parser(capsys, sample_root, sedan_master, value,
                                                 message):
    spring = sample_root / SPRING
    replace_once(spring, 'rate: 30.0', f'rate: {value}')
    check(capsys, sample_root, sedan_master,
          f"{SPRING}: rate: {message} (line {line_no(spring, '  rate:')})")


def test_integer_beyond_python_conversion_limit_names_file_and_line(capsys, sample_root,
                                                                    sedan_master):
    spring = sample_root / SPRING
    replace_once(spring, 'rate: 30.0', 'rate: ' + '9' * 5001)
    check(capsys, sample_root, sedan_master,
          f'{SPRING}: number too large (5001 digits, the limit is 4000) '
          f"(line {line_no(spring, '  rate:')}, column 9)")


def test_bare_numbers_without_a_units_block_are_refused(capsys, sample_root, sedan_master):
    """A spring file that lost its units block is not read as 30 N/m."""
    spring = sample_root / SPRING
    replace_once(spring, 'units: {length: mm, force: N}\n', '')
    check(capsys, sample_root, sedan_master,
          f"{SPRING}: rate: 30.0 has no unit and the file has no units block (add one, e.g. "
          "'units: {length: mm, force: N}', or write the unit with the value, e.g. '30.0 N/m') "
          f"(line {line_no(spring, '  rate:')})\n"
          f"{SPRING}: preload: 4535 has no unit and the file has no units block (add one, e.g. "
          "'units: {length: mm, force: N}', or write the unit with the value, e.g. '4535 N') "
          f"(line {line_no(spring, '  preload:')})")


def test_deep_yaml_is_refused_at_the_depth_limit(capsys, sample_root, sedan_master):
    (sample_root / SPRING).write_text('kind: spring\ndata: ' + '[' * 2000 + ']' * 2000 + '\n')
    check(capsys, sample_root, sedan_master,
          f'{SPRING}: exceeds the limit of 64 nesting levels (line 2)')


def test_alias_bomb_is_refused_without_expanding_it(capsys, sample_root, sedan_master):
    lines = ['kind: spring', 'description: &a0 [x, x, x, x, x, x, x, x, x, x]']
    lines += [f'd{i}: &a{i} [' + ', '.join([f'*a{i - 1}'] * 10) + ']' for i in range(1, 9)]
    (sample_root / SPRING).write_text('\n'.join(lines) + '\n')
    check(capsys, sample_root, sedan_master,
          f'{SPRING}: exceeds the limit of 100000 values with its aliases expanded (line 6)')


def test_huge_file_is_refused_before_it_is_parsed(capsys, sample_root, sedan_master):
    (sample_root / SPRING).write_text('kind: spring\n' + '#' * (2 << 20) + '\n')
    check(capsys, sample_root, sedan_master, f'{SPRING}: exceeds the limit of 1 MiB per file')


def test_many_problems_are_listed_up_to_the_limit(capsys, sample_root, sedan_master):
    points = '\n'.join(f'    p{i}: [0, 0, 0]' for i in range(80))
    hard = sample_root / 'sedan/front_hardpoints/X.yaml'
    text = hard.read_text()
    hard.write_text(text.replace('  points:\n', f'  points:\n{points}\n', 1))
    before = tree_snapshot(sample_root)
    rc, out, err = run(capsys, 'data', 'check', '--master', str(sedan_master))
    lines = err.splitlines()
    assert (rc, len(lines)) == (2, 51)
    assert lines[-1] == '... and 30 more problems (the limit is 50 listed)'
    assert tree_snapshot(sample_root) == before


def test_long_values_are_cut_in_messages(capsys, sample_root, sedan_master):
    replace_once(sample_root / SPRING, 'rate: 30.0', 'rate: ' + 'x' * 5000)
    before = tree_snapshot(sample_root)
    rc, _, err = run(capsys, 'data', 'check', '--master', str(sedan_master))
    assert rc == 2
    assert err.strip().endswith('... (cut at the limit of 500 characters)')
    assert len(err) < 700
    assert tree_snapshot(sample_root) == before


TIRE = 'tires/Sedan_Pac02Tire.tir'


@pytest.mark.parametrize(('line', 'key', 'message'), [
    ('FNOMIN = 1e999', 'FNOMIN', "key 'FNOMIN' in block [VERTICAL] must be a finite number, "
     "found 1e999"),
    ('PKY2 = 0', 'PKY2', "key 'PKY2' in block [LATERAL_COEFFICIENTS] must not be 0 (the Magic "
     "Formula divides by it), found 0"),
    ('PDY1 = 0.0', 'PDY1', "key 'PDY1' in block [LATERAL_COEFFICIENTS] must not be 0 (the "
     "Magic Formula divides by it), found 0.0"),
    ('LFZO = -1', 'LFZO', "key 'LFZO' in block [SCALING_COEFFICIENTS] must be > 0, found -1"),
])
def test_tire_values_that_overflow_or_divide_by_zero(capsys, sample_root, sedan_master, line,
                                                     key, message):
    tir = sample_root / TIRE
    lines = tir.read_text(encoding='latin-1').splitlines()
    number = next(n for n, t in enumerate(lines, start=1) if t.split('=')[0].strip() == key)
    lines[number - 1] = line
    tir.write_text('\n'.join(lines) + '\n', encoding='latin-1')
    check(capsys, sample_root, sedan_master, f'{tir}: {key}: line {number}: {message}')


def test_tire_override_to_zero_is_refused_like_the_file_value(capsys, sample_root,
                                                             sedan_master):
    """`vd data check` refuses what a run would compute from: the overridden coefficient."""
    replace_once(sedan_master, '  baseline:\n', '  baseline:\n    overrides:\n'
                 '      front_tire.tir.LATERAL_COEFFICIENTS.PKY2: 0\n')
    check(capsys, sample_root, sedan_master,
          "sedan/front_tire/X.yaml -> tires/Sedan_Pac02Tire.tir: PKY2: key 'PKY2' in block "
          "[LATERAL_COEFFICIENTS] must not be 0 (the Magic Formula divides by it), found 0")


def test_tire_linked_to_a_file_outside_the_root_is_not_read(capsys, sample_root,
                                                          sedan_master):
    tir = sample_root / TIRE
    tir.unlink()
    tir.symlink_to('/etc/passwd')
    check(capsys, sample_root, sedan_master,
          f"sedan/front_tire/X.yaml: file: '{TIRE}' is outside the data root {sample_root}\n"
          f"sedan/rear_tire/X.yaml: file: '{TIRE}' is outside the data root {sample_root}")
    assert 'root:' not in capsys.readouterr().err


def test_data_file_linked_outside_the_root_is_not_read(capsys, sample_root, sedan_master,
                                                       tmp_path):
    outside = tmp_path / 'elsewhere.yaml'
    outside.write_text((sample_root / SPRING).read_text())
    (sample_root / SPRING).unlink()
    (sample_root / SPRING).symlink_to(outside)
    check(capsys, sample_root, sedan_master,
          f'{SPRING}: resolves outside the data root {sample_root} (a symbolic link?): not read')


def test_a_link_loop_in_the_data_root_does_not_hang(capsys, sample_root, sedan_master):
    from vd_data_server.service import DataService

    (sample_root / 'sedan' / 'loop').symlink_to(sample_root)
    service = DataService(sedan_master)
    assert service.load().errors == ()
    assert service.poll() is None  # walks the root once; the loop is not followed
    rc, out, _ = run(capsys, 'data', 'check', '--master', str(sedan_master))
    assert rc == 0 and out.endswith('OK (3 configurations, 28 data files)\n')


@pytest.mark.parametrize(('old', 'new', 'key', 'message'), [
    ('sprung_mass: 1550', 'sprung_mass: 1.0e+300', 'sprung_mass',
     '1e+300 is implausible: its size must be from 0.01 to 100000 kg (plausibility bound)'),
    ('sprung_mass: 1550', 'sprung_mass: 0.001', 'sprung_mass',
     '0.001 is implausible: its size must be from 0.01 to 100000 kg (plausibility bound)'),
])
def test_impossible_masses_are_errors(capsys, sample_root, sedan_master, old, new, key,
                                      message):
    mass = sample_root / 'sedan/mass/X.yaml'
    replace_once(mass, old, new)
    check(capsys, sample_root, sedan_master,
          f"sedan/mass/X.yaml: {key}: {message} (line {line_no(mass, '  ' + key)})")


def test_hard_point_ten_metres_away_is_an_error(capsys, sample_root, sedan_master):
    hard = sample_root / 'sedan/front_hardpoints/X.yaml'
    replace_once(hard, '[18.4, 706.0, 181.0]', '[10018.4, 706.0, 181.0]')
    check(capsys, sample_root, sedan_master,
          "sedan/front_hardpoints/X.yaml: points.lca_outer: [10018.4, 706.0, 181.0] is "
          "implausible: every coordinate must be within 8 m of the origin (plausibility bound) "
          f"(line {line_no(hard, '    lca_outer:')})")


def test_unusual_values_are_warnings_and_check_passes(capsys, sample_root, sedan_master):
    align = sample_root / 'sedan/front_alignment/X.yaml'
    text = align.read_text()
    camber = next(line for line in text.splitlines() if line.strip().startswith('camber:'))
    align.write_text(text.replace(camber, '  camber: 12.0'))
    before = tree_snapshot(sample_root)
    rc, out, err = run(capsys, 'data', 'check', '--master', str(sedan_master))
    assert rc == 0
    assert out.endswith('OK (3 configurations, 28 data files)\n')
    assert err == (f"warning: sedan/front_alignment/X.yaml: camber: 0.20944 rad is unusual for "
                   f"a car (usual: -0.174533 to 0.174533) (line {line_no(align, '  camber:')})\n")
    assert tree_snapshot(sample_root) == before


@pytest.mark.parametrize(('option', 'message'), [
    ('--set=front_spring.rate=30 N/0', "--set: front_spring.rate: invalid unit 'N/0'"),
    ('--set=front_spring.rate=1e999 N/mm',
     "--set: front_spring.rate: value must be finite, found '1e999 N/mm'"),
    ('--set=mass.sprung_mass=1e300 kg', "--set: mass.sprung_mass: '1e300 kg' is implausible: "
     "its size must be from 0.01 to 100000 kg (plausibility bound)"),
    ('--set=front_hardpoints.points.lca_outer.x=10 m',
     "--set: front_hardpoints.points.lca_outer.x: '10 m' is implausible: every coordinate must "
     "be within 8 m of the origin (plausibility bound)"),
    ('--param=radius=nan m', "event handling_diagram: radius: value must be finite, found "
     "'nan m'"),
    ('--param=radius=inf m', "event handling_diagram: radius: value must be finite, found "
     "'inf m'"),
    ('--param=radius=1e308 km', "event handling_diagram: radius: value must be finite, found "
     "'1e308 km'"),
    (f'--param=steps={BIG}', f"event handling_diagram: steps: expected a whole number, found "
     f"'{BIG}'"),
])
def test_run_refuses_bad_values_at_the_boundary(capsys, sample_root, sedan_master, tmp_path,
                                                option, message):
    bag = tmp_path / 'bag'
    check(capsys, sample_root, sedan_master, message, 'run', 'handling_diagram', '--master',
          str(sedan_master), option, '--bag', str(bag))
    assert not list(tmp_path.glob('bag*'))


@pytest.mark.parametrize(('value', 'message'), [
    ('abc', "VD_DOMAIN_ID: expected a ROS domain id 0..232, found 'abc'"),
    ('500', "VD_DOMAIN_ID: expected a ROS domain id 0..232, found '500'"),
])
def test_bad_domain_id_is_refused(capsys, monkeypatch, sample_root, sedan_master, tmp_path,
                                  value, message):
    monkeypatch.setenv('VD_DOMAIN_ID', value)
    check(capsys, sample_root, sedan_master, message, 'run', 'handling_diagram', '--master',
          str(sedan_master), '--bag', str(tmp_path / 'bag'), '--distributed')
    assert not list(tmp_path.glob('bag*'))


def test_bag_under_proc_is_refused(capsys, sample_root, sedan_master):
    check(capsys, sample_root, sedan_master,
          '/proc/vd/bag: cannot write the bag: No such file or directory',
          'run', 'handling_diagram', '--master', str(sedan_master), '--bag', '/proc/vd/bag')


def test_tire_coefficients_that_overflow_together_fail_the_check(capsys, sample_root,
                                                                 sedan_master):
    """
    Check that tire coefficients that overflow together fail the check.

    Each value is finite, but exp(PKX3 dfz) overflows over the load range: the check
    builds the tire model a run builds and refuses it the same way.
    """
    tir = sample_root / TIRE
    lines = tir.read_text(encoding='latin-1').splitlines()
    number = next(n for n, t in enumerate(lines) if t.split('=')[0].strip() == 'PKX3')
    lines[number] = 'PKX3 = 2977.0'
    tir.write_text('\n'.join(lines) + '\n', encoding='latin-1')
    check(capsys, sample_root, sedan_master, '\n'.join(
        f'sedan/{axle}_tire/X.yaml -> {TIRE}: the Magic Formula gives a non-finite Fx within '
        '0.1..3 x the nominal load: coefficients out of range' for axle in ('front', 'rear')))


def test_vd_data_check_refuses_two_descriptions_of_one_bar(capsys, sample_root, sedan_master):
    """A 22 mm flexible twin of the 24 mm front bar: both files, keys and values named."""
    flex = sample_root / 'sedan/front_flex/X.yaml'
    replace_once(flex, '  sections:\n',
                 '  sections:\n    bar: {shape: solid_round, diameter: 22}\n')
    replace_once(flex, 'anti_roll_bar: {material: bar_steel,',
                 'anti_roll_bar: {material: bar_steel, section: bar,')
    check(capsys, sample_root, sedan_master,
          "sedan/front_flex/X.yaml: components.anti_roll_bar.section: section 'bar' (diameter "
          '22 mm) contradicts sedan/front_stabilizer/X.yaml bar_radius 12 mm (a solid bar of '
          'diameter 24 mm): one bar, one description; leave the section out (the flexible bar '
          "takes the stabilizer's) or make them agree")


def test_run_in_the_domain_of_a_launch_is_refused(capsys, monkeypatch, sample_root,
                                                  sedan_master, tmp_path):
    """`vd launch` claims its ROS domain: a run sent there gets a message, not rclpy errors."""
    import os

    from vd_events.orchestration.domain import claim_launch_domain

    monkeypatch.setenv('ROS_DOMAIN_ID', '231')
    launched = claim_launch_domain()  # what a running `vd launch` holds
    try:
        monkeypatch.setenv('VD_DOMAIN_ID', '231')
        check(capsys, sample_root, sedan_master,
              'VD_DOMAIN_ID: ROS domain 231 is in use by another vd run or vd launch (pid '
              f'{os.getpid()}); unset VD_DOMAIN_ID or choose another', 'run',
              'handling_diagram', '--master', str(sedan_master), '--bag', str(tmp_path / 'bag'),
              '--distributed')
        assert not list(tmp_path.glob('bag*'))
        check(capsys, sample_root, sedan_master,
              'ROS_DOMAIN_ID: ROS domain 231 is in use by another vd run or vd launch (pid '
              f'{os.getpid()}); set another ROS_DOMAIN_ID for this launch', 'launch',
              '--master', str(sedan_master))
    finally:
        launched.release()


def test_tire_file_whose_units_do_not_match_its_numbers(capsys, sample_root, sedan_master):
    """LENGTH = 'mm' over dimensions written in metres: a 0.3 mm tire, refused at check."""
    import re

    tir = sample_root / 'tires' / 'Sedan_Pac02Tire.tir'
    text = tir.read_text(encoding='latin-1')
    before = text
    text = re.sub(r"LENGTH\s*=\s*'meter'", "LENGTH = 'mm'", text, count=1)
    assert text != before
    tir.write_text(text, encoding='latin-1')
    rc, out, err = run(capsys, 'data', 'check', '--master', str(sedan_master))
    assert (rc, out) == (2, '')
    assert err.splitlines()[0].endswith(
        "UNLOADED_RADIUS: line 23: key 'UNLOADED_RADIUS' in block [DIMENSION] must lie within "
        '0.1..2 m for a road tire, here 0.000344 m (are the [UNITS] right, e.g. LENGTH?), '
        'found 0.344')


def test_coincident_hard_points_fail_the_check(capsys, sample_root, sedan_master):
    """Two pivots of the lower arm on one point: the K&C model the run builds refuses it."""
    hard = sample_root / 'sedan/front_hardpoints/X.yaml'
    replace_once(hard, 'lca_rear:       [-260.0, 187.0, 218.0]',
                 'lca_rear:       [260.0, 200.0, 199.0]')
    before = tree_snapshot(sample_root)
    rc, out, err = run(capsys, 'data', 'check', '--master', str(sedan_master))
    assert (rc, out) == (2, '')
    assert err.splitlines()[0] == (
        "configuration 'baseline', axle 'front', flexible: component 'subframe': hard points "
        "'lca_front.left' and 'lca_rear.left' coincide (a member needs length)")
    assert tree_snapshot(sample_root) == before
