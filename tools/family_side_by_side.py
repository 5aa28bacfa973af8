#!/usr/bin/env python3
"""ronray beside Mitsuba 3 on a family of scenes neither was tuned on.

`tools/side_by_side.sh` times the reference scenes, which ronray's speed work
was measured on. This script builds six more from the repository's own
assets, writes each as a ronray scene and as a Mitsuba dict, and in
alternated rounds renders both at 256² with independent samples, 2 threads
(ronray: `Independent`, every pixel the same count, one path per camera
sample, as side_by_side.sh does), and prints each scene's per-sample ratio
(ronray's render time over Mitsuba's `mi.render`, load excluded on both
sides). With `--check SPP` it also renders both at SPP and compares the
images: the mean of the whole image and of 4 × 4 blocks, as ratios, so a
block rendered too dark cannot hide in the whole (both must be converged
enough at SPP for the blocks' noise to be small; 1,024 is).

The scenes: the bunny (3,674 triangles, no normals: flat, `face_normals` in
Mitsuba) on a floor under the sky map, the same under a rectangle light
and a dim constant sky, under a directional sun, a blue sky and a small
lamp, the bunny as a mesh light beside a gold sphere,
100 spheres of three materials, glass and plastic spheres under the sky
map, the bunny on a floor made of triangles (a 10 × 10 grid) under the
rectangle light and dim sky and under the sky map, and (when `--big OBJ` names the 1M-triangle mesh of
`../shared/tools/gen_big_mesh.py`) that mesh under a rectangle light.

Needs a release build of ronray (or RONRAY=path) and a Python with the
`mitsuba` package (run this script with it, or MITSUBA_PYTHON=...);
Mitsuba's LLVM backend may need DRJIT_LIBLLVM_PATH (see side_by_side.sh).

With `--error REF_SPP` each round also renders ronray's defaults (at
`--defaults-spp`, default `--spp / 4`) and measures both renderers' RMSE
against a Mitsuba reference of REF_SPP samples: the defaults' time scaled to
Mitsuba's error over Mitsuba's time, and the worst 4 × 4 block's squared
error × time over Mitsuba's.

Usage: family_side_by_side.py [--rounds N] [--spp N] [--check SPP] [--error REF_SPP] [--defaults-spp N]
                              [--big OBJ] [--only NAME ...]
"""
import argparse
import json
import os
import random
import re
import shutil
import subprocess
import sys
import tempfile

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BUNNY = os.path.join(REPO, "assets", "bunny.obj")
SKY = os.path.join(REPO, "assets", "sky_sun.exr")
GOLD_ETA = (0.143036, 0.375307, 1.44205)
GOLD_K = (3.983, 2.38556, 1.60336)


