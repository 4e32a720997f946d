"""Side by side: `mesh remesh` against two isotropic remeshers (Botsch and
Kobbelt 2004) on the same meshes and target edge length H (the input's mean
edge length), every output measured by this script with the same code.

Peers: gpytoolbox's `remesh_botsch` (10 iterations, projection on) and
MeshLab's isotropic explicit remeshing through pymeshlab (10 iterations,
absolute target length), both with their defaults otherwise.

    python -m venv /tmp/rp && /tmp/rp/bin/pip install gpytoolbox pymeshlab
    /tmp/rp/bin/python mesh-remesh/scripts/compare_remeshers.py \
        --mesh-bin target/release/mesh FILE...

Metrics: smallest angle, mean of each triangle's smallest angle, triangles
under 20 degrees, mean edge over H, edges within [0.5 H, 1.5 H], symmetric
Hausdorff distance over the bounding-box diagonal (sampled at vertices,
face centroids and midpoints between them and the corners, both ways),
faces whose normal points away from the nearest input face's, Euler
characteristic, boundary edges and wall time.
"""

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time

import gpytoolbox as gp
import numpy as np
import pymeshlab


def angles(V, F):
    T = V[F]
    out = []
    for k in range(3):
        a, b, c = T[:, k], T[:, (k + 1) % 3], T[:, (k + 2) % 3]
        x, y = b - a, c - a
        cos = (x * y).sum(1) / np.maximum(np.linalg.norm(x, axis=1) * np.linalg.norm(y, axis=1), 1e-300)
        out.append(np.degrees(np.arccos(np.clip(cos, -1, 1))))
    return np.array(out).T


def edges(F):
    E = np.sort(np.concatenate([F[:, [0, 1]], F[:, [1, 2]], F[:, [2, 0]]]), axis=1)
    uniq, counts = np.unique(E, axis=0, return_counts=True)
    return uniq, counts


def samples(V, F):
    T = V[F]
    g = T.mean(1)
    return np.concatenate([V, g, 0.5 * (g + T[:, 0]), 0.5 * (g + T[:, 1]), 0.5 * (g + T[:, 2])])


def quality(V0, F0, V, F, h):
    A = angles(V, F).min(1)
    E, counts = edges(F)
    L = np.linalg.norm(V[E[:, 0]] - V[E[:, 1]], axis=1)
    diag = np.linalg.norm(V0.max(0) - V0.min(0))
    d_out, _, _ = gp.squared_distance(samples(V, F), V0, F0, use_cpp=True, use_aabb=True)
    d_in, _, _ = gp.squared_distance(samples(V0, F0), V, F, use_cpp=True, use_aabb=True)
    C = V[F].mean(1)
    _, fi, _ = gp.squared_distance(C, V0, F0, use_cpp=True, use_aabb=True)
    N0 = np.cross(V0[F0[:, 1]] - V0[F0[:, 0]], V0[F0[:, 2]] - V0[F0[:, 0]])
    N = np.cross(V[F[:, 1]] - V[F[:, 0]], V[F[:, 2]] - V[F[:, 0]])
    used = np.unique(F)
    return {
        "V": int(len(used)),
        "F": int(len(F)),
        "min_angle": float(A.min()),
        "mean_min_angle": float(A.mean()),
        "below_20": float((A < 20).mean()),
        "mean_edge_over_h": float(L.mean() / h),
        "within_half": float(((L >= 0.5 * h) & (L <= 1.5 * h)).mean()),
        "hausdorff": float(np.sqrt(max(d_out.max(), d_in.max())) / diag),
        "flipped": int(((N0[fi.astype(int)] * N).sum(1) < 0).sum()),
        "chi": int(len(used) - len(E) + len(F)),
        "boundary_edges": int((counts == 1).sum()),
        "nonmanifold_edges": int((counts > 2).sum()),
    }


def ours(mesh_bin, path, h, out):
    t = time.perf_counter()
    r = subprocess.run([mesh_bin, "remesh", path, "--edge-length", repr(h), "--out", out, "--no-hausdorff", "--force"],
                       capture_output=True, text=True)
    dt = time.perf_counter() - t
    if r.returncode != 0:
        raise RuntimeError(r.stderr.strip())
    ms = pymeshlab.MeshSet()
    ms.load_new_mesh(out)
    m = ms.current_mesh()
    return m.vertex_matrix(), m.face_matrix(), dt


def botsch(V, F, h):
    t = time.perf_counter()
    W, G = gp.remesh_botsch(V.astype(np.float64), F.astype(np.int32), i=10, h=h)
    return W, G, time.perf_counter() - t


def meshlab(path, h):
    ms = pymeshlab.MeshSet()
    ms.load_new_mesh(path)
    t = time.perf_counter()
    ms.meshing_isotropic_explicit_remeshing(iterations=10, targetlen=pymeshlab.PureValue(h))
    dt = time.perf_counter() - t
    m = ms.current_mesh()
    return m.vertex_matrix(), m.face_matrix(), dt


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("files", nargs="+")
    ap.add_argument("--mesh-bin", default="target/release/mesh")
    ap.add_argument("--json")
    args = ap.parse_args()
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for path in args.files:
            # Every tool gets the same input: the file cleaned by `mesh clean --manifold`.
            clean = os.path.join(tmp, "input.ply")
            subprocess.run([args.mesh_bin, "clean", path, clean, "--manifold", "--force"], check=True,
                           capture_output=True)
            ms = pymeshlab.MeshSet()
            ms.load_new_mesh(clean)
            V0, F0 = ms.current_mesh().vertex_matrix(), ms.current_mesh().face_matrix()
            E, _ = edges(F0)
            h = float(np.linalg.norm(V0[E[:, 0]] - V0[E[:, 1]], axis=1).mean())
            for name, run in [
                ("mesh remesh", lambda: ours(args.mesh_bin, clean, h, os.path.join(tmp, "ours.ply"))),
                ("gpytoolbox remesh_botsch", lambda: botsch(V0, F0, h)),
                ("MeshLab isotropic", lambda: meshlab(clean, h)),
            ]:
                try:
                    V, F, dt = run()
                    q = quality(V0, F0, V, F, h)
                    q["seconds"] = dt
                except Exception as e:  # a peer failing is a row, not a crash
                    q = {"error": str(e)[:200]}
                q.update({"mesh": os.path.basename(path), "tool": name, "input_V": len(V0), "input_chi": int(
                    len(np.unique(F0)) - len(E) + len(F0))})
                rows.append(q)
                print(json.dumps(q), flush=True)
    if args.json:
        with open(args.json, "w") as f:
            json.dump(rows, f, indent=1)
    print()
    print("| mesh | tool | V | min angle | mean min angle | < 20 deg | mean edge / H | in [0.5H, 1.5H] | Hausdorff / diag | flipped | chi (input) | s |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|")
    for q in rows:
        if "error" in q:
            print(f"| {q['mesh']} | {q['tool']} | error: {q['error']} |")
            continue
        print(f"| {q['mesh']} | {q['tool']} | {q['V']} | {q['min_angle']:.1f} | {q['mean_min_angle']:.1f} | "
              f"{100 * q['below_20']:.2f}% | {q['mean_edge_over_h']:.2f} | {100 * q['within_half']:.1f}% | "
              f"{q['hausdorff']:.1e} | {q['flipped']} | {q['chi']} ({q['input_chi']}) | {q['seconds']:.2f} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
