#!/usr/bin/env python3
"""The 3D Hertz quarter model in CalculiX: the peer of scripts/hertz3d-vs-calculix.sh.

    scripts/calculix-hertz3d.py [--mesh scenes/hertz3d-hex.msh] [--workdir DIR]
                                [--repeat 1] [--threads 2] [--penalty 1e6]
                                [--increment 1.0] [--ccx ccx] [--format json|csv]

Reads the checked-in hexahedral Gmsh mesh (MSH 4.1, binary or ASCII, with
the `gmsh` Python package: `pip install gmsh`) with the physical groups of
scenes/hertz3d.toml (indenter, block, symmetry_x, symmetry_y, bottom,
indenter_top, indenter_surface, block_top) and writes a CalculiX deck
`hertz3d.inp` with the same problem as scenes/hertz3d.toml:

- C3D8 (Gmsh's 8-node hexahedron has CalculiX's node order: the bottom
  face 1-2-3-4, the top 5-6-7-8 above it; every element's volume is
  checked positive), linear elasticity E = 200, nu = 0.3 (small strain: no
  NLGEOM, like the scene);
- symmetry_x: x fixed; symmetry_y: y fixed; bottom: x, y and z fixed;
- indenter_top: u_z = -0.1 prescribed in the step (*BOUNDARY), ramped
  over the step like gapsim's load factor;
- penalty surface-to-surface contact, slave indenter_surface, master
  block_top, both as element faces (*SURFACE TYPE=ELEMENT: each group quad
  is the face S1..S6 of the one hexahedron that has its four nodes),
  linear pressure-overclosure of slope PENALTY (default 1e6, the 2D
  script's: the penetration p0 / PENALTY, about 7e-6 at the peak pressure,
  is 7e-5 of the 0.1 indentation and of the element size h = 0.1, while
  the contact stiffness stays within what CalculiX converges with), no
  tension;
- one *STATIC step, initial increment INCREMENT of the step (default 1.0:
  the whole indentation at once, like gapsim's one load step; CalculiX
  converges so on this mesh, while the 2D script's 0.1 takes about three
  times the iterations and time), at most 200 increments; displacements
  and reactions (U, RF) and contact stresses (CSTR) to the .frd.

Then runs `ccx -i hertz3d` REPEAT times (default 1: one run takes minutes)
with OMP_NUM_THREADS=THREADS, each timed as a whole process (wall clock,
like `time`; also its CPU time, user plus system, of all threads), and
measures the last run's results as gapsim::hertz::sphere::measure_3d does
gapsim's:

- load: P = 4 |sum of RF_z over the bottom nodes| (last increment's FORC
  block of the .frd); Hertz: E* = E / (2 (1 - nu^2)),
  a = (3 P R / (4 E*))^(1/3), p0 = 3 P / (2 pi a^2), R = 10;
- peak: the largest nodal CPRESS of the last increment's CONTACT block at
  the slave nodes (indenter_surface); radius: the largest hypot(x, y) of a
  slave node with CPRESS above 1e-3 of the peak, at the current
  coordinates x_ref + u (DISP block); radius_error: (radius - a) / h with
  h = 0.1;
- penetration: the largest overclosure -COPEN of a slave node;
- iterations: every equilibrium iteration of the .cvg (all increments and
  attempts); increments: the converged increments of the .sta.

Prints one JSON object (or a CSV header and row) on stdout.
"""
import argparse
import json
import math
import os
import shutil
import statistics
import subprocess
import sys
import time

YOUNG, POISSON = 200.0, 0.3
INDENTATION = -0.1        # u_z of indenter_top
RADIUS = 10.0             # the indenter's sphere
H = 0.1                   # the element size at the contact (scripts/make-hertz3d-mesh.py)
GROUPS = ('indenter', 'block', 'symmetry_x', 'symmetry_y', 'bottom',
          'indenter_top', 'indenter_surface', 'block_top')
# C3D8 faces S1..S6 as local nodes (0-based), CalculiX's manual (C3D8)
FACES = ((0, 1, 2, 3), (4, 7, 6, 5), (0, 4, 5, 1), (1, 5, 6, 2), (2, 6, 7, 3), (3, 7, 4, 0))


class MeshError(Exception):
    """A mesh file this script cannot use."""


