# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""Loading one data file: validation with exact messages, sample files, properties."""
from __future__ import annotations

import math
from pathlib import Path
import textwrap
from typing import Any

from numpy.testing import assert_allclose
import pytest
import yaml

from vd_data_server import schema
from vd_data_server.datafile import load_group_file
from vd_data_server.errors import DataError, DataErrors
from vd_data_server.model import GroupData
from vd_data_server.units import SI_UNITS
from vdtest import tree_snapshot

SAMPLE = Path(__file__).resolve().parents[2] / 'src' / 'vd_data_server' / 'data'
SAMPLE_FILES = sorted(p for v in ('sedan', 'hmmwv') for p in (SAMPLE / v).glob('*/*.yaml'))
RTOL = 1e-12

SPRING = """\
    kind: spring
    units: {length: mm, force: N}
    data:
      rate: 30.0
      preload: 4600
    """
MACPHERSON = """\
    kind: hardpoints
    units: {length: mm}
    data:
      template: macpherson
      points:
        lca_front:    [260.0, 200.0, 199.0]
        lca_rear:     [-260.0, 187.0, 218.0]
        lca_outer:    [18.4, 620.6, 181.0]
        tierod_inner: [-260.0, 200.0, 296.0]
        tierod_outer: [-197.4, 575.0, 339.0]
        strut_top:    [-75.0, 465.0, 934.0]
        strut_lower:  [-34.0, 533.3, 603.5]
        wheel_centre: [0.0, 780.0, 329.0]
    """


def shown(group: str) -> str:
    return f'sedan/{group}/X.yaml'


def write(tmp_path: Path, text: str) -> Path:
    path = tmp_path / 'X.yaml'
    path.write_text(textwrap.dedent(text), encoding='utf-8')
    return path


def load(tmp_path: Path, group: str, text: str) -> GroupData:
    return load_group_file(write(tmp_path, text), display=shown(group), group=group, variant='X')


def refused(tmp_path: Path, group: str, text: str) -> list[str]:
    """Return the error lines of a bad file; loading writes nothing."""
    path = write(tmp_path, text)
    before = tree_snapshot(tmp_path)
    with pytest.raises(DataError) as info:
        load_group_file(path, display=shown(group), group=group, variant='X')
    assert tree_snapshot(tmp_path) == before
    return str(info.value).splitlines()


def edit(text: str, old: str, new: str) -> str:
    text = textwrap.dedent(text)
    assert text.count(old) == 1, old
    return text.replace(old, new)


# --- the file as a whole --------------------------------------------------------------------

def test_malformed_yaml_names_line_and_column(tmp_path: Path) -> None:
    lines = refused(tmp_path, 'front_spring', edit(SPRING, 'rate: 30.0', 'rate: [30.0'))
    assert lines == ["sedan/front_spring/X.yaml: malformed YAML: expected ',' or ']', but got "
                     "':' (line 5, column 10)"]  # the ':' of 'preload:'


def test_duplicate_key_is_refused(tmp_path: Path) -> None:
    text = edit(SPRING, 'preload: 4600', 'rate: 31\n  preload: 4600')
    lines = refused(tmp_path, 'front_spring', text)
    assert lines == ["sedan/front_spring/X.yaml: malformed YAML: duplicate key 'rate' "
                     "(line 5, column 3)"]


def test_python_tags_are_not_executed(tmp_path: Path) -> None:
    marker = tmp_path / 'pwned'
    text = edit(SPRING, 'rate: 30.0', f"rate: !!python/object/apply:os.system ['touch {marker}']")
    lines = refused(tmp_path, 'front_spring', text)
    assert lines == ["sedan/front_spring/X.yaml: malformed YAML: could not determine a "
                     "constructor for the tag 'tag:yaml.org,2002:python/object/apply:os.system' "
                     "(line 4, column 9)"]
    assert not marker.exists()


def test_a_file_that_is_not_a_mapping_is_refused(tmp_path: Path) -> None:
    assert refused(tmp_path, 'front_spring', '- rate\n- 30\n') == [
        "sedan/front_spring/X.yaml: expected a mapping with 'kind', 'units' and 'data'"]


def test_unknown_top_level_key_names_key_and_line(tmp_path: Path) -> None:
    lines = refused(tmp_path, 'front_spring', edit(SPRING, 'units:', 'colour: red\nunits:'))
    assert lines == ['sedan/front_spring/X.yaml: colour: unknown key (expected one of: kind, '
                     'description, source, units, mirror, data) (line 2)']


