#!/usr/bin/env python3
"""Frictional ironing in CalculiX: the peer of scenes/ironing-friction.toml.

    scripts/calculix-ironing.py [--penalty 1e6] [--stick-slope K/100]
                                [--increment 0.025] [--direct]
                                [--workdir target/calculix-ironing]
                                [--ccx ccx] [--threads 1]
                                [--csv docs/ironing/calculix-friction.csv]
                                [--gapsim BIN] [--compare DIR]
                                [--report docs/ironing/calculix-friction.md]
                                [--reuse]

Builds the mesh of scenes/ironing-friction.toml node for node and writes a
CalculiX 2.20 deck `ironing.inp` with the same problem:

- the punch from scenes/ironing-punch.msh (MSH 4.1 ASCII, parsed here: no
  gmsh package needed; groups punch, punch_surface, punch_top), node tags
  as in the file;
- the strip as gapsim builds a `[[body]]` block (solver/src/mesh/block.rs):
  origin (0, 0), size 10 x 1, 100 x 10 cells, node (i, j) at
  (10 i / 100, 1 j / 10), CalculiX tag STRIP_BASE + j (nx + 1) + i (so tag
  - STRIP_BASE is gapsim's node index in the body), cells counter-clockwise
  (i, j), (i+1, j), (i+1, j+1), (i, j+1);
- CPE4 (plane strain, thickness 1), *ELASTIC E = 1000, nu = 0.3 with
  *STEP, NLGEOM (St Venant-Kirchhoff, as gapsim's large-displacement
  solids);
- strip bottom (y = 0): x and y fixed; punch_top: u_y = -0.1 with the
  amplitude PRESS (0 -> 1 over step time 0..0.2, then held) and u_x = 5
  with SLIDE (0 until 0.2, then 0 -> 1 at 1.0): the scene's two
  [[prescribe]] items on the same nodes, step time = gapsim's load factor;
- surface-to-surface penalty contact, slave the punch arc
  (punch_surface), master the strip top, both as element faces; linear
  pressure-overclosure of slope PENALTY (default 1e6: the penetration,
  about p / PENALTY = 6e-5 at the peak pressure, is 6e-4 of the 0.1
  indentation); *FRICTION mu = 0.3 with the stick slope STICK_SLOPE
  (default PENALTY / 100, the CalculiX manual's advice: the elastic slip
  before sliding is mu p / STICK_SLOPE, about 2e-3 of the 5 slide);
- one *STATIC step, increment INCREMENT (default 0.025: gapsim's 40
  steps), at most INCREMENT per increment, cut-backs allowed (down to
  1e-6); with --direct, fixed increments (no cut-back);
- per increment: the total reaction (RF) of punch_top and of the bottom
  (*NODE PRINT, TOTALS=ONLY, to the .dat); at the end U and contact
  stresses (CSTR) to the .frd.

Runs `ccx -i ironing` once with OMP_NUM_THREADS=THREADS (default 1), timed
as a whole process (wall clock; CPU: user plus system of all threads), and
writes CSV (default docs/ironing/calculix-friction.csv) with one row per
converged increment: load_factor (CalculiX's step time), slide (the
punch's prescribed slide, 5 (lf - 0.2) / 0.8 after 0.2), press (RF_y of
punch_top) and drag (RF_x of punch_top), bottom_x, bottom_y. RF is the
force the support exerts on the body, as gapsim's reactions
(solver/src/newton/reactions.rs): press is negative (the support pushes
the punch down), drag positive, as gapsim's `press_y` and `slide_x` in
reactions.csv. Also writes WORKDIR/run.json (times, increments,
iterations, cut-backs).

Comparison (optional):

- --gapsim BIN runs `BIN run scenes/ironing-friction.toml --out DIR`
  (DIR: --compare, default WORKDIR/gapsim), timed (wall, CPU), with
  RAYON_NUM_THREADS=THREADS, and keeps its summary in DIR/gapsim.txt;
- --compare DIR reads gapsim's DIR/reactions.csv (the scheduled steps'
  ends: the last row of each step) and, when present, DIR/gapsim.txt
  (written by --gapsim: wall time, iterations);
- then prints, and writes to REPORT (default
  docs/ironing/calculix-friction.md), a table over steady sliding (load
  factors 0.3 to 1.0): mean press, mean drag, mean drag/press with their
  ranges, for both solvers, and their relative differences; CalculiX
  interpolated (linearly in the load factor) at gapsim's step ends, the
  largest difference per step; the wall times.

--reuse skips the CalculiX run and reads WORKDIR's last results
(WORKDIR/ironing.dat, WORKDIR/run.json), e.g. to redo the comparison.

Needs `apt-get install calculix-ccx` (ccx 2.20); never part of the tests.
Example (the checked-in docs/ironing/calculix-friction.*):

    scripts/calculix-ironing.py --gapsim path/to/gapsim
"""
import argparse
import json
import math
import os
import re
import shutil
import statistics
import subprocess
import sys
import time

