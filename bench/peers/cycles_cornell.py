"""Render luxel's built-in Cornell box with Blender Cycles, as a peer for benchmarks.

Run headless (arguments after "--" belong to this script):

    blender -b --factory-startup --python bench/peers/cycles_cornell.py -- \
        --spp 256 --out out/peers/cycles_256.exr --threads 2 --size 256

The scene is rebuilt from the same data as luxel's built-in `cornell` scene,
src/scene/builtin/cornell_box.cpp (the Cornell Program of Computer Graphics measured
data, https://www.graphics.cornell.edu/online/box/data.html, millimetres -> metres),
in luxel's own y-up coordinates (Cycles does not care which axis is up; only the
camera is oriented explicitly).  Everything is set up so that Cycles computes the
same quantity as luxel (linear radiance, box-filtered over each pixel):

  * Lambertian materials only (Diffuse BSDF, roughness 0) with the same reflectances.
  * The light: Emission (colour (17,12,4), strength 1) + Diffuse 0.78 on its front
    face; its back face is black (Mix Shader driven by Geometry > Backfacing), so it
    emits downward only, like luxel's one-sided emitter.  Cycles' Emission shader
    with strength S and colour C emits radiance C*S (W/(m^2 sr)); check it with
    --emission-test, which renders a camera looking straight at a large emissive
    quad of strength 1 (a pixel value of 1.0 means radiance = C*S, 1/pi means C*S/pi),
    and --emission-test indirect, a diffuse plane of reflectance 0.5 lit by that quad
    over its whole hemisphere (expect 0.5 * C * S).  Measured with Blender 3.4.1:
    direct 1.0 * C exactly, indirect 0.498 * C (expected 0.4999): radiance = C * S.
  * Same camera: eye (0.278,0.273,-0.8), target (0.278,0.273,0), up +y, vertical fov
    39.3077 deg (sensor fit vertical), square image.
  * Black world, film exposure 0, view transform Standard, look None; the OpenEXR
    output (float32 RGB) holds scene-linear values anyway.
  * No denoiser, adaptive sampling off, fixed spp, fixed seed, box pixel filter of
    width 1 px, 64 bounces of every kind, no clamping, no filter glossy; light
    sampling threshold 0 (no probabilistic light culling).

The render time (seconds between the start and the end of bpy.ops.render.render,
which includes Cycles' scene sync and BVH build and writing the EXR, but not
Blender's start-up) is printed as a line `CYCLES_RENDER_SECONDS <t>` and, with
--json, written to a JSON file.
"""

import argparse
import json
import math
import os
import struct
import sys
import time

import bpy
from mathutils import Vector

sys.dont_write_bytecode = True  # leave no __pycache__ in the source tree
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import obj_scene  # noqa: E402  (beside this script)

MM = 0.001


def parse_args():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    p = argparse.ArgumentParser(prog="cycles_cornell.py")
    p.add_argument("--spp", type=int, default=256)
    p.add_argument("--out", required=True, help="output OpenEXR file")
    p.add_argument("--threads", type=int, default=2)
    p.add_argument("--size", type=int, default=256, help="image width = height")
    p.add_argument("--seed", type=int, default=0)
    p.add_argument("--bounces", type=int, default=64,
                   help="diffuse bounces; 0 renders the direct light alone (to check it apart)")
    p.add_argument("--json", help="write render settings and time here")
    p.add_argument("--obj", help="render this OBJ (and its MTL: Kd, Ke) instead of the built-in box, "
                                 "from obj_scene.MCGUIRE_CAMERA; for McGuire's Cornell boxes")
    p.add_argument("--glb", help="render this glTF binary as luxel writes it (`luxel bake`): its geometry and "
                                 "camera; Lambertian base colours, emissive factor x strength emitted "
                                 "from the front face only; for scenes too large to rebuild here")
    p.add_argument("--two-sided-light", action="store_true",
                   help="let the light emit from both faces (Cycles' default), for checking")
    p.add_argument("--emission-test", choices=["direct", "indirect"],
                   help="instead of the Cornell box, check Cycles' emission units: 'direct' looks "
                        "straight at a large emissive quad of strength 1 and colour (1,0.5,0.25) "
                        "(pixel = radiance); 'indirect' looks at a diffuse plane of reflectance 0.5 "
                        "1 m under that quad, 100 m wide (pixel = 0.5 * radiance: the quad fills "
                        "the hemisphere)")
    return p.parse_args(argv)