def test_unknown_key_inside_data_names_key_and_line(tmp_path: Path) -> None:
    text = edit(SPRING, '  preload: 4600', '  preload: 4600\n  stiff: 3')
    lines = refused(tmp_path, 'front_spring', text)
    assert lines == ['sedan/front_spring/X.yaml: stiff: unknown key (expected one of: rate, '
                     'curve, free_length, preload) (line 6)']


def test_unknown_nested_key_names_the_full_key_path(tmp_path: Path) -> None:
    lines = refused(tmp_path, 'front_bushings', """\
        kind: bushings
        units: {}
        data:
          connections:
            lca_front:
              stiffness: {x: 8e6, y: 8e6, z: 1.5e6, rx: 200, ry: 200, rz: 30, rw: 1}
        """)
    assert lines == ['sedan/front_bushings/X.yaml: connections.lca_front.stiffness.rw: unknown '
                     'key (expected one of: x, y, z, rx, ry, rz) (line 6)']


def test_missing_kind_is_refused(tmp_path: Path) -> None:
    lines = refused(tmp_path, 'front_spring', edit(SPRING, 'kind: spring\n', ''))
    assert lines == ["sedan/front_spring/X.yaml: kind: missing required key (expected 'spring')"]


def test_missing_data_is_refused(tmp_path: Path) -> None:
    lines = refused(tmp_path, 'front_spring', 'kind: spring\nunits: {length: mm}\n')
    assert lines == ['sedan/front_spring/X.yaml: data: missing required key']


def test_data_must_be_a_mapping(tmp_path: Path) -> None:
    lines = refused(tmp_path, 'front_spring', 'kind: spring\ndata: 30\n')
    assert lines == ['sedan/front_spring/X.yaml: data: expected a mapping, found int 30 (line 2)']


def test_missing_required_key_is_refused(tmp_path: Path) -> None:
    lines = refused(tmp_path, 'front_alignment', """\
        kind: alignment
        units: {angle: deg}
        data:
          camber: -0.5
        """)
    assert lines == ['sedan/front_alignment/X.yaml: toe: missing required key (line 3)']


def test_wrong_kind_for_the_group_is_refused(tmp_path: Path) -> None:
    lines = refused(tmp_path, 'front_damper', SPRING)
    assert lines == ["sedan/front_damper/X.yaml: kind: file is of kind 'spring' but group "
                     "'front_damper' needs kind 'damper' (line 1)"]


def test_mirror_on_a_file_other_than_hardpoints_is_refused(tmp_path: Path) -> None:
    lines = refused(tmp_path, 'front_spring', edit(SPRING, 'units:', 'mirror: true\nunits:'))
    assert lines == ["sedan/front_spring/X.yaml: mirror: only hardpoints files may set 'mirror' "
                     "(line 2)"]


def test_mirror_must_be_true_or_false(tmp_path: Path) -> None:
    text = edit(MACPHERSON, 'units:', 'mirror: yes please\nunits:')
    lines = refused(tmp_path, 'front_hardpoints', text)
    assert lines == ["sedan/front_hardpoints/X.yaml: mirror: expected true or false, found "
                     "'yes please' (line 2)"]


# --- non-physical values ---------------------------------------------------------------------

def test_negative_mass_is_refused(tmp_path: Path) -> None:
    lines = refused(tmp_path, 'mass', """\
        kind: mass
        units: {length: mm, mass: kg}
        data:
          sprung_mass: -1550
          sprung_cog: [-1250, 0, 550]
          sprung_inertia: {ixx: 540, iyy: 2400, izz: 2600}
          unsprung_mass_front: 45
          unsprung_mass_rear: 40
        """)
    assert lines == ['sedan/mass/X.yaml: sprung_mass: must be positive, found -1550 (line 4)']


def test_negative_stiffness_message(tmp_path: Path) -> None:
    lines = refused(tmp_path, 'front_spring', edit(SPRING, 'rate: 30.0', 'rate: -30.0'))
    assert lines == ['sedan/front_spring/X.yaml: rate: must be positive, found -30.0 (line 4)']


def test_zero_stiffness_message(tmp_path: Path) -> None:
    lines = refused(tmp_path, 'front_spring', edit(SPRING, 'rate: 30.0', 'rate: 0'))
    assert lines == ['sedan/front_spring/X.yaml: rate: must be positive, found 0 (line 4)']


