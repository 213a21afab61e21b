# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Every package declares what its Python modules import (package.xml), and nothing else.

The imports of each package's modules and launch files (ast, absolute imports outside
the standard library) are mapped to rosdep keys and compared with the package's
``<depend>``/``<exec_depend>`` entries, both ways.
"""
from __future__ import annotations

import ast
from pathlib import Path
import sys
import xml.etree.ElementTree as ET

import pytest

SRC = Path(__file__).resolve().parents[2] / 'src'
PYTHON_PACKAGES = ('vd_data_server', 'vd_solvers', 'vd_events')

#: import name -> rosdep key, for what is not a ROS package of the same name
ROSDEP_KEYS = {
    'numpy': 'python3-numpy',
    'scipy': 'python3-scipy',
    'yaml': 'python3-yaml',
    'pint': 'python3-pint',
    'rich': 'python3-rich',
    'matplotlib': 'python3-matplotlib',
    'rosbags': 'python3-rosbags-pip',
    'pyopencrg': 'python3-pyopencrg-pip',
    'numba': 'python3-numba',
    'pinocchio': 'pinocchio',
    'vehiclemodels': 'python3-commonroad-vehicle-models-pip',
    'ruamel': 'python3-ruamel.yaml',
    'openpyxl': 'python3-openpyxl',
    'plotly': 'python3-plotly',
    'pyarrow': 'python3-pyarrow',
    'PIL': 'python3-pil',
    'selenium': 'python3-selenium',
    'jinja2': 'python3-jinja2',
    'markupsafe': 'python3-markupsafe',
}
#: imported for type checking only (typeshed's stub-only module)
TYPE_ONLY = {'_typeshed'}
#: used without an import: ``ros2 launch`` runs the package's launch files
RUNTIME_ONLY = {'ros2launch'}
#: imported only by setup.py (the build tool)
BUILD_ONLY = {'setuptools'}


def imports(package: str) -> set[str]:
    """Return the top-level names the package's modules and launch files import."""
    root = SRC / package
    files = [*(root / package).rglob('*.py'), *(root / 'launch').glob('*.py')]
    names: set[str] = set()
    for path in files:
        for node in ast.walk(ast.parse(path.read_text(encoding='utf-8'))):
            if isinstance(node, ast.Import):
                names.update(alias.name.split('.')[0] for alias in node.names)
            elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
                names.add(node.module.split('.')[0])
    return {n for n in names
            if n not in sys.stdlib_module_names and n != package
            and n not in BUILD_ONLY | TYPE_ONLY}


def declared(package: str, tags=('depend', 'exec_depend')) -> set[str]:
    """Return the rosdep keys ``package.xml`` declares under ``tags``."""
    root = ET.parse(SRC / package / 'package.xml').getroot()
    return {e.text.strip() for tag in tags for e in root.findall(tag)}


@pytest.mark.parametrize('package', PYTHON_PACKAGES)
def test_every_import_is_declared_and_every_declaration_used(package):
    needed = {ROSDEP_KEYS.get(name, name) for name in imports(package)}
    have = declared(package)
    assert sorted(needed - have) == [], f'{package}/package.xml misses these'
    assert sorted(have - needed - RUNTIME_ONLY) == [], f'{package}/package.xml: unused'


def test_interface_packages_declare_the_packages_their_fields_use():
    for package in ('vd_interfaces', 'tf2_msgs', 'ackermann_msgs'):
        root = SRC / package
        used = set()
        for path in [*root.glob('msg/*.msg'), *root.glob('srv/*.srv'),
                     *root.glob('action/*.action')]:
            for line in path.read_text(encoding='utf-8').splitlines():
                field = line.split('#')[0].split()
                if field and '/' in field[0]:
                    used.add(field[0].split('/')[0])
        if list(root.glob('action/*.action')):
            used.add('action_msgs')  # the generated goal/result services use it
        used.discard(package)
        assert sorted(used - declared(package)) == [], f'{package}/package.xml misses these'


def test_the_check_finds_a_missing_dependency(tmp_path, monkeypatch):
    """The comparison is not vacuous: an undeclared import is reported."""
    pkg = tmp_path / 'demo_pkg'
    (pkg / 'demo_pkg').mkdir(parents=True)
    (pkg / 'demo_pkg' / 'node.py').write_text('import numpy\nfrom rclpy.node import Node\n'
                                              'import os\n')
    (pkg / 'package.xml').write_text('<package format="3"><name>demo_pkg</name>'
                                     '<exec_depend>rclpy</exec_depend></package>')
    monkeypatch.setattr(sys.modules[__name__], 'SRC', tmp_path)
    needed = {ROSDEP_KEYS.get(n, n) for n in imports('demo_pkg')}
    assert needed - declared('demo_pkg') == {'python3-numpy'}
