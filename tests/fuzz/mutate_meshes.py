#!/usr/bin/env python3
"""Mutated copies of real meshes, loaded as an application loads them.

The check issue 13's reporter ran: each OBJ given is written out as OBJ, OFF, PLY (ASCII and
binary), STL (ASCII and binary), glTF (buffer embedded as base64) and GLB, and each of those
is damaged PER times the way files arrive from the internet: numbers replaced (NaN,
infinities, overflows, negative and huge indices, empty), header counts changed, lines cut,
doubled or dropped, bytes flipped, garbage inserted, binary counts, lengths, indices and
floats overwritten. build/bin/adb-load-check loads every
file (default LoadLimits, isolated reader). Every file must load as a valid mesh or get a
MeshFileError of at most 1,000 bytes, within TIMEOUT seconds; a crash, a hang, a longer
message or anything else is a finding.

  tests/fuzz/mutate_meshes.py [--per 60] [--seed 1] [--out build/mutated] MESH.obj...
"""
import argparse, base64, json, os, random, re, struct, subprocess, sys, time

NUMBERS = ['nan', 'inf', '-inf', '1e309', '-1e309', '4294967295', '4294967296', '-2147483649',
           '99999999999999999999', '-1', '0', '', '1e-320', '0x10', '+', '-', '1.2.3',
           '18446744073709551615']
NUMBER = re.compile(rb'-?\d+(\.\d+)?([eE][-+]?\d+)?')


def read_obj(path):
    vertices, faces = [], []
    for line in open(path, errors='replace'):
        words = line.split()
        if not words:
            continue
        if words[0] == 'v':
            vertices.append(tuple(float(x) for x in words[1:4]))
        elif words[0] == 'f':
            idx = [int(w.split('/')[0]) for w in words[1:]]
            faces.append([i - 1 if i > 0 else len(vertices) + i for i in idx])
    return vertices, faces


def normal(a, b, c):
    u = [b[i] - a[i] for i in range(3)]
    w = [c[i] - a[i] for i in range(3)]
    return (u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0])


def formats(path):
    """The mesh in every format: {name: (extension, bytes)}."""
    V, F = read_obj(path)
    T = [(f[0], f[k], f[k + 1]) for f in F for k in range(1, len(f) - 1)]
    rows = lambda fmt, items: ''.join(fmt(x) for x in items)
    polygons = rows(lambda f: '%d %s\n' % (len(f), ' '.join(map(str, f))), F)
    points = rows(lambda v: '%r %r %r\n' % v, V)
    header = ('ply\nformat ascii 1.0\nelement vertex %d\nproperty float x\nproperty float y\n'
              'property float z\nelement face %d\nproperty list uchar int vertex_indices\n'
              'end_header\n' % (len(V), len(F)))
    binary = (header.replace('ascii', 'binary_little_endian').encode() +
              b''.join(struct.pack('<3f', *v) for v in V) +
              b''.join(struct.pack('<B%di' % len(f), len(f), *f) for f in F))
    stl = 'solid m\n'
    for t in T:
        corners = [V[i] for i in t]
        stl += (' facet normal %r %r %r\n  outer loop\n' % normal(*corners) +
                rows(lambda v: '   vertex %r %r %r\n' % v, corners) + '  endloop\n endfacet\n')
    stl_binary = b'\0' * 80 + struct.pack('<I', len(T)) + b''.join(
        struct.pack('<12fH', *normal(*[V[i] for i in t]), *V[t[0]], *V[t[1]], *V[t[2]], 0) for t in T)
    gltf, glb = gltf_files(V, T)
    return {'obj': ('obj', open(path, 'rb').read()),
            'off': ('off', ('OFF\n%d %d 0\n' % (len(V), len(F)) + points + polygons).encode()),
            'ply': ('ply', (header + points + polygons).encode()),
            'bply': ('ply', binary),
            'stl': ('stl', (stl + 'endsolid m\n').encode()),
            'bstl': ('stl', stl_binary),
            'gltf': ('gltf', gltf),
            'glb': ('glb', glb)}


