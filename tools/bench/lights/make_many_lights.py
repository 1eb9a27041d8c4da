#!/usr/bin/env python3
"""Writes scenes/many-lights.json: a room lit by 248 small lamps (issue 18 item 3).

A 16 x 14 grid of small one-sided quads under the ceiling, facing down, in
eight colours and powers (0.3x to 3x), 24 small sphere sconces on the side
walls, and occluders: four pillars, a partition wall, a table and a few
spheres. Deterministic (no random numbers): rerun it to get the same file.
Usage: make_many_lights.py [--peer] [OUT]   (default: scenes/many-lights.json beside this repo's tools/)

--peer writes the variant that Blender's Cycles renders exactly as we do (tools/peers/cycles/,
default OUT tools/peers/cycles/scenes/many-lights-peer.json): the pillars as square boxes (the
converter has no cylinder), the gold ball a Lambert one (Cycles 3.4 has no complex-index Fresnel),
and the sconces small square quads facing into the room instead of spheres (Cycles would get each
as a 256 x 128 UV-sphere mesh of emitting triangles). Still 248 emitters, 36 x 24 pixels.
"""
import json
import os
import sys

ROOM_X, ROOM_Z0, ROOM_Z1, ROOM_Y = 4.0, -6.0, 2.0, 3.0
LAMP_COLOURS = [  # emission of each lamp material: colour times power
    (1.0, 0.85, 0.6), (0.6, 0.75, 1.0), (1.0, 0.5, 0.35), (0.7, 1.0, 0.6),
    (1.0, 1.0, 1.0), (0.9, 0.6, 1.0), (1.0, 0.95, 0.8), (0.5, 0.9, 0.9)]
LAMP_POWERS = [0.3, 0.6, 1.0, 1.5, 2.0, 3.0, 0.8, 1.2]
LAMP_RADIANCE = 12.0
LAMP_HALF = 0.06


def quad(name, material, v):
    return {"type": "quad", "name": name, "material": material, "vertices": [list(map(float, p)) for p in v]}


def box_sides(name, material, x, z, half, top):
    """The four sides of a vertical square pillar (outward faces; floor and ceiling hide the ends)."""
    c = [(x - half, z + half), (x + half, z + half), (x + half, z - half), (x - half, z - half)]
    return [quad("%s side %d" % (name, k), material, [(a[0], 0, a[1]), (b[0], 0, b[1]), (b[0], top, b[1]),
                                                     (a[0], top, a[1])])
            for k, (a, b) in enumerate(zip(c, c[1:] + c[:1]))]


