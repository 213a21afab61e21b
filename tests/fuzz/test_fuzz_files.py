# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Property-based fuzzing of the files vd reads besides its YAML data (issue 28).

Excel workbooks (``vd import xlsx``), bags (``vd compare`` / ``vd replay``), imported
reduced stiffness files (plain YAML and Nastran DMIG, as ``vd data check`` and a K&C run
build them) and measured logs (rig tables and VBOX ``.vbo`` files). Property: a clean
error of the reader's kind or a valid result; never another exception (a traceback), a
hang or a huge message.
"""
from __future__ import annotations

import io
from pathlib import Path
import shutil
import zipfile

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
import pytest
import yaml

from fuzzing import NUMBER_TEXTS, SCALARS, clean, mutate, no_hang
from vd_data_server.errors import DataError

SAMPLE = Path(__file__).resolve().parents[2] / 'src' / 'vd_data_server' / 'data'
SAMPLES = Path(__file__).resolve().parents[2] / 'src' / 'vd_events' / 'samples'
FIXTURES = [HealthCheck.function_scoped_fixture]
#: what a garbled byte string may hold: the XML and zip constructs that break readers
XML_PIECES = ['<!DOCTYPE x [<!ENTITY a "b">]>', '<!ENTITY a SYSTEM "file:///etc/passwd">',
              '&a;', '<c r="A1"/>', '<c r="XFD1048576"><v>1</v></c>', '<dimension ref="A1"/>',
              '<row r="0">', '</row>', '<f>1+</f>', '<v></v>', '\x00', '<', '>', '"']


@pytest.fixture(scope='module')
def root(tmp_path_factory) -> Path:
    copy = tmp_path_factory.mktemp('fuzz_files') / 'data'
    shutil.copytree(SAMPLE, copy)
    return copy


# --- Excel workbooks ---------------------------------------------------------------------

@pytest.fixture(scope='module')
def workbook(root: Path) -> bytes:
    from vd_data_server.masteredit import load_document
    from vd_data_server.study import load_study
    from vd_data_server.xlsx import export_workbook

    master = root / 'studies' / 'sedan.yaml'
    path = export_workbook(load_study(master), load_document(master.read_text(),
                                                            file=str(master)),
                           root.parent / 'sedan.xlsx')
    return path.read_bytes()


def _import(root: Path, book: bytes) -> None:
    from vd_data_server.xlsx import import_workbook

    path = root.parent / 'fuzz.xlsx'
    path.write_bytes(book)
    with no_hang():
        try:
            import_workbook(path, root / 'studies' / 'fuzz_import.yaml')
        except DataError as err:
            clean(err)


@given(data=st.data())
@settings(suppress_health_check=FIXTURES)
def test_workbooks_with_edited_cells(data, root, workbook):
    from openpyxl import load_workbook

    book = load_workbook(io.BytesIO(workbook))
    for _ in range(data.draw(st.integers(1, 4))):
        sheet = book[data.draw(st.sampled_from(['Study', 'Overview', 'Overrides']))]
        row = data.draw(st.integers(1, sheet.max_row + 2))
        col = data.draw(st.one_of(st.integers(1, sheet.max_column + 2),
                                  st.sampled_from([600, 3000])))
        value = data.draw(st.one_of(SCALARS.filter(lambda v: not isinstance(v, (list, dict))),
                                    st.sampled_from(['="X"', '=1/0', '=A1', 'X', 'Y', 'on',
                                                     'off', 'lca, strut', '../X'])))
        if isinstance(value, int) and abs(value) > 10**15:
            value = str(value)
        if isinstance(value, str):
            value = ''.join(c for c in value if c.isprintable())  # what a cell can hold
        sheet.cell(row, col).value = value
    stream = io.BytesIO()
    book.save(stream)
    _import(root, stream.getvalue())


@given(data=st.data())
@settings(suppress_health_check=FIXTURES)
def test_workbooks_with_garbled_parts(data, root, workbook):
    with zipfile.ZipFile(io.BytesIO(workbook)) as package:
        parts = {i.filename: package.read(i) for i in package.infolist()}
    names = sorted(parts)
    for _ in range(data.draw(st.integers(1, 3))):
        name = data.draw(st.sampled_from(names))
        text = parts[name]
        action = data.draw(st.sampled_from(['truncate', 'insert', 'delete']))
        at = data.draw(st.integers(0, len(text)))
        if action == 'truncate':
            parts[name] = text[:at]
        elif action == 'insert':
            piece = data.draw(st.one_of(st.sampled_from(XML_PIECES), st.text(max_size=20)))
            parts[name] = text[:at] + piece.encode('utf-8') + text[at:]
        else:
            parts[name] = text[:at] + text[at + data.draw(st.integers(1, 40)):]
    stream = io.BytesIO()
    with zipfile.ZipFile(stream, 'w', zipfile.ZIP_DEFLATED) as package:
        for name, content in parts.items():
            package.writestr(name, content)
    book = stream.getvalue()
    if data.draw(st.booleans()):  # or the package itself cut
        book = book[:data.draw(st.integers(0, len(book)))]
    _import(root, book)


# --- bags ------------------------------------------------------------------------------------

@pytest.fixture(scope='module')
def sim_bag(root: Path) -> Path:
    from vd_data_server.study import load_study
    from vd_events.bags.outcomes import write_outcomes
    from vd_solvers.kc.from_config import run_kc_event

    baseline = load_study(root / 'studies' / 'sedan.yaml').configurations['baseline']
    outcome = run_kc_event(baseline, 'parallel_wheel_travel', 'front', ['steps=5'])
    return write_outcomes(root.parent / 'sim', [(outcome, 1_700_000_000_000_000_000)],
                          {'vd.kind': 'fuzz'})


@pytest.mark.ros
@given(data=st.data())
@settings(suppress_health_check=FIXTURES)
def test_damaged_bags(data, root, sim_bag):
    from vd_events.errors import BagError
    from vd_events.measured.compare import load_outcomes

    bag = root.parent / 'damaged'
    shutil.rmtree(bag, ignore_errors=True)
    shutil.copytree(sim_bag, bag)
    (mcap,) = bag.glob('*.mcap')
    if data.draw(st.booleans()):
        raw = bytearray(mcap.read_bytes())
        for _ in range(data.draw(st.integers(1, 4))):
            at = data.draw(st.integers(0, len(raw) - 1))
            raw[at] = data.draw(st.integers(0, 255))
        if data.draw(st.booleans()):
            raw = raw[:data.draw(st.integers(0, len(raw)))]
        mcap.write_bytes(bytes(raw))
    else:
        tree = yaml.safe_load((bag / 'metadata.yaml').read_text())
        (bag / 'metadata.yaml').write_text(yaml.safe_dump(mutate(data, tree, rounds=3)))
    with no_hang():
        try:
            load_outcomes(bag)
        except (BagError, DataError) as err:
            clean(err)


# --- imported reduced stiffness ----------------------------------------------------------

@pytest.fixture(scope='module')
def arm_plain(root: Path) -> dict:
    """Return the front lower arm's condensed stiffness in the plain format (mm, N)."""
    from vd_data_server.study import load_study
    from vd_solvers.flex.imported import dof_scales
    from vd_solvers.kc.from_config import build_kc_model

    config = load_study(root / 'studies' / 'sedan.yaml').configurations['baseline']
    model = build_kc_model(config, 'front', 'flexible', 'arm')
    (comp,) = [c for c in model.system.outputs.components if c.name == 'lca']
    points = yaml.safe_load((root / 'sedan/front_hardpoints/X.yaml').read_text())['data']
    k = comp.stiffness / dof_scales(len(comp.nodes), 1e-3, 1.0, 1.0)
    return {'units': {'length': 'mm', 'force': 'N', 'angle': 'rad'},
            'nodes': {n: points['points'][n] for n in comp.nodes}, 'stiffness': k.tolist()}


