# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""docs/data-format.md documents every key of the schema: the doc cannot fall behind."""
from __future__ import annotations

from pathlib import Path
import re

import pytest

from vd_data_server import schema
from vd_data_server.tir import REQUIRED_BLOCKS
from vd_data_server.units import SI_UNITS, display_si

DOC = Path(__file__).resolve().parents[2] / 'docs' / 'data-format.md'


def text() -> str:
    return DOC.read_text(encoding='utf-8')


def cells(line: str) -> list[str]:
    return [c.strip() for c in line.strip().strip('|').split('|')]


def kind_section(kind: str) -> str:
    """Return the text under '### `kind`' up to the next heading."""
    match = re.search(rf'(?ms)^### `{kind}`\n(.*?)(?=^#)', text())
    assert match, f"no section '### `{kind}`' in {DOC.name}"
    return match.group(1)


def key_rows(section: str) -> dict[str, list[str]]:
    rows = {}
    for line in section.splitlines():
        if line.startswith('| `'):
            row = cells(line)
            rows[row[0].strip('`')] = row
    return rows


@pytest.mark.parametrize('kind', list(schema.KINDS))
def test_every_key_of_every_kind_is_documented(kind: str) -> None:
    rows = key_rows(kind_section(kind))
    for field in schema.describe(schema.KINDS[kind]):
        assert f'`{field.key}`' in text()
        row = rows.get(field.key)
        assert row is not None, f"{kind}: key '{field.key}' has no row in {DOC.name}"
        quantity, si_unit, required = row[1], row[2], row[3]
        assert quantity == field.quantity, (kind, field.key)
        assert required.split(':')[0] == ('yes' if field.required else 'no'), (kind, field.key)
        if field.kind == 'scalar':
            assert si_unit == display_si(field.quantity), (kind, field.key)


@pytest.mark.parametrize('kind', list(schema.KINDS))
def test_no_documented_key_is_unknown_to_the_schema(kind: str) -> None:
    documented = set(key_rows(kind_section(kind)))
    assert documented == {f.key for f in schema.describe(schema.KINDS[kind])}


def test_hard_points_table_matches_the_templates() -> None:
    section = re.search(r'(?ms)^## Hard points per template\n(.*?)(?=^## )', text())
    assert section
    header = next(cells(line) for line in section.group(1).splitlines()
                  if line.startswith('| point'))
    templates = [c.strip('`') for c in header[1:-1]]
    assert templates == list(schema.TEMPLATE_POINTS)
    rows = key_rows(section.group(1))
    required = {t: {p for p, row in rows.items() if row[1 + i] == '✓'}
                for i, t in enumerate(templates)}
    assert required == {t: set(points) for t, points in schema.TEMPLATE_POINTS.items()}
    optional = {p for p, row in rows.items() if row[1:1 + len(templates)] ==
                ['optional'] * len(templates)}
    assert optional == set(schema.OPTIONAL_POINTS)
    assert all(row[-1] for row in rows.values())  # every point has a meaning


def test_every_group_and_unit_quantity_is_documented() -> None:
    doc = text()
    for group in schema.all_group_names():
        assert f'`{group}`' in doc, group
    for quantity in SI_UNITS:
        assert f'`{quantity}`' in doc, quantity


def test_required_tire_blocks_are_documented() -> None:
    for block in REQUIRED_BLOCKS:
        assert f'`[{block}]`' in text(), block
