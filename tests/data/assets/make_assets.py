#!/usr/bin/env python3
"""Writes the small test assets of the importers (docs/importing.md), deterministically.

  obj/two_materials.{obj,mtl}  two quads, a red Lambert one and a textured Blinn-Phong one
                               (plus statements we do not support, for the warnings)
  obj/features.{obj,mtl}       six quads in a row: a map_d cutout, a bump map (-bm), an illum 3
                               mirror, an illum 7 glass, a rough metal with map_Ks and map_Ns, a
                               normal map (norm); with mask.png, stripes.png, tint.png, rough.png,
                               normal.png
  gltf/pbr.gltf + .bin         five quads in a row: alphaMode MASK on the base colour texture's
                               alpha, a metal with metallicRoughnessTexture and a normal map
                               (scale 0.5), a dielectric, metallic 0.5 x the same texture, alphaMode BLEND; with
                               base.png (RGBA), mr.png, normal.png
  gltf/pbr.glb                 the same, its images embedded
  obj/halves.png               the texture: top half red, bottom half blue (uv orientation)
  gltf/hierarchy.gltf + .bin   a node hierarchy: one box mesh placed three times, a ground whose
                               texture uses TEXCOORD_1, a two-primitive lamp (emissive + metal),
                               an alpha-masked leaf with a normal map, a perspective and an
                               orthographic camera, a directional, a point and a spot light
  gltf/halves.png              the same texture as obj/halves.png
  gltf/hierarchy.glb           the same scene as one binary file, the image embedded

Only the Python standard library is used. Run from anywhere: python3 tests/data/assets/make_assets.py
"""
import json
import math
import os
import struct
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))


def png_bytes(width, height, pixel):
    """pixel(x, y): a tuple of 1 (grey), 3 (RGB) or 4 (RGBA) 8-bit values."""
    rows = b"".join(b"\x00" + bytes(c for x in range(width) for c in pixel(x, y)) for y in range(height))
    colour_type = {1: 0, 3: 2, 4: 6}[len(pixel(0, 0))]

    def chunk(kind, data):
        body = kind + data
        return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body) & 0xFFFFFFFF)

    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, colour_type, 0, 0, 0))
            + chunk(b"IDAT", zlib.compress(rows, 9)) + chunk(b"IEND", b""))


def halves(x, y):
    """Top half red, bottom half blue, a green column at the left edge (u orientation)."""
    if x < 2:
        return (0, 200, 0)
    return (220, 20, 20) if y < 8 else (20, 20, 220)


def write(path, data):
    full = os.path.join(HERE, path)
    with open(full, "wb") as f:
        f.write(data if isinstance(data, bytes) else data.encode())


# ---------------------------------------------------------------- OBJ + MTL
OBJ = """# Two quads side by side in the z = 0 plane, facing +z, one per material.
mtllib two_materials.mtl
v -2 -1 0
v 0 -1 0
v 0 1 0
v -2 1 0
v 0 -1 0
v 2 -1 0
v 2 1 0
v 0 1 0
vt 0 0
vt 1 0
vt 1 1
vt 0 1
vn 0 0 1
o left
usemtl red
f 1/1/1 2/2/1 3/3/1 4/4/1
o right
usemtl textured
f 5/1/1 6/2/1 7/3/1 8/4/1
"""

MTL = """# Materials of two_materials.obj
newmtl red
Ka 0.1 0.1 0.1
Kd 0.8 0.1 0.1
Ks 0 0 0
illum 1

newmtl textured
Ka 0 0 0
Kd 1 1 1
Ks 0.1 0.1 0.1
Ns 50
illum 2
map_Kd halves.png
sharpness 60

newmtl unused_glass
Kd 0 0 0
Ni 1.45
d 0.2
Tf 0.9 1 0.9
illum 7
"""

