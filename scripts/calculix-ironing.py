#!/usr/bin/env python3
"""Frictional ironing in CalculiX: the peer of scenes/ironing-friction.toml.

    scripts/calculix-ironing.py [--increments 0.025,0.005,0.0025,0.00125]
                                [--penalty 1e5] [--stick-slope PENALTY/100]
                                [--friction 0.3] [--direct] [--frd]
                                [--workdir target/calculix-ironing]
                                [--ccx ccx] [--threads 1]
                                [--csv docs/ironing/calculix-friction.csv]
                                [--gapsim BIN] [--compare DIR]
                                [--report docs/ironing/calculix-friction.md]
                                [--reuse]

Needs `apt-get install calculix-ccx` (ccx 2.20) and nothing else (no gmsh,
no numpy); never part of the tests. The checked-in
docs/ironing/calculix-friction.{csv,md} come from

    scripts/calculix-ironing.py --gapsim path/to/gapsim

(about 10 minutes on one core: four CalculiX runs, 40 s to 4.5 min, and
one gapsim run of 20 s).

The model
---------
The deck `ironing.inp` has the problem of scenes/ironing-friction.toml:

- the punch from scenes/ironing-punch.msh (MSH 4.1 ASCII, parsed here;
  groups punch, punch_surface, punch_top), node tags as in the file;
- the strip as gapsim builds a `[[body]]` block (solver/src/mesh/block.rs):
  origin (0, 0), size 10 x 1, 100 x 10 cells, node (i, j) at
  (10 i / 100, j / 10) with CalculiX tag STRIP_BASE + j (nx + 1) + i (tag
  minus STRIP_BASE is gapsim's node index in the body), each cell
  (i, j), (i+1, j), (i+1, j+1), (i, j+1), counter-clockwise;
- CPE4 (plane strain, thickness 1), *ELASTIC E = 1000, nu = 0.3 with
  NLGEOM (St Venant-Kirchhoff: gapsim's large-displacement solid);
- the strip bottom (y = 0) fixed in x and y; punch_top: u_y = -0.1 with the
  amplitude PRESS (0 -> 1 over step time 0..0.2, then held) and u_x = 5
  with SLIDE (0 until 0.2, then 0 -> 1 at 1.0), the scene's two
  [[prescribe]] items on the same nodes; step time = gapsim's load factor;
- penalty surface-to-surface contact (TYPE=SURFACE TO SURFACE), slave the
  punch arc (punch_surface), master the strip top, both as element faces;
  linear pressure-overclosure of slope PENALTY; *FRICTION mu = FRICTION
  (0.3; 0 leaves *FRICTION out) with stick slope STICK_SLOPE;
- two steps: step 1 (time 1) holds punch_top fixed and nothing moves; step
  2 is the ironing (the load factor is its step time, the .dat's total time
  minus 1). Why: in the first step of a static analysis CalculiX 2.20
  treats the penetration found at the start of *every* increment as an
  initial overlap and ramps it in over the rest of the step
  (gencontelem_f2f.f: `springarea(2,*)`, `clear - springarea(2)*(1 -
  reltime)`), so in one step the penetration accumulates increment by
  increment and the press depends on the increment size: frictionless, at
  load factor 0.2, 41.5 with increments of 0.025 and 38.3 with 0.005
  (geometric penetration 0.004 and 0.016) against 42.1 for both with the
  settling step;
- step 2: *STATIC with initial and largest increment INCREMENT, cut-backs
  allowed (down to 1e-6; --direct: fixed increments, none); per increment
  the total reaction RF of punch_top and of the bottom (*NODE PRINT,
  TOTALS=ONLY, to the .dat); with --frd also U and the contact stresses
  (CSTR) of every increment to the .frd.

The defaults and why
--------------------
- INCREMENTS 0.025, 0.005, 0.0025, 0.00125: one CalculiX run each; the
  first is gapsim's 40 steps, the others resolve the slide. CalculiX's face-to-face
  penalty contact matches slave integration points to master faces, and
  fixes the master normals, once per increment (the CalculiX manual,
  "Face-to-Face Penalty Contact": "large deformations of the structure may
  require small increments"). An increment of 0.025 slides the punch
  0.156, 1.6 master segments: frictionless the drag should vanish, and
  CalculiX gives about 11 % of the press with 0.025 and 2 % with 0.005;
  with friction its drag over press is then about 0.41 with 0.025 (and the
  press drops by a quarter half way along the slide) and 0.317 with 0.005
  (gapsim: 0.2965). The report shows how CalculiX approaches gapsim as the
  increment shrinks; the finest run is CalculiX's answer.
- PENALTY 1e5 = 10 E / h with h = 0.1 (the manual's 5 to 50 times E for
  the slope, per element length): the penetration p / PENALTY, at most
  about 8e-4 at the peak pressure (about 80), is 0.8 % of the 0.1
  indentation, and the press at load factor 0.2 is 0.7 % below gapsim's.
  1e6 converged badly with increments of 0.005 (18 cut-backs, 3840
  iterations, 413 s) and lost a quarter of the press half way along.
- STICK_SLOPE PENALTY / 100 (the CalculiX manual's advice): the elastic
  slip before sliding is mu p / STICK_SLOPE, at most about 0.024, a
  quarter of a master segment and 0.5 % of the slide; in steady sliding
  every node in contact slips, so the stick slope shows only at the start
  of the slide and at the contact's leading edge.

Output
------
Each run happens in WORKDIR/inc-INCREMENT with OMP_NUM_THREADS=THREADS
(default 1), timed as a whole `ccx -i ironing` process (wall clock; CPU:
user plus system of all threads), facts in its run.json. The CSV (default
docs/ironing/calculix-friction.csv) has one row per converged increment of
every run: increment (the run's), load_factor (step 2's time), slide (the
punch's prescribed slide, 5 (lf - 0.2) / 0.8 after 0.2), press (RF_y of
punch_top), drag (RF_x of punch_top), bottom_x, bottom_y (RF of the
bottom). RF is the force the support exerts on the body, as gapsim's
reactions (solver/src/newton/reactions.rs): press is negative (the
support pushes the punch down) and drag positive, as gapsim's `press_y`
and `slide_x` in reactions.csv.

Comparison (optional):

- --gapsim BIN runs `BIN run scenes/ironing-friction.toml --out DIR`
  (DIR: --compare, default WORKDIR/gapsim) with RAYON_NUM_THREADS=THREADS,
  timed the same way, its facts (wall, CPU, iterations, cut-backs) in
  DIR/gapsim.json;
- --compare DIR reads gapsim's DIR/reactions.csv (the scheduled steps'
  ends: the last row of each step) and DIR/gapsim.json if there is one;
- the report (printed, and written to REPORT, default
  docs/ironing/calculix-friction.md, with the plot REPORT.svg of -press and
  drag against the load factor, drawn here without a plotting package)
  gives, over steady sliding (load
  factors 0.3 to 1.0), the mean press, drag and drag / press with their
  ranges for gapsim and each CalculiX run, the relative differences of the
  means, and the largest difference at one of gapsim's step ends
  (CalculiX interpolated linearly in the load factor there); then the wall
  and CPU times, iterations, increments and cut-backs.

--reuse skips the CalculiX runs and reads WORKDIR's last ones (e.g. to redo
the comparison); the CSV is then not rewritten.
"""
import argparse
import json
import os
import re
import shutil
import statistics
import subprocess
import sys
import time

