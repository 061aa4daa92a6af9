#!/usr/bin/env python3
"""The 3D Hertz benchmark's measurement (issue "The solver in 3D", section 4)
from the output of `gapsim run scenes/hertz3d.toml --out DIR`.

    python3 scripts/hertz3d-measure.py DIR [--young 200] [--poisson 0.3] [--radius 10] [--h 0.1]

P is four times the bottom's z reaction in the last row of DIR/reactions.csv
(the scene is a quarter model); Hertz's contact radius a = (3 P R / 4 E*)^(1/3)
and peak pressure p0 = 3 P / (2 pi a^2) with E* = E / (2 (1 - nu^2)) (two
bodies of one material). The measured peak pressure is the largest nodal
`pressure` of DIR/contact.csv, the measured contact radius the largest
hypot(x, y) of a node whose pressure exceeds 1e-3 of that peak. Prints both
against Hertz (the radius's difference in units of the element size h near
the contact) and the number of slave nodes whose own projection finds no
master face (their gap column is empty; their pressure counts).
"""
import argparse
import csv
import math
import os


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("dir", help="the --out directory of gapsim run")
    parser.add_argument("--young", type=float, default=200.0)
    parser.add_argument("--poisson", type=float, default=0.3)
    parser.add_argument("--radius", type=float, default=10.0)
    parser.add_argument("--h", type=float, default=0.1, help="element size at the contact")
    args = parser.parse_args()
    with open(os.path.join(args.dir, "reactions.csv")) as f:
        reactions = list(csv.DictReader(f))
    with open(os.path.join(args.dir, "contact.csv")) as f:
        rows = list(csv.DictReader(f))
    load = 4.0 * abs(float(reactions[-1]["bottom_z"]))
    e_star = args.young / (2.0 * (1.0 - args.poisson**2))
    a = (3.0 * load * args.radius / (4.0 * e_star)) ** (1.0 / 3.0)
    p0 = 3.0 * load / (2.0 * math.pi * a * a)
    peak = max(float(r["pressure"]) for r in rows)
    radius = max(
        math.hypot(float(r["x"]), float(r["y"]))
        for r in rows
        if float(r["pressure"]) > 1e-3 * peak
    )
    no_gap = sum(1 for r in rows if r["gap"] == "")
    print(f"P = {load:.6g}, Hertz: a = {a:.5g}, p0 = {p0:.5g}")
    print(f"peak pressure  {peak:.5g} ({100.0 * (peak / p0 - 1.0):+.2f} % of p0)")
    print(f"contact radius {radius:.4g} ({(radius - a) / args.h:+.2f} h from a)")
    print(f"slave nodes    {len(rows)}, {no_gap} of them without a projection of their own")


if __name__ == "__main__":
    main()
