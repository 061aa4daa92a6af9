#!/usr/bin/env python3
"""Writes the mesh of the plane-strain Cattaneo-Mindlin benchmark as Gmsh MSH 4.1.

    python3 scripts/make-mindlin-mesh.py [h] [-o OUT]

Geometry (the full model: a tangential load breaks the Hertz scene's
symmetry about x = 0):

* the lower half of a cylinder: radius R = 10, centre (0, R), bounded by
  the arc from (-R, R) through (0, 0) to (R, R) and the top edge y = R;
  it touches
* the block [-W, W] x [-D, 0] (W = D = 20) at the origin.

The two bodies share no nodes (each is its own surface). The element size
is `h` within 1.5 of the contact point and grows linearly to 2.0 at
distance 8 (as the Hertz meshes, `make-hertz-mesh.py`). Every element is a
bilinear quadrilateral (Frontal-Delaunay for quads, recombined, then
subdivided once, which halves the sizes).

Physical groups (the names `scenes/mindlin.toml` refers to):

| name               | dim | what                                     |
|--------------------|-----|------------------------------------------|
| `cylinder`         | 2   | the half cylinder                        |
| `block`            | 2   | the block                                |
| `cylinder_surface` | 1   | the arc (contact slave)                  |
| `block_top`        | 1   | y = 0 of the block (contact master)      |
| `load_edge`        | 1   | y = R of the cylinder (pressed, shifted) |
| `bottom`           | 1   | y = -D of the block                      |

The checked-in meshes are regenerated with

    python3 scripts/make-mindlin-mesh.py 0.1 -o scenes/mindlin.msh
    python3 scripts/make-mindlin-mesh.py 0.2 -o scenes/mindlin-medium.msh
    python3 scripts/make-mindlin-mesh.py 0.4 -o scenes/mindlin-coarse.msh

Needs the `gmsh` Python package (`pip install gmsh`); the output depends on
its version (written with 4.15.2).
"""

import argparse

import gmsh

R = 10.0  # cylinder radius
W = 20.0  # block half width
D = 20.0  # block depth
H_FAR = 2.0  # element size far from the contact
REFINED_WITHIN = 1.5  # size h up to this distance from the contact point
GRADED_UNTIL = 8.0  # size H_FAR from this distance on


def build_geometry():
    """The two surfaces and their bounding curves; returns the entity tags."""
    occ = gmsh.model.occ
    centre = occ.addPoint(0.0, R, 0.0)
    left = occ.addPoint(-R, R, 0.0)
    touch_cyl = occ.addPoint(0.0, 0.0, 0.0)
    right = occ.addPoint(R, R, 0.0)
    arc_left = occ.addCircleArc(left, centre, touch_cyl)
    arc_right = occ.addCircleArc(touch_cyl, centre, right)
    top = occ.addLine(right, left)
    cylinder = occ.addPlaneSurface([occ.addCurveLoop([arc_left, arc_right, top])])

    corners = [
        occ.addPoint(-W, -D, 0.0),
        occ.addPoint(W, -D, 0.0),
        occ.addPoint(W, 0.0, 0.0),
        occ.addPoint(0.0, 0.0, 0.0),  # touch_block: a point of its own
        occ.addPoint(-W, 0.0, 0.0),
    ]
    bottom = occ.addLine(corners[0], corners[1])
    side_right = occ.addLine(corners[1], corners[2])
    top_right = occ.addLine(corners[2], corners[3])
    top_left = occ.addLine(corners[3], corners[4])
    side_left = occ.addLine(corners[4], corners[0])
    block = occ.addPlaneSurface(
        [occ.addCurveLoop([bottom, side_right, top_right, top_left, side_left])]
    )
    occ.synchronize()
    return {
        "touch": [touch_cyl, corners[3]],
        "cylinder": cylinder,
        "block": block,
        "arc": [arc_left, arc_right],
        "top": top,
        "bottom": bottom,
        "block_top": [top_right, top_left],
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
    """The named groups the scene refers to."""
    add = gmsh.model.addPhysicalGroup
    add(2, [e["cylinder"]], name="cylinder")
    add(2, [e["block"]], name="block")
    add(1, e["arc"], name="cylinder_surface")
    add(1, e["block_top"], name="block_top")
    add(1, [e["top"]], name="load_edge")
    add(1, [e["bottom"]], name="bottom")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument(
        "h", nargs="?", type=float, default=0.1, help="element size at the contact"
    )
    parser.add_argument("-o", "--output", default="mindlin.msh", help="the .msh to write")
    args = parser.parse_args()
    if not 0.0 < args.h <= H_FAR:
        parser.error(f"h must be in (0, {H_FAR}]")

    gmsh.initialize()
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.model.add("mindlin")
        entities = build_geometry()
        size_field(entities["touch"], args.h)
        gmsh.option.setNumber("Mesh.RecombineAll", 1)
        gmsh.option.setNumber("Mesh.Algorithm", 8)  # Frontal-Delaunay for quads
        gmsh.option.setNumber("Mesh.SubdivisionAlgorithm", 1)  # all quadrangles
        physical_groups(entities)
        gmsh.model.mesh.generate(2)

        gmsh.option.setNumber("Mesh.MshFileVersion", 4.1)
        gmsh.option.setNumber("Mesh.Binary", 0)
        gmsh.write(args.output)

        node_tags, _, _ = gmsh.model.mesh.getNodes()
        elements = sum(
            len(tags)
            for dim, tag in gmsh.model.getEntities(2)
            for tags in gmsh.model.mesh.getElements(dim, tag)[1]
        )
        print(f"{args.output}: h = {args.h}, {len(node_tags)} nodes, {elements} quadrilaterals")
    finally:
        gmsh.finalize()


if __name__ == "__main__":
    main()
