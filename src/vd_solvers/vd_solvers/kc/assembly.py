# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
The template walk: a :class:`~.model.SuspensionInput` into a :class:`~.system.System`.

:func:`assemble` checks the input against its template, then walks the
template's topology for both sides of the axle: the template's left corner
and its mirror image, the anti-roll bar and the rack coupling them, each
part rigid or a flexible component (a beam-FE frame or an imported reduced
stiffness, condensed to its attachment nodes and embedded with a
co-rotational potential). It hands every part, joint, bushing, force
element and mass to a :class:`~.builder.Builder` and records in an
:class:`~.system.Outputs` where the reported quantities live.
"""
from __future__ import annotations

import numpy as np

from vd_data_server.schema import ARB_POINTS, SUBFRAME_POINTS
from vd_solvers.constants import STANDARD_GRAVITY
from vd_solvers.errors import SolverError
from vd_solvers.flex.component import Condensed, build, clamped
from vd_solvers.flex.imported import mirror_stiffness
from vd_solvers.flex.section import Material, Section

from .builder import Builder
from .bushing import bushing_frame, bushing_measures, side_frame
from .forces import LinearLaw, MatrixLaw, StopLaw, TorsionLaw, spring_law, stiffness_law
from .joints import (
    GROUND,
    JointKind,
    Primitive,
    PrimKind,
    joint_constraints,
    perpendicular_basis,
    point,
    vector,
)
from .model import SIDES, FlexSpec, Side, SuspensionInput, mirror, validate
from .system import Outputs, System, Wheel
from .templates import (
    STEERING,
    TEMPLATES,
    LinkDef,
    PartDef,
    SuspensionTemplate,
    Topology,
)

RACK = 'rack'
BAR = 'anti_roll_bar'
SUBFRAME = 'subframe'


def assemble(inp: SuspensionInput) -> System:
    """Return the axle model of ``inp``; SolverError on any unusable input."""
    validate(inp)
    template = TEMPLATES.get(inp.template)
    if template is None:
        raise SolverError(
            f'unknown suspension template {inp.template!r}; known: {sorted(TEMPLATES)}'
        )
    required = template.required_points + (ARB_POINTS if inp.stabilizer is not None else ()) \
        + (SUBFRAME_POINTS if SUBFRAME in inp.flexible else ())
    for name in required:
        if name not in inp.hardpoints:
            raise SolverError(f'template {template.name!r}: hard point {name!r} is missing')
        value = np.asarray(inp.hardpoints[name], dtype=float)
        if value.shape != (3,) or not np.all(np.isfinite(value)):
            raise SolverError(f'hard point {name!r} must be 3 finite coordinates (m)')
    topo = template.topology()
    _check_keys(inp, topo)
    return _Assembly(inp, template, topo).run()


def _check_keys(inp: SuspensionInput, topo: Topology) -> None:
    """Bushings, masses and joint axes must name something the template has."""
    connections = {j.point for j in topo.joints} | {
        p for link in topo.links for p in (link.inboard_point, link.outboard_point)
    }
    for name in inp.bushings:
        if name not in connections:
            raise SolverError(
                f'bushing {name!r} does not name a connection; known: {sorted(connections)}'
            )
    masses = {p.name for p in topo.parts} | {link.name for link in topo.links} | {'wheel'}
    for name in inp.masses:
        if name not in masses:
            raise SolverError(f'mass {name!r} names no part; known: {sorted(masses)}')
    known = topo.flexible_components(inp.stabilizer is not None)
    for name in inp.flexible:
        if name not in known:
            raise SolverError(f"unknown flexible component {name!r} (components of template "
                              f"{inp.template!r}: {', '.join(known)})")
    universals = {j.point for j in topo.joints if j.kind == 'universal'}
    for name in inp.joint_axes:
        if name not in universals:
            raise SolverError(f'joint_axes {name!r} is not a universal joint; '
                              f'known: {sorted(universals)}')


class _Assembly:
    """One pass over the template for both sides."""

    def __init__(self, inp: SuspensionInput, template: SuspensionTemplate, topo: Topology) -> None:
        self.inp, self.template, self.topo = inp, template, topo
        self.b = Builder()
        self.out = Outputs()
        self.steered = inp.steering is not None
        #: (component, side) -> hard point -> node part, for flexible components
        self.nodes: dict[tuple[str, Side], dict[str, str]] = {}
        self._condensed: dict[str, Condensed] = {}

    def run(self) -> System:
        inp = self.inp
        if self.steered:
            self._rack()
        if SUBFRAME in inp.flexible:
            self._flex_subframe()
        for side in SIDES:
            self._corner(side)
        if inp.stabilizer is not None:
            if BAR in inp.flexible:
                self._flex_bar()
            else:
                self._bar_torsion()
        for side in SIDES:
            self._tracking(side)
        return self.b.build(self.out)

    # -- helpers ---------------------------------------------------------------
    def hp(self, name: str, side: Side) -> np.ndarray:
        return mirror(self.inp.hardpoints[name], side)

    def at(self, part: str, point_name: str, side: Side) -> str:
        """
        Return the part that carries hard point ``point_name`` of ``part``.

        The part itself, or the node of a flexible component at that point (its
        reference node if the point is no node of it).
        """
        resolved = self.resolve(part, side)
        if resolved == GROUND:
            carried = self.nodes.get((SUBFRAME, 'left'), {})
            return carried.get(f'{point_name}.{side}', GROUND)
        nodes = self.nodes.get((part, side))
        if nodes is None:
            return resolved
        return nodes.get(point_name, next(iter(nodes.values())))

    def resolve(self, part: str, side: Side) -> str:
        if part == GROUND:
            return GROUND
        if part == STEERING:
            return RACK if self.steered else GROUND
        return f'{part}.{side}'

    def _gravity(self, part: str, at: np.ndarray, mass: float) -> None:
        if part == GROUND or mass == 0.0:
            return
        prim = Primitive(PrimKind.COMP, (point(part, at), point(GROUND, np.zeros(3))),
                         (0.0, 0.0, 1.0))
        self.b.energy([prim], LinearLaw(np.zeros(1), np.array([mass * STANDARD_GRAVITY])))

    def _connection(
        self, kind: JointKind, name: str, a: str, b: str, at: np.ndarray, side: Side,
        axis: np.ndarray | None = None, cross: tuple[np.ndarray, np.ndarray] | None = None,
    ) -> None:
        """Ideal joint, or the input's bushing keyed by ``name``."""
        bushing = self.inp.bushings.get(name)
        if bushing is None:
            for prim in joint_constraints(kind, a, b, at, axis, cross):
                self.b.constrain(prim)
            return
        frame, signs = side_frame(bushing_frame(bushing.axial), side)
        measures = bushing_measures(a, b, at, frame, signs)
        idx = [
            self.b.energy([m], stiffness_law(k))[0] for m, k in zip(measures, bushing.stiffness)
        ]
        self.out.bushings.setdefault(name, np.full((2, 6), -1))[SIDES.index(side)] = idx
        self.out.elastic.extend(int(i) for i in idx)

    # -- pieces ---------------------------------------------------------------
    def _rack(self) -> None:
        inp = self.inp
        steering = inp.steering
        assert steering is not None
        inner = self.hp('tierod_inner', 'left')
        centre = np.array([inner[0], 0.0, inner[2]])
        self.b.part(RACK, centre)
        self.out.rack_part = self.b.part_index(RACK)
        y = np.array([0.0, 1.0, 0.0])
        for prim in joint_constraints('translational', GROUND, RACK, centre, y):
            self.b.constrain(prim)
        travel = Primitive(PrimKind.COMP, (point(RACK, centre), point(GROUND, centre)),
                           (0.0, 1.0, 0.0))
        compliance = steering.rack_compliance()
        if compliance == 0.0:
            self.out.rack_row = self.b.constrain(travel)
        else:
            law = LinearLaw(np.array([1.0 / compliance]), np.zeros(1))
            self.out.rack_measure = int(self.b.energy([travel], law)[0])
            self.out.elastic.append(self.out.rack_measure)
        # A rack ahead of the wheel centre steers left when moving left.
        ahead = inp.hardpoints['tierod_outer'][0] > inp.hardpoints['wheel_centre'][0]
        self.out.steer_sign = 1.0 if ahead else -1.0

    def _corner(self, side: Side) -> None:
        inp, topo, b = self.inp, self.topo, self.b
        masses = inp.masses
        for part in topo.parts:
            if part.name in inp.flexible:
                self._flex_part(part, side)
                continue
            at = np.mean([self.hp(n, side) for n in part.points], axis=0)
            name = b.part(self.resolve(part.name, side), at)
            self._gravity(name, at, masses.get(part.name, 0.0))
        for j in topo.joints:
            a, c = self.at(j.inboard, j.point, side), self.at(j.outboard, j.point, side)
            at = self.hp(j.point, side)
            axis = cross = None
            if j.axis is not None:
                axis = self.hp(j.axis[1], side) - self.hp(j.axis[0], side)
            if j.kind == 'universal':
                given = inp.joint_axes.get(j.point)
                if given is not None:
                    cross = (mirror(given[0], side), mirror(given[1], side))
                elif axis is not None:
                    # Both cross axes perpendicular to the link: the joint then
                    # only stops the link's spin about its own axis.
                    cross = perpendicular_basis(axis)
                else:
                    raise SolverError(f'template {self.template.name!r}: the universal joint at '
                                      f'{j.point!r} has no axis')
            kind = j.kind
            if kind == 'inline' and (j.inboard in inp.flexible or j.outboard in inp.flexible):
                # The in-line rear pivot only avoids a redundant constraint on a rigid arm;
                # a flexible arm needs its pivot held in place, as its bushing sleeve is.
                kind = 'spherical'
            self._connection(kind, j.point, a, c, at, side, axis, cross)
        for link in topo.links:
            self._link(link, side)
        self._wheel(side)
        self._force_lines(side)
        if inp.stabilizer is not None and BAR not in inp.flexible:
            self._bar_arm(side)

    def _link(self, link: LinkDef, side: Side) -> None:
        """
        Add a two-force link.

        A distance constraint, or a rigid link part when an end has a bushing
        (its spin about its own axis is then held by the bushing).
        """
        inp, b = self.inp, self.b
        a = self.at(link.inboard, link.inboard_point, side)
        c = self.at(link.outboard, link.outboard_point, side)
        pa, pc = self.hp(link.inboard_point, side), self.hp(link.outboard_point, side)
        if link.name in inp.flexible:
            self._flex_link(link, side, a, c, pa, pc)
            return
        mass = inp.masses.get(link.name, 0.0)
        # A link's mass is split between its two ends (two-force member).
        self._gravity(a, pa, 0.5 * mass)
        self._gravity(c, pc, 0.5 * mass)
        ends = ((link.inboard_point, a, pa), (link.outboard_point, c, pc))
        if not any(name in inp.bushings for name, _, _ in ends):
            b.constrain(Primitive(PrimKind.DIST, (point(a, pa), point(c, pc))))
            return
        body = b.part(f'{link.name}.{side}', 0.5 * (pa + pc))
        for name, part, at in ends:
            self._connection('spherical', name, part, body, at, side)

    def _wheel(self, side: Side) -> None:
        inp, b = self.inp, self.b
        upright = self.at(self.topo.wheel_part, 'wheel_centre', side)
        centre = self.hp('wheel_centre', side)
        toe, camber = inp.toe, inp.camber
        # Outward spin axis from ISO toe (+ = toe-in) and camber (+ = top out).
        left = np.array([np.sin(toe) * np.cos(camber), np.cos(toe) * np.cos(camber),
                         -np.sin(camber)])
        axis = mirror(left, side)
        pc, va = point(upright, centre), vector(upright, axis)
        row = b.constrain(Primitive(PrimKind.CPZ, (pc, va), (inp.tire_radius,)))
        self.out.put('pad_rows', side, row)
        self.out.wheels[SIDES.index(side)] = Wheel(b.part_index(upright), b.marker(pc),
                                                   b.marker(va), inp.tire_radius)
        self._gravity(upright, centre, inp.masses.get('wheel', 0.0))

    def _force_lines(self, side: Side) -> None:
        inp, topo, b = self.inp, self.topo, self.b
        sp = topo.spring
        upper, lower = self.hp(sp.upper, side), self.hp(sp.lower, side)
        seat = point(self.at(sp.part, sp.lower, side), lower)
        length = Primitive(PrimKind.DIST, (point(GROUND, upper), seat))
        design = float(np.linalg.norm(upper - lower))
        spring = int(b.energy([length], spring_law(inp.spring, design))[0])
        self.out.put('spring', side, spring)
        self.out.put('spring_length', side, b.prim(length))
        self.out.elastic.append(spring)
        dp = topo.damper
        upper, lower = self.hp(dp.upper, side), self.hp(dp.lower, side)
        seat = point(self.at(dp.part, dp.lower, side), lower)
        damper = Primitive(PrimKind.DIST, (point(GROUND, upper), seat))
        self.out.put('damper_length', side, b.prim(damper))
        for stop, direction, output in (
            (inp.bump_stop, -1.0, 'bump_stop'),
            (inp.rebound_stop, 1.0, 'rebound_stop'),
        ):
            if stop is not None:
                law = StopLaw(stop.curve, stop.clearance, direction)
                measure = int(b.energy([damper], law)[0])
                self.out.put(output, side, measure)
                self.out.elastic.append(measure)

    def _bar_arm(self, side: Side) -> None:
        b = self.b
        pivot = self.hp('arb_pivot', side)
        upper = self.hp('arb_link_upper', side)
        arm = b.part(f'arb_arm.{side}', pivot)
        for prim in joint_constraints('revolute', GROUND, arm, pivot, np.array([0.0, 1.0, 0.0])):
            b.constrain(prim)
        lower_part = self.at(self.topo.arb_part, 'arb_link_lower', side)
        lower = self.hp('arb_link_lower', side)
        row = b.constrain(Primitive(PrimKind.DIST, (point(lower_part, lower), point(arm, upper))))
        self.out.put('droplink_rows', side, row)
        self.out.put('arb_arms', side, b.part_index(arm))

    def _bar_torsion(self) -> None:
        stab = self.inp.stabilizer
        assert stab is not None
        # sin(psi_left - psi_right) for rotations psi about y of the two arms.
        twist = Primitive(
            PrimKind.DOT,
            (vector('arb_arm.left', np.array([0.0, 0.0, 1.0])),
             vector('arb_arm.right', np.array([1.0, 0.0, 0.0]))),
        )
        self.out.arb_twist = int(self.b.energy([twist], TorsionLaw(stab.torsional_stiffness))[0])
        self.out.elastic.append(self.out.arb_twist)

    def _tracking(self, side: Side) -> None:
        """Track every hard point with a point marker on the part whose motion it follows."""
        topo, inp = self.topo, self.inp
        owner: dict[str, str] = {}
        for part in topo.parts:
            for n in part.points:
                owner.setdefault(n, part.name)
        for j in topo.joints:
            owner.setdefault(j.point, j.inboard)
        for link in topo.links:
            owner.setdefault(link.inboard_point, link.inboard)
            owner.setdefault(link.outboard_point, link.outboard)
        owner.setdefault(topo.spring.lower, topo.spring.part)
        owner.setdefault(topo.damper.lower, topo.damper.part)
        owner.update(topo.tracked)
        if inp.stabilizer is not None:
            owner['arb_link_lower'] = topo.arb_part
        tracked = self.out.tracked[SIDES.index(side)]
        for name in inp.hardpoints:
            owner_part = owner.get(name, GROUND)
            if name == 'arb_link_upper' and inp.stabilizer is not None:
                resolved = (self.nodes[(BAR, 'left')][f'arb_link_upper.{side}']
                            if BAR in inp.flexible else f'arb_arm.{side}')
            else:
                resolved = self.at(owner_part, name, side)
            tracked[name] = self.b.marker(point(resolved, self.hp(name, side)))

    # -- flexible components ------------------------------------------------------
    def _attachments(self, part: str) -> list[str]:
        """
        Return the hard points of other elements that act on ``part``.

        Spring and damper seats, the drop-link mount: they must be nodes of its
        FE frame.
        """
        topo, out = self.topo, []
        for line in (topo.spring, topo.damper):
            if line.part == part:
                out.append(line.lower)
        if self.inp.stabilizer is not None and topo.arb_part == part:
            out.append('arb_link_lower')
        return out

    def _component(self, name: str, points: list[str], members, attachments=()) -> Condensed:
        """Return the left-side condensed component ``name`` (built once)."""
        if name in self._condensed:
            return self._condensed[name]
        spec: FlexSpec = self.inp.flexible[name]
        hp = {n: np.asarray(self.inp.hardpoints[n], dtype=float) for n in points}
        if spec.imported is not None:
            comp = _check_imported(name, spec.imported, hp)
        else:
            material, section = _beam(name, spec)
            comp = build(name, hp, members, material, section,
                         attachments=attachments, shape_points=spec.shape_points,
                         elements_per_member=spec.elements_per_member)
        self._condensed[name] = comp
        self.out.components.append(comp)
        return comp

    def _embed(self, comp: Condensed, side: Side, key: tuple[str, Side],
               positions: np.ndarray, stiffness: np.ndarray, cog: np.ndarray) -> dict[str, str]:
        """
        Node parts of a condensed component and its co-rotational potential.

        Deformations are measured in the frame of the first node (the
        reference): per other node, its displacement relative to the point of
        the reference frame it coincided with, and its small-angle rotation
        relative to that frame (the six bushing measures). Rigid motions of all
        nodes leave every measure at zero, so the potential is objective; the
        stiffness on these measures is the condensed one with the reference
        node clamped (exact for a matrix whose null space is the rigid modes).
        """
        b = self.b
        nodes = {n: b.part(f'{key[0]}.{key[1]}@{n}', positions[i])
                 for i, n in enumerate(comp.nodes)}
        ref = nodes[comp.nodes[0]]
        measures = []
        for i, n in enumerate(comp.nodes[1:], start=1):
            measures += bushing_measures(ref, nodes[n], positions[i], np.eye(3), np.ones(6))
        idx = b.energy(measures, MatrixLaw(clamped(stiffness)))
        self.out.elastic.extend(int(i) for i in idx)
        self._gravity(ref, cog, comp.mass)
        for alias, target in comp.aliases.items():
            nodes[alias] = nodes[target]
        self.nodes[key] = nodes
        return nodes

    def _flex_part(self, part: PartDef, side: Side) -> None:
        members = self.topo.frames.get(part.name)
        if members is None:
            raise SolverError(f'template {self.template.name!r} has no beam frame for part '
                              f'{part.name!r}; it cannot be made flexible')
        extra = [p for p in part.points + tuple(self._attachments(part.name))
                 if p not in {n for m in members for n in m}]
        points = list(dict.fromkeys([n for m in members for n in m] + extra))
        comp = self._component(part.name, points, members, extra)
        self._place(comp, part.name, side)

    def _place(self, comp: Condensed, name: str, side: Side) -> dict[str, str]:
        positions = np.array([mirror(p, side) for p in comp.positions])
        stiffness = comp.stiffness if side == 'left' else mirror_stiffness(comp.stiffness)
        return self._embed(comp, side, (name, side), positions, stiffness, mirror(comp.cog, side))

    def _flex_link(self, link: LinkDef, side: Side, a: str, c: str,
                   pa: np.ndarray, pc: np.ndarray) -> None:
        """
        Add a flexible two-force link: a beam between its ball joints.

        Ideal ball joints at both ends would leave its spin about its own axis free, so the
        inboard joint is a universal joint whose cross is normal to the link (it
        only stops the spin, which carries no load).
        """
        comp = self._component(link.name, [link.inboard_point, link.outboard_point],
                               [(link.inboard_point, link.outboard_point)])
        nodes = self._place(comp, link.name, side)
        inner, outer = nodes[link.inboard_point], nodes[link.outboard_point]
        axis = pc - pa
        self._connection('universal', link.inboard_point, a, inner, pa, side, axis,
                         perpendicular_basis(axis))
        self._connection('spherical', link.outboard_point, outer, c, pc, side)

    def _flex_subframe(self) -> None:
        """
        Add a flexible subframe carrying the template's body-side pivots of both sides.

        Per side a rail from the front mount through the carried points to the rear mount, and
        cross-members joining each carried point to its mirror image. The mounts are
        bolted to the body (fixed joints); the carried joints and bushings attach to the
        subframe's nodes instead of the body.
        """
        spec = self.inp.flexible[SUBFRAME]
        if spec.imported is not None:
            raise SolverError('subframe: an imported stiffness is not supported for the subframe')
        carried = self.topo.subframe_points
        chain = ('subframe_front',) + carried + ('subframe_rear',)
        points = {f'{n}.{s}': mirror(self.inp.hardpoints[n], s) for s in SIDES for n in chain}
        members = [(f'{a}.{s}', f'{b}.{s}') for s in SIDES for a, b in zip(chain, chain[1:])]
        members += [(f'{n}.left', f'{n}.right') for n in carried]
        material, section = _beam(SUBFRAME, spec)
        comp = build(SUBFRAME, points, members, material, section,
                     elements_per_member=spec.elements_per_member)
        self.out.components.append(comp)
        nodes = self._embed(comp, 'left', (SUBFRAME, 'left'), comp.positions, comp.stiffness,
                            comp.cog)
        for s in SIDES:
            for mount in ('subframe_front', 'subframe_rear'):
                name = f'{mount}.{s}'
                for prim in joint_constraints('fixed', GROUND, nodes[name], points[name]):
                    self.b.constrain(prim)

    def _flex_bar(self) -> None:
        """
        Add the anti-roll bar as a beam frame.

        Drop-link end, arm, body mount (pivot), torsion part across to the other
        side. The mounts are ball
        joints on the body; the drop links are distance constraints.
        """
        spec = self.inp.flexible[BAR]
        names = {s: (f'arb_link_upper.{s}', f'arb_pivot.{s}') for s in SIDES}
        points = {f'{n}.{s}': mirror(self.inp.hardpoints[n], s) for s in SIDES
                  for n in ('arb_link_upper', 'arb_pivot')}
        members = [names['left'], (names['left'][1], names['right'][1]),
                   (names['right'][1], names['right'][0])]
        if spec.imported is not None:
            raise SolverError('anti_roll_bar: an imported stiffness is not supported for the bar')
        shapes = []
        for sp in spec.shape_points:
            if (sp.start, sp.end) != ('arb_link_upper', 'arb_pivot'):
                raise SolverError('anti_roll_bar: shape points lie on the arm, from '
                                  'arb_link_upper to arb_pivot')
            shapes.append(type(sp)(names['left'][0], names['left'][1], sp.fraction, sp.offset))
            shapes.append(type(sp)(names['right'][1], names['right'][0], 1.0 - sp.fraction,
                                   tuple(mirror(np.asarray(sp.offset), 'right'))))
        material, section = _beam(BAR, spec)
        arm = spec.arm_section or section
        comp = build(BAR, points, members, material, section,
                     shape_points=shapes, elements_per_member=spec.elements_per_member,
                     member_sections={names['left']: arm, members[2]: arm})
        self.out.components.append(comp)
        nodes = self._embed(comp, 'left', (BAR, 'left'), comp.positions, comp.stiffness, comp.cog)
        for side in SIDES:
            upper, pivot = names[side]
            for prim in joint_constraints('spherical', GROUND, nodes[pivot], points[pivot]):
                self.b.constrain(prim)
            lower = self.hp('arb_link_lower', side)
            lower_part = self.at(self.topo.arb_part, 'arb_link_lower', side)
            row = self.b.constrain(Primitive(PrimKind.DIST, (point(lower_part, lower),
                                                             point(nodes[upper], points[upper]))))
            self.out.put('droplink_rows', side, row)
            self.out.put('arb_arms', side, self.b.part_index(nodes[upper]))


