#!/usr/bin/env python3
"""Converts the film state in a file (a raw state, a checkpoint or a shard file) from version 4 to 5.

    python3 tools/dev/film_state_v4_to_v5.py FILE...   # in place

Used once, for the fuzz seeds (tests/fuzz/seeds) when version 5 came (docs/distributed.md, "Shard files");
the layouts are in src/render/film/film_state.cpp and film_state_codec.cpp. Exact: a slot whose value the
compact record cannot hold goes to the exception list, as Film::write_state does.
"""
import math
import struct
import sys

MAGIC = b"PTFILM\r\n"
# Per AovType number: (exact sums, plain values, ranked); src/render/film/aov.cpp's catalogue.
AOVS = [(3, 0, False), (3, 0, False), (0, 4, False), (0, 2, False), (0, 2, False), (0, 2, False), (3, 0, False),
        (3, 0, False), (3, 0, False), (3, 0, False), (3, 0, False), (6, 0, False), (0, 0, False), (0, 1, False),
        (3, 0, False), (2, 0, True), (2, 0, True)]


def plain_float(bits):
    exponent, mantissa = (bits >> 23) & 0xFF, bits & 0x7FFFFF
    if exponent == 0:
        return mantissa == 0
    if exponent == 0xFF:
        return mantissa == 0 or (mantissa & 0x400000) != 0
    return True


def as_float(dbits):
    d = struct.unpack("<d", struct.pack("<Q", dbits))[0]
    try:
        fbytes = struct.pack("<f", d)
    except OverflowError:
        return None
    if math.isnan(d):
        return None  # not produced by renders; kept exact in the list
    fbits = struct.unpack("<I", fbytes)[0]
    back = struct.unpack("<Q", struct.pack("<d", struct.unpack("<f", fbytes)[0]))[0]
    return fbits if plain_float(fbits) and back == dbits else None


def convert(data):
    at = data.index(MAGIC)
    version, w, h, x0, y0, x1, y1, count = struct.unpack_from("<IIIiiiiI", data, at + 8)
    assert version == 4, f"film state version {version}"
    kinds, values = [], 0
    p = at + 8 + 32
    for _ in range(count):
        t, _ct, ranks = data[p], data[p + 1], data[p + 2]
        p += 3
        sums, vals, ranked = AOVS[t]
        kinds += ["u32", "i64"] * ranks if ranked else ["i64"] * sums
        values += vals
    header_end = p + 24 + 1 + 12 + 12  # the non-finite report
    n = (x1 - x0) * (y1 - y0)
    body = data[header_end:]
    assert len(body) == n * (88 + 16 * len(kinds) + 8 * values), "size"
    sums_at, values_at = n * 88, n * (88 + 16 * len(kinds))
    records, exceptions = bytearray(), []

    def i128(off):
        lo, hi = struct.unpack_from("<QQ", body, off)
        return (hi << 64) | lo

    for i in range(n):
        slots = [("i64", i128(i * 88 + 16 * k)) for k in range(5)]
        slots.append(("u32", struct.unpack_from("<Q", body, i * 88 + 80)[0]))
        slots += [(k, i128(sums_at + (i * len(kinds) + j) * 16)) for j, k in enumerate(kinds)]
        slots += [("f32", struct.unpack_from("<Q", body, values_at + (i * values + j) * 8)[0]) for j in range(values)]
        for s, (kind, v) in enumerate(slots):
            if kind == "i64":
                signed = v - (1 << 128) if v >> 127 else v
                fits = -(1 << 63) <= signed < (1 << 63)
                records += struct.pack("<q", signed if fits else 0)
            elif kind == "u32":
                fits = v < (1 << 32)
                records += struct.pack("<I", v if fits else 0)
            else:
                f = as_float(v)
                fits = f is not None
                records += struct.pack("<I", f if fits else 0)
            if not fits:
                exceptions.append(struct.pack("<QIQQ", i, s, v & (2**64 - 1), v >> 64))
    out = bytearray(data[:header_end])
    struct.pack_into("<I", out, at + 8, 5)
    return bytes(out) + struct.pack("<Q", len(exceptions)) + b"".join(exceptions) + bytes(records)


for name in sys.argv[1:]:
    with open(name, "rb") as f:
        converted = convert(f.read())
    with open(name, "wb") as f:
        f.write(converted)
    print(name)