def test_nan_is_refused(tmp_path: Path) -> None:
    lines = refused(tmp_path, 'front_spring', edit(SPRING, 'rate: 30.0', 'rate: .nan'))
    assert lines == ['sedan/front_spring/X.yaml: rate: value must be finite, found nan (line 4)']


def test_negative_clearance_is_refused(tmp_path: Path) -> None:
    lines = refused(tmp_path, 'front_bump_stop', """\
        kind: bump_stop
        units: {length: mm, force: N}
        data:
          clearance: -5
          curve: {x: [0, 5, 10], y: [0, 150, 450]}
        """)
    assert lines == ['sedan/front_bump_stop/X.yaml: clearance: must be >= 0 m, found -5 (line 4)']


def stop(curve: str) -> str:
    return f"""\
        kind: bump_stop
        units: {{length: mm, force: N}}
        data:
          clearance: 60
          curve: {curve}
        """


def test_non_monotonic_force_curve_is_refused(tmp_path: Path) -> None:
    lines = refused(tmp_path, 'front_bump_stop', stop('{x: [0, 5, 10], y: [0, 450, 150]}'))
    assert lines == ['sedan/front_bump_stop/X.yaml: curve: curve y must not decrease '
                     '(non-monotonic force curve) (line 5)']


def test_curve_x_must_increase_strictly(tmp_path: Path) -> None:
    lines = refused(tmp_path, 'front_bump_stop', stop('{x: [0, 5, 5], y: [0, 150, 450]}'))
    assert lines == ['sedan/front_bump_stop/X.yaml: curve: curve x must be strictly increasing '
                     '(line 5)']


def test_curve_lengths_must_agree(tmp_path: Path) -> None:
    lines = refused(tmp_path, 'front_bump_stop', stop('{x: [0, 5, 10], y: [0, 150]}'))
    assert lines == ['sedan/front_bump_stop/X.yaml: curve: curve x has 3 values but y has 2 '
                     '(line 5)']


def test_nan_in_a_curve_is_refused(tmp_path: Path) -> None:
    lines = refused(tmp_path, 'front_bump_stop', stop('{x: [0, 5, 10], y: [0, .nan, 450]}'))
    assert lines == ['sedan/front_bump_stop/X.yaml: curve: curve y values must be finite (no NaN) '
                     '(line 5)']


def test_stop_curve_must_start_at_zero_compression_or_later(tmp_path: Path) -> None:
    lines = refused(tmp_path, 'front_bump_stop', stop('{x: [-5, 0, 5], y: [0, 150, 450]}'))
    assert lines == ['sedan/front_bump_stop/X.yaml: curve: curve x must start at >= 0 (line 5)']


def test_damper_curve_may_decrease_nowhere_but_may_be_negative(tmp_path: Path) -> None:
    damper = load(tmp_path, 'front_damper', """\
        kind: damper
        data:
          curve: {x: [-1.0, 0.0, 1.0], y: [-3600, 0, 1800]}
        """)
    assert damper.curve('curve') == ((-1.0, 0.0, 1.0), (-3600.0, 0.0, 1800.0))
    assert damper.scalar('scale') == 1.0  # the schema default


# --- exactly one of ---------------------------------------------------------------------------

def test_rate_and_curve_together_are_refused(tmp_path: Path) -> None:
    text = edit(SPRING, '  preload: 4600', '  preload: 4600\n  curve: {x: [0, 10], y: [0, 300]}')
    lines = refused(tmp_path, 'front_spring', text)
    assert lines == ['sedan/front_spring/X.yaml: data: give exactly one of: rate, curve '
                     '(found rate, curve) (line 3)']


def test_neither_free_length_nor_preload_is_refused(tmp_path: Path) -> None:
    lines = refused(tmp_path, 'front_spring', edit(SPRING, '  preload: 4600\n', ''))
    assert lines == ['sedan/front_spring/X.yaml: data: give exactly one of: free_length, preload '
                     '(found none) (line 3)']


def test_stabilizer_needs_a_stiffness_or_a_bar(tmp_path: Path) -> None:
    lines = refused(tmp_path, 'front_stabilizer', """\
        kind: stabilizer
        units: {length: mm}
        data:
          torsion_length: 800
        """)
    assert lines == ['sedan/front_stabilizer/X.yaml: data: give exactly one of: '
                     'torsional_stiffness, bar_radius (found none) (line 3)']