# ---------------------------------------------------------------- glTF
class Buffer:
    def __init__(self):
        self.data = bytearray()
        self.views = []
        self.accessors = []

    def view(self, raw, target=None):
        while len(self.data) % 4:
            self.data.append(0)
        v = {"buffer": 0, "byteOffset": len(self.data), "byteLength": len(raw)}
        if target:
            v["target"] = target
        self.data += raw
        self.views.append(v)
        return len(self.views) - 1

    def accessor(self, values, kind):
        """values: list of tuples (float VECn) or ints (SCALAR uint16 indices)."""
        if kind == "SCALAR":
            raw = struct.pack("<%dH" % len(values), *values)
            acc = {"componentType": 5123, "count": len(values), "type": "SCALAR"}
            acc["bufferView"] = self.view(raw, 34963)
        else:
            n = len(values[0])
            raw = b"".join(struct.pack("<%df" % n, *v) for v in values)
            acc = {"componentType": 5126, "count": len(values), "type": kind}
            acc["bufferView"] = self.view(raw, 34962)
            if kind == "VEC3":
                acc["min"] = [min(v[i] for v in values) for i in range(3)]
                acc["max"] = [max(v[i] for v in values) for i in range(3)]
        self.accessors.append(acc)
        return len(self.accessors) - 1


def box():
    """A unit cube centred at the origin: 24 vertices (normals, uvs, tangents), 12 triangles."""
    pos, nrm, uv, tan, idx = [], [], [], [], []
    for axis in range(3):
        for sign in (1, -1):
            n = [0, 0, 0]
            n[axis] = sign
            u_axis, v_axis = (axis + 1) % 3, (axis + 2) % 3
            base = len(pos)
            for (a, b) in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
                p = [0.0, 0.0, 0.0]
                p[axis] = 0.5 * sign
                p[u_axis] = 0.5 * a * sign
                p[v_axis] = 0.5 * b
                pos.append(tuple(p))
                nrm.append(tuple(float(c) for c in n))
                uv.append(((a + 1) / 2, (1 - b) / 2))
                t = [0.0, 0.0, 0.0]
                t[u_axis] = float(sign)
                tan.append(tuple(t) + (1.0,))
            idx += [base, base + 1, base + 2, base, base + 2, base + 3]
    return pos, nrm, uv, tan, idx


def quad(size, y, up=True):
    h = size / 2
    pos = [(-h, y, h), (h, y, h), (h, y, -h), (-h, y, -h)]
    nrm = [(0.0, 1.0 if up else -1.0, 0.0)] * 4
    uv = [(0.0, 1.0), (1.0, 1.0), (1.0, 0.0), (0.0, 0.0)]  # glTF: v = 0 at the image's top
    idx = [0, 1, 2, 0, 2, 3] if up else [0, 2, 1, 0, 3, 2]
    return pos, nrm, uv, idx


def quat(axis, degrees):
    s = math.sin(math.radians(degrees) / 2)
    return [axis[0] * s, axis[1] * s, axis[2] * s, math.cos(math.radians(degrees) / 2)]


