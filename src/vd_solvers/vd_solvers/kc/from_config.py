"""Build a K&C suspension input from a resolved configuration, and run its events.

Every value comes from the configuration's groups of that axle
(``<axle>_hardpoints``, ``_spring``, ``_damper``, ``_bump_stop``,
``_rebound_stop``, ``_bushings``, ``_stabilizer``, ``_alignment``, ``_tire``,
``steering`` on the front axle) plus the static corner load from the mass data.
The tire's loaded radius is the design wheel-centre height (hard points at
design ride height); its vertical stiffness is the .tir's VERTICAL_STIFFNESS.
"""
from __future__ import annotations

import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import replace

import numpy as np

from vd_data_server.model import Configuration, GroupData
from vd_solvers.analytical.from_config import static_wheel_loads
from vd_solvers.errors import SolverError
from vd_solvers.event_params import Param, parse_params
from vd_solvers.results import Channel, EventOutcome, Metric

from .events import EVENTS, KCModel, run_suite
from .metrics import derived_metrics
from .model import (Bushing, Curve, DamperSpec, SpringSpec, StabilizerSpec, SteeringSpec,
                    StopSpec, SuspensionInput)

DEG = 180.0 / math.pi
SIX = ("x", "y", "z", "rx", "ry", "rz")

#: event -> its parameters (SI), as ``vd run --param`` takes them
EVENT_PARAMS: Mapping[str, Mapping[str, Param]] = {
    "parallel_wheel_travel": {
        "travel_min": Param("length", -0.08, "lowest pad travel (rebound)", maximum=0.0),
        "travel_max": Param("length", 0.08, "highest pad travel (bump)", minimum=0.0),
        "steps": Param("integer", 101, "steps", minimum=3, maximum=2001),
    },
    "opposite_wheel_travel": {
        "amplitude": Param("length", 0.08, "left pad +a..-a, right pad opposite", minimum=0.001),
        "steps": Param("integer", 101, "steps", minimum=3, maximum=2001),
    },
    "lateral_force": {
        "force_min": Param("force", -4000.0, "lowest force along +y at both contact patches",
                           maximum=0.0),
        "force_max": Param("force", 4000.0, "highest force", minimum=0.0),
        "steps": Param("integer", 101, "steps", minimum=3, maximum=2001),
    },
    "longitudinal_force": {
        "force_min": Param("force", -4000.0, "braking force at the contact patch (negative)",
                           maximum=0.0),
        "force_max": Param("force", 4000.0, "traction force at the wheel centre", minimum=0.0),
        "steps": Param("integer", 101, "steps", minimum=3, maximum=2001),
    },
    "steering": {
        "steering_wheel_angle": Param("angle", 0.0, "sweep +-angle; 0 = lock to lock",
                                      minimum=0.0),
        "steps": Param("integer", 101, "steps", minimum=3, maximum=2001),
    },
    "aligning_torque": {
        "moment_min": Param("torque", -200.0, "lowest moment about +z at both contact patches",
                            maximum=0.0),
        "moment_max": Param("torque", 200.0, "highest moment", minimum=0.0),
        "steps": Param("integer", 101, "steps", minimum=3, maximum=2001),
    },
}


def _curve(group: GroupData, key: str, scale: float = 1.0) -> Curve:
    xs, ys = group.curve(key)
    return Curve(np.asarray(xs), np.asarray(ys) * scale)


def _optional(config: Configuration, name: str) -> GroupData | None:
    return config.groups.get(name)