YOUNG, POISSON = 1000.0, 0.3
MU = 0.3
PRESS, SLIDE = -0.1, 5.0               # u_y and u_x of punch_top at amplitude 1
T_PRESS = 0.2                          # the press ramps over 0..0.2, the slide over 0.2..1
STRIP_ORIGIN, STRIP_SIZE, STRIP_CELLS = (0.0, 0.0), (10.0, 1.0), (100, 10)
STRIP_BASE = 100001                    # CalculiX tag of the strip's node 0
GROUPS = ('punch', 'punch_surface', 'punch_top')
STEADY = (0.3, 1.0)                    # load factors of steady sliding
SCENE = os.path.join('scenes', 'ironing-friction.toml')
SETTLE = 1.0                           # the length of step 1 (total time = SETTLE + load factor)


class MeshError(Exception):
    """A mesh file this script cannot use."""


def read_msh(path):
    """Nodes {tag: (x, y)} and {physical name: [element node lists]} of an
    MSH 4.1 ASCII file (lines: 2-node edges; surfaces: 4-node quads)."""
    with open(path) as f:
        lines = [ln.strip() for ln in f]
    sections = {}
    i = 0
    while i < len(lines):
        if lines[i].startswith('$') and not lines[i].startswith('$End'):
            name = lines[i][1:]
            end = lines.index('$End' + name, i)
            sections[name] = lines[i + 1:end]
            i = end
        i += 1
    for required in ('MeshFormat', 'PhysicalNames', 'Entities', 'Nodes', 'Elements'):
        if required not in sections:
            raise MeshError(f'{path}: no ${required} section')
    version, binary = sections['MeshFormat'][0].split()[:2]
    if not version.startswith('4.') or binary != '0':
        raise MeshError(f'{path}: MSH format {version} (binary {binary}); need 4.1 ASCII')
    names = {}
    for ln in sections['PhysicalNames'][1:]:
        dim, tag, name = ln.split(maxsplit=2)
        names[(int(dim), int(tag))] = name.strip('"')
    ent = sections['Entities']
    counts = list(map(int, ent[0].split()))
    physical = {}
    row = 1
    for dim in range(4):
        for _ in range(counts[dim]):
            v = ent[row].split()
            row += 1
            k = 4 if dim == 0 else 7          # points: tag x y z; others: tag + bounding box
            physical[(dim, int(v[0]))] = [int(t) for t in v[k + 1:k + 1 + int(v[k])]]
    nodes = {}
    nod = sections['Nodes']
    row = 1
    for _ in range(int(nod[0].split()[0])):
        n = int(nod[row].split()[3])
        tags = [int(t) for t in nod[row + 1:row + 1 + n]]
        for t, xyz in zip(tags, nod[row + 1 + n:row + 1 + 2 * n]):
            x, y, _ = map(float, xyz.split())
            nodes[t] = (x, y)
        row += 1 + 2 * n
    groups = {}
    els = sections['Elements']
    row = 1
    for _ in range(int(els[0].split()[0])):
        dim, tag, etype, n = map(int, els[row].split())
        want = {1: 2, 3: 4}.get(etype)
        for ln in els[row + 1:row + 1 + n]:
            conn = [int(t) for t in ln.split()[1:]]
            for p in physical.get((dim, tag), []):
                name = names.get((dim, p))
                if name is None:
                    continue
                if want is None:
                    raise MeshError(f'{path}: group {name}: element type {etype} '
                                    '(need 2-node lines, 4-node quads)')
                groups.setdefault(name, []).append(conn[:want])
        row += 1 + n
    missing = [g for g in GROUPS if g not in groups]
    if missing:
        raise MeshError(f'{path}: no physical group(s) {", ".join(missing)}')
    if max(nodes) >= STRIP_BASE:
        raise MeshError(f'{path}: node tags reach {max(nodes)}, the strip starts at {STRIP_BASE}')
    return nodes, groups


