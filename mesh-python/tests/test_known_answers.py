"""Every function on shapes with known answers.

Tolerances: the icosphere of level 4 has mean edge length h = 0.075 r. An
inscribed polyhedron with edges h deviates from the sphere by O(h^2)
(sagitta h^2 / 8r), so areas, volumes and polyhedral distances carry a
relative error of order (h/r)^2 = 0.0057; that is the tolerance for them.
Estimators with a stated order or with an exactness property (Gauss-Bonnet,
linear precision of harmonic maps, rigidity of ARAP on a plane) are held to
their own bound, given next to each check.
"""

import math
import pickle

import numpy as np
import pytest
import scipy.sparse

import meshkit as mk
from conftest import great_circle, sphere_of_radius

H_OVER_R = 0.075  # mean edge length / radius of the level-4 icosphere
O_H2 = H_OVER_R**2


def test_shape_counts_and_info_of_the_sphere():
    for level in range(4):
        V, F = mk.shape("icosphere", level)
        assert V.shape == (10 * 4**level + 2, 3) and F.shape == (20 * 4**level, 3)
        assert V.dtype == np.float64 and F.dtype == np.int64
    r = 2.0
    V, F = sphere_of_radius(r)
    i = mk.info(V, F)
    assert (i["euler_characteristic"], i["genus"], i["components"], i["boundary_loops"]) == (2, 0, 1, 0)
    assert i["manifold"] and i["edges"] == 3 * len(F) // 2
    assert i["mean_edge_length"] / r == pytest.approx(H_OVER_R, rel=0.05)
    assert i["area"] == pytest.approx(4 * math.pi * r**2, rel=O_H2)
    assert i["volume"] == pytest.approx(4 / 3 * math.pi * r**3, rel=O_H2)
    assert i["bbox_max"] == pytest.approx([r, r, r], rel=0.01)


def test_info_of_a_torus_and_a_disk():
    t = mk.info(*mk.shape("torus", 8))
    assert (t["euler_characteristic"], t["genus"], t["boundary_loops"]) == (0, 1, 0)
    d = mk.info(*mk.shape("disk", 6))
    assert (d["euler_characteristic"], d["genus"], d["boundary_loops"], d["volume"]) == (1, 0, 1, None)


def test_cotan_laplacian_is_psd_symmetric_with_zero_row_sums(sphere):
    V, F = sphere
    L = mk.cotan_laplacian(V, F)
    assert isinstance(L, scipy.sparse.csr_matrix) and L.shape == (len(V), len(V))
    assert abs(L - L.T).max() < 1e-12
    assert np.abs(L @ np.ones(len(V))).max() < 1e-12
    x = np.random.default_rng(1).standard_normal((len(V), 8))
    assert (np.einsum("ij,ij->j", x, L @ x) > 0).all()  # positive semi-definite convention
    assert (L.diagonal() > 0).all()
    # L x = 2 H n A (eq. 2.26): on the unit sphere (L V)_i / A_i = 2 V_i, O(h^2).
    A = mk.lumped_mass(V, F)
    assert np.abs((L @ V) / A[:, None] - 2 * V).max() < 2 * O_H2


def test_laplacian_of_a_linear_function_vanishes_inside_a_plane():
    V, F = mk.shape("grid", 8)  # planar unit square
    L = mk.cotan_laplacian(V, F)
    f = 3 * V[:, 0] - 2 * V[:, 1] + 1
    inside = (V[:, 0] > 1e-9) & (V[:, 0] < 1 - 1e-9) & (V[:, 1] > 1e-9) & (V[:, 1] < 1 - 1e-9)
    assert np.abs((L @ f)[inside]).max() < 1e-12  # linear precision of the cotangent weights


def test_gradient_divergence_and_the_laplacian(sphere):
    V, F = sphere
    G, D, L = mk.gradient(V, F), mk.divergence(V, F), mk.cotan_laplacian(V, F)
    assert G.shape == (3 * len(F), len(V)) and D.shape == (len(V), 3 * len(F))
    assert abs(D @ G - L).max() < 1e-10
    Vg, Fg = mk.shape("grid", 4)
    g = (mk.gradient(Vg, Fg) @ (2 * Vg[:, 0] + 5 * Vg[:, 1])).reshape(-1, 3)
    assert np.abs(g - [2, 5, 0]).max() < 1e-12  # exact for linear functions


