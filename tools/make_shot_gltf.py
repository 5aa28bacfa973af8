#!/usr/bin/env python3
"""Writes assets/gltf/shot/shot.gltf, the asset of scenes/gltf_shot.ron: a
floor, a thin glass pane (KHR_materials_transmission without a volume), a
red block seen through it, a sign glowing through an emission map read with
clamped edges, and the camera `Shot` the scene looks through. Everything is
in the one file (data-URI buffer and image), written by this script: project
data, no outside source. Usage: python3 tools/make_shot_gltf.py"""
import base64, json, math, os, struct, zlib

def png(w, h, rgb):
    raw = b"".join(b"\0" + bytes(c for x in range(w) for c in rgb(x, y)) for y in range(h))
    chunk = lambda t, d: struct.pack(">I", len(d)) + t + d + struct.pack(">I", zlib.crc32(t + d) & 0xFFFFFFFF)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0))
            + chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b""))

bin_ = bytearray()
views, accessors = [], []
def add(data, fmt, count, ty, comp, minmax=None):
    while len(bin_) % 4:
        bin_.append(0)
    off = len(bin_)
    bin_.extend(struct.pack("<" + fmt * (len(data)), *data))
    views.append({"buffer": 0, "byteOffset": off, "byteLength": len(bin_) - off})
    a = {"bufferView": len(views) - 1, "componentType": comp, "count": count, "type": ty}
    if minmax:
        a["min"], a["max"] = minmax
    accessors.append(a)
    return len(accessors) - 1

def quad(corners, normal, uvs=((0, 1), (1, 1), (1, 0), (0, 0))):
    pos = [c for p in corners for c in p]
    mn = [min(p[k] for p in corners) for k in range(3)]
    mx = [max(p[k] for p in corners) for k in range(3)]
    a = {"POSITION": add(pos, "f", 4, "VEC3", 5126, (mn, mx)),
         "NORMAL": add(list(normal) * 4, "f", 4, "VEC3", 5126),
         "TEXCOORD_0": add([c for uv in uvs for c in uv], "f", 4, "VEC2", 5126)}
    return a, add([0, 1, 2, 0, 2, 3], "H", 6, "SCALAR", 5123)

def box(lo, hi):
    (x0, y0, z0), (x1, y1, z1) = lo, hi
    faces = [
        ([(x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)], (0, 0, 1)),
        ([(x1, y0, z0), (x0, y0, z0), (x0, y1, z0), (x1, y1, z0)], (0, 0, -1)),
        ([(x1, y0, z1), (x1, y0, z0), (x1, y1, z0), (x1, y1, z1)], (1, 0, 0)),
        ([(x0, y0, z0), (x0, y0, z1), (x0, y1, z1), (x0, y1, z0)], (-1, 0, 0)),
        ([(x0, y1, z1), (x1, y1, z1), (x1, y1, z0), (x0, y1, z0)], (0, 1, 0)),
    ]
    return [quad(c, n) for c, n in faces]

