"""Render one of our native scene files in Blender's Cycles, for side-by-side comparisons.

Run inside Blender (Debian's 3.4):

    blender -b --factory-startup --python tools/peers/cycles/scene_to_cycles.py -- \
        SCENE.json --spp N --seed S --threads T -o out.exr [--stats stats.json]

It builds a Cycles scene of the features both renderers share (tools/peers/cycles/README.md lists
them with every mapping and every difference), switches off every Cycles setting that would bias a
comparison, renders on the CPU and writes a linear 32-bit EXR. A scene using anything else is
refused (exit status 2) with one line per unsupported feature, before Blender renders anything.

Timing: `Cycles render time` on stdout (and in --stats) is measured around
bpy.ops.render.render() with time.perf_counter (scene sync, BVH build and path tracing; the EXR is
written afterwards, outside it); `path tracing time` is the span between the first and the last
stats lines Blender prints that report a sample count ("Sample 0/N" to "Sample N/N"), i.e.
Cycles' own progress timer over path tracing alone (bpy.app.handlers.render_stats passes no text
in 3.4, so the lines are read from the process's standard output).
"""
import json
import math
import os
import re
import sys
import time

import bpy
import mathutils

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.normpath(os.path.join(HERE, "..", "..", ".."))

# Our world is right-handed with the scene's own up (native scenes: +Y); Blender's is Z-up. Every
# position goes through TO_BLENDER = +90 degrees about X: (x, y, z) -> (x, -z, y), what Blender's OBJ
# importer does to a Y-up file (-Z forward becomes +Y).
TO_BLENDER = mathutils.Matrix.Rotation(math.radians(90.0), 4, "X")


class Unsupported(Exception):
    pass


class Converter:
    """Turns the parsed scene JSON into Blender data; `problems` collects what cannot be mapped."""

    def __init__(self, scene, scene_dir):
        self.scene = scene
        self.dir = scene_dir
        self.problems = []
        self.materials = {}
        self.default_material = None

    def refuse(self, what):
        self.problems.append(what)

    def path(self, name):
        """Resolves a file as the loader does: the scene's directory first, then the working directory."""
        if os.path.isabs(name):
            return name
        for base in (self.dir, os.getcwd()):
            p = os.path.join(base, name)
            if os.path.isfile(p):
                return p
        raise Unsupported(f"file '{name}' not found (looked in the scene's directory and the working directory)")


# ---------------------------------------------------------------------------------------------
# Transforms (docs/scene-format.md, "Transforms": the first step acts first)

def transform_matrix(steps):
    m = mathutils.Matrix.Identity(4)
    for step in steps or []:
        (kind, value), = step.items()
        if kind == "translate":
            s = mathutils.Matrix.Translation(value)
        elif kind == "rotate":
            s = mathutils.Matrix.Rotation(math.radians(value["angle"]), 4, mathutils.Vector(value["axis"]).normalized())
        elif kind == "scale":
            v = [value] * 3 if isinstance(value, (int, float)) else value
            s = mathutils.Matrix.Diagonal((v[0], v[1], v[2], 1.0))
        elif kind == "matrix":
            s = mathutils.Matrix([value[0:4], value[4:8], value[8:12], value[12:16]])
        else:
            raise Unsupported(f"transform step '{kind}'")
        m = s @ m
    return m


# ---------------------------------------------------------------------------------------------
# Materials

def metal_presets():
    """name -> (eta, k), read from the one home of the presets, src/scene/metal_presets.cpp."""
    src = os.path.join(REPO, "src", "scene", "metal_presets.cpp")
    text = open(src).read()
    out = {}
    for m in re.finditer(r'\{"(\w+)", \{([^}]*)\}, \{([^}]*)\}\}', text):
        vals = lambda s: [float(x.strip().rstrip("f")) for x in s.split(",")]
        out[m.group(1)] = (vals(m.group(2)), vals(m.group(3)))
    return out