def gltf_scene(embed_image):
    buf = Buffer()
    bp, bn, bu, bt, bi = box()
    box_prim = {"attributes": {"POSITION": buf.accessor(bp, "VEC3"), "NORMAL": buf.accessor(bn, "VEC3"),
                               "TEXCOORD_0": buf.accessor(bu, "VEC2"), "TANGENT": buf.accessor(bt, "VEC4")},
                "indices": buf.accessor(bi, "SCALAR"), "material": 0}
    gp, gn, gu, gi = quad(6.0, 0.0)
    ground_prim = {"attributes": {"POSITION": buf.accessor(gp, "VEC3"), "NORMAL": buf.accessor(gn, "VEC3"),
                                  "TEXCOORD_0": buf.accessor([(0.5, 0.5)] * 4, "VEC2"),
                                  "TEXCOORD_1": buf.accessor(gu, "VEC2")},
                   "indices": buf.accessor(gi, "SCALAR"), "material": 1}
    lp, ln, lu, li = quad(0.5, 0.0, up=False)
    glow_prim = {"attributes": {"POSITION": buf.accessor(lp, "VEC3"), "NORMAL": buf.accessor(ln, "VEC3")},
                 "indices": buf.accessor(li, "SCALAR"), "material": 2}
    mp = [(x * 0.3, y * 0.3 + 0.2, z * 0.3) for (x, y, z) in bp]
    metal_prim = {"attributes": {"POSITION": buf.accessor(mp, "VEC3"), "NORMAL": buf.accessor(bn, "VEC3")},
                  "indices": buf.accessor(bi, "SCALAR"), "material": 3}
    fp, fn, fu, fi = quad(1.0, 0.0)
    leaf_prim = {"attributes": {"POSITION": buf.accessor(fp, "VEC3"), "NORMAL": buf.accessor(fn, "VEC3"),
                                "TEXCOORD_0": buf.accessor(fu, "VEC2")},
                 "indices": buf.accessor(fi, "SCALAR"), "material": 4}
    image = png_bytes(16, 16, halves)
    if embed_image:
        images = [{"bufferView": buf.view(image), "mimeType": "image/png", "name": "halves"}]
    else:
        images = [{"uri": "halves.png", "name": "halves"}]
    doc = {
        "asset": {"version": "2.0", "generator": "tests/data/assets/make_assets.py"},
        "extensionsUsed": ["KHR_lights_punctual", "KHR_materials_emissive_strength"],
        "scene": 0,
        "scenes": [{"name": "scene", "nodes": [0, 7, 8, 9, 10, 11]}],
        "nodes": [
            {"name": "root", "translation": [0, -1, 0], "children": [1, 5, 6, 12]},       # 0
            {"name": "boxes", "rotation": quat((0, 1, 0), 45), "children": [2, 3, 4]},  # 1
            {"name": "box_a", "mesh": 0, "translation": [-1.5, 0.5, 0]},                # 2
            {"name": "box_b", "mesh": 0, "translation": [1.5, 0.5, 0]},                 # 3
            {"name": "box_c", "mesh": 0, "translation": [0, 0.25, -1.5], "scale": [0.5, 0.5, 0.5]},  # 4
            {"name": "ground", "mesh": 1},                                              # 5
            {"name": "lamp", "mesh": 2, "translation": [0, 2.5, 0]},                   # 6
            {"name": "camera", "camera": 0, "translation": [0, 1.5, 7],
             "rotation": quat((1, 0, 0), -12)},                                         # 7
            {"name": "top_view", "camera": 1, "translation": [0, 8, 0],
             "rotation": quat((1, 0, 0), -90)},                                         # 8
            {"name": "sun", "rotation": quat((1, 0, 0), -60),
             "extensions": {"KHR_lights_punctual": {"light": 0}}},                     # 9
            {"name": "bulb", "translation": [2, 2, 2],
             "extensions": {"KHR_lights_punctual": {"light": 1}}},                     # 10
            {"name": "spot", "translation": [-2, 3, 1], "rotation": quat((1, 0, 0), -90),
             "extensions": {"KHR_lights_punctual": {"light": 2}}},                     # 11
            {"name": "leaf", "mesh": 3, "translation": [2.2, 0.01, 2.2]},             # 12
        ],
        "meshes": [
            {"name": "box", "primitives": [box_prim]},
            {"name": "ground", "primitives": [ground_prim]},
            {"name": "lamp", "primitives": [glow_prim, metal_prim]},
            {"name": "leaf", "primitives": [leaf_prim]},
        ],
        "materials": [
            {"name": "textured", "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "metallicFactor": 0,
                                                          "roughnessFactor": 1}},
            {"name": "tiles", "pbrMetallicRoughness": {"baseColorTexture": {"index": 0, "texCoord": 1},
                                                       "baseColorFactor": [0.9, 0.9, 0.9, 1],
                                                       "metallicFactor": 0, "roughnessFactor": 1}},
            {"name": "glow", "emissiveFactor": [1.0, 0.9, 0.8],
             "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 8.0}},
             "pbrMetallicRoughness": {"baseColorFactor": [0, 0, 0, 1], "metallicFactor": 0}},
            {"name": "gold", "pbrMetallicRoughness": {"baseColorFactor": [1.0, 0.77, 0.33, 1], "metallicFactor": 1,
                                                      "roughnessFactor": 0.02}},
            {"name": "leafy", "alphaMode": "MASK", "alphaCutoff": 0.4, "doubleSided": True,
             "normalTexture": {"index": 0},
             "pbrMetallicRoughness": {"baseColorFactor": [0.2, 0.6, 0.2, 1], "metallicFactor": 0,
                                      "roughnessFactor": 0.5}},
        ],
        "textures": [{"source": 0}],
        "images": images,
        "cameras": [
            {"name": "main", "type": "perspective",
             "perspective": {"yfov": 0.7, "aspectRatio": 1.5, "znear": 0.1, "zfar": 100}},
            {"name": "top", "type": "orthographic",
             "orthographic": {"xmag": 4.0, "ymag": 3.0, "znear": 0.1, "zfar": 100}},
        ],
        "extensions": {"KHR_lights_punctual": {"lights": [
            {"name": "sun", "type": "directional", "color": [1.0, 1.0, 0.9], "intensity": 2.0},
            {"name": "bulb", "type": "point", "color": [1.0, 0.8, 0.6], "intensity": 20.0},
            {"name": "spot", "type": "spot", "intensity": 30.0,
             "spot": {"innerConeAngle": 0.3, "outerConeAngle": 0.5}},
        ]}},
        "buffers": [{"byteLength": 0}],
        "bufferViews": buf.views,
        "accessors": buf.accessors,
    }
    return doc, close_buffer(doc, buf), image


