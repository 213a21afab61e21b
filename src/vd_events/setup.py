# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
from glob import glob

from setuptools import find_packages, setup

package_name = 'vd_events'

setup(
    name=package_name,
    version='0.1.0',
    packages=find_packages(exclude=['test']),
    package_data={package_name: ['reports/templates/*', 'measured/data/*']},  # pages, bands
    data_files=[
        ('share/ament_index/resource_index/packages', ['resource/' + package_name]),
        ('share/' + package_name, ['package.xml']),
        ('share/' + package_name + '/plans', glob('plans/*.yaml')),
        ('share/' + package_name + '/samples', glob('samples/*')),
        ('share/' + package_name + '/launch', glob('launch/*.launch.*')),
        ('share/' + package_name + '/launch', glob('launch/*.rviz') + glob('launch/*.json')),
    ],
    install_requires=['setuptools'],
    extras_require={'test': ['pytest']},
    zip_safe=True,
    maintainer='vd maintainers',
    maintainer_email='maintainers@vd-sim.org',
    description='vd events: event runner, recorder, reports, vd CLI',
    license='Apache-2.0',
    entry_points={
        'console_scripts': [
            'event_runner = vd_events.nodes.event_runner:main',
            'recorder = vd_events.nodes.recorder:main',
            'rig_bridge = vd_events.nodes.rig_bridge:main',
            'path_follower = vd_events.nodes.path_follower:main',
            'vd = vd_events.cli.main:main',
        ],
    },
)