def test_mass_matrices_sum_to_the_area(sphere):
    V, F = sphere
    area = mk.face_areas(V, F).sum()
    assert area == pytest.approx(mk.info(V, F)["area"], rel=1e-12)
    for kind in ("voronoi", "barycentric", "galerkin"):
        M = mk.mass_matrix(V, F, kind)
        assert M.sum() == pytest.approx(area, rel=1e-12)
        assert mk.lumped_mass(V, F, kind).sum() == pytest.approx(area, rel=1e-12)
    assert mk.mass_matrix(V, F, "voronoi").nnz == len(V)
    assert mk.mass_matrix(V, F, "galerkin").nnz == len(V) + 2 * mk.info(V, F)["edges"]


def test_intrinsic_delaunay_laplacian(data_dir):
    V, F = mk.shape("icosphere", 3)  # already Delaunay: equals the cotangent Laplacian
    L, M = mk.intrinsic_delaunay_laplacian(V, F, mollify=0.0)
    assert abs(L - mk.cotan_laplacian(V, F)).max() < 1e-10
    assert M.diagonal().sum() == pytest.approx(mk.face_areas(V, F).sum(), rel=1e-12)
    # Zero-area faces: finite, non-negative weights on the interior edges.
    V, F = mk.read(data_dir / "cgal_degtri_sliding.off")
    L, M = mk.intrinsic_delaunay_laplacian(V, F)
    assert np.isfinite(L.data).all() and np.abs(L @ np.ones(len(V))).max() < 1e-12


def test_normals_of_the_sphere(sphere):
    V, F = sphere
    for w in ("area", "angle", "uniform", "max"):
        n = mk.vertex_normals(V, F, w)
        assert np.abs(np.linalg.norm(n, axis=1) - 1).max() < 1e-12
        assert np.abs(n - V).max() < 2 * O_H2  # the radial direction, O(h^2)
    assert np.abs(mk.vertex_normals(V, F, "max") - V).max() < 1e-10  # Max 1999: exact on a sphere
    fn = mk.face_normals(V, F)
    assert (np.einsum("ij,ij->i", fn, V[F].mean(axis=1)) > 0).all()


def test_curvature_of_a_sphere_of_radius_two():
    r = 2.0
    V, F = sphere_of_radius(r)
    K = mk.gaussian_curvature(V, F)
    assert np.abs(K * r**2 - 1).max() < O_H2  # angle defect / mixed area, O(h^2) on a sphere
    Kint = mk.gaussian_curvature(V, F, integrated=True)
    assert Kint.sum() == pytest.approx(4 * math.pi, abs=1e-10)  # Gauss-Bonnet, exact
    H = mk.mean_curvature(V, F)
    assert np.abs(H * r - 1).max() < O_H2
    assert mk.mean_curvature(V, F, integrated=True) == pytest.approx(H * mk.lumped_mass(V, F), rel=1e-12)
    normal = V / r
    for method, tol in (("fit", 1e-3), ("quadric", 1e-2), ("rusinkiewicz", 1e-10), ("normal-cycle", 0.05)):
        k1, k2, d1, d2 = mk.principal_curvature(V, F, method)
        assert (k1 >= k2).all()
        assert np.abs(k1 * r - 1).max() < tol and np.abs(k2 * r - 1).max() < tol, method
        # Unit, orthogonal, tangent, d1 x d2 along the outward normal.
        assert np.abs(np.linalg.norm(d1, axis=1) - 1).max() < 1e-10
        assert np.abs(np.einsum("ij,ij->i", d1, d2)).max() < 1e-10
        assert (np.einsum("ij,ij->i", np.cross(d1, d2), normal) > 0.99).all()


def test_curvature_of_a_torus():
    # R = 2, r = 0.5: k = 1/r around the tube, cos v / (R + r cos v) along it.
    V, F = mk.shape("torus", 32)
    rho = np.hypot(V[:, 0], V[:, 1])
    cos_v = (rho - 2.0) / 0.5
    k1, k2, _, _ = mk.principal_curvature(V, F)
    assert np.abs(k1 - 2.0).max() < 1e-2
    assert np.abs(k2 - cos_v / rho).max() < 1e-2
    K = mk.gaussian_curvature(V, F)
    assert np.abs(K - cos_v / (0.5 * rho)).max() < 0.05
    assert mk.gaussian_curvature(V, F, integrated=True).sum() == pytest.approx(0, abs=1e-10)