def clear_scene():
    for obj in list(bpy.data.objects):
        bpy.data.objects.remove(obj, do_unlink=True)
    for coll in (bpy.data.meshes, bpy.data.materials, bpy.data.cameras, bpy.data.lights):
        for block in list(coll):
            coll.remove(block)


def diffuse_material(name, rgb):
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    nt = mat.node_tree
    nt.nodes.clear()
    out = nt.nodes.new("ShaderNodeOutputMaterial")
    bsdf = nt.nodes.new("ShaderNodeBsdfDiffuse")
    bsdf.inputs["Color"].default_value = (*rgb, 1.0)
    bsdf.inputs["Roughness"].default_value = 0.0  # Lambertian (Oren-Nayar off)
    nt.links.new(bsdf.outputs["BSDF"], out.inputs["Surface"])
    return mat


def light_material(name, emission, reflectance, two_sided):
    """Emission + Lambertian reflection on the front face; black on the back face."""
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    mat.cycles.sample_as_light = True  # "Multiple Importance" (next-event estimation)
    nt = mat.node_tree
    nt.nodes.clear()
    out = nt.nodes.new("ShaderNodeOutputMaterial")
    emit = nt.nodes.new("ShaderNodeEmission")
    emit.inputs["Color"].default_value = (*emission, 1.0)
    emit.inputs["Strength"].default_value = 1.0
    bsdf = nt.nodes.new("ShaderNodeBsdfDiffuse")
    bsdf.inputs["Color"].default_value = (*reflectance, 1.0)
    bsdf.inputs["Roughness"].default_value = 0.0
    add = nt.nodes.new("ShaderNodeAddShader")
    nt.links.new(emit.outputs["Emission"], add.inputs[0])
    nt.links.new(bsdf.outputs["BSDF"], add.inputs[1])
    if two_sided:
        nt.links.new(add.outputs["Shader"], out.inputs["Surface"])
        return mat
    geo = nt.nodes.new("ShaderNodeNewGeometry")
    black = nt.nodes.new("ShaderNodeBsdfDiffuse")  # the back face neither emits nor reflects
    black.inputs["Color"].default_value = (0.0, 0.0, 0.0, 1.0)
    mix = nt.nodes.new("ShaderNodeMixShader")
    nt.links.new(geo.outputs["Backfacing"], mix.inputs["Fac"])
    nt.links.new(add.outputs["Shader"], mix.inputs[1])    # Fac 0: front face
    nt.links.new(black.outputs["BSDF"], mix.inputs[2])    # Fac 1: back face
    nt.links.new(mix.outputs["Shader"], out.inputs["Surface"])
    return mat


def add_mesh(name, quads, mat, scale=MM):
    """quads: polygons (4 vertices for the built-in box) in millimetres (`scale` MM) or metres
    (`scale` 1), counter-clockwise seen from the front."""
    verts, faces = [], []
    for q in quads:
        base = len(verts)
        verts.extend(Vector(v) * scale for v in q)
        faces.append(tuple(range(base, base + len(q))))
    me = bpy.data.meshes.new(name)
    me.from_pydata(verts, [], faces)
    me.validate()
    me.update()
    me.materials.append(mat)
    obj = bpy.data.objects.new(name, me)
    bpy.context.scene.collection.objects.link(obj)
    return obj