def gltf_files(V, T):
    """The triangles as glTF 2.0: one mesh, float positions and uint32 indices in one buffer,
    embedded as base64 (.gltf) or as the BIN chunk (.glb)."""
    positions = b''.join(struct.pack('<3f', *v) for v in V)
    indices = b''.join(struct.pack('<3I', *t) for t in T)
    blob = positions + indices
    doc = {'asset': {'version': '2.0'}, 'scene': 0, 'scenes': [{'nodes': [0]}],
           'nodes': [{'mesh': 0}],
           'meshes': [{'primitives': [{'attributes': {'POSITION': 0}, 'indices': 1, 'mode': 4}]}],
           'buffers': [{'byteLength': len(blob)}],
           'bufferViews': [{'buffer': 0, 'byteOffset': 0, 'byteLength': len(positions), 'target': 34962},
                           {'buffer': 0, 'byteOffset': len(positions), 'byteLength': len(indices),
                            'target': 34963}],
           'accessors': [{'bufferView': 0, 'componentType': 5126, 'count': len(V), 'type': 'VEC3',
                          'min': [min(v[i] for v in V) for i in range(3)],
                          'max': [max(v[i] for v in V) for i in range(3)]},
                         {'bufferView': 1, 'componentType': 5125, 'count': 3 * len(T), 'type': 'SCALAR'}]}
    text = dict(doc, buffers=[{'byteLength': len(blob),
                               'uri': 'data:application/octet-stream;base64,' + base64.b64encode(blob).decode()}])
    chunk = json.dumps(doc).encode()
    chunk += b' ' * (-len(chunk) % 4)
    blob += b'\0' * (-len(blob) % 4)
    glb = (struct.pack('<4sII', b'glTF', 2, 12 + 8 + len(chunk) + 8 + len(blob)) +
           struct.pack('<I4s', len(chunk), b'JSON') + chunk + struct.pack('<I4s', len(blob), b'BIN\0') + blob)
    return json.dumps(text, indent=1).encode(), glb


def mutate_text(rng, data):
    kind = rng.choice(['number', 'number', 'number', 'header', 'cut', 'double', 'drop', 'bytes', 'garbage'])
    if kind in ('number', 'header'):
        found = list(NUMBER.finditer(data[:400] if kind == 'header' else data))
        if found:
            m = rng.choice(found)
            return kind, data[:m.start()] + rng.choice(NUMBERS).encode() + data[m.end():]
        kind = 'bytes'
    if kind == 'cut':
        return kind, data[:rng.randrange(len(data))]
    lines = data.split(b'\n')
    if kind == 'double':
        i = rng.randrange(len(lines))
        lines.insert(i, lines[i] * rng.choice([1, 2, 50]))
        return kind, b'\n'.join(lines)
    if kind == 'drop':
        del lines[rng.randrange(min(len(lines), 30)) if rng.random() < 0.5 else rng.randrange(len(lines))]
        return kind, b'\n'.join(lines)
    if kind == 'garbage':
        i = rng.randrange(len(data))
        return kind, data[:i] + bytes(rng.randrange(256) for _ in range(rng.randrange(1, 64))) + data[i:]
    flipped = bytearray(data)
    for _ in range(rng.randrange(1, 20)):
        flipped[rng.randrange(len(flipped)) if rng.random() < 0.5 else rng.randrange(min(len(flipped), 300))] = rng.randrange(256)
    return 'bytes', bytes(flipped)


def mutate_glb(rng, data):
    """Header and chunk lengths, the JSON chunk as text, the BIN chunk's indices and floats."""
    out = bytearray(data)
    json_length = struct.unpack_from('<I', data, 12)[0]
    body = 20 + json_length + 8
    kind = rng.choice(['length', 'json', 'json', 'index', 'float', 'bytes', 'cut'])
    if kind == 'cut':
        return kind, data[:rng.randrange(len(data))]
    if kind == 'json':
        return kind, data[:20] + mutate_text(rng, data[20:20 + json_length])[1] + data[20 + json_length:]
    if kind == 'length':
        struct.pack_into('<I', out, rng.choice([4, 8, 12, 20 + json_length]),
                         rng.choice([0, 1, 2**31, 2**32 - 1, len(data), len(data) + 4, rng.randrange(2**32)]))
        return kind, bytes(out)
    if kind in ('index', 'float') and body + 4 < len(out):
        i = rng.randrange(body, len(out) - 4)
        if kind == 'index':
            struct.pack_into('<I', out, i, rng.choice([2**32 - 1, 2**31, 10**6, 0]))
        else:
            struct.pack_into('<f', out, i, rng.choice([float('nan'), float('inf'), -float('inf'), 3e38]))
        return kind, bytes(out)
    for _ in range(rng.randrange(1, 20)):
        out[rng.randrange(len(out))] = rng.randrange(256)
    return 'bytes', bytes(out)


def mutate(rng, fmt, data):
    if fmt == 'glb':
        return mutate_glb(rng, data)
    if fmt in ('bply', 'bstl'):
        return mutate_binary(rng, data, fmt == 'bply')
    return mutate_text(rng, data)


