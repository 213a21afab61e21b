# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Reader for TeimOrbit tire property files (.tir): PAC2002, MF-Tyre 5.2, 6.1, 6.2.

The files tire suppliers deliver for MF-Tyre and Adams/Tire are line based
(TeimOrbit format; Pacejka, "Tire and Vehicle Dynamics", 3rd ed., ch. 4 and
app. 3 list the Magic Formula parameters they carry):

* ``[BLOCK]`` starts a block. Block and key names are case-insensitive and are
  stored upper-case.
* ``KEY = value``: a number (``4850``, ``1e+006``, ``-3.7604e-005``), a quoted
  string (``'PAC2002'`` or ``"PAC2002"``) or a bare word.
* ``$`` and ``!`` start a comment anywhere outside a quoted string, which covers
  whole comment lines and the trailing ``$description`` of a key.
* A block may hold a table instead of keys, e.g. ``[SHAPE]`` with a
  ``{radial width}`` header and rows of numbers; the rows are kept in
  :attr:`TireProperties.tables` as written (they are ratios, no units).
* Tabs, Windows line endings and a UTF-8 byte-order mark are accepted. A file
  that is not UTF-8 is read as Latin-1 because suppliers' Windows tools write
  degree signs and the like into comments.

Units
-----
[UNITS] names the units of LENGTH, FORCE, ANGLE, MASS, TIME and PRESSURE; an
entry that is absent means the SI unit (PAC2002 files often have no PRESSURE).
Names are looked up in pint, first as written and then in lower case, so
'meter', 'mm', 'millimeter', 'centimeter', 'inch', 'newton', 'N', 'kN',
'radian', 'rad', 'deg', 'degree', 'kg', 'gram', 'second', 'sec', 's',
'pascal', 'Pa', 'kPa', 'bar', 'psi' all work. A name pint does not know, or one
of the wrong kind (a force for LENGTH), is an error.

Only the keys in :data:`DIMENSIONAL_KEYS` carry units and are converted to SI.
Every other value is stored as written: the Magic Formula coefficients and
scaling factors of PAC2002 / MF 6.x are dimensionless by the format's
definition (loads normalised by FNOMIN, lengths by UNLOADED_RADIUS, slip and
camber in radians), so [UNITS] does not apply to them.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
import enum
import math
from pathlib import Path
import re
from types import MappingProxyType
from typing import Final

from vd_data_server.errors import DataError, DataErrors
from vd_data_server.reads import note_read
from vd_data_server.units import ureg
from vd_data_server.yamlio import MAX_FILE_BYTES

__all__ = [
    'DIMENSIONAL_KEYS',
    'MF6_COEFFICIENTS',
    'MF6_REQUIRED_BLOCKS',
    'MF6_REQUIRED_KEYS',
    'REQUIRED_BLOCKS',
    'REQUIRED_KEYS',
    'TireProperties',
    'TireTable',
    'parse_tir_text',
    'read_tir',
]

#: Blocks every supported file must contain, in the order problems are reported.
REQUIRED_BLOCKS: Final[tuple[str, ...]] = (
    'UNITS',
    'MODEL',
    'DIMENSION',
    'VERTICAL',
    'SCALING_COEFFICIENTS',
    'LONGITUDINAL_COEFFICIENTS',
    'LATERAL_COEFFICIENTS',
)

#: Keys without which no steady-state force can be computed. Other Magic
#: Formula coefficients default to 0 and scaling factors to 1, as in MF-Tyre.
REQUIRED_KEYS: Final[Mapping[str, tuple[str, ...]]] = MappingProxyType(
    {
        'DIMENSION': ('UNLOADED_RADIUS',),
        'VERTICAL': ('FNOMIN',),
        'LONGITUDINAL_COEFFICIENTS': ('PCX1', 'PDX1', 'PKX1'),
        'LATERAL_COEFFICIENTS': ('PCY1', 'PDY1', 'PKY1', 'PKY2'),
    }
)

#: Blocks an MF 6.1 / 6.2 file must contain besides :data:`REQUIRED_BLOCKS`: the pressures
#: the Magic Formula is normalised by, and the aligning moment every 6.x file carries.
MF6_REQUIRED_BLOCKS: Final[tuple[str, ...]] = ('OPERATING_CONDITIONS', 'ALIGNING_COEFFICIENTS')

#: Keys an MF 6.1 / 6.2 file must give besides :data:`REQUIRED_KEYS`: INFLPRES is the one a
#: configuration overrides, NOMPRES normalises it (dpi, Pacejka 4.E2b); VERTICAL_STIFFNESS
#: gives the 6.x load-deflection curve (Q_FZ1); QBZ1, QCZ1, QDZ1 the pneumatic trail.
MF6_REQUIRED_KEYS: Final[Mapping[str, tuple[str, ...]]] = MappingProxyType(
    {
        'OPERATING_CONDITIONS': ('INFLPRES', 'NOMPRES'),
        'VERTICAL': ('VERTICAL_STIFFNESS',),
        'ALIGNING_COEFFICIENTS': ('QBZ1', 'QCZ1', 'QDZ1'),
    }
)