def suspension_input(config: Configuration, axle: str) -> SuspensionInput:
    """The K&C input of ``axle`` ('front' or 'rear') of ``config``."""
    hp = config.group(f"{axle}_hardpoints")
    points = {k.split(".", 1)[1]: np.asarray(v.si, dtype=float)
              for k, v in hp.values.items() if k.startswith("points.")}
    spring_g = config.group(f"{axle}_spring")
    spring = SpringSpec(
        rate=spring_g.get_scalar("rate"),
        curve=_curve(spring_g, "curve") if spring_g.has("curve") else None,
        free_length=spring_g.get_scalar("free_length"),
        preload=spring_g.get_scalar("preload"))
    damper_g = config.group(f"{axle}_damper")
    damper = DamperSpec(_curve(damper_g, "curve", damper_g.get_scalar("scale", 1.0) or 1.0))
    stops = {}
    for kind in ("bump_stop", "rebound_stop"):
        g = config.group(f"{axle}_{kind}")
        stops[kind] = StopSpec(g.scalar("clearance"), _curve(g, "curve"))
    bushings = {}
    bush_g = _optional(config, f"{axle}_bushings")
    if bush_g is not None:
        names = sorted({k.split(".")[1] for k in bush_g.values if k.startswith("connections.")})
        for name in names:
            base = f"connections.{name}"
            stiffness = tuple(bush_g.scalar(f"{base}.stiffness.{d}") for d in SIX)
            damping = tuple(bush_g.get_scalar(f"{base}.damping.{d}", 0.0) or 0.0 for d in SIX)
            axis = bush_g.point(f"{base}.axis") if bush_g.has(f"{base}.axis") else None
            bushings[name] = Bushing(stiffness, damping,  # type: ignore[arg-type]
                                     None if axis is None else np.asarray(axis, dtype=float))
    stabilizer = None
    stab_g = _optional(config, f"{axle}_stabilizer")
    if stab_g is not None:
        missing = [p for p in ("arb_link_lower", "arb_link_upper", "arb_pivot") if p not in points]
        if missing:
            raise SolverError(f"{axle}_stabilizer is given but {hp.file} lacks the anti-roll-bar "
                              f"hard points {', '.join(missing)}")
        stabilizer = StabilizerSpec(bar_stiffness(stab_g))
    steering = None
    if axle == "front" and "steering" in config.groups:
        s = config.group("steering")
        steering = SteeringSpec(rack_ratio=s.scalar("rack_ratio"),
                                rack_travel_limit=s.scalar("rack_travel_limit"),
                                rack_stiffness=s.get_scalar("rack_stiffness"),
                                column_stiffness=s.get_scalar("column_stiffness"))
    align = config.group(f"{axle}_alignment")
    tire = config.group(f"{axle}_tire")
    front_load, rear_load = static_wheel_loads(config)
    unsprung = config.group("mass").scalar(f"unsprung_mass_{axle}")
    return SuspensionInput(
        template=hp.text("template"), axle=axle, hardpoints=points, spring=spring,  # type: ignore[arg-type]
        tire_radius=points["wheel_centre"][2],
        tire_vertical_stiffness=tire.scalar("tir.VERTICAL.VERTICAL_STIFFNESS"),
        corner_load=front_load if axle == "front" else rear_load,
        damper=damper, bump_stop=stops["bump_stop"], rebound_stop=stops["rebound_stop"],
        bushings=bushings, stabilizer=stabilizer, steering=steering,
        camber=align.scalar("camber"), toe=align.scalar("toe"), masses={"wheel": unsprung})


def bar_stiffness(group: GroupData) -> float:
    """Torsional stiffness of the anti-roll bar, N*m/rad: given, or G*J/L of a
    solid round bar (J = pi r^4 / 2)."""
    given = group.get_scalar("torsional_stiffness")
    if given is not None:
        return given
    r = group.scalar("bar_radius")
    return group.scalar("shear_modulus") * math.pi * r ** 4 / 2.0 / group.scalar("torsion_length")


def _event_kwargs(event: str, values: Mapping[str, float]) -> dict[str, float]:
    kwargs: dict[str, float] = {k: (int(v) if k == "steps" else v) for k, v in values.items()}
    if event == "steering" and kwargs.get("steering_wheel_angle", 0.0) == 0.0:
        kwargs.pop("steering_wheel_angle", None)
    return kwargs


def run_kc_event(config: Configuration, event: str, axle: str,
                 params: Sequence[str] = (),
                 progress: Callable[[float, str], None] | None = None) -> EventOutcome:
    """One K&C event on one axle, with the derived metrics that event supports.

    ``progress(fraction, stage)`` is called per solved step (it may raise to cancel)."""
    label = f"configuration '{config.name}', event '{event}', axle '{axle}'"
    if event not in EVENT_PARAMS:
        raise SolverError(f"{label}: the K&C solver has no event '{event}' (events: "
                          f"{', '.join(EVENT_PARAMS)})")
    if axle not in ("front", "rear"):
        raise SolverError(f"{label}: K&C events need --axle front or rear")
    values = parse_params(event, EVENT_PARAMS[event], params)
    inp = suspension_input(config, axle)
    if event == "steering" and inp.steering is None:
        raise SolverError(f"{label}: the {axle} axle has no steering")
    model = KCModel(inp, label)
    with_bar = event == "opposite_wheel_travel" and inp.stabilizer is not None
    runs = 2 if with_bar else 1

    def on_step(run: int, stage: str) -> Callable[[int, int], None] | None:
        if progress is None:
            return None
        return lambda done, total: progress((run + done / total) / runs, stage)

    result = model.run(event, on_step(0, "solving"), **_event_kwargs(event, values))
    results = {event: result}
    if with_bar:
        bare = KCModel(replace(model.inp, stabilizer=None), label, solved=True)
        results["opposite_wheel_travel_no_bar"] = bare.run(
            event, on_step(1, "solving without the anti-roll bar"),
            **_event_kwargs(event, values))
    return _outcome(config, event, axle, inp, model, results)


