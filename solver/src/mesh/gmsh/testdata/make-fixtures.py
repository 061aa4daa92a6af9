#!/usr/bin/env python3
"""Writes the small fixtures of the Gmsh reader's tests (run from this directory).

    python3 make-fixtures.py

`square.msh` (ASCII) and `square-binary.msh` (the same mesh, binary): the
unit square [0, 1]^2 as 2 x 2 quadrilaterals (physical surface `left`) next
to [1, 2] x [0, 1] as 8 triangles (`right`); the two surfaces share the
curve x = 1. Physical curves `bottom` (y = 0 of both surfaces) and `inner`
(x = 1), physical point `corner` (the origin). MSH 4.1, gmsh 4.15.2.

The Hertz fixture `hertz-coarse-binary.msh` comes from
`scripts/make-hertz-mesh.py 0.5 --binary`.

The 3D fixtures `cube.msh` (one hexahedron, physical volume `body`, its
bottom written inward) and `tets.msh` (two tetrahedra sharing a face) are
written by hand; `cube-binary.msh` and `tets-binary.msh` are Gmsh's binary
copies of them (same tags; Gmsh adds empty node blocks for the surface
entities).
"""
import gmsh

def square(binary, out):
    gmsh.initialize()
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.model.add("square")
    geo = gmsh.model.geo
    p = [geo.addPoint(x, y, 0.0) for x, y in [(0, 0), (1, 0), (2, 0), (2, 1), (1, 1), (0, 1)]]
    b0 = geo.addLine(p[0], p[1])
    b1 = geo.addLine(p[1], p[2])
    r = geo.addLine(p[2], p[3])
    t1 = geo.addLine(p[3], p[4])
    mid = geo.addLine(p[1], p[4])
    t0 = geo.addLine(p[4], p[5])
    l = geo.addLine(p[5], p[0])
    left = geo.addPlaneSurface([geo.addCurveLoop([b0, mid, t0, l])])
    right = geo.addPlaneSurface([geo.addCurveLoop([b1, r, t1, -mid])])
    geo.synchronize()
    mesh = gmsh.model.mesh
    for c in [b0, b1, r, t1, mid, t0, l]:
        mesh.setTransfiniteCurve(c, 3)
    mesh.setTransfiniteSurface(left)
    mesh.setTransfiniteSurface(right)
    mesh.setRecombine(2, left)
    gmsh.model.addPhysicalGroup(2, [left], name="left")
    gmsh.model.addPhysicalGroup(2, [right], name="right")
    gmsh.model.addPhysicalGroup(1, [b0, b1], name="bottom")
    gmsh.model.addPhysicalGroup(1, [mid], name="inner")
    gmsh.model.addPhysicalGroup(0, [p[0]], name="corner")
    mesh.generate(2)
    gmsh.option.setNumber("Mesh.MshFileVersion", 4.1)
    gmsh.option.setNumber("Mesh.Binary", 1 if binary else 0)
    gmsh.write(out)
    gmsh.finalize()

square(False, "square.msh")
square(True, "square-binary.msh")


def binary_copy(src, dst):
    gmsh.initialize()
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.open(src)
    gmsh.option.setNumber("Mesh.MshFileVersion", 4.1)
    gmsh.option.setNumber("Mesh.Binary", 1)
    gmsh.write(dst)
    gmsh.finalize()

binary_copy("cube.msh", "cube-binary.msh")
binary_copy("tets.msh", "tets-binary.msh")
