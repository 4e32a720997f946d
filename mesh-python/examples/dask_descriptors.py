"""Shape descriptors of every mesh file of a folder, on a Dask cluster.

    python dask_descriptors.py DATA_DIR --workers 2 --out descriptors.csv
    python dask_descriptors.py DATA_DIR --scheduler tcp://scheduler:8786 --out descriptors.csv

Each file gives one row: its area-weighted shape-index histogram and its
heat trace at eight times (both independent of the unit of length), or its
error. Without --scheduler a LocalCluster of --workers processes runs on
this computer; with it, the same script runs on any Dask deployment (the
files must be readable by every worker under the same path). --workers 0
runs without Dask, in this process. The exit status is 1 when any file
failed (after every file was tried; the table has its error), as for
``mesh batch``.
"""

import argparse
import sys
import time

from meshkit import dataset


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("data", help="folder of mesh files (searched recursively) or one file")
    p.add_argument("--out", default="descriptors.csv", help="CSV table to write (atomically)")
    p.add_argument("--scheduler", help="address of a running Dask scheduler, e.g. tcp://host:8786")
    p.add_argument("--workers", type=int, default=2, help="local worker processes when no --scheduler (0: no Dask)")
    p.add_argument("--k", type=int, default=30, help="eigenpairs of the heat trace")
    p.add_argument("--times", type=int, default=8, help="times of the heat trace")
    p.add_argument("--bins", type=int, default=16, help="bins of the shape-index histogram")
    args = p.parse_args(argv)

    files = dataset.mesh_files(args.data)
    options = dict(k=args.k, times=args.times, bins=args.bins)
    start = time.perf_counter()
    if args.scheduler:
        from dask.distributed import Client

        with Client(args.scheduler) as client:
            records = dataset.map_descriptors(files, client=client, **options)
    elif args.workers > 0:
        with dataset.local_cluster(workers=args.workers) as client:
            started = time.perf_counter()
            records = dataset.map_descriptors(files, client=client, **options)
            compute = time.perf_counter() - started
    else:
        records = dataset.map_descriptors(files, **options)
    wall = time.perf_counter() - start
    dataset.write_csv(args.out, records)
    failed = [r for r in records if r["status"] != "ok"]
    vertices = sum(r.get("vertices", 0) for r in records)
    where = args.scheduler or (f"{args.workers} local workers" if args.workers > 0 else "this process")
    print(f"{len(records)} files ({len(failed)} failed), {vertices} vertices in {wall:.1f} s on {where}; "
          f"table in {args.out}")
    if not args.scheduler and args.workers > 0:
        print(f"  of which computing {compute:.1f} s ({len(records) / compute:.1f} files/s), "
              f"the rest starting and stopping the cluster")
    for r in failed:
        print(f"  {r['file']}: {r['error']}", file=sys.stderr)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
