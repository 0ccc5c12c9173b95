#!/usr/bin/env python3
"""Issue 21's stages measured in one run, pdeface against Draco (draco_encoder, draco_decoder, libdraco),
printed as one Markdown table of same-run ratios. scripts/bench.sh builds Release and runs this; see
docs/performance.md for what each row measures and what bounds it.

Whole-process rows run each command alternately with its rival (a busy moment hits both alike), every
run's output deleted first, and report the median wall time of N runs with the CPU time (user + system,
from wait4) beside it; peak memory is the maximum resident set under /usr/bin/time. In-process rows come
from the Google Benchmark programs (median CPU time of their repetitions). Standard library only.
"""

import argparse
import json
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BUILD = os.path.join(ROOT, "build")
PDEFACE = os.path.join(BUILD, "apps", "pdeface", "pdeface")
BENCH = os.path.join(BUILD, "benchmarks")


def faces_folder():
    folder = os.environ.get("PDEFACE_DATA") or os.path.join(ROOT, "..", "shared", "faces")
    return os.path.abspath(folder)


def run_once(argv, outputs):
    for path in outputs:
        try:
            os.remove(path)
        except FileNotFoundError:
            pass
    start = time.perf_counter()
    process = subprocess.Popen(argv, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    _, status, usage = os.wait4(process.pid, 0)
    wall = time.perf_counter() - start
    error = process.stderr.read().decode(errors="replace")
    process.stderr.close()
    if os.waitstatus_to_exitcode(status) != 0:
        sys.exit(f"bench: {' '.join(argv)} failed: {error.strip()}")
    return {"wall": wall * 1e3, "cpu": (usage.ru_utime + usage.ru_stime) * 1e3}


def alternate(commands, runs):
    """Median wall and CPU ms of every command, the commands run in turn `runs` times (after one untimed
    run each)."""
    for argv, outputs in commands.values():
        run_once(argv, outputs)
    samples = {label: [] for label in commands}
    for _ in range(runs):
        for label, (argv, outputs) in commands.items():
            samples[label].append(run_once(argv, outputs))
    return {
        label: {key: statistics.median(s[key] for s in runs_of) for key in ("wall", "cpu")}
        for label, runs_of in samples.items()
    }


def peak_kb(argv, outputs):
    """Maximum resident set (KiB) of one run, from GNU time (a fork of a small process, so the figure is the
    command's own); None without /usr/bin/time."""
    if not os.path.exists("/usr/bin/time"):
        return None
    for path in outputs:
        if os.path.exists(path):
            os.remove(path)
    result = subprocess.run(["/usr/bin/time", "-f", "%M"] + argv, stdout=subprocess.DEVNULL,
                            stderr=subprocess.PIPE, check=True)
    return int(result.stderr.decode().strip().splitlines()[-1])


def google_benchmark(program, repetitions, min_time, benchmark_filter=None):
    """Median CPU time (ms) and counters of every case of a Google Benchmark program."""
    argv = [os.path.join(BENCH, program), "--benchmark_format=json",
            f"--benchmark_repetitions={repetitions}", "--benchmark_report_aggregates_only=true",
            f"--benchmark_min_time={min_time}"]
    if benchmark_filter:
        argv.append(f"--benchmark_filter={benchmark_filter}")
    out = subprocess.run(argv, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, check=True).stdout
    scale = {"ns": 1e-6, "us": 1e-3, "ms": 1.0, "s": 1e3}
    results = {}
    for b in json.loads(out)["benchmarks"]:
        if b.get("aggregate_name", "median") != "median" or b.get("error_occurred"):
            continue
        results[b["run_name"]] = dict(b, cpu_ms=b["cpu_time"] * scale[b["time_unit"]])
    return results


def smoke():
    """Every benchmark program once, for a few iterations (CI: they keep building and running; no time is
    judged). Fails on a crash, or on a case that reports an error while the real scans are there."""
    programs = sorted(f for f in os.listdir(BENCH) if f.endswith("_bench") and os.access(os.path.join(BENCH, f),
                                                                                       os.X_OK))
    have_scans = os.path.exists(os.path.join(faces_folder(), "facefuns_f18.ply"))
    failed = []
    for program in programs:
        start = time.perf_counter()
        result = subprocess.run([os.path.join(BENCH, program), "--benchmark_min_time=0.01",
                                 "--benchmark_format=json"], stdout=subprocess.PIPE, stderr=subprocess.PIPE)
        seconds = time.perf_counter() - start
        if result.returncode != 0:
            failed.append(f"{program}: exit {result.returncode}: {result.stderr.decode(errors='replace')[-500:]}")
            continue
        cases = json.loads(result.stdout)["benchmarks"]
        errors = [f"{b['name']}: {b.get('error_message', '')}" for b in cases if b.get("error_occurred")]
        print(f"bench: {program}: {len(cases)} cases in {seconds:.1f} s" +
              (f", {len(errors)} skipped (no scans)" if errors and not have_scans else ""), file=sys.stderr)
        if errors and have_scans:
            failed += [f"{program}: {e}" for e in errors]
    if failed:
        sys.exit("bench: failed:\n" + "\n".join(failed))


def ms(value):
    return f"{value:,.0f} ms" if value >= 100 else f"{value:.3g} ms"


def ratio(value):
    return f"{value:.3g}×"


def process_cell(result):
    return f"{ms(result['wall'])} [{ms(result['cpu'])} CPU]"


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--runs", type=int, default=7, help="runs of every whole-process command")
    parser.add_argument("--quick", action="store_true", help="3 runs, 1 of compare, short benchmarks")
    parser.add_argument("--json", help="also write every figure to this file")
    parser.add_argument("--smoke", action="store_true",
                        help="only run every benchmark program briefly (CI), no table")
    args = parser.parse_args()
    if args.smoke:
        smoke()
        return
    runs = 3 if args.quick else args.runs
    repetitions, min_time = (1, 0.2) if args.quick else (5, 0.5)
    faces = faces_folder()
    scan = os.path.join(faces, "facefuns_f18.ply")
    if not os.path.exists(scan):
        sys.exit(f"bench: {scan} not found (set PDEFACE_DATA to the faces folder)")
    for tool in ("draco_encoder", "draco_decoder"):
        if not shutil.which(tool):
            sys.exit(f"bench: {tool} not found (Debian package draco; scripts/deps.sh installs it)")
    load = os.getloadavg()[0]
    work = tempfile.mkdtemp(prefix="pdeface-bench-")
    rows, figures = [], {}
    try:
        pdef, drc = os.path.join(work, "face.pdef"), os.path.join(work, "scan.drc")
        subprocess.run([PDEFACE, "encode", scan, "-o", pdef], check=True, capture_output=True)
        subprocess.run(["draco_encoder", "-i", scan, "-o", drc, "-qp", "11", "-cl", "7"], check=True,
                       capture_output=True)
        out = lambda name: os.path.join(work, name)  # noqa: E731
        draco_decode = (["draco_decoder", "-i", drc, "-o", out("draco.ply")], [out("draco.ply")])
        draco_encode = (["draco_encoder", "-i", scan, "-o", out("again.drc"), "-qp", "11", "-cl", "7"],
                        [out("again.drc")])
        note = f"facefuns_f18.ply (30,204 vertices); .pdef {os.path.getsize(pdef)} B (10 %), Draco 11 bits " \
               f"{os.path.getsize(drc):,} B"

        def versus(label, mine, rival_label, rival, count=runs, target=""):
            r = alternate({"pdeface": mine, "draco": rival}, count)
            figures[label] = r
            rows.append((label, process_cell(r["pdeface"]), f"{rival_label} {process_cell(r['draco'])}",
                         ratio(r["draco"]["wall"] / r["pdeface"]["wall"]), target))
            return r

        versus("encode: scan → file (process)",
               ([PDEFACE, "encode", scan, "-o", out("again.pdef")], [out("again.pdef")]), "draco_encoder",
               draco_encode)
        for label, grid in (("default grid, ~1 mm", None), ("--resolution 316", "316"),
                            ("316x316", "316x316"), ("500x500", "500x500"), ("1000x1000", "1000x1000")):
            argv = [PDEFACE, "decode", pdef, "-o", out("face.ply")] + (["--resolution", grid] if grid else [])
            vertices = subprocess.run(argv, check=True, capture_output=True, text=True).stdout.split(": ")[1]
            vertices = vertices.split(" vertices")[0]
            versus(f"decode → PLY, {label} ({vertices} vertices) (process)", (argv, [out("face.ply")]),
                   "draco_decoder", draco_decode, target="> 1")
        million = os.path.getsize(out("face.ply"))
        r = alternate({"dd": (["dd", "if=/dev/zero", f"of={out('zeros')}", "bs=1100000",
                               f"count={million // 1100000 + 1}"], [out("zeros")]),
                       "draco": draco_decode}, runs)
        rows.append((f"floor at 1M: the {million / 1e6:.0f} MB file's bytes written by dd (process)",
                     process_cell(r["dd"]), f"draco_decoder {process_cell(r['draco'])}",
                     ratio(r["draco"]["wall"] / r["dd"]["wall"]), ""))
        versus("landmark detection + alignment: `pdeface align` (process)",
               ([PDEFACE, "align", scan, "-o", out("aligned.ply")], [out("aligned.ply")]), "draco_encoder",
               draco_encode)
        versus("compare, one scan: `pdeface compare` (process)",
               ([PDEFACE, "compare", scan, "--out", out("report")], []), "draco_encoder", draco_encode,
               count=1 if args.quick else 3)
        for label, mine, rival in (
                ("peak memory: decode → PLY 1M vertices",
                 [PDEFACE, "decode", pdef, "-o", out("face.ply"), "--resolution", "1000x1000"], draco_decode[0]),
                ("peak memory: encode", [PDEFACE, "encode", scan, "-o", out("again.pdef")], draco_encode[0]),
                ("peak memory: compare, one scan", [PDEFACE, "compare", scan, "--out", out("report")],
                 draco_encode[0])):
            a, b = peak_kb(mine, []), peak_kb(rival, [])
            if a and b:
                figures[label] = {"pdeface_kb": a, "draco_kb": b}
                rival_name = os.path.basename(rival[0])
                rows.append((label, f"{a / 1024:.1f} MiB", f"{rival_name} {b / 1024:.1f} MiB",
                             ratio(b / a), ""))

        # In process (CPU time, medians).
        pdef_bench = google_benchmark("pdef_bench", repetitions, min_time)
        figures["pdef_bench"] = {k: v["cpu_ms"] for k, v in pdef_bench.items()}
        for mine, rival, label in (
                ("pdef_to_mesh/lossy_warm", "libdraco_decode/warm",
                 ".pdef → 100k-vertex mesh with normals, warm (in process)"),
                ("pdef_to_mesh/lossy_fresh", "libdraco_decode/fresh",
                 ".pdef → 100k-vertex mesh with normals, fresh memory (in process)"),
                ("pdef_to_mesh/lossy_warm_sse2", "libdraco_decode/warm",
                 ".pdef → 100k-vertex mesh, SSE2 only, warm (in process)"),
                ("pdef_to_mesh/lossless_warm", "libdraco_decode/warm",
                 "lossless .pdef → 100k-vertex mesh, warm (in process)")):
            if mine in pdef_bench and rival in pdef_bench:
                a, b = pdef_bench[mine]["cpu_ms"], pdef_bench[rival]["cpu_ms"]
                target = "≤ 1 ms, ≥ 4×" if mine == "pdef_to_mesh/lossy_warm" else ""
                rows.append((label, ms(a), f"libdraco {ms(b)}", ratio(b / a), target))
        align_bench = google_benchmark("align_bench", repetitions, min_time, "detect_scan/facefuns")
        if "detect_scan/facefuns" in align_bench and "libdraco_decode/warm" in pdef_bench:
            a, b = align_bench["detect_scan/facefuns"]["cpu_ms"], pdef_bench["libdraco_decode/warm"]["cpu_ms"]
            figures["detect_in_process_ms"] = a
            rows.append(("landmark detection on the scan (in process)", ms(a), f"libdraco decode {ms(b)}",
                         ratio(b / a), ""))
        readers = google_benchmark("readers_bench", repetitions, min_time)
        totals = {}
        for name, b in readers.items():
            fmt = name.split("/")[1]
            bytes_, seconds = totals.get(fmt, (0.0, 0.0))
            totals[fmt] = (bytes_ + b["file_bytes"], seconds + b["cpu_ms"] / 1e3)
        targets = {"ply_binary": 1000, "ply_ascii": 300, "obj": 300, "wrl": 300}
        names = {"ply_binary": "binary PLY", "ply_ascii": "ASCII PLY (f18 written as text)", "obj": "OBJ",
                 "wrl": "VRML"}
        for fmt in ("ply_binary", "ply_ascii", "obj", "wrl"):
            if fmt in totals:
                bytes_, seconds = totals[fmt]
                rate = bytes_ / seconds / 1e6
                figures[f"reader_{fmt}_MBps"] = rate
                count = sum(1 for n in readers if n.split("/")[1] == fmt)
                rows.append((f"reader: {names[fmt]}, {count} file(s), {bytes_ / 1e6:.1f} MB (in process)",
                             f"{rate:,.0f} MB/s", "", f"{ratio(rate / targets[fmt])} the target",
                             f"≥ {targets[fmt]:,} MB/s"))
    finally:
        shutil.rmtree(work, ignore_errors=True)

    print(f"pdeface vs Draco, one run: {note}; whole processes {runs} runs alternating (median wall "
          f"[CPU]), in process median CPU of {repetitions}; {os.cpu_count()} CPUs, load {load:.1f} at the start, "
          f"{os.getloadavg()[0]:.1f} at the end")
    print()
    print("| stage | pdeface | Draco, same run | Draco ÷ pdeface (> 1: pdeface faster, smaller) | target |")
    print("|---|---|---|---|---|")
    for row in rows:
        print("| " + " | ".join(row) + " |")
    if args.json:
        with open(args.json, "w", encoding="utf-8") as f:
            json.dump(figures, f, indent=1)


if __name__ == "__main__":
    main()
