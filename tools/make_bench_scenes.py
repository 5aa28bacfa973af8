#!/usr/bin/env python3
"""Writes bench/cornell_mesh/: the reference Cornell box (`cornell_diffuse`, whose
renderer-neutral JSON is in ../shared/refs) as a user would bring it, one OBJ with
groups and an MTL whose light comes from `Ke` (36 triangles), plus its Mitsuba
twin (one OBJ per material, since Mitsuba's `obj` shape ignores MTL files) in the
renderer-neutral JSON that ../shared/tools/mitsuba_run.py reads. The room is the
reference's exactly, so its reference image measures both renderers' error.

Usage: python3 tools/make_bench_scenes.py [REFS]   (REFS default ../shared/refs)
"""
import json, os, sys

here = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
refs = sys.argv[1] if len(sys.argv) > 1 else os.path.join(here, "..", "shared", "refs")
out = os.path.join(here, "bench", "cornell_mesh")
os.makedirs(os.path.join(out, "mitsuba"), exist_ok=True)
d = json.load(open(os.path.join(refs, "cornell_diffuse.json")))


def rect_tris(s):
    c, u, v = s["center"], s["u_half"], s["v_half"]
    p = lambda a, b: [c[i] + a * u[i] + b * v[i] for i in range(3)]
    # Counter-clockwise about u x v, the rectangle's normal.
    q = [p(-1, -1), p(1, -1), p(1, 1), p(-1, 1)]
    return q, [[0, 1, 2], [0, 2, 3]]


parts = []  # (name, material, vertices, triangles)
for s in d["shapes"]:
    if s["type"] == "rectangle":
        vs, ts = rect_tris(s)
    else:
        vs, ts = s["vertices"], s["triangles"]
    parts.append((s["name"], s["material"], vs, ts))

fmt = lambda x: f"{x:.9g}"
header = ("# Written by tools/make_bench_scenes.py from ../shared/refs/cornell_diffuse.json\n"
          "# (the Mitsuba 3 reference Cornell box); geometry and colours are the reference's.\n")

# ronray's input: one OBJ, a group and a material per part, the light from Ke.
lines, base = [header, "mtllib cornell_mesh.mtl\n"], 1
for name, mat, vs, ts in parts:
    lines += [f"g {name}\n", f"usemtl {mat}\n"]
    lines += [f"v {' '.join(fmt(x) for x in p)}\n" for p in vs]
    lines += [f"f {' '.join(str(base + i) for i in t)}\n" for t in ts]
    base += len(vs)
open(os.path.join(out, "cornell_mesh.obj"), "w").write("".join(lines))
mtl = [header]
for k, m in d["materials"].items():
    mtl.append(f"newmtl {k}\nKd {' '.join(fmt(x) for x in m['reflectance'])}\n")
    for s in d["shapes"]:
        if s["material"] == k and s.get("emitter"):
            mtl.append(f"Ke {' '.join(fmt(x) for x in s['emitter']['radiance'])}\n")
    mtl.append("\n")
open(os.path.join(out, "cornell_mesh.mtl"), "w").write("".join(mtl))

# Mitsuba's twin: one OBJ per material (the light on its own), same triangles.
shapes = []
for key in sorted({(mat, parts_name == "light") for parts_name, mat, _, _ in parts}):
    mat, is_light = key
    sel = [p for p in parts if p[1] == mat and (p[0] == "light") == is_light]
    fname = f"mitsuba/{'light' if is_light else mat}.obj"
    lines, base = [header], 1
    for name, _, vs, ts in sel:
        lines += [f"v {' '.join(fmt(x) for x in p)}\n" for p in vs]
        lines += [f"f {' '.join(str(base + i) for i in t)}\n" for t in ts]
        base += len(vs)
    open(os.path.join(out, fname), "w").write("".join(lines))
    emitter = next((s["emitter"] for s in d["shapes"] if s["name"] == "light"), None) if is_light else None
    shapes.append({"name": fname.split("/")[1][:-4], "type": "mesh", "material": mat, "file": fname,
                   "emitter": emitter})
twin = dict(d)
twin["scene"] = "cornell_mesh"
# The reference in ../shared/refs that this scene renders (tools/side_by_side.sh).
twin["reference"] = "cornell_diffuse"
twin["generator"] = "tools/make_bench_scenes.py from cornell_diffuse.json"
twin["description"] = "cornell_diffuse as triangle meshes (36 triangles), the light an emissive mesh"
twin["shapes"] = shapes
json.dump(twin, open(os.path.join(out, "cornell_mesh.json"), "w"), indent=1)
print("wrote", out)
