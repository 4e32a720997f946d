"""Wall time of meshkit against libigl and potpourri3d on the same arrays,
and the overhead of the binding. Prints markdown tables.

    python mesh-python/bench/bench.py [--data DIR] [--repeat N]

Meshes: the shared bunny (npm_bunny.obj, 1839 vertices) Loop-subdivided
three times (117,570 vertices), and the shared mushroom (a disk, for the
parameterizations) Loop-subdivided three times (147k vertices). Each figure
is the median of N runs (default 5) after one warm-up run. meshkit runs its
parallel loops on every core (rayon); libigl and potpourri3d mostly run on
one.

Binding overhead: `meshkit._meshkit.loop_subdivide_timed` returns the
seconds the Rust subdivision took inside the call; the overhead is the
Python wall time of the whole call (argument checks, copying V and F into
the mesh, validating it, releasing the GIL, handing the result to numpy)
minus that.
"""

import argparse
import importlib.metadata
import os
import pathlib
import statistics
import sys
import time

import numpy as np

import meshkit as mk

try:
    import igl
except ImportError:
    igl = None
try:
    import potpourri3d as pp3d
except ImportError:
    pp3d = None


def timed(fn, repeat):
    fn()  # warm-up (page faults, lazy imports, caches)
    times = []
    for _ in range(repeat):
        t = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t)
    return statistics.median(times)


def fmt(seconds):
    return "-" if seconds is None else f"{seconds * 1e3:.1f}"


