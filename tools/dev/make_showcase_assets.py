#!/usr/bin/env python3
"""Generates the showcase scene's assets (our own, no downloads):

  scenes/assets/torus_knot.ply   binary PLY: a (2,3) torus knot tube with
                                 per-vertex normals and texture coordinates
  scenes/assets/checker.png      floor texture: a 16x16 checkerboard
  scenes/assets/uv_grid.png      sphere texture: a colour-coded UV grid
  scenes/assets/dimples_normal.png  tangent-space normal map (green up): a grid of round dimples

Only the Python standard library is used (zlib for PNG). The output is
deterministic: running it again rewrites identical files.

    python3 tools/dev/make_showcase_assets.py [--out scenes/assets]
"""

import argparse
import colorsys
import math
import os
import struct
import zlib


# ---------------------------------------------------------------- PNG

def write_png(path, width, height, rows):
    """rows: a list of `height` bytes objects of width*3 RGB8 values each."""
    def chunk(kind, data):
        body = kind + data
        return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body) & 0xFFFFFFFF)

    raw = b"".join(b"\x00" + row for row in rows)  # filter type 0 on every row
    png = (b"\x89PNG\r\n\x1a\n"
           + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0))
           + chunk(b"IDAT", zlib.compress(raw, 9))
           + chunk(b"IEND", b""))
    with open(path, "wb") as f:
        f.write(png)


