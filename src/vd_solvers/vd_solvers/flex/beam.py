# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
The 3D two-node beam element (12 DOF), Timoshenko.

Node DOFs (u_x, u_y, u_z, theta_x, theta_y, theta_z); element DOFs node a then
node b. Local x runs from a to b; local z is the projection of the reference
direction ``up`` (default the vehicle z axis; the vehicle x axis for members
within 10 deg of vertical) on the plane normal to x, and y = z cross x.

Stiffness in local axes (Przemieniecki, "Theory of Matrix Structural
Analysis", 1968, eq. 5.116, with the shear parameters
phi_y = 12 E Iz / (G As_y L^2) and phi_z = 12 E Iy / (G As_z L^2); phi = 0
gives Euler-Bernoulli). The element is exact for end loads of a prismatic
beam, so one element per straight member is enough for statics.

The element is linear and small-strain. Large rigid motions of the component
it belongs to are handled by the co-rotational embedding in the K&C model
(:mod:`vd_solvers.kc.assembly`): deformations are measured in the frame of the
component's reference node, so a rigid rotation stores no strain energy.
"""
from __future__ import annotations

import numpy as np

from vd_solvers.errors import SolverError

from .section import Material, Section

#: cosine above which a member counts as vertical (the x axis then orients it)
_VERTICAL_COS = np.cos(np.radians(10.0))
#: a member shorter than this is a modelling error (coincident points)
MIN_LENGTH = 1e-4  # m


def local_axes(a: np.ndarray, b: np.ndarray, what: str) -> tuple[np.ndarray, float]:
    """Rows (x, y, z) of the element frame in vehicle axes (3, 3) and the length."""
    d = np.asarray(b, dtype=float) - np.asarray(a, dtype=float)
    length = float(np.linalg.norm(d))
    if not length > MIN_LENGTH:
        raise SolverError(
            f"{what}: the member's end points coincide (length {length * 1e3:.3g} mm)"
        )
    x = d / length
    up = np.array([0.0, 0.0, 1.0]) if abs(x[2]) < _VERTICAL_COS else np.array([1.0, 0.0, 0.0])
    z = up - (up @ x) * x
    z /= np.linalg.norm(z)
    return np.vstack((x, np.cross(z, x), z)), length


def local_stiffness(length: float, material: Material, section: Section) -> np.ndarray:
    """12 x 12 element stiffness in local axes."""
    e, g, L = material.youngs_modulus, material.shear_modulus, length
    k = np.zeros((12, 12))
    ea, gj = e * section.area / L, g * section.j / L
    k[0, 0] = k[6, 6] = ea
    k[0, 6] = -ea
    k[3, 3] = k[9, 9] = gj
    k[3, 9] = -gj
    # bending in the x-y plane (u_y, theta_z): Iz, shear area y
    phi = (
        0.0
        if section.shear_area_y is None
        else 12.0 * e * section.iz / (g * section.shear_area_y * L**2)
    )
    c = e * section.iz / (1.0 + phi)
    k1, k2, k3, k4 = 12.0 * c / L**3, 6.0 * c / L**2, (4.0 + phi) * c / L, (2.0 - phi) * c / L
    k[1, 1], k[1, 5], k[1, 7], k[1, 11] = k1, k2, -k1, k2
    k[5, 5], k[5, 7], k[5, 11] = k3, -k2, k4
    k[7, 7], k[7, 11], k[11, 11] = k1, -k2, k3
    # bending in the x-z plane (u_z, theta_y): Iy, shear area z
    phi = (
        0.0
        if section.shear_area_z is None
        else 12.0 * e * section.iy / (g * section.shear_area_z * L**2)
    )
    c = e * section.iy / (1.0 + phi)
    k1, k2, k3, k4 = 12.0 * c / L**3, 6.0 * c / L**2, (4.0 + phi) * c / L, (2.0 - phi) * c / L
    k[2, 2], k[2, 4], k[2, 8], k[2, 10] = k1, -k2, -k1, -k2
    k[4, 4], k[4, 8], k[4, 10] = k3, k2, k4
    k[8, 8], k[8, 10], k[10, 10] = k1, k2, k3
    return np.triu(k) + np.triu(k, 1).T


def element_stiffness(a: np.ndarray, b: np.ndarray, material: Material, section: Section,
                      what: str = 'beam') -> np.ndarray:
    """12 x 12 element stiffness in vehicle axes between points ``a`` and ``b`` (m)."""
    axes, length = local_axes(a, b, what)
    t = np.kron(np.eye(4), axes)
    return t.T @ local_stiffness(length, material, section) @ t


def element_mass(
    a: np.ndarray, b: np.ndarray, material: Material, section: Section
) -> tuple[float, np.ndarray]:
    """Mass (kg) and centre of mass (3,) of the element."""
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    return material.density * section.area * float(np.linalg.norm(b - a)), 0.5 * (a + b)
