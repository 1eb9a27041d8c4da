#!/usr/bin/env python3
"""Regenerates docs/gallery.md and its images (docs/gallery/*.png): one image per
feature (shape, light, material, camera, integrator), the repository's scenes, and
the course scenes beside the courses' official references, each with the command
that made it.

    python3 tools/gallery/make_gallery.py [--build build] [--only NAME,...] [--width 256]
    python3 tools/gallery/make_gallery.py --check DIR    # every command, tiny, into DIR (a ctest)

Most features are one `--set` on scenes/gallery/stage.json (a floor, a subject in
shapes[1], an area light in shapes[2], a dim directional fill in lights[0]), so the
command itself shows the scene JSON of the feature. To add a feature (a new shape,
light or material), add a row to FEATURES. Rows whose files are in ../shared (the
course scenes, their references, the environment map) are skipped with a note
when it is absent, and their earlier images are kept.
Needs build/pathtracer and oiiotool (openimageio-tools) for the references' thumbnails.
"""
import argparse
import os
import shlex
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SHARED = os.path.join(os.path.dirname(ROOT), "shared")
STAGE = "scenes/gallery/stage.json"
OUT_DIR = os.path.join("docs", "gallery")


def subject(shape):
    """--set replacing the stage's subject (shapes[1]) with `shape` (JSON text)."""
    return ["--set", "shapes[1]=" + shape]


def lights_only(lights):
    """The stage's area light switched off and its lights replaced by `lights` (JSON text)."""
    return ["--set", "materials.lamp.emission=[0,0,0]", "--set", "lights=" + lights]


def material(json_text):
    """--set replacing the subject's material (materials.subject) with `json_text`."""
    return ["--set", "materials.subject=" + json_text]


GRID = material('{"type":"lambert","texture":"../assets/uv_grid.png"}')