# Copied from src/scene/builtin/cornell_box.cpp: (mesh, material, quads in millimetres),
# same vertex order (so the same normals: counter-clockwise = front).
_Y = 548.8
CORNELL_MESHES = [
    ("floor", "white", [[(552.8, 0, 0), (0, 0, 0), (0, 0, 559.2), (549.6, 0, 559.2)]]),
    ("ceiling", "white", [
        [(556, _Y, 0), (556, _Y, 227), (0, _Y, 227), (0, _Y, 0)],
        [(556, _Y, 332), (556, _Y, 559.2), (0, _Y, 559.2), (0, _Y, 332)],
        [(556, _Y, 227), (556, _Y, 332), (343, _Y, 332), (343, _Y, 227)],
        [(213, _Y, 227), (213, _Y, 332), (0, _Y, 332), (0, _Y, 227)],
    ]),
    ("light", "light", [[(343, _Y, 227), (343, _Y, 332), (213, _Y, 332), (213, _Y, 227)]]),
    ("back wall", "white",
     [[(549.6, 0, 559.2), (0, 0, 559.2), (0, _Y, 559.2), (556, _Y, 559.2)]]),
    ("right wall", "green", [[(0, 0, 559.2), (0, 0, 0), (0, _Y, 0), (0, _Y, 559.2)]]),
    ("left wall", "red", [[(552.8, 0, 0), (549.6, 0, 559.2), (556, _Y, 559.2), (556, _Y, 0)]]),
    ("short block", "white", [
        [(130, 165, 65), (82, 165, 225), (240, 165, 272), (290, 165, 114)],
        [(290, 0, 114), (290, 165, 114), (240, 165, 272), (240, 0, 272)],
        [(130, 0, 65), (130, 165, 65), (290, 165, 114), (290, 0, 114)],
        [(82, 0, 225), (82, 165, 225), (130, 165, 65), (130, 0, 65)],
        [(240, 0, 272), (240, 165, 272), (82, 165, 225), (82, 0, 225)],
    ]),
    ("tall block", "white", [
        [(423, 330, 247), (265, 330, 296), (314, 330, 456), (472, 330, 406)],
        [(423, 0, 247), (423, 330, 247), (472, 330, 406), (472, 0, 406)],
        [(472, 0, 406), (472, 330, 406), (314, 330, 456), (314, 0, 456)],
        [(314, 0, 456), (314, 330, 456), (265, 330, 296), (265, 0, 296)],
        [(265, 0, 296), (265, 330, 296), (423, 330, 247), (423, 0, 247)],
    ]),
]
CORNELL_CAMERA = dict(eye=(0.278, 0.273, -0.8), target=(0.278, 0.273, 0.0), fov_deg=39.3077)
REFLECTANCE = {"white": (0.725, 0.71, 0.68), "red": (0.63, 0.065, 0.05),
               "green": (0.14, 0.45, 0.091)}


def build_cornell(two_sided_light):
    mats = {name: diffuse_material(name, rgb) for name, rgb in REFLECTANCE.items()}
    mats["light"] = light_material("light", (17.0, 12.0, 4.0), (0.78, 0.78, 0.78),
                                   two_sided_light)
    for name, mat, quads in CORNELL_MESHES:
        add_mesh(name, quads, mats[mat])
    add_camera(**CORNELL_CAMERA)


def build_obj(path, two_sided_light):
    """An OBJ as luxel reads it: Lambertian Kd, and Ke emitted from the front face only."""
    meshes, materials = obj_scene.load_obj(path)
    mats = {}
    for name, m in materials.items():
        mats[name] = (light_material(name, m["ke"], m["kd"], two_sided_light) if obj_scene.emits(m)
                      else diffuse_material(name, m["kd"]))
    for group, material, polygons in meshes:
        add_mesh(f"{group} {material}", polygons, mats[material], scale=1.0)
    add_camera(**obj_scene.MCGUIRE_CAMERA)


def glb_json(path):
    """The JSON chunk of a glTF binary."""
    with open(path, "rb") as f:
        head = f.read(20)
        magic, _, _, length, kind = struct.unpack("<4sIIII", head)
        if magic != b"glTF" or kind != 0x4E4F534A:
            raise SystemExit(f"{path}: not a glTF binary with a JSON chunk first")
        return json.loads(f.read(length))


