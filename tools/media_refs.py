#!/usr/bin/env python3
"""Mitsuba 3 references for ronray's participating media (issue 42): a
heterogeneous density grid (`media_blob`) and a subsurface sphere
(`subsurface_sphere`), made the way the shared references were
(shared/refs/README.md): 256x256, box pixel filter, `independent` sampler,
Mitsuba's `volpath`, box-downsampled 4x to the 64x64 PFM fixtures of
tests/fixtures/refs/, with emitter masks.

    python3 -m venv /tmp/mi && /tmp/mi/bin/pip install mitsuba==3.9.1 numpy
    /tmp/mi/bin/python tools/media_refs.py vol                 # writes the .vol (what the test checks)
    /tmp/mi/bin/python tools/media_refs.py probe               # asserts Mitsuba's gridvolume conventions
    /tmp/mi/bin/python tools/media_refs.py ref NAME --spp 256 --out /tmp/refs   # 256x256 -> 64x64 fixture
    /tmp/mi/bin/python tools/media_refs.py noise NAME --out /tmp/refs   # Mitsuba's RMSE at 64/256 spp, 64x64

Run from the repository root. Variant `scalar_rgb` (Mitsuba's plain C++
path; `llvm_ad_rgb` computes the same estimator but needs libLLVM, which
the machine that made the fixtures did not have).

The scenes are the twins of tests/fixtures/media/media_blob.ron and
subsurface_sphere.ron: every number below is copied from them.

The blob grid is generated here and by `tests/media_refs.rs` with the same
arithmetic (f64 sums and products of exact inputs, rounded once to f32), and
the test asserts its bytes equal the committed `blob.vol`, so both
renderers read the same file.
"""
import argparse
import json
import os
import struct
import sys

FIX = "tests/fixtures/media"
REFS = "tests/fixtures/refs"
RES = 32
# (centre x, y, z, radius, weight) in the unit cube of the grid; each bump
# is w (1 - d^2/r^2)^2 inside radius r, 0 outside, so the density is C1
# and falls to 0 well inside the box. Three unequal bumps make it
# asymmetric along every axis (a transposed read changes the image).
BUMPS = [(0.5, 0.45, 0.5, 0.42, 1.0), (0.7, 0.68, 0.42, 0.2, 0.9), (0.3, 0.6, 0.72, 0.17, 0.7)]
BLOB_MIN = (-1.0, 0.0625, -1.0)
BLOB_MAX = (1.0, 2.0625, 1.0)


def blob_values():
    """RES^3 densities, x fastest; the arithmetic of tests/media_refs.rs."""
    out = []
    for k in range(RES):
        for j in range(RES):
            for i in range(RES):
                p = ((i + 0.5) / RES, (j + 0.5) / RES, (k + 0.5) / RES)
                v = 0.0
                for cx, cy, cz, r, w in BUMPS:
                    dx, dy, dz = p[0] - cx, p[1] - cy, p[2] - cz
                    d2 = (dx * dx + dy * dy + dz * dz) / (r * r)
                    if d2 < 1.0:
                        s = 1.0 - d2
                        v += w * (s * s)
                out.append(v)
    return out


def vol_bytes():
    """Mitsuba's .vol v3: 'VOL' 3, float32, sizes, 1 channel, bbox, values."""
    head = b"VOL\x03" + struct.pack("<5i", 1, RES, RES, RES, 1)
    head += struct.pack("<6f", *BLOB_MIN, *BLOB_MAX)
    return head + struct.pack(f"<{RES ** 3}f", *blob_values())


def rgb(c):
    return {"type": "rgb", "value": [float(x) for x in c]}


def lambert(c):
    return {"type": "twosided", "bsdf": {"type": "diffuse", "reflectance": rgb(c)}}


def rect(mi, center, hu, hv):
    """ronray's Rect(center, half_u, half_v): normal = normalize(u x v)."""
    import numpy as np
    u, v = np.array(hu, float), np.array(hv, float)
    n = np.cross(u, v)
    n /= np.linalg.norm(n)
    m = np.eye(4)
    m[:3, 0], m[:3, 1], m[:3, 2], m[:3, 3] = u, v, n, center
    return {"type": "rectangle", "to_world": mi.ScalarTransform4f(m.tolist())}