#: The coefficients MF-Tyre 6.1 / 6.2 defines in each coefficient block (Besselink et al.
#: 2010 appendix, Pacejka 2012 sec. 4.3.2 and 4.3.3, the MF-Tyre 6.x sample files). In a 6.x
#: file any other key in these blocks is refused: a misspelt coefficient would silently be
#: 0. PAC2002 / MF 5.2 files, whose blocks carry tool-specific extras, are not checked so.
MF6_COEFFICIENTS: Final[Mapping[str, frozenset[str]]] = MappingProxyType(
    {
        'SCALING_COEFFICIENTS': frozenset(
            'LFZO LCX LMUX LEX LKX LHX LVX LCY LMUY LEY LKY LKYC LKZC LHY LVY LTR LRES LXAL '
            'LYKA LVYKA LS LMX LVMX LMY LMP'.split()),
        'LONGITUDINAL_COEFFICIENTS': frozenset(
            'PCX1 PDX1 PDX2 PDX3 PEX1 PEX2 PEX3 PEX4 PKX1 PKX2 PKX3 PHX1 PHX2 PVX1 PVX2 PPX1 '
            'PPX2 PPX3 PPX4 RBX1 RBX2 RBX3 RCX1 REX1 REX2 RHX1'.split()),
        'OVERTURNING_COEFFICIENTS': frozenset(
            'QSX1 QSX2 QSX3 QSX4 QSX5 QSX6 QSX7 QSX8 QSX9 QSX10 QSX11 QSX12 QSX13 QSX14 '
            'PPMX1'.split()),
        'LATERAL_COEFFICIENTS': frozenset(
            'PCY1 PDY1 PDY2 PDY3 PEY1 PEY2 PEY3 PEY4 PEY5 PKY1 PKY2 PKY3 PKY4 PKY5 PKY6 PKY7 '
            'PHY1 PHY2 PVY1 PVY2 PVY3 PVY4 PPY1 PPY2 PPY3 PPY4 PPY5 RBY1 RBY2 RBY3 RBY4 RCY1 '
            'REY1 REY2 RHY1 RHY2 RVY1 RVY2 RVY3 RVY4 RVY5 RVY6'.split()),
        'ROLLING_COEFFICIENTS': frozenset('QSY1 QSY2 QSY3 QSY4 QSY5 QSY6 QSY7 QSY8'.split()),
        'ALIGNING_COEFFICIENTS': frozenset(
            'QBZ1 QBZ2 QBZ3 QBZ4 QBZ5 QBZ9 QBZ10 QCZ1 QDZ1 QDZ2 QDZ3 QDZ4 QDZ6 QDZ7 QDZ8 QDZ9 '
            'QDZ10 QDZ11 QEZ1 QEZ2 QEZ3 QEZ4 QEZ5 QHZ1 QHZ2 QHZ3 QHZ4 PPZ1 PPZ2 SSZ1 SSZ2 '
            'SSZ3 SSZ4'.split()),
        'TURNSLIP_COEFFICIENTS': frozenset(
            'PDXP1 PDXP2 PDXP3 PKYP1 PDYP1 PDYP2 PDYP3 PDYP4 PHYP1 PHYP2 PHYP3 PHYP4 PECP1 '
            'PECP2 QDTP1 QCRP1 QCRP2 QBRP1 QDRP1'.split()),
    }
)

#: Keys with units: key -> ((quantity in [UNITS], exponent), ...). Key names are
#: unique across the PAC2002 and MF 6.x blocks, so the block is not needed.
DIMENSIONAL_KEYS: Final[Mapping[str, tuple[tuple[str, int], ...]]] = MappingProxyType(
    {
        # [MODEL]: measurement speed and the speed below which forces fade out, m/s
        'LONGVL': (('LENGTH', 1), ('TIME', -1)),
        'VXLOW': (('LENGTH', 1), ('TIME', -1)),
        # MF 6.x [MODEL]: road sampling distance, m; Adams integration settings, s
        'ROAD_INCREMENT': (('LENGTH', 1),),
        'HMAX_LOCAL': (('TIME', 1),),
        'TIME_SWITCH_INTEG': (('TIME', 1),),
        # [DIMENSION], m
        'UNLOADED_RADIUS': (('LENGTH', 1),),
        'WIDTH': (('LENGTH', 1),),
        'RIM_RADIUS': (('LENGTH', 1),),
        'RIM_WIDTH': (('LENGTH', 1),),
        'BOTTOMING_RADIUS': (('LENGTH', 1),),
        # [VERTICAL]: N, N/m, N s/m, m
        'FNOMIN': (('FORCE', 1),),
        'VERTICAL_STIFFNESS': (('FORCE', 1), ('LENGTH', -1)),
        'VERTICAL_DAMPING': (('FORCE', 1), ('TIME', 1), ('LENGTH', -1)),
        'BOTTOM_OFFST': (('LENGTH', 1),),
        'BOTTOM_STIFF': (('FORCE', 1), ('LENGTH', -1)),
        # [VERTICAL_FORCE_RANGE], N
        'FZMIN': (('FORCE', 1),),
        'FZMAX': (('FORCE', 1),),
        # [SLIP_ANGLE_RANGE], [INCLINATION_ANGLE_RANGE], rad
        'ALPMIN': (('ANGLE', 1),),
        'ALPMAX': (('ANGLE', 1),),
        'CAMMIN': (('ANGLE', 1),),
        'CAMMAX': (('ANGLE', 1),),
        # PAC2002 [TIRE_CONDITIONS], MF 6.x [OPERATING_CONDITIONS] and
        # [INFLATION_PRESSURE_RANGE], Pa
        'IP': (('PRESSURE', 1),),
        'IP_NOM': (('PRESSURE', 1),),
        'INFLPRES': (('PRESSURE', 1),),
        'NOMPRES': (('PRESSURE', 1),),
        'PRESMIN': (('PRESSURE', 1),),
        'PRESMAX': (('PRESSURE', 1),),
        # PAC2002 belt mass in [ALIGNING_COEFFICIENTS]; MF 6.x [INERTIA]: kg, kg m^2, m/s^2
        'MBELT': (('MASS', 1),),
        'MASS': (('MASS', 1),),
        'IXX': (('MASS', 1), ('LENGTH', 2)),
        'IYY': (('MASS', 1), ('LENGTH', 2)),
        'BELT_MASS': (('MASS', 1),),
        'BELT_IXX': (('MASS', 1), ('LENGTH', 2)),
        'BELT_IYY': (('MASS', 1), ('LENGTH', 2)),
        'GRAVITY': (('LENGTH', 1), ('TIME', -2)),
        # MF 6.x [STRUCTURAL]: N/m, N m/rad, Hz
        'LONGITUDINAL_STIFFNESS': (('FORCE', 1), ('LENGTH', -1)),
        'LATERAL_STIFFNESS': (('FORCE', 1), ('LENGTH', -1)),
        'YAW_STIFFNESS': (('FORCE', 1), ('LENGTH', 1), ('ANGLE', -1)),
        'FREQ_LONG': (('TIME', -1),),
        'FREQ_LAT': (('TIME', -1),),
        'FREQ_YAW': (('TIME', -1),),
        'FREQ_WINDUP': (('TIME', -1),),
        # MF 6.x [CONTACT_PATCH]: largest road step of the enveloping model, m
        'ELLIPS_MAX_STEP': (('LENGTH', 1),),
    }
)