def build_glb(path, two_sided_light):
    """A glb as luxel writes it: each material Lambertian in its base colour, and where it has an
    emissive factor (times KHR_materials_emissive_strength) emitting that radiance from its front
    face only, as luxel's emitters do. Baked vertex colours are left out: Cycles computes the
    light itself. The camera is the file's first (luxel's view of the scene)."""
    doc = glb_json(path)
    # Debian 12's Blender 3.4 glTF importer still uses np.bool, which NumPy 1.24 removed.
    import numpy as np
    if "bool" not in np.__dict__:
        np.bool = bool
    bpy.ops.import_scene.gltf(filepath=os.path.abspath(path))
    mats = {}
    for m in doc.get("materials", []):
        rgb = tuple(m.get("pbrMetallicRoughness", {}).get("baseColorFactor", [1, 1, 1, 1])[:3])
        strength = m.get("extensions", {}).get("KHR_materials_emissive_strength", {}).get("emissiveStrength", 1.0)
        emission = tuple(c * strength for c in m.get("emissiveFactor", [0, 0, 0]))
        name = m.get("name", "")
        mats[name] = (light_material(name + " (luxel)", emission, rgb, two_sided_light) if max(emission) > 0
                      else diffuse_material(name + " (luxel)", rgb))
    for obj in bpy.context.scene.objects:
        if obj.type != "MESH":
            continue
        for slot in obj.material_slots:
            # The importer names materials as the file does, with ".001" where names repeat.
            name = slot.material.name if slot.material else ""
            base = name if name in mats else name.rsplit(".", 1)[0]
            if base not in mats:
                raise SystemExit(f"{path}: material '{slot.material.name if slot.material else None}' "
                                 "is not one of the file's")
            slot.material = mats[base]
    cameras = [o for o in bpy.context.scene.objects if o.type == "CAMERA"]
    if not cameras or not doc.get("cameras"):
        raise SystemExit(f"{path}: no camera")
    cam = cameras[0]
    cam.data.sensor_fit = "VERTICAL"
    cam.data.angle_y = doc["cameras"][0]["perspective"]["yfov"]
    cam.data.clip_start = 0.001
    cam.data.clip_end = 1000.0
    bpy.context.scene.camera = cam


def build_emission_test(kind):
    """A 100 m x 100 m quad of Emission strength 1, colour (1, 0.5, 0.25)."""
    mat = bpy.data.materials.new("emit")
    mat.use_nodes = True
    nt = mat.node_tree
    nt.nodes.clear()
    out = nt.nodes.new("ShaderNodeOutputMaterial")
    emit = nt.nodes.new("ShaderNodeEmission")
    emit.inputs["Color"].default_value = (1.0, 0.5, 0.25, 1.0)
    emit.inputs["Strength"].default_value = 1.0
    nt.links.new(emit.outputs["Emission"], out.inputs["Surface"])
    s = 50000.0  # mm
    if kind == "direct":
        # facing -z, towards a camera at the origin looking down +z
        add_mesh("emitter", [[(s, -s, 1000), (-s, -s, 1000), (-s, s, 1000), (s, s, 1000)]], mat)
        add_camera(eye=(0, 0, 0), target=(0, 0, 1), fov_deg=39.3077)
        return
    # emitter at y = G facing down; diffuse floor at y = 0 facing up; the camera sits
    # between them and looks obliquely down at the floor (its view never reaches the edges).
    # Seen from the floor the emitter fills all but 0.03% of the hemisphere (form factor
    # 0.9997 at G = 1 m), so the floor's radiance is 0.5 * 0.9997 * (1, 0.5, 0.25).
    # (With much smaller gaps, e.g. 1 mm under a 100 m quad, Cycles 3.4 loses a few per
    # cent to grazing-angle precision; 1 m is well conditioned.)
    G = 1000.0  # mm
    add_mesh("emitter", [[(s, G, -s), (s, G, s), (-s, G, s), (-s, G, -s)]], mat)
    add_mesh("floor", [[(s, 0, -s), (-s, 0, -s), (-s, 0, s), (s, 0, s)]],
             diffuse_material("half", (0.5, 0.5, 0.5)))
    add_camera(eye=(0, G * MM / 2, 0), target=(0, 0.0, G * MM * 2), fov_deg=20.0)
    bpy.context.scene.camera.data.clip_start = 1e-6