from msh41 import MeshError, ccx_version, read_msh

YOUNG, POISSON = 1000.0, 0.3
MU = 0.3
PRESS, SLIDE = -0.1, 5.0               # u_y and u_x of punch_top at amplitude 1
T_PRESS = 0.2                          # the press ramps over 0..0.2, the slide over 0.2..1
PRESS_AMP = [(0.0, 0.0), (T_PRESS, 1.0), (1.0, 1.0)]
SLIDE_AMP = [(0.0, 0.0), (T_PRESS, 0.0), (1.0, 1.0)]
STRIP_ORIGIN, STRIP_SIZE, STRIP_CELLS = (0.0, 0.0), (10.0, 1.0), (100, 10)
STRIP_BASE = 100001                    # CalculiX tag of the strip's node 0
GROUPS = ('punch', 'punch_surface', 'punch_top')
STEADY = (0.3, 1.0)                    # load factors of steady sliding
SETTLE = 1.0                           # the length of step 1 (total time = SETTLE + load factor)
SCENE = os.path.join('scenes', 'ironing-friction.toml')
CSV_KEYS = ('increment', 'load_factor', 'slide', 'press', 'drag', 'bottom_x', 'bottom_y')


def read_punch(path):
    """The punch mesh ([`msh41.read_msh`]), its node tags below the
    strip's."""
    nodes, groups = read_msh(path, GROUPS)
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


