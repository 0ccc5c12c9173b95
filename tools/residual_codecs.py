#!/usr/bin/env python3
"""The residual layer's coder beside image codecs at equal bytes (third_party_notes/residual.md).

    build/benchmarks/residual_rd --spacing 0.7 --dump DIR SCAN...   # fields, masks, our coder's RMS
    tools/residual_codecs.py DIR

For every dumped field (a 16-bit PGM, one unit the coder's finest step): JPEG 2000 (OpenJPEG's
opj_compress, EBCOT) with the reversible 5/3 and the irreversible 9/7 wavelet, and AVIF at 12 bits (libaom's
AV1 transforms, monochrome), each at a range of settings; every file decoded and the RMS error of the
offsets on the found nodes measured (mm), then each codec's RMS interpolated (log-log) at our stream
sizes. Prints a Markdown table. Needs numpy, opj_compress/opj_decompress (libopenjp2-tools) and
avifenc/avifdec (libavif-bin), ImageMagick's convert.
"""

import json
import math
import pathlib
import subprocess
import sys
import tempfile

import numpy as np


def read_pgm(path):
    data = path.read_bytes()
    parts, pos = [], 0
    while len(parts) < 4:  # P5, width, height, maxval, separated by whitespace and # comments
        while data[pos:pos + 1].isspace() or data[pos:pos + 1] == b"#":
            if data[pos:pos + 1] == b"#":
                pos = data.index(b"\n", pos)
            pos += 1
        end = pos
        while not data[end:end + 1].isspace():
            end += 1
        parts.append(data[pos:end])
        pos = end
    pos += 1
    width, height, maxval = int(parts[1]), int(parts[2]), int(parts[3])
    dtype = ">u2" if maxval > 255 else "u1"
    return np.frombuffer(data[pos:], dtype=dtype, count=width * height).reshape(height, width).astype(np.float64)


def rms(a, b, mask, step):
    d = (a - b)[mask] * step
    return float(np.sqrt(np.mean(d * d)))


def run(*args):
    subprocess.run(list(map(str, args)), check=True, capture_output=True)


def jpeg2000(pgm, tmp, irreversible):
    raw = pgm.stat().st_size
    points = []
    for ratio in (4000, 2000, 1000, 500, 250, 120, 60, 30, 15, 8, 4):
        out = tmp / f"j{int(irreversible)}_{ratio}.j2k"
        back = tmp / f"j{int(irreversible)}_{ratio}.pgm"
        run("opj_compress", "-i", pgm, "-o", out, "-r", ratio, *(["-I"] if irreversible else []))
        run("opj_decompress", "-i", out, "-o", back)
        points.append((out.stat().st_size, read_pgm(back)))
    return points


def avif(pgm, tmp):
    png = tmp / "field.png"
    run("convert", pgm, "-depth", "16", png)
    points = []
    for q in (60, 55, 50, 45, 40, 35, 30, 25, 20, 15, 10, 6, 3, 1):
        out, back, back_pgm = tmp / f"a{q}.avif", tmp / f"a{q}.png", tmp / f"a{q}.pgm"
        run("avifenc", "-d", "12", "-y", "400", "--min", q, "--max", q, "-s", "6", png, out)
        run("avifdec", "-d", "16", out, back)
        run("convert", back, "-depth", "16", "-colorspace", "gray", back_pgm)
        points.append((out.stat().st_size, read_pgm(back_pgm)))
    return points


def at(points, size):
    """The RMS a codec's (bytes, rms) points give at `size`, log-log between neighbours; None outside."""
    points = sorted(points)
    for (b0, r0), (b1, r1) in zip(points, points[1:]):
        if b0 <= size <= b1 and r0 > 0 and r1 > 0:
            t = (math.log(size) - math.log(b0)) / (math.log(b1) - math.log(b0))
            return math.exp(math.log(r0) + t * (math.log(r1) - math.log(r0)))
    return None


def main(folder):
    folder = pathlib.Path(folder)
    rows = []
    for meta_path in sorted(folder.glob("*.json")):
        meta = json.loads(meta_path.read_text())
        stem = meta_path.with_suffix("")
        pgm, field = stem.with_suffix(".pgm"), read_pgm(stem.with_suffix(".pgm"))
        mask = read_pgm(pathlib.Path(str(stem) + ".mask.pgm")) > 0
        step = meta["step_mm"]
        with tempfile.TemporaryDirectory() as t:
            tmp = pathlib.Path(t)
            codecs = {"JPEG 2000 5/3": jpeg2000(pgm, tmp, False), "JPEG 2000 9/7": jpeg2000(pgm, tmp, True),
                      "AVIF 12-bit": avif(pgm, tmp)}
            measured = {name: [(b, rms(field, img, mask, step)) for b, img in pts] for name, pts in codecs.items()}
        for o in meta["ours"]:
            row = {"scan": pathlib.Path(meta["scan"]).name, "grid": f'{meta["width"]} x {meta["height"]}',
                   "bytes": o["bytes"], "ours": o["rms_mm"]}
            for name, pts in measured.items():
                row[name] = at(pts, o["bytes"])
            rows.append(row)
    names = ["JPEG 2000 5/3", "JPEG 2000 9/7", "AVIF 12-bit"]
    print("| scan | grid | bytes | ours (mm) | " + " | ".join(f"{n} (mm, × ours)" for n in names) + " |")
    print("|---|---|---:|---:|" + "---:|" * len(names))
    for r in rows:
        cells = [f'{r[n]:.4f} ({r[n] / r["ours"]:.2f}×)' if r[n] else "–" for n in names]
        print(f'| {r["scan"]} | {r["grid"]} | {r["bytes"]} | {r["ours"]:.4f} | ' + " | ".join(cells) + " |")
    ratios = {n: [r[n] / r["ours"] for r in rows if r[n]] for n in names}
    print()
    for n in names:
        if ratios[n]:
            g = math.exp(sum(map(math.log, ratios[n])) / len(ratios[n]))
            print(f"{n}: RMS {g:.2f}× ours (geometric mean over {len(ratios[n])} points)")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else ".")