def conductor_f0(eta, k):
    """Normal-incidence reflectance of the complex index eta + i k (exact at cos = 1)."""
    return [((n - 1) ** 2 + kk * kk) / ((n + 1) ** 2 + kk * kk) for n, kk in zip(eta, k)]


def scalar_param(conv, where, mat, key, default):
    v = mat.get(key, default)
    if isinstance(v, dict):
        conv.refuse(f"{where}: textured '{key}'")
        return default
    return v


def blender_roughness(conv, where, mat):
    """Cycles' node roughness r is GGX alpha = r^2; ours is alpha = sqrt(roughness) (remaproughness,
    the default) or alpha = roughness. Returns r with r^2 = our alpha."""
    if "uroughness" in mat or "vroughness" in mat:
        conv.refuse(f"{where}: anisotropic roughness (Cycles' anisotropy is parameterised differently and "
                    "follows another tangent)")
    rough = scalar_param(conv, where, mat, "roughness", 0.0)
    alpha = math.sqrt(rough) if mat.get("remaproughness", True) else rough
    return math.sqrt(alpha)


def new_material(name):
    m = bpy.data.materials.new(name)
    m.use_nodes = True
    nt = m.node_tree
    for n in list(nt.nodes):
        nt.nodes.remove(n)
    out = nt.nodes.new("ShaderNodeOutputMaterial")
    out.target = "CYCLES"
    return m, nt, out


def bsdf_node(conv, where, nt, mat):
    """The BSDF node of one of our materials, or None (refused)."""
    kind = mat.get("type", "phong")
    if kind == "phong":
        if mat.get("ks", 0) != 0 or mat.get("reflectivity", 0) != 0 or mat.get("refractive", False):
            conv.refuse(f"{where}: phong material with ks, reflectivity or refractive (only its Lambert "
                        "special case, ks = reflectivity = 0, maps to Cycles)")
            return None
        kind = "lambert"
    if kind == "lambert":
        if "texture" in mat:
            conv.refuse(f"{where}: texture")
        n = nt.nodes.new("ShaderNodeBsdfDiffuse")
        kd = mat.get("kd", 1.0)
        d = mat.get("diffuse", [0.8, 0.8, 0.8])
        n.inputs["Color"].default_value = (kd * d[0], kd * d[1], kd * d[2], 1.0)
        n.inputs["Roughness"].default_value = 0.0  # Lambert (Oren-Nayar off)
        return n
    if kind == "mirror":
        n = nt.nodes.new("ShaderNodeBsdfGlossy")
        n.distribution = "SHARP"
        s = mat.get("specular", [1, 1, 1])
        n.inputs["Color"].default_value = (s[0], s[1], s[2], 1.0)
        return n
    if kind in ("glass", "dielectric"):
        n = nt.nodes.new("ShaderNodeBsdfGlass")
        r = blender_roughness(conv, where, mat) if kind == "dielectric" else 0.0
        n.distribution = "SHARP" if r == 0.0 else "GGX"  # plain GGX: multiscatter off
        n.inputs["Roughness"].default_value = r
        n.inputs["IOR"].default_value = mat.get("ior", 1.5)
        n.inputs["Color"].default_value = (1, 1, 1, 1)
        return n
    if kind == "conductor":
        return conductor_node(conv, where, nt, mat)
    if kind == "coateddiffuse":
        conv.refuse(f"{where}: coateddiffuse (Cycles 3.4 has no layered coating: the Principled BSDF's "
                    "clearcoat is a GTR1 lobe of fixed index 1.5 over an unattenuated Disney diffuse; "
                    "no faithful equivalent, so it is not converted)")
        return None
    conv.refuse(f"{where}: material type '{kind}'")
    return None


