#!/usr/bin/env python3
"""Writes the meshes of the 3D Hertz benchmark (a sphere pressed on a block) as Gmsh MSH 4.1.

    python3 scripts/make-hertz3d-mesh.py hex [h] [-o OUT] [--ascii]
    python3 scripts/make-hertz3d-mesh.py tet [h] [-o OUT] [--ascii]
    python3 scripts/make-hertz3d-mesh.py hex-half [h] [-o OUT] [--ascii]
    python3 scripts/make-hertz3d-mesh.py hex-nonmatching [h] [--master-ratio R] [-o OUT] [--ascii]

Geometry (a quarter model, symmetric about the planes x = 0 and y = 0):

* the indenter: the part of the box [0, A] x [0, A] x [0, T] (A = T = 5)
  above the sphere of radius R = 10 centred at (0, 0, R); its bottom is
  that sphere, which touches
* the block [0, W] x [0, W] x [-D, 0] (W = D = 10) at the origin.

The two bodies share no nodes (the origin is a node of each). The element
size is `h` (default 0.1) within 1.5 of the origin (1.0 in z for the
hexahedra) and grows from there to the outer boundary.

* `hex`: every element an 8-node hexahedron, structured: the block a
  tensor grid of the spacings below; the indenter the same grid in x and
  y, its columns from the sphere (nodes on it) to z = T, each cut at the
  same fractions of its height. Spacing `h` up to 1.5 from the origin in x
  and y, 1.0 in z, then growing by GROWTH per element to the boundary.
* `hex-half`: the `hex` mesh mirrored about x = 0, a half model
  symmetric about y = 0 only (the 3D Cattaneo-Mindlin scene,
  `scenes/mindlin3d.toml`, shifts the indenter along x): the block
  [-W, W] x [0, W] x [-D, 0], the indenter over [-A, A] x [0, A], the
  spacing in x the quarter model's mirrored; no `symmetry_x` group.
* `hex-nonmatching`: the `hex` quarter model with the block's spacing in x
  and y MASTER_RATIO (or `--master-ratio`) times the indenter's (h at the contact on the
  indenter, MASTER_RATIO h on the block), so that no indenter node but the
  origin's column lies above a block node line: the contact faces do not
  match, as on meshes made body by body.
* `tet`: every element a 4-node tetrahedron, Gmsh's Delaunay mesher on the
  OpenCASCADE geometry, sized TET_SIZE h within 1.5 of the origin (edges of
  about h there), growing linearly to H_FAR at distance 6.

Physical groups (the names the 3D Hertz scene refers to):

| name               | dim | what                                          |
|--------------------|-----|-----------------------------------------------|
| `indenter`         | 3   | the indenter                                  |
| `block`            | 3   | the block                                     |
| `symmetry_x`       | 2   | x = 0 of both bodies                          |
| `symmetry_y`       | 2   | y = 0 of both bodies                          |
| `bottom`           | 2   | z = -D of the block                           |
| `indenter_top`     | 2   | z = T of the indenter (the prescribed motion) |
| `indenter_surface` | 2   | the sphere (contact slave)                    |
| `block_top`        | 2   | z = 0 of the block (contact master)           |

The faces x = A, y = A of the indenter and x = W, y = W of the block are
free and in no group. Surface elements are written counter-clockwise seen
from outside their body.

The checked-in meshes (binary MSH, the default) are regenerated with

    python3 scripts/make-hertz3d-mesh.py hex 0.1 -o scenes/hertz3d-hex.msh
    python3 scripts/make-hertz3d-mesh.py tet 0.1 -o scenes/hertz3d-tet.msh

Needs the `gmsh` Python package (`pip install gmsh`); the tetrahedral mesh
depends on its version (written with 4.15.2), the hexahedral one only on
this script.
"""

import argparse
import math

import gmsh

