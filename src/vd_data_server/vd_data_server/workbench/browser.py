# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Headless Chromium (Debian's chromium and chromium-driver) driven by Selenium.

Used by ``vd gui --screenshots DIR`` and by the workbench's browser tests.
"""
from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager
import os
from pathlib import Path
import shutil
import tempfile
from typing import Any

from PIL import Image

from vd_data_server.workbench.server import Workbench, WorkbenchServer

CHROMIUM = '/usr/bin/chromium'
CHROMEDRIVER = '/usr/bin/chromedriver'
#: the longest wait for the page to show something (generous: a loaded CI machine; the
#: page normally follows a change within a second)
WAIT_TIMEOUT = 30.0
WINDOW = (1500, 1000)


def unavailable() -> str:
    """Why the browser cannot run here ('' when it can)."""
    try:
        import selenium  # noqa: F401 - only whether it is installed
    except ImportError:
        return 'the selenium package is not installed (make setup installs it)'
    for path, package in ((CHROMIUM, 'chromium'), (CHROMEDRIVER, 'chromium-driver')):
        if not (os.path.isfile(path) and os.access(path, os.X_OK)):
            return (f"{path} is missing: Debian's package {package} is not installed "
                    '(tools/setup.sh installs it when it runs as root with apt-get)')
    return ''


@contextmanager
def browser(profile: Path) -> Iterator[Any]:
    """Start a headless Chromium with a new empty profile; quit it at the end."""
    from selenium import webdriver
    from selenium.webdriver.chrome.service import Service

    options = webdriver.ChromeOptions()
    options.binary_location = CHROMIUM
    for flag in ('--headless=new', '--no-sandbox', '--disable-gpu', '--disable-quic',
                 '--no-first-run', '--disable-background-networking',
                 '--disable-component-update', '--disable-sync', '--disable-dev-shm-usage',
                 f'--user-data-dir={profile}', f'--window-size={WINDOW[0]},{WINDOW[1]}'):
        options.add_argument(flag)
    driver = webdriver.Chrome(service=Service(executable_path=CHROMEDRIVER), options=options)
    try:
        driver.set_page_load_timeout(20)
        yield driver
    finally:
        driver.quit()


def wait_for(driver: Any, condition: Any, timeout: float = WAIT_TIMEOUT) -> Any:
    """Wait until ``condition(driver)`` holds; the page re-rendering meanwhile is fine."""
    from selenium.common.exceptions import NoSuchElementException, StaleElementReferenceException
    from selenium.webdriver.support.ui import WebDriverWait

    return WebDriverWait(driver, timeout, poll_frequency=0.05, ignored_exceptions=(
        NoSuchElementException, StaleElementReferenceException)).until(condition)


def full_page_screenshot(driver: Any, path: Path) -> Path:
    """Save the whole page (the window grown to the document's height)."""
    height = driver.execute_script('return document.documentElement.scrollHeight')
    width = driver.execute_script('return document.documentElement.scrollWidth')
    driver.set_window_size(max(WINDOW[0], int(width) + 20), min(int(height) + 140, 6000))
    driver.save_screenshot(str(path))
    driver.set_window_size(*WINDOW)
    _shrink(path)
    return path


def _shrink(path: Path) -> None:
    """Store the screenshot with a palette of its colours (a page has few): ~4x smaller."""
    with Image.open(path) as image:
        small = image.convert('RGB').quantize(colors=128, method=Image.Quantize.MEDIANCUT)
    small.save(path, optimize=True)


def save_screenshots(master: Path, out: Path, *, edits: bool = False,
                     groups: list[str] | None = None) -> list[Path]:
    """Save a PNG of the overview and of every group tab (or of ``groups``) into ``out``."""
    from selenium.webdriver.common.by import By


    reason = unavailable()
    if reason:
        from vd_data_server.errors import DataError

        raise DataError(f'cannot take screenshots: {reason}')
    out.mkdir(parents=True, exist_ok=True)
    server = WorkbenchServer(Workbench(master, edits=edits))
    server.start()
    profile = Path(tempfile.mkdtemp(prefix='vd-chromium-'))
    paths = []
    try:
        with browser(profile) as driver:
            driver.get(server.url)
            wait_for(driver, lambda d: d.find_elements(By.ID, 'overview'))
            paths.append(full_page_screenshot(driver, out / 'workbench-overview.png'))
            tabs = server.workbench.state()['status']['groups']
            for group in [g for g in tabs if groups is None or g in groups]:
                driver.find_element(By.ID, f'tab-{group}').click()
                wait_for(driver, lambda d, g=group: d.find_elements(By.ID, f'group-{g}'))
                paths.append(full_page_screenshot(driver, out / f'workbench-{group}.png'))
    finally:
        server.stop()
        shutil.rmtree(profile, ignore_errors=True)
    return paths
