# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""The data server's launch arguments: one list, one conversion, for both launch files."""
from __future__ import annotations

from pathlib import Path

from vd_data_server.ros.launch_arguments import ARGUMENTS, data_server_settings

REPO = Path(__file__).resolve().parents[2]


def test_settings_from_the_argument_defaults_keep_the_node_defaults():
    defaults = {name: default for name, default, _ in ARGUMENTS}
    assert data_server_settings(defaults.__getitem__) == {
        'master': None, 'watch_period': 0.5, 'allow_edits': False}


def test_settings_convert_the_argument_text():
    given = {'master_file': '/data/studies/x.yaml', 'watch_period': '0', 'allow_edits': 'True'}
    assert data_server_settings(given.__getitem__) == {
        'master': '/data/studies/x.yaml', 'watch_period': 0.0, 'allow_edits': True}


def test_the_xml_launch_file_declares_the_same_arguments():
    """data_server.launch.xml cannot import the list: its arguments must match it."""
    import xml.etree.ElementTree as ET

    root = ET.parse(REPO / 'src/vd_data_server/launch/data_server.launch.xml').getroot()
    declared = {a.get('name'): a.get('default') for a in root.iter('arg')}
    expected = {name: default for name, default, _ in ARGUMENTS}
    # XML sets every parameter, so its master_file default names the bundled study
    # itself where the Python files leave the parameter out
    assert declared.pop('master_file') == (
        '$(find-pkg-share vd_data_server)/data/studies/sedan.yaml')
    expected.pop('master_file')
    assert declared == expected