def main():
    here = pathlib.Path(__file__).resolve()
    default_data = os.environ.get("MESH_SHARED_DATA") or str(here.parents[3] / "shared" / "data")
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--data", default=default_data, help="the shared meshes (default: MESH_SHARED_DATA or ../shared/data)")
    ap.add_argument("--repeat", type=int, default=5)
    args = ap.parse_args()
    data = pathlib.Path(args.data)
    if not (data / "npm_bunny.obj").is_file():
        sys.exit(f"bench: no shared meshes at {data} (pass --data DIR or set MESH_SHARED_DATA)")
    r = args.repeat

    Vb, Fb = mk.read(data / "npm_bunny.obj")
    V, F = mk.loop_subdivide(Vb, Fb, 3)
    Vd, Fd = mk.loop_subdivide(*mk.read(data / "cgal_mushroom.off"), 3)
    def version(dist, module):
        if module is None:
            return "absent"
        try:
            return importlib.metadata.version(dist)
        except importlib.metadata.PackageNotFoundError:
            return "present"

    print(f"meshkit {mk.__version__}; libigl {version('libigl', igl)}; potpourri3d {version('potpourri3d', pp3d)}; "
          f"numpy {np.__version__}; {os.cpu_count()} cores")
    print(f"bunny x3: {len(V)} vertices, {len(F)} faces; mushroom x3: {len(Vd)} vertices, {len(Fd)} faces\n")

    rows = []

    def row(name, ours, libigl=None, potpourri=None):
        peers = [t for t in (libigl, potpourri) if t is not None]
        speedup = f"{min(peers) / ours:.1f}x" if peers else "-"
        rows.append((name, ours, libigl, potpourri, speedup))
        print(f"  {name}: {fmt(ours)} ms", file=sys.stderr)

    has_igl, has_pp = igl is not None, pp3d is not None
    row("cotan Laplacian", timed(lambda: mk.cotan_laplacian(V, F), r),
        timed(lambda: igl.cotmatrix(V, F), r) if has_igl else None,
        timed(lambda: pp3d.cotan_laplacian(V, F), r) if has_pp else None)
    row("mass matrix (voronoi)", timed(lambda: mk.mass_matrix(V, F), r),
        timed(lambda: igl.massmatrix(V, F, igl.MASSMATRIX_TYPE_VORONOI), r) if has_igl else None)
    row("vertex areas (barycentric)", timed(lambda: mk.lumped_mass(V, F, "barycentric"), r),
        None, timed(lambda: pp3d.vertex_areas(V, F), r) if has_pp else None)
    row("vertex normals (area)", timed(lambda: mk.vertex_normals(V, F), r),
        timed(lambda: igl.per_vertex_normals(V, F, igl.PER_VERTEX_NORMALS_WEIGHTING_TYPE_AREA), r) if has_igl else None)
    row("Gaussian curvature (angle defect)", timed(lambda: mk.gaussian_curvature(V, F, integrated=True), r),
        timed(lambda: igl.gaussian_curvature(V, F), r) if has_igl else None)
    row("principal curvature (quadric; libigl radius 2)", timed(lambda: mk.principal_curvature(V, F, "quadric"), r),
        timed(lambda: igl.principal_curvature(V, F, radius=2), r) if has_igl else None)
    row("principal curvature (ours: fit, 2-ring quartic)", timed(lambda: mk.principal_curvature(V, F), r))
    row("heat method: prepare + 1 query", timed(lambda: mk.HeatSolver(V, F).distance([0]), r), None,
        timed(lambda: pp3d.MeshHeatMethodDistanceSolver(V, F).compute_distance(0), r) if has_pp else None)
    hs = mk.HeatSolver(V, F)
    ps = pp3d.MeshHeatMethodDistanceSolver(V, F) if has_pp else None
    row("heat method: 1 query (prepared)", timed(lambda: hs.distance([123]), r), None,
        timed(lambda: ps.compute_distance(123), r) if has_pp else None)
    row("Fast Marching", timed(lambda: mk.fmm_distance(V, F, [0]), r))
    Ve, Fe = mk.loop_subdivide(Vb, Fb, 1)
    src = np.array([0])
    none = np.array([], dtype=np.int64)
    row(f"exact geodesics (bunny x1, {len(Ve)} vertices)", timed(lambda: mk.exact_distance(Ve, Fe, [0]), r),
        timed(lambda: igl.exact_geodesic(Ve, Fe, src, none, np.arange(len(Ve)), none), r) if has_igl else None)
    if has_igl:
        import scipy.sparse.linalg

        def scipy_eigs():
            L = -igl.cotmatrix(V, F)
            M = igl.massmatrix(V, F, igl.MASSMATRIX_TYPE_VORONOI)
            return scipy.sparse.linalg.eigsh(L.tocsc(), 20, M.tocsc(), sigma=-1e-8, which="LM")

        eig_peer = timed(scipy_eigs, max(1, r // 2))
    else:
        eig_peer = None
    row("20 eigenpairs (libigl operators + scipy eigsh shift-invert)", timed(lambda: mk.eigenpairs(V, F, 20), max(1, r // 2)),
        eig_peer)
    row("heat kernel signature (k = 100, 5 times; bunny x1)", timed(lambda: mk.heat_kernel_signature(Ve, Fe, k=100), max(1, r // 2)))
    row("Loop subdivision x3 (bunny, 1839 -> 117570 vertices)", timed(lambda: mk.loop_subdivide(Vb, Fb, 3), r),
        timed(lambda: igl.loop(Vb, Fb, 3), r) if has_igl else None)
    row("midpoint subdivision x3 (bunny)", timed(lambda: mk.subdivide(Vb, Fb, 3, "midpoint"), r),
        timed(lambda: igl.upsample(Vb, Fb, 3), r) if has_igl else None)
    if has_igl:
        b = igl.boundary_loop(Fd)
        bc = igl.map_vertices_to_circle(Vd, b.astype(np.int32))
        row("harmonic parameterization (mushroom x3, given boundary)",
            timed(lambda: mk.parameterize(Vd, Fd, "harmonic", fixed=(b, bc)), r), timed(lambda: igl.harmonic(Vd, Fd, b, bc, 1), r))
        pins = np.array([b[0], b[len(b) // 2]])
        pin_uv = np.array([[0.0, 0.0], [1.0, 0.0]])
        row("LSCM (mushroom x3, 2 pins)", timed(lambda: mk.parameterize(Vd, Fd, "lscm", fixed=(pins, pin_uv)), r),
            timed(lambda: igl.lscm(Vd, Fd, pins, pin_uv), r))
    row("ARAP parameterization (mushroom x3, 20 iterations)", timed(lambda: mk.parameterize(Vd, Fd, "arap"), max(1, r // 2)))
    tmp = pathlib.Path(os.environ.get("TMPDIR", "/tmp")) / f"meshkit-bench-{os.getpid()}.obj"
    try:
        mk.write(tmp, V, F)
        row("read OBJ (bunny x3)", timed(lambda: mk.read(tmp), r), timed(lambda: igl.read_triangle_mesh(str(tmp)), r) if has_igl else None,
            timed(lambda: pp3d.read_mesh(str(tmp)), r) if has_pp else None)
    finally:
        tmp.unlink(missing_ok=True)

    print("| operation (1e5-vertex meshes unless noted) | meshkit ms | libigl ms | potpourri3d ms | meshkit speed-up over the fastest peer |")
    print("|---|---:|---:|---:|---:|")
    for name, ours, li, pp, speedup in rows:
        print(f"| {name} | {fmt(ours)} | {fmt(li)} | {fmt(pp)} | {speedup} |")

    # Binding overhead: Python wall time vs the Rust subdivision timed inside.
    walls, inner = [], []
    mk._native.loop_subdivide_timed(Vb, Fb, 3)
    for _ in range(max(10, 4 * r)):
        t = time.perf_counter()
        _, seconds = mk._native.loop_subdivide_timed(Vb, Fb, 3)
        walls.append(time.perf_counter() - t)
        inner.append(seconds)
    wall, rust = statistics.median(walls), statistics.median(inner)
    public = timed(lambda: mk.loop_subdivide(Vb, Fb, 3), max(10, 4 * r))
    print()
    print("| binding overhead, `loop_subdivide(bunny, 3)` (117,570 vertices out) | ms |")
    print("|---|---:|")
    print(f"| Rust subdivision, timed inside the call | {rust * 1e3:.2f} |")
    print(f"| the native call from Python | {wall * 1e3:.2f} |")
    print(f"| `meshkit.loop_subdivide` (plus the Python argument checks) | {public * 1e3:.2f} |")
    print(f"| overhead of the native call | {(wall - rust) * 1e3:.2f} ({(wall / rust - 1) * 100:.1f}%) |")
    print(f"| overhead of the public function | {(public - rust) * 1e3:.2f} ({(public / rust - 1) * 100:.1f}%) |")


if __name__ == "__main__":
    main()