def strip_mesh():
    """The strip as gapsim's block body: nodes {tag: (x, y)}, quads, bottom
    node tags, top edges (right to left, as gapsim's `top` side)."""
    (x0, y0), (sx, sy), (nx, ny) = STRIP_ORIGIN, STRIP_SIZE, STRIP_CELLS
    tag = lambda i, j: STRIP_BASE + j * (nx + 1) + i
    nodes = {tag(i, j): (x0 + sx * i / nx, y0 + sy * j / ny)
             for j in range(ny + 1) for i in range(nx + 1)}
    quads = [[tag(i, j), tag(i + 1, j), tag(i + 1, j + 1), tag(i, j + 1)]
             for j in range(ny) for i in range(nx)]
    bottom = [tag(i, 0) for i in range(nx + 1)]
    top = [(tag(i + 1, ny), tag(i, ny)) for i in range(nx - 1, -1, -1)]
    return nodes, quads, bottom, top


def amplitude_at(points, t):
    """Piecewise linear amplitude [(t, a), ...] at t (held beyond the ends)."""
    if t <= points[0][0]:
        return points[0][1]
    for (t0, a0), (t1, a1) in zip(points, points[1:]):
        if t <= t1:
            return a0 + (a1 - a0) * (t - t0) / (t1 - t0)
    return points[-1][1]


PRESS_AMP = [(0.0, 0.0), (T_PRESS, 1.0), (1.0, 1.0)]
SLIDE_AMP = [(0.0, 0.0), (T_PRESS, 0.0), (1.0, 1.0)]


