# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
``ros2 run vd_solvers vehicle_solver``: the full-vehicle dynamics solver.

Names relative to the node's namespace (``/vd`` by default). Action ``vehicle/run_event``
(vd_interfaces/RunEvent; events constant_radius_turn and step_steer, goal.fidelity
rigid|flexible passed to the K&C maps, empty: the configuration's flexible switch); results
on ``vehicle/result``, one ``VehicleState`` per recorded step on ``vehicle/state`` (named
fields, four ``VehicleWheel``s) with header stamps on the simulation-time axis (run start +
simulated time), and the body pose as ``nav_msgs/Odometry`` on ``vehicle/odom`` (frame
``odom``, child ``base_link``, REP 105) and as TF on the global ``/tf``
(``tf2_msgs/TFMessage``), stamped alike. Outside the default namespace the frames carry the
parameter ``frame_prefix`` (default: the namespace, ``car2/odom`` -> ``car2/base_link``),
so several vehicles share one TF tree.

Parameter ``mode``: ``events`` (default, the above), ``lockstep`` or ``free``: the
co-simulation of :mod:`vd_solvers.nodes.lockstep` -- one vehicle of ``configuration`` driven
step by step by an external controller (``/clock``, state, odometry and TF out,
``vd_interfaces/VehicleCommand`` in); docs/ros-api.md.
"""
from __future__ import annotations

from pathlib import Path
import sys

from nav_msgs.msg import Odometry
from rcl_interfaces.msg import ParameterDescriptor
from rclpy.executors import Executor
from rclpy.experimental import EventsExecutor
from rclpy.lifecycle import LifecycleNode, TransitionCallbackReturn

from tf2_msgs.msg import TFMessage
from vd_data_server.errors import DataError
from vd_data_server.paths import default_master
from vd_data_server.ros.node_main import make_executor, run_node
from vd_data_server.ros.qos import STATES, TF
from vd_data_server.study import load_study
from vd_interfaces.msg import VehicleState
from vd_solvers.errors import SolverError
from vd_solvers.families import ODOMETRY_TOPIC, TF_TOPIC
from vd_solvers.nodes.lockstep import LockstepSession
from vd_solvers.nodes.solver import SolverNode
from vd_solvers.solve import run_function
from vd_solvers.vehicle.actuators import Actuators, parameters_of
from vd_solvers.vehicle.cosim import Stepper
from vd_solvers.vehicle.description import describe_model
from vd_solvers.vehicle.model import VehicleModel

FAMILY = 'vehicle'
MODES = ('events', 'lockstep', 'free')
#: lock-step parameters: name -> (default, description)
LOCKSTEP_PARAMS = {
    'configuration': ('', "configuration to drive ('' = the study's first)"),
    'master': ('', "master file ('' = the bundled sample study)"),
    'fidelity': ('', "K&C maps: rigid | flexible ('' = the configuration's flexible switch)"),
    'step': (0.005, 'integration step = lock-step, s'),
    'initial_speed': (0.0, 'speed at t = 0, m/s (straight ahead)'),
    'duration': (0.0, 'simulated time after which the session finishes, s (0: no end)'),
    'command_timeout': (2.0, 'wall seconds to wait for the command of a step'),
    'start_timeout': (30.0, 'wall seconds to wait for the first command'),
    'real_time_factor': (1.0, 'free mode: simulated seconds per wall second'),
    'drive_front': (0.5, 'front share of the drive torque'),
    'brake_front': (0.65, 'front share of the brake torque'),
    # the actuator model of the Ackermann and Twist inputs (vd_solvers.vehicle.actuators)
    'steering_lag': (0.05, 'time constant of the steering actuator, s'),
    'torque_lag': (0.05, 'time constant of the drive and brake torque, s'),
    'speed_gain': (1.5, 'speed controller: proportional gain, (m/s^2) per (m/s)'),
    'speed_integral': (0.3, 'speed controller: integral gain, (m/s^2) per m'),
}
#: the parameters that go to the actuator model
ACTUATOR_PARAMS = ('steering_lag', 'torque_lag', 'speed_gain', 'speed_integral')


class VehicleSolver(SolverNode, LifecycleNode):
    """
    The full-vehicle solver; the body pose also as odometry and TF.

    A managed (lifecycle) node. In ``lockstep``/``free`` mode: configure = load the study
    and build the vehicle (its K&C maps), activate = start the session (again from t = 0
    if it ran before), deactivate = hold it, cleanup = drop the session and the vehicle.
    With ``autostart`` (default) the node configures and activates itself at start, as
    before; a failing configure then ends the construction with its ValueError. In
    ``events`` mode the transitions change nothing: the action is always served.
    """

    STATE_TYPE = VehicleState

    def __init__(self, **kwargs) -> None:
        super().__init__('vehicle_solver', FAMILY, run_function(FAMILY), **kwargs)
        self.odom_pub = self.create_publisher(Odometry, ODOMETRY_TOPIC, STATES)
        # the moving frame for RViz and Foxglove (TF: odom -> base_link, REP 105)
        self.tf_pub = self.create_publisher(TFMessage, TF_TOPIC, TF)
        self.publishers_by_topic.update({ODOMETRY_TOPIC: self.odom_pub, TF_TOPIC: self.tf_pub})
        self.declare_parameter('mode', 'events', ParameterDescriptor(
            description='events | lockstep | free', read_only=True))
        self.mode = self.get_parameter('mode').value
        self.lockstep: LockstepSession | None = None
        self._vehicle: dict | None = None  # what configure built, for activate
        self._failure: Exception | None = None  # why the last transition failed
        autostart = self.declare_parameter('autostart', True, ParameterDescriptor(
            description='lockstep/free: configure and activate at start', read_only=True)).value
        if self.mode != 'events' and autostart:
            try:
                for trigger in (self.trigger_configure, self.trigger_activate):
                    trigger()
                    if self._failure is not None:
                        raise self._failure
            except BaseException:
                self.destroy_node()  # an unusable session leaves no node behind
                raise

    # --- lifecycle (docs/ros-api.md) --------------------------------------------------

    def _attempt(self, action) -> TransitionCallbackReturn:
        self._failure = None
        try:
            action()
        except (ValueError, SolverError, DataError) as err:
            self._failure = err
            self.get_logger().error(str(err))
            return TransitionCallbackReturn.FAILURE
        return TransitionCallbackReturn.SUCCESS

    def on_configure(self, state) -> TransitionCallbackReturn:
        if self.mode == 'events':
            return TransitionCallbackReturn.SUCCESS
        return self._attempt(self._configure)

    def on_activate(self, state) -> TransitionCallbackReturn:
        if self.mode == 'events':
            return super().on_activate(state)
        result = self._attempt(self._activate)
        return super().on_activate(state) if result == TransitionCallbackReturn.SUCCESS \
            else result

    def on_deactivate(self, state) -> TransitionCallbackReturn:
        if self.lockstep is not None:
            self.lockstep.hold()
        return super().on_deactivate(state)

    def on_cleanup(self, state) -> TransitionCallbackReturn:
        if self.lockstep is not None:
            self.lockstep.close()
        self.lockstep, self._vehicle = None, None
        return TransitionCallbackReturn.SUCCESS

    def on_shutdown(self, state) -> TransitionCallbackReturn:
        return self.on_cleanup(state)

    def _activate(self) -> None:
        """Start the session, or start it again from t = 0."""
        if self.lockstep is not None:
            self.lockstep.reset()
            return
        assert self._vehicle is not None  # configured
        v = self._vehicle
        p = v['parameters']
        stepper = Stepper(v['model'], float(p['step']), float(p['initial_speed']),
                          float(p['drive_front']), float(p['brake_front']))
        actuators = Actuators(v['actuators'], speed=float(p['initial_speed']))
        self.get_logger().info(f"{self.mode} co-simulation of '{v['name']}': step "
                               f"{stepper.h * 1e3:g} ms")
        self.lockstep = LockstepSession(
            self, stepper, mode=self.mode, duration=float(p['duration']),
            command_timeout=p['command_timeout'], start_timeout=p['start_timeout'],
            real_time_factor=p['real_time_factor'], configuration=v['name'],
            state_pub=self.sample_pub, odom_pub=self.odom_pub, tf_pub=self.tf_pub,
            actuators=actuators, description=v['description'],
            frame_prefix=self.frame_prefix)

    def _configure(self) -> None:
        """Load the study and build the vehicle (ValueError if unusable)."""
        if self.mode not in MODES:
            raise ValueError(f"parameter 'mode' must be one of {', '.join(MODES)}, "
                             f'got {self.mode!r}')
        p = {}
        for name, (default, doc) in LOCKSTEP_PARAMS.items():
            numeric = isinstance(default, float)
            if not self.has_parameter(name):  # declared by an earlier configure
                self.declare_parameter(name, default, ParameterDescriptor(
                    description=doc, read_only=True, dynamic_typing=numeric))
            value = self.get_parameter(name).value
            if numeric:
                if isinstance(value, bool) or not isinstance(value, (int, float)):
                    raise ValueError(f"parameter '{name}' must be a number, got {value!r}")
                value = float(value)
            elif not isinstance(value, str):
                raise ValueError(f"parameter '{name}' must be a string, got {value!r}")
            p[name] = value
        for name in ('command_timeout', 'start_timeout', 'real_time_factor'):
            if not (0.0 < p[name] < 1e6):
                raise ValueError(f"parameter '{name}' must be a positive number of seconds "
                                 f"(or factor), got {p[name]!r}")
        for name in ('initial_speed', 'duration'):
            if not (0.0 <= p[name] < 1e6):
                raise ValueError(f"parameter '{name}' must be >= 0, got {p[name]!r}")

        study = load_study(Path(p['master']) if p['master'] else default_master())
        name = p['configuration'] or study.configuration_names[0]
        if name not in study.configurations:
            raise ValueError(f"configuration '{name}' is not in the study (configurations: "
                             f"{', '.join(study.configuration_names)})")
        model = VehicleModel(study.configurations[name], p['fidelity'])
        Stepper(model, float(p['step']))  # the step size is checked now, not at activate
        self._vehicle = {
            'name': name, 'model': model, 'parameters': p,
            'actuators': parameters_of(model, **{k: p[k] for k in ACTUATOR_PARAMS}),
            'description': describe_model(model)}


def main(args=None) -> None:
    """Spin the solver; in lockstep/free mode on the events executor (docs/ros-api.md)."""

    def build() -> VehicleSolver:
        try:
            return VehicleSolver()
        except (ValueError, SolverError, DataError) as err:
            print(f'vehicle_solver: {err}', file=sys.stderr)
            raise SystemExit(2) from None

    def executor(node) -> Executor:
        return make_executor(2) if node.mode == 'events' else EventsExecutor()

    run_node(build, args=args, executor=executor)


if __name__ == '__main__':
    main()
