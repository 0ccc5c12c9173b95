"""The Dask batch: the command's report from a 2-worker LocalCluster, a bad scan as a row, and a worker
killed mid-run costs no scan."""

import csv
import os
import signal
import threading
import time

import pytest

import pdeface
from pdeface import batch

distributed = pytest.importorskip("dask.distributed")

# A light variant set: every raw format, one Draco, one decimate + Draco budget, the .pdef at 10 %, and the
# .pdef with a residual layer at 2 KB.
OPTIONS = dict(ratios=[0.1], draco_bits=[11], budgets=[2048], pde_budgets=False, lossless=False,
               pdef_sizes=[2048])
CLI_OPTIONS = ["--ratios", "0.1", "--draco-bits", "11", "--budgets", "2048", "--no-pde-budgets", "--lossy-only",
               "--pdef-sizes", "2048"]
TIMING = {"encode_ms", "decode_ms"}


def rows_of(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def same_figures(a, b):
    assert len(a) == len(b)
    for x, y in zip(a, b):
        assert {k: v for k, v in x.items() if k not in TIMING} == {k: v for k, v in y.items() if k not in TIMING}


@pytest.fixture(scope="module")
def client():
    cluster = distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=":0")
    with distributed.Client(cluster) as c:
        yield c
    cluster.close()


def test_the_batch_reports_what_the_command_reports(faces, cli, client, tmp_path):
    start = time.monotonic()
    rows = batch.run([faces], tmp_path / "dask", client=client, **OPTIONS)
    dask_s = time.monotonic() - start
    start = time.monotonic()
    cli("compare", faces, "--out", tmp_path / "cli", "-q", *CLI_OPTIONS)
    cli_s = time.monotonic() - start
    print(f"\n{len({r['scan'] for r in rows})} scans: dask (2 workers) {dask_s:.1f} s, pdeface compare {cli_s:.1f} s")
    same_figures(rows_of(tmp_path / "dask" / "report.csv"), rows_of(tmp_path / "cli" / "report.csv"))
    assert len(rows) == len(rows_of(tmp_path / "cli" / "report.csv"))
    assert sorted(os.listdir(tmp_path / "dask")) == sorted(os.listdir(tmp_path / "cli"))
    assert (tmp_path / "dask" / "report.html").stat().st_size > 10000


def test_a_bad_scan_is_a_row_and_the_others_go_on(faces, client, tmp_path):
    bad = tmp_path / "broken.ply"
    bad.write_bytes(b"ply\nformat binary_little_endian 1.0\nelement vertex 99\n")
    manifest = tmp_path / "scans.txt"
    manifest.write_text(f"{bad}\n# the sample of a real scan\n{faces / 'ict_02.glb'}\n")
    rows = batch.run([manifest], client=client, **OPTIONS)
    failed = [r for r in rows if r["scan"] == "broken.ply"]
    assert len(failed) == 1 and "broken.ply" in failed[0]["failure"]
    assert sum(r["scan"] == "ict_02.glb" and not r["failure"] for r in rows) >= 8


def test_a_worker_killed_mid_run_loses_no_scan(faces, tmp_path):
    scans = [faces / n for n in ["facefuns_f18.ply", "ict_00.obj", "ict_01.ply", "james.obj"]]
    cluster = distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=":0")
    killed = []
    with distributed.Client(cluster) as c:
        def kill_a_busy_worker():
            deadline = time.monotonic() + 120
            while time.monotonic() < deadline and not killed:
                busy = [w for w, tasks in c.processing().items() if tasks]
                if busy:
                    time.sleep(0.5)  # inside its first scan
                    pid = c.run(os.getpid, workers=[busy[0]])[busy[0]]
                    os.kill(pid, signal.SIGKILL)
                    killed.append(pid)
                time.sleep(0.05)

        killer = threading.Thread(target=kill_a_busy_worker)
        killer.start()
        rows = batch.run(scans, client=c, **OPTIONS)
        killer.join()
    cluster.close()
    assert killed, "no worker was killed"
    reported = {r["scan"] for r in rows if not r["failure"]}
    assert reported == {p.name for p in scans}


def test_the_command_line_entry(faces, tmp_path):
    code = batch.main([str(faces / "ict_02.glb"), "--out", str(tmp_path / "r"), "--workers", "1", "-q",
                       "--ratios", "0.1", "--draco-bits", "11", "--budgets", "2048", "--pdef-sizes", "2048"])
    assert code == 0
    assert (tmp_path / "r" / "report.md").is_file()