def write_deck(path, nodes, groups, penalty, stick, increment, direct, mu, contact_type):
    """Writes the CalculiX deck (module docs); returns a summary dict."""
    s_nodes, s_quads, bottom, top = strip_mesh()
    allnodes = dict(nodes)
    allnodes.update(s_nodes)

    def area(q):
        x = [allnodes[n] for n in q]
        return sum(x[i][0] * x[(i + 1) % 4][1] - x[(i + 1) % 4][0] * x[i][1] for i in range(4)) / 2

    elements = {}
    for body, quads in (('punch', groups['punch']), ('strip', s_quads)):
        for q in quads:
            if area(q) <= 0.0:
                raise MeshError(f'{body}: element {q} is not counter-clockwise')
            elements[len(elements) + 1] = (body, q)
    face_of = {}     # CPE4 face k joins local nodes k and k+1 (S1..S4)
    for e, (_, q) in elements.items():
        for k in range(4):
            face_of.setdefault(frozenset((q[k], q[(k + 1) % 4])), []).append((e, k + 1))

    def surface(name, edges):
        out = []
        for a, b in edges:
            faces = face_of.get(frozenset((a, b)), [])
            if len(faces) != 1:
                raise MeshError(f'{name}: edge {a}-{b} is not a boundary face of one element')
            out.append(faces[0])
        return out

    top_nodes = sorted({n for edge in groups['punch_top'] for n in edge})
    L = ['** Frictional ironing (scenes/ironing-friction.toml), written by scripts/calculix-ironing.py',
         '*NODE']
    L += [f'{n},{x:.17g},{y:.17g}' for n, (x, y) in sorted(allnodes.items())]
    for body, name in (('punch', 'PUNCH'), ('strip', 'STRIP')):
        L += [f'*ELEMENT,TYPE=CPE4,ELSET={name}']
        L += [f'{e},{",".join(map(str, q))}' for e, (b, q) in elements.items() if b == body]
    L += ['*NSET,NSET=TOP'] + [str(n) for n in top_nodes]
    L += ['*NSET,NSET=BOT'] + [str(n) for n in bottom]
    L += ['*SURFACE,NAME=SLAVE,TYPE=ELEMENT']
    L += [f'{e},S{k}' for e, k in surface('punch_surface', groups['punch_surface'])]
    L += ['*SURFACE,NAME=MASTER,TYPE=ELEMENT'] + [f'{e},S{k}' for e, k in surface('strip top', top)]
    L += ['*MATERIAL,NAME=MAT', '*ELASTIC', f'{YOUNG},{POISSON}']
    L += ['*SOLID SECTION,ELSET=PUNCH,MATERIAL=MAT', '1.', '*SOLID SECTION,ELSET=STRIP,MATERIAL=MAT', '1.']
    L += ['*SURFACE INTERACTION,NAME=SI', '*SURFACE BEHAVIOR,PRESSURE-OVERCLOSURE=LINEAR',
          f'{penalty:g},0.,0.']
    if mu > 0.0:
        L += ['*FRICTION', f'{mu:g},{stick:g}']
    L += [f'*CONTACT PAIR,INTERACTION=SI,TYPE={contact_type}', 'SLAVE,MASTER']
    for name, amp in (('PRESS', PRESS_AMP), ('SLIDE', SLIDE_AMP)):
        L += [f'*AMPLITUDE,NAME={name}', ','.join(f'{t:g},{a:g}' for t, a in amp)]
    L += ['*BOUNDARY', 'BOT,1,2']
    # step 1: nothing moves (module docs: CalculiX forgives penetration at
    # each increment start of step 1)
    L += ['*STEP,NLGEOM', '*STATIC', f'{SETTLE:g},{SETTLE:g}', '*BOUNDARY', 'TOP,1,2', '*END STEP']
    L += ['*STEP,NLGEOM,INC=10000', '*STATIC,DIRECT' if direct else '*STATIC',
          f'{increment:g},1.' if direct else f'{increment:g},1.,1e-6,{increment:g}']
    L += ['*BOUNDARY,AMPLITUDE=PRESS', f'TOP,2,2,{PRESS:g}']
    L += ['*BOUNDARY,AMPLITUDE=SLIDE', f'TOP,1,1,{SLIDE:g}']
    L += ['*NODE PRINT,NSET=TOP,TOTALS=ONLY', 'RF', '*NODE PRINT,NSET=BOT,TOTALS=ONLY', 'RF']
    L += ['*NODE FILE', 'U', '*CONTACT FILE', 'CSTR', '*END STEP']
    with open(path, 'w') as f:
        f.write('\n'.join(L) + '\n')
    return {'nodes': len(allnodes), 'elements': len(elements),
            'punch_nodes': len(nodes), 'strip_nodes': len(s_nodes)}


def read_totals(path):
    """{set: [(time, [fx, fy, fz])]} of the `total force` blocks of a .dat."""
    out = {}
    pat = re.compile(r'total force \(fx,fy,fz\) for set (\S+) and time\s+(\S+)')
    with open(path) as f:
        lines = f.readlines()
    for i, ln in enumerate(lines):
        m = pat.search(ln)
        if not m:
            continue
        for nxt in lines[i + 1:]:
            if nxt.strip():
                out.setdefault(m.group(1).upper(), []).append(
                    (float(m.group(2)), [float(v) for v in nxt.split()]))
                break
    return out


