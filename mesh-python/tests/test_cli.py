"""Results equal to the `mesh` command's on the shared meshes: the same
Rust functions behind both, so equal to rounding (the CLI writes doubles
in binary PLY and JSON numbers that round-trip)."""

import numpy as np
import pytest

import meshkit as mk
from conftest import SHARED

MESHES = sorted(SHARED)


@pytest.mark.parametrize("name", MESHES)
def test_info_file_equals_mesh_info_json(name, data_dir, cli):
    path = data_dir / name
    expected = cli("info", path, "--json")
    got = mk.info_file(path)
    assert got == expected
    truth = SHARED[name]
    assert (got["vertices"], got["faces"], got["euler_characteristic"]) == (truth["V"], truth["F"], truth["chi"])
    # info(V, F) has the same keys and measures; only what reading did is a file's.
    V, F = mk.read(path)
    arrays = mk.info(V, F)
    assert arrays.keys() == expected.keys()
    assert {k: v for k, v in arrays.items() if k not in ("attributes", "read")} == {
        k: v for k, v in expected.items() if k not in ("attributes", "read")
    }


@pytest.mark.parametrize("name", ["npm_bunny.obj", "cgal_holes.off", "cgal_fandisk.off"])
def test_curvature_equals_mesh_curvature(name, data_dir, cli, tmp_path):
    out = tmp_path / "c.ply"
    cli("curvature", data_dir / name, "--out", out)
    V, F, va, _, _ = mk.read_attributes(out)
    V0, F0 = mk.read(data_dir / name)
    assert np.array_equal(V, V0) and np.array_equal(F, F0)
    k1, k2, d1, d2 = mk.principal_curvature(V0, F0)
    ok = va["flag"] == 0  # the CLI zeroes flagged values
    assert ok.mean() > 0.9
    for ours, theirs in ((k1, "k1"), (k2, "k2"), (d1, "d1"), (d2, "d2")):
        assert np.abs(ours[ok] - va[theirs][ok]).max() < 1e-9 * (1 + np.abs(ours).max()), theirs
    ok = va["flag_discrete"] == 0
    assert np.abs(mk.gaussian_curvature(V0, F0)[ok] - va["gaussian_discrete"][ok]).max() < 1e-9
    assert np.abs(mk.mean_curvature(V0, F0)[ok] - va["mean_discrete"][ok]).max() < 1e-9
    assert np.abs(mk.gaussian_curvature(V0, F0, integrated=True)[ok] - va["gaussian_integrated"][ok]).max() < 1e-12


# Exact geodesics refuse zero-area faces: tested below.
GEODESIC_CASES = [
    (name, method)
    for name in ["npm_bunny.obj", "cgal_holes.off", "cgal_degtri_sliding.off"]
    for method in ["heat", "fmm", "dijkstra", "exact"]
    if not (method == "exact" and name == "cgal_degtri_sliding.off")
]


@pytest.mark.parametrize("name,method", GEODESIC_CASES)
def test_geodesic_equals_mesh_geodesic(name, method, data_dir, cli, tmp_path):
    out = tmp_path / "d.ply"
    cli("geodesic", data_dir / name, "--source", "0,3", "--method", method, "--out", out)
    _, _, va, _, _ = mk.read_attributes(out)
    V, F = mk.read(data_dir / name)
    ours = {
        "heat": lambda: mk.HeatSolver(V, F).distance([0, 3]),
        "fmm": lambda: mk.fmm_distance(V, F, [0, 3]),
        "dijkstra": lambda: mk.dijkstra(V, F, [0, 3])[0],
        "exact": lambda: mk.exact_distance(V, F, [0, 3]),
    }[method]()
    assert np.abs(ours - va["distance"]).max() < 1e-9 * ours.max()


def test_exact_geodesics_refuse_zero_area_faces(data_dir):
    V, F = mk.read(data_dir / "cgal_degtri_sliding.off")
    with pytest.raises(mk.MeshkitError, match="degenerate|zero-area"):
        mk.exact_distance(V, F, [0])


@pytest.mark.parametrize("name", ["npm_bunny.obj", "cgal_holes.off"])
def test_eigenpairs_and_hks_equal_mesh_spectral(name, data_dir, cli, tmp_path):
    V, F = mk.read(data_dir / name)
    expected = cli("spectral", data_dir / name, "--k", 12, "--json")
    evals, evecs = mk.eigenpairs(V, F, 12)
    assert np.abs(evals - np.array(expected["eigenvalues"])).max() < 1e-10
    out = tmp_path / "h.ply"
    cli("spectral", "hks", data_dir / name, "--k", 40, "--times", 4, "--out", out)
    _, _, va, _, _ = mk.read_attributes(out)
    hks, times = mk.heat_kernel_signature(V, F, k=40, count=4)
    for j in range(4):
        assert np.abs(hks[:, j] - va[f"hks{j}"]).max() < 1e-9 * hks[:, j].max()


@pytest.mark.parametrize("scheme", ["loop", "midpoint", "butterfly"])
def test_subdivide_equals_mesh_subdivide(scheme, data_dir, cli, tmp_path):
    out = tmp_path / "s.ply"
    cli("subdivide", data_dir / "cgal_nefertiti.off", "--scheme", scheme, "--levels", 2, "--out", out)
    Vc, Fc = mk.read(out)
    V, F = mk.subdivide(*mk.read(data_dir / "cgal_nefertiti.off"), 2, scheme)
    assert np.array_equal(F, Fc) and np.abs(V - Vc).max() < 1e-12


