"""``pdeface compare`` over a face database, spread over a Dask distributed cluster.

    python3 -m pdeface.batch FOLDER_OR_GLOB_OR_MANIFEST... --out DIR [--workers N] [--scheduler ADDR]

Each scan is one task: a worker reads it, compares it (:func:`pdeface.compare_file`, the command's own
code) and sends back its :class:`pdeface.ScanReport` (a few hundred KB: the figures and the heat-map
GLBs); the client gathers them in input order and writes the same report folder as ``pdeface compare
--out DIR`` (report.md, .json, .csv, .html, rd.svg, heat maps). What is shipped to workers is the scan's
*path*: on several machines they must see the same files (a shared file system). A scan that cannot be
read or has no face is a row with its error; a worker lost mid-run loses nothing (Dask runs its task
again elsewhere).
"""

from __future__ import annotations

import argparse
import glob
import os
import sys
import time
from typing import Iterable, List, Optional, Sequence

from . import _pdeface

__all__ = ["scan_paths", "run", "main"]


def scan_paths(inputs: Iterable[str]) -> List[str]:
    """Scan files from folders (the mesh files in them, sorted), glob patterns and manifests (a ``.txt``
    or ``.lst`` file with one path per line, relative to the manifest; ``#`` starts a comment)."""
    paths: List[str] = []
    for item in inputs:
        item = os.fspath(item)
        if os.path.isfile(item) and item.endswith((".txt", ".lst")):
            base = os.path.dirname(os.path.abspath(item))
            with open(item, encoding="utf-8") as manifest:
                listed = [line.split("#", 1)[0].strip() for line in manifest]
            paths += scan_paths(os.path.join(base, p) for p in listed if p)
        elif glob.has_magic(item):
            matches = sorted(glob.glob(item, recursive=True))
            if not matches:
                raise FileNotFoundError(f"{item}: no file matches")
            paths += [str(p) for p in _pdeface.expand_inputs(matches)]
        else:
            paths += [str(p) for p in _pdeface.expand_inputs([item])]
    return paths


def _compare_one(path: str, name: str, options: dict) -> "_pdeface.ScanReport":
    return _pdeface.compare_file(path, name, **options)


def run(inputs: Iterable[str], out: Optional[str] = None, *, client=None, workers: Optional[int] = None,
        scheduler: Optional[str] = None, progress: bool = False, retries: int = 1, **options) -> List[dict]:
    """Compares every scan on a Dask cluster and returns the report's rows (report.csv's columns); with
    ``out``, writes the report folder too.

    The cluster: ``client`` (a ``distributed.Client``), else one connected to ``scheduler``
    ("tcp://host:8786"), else a ``LocalCluster`` of ``workers`` processes (default: the cores), one scan at
    a time each. ``options`` are those of :func:`pdeface.compare` (ratios, draco_bits, budgets, ...).
    ``retries``: how often a task that *raised* is run again (a lost worker's task is always rerun)."""
    from dask.distributed import Client, LocalCluster
    from dask.distributed import progress as show_progress

    paths = scan_paths(inputs)
    if not paths:
        raise FileNotFoundError("no scan files in " + ", ".join(map(str, inputs)))
    names = _pdeface.scan_names(paths)
    options = dict(options)
    options.setdefault("threads", 1)  # one scan per worker process, one core each
    own_cluster = None
    if client is None:
        if scheduler:
            client = Client(scheduler)
        else:
            own_cluster = LocalCluster(n_workers=workers or os.cpu_count() or 1, threads_per_worker=1,
                                       processes=True, dashboard_address=":0")
            client = Client(own_cluster)
    try:
        start = time.monotonic()
        futures = client.map(_compare_one, paths, names, options=options, pure=False, retries=retries,
                             key=[f"pdeface-compare-{i}-{n}" for i, n in enumerate(names)])
        if progress:
            show_progress(futures)
        reports = client.gather(futures)
        seconds = time.monotonic() - start
    finally:
        if own_cluster is not None:
            client.close()
            own_cluster.close()
    report_options = {k: v for k, v in options.items() if k != "threads"}
    if out is not None:
        return _pdeface.write_report(reports, out, seconds, **report_options)
    return _pdeface.report_rows(reports, **report_options)


def main(argv: Optional[Sequence[str]] = None) -> int:
    parser = argparse.ArgumentParser(
        prog="python3 -m pdeface.batch",
        description="pdeface compare over many scans on a Dask distributed cluster; writes the same report "
                    "folder as `pdeface compare --out`")
    parser.add_argument("inputs", nargs="+", help="scan files, folders, glob patterns or manifests (.txt)")
    parser.add_argument("--out", default="pdeface-report", help="report folder (default: pdeface-report)")
    parser.add_argument("--workers", type=int, help="local worker processes (default: the cores)")
    parser.add_argument("--scheduler", help="an existing cluster's scheduler, e.g. tcp://host:8786")
    parser.add_argument("--ratios", type=lambda s: [float(x) for x in s.split(",")],
                        help="PDE sampling ratios, comma-separated (0.05..0.6)")
    parser.add_argument("--draco-bits", type=lambda s: [int(x) for x in s.split(",")])
    parser.add_argument("--budgets", type=lambda s: [int(x) for x in s.split(",")],
                        help="decimate + Draco byte budgets, comma-separated")
    parser.add_argument("--pdef-sizes", type=lambda s: [int(x) for x in s.split(",")],
                        help=".pdef + residual layer sizes in bytes, comma-separated")
    parser.add_argument("--crop-face", action="store_true")
    parser.add_argument("--no-colour", action="store_true",
                        help="no colour rows (Draco with the photograph, the .pdef with a texture layer)")
    parser.add_argument("-q", "--quiet", action="store_true", help="no progress bar")
    args = parser.parse_args(argv)
    options = {k: v for k, v in (("ratios", args.ratios), ("draco_bits", args.draco_bits),
                                  ("budgets", args.budgets), ("pdef_sizes", args.pdef_sizes)) if v is not None}
    if args.crop_face:
        options["crop_face"] = True
    if args.no_colour:
        options["colour"] = False
    from .errors import Error
    try:
        rows = run(args.inputs, args.out, workers=args.workers, scheduler=args.scheduler,
                   progress=not args.quiet, **options)
    except (Error, OSError, ValueError) as e:
        print(f"pdeface: error: {e}", file=sys.stderr)
        return 1
    scans = {r["scan"] for r in rows}
    failed = {r["scan"] for r in rows if r["failure"] and r["variant"] == ""}
    print(f"{len(scans)} scans ({len(failed)} failed) -> {args.out}/report.md, report.html, report.json, "
          f"report.csv, rd.svg")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
