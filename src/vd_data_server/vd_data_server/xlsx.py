# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Excel interop: the overview and group tabs as a workbook, and a workbook back to a master file.

Sheets written by :func:`export_workbook`:

``Study``
    name, description, vehicle, data_root of the master file (column A the field,
    column B its value).
``Overview``
    the thesis' overview tab (Fig. 2.3.1): input groups as rows, column B the
    ``defaults`` variant, then one column per configuration with the variant it
    uses (green fill UNCHANGED, red MODIFIED), the last column SAME/DIFFERS
    (yellow where the configurations differ); below the groups the rows
    ``flexible`` (``off``, ``on`` or the list of components) and ``description``.
``Overrides``
    one row per override: configuration, key (``GROUP.KEY``), value, unit.
one sheet per input group
    every value of every configuration in the unit of its data file (red where it
    differs from the data file, the key yellow where the configurations differ).

:func:`import_workbook` reads ``Study``, ``Overview`` and ``Overrides`` (the group
sheets are results, not input) into a master file; every bad cell is reported as
``Sheet!CELL: message``. Comments of a master file do not travel through a workbook.
"""
from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path
import re
from typing import Any
import zipfile

from openpyxl import Workbook, load_workbook
from openpyxl.styles import Alignment, Font, PatternFill
from openpyxl.utils import get_column_letter
from ruamel.yaml.comments import CommentedMap, CommentedSeq

from vd_data_server.overview import study_state

from . import schema
from .errors import DataError, DataErrors
from .masteredit import write_master
from .shape import PLAIN_NAME as _NAME  # the one rule for configuration and variant names
from .study import NOT_USED, Study

#: fills matching the workbench page (workbench.css)
GREEN = PatternFill('solid', fgColor='B9F2B0')
RED = PatternFill('solid', fgColor='F7A3A3')
YELLOW = PatternFill('solid', fgColor='FFE27A')
GREY = PatternFill('solid', fgColor='EEEEEE')
BOLD = Font(bold=True)
STUDY_FIELDS = ('name', 'description', 'vehicle', 'data_root')
OVERVIEW_HEAD = ('input group', 'defaults')
CONSISTENCY_HEAD = 'all configurations'
OVERRIDE_HEAD = ('configuration', 'key', 'value', 'unit')
_QUANTITY = re.compile(r'^\s*([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)\s+(\S.*?)\s*$')
#: largest workbook read, bytes (a study of 50 configurations is < 200 kB)
MAX_BYTES = 20 * 1024 * 1024
#: largest workbook unpacked (all its XML parts), bytes
MAX_UNPACKED = 200 * 1024 * 1024
#: bytes of an XML part read at a time when it is searched for a document type
CHUNK_BYTES = 1 << 20
#: rows and columns of an input sheet read; a cell beyond is refused
MAX_ROWS = 2000
MAX_COLUMNS = 512
#: the sheets a workbook is imported from (the group sheets are results)
INPUT_SHEETS = ('Study', 'Overview', 'Overrides')


def _split(raw: Any) -> tuple[Any, str]:
    """Split an override into (value cell, unit cell); a number only where it reads back."""
    if isinstance(raw, bool) or not isinstance(raw, (str, int, float)):
        return str(raw), ''
    if not isinstance(raw, str):
        return raw, ''
    match = _QUANTITY.match(raw)
    if not match or f'{match.group(1)} {match.group(2)}' != raw:
        return raw, ''
    number, unit = match.group(1), match.group(2)
    for kind in (int, float):
        try:
            parsed = kind(number)
        except ValueError:
            continue
        if _number_text(parsed) == number:
            return parsed, unit
    return number, unit


def _number_text(value: int | float) -> str:
    return str(value) if isinstance(value, int) else repr(value)


def _head(sheet: Any, row: int, labels: list[str]) -> None:
    for col, label in enumerate(labels, 1):
        cell = sheet.cell(row, col, label)
        cell.font = BOLD
        cell.fill = GREY


def _widths(sheet: Any, first: int = 24, rest: int = 16) -> None:
    for col in range(1, sheet.max_column + 1):
        sheet.column_dimensions[get_column_letter(col)].width = first if col == 1 else rest


def export_workbook(study: Study, raw: Mapping[str, Any], out: Path) -> Path:
    """Write the workbook of ``study`` (``raw``: the master file as parsed) to ``out``."""
    book = Workbook()
    info = book.active
    info.title = 'Study'
    meta = raw.get('study') or {}
    _head(info, 1, ['field', 'value'])
    for row, key in enumerate(STUDY_FIELDS, 2):
        info.cell(row, 1, key).font = BOLD
        if key in meta:
            info.cell(row, 2, str(meta[key]))
    info.cell(len(STUDY_FIELDS) + 3, 1, 'master file').font = BOLD
    info.cell(len(STUDY_FIELDS) + 3, 2, str(study.master.path))
    _widths(info, 16, 90)

    names = study.configuration_names
    defaults = raw.get('defaults') or {}
    view = book.create_sheet('Overview')
    _head(view, 1, [*OVERVIEW_HEAD, *names, CONSISTENCY_HEAD])
    row = 2
    for row, group in enumerate(study.groups, 2):
        view.cell(row, 1, group).font = BOLD
        if group in defaults:
            view.cell(row, 2, str(defaults[group]))
        consistency = 'SAME'
        for col, name in enumerate(names, 3):
            entry = study.status_of(name, group)
            consistency = entry.consistency
            cell = view.cell(row, col, entry.variant if entry.variant != NOT_USED else None)
            cell.fill = GREY if entry.variant == NOT_USED else (
                RED if entry.state == 'MODIFIED' else GREEN)
            cell.alignment = Alignment(horizontal='center')
        cell = view.cell(row, len(names) + 3, consistency)
        if consistency == 'DIFFERS':
            cell.fill = YELLOW
    switches = study.flexible_switches()
    flex_row, desc_row = row + 1, row + 2
    view.cell(flex_row, 1, 'flexible').font = BOLD
    view.cell(desc_row, 1, 'description').font = BOLD
    for col, name in enumerate(names, 3):
        on, components = switches[name]
        view.cell(flex_row, col, ', '.join(components) if components else ('on' if on else 'off'))
        view.cell(desc_row, col, study.master.configurations[name].description or None)
    same = len(set(switches.values())) == 1
    view.cell(flex_row, len(names) + 3, 'SAME' if same else 'DIFFERS').fill = \
        YELLOW if not same else PatternFill()
    view.freeze_panes = 'C2'
    _widths(view)

    overrides = book.create_sheet('Overrides')
    _head(overrides, 1, list(OVERRIDE_HEAD))
    row = 2
    for name in names:
        for key, value in study.master.configurations[name].overrides.items():
            number, unit = _split(value)
            overrides.cell(row, 1, name)
            overrides.cell(row, 2, str(key))
            overrides.cell(row, 3, number)
            overrides.cell(row, 4, unit or None)
            for col in range(1, 5):
                overrides.cell(row, col).fill = RED
            row += 1
    _widths(overrides, 16, 40)

    state = study_state(study)
    for group in study.groups:
        sheet = book.create_sheet(group[:31])
        _head(sheet, 1, ['key', *names, 'unit', CONSISTENCY_HEAD])
        for row, entry in enumerate(state['groups'][group]['rows'], 2):
            sheet.cell(row, 1, entry['key'])
            unit = ''
            for col, name in enumerate(names, 2):
                value = entry['cells'].get(name)
                if value is None:
                    sheet.cell(row, col).fill = GREY
                    continue
                cell = sheet.cell(row, col, value['text'])
                unit = unit or value['unit']
                if value['modified']:
                    cell.fill = RED
            sheet.cell(row, len(names) + 2, unit or None)
            sheet.cell(row, len(names) + 3, entry['consistency'])
            if entry['consistency'] == 'DIFFERS':
                sheet.cell(row, 1).fill = YELLOW
                sheet.cell(row, len(names) + 3).fill = YELLOW
        sheet.freeze_panes = 'B2'
        _widths(sheet, 40, 16)
    out.parent.mkdir(parents=True, exist_ok=True)
    tmp = out.with_name(f'.{out.name}.tmp')
    book.save(tmp)
    tmp.replace(out)
    return out


class _Cells:
    """Collects ``Sheet!CELL: message`` problems."""

    def __init__(self, book: str) -> None:
        self.book = book
        self.errors: list[DataError] = []

    def add(self, sheet: str, ref: str, message: str) -> None:
        self.errors.append(DataError(message, file=self.book, key=f'{sheet}!{ref}'))

    def raise_if_any(self) -> None:
        if self.errors:
            raise self.errors[0] if len(self.errors) == 1 else DataErrors(self.errors)


def _text(value: Any) -> str:
    if value is None:
        return ''
    if isinstance(value, float) and value.is_integer():
        return str(int(value))
    return str(value).strip()


class _Sheet:
    """
    One sheet's values by position (row, column from 1), read whole and bounded.

    Positions, not openpyxl's cells: a read-only sheet gives an empty cell no coordinate,
    and a row with gaps or a sheet without a ``<dimension>`` has rows of any length.
    """

    def __init__(self, name: str, rows: list[tuple[Any, ...]]) -> None:
        self.name = name
        self.rows = rows

    def value(self, row: int, col: int) -> Any:
        values = self.rows[row - 1] if row <= len(self.rows) else ()
        return values[col - 1] if col <= len(values) else None

    def text(self, row: int, col: int) -> str:
        return _text(self.value(row, col))

    def width(self, row: int) -> int:
        values = self.rows[row - 1] if row <= len(self.rows) else ()
        return max((i + 1 for i, v in enumerate(values) if v is not None), default=0)

    @staticmethod
    def ref(row: int, col: int) -> str:
        return f'{get_column_letter(col)}{row}'


def _check_package(path: Path, display: str) -> None:
    """
    Refuse a workbook whose XML declares a DOCTYPE or entities, or that unpacks too large.

    openpyxl parses the package's XML with the standard library; a document type with
    entity definitions ("billion laughs", external entities) is refused before it is
    parsed, as defusedxml would. Spreadsheet programs never write one.
    """
    try:
        with zipfile.ZipFile(path) as package:
            members = package.infolist()
            if sum(m.file_size for m in members) > MAX_UNPACKED:
                raise DataError(f'unpacks to more than the limit of {MAX_UNPACKED >> 20} MiB',
                                file=display)
            for member in members:
                if not member.filename.endswith(('.xml', '.rels')):
                    continue
                if _declares_entities(package, member):
                    raise DataError(f'{member.filename}: a document type or entity '
                                    'definition (<!DOCTYPE, <!ENTITY) is refused: a workbook '
                                    'has none', file=display)
    except (zipfile.BadZipFile, OSError, EOFError, ValueError) as err:
        raise DataError(f'not an xlsx workbook ({type(err).__name__}: {err})',
                        file=display) from None


def _declares_entities(package: zipfile.ZipFile, member: zipfile.ZipInfo) -> bool:
    """Tell whether the XML part holds ``<!DOCTYPE`` or ``<!ENTITY`` (read in chunks)."""
    tail = b''
    with package.open(member) as stream:
        while chunk := stream.read(CHUNK_BYTES):
            text = tail + chunk
            if b'<!DOCTYPE' in text or b'<!ENTITY' in text:
                return True
            tail = text[-8:]
    return False


def _read_sheets(path: Path, display: str, cells: _Cells) -> dict[str, _Sheet] | None:
    """Read the three input sheets; a formula without a computed value is a bad cell."""
    try:
        if path.stat().st_size > MAX_BYTES:
            raise DataError(f'exceeds the limit of {MAX_BYTES >> 20} MiB per workbook',
                            file=display)
        _check_package(path, display)
        values = load_workbook(path, read_only=True, data_only=True)
        formulas = load_workbook(path, read_only=True, data_only=False)
        sheets: dict[str, _Sheet] = {}
        for name in INPUT_SHEETS:
            if name not in values.sheetnames:
                cells.add(name, 'A1', f"sheet '{name}' missing (the workbook needs the sheets "
                          'Study, Overview and Overrides, as vd export xlsx writes them)')
                continue
            sheets[name] = _bounded(name, values[name], cells)
            # the same cells again: their limits are reported once, above
            _formulas(sheets[name], _bounded(name, formulas[name], _Cells(display)), cells)
    except DataError:
        raise
    except FileNotFoundError:
        raise DataError('file not found', file=display) from None
    except Exception as err:  # noqa: BLE001 - openpyxl raises many kinds on a non-workbook
        raise DataError(f'not an xlsx workbook ({type(err).__name__}: {err})',
                        file=display) from None
    return None if cells.errors else sheets


def _bounded(name: str, sheet: Any, cells: _Cells) -> _Sheet:
    """Read the sheet's rows up to :data:`MAX_ROWS` x :data:`MAX_COLUMNS`; beyond: a bad cell."""
    # the cells themselves, not the <dimension> the file declares (absent, or wrong): each
    # row is as long as its last cell (at most Excel's 16384 columns)
    sheet.reset_dimensions()
    rows = [tuple(r) for r in sheet.iter_rows(min_row=1, max_row=MAX_ROWS + 1,
                                              values_only=True)]
    if len(rows) > MAX_ROWS and any(v is not None for v in rows[MAX_ROWS]):
        cells.add(name, _Sheet.ref(MAX_ROWS + 1, 1), f'the sheet has more than the limit of '
                  f'{MAX_ROWS} rows')
    for r, row in enumerate(rows[:MAX_ROWS], 1):
        beyond = [c for c, v in enumerate(row[MAX_COLUMNS:], MAX_COLUMNS + 1) if v is not None]
        if beyond:
            cells.add(name, _Sheet.ref(r, beyond[0]), f'the sheet has more than the limit of '
                      f'{MAX_COLUMNS} columns')
            break
    return _Sheet(name, [row[:MAX_COLUMNS] for row in rows[:MAX_ROWS]])


