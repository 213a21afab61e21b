# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
The layout stands on clean floors (docs/architecture.md): read from every import of src/.

Every import counts, the ones inside functions too. Packages stand on floors
(vd_events over vd_solvers over vd_data_server); inside a package the rooms (its
sub-packages; each module at the package's root on its own) import each other without a
circle, and no two modules import each other, however long the loop.
"""
from __future__ import annotations

import ast
from collections.abc import Iterable, Mapping
from pathlib import Path

import pytest

SRC = Path(__file__).resolve().parents[1] / 'src'
#: top floor first
PACKAGES = ('vd_events', 'vd_solvers', 'vd_data_server')


def _modules() -> dict[str, Path]:
    out = {}
    for package in PACKAGES:
        for path in (SRC / package / package).rglob('*.py'):
            parts = list(path.relative_to(SRC / package).with_suffix('').parts)
            if parts[-1] == '__init__':
                parts = parts[:-1]
            out['.'.join(parts)] = path
    return out


MODULES = _modules()


def _targets(module: str, node: ast.Import | ast.ImportFrom) -> list[str]:
    """Return the project modules an import statement of ``module`` names."""
    if isinstance(node, ast.Import):
        names = [a.name for a in node.names]
    else:
        if node.level:
            base = module.split('.')
            if MODULES[module].name != '__init__.py':
                base = base[:-1]
            base = base[:len(base) - (node.level - 1)]
            prefix = '.'.join(base + ([node.module] if node.module else []))
        else:
            prefix = node.module or ''
        names = [f'{prefix}.{a.name}' for a in node.names]
    out = []
    for name in names:
        while name and name not in MODULES and '.' in name:
            name = name.rsplit('.', 1)[0]  # a name defined in a module, not a module
        if name in MODULES and name != module:
            out.append(name)
    return out


def _imports() -> dict[str, set[str]]:
    graph: dict[str, set[str]] = {m: set() for m in MODULES}
    for module, path in MODULES.items():
        for node in ast.walk(ast.parse(path.read_text(encoding='utf-8'))):
            if isinstance(node, (ast.Import, ast.ImportFrom)):
                graph[module].update(_targets(module, node))
    return graph


IMPORTS = _imports()


def circles(graph: Mapping[str, Iterable[str]]) -> list[list[str]]:
    """Return the strongly connected components of more than one node (Tarjan)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    found: list[list[str]] = []

    def visit(v: str) -> None:
        index[v] = low[v] = len(index)
        stack.append(v)
        on_stack.add(v)
        for w in graph.get(v, ()):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            component = []
            while True:
                w = stack.pop()
                on_stack.discard(w)
                component.append(w)
                if w == v:
                    break
            if len(component) > 1:
                found.append(sorted(component))

    for v in list(graph):
        if v not in index:
            visit(v)
    return found


def room(module: str) -> str:
    """Return the room of a module: its sub-package, or itself at the package's root."""
    parts = module.split('.')
    if len(parts) >= 3 or (len(parts) == 2 and (SRC / parts[0] / parts[0] / parts[1]).is_dir()):
        return '.'.join(parts[:2])
    return module


def test_the_circle_finder_finds_a_circle():
    """The check itself: a loop of three is one circle, a chain is none."""
    assert circles({'a': {'b'}, 'b': {'c'}, 'c': {'a'}, 'd': {'a'}}) == [['a', 'b', 'c']]
    assert circles({'a': {'b'}, 'b': {'c'}, 'c': set()}) == []


def test_every_module_was_read():
    assert len(MODULES) > 100
    assert 'vd_events.orchestration.runner' in IMPORTS['vd_events.cli.run']


def test_no_module_circle():
    assert circles(IMPORTS) == []


@pytest.mark.parametrize('package', PACKAGES)
def test_no_room_circle(package):
    rooms: dict[str, set[str]] = {}
    for module, targets in IMPORTS.items():
        if module.split('.')[0] != package:
            continue
        for target in targets:
            if target.split('.')[0] == package and room(target) != room(module):
                rooms.setdefault(room(module), set()).add(room(target))
    assert circles(rooms) == []


def test_packages_import_only_downward():
    upward = sorted(f'{m} -> {t}' for m, targets in IMPORTS.items() for t in targets
                    if PACKAGES.index(t.split('.')[0]) < PACKAGES.index(m.split('.')[0]))
    assert upward == []