R = 10.0  # sphere radius
A = 5.0  # indenter width and depth (quarter model)
T = 5.0  # indenter height at the axis
W = 10.0  # block width and depth (quarter model)
D = 10.0  # block depth
FINE_XY = 1.5  # spacing h up to this distance from the origin in x and y
FINE_Z = 1.0  # and in z
GROWTH = 1.3  # the hexahedral spacing's growth beyond
H_FAR = 1.5  # the tetrahedral size far from the contact
REFINED_WITHIN = 1.5  # tetrahedral size h up to this distance from the origin
GRADED_UNTIL = 6.0  # size H_FAR from this distance on
MASTER_RATIO = 1.37  # hex-nonmatching: the block's spacing per the indenter's
TET_SIZE = 0.85  # Gmsh's size per h: its edges come out about 1.2 times the size


def spacing(length, h, fine):
    """Coordinates 0 = s_0 < ... < s_n = length: steps h up to `fine`, then
    steps growing by GROWTH, the graded part scaled to end at `length`."""
    n_fine = max(1, round(min(fine, length) / h))
    s = [k * h for k in range(n_fine + 1)]
    rest = length - s[-1]
    if rest <= 1e-12:
        return [v * length / s[-1] for v in s]
    steps = []
    step = h
    while sum(steps) < rest:
        step *= GROWTH
        steps.append(step)
    scale = rest / sum(steps)
    for st in steps:
        s.append(s[-1] + st * scale)
    s[-1] = length
    return s


def sphere_z(x, y):
    """The height of the sphere (the indenter's bottom) above (x, y)."""
    return R - math.sqrt(R * R - x * x - y * y)


class Writer:
    """Adds a structured body's nodes, hexahedra and side quads to Gmsh as
    discrete entities."""

    def __init__(self):
        self.next_node = 1
        self.next_element = 1
        self.next_entity = {2: 1, 3: 1}
        self.groups = {}  # (dim, name) -> entity tags

    def entity(self, dim, name):
        tag = self.next_entity[dim]
        self.next_entity[dim] += 1
        gmsh.model.addDiscreteEntity(dim, tag)
        if name is not None:
            self.groups.setdefault((dim, name), []).append(tag)
        return tag

    def body(self, name, position, ni, nj, nk, sides):
        """position(i, j, k) -> (x, y, z); sides: {name: (axis, high)} of
        the faces to group. Nodes (i, j, k), hexahedra and side quads as
        in solver/src/mesh/block.rs (3D)."""
        volume = self.entity(3, name)
        base = self.next_node

        def node(i, j, k):
            return base + (k * (nj + 1) + j) * (ni + 1) + i

        tags, coords = [], []
        for k in range(nk + 1):
            for j in range(nj + 1):
                for i in range(ni + 1):
                    tags.append(node(i, j, k))
                    coords.extend(position(i, j, k))
        self.next_node += len(tags)
        gmsh.model.mesh.addNodes(3, volume, tags, coords)

        hexes = []
        for k in range(nk):
            for j in range(nj):
                for i in range(ni):
                    hexes.extend(
                        [
                            node(i, j, k),
                            node(i + 1, j, k),
                            node(i + 1, j + 1, k),
                            node(i, j + 1, k),
                            node(i, j, k + 1),
                            node(i + 1, j, k + 1),
                            node(i + 1, j + 1, k + 1),
                            node(i, j + 1, k + 1),
                        ]
                    )
        self.elements(3, volume, 5, hexes, 8)

        # the hexahedron's outward faces (HEX8_FACES) by side
        local = {
            (2, False): [0, 3, 2, 1],
            (2, True): [4, 5, 6, 7],
            (1, False): [0, 1, 5, 4],
            (0, True): [1, 2, 6, 5],
            (1, True): [2, 3, 7, 6],
            (0, False): [3, 0, 4, 7],
        }
        n = [ni, nj, nk]
        for group, (axis, high) in sides.items():
            surface = self.entity(2, group)
            a, b = [c for c in range(3) if c != axis]
            quads = []
            for q in range(n[b]):
                for p in range(n[a]):
                    ijk = [0, 0, 0]
                    ijk[axis] = n[axis] - 1 if high else 0
                    ijk[a], ijk[b] = p, q
                    i, j, k = ijk
                    corners = [
                        node(i, j, k),
                        node(i + 1, j, k),
                        node(i + 1, j + 1, k),
                        node(i, j + 1, k),
                        node(i, j, k + 1),
                        node(i + 1, j, k + 1),
                        node(i + 1, j + 1, k + 1),
                        node(i, j + 1, k + 1),
                    ]
                    quads.extend(corners[c] for c in local[(axis, high)])
            self.elements(2, surface, 3, quads, 4)

    def elements(self, dim, entity, gmsh_type, nodes, per):
        count = len(nodes) // per
        tags = list(range(self.next_element, self.next_element + count))
        self.next_element += count
        gmsh.model.mesh.addElementsByType(entity, gmsh_type, tags, nodes)

    def physical_groups(self):
        for (dim, name), tags in self.groups.items():
            gmsh.model.addPhysicalGroup(dim, tags, name=name)


