#!/usr/bin/env python3
"""Render a glTF 2.0 asset with Mitsuba 3, restricted to the materials ronray and Mitsuba share,
to make a reference for ronray's glTF import (`tests/reference.rs`, `docs/gltf.md`).

    python3 -m venv /tmp/mi && /tmp/mi/bin/pip install mitsuba==3.9.1 numpy pygltflib
    /tmp/mi/bin/python tools/gltf_to_mitsuba.py assets/gltf/FlightHelmet/FlightHelmet.gltf \
        --out /tmp/helmet --envmap assets/sky_sun.exr --spp 1024 --size 256 --exr ref.exr
    /tmp/mi/bin/python tools/gltf_to_mitsuba.py ASSET.gltf --out /tmp/helmet --ron   # ronray's twin

What it does:
1. Flattens the node tree of the asset's default scene (TRS or `matrix`, parents first) and writes
   each TRIANGLES primitive as a binary PLY in world space under `--out` (positions, normals by the
   inverse transpose, `TEXCOORD_0` unchanged: glTF's v runs down the image, and so does Mitsuba's
   bitmap lookup, row 0 at v = 0). Mirroring node transforms reverse the winding.
2. Maps every glTF material onto the shared model (docs/gltf.md, "Reference"):
   `twosided(normalmap(roughplastic))` in Mitsuba and
   `NormalMap(tangents: Triangle, material: RoughPlastic(...))` in ronray, with
   - the diffuse reflectance = `baseColorTexture` (sRGB, Mitsuba `raw: false`) × factor;
   - the coat's GGX alpha = the mean over texels of (G × roughnessFactor)² of
     `metallicRoughnessTexture`, rounded to 3 decimals (Mitsuba's `roughplastic` takes a
     constant alpha: its tables are per alpha), ior 1.5, `nonlinear: false`;
   - `normalTexture` (linear, `raw: true`) in the per-triangle dp/du frame both renderers can
     form (`flip_invalid_normals`, `use_shadowing_function` off); `scale` must be 1.
   Dropped on both sides: metalness, occlusion, alpha (BLEND/MASK: opaque), emission.
3. With `--exr`, renders: the asset under the equirectangular sky `--envmap` (Mitsuba `envmap`,
   unrotated, ronray's `Environment(map: ...)`), on a grey Lambert floor at y = 0, through the
   camera `--eye/--target/--fov` (vertical degrees), box filter, independent sampler, `path`
   with max_depth 8 and rr_depth 5, `scalar_rgb` (or `--variant llvm_ad_rgb`: how
   tools/side_by_side.sh times it). The JSON report gives `load_s` and `render_s` (the scene's
   load, and the render alone: what ronray's own `in X s` measures).
With `--ron`, prints the ronray `materials` block (and the `Gltf` overrides) of the same model.
"""
import argparse
import json
import os
import sys

import numpy as np
import pygltflib

COMPONENT = {5120: np.int8, 5121: np.uint8, 5122: np.int16, 5123: np.uint16, 5125: np.uint32, 5126: np.float32}
WIDTH = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4, "MAT4": 16}


def accessor(g, blob, i):
    """Accessor `i` as an (count, width) float64 array (no sparse, no normalised ints: not needed
    for the assets this is used on; it refuses rather than guesses)."""
    a = g.accessors[i]
    if a.sparse is not None or a.normalized:
        sys.exit(f"accessor {i}: sparse or normalised accessors are not handled by this script")
    v = g.bufferViews[a.bufferView]
    dt = np.dtype(COMPONENT[a.componentType])
    w = WIDTH[a.type]
    stride = v.byteStride or dt.itemsize * w
    start = (v.byteOffset or 0) + (a.byteOffset or 0)
    rows = [np.frombuffer(blob, dt, w, start + k * stride) for k in range(a.count)] if stride != dt.itemsize * w \
        else [np.frombuffer(blob, dt, w * a.count, start).reshape(a.count, w)]
    return np.vstack(rows).astype(np.float64).reshape(a.count, w)


