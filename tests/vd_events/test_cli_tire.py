# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""`vd tire FILE`: key data of a .tir file, its curves as a PNG, bad files refused (exit 2)."""
from __future__ import annotations

import json
import math
from pathlib import Path

from numpy.testing import assert_allclose
import pytest

from vd_data_server.tir import read_tir
from vd_events.cli.main import main
from vd_solvers.tire.magic_formula import MagicFormula
from vdtest import tree_snapshot

TIRES = Path(__file__).resolve().parents[2] / 'src' / 'vd_data_server' / 'data' / 'tires'
MF62 = TIRES / 'MF62_255_55R20.tir'
PNG_SIGNATURE = b'\x89PNG\r\n\x1a\n'


def run(capsys: pytest.CaptureFixture[str], *argv: str) -> tuple[int, str, str]:
    rc = main(list(argv))
    out, err = capsys.readouterr()
    return rc, out, err


def test_the_sample_62_file_is_shown_and_plotted(capsys: pytest.CaptureFixture[str],
                                                 tmp_path: Path) -> None:
    rc, out, err = run(capsys, 'tire', str(MF62), '--out', str(tmp_path))
    assert (rc, err) == (0, '')
    lines = out.splitlines()
    assert lines[0] == str(MF62)
    assert '  version' in lines[1] and lines[1].endswith(
        'MF-Tyre 6.2 (FITTYP 62, PROPERTY_FILE_FORMAT USER)')
    tire = MagicFormula(read_tir(MF62))
    stiffness = float(tire.cornering_stiffness(6752.0)) * math.pi / 180.0
    row = next(line for line in lines if 'cornering stiffness' in line)
    assert row.endswith(f'{stiffness:.4g} N/deg')
    assert any(line.endswith('inflation pressure                        2.6 bar')
               for line in lines)
    png = tmp_path / 'MF62_255_55R20_curves.png'
    assert lines[-1] == f'curves: {png}'
    assert png.read_bytes()[:8] == PNG_SIGNATURE


