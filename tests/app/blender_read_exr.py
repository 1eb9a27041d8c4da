# Reads one of our EXRs in Blender as a compositor would (run headless by
# tests/app/test_blender_exr.cpp; Debian's blender is 3.4):
#
#   blender -b --factory-startup --python blender_read_exr.py -- IN.exr WIDTH HEIGHT TYPE NAME OUT.exr OUT.json
#
# Loads IN.exr as an image, lists the passes Blender found in it (the outputs
# of an Image node) and the Cryptomatte layers its Cryptomatte node offers,
# then extracts the matte of NAME from the Cryptomatte layer TYPE
# ("CryptoObject", "CryptoMaterial") with the Cryptomatte node and renders it
# through the compositor into OUT.exr (WIDTH x HEIGHT, the image's size, which
# Blender does not report for a multilayer image before it is displayed; the
# matte in R, G and B). OUT.json gets {"passes": [...], "cryptomatte_layers": "..."}:
# the Image node's outputs, and Blender's message listing the Cryptomatte
# layers its node offers for the image (from the file's header).
import json
import sys

import bpy

args = sys.argv[sys.argv.index("--") + 1:]
exr_in, width, height, crypto_type, name, exr_out, json_out = args

image = bpy.data.images.load(exr_in)
scene = bpy.context.scene
scene.use_nodes = True
tree = scene.node_tree
for node in list(tree.nodes):
    tree.nodes.remove(node)

source = tree.nodes.new("CompositorNodeImage")
source.image = image
passes = [socket.name for socket in source.outputs]

crypto = tree.nodes.new("CompositorNodeCryptomatteV2")
crypto.source = "IMAGE"
crypto.image = image
# The layers are a dynamic enum (from the image's header), which Python cannot
# list; setting a name that is not one makes Blender list them.
layers = ""
try:
    crypto.layer_name = "(not a layer)"
except TypeError as e:
    layers = str(e)
crypto.layer_name = crypto_type
crypto.matte_id = name

composite = tree.nodes.new("CompositorNodeComposite")
tree.links.new(crypto.outputs["Matte"], composite.inputs["Image"])

render = scene.render
render.resolution_x, render.resolution_y, render.resolution_percentage = int(width), int(height), 100
render.use_compositing = True
render.use_sequencer = False
render.image_settings.file_format = "OPEN_EXR"
render.image_settings.color_depth = "32"
render.image_settings.exr_codec = "ZIP"
scene.view_settings.view_transform = "Standard"
scene.view_settings.look = "None"
render.filepath = exr_out
bpy.ops.render.render(write_still=True)  # no Render Layers node: only the compositor runs

with open(json_out, "w") as f:
    json.dump({"passes": passes, "cryptomatte_layers": layers}, f)
