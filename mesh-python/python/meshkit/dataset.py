"""Descriptors of many mesh files: on one machine, or on a Dask cluster.

A dataset is a list of mesh files; :func:`descriptor` turns one file into a
record (a dict of plain Python values) and never raises: a file that cannot
be read or processed gives a record with ``status == "failed"`` and the
error's text, so one bad file does not stop a run over thousands.
:func:`map_descriptors` runs it over a list of files, here or on the workers
of a ``dask.distributed`` client, and returns the records in the order of
the files. The same records come out of ``mesh batch --do curvature,hks``
(sections ``curvature.shape_index_histogram`` and ``hks.heat_trace``).

Dask is optional (``pip install "dask[distributed]"``); only
:func:`map_descriptors` with a client and :func:`local_cluster` need it.

Example (one machine, two worker processes)::

    from meshkit import dataset
    files = dataset.mesh_files("data/")
    with dataset.local_cluster(workers=2) as client:
        records = dataset.map_descriptors(files, client=client)
    dataset.write_csv("descriptors.csv", records)

On a cluster, point the client at the scheduler instead
(``Client("tcp://scheduler:8786")``): the files must be readable by every
worker under the same path (a shared file system or object store mount).
"""

import csv
import os
import time
from pathlib import Path

import numpy as np

from . import Harmonics, read, shape_index_histogram

#: The extensions of the mesh formats meshkit reads.
MESH_EXTENSIONS = (".obj", ".off", ".ply", ".stl", ".gltf", ".glb")


def mesh_files(root, recursive=True):
    """Every mesh file (by extension) under the folder ``root``, sorted; a
    file path is returned as a one-element list. Links to folders are not
    followed."""
    root = Path(root)
    if root.is_file():
        return [str(root)]
    if not root.is_dir():
        raise FileNotFoundError(f"{root}: no such file or folder")
    def unreadable(error):
        raise OSError(f"{error.filename}: cannot be listed: {error.strerror}") from error

    found = []
    for folder, dirs, files in os.walk(root, followlinks=False, onerror=unreadable):
        dirs.sort()
        found.extend(str(Path(folder) / f) for f in files if f.lower().endswith(MESH_EXTENSIONS))
        if not recursive:
            break
    return sorted(found)


def descriptor(path, k=30, times=8, bins=16):
    """The descriptor record of one mesh file; never raises.

    Keys: ``file``, ``status`` (``"ok"`` or ``"failed"``), ``error`` (the
    message, failed only), ``vertices``, ``faces``, ``shape_index_histogram``
    (``bins`` area fractions, :func:`meshkit.shape_index_histogram`),
    ``heat_trace`` and ``times`` (``times`` values of
    :meth:`meshkit.Harmonics.heat_trace` from ``k`` eigenpairs), ``seconds``.
    Both descriptors are independent of the unit of length and of rigid
    motions, so files of any scale compare; the histogram leaves out flat
    regions, and the curvature that the rounding of a file's coordinates
    (single precision, 6-7 decimal digits) can fake (see
    ``mesh_curvature::NOISE_CURVEDNESS``).
    """
    start = time.perf_counter()
    record = {"file": str(path)}
    try:
        V, F = read(path)
        record["vertices"], record["faces"] = int(len(V)), int(len(F))
        hist = shape_index_histogram(V, F, bins)
        trace, t = Harmonics(V, F, min(int(k), len(V))).heat_trace(count=times)
        record.update(
            status="ok",
            shape_index_histogram=[float(x) for x in hist],
            heat_trace=[float(x) for x in trace],
            times=[float(x) for x in t],
        )
    except (KeyboardInterrupt, SystemExit):
        raise
    except BaseException as e:  # every failure (a Rust panic too) becomes a record; the run goes on
        record.update(status="failed", error=f"{type(e).__name__}: {e}")
    record["seconds"] = time.perf_counter() - start
    return record