def read_sta(path, step=2):
    """The attempts of step STEP in a .sta: [(inc, attempt, iterations,
    step time, converged)] (an attempt marked U did not converge)."""
    rows = []
    with open(path) as f:
        for ln in f:
            v = ln.split()
            if len(v) >= 7 and v[0].isdigit() and int(v[0]) == step:
                rows.append((int(v[1]), int(v[2].rstrip('U')), int(v[3]), float(v[5]),
                             not v[2].endswith('U')))
    return rows


def ccx_version(ccx):
    r = subprocess.run([ccx, '-v'], capture_output=True, text=True)
    out = (r.stdout + r.stderr).strip().splitlines()
    return out[-1].replace('This is Version', '').strip() if out else 'unknown'


def timed(cmd, cwd, env, log):
    """Runs cmd; returns (returncode, stdout, wall s, cpu s)."""
    cpu0 = os.times()
    t0 = time.perf_counter()
    r = subprocess.run(cmd, cwd=cwd, env=env, stdout=subprocess.PIPE,
                       stderr=subprocess.STDOUT, text=True)
    wall = time.perf_counter() - t0
    cpu1 = os.times()
    cpu = (cpu1.children_user + cpu1.children_system
           - cpu0.children_user - cpu0.children_system)
    with open(log, 'w') as f:
        f.write(r.stdout)
    return r.returncode, r.stdout, wall, cpu


def slide_of(lf):
    return SLIDE * amplitude_at(SLIDE_AMP, lf)


def read_gapsim(dirname):
    """gapsim's scheduled step ends [(lf, press, drag)] from reactions.csv
    (the last row of each step) and its run facts (gapsim.txt) if any."""
    path = os.path.join(dirname, 'reactions.csv')
    with open(path) as f:
        header = f.readline().strip().split(',')
        rows = [dict(zip(header, ln.strip().split(','))) for ln in f if ln.strip()]
    for key in ('press_y', 'slide_x'):
        if key not in header:
            raise RuntimeError(f'{path}: no column {key}')
    ends = {}
    for r in rows:
        ends[int(r['step'])] = (float(r['load_factor']), float(r['press_y']), float(r['slide_x']))
    facts = {}
    try:
        with open(os.path.join(dirname, 'gapsim.txt')) as f:
            facts = json.load(f)
    except FileNotFoundError:
        pass
    return [ends[k] for k in sorted(ends)], len(rows), facts


def interpolate(series, lf):
    """Linear interpolation of [(lf, value)] (sorted) at lf."""
    for (a, va), (b, vb) in zip(series, series[1:]):
        if a - 1e-12 <= lf <= b + 1e-12:
            return va if b == a else va + (vb - va) * (lf - a) / (b - a)
    raise ValueError(f'load factor {lf} outside {series[0][0]}..{series[-1][0]}')


def stats(values):
    return statistics.fmean(values), min(values), max(values)


