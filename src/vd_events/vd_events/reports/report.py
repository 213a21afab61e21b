# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
``vd report BAG...``: an HTML report with PNG plots from recorded bags.

Per event and model, one plot per channel pair with every configuration
overlaid (like the thesis' Figs. 4.1.1-4.1.2, 4.2.x-4.3.x and, for the full vehicle,
4.4.1-4.4.3), a metrics table,
and the configuration overview with the modified/unchanged feedback.
"""
from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
import html
import math
import os
from pathlib import Path
from typing import Any

import numpy as np

from vd_events.bags.bag import BagError, read_bag
from vd_events.reports.display import HEADLINE_NAMES, display
from vd_solvers.analytical.budget import TERMS as BUDGET_TERMS
from vd_solvers.conversions import outcome_from_msg
from vd_solvers.results import EventOutcome

G = 9.80665
DEG = 180.0 / math.pi  # plot axes (display)
LINE_STYLES = ('-', '--', ':', '-.')


@dataclass(frozen=True)
class Axis:
    channel: str
    label: str
    scale: float = 1.0
    relative: bool = False  # plot the change from the step nearest the design (x = 0)


#: event -> plots (x axis, y axis); channels missing from a result are skipped
PLOTS: Mapping[str, Sequence[tuple[Axis, Axis]]] = {
    'handling_diagram': (
        (Axis('slip_angle_difference', 'front minus rear slip angle α_f − α_r [deg]', DEG),
         Axis('lateral_acceleration', 'lateral acceleration [g]', 1 / G)),
        (Axis('lateral_acceleration', 'lateral acceleration [g]', 1 / G),
         Axis('steer_angle', 'road-wheel steer angle [deg]', DEG)),
        (Axis('lateral_acceleration', 'lateral acceleration [g]', 1 / G),
         Axis('roll_angle', 'roll angle [deg]', DEG)),
        # the thesis' Figs. 4.1.1-4.1.2: axle lateral force over slip angle
        (Axis('slip_angle_front', 'front slip angle [deg]', DEG),
         Axis('lateral_force_front_axle', 'front axle lateral force [kN]', 1e-3)),
        (Axis('slip_angle_rear', 'rear slip angle [deg]', DEG),
         Axis('lateral_force_rear_axle', 'rear axle lateral force [kN]', 1e-3)),
    ),
    'steady_state_circular': (
        (Axis('lateral_acceleration', 'lateral acceleration [g]', 1 / G),
         Axis('steer_angle', 'road-wheel steer angle [deg]', DEG)),
        (Axis('lateral_acceleration', 'lateral acceleration [g]', 1 / G),
         Axis('sideslip', 'sideslip angle [deg]', DEG)),
        (Axis('lateral_acceleration', 'lateral acceleration [g]', 1 / G),
         Axis('roll_angle', 'roll angle [deg]', DEG)),
    ),
    'step_steer': (
        (Axis('time', 'time [s]'), Axis('yaw_rate', 'yaw rate [deg/s]', DEG)),
        (Axis('time', 'time [s]'), Axis('lateral_acceleration', 'lateral acceleration [m/s²]')),
    ),
}
_TRAVEL = Axis('wheel_travel_left', 'vertical wheel travel, left [mm]', 1e3)
_OPPOSITE = Axis('wheel_travel_left', 'opposite wheel travel, left wheel [mm]', 1e3)
_FORCE = Axis('applied_force', 'applied force per wheel [kN]', 1e-3)
_TOE = Axis('toe_left', 'toe angle, left [deg]', DEG)
_CAMBER = Axis('camber_left', 'camber angle, left [deg]', DEG)
KC_PLOTS: Mapping[str, Sequence[tuple[Axis, Axis]]] = {
    'parallel_wheel_travel': (
        (_TRAVEL, _TOE), (_TRAVEL, _CAMBER),
        (_TRAVEL, Axis('track', 'track change [mm]', 1e3, relative=True)),
        (_TRAVEL, Axis('contact_point_x_left', 'wheelbase change, left contact patch x [mm]',
                       1e3, relative=True)),
        (_TRAVEL, Axis('pad_force_left', 'wheel vertical load, left [N]')),
        (_TRAVEL, Axis('caster_left', 'caster, left [deg]', DEG)),
    ),
    'opposite_wheel_travel': (
        (_OPPOSITE, _TOE), (_OPPOSITE, _CAMBER),
        (_OPPOSITE, Axis('pad_force_left', 'wheel vertical load, left [N]')),
    ),
    'lateral_force': (
        (_FORCE, _CAMBER), (_FORCE, _TOE),
        (_FORCE, Axis('pad_force_left', 'wheel vertical load, left [N]')),
        (_FORCE, Axis('contact_point_y_left', 'contact patch y change, left [mm]', 1e3,
                      relative=True)),
    ),
    'longitudinal_force': (
        (_FORCE, Axis('wheel_centre_x_left', 'wheel centre x change, left [mm]', 1e3,
                      relative=True)),
        (_FORCE, Axis('pad_force_left', 'wheel vertical load, left [N]')),
        (_FORCE, _TOE),
    ),
    'steering': (
        (Axis('steering_wheel_angle', 'steering-wheel angle [deg]', DEG),
         Axis('steer_angle_left', 'road-wheel angle, left [deg]', DEG)),
        (Axis('steering_wheel_angle', 'steering-wheel angle [deg]', DEG),
         Axis('steer_angle_right', 'road-wheel angle, right [deg]', DEG)),
        (Axis('rack_travel', 'rack travel [mm]', 1e3),
         Axis('rack_force', 'rack force [N]')),
    ),
}
_TIME = Axis('time', 'time [s]')
_AY = Axis('lateral_acceleration', 'lateral acceleration [m/s²]')
#: full-vehicle plots; over time: the thesis' Figs. 4.4.1-4.4.3 (lateral acceleration,
#: roll and steering angle over time, configurations overlaid)
VEHICLE_PLOTS: Mapping[str, Sequence[tuple[Axis, Axis]]] = {
    'constant_radius_turn': (
        (_TIME, _AY),
        (_TIME, Axis('roll', 'roll angle [deg]', DEG)),
        (_TIME, Axis('steering_wheel_angle', 'steering-wheel angle [deg]', DEG)),
        (_AY, Axis('steering_wheel_angle', 'steering-wheel angle [deg]', DEG)),
        (_AY, Axis('roll', 'roll angle [deg]', DEG)),
        (_AY, Axis('sideslip', 'sideslip angle [deg]', DEG)),
    ),
    'step_steer': (
        (_TIME, Axis('yaw_rate', 'yaw rate [deg/s]', DEG)),
        (_TIME, _AY),
        (_TIME, Axis('roll', 'roll angle [deg]', DEG)),
        (_TIME, Axis('steering_wheel_angle', 'steering-wheel angle [deg]', DEG)),
    ),
}
@dataclass(frozen=True)
class Run:
    """One recorded result (read through ``conversions.outcome_from_msg``) and its bag."""

    bag: Path
    outcome: EventOutcome
    modified: list[str] = field(default_factory=list)

    def __getattr__(self, name: str):
        return getattr(self.outcome, name)  # event, configuration, model, axle, notes, ...

    @property
    def channels(self) -> dict[str, np.ndarray]:
        return {k: c.values for k, c in self.outcome.channels.items()}

    @property
    def units(self) -> dict[str, str]:
        return {k: c.unit for k, c in self.outcome.channels.items()}

    @property
    def label(self) -> str:
        flex = ', flexible' if self.fidelity == 'flexible' else ''
        return f'{self.configuration} ({self.model}{flex})'



def save_figure(fig, ax, path: Path, xlabel: str, ylabel: str, title: str,
                legend: str = 'small') -> None:
    """Label, grid and title ``ax`` the report's way; write ``fig`` to ``path``, close it."""
    import matplotlib.pyplot as plt

    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=legend)
    ax.set_title(title, fontsize='medium')
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)

