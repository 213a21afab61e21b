# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
The one definition of the vd graph: which nodes ``vd launch`` and the launch files start.

``graph()`` lists the nodes (package, executable, parameters): the data server and one
solver per family. ``vd launch`` starts them in one process (``node_class``) or as
processes (``command``); ``vd run --distributed`` starts the ones its runs need; the
launch file ``vd_events/launch/vd.launch.py`` turns the same list into
``launch_ros`` Node actions for ``ros2 launch``. Every node starts in ``namespace``
(``/vd`` by default; ``__ns:=`` remaps it), so its relative names move with it.
"""
from __future__ import annotations

from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path

from ament_index_python.packages import get_package_prefix

from vd_data_server.ros import names
from vd_solvers.families import FAMILIES
from vd_solvers.nodes.solver import SolverNode


@dataclass(frozen=True)
class NodeSpec:
    """One node of the graph: ``ros2 run PACKAGE EXECUTABLE -p NAME:=VALUE ...``."""

    package: str
    executable: str
    parameters: Mapping[str, object] = field(default_factory=dict)
    #: node name of another instance of the executable (``-r __node:=NAME``); None: default
    name: str | None = None


def data_server(master: Path | str | None = None, *, watch_period: float | None = None,
                allow_edits: bool | None = None) -> NodeSpec:
    """Return the data server's node (parameters left out keep the node's defaults)."""
    params: dict[str, object] = {}
    if master is not None:
        params['master_file'] = str(master)
    if watch_period is not None:
        params['watch_period'] = float(watch_period)
    if allow_edits is not None:
        params['allow_edits'] = bool(allow_edits)
    return NodeSpec('vd_data_server', 'data_server', params)


def instance_names(family: str, count: int) -> list[str]:
    """Return the node names of ``count`` instances: the executable, then _2, _3, ..."""
    base = FAMILIES[family].executable
    return [base] + [f'{base}_{i}' for i in range(2, count + 1)]


def solver(family: str, name: str | None = None) -> NodeSpec:
    """Return the solver node of ``family`` (``steady_state``, ``kc``, ``vehicle``)."""
    executable = FAMILIES[family].executable
    return NodeSpec('vd_solvers', executable, name=None if name == executable else name)


def graph(master: Path | str | None = None, *, watch_period: float | None = None,
          allow_edits: bool | None = None, families: Iterable[str] | None = None,
          instances: Mapping[str, int] | None = None) -> list[NodeSpec]:
    """
    Return the graph: the data server and the solvers (default: one of every family).

    ``instances`` (family -> count, ``vd launch --solvers kc=2``) adds instances named
    ``kc_solver_2``, ... (each serves its own action, ``families.Family.action``).
    """
    chosen = list(FAMILIES) if families is None else sorted(set(families))
    counts = dict.fromkeys(chosen, 1)
    counts.update(instances or {})
    return [data_server(master, watch_period=watch_period, allow_edits=allow_edits),
            *(solver(f, name) for f, n in counts.items() for name in instance_names(f, n))]


def parameter_text(value: object) -> str:
    """Return ``value`` as ``-p NAME:=TEXT`` takes it (YAML: true, 0.5, ['a'])."""
    if isinstance(value, bool):
        return 'true' if value else 'false'
    if isinstance(value, (list, tuple)):
        return '[' + ', '.join(f"'{v}'" for v in value) + ']'
    return str(value)


def executable(package: str, name: str) -> Path:
    """Return the path ``ros2 run PACKAGE NAME`` starts, or FileNotFoundError."""
    path = Path(get_package_prefix(package)) / 'lib' / package / name
    if not path.exists():
        raise FileNotFoundError(f'executable {path} not found (is the workspace built?)')
    return path


def command(spec: NodeSpec, namespace: str = names.DEFAULT_NAMESPACE,
            ros_args: Sequence[str] = ()) -> list[str]:
    """Return the command line that starts ``spec`` in ``namespace`` as ``ros2 run`` does."""
    args = [str(executable(spec.package, spec.executable)), '--ros-args',
            '-r', f'__ns:={namespace}', *ros_args]
    if spec.name is not None:
        args += ['-r', f'__node:={spec.name}']
    for name, value in spec.parameters.items():
        args += ['-p', f'{name}:={parameter_text(value)}']
    return args


def solver_class(family: str) -> type[SolverNode]:
    """
    Return the node class of ``family``'s solver.

    Imported on demand (docs/architecture.md#imports): an embedded run imports only the
    solvers it starts, and the vehicle's imports Pinocchio.
    """
    if family == 'steady_state':
        from vd_solvers.nodes.analytical import AnalyticalSolver

        return AnalyticalSolver
    if family == 'kc':
        from vd_solvers.nodes.kc import KCSolver

        return KCSolver
    from vd_solvers.nodes.vehicle import VehicleSolver

    return VehicleSolver


def node_class(spec: NodeSpec) -> type:
    """Return the node class that ``spec``'s executable runs."""
    if spec.executable == 'data_server':
        from vd_data_server.nodes.data_server import DataServer

        return DataServer
    family = next(f.name for f in FAMILIES.values() if f.executable == spec.executable)
    return solver_class(family)
