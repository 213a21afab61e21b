# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""Shared fixtures: sample data copies and a private ROS graph for node tests."""
from __future__ import annotations

from collections.abc import Iterator
import os
from pathlib import Path
import shutil

import pytest

REPO = Path(__file__).resolve().parents[1]
SAMPLE_DATA = REPO / 'src' / 'vd_data_server' / 'data'


@pytest.fixture
def sample_root(tmp_path: Path) -> Path:
    """Return a writable copy of the bundled data root (tests edit it)."""
    root = tmp_path / 'data'
    shutil.copytree(SAMPLE_DATA, root)
    return root


@pytest.fixture
def sedan_master(sample_root: Path) -> Path:
    return sample_root / 'studies' / 'sedan.yaml'


@pytest.fixture(scope='session')
def ros_domain() -> Iterator[int]:
    """Rclpy initialised once, in a private domain on loopback."""
    import rclpy

    from vd_events.orchestration.domain import claim_domain

    os.environ['ROS_AUTOMATIC_DISCOVERY_RANGE'] = 'LOCALHOST'
    # claimed like a run's domain, so the runs of this session (and of other sessions
    # on the machine) never share it
    claim = claim_domain()
    os.environ['ROS_DOMAIN_ID'] = str(claim.domain)
    rclpy.init(domain_id=claim.domain)
    yield claim.domain
    rclpy.try_shutdown()
    claim.release()