def node_matrix(n):
    """The node's local transform, column vectors (glTF `matrix` is column-major)."""
    if n.matrix is not None:
        return np.array(n.matrix, dtype=np.float64).reshape(4, 4).T
    t = np.array(n.translation or [0, 0, 0], dtype=np.float64)
    x, y, z, w = n.rotation or [0, 0, 0, 1]
    r = np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                  [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                  [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])
    s = np.array(n.scale or [1, 1, 1], dtype=np.float64)
    m = np.eye(4)
    m[:3, :3] = r * s
    m[:3, 3] = t
    return m


def flatten(g):
    """(mesh index, world matrix) for every node with a mesh in the default scene, parents first."""
    out = []
    stack = [(n, np.eye(4)) for n in g.scenes[g.scene or 0].nodes]
    while stack:
        i, parent = stack.pop()
        m = parent @ node_matrix(g.nodes[i])
        if g.nodes[i].mesh is not None:
            out.append((g.nodes[i].mesh, m))
        stack.extend((c, m) for c in (g.nodes[i].children or []))
    return out


def write_ply(path, p, n, uv, tris):
    """Binary little-endian PLY with what Mitsuba's `ply` reads: x y z nx ny nz u v, int faces."""
    head = ("ply\nformat binary_little_endian 1.0\n"
            f"element vertex {len(p)}\n"
            "property float x\nproperty float y\nproperty float z\n"
            "property float nx\nproperty float ny\nproperty float nz\n"
            "property float u\nproperty float v\n"
            f"element face {len(tris)}\nproperty list uchar int vertex_indices\nend_header\n")
    verts = np.hstack([p, n, uv]).astype("<f4")
    faces = np.zeros(len(tris), dtype=[("k", "u1"), ("i", "<i4", 3)])
    faces["k"] = 3
    faces["i"] = tris
    with open(path, "wb") as f:
        f.write(head.encode("ascii"))
        f.write(verts.tobytes())
        f.write(faces.tobytes())


def image_path(g, here, tex_index):
    img = g.images[g.textures[tex_index].source]
    if img.uri is None or img.uri.startswith("data:"):
        sys.exit("embedded images are not handled by this script: use a .gltf with image files")
    return os.path.normpath(os.path.join(here, img.uri))


def srgb_to_linear(c):
    return np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)


def shared_material(g, here, m):
    """The shared model of glTF material `m`: a dict both writers read."""
    from PIL import Image
    pbr = m.pbrMetallicRoughness
    factor = pbr.baseColorFactor or [1, 1, 1, 1]
    if pbr.baseColorTexture is None or m.normalTexture is None:
        sys.exit(f"material {m.name}: this script expects base-colour and normal textures")
    if factor[:3] != [1, 1, 1]:
        sys.exit(f"material {m.name}: a non-white baseColorFactor is not handled by this script")
    if (m.normalTexture.scale or 1.0) != 1.0:
        sys.exit(f"material {m.name}: normalTexture.scale != 1 is not handled by this script")
    rough_f = 1.0 if pbr.roughnessFactor is None else pbr.roughnessFactor
    if pbr.metallicRoughnessTexture is not None:
        mr = np.asarray(Image.open(image_path(g, here, pbr.metallicRoughnessTexture.index)).convert("RGB"))
        alpha = float(np.mean((mr[..., 1] / 255.0 * rough_f) ** 2))
    else:
        alpha = rough_f ** 2
    return {"name": m.name, "base": image_path(g, here, pbr.baseColorTexture.index),
            "normal": image_path(g, here, m.normalTexture.index), "alpha": round(max(alpha, 1e-3), 3)}


