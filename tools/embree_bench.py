"""Embree 4's BVH build time on a triangle OBJ, on 1 and 2 threads, and its
closest-hit throughput on `ronray bench`'s incoherent rays, for issue 18's
build and traversal lines measured side by side (the performance anchors'
Embree figures are from another day; on this shared machine only same-run
ratios mean anything).

Calls Embree's C API through ctypes, from the libembree4 bundled in the
`embreex` wheel (Embree 4.4, TBB; its verbose mode reports the AVX-512 ISA and
`avx::BVH8BuilderSAH` building `BVH8<triangle4>`: the anchors' binned-SAH
8-wide build), at the default medium build quality. Each thread count gets
one warm-up build (thread pool, allocator), then ROUNDS timed ones of
`rtcCommitScene`, printed sorted. The rays are `ronray bench`'s incoherent
set in distribution (2^20, origins uniform in the mesh's bounding box,
directions uniform on the sphere; numpy's generator, not ronray's), traced
one at a time on one thread by embreex's `EmbreeScene.run`, a Cython loop
over `rtcIntersect1`: its per-call overhead, printed as the rate of rays
that miss the box, is counted against Embree. Not part of ronray: a
measuring tool.

Needs: pip install embreex numpy
Usage: python3 tools/embree_bench.py MESH.obj [ROUNDS]   (ROUNDS default 3)
Compare with `ronray bench MESH.obj --threads 2` run alternately with it."""
import ctypes, glob, os, sys, time
import numpy as np
import embreex
libdir = os.path.join(os.path.dirname(embreex.__file__), os.pardir, 'embreex.libs')
lib = ctypes.CDLL(glob.glob(os.path.join(libdir, 'libembree4*'))[0])
vp = ctypes.c_void_p
lib.rtcNewDevice.restype = vp; lib.rtcNewDevice.argtypes = [ctypes.c_char_p]
lib.rtcNewScene.restype = vp; lib.rtcNewScene.argtypes = [vp]
lib.rtcNewGeometry.restype = vp; lib.rtcNewGeometry.argtypes = [vp, ctypes.c_int]
lib.rtcSetNewGeometryBuffer.restype = vp
lib.rtcSetNewGeometryBuffer.argtypes = [vp, ctypes.c_int, ctypes.c_uint, ctypes.c_int, ctypes.c_size_t, ctypes.c_size_t]
for f in ['rtcCommitGeometry', 'rtcReleaseGeometry', 'rtcCommitScene', 'rtcReleaseScene', 'rtcReleaseDevice']:
    getattr(lib, f).argtypes = [vp]
lib.rtcAttachGeometry.argtypes = [vp, vp]
lib.rtcSetSceneBuildQuality.argtypes = [vp, ctypes.c_int]

def load(path):
    v, f = [], []
    with open(path) as fh:
        for line in fh:
            if line.startswith('v '):
                v.append(line.split()[1:4])
            elif line.startswith('f '):
                # 1-based, or negative from the end; polygons as fans.
                ix = [int(t.split('/')[0]) for t in line.split()[1:]]
                ix = [i - 1 if i > 0 else len(v) + i for i in ix]
                f.extend([ix[0], ix[k], ix[k + 1]] for k in range(1, len(ix) - 1))
    return np.array(v, dtype=np.float32), np.array(f, dtype=np.uint32)

def build(dev, v, f):
    scene = lib.rtcNewScene(dev)
    lib.rtcSetSceneBuildQuality(scene, 1)  # RTC_BUILD_QUALITY_MEDIUM
    geom = lib.rtcNewGeometry(dev, 0)  # RTC_GEOMETRY_TYPE_TRIANGLE
    vb = lib.rtcSetNewGeometryBuffer(geom, 1, 0, 0x9003, 12, len(v))  # VERTEX, FLOAT3
    ctypes.memmove(vb, v.ctypes.data, v.nbytes)
    ib = lib.rtcSetNewGeometryBuffer(geom, 0, 0, 0x5003, 12, len(f))  # INDEX, UINT3
    ctypes.memmove(ib, f.ctypes.data, f.nbytes)
    lib.rtcCommitGeometry(geom)
    lib.rtcAttachGeometry(scene, geom)
    lib.rtcReleaseGeometry(geom)
    t = time.perf_counter()
    lib.rtcCommitScene(scene)
    dt = time.perf_counter() - t
    lib.rtcReleaseScene(scene)
    return dt

v, f = load(sys.argv[1])
rounds = int(sys.argv[2]) if len(sys.argv) > 2 else 3
for threads in (1, 2):
    dev = lib.rtcNewDevice(f'threads={threads},set_affinity=0'.encode())
    build(dev, v, f)  # warm-up: thread pool, allocator
    times = sorted(build(dev, v, f) for _ in range(rounds))
    print(f'embree {len(f)} triangles, {threads} thread(s): ' + ' '.join(f'{1000 * t:.1f}' for t in times) + ' ms')
    lib.rtcReleaseDevice(dev)

# Incoherent closest hits, one thread, as `ronray bench` defines them.
from embreex import rtcore_scene
from embreex.mesh_construction import TriangleMesh
scene = rtcore_scene.EmbreeScene()
TriangleMesh(scene, v[f.astype(np.int64)])
lo, hi = v.min(0), v.max(0)
rng = np.random.default_rng(1)
n = 1 << 20
o = (lo + rng.random((n, 3)) * (hi - lo)).astype(np.float32)
d = rng.normal(size=(n, 3))
d = (d / np.linalg.norm(d, axis=1)[:, None]).astype(np.float32)
scene.run(o[:1024], d[:1024])  # builds the BVH
rates = []
for _ in range(rounds):
    t = time.perf_counter()
    ids = scene.run(o, d)
    rates.append(n / (time.perf_counter() - t) / 1e6)
print(f'embree incoherent, 1 thread: ' + ' '.join(f'{r:.2f}' for r in sorted(rates))
      + f' Mrays/s, hit {100 * np.mean(ids >= 0):.1f}%')
t = time.perf_counter()
away = np.broadcast_to((hi - lo) / np.linalg.norm(hi - lo), d.shape).astype(np.float32)
scene.run((o + 4 * (hi - lo).max() + 1).astype(np.float32), away)
print(f'embree call overhead: {n / (time.perf_counter() - t) / 1e6:.1f} Mrays/s on rays that miss the box')