def close_buffer(doc, buf):
    """Pads the binary buffer to 4 bytes, records its length in `doc` and returns its bytes."""
    while len(buf.data) % 4:
        buf.data.append(0)
    doc["buffers"][0]["byteLength"] = len(buf.data)
    return bytes(buf.data)


def glb(doc, binary):
    text = json.dumps(doc, separators=(",", ":")).encode()
    text += b" " * ((4 - len(text) % 4) % 4)
    body = struct.pack("<II", len(text), 0x4E4F534A) + text + struct.pack("<II", len(binary), 0x004E4942) + binary
    return struct.pack("<III", 0x46546C67, 2, 12 + len(body)) + body


# ---------------------------------------------------------------- OBJ + MTL features and glTF PBR
def row_of_quads(n, spacing=2.0, size=1.8):
    """n quads in the z = 0 plane facing +z, centred at x = (i - (n - 1) / 2) * spacing; uv (0, 0) at the
    bottom left (OBJ's convention; the importer flips v)."""
    pos, uv = [], []
    h = size / 2
    for i in range(n):
        cx = (i - (n - 1) / 2) * spacing
        pos += [(cx - h, -h, 0.0), (cx + h, -h, 0.0), (cx + h, h, 0.0), (cx - h, h, 0.0)]
        uv += [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)]
    return pos, uv


FEATURES = ["cutout", "bumpy", "mirror", "glass", "rough_metal", "normal_mapped"]

FEATURES_MTL = """# Materials of features.obj: what issue 16 maps onto the microfacet materials
newmtl cutout
Kd 0.8 0.8 0.8
illum 1
map_d mask.png

newmtl bumpy
Kd 0.8 0.8 0.8
illum 1
bump -bm 0.05 stripes.png

newmtl mirror
Kd 0 0 0
Ks 0.9 0.6 0.3
illum 3

newmtl glass
Kd 0 0 0
Ks 1 1 1
Ni 1.5
d 0.5
illum 7

newmtl rough_metal
Kd 0 0 0
Ks 1 1 1
Ns 50
map_Ks tint.png
map_Ns rough.png
illum 3

newmtl normal_mapped
Kd 0.8 0.8 0.8
illum 1
norm normal.png
"""


def features_obj():
    pos, uv = row_of_quads(len(FEATURES))
    lines = ["# Six quads in a row (x = -5 .. 5), facing +z, one per material of features.mtl", "mtllib features.mtl"]
    lines += ["v %g %g %g" % p for p in pos] + ["vt %g %g" % t for t in uv] + ["vn 0 0 1"]
    for i, name in enumerate(FEATURES):
        k = 4 * i
        lines += ["o %s" % name, "usemtl %s" % name,
                  "f %d/%d/1 %d/%d/1 %d/%d/1 %d/%d/1" % (k + 1, k + 1, k + 2, k + 2, k + 3, k + 3, k + 4, k + 4)]
    return "\n".join(lines) + "\n"


def mask(x, y):
    """Grey: white on the left half, black on the right half."""
    return (255,) if x < 8 else (0,)


