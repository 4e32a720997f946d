#!/usr/bin/env python3
"""Heat-method distances of the peers (potpourri3d, libigl) and of this crate
against one reference field, on the connected component of the source.

    ~/.peers/bin/python scripts/compare_heat_peers.py MESH.off REFERENCE.txt [OURS.txt ...] [--source 0]

REFERENCE.txt and OURS.txt hold one distance per vertex, one per line, as
written by `examples/export_fields.rs` (`NAME.exact.txt`, `NAME.fmm-CurvedFront.txt`,
`NAME.heat.txt`). Prints, per method, the plateau fraction (vertices within 1%
of the method's own maximum), and the max and median of |d - reference|
relative to the largest reference distance, plus the precompute and solve
times (one run each, milliseconds).
"""
import argparse
import time

import igl
import numpy as np
import potpourri3d as pp3d
import scipy.sparse as sp
import scipy.sparse.csgraph as csg


def component_of(F, n, source):
    """Boolean mask of the vertices in the source's connected component."""
    e = np.concatenate([F[:, [0, 1]], F[:, [1, 2]], F[:, [2, 0]]])
    g = sp.coo_matrix((np.ones(len(e)), (e[:, 0], e[:, 1])), shape=(n, n))
    _, labels = csg.connected_components(g, directed=False)
    return labels == labels[source]


def stats(d, ref, mask):
    d, ref = d[mask], ref[mask]
    scale = ref.max()
    err = np.abs(d - ref) / scale
    top = d.max()
    plateau = np.mean(d > 0.99 * top)
    return plateau, err.max(), np.median(err), top, scale


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("mesh")
    ap.add_argument("reference")
    ap.add_argument("ours", nargs="*")
    ap.add_argument("--source", type=int, default=0)
    a = ap.parse_args()
    V, F = igl.read_triangle_mesh(a.mesh)
    F = F.astype(np.int64)
    ref = np.loadtxt(a.reference)
    mask = component_of(F, len(V), a.source) & np.isfinite(ref)
    rows = []

    def pp3d_heat():
        solver = pp3d.MeshHeatMethodDistanceSolver(V, F)
        return solver, lambda: solver.compute_distance(a.source)

    def igl_heat():
        data = igl.HeatGeodesicsData()
        igl.heat_geodesics_precompute(V, F, data)
        return data, lambda: np.asarray(igl.heat_geodesics_solve(data, np.array([a.source], np.int64)), float).ravel()

    for name, setup in [("potpourri3d 1.4.0", pp3d_heat), ("libigl 2.6.3", igl_heat)]:
        try:
            t0 = time.perf_counter()
            _, solve = setup()
            t1 = time.perf_counter()
            d = solve()
            t2 = time.perf_counter()
            rows.append((name, d, (t1 - t0) * 1e3, (t2 - t1) * 1e3))
        except Exception as e:  # a peer failing on a mesh is a result too
            print(f"{name}: error: {type(e).__name__}: {e}")

    for path in a.ours:
        rows.append((path, np.loadtxt(path), float("nan"), float("nan")))

    print(f"{a.mesh}: {len(V)} vertices, {mask.sum()} on the source's component, reference {a.reference}")
    print(f"{'method':40s} {'plateau':>8s} {'max err':>8s} {'median':>8s} {'max d':>10s} {'ref max':>10s} {'pre ms':>9s} {'solve ms':>9s}")
    for name, d, pre, solve in rows:
        if not np.all(np.isfinite(d[mask])):
            print(f"{name:40s} non-finite values on the component ({np.sum(~np.isfinite(d[mask]))})")
            d = np.where(np.isfinite(d), d, 0.0)
        p, mx, med, top, scale = stats(d, ref, mask)
        print(f"{name:40s} {100 * p:7.1f}% {100 * mx:7.2f}% {100 * med:7.3f}% {top:10.4f} {scale:10.4f} {pre:9.0f} {solve:9.0f}")


if __name__ == "__main__":
    main()
