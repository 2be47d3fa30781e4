#!/usr/bin/env python3
"""Writes the fuzzer's seed corpus (tests/fuzz/corpus): small meshes in fuzz_cores.cpp's byte
layout — a tetrahedron, an octahedron, a bumpy 5 x 5 grid and a fan — for each core, with
automatic and given pre-smoothing. Run it again after changing the layout."""
import math, os, struct

here = os.path.dirname(os.path.abspath(__file__))
out = os.path.join(here, "corpus")
os.makedirs(out, exist_ok=True)

def encode(verts, faces, flags, presmoothing=0.0, threshold=1.0):
    b = bytes([len(verts) % 256, len(faces) % 256, flags]) + struct.pack("<ff", presmoothing, threshold)
    for v in verts:
        b += struct.pack("<fff", *v)
    for f in faces:
        b += bytes(f)
    return b

tet = ([(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)], [(0, 2, 1), (0, 1, 3), (0, 3, 2), (1, 2, 3)])
octa = ([(1, 0, 0), (-1, 0, 0), (0, 1, 0), (0, -1, 0), (0, 0, 1), (0, 0, -1)],
        [(0, 2, 4), (2, 1, 4), (1, 3, 4), (3, 0, 4), (2, 0, 5), (1, 2, 5), (3, 1, 5), (0, 3, 5)])
n = 5
grid_v = [(i, j, 0.3 * math.sin(i) * math.cos(j)) for j in range(n) for i in range(n)]
grid_f = []
for j in range(n - 1):
    for i in range(n - 1):
        a = j * n + i
        grid_f += [(a, a + 1, a + n + 1), (a, a + n + 1, a + n)]
fan_v = [(0, 0, 0.3)] + [(math.cos(2 * math.pi * k / 20), math.sin(2 * math.pi * k / 20), 0) for k in range(20)]
fan_f = [(0, 1 + k, 1 + (k + 1) % 20) for k in range(20)]
meshes = {"tet": tet, "octa": octa, "grid": (grid_v, grid_f), "fan": (fan_v, fan_f)}
for name, (v, f) in meshes.items():
    for core in range(4):
        for given in (0, 4):
            data = encode(v, f, core | given, presmoothing=1.0 if given else 0.0)
            with open(os.path.join(out, f"{name}_core{core}_{'given' if given else 'auto'}"), "wb") as fh:
                fh.write(data)
print(f"{len(os.listdir(out))} seeds in {out}")