def _formulas(values: _Sheet, formulas: _Sheet, cells: _Cells) -> None:
    """Refuse a formula whose result the file does not hold (never read as an empty cell)."""
    for r, row in enumerate(formulas.rows, 1):
        for c, formula in enumerate(row, 1):
            if isinstance(formula, str) and formula.startswith('=') and \
                    values.value(r, c) is None:
                cells.add(values.name, _Sheet.ref(r, c), f'formula {formula[:60]} has no '
                          'computed value in the file (open and save the workbook in a '
                          'spreadsheet program, or type the value)')


def read_workbook(path: Path, target: Path) -> dict[str, Any]:
    """
    Read the master file a workbook describes (a plain mapping, in master-file order).

    ``target`` is where the master file will be written: its data root decides which
    variants exist. Raises DataError with every bad cell as ``Sheet!CELL: message``.
    """
    display = str(path)
    cells = _Cells(display)
    sheets = _read_sheets(path, display, cells)
    cells.raise_if_any()
    assert sheets is not None
    study_sheet, view, over = (sheets[n] for n in INPUT_SHEETS)
    study: dict[str, Any] = {}
    for r in range(2, len(study_sheet.rows) + 1):
        if study_sheet.value(r, 1) is None:
            continue
        key, value = study_sheet.text(r, 1), study_sheet.text(r, 2)
        if key == 'master file':
            continue
        if key not in STUDY_FIELDS:
            cells.add('Study', _Sheet.ref(r, 1), f"unknown field '{key}' (expected one of: "
                      f"{', '.join(STUDY_FIELDS)})")
        elif value:
            study[key] = value
    for key in ('name', 'vehicle'):
        if key not in study:
            cells.add('Study', 'B2' if key == 'name' else 'B4', f"missing the study's {key}")
    if not view.rows:
        cells.add('Overview', 'A1', 'the sheet is empty')
        cells.raise_if_any()
    head = [view.text(1, c) for c in range(1, view.width(1) + 1)]
    if tuple(head[:2]) != OVERVIEW_HEAD:
        cells.add('Overview', 'A1', f"expected the headings '{OVERVIEW_HEAD[0]}', "
                  f"'{OVERVIEW_HEAD[1]}' in A1:B1, found {head[:2]}")
        cells.raise_if_any()
    names: list[tuple[int, str]] = []
    for col, name in enumerate(head[2:], 3):
        if not name or name == CONSISTENCY_HEAD:
            break
        ref = _Sheet.ref(1, col)
        if not _NAME.match(name):
            cells.add('Overview', ref, f"configuration name '{name}': names may hold letters, "
                      "digits, '_', '-' and '.'")
        elif name in {n for _, n in names}:
            cells.add('Overview', ref, f"configuration '{name}' appears twice")
        else:
            names.append((col, name))
    if not names:
        cells.add('Overview', 'C1', 'no configuration columns')
    root = _data_root(target, study)
    vehicle = root / study.get('vehicle', '') if root else None
    known = schema.all_group_names()
    defaults: dict[str, str] = {}
    variants: dict[str, dict[str, str]] = {n: {} for _, n in names}
    flexible: dict[str, str] = {}
    descriptions: dict[str, str] = {}
    refs: dict[tuple[str, str], str] = {}
    for r in range(2, len(view.rows) + 1):
        label = view.text(r, 1)
        if not label:
            continue
        if label == 'flexible':
            for col, name in names:
                flexible[name] = view.text(r, col)
                refs[(name, 'flexible')] = refs[(name, 'flexible_components')] = \
                    _Sheet.ref(r, col)
            continue
        if label == 'description':
            for col, name in names:
                descriptions[name] = view.text(r, col)
            continue
        if label not in known:
            cells.add('Overview', _Sheet.ref(r, 1), f"unknown input group '{label}' (expected "
                      f"one of: {', '.join(known)})")
            continue
        available = sorted(p.stem for p in (vehicle / label).glob('*.yaml')) \
            if vehicle is not None and (vehicle / label).is_dir() else None

        def check(ref: str, variant: str, group: str = label,
                  available: list[str] | None = available) -> bool:
            if not _NAME.match(variant):
                cells.add('Overview', ref, f"variant must be a plain name, found '{variant}'")
                return False
            if available is not None and variant not in available:
                cells.add('Overview', ref, f"unknown variant '{variant}' for group "
                          f"'{group}' (available: {', '.join(available) or 'none'})")
                return False
            return True

        default = view.text(r, 2)
        if default and check(_Sheet.ref(r, 2), default):
            defaults[label] = default
        for col, name in names:
            variant = view.text(r, col)
            if not variant:
                continue
            refs[(name, f'variants.{label}')] = _Sheet.ref(r, col)
            if check(_Sheet.ref(r, col), variant) and variant != defaults.get(label):
                variants[name][label] = variant
    overrides: dict[str, dict[str, str]] = {n: {} for _, n in names}
    for r in range(2, len(over.rows) + 1):
        name, key, value, unit = (over.value(r, c) for c in range(1, 5))
        if all(v is None for v in (name, key, value, unit)):
            continue
        ref = _Sheet.ref(r, 1)
        name, key = _text(name), _text(key)
        if name not in overrides:
            cells.add('Overrides', ref, f"configuration '{name}' is not a column of Overview "
                      f"(columns: {', '.join(n for _, n in names)})")
            continue
        group, _, rest = key.partition('.')
        key_ref = _Sheet.ref(r, 2)
        if not rest or group not in known:
            cells.add('Overrides', key_ref, f"expected GROUP.KEY with a known group, found "
                      f"'{key}'")
            continue
        if key in overrides[name]:
            cells.add('Overrides', key_ref, f"'{key}' is overridden twice for '{name}'")
            continue
        if value is None or _text(value) == '':
            cells.add('Overrides', _Sheet.ref(r, 3), 'missing the value')
            continue
        if isinstance(value, bool):
            cells.add('Overrides', _Sheet.ref(r, 3), f'expected a number or a text, found '
                      f'{value!r}')
            continue
        number = _number_text(value) if isinstance(value, (int, float)) else str(value).strip()
        unit = _text(unit)
        overrides[name][key] = f'{number} {unit}' if unit else number
        refs[(name, f'overrides.{key}')] = _Sheet.ref(r, 3)
    cells.raise_if_any()
    doc: dict[str, Any] = {'study': {k: study[k] for k in STUDY_FIELDS if k in study},
                           'defaults': defaults, 'configurations': {}}
    for _, name in names:
        body: dict[str, Any] = {}
        if descriptions.get(name):
            body['description'] = descriptions[name]
        if variants[name]:
            body['variants'] = variants[name]
        if overrides[name]:
            body['overrides'] = overrides[name]
        switch = flexible.get(name, '')
        if switch == 'on':
            body['flexible'] = True
        elif switch not in ('', 'off'):
            body['flexible_components'] = [c.strip() for c in switch.split(',') if c.strip()]
        doc['configurations'][name] = body
    doc['_refs'] = refs
    return doc


