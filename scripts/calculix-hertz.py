#!/usr/bin/env python3
"""The Hertz quarter model in CalculiX: the peer of scripts/hertz-vs-calculix.sh.

    scripts/calculix-hertz.py [--mesh scenes/hertz.msh] [--workdir DIR]
                              [--repeat 3] [--threads 2] [--penalty 1e6]
                              [--ccx ccx] [--format json|csv]

Reads the checked-in Gmsh mesh (MSH 4.1 ASCII, parsed here: no gmsh package
needed) with the physical groups of scenes/hertz.toml (cylinder, block,
cylinder_surface, block_top, load_edge, symmetry, bottom) and writes a
CalculiX deck `hertz.inp` with the same problem as scenes/hertz.toml:

- CPE4 (plane strain, thickness 1), linear elasticity E = 200, nu = 0.3
  (small strain: no NLGEOM, like the peer of issue #10);
- symmetry: x fixed; bottom: x and y fixed;
- the traction (0, -0.4315) per unit length on load_edge as equivalent nodal
  forces (*CLOAD; a linear edge of length L gives t L / 2 to each end);
- penalty surface-to-surface contact, slave cylinder_surface, master
  block_top, linear pressure-overclosure of slope PENALTY (default 1e6, the
  peer's), no tension;
- one *STATIC step, initial increment 0.1 of the load (the peer's), at most
  200 increments; contact stresses (CSTR) and displacements (U) to the .frd.

Then runs `ccx -i hertz` REPEAT times with OMP_NUM_THREADS=THREADS, each
timed as a whole process (wall clock, like `time`; also its CPU time, user
plus system, of all threads), and reads the last run's results:

- pressures: CPRESS of the last increment's CONTACT block of the .frd at the
  slave nodes (cylinder_surface), at the current x = x_ref + u_x (U of the
  .frd), as gapsim::hertz::measure does with gapsim's multipliers;
- peak: the largest nodal CPRESS; p0_fit, a_fit: the least-squares fit of
  p^2 = A + B x^2 over the slave nodes with p > 0 (p0 = sqrt(A),
  a = sqrt(-A/B)), the fit of gapsim::hertz::measure; a_last: the current x
  of the outermost slave node with p > 0;
- iterations: every equilibrium iteration of the .cvg (all increments and
  attempts); increments: the converged increments of the .sta.

Prints one JSON object (or a CSV header and row) on stdout; the errors are
relative to Hertz's a = sqrt(4 P R / (pi E*)), p0 = 2 P / (pi a) with
P = 8.63 (the full cylinder's load), R = 10, E* = E / (2 (1 - nu^2)).
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

from msh41 import MeshError, ccx_version, read_msh

YOUNG, POISSON = 200.0, 0.3
TRACTION_Y = -0.4315          # force per unit length on load_edge
RADIUS, LOAD = 10.0, 8.63      # Hertz: cylinder radius, load on the full cylinder
GROUPS = ('cylinder', 'block', 'cylinder_surface', 'block_top', 'load_edge', 'symmetry', 'bottom')


def write_deck(path, nodes, groups, penalty):
    """Writes the CalculiX deck; returns (elements, slave node tags)."""
    def ccw(q):
        x = [nodes[n] for n in q]
        area = sum(x[i][0] * x[(i + 1) % 4][1] - x[(i + 1) % 4][0] * x[i][1] for i in range(4))
        return q if area > 0 else q[::-1]
    elements = {}
    for body in ('cylinder', 'block'):
        for q in groups[body]:
            elements[len(elements) + 1] = (body, ccw(q))
    face_of = {}     # CPE4 face k joins local nodes k and k+1 (S1..S4)
    for e, (_, q) in elements.items():
        for k in range(4):
            face_of.setdefault(frozenset((q[k], q[(k + 1) % 4])), []).append((e, k + 1))

    def surface(group):
        out = []
        for a, b in groups[group]:
            faces = face_of.get(frozenset((a, b)), [])
            if len(faces) != 1:
                raise MeshError(f'group {group}: edge {a}-{b} is not a boundary face of one element')
            out.append(faces[0])
        return out

    def node_set(*names):
        return sorted({n for g in names for edge in groups[g] for n in edge})

    forces = {}
    for a, b in groups['load_edge']:
        length = math.dist(nodes[a], nodes[b])
        for n in (a, b):
            forces[n] = forces.get(n, 0.0) + TRACTION_Y * length / 2
    used = sorted({n for _, q in elements.values() for n in q})
    L = ['** Hertz quarter model (scenes/hertz.toml), written by scripts/calculix-hertz.py', '*NODE']
    L += [f'{n},{nodes[n][0]:.17g},{nodes[n][1]:.17g}' for n in used]
    for body, name in (('cylinder', 'CYL'), ('block', 'BLK')):
        L += [f'*ELEMENT,TYPE=CPE4,ELSET={name}']
        L += [f'{e},{",".join(map(str, q))}' for e, (b, q) in elements.items() if b == body]
    L += ['*NSET,NSET=SYM'] + [str(n) for n in node_set('symmetry')]
    L += ['*NSET,NSET=BOT'] + [str(n) for n in node_set('bottom')]
    L += ['*SURFACE,NAME=SLAVE,TYPE=ELEMENT'] + [f'{e},S{k}' for e, k in surface('cylinder_surface')]
    L += ['*SURFACE,NAME=MASTER,TYPE=ELEMENT'] + [f'{e},S{k}' for e, k in surface('block_top')]
    L += ['*MATERIAL,NAME=MAT', '*ELASTIC', f'{YOUNG},{POISSON}']
    L += ['*SOLID SECTION,ELSET=CYL,MATERIAL=MAT', '1.', '*SOLID SECTION,ELSET=BLK,MATERIAL=MAT', '1.']
    L += ['*SURFACE INTERACTION,NAME=SI', '*SURFACE BEHAVIOR,PRESSURE-OVERCLOSURE=LINEAR', f'{penalty:g},0.,0.']
    L += ['*CONTACT PAIR,INTERACTION=SI,TYPE=SURFACE TO SURFACE', 'SLAVE,MASTER']
    L += ['*BOUNDARY', 'SYM,1,1', 'BOT,1,2']
    L += ['*STEP,INC=200', '*STATIC', '0.1,1.0', '*CLOAD']
    L += [f'{n},2,{f:.17g}' for n, f in sorted(forces.items())]
    L += ['*NODE FILE', 'U', '*CONTACT FILE', 'CSTR', '*END STEP']
    with open(path, 'w') as f:
        f.write('\n'.join(L) + '\n')
    return elements, node_set('cylinder_surface')


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


def main():
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('--mesh', default=os.path.join(root, 'scenes', 'hertz.msh'))
    ap.add_argument('--workdir', default=os.path.join(root, 'target', 'calculix-hertz'))
    ap.add_argument('--repeat', type=int, default=3)
    ap.add_argument('--threads', type=int, default=2)
    ap.add_argument('--penalty', type=float, default=1e6)
    ap.add_argument('--ccx', default='ccx')
    ap.add_argument('--format', choices=('json', 'csv'), default='json')
    args = ap.parse_args()
    if shutil.which(args.ccx) is None:
        sys.exit(f'calculix-hertz: {args.ccx} not found (apt-get install calculix-ccx)')
    if args.repeat < 1:
        sys.exit('calculix-hertz: --repeat must be at least 1')
    try:
        nodes, groups = read_msh(args.mesh, GROUPS)
        os.makedirs(args.workdir, exist_ok=True)
        elements, slaves = write_deck(os.path.join(args.workdir, 'hertz.inp'), nodes, groups, args.penalty)
    except (OSError, MeshError) as e:
        sys.exit(f'calculix-hertz: {e}')

    env = dict(os.environ, OMP_NUM_THREADS=str(args.threads))
    walls, cpus = [], []
    for i in range(args.repeat):
        for ext in ('frd', 'dat', 'sta', 'cvg'):
            try:
                os.remove(os.path.join(args.workdir, 'hertz.' + ext))
            except FileNotFoundError:
                pass
        cpu_start = os.times()
        start = time.perf_counter()
        r = subprocess.run([args.ccx, '-i', 'hertz'], cwd=args.workdir, env=env,
                           stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        walls.append(time.perf_counter() - start)
        cpu_end = os.times()
        cpus.append(cpu_end.children_user + cpu_end.children_system
                    - cpu_start.children_user - cpu_start.children_system)
        with open(os.path.join(args.workdir, 'ccx.log'), 'w') as f:
            f.write(r.stdout)
        if r.returncode != 0 or 'Job finished' not in r.stdout:
            sys.exit(f'calculix-hertz: ccx failed (exit {r.returncode}); see {args.workdir}/ccx.log')
        print(f'calculix-hertz: run {i + 1}/{args.repeat}: {walls[-1]:.2f} s (cpu {cpus[-1]:.2f} s)', file=sys.stderr)

    frd = os.path.join(args.workdir, 'hertz.frd')
    contact = read_frd_block(frd, 'CONTACT')     # COPEN CSLIP1 CSLIP2 CPRESS CSHEAR1 CSHEAR2
    disp = read_frd_block(frd, 'DISP')           # D1 D2 D3
    profile = sorted((nodes[n][0] + disp[n][0], contact.get(n, [0.0] * 4)[3]) for n in slaves)
    touching = [(x, p) for x, p in profile if p > 0.0]
    peak = max((p for _, p in touching), default=0.0)
    fit = None
    if len(touching) >= 3:
        n = len(touching)
        u = [x * x for x, _ in touching]
        v = [p * p for _, p in touching]
        sx, sy = sum(u), sum(v)
        sxx = sum(t * t for t in u)
        sxy = sum(s * t for s, t in zip(u, v))
        b = (n * sxy - sx * sy) / (n * sxx - sx * sx)
        a0 = (sy - b * sx) / n
        if a0 > 0.0 and b < 0.0:
            fit = (math.sqrt(a0), math.sqrt(-a0 / b))
    with open(os.path.join(args.workdir, 'hertz.sta')) as f:
        sta = [ln.split() for ln in f if ln.split() and ln.split()[0].isdigit()]
    with open(os.path.join(args.workdir, 'hertz.cvg')) as f:
        cvg = [ln.split() for ln in f if ln.split() and ln.split()[0].isdigit()]
    e_star = YOUNG / (2 * (1 - POISSON ** 2))
    a_hertz = math.sqrt(4 * LOAD * RADIUS / (math.pi * e_star))
    p0_hertz = 2 * LOAD / (math.pi * a_hertz)
    rel = lambda v, exact: None if v is None else v / exact - 1.0
    out = {
        'solver': f'CalculiX {ccx_version(args.ccx)}',
        'mesh': os.path.relpath(args.mesh, root),
        'nodes': len({n for _, q in elements.values() for n in q}),
        'elements': len(elements),
        'threads': args.threads,
        'penalty': args.penalty,
        'repeat': args.repeat,
        'seconds': statistics.median(walls),
        'seconds_all': walls,
        'cpu_seconds': statistics.median(cpus),
        'cpu_seconds_all': cpus,
        'peak': peak,
        'peak_error': rel(peak, p0_hertz),
        'p0_fit': fit and fit[0],
        'p0_fit_error': rel(fit and fit[0], p0_hertz),
        'a_fit': fit and fit[1],
        'a_fit_error': rel(fit and fit[1], a_hertz),
        'a_last': max((x for x, _ in touching), default=0.0),
        'in_contact': len(touching),
        'increments': len(sta),
        'iterations': len(cvg),
    }
    if args.format == 'json':
        print(json.dumps(out, indent=1))
    else:
        keys = [k for k in out if not k.endswith('_all')]
        print(','.join(keys))
        print(','.join('' if out[k] is None else str(out[k]) for k in keys))


if __name__ == '__main__':
    main()