# --- hard points ------------------------------------------------------------------------------

def test_hard_points_missing_for_the_template_are_named(tmp_path: Path) -> None:
    text = edit(MACPHERSON, '    strut_top:    [-75.0, 465.0, 934.0]\n', '')
    text = text.replace('    wheel_centre: [0.0, 780.0, 329.0]\n', '')
    lines = refused(tmp_path, 'front_hardpoints', text)
    assert lines == [
        "sedan/front_hardpoints/X.yaml: points.strut_top: missing hard point required by "
        "template 'macpherson' (line 5)",
        "sedan/front_hardpoints/X.yaml: points.wheel_centre: missing hard point required by "
        "template 'macpherson' (line 5)",
    ]


def test_unknown_hard_point_name_is_refused(tmp_path: Path) -> None:
    text = edit(MACPHERSON, '    wheel_centre:',
                '    wheel_center: [0.0, 780.0, 329.0]\n    wheel_centre:')
    lines = refused(tmp_path, 'front_hardpoints', text)
    allowed = sorted({*schema.TEMPLATE_POINTS['macpherson'], *schema.OPTIONAL_POINTS})
    assert lines == [f"sedan/front_hardpoints/X.yaml: points.wheel_center: unknown hard point for "
                     f"template 'macpherson' (expected: {', '.join(allowed)}) (line 13)"]


def test_optional_anti_roll_bar_points_are_accepted(tmp_path: Path) -> None:
    text = edit(MACPHERSON, '    wheel_centre:',
                '    arb_pivot: [190.0, 230.0, 355.0]\n    wheel_centre:')
    points = load(tmp_path, 'front_hardpoints', text)
    assert_allclose(points.point('points.arb_pivot'), (0.190, 0.230, 0.355), rtol=RTOL)


def test_unknown_template_is_refused(tmp_path: Path) -> None:
    text = edit(MACPHERSON, 'template: macpherson', 'template: swing_axle')
    lines = refused(tmp_path, 'front_hardpoints', text)
    assert lines == ["sedan/front_hardpoints/X.yaml: template: 'swing_axle' is not one of: "
                     "macpherson, double_wishbone, multilink (line 4)"]


@pytest.mark.parametrize(('point', 'shown_as'), [
    ('[18.4, 620.6]', '[18.4, 620.6]'),
    ('[18.4, 620.6, 181.0, 1.0]', '[18.4, 620.6, 181.0, 1.0]'),
    ('[18.4, 620.6, high]', "[18.4, 620.6, 'high']"),
    ('18.4', '18.4'),
])
def test_a_point_must_be_three_numbers(tmp_path: Path, point: str, shown_as: str) -> None:
    text = edit(MACPHERSON, '[18.4, 620.6, 181.0]', point)
    lines = refused(tmp_path, 'front_hardpoints', text)
    assert lines == [f'sedan/front_hardpoints/X.yaml: points.lca_outer: expected [x, y, z] '
                     f'numbers, found {shown_as} (line 8)']


def test_points_are_converted_to_metres(tmp_path: Path) -> None:
    points = load(tmp_path, 'front_hardpoints', MACPHERSON)
    assert_allclose(points.point('points.lca_outer'), (0.0184, 0.6206, 0.181), rtol=RTOL)
    assert points.values['points.lca_outer'].display_unit == 'mm'


def test_bushing_axis_is_normalised(tmp_path: Path) -> None:
    bushings = load(tmp_path, 'front_bushings', """\
        kind: bushings
        units: {}
        data:
          connections:
            lca_front:
              stiffness: {x: 8e6, y: 8e6, z: 1.5e6, rx: 200, ry: 200, rz: 30}
              axis: [3, 0, 4]
        """)
    assert_allclose(bushings.values['connections.lca_front.axis'].si, (0.6, 0.0, 0.8), rtol=RTOL)