def load_runs(bags: Sequence[Path]) -> tuple[list[Run], object | None]:
    """Every EventResult in the bags (as EventOutcomes), and the newest data status seen."""
    runs: list[Run] = []
    status = None
    for bag in bags:
        provenance: dict[str, list[str]] = {}
        results = []
        for item in read_bag(bag):
            msg = item.msg
            # topics of any namespace (/vd/data_status, /car2/data_status)
            if item.topic.endswith('/data_status'):
                status = msg
            elif item.topic.endswith('/provenance'):
                provenance[msg.configuration] = [
                    f'{g.group}.{k.key}: {k.data_value} → {k.master_value} {k.unit}'.strip()
                    for g in msg.groups for k in g.modified_keys]
            elif item.topic.endswith('/result'):
                results.append(outcome_from_msg(msg))
        runs += [Run(bag, o, provenance.get(o.configuration, [])) for o in results]
    return runs, status


def build_report(bags: Sequence[Path], out: Path) -> Path:
    """Write ``out/report.html`` and its PNGs; returns the HTML path."""
    import matplotlib

    matplotlib.use('Agg')
    import matplotlib.pyplot as plt

    for bag in bags:
        if not (Path(bag) / 'metadata.yaml').is_file():
            raise BagError(f'{bag}: not a finished rosbag2 bag (no metadata.yaml)')
    runs, status = load_runs(bags)
    tables = load_capability(bags)
    if not runs and not tables:
        raise BagError('no event results in ' + ', '.join(str(b) for b in bags))
    out.mkdir(parents=True, exist_ok=True)
    sections: list[str] = [_capability_section(t) for t in tables]
    groups: dict[tuple[str, str, str], list[Run]] = {}
    for run in runs:
        groups.setdefault((run.event, run.axle, _family(run.model)), []).append(run)
    for (event, axle, family), members in groups.items():
        if event == 'sine_with_dwell':
            from vd_events.reports.sine_with_dwell import sine_with_dwell_section
            sections.append(sine_with_dwell_section(members, out, family))
            continue
        images = []
        table = {'kc': KC_PLOTS, 'vehicle': VEHICLE_PLOTS}.get(family, PLOTS)
        plots = table.get(event, _generic_plots(members[0]))
        for i, (xa, ya) in enumerate(plots):
            usable = [r for r in members if xa.channel in r.channels and ya.channel in r.channels]
            if not usable:
                continue
            fig, ax = plt.subplots(figsize=(6.4, 4.2), dpi=110)
            for k, run in enumerate(usable):
                x, y = run.channels[xa.channel], run.channels[ya.channel]
                if ya.relative:
                    y = y - y[int(np.argmin(np.abs(x)))]
                # line styles cycle too, so identical curves stay visible on top of each other
                ax.plot(x * xa.scale, y * ya.scale, label=run.label,
                        linestyle=LINE_STYLES[k % len(LINE_STYLES)],
                        marker='.' if len(x) < 30 else None)
            name = f"{event}{'_' + axle if axle else ''}_{family}_{i}.png"
            save_figure(fig, ax, out / name, xa.label, ya.label,
                        f"{event}{' ' + axle if axle else ''}: {ya.channel} vs {xa.channel}")
            images.append(name)
        sections.append(_section(event, axle, family, members, images))
    html_path = out / 'report.html'
    tmp = out / '.report.html.partial'
    tmp.write_text(_page(runs, status, sections, bags, out), encoding='utf-8')
    os.replace(tmp, html_path)
    return html_path