def read_msh(path):
    """Nodes {tag: (x, y, z)} and {physical name: [element node lists]} of
    an MSH 4.1 file (surfaces: 4-node quads; volumes: 8-node hexahedra)."""
    try:
        import gmsh
    except ImportError:
        raise MeshError('needs the gmsh Python package (pip install gmsh)')
    if not os.path.exists(path):
        raise MeshError(f'{path}: no such file')
    gmsh.initialize()
    try:
        gmsh.option.setNumber('General.Terminal', 0)
        gmsh.open(path)
        tags, coords, _ = gmsh.model.mesh.getNodes()
        nodes = {int(t): (coords[3 * i], coords[3 * i + 1], coords[3 * i + 2])
                 for i, t in enumerate(tags)}
        groups = {}
        for dim, tag in gmsh.model.getPhysicalGroups():
            name = gmsh.model.getPhysicalName(dim, tag)
            for entity in gmsh.model.getEntitiesForPhysicalGroup(dim, tag):
                for etype, _, conn in zip(*gmsh.model.mesh.getElements(dim, entity)):
                    want = {2: (3, 4), 3: (5, 8)}.get(dim)
                    if want is None or etype != want[0]:
                        raise MeshError(f'{path}: group {name}: element type {etype} '
                                        '(need 4-node quads, 8-node hexahedra)')
                    per = want[1]
                    groups.setdefault(name, []).extend(
                        [int(n) for n in conn[k:k + per]] for k in range(0, len(conn), per))
    except ValueError as e:     # gmsh's errors
        raise MeshError(f'{path}: {e}')
    finally:
        gmsh.finalize()
    missing = [g for g in GROUPS if g not in groups]
    if missing:
        raise MeshError(f'{path}: no physical group(s) {", ".join(missing)}')
    return nodes, groups


def hex_volume(x):
    """The volume of a hexahedron with corners x (C3D8 order), by its 2x2x2
    Gauss rule: negative when the node order is inside out."""
    g = 1.0 / math.sqrt(3.0)
    signs = ((-1, -1, -1), (1, -1, -1), (1, 1, -1), (-1, 1, -1),
             (-1, -1, 1), (1, -1, 1), (1, 1, 1), (-1, 1, 1))
    vol = 0.0
    for a in (-g, g):
        for b in (-g, g):
            for c in (-g, g):
                j = [[0.0] * 3 for _ in range(3)]
                for (sa, sb, sc), p in zip(signs, x):
                    d = (sa * (1 + sb * b) * (1 + sc * c) / 8,
                         sb * (1 + sa * a) * (1 + sc * c) / 8,
                         sc * (1 + sa * a) * (1 + sb * b) / 8)
                    for r in range(3):
                        for s in range(3):
                            j[r][s] += p[r] * d[s]
                vol += (j[0][0] * (j[1][1] * j[2][2] - j[1][2] * j[2][1])
                        - j[0][1] * (j[1][0] * j[2][2] - j[1][2] * j[2][0])
                        + j[0][2] * (j[1][0] * j[2][1] - j[1][1] * j[2][0]))
    return vol