def _beam(name: str, spec: FlexSpec) -> tuple[Material, Section]:
    """Return the material and section of a beam-frame component."""
    if spec.material is None or spec.section is None:
        raise SolverError(f'flexible component {name!r}: a beam frame needs a material and a '
                          'section')
    return spec.material, spec.section


def _check_imported(name: str, comp: Condensed, hardpoints: dict[str, np.ndarray]) -> Condensed:
    """Check that an imported reduced stiffness has its nodes on the hard points."""
    missing = [n for n in hardpoints if n not in comp.nodes]
    if missing:
        raise SolverError(f"flexible component {name!r}: the imported stiffness has no node "
                          f"for hard point(s) {', '.join(missing)} "
                          f"(nodes: {', '.join(comp.nodes)})")
    order = [comp.nodes.index(n) for n in hardpoints]
    extra = [n for n in comp.nodes if n not in hardpoints]
    if extra:
        raise SolverError(f"flexible component {name!r}: imported node(s) {', '.join(extra)} are "
                          f"not attachment points of this component ({', '.join(hardpoints)})")
    for i, n in zip(order, hardpoints):
        gap = float(np.linalg.norm(comp.positions[i] - hardpoints[n]))
        if np.isfinite(gap) and gap > IMPORT_POSITION_TOL:
            raise SolverError(f'flexible component {name!r}: imported node {n} lies '
                              f'{gap * 1e3:.1f} mm from the hard point (more than '
                              f'{IMPORT_POSITION_TOL * 1e3:g} mm): the stiffness belongs to '
                              'other geometry')
    dofs = np.concatenate([np.arange(6 * i, 6 * i + 6) for i in order])
    positions = np.array([hardpoints[n] for n in hardpoints])
    cog = comp.cog if np.all(np.isfinite(comp.cog)) else positions.mean(axis=0)
    return Condensed(name, tuple(hardpoints), positions, comp.stiffness[np.ix_(dofs, dofs)],
                     comp.mass, cog, 0, comp.source)


#: how far an imported node may lie from its hard point, m
IMPORT_POSITION_TOL = 0.002