def conductor_node(conv, where, nt, mat):
    """A conductor as the Principled BSDF with metallic 1 and base colour F0 (plain GGX).

    Cycles 3.4 has no complex-index Fresnel node: an `eta`/`k` or `metal` conductor gets its exact
    normal-incidence reflectance as F0, and the Fresnel curve towards grazing is then Principled's
    (F0 + (1 - F0) (F_d(cos, 1.5) - 0.04) / 0.96, F_d the dielectric Fresnel of index 1.5), not the
    complex one. With `reflectance` ours is Schlick's F0 + (1 - F0)(1 - cos)^5: the same at normal
    incidence, slightly different towards grazing (README)."""
    if "reflectance" in mat:
        f0 = scalar_param(conv, where, mat, "reflectance", [1, 1, 1])
    else:
        if "eta" in mat:
            eta, k = mat["eta"], mat["k"]
            if isinstance(eta, dict) or isinstance(k, dict):
                conv.refuse(f"{where}: textured eta/k")
                return None
        else:
            presets = metal_presets()
            name = mat.get("metal", "Cu")
            if name not in presets:
                conv.refuse(f"{where}: unknown metal preset '{name}'")
                return None
            eta, k = presets[name]
        f0 = conductor_f0(eta, k)
    n = nt.nodes.new("ShaderNodeBsdfPrincipled")
    n.distribution = "GGX"
    n.inputs["Base Color"].default_value = (f0[0], f0[1], f0[2], 1.0)
    n.inputs["Metallic"].default_value = 1.0
    n.inputs["Specular"].default_value = 0.5
    n.inputs["Specular Tint"].default_value = 0.0
    n.inputs["Sheen"].default_value = 0.0
    n.inputs["Clearcoat"].default_value = 0.0
    n.inputs["Anisotropic"].default_value = 0.0
    n.inputs["Roughness"].default_value = blender_roughness(conv, where, mat)
    return n


def build_material(conv, name, mat):
    where = f"materials.{name}"
    for key in ("alpha", "normalmap", "displacement"):
        if key in mat:
            conv.refuse(f"{where}: '{key}'")
    m, nt, out = new_material(name)
    bsdf = bsdf_node(conv, where, nt, mat)
    emission = mat.get("emission", [0, 0, 0])
    shader = bsdf.outputs[0] if bsdf else None
    if any(e > 0 for e in emission):
        em = nt.nodes.new("ShaderNodeEmission")
        em.inputs["Color"].default_value = (emission[0], emission[1], emission[2], 1.0)
        em.inputs["Strength"].default_value = 1.0  # radiance = colour x strength
        emits = em.outputs[0]
        if not mat.get("two_sided", False):
            # One-sided as ours: the back face (geometric normal away from the ray) emits nothing.
            # Cycles' mesh emitters are two-sided otherwise.
            black = nt.nodes.new("ShaderNodeMixShader")
            geo = nt.nodes.new("ShaderNodeNewGeometry")
            nt.links.new(geo.outputs["Backfacing"], black.inputs["Fac"])
            nt.links.new(em.outputs[0], black.inputs[1])  # front: emits; back (inputs[2]): nothing
            emits = black.outputs[0]
        if shader is not None:
            add = nt.nodes.new("ShaderNodeAddShader")
            nt.links.new(shader, add.inputs[0])
            nt.links.new(emits, add.inputs[1])
            shader = add.outputs[0]
        else:
            shader = emits
    if shader is not None:
        nt.links.new(shader, out.inputs["Surface"])
    return m


# ---------------------------------------------------------------------------------------------
# Shapes

def link_object(name, data, matrix, material):
    obj = bpy.data.objects.new(name, data)
    bpy.context.scene.collection.objects.link(obj)
    obj.matrix_world = TO_BLENDER @ matrix
    if material is not None and hasattr(data, "materials"):
        data.materials.append(material)
    return obj


def mesh_object(name, positions, faces, matrix, material, normals=None):
    me = bpy.data.meshes.new(name)
    me.from_pydata([tuple(p) for p in positions], [], [tuple(f) for f in faces])
    me.validate()
    smooth = normals is not None
    for poly in me.polygons:
        poly.use_smooth = smooth
    if smooth:
        me.use_auto_smooth = True  # custom normals are used only with auto smooth in 3.4
        me.normals_split_custom_set_from_vertices([tuple(n) for n in normals])
    return link_object(name, me, matrix, material)