def scenes(big):
    """name -> dict(camera=(eye, target, fov_y), mats, objects, lights)."""
    rnd = random.Random(7)
    mats = {
        "floor": ("lambert", (0.5, 0.5, 0.5)),
        "clay": ("lambert", (0.8, 0.65, 0.5)),
        "gold": ("conductor", 0.2),
        "glass": ("dielectric",),
        "blue": ("plastic", (0.1, 0.25, 0.6), 0.1),
    }
    floor = {"kind": "rect", "center": (0, 0, 0), "hu": (5, 0, 0), "hv": (0, 0, -5), "mat": "floor"}
    bunny = {"kind": "mesh", "file": BUNNY, "scale": 0.1, "mat": "clay"}
    area = ("rect", (0.5, 3, 1), (0.6, 0, 0), (0, 0, 0.6), 10.0)
    cam = ((0, 1.1, 3.2), (0, 0.55, 0), 35)
    out = {
        "bunny_sky": dict(camera=cam, mats=mats, objects=[floor, bunny], lights=[("env", SKY)]),
        "bunny_area": dict(camera=cam, mats=mats, objects=[floor, bunny], lights=[area, ("const", 0.05)]),
        # The most ordinary outdoor scene: a sun (a directional light, 45° up,
        # behind and to the right) over a blue sky, beside a small lamp.
        "bunny_sun": dict(camera=cam, mats=mats, objects=[floor, bunny],
                          lights=[("sun", (-0.5, -0.7071, -0.5), 3.0), ("const", 0.15), ("rect", (-1, 2, 1), (0.2, 0, 0), (0, 0, 0.2), 20.0)]),
        "bunny_glow": dict(
            camera=cam,
            mats=mats,
            objects=[floor, dict(bunny, emit=4.0), {"kind": "sphere", "center": (0.8, 0.3, 0.2), "r": 0.3, "mat": "gold"}],
            lights=[],
        ),
    }
    spheres = [floor]
    for _ in range(100):
        x, z, r = rnd.uniform(-3, 3), rnd.uniform(-4, 1.5), rnd.uniform(0.08, 0.25)
        spheres.append({"kind": "sphere", "center": (x, r, z), "r": r, "mat": rnd.choice(["clay", "gold", "blue"])})
    out["spheres100"] = dict(
        camera=((0, 2.0, 5.0), (0, 0.2, -1), 40),
        mats=mats,
        objects=spheres,
        lights=[("rect", (0.5, 4, 0), (1.0, 0, 0), (0, 0, 0.6), 10.0), ("const", 0.05)],
    )
    out["glass_sky"] = dict(
        camera=((0, 1.6, 6), (0, 0.5, 0), 35),
        mats=mats,
        objects=[
            floor,
            {"kind": "sphere", "center": (-0.8, 0.6, 0), "r": 0.6, "mat": "glass"},
            {"kind": "sphere", "center": (0.8, 0.6, 0), "r": 0.6, "mat": "blue"},
        ],
        lights=[("env", SKY)],
    )
    # The floor as a triangle mesh (a 10 × 10 grid of quads at y = 0, as an
    # exported ground plane is): a mesh floor under a sky reflected 0.42 of
    # its 0.5 albedo before the triangle test's self-hit bound.
    grid = mesh_floor_obj()
    mfloor = {"kind": "mesh", "file": grid, "scale": 1.0, "mat": "floor"}
    out["meshfloor_area"] = dict(camera=cam, mats=mats, objects=[mfloor, bunny], lights=[area, ("const", 0.05)])
    out["meshfloor_sky"] = dict(camera=cam, mats=mats, objects=[mfloor, bunny], lights=[("env", SKY)])
    if big:
        out["big_mesh"] = dict(
            camera=((0, 0.5, 3.5), (0, 0, 0), 40),
            mats=mats,
            objects=[
                {"kind": "rect", "center": (0, -1.2, 0), "hu": (5, 0, 0), "hv": (0, 0, -5), "mat": "floor"},
                {"kind": "mesh", "file": os.path.abspath(big), "scale": 1.0, "mat": "clay"},
            ],
            lights=[("rect", (0.5, 3, 1), (0.8, 0, 0), (0, 0, 0.8), 10.0), ("const", 0.05)],
        )
    return out


def mesh_floor_obj():
    """Writes the 10 × 10 floor grid (−5..5 in x and z, y = 0, normal +y) as
    an OBJ in the temporary folder; returns its path."""
    path = os.path.join(tempfile.gettempdir(), "ronray_family_floor.obj")
    n = 10
    lines = []
    for j in range(n + 1):
        for i in range(n + 1):
            lines.append("v %r 0 %r" % (-5 + 10 * i / n, -5 + 10 * j / n))
    for j in range(n):
        for i in range(n):
            a = 1 + j * (n + 1) + i
            b, c, d = a + 1, a + n + 2, a + n + 1
            # Counter-clockwise seen from above (+y): a, d, c and a, c, b.
            lines.append("f %d %d %d" % (a, d, c))
            lines.append("f %d %d %d" % (a, c, b))
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")
    return path


