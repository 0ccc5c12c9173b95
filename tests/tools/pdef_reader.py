#!/usr/bin/env python3
"""A .pdef reader written from docs/pdef-format.md alone (no code shared with the C++ decoder), for lossy
files: it checks the container, decodes every section and prints the document, the samples with 17
significant digits, one line per sample: "j k x y z filled". The tests compare its output with the C++
decoder's (PdefSpec.AnIndependentReaderAgrees). Lossless files need zstd and are only described.

A version 3 file (or any prefix of one that holds its curves) then has its residual layer: a line
"residual width W height H levels … step Δ(mm) planes P stream S held n complete 0|1" and H lines of W
offsets (mm, 17 digits), line k the nodes (0 … W−1, k), then "trim bytes T held n complete 0|1 cells c"
and a line of the c trimmed cells' indices k·(W − 1) + i (empty without any); or "residual none: …" when
the file is cut inside the layer's header (PdefSpec.AnIndependentReaderReadsTheResidualLayer).

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


class Truncated(Bad):
    pass


class Reader:
    def __init__(self, data, pos, end):
        self.data, self.pos, self.end = data, pos, end

    def take(self, n):
        if self.pos + n > self.end:
            raise Truncated("truncated at byte %d" % self.pos)
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


#  The residual layer (version 3)

ALPHA, BETA = -1.586134342059924, -0.052980118572961
GAMMA, DELTA = 0.882911075530934, 0.443506852043971
ZETA_LOW, ZETA_HIGH = 1.139764007654642, 0.887277075635907
LEVELS = 4  # node levels: sides 2, 4, 8, 16; level-4 nodes are the roots


class Starved(Exception):
    """The range decoder needed a byte beyond the prefix: the decision asked for is not the encoder's."""


class RangeDecoder:
    """LZMA's binary range decoder over the stream's bytes held: 145 adaptive probabilities of a 0
    (0-143 starting at 1280, 144 at 1024), and even decisions."""

    def __init__(self, stream):
        self.data, self.pos, self.starved = stream, 0, False
        self.range, self.code = 0xFFFFFFFF, 0
        for _ in range(4):
            self.code = (self.code << 8) | self.next_byte()
        self.p = [1280] * 144 + [1024]

    def next_byte(self):
        if self.pos >= len(self.data):
            self.starved = True
            return 0
        self.pos += 1
        return self.data[self.pos - 1]

    def normalise(self):
        while self.range < 2 ** 24:
            self.range = (self.range << 8) & 0xFFFFFFFF
            self.code = ((self.code << 8) | self.next_byte()) & 0xFFFFFFFF

    def bit(self, context):
        if self.starved:
            raise Starved()
        p = self.p[context]
        bound = (self.range >> 11) * p
        if self.code < bound:
            self.range = bound
            self.p[context] = p + ((2048 - p) >> 5)
            out = 0
        else:
            self.code -= bound
            self.range -= bound
            self.p[context] = p - (p >> 5)
            out = 1
        self.normalise()
        return out

    def even(self):
        if self.starved:
            raise Starved()
        self.range >>= 1
        out = 0
        if self.code >= self.range:
            self.code -= self.range
            out = 1
        self.normalise()
        return out


def levels_for(w, h):
    levels = 0
    while levels < 8 and w >= 8 and h >= 8:
        w, h, levels = (w + 1) // 2, (h + 1) // 2, levels + 1
    return levels