def slide_of(lf):
    return SLIDE * amplitude_at(SLIDE_AMP, lf)


def write_deck(path, nodes, groups, opts):
    """Writes the CalculiX deck (module docs) with the options opts
    (penalty, stick_slope, friction, increment, direct, frd); returns the
    model's size."""
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

    inc = opts['increment']
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
    L += ['*MATERIAL,NAME=MAT', '*ELASTIC', f'{YOUNG:g},{POISSON:g}']
    L += ['*SOLID SECTION,ELSET=PUNCH,MATERIAL=MAT', '1.', '*SOLID SECTION,ELSET=STRIP,MATERIAL=MAT', '1.']
    L += ['*SURFACE INTERACTION,NAME=SI', '*SURFACE BEHAVIOR,PRESSURE-OVERCLOSURE=LINEAR',
          f'{opts["penalty"]:g}']
    if opts['friction'] > 0.0:
        L += ['*FRICTION', f'{opts["friction"]:g},{opts["stick_slope"]:g}']
    L += ['*CONTACT PAIR,INTERACTION=SI,TYPE=SURFACE TO SURFACE', 'SLAVE,MASTER']
    for name, amp in (('PRESS', PRESS_AMP), ('SLIDE', SLIDE_AMP)):
        L += [f'*AMPLITUDE,NAME={name}', ','.join(f'{t:g},{a:g}' for t, a in amp)]
    L += ['*BOUNDARY', 'BOT,1,2']
    # step 1: nothing moves (module docs: CalculiX ramps in the penetration
    # found at each increment start of the first step)
    L += ['** step 1: settling, nothing moves', '*STEP,NLGEOM', '*STATIC',
          f'{SETTLE:g},{SETTLE:g}', '*BOUNDARY', 'TOP,1,2', '*END STEP']
    L += ['** step 2: the ironing, step time = load factor', '*STEP,NLGEOM,INC=100000']
    L += ['*STATIC,DIRECT', f'{inc:g},1.'] if opts['direct'] else ['*STATIC', f'{inc:g},1.,1e-6,{inc:g}']
    L += ['*BOUNDARY,AMPLITUDE=PRESS', f'TOP,2,2,{PRESS:g}']
    L += ['*BOUNDARY,AMPLITUDE=SLIDE', f'TOP,1,1,{SLIDE:g}']
    L += ['*NODE PRINT,NSET=TOP,TOTALS=ONLY', 'RF', '*NODE PRINT,NSET=BOT,TOTALS=ONLY', 'RF']
    if opts['frd']:
        L += ['*NODE FILE', 'U', '*CONTACT FILE', 'CSTR']
    L += ['*END STEP']
    with open(path, 'w') as f:
        f.write('\n'.join(L) + '\n')
    return {'nodes': len(allnodes), 'elements': len(elements)}