def _family(model: str) -> str:
    # measured results (vd import) overlay the simulations of their family
    measured = {'rig': 'kc', 'test': 'vehicle'}
    return 'analytical' if model in ('bicycle', 'two_track') else measured.get(model, model)


def _generic_plots(run: Run) -> Sequence[tuple[Axis, Axis]]:
    names = list(run.channels)
    if not names:
        return ()
    x = Axis(names[0], f'{names[0]} [{run.units[names[0]]}]')
    return tuple((x, Axis(n, f'{n} [{run.units[n]}]')) for n in names[1:7])


def _fmt(value: float) -> str:
    return '–' if not math.isfinite(value) else f'{value:.4g}'


def _section(event: str, axle: str, family: str, runs: list[Run], images: list[str]) -> str:
    names = [m for m in HEADLINE_NAMES if any(m in r.metrics for r in runs)]
    names += sorted({m for r in runs for m in r.metrics} - set(names))
    head = ''.join(f'<th>{html.escape(n)}<br><small>{html.escape(_unit(runs, n))}</small></th>'
                   for n in names)
    rows = ''.join(
        '<tr><td>' + html.escape(r.label) + '</td>' + ''.join(
            f"<td>{_fmt(_shown(r, n)) if n in r.metrics else ''}</td>" for n in names)
        + '</tr>' for r in runs)
    imgs = ''.join(f'<img src="{html.escape(i)}" alt="{html.escape(i)}">' for i in images)
    notes = ''.join(f'<li>{html.escape(r.label)}: {html.escape(r.notes[0])}</li>'
                    for r in runs if r.notes)
    title = f"{event}{' — ' + axle if axle else ''} ({family})"
    budgets = ''.join(_budget(r) for r in runs)
    return (f"<h2>{html.escape(title)}</h2><div class='plots'>{imgs}</div>"
            f"<div class='scroll'><table><tr><th>run</th>{head}</tr>{rows}</table></div>"
            f"{budgets}<ul class='notes'>{notes}</ul>")


