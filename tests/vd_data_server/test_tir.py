# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Tests of the .tir reader against the Chrono sample files and malformed copies.

Expected values are read off the file text; unit factors come from their
definitions (1 inch = 0.0254 m, 1 lbf = 4.4482216152605 N, 1 bar = 1e5 Pa).
"""

from __future__ import annotations

from collections.abc import Callable
import math
from pathlib import Path
import re

import numpy.testing as npt
import pytest

from vd_data_server.errors import DataError, DataErrors
from vd_data_server.tir import TireProperties, TireTable, parse_tir_text, read_tir

DATA_DIR = Path(__file__).resolve().parents[2] / 'src' / 'vd_data_server' / 'data' / 'tires'
SEDAN = DATA_DIR / 'Sedan_Pac02Tire.tir'
HMMWV = DATA_DIR / 'HMMWV_Pac02Tire.tir'
MF62 = DATA_DIR / 'MF62_255_55R20.tir'
RTOL = 1e-12


def sedan_text() -> str:
    return SEDAN.read_text(encoding='ascii')


def set_line(text: str, key: str, line: str) -> str:
    """Replace the (only) line assigning ``key``."""
    new, count = re.subn(rf'(?m)^{key}\s*=.*$', line, text)
    assert count == 1
    return new


#: the sedan file's dimensions, m, and the length units the tests write them in
DIMENSIONS = {'UNLOADED_RADIUS': 0.344, 'WIDTH': 0.245, 'RIM_RADIUS': 0.2286, 'RIM_WIDTH': 0.2159}
PER_METRE = {"'METER'": 1.0, "'mm'": 1000.0, "'millimeter'": 1000.0, "'centimeter'": 100.0,
             "'inch'": 1 / 0.0254}


def in_length_unit(text: str, unit_line: str) -> str:
    """Set ``LENGTH`` and write the dimensions in it: the file stays a physical tire."""
    per_metre = PER_METRE[unit_line.split('=')[1].strip()]
    text = set_line(text, 'LENGTH', unit_line)
    for key, metres in DIMENSIONS.items():
        text = set_line(text, key, f'{key} = {metres * per_metre!r}')
    return text


def drop_line(text: str, key: str) -> str:
    return set_line(text, key, '')


def drop_block(text: str, block: str) -> str:
    """Remove ``[block]`` and everything up to the next block header."""
    new, count = re.subn(rf'(?ms)^\[{block}\].*?(?=^\[)', '', text)
    assert count == 1
    return new


def line_of(text: str, start: str) -> int:
    """1-based number of the line starting with ``start``."""
    return next(n for n, line in enumerate(text.splitlines(), start=1) if line.startswith(start))


def expect_read_error(tmp_path: Path, text: str, error: type[DataError] = DataError) -> DataError:
    """Write ``text`` to a file, read it, return the error; the reader writes nothing."""
    path = tmp_path / 'tire.tir'
    path.write_text(text, encoding='ascii')
    before = sorted(tmp_path.iterdir())
    with pytest.raises(error) as info:
        read_tir(path)
    assert sorted(tmp_path.iterdir()) == before
    problems = info.value.errors if isinstance(info.value, DataErrors) else [info.value]
    assert {problem.file for problem in problems} == {str(path)}
    return info.value


# --- the sample files ---------------------------------------------------------


@pytest.mark.parametrize(
    ('path', 'block', 'key', 'expected'),
    [
        (SEDAN, 'VERTICAL', 'FNOMIN', 4850.0),
        (SEDAN, 'DIMENSION', 'UNLOADED_RADIUS', 0.344),
        (SEDAN, 'DIMENSION', 'WIDTH', 0.245),
        (SEDAN, 'DIMENSION', 'RIM_RADIUS', 0.2286),
        (SEDAN, 'VERTICAL', 'VERTICAL_STIFFNESS', 280835.2941),
        (SEDAN, 'VERTICAL_FORCE_RANGE', 'FZMAX', 10125.0),
        (SEDAN, 'SCALING_COEFFICIENTS', 'LFZO', 0.81),
        (SEDAN, 'LATERAL_COEFFICIENTS', 'PKY1', -21.92),
        (SEDAN, 'LONGITUDINAL_COEFFICIENTS', 'PEX4', -3.7604e-5),  # written -3.7604e-005
        (HMMWV, 'VERTICAL', 'FNOMIN', 35000.0),
        (HMMWV, 'DIMENSION', 'UNLOADED_RADIUS', 0.4699),
        (HMMWV, 'VERTICAL', 'VERTICAL_STIFFNESS', 1.0e6),  # written 1e+006, followed by a tab
        (HMMWV, 'TIRE_CONDITIONS', 'IP', 800000.0),
        (HMMWV, 'SCALING_COEFFICIENTS', 'LFZO', 0.580904846),
        (HMMWV, 'LATERAL_COEFFICIENTS', 'PDY1', 0.73957),
    ],
)
def test_sample_file_values_are_read_as_written(
    path: Path, block: str, key: str, expected: float
) -> None:
    npt.assert_allclose(read_tir(path).number(block, key), expected, rtol=RTOL)


@pytest.mark.parametrize('path', [SEDAN, HMMWV])
def test_sample_files_are_pac2002_left_tires(path: Path) -> None:
    props = read_tir(path)
    assert (props.file_format, props.get('MODEL', 'TYRESIDE'), props.path) == (
        'PAC2002',
        'LEFT',
        str(path),
    )


@pytest.mark.parametrize(
    ('path', 'radius', 'fnomin', 'stiffness'),
    [(SEDAN, 0.344, 4850.0, 280835.2941), (HMMWV, 0.4699, 35000.0, 1.0e6)],
)
def test_helpers_return_radius_load_and_stiffness(
    path: Path, radius: float, fnomin: float, stiffness: float
) -> None:
    props = read_tir(path)
    npt.assert_allclose(
        (props.unloaded_radius, props.fnomin, props.vertical_stiffness),
        (radius, fnomin, stiffness),
        rtol=RTOL,
    )


def test_sample_file_has_windows_line_endings() -> None:
    # The property the parser is tested for by the sample-file tests above.
    assert b'\r\n' in SEDAN.read_bytes()


def test_shape_table_rows_are_kept() -> None:
    assert read_tir(SEDAN).tables['SHAPE'] == TireTable(
        columns=('radial', 'width'), rows=((1.0, 0.0), (1.0, 0.4), (1.0, 0.9), (0.9, 1.0))
    )


def test_commented_out_key_is_skipped() -> None:
    # The sedan file has "!CONTACT_MODEL = '3D_ENVELOPING'" in [MODEL].
    assert 'CONTACT_MODEL' not in read_tir(SEDAN).sections['MODEL']


def test_trailing_dollar_comment_is_not_part_of_the_value() -> None:
    assert read_tir(SEDAN).get('MODEL', 'USE_MODE') == 4.0  # "= 4   $Tyre use switch (IUSED)"


# --- syntax variants ------------------------------------------------------------


def test_crlf_and_tabs_give_the_same_result() -> None:
    text = sedan_text()
    variant = text.replace('\r\n', '\n').replace('\n', '\r\n').replace('=', '\t=\t')
    assert parse_tir_text(variant, 'x').sections == parse_tir_text(text, 'x').sections


def test_keys_and_blocks_are_case_insensitive() -> None:
    text = set_line(sedan_text(), 'PDY1', 'pdy1 = 1.5').replace(
        '[LATERAL_COEFFICIENTS]', '[Lateral_Coefficients]'
    )
    props = parse_tir_text(text, 'x')
    assert (
        props.sections['LATERAL_COEFFICIENTS']['PDY1'],
        props.get('lateral_coefficients', 'Pdy1'),
    ) == (1.5, 1.5)


def test_double_quotes_and_trailing_bang_comment() -> None:
    text = set_line(sedan_text(), 'TYRESIDE', 'TYRESIDE = "RIGHT" ! mounted side, a $ sign')
    assert parse_tir_text(text, 'x').get('MODEL', 'TYRESIDE') == 'RIGHT'


def test_comment_characters_inside_quotes_are_kept() -> None:
    text = set_line(sedan_text(), 'MESSAGES', "MESSAGES = 'a $ b ! c'  $ comment")
    assert parse_tir_text(text, 'x').get('MODEL', 'MESSAGES') == 'a $ b ! c'


def test_bare_word_is_a_string() -> None:
    text = set_line(sedan_text(), 'TYRESIDE', 'TYRESIDE = LEFT')
    assert parse_tir_text(text, 'x').get('MODEL', 'TYRESIDE') == 'LEFT'


def test_latin1_comment_is_accepted(tmp_path: Path) -> None:
    path = tmp_path / 'tire.tir'
    path.write_bytes(
        sedan_text().replace('! 245/40 R 18', '! 245/40 R 18, 20 \xb0C').encode('latin-1')
    )
    npt.assert_allclose(read_tir(path).fnomin, 4850.0, rtol=RTOL)


def test_utf8_byte_order_mark_is_accepted(tmp_path: Path) -> None:
    path = tmp_path / 'tire.tir'
    path.write_bytes(b'\xef\xbb\xbf' + sedan_text().encode('ascii'))
    npt.assert_allclose(read_tir(path).fnomin, 4850.0, rtol=RTOL)


@pytest.mark.parametrize(
    ('declaration', 'expected'),
    [
        ("PROPERTY_FILE_FORMAT = 'MF_05'", 'MF52'),
        ('FITTYP = 6', 'MF52'),
        ('FITTYP = 21', 'MF52'),
    ],
)
def test_file_format_from_property_file_format_or_fittyp(declaration: str, expected: str) -> None:
    text = set_line(sedan_text(), 'PROPERTY_FILE_FORMAT', declaration)
    assert parse_tir_text(text, 'x').file_format == expected


@pytest.mark.parametrize(
    ('declaration', 'expected'),
    [
        ("PROPERTY_FILE_FORMAT = 'mf61'", 'MF61'),
        ('FITTYP = 61', 'MF61'),
        ('FITTYP = 62', 'MF62'),
        ("PROPERTY_FILE_FORMAT = 'MF-TYRE'\nFITTYP = 62", 'MF62'),
        ("PROPERTY_FILE_FORMAT = 'USER'\nFITTYP = 61", 'MF61'),
    ],
)
def test_mf6_file_format(declaration: str, expected: str) -> None:
    """An MF 6.x file (the bundled 6.2 sample) as its [MODEL] declares it."""
    text = drop_line(MF62.read_text(encoding='ascii'), 'FITTYP')
    text = set_line(text, 'PROPERTY_FILE_FORMAT', declaration)
    assert parse_tir_text(text, 'x').file_format == expected


# --- units ------------------------------------------------------------------------

LBF = 4.4482216152605  # N, definition
INCH = 0.0254  # m, definition


@pytest.mark.parametrize(
    ('unit_line', 'value_line', 'block', 'key', 'expected'),
    [
        ("LENGTH = 'mm'", 'UNLOADED_RADIUS = 234', 'DIMENSION', 'UNLOADED_RADIUS', 0.234),
        ("LENGTH = 'millimeter'", 'WIDTH = 245', 'DIMENSION', 'WIDTH', 0.245),
        ("LENGTH = 'centimeter'", 'RIM_RADIUS = 22.86', 'DIMENSION', 'RIM_RADIUS', 0.2286),
        ("LENGTH = 'inch'", 'RIM_WIDTH = 8.5', 'DIMENSION', 'RIM_WIDTH', 8.5 * INCH),
        ("LENGTH = 'METER'", 'UNLOADED_RADIUS = 0.35', 'DIMENSION', 'UNLOADED_RADIUS', 0.35),
        (
            "LENGTH = 'mm'",
            'VERTICAL_STIFFNESS = 280.8352941',
            'VERTICAL',
            'VERTICAL_STIFFNESS',
            280835.2941,
        ),
        ("LENGTH = 'mm'", 'LONGVL = 16600', 'MODEL', 'LONGVL', 16.6),
        ("FORCE = 'kN'", 'FNOMIN = 4.85', 'VERTICAL', 'FNOMIN', 4850.0),
        ("FORCE = 'pound_force'", 'FZMAX = 1000', 'VERTICAL_FORCE_RANGE', 'FZMAX', 1000.0 * LBF),
        (
            "FORCE = 'kN'",
            'VERTICAL_STIFFNESS = 280.8352941',
            'VERTICAL',
            'VERTICAL_STIFFNESS',
            280835.2941,
        ),
        ("ANGLE = 'deg'", 'ALPMAX = 90', 'SLIP_ANGLE_RANGE', 'ALPMAX', math.pi / 2.0),
        (
            "ANGLE = 'degree'",
            'CAMMIN = -15',
            'INCLINATION_ANGLE_RANGE',
            'CAMMIN',
            -15.0 * math.pi / 180.0,
        ),
        ("TIME = 'millisecond'", 'VERTICAL_DAMPING = 2e6', 'VERTICAL', 'VERTICAL_DAMPING', 2000.0),
        ("TIME = 'sec'", 'VXLOW = 1.5', 'MODEL', 'VXLOW', 1.5),
        ("MASS = 'gram'", 'MBELT = 5400', 'ALIGNING_COEFFICIENTS', 'MBELT', 5.4),
    ],
)
def test_dimensional_values_are_converted_to_si(
    unit_line: str, value_line: str, block: str, key: str, expected: float
) -> None:
    quantity = unit_line.split('=')[0].strip()
    text = (in_length_unit(sedan_text(), unit_line) if quantity == 'LENGTH'
            else set_line(sedan_text(), quantity, unit_line))
    text = set_line(text, value_line.split('=')[0].strip(), value_line)
    npt.assert_allclose(parse_tir_text(text, 'x').number(block, key), expected, rtol=RTOL)


@pytest.mark.parametrize(
    ('unit', 'value', 'expected'),
    [
        ("'bar'", '2.5', 2.5e5),
        ("'kPa'", '250', 2.5e5),
        ("'psi'", '36', 36.0 * LBF / INCH**2),
        ("'Pa'", '8e5', 8e5),
    ],
)
def test_pressure_is_converted_to_pascal(unit: str, value: str, expected: float) -> None:
    text = set_line(HMMWV.read_text(encoding='ascii'), 'PRESSURE', f'PRESSURE = {unit}')
    text = set_line(text, 'IP', f'IP = {value}')
    npt.assert_allclose(
        parse_tir_text(text, 'x').number('TIRE_CONDITIONS', 'IP'), expected, rtol=RTOL
    )


def test_magic_formula_coefficients_are_not_converted() -> None:
    # the file kept physical in mm
    text = set_line(in_length_unit(sedan_text(), "LENGTH = 'mm'"), 'FORCE', "FORCE = 'kN'")
    props = parse_tir_text(text, 'x')
    npt.assert_allclose(
        (
            props.number('LATERAL_COEFFICIENTS', 'PKY1'),
            props.number('SCALING_COEFFICIENTS', 'LFZO'),
        ),
        (-21.92, 0.81),
        rtol=RTOL,
    )


def test_dimensions_in_metres_under_length_mm_are_refused() -> None:
    """A 0.344 'mm' tire: the [UNITS] do not match the numbers; every dimension says so."""
    with pytest.raises(DataError) as err:
        parse_tir_text(set_line(sedan_text(), 'LENGTH', "LENGTH = 'mm'"), 'x')
    assert str(err.value).splitlines() == [
        f"x: {key}: line {line}: key '{key}' in block [DIMENSION] must lie within "
        f'{low:g}..{high:g} m for a road tire, here {metres / 1000:g} m (are the [UNITS] '
        f'right, e.g. LENGTH?), found {metres:g}'
        for key, line, low, high, metres in (('UNLOADED_RADIUS', 23, 0.1, 2, 0.344),
                                             ('WIDTH', 24, 0.05, 1.5, 0.245),
                                             ('RIM_RADIUS', 26, 0.05, 1.5, 0.2286),
                                             ('RIM_WIDTH', 27, 0.03, 1.5, 0.2159))]


def test_absent_unit_entry_means_si() -> None:
    props = parse_tir_text(drop_line(sedan_text(), 'LENGTH'), 'x')
    npt.assert_allclose(props.unloaded_radius, 0.344, rtol=RTOL)


# --- accessors ----------------------------------------------------------------------


def test_get_returns_default_for_absent_key_and_block() -> None:
    props = read_tir(SEDAN)
    assert (props.get('MODEL', 'NO_SUCH_KEY', 7.0), props.get('NO_SUCH_BLOCK', 'X', 'd')) == (
        7.0,
        'd',
    )


def test_get_without_default_names_missing_key() -> None:
    with pytest.raises(DataError) as info:
        read_tir(SEDAN).get('TIRE_CONDITIONS', 'IP')
    assert (info.value.detail, info.value.key) == ('missing block [TIRE_CONDITIONS]', None)


def test_number_rejects_a_string() -> None:
    with pytest.raises(DataError) as info:
        read_tir(SEDAN).number('MODEL', 'TYRESIDE')
    assert (info.value.detail, info.value.key) == (
        "key 'TYRESIDE' in block [MODEL] is not a number: 'LEFT'",
        'TYRESIDE',
    )


def test_properties_are_read_only() -> None:
    props = read_tir(SEDAN)
    with pytest.raises(TypeError):
        props.sections['VERTICAL']['FNOMIN'] = 1.0  # type: ignore[index]


def test_vertical_stiffness_helper_names_missing_key() -> None:
    props = parse_tir_text(drop_line(sedan_text(), 'VERTICAL_STIFFNESS'), 'x')
    with pytest.raises(DataError) as info:
        _ = props.vertical_stiffness
    assert (
        str(info.value)
        == "x: VERTICAL_STIFFNESS: key 'VERTICAL_STIFFNESS' missing in block [VERTICAL]"
    )


# --- bad input ----------------------------------------------------------------------


def test_missing_block(tmp_path: Path) -> None:
    error = expect_read_error(tmp_path, drop_block(sedan_text(), 'LATERAL_COEFFICIENTS'))
    assert (error.detail, error.key) == ('missing block [LATERAL_COEFFICIENTS]', None)
    assert str(error) == f"{tmp_path / 'tire.tir'}: missing block [LATERAL_COEFFICIENTS]"


@pytest.mark.parametrize(
    ('block', 'key'),
    [
        ('LATERAL_COEFFICIENTS', 'PDY1'),
        ('LATERAL_COEFFICIENTS', 'PKY2'),
        ('LONGITUDINAL_COEFFICIENTS', 'PKX1'),
        ('VERTICAL', 'FNOMIN'),
        ('DIMENSION', 'UNLOADED_RADIUS'),
    ],
)
def test_missing_required_key(tmp_path: Path, block: str, key: str) -> None:
    error = expect_read_error(tmp_path, drop_line(sedan_text(), key))
    assert (error.detail, error.key) == (f"key '{key}' missing in block [{block}]", key)


def test_several_problems_are_reported_together(tmp_path: Path) -> None:
    text = drop_line(drop_block(sedan_text(), 'SCALING_COEFFICIENTS'), 'PCX1')
    error = expect_read_error(tmp_path, text, DataErrors)
    assert isinstance(error, DataErrors)
    assert [e.detail for e in error.errors] == [
        'missing block [SCALING_COEFFICIENTS]',
        "key 'PCX1' missing in block [LONGITUDINAL_COEFFICIENTS]",
    ]


@pytest.mark.parametrize(
    ('line', 'block', 'key', 'found'),
    [
        ('PDY1 = 1.04x', 'LATERAL_COEFFICIENTS', 'PDY1', '1.04x'),
        ("FNOMIN = '4850'", 'VERTICAL', 'FNOMIN', "'4850'"),
        ('LFZO = nan', 'SCALING_COEFFICIENTS', 'LFZO', 'nan'),
        ('LONGVL = fast', 'MODEL', 'LONGVL', 'fast'),
    ],
)
def test_value_that_is_not_a_number(
    tmp_path: Path, line: str, block: str, key: str, found: str
) -> None:
    text = set_line(sedan_text(), key, line)
    error = expect_read_error(tmp_path, text)
    number = line_of(text, f'{key} ')
    assert (error.detail, error.key) == (
        f"line {number}: key '{key}' in block [{block}] is not a number: {found}",
        key,
    )


@pytest.mark.parametrize(
    ('line', 'quantity', 'word'),
    [
        ("LENGTH = 'bananas'", 'LENGTH', 'length'),
        ("LENGTH = 'newton'", 'LENGTH', 'length'),
        ("LENGTH = 'm/s'", 'LENGTH', 'length'),
        ("FORCE = 'KN'", 'FORCE', 'force'),  # pint reads 'kn' as knot, not kilonewton
        ("ANGLE = 'percent'", 'ANGLE', 'angle'),
        ("MASS = 'second'", 'MASS', 'mass'),
        ("TIME = ''", 'TIME', 'time'),
    ],
)
def test_unknown_unit(tmp_path: Path, line: str, quantity: str, word: str) -> None:
    text = set_line(sedan_text(), quantity, line)
    error = expect_read_error(tmp_path, text)
    found = line.split('=')[1].strip()
    assert (error.detail, error.key) == (
        f'line {line_of(text, quantity)}: {found} is not a known unit of {word}',
        quantity,
    )


def test_unknown_property_file_format(tmp_path: Path) -> None:
    text = set_line(sedan_text(), 'PROPERTY_FILE_FORMAT', "PROPERTY_FILE_FORMAT = 'PAC89'")
    error = expect_read_error(tmp_path, text)
    assert (error.detail, error.key) == (
        f"line {line_of(text, 'PROPERTY_FILE_FORMAT')}: unknown PROPERTY_FILE_FORMAT 'PAC89' "
        "(known: 'MF-TYRE', 'MF52', 'MF61', 'MF62', 'MF_05', 'MF_TYRE', 'PAC2002', 'USER')",
        'PROPERTY_FILE_FORMAT',
    )


def test_unknown_fittyp(tmp_path: Path) -> None:
    text = set_line(sedan_text(), 'PROPERTY_FILE_FORMAT', 'FITTYP = 5')
    error = expect_read_error(tmp_path, text)
    assert (error.detail, error.key) == (
        f"line {line_of(text, 'FITTYP')}: unknown FITTYP 5 (known: 6, 21, 61, 62)",
        'FITTYP',
    )


def test_no_format_given(tmp_path: Path) -> None:
    error = expect_read_error(tmp_path, drop_line(sedan_text(), 'PROPERTY_FILE_FORMAT'))
    assert (error.detail, error.key) == (
        'block [MODEL] gives neither PROPERTY_FILE_FORMAT nor FITTYP',
        None,
    )


def test_generic_format_without_fittyp(tmp_path: Path) -> None:
    text = set_line(sedan_text(), 'PROPERTY_FILE_FORMAT', "PROPERTY_FILE_FORMAT = 'MF-TYRE'")
    error = expect_read_error(tmp_path, text)
    assert (error.detail, error.key) == (
        f"line {line_of(text, 'PROPERTY_FILE_FORMAT')}: "
        "PROPERTY_FILE_FORMAT 'MF-TYRE' needs FITTYP in block [MODEL]",
        'FITTYP',
    )


@pytest.mark.parametrize(
    ('line', 'block', 'key'),
    [
        ('FNOMIN = 0', 'VERTICAL', 'FNOMIN'),
        ('FNOMIN = -4850', 'VERTICAL', 'FNOMIN'),
        ('UNLOADED_RADIUS = 0.0', 'DIMENSION', 'UNLOADED_RADIUS'),
        ('UNLOADED_RADIUS = -0.344', 'DIMENSION', 'UNLOADED_RADIUS'),
    ],
)
def test_non_physical_value(tmp_path: Path, line: str, block: str, key: str) -> None:
    text = set_line(sedan_text(), key, line)
    error = expect_read_error(tmp_path, text)
    found = line.split('=')[1].strip()
    assert (error.detail, error.key) == (
        f"line {line_of(text, key)}: key '{key}' in block [{block}] must be > 0, found {found}",
        key,
    )


def test_missing_file(tmp_path: Path) -> None:
    path = tmp_path / 'absent.tir'
    with pytest.raises(DataError) as info:
        read_tir(path)
    assert (info.value.detail, info.value.file) == (
        'cannot read tire property file: No such file or directory',
        str(path),
    )
    assert list(tmp_path.iterdir()) == []


def test_directory_instead_of_file(tmp_path: Path) -> None:
    with pytest.raises(DataError) as info:
        read_tir(tmp_path)
    assert (info.value.detail, info.value.file) == (
        'cannot read tire property file: Is a directory',
        str(tmp_path),
    )
    assert list(tmp_path.iterdir()) == []


def lines_of(text: str, start: str) -> list[int]:
    """1-based numbers of all lines starting with ``start``."""
    return [n for n, line in enumerate(text.splitlines(), start=1) if line.startswith(start)]


def with_messages(line: str) -> Callable[[str], str]:
    """Edit: put ``line`` in place of the MESSAGES line of [MODEL]."""
    return lambda text: set_line(text, 'MESSAGES', line)


@pytest.mark.parametrize(
    ('edit', 'expected'),
    [
        (
            with_messages('GARBAGE LINE'),
            lambda t: (
                f"line {line_of(t, 'GARBAGE')}: cannot read 'GARBAGE LINE' in block [MODEL]: "
                'expected KEY = value, a {column header} or a row of numbers'
            ),
        ),
        (
            with_messages("MESSAGES = 'YES"),
            lambda t: (
                f'line {line_of(t, "MESSAGES")}: unterminated quoted string in "MESSAGES = \'YES"'
            ),
        ),
        (
            with_messages('MESSAGES ='),
            lambda t: (
                f"line {line_of(t, 'MESSAGES')}: key 'MESSAGES' in block [MODEL] has no value"
            ),
        ),
        (
            with_messages('2ND KEY = 1'),
            lambda t: f"line {line_of(t, '2ND')}: '2ND KEY' is not a key name",
        ),
        (
            with_messages("TYRESIDE = 'RIGHT'"),
            lambda t: "line {1}: key 'TYRESIDE' repeats line {0} in block [MODEL]".format(
                *lines_of(t, 'TYRESIDE')
            ),
        ),
        (
            with_messages('[UNITS]'),
            lambda t: 'line {1}: block [UNITS] repeats line {0}'.format(*lines_of(t, '[UNITS]')),
        ),
        (
            lambda t: t.replace(' 0.9    1.0', ' 0.9    1.0    2.0'),
            lambda t: (
                f"line {line_of(t, ' 0.9    1.0    2.0')}: "
                'table row in block [SHAPE] has 3 values, expected 2'
            ),
        ),
        (lambda t: 'KEY = 1\n' + t, lambda t: "line 1: 'KEY = 1' comes before the first [BLOCK]"),
    ],
    ids=[
        'garbage',
        'open-quote',
        'no-value',
        'bad-key',
        'repeated-key',
        'repeated-block',
        'table-row',
        'before-block',
    ],
)
def test_syntax_error_names_the_line(
    tmp_path: Path, edit: Callable[[str], str], expected: Callable[[str], str]
) -> None:
    text = edit(sedan_text().replace('\r\n', '\n'))
    error = expect_read_error(tmp_path, text)
    assert error.detail == expected(text)


def test_parse_tir_text_uses_source_as_path() -> None:
    props = parse_tir_text(sedan_text(), 'memory:sedan')
    assert isinstance(props, TireProperties) and props.path == 'memory:sedan'


# --- MF 6.1 / 6.2 files -------------------------------------------------------------


def mf62_text() -> str:
    return MF62.read_text(encoding='ascii')


def test_the_mf62_sample_is_read_as_62_with_its_pressures() -> None:
    props = read_tir(MF62)
    assert props.file_format == 'MF62'
    assert props.number('OPERATING_CONDITIONS', 'INFLPRES') == 260000.0
    assert props.number('OPERATING_CONDITIONS', 'NOMPRES') == 260000.0
    assert props.get('UNITS', 'ANGLE') == 'radians'  # pint's plural of radian


@pytest.mark.parametrize(
    ('case', 'edit', 'key', 'message'),
    [
        ('no operating conditions', lambda t: drop_block(t, 'OPERATING_CONDITIONS'), None,
         'missing block [OPERATING_CONDITIONS] (needed by MF 6.2)'),
        ('no NOMPRES', lambda t: drop_line(t, 'NOMPRES'), 'NOMPRES',
         "key 'NOMPRES' missing in block [OPERATING_CONDITIONS]"),
        ('no aligning coefficients', lambda t: drop_block(t, 'ALIGNING_COEFFICIENTS'), None,
         'missing block [ALIGNING_COEFFICIENTS] (needed by MF 6.2)'),
        ('misspelt coefficient', lambda t: set_line(t, 'PKY7', 'PKY7 = 0.2665448\nPKY8 = 1'),
         'PKY8', "line {PKY8}: 'PKY8' is no MF 6.2 coefficient of block [LATERAL_COEFFICIENTS] "
         '(a misspelt coefficient would silently be 0)'),
        ('PAC2002 coefficient', lambda t: set_line(t, 'PHY2', 'PHY2 = 0.0016\nPHY3 = 0.03'),
         'PHY3', "line {PHY3}: 'PHY3' is no MF 6.2 coefficient of block [LATERAL_COEFFICIENTS] "
         '(a misspelt coefficient would silently be 0)'),
        ('unknown FITTYP', lambda t: set_line(t, 'FITTYP', 'FITTYP = 63'), 'FITTYP',
         'line {FITTYP}: unknown FITTYP 63 (known: 6, 21, 61, 62)'),
        ('FITTYP against the format',
         lambda t: set_line(t, 'PROPERTY_FILE_FORMAT', "PROPERTY_FILE_FORMAT = 'PAC2002'"),
         'FITTYP', "line {FITTYP}: FITTYP 62 (MF 6.2) contradicts PROPERTY_FILE_FORMAT "
         "'PAC2002' of line {PROPERTY_FILE_FORMAT} (MF 5.2)"),
        ('pressure outside the range', lambda t: set_line(t, 'INFLPRES', 'INFLPRES = 500000'),
         'INFLPRES', "line {INFLPRES}: key 'INFLPRES' in block [OPERATING_CONDITIONS] must lie "
         'in the range the file is valid for, PRESMIN..PRESMAX = 200000..400000 Pa, found '
         '500000'),
        ('negative nominal pressure', lambda t: set_line(t, 'NOMPRES', 'NOMPRES = -1'),
         'NOMPRES', "line {NOMPRES}: key 'NOMPRES' in block [OPERATING_CONDITIONS] must be > 0, "
         'found -1'),
        ('pressure range upside down', lambda t: set_line(t, 'PRESMIN', 'PRESMIN = 500000'),
         'PRESMAX', "line {PRESMAX}: key 'PRESMAX' in block [INFLATION_PRESSURE_RANGE] must be > "
         'PRESMIN (500000), found 400000'),
        ('no real Q_FZ1', lambda t: set_line(t, 'Q_FZ2', 'Q_FZ2 = 500'), 'Q_FZ2',
         "line {Q_FZ2}: key 'Q_FZ2' in block [VERTICAL] must be at most (VERTICAL_STIFFNESS "
         'UNLOADED_RADIUS / FNOMIN)^2 / 4 = 88.5757 (Q_FZ1 = sqrt((C_z R0 / FNOMIN)^2 - 4 '
         'Q_FZ2)), found 500'),
        ('USE_MODE not evaluated', lambda t: set_line(t, 'USE_MODE', 'USE_MODE = 127'),
         'USE_MODE', "line {USE_MODE}: key 'USE_MODE' in block [MODEL] must end in one of 1, 2, "
         '3, 4, 5 (1 Fx, 2 Fy and Mz, 3 uncombined, 4 combined, 5 combined with turn slip), '
         'found 127'),
        ('turn slip without its coefficients',
         lambda t: set_line(set_line(t, 'PHYP2', 'PHYP2 = 0'), 'USE_MODE', 'USE_MODE = 125'),
         'USE_MODE', "line {USE_MODE}: key 'USE_MODE' in block [MODEL] asks for turn slip (5), "
         'which needs PHYP2 != 0 in block [TURNSLIP_COEFFICIENTS]'),
        ('pressure not a number', lambda t: set_line(t, 'NOMPRES', "NOMPRES = 'high'"),
         'NOMPRES', "line {NOMPRES}: key 'NOMPRES' in block [OPERATING_CONDITIONS] is not a "
         "number: 'high'"),
        ('unknown unit', lambda t: set_line(t, 'LENGTH', "LENGTH = 'furlong_x'"), 'LENGTH',
         "line {LENGTH}: 'furlong_x' is not a known unit of length"),
    ],
)
def test_bad_mf6_files_are_refused_naming_file_and_line(
    tmp_path: Path, case: str, edit: Callable[[str], str], key: str | None, message: str
) -> None:
    text = edit(mf62_text())
    lines = {k: line_of(text, k) for k in re.findall(r'\{(\w+)\}', message)}
    error = expect_read_error(tmp_path, text)
    assert (error.detail, error.key) == (message.format(**lines), key), case


def test_turn_slip_needs_an_mf6_file(tmp_path: Path) -> None:
    text = set_line(sedan_text(), 'USE_MODE', 'USE_MODE = 5')
    error = expect_read_error(tmp_path, text)
    assert (error.detail, error.key) == (
        f"line {line_of(text, 'USE_MODE')}: key 'USE_MODE' in block [MODEL] asks for turn slip "
        '(5), which needs an MF 6.1 / 6.2 file, found 5 in a PAC2002 file', 'USE_MODE')


# (key, factor of its value in the millimetre file): lengths x 1000, N/m / 1000, ...
MILLIMETRE = {
    'UNLOADED_RADIUS': 1e3, 'WIDTH': 1e3, 'RIM_RADIUS': 1e3, 'RIM_WIDTH': 1e3,
    'BOTTOM_OFFST': 1e3, 'ROAD_INCREMENT': 1e3, 'ELLIPS_MAX_STEP': 1e3, 'LONGVL': 1e3,
    'VXLOW': 1e3, 'VERTICAL_STIFFNESS': 1e-3, 'VERTICAL_DAMPING': 1e-3, 'BOTTOM_STIFF': 1e-3,
    'LONGITUDINAL_STIFFNESS': 1e-3, 'LATERAL_STIFFNESS': 1e-3, 'YAW_STIFFNESS': 1e3,
    'IXX': 1e6, 'IYY': 1e6, 'BELT_IXX': 1e6, 'BELT_IYY': 1e6, 'GRAVITY': 1e3,
}  # fmt: skip


def test_an_mf6_file_in_millimetres_is_the_same_tire() -> None:
    """LENGTH = 'mm' converts every key with a length; the coefficients stay as written."""
    text = set_line(mf62_text(), 'LENGTH', "LENGTH = 'mm'")
    for key, factor in MILLIMETRE.items():
        value = float(re.search(rf'(?m)^{key}\s*=\s*(\S+)', text)[1])
        text = set_line(text, key, f'{key} = {value * factor!r}')
    metre, millimetre = read_tir(MF62), parse_tir_text(text, 'mm.tir')
    for block, entries in metre.sections.items():
        for key, value in entries.items():
            if isinstance(value, str):
                assert millimetre.sections[block][key] == value or block == 'UNITS'
            else:
                npt.assert_allclose(millimetre.sections[block][key], value, rtol=1e-12,
                                    err_msg=f'{block} {key}')