def sphere_object(conv, where, name, shape, matrix, material, needs_mesh):
    """A sphere as a one-point point cloud (Cycles 3.x renders points as true spheres), made by a
    geometry-nodes modifier (Mesh to Points) on a one-vertex mesh; or, when the material refracts or
    emits (`needs_mesh`), as a UV sphere mesh of 256 x 128 segments with smooth normals: Cycles 3.4
    finds no exit from inside a point (a glass point renders as a single refraction, measured), and
    samples only emissive triangles as lights."""
    scale = matrix.to_scale()
    if max(scale) - min(scale) > 1e-6 * max(scale) or matrix.determinant() < 0:
        conv.refuse(f"{where}: sphere under a non-uniform scale or mirror (an ellipsoid)")
        return
    center = matrix @ mathutils.Vector(shape["center"])
    radius = shape["radius"] * scale[0]
    me = bpy.data.meshes.new(name)
    if needs_mesh:
        import bmesh
        bm = bmesh.new()
        bmesh.ops.create_uvsphere(bm, u_segments=256, v_segments=128, radius=radius)
        bm.to_mesh(me)
        bm.free()
        for poly in me.polygons:
            poly.use_smooth = True
        link_object(name, me, mathutils.Matrix.Translation(center), material)
        return
    me.from_pydata([(0.0, 0.0, 0.0)], [], [])
    obj = link_object(name, me, mathutils.Matrix.Translation(center), material)
    tree = bpy.data.node_groups.new(name + " points", "GeometryNodeTree")
    tree.inputs.new("NodeSocketGeometry", "Geometry")
    tree.outputs.new("NodeSocketGeometry", "Geometry")
    gi = tree.nodes.new("NodeGroupInput")
    go = tree.nodes.new("NodeGroupOutput")
    pts = tree.nodes.new("GeometryNodeMeshToPoints")
    pts.inputs["Radius"].default_value = radius
    setmat = tree.nodes.new("GeometryNodeSetMaterial")
    setmat.inputs["Material"].default_value = material
    tree.links.new(gi.outputs["Geometry"], pts.inputs["Mesh"])
    tree.links.new(pts.outputs["Points"], setmat.inputs["Geometry"])
    tree.links.new(setmat.outputs["Geometry"], go.inputs["Geometry"])
    mod = obj.modifiers.new("points", "NODES")
    mod.node_group = tree


def import_mesh_file(conv, where, name, file, matrix, material):
    path = conv.path(file)
    before = set(bpy.data.objects)
    ext = os.path.splitext(path)[1].lower()
    if ext == ".obj":
        bpy.ops.wm.obj_import(filepath=path, forward_axis="Y", up_axis="Z")  # no axis change: we place it
    elif ext == ".ply":
        bpy.ops.import_mesh.ply(filepath=path)  # Blender 3.4's PLY importer changes no axis
    else:
        conv.refuse(f"{where}: mesh file format '{ext}'")
        return
    for obj in set(bpy.data.objects) - before:
        obj.matrix_world = TO_BLENDER @ matrix
        obj.data.materials.clear()
        obj.data.materials.append(material)
        for poly in obj.data.polygons:
            poly.material_index = 0