def base(mi, eye, target, fov, spp, max_depth, size):
    T = mi.ScalarTransform4f
    d = {
        "type": "scene",
        "integrator": {"type": "volpath", "max_depth": max_depth, "rr_depth": 5, "hide_emitters": False},
        "sensor": {
            "type": "perspective", "fov": fov, "fov_axis": "y", "near_clip": 1e-3, "far_clip": 1000.0,
            "to_world": T().look_at(origin=eye, target=target, up=[0, 1, 0]),
            "film": {"type": "hdrfilm", "width": size, "height": size, "rfilter": {"type": "box"},
                     "pixel_format": "rgb", "component_format": "float32", "sample_border": False},
            "sampler": {"type": "independent", "sample_count": spp},
        },
    }
    return d


def media_blob(mi, spp, size, max_depth=64, with_env=True):
    """tests/fixtures/media/media_blob.ron."""
    T = mi.ScalarTransform4f
    d = base(mi, [0, 1.2, 5.0], [0, 0.9, 0], 35.0, spp, max_depth, size)
    lo, hi = BLOB_MIN, BLOB_MAX
    d["ground"] = dict(rect(mi, [0, 0, 0], [4, 0, 0], [0, 0, -4]), bsdf=lambert([0.5, 0.5, 0.5]))
    d["light"] = dict(rect(mi, [-1.5, 4, 1.5], [0.75, 0, 0], [0, 0, 0.75]),
                      bsdf=lambert([0, 0, 0]), emitter={"type": "area", "radiance": rgb([15, 15, 15])})
    d["blob"] = {
        "type": "obj", "filename": os.path.join(FIX, "blob_box.obj"), "face_normals": True,
        "bsdf": {"type": "null"},
        "interior": {
            "type": "heterogeneous", "scale": 4.0, "albedo": rgb([0.9, 0.75, 0.55]),
            "phase": {"type": "isotropic"},
            "sigma_t": {"type": "gridvolume", "filename": os.path.join(FIX, "blob.vol"),
                        "filter_type": "trilinear", "use_grid_bbox": False,
                        "to_world": T().translate(list(lo)).scale([hi[i] - lo[i] for i in range(3)])},
        },
    }
    if with_env:
        d["sky"] = {"type": "constant", "radiance": rgb([0.2, 0.2, 0.2])}
    return d


def subsurface_sphere(mi, spp, size, max_depth=256, with_env=True):
    """tests/fixtures/media/subsurface_sphere.ron."""
    d = base(mi, [0, 1.2, 3.5], [0, 0.45, 0], 30.0, spp, max_depth, size)
    d["ground"] = dict(rect(mi, [0, 0, 0], [4, 0, 0], [0, 0, -4]), bsdf=lambert([0.6, 0.6, 0.6]))
    d["light"] = dict(rect(mi, [-1, 3, 1.5], [0.8, 0, 0], [0, 0, 0.8]),
                      bsdf=lambert([0, 0, 0]), emitter={"type": "area", "radiance": rgb([4, 4, 4])})
    d["sphere"] = {
        "type": "sphere", "center": [0, 0.5, 0], "radius": 0.5,
        "bsdf": {"type": "dielectric", "int_ior": 1.5, "ext_ior": 1.0},
        "interior": {"type": "homogeneous", "sigma_t": 20.0, "albedo": rgb([0.99, 0.97, 0.95]),
                     "scale": 1.0, "phase": {"type": "isotropic"}},
    }
    if with_env:
        d["sky"] = {"type": "constant", "radiance": rgb([0.5, 0.5, 0.5])}
    return d


SCENES = {"media_blob": media_blob, "subsurface_sphere": subsurface_sphere}


def render(mi, name, spp, seed, size=256, **kw):
    import numpy as np
    scene = mi.load_dict(SCENES[name](mi, spp, size, **kw))
    return np.array(mi.render(scene, spp=spp, seed=seed), dtype=np.float32)


def write_pfm(path, img):
    import numpy as np
    h, w, c = img.shape
    with open(path, "wb") as f:
        f.write(f"{'PF' if c == 3 else 'Pf'}\n{w} {h}\n-1.0\n".encode())
        f.write(np.ascontiguousarray(img[::-1], dtype="<f4").tobytes())  # bottom row first


def read_pfm(path):
    import numpy as np
    with open(path, "rb") as f:
        magic = f.readline().strip()
        w, h = map(int, f.readline().split())
        scale = float(f.readline())
        data = np.frombuffer(f.read(), dtype="<f4" if scale < 0 else ">f4")
    return data.reshape(h, w, 3 if magic == b"PF" else 1)[::-1]


