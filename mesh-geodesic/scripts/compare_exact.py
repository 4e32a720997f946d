#!/usr/bin/env python3
"""Compares the fields written by `examples/export_fields.rs` with exact
polyhedral geodesic distances (MMP, pygeodesic) from vertex 0, relative to
the bounding-box diagonal (max / mean). `exact` is this crate's window
propagation; it is absent where it refused the mesh (zero-area faces).

    OPENBLAS_NUM_THREADS=1 ~/.peers/bin/python scripts/compare_exact.py DIR
"""
import glob, os, sys
import numpy as np
import igl
import pygeodesic.geodesic as geodesic

methods = ["exact", "fmm-CurvedFront", "fmm-PointSource", "fmm-PlaneWave", "heat", "dijkstra"]
print(f"{'mesh':16s} {'V':>6s} " + " ".join(f"{m:>22s}" for m in methods))
for off in sorted(glob.glob(os.path.join(sys.argv[1], "*.off"))):
    V, F = igl.read_triangle_mesh(off)
    exact, _ = geodesic.PyGeodesicAlgorithmExact(V, F.astype(np.int32)).geodesicDistances(np.array([0]), None)
    ok = np.isfinite(exact) & (exact < 1e10)
    diag = np.linalg.norm(V.max(0) - V.min(0))
    cells = []
    for m in methods:
        if not os.path.exists(off[:-4] + f".{m}.txt"):
            cells.append("-")
            continue
        e = np.abs(np.loadtxt(off[:-4] + f".{m}.txt")[ok] - exact[ok]) / diag
        cells.append(f"{e.max():9.1e} / {e.mean():8.1e}")
    print(f"{os.path.basename(off)[:-4]:16s} {len(V):6d} " + " ".join(f"{c:>22s}" for c in cells))