def build_shape(conv, i, shape):
    kind = shape.get("type")
    name = shape.get("name", f"shapes[{i}]")
    where = f"shapes[{i}] ({kind})"
    matrix = transform_matrix(shape.get("transform"))
    mat_name = shape.get("material")
    material = conv.materials.get(mat_name) if mat_name else conv.default_material
    if kind == "sphere":
        # `pole` only orients texture coordinates, which nothing converted reads.
        mat = conv.scene.get("materials", {}).get(mat_name, {}) if mat_name else {}
        needs_mesh = (mat.get("type") in ("glass", "dielectric") or mat.get("refractive", False)
                      or any(e > 0 for e in mat.get("emission", [0, 0, 0])))
        sphere_object(conv, where, name, shape, matrix, material, needs_mesh)
    elif kind in ("quad", "triangle", "polygon"):
        v = shape["vertices"]
        mesh_object(name, v, [list(range(len(v)))], matrix, material)
    elif kind == "mesh":
        if "file" in shape:
            import_mesh_file(conv, where, name, shape["file"], matrix, material)
        else:
            # `uvs` (texture coordinates): nothing converted reads them.
            mesh_object(name, shape["positions"], shape["indices"], matrix, material, shape.get("normals"))
    else:
        conv.refuse(f"{where}: shape type '{kind}' (only sphere, quad, triangle, polygon and mesh are converted)")


# ---------------------------------------------------------------------------------------------
# Lights, environment, camera

def build_light(conv, i, light):
    kind = light.get("type")
    where = f"lights[{i}] ({kind})"
    if kind == "point":
        if light.get("falloff", "inverse_square") != "inverse_square":
            conv.refuse(f"{where}: falloff 'none'")
            return
        # Ours: a white Lambert surface facing the light at distance r shows I / r^2, a radiant
        # intensity of pi I W/sr. Cycles' point lamp of power P W has radiant intensity
        # P / (4 pi^2) W/sr... measured in README ("Units"): P = 4 pi^2 I.
        data = bpy.data.lights.new(f"light{i}", "POINT")
        intensity = light["intensity"]
        power = max(intensity)
        data.energy = 4.0 * math.pi * math.pi * power
        data.color = [c / power for c in intensity] if power > 0 else (0, 0, 0)
        data.shadow_soft_size = 0.0  # a true point
        matrix = mathutils.Matrix.Translation(light["position"])
    elif kind == "directional":
        data = bpy.data.lights.new(f"light{i}", "SUN")
        irr = light["irradiance"]
        strength = max(irr)
        data.energy = strength  # a sun's strength is irradiance in W/m^2
        data.color = [c / strength for c in irr] if strength > 0 else (0, 0, 0)
        data.angle = 0.0
        d = mathutils.Vector(light["direction"]).normalized()
        # A sun shines along its local -Z.
        matrix = d.to_track_quat("-Z", "Y").to_matrix().to_4x4()
    else:
        conv.refuse(f"{where}: light type '{kind}' (point and directional lights are converted)")
        return
    data.cycles.cast_shadow = True
    data.cycles.use_multiple_importance_sampling = True
    link_object(f"light{i}", data, matrix, None)


def build_world(conv):
    scene = conv.scene
    world = bpy.data.worlds.new("world")
    bpy.context.scene.world = world
    world.use_nodes = True
    nt = world.node_tree
    bg = nt.nodes["Background"]
    bg.inputs["Strength"].default_value = 1.0
    env = scene.get("environment")
    if env is None:
        c = scene.get("render", {}).get("background", [0, 0, 0])
        bg.inputs["Color"].default_value = (c[0], c[1], c[2], 1.0)
        return
    if list(env.get("up", [0, 1, 0])) != [0, 1, 0]:
        conv.refuse("environment: 'up' other than [0, 1, 0]")
    tex = nt.nodes.new("ShaderNodeTexEnvironment")
    tex.image = bpy.data.images.load(conv.path(env["file"]))
    tex.image.colorspace_settings.name = "Linear"
    tex.interpolation = "Closest"  # ours is nearest-texel
    tex.projection = "EQUIRECTANGULAR"
    # Ours: -Z (Blender +Y) at the image's centre, +X at 3/4 of its width; Cycles: +X at the centre,
    # -Y at 3/4. Rotating the lookup direction by -90 degrees about Z maps one onto the other; our
    # `rotation` turns the environment counter-clockwise seen from above, so the lookup turns back.
    mapping = nt.nodes.new("ShaderNodeMapping")
    mapping.vector_type = "VECTOR"
    mapping.inputs["Rotation"].default_value = (0.0, 0.0, math.radians(-90.0 - env.get("rotation", 0.0)))
    coord = nt.nodes.new("ShaderNodeTexCoord")
    nt.links.new(coord.outputs["Generated"], mapping.inputs["Vector"])
    nt.links.new(mapping.outputs["Vector"], tex.inputs["Vector"])
    nt.links.new(tex.outputs["Color"], bg.inputs["Color"])
    bg.inputs["Strength"].default_value = env.get("intensity", 1.0)