# SI unit each [UNITS] quantity is converted to, and the word used in messages.
_SI_UNITS: Final[Mapping[str, str]] = MappingProxyType(
    {
        'LENGTH': 'meter',
        'FORCE': 'newton',
        'ANGLE': 'radian',
        'MASS': 'kilogram',
        'TIME': 'second',
        'PRESSURE': 'pascal',
    }
)
_QUANTITY_WORDS: Final[Mapping[str, str]] = MappingProxyType(
    {
        'LENGTH': 'length',
        'FORCE': 'force',
        'ANGLE': 'angle',
        'MASS': 'mass',
        'TIME': 'time',
        'PRESSURE': 'pressure',
    }
)
# pint treats angles as dimensionless, so a dimension check would let
# 'percent' through as an ANGLE; only these (pint's canonical names) are angles.
_ANGLE_UNITS: Final[frozenset[str]] = frozenset({'radian', 'degree'})

# PROPERTY_FILE_FORMAT values naming one version. 'MF_05' is TNO's MF-Tyre 5.x
# format, whose steady-state equations are those of MF 5.2 / PAC2002.
_FORMAT_NAMES: Final[Mapping[str, str]] = MappingProxyType(
    {'PAC2002': 'PAC2002', 'MF_05': 'MF52', 'MF52': 'MF52', 'MF61': 'MF61', 'MF62': 'MF62'}
)
# PROPERTY_FILE_FORMAT values that leave the version to FITTYP.
# 'USER' is how MF-Tyre 6.x files for Adams name their format (with USER_SUB_ID = 815).
_GENERIC_FORMAT_NAMES: Final[frozenset[str]] = frozenset({'MF-TYRE', 'MF_TYRE', 'USER'})
# Versions with the same steady-state equations: a PROPERTY_FILE_FORMAT and a FITTYP of the
# same family agree.
_FAMILIES: Final[Mapping[str, str]] = MappingProxyType(
    {'PAC2002': 'MF 5.2', 'MF52': 'MF 5.2', 'MF61': 'MF 6.1', 'MF62': 'MF 6.2'})
_MF6_FORMATS: Final[frozenset[str]] = frozenset({'MF61', 'MF62'})
# FITTYP (MF-Tyre "Magic Formula version number"): 6 and 21 are MF 5.2.
_FITTYP_FORMATS: Final[Mapping[int, str]] = MappingProxyType(
    {6: 'MF52', 21: 'MF52', 61: 'MF61', 62: 'MF62'}
)

# Blocks in which every value must be a number.
_NUMERIC_BLOCKS: Final[frozenset[str]] = frozenset(
    {'DIMENSION', 'VERTICAL', 'OPERATING_CONDITIONS', 'STRUCTURAL', 'INERTIA', 'CONTACT_PATCH'})
_NUMERIC_BLOCK_SUFFIXES: Final[tuple[str, ...]] = ('_COEFFICIENTS', '_RANGE')

_COMMENT_CHARS: Final[str] = '$!'
_QUOTE_CHARS: Final[str] = "'\""
# No inf/nan: they are not numbers a supplier writes, float() would accept them.
_NUMBER_RE: Final = re.compile(r'[+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?')
_BLOCK_RE: Final = re.compile(r'\[\s*([A-Za-z][A-Za-z0-9_]*)\s*\]')
_KEY_RE: Final = re.compile(r'[A-Za-z_][A-Za-z0-9_]*')
_TABLE_HEADER_RE: Final = re.compile(r'\{([^{}]*)\}')
# A unit is one name; pint's expression parser would accept 'm,' or 'm=1'.
_UNIT_NAME_RE: Final = re.compile(r'[A-Za-z][A-Za-z_]*')



class _Required(enum.Enum):
    """Marker for "no default": a missing block or key is an error."""

    TOKEN = enum.auto()


_REQUIRED: Final = _Required.TOKEN


@dataclass(frozen=True)
class TireTable:
    """Rows of a table block such as [SHAPE] (``{radial width}``), as written."""

    columns: tuple[str, ...]  # names in the {...} header, empty if there is none
    rows: tuple[tuple[float, ...], ...]