def test_json_gives_every_value_in_si(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    rc, out, _ = run(capsys, 'tire', str(MF62), '--out', str(tmp_path), '--json',
                     '--pressure', '3 bar')
    assert rc == 0
    data = json.loads(out)
    assert data['format'] == 'MF62'
    values = {row['name']: (row['value'], row['unit']) for row in data['data']}
    assert values['inflation pressure'] == (300000.0, 'Pa')
    stiffness = MagicFormula(read_tir(MF62), pressure=3e5).cornering_stiffness(6752.0)
    assert_allclose(values['cornering stiffness dFy/dalpha at FNOMIN'][0], stiffness,
                    rtol=1e-12)
    assert data['warnings'] == []
    assert Path(data['plot']).is_file()


def test_a_pac2002_file_is_shown_with_its_version(capsys: pytest.CaptureFixture[str],
                                                  tmp_path: Path) -> None:
    rc, out, _ = run(capsys, 'tire', str(TIRES / 'Sedan_Pac02Tire.tir'), '--out',
                     str(tmp_path), '--json')
    data = json.loads(out)
    values = {row['name']: row['value'] for row in data['data']}
    assert (rc, values['version']) == (0, 'PAC2002 (MF 5.2) (PROPERTY_FILE_FORMAT PAC2002)')
    # book normalisation: the trail by FNOMIN LFZO is the MF-Tyre one over LFZO = 0.81
    rc, book, _ = run(capsys, 'tire', str(TIRES / 'Sedan_Pac02Tire.tir'), '--out',
                      str(tmp_path), '--json', '--aligning-normalisation', 'book')
    book_values = {row['name']: row['value'] for row in json.loads(book)['data']}
    assert_allclose(book_values['pneumatic trail at FNOMIN'] * 0.81,
                    values['pneumatic trail at FNOMIN'], rtol=1e-12)


def test_a_broken_file_is_refused_and_nothing_is_written(capsys: pytest.CaptureFixture[str],
                                                         tmp_path: Path) -> None:
    bad = tmp_path / 'bad.tir'
    bad.write_text(MF62.read_text(encoding='ascii').replace(
        'NOMPRES                   = 260000', 'NOMPRES                   = 2.6bar'),
        encoding='ascii')
    line = next(n for n, text in enumerate(bad.read_text().splitlines(), start=1)
                if text.startswith('NOMPRES'))
    before = tree_snapshot(tmp_path)
    rc, out, err = run(capsys, 'tire', str(bad), '--out', str(tmp_path / 'out'))
    assert (rc, out) == (2, '')
    assert err == (f"{bad}: NOMPRES: line {line}: key 'NOMPRES' in block "
                   '[OPERATING_CONDITIONS] is not a number: 2.6bar\n')
    assert tree_snapshot(tmp_path) == before


def test_missing_blocks_are_all_named(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    bad = tmp_path / 'bad.tir'
    bad.write_text('[UNITS]\n[MODEL]\nFITTYP = 61\n[DIMENSION]\nUNLOADED_RADIUS = 0.3\n'
                   '[VERTICAL]\nFNOMIN = 4000\nVERTICAL_STIFFNESS = 2e5\n'
                   '[SCALING_COEFFICIENTS]\n[LONGITUDINAL_COEFFICIENTS]\nPCX1 = 1.6\n'
                   'PDX1 = 1\nPKX1 = 20\n[LATERAL_COEFFICIENTS]\nPCY1 = 1.3\nPDY1 = 1\n'
                   'PKY1 = -15\nPKY2 = 2\n', encoding='ascii')
    rc, out, err = run(capsys, 'tire', str(bad), '--json', '--out', str(tmp_path / 'out'))
    assert (rc, json.loads(out)) == (2, {'error': (
        f'{bad}: missing block [OPERATING_CONDITIONS] (needed by MF 6.1)\n'
        f'{bad}: missing block [ALIGNING_COEFFICIENTS] (needed by MF 6.1)')})
    assert not (tmp_path / 'out').exists()


def test_a_pressure_without_unit_is_refused(capsys: pytest.CaptureFixture[str],
                                            tmp_path: Path) -> None:
    rc, out, err = run(capsys, 'tire', str(MF62), '--pressure', '2.4', '--out', str(tmp_path))
    assert (rc, out) == (2, '')
    assert err == (f"{MF62}: --pressure: value '2.4' needs a unit (a pressure, e.g. '2.4 Pa')"
                   '\n')


def test_a_missing_file_is_refused(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    missing = tmp_path / 'none.tir'
    rc, out, err = run(capsys, 'tire', str(missing))
    assert (rc, out) == (2, '')
    assert err == f'{missing}: cannot read tire property file: No such file or directory\n'


def test_data_check_accepts_the_mf62_study(capsys: pytest.CaptureFixture[str],
                                           sample_root: Path) -> None:
    master = sample_root / 'studies' / 'sedan_mf62.yaml'
    rc, out, err = run(capsys, 'data', 'check', '--master', str(master))
    assert (rc, err) == (0, '')
    assert out == f'{master}: OK (2 configurations, 24 data files)\n'


def test_data_check_names_the_line_of_a_bad_mf62_value(capsys: pytest.CaptureFixture[str],
                                                       sample_root: Path) -> None:
    tire = sample_root / 'tires' / 'MF62_255_55R20.tir'
    text = tire.read_text(encoding='ascii')
    assert text.count('PDYP1                     = 0.4') == 1
    tire.write_text(text.replace('PDYP1                     = 0.4',
                                 'PDYP1                     = 0.4\nPDYP5 = 1'), encoding='ascii')
    line = next(n for n, t in enumerate(tire.read_text().splitlines(), start=1)
                if t.startswith('PDYP5'))
    before = tree_snapshot(sample_root)
    rc, out, err = run(capsys, 'data', 'check', '--master',
                       str(sample_root / 'studies' / 'sedan_mf62.yaml'))
    assert (rc, out) == (2, '')
    assert err == (f"{tire}: PDYP5: line {line}: 'PDYP5' is no MF 6.2 coefficient of block "
                   '[TURNSLIP_COEFFICIENTS] (a misspelt coefficient would silently be 0)\n')
    assert tree_snapshot(sample_root) == before
