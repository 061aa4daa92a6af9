#!/usr/bin/env python3
"""Writes the punch of the ironing benchmark as Gmsh MSH 4.1 (ASCII).

    python3 scripts/make-ironing-mesh.py [-o scenes/ironing-punch.msh]

Needs only the Python standard library (no Gmsh): the mesh is structured and
written directly, so the checked-in file is reproduced byte for byte.

The punch is the lower half of a disc of radius R = 1 centred at
(2.5, 2.0): its flat top is y = 2 and its arc touches the strip top y = 1 at
(2.5, 1). It is an O-grid of bilinear quadrilaterals:

* the arc from 180 to 360 degrees in 60 equal segments (length pi/60,
  about 0.052);
* a core rectangle [-0.5, 0.5] x [-0.5, 0] (relative to the centre) of
  30 x 15 squares; its left side, bottom and right side (15 + 30 + 15
  segments) face the arc's 60 segments;
* a ring of 10 layers between the core's boundary and the arc, each node on
  the straight line from a core boundary node to its arc node, equally
  spaced.

Every element is written counter-clockwise. The strip (10 x 1, 0.1
elements) is a block body of the scene, `scenes/ironing.toml`.

Physical groups:

| name            | dim | what                                   |
|-----------------|-----|----------------------------------------|
| `punch`         | 2   | the half disc                          |
| `punch_surface` | 1   | the arc (contact slave)                |
| `punch_top`     | 1   | the flat top y = 2 (press, then slide) |
"""

import argparse
import math

R = 1.0
CENTRE = (2.5, 2.0)
ARC = 60  # arc segments
SIDE = 15  # core side segments (each side of the core faces SIDE arc segments)
CORE = 0.5  # core half width and depth
LAYERS = 10  # ring layers


def build():
    """Nodes (list of (x, y)), quads (node index lists), arc and top edges."""
    cx, cy = CENTRE
    nodes = []

    def add(x, y):
        nodes.append((cx + x, cy + y))
        return len(nodes) - 1

    # core grid: i along x (0..2 SIDE), l along y from -CORE (l = 0) to 0
    ni, nl = 2 * SIDE, SIDE
    core = [[add(-CORE + 2 * CORE * i / ni, -CORE + CORE * l / nl) for l in range(nl + 1)]
            for i in range(ni + 1)]

    def core_boundary(k):
        """The core node facing arc node k (0 at 180 degrees, ARC at 360)."""
        if k <= SIDE:
            return core[0][nl - k]
        if k <= SIDE + ni:
            return core[k - SIDE][0]
        return core[ni][k - SIDE - ni]

    # ring: (k, j), j = 0 the core boundary, j = LAYERS the arc
    ring = []
    for k in range(ARC + 1):
        p = core_boundary(k)
        px, py = nodes[p][0] - cx, nodes[p][1] - cy
        t = math.pi + math.pi * k / ARC
        ax, ay = R * math.cos(t), R * math.sin(t)
        if k in (0, ARC):
            ay = 0.0  # exactly on the flat top
        column = [p]
        for j in range(1, LAYERS + 1):
            s = j / LAYERS
            column.append(add(px + s * (ax - px), py + s * (ay - py)))
        ring.append(column)

    quads = []
    for i in range(ni):
        for l in range(nl):
            quads.append([core[i][l], core[i + 1][l], core[i + 1][l + 1], core[i][l + 1]])
    for k in range(ARC):
        for j in range(LAYERS):
            quads.append([ring[k][j], ring[k][j + 1], ring[k + 1][j + 1], ring[k + 1][j]])
    quads = [counter_clockwise(q, nodes) for q in quads]

    arc = [(ring[k][LAYERS], ring[k + 1][LAYERS]) for k in range(ARC)]
    top_nodes = ([ring[0][j] for j in range(LAYERS, 0, -1)] + [core[i][nl] for i in range(ni + 1)]
                 + [ring[ARC][j] for j in range(1, LAYERS + 1)])
    top = list(zip(top_nodes, top_nodes[1:]))
    return nodes, quads, arc, top


def counter_clockwise(q, nodes):
    area = 0.0
    for a, b in zip(q, q[1:] + q[:1]):
        area += nodes[a][0] * nodes[b][1] - nodes[b][0] * nodes[a][1]
    if area == 0.0:
        raise ValueError(f"degenerate element {q}")
    return q if area > 0.0 else q[::-1]


def bbox(points):
    xs = [p[0] for p in points]
    ys = [p[1] for p in points]
    return f"{min(xs)!r} {min(ys)!r} 0 {max(xs)!r} {max(ys)!r} 0"


def write(path):
    nodes, quads, arc, top = build()
    arc_pts = [nodes[a] for e in arc for a in e]
    top_pts = [nodes[a] for e in top for a in e]
    lines = ["$MeshFormat", "4.1 0 8", "$EndMeshFormat",
             "$PhysicalNames", "3",
             '1 2 "punch_surface"', '1 3 "punch_top"', '2 1 "punch"',
             "$EndPhysicalNames",
             "$Entities", "0 2 1 0",
             f"1 {bbox(arc_pts)} 1 2 0",
             f"2 {bbox(top_pts)} 1 3 0",
             f"1 {bbox(nodes)} 1 1 0",
             "$EndEntities"]
    n = len(nodes)
    lines += ["$Nodes", f"1 {n} 1 {n}", f"2 1 0 {n}"]
    lines += [str(i + 1) for i in range(n)]
    lines += [f"{x!r} {y!r} 0" for x, y in nodes]
    lines += ["$EndNodes"]
    total = len(arc) + len(top) + len(quads)
    lines += ["$Elements", f"3 {total} 1 {total}"]
    tag = 0
    for entity_dim, entity, kind, items in [(1, 1, 1, arc), (1, 2, 1, top), (2, 1, 3, quads)]:
        lines.append(f"{entity_dim} {entity} {kind} {len(items)}")
        for item in items:
            tag += 1
            lines.append(" ".join(str(v) for v in [tag] + [a + 1 for a in item]))
    lines += ["$EndElements"]
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("-o", "--out", default="scenes/ironing-punch.msh")
    write(parser.parse_args().out)


if __name__ == "__main__":
    main()