@dataclass(frozen=True)
class TireProperties:
    """
    Contents of one .tir file, dimensional values in SI (see module doc).

    ``sections`` maps upper-case block names to upper-case keys and values
    (``float`` for numbers, ``str`` for quoted strings and bare words).
    """

    path: str  # file the data came from (or the source name given to parse_tir_text)
    file_format: str  # 'PAC2002', 'MF52', 'MF61' or 'MF62'
    sections: Mapping[str, Mapping[str, float | str]]
    tables: Mapping[str, TireTable] = field(default_factory=lambda: MappingProxyType({}))
    # load the pneumatic trail and the Fx arm are normalised by: 'mf-tyre' (FNOMIN) or
    # 'book' (FNOMIN LFZO); a choice of the tire group, not of the file
    # (vd_solvers.tire.magic_formula, module doc)
    aligning_normalisation: str = 'mf-tyre'

    def get(
        self, section: str, key: str, default: float | str | _Required = _REQUIRED
    ) -> float | str:
        """
        Value of ``key`` in block ``section`` (names case-insensitive).

        Without ``default`` a missing block or key raises :class:`DataError`.
        """
        block_name, key_name = section.upper(), key.upper()
        block = self.sections.get(block_name)
        if block is None:
            if isinstance(default, _Required):
                raise DataError(f'missing block [{block_name}]', file=self.path)
            return default
        if key_name not in block:
            if isinstance(default, _Required):
                raise DataError(
                    _missing_key_message(key_name, block_name), file=self.path, key=key_name
                )
            return default
        return block[key_name]

    def number(self, section: str, key: str, default: float | _Required = _REQUIRED) -> float:
        """Like :meth:`get`, but the value must be a number."""
        value = self.get(section, key, default)
        if isinstance(value, str):
            raise DataError(
                f'key {key.upper()!r} in block [{section.upper()}] is not a number: {value!r}',
                file=self.path,
                key=key.upper(),
            )
        return value

    @property
    def unloaded_radius(self) -> float:
        """Free tire radius R0, m."""
        return self.number('DIMENSION', 'UNLOADED_RADIUS')

    @property
    def fnomin(self) -> float:
        """Nominal wheel load Fz0 (before the LFZO scaling), N."""
        return self.number('VERTICAL', 'FNOMIN')

    @property
    def vertical_stiffness(self) -> float:
        """Vertical tire stiffness, N/m."""
        return self.number('VERTICAL', 'VERTICAL_STIFFNESS')


@dataclass(frozen=True)
class _Entry:
    """One ``KEY = value`` line before unit conversion."""

    value: float | str
    text: str  # value as written, for messages
    line: int


@dataclass
class _RawTable:
    """Table rows collected while reading one block."""

    columns: tuple[str, ...] = ()
    rows: list[tuple[float, ...]] = field(default_factory=list)


@dataclass
class _RawFile:
    """Result of the line-by-line pass."""

    blocks: dict[str, dict[str, _Entry]] = field(default_factory=dict)
    tables: dict[str, _RawTable] = field(default_factory=dict)


def read_tir(path: str | Path) -> TireProperties:
    """
    Read a .tir file; see the module doc for syntax, units and checks.

    Raises :class:`DataError` (or :class:`DataErrors` for several independent
    problems) naming the file, the key and, where known, the line.
    """
    file = Path(path)
    try:
        with file.open('rb') as stream:
            data = stream.read(MAX_FILE_BYTES + 1)
    except OSError as exc:
        raise DataError(
            f'cannot read tire property file: {exc.strerror or exc}', file=str(file)
        ) from exc
    if len(data) > MAX_FILE_BYTES:
        raise DataError(
            f'exceeds the limit of {MAX_FILE_BYTES >> 20} MiB per file', file=str(file)
        )
    note_read(file, data)
    try:
        text = data.decode('utf-8-sig')
    except UnicodeDecodeError:
        text = data.decode('latin-1')
    return parse_tir_text(text, str(file))


def parse_tir_text(text: str, source: str) -> TireProperties:
    """Parse the text of a .tir file; ``source`` names it in messages and ``path``."""
    raw = _read_lines(text, source)
    file_format = _file_format(raw.blocks['MODEL'], source) if 'MODEL' in raw.blocks else ''
    _raise_if_any(_check_structure(raw.blocks, source, file_format))
    factors = _unit_factors(raw.blocks['UNITS'], source)
    sections = {
        block: {key: _to_si(block, key, entry.value, factors) for key, entry in entries.items()}
        for block, entries in raw.blocks.items()
    }
    _raise_if_any(_check_physical(raw.blocks, sections, source, file_format))
    return TireProperties(
        path=source,
        file_format=file_format,
        sections=MappingProxyType(
            {block: MappingProxyType(values) for block, values in sections.items()}
        ),
        tables=MappingProxyType(
            {
                block: TireTable(table.columns, tuple(table.rows))
                for block, table in raw.tables.items()
            }
        ),
    )


