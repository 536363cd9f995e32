"""Directional albedo E(θo) of Cycles' Principled BSDF for the grey cases of the OpenPBR conformance
set (the cases of brdfs/tests/data/openpbr_adobe.json numbered 1-12, 18, 25), written as
brdfs/tests/data/openpbr_cycles.json in the same shape (albedo only, "energy" build).

    python3.11 -m venv /tmp/bpyvenv && /tmp/bpyvenv/bin/pip install bpy==5.0.1
    nice -n 10 /tmp/bpyvenv/bin/python tools/scripts/cycles_openpbr_albedo.py \
        [--out brdfs/tests/data/openpbr_cycles.json] [--spp 1024] [--res 32]

Scene: a 1000 m plane carrying the material under a uniform white world (Background colour 1,
strength 1), an orthographic camera looking down -ωo, ωo = (sin θo, 0, cos θo), one bounce (max
bounces 1, every bounce type 1), no clamping, no glossy filter, no denoising, no adaptive
sampling, box pixel filter, 'Standard' view transform, one thread; a float EXR (32-bit, no
compression). Every pixel then estimates E(θo) = ∫ f cos θi dωi; the value is the mean over the
res×res pixels and the error the standard error of that mean (pixels treated as independent).

OpenPBR → Principled BSDF (Blender 4.x/5.0): base_color → Base Color; base_metalness → Metallic;
base_diffuse_roughness → Diffuse Roughness (EON); specular_weight → Specular IOR Level =
0.5·specular_weight (Cycles scales F0 by 2·level); specular_color → Specular Tint (F82 tint for
metals); specular_roughness → Roughness (α = r² in both); specular_ior → IOR; coat_weight →
Coat Weight; coat_roughness → Coat Roughness; coat_ior → Coat IOR; coat_color → Coat Tint;
fuzz_weight → Sheen Weight; fuzz_color → Sheen Tint; fuzz_roughness → Sheen Roughness. OpenPBR's
defaults are set explicitly where Blender's differ (Roughness 0.5 → 0.3, Coat IOR 1.5 → 1.6,
Coat Roughness 0.03 → 0). coat_darkening has no Cycles counterpart (not in these cases).
"""

import argparse
import json
import math
import os
import sys
import tempfile
import time

import bpy
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))

THETA_O = [0, 15, 30, 45, 60, 75, 85]

# The grey cases (numbers of the conformance set in the comments); OpenPBR names, colours [r,g,b].
CASES = [
    ("defaults", {}),                                                                    # 1
    ("white-plastic-r0.1", {"base_color": [1, 1, 1], "specular_roughness": 0.1}),         # 2
    ("white-diffuse", {"base_color": [1, 1, 1], "specular_weight": 0}),                   # 3
    ("coat-over-white-diffuse", {"base_color": [1, 1, 1], "specular_weight": 0,
                                 "coat_weight": 1, "coat_roughness": 0.1}),               # 4
    ("coat-over-white-plastic", {"base_color": [1, 1, 1], "coat_weight": 1,
                                 "coat_roughness": 0.1}),                                 # 5
    ("coat-over-white-metal", {"base_metalness": 1, "base_color": [1, 1, 1],
                               "coat_weight": 1, "coat_roughness": 0.1}),                 # 6
    ("coat-over-grey-diffuse", {"base_color": [0.5, 0.5, 0.5], "specular_weight": 0,
                                "coat_weight": 1, "coat_roughness": 0.1}),                # 7
    ("coat-r0-over-grey-diffuse", {"base_color": [0.5, 0.5, 0.5], "specular_weight": 0,
                                   "coat_weight": 1, "coat_roughness": 0}),               # 8
    ("white-fuzz-over-white", {"base_color": [1, 1, 1], "specular_weight": 0, "fuzz_weight": 1,
                               "fuzz_color": [1, 1, 1], "fuzz_roughness": 0.5}),          # 9
    ("all-layers-white", {"base_color": [1, 1, 1], "base_metalness": 0.5, "specular_roughness": 0.3,
                          "coat_weight": 1, "coat_roughness": 0.2, "fuzz_weight": 1,
                          "fuzz_color": [1, 1, 1], "fuzz_roughness": 0.5}),               # 10
    ("white-metal-r0.3", {"base_metalness": 1, "base_color": [1, 1, 1],
                          "specular_roughness": 0.3}),                                    # 11
    ("white-metal-r0.8", {"base_metalness": 1, "base_color": [1, 1, 1],
                          "specular_roughness": 0.8}),                                    # 12
    ("rough-diffuse-white", {"base_color": [1, 1, 1], "specular_weight": 0,
                             "base_diffuse_roughness": 1}),                               # 18
    ("coat-grey-0.5-plastic", {"base_color": [0.5, 0.5, 0.5], "coat_weight": 1,
                               "coat_roughness": 0.2}),                                   # 25
]