def compare(ccx_rows, run, gap_ends, gap_rows, gap_facts, report, root):
    """The comparison table (module docs) as Markdown; also printed."""
    lo, hi = STEADY
    in_window = lambda lf: lo - 1e-9 <= lf <= hi + 1e-9
    g = [(lf, p, d) for lf, p, d in gap_ends if in_window(lf)]
    c = [(r['load_factor'], r['press'], r['drag']) for r in ccx_rows if in_window(r['load_factor'])]
    # CalculiX at gapsim's step ends (exact where the increments coincide)
    press_s = [(r['load_factor'], r['press']) for r in ccx_rows]
    drag_s = [(r['load_factor'], r['drag']) for r in ccx_rows]
    ci = [(lf, interpolate(press_s, lf), interpolate(drag_s, lf)) for lf, _, _ in g]
    rows = []
    for label, fn in (('press', lambda p, d: p), ('drag', lambda p, d: d),
                      ('drag / press', lambda p, d: -d / p)):
        gs = stats([fn(p, d) for _, p, d in g])
        cs = stats([fn(p, d) for _, p, d in c])
        diffs = [fn(pc, dc) - fn(pg, dg) for (_, pc, dc), (_, pg, dg) in zip(ci, g)]
        worst = max(diffs, key=abs)
        rows.append((label, gs, cs, (cs[0] - gs[0]) / abs(gs[0]), worst, worst / abs(gs[0])))
    out = []
    out.append('# Frictional ironing: gapsim against CalculiX')
    out.append('')
    out.append('Generated by `scripts/calculix-ironing.py` (do not edit by hand). The scene '
               '`scenes/ironing-friction.toml`: a half-disc punch (R = 1, `scenes/ironing-punch.msh`) '
               'pressed 0.1 into a 10 x 1 strip (100 x 10 quads) over load factor 0..0.2, then slid '
               '5 along it over 0.2..1; plane strain, E = 1000, nu = 0.3, large displacement, '
               f'Coulomb friction mu = {MU:g}, slave the punch arc, master the strip top.')
    out.append('')
    out.append(f'- CalculiX {run["version"]}: CPE4, *STEP NLGEOM, penalty surface-to-surface contact '
               f'(linear pressure-overclosure, slope {run["penalty"]:g}), *FRICTION mu = {MU:g}, '
               f'stick slope {run["stick_slope"]:g}; increments of {run["increment"]:g}'
               f'{" (DIRECT)" if run["direct"] else " (cut-backs allowed)"}: '
               f'{run["increments"]} converged increments, {run["iterations"]} iterations, '
               f'{run["cutbacks"]} cut-backs; OMP_NUM_THREADS={run["threads"]}; '
               f'{run["nodes"]} nodes, {run["elements"]} elements. '
               'Reactions: `*NODE PRINT, TOTALS=ONLY` of RF over punch_top per increment '
               '([calculix-friction.csv](calculix-friction.csv)).')
    if gap_facts:
        out.append(f'- gapsim: `gapsim run {SCENE}` ({gap_facts.get("summary", "")}); '
                   f'RAYON_NUM_THREADS={gap_facts.get("threads")}; '
                   f'reactions.csv: {gap_rows} converged (sub)steps.')
    else:
        out.append(f'- gapsim: `reactions.csv` of a `gapsim run {SCENE} --out DIR` '
                   f'({gap_rows} converged (sub)steps; its run time not recorded).')
    out.append(f'- Steady sliding: load factors {lo:g} to {hi:g} (slide {slide_of(lo):g} to '
               f'{slide_of(hi):g}): gapsim\'s {len(g)} scheduled step ends, CalculiX\'s {len(c)} '
               'converged increments. press: the vertical reaction of punch_top (negative: the '
               'support pushes the punch down), drag: the horizontal one (gapsim\'s `press_y` and '
               '`slide_x`). Per step: CalculiX interpolated linearly in the load factor at '
               'gapsim\'s step ends (the same load factors when no increment was cut back), the '
               'difference of largest magnitude, CalculiX minus gapsim.')
    out.append('')
    out.append('| quantity | gapsim mean | gapsim range | CalculiX mean | CalculiX range | '
               'mean difference | largest step difference | (of gapsim\'s mean) |')
    out.append('|---|---:|---|---:|---|---:|---:|---:|')
    for label, gs, cs, rel, worst, wrel in rows:
        out.append(f'| {label} | {gs[0]:.4f} | {gs[1]:.4f} .. {gs[2]:.4f} | {cs[0]:.4f} | '
                   f'{cs[1]:.4f} .. {cs[2]:.4f} | {100 * rel:+.2f} % | {worst:+.4f} | {100 * wrel:+.2f} % |')
    out.append('')
    out.append('| solver | wall (s) | CPU (s) | iterations | increments / steps | cut-backs |')
    out.append('|---|---:|---:|---:|---:|---:|')
    out.append(f'| CalculiX {run["version"]} | {run["wall"]:.2f} | {run["cpu"]:.2f} | '
               f'{run["iterations"]} | {run["increments"]} | {run["cutbacks"]} |')
    if gap_facts:
        out.append(f'| gapsim | {gap_facts["wall"]:.2f} | {gap_facts["cpu"]:.2f} | '
                   f'{gap_facts.get("iterations", "-")} | {len(gap_ends)} | '
                   f'{gap_facts.get("cutbacks", "-")} |')
    else:
        out.append(f'| gapsim | - | - | - | {len(gap_ends)} | - |')
    out.append('')
    load = run.get('loadavg')
    if load:
        out.append(f'Machine: {os.cpu_count()} cores, load average {load[0]:.2f} before the CalculiX '
                   f'run and {load[1]:.2f} after; one run each.')
    text = '\n'.join(out) + '\n'
    print(text)
    if report:
        os.makedirs(os.path.dirname(os.path.abspath(report)), exist_ok=True)
        with open(report, 'w') as f:
            f.write(text)
        print(f'calculix-ironing: wrote {os.path.relpath(report, root)}', file=sys.stderr)