def read_totals(path):
    """{set: [(total time, [fx, fy, fz])]} of the `total force` blocks of a .dat."""
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


def run_ccx(workdir, nodes, groups, opts, args):
    """Writes the deck into workdir, runs ccx timed; returns the run's facts
    (also in workdir/run.json)."""
    os.makedirs(workdir, exist_ok=True)
    size = write_deck(os.path.join(workdir, 'ironing.inp'), nodes, groups, opts)
    for ext in ('frd', 'dat', 'sta', 'cvg'):
        try:
            os.remove(os.path.join(workdir, 'ironing.' + ext))
        except FileNotFoundError:
            pass
    env = dict(os.environ, OMP_NUM_THREADS=str(args.threads))
    load_before = os.getloadavg()[0]
    code, stdout, wall, cpu = timed([args.ccx, '-i', 'ironing'], workdir, env,
                                    os.path.join(workdir, 'ccx.log'))
    sta = read_sta(os.path.join(workdir, 'ironing.sta'))
    run = dict(opts, **size, version=ccx_version(args.ccx), threads=args.threads,
               wall=wall, cpu=cpu, loadavg=[load_before, os.getloadavg()[0]],
               increments=sum(r[4] for r in sta), iterations=sum(r[2] for r in sta),
               cutbacks=sum(not r[4] for r in sta),
               finished=code == 0 and 'Job finished' in stdout,
               end_time=max((r[3] for r in sta if r[4]), default=0.0))
    with open(os.path.join(workdir, 'run.json'), 'w') as f:
        json.dump(run, f, indent=1)
    print(f'calculix-ironing: increment {opts["increment"]:g}: ccx {wall:.2f} s (cpu {cpu:.2f} s), '
          f'{run["increments"]} increments, {run["iterations"]} iterations, {run["cutbacks"]} cut-backs, '
          f'reached {run["end_time"]:g}', file=sys.stderr)
    if not run['finished']:
        sys.exit(f'calculix-ironing: ccx failed (exit {code}); see {workdir}/ccx.log')
    return run


def read_reactions(workdir, increment):
    """The CSV rows (CSV_KEYS) of the run in workdir."""
    path = os.path.join(workdir, 'ironing.dat')
    totals = read_totals(path)
    top, bot = totals.get('TOP', []), totals.get('BOT', [])
    if not top or len(top) != len(bot):
        sys.exit(f'calculix-ironing: {path}: no or unmatched reaction totals')
    rows = []
    for (t, f), (_, b) in zip(top, bot):
        lf = round(t - SETTLE, 9)
        rows.append(dict(zip(CSV_KEYS, (increment, lf, slide_of(lf), f[1], f[0], b[0], b[1]))))
    return rows


def run_gapsim(binary, outdir, threads, root):
    """Runs gapsim on the scene into outdir, timed; writes outdir/gapsim.json."""
    env = dict(os.environ, RAYON_NUM_THREADS=str(threads))
    os.makedirs(outdir, exist_ok=True)
    log = os.path.join(outdir, 'gapsim.log')
    code, stdout, wall, cpu = timed([binary, 'run', SCENE, '--out', outdir], root, env, log)
    if code != 0:
        sys.exit(f'calculix-ironing: gapsim failed (exit {code}); see {log}')
    facts = {'wall': wall, 'cpu': cpu, 'threads': threads}
    for key, pat in (('iterations', r'^Newton\s+(\d+) iterations'), ('cutbacks', r'^cut-backs\s+(\d+)'),
                     ('method', r'^method\s+(.*)$'), ('equations', r'^equations\s+(\d+)')):
        m = re.search(pat, stdout, re.M)
        if m:
            facts[key] = m.group(1).strip()
    with open(os.path.join(outdir, 'gapsim.json'), 'w') as f:
        json.dump(facts, f, indent=1)
    print(f'calculix-ironing: gapsim {wall:.2f} s (cpu {cpu:.2f} s)', file=sys.stderr)


