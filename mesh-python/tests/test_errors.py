"""Bad input raises a typed exception (a MeshkitError carrying the Rust
error's text), never crashes the interpreter; the GIL is released; Ctrl-C
interrupts between stages; prepared objects pickle."""

import os
import pickle
import signal
import subprocess
import sys
import threading
import time

import numpy as np
import pytest

import meshkit as mk
from meshkit import (
    InvalidMeshError,
    InvalidOptionError,
    MeshFileNotFoundError,
    MeshIOError,
    MeshkitError,
    TopologyError,
)

V = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1.0]])
F = np.array([[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]])

# Every function taking (V, F), with its other arguments.
CALLS = [
    (mk.info, ()), (mk.cotan_laplacian, ()), (mk.uniform_laplacian, ()), (mk.adjacency_matrix, ()),
    (mk.gradient, ()), (mk.divergence, ()), (mk.mass_matrix, ()), (mk.lumped_mass, ()),
    (mk.intrinsic_delaunay_laplacian, ()), (mk.vertex_normals, ()), (mk.face_normals, ()), (mk.face_areas, ()),
    (mk.gaussian_curvature, ()), (mk.mean_curvature, ()), (mk.principal_curvature, ()),
    (mk.HeatSolver, ()), (mk.FastMarchingSolver, ()), (mk.fmm_distance, ([0],)), (mk.exact_distance, ([0],)),
    (mk.dijkstra, ([0],)), (mk.farthest_point_sampling, (2,)), (mk.parameterize, ()), (mk.parameterize_cut, ()),
    (mk.eigenpairs, (2,)), (mk.Harmonics, (2,)), (mk.heat_kernel_signature, (3,)), (mk.subdivide, ()),
    (mk.loop_subdivide, ()), (mk.Multiresolution, ()),
]
IDS = [c[0].__name__ for c in CALLS]


def test_the_hierarchy():
    for cls in (InvalidMeshError, InvalidOptionError):
        assert issubclass(cls, MeshkitError) and issubclass(cls, ValueError)
    assert issubclass(MeshFileNotFoundError, FileNotFoundError) and issubclass(MeshIOError, OSError)
    assert issubclass(TopologyError, MeshkitError)


@pytest.mark.parametrize("fn,args", CALLS, ids=IDS)
def test_every_function_refuses_bad_arrays(fn, args):
    bad = {
        "V of shape (n, 2)": (V[:, :2], F),
        "F of shape (m, 4)": (V, np.hstack([F, F[:, :1]])),
        "float F": (V, F.astype(float)),
        "string V": (np.array([["a", "b", "c"]] * 4), F),
        "ragged V": ([[0, 0, 0], [1, 0]], F),
        "index out of range": (V, np.where(F == 3, 4, F)),
        "negative index": (V, np.where(F == 3, -1, F)),
        "index past int32": (V, np.where(F == 3, 2**40, F)),
        "NaN coordinate": (np.where(V == 1, np.nan, V), F),
        "infinite coordinate": (np.where(V == 1, np.inf, V), F),
        "repeated corner": (V, np.array([[0, 0, 1]])),
    }
    for what, (v, f) in bad.items():
        with pytest.raises(InvalidMeshError) as e:
            fn(v, f, *args)
        assert str(e.value), what


def test_messages_carry_the_rust_error_text():
    with pytest.raises(InvalidMeshError, match="refers to vertex 7, but the mesh has only 4 vertices"):
        mk.cotan_laplacian(V, np.array([[0, 1, 7]]))
    with pytest.raises(InvalidMeshError, match="non-finite coordinate"):
        mk.mass_matrix(np.where(V == 1, np.nan, V), F)


def test_int32_faces_and_views_are_read_in_place():
    L64 = mk.cotan_laplacian(V, F)
    assert abs(mk.cotan_laplacian(V, F.astype(np.int32)) - L64).max() == 0
    assert abs(mk.cotan_laplacian(V, F.astype(np.uint16)) - L64).max() == 0
    big = np.zeros((4, 6))
    big[:, ::2] = V  # a strided view
    assert abs(mk.cotan_laplacian(big[:, ::2], F) - L64).max() == 0
    assert abs(mk.cotan_laplacian(V.astype(np.float32), F) - L64).max() < 1e-6


def test_bad_options_and_arguments():
    with pytest.raises(InvalidOptionError, match="voronoy"):
        mk.mass_matrix(V, F, "voronoy")
    with pytest.raises(InvalidOptionError):
        mk.principal_curvature(V, F, "magic")
    with pytest.raises(InvalidOptionError, match="out of range"):
        mk.fmm_distance(V, F, [4])
    with pytest.raises(InvalidOptionError):
        mk.HeatSolver(V, F).distance([-1])
    with pytest.raises(InvalidOptionError):
        mk.fmm_distance(V, F, [0.5])
    with pytest.raises(InvalidOptionError):
        mk.HeatSolver(V, F, t_coef=-1)
    with pytest.raises(MeshkitError):
        mk.eigenpairs(V, F, 0)
    with pytest.raises(InvalidOptionError):
        mk.eigenpairs(V, F, 10)  # more pairs than vertices
    with pytest.raises(InvalidOptionError):
        mk.trace_path(V, F, np.zeros(3), [0], start=1)  # field of the wrong length
    with pytest.raises(InvalidOptionError):
        mk.trace_path(V, F, np.zeros(4), [0])  # no start
    with pytest.raises(InvalidOptionError):
        mk.Harmonics(*mk.shape("icosphere", 1), 4).filter("low-pass")  # no cutoff
    with pytest.raises(InvalidOptionError):
        mk.heat_kernel_signature(*mk.shape("icosphere", 1), k=10, times=[-1.0])
    with pytest.raises(MeshkitError):
        mk.subdivide(V, F, 1, "catmull-clark")


