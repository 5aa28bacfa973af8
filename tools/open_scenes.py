#!/usr/bin/env python3
"""Issue 37's table: noise of ronray (default light selection and uniform) and of
Mitsuba 3 at equal spp on the generated open and closed scenes of tests/open_scenes.rs.

Noise needs no reference: the RMS difference of two renders with different seeds,
over pixels and channels, divided by sqrt(2).

    cargo build --release
    DRJIT_LIBLLVM_PATH=/usr/lib/x86_64-linux-gnu/libLLVM-19.so \\
        python3 tools/open_scenes.py [--size 256] [--spp 64] [--only NAME_SUBSTRING]

Needs the `mitsuba` and `numpy` packages and ../shared/tools/mitsuba_run.py (or
MITSUBA_RUN=...). Dumps the scenes with `cargo test --test integration open_scenes::dump`
(RONRAY_DUMP_OPEN_SCENES), renders each with ronray (Independent, as written) and with
Mitsuba `llvm_ad_rgb` (independent sampler), two seeds each, and prints a Markdown table.

With --timing (run it on a quiet machine): Mitsuba at 256 spp and ronray's defaults (Sobol,
samples spread by noise) at --spp, two seeds each, timed (Mitsuba's render_s, ronray's own
render time, as tools/side_by_side.sh takes them); the error of an unbiased render is its
noise, so ronray's time to Mitsuba's 256-spp error is its time x (its noise / Mitsuba's)^2.
Prints that time over Mitsuba's."""
import argparse, json, os, subprocess, sys, tempfile

here = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def load(path):
    import mitsuba as mi
    import numpy as np
    return np.array(mi.Bitmap(path), dtype=np.float64)[..., :3]


def noise(a, b):
    import numpy as np
    return float(np.sqrt(np.mean((a - b) ** 2) / 2.0))


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--size", type=int, default=256)
    ap.add_argument("--spp", type=int, default=64)
    ap.add_argument("--only", default="")
    ap.add_argument("--no-mitsuba", action="store_true")
    ap.add_argument("--timing", action="store_true")
    a = ap.parse_args()
    import mitsuba as mi
    mi.set_variant("llvm_ad_rgb")
    run = os.environ.get("MITSUBA_RUN", os.path.join(here, "..", "shared", "tools", "mitsuba_run.py"))
    ronray = os.environ.get("RONRAY", os.path.join(here, "target", "release", "ronray"))
    out = tempfile.mkdtemp(prefix="open_scenes.")
    env = dict(os.environ, RONRAY_DUMP_OPEN_SCENES=out, RONRAY_DUMP_SIZE=str(a.size))
    subprocess.run(["cargo", "test", "-q", "--test", "integration", "open_scenes::dump"], cwd=here, env=env,
                   check=True, stdout=subprocess.DEVNULL)
    names = sorted(f[:-5] for f in os.listdir(out) if f.endswith(".json") and a.only in f)
    # mitsuba_run.py reads no directional light: those scenes would be compared without their sun.
    skipped = [n for n in names if "directional_lights" in open(os.path.join(out, n + ".json")).read()]
    if skipped:
        print(f"left out (mitsuba_run.py has no directional light): {', '.join(skipped)}", file=sys.stderr)
    names = [n for n in names if n not in skipped]
    if a.timing:
        return timing(a, names, out, run, ronray)
    print(f"| scene | Mitsuba llvm | ronray uniform | ronray default | default / Mitsuba | default / uniform |")
    print("|---|---|---|---|---|---|")
    worse = 0
    for name in names:
        res = {}
        for kind, scene in [("default", f"{name}.ron"), ("uniform", f"{name}.uniform.ron")]:
            imgs = []
            for seed in (1, 2):
                o = os.path.join(out, f"{name}.{kind}.{seed}.exr")
                subprocess.run([ronray, "render", scene, "--spp", str(a.spp), "--seed", str(seed), "-o", o,
                                "--progress", "none"], cwd=out, check=True, stdout=subprocess.DEVNULL)
                imgs.append(load(o))
            res[kind] = noise(*imgs)
        if not a.no_mitsuba:
            imgs = []
            for seed in (1, 2):
                o = os.path.join(out, f"{name}.mi.{seed}.exr")
                subprocess.run([sys.executable, run, os.path.join(out, f"{name}.json"), "--variant", "llvm_ad_rgb",
                                "--spp", str(a.spp), "--seed", str(seed), "--out", o], check=True,
                               stdout=subprocess.DEVNULL)
                imgs.append(load(o))
            res["mi"] = noise(*imgs)
        m = res.get("mi", float("nan"))
        r = res["default"] / m if m == m else float("nan")
        worse += r > 1.0
        print(f"| {name} | {m:.5f} | {res['uniform']:.5f} | {res['default']:.5f} | {r:.2f}x | "
              f"{res['default'] / res['uniform']:.2f}x |", flush=True)
    print(f"\n{worse} of {len(names)} scenes noisier than Mitsuba at equal spp ({a.size}^2, {a.spp} spp).")


def timing(a, names, out, run, ronray):
    import re
    # Warm Mitsuba's JIT caches.
    subprocess.run([sys.executable, run, os.path.join(out, f"{names[0]}.json"), "--spp", "4"],
                   check=True, stdout=subprocess.DEVNULL)
    print("| scene | Mitsuba 256 spp: s, noise | ronray defaults " + str(a.spp) +
          " spp: s, noise | ronray's time to Mitsuba's noise / Mitsuba's time |")
    print("|---|---|---|---|")
    ratios = []
    for name in names:
        mi_t, mi_img, rr_t, rr_img = [], [], [], []
        for seed in (1, 2):
            o = os.path.join(out, f"{name}.mi256.{seed}.exr")
            r = subprocess.run([sys.executable, run, os.path.join(out, f"{name}.json"), "--variant", "llvm_ad_rgb",
                                "--spp", "256", "--seed", str(seed), "--out", o], check=True,
                               capture_output=True, text=True)
            mi_t.append(json.loads(r.stdout.strip().splitlines()[-1])["render_s"])
            mi_img.append(load(o))
            o = os.path.join(out, f"{name}.def.{seed}.exr")
            r = subprocess.run([ronray, "render", f"{name}.ron", "--spp", str(a.spp), "--seed", str(seed),
                                "--set", "film.sampler=Sobol", "-o", o, "--progress", "none"], cwd=out,
                               check=True, capture_output=True, text=True)
            rr_t.append(float(re.search(r" in ([0-9.]+) s", r.stderr + r.stdout).group(1)))
            rr_img.append(load(o))
        nm, nr = noise(*mi_img), noise(*rr_img)
        tm, tr = sum(mi_t) / 2, sum(rr_t) / 2
        ratio = tr * (nr / nm) ** 2 / tm
        ratios.append(ratio)
        print(f"| {name} | {tm:.2f} s, {nm:.5f} | {tr:.2f} s, {nr:.5f} | {ratio:.2f}x |", flush=True)
    print(f"\nworst {max(ratios):.2f}x, median {sorted(ratios)[len(ratios) // 2]:.2f}x over {len(ratios)} scenes.")


if __name__ == "__main__":
    main()