def _read_lines(text: str, source: str) -> _RawFile:
    """Split ``text`` into blocks, keys and table rows; collect syntax errors."""
    raw = _RawFile()
    errors: list[DataError] = []
    block_lines: dict[str, int] = {}
    block: str | None = None
    # Keys of a repeated block go here so they are not reported a second time.
    entries: dict[str, _Entry] = {}
    for number, line in enumerate(text.splitlines(), start=1):
        code, quote_closed = _strip_comment(line)
        code = code.strip()
        if not quote_closed:
            errors.append(
                DataError(f'line {number}: unterminated quoted string in {code!r}', file=source)
            )
            continue
        if not code:
            continue
        if match := _BLOCK_RE.fullmatch(code):
            block = match[1].upper()
            if block in raw.blocks:
                errors.append(
                    DataError(
                        f'line {number}: block [{block}] repeats line {block_lines[block]}',
                        file=source,
                    )
                )
                entries = {}
            else:
                entries = raw.blocks[block] = {}
                block_lines[block] = number
            continue
        if block is None:
            errors.append(
                DataError(f'line {number}: {code!r} comes before the first [BLOCK]', file=source)
            )
        elif '=' in code:
            error = _read_key_line(code, number, block, entries, source)
            if error is not None:
                errors.append(error)
        else:
            error = _read_table_line(code, number, block, raw.tables, source)
            if error is not None:
                errors.append(error)
    _raise_if_any(errors)
    return raw


def _strip_comment(line: str) -> tuple[str, bool]:
    """Cut ``line`` at the first ``$`` or ``!`` outside quotes; False if a quote is left open."""
    quote: str | None = None
    for index, char in enumerate(line):
        if quote is not None:
            if char == quote:
                quote = None
        elif char in _QUOTE_CHARS:
            quote = char
        elif char in _COMMENT_CHARS:
            return line[:index], True
    return line, quote is None


def _read_key_line(
    code: str, number: int, block: str, entries: dict[str, _Entry], source: str
) -> DataError | None:
    """Store one ``KEY = value`` line in ``entries``; return the problem if any."""
    key_text, _, value_text = code.partition('=')
    key, value_text = key_text.strip().upper(), value_text.strip()
    if not _KEY_RE.fullmatch(key):
        return DataError(f'line {number}: {key_text.strip()!r} is not a key name', file=source)
    if not value_text:
        return DataError(
            f'line {number}: key {key!r} in block [{block}] has no value', file=source, key=key
        )
    if key in entries:
        return DataError(
            f'line {number}: key {key!r} repeats line {entries[key].line} in block [{block}]',
            file=source,
            key=key,
        )
    entries[key] = _Entry(_parse_value(value_text), value_text, number)
    return None


def _parse_value(text: str) -> float | str:
    """Return the value of ``text``: a number, a quoted string (quotes removed) or a bare word."""
    if len(text) >= 2 and text[0] in _QUOTE_CHARS and text[-1] == text[0]:
        return text[1:-1].strip()
    if _NUMBER_RE.fullmatch(text):
        return float(text)
    return text


def _read_table_line(
    code: str, number: int, block: str, tables: dict[str, _RawTable], source: str
) -> DataError | None:
    """Store a ``{column header}`` or a row of numbers of a table block."""
    table = tables.setdefault(block, _RawTable())
    if match := _TABLE_HEADER_RE.fullmatch(code):
        table.columns = tuple(match[1].split())
        return None
    cells = code.replace(',', ' ').split()
    if not all(_NUMBER_RE.fullmatch(cell) for cell in cells):
        return DataError(
            f'line {number}: cannot read {code!r} in block [{block}]: '
            'expected KEY = value, a {column header} or a row of numbers',
            file=source,
        )
    width = (
        len(table.columns) if table.columns else len(table.rows[0]) if table.rows else len(cells)
    )
    if len(cells) != width:
        return DataError(
            f'line {number}: table row in block [{block}] has {len(cells)} values, '
            f'expected {width}',
            file=source,
        )
    table.rows.append(tuple(float(cell) for cell in cells))
    return None


def _check_structure(
    blocks: Mapping[str, Mapping[str, _Entry]], source: str, file_format: str
) -> list[DataError]:
    """Missing blocks or keys, unknown 6.x coefficients, non-numbers where numbers are needed."""
    mf6 = file_format in _MF6_FORMATS
    required_blocks = REQUIRED_BLOCKS + (MF6_REQUIRED_BLOCKS if mf6 else ())
    errors = [
        DataError(f'missing block [{name}]' + (f' (needed by {_FAMILIES[file_format]})'
                                                 if name in MF6_REQUIRED_BLOCKS else ''),
                  file=source)
        for name in required_blocks
        if name not in blocks
    ]
    required_keys = [REQUIRED_KEYS, MF6_REQUIRED_KEYS] if mf6 else [REQUIRED_KEYS]
    for table in required_keys:
        for block, keys in table.items():
            if block in blocks:
                errors.extend(
                    DataError(_missing_key_message(key, block), file=source, key=key)
                    for key in keys
                    if key not in blocks[block]
                )
    if mf6:
        for block, known in MF6_COEFFICIENTS.items():
            errors.extend(
                DataError(
                    f'line {entry.line}: {key!r} is no {_FAMILIES[file_format]} coefficient of '
                    f'block [{block}] (a misspelt coefficient would silently be 0)',
                    file=source, key=key)
                for key, entry in blocks.get(block, {}).items()
                if key not in known
            )
    for block, entries in blocks.items():
        numeric_block = block in _NUMERIC_BLOCKS or block.endswith(_NUMERIC_BLOCK_SUFFIXES)
        for key, entry in entries.items():
            needs_number = numeric_block or (key in DIMENSIONAL_KEYS and block != 'UNITS')
            if needs_number and isinstance(entry.value, str):
                errors.append(
                    DataError(
                        f'line {entry.line}: key {key!r} in block [{block}] '
                        f'is not a number: {entry.text}',
                        file=source,
                        key=key,
                    )
                )
    return errors


def _missing_key_message(key: str, block: str) -> str:
    return f'key {key!r} missing in block [{block}]'