# (section, name, title, scene, options, official reference or None). Paths are relative to the
# repository; "../shared/..." are the course files (skipped without them).
FEATURES = [
    # Shapes: the subject of the stage.
    ("Shapes", "sphere", "`sphere`", STAGE, [], None),
    ("Shapes", "quad", "`quad`", STAGE, subject(
        '{"type":"quad","material":"subject","vertices":[[-0.8,0.1,0.2],[0.8,0.1,0.2],[0.8,1.5,-0.3],[-0.8,1.5,-0.3]]}') + GRID,
     None),
    ("Shapes", "triangle", "`triangle`", STAGE, subject(
        '{"type":"triangle","material":"subject","vertices":[[-0.9,0,0.3],[0.9,0,0.3],[0,1.5,-0.2]]}'), None),
    ("Shapes", "cylinder", "`cylinder` (capped)", STAGE, subject(
        '{"type":"cylinder","material":"subject","p0":[0,0,0],"p1":[0,1.3,0],"radius":0.5}'), None),
    ("Shapes", "cone", "`cone`", STAGE, subject(
        '{"type":"cone","material":"subject","p0":[0,0,0],"p1":[0,1.5,0],"radius":0.6}'), None),
    ("Shapes", "cone-truncated", "`cone` with `top_radius`", STAGE, subject(
        '{"type":"cone","material":"subject","p0":[0,0,0],"p1":[0,1.1,0],"radius":0.6,"top_radius":0.3}') + GRID, None),
    ("Shapes", "disc", "`disc` with `inner_radius` (an annulus)", STAGE, subject(
        '{"type":"disc","material":"subject","center":[0,0.8,0],"normal":[0,0.25,1],"radius":0.75,"inner_radius":0.25}') + GRID,
     None),
    ("Shapes", "polygon", "`polygon`", STAGE, subject(
        '{"type":"polygon","material":"subject","vertices":[[-0.5,0,0],[0.5,0,0],[0.85,0.75,0],[0.5,1.5,0],'
        '[-0.5,1.5,0],[-0.85,0.75,0]]}') + GRID, None),
    ("Shapes", "plane", "`plane` (infinite, `uv_scale`)", STAGE, [
        "--set", 'shapes[0]={"type":"plane","material":"floor","point":[0,0,0],"normal":[0,1,0],"uv_scale":2}'], None),
    ("Shapes", "mesh", "`mesh` from a PLY file, with a `transform`", STAGE, subject(
        '{"type":"mesh","file":"../assets/torus_knot.ply","material":"subject","transform":[{"translate":'
        '[-0.13,-1.45,1.8]},{"scale":0.6},{"translate":[0,0.85,0]}]}'), None),
    ("Shapes", "instance", "`objects` placed by `instance` shapes", STAGE, [
        "--set", 'objects=[{"name":"pair","shapes":[{"type":"sphere","center":[0,0.3,0],"radius":0.3,'
        '"material":"floor"},{"type":"cone","p0":[0.7,0,0],"p1":[0.7,0.8,0],"radius":0.3,"material":"subject"}]}]',
        "--set", 'shapes[1]={"type":"instance","object":"pair","transform":[{"translate":[-1.2,0,0]}]}',
        "--set", 'shapes[2]={"type":"instance","object":"pair","transform":[{"rotate":{"axis":[0,1,0],"angle":60}},'
        '{"translate":[0.6,0,0.3]}]}'], None),
    # Lights.
    ("Lights", "area-light", "an area light: an emitting `quad` (`emission`), alone", STAGE,
     ["--set", "lights=[]"], None),
    ("Lights", "point-light", "`point` light", STAGE, lights_only(
        '[{"type":"point","position":[1.5,2.5,1.5],"intensity":[14,13,12]}]'), None),
    # In the dark: beside the stage's sky colour (a constant environment light) the spot is chosen by its
    # power for too few samples, and its light comes out speckled at 64 spp.
    ("Lights", "spot-light", "`spot` light (`cone_angle`, `cone_delta`), under a black sky", STAGE, lights_only(
        '[{"type":"spot","position":[0,3,1.5],"look_at":[0,0.5,0],"intensity":[30,28,25],"cone_angle":25,'
        '"cone_delta":5}]') + ["--set", 'render={"integrator":"path","max_depth":8,"spp":64}'], None),
    ("Lights", "directional-light", "`directional` light", STAGE, lights_only(
        '[{"type":"directional","direction":[0.5,-1,-0.6],"irradiance":[2.5,2.4,2.2]}]'), None),
    ("Lights", "emitting-sphere", "an emitting sphere (a material's `emission`), alone", STAGE, lights_only("[]") + material(
        '{"type":"lambert","diffuse":[0,0,0],"emission":[1.6,1.4,1.2]}'), None),
    ("Lights", "environment", "`environment` map (the showcase's HDR, `scenes/assets/studio_512.hdr`), alone", STAGE,
     lights_only("[]") + ["--set", 'render={"integrator":"path","max_depth":8,"spp":64}', "--set",
                          'environment={"file":"../assets/studio_512.hdr","rotation":200}'], None),
    # Materials: the subject sphere's.
    ("Materials", "lambert", "`lambert`", STAGE, [], None),
    ("Materials", "phong", "`phong` (normalised Blinn-Phong)", STAGE, material(
        '{"type":"phong","diffuse":[0.15,0.35,0.8],"kd":0.8,"ks":0.5,"exponent":60}'), None),
    ("Materials", "mirror", "`mirror`", STAGE, material('{"type":"mirror","specular":[0.9,0.9,0.9]}'), None),
    ("Materials", "glass", "`glass` (Fresnel, `ior`)", STAGE, material('{"type":"glass","ior":1.5}'), None),
    ("Materials", "texture", "a `texture` (PNG, sRGB)", STAGE, GRID, None),
    # Cameras.
    ("Cameras", "pinhole", "`pinhole` (the default)", STAGE, [], None),
    ("Cameras", "thin-lens", "`thin_lens`: depth of field", STAGE, [
        "--set", 'camera={"type":"thin_lens","position":[0.6,0.5,2.6],"look_at":[0,0.6,0],"fov":45,'
        '"lens_radius":0.08,"focus_distance":2.7}'], None),
    ("Cameras", "orthographic", "`orthographic`", STAGE, [
        "--set", 'camera={"type":"orthographic","position":[3,3,4],"look_at":[0,0.6,0],"view_height":3}'], None),
    ("Cameras", "spherical", "`spherical` (latitude-longitude)", STAGE, [
        "--set", 'camera={"type":"spherical","position":[0,1,2],"look_at":[0,0.75,0]}', "--height", "128"], None),
    # Integrators and debug views.
    ("Integrators and views", "path", "`--integrator path` (the showcase's own)", "scenes/showcase.json", [], None),
    ("Integrators and views", "whitted", "`--integrator whitted` (the classic showcase's own)", "scenes/classic.json",
     [], None),
    ("Integrators and views", "normal", "`--integrator normal`", "scenes/showcase.json",
     ["--integrator", "normal", "--spp", "1"], None),
    ("Integrators and views", "depth", "`--integrator depth`", "scenes/showcase.json",
     ["--integrator", "depth", "--spp", "1"], None),
    ("Integrators and views", "bvh-cost", "`--integrator bvh-cost`: BVH traversal cost per pixel",
     "scenes/showcase.json", ["--integrator", "bvh-cost", "--accel", "bvh", "--spp", "1"], None),
    # The repository's scenes (showcase.json and classic.json are above, under path and whitted).
    ("Scenes", "cornell-box", "`scenes/cornell-box.json` beside the Cycles reference (8192 spp)",
     "scenes/cornell-box.json", ["--spp", "128"], "../shared/reference/cornell-box/cornell_cycles_8192spp.exr"),
    ("Scenes", "shapes", "`scenes/shapes.json`", "scenes/shapes.json", [], None),
    ("Scenes", "primitives", "`scenes/primitives.json`", "scenes/primitives.json", [], None),
    ("Scenes", "cornell-classic", "`scenes/cornell-classic.json`", "scenes/cornell-classic.json", [], None),
    # The course scenes, loaded unmodified, beside the courses' own images.
    ("Course scenes", "cgr-binary-primitives", "CGR `binary_primitives.json`",
     "../shared/seed-scenes/cgr/binary_primitives.json", [],
     "../shared/reference/course-official/cgr/binary_primitives.png"),
    ("Course scenes", "cgr-scene-binary", "CGR `scene.json` (binary)", "../shared/seed-scenes/cgr/scene.json", [],
     "../shared/reference/course-official/cgr/scene_binary.png"),
    ("Course scenes", "cgr-scene-phong", "CGR `scene.json` with `rendermode` phong",
     "../shared/seed-scenes/cgr/scene.json", ["--set", "rendermode=phong"],
     "../shared/reference/course-official/cgr/scene_phong.png"),
    ("Course scenes", "cgr-simple-phong", "CGR `simple_phong.json`", "../shared/seed-scenes/cgr/simple_phong.json", [],
     "../shared/reference/course-official/cgr/simple_phong.png"),
    ("Course scenes", "cgr-mirror-image", "CGR `mirror_image.json` (no official image)",
     "../shared/seed-scenes/cgr/mirror_image.json", [], None),
    ("Course scenes", "pol-example", "Path of Light `example.json`",
     "../shared/seed-scenes/path-of-light/examples/example.json", [],
     "../shared/reference/course-official/path-of-light/example.png"),
]


