#!/usr/bin/env python3
"""Compares our render of a scene of spheres with Cycles' render of the same scene, region by region.

    compare_images.py SCENE.json OURS.exr CYCLES.exr [--png-prefix docs/compare/x] [--json out.json]

Each sphere of the scene (native format, pinhole camera) is a region: the pixels whose centre ray
hits the sphere shrunk to 90% of its radius (so no pixel on a silhouette counts); the background is
the pixels whose centre ray misses every sphere grown to 110%. For each region and the whole image
it prints the mean RGB of both images and their ratio ours / Cycles (per channel and of the channel
means). With --png-prefix it writes PREFIX-ours.png, PREFIX-cycles.png (sRGB), PREFIX-diff.png (the
signed difference of the channel means, ours - Cycles, scaled by --diff-scale: red where ours is
brighter, blue where darker) and PREFIX-side.png (the three side by side).

Needs only Python 3 and oiiotool (Debian: openimageio-tools); images are read with
`oiiotool --dumpdata`.
"""
import argparse
import json
import math
import os
import re
import subprocess
import sys
import tempfile


def read_rgb(path):
    """(width, height, [(r, g, b)] in row-major order from the top) of an image's first three channels."""
    out = subprocess.run(["oiiotool", "--dumpdata", "--info", path], capture_output=True, text=True, check=True).stdout
    lines = out.splitlines()
    m = re.search(r":\s+(\d+)\s+x\s+(\d+),", lines[0])
    w, h = int(m.group(1)), int(m.group(2))
    px = []
    for line in lines[1:]:
        if line.strip().startswith("Pixel"):
            vals = line.split(":", 1)[1].split()
            px.append(tuple(float(v) for v in vals[:3]))
    if len(px) != w * h:
        raise RuntimeError(f"{path}: read {len(px)} pixels, expected {w * h}")
    return w, h, px


def sub(a, b):
    return [a[i] - b[i] for i in range(3)]


def dot(a, b):
    return sum(a[i] * b[i] for i in range(3))


def norm(a):
    l = math.sqrt(dot(a, a))
    return [x / l for x in a]


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def camera_rays(scene, w, h):
    """The pinhole camera's ray direction through each pixel centre (docs/scene-format.md, camera)."""
    cam = scene["camera"]
    if cam.get("type", "pinhole") not in ("pinhole", "perspective"):
        raise SystemExit("compare_images.py: only pinhole cameras")
    pos = cam["position"]
    fwd = norm(sub(cam["look_at"], pos))
    right = norm(cross(fwd, cam.get("up", [0, 1, 0])))
    up = cross(right, fwd)
    t = math.tan(math.radians(cam.get("fov", 45)) / 2)
    for y in range(h):
        for x in range(w):
            sx = (2 * (x + 0.5) / w - 1) * t * w / h
            sy = (1 - 2 * (y + 0.5) / h) * t
            yield pos, norm([fwd[i] + sx * right[i] + sy * up[i] for i in range(3)])


def hit(o, d, c, r):
    oc = sub(o, c)
    b = dot(oc, d)
    disc = b * b - (dot(oc, oc) - r * r)
    return disc >= 0 and -b + math.sqrt(disc) > 0


def regions(scene, w, h):
    """Per pixel: the name of the sphere it shows, 'background', or None (a silhouette pixel)."""
    spheres = [(s.get("name", f"shapes[{i}]"), s["center"], s["radius"])
               for i, s in enumerate(scene["shapes"]) if s["type"] == "sphere" and "transform" not in s]
    labels = []
    for o, d in camera_rays(scene, w, h):
        label = "background"
        for name, c, r in spheres:
            if hit(o, d, c, 0.9 * r):
                label = name
                break
            if hit(o, d, c, 1.1 * r):
                label = None
        labels.append(label)
    return [name for name, _, _ in spheres], labels


def mean(px, idx):
    n = max(1, len(idx))
    return [sum(px[i][c] for i in idx) / n for c in range(3)]


def write_png(path, w, h, rgb8):
    """Writes 8-bit RGB rows through a PPM and oiiotool."""
    with tempfile.NamedTemporaryFile(suffix=".ppm", delete=False) as f:
        f.write(b"P6 %d %d 255\n" % (w, h))
        f.write(bytes(v for p in rgb8 for v in p))
        tmp = f.name
    subprocess.run(["oiiotool", tmp, "-o", path], check=True)
    os.unlink(tmp)


def srgb8(v):
    v = max(0.0, min(1.0, v))
    v = 12.92 * v if v <= 0.0031308 else 1.055 * v ** (1 / 2.4) - 0.055
    return int(round(255 * v))


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("scene")
    p.add_argument("ours")
    p.add_argument("cycles")
    p.add_argument("--png-prefix")
    p.add_argument("--diff-scale", type=float, default=4.0, help="difference images: |diff| x this is full red/blue")
    p.add_argument("--json")
    a = p.parse_args()
    scene = json.load(open(a.scene))
    w, h, ours = read_rgb(a.ours)
    w2, h2, cyc = read_rgb(a.cycles)
    if (w, h) != (w2, h2):
        raise SystemExit(f"sizes differ: {w}x{h} and {w2}x{h2}")
    names, labels = regions(scene, w, h)
    rows = []
    for name in ["image"] + names + ["background"]:
        idx = range(w * h) if name == "image" else [i for i, l in enumerate(labels) if l == name]
        mo, mc = mean(ours, idx), mean(cyc, idx)
        ratio = [mo[c] / mc[c] if mc[c] > 0 else float("nan") for c in range(3)]
        rows.append({"region": name, "pixels": len(idx), "ours": mo, "cycles": mc, "ratio": ratio,
                     "ratio_mean": sum(mo) / sum(mc) if sum(mc) > 0 else float("nan")})
    print(f"{'region':12} {'pixels':>6}  {'ours (mean RGB)':>24}  {'Cycles (mean RGB)':>24}  ratio R G B, mean")
    for r in rows:
        f3 = lambda v: " ".join(f"{x:7.4f}" for x in v)
        print(f"{r['region']:12} {r['pixels']:6d}  {f3(r['ours'])}  {f3(r['cycles'])}  "
              f"{f3(r['ratio'])}  {r['ratio_mean']:.4f}")
    if a.json:
        json.dump(rows, open(a.json, "w"), indent=1)
    if a.png_prefix:
        pre = a.png_prefix
        write_png(pre + "-ours.png", w, h, [tuple(srgb8(v) for v in p) for p in ours])
        write_png(pre + "-cycles.png", w, h, [tuple(srgb8(v) for v in p) for p in cyc])
        diff = []
        for po, pc in zip(ours, cyc):
            d = (sum(po) - sum(pc)) / 3 * a.diff_scale
            v = int(round(255 * min(1.0, abs(d))))
            diff.append((v, 0, 0) if d > 0 else (0, 0, v))
        write_png(pre + "-diff.png", w, h, diff)
        subprocess.run(["oiiotool", pre + "-ours.png", pre + "-cycles.png", pre + "-diff.png",
                        "--mosaic:pad=4", "3x1", "-o", pre + "-side.png"], check=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