def convert(gltf_path, out):
    """Writes the PLYs; returns [(ply path, material dict)]."""
    g = pygltflib.GLTF2().load(gltf_path)
    here = os.path.dirname(os.path.abspath(gltf_path))
    blob = open(os.path.join(here, g.buffers[0].uri), "rb").read()
    if len(g.buffers) != 1:
        sys.exit("only single-buffer assets are handled by this script")
    os.makedirs(out, exist_ok=True)
    mats = {}
    shapes = []
    for mesh_i, world in flatten(g):
        normal_m = np.linalg.inv(world[:3, :3]).T
        for k, prim in enumerate(g.meshes[mesh_i].primitives):
            if (prim.mode if prim.mode is not None else 4) != 4:
                sys.exit(f"mesh {mesh_i}: only TRIANGLES primitives are handled by this script")
            at = prim.attributes
            p = accessor(g, blob, at.POSITION)
            n = accessor(g, blob, at.NORMAL)
            uv = accessor(g, blob, at.TEXCOORD_0)
            idx = accessor(g, blob, prim.indices).astype(np.int64).reshape(-1, 3)
            p = p @ world[:3, :3].T + world[:3, 3]
            n = n @ normal_m.T
            n /= np.linalg.norm(n, axis=1, keepdims=True)
            if np.linalg.det(world[:3, :3]) < 0:
                idx = idx[:, ::-1]
            if prim.material not in mats:
                mats[prim.material] = shared_material(g, here, g.materials[prim.material])
            ply = os.path.join(out, f"mesh{mesh_i}_{k}.ply")
            write_ply(ply, p, n, uv, idx)
            shapes.append((ply, mats[prim.material]))
    return shapes


def ron_block(shapes, gltf_rel):
    """ronray's twin of the shared model: materials and the Gltf object's overrides."""
    seen = {}
    for _, m in shapes:
        seen[m["name"]] = m
    lines = ["    materials: {"]
    for name, m in seen.items():
        lines.append(f'        "{name}": NormalMap(\n'
                     f'            map: Image(file: "{m["normal_rel"]}", colorspace: Linear),\n'
                     f"            tangents: Triangle,\n"
                     f"            material: RoughPlastic(\n"
                     f'                diffuse: Image(file: "{m["base_rel"]}"),\n'
                     f'                roughness: {m["alpha"]},\n'
                     f"                roughness_unit: Alpha,\n"
                     f"                ior: 1.5,\n"
                     f"            ),\n"
                     f"        ),")
    lines.append("    },")
    overrides = ", ".join(f'"{n}": "{n}"' for n in seen)
    lines.append(f'    // Gltf(file: "{gltf_rel}", materials: {{ {overrides} }})')
    return "\n".join(lines)


def read_pfm(p):
    """A PFM as rows top first (the format stores the bottom row first)."""
    with open(p, "rb") as f:
        magic = f.readline().strip()
        w, h = map(int, f.readline().split())
        scale = float(f.readline())
        data = np.frombuffer(f.read(), dtype="<f4" if scale < 0 else ">f4")
    return data.reshape(h, w, 3 if magic == b"PF" else 1)[::-1].astype(np.float64)


def write_pfm(p, img):
    """Little-endian PFM, bottom row first, as tests/fixtures/refs/downsample_refs.py writes."""
    h, w, c = img.shape
    with open(p, "wb") as f:
        f.write(b"PF\n" if c == 3 else b"Pf\n")
        f.write(f"{w} {h}\n".encode())
        f.write(b"-1.0\n")
        f.write(np.ascontiguousarray(img[::-1]).astype("<f4").tobytes())


