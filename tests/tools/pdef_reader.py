#!/usr/bin/env python3
"""A .pdef reader written from docs/pdef-format.md alone (no code shared with the C++ decoder), for lossy
files: it checks the container, decodes every section and prints the document, the samples with 17
significant digits, one line per sample: "j k x y z filled". The tests compare its output with the C++
decoder's (PdefSpec.AnIndependentReaderAgrees). Lossless files need zstd and are only described.

Usage: python3 pdef_reader.py FILE.pdef
"""
import math
import struct
import sys
import zlib

UNIT = 2.0 ** -20
MAX_Q = 2 ** 26
DEFAULT_WEIGHTS = [[3621, 82, 3395, -3123, 141, 292, -324], [3635, -744, 225, -101, 897, 310, -659]]
LEVEL_WEIGHT = [0] + [round(4 * 2 ** (q / 2)) for q in range(1, 32)]


class Bad(Exception):
    pass


class Reader:
    def __init__(self, data, pos, end):
        self.data, self.pos, self.end = data, pos, end

    def take(self, n):
        if self.pos + n > self.end:
            raise Bad("truncated at byte %d" % self.pos)
        out = self.data[self.pos:self.pos + n]
        self.pos += n
        return out

    def u8(self):
        return self.take(1)[0]

    def f32(self):
        return struct.unpack("<f", self.take(4))[0]

    def f64(self):
        return struct.unpack("<d", self.take(8))[0]

    def varint(self, max_bytes=5):
        value = 0
        for i in range(max_bytes):
            b = self.u8()
            value |= (b & 0x7F) << (7 * i)
            if b < 0x80:
                if b == 0 and i > 0:
                    raise Bad("a varint not in its shortest form")
                if value >= 2 ** (32 if max_bytes == 5 else 64):
                    raise Bad("a varint too large")
                return value
        raise Bad("a varint too long")

    def svarint(self, max_bytes=5):
        u = self.varint(max_bytes)
        return (u >> 1) ^ -(u & 1)


def rounded_div(n, d):  # round(n / d), d > 0, halves away from zero
    return (2 * n + d) // (2 * d) if n >= 0 else -((-2 * n + d) // (2 * d))


def predict(a, planes, K, w, j, k):
    def at(jj, kk):
        return a[jj * K + kk]

    if j >= 2:
        near, far = planes[j] - planes[j - 1], planes[j - 1] - planes[j - 2]

        def across(kk):
            return max(-(2 ** 30), min(2 ** 30, rounded_div((at(j - 1, kk) - at(j - 2, kk)) * near, far)))

        f = [0] * 7
        f[2] = across(k)
        if k >= 1:
            f[0] = at(j, k - 1) - at(j - 1, k - 1)
            f[3] = across(k - 1)
            f[6] = at(j - 1, k) - at(j - 1, k - 1)
        if k >= 2:
            f[1] = at(j, k - 2) - at(j - 1, k - 2)
        if k + 1 < K:
            f[4] = across(k + 1)
            f[5] = at(j - 1, k + 1) - at(j - 1, k)
        s = sum(wi * fi for wi, fi in zip(w, f))
        p = at(j - 1, k) + ((s + 2048) >> 12 if s >= 0 else -((-s + 2048) >> 12))
    elif j == 1:
        p = at(1, k - 1) + at(0, k) - at(0, k - 1) if k >= 1 else at(0, k)
    elif k >= 2:
        p = 2 * at(0, k - 1) - at(0, k - 2)
    else:
        p = at(0, 0) if k == 1 else 0
    return max(-MAX_Q, min(MAX_Q, p))


def class_base(c):  # the smallest symbol of class c and its lower bits' count
    if c < 4:
        return c, 0
    b = (c - 4) // 2 + 2
    return (2 + ((c - 4) & 1)) << (b - 1), b - 1


