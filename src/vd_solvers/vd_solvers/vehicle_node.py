"""
``ros2 run vd_solvers vehicle_solver``: the full-vehicle dynamics solver.

Action ``/vd/vehicle/run_event`` (vd_interfaces/RunEvent; events constant_radius_turn and
step_steer, goal.fidelity rigid|flexible passed to the K&C maps); results on
``/vd/vehicle/result``, one ``VehicleState`` per recorded step on ``/vd/vehicle/state``
(named fields, four ``VehicleWheel``s) with header stamps on the simulation-time axis
(run start + simulated time), and the body
pose as ``nav_msgs/Odometry`` on ``/vd/vehicle/odom`` (frame ``odom``, child
``base_link``, REP 105) and as TF on ``/tf`` (``tf2_msgs/TFMessage``), stamped alike.

Parameter ``mode``: ``events`` (default, the above), ``lockstep`` or ``free``: the
co-simulation of :mod:`vd_solvers.lockstep` -- one vehicle of ``configuration`` driven
step by step by an external controller (``/clock``, state, odometry and TF out,
``vd_interfaces/VehicleCommand`` in); docs/ros-api.md.
"""
from __future__ import annotations

from nav_msgs.msg import Odometry
from rcl_interfaces.msg import ParameterDescriptor
import rclpy
from rclpy.executors import ExternalShutdownException

from tf2_msgs.msg import TFMessage
from vd_data_server.errors import DataError
from vd_data_server.model import Configuration
from vd_data_server.node_main import die_with_parent, spin_guarded
from vd_interfaces.msg import VehicleState
from vd_solvers.conversions import outcome_odometry, outcome_transforms, outcome_vehicle_states
from vd_solvers.errors import SolverError
from vd_solvers.results import EventOutcome
from vd_solvers.solver_node import SAMPLES, SolverNode
from vd_solvers.vehicle.events import run_vehicle_event

FAMILY = 'vehicle'
MODES = ('events', 'lockstep', 'free')
#: lock-step parameters: name -> (default, description)
LOCKSTEP_PARAMS = {
    'configuration': ('', "configuration to drive ('' = the study's first)"),
    'master': ('', "master file ('' = the bundled sample study)"),
    'fidelity': ('rigid', 'K&C maps: rigid | flexible'),
    'step': (0.005, 'integration step = lock-step, s'),
    'initial_speed': (0.0, 'speed at t = 0, m/s (straight ahead)'),
    'duration': (0.0, 'simulated time after which the session finishes, s (0: no end)'),
    'command_timeout': (2.0, 'wall seconds to wait for the command of a step'),
    'start_timeout': (30.0, 'wall seconds to wait for the first command'),
    'real_time_factor': (1.0, 'free mode: simulated seconds per wall second'),
    'drive_front': (0.5, 'front share of the drive torque'),
    'brake_front': (0.65, 'front share of the brake torque'),
}


def _run(config: Configuration, goal, progress) -> EventOutcome:
    return run_vehicle_event(config, goal.event, list(goal.parameters), goal.fidelity or 'rigid',
                             progress)


class VehicleSolver(SolverNode):
    STATE_TYPE = VehicleState

    def __init__(self, **kwargs) -> None:
        super().__init__('vehicle_solver', FAMILY, _run, **kwargs)
        self.odom_pub = self.create_publisher(Odometry, f'/vd/{FAMILY}/odom', SAMPLES)
        # the moving frame for RViz and Foxglove (TF: odom -> base_link, REP 105)
        self.tf_pub = self.create_publisher(TFMessage, '/tf', SAMPLES)
        self.declare_parameter('mode', 'events', ParameterDescriptor(
            description='events | lockstep | free', read_only=True))
        self.mode = self.get_parameter('mode').value
        self.lockstep = None
        if self.mode != 'events':
            self.lockstep = self._start_lockstep()

    def _start_lockstep(self):
        """Build the vehicle and start the co-simulation session (ValueError if unusable)."""
        from vd_data_server.paths import default_master
        from vd_data_server.study import load_study
        from vd_solvers.lockstep import LockstepSession
        from vd_solvers.vehicle.cosim import Stepper
        from vd_solvers.vehicle.model import VehicleModel

        if self.mode not in MODES:
            raise ValueError(f"parameter 'mode' must be one of {', '.join(MODES)}, "
                             f'got {self.mode!r}')
        p = {}
        for name, (default, doc) in LOCKSTEP_PARAMS.items():
            numeric = isinstance(default, float)
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
        from pathlib import Path

        study = load_study(Path(p['master']) if p['master'] else default_master())
        name = p['configuration'] or study.configuration_names[0]
        if name not in study.configurations:
            raise ValueError(f"configuration '{name}' is not in the study (configurations: "
                             f"{', '.join(study.configuration_names)})")
        model = VehicleModel(study.configurations[name], p['fidelity'])
        stepper = Stepper(model, float(p['step']), float(p['initial_speed']),
                          float(p['drive_front']), float(p['brake_front']))
        self.get_logger().info(f"{self.mode} co-simulation of '{name}': step "
                               f"{stepper.h * 1e3:g} ms")
        return LockstepSession(self, stepper, mode=self.mode, duration=float(p['duration']),
                               command_timeout=p['command_timeout'],
                               start_timeout=p['start_timeout'],
                               real_time_factor=p['real_time_factor'], configuration=name,
                               state_pub=self.sample_pub, odom_pub=self.odom_pub,
                               tf_pub=self.tf_pub)

    def publish_outcome(self, outcome: EventOutcome, config: Configuration, changes: list) -> None:
        stamp = self.get_clock().now().to_msg()
        # odometry and TF first: a recorder stops once the result and its samples are in
        for msg in outcome_transforms(outcome, stamp):
            self.tf_pub.publish(msg)
        for msg in outcome_odometry(outcome, stamp):
            self.odom_pub.publish(msg)
        super().publish_outcome(outcome, config, changes, stamp=stamp)

    def state_messages(self, outcome: EventOutcome, stamp) -> list:
        return outcome_vehicle_states(outcome, stamp)


def main(args=None) -> None:
    """Spin the solver; in lockstep/free mode on the events executor (docs/ros-api.md)."""
    import sys

    from rclpy.executors import MultiThreadedExecutor
    from rclpy.experimental import EventsExecutor

    die_with_parent()
    rclpy.init(args=args)
    node = None
    try:
        try:
            node = VehicleSolver()
        except (ValueError, SolverError, DataError) as err:
            print(f'vehicle_solver: {err}', file=sys.stderr)
            raise SystemExit(2) from None
        executor = MultiThreadedExecutor(num_threads=2) if node.mode == 'events' \
            else EventsExecutor()
        executor.add_node(node)
        spin_guarded(executor, node)
    except (KeyboardInterrupt, ExternalShutdownException):
        pass
    finally:
        if node is not None:
            node.destroy_node()
        rclpy.try_shutdown()


if __name__ == '__main__':
    main()