def _build_with_imported(root: Path, entry: str, name: str, text: str) -> None:
    from vd_data_server.study import load_study
    from vd_solvers.errors import SolverError
    from vd_solvers.kc.from_config import build_kc_model

    flex = root / 'sedan' / 'front_flex' / 'X.yaml'
    original = flex.read_text()
    lca = 'lca: {material: steel, section: pressed_arm, rigid_mass: 3.5, elements_per_member: 2}'
    flex.write_text(original.replace(lca, entry))
    (root / 'sedan' / 'front_flex' / name).write_text(text)
    try:
        with no_hang():
            try:
                config = load_study(root / 'studies' / 'sedan.yaml').configurations['baseline']
                build_kc_model(config, 'front', 'flexible', 'fuzz')
            except (DataError, SolverError) as err:
                clean(err)
    finally:
        flex.write_text(original)


@given(data=st.data())
@settings(suppress_health_check=FIXTURES)
def test_mutated_plain_stiffness(data, root, arm_plain):
    text = data.draw(st.one_of(
        st.just(yaml.safe_dump(mutate(data, arm_plain, rounds=3))),
        st.text(max_size=200),
        st.sampled_from(['', 'stiffness: ' + '[' * 100 + ']' * 100, '~', '[]', 'units: 1'])))
    _build_with_imported(root, 'lca: {rigid_mass: 3.5, imported: {file: sedan/front_flex/k.yaml, '
                         'format: plain}}', 'k.yaml', text)


