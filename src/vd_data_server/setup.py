# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
from glob import glob
import os

from setuptools import find_packages, setup

package_name = 'vd_data_server'


def data_tree(root):
    """(install dir, files) pairs that keep the sample data's folder layout."""
    pairs = []
    for folder, _, files in os.walk(root):
        if files:
            pairs.append((os.path.join('share', package_name, folder),
                          [os.path.join(folder, f) for f in files]))
    return pairs


setup(
    name=package_name,
    version='0.1.0',
    packages=find_packages(exclude=['test']),
    package_data={package_name: ['workbench/web/*']},  # the workbench page (vd gui)
    data_files=[
        ('share/ament_index/resource_index/packages', ['resource/' + package_name]),
        ('share/' + package_name, ['package.xml']),
        ('share/' + package_name + '/launch', glob('launch/*.launch.*')),
        *data_tree('data'),
    ],
    install_requires=['setuptools'],
    extras_require={'test': ['pytest']},
    zip_safe=True,
    maintainer='vd maintainers',
    maintainer_email='maintainers@vd-sim.org',
    description='vd data server: vehicle data files, master files, feedback',
    license='Apache-2.0',
    entry_points={
        'console_scripts': [
            'data_server = vd_data_server.nodes.data_server:main',
        ],
    },
)
