# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""Where the bundled sample data lives (installed share/ or the source tree)."""
from __future__ import annotations

from pathlib import Path

PACKAGE = 'vd_data_server'
SAMPLE_STUDY = 'studies/sedan.yaml'


def sample_data_root() -> Path:
    """Return the bundled data root: the installed share folder if there is one."""
    try:
        from ament_index_python.packages import PackageNotFoundError, get_package_share_directory
    except ImportError:  # a plain Python environment without ROS
        return _source_root()
    try:
        installed = Path(get_package_share_directory(PACKAGE)) / 'data'
    except (PackageNotFoundError, OSError):  # OSError: no AMENT_PREFIX_PATH at all
        return _source_root()
    return installed if installed.is_dir() else _source_root()


def _source_root() -> Path:
    return Path(__file__).resolve().parents[1] / 'data'


def default_master() -> Path:
    """Return the bundled sample study (the sedan)."""
    return sample_data_root() / SAMPLE_STUDY