def t3(v):
    return "(%s)" % ", ".join(repr(float(x)) for x in v)


def ron_material(m):
    kind = m[0]
    if kind == "lambert":
        return "Lambert(albedo: %s)" % t3(m[1])
    if kind == "conductor":
        return "CookTorrance(distribution: Ggx, roughness: %r, roughness_unit: Alpha, fresnel: Conductor(eta: %s, k: %s))" % (
            m[1], t3(GOLD_ETA), t3(GOLD_K))
    if kind == "dielectric":
        return "Glass(ior: 1.5, fresnel: Exact)"
    return "RoughPlastic(diffuse: %s, roughness: %r, roughness_unit: Alpha, ior: 1.5)" % (t3(m[1]), m[2])


def write_ron(path, s):
    eye, target, fov = s["camera"]
    lines = [
        "Scene(",
        f"    camera: (eye: {t3(eye)}, target: {t3(target)}, up: (0, 1, 0), fov_y_degrees: {fov}),",
        # No sampler: the defaults (`--error` times them); the per-sample
        # rounds set `Independent` on the command line.
        "    film: (width: 256, height: 256, spp: 64),",
        "    integrator: Path(max_depth: 8, rr_depth: 5),",
        "    materials: {",
    ]
    lines += [f'        "{k}": {ron_material(m)},' for k, m in s["mats"].items()]
    lines += ["    },", "    lights: ["]
    for light in s["lights"]:
        if light[0] == "env":
            lines.append(f'        Environment(map: "{light[1]}"),')
        elif light[0] == "const":
            lines.append(f"        Environment(radiance: {t3([light[1]] * 3)}),")
        elif light[0] == "sun":
            lines.append(f"        Directional(direction: {t3(light[1])}, irradiance: {t3([light[2]] * 3)}),")
        else:
            _, c, hu, hv, le = light
            lines.append(f"        Rect(center: {t3(c)}, half_u: {t3(hu)}, half_v: {t3(hv)}, radiance: {t3([le] * 3)}),")
    lines += ["    ],", "    objects: ["]
    for o in s["objects"]:
        emit = f", emission: (radiance: {t3([o['emit']] * 3)})" if o.get("emit") else ""
        mat = o["mat"]
        if o["kind"] == "rect":
            lines.append(f'        Rect(center: {t3(o["center"])}, half_u: {t3(o["hu"])}, half_v: {t3(o["hv"])}, material: "{mat}"{emit}),')
        elif o["kind"] == "sphere":
            lines.append(f'        Sphere(center: {t3(o["center"])}, radius: {o["r"]}, material: "{mat}"{emit}),')
        else:
            k = o["scale"]
            lines.append(f'        Mesh(file: "{o["file"]}", material: "{mat}", transform: [Scale({t3([k] * 3)})]{emit}),')
    lines += ["    ],", ")"]
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")