def test_several_errors_in_one_file_are_all_reported(tmp_path: Path) -> None:
    path = write(tmp_path, """\
        kind: mass
        units: {length: mm, mass: kg}
        data:
          sprung_mass: -1550
          sprung_cog: [-1250, 0]
          sprung_inertia: {ixx: 540, iyy: 2400}
          unsprung_mass_front: .nan
          unsprung_mass_rear: 40
          wheels: 4
        """)
    before = tree_snapshot(tmp_path)
    with pytest.raises(DataErrors) as info:
        load_group_file(path, display='sedan/mass/X.yaml', group='mass', variant='X')
    assert tree_snapshot(tmp_path) == before
    assert sorted(str(e) for e in info.value.errors) == sorted([
        'sedan/mass/X.yaml: wheels: unknown key (expected one of: sprung_mass, sprung_cog, '
        'sprung_inertia, unsprung_mass_front, unsprung_mass_rear) (line 9)',
        'sedan/mass/X.yaml: sprung_mass: must be positive, found -1550 (line 4)',
        'sedan/mass/X.yaml: sprung_cog: expected [x, y, z] numbers, found [-1250, 0] (line 5)',
        'sedan/mass/X.yaml: sprung_inertia.izz: missing required key (line 6)',
        'sedan/mass/X.yaml: unsprung_mass_front: value must be finite, found nan (line 7)',
    ])
    assert str(info.value) == '\n'.join(str(e) for e in info.value.errors)


def test_values_name_their_file_and_variant(tmp_path: Path) -> None:
    spring = load(tmp_path, 'front_spring', SPRING)
    assert {v.source for v in spring.values.values()} == {'sedan/front_spring/X.yaml (variant X)'}


# --- the bundled sample data and its conventions ---------------------------------------------

@pytest.mark.parametrize('path', SAMPLE_FILES, ids=lambda p: str(p.relative_to(SAMPLE)))
def test_every_bundled_data_file_is_valid(path: Path) -> None:
    group = path.parent.name
    data = load_group_file(path, display=str(path.relative_to(SAMPLE)), group=group,
                           variant=path.stem)
    assert data.kind == schema.group_kind(group)
    assert data.values


@pytest.mark.parametrize('path', [p for p in SAMPLE_FILES if p.parent.name.endswith('hardpoints')],
                         ids=lambda p: str(p.relative_to(SAMPLE)))
def test_bundled_hard_points_are_given_for_the_left_side(path: Path) -> None:
    # y points left (ISO 8855 / REP 103); the right side is the mirror image y -> -y
    data = load_group_file(path, display=path.name, group=path.parent.name, variant=path.stem)
    assert all(v.si[1] > 0.0 for k, v in data.values.items() if k.startswith('points.'))


@pytest.mark.parametrize('vehicle', ['sedan', 'hmmwv'])
def test_bundled_geometry_agrees_with_the_mirrored_hard_points(vehicle: str) -> None:
    def group(name: str) -> GroupData:
        path = SAMPLE / vehicle / name / 'X.yaml'
        return load_group_file(path, display=name, group=name, variant='X')

    front = group('front_hardpoints').point('points.wheel_centre')
    rear = group('rear_hardpoints').point('points.wheel_centre')
    geometry = group('geometry')
    # origin under the front axle centre: front wheel centre at x = 0, y = track / 2
    assert front[0] == 0.0
    assert_allclose(2 * front[1], geometry.scalar('track_front'), rtol=RTOL)
    assert_allclose(2 * rear[1], geometry.scalar('track_rear'), rtol=RTOL)
    assert_allclose(front[0] - rear[0], geometry.scalar('wheelbase'), rtol=RTOL)


@pytest.mark.parametrize('vehicle', ['sedan', 'hmmwv'])
def test_bundled_inertias_are_those_of_a_car(vehicle: str) -> None:
    # radii of gyration of a car body lie between 0.5 m and the wheelbase; an inertia read
    # in the wrong unit (kg*mm^2 for kg*m^2) is a thousand times outside
    def group(name: str) -> GroupData:
        path = SAMPLE / vehicle / name / 'X.yaml'
        return load_group_file(path, display=name, group=name, variant='X')

    mass, wheelbase = group('mass'), group('geometry').scalar('wheelbase')
    for axis in ('ixx', 'iyy', 'izz'):
        radius = math.sqrt(mass.scalar(f'sprung_inertia.{axis}') / mass.scalar('sprung_mass'))
        assert 0.5 < radius < wheelbase, (axis, radius)


def _as_si_file(data: GroupData) -> dict[str, Any]:
    """Return the values of ``data`` written back as a data file in SI units."""
    tree: dict[str, Any] = {}
    for key, value in data.values.items():
        *parents, leaf = key.split('.')
        node = tree
        for part in parents:
            node = node.setdefault(part, {})
        if value.type == 'curve':
            xs, ys = value.table()
            node[leaf] = {'x': list(xs), 'y': list(ys)}
        elif value.type in ('point', 'vector'):
            node[leaf] = list(value.triple())
        else:
            node[leaf] = value.si
    units = {q: u for q, u in SI_UNITS.items() if u}
    return {'kind': data.kind, 'units': units, 'data': tree}