def _shown(run: Run, name: str) -> float:
    """Return a metric of ``run`` in its display unit (``display.display``)."""
    m = run.metrics[name]
    return display(m.value, m.unit, name)[0]


def _budget(run: Run) -> str:
    """Tabulate the understeer-gradient budget of a run (Gillespie ch. 6): term, value, source."""
    names = [f'understeer_budget_{t}' for t in BUDGET_TERMS]
    if not all(n in run.metrics for n in names):
        return ''
    unit = _unit([run], names[0])
    rows = ''.join(
        f"<tr><td>{html.escape(t.replace('_', ' '))}</td><td>{_shown(run, n):.3f}</td>"
        f"<td><small>{html.escape(run.metrics[n].source)}</small></td></tr>"
        for t, n in zip(BUDGET_TERMS, names))
    if 'understeer_budget_total' in run.metrics:
        rows += (f"<tr><th>total</th><th>{_shown(run, 'understeer_budget_total'):.3f}</th>"
                 '<td></td></tr>')
    return (f"<h3>Understeer budget — {html.escape(run.label)}</h3>"
            f"<table class='budget'><tr><th>term</th><th>{html.escape(unit)}</th>"
            f"<th>source</th></tr>{rows}</table>")


def _unit(runs: list[Run], name: str) -> str:
    """Return the display unit of metric ``name`` (from the first run that has it)."""
    for run in runs:
        if name in run.metrics:
            m = run.metrics[name]
            return display(m.value, m.unit, name)[1]
    return ''


def _overview(status) -> str:
    if status is None:
        return '<p>No data status recorded.</p>'
    configs = list(status.configurations)
    cells: dict[tuple[str, str], Any] = {(s.configuration, s.group): s for s in status.status}
    head = ''.join(f'<th>{html.escape(c)}</th>' for c in configs)
    rows = []
    for group in status.groups:
        tds, consistency = [], 'SAME'
        for c in configs:
            s = cells.get((c, group))
            if s is None or not s.variant:
                tds.append("<td class='unused'>–</td>")
                continue
            modified = s.state == s.MODIFIED
            consistency = 'DIFFERS' if s.consistency == s.DIFFERS else 'SAME'
            title = '; '.join(f'{k.key}: {k.data_value} → {k.master_value} {k.unit}'
                              for k in s.modified_keys)
            tds.append(f"<td class='{'mod' if modified else 'unch'}' title='{html.escape(title)}'>"
                       f"{html.escape(s.variant)} {'MODIFIED' if modified else 'UNCHANGED'}</td>")
        rows.append(f"<tr><th>{html.escape(group)}</th>{''.join(tds)}"
                    f"<td class='{consistency.lower()}'>{consistency}</td></tr>")
    modified = ''.join(
        f"<tr><td>{html.escape(s.configuration)}</td><td>{html.escape(s.group)}</td>"
        f"<td>{html.escape(k.key)}</td><td>{html.escape(k.data_value)}</td>"
        f"<td class='mod'>{html.escape(k.master_value)}</td><td>{html.escape(k.unit)}</td></tr>"
        for s in status.status for k in s.modified_keys)
    table = (f"<table><tr><th>input group</th>{head}<th>all configurations</th></tr>"
             f"{''.join(rows)}</table>")
    if modified:
        table += ('<h3>Modified values</h3><table><tr><th>configuration</th><th>group</th>'
                  '<th>key</th><th>data file</th><th>master</th><th>unit</th></tr>'
                  f'{modified}</table>')
    return f'<p>Master file: {html.escape(status.master_file)}</p>{table}'


