#!/usr/bin/env python3
"""Writes assets/painted_vase.obj: a vase (a surface of revolution, 32
segments x 20 rings, closed at the bottom) with a colour per vertex
(`v x y z r g b`, sRGB as MeshLab and Blender write them): a hue that turns
with height, and a green band at mid height that `scenes/vertex_colors.ron`
also reads as a blend mask. No normals: the scene asks for `smooth: true`.
"""
import colorsys
import math
import pathlib

SEGMENTS, RINGS = 32, 20
out = pathlib.Path(__file__).resolve().parent.parent / "assets" / "painted_vase.obj"


def radius(h):
    # A belly low, a neck near the top, a lip.
    return 0.35 + 0.25 * math.sin(math.pi * min(h / 0.75, 1.0)) * (1.0 - h) + 0.1 * max(0.0, h - 0.85) / 0.15


lines = ["# painted vase: written by tools/make_painted_vase.py (project data)"]
for r in range(RINGS + 1):
    h = r / RINGS
    y = 1.4 * h
    rad = radius(h)
    for s in range(SEGMENTS):
        a = 2 * math.pi * s / SEGMENTS
        x, z = rad * math.cos(a), rad * math.sin(a)
        band = math.exp(-((h - 0.5) / 0.06) ** 2)
        cr, cg, cb = colorsys.hsv_to_rgb((0.98 - 0.35 * h) % 1.0, 0.92, 0.85)
        cr, cg, cb = cr * (1 - band), cg * (1 - band) + band, cb * (1 - band)
        lines.append(f"v {x:.5f} {y:.5f} {z:.5f} {cr:.4f} {cg:.4f} {cb:.4f}")
# The bottom's centre.
lines.append("v 0 0 0 0.2000 0.1500 0.1000")
centre = (RINGS + 1) * SEGMENTS + 1
for r in range(RINGS):
    for s in range(SEGMENTS):
        a = r * SEGMENTS + s + 1
        b = r * SEGMENTS + (s + 1) % SEGMENTS + 1
        c, d = a + SEGMENTS, b + SEGMENTS
        # Counter-clockwise seen from outside.
        lines.append(f"f {a} {d} {b}")
        lines.append(f"f {a} {c} {d}")
for s in range(SEGMENTS):
    a, b = s + 1, (s + 1) % SEGMENTS + 1
    lines.append(f"f {centre} {a} {b}")
out.write_text("\n".join(lines) + "\n")
print(out, out.stat().st_size, "bytes")