def _data_root(target: Path, study: Mapping[str, str]) -> Path | None:
    root = (target.absolute().parent / study.get('data_root', '..')).resolve()
    return root if root.is_dir() else None


def import_workbook(path: Path, target: Path) -> str:
    """Write the master file ``target`` from the workbook ``path``; returns its text."""
    doc = read_workbook(path, target)
    refs = doc.pop('_refs')
    try:
        return write_master(target, _flow(doc))
    except DataErrors as err:
        raise DataErrors([_at_cell(e, refs, path) for e in err.errors]) from None
    except DataError as err:
        raise _at_cell(err, refs, path) from None


def _flow(doc: Mapping[str, Any]) -> Any:
    """Turn the plain mapping into a round-trip document: component lists in flow style."""
    def convert(value: Any) -> Any:
        if isinstance(value, Mapping):
            return CommentedMap((k, convert(v)) for k, v in value.items())
        if isinstance(value, list):
            seq = CommentedSeq(value)
            seq.fa.set_flow_style()
            return seq
        return value

    return convert(doc)


def _at_cell(err: DataError, refs: Mapping[tuple[str, str], str], book: Path) -> DataError:
    """Name a master-file problem by the cell it came from, where one is known."""
    key = err.key or ''
    for (name, what), ref in refs.items():
        prefix = f'configurations.{name}.{what}'
        if ref and (key == prefix or key.startswith(prefix + '.')):
            sheet = 'Overrides' if what.startswith('overrides.') else 'Overview'
            return DataError(err.detail, file=str(book), key=f'{sheet}!{ref}')
    return err
