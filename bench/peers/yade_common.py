# What the Yade scripts of bench/peers share: the rock, boxes as polyhedra, the engines of a
# polyhedra DEM run and its time step (imported by yade_sliding.py and yade_pile.py, which
# Yade runs with its own globals: O and the engine classes come from yade.wrapper).
import math

from yade import polyhedra_utils
from yade.wrapper import (Bo1_Polyhedra_Aabb, ForceResetter, Ig2_Polyhedra_Polyhedra_PolyhedraGeom,
                          InsertionSortCollider, InteractionLoop,
                          Ip2_PolyhedraMat_PolyhedraMat_PolyhedraPhys,
                          Law2_PolyhedraGeom_PolyhedraPhys_Volumetric, NewtonIntegrator,
                          PolyhedraMat)

DENSITY = 2600.0  # kg/m3, as scenes::setRock of the rockmass benchmarks
YOUNG = 10e9  # Pa


def rock(friction_angle):
    return PolyhedraMat(density=DENSITY, young=YOUNG, poisson=0.25, frictionAngle=friction_angle)


def box(material, lo, hi, fixed=False):
    """A box polyhedron from corner lo to corner hi (m)."""
    corners = [(x, y, z) for x in (lo[0], hi[0]) for y in (lo[1], hi[1]) for z in (lo[2], hi[2])]
    return polyhedra_utils.polyhedra(material, v=corners, fixed=fixed)


def engines(gravity, damping):
    """Collision, the volumetric contact law and Newton's integrator (no damping at 0)."""
    return [
        ForceResetter(),
        InsertionSortCollider([Bo1_Polyhedra_Aabb()]),
        InteractionLoop([Ig2_Polyhedra_Polyhedra_PolyhedraGeom()],
                        [Ip2_PolyhedraMat_PolyhedraMat_PolyhedraPhys()],
                        [Law2_PolyhedraGeom_PolyhedraPhys_Volumetric()]),
        NewtonIntegrator(damping=damping, gravity=gravity),
    ]


def time_step(factor):
    """factor x L sqrt(rho / E) with L = 1 m: the P-wave time across a 1 m cube, sqrt(m / k)
    for the volumetric law's face stiffness E A on its 1 m2 face (the explicit scheme is
    stable below about 2 of it; Yade's PWaveTimeStep() looks for spheres and finds none)."""
    return factor * 1.0 * math.sqrt(DENSITY / YOUNG)