def build_camera(conv):
    cam = conv.scene["camera"]
    kind = cam.get("type", "pinhole")
    if kind not in ("pinhole", "perspective", "thin_lens", "thinlens"):
        conv.refuse(f"camera: type '{kind}' (pinhole and thin lens are converted)")
        return
    if cam.get("handedness", "right") != "right":
        conv.refuse("camera: handedness 'left' (a mirrored image)")
    if "transform" in cam:
        conv.refuse("camera: 'transform'")
    data = bpy.data.cameras.new("camera")
    data.sensor_fit = "VERTICAL"
    data.lens_unit = "FOV"
    data.angle_y = math.radians(cam.get("fov", 45.0))
    data.clip_start = 1e-4
    data.clip_end = 1e8
    pos = mathutils.Vector(cam["position"])
    forward = (mathutils.Vector(cam["look_at"]) - pos).normalized()
    up = mathutils.Vector(cam.get("up", [0, 1, 0]))
    right = forward.cross(up).normalized()
    true_up = right.cross(forward)
    # A Blender camera looks down its local -Z with +Y up and +X right.
    rot = mathutils.Matrix((right, true_up, -forward)).transposed().to_4x4()
    if kind in ("thin_lens", "thinlens"):
        data.dof.use_dof = True
        data.dof.focus_distance = cam["focus_distance"]
        # Cycles: aperture radius = 0.5 * (focal length in mm / 1000) / f-stop (scene units = metres).
        data.dof.aperture_fstop = 0.5 * (data.lens * 1e-3) / cam["lens_radius"]
        data.dof.aperture_blades = 0  # a round aperture
        data.dof.aperture_ratio = 1.0
        data.dof.aperture_rotation = 0.0
    link_object("camera", data, mathutils.Matrix.Translation(pos) @ rot, None)
    bpy.context.scene.camera = bpy.data.objects["camera"]


# ---------------------------------------------------------------------------------------------
# Settings