def write_deck(path, nodes, groups, penalty, increment):
    """Writes the CalculiX deck; returns (elements, slave node tags,
    bottom node tags)."""
    elements = {}
    for body in ('indenter', 'block'):
        for q in groups[body]:
            if hex_volume([nodes[n] for n in q]) <= 0.0:
                raise MeshError(f'{body}: a hexahedron {q} with non-positive volume')
            elements[len(elements) + 1] = (body, q)

    def surface(group, body):
        want = {frozenset(q): tuple(q) for q in groups[group]}
        found = {}
        for e, (b, q) in elements.items():
            if b != body:
                continue
            for k, face in enumerate(FACES):
                key = frozenset(q[i] for i in face)
                if key in want:
                    if key in found:
                        raise MeshError(f'group {group}: quad {want[key]} is a face of two elements')
                    found[key] = (e, k + 1)
        if len(found) != len(want):
            raise MeshError(f'group {group}: {len(want) - len(found)} quad(s) are no face of {body}')
        return sorted(found.values())

    def node_set(*names):
        return sorted({n for g in names for quad in groups[g] for n in quad})

    used = sorted({n for _, q in elements.values() for n in q})
    L = ['** 3D Hertz quarter model (scenes/hertz3d.toml), written by scripts/calculix-hertz3d.py',
         '*NODE']
    L += [f'{n},{nodes[n][0]:.17g},{nodes[n][1]:.17g},{nodes[n][2]:.17g}' for n in used]
    for body, name in (('indenter', 'IND'), ('block', 'BLK')):
        L += [f'*ELEMENT,TYPE=C3D8,ELSET={name}']
        L += [f'{e},{",".join(map(str, q))}' for e, (b, q) in elements.items() if b == body]

    def nset(name, ids):
        # at most 16 entries a line (CalculiX's limit)
        return [f'*NSET,NSET={name}'] + [','.join(map(str, ids[k:k + 16])) for k in range(0, len(ids), 16)]

    L += nset('SYMX', node_set('symmetry_x'))
    L += nset('SYMY', node_set('symmetry_y'))
    L += nset('BOT', node_set('bottom'))
    L += nset('TOP', node_set('indenter_top'))
    L += ['*SURFACE,NAME=SLAVE,TYPE=ELEMENT'] + [f'{e},S{k}' for e, k in surface('indenter_surface', 'indenter')]
    L += ['*SURFACE,NAME=MASTER,TYPE=ELEMENT'] + [f'{e},S{k}' for e, k in surface('block_top', 'block')]
    L += ['*MATERIAL,NAME=MAT', '*ELASTIC', f'{YOUNG},{POISSON}']
    L += ['*SOLID SECTION,ELSET=IND,MATERIAL=MAT', '*SOLID SECTION,ELSET=BLK,MATERIAL=MAT']
    L += ['*SURFACE INTERACTION,NAME=SI', '*SURFACE BEHAVIOR,PRESSURE-OVERCLOSURE=LINEAR', f'{penalty:g},0.,0.']
    L += ['*CONTACT PAIR,INTERACTION=SI,TYPE=SURFACE TO SURFACE', 'SLAVE,MASTER']
    L += ['*BOUNDARY', 'SYMX,1,1', 'SYMY,2,2', 'BOT,1,3']
    L += ['*STEP,INC=200', '*STATIC', f'{increment:g},1.0']
    L += ['*BOUNDARY', f'TOP,3,3,{INDENTATION}']
    L += ['*NODE FILE', 'U,RF', '*CONTACT FILE', 'CSTR', '*END STEP']
    with open(path, 'w') as f:
        f.write('\n'.join(L) + '\n')
    return elements, node_set('indenter_surface'), node_set('bottom')


