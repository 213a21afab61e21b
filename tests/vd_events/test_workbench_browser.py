# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
The workbench page in a real browser.

Headless Chromium (Debian's chromium and chromium-driver) driven by Selenium against
``vd gui``'s server on 127.0.0.1.

Without Chromium these tests skip and say why (tools/setup.sh installs it as root).
"""
from __future__ import annotations

from collections.abc import Iterator
import json
from pathlib import Path
import shutil
from typing import Any

import pytest

from vd_data_server.workbench.browser import browser, unavailable, wait_for
from vd_events.cli.main import main
from vdtest import replace_once, tree_snapshot

REASON = unavailable()
pytestmark = pytest.mark.skipif(bool(REASON), reason=f'no browser here: {REASON}')
#: the page's fills (workbench.css) as the browser computes them
COLOURS = {'UNCHANGED': 'rgba(185, 242, 176, 1)', 'MODIFIED': 'rgba(247, 163, 163, 1)'}


@pytest.fixture(scope='module')
def driver(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Any]:
    with browser(tmp_path_factory.mktemp('chromium-profile')) as chromium:
        yield chromium


@pytest.fixture
def page(driver: Any, sedan_master: Path) -> Iterator[Any]:
    """Open the sedan study's workbench (edits on) in the browser."""
    from selenium.webdriver.common.by import By

    from vd_data_server.workbench.server import Workbench, WorkbenchServer

    server = WorkbenchServer(Workbench(sedan_master, edits=True))
    server.start()
    driver.get(server.url)
    wait_for(driver, lambda d: d.find_elements(By.ID, 'overview'))
    wait_for(driver, lambda d: d.find_element(By.ID, 'connection').text.startswith('live'))
    yield driver
    driver.get('about:blank')  # closes the event stream before the server stops
    server.stop()


def cell(driver: Any, configuration: str, group: str) -> Any:
    from selenium.webdriver.common.by import By

    return driver.find_element(By.ID, f'cell-{configuration}-{group}')


def test_the_overview_colours_match_the_status_json(page: Any, sedan_master: Path,
                                                    capsys: pytest.CaptureFixture[str]) -> None:
    from selenium.webdriver.common.by import By

    assert main(['data', 'status', '--master', str(sedan_master), '--json']) == 0
    status = json.loads(capsys.readouterr().out)
    for entry in status['status']:
        td = cell(page, entry['configuration'], entry['group'])
        assert td.get_attribute('data-state') == entry['state']
        assert td.value_of_css_property('background-color') == COLOURS[entry['state']]
        assert td.text.endswith(entry['state'])
        consistency = page.find_element(By.ID, f"consistency-{entry['group']}")
        assert consistency.text == entry['consistency']
    assert page.find_element(By.ID, 'flex-sport').text == 'on (lca, strut, upright)'
    assert page.find_element(By.ID, 'flex-baseline').text == 'off'


def type_override(driver: Any, configuration: str, key: str, value: str) -> None:
    from selenium.webdriver.common.by import By
    from selenium.webdriver.support.ui import Select

    Select(driver.find_element(By.ID, 'ov-config')).select_by_value(configuration)
    for name, text in (('ov-key', key), ('ov-value', value)):
        field = driver.find_element(By.ID, name)
        field.clear()
        field.send_keys(text)
    driver.find_element(By.ID, 'ov-set').click()


def test_an_override_entered_lands_in_the_master_file(page: Any, sedan_master: Path) -> None:
    from selenium.webdriver.common.by import By

    assert cell(page, 'baseline', 'front_alignment').get_attribute('data-state') == 'UNCHANGED'
    type_override(page, 'baseline', 'front_alignment.camber', '-1.2 deg')
    wait_for(page, lambda d: cell(d, 'baseline', 'front_alignment').get_attribute(
        'data-state') == 'MODIFIED')
    wait_for(page, lambda d: cell(d, 'baseline', 'front_alignment').value_of_css_property(
        'background-color') == COLOURS['MODIFIED'])
    assert page.find_element(By.ID, 'message').text == (
        'baseline: front_alignment.camber = -1.2 deg')
    assert '    overrides:\n      front_alignment.camber: -1.2 deg\n' in sedan_master.read_text()
    wait_for(page, lambda d: 'front_alignment.camber = -1.2 deg' in d.find_element(
        By.ID, 'overrides-baseline').text)


def test_a_bad_value_is_refused_and_nothing_changes(page: Any, sample_root: Path,
                                                    sedan_master: Path) -> None:
    from selenium.webdriver.common.by import By

    before = tree_snapshot(sample_root)
    type_override(page, 'baseline', 'front_alignment.camber', '-1.2 kg')
    expected = (f'{sedan_master}: configurations.baseline.overrides.front_alignment.camber: '
                "unit 'kg' is not an angle unit (expected e.g. 'rad')")
    wait_for(page, lambda d: d.find_element(By.ID, 'message').text == expected)
    assert 'error' in page.find_element(By.ID, 'message').get_attribute('class')
    assert tree_snapshot(sample_root) == before
    wait_for(page, lambda d: cell(d, 'baseline', 'front_alignment').get_attribute('data-state')
             == 'UNCHANGED')


def test_an_edit_of_a_data_file_on_disk_updates_the_page(page: Any, sample_root: Path) -> None:
    from selenium.webdriver.common.by import By

    wait_for(page, lambda d: d.find_element(By.ID, 'tab-front_spring').click() or True)
    value = wait_for(page, lambda d: d.find_element(By.ID, 'value-front_spring-baseline-rate'))
    assert value.text == '30'
    replace_once(sample_root / 'sedan/front_spring/X.yaml', 'rate: 30.0', 'rate: 32.5')
    wait_for(page, lambda d: d.find_element(By.ID, 'value-front_spring-baseline-rate').text
             == '32.5')
    # a shared file changed for everyone: the configuration still uses it unchanged
    wait_for(page, lambda d: d.find_element(By.ID, 'tab-overview').click() or True)
    wait_for(page, lambda d: cell(d, 'baseline', 'front_spring').get_attribute('data-state')
             == 'UNCHANGED')


def test_the_page_says_when_edits_are_off(driver: Any, sedan_master: Path) -> None:
    from selenium.webdriver.common.by import By

    from vd_data_server.workbench.server import Workbench, WorkbenchServer

    server = WorkbenchServer(Workbench(sedan_master))
    server.start()
    try:
        driver.get(server.url)
        note = wait_for(driver, lambda d: d.find_element(By.ID, 'edits-off'))
        assert note.text.startswith('Edits are off')
        assert not driver.find_elements(By.ID, 'ov-set')
    finally:
        driver.get('about:blank')
        server.stop()


def test_screenshots_of_the_tabs(sedan_master: Path, tmp_path: Path) -> None:
    from vd_data_server.workbench.browser import save_screenshots

    out = tmp_path / 'img'
    paths = save_screenshots(sedan_master, out, groups=['front_hardpoints'])
    assert [p.name for p in paths] == ['workbench-overview.png',
                                       'workbench-front_hardpoints.png']
    assert all(p.read_bytes()[:8] == b'\x89PNG\r\n\x1a\n' for p in paths)
    shutil.rmtree(out)