def map_descriptors(paths, client=None, **options):
    """:func:`descriptor` of every path (``options``: ``k``, ``times``,
    ``bins``), in the order of ``paths``. With a ``dask.distributed.Client``
    each file is a task on the cluster's workers (``pure=False``: a file may
    change between runs); without one they run here, one after the other."""
    paths = [str(p) for p in paths]
    if client is None:
        return [descriptor(p, **options) for p in paths]
    from dask.distributed import as_completed

    futures = client.map(descriptor, paths, pure=False, **options)
    index = {f.key: i for i, f in enumerate(futures)}
    records = [None] * len(paths)
    # Task by task: a task that fails on the cluster (its worker died, e.g.
    # out of memory, more often than the scheduler allows) becomes a failed
    # record instead of losing every other record.
    for future in as_completed(futures):
        i = index[future.key]
        try:
            records[i] = future.result()
        except Exception as e:
            records[i] = {"file": paths[i], "status": "failed", "error": f"{type(e).__name__}: {e}"}
    return records


def local_cluster(workers=2, threads_per_worker=1):
    """A ``dask.distributed.Client`` on a ``LocalCluster`` of ``workers``
    processes (use it as a context manager: the cluster stops with it).
    Each worker runs ``threads_per_worker`` tasks at once, and meshkit's
    Rust thread pool in it gets as many threads (``RAYON_NUM_THREADS``), so
    that ``workers * threads_per_worker`` threads share the cores instead of
    every worker's pool claiming all of them. On a real cluster, start the
    workers with ``RAYON_NUM_THREADS`` set to their ``--nthreads``."""
    from dask.distributed import Client, LocalCluster

    cluster = LocalCluster(
        n_workers=int(workers),
        threads_per_worker=int(threads_per_worker),
        processes=True,
        dashboard_address=None,
        env={"RAYON_NUM_THREADS": str(int(threads_per_worker))},
    )
    try:
        return _ClusterClient(Client(cluster), cluster)
    except BaseException:
        cluster.close()
        raise


class _ClusterClient:
    """A client that also closes its local cluster."""

    def __init__(self, client, cluster):
        self.client, self.cluster = client, cluster

    def __getattr__(self, name):
        return getattr(self.client, name)

    def close(self):
        self.client.close()
        self.cluster.close()

    def __enter__(self):
        return self.client

    def __exit__(self, *exc):
        self.close()


def table(records, bins=None, times=None):
    """``(header, rows)``: one row per record, the histogram and the heat
    trace spread into columns ``si0..`` and ``z0..`` (empty cells for failed
    records)."""
    ok = [r for r in records if r.get("status") == "ok"]
    bins = bins if bins is not None else max((len(r["shape_index_histogram"]) for r in ok), default=0)
    times = times if times is not None else max((len(r["heat_trace"]) for r in ok), default=0)
    header = ["file", "status", "vertices", "faces", "seconds", "error"]
    header += [f"si{i}" for i in range(bins)] + [f"z{i}" for i in range(times)]
    rows = []
    for r in records:
        row = [r.get("file"), r.get("status"), r.get("vertices", ""), r.get("faces", ""), r.get("seconds", ""),
               r.get("error", "")]
        hist = r.get("shape_index_histogram", [])
        trace = r.get("heat_trace", [])
        row += [hist[i] if i < len(hist) else "" for i in range(bins)]
        row += [trace[i] if i < len(trace) else "" for i in range(times)]
        rows.append(row)
    return header, rows


def write_csv(path, records):
    """Writes :func:`table` as CSV, atomically (a temporary file in the same
    folder, then a rename): an interrupted run leaves the old file or none."""
    header, rows = table(records)
    path = Path(path)
    tmp = path.with_name(f".{path.name}.tmp-{os.getpid()}")
    try:
        with open(tmp, "w", newline="") as f:
            w = csv.writer(f)
            w.writerow(header)
            w.writerows(rows)
        os.replace(tmp, path)
    finally:
        if tmp.exists():
            tmp.unlink()


def features(records):
    """The descriptors of the successful records as one float array
    (records x (bins + times)), with the files in the same order: the input
    of a classifier or a nearest-neighbour search."""
    ok = [r for r in records if r.get("status") == "ok"]
    if not ok:
        return np.zeros((0, 0)), []
    X = np.array([r["shape_index_histogram"] + r["heat_trace"] for r in ok], dtype=np.float64)
    return X, [r["file"] for r in ok]