def _file_format(model: Mapping[str, _Entry], source: str) -> str:
    """
    Version from PROPERTY_FILE_FORMAT, or from FITTYP where that is absent or generic.

    Where both name a version they must agree (MF 5.2 and PAC2002 are one family).
    """
    declared = model.get('PROPERTY_FILE_FORMAT')
    if declared is not None:
        name = str(declared.value).upper()
        if name in _FORMAT_NAMES:
            named = _FORMAT_NAMES[name]
            fittyp = model.get('FITTYP')
            if fittyp is not None:
                by_fittyp = _fittyp_format(fittyp, source)
                if _FAMILIES[by_fittyp] != _FAMILIES[named]:
                    raise DataError(
                        f'line {fittyp.line}: FITTYP {fittyp.text} ({_FAMILIES[by_fittyp]}) '
                        f'contradicts PROPERTY_FILE_FORMAT {declared.value!r} of line '
                        f'{declared.line} ({_FAMILIES[named]})',
                        file=source,
                        key='FITTYP',
                    )
            return named
        if name not in _GENERIC_FORMAT_NAMES:
            known = ', '.join(repr(n) for n in sorted({*_FORMAT_NAMES, *_GENERIC_FORMAT_NAMES}))
            raise DataError(
                f'line {declared.line}: unknown PROPERTY_FILE_FORMAT {declared.value!r} '
                f'(known: {known})',
                file=source,
                key='PROPERTY_FILE_FORMAT',
            )
    fittyp = model.get('FITTYP')
    if fittyp is None:
        if declared is None:
            raise DataError(
                'block [MODEL] gives neither PROPERTY_FILE_FORMAT nor FITTYP', file=source
            )
        raise DataError(
            f'line {declared.line}: PROPERTY_FILE_FORMAT {declared.value!r} '
            'needs FITTYP in block [MODEL]',
            file=source,
            key='FITTYP',
        )
    return _fittyp_format(fittyp, source)


def _fittyp_format(fittyp: _Entry, source: str) -> str:
    """Version named by FITTYP, or the error naming its line."""
    value = fittyp.value
    if isinstance(value, float) and value.is_integer() and int(value) in _FITTYP_FORMATS:
        return _FITTYP_FORMATS[int(value)]
    known = ', '.join(str(n) for n in _FITTYP_FORMATS)
    raise DataError(
        f'line {fittyp.line}: unknown FITTYP {fittyp.text} (known: {known})',
        file=source,
        key='FITTYP',
    )


def _unit_factors(units: Mapping[str, _Entry], source: str) -> dict[str, float]:
    """SI factor of each [UNITS] quantity; an absent entry means the SI unit."""
    factors: dict[str, float] = {}
    errors: list[DataError] = []
    for quantity, si_unit in _SI_UNITS.items():
        entry = units.get(quantity)
        if entry is None:
            factors[quantity] = 1.0
            continue
        factor = _unit_factor(quantity, str(entry.value), si_unit)
        if factor is None:
            errors.append(
                DataError(
                    f'line {entry.line}: {entry.text} is not a known unit of '
                    f'{_QUANTITY_WORDS[quantity]}',
                    file=source,
                    key=quantity,
                )
            )
        else:
            factors[quantity] = factor
    _raise_if_any(errors)
    return factors


def _unit_factor(quantity: str, name: str, si_unit: str) -> float | None:
    """Factor from unit ``name`` to ``si_unit``, None if ``name`` is no unit of that kind."""
    if not _UNIT_NAME_RE.fullmatch(name):
        return None
    from pint.errors import UndefinedUnitError

    units = ureg()
    # Exact spelling first: 'N' is newton, while 'n' is not a unit.
    for candidate in dict.fromkeys((name, name.lower())):
        try:
            unit = units.Unit(candidate)
        except UndefinedUnitError:
            continue
        if quantity == 'ANGLE' and str(unit) not in _ANGLE_UNITS:
            continue
        if unit.is_compatible_with(si_unit):
            return float(units.Quantity(1.0, unit).to(si_unit).magnitude)
    return None


def _to_si(block: str, key: str, value: float | str, factors: Mapping[str, float]) -> float | str:
    """``value`` in SI if ``key`` carries a unit (structure checks made it a number)."""
    if block == 'UNITS' or key not in DIMENSIONAL_KEYS or isinstance(value, str):
        return value
    factor = 1.0
    for quantity, exponent in DIMENSIONAL_KEYS[key]:
        factor *= factors[quantity] ** exponent
    return value * factor


