"""The typed pieces of a model for piezocontact.Problem: a material, a
boundary, a contact law, the time interval. Each turns into the config's
keys (`config()`); the C++ validator checks them, with the config's rules
and messages. Values are SI: m, s, Pa, C, V (each field says which).

A load may be a number, a history ({"history": ...}), an expression string
of x, y, z, t (muparser), a UFL expression of the mesh's
ufl.SpatialCoordinate (and of the user's own Constants), or a function
f(x, t) returning one (t: the time, a Constant the core sets every step)."""

from dataclasses import dataclass, fields
from typing import Any, Optional, Sequence

import numpy as np
import ufl

def is_ufl(value):
    """A UFL expression, a function f(x, t) returning one, or a list with a
    UFL entry (a vector written entry by entry)."""
    if isinstance(value, ufl.core.expr.Expr) or (callable(value) and not isinstance(value, type)):
        return True
    return isinstance(value, (list, tuple)) and any(isinstance(v, ufl.core.expr.Expr)
                                                    for v in value)


def as_function_of_x_t(value):
    """The `data` hook's f(x, t) of a UFL value."""
    if isinstance(value, (list, tuple)):
        value = ufl.as_vector(list(value))
    if isinstance(value, ufl.core.expr.Expr):
        return lambda x, t: value
    return value


def plain(value):
    """A value as JSON takes it (numpy arrays and scalars, tuples, typed
    pieces)."""
    if hasattr(value, "config"):
        return value.config()
    if isinstance(value, np.ndarray):
        return value.tolist()
    if isinstance(value, np.generic):
        return value.item()
    if isinstance(value, (list, tuple)):
        return [plain(v) for v in value]
    if isinstance(value, dict):
        return {str(k): plain(v) for k, v in value.items()}
    return value


class _Keys:
    """A dataclass whose fields are config keys: the ones given (not None)."""

    def config(self):
        return {f.name: plain(getattr(self, f.name)) for f in fields(self)
                if getattr(self, f.name) is not None}


@dataclass
class Material(_Keys):
    """A region's material: a preset of config/materials.json with its
    orientation, or explicit Voigt tensors in the mesh frame (Voigt order
    xx, yy, zz, yz, xz, xy in 3D; a 2D mesh takes the reduced 3x3 / 2x3 /
    2x2 forms or the 3D ones, which its formulation reduces)."""
    preset: Optional[str] = None                 # "PZT-5H", "PZT-4", "ZnO-paper"
    poling: Optional[Sequence[float]] = None     # the preset's axis 3 in the mesh frame
    euler: Optional[Sequence[float]] = None      # Bunge angles of its axes, degrees
    elastic: Optional[Any] = None                # Bv, Pa
    viscosity: Optional[Any] = None              # Av, Pa s
    relaxation_time: Optional[float] = None      # Av = relaxation_time Bv, s
    piezoelectric: Optional[Any] = None          # e, C/m^2 (rows: D components)
    permittivity: Optional[Any] = None           # beta, C^2/(N m^2) = F/m
    density: Optional[float] = None              # rho, kg/m^3 (dynamic analyses)


@dataclass
class Contact(_Keys):
    """A contact law and obstacle (the top-level `contact` block, or a
    boundary's own)."""
    c_p: Optional[float] = None                  # normal compliance, N/m^3
    gap: Optional[Any] = None                    # the foundation's gap g, m (or an expression)
    obstacle: Optional[dict] = None              # {"plane"|"sphere"|"cylinder": {...}}
    method: Optional[str] = None                 # "penalty" (default) or "nitsche"
    gamma: Optional[float] = None                # Nitsche's gamma_0 (dimensionless)
    theta: Optional[int] = None                  # Nitsche's 1, 0 or -1


@dataclass
class Boundary(_Keys):
    """What holds on a named boundary. Dirichlet data (displacement,
    potential) are numbers, histories, expression strings or None (a free
    component); traction and surface_charge may also be UFL."""
    displacement: Optional[Sequence[Any]] = None  # u, m (None entries: free)
    potential: Optional[Any] = None               # phi, V
    floating: Optional[dict] = None               # a floating electrode ({} or {"charge": C})
    traction: Optional[Any] = None                # f_F, N/m^2
    surface_charge: Optional[Any] = None          # q_F, C/m^2
    contact: Optional[Any] = None                 # True (the top-level law) or a Contact
    spring: Optional[dict] = None                 # {"normal": N/m^3, "tangential": N/m^3}


@dataclass
class Time(_Keys):
    """The time interval [0, T] (s) in `steps` backward Euler steps."""
    T: float
    steps: int