def read_gapsim(dirname):
    """gapsim's scheduled step ends [(lf, press, drag)] from reactions.csv
    (the last row of each step), its number of rows, and its run facts
    (gapsim.json, written by run_gapsim) if any."""
    path = os.path.join(dirname, 'reactions.csv')
    with open(path) as f:
        header = f.readline().strip().split(',')
        rows = [dict(zip(header, ln.strip().split(','))) for ln in f if ln.strip()]
    for key in ('step', 'load_factor', 'press_y', 'slide_x'):
        if key not in header:
            raise RuntimeError(f'{path}: no column {key}')
    ends = {}
    for r in rows:
        ends[int(r['step'])] = (float(r['load_factor']), float(r['press_y']), float(r['slide_x']))
    facts = {}
    try:
        with open(os.path.join(dirname, 'gapsim.json')) as f:
            facts = json.load(f)
    except FileNotFoundError:
        pass
    return [ends[k] for k in sorted(ends)], len(rows), facts


def interpolate(series, lf):
    """Linear interpolation of [(lf, value)] (sorted) at lf."""
    for (a, va), (b, vb) in zip(series, series[1:]):
        if a - 1e-9 <= lf <= b + 1e-9:
            return va if b == a else va + (vb - va) * (lf - a) / (b - a)
    raise ValueError(f'load factor {lf} outside {series[0][0]}..{series[-1][0]}')


QUANTITIES = (('press', lambda p, d: p), ('drag', lambda p, d: d), ('drag / press', lambda p, d: -d / p))


def steady(points):
    """{quantity: (mean, min, max)} over [(lf, press, drag)] in STEADY."""
    lo, hi = STEADY
    w = [(p, d) for lf, p, d in points if lo - 1e-9 <= lf <= hi + 1e-9]
    out = {}
    for label, fn in QUANTITIES:
        v = [fn(p, d) for p, d in w]
        out[label] = (statistics.fmean(v), min(v), max(v))
    return out, len(w)