#: (block, key) that must be > 0: the loads, lengths and scaling factors the Magic
#: Formula divides by or normalises with (Pacejka 4.E1: dfz = (Fz - Fz0') / Fz0'; 4.E2b:
#: dpi = (p - p0) / p0), and the pressures and stiffnesses a tire has where a file gives them.
POSITIVE_KEYS: Final[tuple[tuple[str, str], ...]] = (
    ('VERTICAL', 'FNOMIN'),
    ('DIMENSION', 'UNLOADED_RADIUS'),
    ('SCALING_COEFFICIENTS', 'LFZO'),
    ('VERTICAL', 'VERTICAL_STIFFNESS'),
    ('OPERATING_CONDITIONS', 'NOMPRES'),
    ('OPERATING_CONDITIONS', 'INFLPRES'),
    ('TIRE_CONDITIONS', 'IP_NOM'),
    ('TIRE_CONDITIONS', 'IP'),
)
#: (block, key) that must not be 0: B = K / (C D) divides by the shape factors C and the
#: peak factors D (and their scaling factors), and K_y by PKY2 (Pacejka 4.E25).
NONZERO_KEYS: Final[tuple[tuple[str, str], ...]] = (
    ('LATERAL_COEFFICIENTS', 'PCY1'),
    ('LATERAL_COEFFICIENTS', 'PDY1'),
    ('LATERAL_COEFFICIENTS', 'PKY2'),
    ('LONGITUDINAL_COEFFICIENTS', 'PCX1'),
    ('LONGITUDINAL_COEFFICIENTS', 'PDX1'),
    ('SCALING_COEFFICIENTS', 'LCY'),
    ('SCALING_COEFFICIENTS', 'LMUY'),
    ('SCALING_COEFFICIENTS', 'LCX'),
    ('SCALING_COEFFICIENTS', 'LMUX'),
)
#: (block, key, lowest, highest) in SI of the dimensions a road tire has: outside, the
#: file's [UNITS] are likely wrong (LENGTH = 'mm' for values in metres reads a 0.3 mm tire)
DIMENSION_RANGES: Final[tuple[tuple[str, str, float, float], ...]] = (
    ('DIMENSION', 'UNLOADED_RADIUS', 0.1, 2.0),
    ('DIMENSION', 'WIDTH', 0.05, 1.5),
    ('DIMENSION', 'RIM_RADIUS', 0.05, 1.5),
    ('DIMENSION', 'RIM_WIDTH', 0.03, 1.5),
)
#: Validity ranges (block, smallest key, largest key): the smallest must lie below the largest.
RANGES: Final[tuple[tuple[str, str, str], ...]] = (
    ('INFLATION_PRESSURE_RANGE', 'PRESMIN', 'PRESMAX'),
    ('VERTICAL_FORCE_RANGE', 'FZMIN', 'FZMAX'),
    ('LONG_SLIP_RANGE', 'KPUMIN', 'KPUMAX'),
    ('SLIP_ANGLE_RANGE', 'ALPMIN', 'ALPMAX'),
    ('INCLINATION_ANGLE_RANGE', 'CAMMIN', 'CAMMAX'),
)
#: Where each version keeps its inflation pressure (block, pressure, nominal pressure).
PRESSURE_KEYS: Final[tuple[tuple[str, str, str], ...]] = (
    ('OPERATING_CONDITIONS', 'INFLPRES', 'NOMPRES'),
    ('TIRE_CONDITIONS', 'IP', 'IP_NOM'),
)
#: USE_MODE: its last digit selects the forces (1 Fx, 2 Fy/Mz, 3 uncombined, 4 combined,
#: 5 combined with turn slip, MF-Tyre 6.x and Adams PAC2002); the digits before it pick
#: transient and contact models vd does not use.
USE_MODES: Final[tuple[int, ...]] = (1, 2, 3, 4, 5)
TURN_SLIP_MODE: Final[int] = 5
#: Turn-slip coefficients the equations divide by (Pacejka 4.88: C_Hyp D_Hyp; 4.94:
#: sin(pi/2 C_Drp)), so USE_MODE 5 needs them != 0.
TURN_SLIP_DIVISORS: Final[tuple[str, ...]] = ('PHYP1', 'PHYP2', 'QDRP1')


def check_values(
    sections: Mapping[str, Mapping[str, float | str]],
    source: str,
    where: Mapping[tuple[str, str], tuple[str, str]] | None = None,
    file_format: str = '',
) -> list[DataError]:
    """
    Return the problems of values no tire can have.

    These are non-finite numbers (``1e999``), a non-positive nominal load, free radius,
    LFZO, pressure or vertical stiffness, a zero divisor of the Magic Formula, a validity
    range whose minimum is not below its maximum, an inflation pressure outside
    [PRESMIN, PRESMAX], a load-deflection curve without a real Q_FZ1
    ((C_z R0 / FNOMIN)^2 < 4 Q_FZ2), a USE_MODE vd does not evaluate, and tire dimensions
    outside :data:`DIMENSION_RANGES` (a file whose [UNITS] do not match its numbers).

    ``where`` gives the ``line N: `` prefix and the text as written of a (block, key)
    read from a file; the same check runs on the values of a tire group after
    master-file overrides (``front_tire.tir.OPERATING_CONDITIONS.INFLPRES: 5 bar``).
    ``file_format`` ('PAC2002', 'MF52', 'MF61', 'MF62') selects the version's rules.
    """
    where = where or {}
    errors = []

    def at(block: str, key: str, value: float | str) -> tuple[str, str]:
        return where.get((block, key), ('', f'{value:g}' if isinstance(value, float)
                                         else repr(value)))

    def bad(block: str, key: str, rule: str, value: float | str) -> None:
        line, text = at(block, key, value)
        errors.append(DataError(f'{line}key {key!r} in block [{block}] {rule}, found {text}',
                                file=source, key=key))

    def number(block: str, key: str) -> float | None:
        value = sections.get(block, {}).get(key)
        return value if isinstance(value, float) and math.isfinite(value) else None

    for block, entries in sections.items():
        for key, value in entries.items():
            if isinstance(value, float) and not math.isfinite(value):
                bad(block, key, 'must be a finite number', value)
    for block, key in POSITIVE_KEYS:
        given = number(block, key)
        if given is not None and given <= 0.0:
            bad(block, key, 'must be > 0', given)
    for block, key, lowest, highest in DIMENSION_RANGES:
        given = number(block, key)
        if given is not None and given > 0.0 and not lowest <= given <= highest:
            bad(block, key, f'must lie within {lowest:g}..{highest:g} m for a road tire, here '
                f'{given:g} m (are the [UNITS] right, e.g. LENGTH?)', given)
    for block, key in NONZERO_KEYS:
        divisor = sections.get(block, {}).get(key)
        if isinstance(divisor, float) and divisor == 0.0:
            bad(block, key, 'must not be 0 (the Magic Formula divides by it)', divisor)
    for block, low_key, high_key in RANGES:
        low, high = number(block, low_key), number(block, high_key)
        if low is not None and high is not None and not low < high:
            line, text = at(block, high_key, high)
            errors.append(DataError(
                f'{line}key {high_key!r} in block [{block}] must be > {low_key} '
                f'({low:g}), found {text}', file=source, key=high_key))
    errors.extend(_pressure_range(source, at, number))
    errors.extend(_vertical_curve(source, at, number))
    errors.extend(_use_mode(sections, source, at, file_format))
    return errors


