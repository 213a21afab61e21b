# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
from glob import glob

from setuptools import find_packages, setup

package_name = 'vd_solvers'

setup(
    name=package_name,
    version='0.1.0',
    packages=find_packages(exclude=['test']),
    data_files=[
        ('share/ament_index/resource_index/packages', ['resource/' + package_name]),
        ('share/' + package_name, ['package.xml']),
        ('share/' + package_name + '/launch', glob('launch/*.launch.*')),
    ],
    install_requires=['setuptools'],
    extras_require={'test': ['pytest']},
    zip_safe=True,
    maintainer='vd maintainers',
    maintainer_email='maintainers@vd-sim.org',
    description='vd solvers: analytical, K&C and full-vehicle models and their nodes',
    license='Apache-2.0',
    entry_points={
        'console_scripts': [
            'analytical_solver = vd_solvers.nodes.analytical:main',
            'kc_solver = vd_solvers.nodes.kc:main',
            'vehicle_solver = vd_solvers.nodes.vehicle:main',
        ],
    },
)