def test_geodesic_distances_on_the_unit_sphere(sphere):
    V, F = sphere
    truth = great_circle(V, 0)
    fmm = mk.fmm_distance(V, F, 0)
    assert fmm[0] == 0 and np.abs(fmm - truth).max() < 2e-3  # the crate's documented bound
    heat = mk.HeatSolver(V, F)
    assert np.abs(heat.distance(0) - truth).max() < 0.05  # heat method, t = h^2
    assert np.array_equal(heat.compute_distance(0), heat.distance([0]))
    exact = mk.exact_distance(V, F, [0])
    assert np.abs(exact - truth).max() < O_H2 * math.pi  # polyhedral vs. spherical, O(h^2)
    graph, pred = mk.dijkstra(V, F, 0)
    assert (graph >= exact - 1e-12).all()  # paths along edges are never shorter
    assert pred[0] == -1 and (pred[1:] >= 0).all()
    assert np.array_equal(mk.FastMarchingSolver(V, F).distance(0), fmm)
    both = heat.distance([0, 1000])
    assert both[0] == both[1000] == 0
    d, status = heat.distance_and_status(0)
    assert np.array_equal(d, heat.distance(0)) and (status == 0).all()


def test_unreachable_vertices_are_infinite():
    V = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [5, 0, 0], [6, 0, 0], [5, 1, 0.0]])
    F = np.array([[0, 1, 2], [3, 4, 5]], dtype=np.int32)
    for d in (mk.fmm_distance(V, F, [0]), mk.HeatSolver(V, F).distance([0]), mk.dijkstra(V, F, [0])[0],
              mk.exact_distance(V, F, [0])):
        assert d[0] == 0 and np.isfinite(d[:3]).all() and (d[3:] == np.inf).all()


def test_trace_path_follows_a_great_circle(sphere):
    V, F = sphere
    d = mk.fmm_distance(V, F, [0])
    points, length, source = mk.trace_path(V, F, d, [0], start=1000)
    assert source == 0 and np.allclose(points[0], V[1000]) and np.allclose(points[-1], V[0])
    assert length == pytest.approx(great_circle(V, 0)[1000], rel=0.01)
    f = 17
    _, length2, _ = mk.trace_path(V, F, d, [0], face=f, bary=[1 / 3, 1 / 3, 1 / 3])
    assert length2 == pytest.approx(great_circle(V, 0)[F[f]].mean(), rel=0.02)


def test_farthest_point_sampling(sphere):
    V, F = sphere
    samples, region, dist = mk.farthest_point_sampling(V, F, 12, start=0)
    assert samples[0] == 0 and len(set(samples)) == 12
    assert region.min() == 0 and region.max() == 11 and (dist[samples] == 0).all()
    assert np.array_equal(region[samples], np.arange(12))


def _similarity_residual(uv, xy):
    """Largest distance after the best similarity (rotation, scale, shift) uv -> xy, and the scale."""
    a, b = uv - uv.mean(0), xy - xy.mean(0)
    u, s, vt = np.linalg.svd(a.T @ b)
    rot = u @ vt
    scale = s.sum() / (a**2).sum()
    return np.abs(scale * a @ rot - b).max(), scale


def test_every_parameterization_method_on_a_planar_disk():
    V, F = mk.shape("disk", 10)  # unit disk in the plane z = 0, irregular triangles
    boundary = np.where(np.abs(np.hypot(V[:, 0], V[:, 1]) - 1) < 1e-12)[0]
    target = 0.5 + 0.5 * V[:, :2]
    for method in mk.PARAMETERIZATION_METHODS:
        free = method in ("lscm", "arap")
        fixed = None if free else (boundary, target[boundary])
        uv, report = mk.parameterize(V, F, method, fixed=fixed, return_report=True)
        assert uv.shape == (len(V), 2) and report["bijective"] and report["flipped_faces"] == 0, method
        if method == "tutte":
            continue  # uniform weights do not reproduce planar meshes
        if free:
            residual, scale = _similarity_residual(uv, V[:, :2])
            assert residual < 1e-8, method  # conformal / rigid maps of a plane are similarities
            if method == "arap":
                assert scale == pytest.approx(1, abs=1e-8)
        else:
            assert np.abs(uv - target).max() < 1e-10, method  # linear precision of the weights
    uv = mk.parameterize(V, F, boundary="square")
    assert uv.min() >= -1e-12 and uv.max() <= 1 + 1e-12


def test_parameterize_cut_handles_closed_meshes():
    V, F = mk.shape("icosphere", 2)
    Vc, Fc, uv, origin, summary = mk.parameterize_cut(V, F, "mean-value")
    assert mk.info(Vc, Fc)["boundary_loops"] == 1 and len(uv) == len(Vc)
    assert np.array_equal(Vc, V[origin]) and summary["flipped_faces"] == 0