def configure(scene_json, args, conv):
    render = scene_json.get("render", {})
    film = scene_json.get("film", {})
    if render.get("integrator", "whitted") != "path":
        conv.refuse(f"render.integrator '{render.get('integrator', 'whitted')}' (only the path integrator "
                    "has a Cycles equivalent)")
    if render.get("filter", "box") != "box":
        conv.refuse(f"render.filter '{render.get('filter')}' (Cycles' only unbiased match is its box "
                    "filter, whose width it ignores: always one pixel, as our 'box')")
    for key in ("clamp",):
        if render.get(key, 0) != 0:
            conv.refuse(f"render.{key} (a firefly clamp biases the comparison)")
    for key in ("background_image", "film_transparent"):
        if key in render:
            conv.refuse(f"render.{key}")
    for key in ("textures", "objects"):
        if scene_json.get(key):
            conv.refuse(f"'{key}' (textures and instancing are not converted)")
    max_depth = render.get("max_depth", 5)
    if max_depth < 1:
        conv.refuse("render.max_depth 0 (Cycles' smallest cap, 0 bounces, is our max_depth 1)")

    s = bpy.context.scene
    s.render.engine = "CYCLES"
    c = s.cycles
    c.device = "CPU"
    c.samples = args.spp
    c.seed = args.seed
    c.use_animated_seed = False
    c.sample_offset = 0
    c.use_adaptive_sampling = False
    c.use_denoising = False
    c.use_preview_denoising = False
    s.view_layers[0].cycles.use_denoising = False
    c.light_sampling_threshold = 0.0
    c.sample_clamp_direct = 0.0
    c.sample_clamp_indirect = 0.0
    c.blur_glossy = 0.0
    c.caustics_reflective = True
    c.caustics_refractive = True
    # Ours: max_depth = scattering events a path may make before it stops (emitters reached by the last
    # bounce still count). Cycles: max_bounces = 0 is direct lighting only (one scattering event).
    bounces = max(0, max_depth - 1)
    c.max_bounces = bounces
    c.diffuse_bounces = bounces
    c.glossy_bounces = bounces
    c.transmission_bounces = bounces
    c.transparent_max_bounces = bounces
    c.volume_bounces = 0
    c.min_light_bounces = 0
    c.min_transparent_bounces = 0
    c.pixel_filter_type = "BOX"  # its width is ignored: a one-pixel box
    if args.threads > 0:
        s.render.threads_mode = "FIXED"
        s.render.threads = args.threads
    else:
        s.render.threads_mode = "AUTO"
    s.render.resolution_x = film.get("width", 640)
    s.render.resolution_y = film.get("height", 480)
    s.render.resolution_percentage = 100
    s.render.pixel_aspect_x = s.render.pixel_aspect_y = 1.0
    s.render.film_transparent = False
    s.render.use_border = False
    s.render.use_compositing = False
    s.render.use_sequencer = False
    s.view_settings.view_transform = "Standard"
    s.view_settings.look = "None"
    s.view_settings.exposure = 0.0
    s.view_settings.gamma = 1.0
    img = s.render.image_settings
    img.file_format = "OPEN_EXR"
    img.color_mode = "RGBA"
    img.color_depth = "32"
    img.exr_codec = "ZIP"
    s.render.use_file_extension = False
    s.render.filepath = os.path.abspath(args.output)


def build(conv):
    scene_json = conv.scene
    for name, mat in scene_json.get("materials", {}).items():
        conv.materials[name] = build_material(conv, name, mat)
    conv.default_material = build_material(conv, "default", {"type": "lambert"})
    build_camera(conv)
    build_world(conv)
    for i, light in enumerate(scene_json.get("lights", [])):
        build_light(conv, i, light)
    for i, shape in enumerate(scene_json.get("shapes", [])):
        try:
            build_shape(conv, i, shape)
        except Unsupported as e:
            conv.refuse(f"shapes[{i}]: {e}")


def set_shadow_terminator(args):
    """Cycles' shadow terminator settings are per object (Object Properties > Shading > Shadow
    Terminator); the options set them on every object the scene made."""
    for obj in bpy.data.objects:
        if obj.type != "MESH":
            continue
        if args.terminator_geometry_offset is not None:
            obj.cycles.shadow_terminator_geometry_offset = args.terminator_geometry_offset
        if args.terminator_shading_offset is not None:
            obj.cycles.shadow_terminator_offset = args.terminator_shading_offset


def parse_args(argv):
    import argparse
    p = argparse.ArgumentParser(prog="scene_to_cycles.py", description=__doc__.split("\n")[0])
    p.add_argument("scene")
    p.add_argument("--spp", type=int, required=True)
    p.add_argument("--seed", type=int, default=0)
    p.add_argument("--threads", type=int, default=0, help="0: Blender's default (every core)")
    p.add_argument("-o", "--output", required=True, help="the EXR to write")
    p.add_argument("--stats", help="write the timings as JSON here")
    p.add_argument("--width", type=int, help="the film's width instead of the scene's (as pathtracer --width)")
    p.add_argument("--height", type=int, help="the film's height instead of the scene's (as pathtracer --height)")
    p.add_argument("--terminator-geometry-offset", type=float, metavar="F",
                   help="Cycles' per-object Shadow Terminator > Geometry Offset, set on every object "
                        "(Blender's default 0.1; 0 switches it off)")
    p.add_argument("--terminator-shading-offset", type=float, metavar="F",
                   help="Cycles' per-object Shadow Terminator > Shading Offset, set on every object "
                        "(Blender's default 0)")
    return p.parse_args(argv)


