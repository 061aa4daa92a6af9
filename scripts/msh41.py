"""MSH 4.1 ASCII (2D) and CalculiX helpers shared by the CalculiX peer
scripts (scripts/calculix-hertz.py, scripts/calculix-ironing.py): the
mesh reader and `ccx`'s version. Standard library only."""

import subprocess


class MeshError(Exception):
    """A mesh file this script cannot use."""


def read_msh(path, needed):
    """Nodes {tag: (x, y)} and {physical name: [element node lists]} of an
    MSH 4.1 ASCII file (lines: 2-node edges; surfaces: 4-node quads);
    MeshError when a group of `needed` is missing."""
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
    # entities: (dim, tag) -> physical tags
    ent = sections['Entities']
    counts = list(map(int, ent[0].split()))
    physical = {}
    row = 1
    for dim in range(4):
        for _ in range(counts[dim]):
            v = ent[row].split()
            row += 1
            tag = int(v[0])
            k = 4 if dim == 0 else 7          # points: tag x y z; others: tag + bounding box
            physical[(dim, tag)] = [int(t) for t in v[k + 1:k + 1 + int(v[k])]]
    nodes = {}
    nod = sections['Nodes']
    blocks = int(nod[0].split()[0])
    row = 1
    for _ in range(blocks):
        _, _, _, n = map(int, nod[row].split())
        tags = [int(t) for t in nod[row + 1:row + 1 + n]]
        for t, xyz in zip(tags, nod[row + 1 + n:row + 1 + 2 * n]):
            x, y, _ = map(float, xyz.split())
            nodes[t] = (x, y)
        row += 1 + 2 * n
    groups = {}
    els = sections['Elements']
    blocks = int(els[0].split()[0])
    row = 1
    for _ in range(blocks):
        dim, tag, etype, n = map(int, els[row].split())
        want = {1: 2, 3: 4}.get(etype)
        for ln in els[row + 1:row + 1 + n]:
            conn = [int(t) for t in ln.split()[1:]]
            for p in physical.get((dim, tag), []):
                name = names.get((dim, p))
                if name is None:
                    continue
                if want is None:
                    raise MeshError(f'{path}: group {name}: element type {etype} (need 2-node lines, 4-node quads)')
                groups.setdefault(name, []).append(conn[:want])
        row += 1 + n
    missing = [g for g in needed if g not in groups]
    if missing:
        raise MeshError(f'{path}: no physical group(s) {", ".join(missing)}')
    return nodes, groups


def ccx_version(ccx):
    r = subprocess.run([ccx, '-v'], capture_output=True, text=True)
    out = (r.stdout + r.stderr).strip().splitlines()
    return out[-1].replace('This is Version', '').strip() if out else 'unknown'