def probe(mi, out):
    """Mitsuba's gridvolume conventions, asserted: a 4x3x2 grid of value
    x + 10y + 100z (x fastest) whose header box is deliberately wrong, placed
    by to_world in [1,5]x[2,5]x[3,5]: texel centres hold the values,
    trilinear between them, clamped at the faces, header box ignored."""
    nx, ny, nz = 4, 3, 2
    vals = [x + 10 * y + 100 * z for z in range(nz) for y in range(ny) for x in range(nx)]
    path = os.path.join(out, "probe.vol")
    with open(path, "wb") as f:
        f.write(b"VOL\x03" + struct.pack("<5i", 1, nx, ny, nz, 1) + struct.pack("<6f", 9, 9, 9, 10, 10, 10)
                + struct.pack(f"<{len(vals)}f", *vals))
    T = mi.ScalarTransform4f
    vol = mi.load_dict({"type": "gridvolume", "filename": path, "to_world": T().translate([1, 2, 3]).scale([4, 3, 2])})

    def at(p):
        it = mi.Interaction3f()
        it.p = mi.Point3f(p)
        return vol.eval(it)[0]
    cases = [([1.5, 2.5, 3.5], 0), ([2.5, 2.5, 3.5], 1), ([1.5, 3.5, 3.5], 10), ([1.5, 2.5, 4.5], 100),
             ([2.0, 2.5, 3.5], 0.5), ([1.5, 2.5, 4.0], 50), ([1.01, 2.01, 3.01], 0), ([4.99, 4.99, 4.99], 123)]
    for p, want in cases:
        got = at(p)
        assert abs(got - want) < 1e-4, (p, got, want)
    bb = vol.bbox()
    assert list(bb.min) == [1, 2, 3] and list(bb.max) == [5, 5, 5], bb
    print("gridvolume conventions: texel centres, x fastest, trilinear, clamped, header box ignored: ok")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("what", choices=["vol", "probe", "ref", "noise"])
    ap.add_argument("name", nargs="?", choices=sorted(SCENES))
    ap.add_argument("--spp", type=int, default=256)
    ap.add_argument("--out", default="/tmp/media_refs")
    ap.add_argument("--threads", type=int, default=2)
    a = ap.parse_args()
    if a.what == "vol":
        with open(os.path.join(FIX, "blob.vol"), "wb") as f:
            f.write(vol_bytes())
        return
    import numpy as np
    import mitsuba as mi
    import drjit as dr
    mi.set_variant("scalar_rgb")
    dr.set_thread_count(a.threads)
    os.makedirs(a.out, exist_ok=True)
    if a.what == "probe":
        probe(mi, a.out)
    elif a.what == "ref":
        img = render(mi, a.name, a.spp, 0)
        write_pfm(os.path.join(a.out, f"{a.name}_ref.pfm"), img)
        # Emitter mask: area lights seen directly (through the media), sky left out.
        emit = render(mi, a.name, 64, 0, max_depth=1, with_env=False)
        mask = (emit.max(axis=2) > 0).astype(np.float32)
        write_pfm(os.path.join(a.out, f"{a.name}_mask.pfm"), mask[..., None].repeat(3, axis=2))
        small = img.reshape(64, 4, 64, 4, 3).mean(axis=(1, 3))
        m64 = (mask.reshape(64, 4, 64, 4).max(axis=(1, 3)) > 0).astype(np.float32)[..., None]
        write_pfm(os.path.join(REFS, f"{a.name}_64.pfm"), small)
        write_pfm(os.path.join(REFS, f"{a.name}_mask_64.pfm"), m64)
        print(json.dumps({"scene": a.name, "spp": a.spp, "mean": small.reshape(-1, 3).mean(0).tolist(),
                          "mask_pixels_64": int(m64.sum())}))
    else:
        # At 64x64, the size the tests render at, against the fixture: the
        # same figures as tests/reference.rs computes for ronray.
        ref = read_pfm(os.path.join(REFS, f"{a.name}_64.pfm"))
        keep = read_pfm(os.path.join(REFS, f"{a.name}_mask_64.pfm"))[..., 0] < 0.5
        rows = []
        for spp, seeds in ((64, (1, 2)), (256, (1, 2))):
            for seed in seeds:
                img = render(mi, a.name, spp, seed, size=64)
                d2 = ((img - ref) ** 2).mean(axis=2)
                rows.append({"spp": spp, "seed": seed, "rmse": float(np.sqrt(d2.mean())),
                             "rmse_off_light": float(np.sqrt(d2[keep].mean())),
                             "mean": img.reshape(-1, 3).mean(0).tolist()})
                write_pfm(os.path.join(a.out, f"{a.name}_mi_{spp}_{seed}.pfm"), img)
                print(json.dumps(rows[-1]), flush=True)


if __name__ == "__main__":
    sys.exit(main())