def run_gapsim(binary, outdir, threads, root):
    """Runs gapsim on the scene into outdir, timed; writes outdir/gapsim.txt."""
    env = dict(os.environ, RAYON_NUM_THREADS=str(threads))
    os.makedirs(outdir, exist_ok=True)
    log = os.path.join(outdir, 'gapsim.log')
    code, stdout, wall, cpu = timed([binary, 'run', SCENE, '--out', outdir], root, env, log)
    if code != 0:
        sys.exit(f'calculix-ironing: gapsim failed (exit {code}); see {log}')
    facts = {'wall': wall, 'cpu': cpu, 'threads': threads}
    m = re.search(r'^Newton\s+(\d+) iterations', stdout, re.M)
    if m:
        facts['iterations'] = int(m.group(1))
    m = re.search(r'^cut-backs\s+(\d+)', stdout, re.M)
    if m:
        facts['cutbacks'] = int(m.group(1))
    m = re.search(r'^method\s+(.*)$', stdout, re.M)
    if m:
        facts['summary'] = m.group(1).strip()
    with open(os.path.join(outdir, 'gapsim.txt'), 'w') as f:
        json.dump(facts, f, indent=1)
    print(f'calculix-ironing: gapsim {wall:.2f} s (cpu {cpu:.2f} s)', file=sys.stderr)