def decode_classes(r, count):
    used = r.u8()
    if used > 64:
        raise Bad("more than 64 classes")
    table = r.take((used * 5 + 7) // 8)
    bits = int.from_bytes(table, "little")
    levels = [(bits >> (5 * c)) & 31 for c in range(used)] + [0] * (64 - used)
    if used == 0 or levels[used - 1] == 0 or bits >> (5 * used):
        raise Bad("a bad class table")
    total = sum(LEVEL_WEIGHT[q] for q in levels)
    freq = [max(1, LEVEL_WEIGHT[q] * 4096 // total) if q else 0 for q in levels]
    largest = max(range(64), key=lambda c: (freq[c], -c))
    freq[largest] += 4096 - sum(freq)
    cum = [sum(freq[:c]) for c in range(64)]
    size = r.varint(4)
    data = r.take(size)
    # Draco's rANS: the final state at the end of the data (its top two bits say how many bytes)
    x = data[-1] >> 6
    if x + 1 > size:
        raise Bad("a bad rANS state")
    offset = size - 1 - x
    state = int.from_bytes(data[offset:size], "little") & ((1 << (6 + 8 * x)) - 1)
    state += 16384
    symbols = []
    for _ in range(count):
        while state < 16384 and offset > 0:
            offset -= 1
            state = state * 256 + data[offset]
        quo, rem = divmod(state, 4096)
        c = max(i for i in range(64) if freq[i] and cum[i] <= rem)
        state = quo * freq[c] + rem - cum[c]
        symbols.append(c)
    nbits = sum(class_base(c)[1] for c in symbols)
    rest = int.from_bytes(r.take((nbits + 7) // 8), "little")
    if rest >> nbits:
        raise Bad("lower bits' padding is not zero")
    out = []
    for c in symbols:
        base, n = class_base(c)
        out.append(base + (rest & ((1 << n) - 1)))
        rest >>= n
    return out


def unzigzag(u):
    return (u >> 1) ^ -(u & 1)


def read_heights(r, X, J, K, step):
    """y of every sample (units of 2^-20 mm) from its curve's extent and the anchors' relative heights."""
    s, h, flags = r.varint(), r.u8(), r.u8()
    if s < 1 or s >= J or (J - 1) % s or h < 1 or h > 16 or flags & ~1:
        raise Bad("a bad heights layout")
    extents = [unzigzag(u) for u in decode_classes(r, 2 * J)]
    lines = []
    for d in (extents[:J], extents[J:]):
        v = []
        for j in range(J):
            v.append(d[j] if j == 0 else v[0] + d[j] if j == 1 else d[j] + 2 * v[j - 1] - v[j - 2])
        lines.append(v)
    B, T = lines
    if any(abs(b) > MAX_Q for b in B + T) or any(not 0 < (T[j] - B[j]) * step < 2 ** 32 for j in range(J)):
        raise Bad("a bad extent")
    n = (J - 1) // s + 1
    stored = (n + 1) // 2 if flags & 1 else n
    codes = decode_classes(r, stored * (K - 2))
    H = [[0] * K for _ in range(n)]
    for a in range(n):
        H[a][K - 1] = 2 ** h
        for k in range(1, K - 1):
            mirror = n - 1 - a
            if flags & 1 and a >= stored:
                H[a][k] = H[mirror][k]
                continue
            if mirror < a:
                p = H[mirror][k]
            elif a > 0:
                p = H[a - 1][k] + H[a][k - 1] - H[a - 1][k - 1]
            else:
                p = rounded_div(2 ** h, K - 1) if k == 1 else 2 * H[0][k - 1] - H[0][k - 2]
            H[a][k] = p + unzigzag(codes[a * (K - 2) + k - 1])
            if not 0 <= H[a][k] <= 2 ** h:
                raise Bad("a relative height outside 0..2^h")
    rest = [unzigzag(u) for u in decode_classes(r, J * (K - 2))]
    y = []
    for j in range(J):
        b, t, a = B[j] * step, T[j] * step, j // s
        w = 0 if j % s == 0 else rounded_div(4096 * (X[j] - X[a * s]), X[(a + 1) * s] - X[a * s])
        for k in range(K):
            if k == 0:
                y.append(b)
            elif k == K - 1:
                y.append(t)
            else:
                m = (4096 - w) * H[a][k] + (w * H[a + 1][k] if w else 0)
                y.append(b + rounded_div((t - b) * m, 2 ** (h + 12)) + rest[j * (K - 2) + k - 1] * step)
    return y


def main(path):
    data = open(path, "rb").read()
    if data[:4] != b"PDEF":
        raise Bad("bad magic")
    if data[4] != 2:
        raise Bad("unknown version %d" % data[4])
    flags = data[5]
    if flags & ~1:
        raise Bad("unknown flags")
    length = struct.unpack_from("<I", data, 6)[0]
    if length != len(data):
        raise Bad("length %d, file %d" % (length, len(data)))
    if zlib.crc32(data[:-4]) != struct.unpack_from("<I", data, length - 4)[0]:
        raise Bad("checksum mismatch")
    lossless = flags & 1
    pos, sections = 10, {}
    while pos < length - 4:
        r = Reader(data, pos, length - 4)
        tag, size = r.u8(), r.varint()
        sections[tag] = (r.pos, r.pos + size)
        pos = r.pos + size
    r = Reader(data, *sections[1])
    units = ["unknown", "mm", "cm", "m", "inch"][r.u8()]
    precision = r.u8()
    if precision == 4:
        qx, qy, qz = r.f32(), r.f32(), r.f32()
        t = [r.f32() for _ in range(3)]
        scale = r.f32()
    else:
        rotation = [r.f64() for _ in range(9)]
        t = [r.f64() for _ in range(3)]
        scale = r.f64()
    surface = r.u8()
    a = r.f64()
    J, K, N = r.varint(), r.varint(), r.varint()
    print("units %s scale %.17g scheme %d spacing %s remainder %d a %.17g J %d K %d N %d" % (
        units, scale, surface & 3, "physical" if surface & 4 else "uniform", (surface >> 3) & 1, a, J, K, N))
    if lossless:
        print("lossless: samples in a zstd frame (not decoded here)")
        return
    step, plane_step = r.varint(), r.varint()
    r = Reader(data, *sections[2])
    runs = [r.varint() for _ in range(r.varint())]
    across, state = [], False  # sample by sample across the curves
    for run in runs:
        across += [state] * run
        state = not state
    filled = [across[(i % K) * J + i // K] for i in range(J * K)]
    X = []
    for j in range(J):
        v = r.svarint(10)
        X.append(v if j == 0 else X[0] + v if j == 1 else v + 2 * X[-1] - X[-2])
    coords = []
    for c in range(2):
        kind = r.u8()
        if c == 0 and kind == 2:
            coords.append(read_heights(r, X, J, K, step))
            continue
        if kind > 1:
            raise Bad("unknown kind %d" % kind)
        w = DEFAULT_WEIGHTS[c] if kind == 0 else [r.svarint() for _ in range(7)]
        symbols = decode_classes(r, J * K)
        a_values = []
        for i, s in enumerate(symbols):
            a_values.append(predict(a_values + [0], X, K, w, i // K, i % K) + ((s >> 1) ^ -(s & 1)))
        coords.append([v * step for v in a_values])
    if r.pos != r.end:
        raise Bad("bytes left in the curves section")
    print("step %.17g plane_step %.17g" % (step * UNIT, plane_step * UNIT))
    for j in range(J):
        for k in range(K):
            i = j * K + k
            print("%d %d %.17g %.17g %.17g %d" % (j, k, X[j] * plane_step * UNIT, coords[0][i] * UNIT,
                                                  coords[1][i] * UNIT, filled[i]))


if __name__ == "__main__":
    try:
        main(sys.argv[1])
    except Bad as e:
        print("pdef_reader: %s: %s" % (sys.argv[1], e), file=sys.stderr)
        sys.exit(1)