def test_topology_errors():
    Vs, Fs = mk.shape("icosphere", 2)
    with pytest.raises(TopologyError, match="disk"):
        mk.parameterize(Vs, Fs)
    Vb, Fb = mk.loop_subdivide(Vs, Fs, 1)
    Vb = Vb + 1e-3 * np.random.default_rng(0).standard_normal(Vb.shape)
    perm = np.random.default_rng(1).permutation(len(Fb))
    with pytest.raises(MeshkitError):
        mk.wavelet_analysis(*mk.shape("torus", 5))  # no subdivision connectivity
    assert mk.wavelet_analysis(Vb, Fb[perm]).levels >= 1


def test_files():
    with pytest.raises(MeshFileNotFoundError, match="nope.obj"):
        mk.read("/nonexistent/nope.obj")
    with pytest.raises(FileNotFoundError):
        mk.info_file("/nonexistent/nope.off")


def test_malformed_files(tmp_path):
    p = tmp_path / "bad.off"
    p.write_text("OFF\n3 1 0\n0 0 0\n1 0 0\n")
    with pytest.raises(MeshIOError):
        mk.read(p)
    q = tmp_path / "mesh.xyz"
    q.write_text("")
    with pytest.raises(MeshIOError, match="unknown mesh format"):
        mk.read(q)
    with pytest.raises(MeshIOError):
        mk.write(tmp_path / "missing-folder" / "x.ply", V, F)
    with pytest.raises(InvalidOptionError):
        mk.write(tmp_path / "x.ply", V, F, field=np.zeros(3))  # wrong length
    with pytest.raises(InvalidOptionError):
        mk.write(tmp_path / "x.ply", V, F, field=np.zeros((4, 5)))


def test_no_input_crashes_the_interpreter():
    # Hostile input in a child interpreter: it must exit normally.
    code = r"""
import numpy as np, meshkit as mk
cases = [
    (np.zeros((0, 3)), np.zeros((0, 3), dtype=np.int64)),
    (np.zeros((3, 3)), np.array([[0, 1, 2]])),                 # zero-area face
    (np.ones((3, 3)) * 1e308, np.array([[0, 1, 2]])),           # overflow-prone
    (np.random.default_rng(0).random((50, 3)), np.random.default_rng(1).integers(0, 50, (200, 3))),
]
for V, F in cases:
    for fn in (mk.info, mk.cotan_laplacian, mk.principal_curvature, mk.gaussian_curvature, mk.vertex_normals,
               lambda V, F: mk.fmm_distance(V, F, [0]), lambda V, F: mk.HeatSolver(V, F).distance([0]),
               lambda V, F: mk.exact_distance(V, F, [0]), lambda V, F: mk.eigenpairs(V, F, 2),
               mk.parameterize, mk.loop_subdivide, mk.Multiresolution):
        try:
            fn(V, F)
        except mk.MeshkitError:
            pass
print("survived")
"""
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=600)
    assert out.returncode == 0 and "survived" in out.stdout, out.stderr


def test_the_gil_is_released_during_computation():
    V, F = mk.loop_subdivide(*mk.shape("icosphere", 3), 3)  # 40962 vertices
    done = threading.Event()
    ticks = 0

    def work():
        mk.exact_distance(V, F, [0])
        done.set()

    t = threading.Thread(target=work)
    start = time.perf_counter()
    t.start()
    while not done.is_set():
        ticks += 1
        time.sleep(0.001)
    t.join()
    elapsed = time.perf_counter() - start
    # With the GIL held the main thread could not tick until the call ends.
    assert elapsed > 0.05 and ticks > 0.3 * elapsed / 0.0011


@pytest.mark.skipif(sys.platform == "win32", reason="POSIX signals")
def test_ctrl_c_interrupts_between_stages():
    V, F = mk.loop_subdivide(*mk.shape("icosphere", 3), 3)
    # Python's own Ctrl-C handler, also where the run inherited SIGINT as
    # ignored (a job started in the background by a non-interactive shell).
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    timer = threading.Timer(0.01, lambda: os.kill(os.getpid(), signal.SIGINT))
    try:
        timer.start()
        with pytest.raises(KeyboardInterrupt):
            for _ in range(100):  # each call: validation, then the distance computation
                mk.exact_distance(V, F, [0])
    finally:
        timer.cancel()
        signal.signal(signal.SIGINT, previous)


def test_prepared_solvers_pickle(sphere):
    V, F = sphere
    for solver in (mk.HeatSolver(V, F, t_coef=2.0), mk.FastMarchingSolver(V, F)):
        back = pickle.loads(pickle.dumps(solver))
        assert np.array_equal(back.distance([5]), solver.distance([5]))