def mutate_binary(rng, data, ply):
    out = bytearray(data)
    body = data.find(b'end_header\n') + 11 if ply else 84
    kind = rng.choice(['count', 'index', 'float', 'bytes', 'cut', 'header'])
    if kind == 'cut':
        return kind, data[:rng.randrange(len(data))]
    if kind == 'header' and ply:
        return kind, mutate_text(rng, data[:body])[1] + data[body:]
    if kind == 'count' and not ply:
        struct.pack_into('<I', out, 80, rng.choice([0, 1, 2**31, 2**32 - 1, len(data) // 50 + 1, rng.randrange(2**32)]))
        return kind, bytes(out)
    if kind in ('count', 'index') and ply:
        i = rng.randrange(body, len(out) - 4)
        struct.pack_into('<i', out, i, rng.choice([-1, 2**31 - 1, -2**31, 10**6, 255]))
        return 'index', bytes(out)
    if kind == 'float':
        struct.pack_into('<f', out, rng.randrange(body, len(out) - 4),
                         rng.choice([float('nan'), float('inf'), -float('inf'), 3e38, 1e-45]))
        return kind, bytes(out)
    for _ in range(rng.randrange(1, 20)):
        out[rng.randrange(len(out))] = rng.randrange(256)
    return 'bytes', bytes(out)


def main():
    root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument('meshes', nargs='+', help='OBJ files to mutate')
    ap.add_argument('--per', type=int, default=60, help='mutants per mesh and format')
    ap.add_argument('--seed', type=int, default=1)
    ap.add_argument('--out', default=os.path.join(root, 'build', 'mutated'))
    ap.add_argument('--timeout', type=float, default=60, help='seconds for a batch of 20 loads')
    ap.add_argument('--loader', default=os.path.join(root, 'build', 'bin', 'adb-load-check'))
    args = ap.parse_args()
    rng = random.Random(args.seed)
    os.makedirs(args.out, exist_ok=True)
    files = []
    for mesh in args.meshes:
        name = os.path.splitext(os.path.basename(mesh))[0]
        for fmt, (ext, data) in formats(mesh).items():
            base = os.path.join(args.out, '%s_%s_base.%s' % (name, fmt, ext))
            open(base, 'wb').write(data)
            files.append(base)
            for k in range(args.per):
                kind, bad = mutate(rng, fmt, data)
                path = os.path.join(args.out, '%s_%s_%03d_%s.%s' % (name, fmt, k, kind, ext))
                open(path, 'wb').write(bad)
                files.append(path)
    findings, rows = [], []
    for i in range(0, len(files), 20):
        batch = files[i:i + 20]
        try:
            run = subprocess.run([args.loader] + batch, capture_output=True, text=True, errors='replace',
                                 timeout=args.timeout)
        except subprocess.TimeoutExpired:
            findings.append('batch %s...: no answer within %g s' % (batch[0], args.timeout))
            continue
        done = [line.split('\t', 2) for line in run.stdout.splitlines() if line.count('\t') >= 2]
        rows += done
        if run.returncode != 0:
            findings.append('batch from %s: exit %d after %d of %d files\n%s' %
                            (batch[0], run.returncode, len(done), len(batch), run.stderr[-2000:]))
        print('\r%d of %d files' % (min(i + 20, len(files)), len(files)), end='', file=sys.stderr, flush=True)
    print(file=sys.stderr)
    bases = [r for r in rows if '_base.' in r[1]]
    loaded = sum(r[2].startswith('ok ') for r in rows)
    errors = sum(r[2].startswith('error ') for r in rows)
    slowest = max(rows, key=lambda r: float(r[0])) if rows else ['0', '-', '-']
    longest = max((len(r[2]) for r in rows), default=0)
    print('%d files: %d loaded, %d MeshFileError, %d findings' % (len(files), loaded, errors, len(findings)))
    print('slowest: %s s (%s); longest message: %d bytes' % (slowest[0], slowest[1], longest))
    for r in rows:
        if len(r[2]) > 1000:  # one clear error, not a page of the file
            findings.append('%s: a message of %d bytes' % (r[1], len(r[2])))
    for r in bases:
        if not r[2].startswith('ok '):
            findings.append('%s: the undamaged file does not load: %s' % (r[1], r[2]))
    for f in findings:
        print('FINDING: ' + f)
    return 1 if findings else 0


if __name__ == '__main__':
    sys.exit(main())
