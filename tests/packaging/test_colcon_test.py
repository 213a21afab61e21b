# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
``colcon test`` runs the project's tests, package by package.

colcon's pytest step runs in each Python package's folder with the package's
``pytest-args`` from ``colcon.meta`` (colcon's per-package metadata), once the package
declares pytest as its test dependency: together the packages' paths must cover every
test under tests/, each test once, so ``colcon test-result`` counts the whole suite.
"""
from __future__ import annotations

import ast
import json
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
PYTHON_PACKAGES = ('vd_data_server', 'vd_solvers', 'vd_events')


def _setup_call(package: str) -> ast.Call:
    tree = ast.parse((ROOT / 'src' / package / 'setup.py').read_text(encoding='utf-8'))
    return next(n for n in ast.walk(tree) if isinstance(n, ast.Call)
                and getattr(n.func, 'id', '') == 'setup')


def test_every_python_package_declares_pytest_for_colcon():
    for package in PYTHON_PACKAGES:
        extras = next(k.value for k in _setup_call(package).keywords
                      if k.arg == 'extras_require')
        assert ast.literal_eval(extras) == {'test': ['pytest']}, package


def test_the_packages_test_paths_cover_every_test_once():
    meta = json.loads((ROOT / 'colcon.meta').read_text(encoding='utf-8'))['names']
    covered: list[Path] = []
    for package in PYTHON_PACKAGES:
        for arg in meta[package]['pytest-args']:
            path = (ROOT / 'src' / package / arg).resolve()
            assert path.exists(), (package, arg)
            covered += [path] if path.is_file() else sorted(path.rglob('test_*.py'))
    tests = sorted((ROOT / 'tests').rglob('test_*.py'))
    assert sorted(covered) == tests  # each once, none left out