CSS = """
body{font-family:system-ui,sans-serif;margin:2em;color:#222}
table{border-collapse:collapse;margin:0.5em 0;font-size:0.9em}
td,th{border:1px solid #ccc;padding:3px 8px;text-align:center}
td.unch{background:#d9f2d9}td.mod{background:#f7c6c6;font-weight:bold}
td.differs{background:#fff3c4}td.same{color:#777}td.unused{color:#aaa}
.plots img{max-width:48%;margin:0.3em}.scroll{overflow-x:auto}.notes{font-size:0.85em;color:#555}
"""


def _page(runs: list[Run], status, sections: list[str], bags: Sequence[Path], out: Path) -> str:
    provenance = ''.join(
        f"<tr><td>{html.escape(os.path.relpath(r.bag, out))}</td><td>{html.escape(r.event)}</td>"
        f"<td>{html.escape(r.configuration)}</td><td>{html.escape(r.model)}</td>"
        f"<td>{html.escape(r.data_hash)}</td><td>{html.escape('; '.join(r.modified) or '–')}</td>"
        "</tr>" for r in runs)
    return f"""<!DOCTYPE html>
<html><head><meta charset="utf-8"><title>vd report</title><style>{CSS}</style></head><body>
<h1>vd report</h1>
<p>{len(runs)} results from {len(bags)} bag(s).</p>
<h2>Configuration overview</h2>
<p>Green: the data fed to the models is the shared data file unchanged; red: the master file
modifies it (hover for the values). Last column: whether all configurations use the same data.</p>
{_overview(status)}
{''.join(sections)}
<h2>Provenance</h2>
<table><tr><th>bag</th><th>event</th><th>configuration</th><th>model</th><th>data hash</th>
<th>modified values</th></tr>{provenance}</table>
</body></html>
"""


def load_capability(bags: Sequence[Path]) -> list:
    """Every capability table (vd capability) recorded in the bags."""
    from vd_events.studies.capability import TOPIC, from_msg

    return [from_msg(item.msg) for bag in bags for item in read_bag(bag, {TOPIC})]


def _capability_section(table) -> str:
    """Render the table coloured as the thesis' Tables 5.2.1/5.2.2, worst difference per cell."""
    from vd_events.studies.capability import QUANTITIES, format_table

    head = ''.join(f'<th>{html.escape(q)}</th>' for q in QUANTITIES)
    rows = []
    for row in format_table(table):
        cells = ''.join(
            f'<td style="background:{"#f4c7c3" if c.startswith("Flexible") else "#c9e7c0"}">'
            f'{html.escape(c)}</td>' for c in row[1:])
        rows.append(f'<tr><td>{html.escape(row[0])}</td>{cells}</tr>')
    metric_rows = []
    for c in table.metrics:
        unit = html.escape(c.unit)
        metric_rows.append(
            f'<tr><td>{html.escape(c.event)}</td><td>{html.escape(c.quantity)}</td>'
            f'<td>{c.rigid_value:.4g}</td><td>{c.flexible_value:.4g}</td><td>{unit}</td>'
            f'<td style="background:{"#f4c7c3" if c.verdict == "Flexible" else "#c9e7c0"}">'
            f'{c.verdict}</td></tr>')
    offsets = '; '.join(
        '{} {} {:.3g} {}'.format(c.event, c.quantity,
                                 *display(c.design_offset, c.unit, c.quantity))
        for c in table.cells if c.quantity == 'wheel_load' and abs(c.design_offset) > 0.0)
    return (f"<h2>Analytical capability: {html.escape(table.configuration)}, "
            f"{html.escape(table.axle)} axle</h2>"
            f"<p>Rigid vs flexible K&amp;C (flexible: {html.escape(', '.join(table.components))}"
            f"; data hash {html.escape(table.data_hash)}). Green: the rigid model is good "
            f"enough; red: the flexible model is needed; worst difference in brackets. "
            f"{html.escape(' '.join(table.notes))}</p>"
            f"<table><tr><th>event</th>{head}</tr>{''.join(rows)}</table>"
            f"<p>Wheel-load offset at design (flexible − rigid: FE vs user-given masses, "
            f"thesis 5.1): {html.escape(offsets or 'none')}</p>"
            f"<table><tr><th>event</th><th>metric</th><th>rigid</th><th>flexible</th>"
            f"<th>unit</th><th>verdict</th></tr>{''.join(metric_rows)}</table>")