@pytest.mark.parametrize("method", ["harmonic", "mean-value", "lscm", "arap"])
def test_parameterize_equals_mesh_param_up_to_the_atlas_layout(method, data_dir, cli, tmp_path):
    # `mesh param` packs its one chart into the unit square (rotated to its
    # smallest bounding box, scaled, shifted): equal up to a similarity.
    out = tmp_path / "p.ply"
    cli("param", data_dir / "cgal_nefertiti.off", "--method", method, "--out", out)
    _, _, va, _, _ = mk.read_attributes(out)
    V, F = mk.read(data_dir / "cgal_nefertiti.off")
    uv = mk.parameterize(V, F, method, boundary="circle")
    a, b = uv - uv.mean(0), va["uvs"] - va["uvs"].mean(0)
    u, s, vt = np.linalg.svd(a.T @ b)
    r = u @ vt
    scale = s.sum() / (a**2).sum()
    assert np.abs(scale * a @ r - b).max() < 1e-9


def test_wavelet_statistics_equal_mesh_wavelet_analyze(cli):
    expected = cli("wavelet", "analyze", "--shape", "icosphere", "--res", 3, "--json")
    mr = mk.Multiresolution(*mk.shape("icosphere", 3))
    assert mr.levels == expected["levels"]
    for ours, theirs in zip(mr.statistics(), expected["per_level"]):
        assert ours["count"] == theirs["coefficients"]
        for key in ("mean", "rms", "max"):
            assert ours[key] == pytest.approx(theirs[key], rel=1e-12, abs=1e-15)


def test_read_write_round_trip_with_attributes(tmp_path, bunny):
    V, F = bunny
    k1, k2, d1, _ = mk.principal_curvature(V, F)
    labels = np.arange(len(V)) % 7
    uv = V[:, :2] / 10
    for ext in ("ply", "obj", "off", "stl", "glb", "gltf"):
        p = tmp_path / f"m.{ext}"
        report = mk.write(p, V, F, k1=k1, label=labels, d1=d1, normals=mk.vertex_normals(V, F), uvs=uv)
        V2, F2, va, fa, _ = mk.read_attributes(p)
        if ext == "stl":  # 32-bit floats, welded by position
            assert len(V2) == len(V) and np.abs(V2[F2] - V[F]).max() < 1e-6 * np.abs(V).max()
            continue
        assert np.array_equal(F2, F)
        tol = 0 if ext in ("ply", "obj", "off") else 1e-6 * np.abs(V).max()
        assert np.abs(V2 - V).max() <= tol, ext
        if ext in ("ply", "glb", "gltf"):
            assert np.abs(va["k1"] - k1).max() <= 1e-6 * np.abs(k1).max(), ext
            assert np.array_equal(va["label"], labels), ext
            assert np.abs(va["d1"] - d1).max() <= 1e-6, ext
            assert not report["dropped"]
        else:
            assert report["dropped"], ext
    mk.write_mesh(tmp_path / "f.ply", V, F, face_attributes={"area": mk.face_areas(V, F)}, ply_binary=False)
    _, _, _, fa, _ = mk.read_attributes(tmp_path / "f.ply")
    assert np.abs(fa["area"] - mk.face_areas(V, F)).max() < 1e-12


@pytest.mark.parametrize("manifold", [False, True])
def test_clean_equals_mesh_clean_on_the_dirty_dragon(manifold, data_dir, cli, tmp_path):
    out = tmp_path / "clean.ply"
    flags = ["--manifold"] if manifold else []
    expected = cli("clean", data_dir / "npm_dragon_res3.ply", out, *flags, "--json")
    V2, F2, report = mk.clean(*mk.read(data_dir / "npm_dragon_res3.ply"), manifold=manifold)
    assert {k: v for k, v in expected.items() if k in report} == report
    assert (len(V2), len(F2), mk.info(V2, F2)["manifold"]) == (expected["vertices"], expected["faces"], expected["manifold"])
    Vc, Fc = mk.read(out)
    assert np.array_equal(Fc, F2) and np.abs(Vc - V2).max() == 0


@pytest.mark.parametrize("name", ["cgal_nefertiti.off", "npm_bunny.obj"])
def test_remesh_equals_mesh_remesh(name, data_dir, cli, tmp_path):
    # The same Rust function behind both: the same mesh and report.
    path = data_dir / name
    out = tmp_path / "out.ply"
    expected = cli("remesh", path, "--out", out, "--json")
    V, F = mk.read(path)
    (W, G), report = mk.remesh(V, F, return_report=True)
    Wc, Gc = mk.read(out)
    assert np.array_equal(G, Gc) and np.allclose(W, Wc, rtol=0, atol=1e-12)
    assert report["vertices"] == expected["vertices"] and report["faces"] == expected["faces"]
    assert report["hausdorff_relative"] == pytest.approx(expected["hausdorff"]["symmetric_relative"], rel=1e-12)
    assert report["output_topology"]["euler_characteristic"] == expected["output_topology"]["euler_characteristic"]
    assert not report["topology_changed"]
