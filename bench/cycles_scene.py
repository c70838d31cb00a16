"""Blender side of bench/cycles_bench.py: a Cycles render server driven over stdin/stdout.

    blender -b --factory-startup -noaudio --python bench/cycles_scene.py

Reads one JSON object per line from stdin and answers each with one line on stdout starting
with "CYCLES_BENCH " followed by JSON (Blender prints its own log lines in between):

    {"cmd": "setup", ...scene...}   builds the scene (below); answers {"ok": true}
    {"cmd": "render", "samples": N, "step_rate": R, "seed": S, "out": "x.exr"}
                                    renders and writes a linear float OpenEXR; answers the times
    {"cmd": "quit"}

One long-lived process renders many images, so Blender's start-up (20-30 s of wall time on the
loaded benchmark machine, about 2 s of CPU) is paid once; the driver measures it separately.

Scene ("setup" keys; kasumi's +Y-up world, metres): vdb, density_scale, albedo, g, eye, target,
up, fov_deg (vertical), width, height, sun_toward (unit direction toward the sun), irradiance,
volume_bounces, threads. Mapping to Blender (Z-up, right-handed): the rotation of +90 degrees
about X, (x, y, z) -> (x, -z, y), applied to the Volume object, the camera and the sun.

- Volume: the VDB as a Volume object (bpy.ops.object.volume_import), full float precision,
  clipping 0 (no voxel treated as empty), automatic step size (the voxel size).
- Principled Volume: Density = density_scale, Density Attribute "density", Color = albedo,
  Absorption Color black, Anisotropy = g, no emission. Cycles' closure (intern/cycles/kernel/
  svm/closure.h, CLOSURE_VOLUME_PRINCIPLED): sigma_s = Color * Density * d and sigma_t = (Color
  + (1 - Color)(1 - sqrt(Absorption Color))) * Density * d, so with a black absorption colour
  sigma_t = Density * d and sigma_s / sigma_t = Color: kasumi's density_scale and albedo.
  Phase: Henyey-Greenstein with g, as kasumi's "hg" model. Linear (trilinear) interpolation.
- Sun: strength = irradiance (W/m^2 in Blender's words: scene-linear irradiance on a surface
  facing it, the number kasumi calls lux), white, angle 0 (a delta light, as kasumi's
  directional light).
- Camera: perspective, sensor fit vertical, vertical field of view fov_deg, pixel filter a box
  of 0.01 pixel (every sample through the pixel centre, as kasumi's film.jitter = false).
- World black (strength 0), no surfaces. Cycles: CPU, fixed thread count, fixed sample count
  (adaptive sampling off), denoising off, no clamping, bounces: volume = volume_bounces,
  diffuse = glossy = transmission = 0, total and transparent 1024 (a ray crosses the volume's
  bounding mesh many times), volume max steps 4096. View transform Standard, look None,
  exposure 0, gamma 1 (EXR output is scene linear anyway).
"""
import json
import math
import resource
import sys
import time

import bpy
from mathutils import Matrix, Vector


def answer(obj):
    sys.stdout.write("CYCLES_BENCH " + json.dumps(obj) + "\n")
    sys.stdout.flush()


def to_blender(v):
    """kasumi (+Y up) to Blender (+Z up): rotation of +90 degrees about X."""
    x, y, z = v
    return Vector((x, -z, y))