def _outcome(config, event, axle, inp, model, results) -> EventOutcome:
    geo = config.group("geometry")
    mass_cog = _cog_height(config)
    metrics = {k: Metric(float(v), u) for k, (v, u) in derived_metrics(
        results, inp.tire_vertical_stiffness, cg_height=mass_cog,
        wheelbase=geo.scalar("wheelbase")).items()}
    raw = results[event].channels
    channels = flatten_channels(raw)
    if event == "lateral_force":
        channels["applied_force"] = Channel("N", raw["contact_force"][:, 0, 1])
    elif event == "aligning_torque":
        channels["applied_moment"] = Channel("N*m", raw["contact_moment"][:, 0, 2])
    elif event == "longitudinal_force":
        channels["applied_force"] = Channel("N", raw["contact_force"][:, 0, 0]
                                            + raw["centre_force"][:, 0, 0])
    residual_c = float(np.max(raw["constraint_residual"]))
    residual_f = float(np.max(raw["force_residual"]))
    metrics["max_constraint_residual"] = Metric(residual_c, "m")
    metrics["max_force_residual"] = Metric(residual_f, "N")
    notes = [f"rigid K&C, {inp.template} {axle}; joints to 1e-9 m, forces to 1e-6 N "
             f"(worst step: {residual_c:.1e} m, {residual_f:.1e} N)",
             f"spring preload at design: {model.inp.spring.preload or 0.0:.0f} N; corner load "
             f"{inp.corner_load:.0f} N from the mass data"]
    return EventOutcome(event=event, configuration=config.name, model="kc", fidelity="rigid",
                        axle=axle, data_hash=config.data_hash, metrics=metrics,
                        channels=channels, notes=tuple(notes))


def _cog_height(config: Configuration) -> float:
    from vd_solvers.analytical.from_config import mass_properties

    return mass_properties(config).cog_height


#: per-wheel channel suffixes, vector component names
WHEEL = ("left", "right")
XYZ = ("x", "y", "z")
SIX_NAMES = ("x", "y", "z", "rx", "ry", "rz")

_UNITS = {
    "wheel_travel": "m", "pad_travel": "m", "wheel_centre": "m", "contact_point": "m",
    "track": "m", "contact_force": "N", "centre_force": "N", "contact_moment": "N*m", "toe": "rad",
    "camber": "rad",
    "caster": "rad", "kingpin_inclination": "rad", "scrub_radius": "m",
    "mechanical_trail": "m", "steer_angle": "rad", "pad_force": "N", "spring_length": "m",
    "spring_force": "N", "damper_length": "m", "bump_stop_force": "N",
    "bump_stop_deflection": "m", "rebound_stop_force": "N", "rebound_stop_deflection": "m",
    "arb_twist": "rad", "arb_torque": "N*m", "arb_arm_angle": "rad", "droplink_force": "N",
    "rack_travel": "m", "rack_force": "N", "steering_wheel_angle": "rad",
    "elastic_energy": "J", "constraint_residual": "m", "force_residual": "N",
    "iterations": "-", "camber_ground": "rad", "steering_axis_ground": "m",
}


def flatten_channels(raw: Mapping[str, np.ndarray]) -> dict[str, Channel]:
    """(n,), (n, 2), (n, 2, 3) and bushing (n, 2, 6) arrays -> named 1-D channels."""
    out: dict[str, Channel] = {}
    for name, array in raw.items():
        base = name.split(".", 1)[0]
        unit = _UNITS.get(base, "")
        a = np.asarray(array, dtype=float)
        if a.ndim == 1:
            out[name] = Channel(unit, a)
        elif a.ndim == 2 and a.shape[1] == 2:
            for s, side in enumerate(WHEEL):
                out[f"{name}_{side}"] = Channel(unit, a[:, s])
        elif a.ndim == 3 and a.shape[2] == 3:
            for s, side in enumerate(WHEEL):
                for c, comp in enumerate(XYZ):
                    out[f"{name}_{comp}_{side}"] = Channel(unit, a[:, s, c])
        elif a.ndim == 3 and a.shape[2] == 6:
            kind = "force" if "force" in base else "deflection"
            for s, side in enumerate(WHEEL):
                for c, comp in enumerate(SIX_NAMES):
                    u = ("N" if c < 3 else "N*m") if kind == "force" else ("m" if c < 3 else "rad")
                    out[f"{name}.{comp}_{side}"] = Channel(u, a[:, s, c])
        elif a.ndim == 2:
            for c in range(a.shape[1]):
                out[f"{name}_{c}"] = Channel(unit, a[:, c])
    return out


__all__ = ["EVENT_PARAMS", "EVENTS", "run_kc_event", "run_suite", "suspension_input",
           "bar_stiffness", "flatten_channels"]