def mirrored(s):
    """The spacing `s` (from 0) mirrored about 0: -s_n, ..., 0, ..., s_n."""
    return [-v for v in reversed(s[1:])] + s


def hex_mesh(h, half=False, master_ratio=1.0):
    """The structured hexahedral mesh (module docs); `half`: mirrored
    about x = 0; `master_ratio`: the block's spacing in x and y per the
    indenter's."""
    writer = Writer()
    ys = spacing(W, master_ratio * h, FINE_XY)
    xs = mirrored(ys) if half else ys
    zs = spacing(D, h, FINE_Z)
    symmetry = {} if half else {"symmetry_x": (0, False)}
    symmetry["symmetry_y"] = (1, False)
    writer.body(
        "block",
        lambda i, j, k: (xs[i], ys[j], -zs[len(zs) - 1 - k]),
        len(xs) - 1,
        len(ys) - 1,
        len(zs) - 1,
        {**symmetry, "bottom": (2, False), "block_top": (2, True)},
    )
    yi = spacing(A, h, FINE_XY)
    xi = mirrored(yi) if half else yi
    ts = [t / T for t in spacing(T, h, FINE_Z)]

    def indenter(i, j, k):
        x, y = xi[i], yi[j]
        z0 = sphere_z(x, y)
        return (x, y, z0 + ts[k] * (T - z0))

    writer.body(
        "indenter",
        indenter,
        len(xi) - 1,
        len(yi) - 1,
        len(ts) - 1,
        {**symmetry, "indenter_surface": (2, False), "indenter_top": (2, True)},
    )
    writer.physical_groups()