_Sections = Mapping[str, Mapping[str, float | str]]
_At = Callable[[str, str, float | str], tuple[str, str]]
_Number = Callable[[str, str], float | None]


def _pressure_range(source: str, at: _At, number: _Number) -> list[DataError]:
    """Check that the inflation pressure lies in the file's [PRESMIN, PRESMAX]."""
    low = number('INFLATION_PRESSURE_RANGE', 'PRESMIN')
    high = number('INFLATION_PRESSURE_RANGE', 'PRESMAX')
    if low is not None and high is not None and low >= high:
        return []  # the range itself is reported
    for block, key, _ in PRESSURE_KEYS:
        pressure = number(block, key)
        if pressure is None or low is None or high is None or low <= pressure <= high:
            continue
        line, text = at(block, key, pressure)
        return [DataError(
            f'{line}key {key!r} in block [{block}] must lie in the range the file is valid '
            f'for, PRESMIN..PRESMAX = {low:g}..{high:g} Pa, found {text}',
            file=source, key=key)]
    return []


def _vertical_curve(source: str, at: _At, number: _Number) -> list[DataError]:
    """Check that Q_FZ1 = sqrt((C_z R0 / FNOMIN)^2 - 4 Q_FZ2) is real (Besselink 2010, eq. 4)."""
    q_fz2 = number('VERTICAL', 'Q_FZ2')
    stiffness = number('VERTICAL', 'VERTICAL_STIFFNESS')
    radius = number('DIMENSION', 'UNLOADED_RADIUS')
    load = number('VERTICAL', 'FNOMIN')
    if None in (q_fz2, stiffness, radius, load) or number('VERTICAL', 'Q_FZ1') is not None:
        return []
    assert q_fz2 is not None and stiffness is not None and radius is not None
    assert load is not None
    linear = stiffness * radius / load
    if linear * linear >= 4.0 * q_fz2 or load <= 0.0:
        return []
    line, text = at('VERTICAL', 'Q_FZ2', q_fz2)
    return [DataError(
        f'{line}key {"Q_FZ2"!r} in block [VERTICAL] must be at most (VERTICAL_STIFFNESS '
        f'UNLOADED_RADIUS / FNOMIN)^2 / 4 = {linear * linear / 4.0:g} (Q_FZ1 = sqrt((C_z R0 / '
        f'FNOMIN)^2 - 4 Q_FZ2)), found {text}', file=source, key='Q_FZ2')]


def _use_mode(sections: _Sections, source: str, at: _At, file_format: str) -> list[DataError]:
    """Check that USE_MODE ends in a digit vd evaluates; turn slip needs an MF 6.x file."""
    value = sections.get('MODEL', {}).get('USE_MODE')
    if value is None:
        return []
    line, text = at('MODEL', 'USE_MODE', value)
    if not isinstance(value, float) or not value.is_integer() or value < 0:
        return [DataError(f'{line}key {"USE_MODE"!r} in block [MODEL] must be a whole number '
                          f'ending in one of {", ".join(map(str, USE_MODES))}, found {text}',
                          file=source, key='USE_MODE')]
    digit = int(value) % 10
    if digit not in USE_MODES:
        return [DataError(
            f'{line}key {"USE_MODE"!r} in block [MODEL] must end in one of '
            f'{", ".join(map(str, USE_MODES))} (1 Fx, 2 Fy and Mz, 3 uncombined, 4 combined, '
            f'5 combined with turn slip), found {text}', file=source, key='USE_MODE')]
    if digit != TURN_SLIP_MODE:
        return []
    if file_format and file_format not in _MF6_FORMATS:
        return [DataError(f'{line}key {"USE_MODE"!r} in block [MODEL] asks for turn slip (5), '
                          f'which needs an MF 6.1 / 6.2 file, found {text} in a {file_format} '
                          'file', file=source, key='USE_MODE')]
    turn = sections.get('TURNSLIP_COEFFICIENTS', {})
    missing = [key for key in TURN_SLIP_DIVISORS if not turn.get(key)]
    if missing:
        return [DataError(f'{line}key {"USE_MODE"!r} in block [MODEL] asks for turn slip (5), '
                          f'which needs {", ".join(missing)} != 0 in block '
                          '[TURNSLIP_COEFFICIENTS]', file=source, key='USE_MODE')]
    return []


def _check_physical(
    blocks: Mapping[str, Mapping[str, _Entry]],
    sections: Mapping[str, Mapping[str, float | str]],
    source: str,
    file_format: str,
) -> list[DataError]:
    where = {(block, key): (f'line {entry.line}: ', entry.text)
             for block, entries in blocks.items() for key, entry in entries.items()}
    return check_values(sections, source, where, file_format)


def _raise_if_any(errors: list[DataError]) -> None:
    """Raise the one problem found, or all of them together."""
    if len(errors) == 1:
        raise errors[0]
    if errors:
        raise DataErrors(errors)
