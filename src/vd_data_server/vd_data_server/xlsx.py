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


def _sheet(book: Any, name: str, cells: _Cells) -> Any:
    if name not in book.sheetnames:
        cells.add(name, 'A1', f"sheet '{name}' missing (the workbook needs the sheets Study, "
                  'Overview and Overrides, as vd export xlsx writes them)')
        return None
    return book[name]


def read_workbook(path: Path, target: Path) -> dict[str, Any]:
    """
    Read the master file a workbook describes (a plain mapping, in master-file order).

    ``target`` is where the master file will be written: its data root decides which
    variants exist. Raises DataError with every bad cell as ``Sheet!CELL: message``.
    """
    display = str(path)
    try:
        if path.stat().st_size > MAX_BYTES:
            raise DataError(f'exceeds the limit of {MAX_BYTES >> 20} MiB per workbook',
                            file=display)
        book = load_workbook(path, read_only=True, data_only=True)
    except DataError:
        raise
    except FileNotFoundError:
        raise DataError('file not found', file=display) from None
    except Exception as err:  # noqa: BLE001 - openpyxl raises many kinds on a non-workbook
        raise DataError(f'not an xlsx workbook ({type(err).__name__}: {err})',
                        file=display) from None
    cells = _Cells(display)
    study_sheet, view, over = (_sheet(book, n, cells) for n in ('Study', 'Overview',
                                                                'Overrides'))
    cells.raise_if_any()
    study: dict[str, Any] = {}
    for row in study_sheet.iter_rows(min_row=2):
        if not row or row[0].value is None:
            continue
        key = _text(row[0].value)
        value = _text(row[1].value) if len(row) > 1 else ''
        if key == 'master file':
            continue
        if key not in STUDY_FIELDS:
            cells.add('Study', row[0].coordinate, f"unknown field '{key}' (expected one of: "
                      f"{', '.join(STUDY_FIELDS)})")
        elif value:
            study[key] = value
    for key in ('name', 'vehicle'):
        if key not in study:
            cells.add('Study', 'B2' if key == 'name' else 'B4', f"missing the study's {key}")
    rows = list(view.iter_rows())
    if not rows:
        cells.add('Overview', 'A1', 'the sheet is empty')
        cells.raise_if_any()
    head = [_text(c.value) for c in rows[0]]
    if tuple(head[:2]) != OVERVIEW_HEAD:
        cells.add('Overview', 'A1', f"expected the headings '{OVERVIEW_HEAD[0]}', "
                  f"'{OVERVIEW_HEAD[1]}' in A1:B1, found {head[:2]}")
        cells.raise_if_any()
    names: list[tuple[int, str]] = []
    for col, name in enumerate(head[2:], 2):
        if not name or name == CONSISTENCY_HEAD:
            break
        ref = rows[0][col].coordinate
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
    for row in rows[1:]:
        label = _text(row[0].value)
        if not label:
            continue
        if label == 'flexible':
            for col, name in names:
                flexible[name] = _text(row[col].value) if col < len(row) else ''
                ref = row[col].coordinate if col < len(row) else ''
                refs[(name, 'flexible')] = refs[(name, 'flexible_components')] = ref
            continue
        if label == 'description':
            for col, name in names:
                descriptions[name] = _text(row[col].value) if col < len(row) else ''
            continue
        if label not in known:
            cells.add('Overview', row[0].coordinate, f"unknown input group '{label}' (expected "
                      f"one of: {', '.join(known)})")
            continue
        available = sorted(p.stem for p in (vehicle / label).glob('*.yaml')) \
            if vehicle is not None and (vehicle / label).is_dir() else None

        def check(cell: Any, variant: str, group: str = label,
                  available: list[str] | None = available) -> bool:
            if not _NAME.match(variant):
                cells.add('Overview', cell.coordinate, f"variant must be a plain name, found "
                          f"'{variant}'")
                return False
            if available is not None and variant not in available:
                cells.add('Overview', cell.coordinate, f"unknown variant '{variant}' for group "
                          f"'{group}' (available: {', '.join(available) or 'none'})")
                return False
            return True

        default = _text(row[1].value) if len(row) > 1 else ''
        if default and check(row[1], default):
            defaults[label] = default
        for col, name in names:
            variant = _text(row[col].value) if col < len(row) else ''
            if not variant:
                continue
            refs[(name, f'variants.{label}')] = row[col].coordinate
            if check(row[col], variant) and variant != defaults.get(label):
                variants[name][label] = variant
    overrides: dict[str, dict[str, str]] = {n: {} for _, n in names}
    for row in list(over.iter_rows())[1:]:
        values = [c.value for c in row] + [None] * 4
        if all(v is None for v in values[:4]):
            continue
        name, key, value, unit = values[:4]
        ref = row[0].coordinate
        name, key = _text(name), _text(key)
        if name not in overrides:
            cells.add('Overrides', ref, f"configuration '{name}' is not a column of Overview "
                      f"(columns: {', '.join(n for _, n in names)})")
            continue
        group, _, rest = key.partition('.')
        key_ref = row[1].coordinate
        if not rest or group not in known:
            cells.add('Overrides', key_ref, f"expected GROUP.KEY with a known group, found "
                      f"'{key}'")
            continue
        if key in overrides[name]:
            cells.add('Overrides', key_ref, f"'{key}' is overridden twice for '{name}'")
            continue
        if value is None or _text(value) == '':
            cells.add('Overrides', row[2].coordinate, 'missing the value')
            continue
        if isinstance(value, bool):
            cells.add('Overrides', row[2].coordinate, f'expected a number or a text, found '
                      f'{value!r}')
            continue
        number = _number_text(value) if isinstance(value, (int, float)) else str(value).strip()
        unit = _text(unit)
        overrides[name][key] = f'{number} {unit}' if unit else number
        refs[(name, f'overrides.{key}')] = row[2].coordinate
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