materials = [
    {"name": "Floor", "doubleSided": True, "pbrMetallicRoughness": {"baseColorFactor": [0.55, 0.55, 0.5, 1], "metallicFactor": 0, "roughnessFactor": 0.9}},
    {"name": "Pane", "doubleSided": True, "pbrMetallicRoughness": {"baseColorFactor": [0.85, 0.95, 0.9, 1], "metallicFactor": 0, "roughnessFactor": 0},
     "extensions": {"KHR_materials_transmission": {"transmissionFactor": 1.0}, "KHR_materials_ior": {"ior": 1.5}}},
    {"name": "Block", "doubleSided": True, "pbrMetallicRoughness": {"baseColorFactor": [0.7, 0.12, 0.08, 1], "metallicFactor": 0, "roughnessFactor": 0.5}},
    {"name": "Sign", "doubleSided": True, "pbrMetallicRoughness": {"baseColorFactor": [0, 0, 0, 1], "metallicFactor": 0, "roughnessFactor": 1},
     "emissiveFactor": [1, 1, 1], "emissiveTexture": {"index": 0},
     "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 6}}},
]
prims = [
    (quad([(-3, 0, 3), (3, 0, 3), (3, 0, -3), (-3, 0, -3)], (0, 1, 0)), 0),
    (quad([(-0.8, 0.05, 0.2), (0.8, 0.05, 0.2), (0.8, 1.25, 0.2), (-0.8, 1.25, 0.2)], (0, 0, 1)), 1),
] + [(p, 2) for p in box((-0.35, 0, -0.7), (0.25, 0.6, -0.2))] + [
    # The sign: UVs past [0, 1] along u, so the clamped map's edge columns stretch.
    (quad([(-1.4, 0.4, -1.6), (1.4, 0.4, -1.6), (1.4, 1.3, -1.6), (-1.4, 1.3, -1.6)], (0, 0, 1),
          ((-0.3, 1), (1.3, 1), (1.3, 0), (-0.3, 0))), 3),
]
meshes = [{"name": "Set", "primitives": [{"attributes": a, "indices": i, "material": m} for (a, i), m in prims]}]

# The camera at `eye` looking at `at`: its node's −z along the view, +y up.
eye, at = (1.3, 1.25, 3.4), (0.0, 0.5, -0.6)
f = [a - e for a, e in zip(at, eye)]; n = math.sqrt(sum(c * c for c in f)); f = [c / n for c in f]
r = [f[1] * 0 - f[2] * 1, f[2] * 0 - f[0] * 0, f[0] * 1 - f[1] * 0]; n = math.sqrt(sum(c * c for c in r)); r = [c / n for c in r]
u = [r[1] * f[2] - r[2] * f[1], r[2] * f[0] - r[0] * f[2], r[0] * f[1] - r[1] * f[0]]
b = [-c for c in f]  # columns: x = right, y = up, z = back
m = [[r[0], u[0], b[0]], [r[1], u[1], b[1]], [r[2], u[2], b[2]]]
t = m[0][0] + m[1][1] + m[2][2]
s = math.sqrt(t + 1.0) * 2  # the trace is positive for this view
q = [(m[2][1] - m[1][2]) / s, (m[0][2] - m[2][0]) / s, (m[1][0] - m[0][1]) / s, 0.25 * s]

sign = png(8, 4, lambda x, y: (255, 150, 40) if (x + y) % 2 == 0 and 0 < x < 7 else (40, 10, 0))
doc = {
    "asset": {"version": "2.0", "generator": "ronray tools/make_shot_gltf.py"},
    "extensionsUsed": ["KHR_materials_transmission", "KHR_materials_ior", "KHR_materials_emissive_strength"],
    "scene": 0,
    "scenes": [{"nodes": [0, 1]}],
    "nodes": [{"name": "Set", "mesh": 0}, {"name": "Shot", "camera": 0, "translation": list(eye), "rotation": q}],
    "cameras": [{"name": "Shot", "type": "perspective", "perspective": {"yfov": math.radians(38), "aspectRatio": 4 / 3, "znear": 0.05}}],
    "meshes": meshes,
    "materials": materials,
    "samplers": [{"wrapS": 33071, "wrapT": 33071, "magFilter": 9729}],
    "images": [{"uri": "data:image/png;base64," + base64.b64encode(sign).decode()}],
    "textures": [{"source": 0, "sampler": 0}],
    "buffers": [{"byteLength": len(bin_), "uri": "data:application/octet-stream;base64," + base64.b64encode(bytes(bin_)).decode()}],
    "bufferViews": views,
    "accessors": accessors,
}
out = os.path.join(os.path.dirname(__file__), "..", "assets", "gltf", "shot", "shot.gltf")
with open(out, "w") as fh:
    json.dump(doc, fh, separators=(",", ":"))
print("wrote", os.path.normpath(out))