def setup(p):
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    scene.render.engine = "CYCLES"
    cy = scene.cycles
    cy.device = "CPU"
    cy.use_adaptive_sampling = False
    cy.time_limit = 0.0
    cy.use_denoising = False
    scene.view_layers[0].cycles.use_denoising = False
    cy.sample_clamp_direct = 0.0
    cy.sample_clamp_indirect = 0.0
    cy.max_bounces = 1024
    cy.transparent_max_bounces = 1024
    cy.volume_bounces = int(p["volume_bounces"])
    cy.diffuse_bounces = 0
    cy.glossy_bounces = 0
    cy.transmission_bounces = 0
    cy.caustics_reflective = False
    cy.caustics_refractive = False
    cy.volume_max_steps = 4096
    cy.pixel_filter_type = "BOX"
    cy.filter_width = 0.01
    cy.use_animated_seed = False
    scene.render.threads_mode = "FIXED"
    scene.render.threads = int(p["threads"])
    scene.render.resolution_x = int(p["width"])
    scene.render.resolution_y = int(p["height"])
    scene.render.resolution_percentage = 100
    scene.render.film_transparent = False
    scene.render.use_persistent_data = False
    scene.view_settings.view_transform = "Standard"
    scene.view_settings.look = "None"
    scene.view_settings.exposure = 0.0
    scene.view_settings.gamma = 1.0
    settings = scene.render.image_settings
    settings.file_format = "OPEN_EXR"
    settings.color_depth = "32"
    settings.color_mode = "RGB"
    settings.exr_codec = "ZIP"

    world = bpy.data.worlds.new("black")
    world.use_nodes = True
    background = world.node_tree.nodes["Background"]
    background.inputs["Color"].default_value = (0.0, 0.0, 0.0, 1.0)
    background.inputs["Strength"].default_value = 0.0
    scene.world = world

    # The cloud.
    bpy.ops.object.volume_import(filepath=p["vdb"], align="WORLD", location=(0.0, 0.0, 0.0))
    cloud = bpy.context.active_object
    cloud.rotation_euler = (math.pi / 2.0, 0.0, 0.0)
    volume = cloud.data
    volume.render.precision = "FULL"
    volume.render.space = "OBJECT"
    volume.render.step_size = 0.0
    volume.render.clipping = 0.0
    # Optional shift of the grid by voxel_offset voxels along each index axis (object space),
    # to test the two conventions for where a voxel's value sits (OpenVDB and kasumi: at the
    # index point i; a dense texture sampled at texel centres: at i + 0.5).
    offset = float(p.get("voxel_offset", 0.0))
    if offset != 0.0:
        volume.grids.load()
        index_to_object = volume.grids[0].matrix_object.to_3x3()
        cloud.location = cloud.rotation_euler.to_matrix() @ (index_to_object @ Vector((offset,) * 3))
    material = bpy.data.materials.new("cloud")
    material.use_nodes = True
    nodes = material.node_tree.nodes
    nodes.clear()
    output = nodes.new("ShaderNodeOutputMaterial")
    principled = nodes.new("ShaderNodeVolumePrincipled")
    a = float(p["albedo"])
    principled.inputs["Color"].default_value = (a, a, a, 1.0)
    principled.inputs["Density"].default_value = float(p["density_scale"])
    principled.inputs["Density Attribute"].default_value = "density"
    principled.inputs["Anisotropy"].default_value = float(p["g"])
    principled.inputs["Absorption Color"].default_value = (0.0, 0.0, 0.0, 1.0)
    principled.inputs["Emission Strength"].default_value = 0.0
    principled.inputs["Blackbody Intensity"].default_value = 0.0
    material.node_tree.links.new(principled.outputs["Volume"], output.inputs["Volume"])
    material.cycles.volume_interpolation = "LINEAR"
    material.cycles.homogeneous_volume = False
    volume.materials.clear()
    volume.materials.append(material)

    # The sun: its light travels along its local -Z.
    sun_data = bpy.data.lights.new("sun", "SUN")
    sun_data.energy = float(p["irradiance"])
    sun_data.color = (1.0, 1.0, 1.0)
    sun_data.angle = 0.0
    sun = bpy.data.objects.new("sun", sun_data)
    scene.collection.objects.link(sun)
    travel = -to_blender(p["sun_toward"]).normalized()
    sun.rotation_euler = travel.to_track_quat("-Z", "Y").to_euler()

    # The camera looks along its local -Z with +Y up.
    cam_data = bpy.data.cameras.new("camera")
    cam_data.type = "PERSP"
    cam_data.sensor_fit = "VERTICAL"
    cam_data.angle_y = math.radians(float(p["fov_deg"]))
    # Cycles puts pixel (i, j) at raster position (i, j) plus the filter offset, which a box
    # of 0.01 pixel keeps within 0.005: a pixel's corner. kasumi samples the centre (i + 0.5,
    # j + 0.5): a lens shift of half a pixel (shift is in units of the larger image side)
    # moves Cycles' samples there (measured: without it the images are offset by 0.5 pixel).
    side = max(int(p["width"]), int(p["height"]))
    cam_data.shift_x = 0.5 / side
    cam_data.shift_y = 0.5 / side
    cam_data.clip_start = 0.01
    cam_data.clip_end = 1.0e7
    camera = bpy.data.objects.new("camera", cam_data)
    scene.collection.objects.link(camera)
    eye = to_blender(p["eye"])
    forward = (to_blender(p["target"]) - eye).normalized()
    right = forward.cross(to_blender(p["up"])).normalized()
    up = right.cross(forward)
    rotation = Matrix((right, up, -forward)).transposed()
    camera.matrix_world = Matrix.Translation(eye) @ rotation.to_4x4()
    scene.camera = camera
    return {"ok": True, "blender": bpy.app.version_string,
            "sampling_pattern": str(cy.sampling_pattern),
            "volume_sampling": str(material.cycles.volume_sampling),
            "grids": [g.name for g in volume.grids]}


def cpu_s():
    r = resource.getrusage(resource.RUSAGE_SELF)
    return r.ru_utime + r.ru_stime


def render(p):
    scene = bpy.context.scene
    scene.cycles.samples = int(p["samples"])
    scene.cycles.volume_step_rate = float(p["step_rate"])
    scene.cycles.seed = int(p["seed"])
    cpu0 = cpu_s()
    t0 = time.perf_counter()
    bpy.ops.render.render(write_still=False)
    t1 = time.perf_counter()
    cpu1 = cpu_s()
    bpy.data.images["Render Result"].save_render(p["out"])
    # Blender's own split of the call (its "Time:" at "Sample 0/N", i.e. scene synchronisation,
    # and at "Finished") is in the log lines before this answer; the driver parses them.
    return {"ok": True, "render_call_s": t1 - t0, "cpu_s": cpu1 - cpu0}


def main():
    answer({"ready": True})
    for line in sys.stdin:
        line = line.strip()
        if not line:
            continue
        job = json.loads(line)
        try:
            if job["cmd"] == "setup":
                answer(setup(job))
            elif job["cmd"] == "render":
                answer(render(job))
            elif job["cmd"] == "quit":
                answer({"ok": True})
                break
            else:
                answer({"ok": False, "error": "unknown command " + job["cmd"]})
        except Exception as e:  # reported to the driver, which stops with the message
            answer({"ok": False, "error": "%s: %s" % (type(e).__name__, e)})


main()