def scene(peer=False):
    materials = {
        "wall": {"type": "lambert", "diffuse": [0.7, 0.68, 0.64]},
        "floor": {"type": "lambert", "diffuse": [0.45, 0.4, 0.35]},
        "pillar": {"type": "lambert", "diffuse": [0.6, 0.6, 0.62]},
        "table": {"type": "lambert", "diffuse": [0.5, 0.3, 0.15]},
        "red": {"type": "lambert", "diffuse": [0.7, 0.12, 0.1]},
        "metal": ({"type": "lambert", "diffuse": [0.8, 0.6, 0.2]} if peer
                  else {"type": "conductor", "metal": "Au", "roughness": 0.25}),
        "sconce": {"type": "lambert", "diffuse": [0, 0, 0], "emission": [40, 30, 18]},
    }
    for i, (c, p) in enumerate(zip(LAMP_COLOURS, LAMP_POWERS)):
        materials["lamp%d" % i] = {"type": "lambert", "diffuse": [0, 0, 0],
                                   "emission": [round(LAMP_RADIANCE * p * x, 3) for x in c]}
    X, Z0, Z1, Y = ROOM_X, ROOM_Z0, ROOM_Z1, ROOM_Y
    shapes = [
        quad("floor", "floor", [(-X, 0, Z1), (X, 0, Z1), (X, 0, Z0), (-X, 0, Z0)]),
        quad("ceiling", "wall", [(-X, Y, Z0), (X, Y, Z0), (X, Y, Z1), (-X, Y, Z1)]),
        quad("back wall", "wall", [(-X, 0, Z0), (X, 0, Z0), (X, Y, Z0), (-X, Y, Z0)]),
        quad("front wall", "wall", [(X, 0, Z1), (-X, 0, Z1), (-X, Y, Z1), (X, Y, Z1)]),
        quad("left wall", "wall", [(-X, 0, Z1), (-X, 0, Z0), (-X, Y, Z0), (-X, Y, Z1)]),
        quad("right wall", "wall", [(X, 0, Z0), (X, 0, Z1), (X, Y, Z1), (X, Y, Z0)]),
        quad("partition", "wall", [(-1.5, 0, -3.0), (1.5, 0, -3.0), (1.5, 2.2, -3.0), (-1.5, 2.2, -3.0)]),
        quad("partition back", "wall", [(1.5, 0, -3.01), (-1.5, 0, -3.01), (-1.5, 2.2, -3.01), (1.5, 2.2, -3.01)]),
        quad("table", "table", [(-0.9, 0.8, 0.2), (0.9, 0.8, 0.2), (0.9, 0.8, -1.0), (-0.9, 0.8, -1.0)]),
        {"type": "sphere", "name": "red ball", "material": "red", "center": [-1.6, 0.45, -0.6], "radius": 0.45},
        {"type": "sphere", "name": "gold ball", "material": "metal", "center": [0.3, 1.1, -0.4], "radius": 0.3},
        {"type": "sphere", "name": "far ball", "material": "red", "center": [1.2, 0.5, -4.6], "radius": 0.5},
    ]
    for i, (x, z) in enumerate([(-2.2, -1.6), (2.2, -1.6), (-2.2, -4.4), (2.2, -4.4)]):
        if peer:
            shapes += box_sides("pillar %d" % i, "pillar", x, z, 0.2, Y)
        else:
            shapes.append({"type": "cylinder", "name": "pillar %d" % i, "material": "pillar",
                           "p0": [x, 0.0, z], "p1": [x, Y, z], "radius": 0.22})
    lamps = 0
    nx, nz = 16, 14
    for j in range(nz):
        for i in range(nx):
            x = -X + (i + 0.5) * (2 * X / nx)
            z = Z0 + (j + 0.5) * ((Z1 - Z0) / nz)
            h = LAMP_HALF
            m = "lamp%d" % ((i * 3 + j * 5) % len(LAMP_COLOURS))
            y = Y - 0.08
            shapes.append(quad("lamp %d %d" % (i, j), m, [(x - h, y, z - h), (x + h, y, z - h), (x + h, y, z + h),
                                                         (x - h, y, z + h)]))
            lamps += 1
    for k in range(12):
        z = Z0 + 0.4 + k * (Z1 - Z0 - 0.8) / 11
        for side in (-1, 1):
            name, cx = "sconce %d %d" % (k, side), side * (X - 0.08)
            if peer:  # a square of the sphere's cross-section, facing into the room (-side x)
                h, z = 0.035, round(z, 4)
                v = [(cx, 1.8 - h, z - h), (cx, 1.8 - h, z + h), (cx, 1.8 + h, z + h), (cx, 1.8 + h, z - h)]
                shapes.append(quad(name, "sconce", v if side > 0 else v[::-1]))
            else:
                shapes.append({"type": "sphere", "name": name, "material": "sconce",
                               "center": [cx, 1.8, round(z, 4)], "radius": 0.04})
            lamps += 1
    return {
        "format": "pathtracer-scene", "version": 1,
        "camera": {"position": [0.0, 1.5, 1.8], "look_at": [0.0, 1.1, -4.0], "up": [0, 1, 0], "fov": 62},
        "film": {"width": 36, "height": 24} if peer else {"width": 240, "height": 160},
        "render": {"integrator": "path", "max_depth": 5, "spp": 16},
        "materials": materials,
        "shapes": shapes,
    }, lamps


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    args = sys.argv[1:]
    peer = "--peer" in args
    args = [a for a in args if a != "--peer"]
    default = (os.path.join(here, "..", "..", "peers", "cycles", "scenes", "many-lights-peer.json") if peer
               else os.path.join(here, "..", "..", "..", "scenes", "many-lights.json"))
    out = args[0] if args else default
    s, lamps = scene(peer)
    one = lambda v: json.dumps(v, separators=(", ", ": "))
    lines = ["{", '  "format": "pathtracer-scene", "version": 1,']
    for key in ("camera", "film", "render"):
        lines.append('  "%s": %s,' % (key, one(s[key])))
    lines.append('  "materials": {')
    mats = list(s["materials"].items())
    lines += ['    "%s": %s%s' % (k, one(v), "," if i + 1 < len(mats) else "") for i, (k, v) in enumerate(mats)]
    lines.append("  },")
    lines.append('  "shapes": [')
    lines += ["    %s%s" % (one(v), "," if i + 1 < len(s["shapes"]) else "") for i, v in enumerate(s["shapes"])]
    lines += ["  ]", "}"]
    with open(out, "w") as f:
        f.write("\n".join(lines) + "\n")
    print("%s: %d emitters" % (os.path.normpath(out), lamps))


if __name__ == "__main__":
    main()
