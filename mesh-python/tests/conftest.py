"""Shared fixtures: built-in shapes, the workspace's shared meshes and the
`mesh` command, found by the workspace's rules (CONTRIBUTING.md):

- shared meshes: ``MESH_SHARED_DATA`` if set, else ``../shared/data`` beside
  the workspace; when neither exists the tests that need them are skipped
  with a message, or fail when ``MESH_REQUIRE_SHARED_DATA=1`` (CI);
- the ``mesh`` binary: ``MESH_BIN`` if set, else ``target/{debug,release}/mesh``
  of the workspace (``cargo test --workspace`` builds it); missing, the CLI
  comparisons are skipped with a message, or fail under
  ``MESH_REQUIRE_SHARED_DATA=1``.
"""

import json
import os
import pathlib
import subprocess

import numpy as np
import pytest

import meshkit as mk

WORKSPACE = pathlib.Path(__file__).resolve().parents[2]
REQUIRED = os.environ.get("MESH_REQUIRE_SHARED_DATA") == "1"

# The shared meshes and their ground truth (the data folder's README).
SHARED = {
    "cgal_nefertiti.off": dict(V=299, F=562, chi=1, loops=1),
    "cgal_mushroom.off": dict(V=2337, F=4608, chi=1, loops=1),
    "cgal_elephant.off": dict(V=2775, F=5558, chi=-4, loops=0),
    "cgal_fandisk.off": dict(V=6475, F=12946, chi=2, loops=0),
    "npm_bunny.obj": dict(V=1839, F=3674, chi=2, loops=0),
    "cgal_holes.off": dict(V=4291, F=8288, chi=-5, loops=7),
    "cgal_degtri_sliding.off": dict(V=8, F=8, chi=1, loops=1),
    "npm_dragon_res3.ply": dict(V=22998, F=47794, chi=1267, loops=None),
}


def _missing(what):
    message = f"needs {what}"
    if REQUIRED:
        pytest.fail(message + " (MESH_REQUIRE_SHARED_DATA=1)")
    pytest.skip(message)


@pytest.fixture(scope="session")
def data_dir():
    d = os.environ.get("MESH_SHARED_DATA")
    path = pathlib.Path(d) if d else WORKSPACE.parent / "shared" / "data"
    if not path.is_dir():
        _missing(f"the workspace's shared data at {path} (set MESH_SHARED_DATA)")
    return path


@pytest.fixture(scope="session")
def mesh_bin():
    env = os.environ.get("MESH_BIN")
    candidates = [pathlib.Path(env)] if env else [WORKSPACE / "target" / p / "mesh" for p in ("debug", "release")]
    for c in candidates:
        if c.is_file():
            return c
    _missing(f"the `mesh` binary (cargo build -p mesh-cli, or set MESH_BIN; looked at {candidates})")


@pytest.fixture(scope="session")
def cli(mesh_bin):
    """Runs `mesh ARGS...`; returns the parsed JSON when `--json` is given."""

    def run(*args):
        args = [str(a) for a in args]
        out = subprocess.run([str(mesh_bin), *args], capture_output=True, text=True, timeout=600)
        assert out.returncode == 0, f"mesh {' '.join(args)} failed: {out.stderr}"
        return json.loads(out.stdout) if "--json" in args else out.stdout

    return run


@pytest.fixture(scope="session")
def bunny(data_dir):
    return mk.read(data_dir / "npm_bunny.obj")


@pytest.fixture(scope="session")
def sphere():
    """Unit icosphere, level 4: 2562 vertices."""
    return mk.shape("icosphere", 4)


def sphere_of_radius(r, level=4):
    V, F = mk.shape("icosphere", level)
    return V * r, F


def great_circle(V, source):
    """Great-circle distance on the unit sphere from vertex `source`."""
    p = V / np.linalg.norm(V, axis=1, keepdims=True)
    return np.arccos(np.clip(p @ p[source], -1.0, 1.0))