def needs_shared(row):
    _, _, _, scene, options, reference = row
    return any("shared/" in x for x in [scene] + options + [reference or ""])


def command(row, width, out_dir=OUT_DIR, spp=None):
    """The row's command line; `spp` replaces the row's own --spp (the quick check's)."""
    _, name, _, scene, options, _ = row
    if spp:
        at = options.index("--spp") if "--spp" in options else None
        options = (options[:at] + options[at + 2:] if at is not None else options) + ["--spp", str(spp)]
    return ["build/pathtracer", scene] + options + ["--width", str(width), "-o", "%s/%s.png" % (out_dir, name)]


def render(row, args):
    if args.check:  # every command, tiny and at 1 spp, into the check's folder
        cmd = command(row, 24, os.path.abspath(args.check), spp=1)
    else:
        cmd = command(row, args.width)
    exe = os.path.join(os.path.abspath(args.build), "pathtracer")
    t = time.monotonic()
    r = subprocess.run([exe] + cmd[1:] + ["--quiet"], cwd=ROOT, capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit("error: %s failed (exit %d):\n%s" % (shlex.join(cmd), r.returncode, r.stderr.strip()))
    print("%-24s %5.1f s" % (row[1], time.monotonic() - t), flush=True)


def thumbnail(row, width):
    """The official reference, resized to the gallery's width, as docs/gallery/NAME-reference.png."""
    src = os.path.join(ROOT, row[5])
    dst = os.path.join(ROOT, OUT_DIR, row[1] + "-reference.png")
    cmd = ["oiiotool", src, "--resize", "%dx0" % width]
    if src.endswith(".exr"):
        cmd += ["--colorconvert", "linear", "sRGB"]
    r = subprocess.run(cmd + ["-d", "uint8", "-o", dst], capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit("error: oiiotool %s: %s" % (src, r.stderr.strip()))


def markdown(width, skipped):
    lines = ["# Gallery", "",
             "One image per feature, each with the command that made it (run from the repository root after "
             "the README's first command). `python3 tools/gallery/make_gallery.py` renders them all again "
             "(%d images, %d px wide; a few minutes on 2 cores) and rewrites this page; its table `FEATURES` "
             "lists them. Most are one `--set` on `%s` (a checkered floor, a subject in `shapes[1]` of material "
             "`subject`, an area light in `shapes[2]`, a dim directional fill), so the command shows the feature's scene JSON "
             "(`docs/scene-format.md`)." % (len(FEATURES), width, STAGE), ""]
    if skipped:
        lines += ["Not re-rendered in the last run (no `../shared`): %s." % ", ".join(skipped), ""]
    section = None
    for row in FEATURES:
        if row[0] != section:
            section = row[0]
            lines += ["## " + section, ""]
        name, title, reference = row[1], row[2], row[5]
        lines.append("### %s" % title)
        lines.append("")
        if reference:
            lines += ["| ours | reference (`%s`) |" % reference.replace("../shared/", ""), "|---|---|",
                      "| ![%s](gallery/%s.png) | ![reference](gallery/%s-reference.png) |" % (name, name, name)]
        else:
            lines.append("![%s](gallery/%s.png)" % (name, name))
        lines += ["", "```sh", shlex.join(command(row, width)), "```", ""]
    return "\n".join(lines)


def check(args):
    """--check: every row's command runs and writes its image; every reference exists; names are unique."""
    names = [row[1] for row in FEATURES]
    if len(set(names)) != len(names):
        sys.exit("error: FEATURES names a row twice")
    os.makedirs(args.check, exist_ok=True)
    done = 0
    for row in FEATURES:
        if needs_shared(row) and not os.path.isdir(SHARED):
            print("%-24s skipped: no ../shared" % row[1])
            continue
        render(row, args)  # exits with the command and its message if it fails
        if not os.path.isfile(os.path.join(args.check, row[1] + ".png")):
            sys.exit("error: %s wrote no image" % row[1])
        if row[5] and not os.path.isfile(os.path.join(ROOT, row[5])):
            sys.exit("error: %s: the reference %s is missing" % (row[1], row[5]))
        done += 1
    print("gallery: %d of %d commands ran" % (done, len(FEATURES)))
    return 0


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--build", default=os.path.join(ROOT, "build"), help="build folder (default: build/)")
    p.add_argument("--width", type=int, default=256, help="image width (default 256)")
    p.add_argument("--only", help="render only these rows (comma-separated names); the page lists all")
    p.add_argument("--check", metavar="DIR",
                   help="run every command at 24 px and 1 spp into DIR and check the references exist; "
                        "docs/ untouched (the ctest gallery_commands)")
    args = p.parse_args()
    only = set(args.only.split(",")) if args.only else None
    if args.check:
        return check(args)
    os.makedirs(os.path.join(ROOT, OUT_DIR), exist_ok=True)
    skipped = []
    for row in FEATURES:
        if only and row[1] not in only:
            continue
        if needs_shared(row) and not os.path.isdir(SHARED):
            skipped.append(row[1])
            continue
        render(row, args)
        if row[5]:
            thumbnail(row, args.width)
    with open(os.path.join(ROOT, "docs", "gallery.md"), "w") as f:
        f.write(markdown(args.width, skipped))
    print("wrote docs/gallery.md")
    return 0


if __name__ == "__main__":
    sys.exit(main())
