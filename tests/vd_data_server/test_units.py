# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Units at the file boundary: every value read from a data file ends up in SI.

Expected numbers come from the unit definitions (1 mm = 1e-3 m, 1 deg = pi/180 rad,
1 revolution = 2 pi rad), never from the code under test.
"""
from __future__ import annotations

import math
from pathlib import Path
import textwrap

from numpy.testing import assert_allclose
import pytest

from vd_data_server.datafile import load_group_file
from vd_data_server.errors import DataError
from vd_data_server.model import GroupData
from vdtest import tree_snapshot

RTOL = 1e-12
SHOWN = 'sedan/front_spring/X.yaml'  # the path a user sees in messages


def load(tmp_path: Path, group: str, text: str) -> GroupData:
    path = tmp_path / 'X.yaml'
    path.write_text(textwrap.dedent(text), encoding='utf-8')
    return load_group_file(path, display=SHOWN, group=group, variant='X')


def refused(tmp_path: Path, group: str, text: str) -> str:
    """Return the error message of a bad file; the loader must not write anything."""
    path = tmp_path / 'X.yaml'
    path.write_text(textwrap.dedent(text), encoding='utf-8')
    before = tree_snapshot(tmp_path)
    with pytest.raises(DataError) as info:
        load_group_file(path, display=SHOWN, group=group, variant='X')
    assert tree_snapshot(tmp_path) == before
    return str(info.value)


def test_length_in_mm_is_converted_to_metres(tmp_path: Path) -> None:
    spring = load(tmp_path, 'front_spring', """\
        kind: spring
        units: {length: mm, force: N}
        data: {rate: 30, free_length: 306}
        """)
    assert_allclose(spring.scalar('free_length'), 0.306, rtol=RTOL)
    assert spring.values['free_length'].unit == 'm'


def test_stiffness_unit_follows_from_length_and_force(tmp_path: Path) -> None:
    spring = load(tmp_path, 'front_spring', """\
        kind: spring
        units: {length: mm, force: N}
        data: {rate: 36.9, free_length: 306}
        """)
    assert_allclose(spring.scalar('rate'), 36.9e3, rtol=RTOL)  # N/mm -> N/m
    assert spring.values['rate'].unit == 'N/m'


def test_stiffness_follows_from_a_kilonewton_force_unit(tmp_path: Path) -> None:
    spring = load(tmp_path, 'front_spring', """\
        kind: spring
        units: {length: mm, force: kN}
        data: {rate: 0.0369, free_length: 306}
        """)
    assert_allclose(spring.scalar('rate'), 36.9e3, rtol=RTOL)


def test_a_units_block_may_name_a_derived_unit_itself(tmp_path: Path) -> None:
    spring = load(tmp_path, 'front_spring', """\
        kind: spring
        units: {length: mm, force: N, stiffness: N/m}
        data: {rate: 36900, free_length: 306}
        """)
    assert_allclose(spring.scalar('rate'), 36.9e3, rtol=RTOL)
    assert_allclose(spring.scalar('free_length'), 0.306, rtol=RTOL)


def test_angle_in_degrees_is_converted_to_radians(tmp_path: Path) -> None:
    alignment = load(tmp_path, 'front_alignment', """\
        kind: alignment
        units: {angle: deg}
        data: {camber: -0.5, toe: 0.05}
        """)
    assert_allclose(alignment.scalar('camber'), -0.5 * math.pi / 180, rtol=RTOL)
    assert_allclose(alignment.scalar('toe'), 0.05 * math.pi / 180, rtol=RTOL)


def test_torsional_stiffness_follows_from_force_length_and_angle(tmp_path: Path) -> None:
    targets = load(tmp_path, 'targets', """\
        kind: targets
        units: {length: mm, force: N, angle: deg}
        data:
          roll_stiffness_front: 900000
          roll_stiffness_rear: 550000
          roll_centre_height_front: 60
          roll_centre_height_rear: 110
        """)
    # 900000 N*mm/deg = 900 N*m per (pi/180) rad
    assert_allclose(targets.scalar('roll_stiffness_front'), 900.0 * 180 / math.pi, rtol=RTOL)


def test_damping_follows_from_force_time_and_length(tmp_path: Path) -> None:
    bushings = load(tmp_path, 'front_bushings', """\
        kind: bushings
        units: {length: mm, force: N, angle: deg, time: s}
        data:
          connections:
            lca_front:
              stiffness: {x: 8000, y: 8000, z: 1500, rx: 4000, ry: 4000, rz: 500}
              damping: {x: 2.0}
        """)
    assert_allclose(bushings.scalar('connections.lca_front.damping.x'), 2.0e3, rtol=RTOL)
    # damping not given defaults to zero
    assert bushings.scalar('connections.lca_front.damping.rz') == 0.0


def test_inertia_follows_from_mass_and_length(tmp_path: Path) -> None:
    mass = load(tmp_path, 'mass', """\
        kind: mass
        units: {length: m, mass: kg}
        data:
          sprung_mass: 1550
          sprung_cog: [-1.25, 0, 0.55]
          sprung_inertia: {ixx: 540, iyy: 2400, izz: 2600}
          unsprung_mass_front: 45
          unsprung_mass_rear: 40
        """)
    assert_allclose(mass.scalar('sprung_inertia.izz'), 2600.0, rtol=RTOL)
    assert mass.values['sprung_inertia.izz'].unit == 'kg*m^2'


def test_rack_ratio_in_mm_per_revolution(tmp_path: Path) -> None:
    steering = load(tmp_path, 'steering', """\
        kind: steering
        units: {length: mm}
        data:
          rack_ratio: 50 mm/revolution
          rack_travel_limit: 76
        """)
    assert_allclose(steering.scalar('rack_ratio'), 0.050 / (2 * math.pi), rtol=RTOL)
    assert steering.values['rack_ratio'].unit == 'm/rad'


def test_pressure_in_newton_per_square_millimetre(tmp_path: Path) -> None:
    bar = load(tmp_path, 'front_stabilizer', """\
        kind: stabilizer
        units: {length: mm, force: N}
        data:
          bar_radius: 12.0
          torsion_length: 800
          shear_modulus: 79300 N/mm^2
        """)
    assert_allclose(bar.scalar('shear_modulus'), 79300 * 1e6, rtol=RTOL)  # 1 N/mm^2 = 1 MPa


def test_inline_unit_wins_over_the_units_block(tmp_path: Path) -> None:
    spring = load(tmp_path, 'front_spring', """\
        kind: spring
        units: {length: m, force: N}
        data: {rate: 36.9 N/mm, free_length: 0.306}
        """)
    assert_allclose(spring.scalar('rate'), 36.9e3, rtol=RTOL)


def test_percent_is_a_dimensionless_unit(tmp_path: Path) -> None:
    damper = load(tmp_path, 'front_damper', """\
        kind: damper
        data:
          curve: {x: [-1, 0, 1], y: [-2000, 0, 1000]}
          scale: 120 %
        """)
    assert_allclose(damper.scalar('scale'), 1.2, rtol=RTOL)


def test_curve_may_give_its_own_axis_units(tmp_path: Path) -> None:
    damper = load(tmp_path, 'front_damper', """\
        kind: damper
        units: {length: m, force: N}
        data:
          curve: {x: [-1000, 0, 1000], y: [-2, 0, 1], x_unit: mm/s, y_unit: kN}
        """)
    xs, ys = damper.curve('curve')
    assert_allclose(xs, [-1.0, 0.0, 1.0], rtol=RTOL)
    assert_allclose(ys, [-2000.0, 0.0, 1000.0], rtol=RTOL)


def test_yaml_1_1_exponent_without_sign_is_read_as_a_number(tmp_path: Path) -> None:
    # YAML 1.1 (PyYAML) reads 7.0e7 as the string '7.0e7'; it is a number to us.
    bushings = load(tmp_path, 'front_bushings', """\
        kind: bushings
        units: {length: m, force: N, angle: rad}
        data:
          connections:
            uca_front:
              stiffness: {x: 7.0e7, y: 7.0e7, z: 7.0e7, rx: 1.0e5, ry: 1.0e5, rz: 1.0e5}
        """)
    assert_allclose(bushings.scalar('connections.uca_front.stiffness.x'), 7.0e7, rtol=RTOL)
    assert_allclose(bushings.scalar('connections.uca_front.stiffness.rx'), 1.0e5, rtol=RTOL)


def test_an_empty_units_block_means_si(tmp_path: Path) -> None:
    spring = load(tmp_path, 'front_spring', """\
        kind: spring
        units: {}
        data: {rate: 36900, free_length: 0.306}
        """)
    assert_allclose(spring.scalar('rate'), 36900.0, rtol=RTOL)
    assert_allclose(spring.scalar('free_length'), 0.306, rtol=RTOL)


def test_without_a_units_block_values_carry_their_units(tmp_path: Path) -> None:
    spring = load(tmp_path, 'front_spring', """\
        kind: spring
        data: {rate: 36.9 N/mm, free_length: 306 mm}
        """)
    assert_allclose(spring.scalar('rate'), 36900.0, rtol=RTOL)
    assert_allclose(spring.scalar('free_length'), 0.306, rtol=RTOL)


def test_unknown_unit_name_in_the_units_block_is_refused(tmp_path: Path) -> None:
    message = refused(tmp_path, 'front_spring', """\
        kind: spring
        units: {length: furlongz, force: N}
        data: {rate: 30, free_length: 306}
        """)
    assert message == f"{SHOWN}: units.length: unknown unit 'furlongz'"


def test_unit_of_the_wrong_dimension_in_the_units_block_is_refused(tmp_path: Path) -> None:
    message = refused(tmp_path, 'front_spring', """\
        kind: spring
        units: {length: kg, force: N}
        data: {rate: 30, free_length: 306}
        """)
    assert message == f"{SHOWN}: units.length: unit 'kg' is not a length unit (expected e.g. 'm')"


def test_a_ratio_is_not_an_angle_unit(tmp_path: Path) -> None:
    # pint counts angles as dimensionless; '%' must still not pass for an angle
    message = refused(tmp_path, 'front_alignment', """\
        kind: alignment
        units: {angle: percent}
        data: {camber: -0.5, toe: 0.05}
        """)
    assert message == (f"{SHOWN}: units.angle: unit 'percent' is not an angle unit "
                       "(expected e.g. 'rad')")


def test_an_angle_is_not_a_dimensionless_unit(tmp_path: Path) -> None:
    message = refused(tmp_path, 'front_damper', """\
        kind: damper
        data:
          curve: {x: [-1, 0, 1], y: [-2000, 0, 1000]}
          scale: 120 deg
        """)
    assert message == (f"{SHOWN}: scale: unit 'deg' is not a dimensionless unit "
                       "(expected e.g. '-') (line 4)")


def test_unknown_quantity_in_the_units_block_is_refused(tmp_path: Path) -> None:
    message = refused(tmp_path, 'front_spring', """\
        kind: spring
        units: {lenght: mm, force: N}
        data: {rate: 30, free_length: 306}
        """)
    assert message.startswith(f"{SHOWN}: units.lenght: unknown quantity 'lenght' (known: ")
    assert 'length' in message.split('(known: ', 1)[1]


def test_units_block_must_be_a_mapping(tmp_path: Path) -> None:
    message = refused(tmp_path, 'front_spring', """\
        kind: spring
        units: mm
        data: {rate: 30, free_length: 306}
        """)
    assert message == f'{SHOWN}: units: expected a mapping of quantity: unit'


def test_unit_in_the_units_block_must_be_text(tmp_path: Path) -> None:
    message = refused(tmp_path, 'front_spring', """\
        kind: spring
        units: {length: 5}
        data: {rate: 30, free_length: 306}
        """)
    assert message == f'{SHOWN}: units.length: unit must be a string, found 5'


def test_inline_unit_of_the_wrong_dimension_is_refused(tmp_path: Path) -> None:
    message = refused(tmp_path, 'front_spring', """\
        kind: spring
        units: {length: mm, force: N}
        data:
          rate: 30 kg
          free_length: 306
        """)
    assert message == (f"{SHOWN}: rate: unit 'kg' is not a stiffness unit (expected e.g. "
                       "'N/m') (line 4)")


def test_inline_unknown_unit_is_refused(tmp_path: Path) -> None:
    message = refused(tmp_path, 'front_spring', """\
        kind: spring
        units: {length: mm, force: N}
        data:
          rate: 30 blorg
          free_length: 306
        """)
    assert message == f"{SHOWN}: rate: unknown unit 'blorg' (line 4)"


def test_curve_axis_unit_of_the_wrong_dimension_is_refused(tmp_path: Path) -> None:
    message = refused(tmp_path, 'front_damper', """\
        kind: damper
        data:
          curve: {x: [-1, 0, 1], y: [-2000, 0, 1000], x_unit: mm}
        """)
    assert message == (f"{SHOWN}: curve: unit 'mm' is not a velocity unit (expected e.g. "
                       "'m/s') (line 3)")


def test_text_that_is_not_a_number_is_refused(tmp_path: Path) -> None:
    message = refused(tmp_path, 'front_spring', """\
        kind: spring
        units: {length: mm, force: N}
        data:
          rate: thirty
          free_length: 306
        """)
    assert message == (f"{SHOWN}: rate: expected a number with a unit, found 'thirty' "
                       "(line 4)")


def test_overflow_to_infinity_is_refused(tmp_path: Path) -> None:
    message = refused(tmp_path, 'front_spring', """\
        kind: spring
        units: {length: mm, force: N}
        data:
          rate: '1e400'
          free_length: 306
        """)
    assert message == f"{SHOWN}: rate: value must be finite, found '1e400' (line 4)"
