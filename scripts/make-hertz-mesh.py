#!/usr/bin/env python3
"""Writes the mesh of the plane-strain Hertz benchmark (issue #7) as Gmsh MSH 4.1.

    python3 scripts/make-hertz-mesh.py [h] [-o OUT] [--binary] [--triangles]

Geometry (the quarter model, symmetric about x = 0; lengths as in the issue):

* the quarter cylinder: radius R = 10, centre (0, R), bounded by the arc
  from (0, 0) to (R, R), the top edge y = R and the axis x = 0; it touches
* the block [0, W] x [-D, 0] (W = D = 20) at the origin.

The two bodies share no nodes (each is its own surface). The element size is
`h` within 1.5 of the contact point and grows linearly to 2.0 at distance 8.
Every element is a bilinear quadrilateral (Frontal-Delaunay for quads,
recombined, then subdivided once, which halves the sizes). With
`--triangles` every element is a linear triangle (Frontal-Delaunay, not
recombined) and the size field is halved instead, so that the edges have
about the lengths of the quadrilateral mesh of the same `h`.

Physical groups (the names the scenes refer to; the same names and geometry
as the CalculiX peer, so that both can run the same mesh):

| name               | dim | what                                     |
|--------------------|-----|------------------------------------------|
| `cylinder`         | 2   | the quarter cylinder                     |
| `block`            | 2   | the block                                |
| `cylinder_surface` | 1   | the arc (contact slave)                  |
| `block_top`        | 1   | y = 0 of the block (contact master)      |
| `load_edge`        | 1   | y = R of the cylinder (the load)         |
| `symmetry`         | 1   | x = 0 of both bodies                     |
| `bottom`           | 1   | y = -D of the block                      |

The checked-in meshes are regenerated with

    python3 scripts/make-hertz-mesh.py 0.1 -o scenes/hertz.msh
    python3 scripts/make-hertz-mesh.py 0.5 -o scenes/hertz-coarse.msh
    python3 scripts/make-hertz-mesh.py 0.5 --binary \\
        -o solver/src/mesh/gmsh/testdata/hertz-coarse-binary.msh
    for h in 0.8 0.4 0.2 0.05; do    # the refinement study's meshes
        python3 scripts/make-hertz-mesh.py $h -o scenes/hertz-refinement/h$h.msh
    done
    python3 scripts/make-hertz-mesh.py 0.5 --triangles -o scenes/hertz-tri-coarse.msh

Needs the `gmsh` Python package (`pip install gmsh`); the output depends on
its version (written with 4.15.2).
"""

import argparse

import gmsh

R = 10.0  # cylinder radius
W = 20.0  # block width
D = 20.0  # block depth
H_FAR = 2.0  # element size far from the contact
REFINED_WITHIN = 1.5  # size h up to this distance from the contact point
GRADED_UNTIL = 8.0  # size H_FAR from this distance on


def build_geometry():
    """The two surfaces and their bounding curves; returns the entity tags."""
    occ = gmsh.model.occ
    centre = occ.addPoint(0.0, R, 0.0)
    touch_cyl = occ.addPoint(0.0, 0.0, 0.0)
    rim = occ.addPoint(R, R, 0.0)
    arc = occ.addCircleArc(touch_cyl, centre, rim)
    top = occ.addLine(rim, centre)
    axis = occ.addLine(centre, touch_cyl)
    cylinder = occ.addPlaneSurface([occ.addCurveLoop([arc, top, axis])])

    corners = [
        occ.addPoint(0.0, -D, 0.0),
        occ.addPoint(W, -D, 0.0),
        occ.addPoint(W, 0.0, 0.0),
        occ.addPoint(0.0, 0.0, 0.0),  # touch_block: a point of its own
    ]
    bottom, right, block_top, block_axis = (
        occ.addLine(corners[k], corners[(k + 1) % 4]) for k in range(4)
    )
    block = occ.addPlaneSurface(
        [occ.addCurveLoop([bottom, right, block_top, block_axis])]
    )
    occ.synchronize()
    return {
        "touch": [touch_cyl, corners[3]],
        "cylinder": cylinder,
        "block": block,
        "arc": arc,
        "top": top,
        "axis": axis,
        "bottom": bottom,
        "block_top": block_top,
        "block_axis": block_axis,
    }


def size_field(touch_points, h, far=H_FAR):
    """Size h near the contact point, graded to `far`."""
    field = gmsh.model.mesh.field
    distance = field.add("Distance")
    field.setNumbers(distance, "PointsList", touch_points)
    threshold = field.add("Threshold")
    field.setNumber(threshold, "InField", distance)
    field.setNumber(threshold, "SizeMin", h)
    field.setNumber(threshold, "SizeMax", far)
    field.setNumber(threshold, "DistMin", REFINED_WITHIN)
    field.setNumber(threshold, "DistMax", GRADED_UNTIL)
    field.setAsBackgroundMesh(threshold)
    gmsh.option.setNumber("Mesh.MeshSizeExtendFromBoundary", 0)


def physical_groups(e):
    """The named groups the scenes refer to."""
    add = gmsh.model.addPhysicalGroup
    add(2, [e["cylinder"]], name="cylinder")
    add(2, [e["block"]], name="block")
    add(1, [e["arc"]], name="cylinder_surface")
    add(1, [e["block_top"]], name="block_top")
    add(1, [e["top"]], name="load_edge")
    add(1, [e["axis"], e["block_axis"]], name="symmetry")
    add(1, [e["bottom"]], name="bottom")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument(
        "h", nargs="?", type=float, default=0.1, help="element size at the contact"
    )
    parser.add_argument("-o", "--output", default="hertz.msh", help="the .msh to write")
    parser.add_argument(
        "--binary", action="store_true", help="binary MSH 4.1 (default ASCII)"
    )
    parser.add_argument(
        "--triangles",
        action="store_true",
        help="linear triangles only (default: quadrilaterals only)",
    )
    args = parser.parse_args()
    if not 0.0 < args.h <= H_FAR:
        parser.error(f"h must be in (0, {H_FAR}]")

    gmsh.initialize()
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.model.add("hertz")
        entities = build_geometry()
        if args.triangles:
            # no subdivision: halve the sizes here instead
            size_field(entities["touch"], args.h / 2.0, H_FAR / 2.0)
            gmsh.option.setNumber("Mesh.Algorithm", 6)  # Frontal-Delaunay
        else:
            size_field(entities["touch"], args.h)
            gmsh.option.setNumber("Mesh.RecombineAll", 1)
            gmsh.option.setNumber("Mesh.Algorithm", 8)  # Frontal-Delaunay for quads
            gmsh.option.setNumber("Mesh.SubdivisionAlgorithm", 1)  # all quadrangles
        physical_groups(entities)
        gmsh.model.mesh.generate(2)

        gmsh.option.setNumber("Mesh.MshFileVersion", 4.1)
        gmsh.option.setNumber("Mesh.Binary", 1 if args.binary else 0)
        gmsh.write(args.output)

        node_tags, _, _ = gmsh.model.mesh.getNodes()
        elements = sum(
            len(tags)
            for dim, tag in gmsh.model.getEntities(2)
            for tags in gmsh.model.mesh.getElements(dim, tag)[1]
        )
        kind = "triangles" if args.triangles else "quadrilaterals"
        print(f"{args.output}: h = {args.h}, {len(node_tags)} nodes, {elements} {kind}")
    finally:
        gmsh.finalize()


if __name__ == "__main__":
    main()