def band_sizes(W, H, levels):  # (w_l, h_l) for l = 0 … levels
    sizes = [(W, H)]
    for _ in range(levels):
        w, h = sizes[-1]
        sizes.append(((w + 1) // 2, (h + 1) // 2))
    return sizes


def subbands(W, H, levels):
    """(x0, y0, x1, y1, kind) of every band in coding order: the low band, then each level's from the last."""
    sizes = band_sizes(W, H, levels)
    bands = [(0, 0, sizes[levels][0], sizes[levels][1], 0)]
    for l in range(levels - 1, -1, -1):
        (w, h), (w1, h1) = sizes[l], sizes[l + 1]
        bands += [(w1, 0, w, h1, 1), (0, h1, w1, h, 1), (w1, h1, w, h, 2)]
    return bands


def decode_stream(stream, W, H, levels, planes):
    """The bit-planes: each coefficient's magnitude m, sign and the lowest plane known (None: never
    significant), as far as the stream's bytes held determine them."""
    m, negative, lowest, first = [0] * (W * H), [False] * (W * H), [None] * (W * H), [0] * (W * H)
    bands = []
    for i, (x0, y0, x1, y1, kind) in enumerate(subbands(W, H, levels)):
        bands.append({"x0": x0, "y0": y0, "w": x1 - x0, "h": y1 - y0, "kind": kind,
                      "parent": i - 3 if i >= 4 else None})
    active = set()  # (band, t, p, q) of the active nodes

    def count(band, t):  # nodes of level t across and down
        side = 2 ** t
        return -(-band["w"] // side), -(-band["h"] // side)

    def exists(band, t, p, q):
        across, down = count(band, t)
        return 0 <= p < across and 0 <= q < down

    def significant(bi, x, y):
        return lowest[(bands[bi]["y0"] + y) * W + bands[bi]["x0"] + x] is not None

    def coefficient_context(bi, x, y, fresh):
        band = bands[bi]
        s = 0
        for yy in (y - 1, y, y + 1):
            for xx in (x - 1, x, x + 1):
                if (xx, yy) != (x, y) and 0 <= xx < band["w"] and 0 <= yy < band["h"] and significant(bi, xx, yy):
                    s += 1
        parent = 0
        if band["parent"] is not None:
            up = bands[band["parent"]]
            parent = 1 if significant(band["parent"], min(x // 2, up["w"] - 1), min(y // 2, up["h"] - 1)) else 0
        return 96 + 8 * (2 * band["kind"] + fresh) + 4 * parent + min(s, 3)

    def node_context(bi, t, p, q, fresh):
        band = bands[bi]
        near = any(exists(band, t, pp, qq) and (bi, t, pp, qq) in active
                   for pp, qq in ((p - 1, q), (p, q - 1), (p + 1, q), (p, q + 1)))
        parent = 0
        if band["parent"] is not None:
            up = bands[band["parent"]]
            if t == 1:
                parent = significant(band["parent"], min(p, up["w"] - 1), min(q, up["h"] - 1))
            else:
                across, down = count(up, t - 1)
                parent = (band["parent"], t - 1, min(p, across - 1), min(q, down - 1)) in active
        return 8 * (3 * (t - 1) + band["kind"]) + (4 if parent else 0) + 2 * fresh + (1 if near else 0)

    C, N, S = [], {t: [] for t in range(1, LEVELS + 1)}, []
    for bi, band in enumerate(bands):
        across, down = count(band, LEVELS)
        N[LEVELS] += [(bi, p, q) for q in range(down) for p in range(across)]
    rc = RangeDecoder(stream)

    def become_significant(bi, x, y, b):
        i = (bands[bi]["y0"] + y) * W + bands[bi]["x0"] + x
        sign = rc.even()  # read before anything changes: a sign beyond the bytes leaves it at 0
        negative[i] = sign == 1
        m[i], lowest[i], first[i] = 2 ** b, b, b
        S.append(i)

    def split(bi, t, p, q, b):
        band = bands[bi]
        children = [(2 * p + dx, 2 * q + dy) for dy in (0, 1) for dx in (0, 1)
                    if (t > 1 and exists(band, t - 1, 2 * p + dx, 2 * q + dy)) or
                    (t == 1 and 2 * p + dx < band["w"] and 2 * q + dy < band["h"])]
        any_on = False
        for k, (cp, cq) in enumerate(children):
            inferred = not any_on and k == len(children) - 1
            if t == 1:
                if inferred or rc.bit(coefficient_context(bi, cp, cq, 1)):
                    any_on = True
                    become_significant(bi, cp, cq, b)
                else:
                    C.append((bi, cp, cq))
            else:
                if inferred or rc.bit(node_context(bi, t - 1, cp, cq, 1)):
                    any_on = True
                    active.add((bi, t - 1, cp, cq))
                    split(bi, t - 1, cp, cq, b)
                else:
                    N[t - 1].append((bi, cp, cq))

    try:
        for b in range(planes - 1, -1, -1):
            before = len(S)
            kept = []
            for bi, x, y in C:
                if rc.bit(coefficient_context(bi, x, y, 0)):
                    become_significant(bi, x, y, b)
                else:
                    kept.append((bi, x, y))
            C[:] = kept
            for t in (1, 2, 0, 3, 4):  # 0: the refinement pass, between the sets of levels 2 and 3
                if t == 0:
                    for i in S[:before]:
                        bit = rc.bit(144) if first[i] == b + 1 else rc.even()
                        m[i] |= bit << b
                        lowest[i] = b
                    continue
                entries, N[t] = N[t], []
                for bi, p, q in entries:
                    if rc.bit(node_context(bi, t, p, q, 0)):
                        active.add((bi, t, p, q))
                        split(bi, t, p, q, b)
                    else:
                        N[t].append((bi, p, q))
    except Starved:
        pass
    return m, negative, lowest


def inverse_lift(values):
    """The inverse one-dimensional CDF 9/7 transform of n ≥ 2 values stored as [lows …, highs …]."""
    n, lows = len(values), (len(values) + 1) // 2
    x = [0.0] * n
    for i in range(n):
        if i < lows:
            x[2 * i] = values[i] / ZETA_LOW
        else:
            x[2 * (i - lows) + 1] = values[i] / ZETA_HIGH

    def at(i):  # symmetric extension
        return x[1] if i < 0 else x[n - 2] if i >= n else x[i]

    # x −= c (a + b) as x − (c · (a + b)), each step over all its i before the next
    for parity, c in ((0, DELTA), (1, GAMMA), (0, BETA), (1, ALPHA)):
        for i in range(parity, n, 2):
            x[i] = x[i] - c * (at(i - 1) + at(i + 1))
    return x


def inverse_wavelet(c, W, H, levels):
    sizes = band_sizes(W, H, levels)
    for l in range(levels - 1, -1, -1):
        w, h = sizes[l]
        for x in range(w):
            column = inverse_lift([c[y * W + x] for y in range(h)])
            for y in range(h):
                c[y * W + x] = column[y]
        for y in range(h):
            c[y * W:y * W + w] = inverse_lift(c[y * W:y * W + w])
    return c


def decode_trim(stream, across, down):
    """The trimmed cells (a set of indices k·across + i) that the trim stream's bytes held determine."""
    rc = RangeDecoder(stream)
    rc.p = [1024] * 72
    top = 0
    while 2 ** top < max(across, down):
        top += 1
    trimmed = set()
    coded = {}  # (l, p, q) -> "kept" | "trimmed" | "mixed"

    def exists(l, p, q):
        return p * 2 ** l < across and q * 2 ** l < down

    def state(l, p, q):
        m = l
        while m <= top:
            s = coded.get((m, p, q))
            if s in ("kept", "trimmed"):
                return s
            if s == "mixed":
                return s if m == l else None
            m, p, q = m + 1, p // 2, q // 2
        return None

    def neighbours(l, p, q, what):
        n = 0
        for pp, qq in ((p - 1, q), (p, q - 1)):
            if pp >= 0 and qq >= 0 and exists(l, pp, qq) and state(l, pp, qq) in ("mixed", what):
                n += 1
        return n

    def code(l, p, q, t_known=None, k_known=None):
        lv = min(l, 11)
        t = t_known if t_known is not None else rc.bit((2 * lv) * 3 + neighbours(l, p, q, "trimmed"))
        if l == 0 or not t:
            k = not t
        elif k_known is not None:
            k = k_known
        else:
            k = rc.bit((2 * lv + 1) * 3 + neighbours(l, p, q, "kept"))
        coded[(l, p, q)] = "mixed" if t and k else "trimmed" if t else "kept"
        if t and not k:
            for y in range(q * 2 ** l, min(down, (q + 1) * 2 ** l)):
                for x in range(p * 2 ** l, min(across, (p + 1) * 2 ** l)):
                    trimmed.add(y * across + x)
        return bool(t), bool(k)

    try:
        t, k = code(top, 0, 0)
        mixed = [(0, 0)] if t and k else []
        for l in range(top - 1, -1, -1):
            following = []
            for p, q in mixed:
                children = [(2 * p + dx, 2 * q + dy) for dy in (0, 1) for dx in (0, 1) if exists(l, 2 * p + dx, 2 * q + dy)]
                any_t = any_k = False
                for i, (cp, cq) in enumerate(children):
                    last = i == len(children) - 1
                    t_known = k_known = None
                    if last and not any_t:
                        t_known = 1
                    if last and not any_k:
                        if l == 0:
                            t_known = 0
                        else:
                            k_known = 1
                    t, k = code(l, cp, cq, t_known, k_known)
                    any_t, any_k = any_t or t, any_k or k
                    if t and k:
                        following.append((cp, cq))
            mixed = following
    except Starved:
        pass
    return trimmed


def read_residual(data, L):
    """The layer after the checksum: its settings, and the offsets (None when cut inside its header)."""
    r = Reader(data, L, len(data))
    # A prefix that ends inside the header decodes to the curves alone, but what it holds is checked as it
    # is read: an unknown transform, a varint not in its shortest form or too long.
    T, trim_crc = 0, 0
    try:
        kind = r.u8()
        if kind not in (1, 2):
            raise Bad("residual layer kind %d at byte %d" % (kind, L))
        at_w = r.pos
        W, H = r.varint(), r.varint()
        at_levels = r.pos
        levels = r.u8()
        at_step = r.pos
        step = r.varint()
        at_planes = r.pos
        planes = r.u8()
        if kind == 2:
            at_t = r.pos
            T = r.varint()
            trim_crc_at = r.pos
            trim_crc = struct.unpack("<I", r.take(4))[0]
        at_s = r.pos
        S = r.varint()
        stream_crc = struct.unpack("<I", r.take(4))[0]
        header_crc_at = r.pos
        header_crc = struct.unpack("<I", r.take(4))[0]
    except Truncated:
        return {"cut": True}
    if zlib.crc32(data[L:header_crc_at]) != header_crc:
        raise Bad("the residual header's checksum at byte %d" % header_crc_at)
    if W < 2 or H < 2:
        raise Bad("a residual grid below 2 at byte %d" % at_w)
    if W > 4097 or H > 4097 or W * H > 2 ** 18 + 256 * len(data):
        raise Bad("a residual grid too large at byte %d" % at_w)
    if levels > levels_for(W, H):
        raise Bad("too many wavelet levels at byte %d" % at_levels)
    if step == 0 or step >= MAX_Q:
        raise Bad("a residual step out of range at byte %d" % at_step)
    if planes == 0 or planes > 40:
        raise Bad("a bit-plane count out of range at byte %d" % at_planes)
    if kind == 2 and T > MAX_Q:
        raise Bad("a residual trim too long at byte %d" % at_t)
    if S > MAX_Q:
        raise Bad("a residual stream too long at byte %d" % at_s)
    trim_start = r.pos
    start = trim_start + T
    if len(data) - trim_start > T + S:
        raise Bad("bytes after the residual stream at byte %d" % (start + S))
    trim = data[trim_start:min(len(data), start)]
    if kind == 2 and len(trim) == T and zlib.crc32(trim) != trim_crc:
        raise Bad("the residual trim's checksum at byte %d" % trim_crc_at)
    stream = data[start:] if len(data) > start else b""
    complete = len(stream) == S
    if complete and zlib.crc32(stream) != stream_crc:
        raise Bad("the residual stream's checksum at byte %d" % (header_crc_at - 4))
    trimmed = decode_trim(trim, W - 1, H - 1) if T > 0 and len(trim) > 0 else set()
    m, negative, lowest = decode_stream(stream, W, H, levels, planes)
    delta = step * UNIT
    c = [0.0] * (W * H)
    for i in range(W * H):
        if lowest[i] is not None:
            v = (m[i] + 2 ** lowest[i] / 2) * delta
            c[i] = -v if negative[i] else v
    return {"cut": False, "W": W, "H": H, "levels": levels, "step": delta, "planes": planes, "S": S,
            "held": len(stream), "complete": complete, "offsets": inverse_wavelet(c, W, H, levels),
            "T": T, "trim_held": len(trim), "trim_complete": kind == 2 and len(trim) == T, "trimmed": trimmed}


def print_residual(layer):
    if layer["cut"]:
        print("residual none: cut inside the layer's header")
        return
    print("residual width %d height %d levels %d step %.17g planes %d stream %d held %d complete %d" % (
        layer["W"], layer["H"], layer["levels"], layer["step"], layer["planes"], layer["S"], layer["held"],
        layer["complete"]))
    W = layer["W"]
    for k in range(layer["H"]):  # row k: v = k·π/(H − 1), its W nodes across u
        print(" ".join("%.17g" % d for d in layer["offsets"][k * W:(k + 1) * W]))
    print("trim bytes %d held %d complete %d cells %d" % (layer["T"], layer["trim_held"], layer["trim_complete"],
                                                       len(layer["trimmed"])))
    print(" ".join(str(c) for c in sorted(layer["trimmed"])))


def main(path):
    data = open(path, "rb").read()
    if data[:4] != b"PDEF":
        raise Bad("bad magic")
    version = data[4]
    if version not in (2, 3):
        raise Bad("unknown version %d" % version)
    flags = data[5]
    if flags & ~1:
        raise Bad("unknown flags")
    length = struct.unpack_from("<I", data, 6)[0]
    if length > len(data) or (version == 2 and length != len(data)):
        raise Bad("length %d, file %d" % (length, len(data)))
    print_curves(data[:length], length, flags)
    if version == 3:
        print_residual(read_residual(data, length))


def print_curves(data, length, flags):
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