def stripes(x, y):
    """Grey vertical bands, 4 texels wide (a height field of ridges along v)."""
    return (255,) if (x // 4) % 2 == 0 else (0,)


def tint(x, y):
    return (255, 200, 120)


def rough(x, y):
    return (128,)


def normal_tilted(x, y):
    """Tangent-space normal tilted towards +u: (0.5, 0, 0.866) encoded as (c + 1) / 2."""
    return (191, 128, 238)


def base_rgba(x, y):
    """Green, opaque on the left half, transparent on the right half."""
    return (40, 200, 40, 255) if x < 8 else (40, 200, 40, 0)


def metal_roughness(x, y):
    """glTF: G = roughness 0.5 (128), B = metalness 1."""
    return (0, 128, 255)


def pbr_scene(embed):
    buf = Buffer()
    n = 5
    pos, uv = row_of_quads(n)
    uv = [(u, 1.0 - v) for (u, v) in uv]  # glTF: v = 0 at the image's top
    images = [("base", png_bytes(16, 16, base_rgba)), ("mr", png_bytes(16, 16, metal_roughness)),
              ("normal", png_bytes(16, 16, normal_tilted))]
    meshes, nodes = [], []
    for i in range(n):
        q = pos[4 * i:4 * i + 4]
        prim = {"attributes": {"POSITION": buf.accessor(q, "VEC3"), "NORMAL": buf.accessor([(0.0, 0.0, 1.0)] * 4, "VEC3"),
                               "TEXCOORD_0": buf.accessor(uv[4 * i:4 * i + 4], "VEC2")},
                "indices": buf.accessor([0, 1, 2, 0, 2, 3], "SCALAR"), "material": i}
        meshes.append({"name": "quad%d" % i, "primitives": [prim]})
        nodes.append({"name": "quad%d" % i, "mesh": i})
    if embed:
        image_list = [{"bufferView": buf.view(data), "mimeType": "image/png", "name": name} for name, data in images]
    else:
        image_list = [{"uri": name + ".png", "name": name} for name, _ in images]
    doc = {
        "asset": {"version": "2.0", "generator": "tests/data/assets/make_assets.py"},
        "scene": 0,
        "scenes": [{"name": "scene", "nodes": list(range(n))}],
        "nodes": nodes,
        "meshes": meshes,
        "materials": [
            {"name": "masked", "alphaMode": "MASK", "alphaCutoff": 0.5,
             "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "metallicFactor": 0, "roughnessFactor": 1}},
            {"name": "metal_rough", "normalTexture": {"index": 2, "scale": 0.5},
             "pbrMetallicRoughness": {"baseColorFactor": [0.9, 0.6, 0.3, 1], "metallicFactor": 1,
                                      "roughnessFactor": 0.8, "metallicRoughnessTexture": {"index": 1}}},
            {"name": "plastic", "pbrMetallicRoughness": {"baseColorFactor": [0.2, 0.4, 0.8, 1], "metallicFactor": 0,
                                                         "roughnessFactor": 0.5}},
            {"name": "half_metal", "pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.8, 0.8, 1],
                                                            "metallicFactor": 0.5, "roughnessFactor": 0.3,
                                                            "metallicRoughnessTexture": {"index": 1}}},
            {"name": "blend", "alphaMode": "BLEND",
             "pbrMetallicRoughness": {"baseColorFactor": [1, 0, 0, 0.3], "metallicFactor": 0}},
        ],
        "textures": [{"source": 0}, {"source": 1}, {"source": 2}],
        "images": image_list,
        "buffers": [{"byteLength": 0}],
        "bufferViews": buf.views,
        "accessors": buf.accessors,
    }
    return doc, close_buffer(doc, buf), images


def write_features():
    write("obj/features.obj", features_obj())
    write("obj/features.mtl", FEATURES_MTL)
    for name, pixel in (("mask", mask), ("stripes", stripes), ("tint", tint), ("rough", rough),
                        ("normal", normal_tilted)):
        write("obj/%s.png" % name, png_bytes(16, 16, pixel))
    doc, binary, images = pbr_scene(embed=False)
    doc["buffers"][0]["uri"] = "pbr.bin"
    write("gltf/pbr.gltf", json.dumps(doc, indent=1) + "\n")
    write("gltf/pbr.bin", binary)
    for name, data in images:
        write("gltf/%s.png" % name, data)
    doc, binary, _ = pbr_scene(embed=True)
    write("gltf/pbr.glb", glb(doc, binary))


def main():
    write("obj/two_materials.obj", OBJ)
    write("obj/two_materials.mtl", MTL)
    image = png_bytes(16, 16, halves)
    write("obj/halves.png", image)
    doc, binary, _ = gltf_scene(embed_image=False)
    doc["buffers"][0]["uri"] = "hierarchy.bin"
    write("gltf/hierarchy.gltf", json.dumps(doc, indent=1) + "\n")
    write("gltf/hierarchy.bin", binary)
    write("gltf/halves.png", image)
    doc, binary, _ = gltf_scene(embed_image=True)
    write("gltf/hierarchy.glb", glb(doc, binary))
    write_features()


if __name__ == "__main__":
    main()
