# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
``ros2 run vd_data_server data_server``: publishes the master file's data.

Names are relative to the node's namespace (``/vd`` unless remapped with ``__ns:=``).
Topics (reliable + transient_local, so late subscribers get everything):
  configuration  vd_interfaces/Configuration, exactly one message per configuration
  data_status    vd_interfaces/DataStatus, the modified/unchanged feedback
Services: get_configuration, set_override (only with allow_edits), reload.
Parameters (all read-only once the node runs): master_file, allow_edits, watch_period
(s; 0 disables watching). The trust model is in docs/ros-api.md.

A bad file, edit or reload never stops the node: it keeps serving the last good
data and reports the error on /vd/data_status.
"""
from __future__ import annotations

from rcl_interfaces.msg import ParameterDescriptor
from rclpy.node import Node
from rclpy.publisher import Publisher

from vd_data_server.conversions import configuration_to_msg, study_to_status_msg
from vd_data_server.errors import DataError
from vd_data_server.paths import default_master
from vd_data_server.ros import names
from vd_data_server.ros.node_main import spin_node
from vd_data_server.ros.qos import LATEST, latched
from vd_data_server.service import DataService
from vd_interfaces.msg import Configuration as ConfigurationMsg
from vd_interfaces.msg import DataStatus
from vd_interfaces.srv import GetConfiguration, Reload, SetOverride


class DataServer(Node):
    """The data server node: configurations and feedback out, edits and reloads in."""

    def __init__(self, *, study=None, **kwargs) -> None:
        """Build the node; ``study``: the master file's study, already loaded in-process."""
        kwargs.setdefault('namespace', names.DEFAULT_NAMESPACE)
        super().__init__('data_server', **kwargs)
        self.declare_parameter('master_file', str(default_master()), ParameterDescriptor(
            description='master file (study) to serve', read_only=True))
        # read-only: a participant on the domain must not switch edits on for itself
        self.declare_parameter('allow_edits', False, ParameterDescriptor(
            description='accept /vd/set_override requests (fixed at start)', read_only=True))
        self.declare_parameter('watch_period', 0.5, ParameterDescriptor(
            description='seconds between checks of the data files (0: do not watch)',
            read_only=True))
        edits = self.resolve_service_name(names.SET_OVERRIDE)
        self.service = DataService(self.get_parameter('master_file').value,
                                   edit_source=f'ROS edit {edits}')
        # created for the study's number of configurations
        self.config_pub: Publisher | None = None
        self.status_pub = self.create_publisher(DataStatus, names.DATA_STATUS, LATEST)
        self.create_service(GetConfiguration, names.GET_CONFIGURATION, self._get_configuration)
        self.create_service(SetOverride, names.SET_OVERRIDE, self._set_override)
        self.create_service(Reload, names.RELOAD, self._reload)
        self._publish_outcome(self.service.load(study))
        period = float(self.get_parameter('watch_period').value)
        if period > 0.0:
            self.create_timer(period, self._poll)

    def _poll(self) -> None:
        outcome = self.service.poll()
        if outcome is not None:
            self._publish_outcome(outcome)

    def _publish_outcome(self, outcome) -> None:
        for line in outcome.errors:
            self.get_logger().error(line)
        if outcome.changed:
            self.publish_all()
        elif self.service.study is not None:
            self._publish_status()
        else:
            self.status_pub.publish(DataStatus(master_file=str(self.service.master_file),
                                               errors=list(outcome.errors),
                                               stamp=self.get_clock().now().to_msg()))

    def publish_all(self) -> None:
        """
        Publish every configuration, then the status.

        The publisher keeps exactly one message per configuration (its depth is their
        number; a study with another number gets a new publisher), so a late joiner
        receives the current version of each, never an older one or a removed one.
        """
        stamp = self.get_clock().now().to_msg()
        study = self.service.study
        assert study is not None
        depth = len(study.configurations)
        if self.config_pub is None or self.config_pub.qos_profile.depth != depth:
            if self.config_pub is not None:
                self.destroy_publisher(self.config_pub)
            self.config_pub = self.create_publisher(ConfigurationMsg, names.CONFIGURATION,
                                                    latched(depth))
        for config in study.configurations.values():
            self.config_pub.publish(configuration_to_msg(config, stamp))
        self._publish_status()
        self.get_logger().info(f'published {len(study.configurations)} configurations of '
                               f'{study.master.path}')

    def _publish_status(self) -> None:
        study = self.service.study
        assert study is not None
        self.status_pub.publish(study_to_status_msg(study, self.service.errors,
                                                    self.get_clock().now().to_msg()))

    def _get_configuration(self, request, response):
        configs = self.service.configurations()
        if request.name not in configs:
            response.success = False
            response.message = (f"configuration '{request.name}' does not exist (available: "
                                f"{', '.join(configs)})")
            return response
        response.success = True
        response.configuration = configuration_to_msg(configs[request.name],
                                                      self.get_clock().now().to_msg())
        return response

    def _set_override(self, request, response):
        if not self.get_parameter('allow_edits').value:
            response.success = False
            response.message = ('edits are disabled (start the data server with parameter '
                                'allow_edits:=true)')
            return response
        try:
            self.service.set_override(request.configuration, request.key, request.value)
        except DataError as err:
            response.success = False
            response.message = str(err)
            return response
        self.publish_all()
        response.success = True
        response.message = f'{request.configuration}: {request.key} = {request.value}'
        return response

    def _reload(self, request, response):
        outcome = self.service.load()
        self._publish_outcome(outcome)
        response.success = not outcome.errors
        response.message = '\n'.join(outcome.errors) or 'reloaded'
        return response


def main(args=None) -> None:
    """Entry point of ``ros2 run vd_data_server data_server``."""
    spin_node(DataServer, args, threads=1)


if __name__ == '__main__':
    main()