OPENPBR_DEFAULTS = {
    "base_weight": 1.0, "base_color": [0.8, 0.8, 0.8], "base_metalness": 0.0,
    "base_diffuse_roughness": 0.0, "specular_weight": 1.0, "specular_color": [1, 1, 1],
    "specular_roughness": 0.3, "specular_ior": 1.5, "coat_weight": 0.0, "coat_color": [1, 1, 1],
    "coat_roughness": 0.0, "coat_ior": 1.6, "fuzz_weight": 0.0, "fuzz_color": [1, 1, 1],
    "fuzz_roughness": 0.5,
}


def principled_inputs(params):
    p = dict(OPENPBR_DEFAULTS)
    p.update(params)
    bw = p["base_weight"]
    return {
        "Base Color": [bw * c for c in p["base_color"]] + [1.0],
        "Metallic": p["base_metalness"],
        "Diffuse Roughness": p["base_diffuse_roughness"],
        "Specular IOR Level": 0.5 * p["specular_weight"],
        "Specular Tint": list(p["specular_color"]) + [1.0],
        "Roughness": p["specular_roughness"],
        "IOR": p["specular_ior"],
        "Coat Weight": p["coat_weight"],
        "Coat Roughness": p["coat_roughness"],
        "Coat IOR": p["coat_ior"],
        "Coat Tint": list(p["coat_color"]) + [1.0],
        "Sheen Weight": p["fuzz_weight"],
        "Sheen Tint": list(p["fuzz_color"]) + [1.0],
        "Sheen Roughness": p["fuzz_roughness"],
        "Subsurface Weight": 0.0,
        "Transmission Weight": 0.0,
        "Emission Strength": 0.0,
        "Thin Film Thickness": 0.0,
        "Anisotropic": 0.0,
        "Alpha": 1.0,
    }


def setup_scene(res, spp):
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    scene.render.engine = "CYCLES"
    cy = scene.cycles
    cy.device = "CPU"
    cy.samples = spp
    cy.use_adaptive_sampling = False
    cy.use_denoising = False
    cy.max_bounces = 1
    cy.diffuse_bounces = 1
    cy.glossy_bounces = 1
    cy.transmission_bounces = 1
    cy.volume_bounces = 0
    cy.transparent_max_bounces = 0
    cy.sample_clamp_direct = 0.0
    cy.sample_clamp_indirect = 0.0
    cy.blur_glossy = 0.0
    cy.pixel_filter_type = "BOX"
    cy.filter_width = 1.0
    scene.render.threads_mode = "FIXED"
    scene.render.threads = 1
    scene.render.resolution_x = res
    scene.render.resolution_y = res
    scene.render.resolution_percentage = 100
    scene.render.film_transparent = False
    scene.view_settings.view_transform = "Standard"
    scene.view_settings.look = "None"
    scene.view_settings.exposure = 0.0
    scene.view_settings.gamma = 1.0
    im = scene.render.image_settings
    im.file_format = "OPEN_EXR"
    im.color_depth = "32"
    im.exr_codec = "NONE"
    im.color_mode = "RGB"

    world = bpy.data.worlds.new("white")
    world.use_nodes = True
    bg = world.node_tree.nodes["Background"]
    bg.inputs["Color"].default_value = (1.0, 1.0, 1.0, 1.0)
    bg.inputs["Strength"].default_value = 1.0
    scene.world = world

    bpy.ops.mesh.primitive_plane_add(size=1000.0, location=(0, 0, 0))
    plane = bpy.context.active_object
    mat = bpy.data.materials.new("openpbr")
    mat.use_nodes = True
    plane.data.materials.append(mat)

    cam_data = bpy.data.cameras.new("cam")
    cam_data.type = "ORTHO"
    cam_data.ortho_scale = 1.0
    cam_data.clip_start = 0.01
    cam_data.clip_end = 100.0
    cam = bpy.data.objects.new("cam", cam_data)
    scene.collection.objects.link(cam)
    scene.camera = cam
    return scene, mat, cam