def add_camera(eye, target, fov_deg):
    cam_data = bpy.data.cameras.new("camera")
    cam_data.type = "PERSP"
    cam_data.sensor_fit = "VERTICAL"
    cam_data.angle_y = math.radians(fov_deg)
    cam_data.clip_start = 0.001
    cam_data.clip_end = 1000.0
    cam = bpy.data.objects.new("camera", cam_data)
    bpy.context.scene.collection.objects.link(cam)
    eye, target = Vector(eye), Vector(target)
    cam.location = eye
    # A Blender camera looks down its local -Z with local +Y up.
    cam.rotation_euler = (target - eye).to_track_quat("-Z", "Y").to_euler()
    bpy.context.scene.camera = cam


def configure(args):
    scene = bpy.context.scene
    scene.render.engine = "CYCLES"
    c = scene.cycles
    c.device = "CPU"
    c.samples = args.spp
    c.use_adaptive_sampling = False
    c.use_denoising = False
    c.use_preview_denoising = False
    c.seed = args.seed
    c.use_animated_seed = False
    c.pixel_filter_type = "BOX"
    c.filter_width = 1.0
    c.max_bounces = args.bounces
    c.diffuse_bounces = args.bounces
    c.glossy_bounces = 64
    c.transmission_bounces = 64
    c.volume_bounces = 64
    c.transparent_max_bounces = 64
    c.sample_clamp_direct = 0.0
    c.sample_clamp_indirect = 0.0
    c.blur_glossy = 0.0
    c.caustics_reflective = True
    c.caustics_refractive = True
    c.light_sampling_threshold = 0.0
    c.use_auto_tile = False
    c.film_exposure = 1.0  # a linear multiplier in Cycles: 1.0 means exposure 0
    scene.render.film_transparent = False
    scene.render.use_persistent_data = False
    scene.render.threads_mode = "FIXED"
    scene.render.threads = args.threads
    scene.render.resolution_x = args.size
    scene.render.resolution_y = args.size
    scene.render.resolution_percentage = 100
    scene.render.pixel_aspect_x = 1.0
    scene.render.pixel_aspect_y = 1.0
    scene.render.use_compositing = False
    scene.render.use_sequencer = False
    scene.view_settings.view_transform = "Standard"
    scene.view_settings.look = "None"
    scene.view_settings.exposure = 0.0
    scene.view_settings.gamma = 1.0
    # A black world: nothing but the scene's emitter lights anything.
    world = scene.world or bpy.data.worlds.new("World")
    scene.world = world
    world.use_nodes = True
    bg = world.node_tree.nodes.get("Background")
    if bg is not None:
        bg.inputs["Color"].default_value = (0.0, 0.0, 0.0, 1.0)
        bg.inputs["Strength"].default_value = 0.0
    world.color = (0.0, 0.0, 0.0)
    img = scene.render.image_settings
    img.file_format = "OPEN_EXR"
    img.color_mode = "RGB"
    img.color_depth = "32"
    img.exr_codec = "ZIP"
    scene.render.filepath = args.out
    scene.render.use_file_extension = False


def main():
    args = parse_args()
    clear_scene()
    configure(args)
    if args.emission_test:
        build_emission_test(args.emission_test)
    elif args.obj:
        build_obj(args.obj, args.two_sided_light)
    elif args.glb:
        build_glb(args.glb, args.two_sided_light)
    else:
        build_cornell(args.two_sided_light)
    t0 = time.perf_counter()
    bpy.ops.render.render(write_still=True)
    seconds = time.perf_counter() - t0
    print(f"CYCLES_RENDER_SECONDS {seconds:.6f}", flush=True)
    if args.json:
        with open(args.json, "w") as f:
            json.dump({"renderer": "cycles", "blender": bpy.app.version_string,
                       "spp": args.spp, "size": args.size, "threads": args.threads,
                       "seed": args.seed, "sampling_pattern": bpy.context.scene.cycles.sampling_pattern,
                       "two_sided_light": args.two_sided_light,
                       "emission_test": args.emission_test, "obj": args.obj, "glb": args.glb,
                       "output": args.out,
                       "render_seconds": seconds}, f, indent=2)


if __name__ == "__main__":
    main()
