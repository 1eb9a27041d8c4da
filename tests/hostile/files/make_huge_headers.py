#!/usr/bin/env python3
"""Writes the two tiny images whose headers declare huge sizes (hostile cases
texture-huge-declared-size and environment-huge-declared-size):

  huge-declared-size.png  70 bytes: IHDR 100000 x 100000 RGB, one small IDAT
  huge-declared-size.exr  a 4x2 tiled EXR whose header is patched to declare
                          40000 x 40000 pixels in 2048 x 2048 tiles (small enough
                          for OpenEXR to open the file in little memory), with an
                          offset table of the right length (400 tiles,
                          all pointing at the one real tile)

Run in this folder:
  oiiotool --pattern constant:color=0.5,0.5,0.5 4x2 3 -d half --tile 16 16 -o /tmp/tiled.exr
  python3 make_huge_headers.py /tmp/tiled.exr
"""
import struct
import sys
import zlib


def png_chunk(kind, data):
    return struct.pack('>I', len(data)) + kind + data + struct.pack('>I', zlib.crc32(kind + data) & 0xffffffff)


def huge_png():
    ihdr = struct.pack('>IIBBBBB', 100000, 100000, 8, 2, 0, 0, 0)
    return (b'\x89PNG\r\n\x1a\n' + png_chunk(b'IHDR', ihdr) + png_chunk(b'IDAT', zlib.compress(b'\0' * 301)) +
            png_chunk(b'IEND', b''))


def huge_exr(tiled, width=40000, height=40000, tile=2048):
    b = bytearray(tiled)
    i = 8  # magic and version
    while b[i] != 0:  # attributes: name, type, size, value; an empty name ends the header
        n = b.index(0, i)
        name = bytes(b[i:n])
        t = b.index(0, n + 1)
        size, = struct.unpack('<i', b[t + 1:t + 5])
        d = t + 5
        if name in (b'dataWindow', b'displayWindow'):
            b[d:d + 16] = struct.pack('<4i', 0, 0, width - 1, height - 1)
        if name == b'tiles':
            b[d:d + 8] = struct.pack('<II', tile, tile)
        i = d + size
    table = i + 1
    first, = struct.unpack('<Q', b[table:table + 8])
    tiles = -(-width // tile) * -(-height // tile)
    shift = 8 * (tiles - 1)
    b[table:table + 8] = b''.join(struct.pack('<Q', first + shift) for _ in range(tiles))
    return bytes(b)


if __name__ == '__main__':
    with open('huge-declared-size.png', 'wb') as f:
        f.write(huge_png())
    with open(sys.argv[1], 'rb') as f:
        exr = huge_exr(f.read())
    with open('huge-declared-size.exr', 'wb') as f:
        f.write(exr)