def compare(runs, gap_ends, gap_rows, gap_facts, report, root):
    """The comparison (module docs) as Markdown; printed and written to report."""
    lo, hi = STEADY
    g_stats, g_n = steady(gap_ends)
    g_window = [(lf, p, d) for lf, p, d in gap_ends if lo - 1e-9 <= lf <= hi + 1e-9]
    first = runs[0][0]
    out = ['# Frictional ironing: gapsim against CalculiX', '',
           'Generated by `scripts/calculix-ironing.py` (see its header; do not edit by hand). The scene '
           f'`{SCENE}`: a half-disc punch (R = 1, `scenes/ironing-punch.msh`) pressed 0.1 into a '
           '10 x 1 strip (100 x 10 quads) over load factor 0..0.2, then slid 5 along it over 0.2..1; '
           'plane strain, E = 1000, nu = 0.3, large displacement, Coulomb friction mu = '
           f'{first["friction"]:g}, slave the punch arc, master the strip top.', '',
           f'- CalculiX {first["version"]}: CPE4, NLGEOM, penalty surface-to-surface contact '
           f'(linear pressure-overclosure, slope {first["penalty"]:g}), *FRICTION mu = '
           f'{first["friction"]:g} with stick slope {first["stick_slope"]:g}; a settling step, then '
           'the ironing step with the increments below '
           f'({"fixed (DIRECT)" if first["direct"] else "cut-backs allowed"}); '
           f'OMP_NUM_THREADS={first["threads"]}; {first["nodes"]} nodes, {first["elements"]} elements. '
           'Reactions: `*NODE PRINT, TOTALS=ONLY` of RF over punch_top at every converged increment '
           '([calculix-friction.csv](calculix-friction.csv)).']
    if gap_facts:
        out.append(f'- gapsim: `gapsim run {SCENE}` ({gap_facts.get("method", "")}, '
                   f'{gap_facts.get("equations", "?")} equations), RAYON_NUM_THREADS='
                   f'{gap_facts.get("threads")}; its reactions.csv: {gap_rows} converged (sub)steps.')
    else:
        out.append(f'- gapsim: reactions.csv of `gapsim run {SCENE} --out DIR` ({gap_rows} converged '
                   '(sub)steps; run time not recorded).')
    out.append(f'- Steady sliding: load factors {lo:g} to {hi:g} (slide {slide_of(lo):g} to '
               f'{slide_of(hi):g}): gapsim\'s {g_n} scheduled step ends, each CalculiX run\'s converged '
               'increments in that range. press: the vertical reaction of punch_top (negative: the '
               'support pushes the punch down); drag: the horizontal one (gapsim\'s `press_y` and '
               '`slide_x`). Difference: CalculiX minus gapsim, of the means relative to gapsim\'s '
               'mean (press is negative: + is a smaller press); per step: CalculiX interpolated linearly in the load factor at each of gapsim\'s '
               f'{len(g_window)} step ends in the range, the difference of largest magnitude.')
    out += ['', '| solver | increment | quantity | mean | range | mean difference | '
            'largest step difference |', '|---|---:|---|---:|---|---:|---:|']
    for label, _ in QUANTITIES:
        m, a, b = g_stats[label]
        out.append(f'| gapsim | 0.025 | {label} | {m:.4f} | {a:.4f} .. {b:.4f} | | |')
    for run, rows in runs:
        pts = [(r['load_factor'], r['press'], r['drag']) for r in rows]
        c_stats, _ = steady(pts)
        ps = [(lf, p) for lf, p, _ in pts]
        ds = [(lf, d) for lf, _, d in pts]
        for label, fn in QUANTITIES:
            m, a, b = c_stats[label]
            gm = g_stats[label][0]
            diffs = [fn(interpolate(ps, lf), interpolate(ds, lf)) - fn(p, d) for lf, p, d in g_window]
            worst = max(diffs, key=abs)
            out.append(f'| CalculiX | {run["increment"]:g} | {label} | {m:.4f} | {a:.4f} .. {b:.4f} | '
                       f'{100 * (m - gm) / abs(gm):+.2f} % | {worst:+.4f} ({100 * worst / abs(gm):+.1f} %) |')
    out += ['', '| solver | increment | wall (s) | CPU (s) | iterations | converged increments '
            '(gapsim: (sub)steps) | cut-backs |', '|---|---:|---:|---:|---:|---:|---:|']
    if gap_facts:
        out.append(f'| gapsim | 0.025 | {gap_facts["wall"]:.2f} | {gap_facts["cpu"]:.2f} | '
                   f'{gap_facts.get("iterations", "-")} | {gap_rows} | {gap_facts.get("cutbacks", "-")} |')
    for run, _ in runs:
        out.append(f'| CalculiX {run["version"]} | {run["increment"]:g} | {run["wall"]:.2f} | '
                   f'{run["cpu"]:.2f} | {run["iterations"]} | {run["increments"]} | {run["cutbacks"]} |')
    out += ['', 'Iterations: gapsim\'s Newton iterations, failed attempts included; CalculiX\'s '
            'iterations of the ironing step (its .sta), failed attempts included. Times: each a whole '
            f'process, one run each, on this machine ({os.cpu_count()} cores, shared; load average '
            + ', '.join(f'{r["loadavg"][0]:.2f}' for r, _ in runs) + ' before the CalculiX runs).']
    if report:
        svg = os.path.splitext(os.path.basename(report))[0] + '.svg'
        out += ['', f'![-press and drag against the load factor, gapsim and CalculiX]({svg})']
    text = '\n'.join(out) + '\n'
    print(text)
    if report:
        os.makedirs(os.path.dirname(os.path.abspath(report)), exist_ok=True)
        with open(report, 'w') as f:
            f.write(text)
        print(f'calculix-ironing: wrote {os.path.relpath(report, root)}', file=sys.stderr)


