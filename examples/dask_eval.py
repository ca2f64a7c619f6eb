#!/usr/bin/env python3
"""Evaluate a VR-Folding store (or folders of Sample JSON files) on a Dask cluster.

`close.evaluate(path, executor=...)` cuts the work into units (the store's videos, the
sample files), and each Dask worker reads its own units from the path (no arrays go through
the scheduler); the rows come back in order and make the same report as `close eval --json`.

    python examples/dask_eval.py STORE [STORE ...]                     # a local 2-worker cluster
    python examples/dask_eval.py STORE --scheduler tcp://10.0.0.5:8786  # an existing cluster
    python examples/dask_eval.py STORE --workers 4 --json report.json

The paths must be readable by every worker (a shared file system on a real cluster).
"""

import argparse
import json
import sys

import close


def evaluate_on(client, paths, method="default"):
    """The `close eval --json` report of `paths`, computed by the workers of a Dask `client`."""
    return close.evaluate(paths, executor=client.get_executor(), method=method)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("paths", nargs="+", help="VR-Folding Zarr stores, folders or Sample JSON files")
    parser.add_argument("--scheduler", help="address of a running Dask scheduler (default: start a LocalCluster)")
    parser.add_argument("--workers", type=int, default=2, help="workers of the LocalCluster (default: 2)")
    parser.add_argument("--method", default="default", help='fold method: "default", "cut" or "paper"')
    parser.add_argument("--json", metavar="FILE", help="write the report as JSON here (default: print the table's rows)")
    args = parser.parse_args(argv)

    from distributed import Client, LocalCluster

    if args.scheduler:
        client, cluster = Client(args.scheduler), None
    else:
        cluster = LocalCluster(n_workers=args.workers, threads_per_worker=1, dashboard_address=":0")
        client = Client(cluster)
    try:
        report = evaluate_on(client, args.paths, args.method)
    finally:
        client.close()
        if cluster is not None:
            cluster.close()
    if args.json:
        with open(args.json, "w") as out:
            json.dump(report, out, indent=1)
    else:
        for row in report["categories"] + [report["overall"]]:
            rmse = row.get("rmse") or {}
            print(f"{row['category']:<24} {row['count']:>5}  RMSE {rmse.get('mean', float('nan')):.4f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