def test_eigenpairs_of_the_unit_sphere(sphere):
    V, F = sphere
    evals, evecs = mk.eigenpairs(V, F, 9)
    assert evals.shape == (9,) and evecs.shape == (len(V), 9)
    assert evals[0] == 0
    # l (l + 1), 2 l + 1 times; the error of linear elements grows like
    # lambda^2 h^2: measured 1e-7 for l = 1 and 0.14% for l = 2.
    assert np.abs(evals[1:4] - 2).max() < 1e-3 and np.abs(evals[4:9] - 6).max() < 0.01 * 6
    M = mk.mass_matrix(V, F)
    assert np.abs(evecs.T @ M @ evecs - np.eye(9)).max() < 1e-8
    L = mk.cotan_laplacian(V, F)
    assert np.abs(L @ evecs - (M @ evecs) * evals).max() < 1e-8


def test_heat_kernel_signature_of_the_unit_sphere(sphere):
    # HKS(x, t) = sum_l (2 l + 1) / (4 pi) exp(-l (l + 1) t) on the unit sphere
    # (every point alike); 100 pairs hold l <= 9, and the terms left out are
    # below exp(-110 t). Measured error 0.13% at t = 1, 0.8% at t = 0.1.
    V, F = sphere
    times = [0.1, 1.0]
    hks, t = mk.heat_kernel_signature(V, F, k=100, times=times)
    assert hks.shape == (len(V), 2) and np.array_equal(t, times)
    for j, tj in enumerate(times):
        truth = sum((2 * l + 1) / (4 * math.pi) * math.exp(-l * (l + 1) * tj) for l in range(30))
        assert np.abs(hks[:, j] / truth - 1).max() < 0.02
    hks5, t5 = mk.heat_kernel_signature(V, F, k=50)
    assert hks5.shape == (len(V), 5) and (np.diff(t5) > 0).all()


def test_harmonics_transforms_filter_and_compression(sphere):
    V, F = sphere
    mh = mk.Harmonics(V, F, 16)
    assert len(mh) == 16 and mh.basis.shape == (len(V), 16)
    f = mh.basis[:, 3] * 2.5 - mh.basis[:, 0]
    c = mh.forward(f)
    assert np.abs(c - np.eye(16)[3] * 2.5 + np.eye(16)[0]).max() < 1e-8
    assert np.abs(mh.inverse(c) - f).max() < 1e-8
    # The first harmonic is constant: keeping it alone collapses the sphere to its centre.
    p = mh.filter("keep", keep=1)
    assert np.abs(p).max() < 1e-8
    (Vc, Fc), err = mh.compress(16)
    (Vd, Fd), err4 = mh.compress(4)
    # More coefficients never do worse; on the sphere the l = 2, 3 harmonics
    # add nothing to the coordinates, so the two errors agree to rounding.
    assert err["rms"] <= err4["rms"] * (1 + 1e-9) and np.array_equal(Fc, F)
    # A sphere is spanned by the constant and the three l = 1 harmonics.
    assert err4["max"] < 1e-3
    low = mh.filter("low-pass", cutoff=2.0, order=4)
    assert low.shape == V.shape
    hks, _ = mh.heat_kernel_signature(times=[1.0])
    assert hks.shape == (len(V), 1)
    back = pickle.loads(pickle.dumps(mh))
    assert np.array_equal(back.eigenvalues, mh.eigenvalues)


def test_loop_and_midpoint_subdivision():
    V, F = mk.shape("icosphere", 0)
    V2, F2 = mk.loop_subdivide(V, F, 2)
    assert V2.shape == (162, 3) and F2.shape == (320, 3)
    assert mk.info(V2, F2)["euler_characteristic"] == 2
    # Midpoint subdivision inserts the midpoints of the edges, keeps the rest.
    Vm, Fm = mk.subdivide(V, F, 1, "midpoint")
    assert np.array_equal(Vm[:12], V)
    edges = {tuple(sorted((a, b))) for t in F for a, b in ((t[0], t[1]), (t[1], t[2]), (t[2], t[0]))}
    mids = np.array(sorted(tuple((V[a] + V[b]) / 2) for a, b in edges))
    assert np.abs(np.array(sorted(map(tuple, Vm[12:]))) - mids).max() < 1e-15
    # Butterfly interpolates: the old vertices stay.
    Vb, _ = mk.subdivide(V, F, 1, "butterfly")
    assert np.array_equal(Vb[:12], V)