def plot_svg(runs, gap_ends, path):
    """An SVG (no plotting package needed) of -press and drag against the load
    factor: gapsim's step ends and every CalculiX run."""
    w, h, left, right, top, bottom = 760, 420, 60, 240, 20, 50
    ymax = 50.0
    sx = lambda lf: left + (w - left - right) * lf
    sy = lambda f: top + (h - top - bottom) * (1 - f / ymax)
    colours = ['#e6a23c', '#67c23a', '#409eff', '#d03050', '#8e44ad']
    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" '
           'font-family="sans-serif" font-size="12">',
           f'<rect width="{w}" height="{h}" fill="white"/>']
    for k in range(6):
        f = 10 * k
        out.append(f'<line x1="{left}" y1="{sy(f):.1f}" x2="{w - right}" y2="{sy(f):.1f}" stroke="#ddd"/>')
        out.append(f'<text x="{left - 6}" y="{sy(f) + 4:.1f}" text-anchor="end">{f}</text>')
    for k in range(6):
        lf = k / 5
        out.append(f'<line x1="{sx(lf):.1f}" y1="{top}" x2="{sx(lf):.1f}" y2="{h - bottom}" stroke="#ddd"/>')
        out.append(f'<text x="{sx(lf):.1f}" y="{h - bottom + 16}" text-anchor="middle">{lf:g}</text>')
    out.append(f'<text x="{sx(0.5):.1f}" y="{h - 12}" text-anchor="middle">load factor '
               '(press 0..0.2, slide 0..5 over 0.2..1)</text>')
    out.append(f'<text x="16" y="{sy(25):.1f}" transform="rotate(-90 16 {sy(25):.1f})" '
               'text-anchor="middle">reaction of punch_top</text>')

    def line(points, colour, dash, width):
        d = ' '.join(f'{sx(lf):.1f},{sy(v):.1f}' for lf, v in points)
        extra = f' stroke-dasharray="{dash}"' if dash else ''
        out.append(f'<polyline points="{d}" fill="none" stroke="{colour}" stroke-width="{width}"{extra}/>')

    legend = []
    for i, (run, rows) in enumerate(runs):
        c = colours[i % len(colours)]
        line([(r['load_factor'], -r['press']) for r in rows], c, None, 1.2)
        line([(r['load_factor'], r['drag']) for r in rows], c, '5,3', 1.2)
        legend.append((c, f'CalculiX, increment {run["increment"]:g}'))
    line([(lf, -p) for lf, p, _ in gap_ends], 'black', None, 2)
    line([(lf, d) for lf, _, d in gap_ends], 'black', '5,3', 2)
    for lf, p, d in gap_ends:
        out.append(f'<circle cx="{sx(lf):.1f}" cy="{sy(-p):.1f}" r="2.5" fill="black"/>')
        out.append(f'<circle cx="{sx(lf):.1f}" cy="{sy(d):.1f}" r="2.5" fill="black"/>')
    legend.insert(0, ('black', 'gapsim, 40 steps'))
    y = top + 10
    for c, text in legend:
        out.append(f'<line x1="{w - right + 10}" y1="{y}" x2="{w - right + 35}" y2="{y}" stroke="{c}" '
                   'stroke-width="2"/>')
        out.append(f'<text x="{w - right + 40}" y="{y + 4}">{text}</text>')
        y += 18
    out.append(f'<text x="{w - right + 10}" y="{y + 10}">solid: -press</text>')
    out.append(f'<text x="{w - right + 10}" y="{y + 28}">dashed: drag</text>')
    out.append('</svg>')
    with open(path, 'w') as f:
        f.write('\n'.join(out) + '\n')