def stats_seconds(text):
    """Seconds of a Blender stats line's "Time:[HH:]MM:SS.ss" field."""
    m = re.search(r"Time:((?:\d+:)?\d+:\d+(?:\.\d+)?)", text)
    if not m:
        return None
    secs = 0.0
    for part in m.group(1).split(":"):
        secs = secs * 60 + float(part)
    return secs


def render(args):
    """Renders; returns (seconds around bpy.ops.render.render, seconds of path tracing).

    bpy.app.handlers.render_stats passes no text in 3.4 (its arguments are None), so the path tracing
    time comes from the stats lines Blender prints: fd 1 is sent to a temporary file during the
    render, and the "Time:" of the first line reporting a sample count ("Sample 0/N") is subtracted
    from that of the last ("Sample N/N"); Cycles prints them at 0.01 s resolution."""
    import tempfile
    sys.stdout.flush()
    saved = os.dup(1)
    with tempfile.TemporaryFile(mode="w+b") as log:
        os.dup2(log.fileno(), 1)
        try:
            t0 = time.perf_counter()
            bpy.ops.render.render(write_still=False)
            total = time.perf_counter() - t0
        finally:
            sys.stdout.flush()
            os.dup2(saved, 1)
            os.close(saved)
        log.seek(0)
        text = log.read().decode(errors="replace")
    sys.stdout.write(text)
    times = [stats_seconds(line) for line in text.splitlines() if re.search(r"\| Sample \d+/\d+", line)]
    times = [t for t in times if t is not None]
    tracing = times[-1] - times[0] if len(times) >= 2 else float("nan")
    return total, tracing


def main():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    args = parse_args(argv)
    with open(args.scene) as f:
        scene_json = json.load(f)
    for key in ("width", "height"):
        if getattr(args, key):
            scene_json.setdefault("film", {})[key] = getattr(args, key)
    if scene_json.get("format") != "pathtracer-scene":
        print(f"{args.scene}: error: only native scenes (\"format\": \"pathtracer-scene\") are converted",
              file=sys.stderr)
        return 2
    # Start from an empty scene (factory startup still has a cube, a lamp and a camera).
    for obj in list(bpy.data.objects):
        bpy.data.objects.remove(obj)
    conv = Converter(scene_json, os.path.dirname(os.path.abspath(args.scene)))
    configure(scene_json, args, conv)
    try:
        build(conv)
    except Unsupported as e:
        conv.refuse(str(e))
    if conv.problems:
        print(f"{args.scene}: error: the scene uses what this tool does not convert to Cycles:", file=sys.stderr)
        for p in conv.problems:
            print(f"  - {p}", file=sys.stderr)
        return 2
    set_shadow_terminator(args)
    total, tracing = render(args)
    result = bpy.data.images["Render Result"]
    result.save_render(os.path.abspath(args.output))
    print(f"Cycles render time: {total:.3f} s (path tracing: {tracing:.3f} s)")
    if args.stats:
        with open(args.stats, "w") as f:
            json.dump({"render_seconds": total, "path_tracing_seconds": tracing, "spp": args.spp,
                       "seed": args.seed, "threads": args.threads,
                       "terminator_geometry_offset": args.terminator_geometry_offset,
                       "terminator_shading_offset": args.terminator_shading_offset,
                       "blender": bpy.app.version_string}, f, indent=1)
    return 0


if __name__ == "__main__":
    code = main()
    sys.stdout.flush()
    sys.stderr.flush()
    os._exit(code)  # Blender's own exit status is 0 whatever a --python script does