def checker_rows(size=512, checks=16):
    light, dark = bytes((214, 208, 196)), bytes((62, 70, 84))
    cell = size // checks
    rows = []
    for y in range(size):
        row = bytearray()
        for x in range(size):
            row += light if ((x // cell) + (y // cell)) % 2 == 0 else dark
        rows.append(bytes(row))
    return rows


def uv_grid_rows(width=1024, height=512, cells_u=16, cells_v=8):
    """Hue runs with u, lightness with v; thin dark lines on the cell borders."""
    rows = []
    line = 2
    for y in range(height):
        v = (y + 0.5) / height
        row = bytearray()
        for x in range(width):
            u = (x + 0.5) / width
            cx, cy = x % (width // cells_u), y % (height // cells_v)
            if cx < line or cy < line:
                rgb = (0.08, 0.08, 0.1)
            else:
                checker = ((x * cells_u // width) + (y * cells_v // height)) % 2
                light = 0.35 + 0.3 * (1.0 - v) + 0.08 * checker
                rgb = colorsys.hls_to_rgb(u, light, 0.65)
            row += bytes(int(round(255 * max(0.0, min(1.0, c)))) for c in rgb)
        rows.append(bytes(row))
    return rows


def dimples_normal_rows(size=256, cells=8, radius=0.38, depth=0.35):
    """A tangent-space normal map of round dimples (spherical caps pressed into
    the surface): x to the right, y up the image, z out of the surface."""
    rows = []
    cell = size / cells
    for y in range(size):
        row = bytearray()
        for x in range(size):
            # Position in the cell, in cell units, y up the image.
            px = ((x + 0.5) % cell) / cell - 0.5
            py = 0.5 - ((y + 0.5) % cell) / cell
            r2 = px * px + py * py
            if r2 < radius * radius:
                # Inside a dimple the surface slopes down towards its centre:
                # the normal leans towards the centre.
                n = normalize((-px * depth / radius, -py * depth / radius, 1.0))
            else:
                n = (0.0, 0.0, 1.0)
            row += bytes(int(round(255 * (0.5 * c + 0.5))) for c in n)
        rows.append(bytes(row))
    return rows


# ---------------------------------------------------------------- torus knot

def sub(a, b): return (a[0] - b[0], a[1] - b[1], a[2] - b[2])
def add(a, b): return (a[0] + b[0], a[1] + b[1], a[2] + b[2])
def mul(a, s): return (a[0] * s, a[1] * s, a[2] * s)
def dot(a, b): return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
def cross(a, b): return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])
def normalize(a): return mul(a, 1.0 / math.sqrt(dot(a, a)))


def torus_knot(p=2, q=3, segments=480, sides=36, scale=0.42, tube=0.13, centre=(0.0, 1.45, -1.8)):
    """A (p,q) torus knot tube in the world's xy plane (facing +z), centred at
    `centre`. Returns (positions, normals, uvs, triangles). The frame around the
    curve uses the fixed axis z (the tangent is never parallel to it), so it
    closes exactly and the seam vertices coincide."""
    def curve(t):
        r = 2.0 + math.cos(q * t)
        return (r * math.cos(p * t) * scale, r * math.sin(p * t) * scale, -math.sin(q * t) * scale)

    positions, normals, uvs = [], [], []
    for i in range(segments + 1):
        t = 2.0 * math.pi * (i % segments) / segments
        c = curve(t)
        h = 1e-4
        tangent = normalize(sub(curve(t + h), curve(t - h)))
        side = normalize(cross(tangent, (0.0, 0.0, 1.0)))
        up = cross(side, tangent)
        for j in range(sides + 1):
            phi = 2.0 * math.pi * (j % sides) / sides
            n = add(mul(side, math.cos(phi)), mul(up, math.sin(phi)))
            positions.append(add(add(c, mul(n, tube)), centre))
            normals.append(n)
            uvs.append((8.0 * i / segments, j / sides))  # the texture repeats 8 times along the tube

    triangles = []
    stride = sides + 1
    for i in range(segments):
        for j in range(sides):
            a, b = i * stride + j, (i + 1) * stride + j
            triangles.append((a, b, b + 1))
            triangles.append((a, b + 1, a + 1))

    # Wind the triangles counter-clockwise seen from outside (along the normals).
    a, b, c = triangles[0]
    geometric = cross(sub(positions[b], positions[a]), sub(positions[c], positions[a]))
    if dot(geometric, normals[a]) < 0:
        triangles = [(x, z, y) for (x, y, z) in triangles]
    return positions, normals, uvs, triangles


def write_ply(path, positions, normals, uvs, triangles):
    header = "\n".join([
        "ply",
        "format binary_little_endian 1.0",
        "comment (2,3) torus knot, generated by tools/dev/make_showcase_assets.py",
        "element vertex %d" % len(positions),
        "property float x", "property float y", "property float z",
        "property float nx", "property float ny", "property float nz",
        "property float u", "property float v",
        "element face %d" % len(triangles),
        "property list uchar int vertex_indices",
        "end_header",
    ]) + "\n"
    vertex = struct.Struct("<8f")
    face = struct.Struct("<B3i")
    with open(path, "wb") as f:
        f.write(header.encode("ascii"))
        f.write(b"".join(vertex.pack(*p, *n, *uv) for p, n, uv in zip(positions, normals, uvs)))
        f.write(b"".join(face.pack(3, *t) for t in triangles))


def main():
    root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--out", default=os.path.join(root, "scenes", "assets"), help="output folder")
    args = parser.parse_args()
    os.makedirs(args.out, exist_ok=True)

    positions, normals, uvs, triangles = torus_knot()
    write_ply(os.path.join(args.out, "torus_knot.ply"), positions, normals, uvs, triangles)
    write_png(os.path.join(args.out, "checker.png"), 512, 512, checker_rows())
    write_png(os.path.join(args.out, "uv_grid.png"), 1024, 512, uv_grid_rows())
    write_png(os.path.join(args.out, "dimples_normal.png"), 256, 256, dimples_normal_rows())
    for name in ("torus_knot.ply", "checker.png", "uv_grid.png", "dimples_normal.png"):
        path = os.path.join(args.out, name)
        print("%-40s %8d bytes" % (os.path.relpath(path), os.path.getsize(path)))
    print("torus knot: %d vertices, %d triangles" % (len(positions), len(triangles)))


if __name__ == "__main__":
    main()