def mitsuba_scene(mi, np, s, spp):
    T = mi.ScalarTransform4f

    def rgb(c):
        return {"type": "rgb", "value": [float(x) for x in c]}

    def rect_to_world(c, hu, hv):
        c, hu, hv = map(np.array, (c, hu, hv))
        n = np.cross(hu, hv)
        m = np.eye(4)
        m[:3, 0], m[:3, 1], m[:3, 2], m[:3, 3] = hu, hv, n / np.linalg.norm(n), c
        return T(m.tolist())

    def bsdf(m):
        kind = m[0]
        if kind == "dielectric":
            return {"type": "dielectric", "int_ior": 1.5, "ext_ior": 1.0}
        if kind == "lambert":
            b = {"type": "diffuse", "reflectance": rgb(m[1])}
        elif kind == "conductor":
            b = {"type": "roughconductor", "distribution": "ggx", "alpha": m[1], "eta": rgb(GOLD_ETA), "k": rgb(GOLD_K)}
        else:
            b = {"type": "roughplastic", "distribution": "ggx", "alpha": m[2], "diffuse_reflectance": rgb(m[1]),
                 "int_ior": 1.5, "nonlinear": False, "sample_visible": True}
        return {"type": "twosided", "bsdf": b}

    eye, target, fov = s["camera"]
    d = {
        "type": "scene",
        "integrator": {"type": "path", "max_depth": 8, "rr_depth": 5},
        "sensor": {
            "type": "perspective", "fov": fov, "fov_axis": "y",
            "to_world": T().look_at(origin=list(eye), target=list(target), up=[0, 1, 0]),
            "film": {"type": "hdrfilm", "width": 256, "height": 256, "rfilter": {"type": "box"}},
            "sampler": {"type": "independent", "sample_count": spp},
        },
    }
    for k, m in s["mats"].items():
        d["m_" + k] = bsdf(m)
    for i, o in enumerate(s["objects"]):
        if o["kind"] == "rect":
            sh = {"type": "rectangle", "to_world": rect_to_world(o["center"], o["hu"], o["hv"])}
        elif o["kind"] == "sphere":
            sh = {"type": "sphere", "center": list(o["center"]), "radius": o["r"]}
        else:
            # ronray shades a mesh without normals flat; so does Mitsuba with this.
            sh = {"type": "obj", "filename": o["file"], "to_world": T().scale(o["scale"]), "face_normals": True}
        sh["bsdf"] = {"type": "ref", "id": "m_" + o["mat"]}
        if o.get("emit"):
            sh["emitter"] = {"type": "area", "radiance": rgb([o["emit"]] * 3)}
        d[f"o{i}"] = sh
    for i, light in enumerate(s["lights"]):
        if light[0] == "env":
            d[f"l{i}"] = {"type": "envmap", "filename": light[1]}
        elif light[0] == "const":
            d[f"l{i}"] = {"type": "constant", "radiance": rgb([light[1]] * 3)}
        elif light[0] == "sun":
            d[f"l{i}"] = {"type": "directional", "direction": list(light[1]), "irradiance": rgb([light[2]] * 3)}
        else:
            _, c, hu, hv, le = light
            d[f"l{i}"] = {"type": "rectangle", "to_world": rect_to_world(c, hu, hv),
                          "emitter": {"type": "area", "radiance": rgb([le] * 3)},
                          "bsdf": {"type": "diffuse", "reflectance": rgb([0, 0, 0])}}
    return d


# Run in Mitsuba's Python, one render per process (as mitsuba_run.py): the
# scene's JSON, the sample count, the output EXR; prints render seconds.
MITSUBA_CHILD = r"""
import json, sys, time
import numpy as np, mitsuba as mi, drjit as dr
sys.dont_write_bytecode = True
sys.path.insert(0, sys.argv[1])
from family_side_by_side import mitsuba_scene
mi.set_variant("llvm_ad_rgb")
dr.set_thread_count(2)
s = json.load(open(sys.argv[2]))
spp = int(sys.argv[3])
seed = int(sys.argv[5]) if len(sys.argv) > 5 else 0
scene = mi.load_dict(mitsuba_scene(mi, np, s, spp))
t0 = time.time()
img = np.array(mi.render(scene, spp=spp, seed=seed), dtype=np.float32)
t1 = time.time()
mi.Bitmap(np.ascontiguousarray(img), mi.Bitmap.PixelFormat.RGB).write(sys.argv[4])
print(t1 - t0)
"""