def set_material(mat, params):
    bsdf = mat.node_tree.nodes["Principled BSDF"]
    bsdf.distribution = "MULTI_GGX"
    for name, v in principled_inputs(params).items():
        bsdf.inputs[name].default_value = v


def render_albedo(scene, cam, theta_deg, path, seed):
    t = math.radians(theta_deg)
    cam.location = (10.0 * math.sin(t), 0.0, 10.0 * math.cos(t))
    cam.rotation_euler = (0.0, t, 0.0)  # R_y(θ) maps the camera's -Z to -(sin θ, 0, cos θ)
    scene.cycles.seed = seed
    scene.render.filepath = path
    bpy.ops.render.render(write_still=True)
    img = bpy.data.images.load(path)
    px = np.array(img.pixels[:], dtype=np.float64).reshape(-1, img.channels)[:, :3]
    bpy.data.images.remove(img)
    n = px.shape[0]
    return px.mean(axis=0), px.std(axis=0, ddof=1) / math.sqrt(n)


def main():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else sys.argv[1:]
    ap = argparse.ArgumentParser()
    ap.add_argument("--out", default=os.path.join(REPO, "brdfs", "tests", "data", "openpbr_cycles.json"))
    ap.add_argument("--spp", type=int, default=1024)
    ap.add_argument("--res", type=int, default=32)
    ap.add_argument("--only", nargs="*")
    args = ap.parse_args(argv)

    scene, mat, cam = setup_scene(args.res, args.spp)
    tmp = tempfile.mkdtemp(prefix="cycles_albedo_")
    cases = []
    for ci, (name, params) in enumerate(CASES):
        if args.only and name not in args.only:
            continue
        set_material(mat, params)
        alb, se = [], []
        t0 = time.time()
        for ti, th in enumerate(THETA_O):
            m, s = render_albedo(scene, cam, th, os.path.join(tmp, f"{name}_{th}.exr"), 1000 * ci + ti)
            alb.append([float(f"{x:.7g}") for x in m])
            se.append([float(f"{x:.7g}") for x in s])
        print(f"{name}: {time.time() - t0:.1f} s  E(0) = {alb[0]}  E(75) = {alb[5]}", file=sys.stderr, flush=True)
        cases.append({"name": name, "params": params,
                      "principled": {k: v for k, v in principled_inputs(params).items()},
                      "energy": {"albedo": alb, "albedo_se": se}})

    cmd = ("python3.11 -m venv /tmp/bpyvenv && /tmp/bpyvenv/bin/pip install bpy==5.0.1; "
           "nice -n 10 /tmp/bpyvenv/bin/python tools/scripts/cycles_openpbr_albedo.py "
           f"--spp {args.spp} --res {args.res}")
    doc = {
        "source": f"Cycles (Blender {bpy.app.version_string}, pip bpy==5.0.1, build hash "
                  f"{bpy.app.build_hash.decode() if isinstance(bpy.app.build_hash, bytes) else bpy.app.build_hash}), "
                  "Principled BSDF, distribution Multiscatter GGX",
        "command": cmd,
        "method": f"plane under a uniform white world, orthographic camera at θo, max bounces 1, no clamping, "
                  f"no glossy filter, no denoising, no adaptive sampling, box filter; {args.res}x{args.res} "
                  f"pixels x {args.spp} spp, float EXR; albedo = pixel mean, albedo_se = pixel sd / sqrt(pixels)",
        "theta_o": THETA_O,
        "cases": cases,
    }
    with open(args.out, "w") as f:
        f.write("{\n")
        items = []
        for k, v in doc.items():
            if k != "cases":
                items.append(f"  {json.dumps(k)}: {json.dumps(v, ensure_ascii=False)}")
        cs = ",\n".join("    " + json.dumps(c, separators=(", ", ": ")) for c in doc["cases"])
        items.append('  "cases": [\n' + cs + "\n  ]")
        f.write(",\n".join(items) + "\n}\n")
    print("wrote", args.out, file=sys.stderr)


if __name__ == "__main__":
    main()
