# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Excel interop: vd export xlsx writes the overview and group tabs; vd import xlsx reads them back.

The round trip master -> xlsx -> master is lossless (the parsed master files and every
resolved configuration are equal); every bad cell is named by sheet and cell reference,
and a refused import writes nothing.
"""
from __future__ import annotations

from pathlib import Path

from openpyxl import load_workbook
import pytest

from vd_data_server import schema
from vd_data_server.errors import DataError
from vd_data_server.master import load_master
from vd_data_server.masteredit import load_document
from vd_data_server.study import load_study
from vd_data_server.xlsx import export_workbook, import_workbook
from vdtest import tree_snapshot


def export(master: Path, out: Path) -> Path:
    return export_workbook(load_study(master), load_document(master.read_text(),
                                                             file=str(master)), out)


def fill(cell) -> str:
    return cell.fill.fgColor.rgb[-6:] if cell.fill and cell.fill.fill_type else ''


@pytest.mark.parametrize('study', ['sedan', 'hmmwv'])
def test_the_round_trip_is_lossless(sample_root: Path, tmp_path: Path, study: str) -> None:
    master = sample_root / 'studies' / f'{study}.yaml'
    book = export(master, tmp_path / f'{study}.xlsx')
    back = sample_root / 'studies' / f'{study}_from_xlsx.yaml'
    import_workbook(book, back)
    original, copy = load_master(master), load_master(back)
    assert (copy.name, copy.description, copy.vehicle, copy.data_root) == (
        original.name, original.description, original.vehicle, original.data_root)
    assert copy.configurations == original.configurations
    a, b = load_study(master), load_study(back)
    assert {n: c.data_hash for n, c in b.configurations.items()} == {
        n: c.data_hash for n, c in a.configurations.items()}
    assert b.to_json()['status'] == a.to_json()['status']
    # and once more: a workbook of the imported file is the same master again
    import_workbook(export(back, tmp_path / 'again.xlsx'), back)
    assert load_master(back).configurations == original.configurations


def test_the_workbook_has_the_page_colours(sedan_master: Path, tmp_path: Path) -> None:
    book = load_workbook(export(sedan_master, tmp_path / 'sedan.xlsx'))
    assert book.sheetnames[:3] == ['Study', 'Overview', 'Overrides']
    view = book['Overview']
    head = [c.value for c in view[1]]
    assert head == ['input group', 'defaults', 'baseline', 'stiff_rear', 'sport',
                    'all configurations']
    status = load_study(sedan_master).to_json()
    colour = {'UNCHANGED': 'B9F2B0', 'MODIFIED': 'F7A3A3'}
    rows = {view.cell(r, 1).value: r for r in range(2, view.max_row + 1)}
    for entry in status['status']:
        cell = view.cell(rows[entry['group']], head.index(entry['configuration']) + 1)
        assert (cell.value, fill(cell)) == (entry['variant'], colour[entry['state']])
        consistency = view.cell(rows[entry['group']], len(head))
        assert consistency.value == entry['consistency']
        assert fill(consistency) == ('FFE27A' if entry['consistency'] == 'DIFFERS' else '')
    assert [view.cell(rows['flexible'], c).value for c in (3, 4, 5)] == [
        'off', 'off', 'lca, strut, upright']
    overrides = [[c.value for c in row] for row in book['Overrides'].iter_rows(min_row=2)]
    assert overrides == [['sport', 'front_alignment.camber', -1.5, 'deg'],
                         ['sport', 'front_hardpoints.points.lca_outer.z', 171, 'mm'],
                         ['sport', 'front_damper.scale', 120, '%']]
    camber = {r[0].value: r for r in book['front_alignment'].iter_rows(min_row=2)}['camber']
    assert [c.value for c in camber] == ['camber', '-0.5', '-0.5', '-1.5', 'deg', 'DIFFERS']
    assert [fill(c) for c in camber[1:4]] == ['', '', 'F7A3A3']


def refused(root: Path, book: Path, target: Path) -> list[str]:
    before = tree_snapshot(root)
    with pytest.raises(DataError) as info:
        import_workbook(book, target)
    assert tree_snapshot(root) == before
    return str(info.value).splitlines()


def test_bad_cells_are_named_by_sheet_and_reference(sample_root: Path, sedan_master: Path,
                                                    tmp_path: Path) -> None:
    path = export(sedan_master, tmp_path / 'sedan.xlsx')
    book = load_workbook(path)
    view = book['Overview']
    rows = {view.cell(r, 1).value: r for r in range(2, view.max_row + 1)}
    view.cell(rows['front_spring'], 3).value = 'x'
    view.cell(rows['mass'], 4).value = '../X'
    view.cell(rows['steering'], 1).value = 'front_springs'
    book['Overrides']['D2'] = 'kg'
    book['Overrides']['A4'] = 'race'
    book.save(path)
    target = sample_root / 'studies' / 'imported.yaml'
    assert refused(sample_root, path, target) == [
        f"{path}: Overview!D{rows['mass']}: variant must be a plain name, found '../X'",
        f"{path}: Overview!A{rows['steering']}: unknown input group 'front_springs' (expected "
        f"one of: {', '.join(schema.all_group_names())})",
        f"{path}: Overview!C{rows['front_spring']}: unknown variant 'x' for group "
        "'front_spring' (available: X, Y)",
        f"{path}: Overrides!A4: configuration 'race' is not a column of Overview (columns: "
        'baseline, stiff_rear, sport)']
    # the cell problems fixed, the value is checked as in a master file: named by its cell
    view.cell(rows['front_spring'], 3).value = 'X'
    view.cell(rows['mass'], 4).value = 'X'
    view.cell(rows['steering'], 1).value = 'steering'
    book['Overrides']['A4'] = 'sport'
    book.save(path)
    assert refused(sample_root, path, target) == [
        f"{path}: Overrides!C2: unit 'kg' is not an angle unit (expected e.g. 'rad')"]


def test_a_file_that_is_no_workbook_is_refused(sample_root: Path, tmp_path: Path) -> None:
    bogus = tmp_path / 'bogus.xlsx'
    bogus.write_text('not a zip')
    target = sample_root / 'studies' / 'imported.yaml'
    (message,) = refused(sample_root, bogus, target)
    assert message.startswith(f'{bogus}: not an xlsx workbook (')
    assert refused(sample_root, tmp_path / 'none.xlsx', target) == [
        f"{tmp_path / 'none.xlsx'}: file not found"]
    from openpyxl import Workbook

    empty = tmp_path / 'empty.xlsx'
    Workbook().save(empty)
    assert refused(sample_root, empty, target) == [
        f"{empty}: {name}!A1: sheet '{name}' missing (the workbook needs the sheets Study, "
        'Overview and Overrides, as vd export xlsx writes them)'
        for name in ('Study', 'Overview', 'Overrides')]


def _edit_part(book: Path, part: str, edit) -> None:
    """Rewrite one XML part of the workbook package (what other programs write differently)."""
    import zipfile

    with zipfile.ZipFile(book) as package:
        parts = {i.filename: package.read(i) for i in package.infolist()}
    parts[part] = edit(parts[part].decode('utf-8')).encode('utf-8')
    with zipfile.ZipFile(book, 'w', zipfile.ZIP_DEFLATED) as package:
        for name, data in parts.items():
            package.writestr(name, data)


OVERVIEW_PART = 'xl/worksheets/sheet2.xml'
OVERRIDES_PART = 'xl/worksheets/sheet3.xml'


def _no_dimension(text: str) -> str:
    import re

    return re.sub(r'<dimension ref="[^"]*"\s*/>', '', text)


@pytest.mark.parametrize('dimension', [True, False])
def test_a_row_without_its_first_cell_is_named_by_that_cell(sample_root: Path,
                                                            sedan_master: Path, tmp_path: Path,
                                                            dimension: bool) -> None:
    path = export(sedan_master, tmp_path / 'sedan.xlsx')
    book = load_workbook(path)
    over = book['Overrides']
    row = over.max_row + 1
    over.cell(row, 2).value = 'front_alignment.toe'
    over.cell(row, 3).value = 0.1
    over.cell(row, 4).value = 'deg'
    book.save(path)
    if not dimension:
        _edit_part(path, OVERRIDES_PART, _no_dimension)
    assert refused(sample_root, path, sample_root / 'studies' / 'imported.yaml') == [
        f"{path}: Overrides!A{row}: configuration '' is not a column of Overview (columns: "
        'baseline, stiff_rear, sport)']


@pytest.mark.parametrize('dimension', [True, False])
def test_one_cell_rows_and_styled_empty_cells_are_read(sample_root: Path, sedan_master: Path,
                                                       tmp_path: Path, dimension: bool) -> None:
    from openpyxl.styles import PatternFill

    path = export(sedan_master, tmp_path / 'sedan.xlsx')
    book = load_workbook(path)
    view = book['Overview']
    rows = {view.cell(r, 1).value: r for r in range(2, view.max_row + 1)}
    empty = view.cell(rows['flexible'], 5)  # sport's components: an empty cell with a fill
    empty.value = None
    empty.fill = PatternFill('solid', fgColor='FFE27A')
    view.cell(view.max_row + 2, 1).value = 'notes'  # a row of one cell, after a gap
    book.save(path)
    if not dimension:
        _edit_part(path, OVERVIEW_PART, _no_dimension)
    assert refused(sample_root, path, sample_root / 'studies' / 'imported.yaml') == [
        f"{path}: Overview!A{view.max_row}: unknown input group 'notes' (expected one of: "
        f"{', '.join(schema.all_group_names())})"]
    view.cell(view.max_row, 1).value = None
    book.save(path)
    if not dimension:
        _edit_part(path, OVERVIEW_PART, _no_dimension)
    target = sample_root / 'studies' / 'imported.yaml'
    import_workbook(path, target)
    study = load_study(target)
    assert study.configurations['sport'].flexible_components == ()
    assert study.configurations['sport'].flexible is False


def test_a_sheet_beyond_the_column_limit_is_refused(sample_root: Path, sedan_master: Path,
                                                    tmp_path: Path) -> None:
    from openpyxl.utils import get_column_letter

    path = export(sedan_master, tmp_path / 'sedan.xlsx')
    book = load_workbook(path)
    book['Overview'].cell(1, 3000).value = 'far'
    book.save(path)
    assert refused(sample_root, path, sample_root / 'studies' / 'imported.yaml') == [
        f'{path}: Overview!{get_column_letter(3000)}1: the sheet has more than the limit of '
        '512 columns']


@pytest.mark.parametrize('declaration', [
    '<!DOCTYPE worksheet [<!ENTITY a "aaaaaaaaaa"><!ENTITY b "&a;&a;&a;&a;">]>',
    '<!DOCTYPE worksheet SYSTEM "file:///etc/passwd">',
])
def test_document_types_and_entities_are_refused(sample_root: Path, sedan_master: Path,
                                                 tmp_path: Path, declaration: str) -> None:
    path = export(sedan_master, tmp_path / 'sedan.xlsx')
    _edit_part(path, OVERVIEW_PART, lambda text: declaration + text)
    assert refused(sample_root, path, sample_root / 'studies' / 'imported.yaml') == [
        f'{path}: {OVERVIEW_PART}: a document type or entity definition (<!DOCTYPE, <!ENTITY) '
        'is refused: a workbook has none']


def test_a_formula_without_its_computed_value_is_an_error(sample_root: Path,
                                                          sedan_master: Path,
                                                          tmp_path: Path) -> None:
    """A formula the writing program did not compute is not read as an empty cell."""
    path = export(sedan_master, tmp_path / 'sedan.xlsx')
    book = load_workbook(path)
    view = book['Overview']
    rows = {view.cell(r, 1).value: r for r in range(2, view.max_row + 1)}
    view.cell(rows['front_spring'], 5).value = '="Y"'
    book.save(path)
    assert refused(sample_root, path, sample_root / 'studies' / 'imported.yaml') == [
        f"{path}: Overview!E{rows['front_spring']}: formula =\"Y\" has no computed value in "
        'the file (open and save the workbook in a spreadsheet program, or type the value)']