@pytest.mark.parametrize('path', SAMPLE_FILES, ids=lambda p: str(p.relative_to(SAMPLE)))
def test_si_values_written_back_read_the_same(tmp_path: Path, path: Path) -> None:
    group = path.parent.name
    first = load_group_file(path, display='first', group=group, variant='X')
    copy = tmp_path / 'copy.yaml'
    copy.write_text(yaml.safe_dump(_as_si_file(first)), encoding='utf-8')
    second = load_group_file(copy, display='second', group=group, variant='X')
    assert second.values.keys() == first.values.keys()
    for key, value in first.values.items():
        again = second.values[key]
        assert (again.type, again.unit, again.x_unit) == (value.type, value.unit, value.x_unit)
        if value.type == 'text':
            assert again.si == value.si
        else:
            assert_allclose(_flat(again.si), _flat(value.si), rtol=RTOL, atol=0.0, err_msg=key)


def _flat(si: Any) -> list[float]:
    if isinstance(si, tuple):
        return [c for part in si for c in _flat(part)]
    assert isinstance(si, float) and math.isfinite(si)
    return [si]


# --- flex files -------------------------------------------------------------------------------

def _flex_refused(sample_root, old, new):
    from vd_data_server.study import load_study
    from vdtest import replace_once, tree_snapshot

    path = sample_root / 'sedan' / 'front_flex' / 'X.yaml'
    replace_once(path, old, new)
    before = tree_snapshot(sample_root)
    with pytest.raises(DataError) as info:
        load_study(sample_root / 'studies' / 'sedan.yaml')
    assert tree_snapshot(sample_root) == before
    return str(info.value).splitlines()


def test_flex_section_with_zero_size_is_refused(sample_root):
    from vdtest import line_no

    lines = _flex_refused(sample_root, 'tie_rod: {shape: solid_round, diameter: 16}',
                          'tie_rod: {shape: solid_round, diameter: 0}')
    line = line_no(sample_root / 'sedan' / 'front_flex' / 'X.yaml', '    tie_rod:')
    assert lines == ['sedan/front_flex/X.yaml: sections.tie_rod.diameter: must be positive, '
                     f'found 0 (line {line})']


def test_flex_section_needs_its_shape_dimensions(sample_root):
    lines = _flex_refused(sample_root, 'strut_tube: {shape: tube, outer_diameter: 50, wall: 3}',
                          'strut_tube: {shape: tube, outer_diameter: 50, diameter: 3}')
    assert lines == ["sedan/front_flex/X.yaml: sections.strut_tube.wall: required by shape 'tube'",
                     "sedan/front_flex/X.yaml: sections.strut_tube.diameter: not a dimension of "
                     "shape 'tube' (expected: outer_diameter, wall)"]


def test_flex_component_must_name_a_known_section(sample_root):
    lines = _flex_refused(sample_root, 'section: tie_rod,', 'section: tie_bar,')
    assert lines == ["sedan/front_flex/X.yaml: components.tierod.section: 'tie_bar' is not in "
                     'sections (known: knuckle, pressed_arm, strut_tube, subframe_box, '
                     'tie_rod)']


def test_flex_component_must_exist_in_the_template(sample_root):
    lines = _flex_refused(sample_root, '    tierod: {', '    crossmember: {')
    assert lines == ["sedan/front_flex/X.yaml: components.crossmember: template 'macpherson' has "
                     "no component 'crossmember' (components: upright, lca, strut, tierod, "
                     "anti_roll_bar, subframe)"]


def test_flexible_subframe_needs_its_mounts(sample_root):
    from vdtest import replace_once

    replace_once(sample_root / 'sedan' / 'front_hardpoints' / 'X.yaml',
                 '    subframe_rear:  [-420.0, 320.0, 250.0]\n', '')
    lines = _flex_refused(sample_root, 'section: subframe_box, elements_per_member: 2',
                          'section: subframe_box, elements_per_member: 3')
    assert lines == ['sedan/front_flex/X.yaml: components.subframe: a flexible subframe needs '
                     'its body mounts: hard point(s) subframe_rear missing in '
                     'sedan/front_hardpoints/X.yaml']