def main():
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('--mesh', default=os.path.join(root, 'scenes', 'ironing-punch.msh'))
    ap.add_argument('--workdir', default=os.path.join(root, 'target', 'calculix-ironing'))
    ap.add_argument('--penalty', type=float, default=1e6)
    ap.add_argument('--stick-slope', type=float, default=None,
                    help='*FRICTION stick slope (default: penalty / 100)')
    ap.add_argument('--increment', type=float, default=0.025)
    ap.add_argument('--friction', type=float, default=MU, help='mu (0: frictionless, no *FRICTION)')
    ap.add_argument('--node-to-surface', action='store_true',
                    help='node-to-surface contact instead of surface-to-surface')
    ap.add_argument('--direct', action='store_true', help='fixed increments, no cut-backs')
    ap.add_argument('--threads', type=int, default=1)
    ap.add_argument('--ccx', default='ccx')
    ap.add_argument('--csv', default=os.path.join(root, 'docs', 'ironing', 'calculix-friction.csv'))
    ap.add_argument('--gapsim', metavar='BIN', help='run this gapsim binary on the scene, timed')
    ap.add_argument('--compare', metavar='DIR', help="gapsim's --out directory (reactions.csv)")
    ap.add_argument('--report', default=os.path.join(root, 'docs', 'ironing', 'calculix-friction.md'))
    ap.add_argument('--reuse', action='store_true', help="read WORKDIR's last CalculiX run")
    args = ap.parse_args()
    stick = args.stick_slope if args.stick_slope is not None else args.penalty / 100
    if not 0.0 < args.increment <= 1.0:
        sys.exit('calculix-ironing: --increment must be in (0, 1]')
    os.makedirs(args.workdir, exist_ok=True)
    runfile = os.path.join(args.workdir, 'run.json')

    if args.reuse:
        with open(runfile) as f:
            run = json.load(f)
    else:
        if shutil.which(args.ccx) is None:
            sys.exit(f'calculix-ironing: {args.ccx} not found (apt-get install calculix-ccx)')
        try:
            nodes, groups = read_msh(args.mesh)
            facts = write_deck(os.path.join(args.workdir, 'ironing.inp'), nodes, groups,
                               args.penalty, stick, args.increment, args.direct, args.friction,
                               'NODE TO SURFACE' if args.node_to_surface else 'SURFACE TO SURFACE')
        except (OSError, MeshError) as e:
            sys.exit(f'calculix-ironing: {e}')
        for ext in ('frd', 'dat', 'sta', 'cvg'):
            try:
                os.remove(os.path.join(args.workdir, 'ironing.' + ext))
            except FileNotFoundError:
                pass
        env = dict(os.environ, OMP_NUM_THREADS=str(args.threads))
        load_before = os.getloadavg()[0]
        code, stdout, wall, cpu = timed([args.ccx, '-i', 'ironing'], args.workdir, env,
                                        os.path.join(args.workdir, 'ccx.log'))
        ok = code == 0 and 'Job finished' in stdout
        sta = read_sta(os.path.join(args.workdir, 'ironing.sta'))
        run = dict(facts, version=ccx_version(args.ccx), penalty=args.penalty, stick_slope=stick,
                   increment=args.increment, direct=args.direct, threads=args.threads,
                   friction=args.friction, node_to_surface=args.node_to_surface,
                   wall=wall, cpu=cpu, loadavg=[load_before, os.getloadavg()[0]],
                   increments=sum(r[4] for r in sta), iterations=sum(r[2] for r in sta),
                   cutbacks=sum(not r[4] for r in sta), finished=ok,
                   end_time=max((r[3] for r in sta if r[4]), default=0.0))
        with open(runfile, 'w') as f:
            json.dump(run, f, indent=1)
        print(f'calculix-ironing: ccx {wall:.2f} s (cpu {cpu:.2f} s), {run["increments"]} increments, '
              f'{run["iterations"]} iterations, {run["cutbacks"]} cut-backs, reached {run["end_time"]:g}',
              file=sys.stderr)
        if not ok:
            sys.exit(f'calculix-ironing: ccx failed (exit {code}); see {args.workdir}/ccx.log')

    totals = read_totals(os.path.join(args.workdir, 'ironing.dat'))
    top, bot = totals.get('TOP', []), totals.get('BOT', [])
    if not top or len(top) != len(bot):
        sys.exit(f'calculix-ironing: {args.workdir}/ironing.dat: no or unmatched reaction totals')
    rows = [{'load_factor': round(t - SETTLE, 12), 'slide': slide_of(t - SETTLE), 'press': f[1], 'drag': f[0],
             'bottom_x': b[0], 'bottom_y': b[1]} for (t, f), (_, b) in zip(top, bot)]
    if not args.reuse:
        os.makedirs(os.path.dirname(os.path.abspath(args.csv)), exist_ok=True)
        with open(args.csv, 'w') as f:
            keys = list(rows[0])
            f.write(','.join(keys) + '\n')
            for r in rows:
                f.write(','.join(repr(r[k]) for k in keys) + '\n')
        print(f'calculix-ironing: wrote {os.path.relpath(args.csv, root)} ({len(rows)} increments)',
              file=sys.stderr)

    gapdir = args.compare or (os.path.join(args.workdir, 'gapsim') if args.gapsim else None)
    if args.gapsim:
        run_gapsim(args.gapsim, gapdir, args.threads, root)
    if gapdir:
        ends, nrows, gfacts = read_gapsim(gapdir)
        compare(rows, run, ends, nrows, gfacts, args.report, root)


if __name__ == '__main__':
    main()
