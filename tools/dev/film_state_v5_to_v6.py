#!/usr/bin/env python3
"""Converts the film state in a file (a raw state, a checkpoint or a shard file) from version 5 to 6.

    python3 tools/dev/film_state_v5_to_v6.py FILE...   # in place

Used once, for the fuzz seeds (tests/fuzz/seeds) when version 6 came (docs/distributed.md, "Shard files");
the layouts are in src/render/film/film_state.cpp and film_state_codec.cpp. Version 5's full records
become the defaults (the slots every pixel holds alike, else 0), the record index and records that hold
only the slots that differ from the defaults, after a mask of them; the exceptions stay as they are.
"""
import struct
import sys

MAGIC = b"PTFILM\r\n"
# Per AovType number: (exact sums, plain values, ranked); src/render/film/aov.cpp's catalogue.
AOVS = [(3, 0, False), (3, 0, False), (0, 4, False), (0, 2, False), (0, 2, False), (0, 2, False), (3, 0, False),
        (3, 0, False), (3, 0, False), (3, 0, False), (3, 0, False), (6, 0, False), (0, 0, False), (0, 1, False),
        (3, 0, False), (2, 0, True), (2, 0, True)]
GROUP = 32  # records per entry of the record index


def convert(data):
    at = data.index(MAGIC)
    version, w, h, x0, y0, x1, y1, count = struct.unpack_from("<IIIiiiiI", data, at + 8)
    assert version == 5, f"film state version {version}"
    widths, values = [8] * 5 + [4], []
    p = at + 8 + 32
    for _ in range(count):
        t, _ct, ranks = data[p], data[p + 1], data[p + 2]
        p += 3
        sums, vals, ranked = AOVS[t]
        widths += [4, 8] * ranks if ranked else [8] * sums
        values += [4] * vals
    widths += values
    full = sum(widths)
    offsets = [sum(widths[:k]) for k in range(len(widths))]
    header_end = p + 24 + 1 + 12 + 12  # the non-finite report
    n = (x1 - x0) * (y1 - y0)
    (exceptions,) = struct.unpack_from("<Q", data, header_end)
    records_at = header_end + 8 + 28 * exceptions
    assert len(data) - records_at == n * full, "size"
    rec = [data[records_at + i * full:records_at + (i + 1) * full] for i in range(n)]
    slot = lambda r, k: r[offsets[k]:offsets[k] + widths[k]]  # noqa: E731
    defaults = bytearray(full)
    for k in range(len(widths)):
        if n and all(slot(r, k) == slot(rec[0], k) for r in rec):
            defaults[offsets[k]:offsets[k] + widths[k]] = slot(rec[0], k)
    body, index = bytearray(), []
    for i, r in enumerate(rec):
        if i % GROUP == 0:
            index.append(len(body))
        mask, held = bytearray((len(widths) + 7) // 8), bytearray()
        for k in range(len(widths)):
            if slot(r, k) != slot(defaults, k):
                mask[k // 8] |= 1 << (k % 8)
                held += slot(r, k)
        body += mask + held
    index.append(len(body))
    out = bytearray(data[:header_end])
    struct.pack_into("<I", out, at + 8, 6)
    return (bytes(out) + bytes(defaults) + data[header_end:records_at] + struct.pack(f"<{len(index)}Q", *index)
            + bytes(body))


for name in sys.argv[1:]:
    with open(name, "rb") as f:
        converted = convert(f.read())
    with open(name, "wb") as f:
        f.write(converted)
    print(name)