# Compares two EXRs (in Mitsuba's Python, which reads them): the whole
# image's mean ratio a/b, the 4 x 4 blocks' smallest and largest (blocks
# darker than 1% of the image's mean left out: black sky, whose ratio is
# 0/0, and a few dim pixels, whose ratio is noise), how many were, and the RMSE.
COMPARE_CHILD = r"""
import sys, numpy as np, mitsuba as mi
mi.set_variant("scalar_rgb")
a, b = (np.array(mi.Bitmap(p), dtype=np.float64)[..., :3].mean(axis=2) for p in sys.argv[1:3])
h, w = a.shape
pairs = [(a[y:y + h // 4, x:x + w // 4].mean(), b[y:y + h // 4, x:x + w // 4].mean())
         for y in range(0, h, h // 4) for x in range(0, w, w // 4)]
ratios = [p / q for p, q in pairs if q > 0.01 * b.mean()]
rmse = np.sqrt(((a - b) ** 2).mean())
print(a.mean() / b.mean(), min(ratios), max(ratios), len(pairs) - len(ratios), rmse)
"""

# The error of two renders against a reference (in Mitsuba's Python): each
# one's RMSE over the whole image, and over each of 4 x 4 blocks the ratio of
# the second's mean squared error to the first's (blocks where the first's
# is nil left out); prints the two RMSEs and the blocks' smallest and
# largest ratio.
ERROR_CHILD = r"""
import sys, numpy as np, mitsuba as mi
mi.set_variant("scalar_rgb")
ref, a, b = (np.array(mi.Bitmap(p), dtype=np.float64)[..., :3] for p in sys.argv[1:4])
ea, eb = ((x - ref) ** 2 for x in (a, b))
h, w = ref.shape[:2]
blocks = [(ea[y:y + h // 4, x:x + w // 4].mean(), eb[y:y + h // 4, x:x + w // 4].mean())
          for y in range(0, h, h // 4) for x in range(0, w, w // 4)]
ratios = [q / p for p, q in blocks if p > 0]
print(np.sqrt(ea.mean()), np.sqrt(eb.mean()), min(ratios), max(ratios))
"""


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--spp", type=int, default=128)
    ap.add_argument("--check", type=int, default=0, help="also compare images rendered at this many spp")
    ap.add_argument("--big", help="the 1M-triangle OBJ of gen_big_mesh.py (row left out without it)")
    ap.add_argument("--error", type=int, default=0,
                    help="also time ronray's defaults to Mitsuba's error at --spp, against a Mitsuba reference of this many spp")
    ap.add_argument("--defaults-spp", type=int, default=0,
                    help="ronray's defaults at this many spp for --error (default: --spp / 4, so that their error is about "
                         "Mitsuba's and the reference's noise is small beside both)")
    ap.add_argument("--only", nargs="*", default=[])
    a = ap.parse_args()
    ronray = os.environ.get("RONRAY", os.path.join(REPO, "target", "release", "ronray"))
    py = os.environ.get("MITSUBA_PYTHON", sys.executable)
    if not os.access(ronray, os.X_OK):
        sys.exit("build first: cargo build --release (or set RONRAY)")
    here = os.path.dirname(os.path.abspath(__file__))
    work = tempfile.mkdtemp(prefix="family_")
    child = os.path.join(work, "child.py")
    with open(child, "w") as f:
        f.write(MITSUBA_CHILD)
    compare = os.path.join(work, "compare.py")
    with open(compare, "w") as f:
        f.write(COMPARE_CHILD)
    error = os.path.join(work, "error.py")
    with open(error, "w") as f:
        f.write(ERROR_CHILD)

    def mitsuba(js, spp, out, seed=0):
        p = subprocess.run([py, child, here, js, str(spp), out, str(seed)], capture_output=True, text=True)
        if p.returncode != 0:
            sys.exit(f"Mitsuba failed on {js}:\n{p.stderr[-3000:]}")
        return float(p.stdout.split()[-1])

    def rr(scene, spp, out, defaults=False):
        per_sample = [] if defaults else ["--set", "film.sampler=Independent", "--set", "film.allocation=Even",
                                          "--set", "integrator.splits=1"]
        p = subprocess.run([ronray, "render", scene, "--spp", str(spp), "--size", "256x256", "--threads", "2",
                            "--progress", "none", *per_sample, "-o", out], capture_output=True, text=True)
        m = re.search(r" in ([0-9.]+) s", p.stdout + p.stderr)
        if p.returncode != 0 or not m:
            sys.exit(f"ronray failed on {scene}:\n{(p.stdout + p.stderr)[-3000:]}")
        return float(m.group(1))

    try:
        rows = []
        for name, s in scenes(a.big).items():
            if a.only and name not in a.only:
                continue
            scene, js = os.path.join(work, name + ".ron"), os.path.join(work, name + ".json")
            write_ron(scene, s)
            with open(js, "w") as f:
                json.dump(s, f)
            mitsuba(js, 4, os.path.join(work, "warm.exr"))  # Mitsuba's kernel cache
            ref = os.path.join(work, "ref.exr")
            if a.error:
                mitsuba(js, a.error, ref, seed=1)
            ratios, to_error, worst = [], [], []
            for r in range(a.rounds):
                mt = mitsuba(js, a.spp, os.path.join(work, "mi.exr"))
                rt = rr(scene, a.spp, os.path.join(work, "rr.exr"))
                ratios.append(rt / mt)
                line = f"{name} round {r + 1}: Mitsuba {mt:.2f} s, ronray {rt:.2f} s, {rt / mt:.2f}x"
                if a.error:
                    # ronray's defaults at --defaults-spp, scaled to Mitsuba's
                    # error (error ∝ 1/√time): time × (RMSE / Mitsuba's)².
                    dt = rr(scene, a.defaults_spp or max(a.spp // 4, 1), os.path.join(work, "rd.exr"), defaults=True)
                    p = subprocess.run([py, error, ref, os.path.join(work, "mi.exr"), os.path.join(work, "rd.exr")],
                                       capture_output=True, text=True)
                    if p.returncode != 0:
                        sys.exit(f"measuring the {name} errors failed:\n{p.stderr[-3000:]}")
                    em, ed, _, hi = map(float, p.stdout.split())
                    to_error.append(dt * (ed / em) ** 2 / mt)
                    # The worst block, at equal time: its squared error × time.
                    worst.append(hi * dt / mt)
                    line += f"; defaults {dt:.2f} s, RMSE {ed:.4f} vs {em:.4f}: {to_error[-1]:.2f}x to error"
                print(line, flush=True)
            ratios.sort()
            row = [name, f"{ratios[len(ratios) // 2]:.2f}x ({', '.join('%.2f' % x for x in ratios)})"]
            if a.error:
                to_error.sort()
                worst.sort()
                row += [f"{to_error[len(to_error) // 2]:.2f}x", f"{worst[len(worst) // 2]:.2f}x"]
            if a.check:
                mitsuba(js, a.check, os.path.join(work, "mi_check.exr"))
                rr(scene, a.check, os.path.join(work, "rr_check.exr"))
                p = subprocess.run([py, compare, os.path.join(work, "rr_check.exr"), os.path.join(work, "mi_check.exr")],
                                   capture_output=True, text=True)
                if p.returncode != 0:
                    sys.exit(f"comparing the {name} images failed:\n{p.stderr[-3000:]}")
                whole, lo, hi, dark, rmse = map(float, p.stdout.split())
                row += [f"{whole:.4f}", f"{lo:.4f}–{hi:.4f}" + (f" ({dark:.0f} dark left out)" if dark else ""), f"{rmse:.4f}"]
            rows.append(row)
        head = ["scene", f"ronray / Mitsuba per sample ({a.spp} spp, {a.rounds} rounds)"]
        if a.error:
            head += [f"defaults' time to Mitsuba's {a.spp}-spp error / Mitsuba's", "worst 4 × 4 block, MSE × time"]
        if a.check:
            head += [f"mean ratio at {a.check} spp", "4 × 4 blocks' mean ratios", "RMSE"]
        print("| " + " | ".join(head) + " |")
        print("|" + "---|" * len(head))
        for row in rows:
            print("| " + " | ".join(row) + " |")
    finally:
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()