@given(data=st.data())
@settings(suppress_health_check=FIXTURES)
def test_mutated_dmig_punch(data, root, arm_plain):
    import numpy as np

    from vd_solvers.flex.imported import dof_scales

    k = np.array(arm_plain['stiffness']) * dof_scales(3, 1e-3, 1.0, 1.0)
    lines = [f"DMIG*   {'KAAX':<16}{0:>16}{6:>16}{2:>16}", '*       ' + f'{0:>16}']
    for j in range(18):
        lines.append(f"DMIG*   {'KAAX':<16}{101 + j // 6:>16}{j % 6 + 1:>16}")
        lines += [f'*       {101 + i // 6:>16}{i % 6 + 1:>16}{k[i, j]:>16.9E}'
                  for i in range(j + 1)]
    for _ in range(data.draw(st.integers(1, 4))):
        at = data.draw(st.integers(0, len(lines) - 1))
        action = data.draw(st.sampled_from(['number', 'delete', 'insert', 'cut']))
        if action == 'number':
            lines[at] = lines[at][:40] + f'{data.draw(NUMBER_TEXTS)[:16]:>16}'
        elif action == 'delete':
            del lines[at]
        elif action == 'insert':
            lines.insert(at, data.draw(st.sampled_from(
                ['DMIG    KAAX    0       6       2', 'GRID    101             1e9', '+',
                 'DMIG*   KAAX', '$ comment', ','])))
        else:
            lines = lines[:at]
        if not lines:
            break
    names = list(arm_plain['nodes'])
    grids = ', '.join(f'{101 + i}: {n}' for i, n in enumerate(names))
    _build_with_imported(root, 'lca: {rigid_mass: 3.5, imported: {file: sedan/front_flex/k.pch, '
                         f'format: dmig, matrix: KAAX, grids: {{{grids}}}}}}}', 'k.pch',
                         '\n'.join(lines) + '\n')


# --- measured logs ---------------------------------------------------------------------------

def _read_measured(tmp: Path, name: str, text: str, cmap: Path | None,
                   encoding: str = 'utf-8') -> None:
    from vd_events.measured.columns import load_map
    from vd_events.measured.importer import read_measurement

    path = tmp / name
    path.write_text(text, encoding=encoding, errors='replace')
    with no_hang():
        try:
            read_measurement(path, load_map(cmap) if cmap is not None else None)
        except DataError as err:  # InputError is the measured kind
            clean(err)


def _mutated_lines(data, lines: list[str], separator: str) -> str:
    lines = list(lines)
    for _ in range(data.draw(st.integers(1, 5))):
        at = data.draw(st.integers(0, len(lines) - 1))
        action = data.draw(st.sampled_from(['field', 'delete', 'duplicate', 'cut', 'swap']))
        if action == 'field':
            fields = lines[at].split(separator) if separator else lines[at].split()
            if fields:
                fields[data.draw(st.integers(0, len(fields) - 1))] = data.draw(
                    st.one_of(NUMBER_TEXTS, st.sampled_from(['', 'time', '1e308', '-1e308'])))
            lines[at] = (separator or ' ').join(fields)
        elif action == 'delete' and len(lines) > 1:
            del lines[at]
        elif action == 'duplicate':
            lines.insert(at, lines[at])
        elif action == 'cut':
            lines = lines[:max(at, 1)]
        else:
            other = data.draw(st.integers(0, len(lines) - 1))
            lines[at], lines[other] = lines[other], lines[at]
    return '\n'.join(lines) + '\n'


@given(data=st.data(), sample=st.sampled_from(['kc_spmm_bounce_front.csv',
                                                'kc_abd_lateral_front.txt',
                                                'vehicle_log.csv']))
@settings(suppress_health_check=FIXTURES)
def test_mutated_measured_tables(data, sample, tmp_path):
    path = SAMPLES / sample
    cmap = path.with_name(path.stem + '.map.yaml')
    lines = path.read_text(encoding='utf-8').splitlines()
    separator = ',' if path.suffix == '.csv' else ''
    _read_measured(tmp_path, path.name, _mutated_lines(data, lines, separator), cmap)


@given(data=st.data())
@settings(suppress_health_check=FIXTURES)
def test_mutated_vbox_logs(data, tmp_path):
    # a VBOX writes Windows-1252 (the degree sign of its units)
    lines = (SAMPLES / 'vbox_sine_steer.vbo').read_text(encoding='cp1252').splitlines()
    head = next(i for i, line in enumerate(lines) if line.strip() == '[data]') + 1
    lines = lines[:head + 200]  # the header and the first two seconds: quick examples
    _read_measured(tmp_path, 'log.vbo', _mutated_lines(data, lines, ''), None, 'cp1252')
