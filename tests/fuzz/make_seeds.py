#!/usr/bin/env python3
"""Writes the fuzz targets' seed corpora (tests/fuzz/corpus/TARGET/): small valid files of
every format the mesh targets read, a few valid scenes, and meshes for the tree target. Run
it again after changing a seed; the files are checked in (the fuzzer starts from them, and
`make test` replays them).  tests/fuzz/make_seeds.py"""
import base64, io, json, os, struct, zipfile

HERE = os.path.dirname(os.path.abspath(__file__))
V = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)]
QUADS = [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7)]
TRIS = [t for q in QUADS for t in ((q[0], q[1], q[2]), (q[0], q[2], q[3]))]


def write(target, name, data):
    d = os.path.join(HERE, "corpus", target)
    os.makedirs(d, exist_ok=True)
    with open(os.path.join(d, name), "wb") as f:
        f.write(data if isinstance(data, bytes) else data.encode())


def obj():
    s = "# cube\n" + "".join("v %g %g %g\n" % v for v in V)
    write("mesh_obj", "cube_quads.obj", s + "".join("f %d %d %d %d\n" % tuple(i + 1 for i in q) for q in QUADS))
    write("mesh_obj", "cube_tris.obj", s + "o part\n" + "".join("f %d %d %d\n" % tuple(i + 1 for i in t) for t in TRIS))
    write("mesh_obj", "negative_indices.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\n")


def normal(t):
    a, b, c = (V[i] for i in t)
    u = [b[k] - a[k] for k in range(3)]
    w = [c[k] - a[k] for k in range(3)]
    return (u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0])


def stl():
    s = "solid cube\n"
    for t in TRIS:
        s += " facet normal %g %g %g\n  outer loop\n" % normal(t)
        s += "".join("   vertex %g %g %g\n" % V[i] for i in t)
        s += "  endloop\n endfacet\n"
    write("mesh_stl", "cube_ascii.stl", s + "endsolid cube\n")
    b = b"binary cube".ljust(80, b" ") + struct.pack("<I", len(TRIS))
    for t in TRIS:
        b += struct.pack("<3f", *normal(t)) + b"".join(struct.pack("<3f", *V[i]) for i in t) + b"\0\0"
    write("mesh_stl", "cube_binary.stl", b)


def ply():
    head = "ply\nformat %s 1.0\ncomment cube\nelement vertex 8\nproperty float x\nproperty float y\nproperty float z\nelement face 6\nproperty list uchar int vertex_indices\nend_header\n"
    s = head % "ascii" + "".join("%g %g %g\n" % v for v in V) + "".join("4 %d %d %d %d\n" % q for q in QUADS)
    write("mesh_ply", "cube_ascii.ply", s)
    b = (head % "binary_little_endian").encode() + b"".join(struct.pack("<3f", *v) for v in V)
    b += b"".join(struct.pack("<B4i", 4, *q) for q in QUADS)
    write("mesh_ply", "cube_binary_le.ply", b)
    b = (head % "binary_big_endian").encode() + b"".join(struct.pack(">3f", *v) for v in V)
    b += b"".join(struct.pack(">B4i", 4, *q) for q in QUADS)
    write("mesh_ply", "cube_binary_be.ply", b)
    # The 41-byte hang: a header cut short.
    write("mesh_ply", "regression_cut_header.ply", "ply\nformat ascii 1.0\nelement vertex 4\nprop")


def off():
    s = "OFF\n8 6 12\n" + "".join("%g %g %g\n" % v for v in V) + "".join("4 %d %d %d %d\n" % q for q in QUADS)
    write("mesh_off", "cube.off", s)
    write("mesh_off", "cube_counts_inline.off", "OFF 8 12 0\n" + "".join("%g %g %g\n" % v for v in V) + "".join("3 %d %d %d\n" % t for t in TRIS))