def read_frd_block(path, name):
    """{node: [values]} of the last result block NAME of a .frd file."""
    block, inside = None, False
    with open(path) as f:
        for line in f:
            if line.startswith(' -4'):
                inside = line.split()[1] == name
                if inside:
                    block = {}
            elif inside and line.startswith(' -3'):
                inside = False
            elif inside and line.startswith(' -1'):
                node = int(line[3:13])
                body = line[13:].rstrip('\n')
                block[node] = [float(body[12 * k:12 * k + 12]) for k in range(len(body) // 12)]
    if block is None:
        raise RuntimeError(f'{path}: no {name} block (did ccx converge?)')
    return block


def ccx_version(ccx):
    r = subprocess.run([ccx, '-v'], capture_output=True, text=True)
    out = (r.stdout + r.stderr).strip().splitlines()
    return out[-1].replace('This is Version', '').strip() if out else 'unknown'


def main():
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('--mesh', default=os.path.join(root, 'scenes', 'hertz3d-hex.msh'))
    ap.add_argument('--workdir', default=os.path.join(root, 'target', 'calculix-hertz3d'))
    ap.add_argument('--repeat', type=int, default=1)
    ap.add_argument('--threads', type=int, default=2)
    ap.add_argument('--penalty', type=float, default=1e6)
    ap.add_argument('--increment', type=float, default=1.0)
    ap.add_argument('--ccx', default='ccx')
    ap.add_argument('--format', choices=('json', 'csv'), default='json')
    args = ap.parse_args()
    if shutil.which(args.ccx) is None:
        sys.exit(f'calculix-hertz3d: {args.ccx} not found (apt-get install calculix-ccx)')
    if args.repeat < 1:
        sys.exit('calculix-hertz3d: --repeat must be at least 1')
    if not 0.0 < args.increment <= 1.0:
        sys.exit('calculix-hertz3d: --increment must be in (0, 1]')
    try:
        nodes, groups = read_msh(args.mesh)
        os.makedirs(args.workdir, exist_ok=True)
        elements, slaves, bottom = write_deck(os.path.join(args.workdir, 'hertz3d.inp'),
                                              nodes, groups, args.penalty, args.increment)
    except (OSError, MeshError) as e:
        sys.exit(f'calculix-hertz3d: {e}')

    env = dict(os.environ, OMP_NUM_THREADS=str(args.threads))
    walls, cpus, loads = [], [], []
    for i in range(args.repeat):
        for ext in ('frd', 'dat', 'sta', 'cvg'):
            try:
                os.remove(os.path.join(args.workdir, 'hertz3d.' + ext))
            except FileNotFoundError:
                pass
        load_before = os.getloadavg()[0]
        cpu_start = os.times()
        start = time.perf_counter()
        r = subprocess.run([args.ccx, '-i', 'hertz3d'], cwd=args.workdir, env=env,
                           stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        walls.append(time.perf_counter() - start)
        cpu_end = os.times()
        cpus.append(cpu_end.children_user + cpu_end.children_system
                    - cpu_start.children_user - cpu_start.children_system)
        loads.append([load_before, os.getloadavg()[0]])
        with open(os.path.join(args.workdir, 'ccx.log'), 'w') as f:
            f.write(r.stdout)
        if r.returncode != 0 or 'Job finished' not in r.stdout:
            sys.exit(f'calculix-hertz3d: ccx failed (exit {r.returncode}); see {args.workdir}/ccx.log')
        print(f'calculix-hertz3d: run {i + 1}/{args.repeat}: {walls[-1]:.2f} s (cpu {cpus[-1]:.2f} s)',
              file=sys.stderr)

    frd = os.path.join(args.workdir, 'hertz3d.frd')
    contact = read_frd_block(frd, 'CONTACT')     # COPEN CSLIP1 CSLIP2 CPRESS CSHEAR1 CSHEAR2
    disp = read_frd_block(frd, 'DISP')           # D1 D2 D3
    forces = read_frd_block(frd, 'FORC')         # F1 F2 F3 (RF)
    load = 4.0 * abs(sum(forces.get(n, [0.0] * 3)[2] for n in bottom))
    points = []
    for n in slaves:
        x = [nodes[n][k] + disp[n][k] for k in range(3)]
        points.append((math.hypot(x[0], x[1]), contact.get(n, [0.0] * 4)[3]))
    peak = max(p for _, p in points)
    radius = max((r for r, p in points if p > 1e-3 * peak), default=0.0)
    penetration = max((-contact[n][0] for n in slaves if n in contact), default=0.0)
    with open(os.path.join(args.workdir, 'hertz3d.sta')) as f:
        sta = [ln.split() for ln in f if ln.split() and ln.split()[0].isdigit()]
    with open(os.path.join(args.workdir, 'hertz3d.cvg')) as f:
        cvg = [ln.split() for ln in f if ln.split() and ln.split()[0].isdigit()]
    e_star = YOUNG / (2 * (1 - POISSON ** 2))
    a = (3 * load * RADIUS / (4 * e_star)) ** (1 / 3)
    p0 = 3 * load / (2 * math.pi * a * a)
    out = {
        'solver': f'CalculiX {ccx_version(args.ccx)}',
        'mesh': os.path.relpath(args.mesh, root),
        'nodes': len({n for _, q in elements.values() for n in q}),
        'elements': len(elements),
        'threads': args.threads,
        'penalty': args.penalty,
        'increment': args.increment,
        'repeat': args.repeat,
        'seconds': statistics.median(walls),
        'seconds_all': walls,
        'cpu_seconds': statistics.median(cpus),
        'cpu_seconds_all': cpus,
        'load_average_all': loads,
        'load': load,
        'a': a,
        'p0': p0,
        'peak': peak,
        'peak_error': peak / p0 - 1.0,
        'radius': radius,
        'radius_error_h': (radius - a) / H,
        'in_contact': sum(1 for _, p in points if p > 1e-3 * peak),
        'slave_nodes': len(points),
        'penetration': penetration,
        'increments': len(sta),
        'iterations': len(cvg),
    }
    if args.format == 'json':
        print(json.dumps(out, indent=1))
    else:
        keys = [k for k in out if not k.endswith('_all')]
        print(','.join(keys))
        print(','.join(str(out[k]) for k in keys))


if __name__ == '__main__':
    main()
