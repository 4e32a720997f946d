"""meshkit.dataset: descriptors of many files, here and on a Dask LocalCluster
of two workers, equal to each other and to `mesh batch`; failures recorded;
the example script end to end.

Dask is optional: these tests skip without it, unless MESHKIT_REQUIRE_DASK=1
(CI) makes its absence a failure.
"""

import csv
import json
import os
import pathlib
import subprocess
import sys

import numpy as np
import pytest

import meshkit as mk
from meshkit import dataset

EXAMPLE = pathlib.Path(__file__).resolve().parents[1] / "examples" / "dask_descriptors.py"


def _need_dask():
    try:
        import dask.distributed  # noqa: F401
    except ImportError:
        if os.environ.get("MESHKIT_REQUIRE_DASK") == "1":
            pytest.fail("dask.distributed is required (MESHKIT_REQUIRE_DASK=1)")
        pytest.skip("needs dask[distributed]")


@pytest.fixture(scope="module")
def files(tmp_path_factory):
    """Four meshes (one twice, at two scales and rotated), a PLY cut short,
    and a file that is not a mesh (not listed)."""
    d = tmp_path_factory.mktemp("data")
    (d / "sub").mkdir()
    V, F = mk.shape("icosphere", 2)
    mk.write(d / "sphere.off", V, F)
    c, s = np.cos(0.4), np.sin(0.4)
    R = np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])
    mk.write(d / "sub" / "sphere_big.ply", (V @ R.T) * 1e3 + 7.0, F)
    mk.write(d / "torus.obj", *mk.shape("torus", 12))
    mk.write(d / "cube.stl", *mk.shape("cube", 4))
    good = (d / "sub" / "sphere_big.ply").read_bytes()
    (d / "broken.ply").write_bytes(good[: len(good) // 3])
    (d / "notes.txt").write_text("not a mesh")
    return d, dataset.mesh_files(d)


def test_mesh_files_lists_meshes_only_sorted(files):
    d, paths = files
    names = [pathlib.Path(p).relative_to(d).as_posix() for p in paths]
    assert names == ["broken.ply", "cube.stl", "sphere.off", "sub/sphere_big.ply", "torus.obj"]
    assert dataset.mesh_files(d, recursive=False) == [p for p in paths if "/sub/" not in p]
    with pytest.raises(FileNotFoundError):
        dataset.mesh_files(d / "missing")


def test_descriptors_fail_softly_and_ignore_the_unit_of_length(files):
    d, paths = files
    records = dataset.map_descriptors(paths, k=20, times=6)
    by_name = {pathlib.Path(r["file"]).name: r for r in records}
    broken = by_name["broken.ply"]
    assert broken["status"] == "failed" and "broken.ply" in broken["error"], broken
    ok = [r for r in records if r["status"] == "ok"]
    assert len(ok) == 4
    for r in ok:
        assert len(r["shape_index_histogram"]) == 16 and len(r["heat_trace"]) == 6
        assert abs(sum(r["shape_index_histogram"]) - 1.0) < 1e-12
        assert all(np.diff(r["heat_trace"]) < 0), "the heat trace decreases in time"
    small, big = by_name["sphere.off"], by_name["sphere_big.ply"]
    np.testing.assert_allclose(big["shape_index_histogram"], small["shape_index_histogram"], atol=1e-9)
    np.testing.assert_allclose(big["heat_trace"], small["heat_trace"], rtol=1e-8)
    np.testing.assert_allclose(np.array(big["times"]) / 1e6, small["times"], rtol=1e-8)
    assert small["shape_index_histogram"][-1] > 0.99, "a sphere is all cap"
    X, names = dataset.features(records)
    assert X.shape == (4, 22) and len(names) == 4 and np.isfinite(X).all()


def test_descriptors_equal_mesh_batch(files, mesh_bin, tmp_path):
    d, paths = files
    out = tmp_path / "batch"
    run = subprocess.run(
        [str(mesh_bin), "batch", str(d), "--recursive", "--do", "curvature,hks", "--k", "20", "--times", "6",
         "--no-fields", "--out", str(out)],
        capture_output=True, text=True, timeout=600,
    )
    assert run.returncode == 1, "the broken file fails the run: " + run.stderr
    batch = {}
    for line in (out / "results.jsonl").read_text().splitlines():
        r = json.loads(line)
        batch[pathlib.Path(r["input"]).resolve()] = r
    for r in dataset.map_descriptors(paths, k=20, times=6):
        b = batch[pathlib.Path(r["file"]).resolve()]
        assert b["status"] == r["status"]
        if r["status"] == "ok":
            np.testing.assert_allclose(r["shape_index_histogram"], b["sections"]["curvature"]["shape_index_histogram"],
                                       rtol=1e-12, atol=1e-15)
            np.testing.assert_allclose(r["heat_trace"], b["sections"]["hks"]["heat_trace"], rtol=1e-12)
            np.testing.assert_allclose(r["times"], b["sections"]["hks"]["times"], rtol=1e-12)


def test_a_two_worker_cluster_gives_the_same_records(files):
    _need_dask()
    d, paths = files
    local = dataset.map_descriptors(paths, k=20, times=6)
    with dataset.local_cluster(workers=2) as client:
        assert len(client.scheduler_info()["workers"]) == 2
        remote = dataset.map_descriptors(paths, client=client, k=20, times=6)
    assert [r["file"] for r in remote] == [r["file"] for r in local]
    for a, b in zip(local, remote):
        assert a["status"] == b["status"]
        for key in ("shape_index_histogram", "heat_trace", "times"):
            if key in a:
                np.testing.assert_allclose(a[key], b[key], rtol=1e-12, atol=1e-15)


def test_the_example_script_writes_the_table(files, tmp_path):
    _need_dask()
    d, paths = files
    table = tmp_path / "descriptors.csv"
    run = subprocess.run(
        [sys.executable, str(EXAMPLE), str(d), "--workers", "2", "--out", str(table), "--k", "20"],
        capture_output=True, text=True, timeout=600,
    )
    assert run.returncode == 1, "one file is broken, so the run fails after trying all: " + run.stderr
    assert "5 files (1 failed)" in run.stdout, run.stdout
    with open(table, newline="") as f:
        rows = list(csv.reader(f))
    assert rows[0][:6] == ["file", "status", "vertices", "faces", "seconds", "error"]
    assert len(rows) == 6 and sum(r[1] == "ok" for r in rows[1:]) == 4
    assert [p.name for p in tmp_path.iterdir()] == ["descriptors.csv"], "no temporary file left"