def test_wavelet_analysis_synthesis_and_compression():
    V, F = mk.shape("icosphere", 3)
    mr = mk.wavelet_analysis(V, F)
    assert mr.levels == 3 and mr.base_positions.shape == (12, 3)
    Vs, Fs = mk.wavelet_synthesis(mr)
    assert np.abs(Vs - V).max() < 1e-12 and np.array_equal(Fs, F)
    assert [s["count"] for s in mr.statistics()] == [30, 120, 480]
    assert mr.coefficients(2).shape == (480, 3)
    Vb, Fb = mr.level(0)
    assert Vb.shape == (12, 3) and Fb.shape == (20, 3)
    (Vc, _), err = mr.compress(0.2)
    assert err["rms_error"] < 1e-2 and err["kept_coefficients"] < err["total_coefficients"]
    (Vall, _), err_all = mk.wavelet_compress(V, F, 1.0)
    assert err_all["max_error"] < 1e-12
    # Editing: zero details give the smooth (midpoint-subdivided) base.
    for j in range(mr.levels):
        mr.set_coefficients(j, np.zeros_like(mr.coefficients(j)))
    flat, _ = mr.synthesize()
    assert np.abs(np.linalg.norm(flat, axis=1) - 1).max() > 0.05
    back = pickle.loads(pickle.dumps(mr))
    assert np.array_equal(back.synthesize()[0], flat)


def test_topology_edges_boundary_loops_components():
    V, F = mk.shape("icosphere", 1)
    E = mk.edges(V, F)
    assert E.shape == (120, 2) and (E[:, 0] < E[:, 1]).all() and len({tuple(e) for e in E}) == 120
    assert mk.boundary_loops(V, F) == []
    Vd, Fd = mk.shape("disk", 4)
    (loop,) = mk.boundary_loops(Vd, Fd)
    assert np.abs(np.hypot(Vd[loop, 0], Vd[loop, 1]) - 1).max() < 1e-12 and len(loop) == 24
    # Two disjoint copies and an unused vertex.
    V2 = np.vstack([V, V + 3, [[9, 9, 9]]])
    F2 = np.vstack([F, F + len(V)])
    labels = mk.connected_components(V2, F2)
    assert set(labels[: len(V)]) == {0} and set(labels[len(V) : -1]) == {1} and labels[-1] == -1


def test_clean_repairs_what_info_counts():
    V, F = mk.shape("icosphere", 2)
    # Split the mesh into a triangle soup (3 vertices per face), duplicate a
    # face, flip another, add an unused vertex: clean restores the sphere.
    soup_V = V[F.ravel()]
    soup_F = np.arange(3 * len(F)).reshape(-1, 3)
    soup_F = np.vstack([soup_F, soup_F[:1]])
    soup_F[5] = soup_F[5, ::-1]
    soup_V = np.vstack([soup_V, [[7, 7, 7]]])
    i = mk.info(soup_V, soup_F)
    assert i["components"] > 1 and i["duplicate_faces"] == 1 and i["unreferenced_vertices"] == 1
    V2, F2, report = mk.clean(soup_V, soup_F)
    assert (len(V2), len(F2)) == (len(V), len(F))
    assert report["duplicate_faces"] == 1 and report["flipped_faces"] == 1 and report["unreferenced_vertices"] == 1
    j = mk.info(V2, F2)
    assert (j["components"], j["euler_characteristic"], j["manifold"], j["inconsistent_edges"]) == (1, 2, True, 0)
    assert j["volume"] > 0  # faces outward


def test_remesh_keeps_the_sphere_and_its_topology():
    V, F = mk.shape("icosphere", 4)
    (W, G), report = mk.remesh(V, F, edge_length=0.15, return_report=True)
    # Vertices on the input, which lies within its own sagitta of the unit sphere.
    assert np.all(np.abs(np.linalg.norm(W, axis=1) - 1.0) < H_OVER_R**2 / 2)
    assert report["output_topology"]["euler_characteristic"] == 2 and not report["topology_changed"]
    assert report["edges_within_half"] > 0.95 and report["mean_min_angle_degrees"] > 45
    assert report["normal_disagreements"] == 0
    assert G.dtype == np.int64 and G.max() < len(W)
    with pytest.raises(mk.InvalidOptionError):
        mk.remesh(V, F, edge_length=-1.0)
    with pytest.raises(mk.InvalidOptionError):
        mk.remesh(V, F, edge_length=1e-6, max_vertices=1000)
    with pytest.raises(mk.InvalidOptionError):
        mk.remesh(V, F, smoothing_rounds=101)