def tet_mesh(h):
    """The tetrahedral mesh (module docs)."""
    occ = gmsh.model.occ
    ball = occ.addSphere(0.0, 0.0, R, R)
    box = occ.addBox(0.0, 0.0, 0.0, A, A, T)
    indenter = occ.intersect([(3, ball)], [(3, box)])[0][0][1]
    block = occ.addBox(0.0, 0.0, -D, W, W, D)
    occ.synchronize()
    eps = 1e-5  # OpenCASCADE bounding boxes carry its tolerance

    def classify(volume, top_name, bottom_name):
        groups = {}
        for dim, s in gmsh.model.getBoundary([(3, volume)], oriented=False):
            x0, y0, z0, x1, y1, z1 = gmsh.model.getBoundingBox(dim, s)
            if x1 < eps:
                name = "symmetry_x"
            elif y1 < eps:
                name = "symmetry_y"
            elif gmsh.model.getType(dim, s) == "Sphere":
                name = bottom_name
            elif z1 - z0 < eps and abs(z0 - (T if volume == indenter else 0.0)) < eps:
                name = top_name
            elif z1 - z0 < eps and abs(z0 + D) < eps:
                name = bottom_name
            else:
                name = None  # a free side
            if name is not None:
                groups.setdefault(name, []).append(s)
        return groups

    groups = {}
    for name, tags in classify(indenter, "indenter_top", "indenter_surface").items():
        groups.setdefault(name, []).extend(tags)
    for name, tags in classify(block, "block_top", "bottom").items():
        groups.setdefault(name, []).extend(tags)
    expected = {
        "symmetry_x",
        "symmetry_y",
        "bottom",
        "indenter_top",
        "indenter_surface",
        "block_top",
    }
    if set(groups) != expected or any(len(groups[g]) != 1 for g in expected - {"symmetry_x", "symmetry_y"}):
        raise SystemExit(f"unexpected surfaces: {groups}")
    gmsh.model.addPhysicalGroup(3, [indenter], name="indenter")
    gmsh.model.addPhysicalGroup(3, [block], name="block")
    for name in sorted(groups):
        gmsh.model.addPhysicalGroup(2, groups[name], name=name)

    # size h near the origin (a point of each body)
    origin = [
        tag
        for dim, tag in gmsh.model.getEntities(0)
        if max(abs(c) for c in gmsh.model.getValue(0, tag, [])) < eps
    ]
    field = gmsh.model.mesh.field
    distance = field.add("Distance")
    field.setNumbers(distance, "PointsList", origin)
    threshold = field.add("Threshold")
    field.setNumber(threshold, "InField", distance)
    field.setNumber(threshold, "SizeMin", TET_SIZE * h)
    field.setNumber(threshold, "SizeMax", H_FAR)
    field.setNumber(threshold, "DistMin", REFINED_WITHIN)
    field.setNumber(threshold, "DistMax", GRADED_UNTIL)
    field.setAsBackgroundMesh(threshold)
    for option in [
        "Mesh.MeshSizeExtendFromBoundary",
        "Mesh.MeshSizeFromPoints",
        "Mesh.MeshSizeFromCurvature",
    ]:
        gmsh.option.setNumber(option, 0)
    gmsh.option.setNumber("Mesh.Algorithm3D", 1)  # Delaunay
    gmsh.option.setNumber("Mesh.Optimize", 1)
    gmsh.model.mesh.generate(3)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument(
        "kind", choices=["hex", "tet", "hex-half", "hex-nonmatching"],
        help="hexahedra, tetrahedra, the half model's hexahedra, or hexahedra whose contact faces do not match"
    )
    parser.add_argument(
        "h", nargs="?", type=float, default=0.1, help="element size at the contact"
    )
    parser.add_argument(
        "--master-ratio",
        type=float,
        default=MASTER_RATIO,
        help=f"hex-nonmatching: the block's spacing per the indenter's (default {MASTER_RATIO})",
    )
    parser.add_argument("-o", "--output", help="the .msh to write (default hertz3d-KIND.msh)")
    parser.add_argument("--ascii", action="store_true", help="ASCII MSH 4.1 (default binary)")
    args = parser.parse_args()
    if not 0.0 < args.h <= 1.0:
        parser.error("h must be in (0, 1]")
    output = args.output or f"hertz3d-{args.kind}.msh"

    gmsh.initialize()
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.model.add("hertz3d")
        if args.kind == "hex":
            hex_mesh(args.h)
        elif args.kind == "hex-half":
            hex_mesh(args.h, half=True)
        elif args.kind == "hex-nonmatching":
            hex_mesh(args.h, master_ratio=args.master_ratio)
        else:
            tet_mesh(args.h)
        gmsh.option.setNumber("Mesh.MshFileVersion", 4.1)
        gmsh.option.setNumber("Mesh.Binary", 0 if args.ascii else 1)
        gmsh.option.setNumber("Mesh.SaveAll", 0)
        gmsh.write(output)
        # what was written: the elements of the physical groups' entities
        types = {}
        entities = {
            (dim, e)
            for dim, g in gmsh.model.getPhysicalGroups()
            for e in gmsh.model.getEntitiesForPhysicalGroup(dim, g)
        }
        for dim, e in sorted(entities):
            for t, tags, _ in zip(*gmsh.model.mesh.getElements(dim, e)):
                name = gmsh.model.mesh.getElementProperties(t)[0]
                types[name] = types.get(name, 0) + len(tags)
        nodes = len(gmsh.model.mesh.getNodes()[0])
        print(f"{output}: {nodes} nodes, " + ", ".join(f"{n} {k}" for k, n in types.items()))
    finally:
        gmsh.finalize()


if __name__ == "__main__":
    main()
