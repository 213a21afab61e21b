# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
OpenCRG roads: a hand-written file read back exactly; bad files name the file.

The test writes LDFI text, the format of the OpenCRG user manual: a $ROAD_CRG header of
the u and v grid, a $KD_DEFINITION of the channels, one row of heights per u, each value
in a field of 20 characters.

The surface z(u, v) = 0.01 u + 0.02 v + 0.003 u v is bilinear, so OpenCRG's bilinear
evaluation between the grid points reproduces it exactly everywhere on the grid.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from vd_data_server.errors import DataError
from vd_solvers.road.crg import read_crg

U = np.arange(0.0, 10.0 + 1e-9, 0.5)  # m along the straight reference line (earth x)
V = np.array([-1.5, -0.5, 0.5, 1.5])  # m to the left (earth y)


def surface(u, v):
    return 0.01 * u + 0.02 * v + 0.003 * u * v


def row(values) -> str:
    return ''.join(f'{z:20.12f}' for z in values)


def write_ldfi(path: Path, rows=None) -> Path:
    header = [
        '$CT', 'a bilinear test surface', '$',
        '$ROAD_CRG',
        f'REFERENCE_LINE_START_U = {U[0]}',
        f'REFERENCE_LINE_END_U = {U[-1]}',
        f'REFERENCE_LINE_INCREMENT = {U[1] - U[0]}',
        f'LONG_SECTION_V_RIGHT = {V[0]}',
        f'LONG_SECTION_V_LEFT = {V[-1]}',
        f'LONG_SECTION_V_INCREMENT = {V[1] - V[0]}',
        '$',
        '$KD_DEFINITION',
        '#:LDFI',
        f'U:reference line u,m,{U[0]},{U[1] - U[0]}',
    ] + [f'D:long section {i + 1},m' for i in range(V.size)] + ['$', '$' * 72]
    if rows is None:
        rows = [row(surface(u, V)) for u in U]
    path.write_text('\n'.join(header + list(rows)) + '\n', encoding='ascii')
    return path


def test_a_written_surface_reads_back_exactly(tmp_path):
    road = read_crg(write_ldfi(tmp_path / 'plane.crg'), friction=0.8)
    uu, vv = np.meshgrid(U, V, indexing='ij')
    np.testing.assert_allclose(road.height(uu, vv), surface(uu, vv), atol=1e-11)
    rng = np.random.default_rng(0)
    x, y = rng.uniform(0.0, 10.0, 50), rng.uniform(-1.5, 1.5, 50)
    np.testing.assert_allclose(road.height(x, y), surface(x, y), atol=1e-11)
    assert road.length == pytest.approx(10.0)
    assert road.friction == 0.8
    assert road.description.startswith('OpenCRG plane.crg (sha256 ')


def test_the_description_follows_the_content(tmp_path):
    a = read_crg(write_ldfi(tmp_path / 'a.crg')).description
    rows = [row(surface(u, V) + 0.001) for u in U]
    b = read_crg(write_ldfi(tmp_path / 'a.crg', rows)).description
    assert a != b


@pytest.mark.parametrize('rows', [
    [row(surface(u, V)) for u in U[:1]],  # one row: no road
    [row([0.0, 0.0]) + f'{"zero":>20}' + row([0.0])] * U.size,  # not a number
    [],  # no data
])
def test_bad_files_name_the_file(tmp_path, rows):
    path = write_ldfi(tmp_path / 'bad.crg', rows)
    with pytest.raises(DataError) as err:
        read_crg(path)
    assert str(err.value).startswith(f'{path}: not a valid OpenCRG road file: ')


def test_a_missing_file_or_bad_friction_is_a_data_error(tmp_path):
    with pytest.raises(DataError) as err:
        read_crg(tmp_path / 'none.crg')
    missing = tmp_path / 'none.crg'
    assert str(err.value) == f'{missing}: cannot read the road file: No such file or directory'
    with pytest.raises(DataError, match='friction scale must be positive'):
        read_crg(write_ldfi(tmp_path / 'ok.crg'), friction=0.0)
