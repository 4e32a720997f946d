#!/usr/bin/env python3
"""Writes the reference fixtures of `cargo xtask validate --only geodesic`:
exact polyhedral distances from vertex 0 by MMP (pygeodesic 0.1.11,
PyGeodesicAlgorithmExact, Kirsanov's implementation of Surazhsky et al.
2005) on each mesh given, at every `step`-th vertex (at most about 600 per
mesh), with the largest distance over all vertices in the header (the
comparison is relative to it).

    ~/.peers/bin/python scripts/exact_fixtures.py OUT_DIR MESH.off|obj ...

`icosphere6.off` is `mesh generate icosphere6.off --shape icosphere --res 6`
(coordinates round-trip, so it is `shapes::icosphere(6)` exactly).
"""
import os, sys
import numpy as np
import igl
import pygeodesic.geodesic as geodesic

out = sys.argv[1]
for path in sys.argv[2:]:
    V, F = igl.read_triangle_mesh(path)
    d, _ = geodesic.PyGeodesicAlgorithmExact(V, F.astype(np.int32)).geodesicDistances(np.array([0]), None)
    reachable = np.isfinite(d) & (d < 1e10)
    step = max(1, -(-len(V) // 600))
    name = os.path.splitext(os.path.basename(path))[0]
    with open(os.path.join(out, f"{name}_exact_v0.txt"), "w") as f:
        f.write(f"# pygeodesic 0.1.11 PyGeodesicAlgorithmExact (MMP) on {os.path.basename(path)} "
                f"({len(V)} vertices), source vertex 0; the vertices whose index is a multiple of {step}\n")
        f.write(f"# max {float(d[reachable].max())!r}\n")
        for i in range(0, len(V), step):
            f.write(f"{i} {float(d[i])!r}\n" if reachable[i] else f"{i} inf\n")