def main():
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('--mesh', default=os.path.join(root, 'scenes', 'ironing-punch.msh'))
    ap.add_argument('--workdir', default=os.path.join(root, 'target', 'calculix-ironing'))
    ap.add_argument('--increments', default='0.025,0.005,0.0025,0.00125',
                    help='comma-separated increments of the ironing step, one run each')
    ap.add_argument('--penalty', type=float, default=1e5)
    ap.add_argument('--stick-slope', type=float, default=None, help='default: penalty / 100')
    ap.add_argument('--friction', type=float, default=MU, help='mu (0: frictionless, no *FRICTION)')
    ap.add_argument('--direct', action='store_true', help='fixed increments, no cut-backs')
    ap.add_argument('--frd', action='store_true', help='U and CSTR of every increment to the .frd')
    ap.add_argument('--threads', type=int, default=1)
    ap.add_argument('--ccx', default='ccx')
    ap.add_argument('--csv', default=os.path.join(root, 'docs', 'ironing', 'calculix-friction.csv'))
    ap.add_argument('--gapsim', metavar='BIN', help='run this gapsim binary on the scene, timed')
    ap.add_argument('--compare', metavar='DIR', help="gapsim's --out directory (reactions.csv)")
    ap.add_argument('--report', default=os.path.join(root, 'docs', 'ironing', 'calculix-friction.md'))
    ap.add_argument('--reuse', action='store_true', help="read WORKDIR's last CalculiX runs")
    args = ap.parse_args()
    try:
        increments = [float(v) for v in args.increments.split(',')]
    except ValueError:
        sys.exit(f'calculix-ironing: --increments {args.increments}: not numbers')
    if not all(0.0 < v <= 1.0 for v in increments):
        sys.exit('calculix-ironing: increments must be in (0, 1]')
    opts = {'penalty': args.penalty, 'friction': args.friction, 'direct': args.direct, 'frd': args.frd,
            'stick_slope': args.stick_slope if args.stick_slope is not None else args.penalty / 100}

    runs = []
    if args.reuse:
        for inc in increments:
            workdir = os.path.join(args.workdir, f'inc-{inc:g}')
            with open(os.path.join(workdir, 'run.json')) as f:
                runs.append((json.load(f), read_reactions(workdir, inc)))
    else:
        if shutil.which(args.ccx) is None:
            sys.exit(f'calculix-ironing: {args.ccx} not found (apt-get install calculix-ccx)')
        try:
            nodes, groups = read_punch(args.mesh)
        except (OSError, MeshError) as e:
            sys.exit(f'calculix-ironing: {e}')
        for inc in increments:
            workdir = os.path.join(args.workdir, f'inc-{inc:g}')
            run = run_ccx(workdir, nodes, groups, dict(opts, increment=inc), args)
            runs.append((run, read_reactions(workdir, inc)))
        os.makedirs(os.path.dirname(os.path.abspath(args.csv)), exist_ok=True)
        with open(args.csv, 'w') as f:
            f.write(','.join(CSV_KEYS) + '\n')
            for _, rows in runs:
                for r in rows:
                    f.write(','.join(repr(r[k]) for k in CSV_KEYS) + '\n')
        print(f'calculix-ironing: wrote {os.path.relpath(args.csv, root)} '
              f'({sum(len(r) for _, r in runs)} increments)', file=sys.stderr)

    gapdir = args.compare or (os.path.join(args.workdir, 'gapsim') if args.gapsim else None)
    if args.gapsim:
        run_gapsim(args.gapsim, gapdir, args.threads, root)
    if gapdir:
        ends, nrows, gfacts = read_gapsim(gapdir)
        compare(runs, ends, nrows, gfacts, args.report, root)
        if args.report:
            svg = os.path.splitext(args.report)[0] + '.svg'
            plot_svg(runs, ends, svg)
            print(f'calculix-ironing: wrote {os.path.relpath(svg, root)}', file=sys.stderr)


if __name__ == '__main__':
    main()