def mitsuba_scene(mi, shapes, a):
    T = mi.ScalarTransform4f
    d = {"type": "scene",
         "integrator": {"type": "path", "max_depth": 8, "rr_depth": 5, "hide_emitters": False},
         "sensor": {"type": "perspective", "fov": a.fov, "fov_axis": "y", "near_clip": 1e-3,
                    "far_clip": 1000.0,
                    "to_world": T().look_at(origin=a.eye, target=a.target, up=[0, 1, 0]),
                    "film": {"type": "hdrfilm", "width": a.size, "height": a.size,
                             "rfilter": {"type": "box"}, "pixel_format": "rgb",
                             "component_format": "float32", "sample_border": False},
                    "sampler": {"type": "independent", "sample_count": a.spp}},
         "sky": {"type": "envmap", "filename": a.envmap, "scale": 1.0},
         # Rect(center: 0, half_u: (h, 0, 0), half_v: (0, 0, -h)): normal +y.
         "floor": {"type": "rectangle",
                   "to_world": T().rotate([1, 0, 0], -90).scale([a.floor_half, a.floor_half, 1]),
                   "bsdf": {"type": "diffuse", "reflectance": {"type": "rgb", "value": [0.5, 0.5, 0.5]}}}}
    for i, (ply, m) in enumerate(shapes):
        bitmap = lambda f, raw: {"type": "bitmap", "filename": f, "raw": raw,
                                 "filter_type": "bilinear", "wrap_mode": "repeat"}
        d[f"part{i}"] = {"type": "ply", "filename": ply, "face_normals": False, "bsdf": {
            "type": "twosided", "bsdf": {
                "type": "normalmap", "normalmap": bitmap(m["normal"], True),
                "flip_invalid_normals": False, "use_shadowing_function": False,
                "bsdf": {"type": "roughplastic", "distribution": "ggx", "alpha": m["alpha"],
                         "int_ior": 1.5, "ext_ior": 1.0, "nonlinear": False, "sample_visible": True,
                         "diffuse_reflectance": bitmap(m["base"], False)}}}}
    return d


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("gltf")
    ap.add_argument("--out", required=True, help="folder for the PLY files")
    ap.add_argument("--ron", action="store_true", help="print ronray's materials block")
    ap.add_argument("--ron-dir", default=".", help="folder the RON scene sits in (for relative paths)")
    ap.add_argument("--exr", help="render with Mitsuba to this file")
    ap.add_argument("--envmap")
    ap.add_argument("--eye", type=float, nargs=3, default=[0.3, 0.45, 1.05])
    ap.add_argument("--target", type=float, nargs=3, default=[0.0, 0.31, 0.0])
    ap.add_argument("--fov", type=float, default=36.0)
    ap.add_argument("--floor-half", type=float, default=5.0)
    ap.add_argument("--size", type=int, default=64)
    ap.add_argument("--spp", type=int, default=64)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--variant", default="scalar_rgb", choices=["scalar_rgb", "llvm_ad_rgb"])
    ap.add_argument("--fixture", help="also write FIXTURE_64.pfm (box-downsampled to 64²) and an "
                    "all-zero FIXTURE_mask_64.pfm (the scene has no area lights)")
    ap.add_argument("--compare", help="print the RMSE of the 64² image against this 64² PFM")
    a = ap.parse_args()
    shapes = convert(a.gltf, a.out)
    for _, m in shapes:
        m["base_rel"] = os.path.relpath(m["base"], a.ron_dir)
        m["normal_rel"] = os.path.relpath(m["normal"], a.ron_dir)
    if a.ron:
        print(ron_block(shapes, os.path.relpath(os.path.abspath(a.gltf), a.ron_dir)))
    if a.exr:
        import time
        import mitsuba as mi
        import drjit as dr
        mi.set_variant(a.variant)
        dr.set_thread_count(a.threads)
        t0 = time.perf_counter()
        scene = mi.load_dict(mitsuba_scene(mi, shapes, a))
        t1 = time.perf_counter()
        # As ../shared/tools/mitsuba_run.py times it: up to the image in memory.
        img = np.array(mi.render(scene, spp=a.spp, seed=a.seed), dtype=np.float32)
        t2 = time.perf_counter()
        mi.Bitmap(np.ascontiguousarray(img), mi.Bitmap.PixelFormat.RGB).write(a.exr)
        k = a.size // 64
        if k * 64 != a.size:
            sys.exit("--size must be a multiple of 64")
        small = img.reshape(64, k, 64, k, 3).mean(axis=(1, 3))
        report = {"exr": a.exr, "spp": a.spp, "size": a.size, "seed": a.seed, "mitsuba": mi.__version__,
                  "variant": a.variant, "load_s": round(t1 - t0, 3), "render_s": round(t2 - t1, 3),
                  "mean_64": [float(x) for x in small.reshape(-1, 3).mean(axis=0)]}
        if a.fixture:
            write_pfm(a.fixture + "_64.pfm", small)
            write_pfm(a.fixture + "_mask_64.pfm", np.zeros((64, 64, 1), dtype=np.float32))
        if a.compare:
            ref = read_pfm(a.compare)
            report["rmse_64"] = float(np.sqrt(np.mean((small.astype(np.float64) - ref) ** 2)))
        print(json.dumps(report))


if __name__ == "__main__":
    main()