def gltf_parts():
    pos = b"".join(struct.pack("<3f", *v) for v in V)
    idx = b"".join(struct.pack("<H", i) for t in TRIS for i in t)
    buf = pos + idx
    doc = {"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
           "nodes": [{"mesh": 0, "translation": [0.5, 0, 0]}],
           "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
           "buffers": [{"byteLength": len(buf)}],
           "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": len(pos)},
                           {"buffer": 0, "byteOffset": len(pos), "byteLength": len(idx)}],
           "accessors": [{"bufferView": 0, "componentType": 5126, "count": 8, "type": "VEC3",
                          "min": [0, 0, 0], "max": [1, 1, 1]},
                         {"bufferView": 1, "componentType": 5123, "count": len(idx) // 2, "type": "SCALAR"}]}
    return doc, buf


def gltf():
    doc, buf = gltf_parts()
    doc["buffers"][0]["uri"] = "data:application/octet-stream;base64," + base64.b64encode(buf).decode()
    write("mesh_gltf", "cube_embedded.gltf", json.dumps(doc))
    doc, buf = gltf_parts()
    j = json.dumps(doc).encode()
    j += b" " * ((4 - len(j) % 4) % 4)
    buf += b"\0" * ((4 - len(buf) % 4) % 4)
    glb = struct.pack("<III", 0x46546C67, 2, 12 + 8 + len(j) + 8 + len(buf))
    glb += struct.pack("<II", len(j), 0x4E4F534A) + j + struct.pack("<II", len(buf), 0x004E4942) + buf
    write("mesh_gltf", "cube.glb", glb)


def threemf():
    model = ('<?xml version="1.0" encoding="UTF-8"?>\n<model unit="millimeter" xmlns="http://schemas.microsoft.com/3dmanufacturing/core/2015/02">'
             "<resources><object id=\"1\" type=\"model\"><mesh><vertices>"
             + "".join('<vertex x="%g" y="%g" z="%g"/>' % v for v in V)
             + "</vertices><triangles>"
             + "".join('<triangle v1="%d" v2="%d" v3="%d"/>' % t for t in TRIS)
             + "</triangles></mesh></object></resources><build><item objectid=\"1\"/></build></model>")
    types = ('<?xml version="1.0" encoding="UTF-8"?>\n<Types xmlns="http://schemas.openxmlformats.org/package/2006/content-types">'
             '<Default Extension="rels" ContentType="application/vnd.openxmlformats-package.relationships+xml"/>'
             '<Default Extension="model" ContentType="application/vnd.ms-package.3dmanufacturing-3dmodel+xml"/></Types>')
    rels = ('<?xml version="1.0" encoding="UTF-8"?>\n<Relationships xmlns="http://schemas.openxmlformats.org/package/2006/relationships">'
            '<Relationship Target="/3D/3dmodel.model" Id="rel0" Type="http://schemas.microsoft.com/3dmanufacturing/2013/01/3dmodel"/></Relationships>')
    out = io.BytesIO()
    with zipfile.ZipFile(out, "w", zipfile.ZIP_DEFLATED) as z:
        for name, text in (("[Content_Types].xml", types), ("_rels/.rels", rels), ("3D/3dmodel.model", model)):
            info = zipfile.ZipInfo(name, date_time=(2026, 1, 1, 0, 0, 0))  # reproducible bytes
            z.writestr(info, text, zipfile.ZIP_DEFLATED)
    write("mesh_3mf", "cube.3mf", out.getvalue())


def scenes():
    base = {"world": {"steps": 3, "budget": {"node_pairs": 500}},
            "shapes": {"floor": {"type": "box", "half_extents": [2, 0.25, 2]},
                       "ring": {"type": "generated", "model": "torus", "triangles": 200, "scale": 0.4},
                       "ball": {"type": "sphere", "radius": 0.2}},
            "bodies": [{"name": "floor", "shape": "floor", "kind": "static", "position": [0, -0.25, 0]},
                       {"name": "ring", "shape": "ring", "position": [0, 0.5, 0], "axis_angle": {"axis": [1, 0, 0], "degrees": 90}},
                       {"name": "ball", "shape": "ball", "position": [0.1, 1.5, 0], "velocity": [0, -3, 0]}],
            "effects": ["dynamics", "friction", "ccd"]}
    write("scene_file", "dynamics.json", json.dumps(base, indent=1))
    over = dict(base, effects=["overlap"], motions=[])
    over["bodies"] = [dict(b) for b in base["bodies"]]
    over["bodies"][2]["kind"] = "kinematic"
    del over["bodies"][2]["velocity"]
    over["motions"] = [{"body": "ball", "keyframes": [{"time": 0.02, "position": [0, 0.3, 0]}, {"time": 0.05, "position": [0, 2, 0]}]}]
    write("scene_file", "overlap.json", json.dumps(over, indent=1))
    cont = dict(base, effects=["contacts"])
    cont["view"] = {"eye": [3, 3, 3], "target": [0, 0, 0]}
    write("scene_file", "contacts.json", json.dumps(cont, indent=1))


def tree_inputs():
    # The tree target reads: a settings byte block, then poses, then vertices and triangles
    # (tests/fuzz/fuzz_tree_query.cpp says how); seeds are a cube against itself.
    head = struct.pack("<8B", 1, 10, 99, 0, 0, 0, 0, 0)
    pose = struct.pack("<7d", 1, 0, 0, 0, 0.5, 0.2, 0.1)
    verts = struct.pack("<I", len(V)) + b"".join(struct.pack("<3d", *v) for v in V)
    tris = struct.pack("<I", len(TRIS)) + b"".join(struct.pack("<3I", *t) for t in TRIS)
    write("tree_query", "cube_pair.bin", head + pose + verts + tris)
    write("tree_query", "cube_far.bin", head + struct.pack("<7d", 1, 0, 0, 0, 5, 0, 0) + verts + tris)


for make in (obj, stl, ply, off, gltf, threemf, scenes, tree_inputs):
    make()
print("seeds written under", os.path.join(HERE, "corpus"))
