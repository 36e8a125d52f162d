#!/usr/bin/env python3
"""An independent check of the shading model (issue 13, item 8; issue 36).

Every renderer includes the same lighting.inc.glsl, so their agreement with each other
cannot catch an error in it. This script evaluates the models by itself, in float64 with
numpy, for a plane seen by a known camera, and compares every renderer's screenshot with
them: seed 000 appendix D's Phong model with one light per case (`shading: {model:
phong}`); glTF 2.0's metallic-roughness model (files pbr-NAME, `model: pbr`); and three
cases lit only by `environment: sky` (ENV_CASES). The formulas are beside model() and
pbr_shade(), what is read from the project beside "scene files", the tolerance beside
check().

    shading_model.py gen DIR      writes the glTF scenes and the manifests into DIR
    shading_model.py check DIR    compares DIR/out-*/runs/*/screenshot-*.png with the model
"""
import base64
import csv
import glob
import json
import math
import os
import struct
import sys
import zlib

import numpy as np

W, H = 80, 60
RENDERERS = ["deferred", "forward-spml", "forward-mpml", "forward-plus", "tiled-deferred",
             "clustered", "deferred-lighting", "visibility"]
HALF = 20.0              # the plane: y = 0, x and z in [-HALF, HALF], normal +Y
TOP = 4.0                # a small triangle at this height behind the camera: it puts
                         # the light bounds' centre (a grid light) at (0, TOP / 2, 0)
AMBIENT = 0.1
BASE = (0.8, 0.6, 0.4)
METALLIC, ROUGHNESS = 1.0, 0.5
# pbr: a material partly metal, so that both lobes of the BRDF show, and lights twice as
# bright (its diffuse lobe is Lambert's c_diff / pi; more saturates the highlights)
PBR_METALLIC, PBR_GAIN = 0.4, 2.0
MODELS = ("phong", "pbr")
CAMERA = {"t": (0.0, 4.0, 4.0), "pitch_deg": -50.0, "yfov": 0.7, "znear": 0.1,
          "zfar": 100.0}
SEED, COLOR_MAX = 1337, 3.0
EDGE_EPS = 1e-4
MAX_TOL, RMSE_TOL = 1.0 / 255.0, 0.5 / 255.0


def unit(v):
    v = np.asarray(v, dtype=np.float64)
    return v / np.linalg.norm(v)


def quat_axis(axis, angle):
    a = unit(axis) * math.sin(angle / 2.0)
    return [float(a[0]), float(a[1]), float(a[2]), math.cos(angle / 2.0)]


def quat_to_dir(q, v=(0.0, 0.0, -1.0)):
    """v rotated by the unit quaternion q = (x, y, z, w) (glTF's order)."""
    x, y, z, w = q
    m = np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                  [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                  [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])
    return m @ np.asarray(v, dtype=np.float64), m


def quat_towards(d):
    """The rotation that turns -Z into the unit direction d (shortest arc)."""
    f = np.array([0.0, 0.0, -1.0])
    d = unit(d)
    axis = np.cross(f, d)
    s = np.linalg.norm(axis)
    if s < 1e-12:
        return [0.0, 0.0, 0.0, 1.0]
    return quat_axis(axis, math.atan2(s, float(np.dot(f, d))))


# The cases: a light each. `file` lights come from the glTF (lights.placement scene);
# `grid` ones from the manifest (one grid light at the bounds' centre).
CASES = {
    "directional": {"light": {"type": "directional", "color": [1.0, 0.9, 0.8],
                              "intensity": 0.6},
                    "dir": (0.3, -0.75, 0.6)},
    "point": {"light": {"type": "point", "color": [1.0, 0.85, 0.6], "intensity": 3.0,
                        "range": 60.0},
              "pos": (0.6, 1.5, 0.2)},
    "spot": {"light": {"type": "spot", "color": [0.7, 0.9, 1.0], "intensity": 5.0,
                       "range": 60.0,
                       "spot": {"innerConeAngle": 0.2, "outerConeAngle": 0.45}},
             "pos": (-0.5, 2.5, 0.3), "at": (0.2, 0.0, 0.6)},
    # the point light on a material with glTF's metallic-roughness map (G roughness, B
    # metallic; its R must be ignored) and an occlusion map (R, at strength 0.8) of
    # another size: uniform images, so that every texel read is exact. pbr multiplies
    # the factors by them and the ambient light by the occlusion; phong ignores both.
    "maps": {"light": {"type": "point", "color": [1.0, 0.85, 0.6], "intensity": 3.0,
                       "range": 60.0},
             "pos": (0.6, 1.5, 0.2),
             "mr": (17, 200, 128), "occlusion": (100, 33, 33), "strength": 0.8},
    "linear-range": {"grid": {"attenuation": "linear-range", "radius": 3.0}},
    # Karis 2013's windowed inverse-square: the window cuts the light inside the plane;
    # its colour 2.5 times color_max, so that the plane spans a strong range
    "windowed": {"grid": {"attenuation": "windowed", "radius": 3.0, "boost": 2.5}},
    "quadratic": {"grid": {"attenuation": "quadratic", "radius": 60.0,
                           "quadratic": {"a": 0.5, "b": 0.4, "c": 0.6}}},
}


# Issue 36: the environment light (environment.light sky), no lights: the plane under the
# procedural sky, written here from its definition (renderers/frame/environment.c's
# environment_sky: y up, each side blended exponentially into the horizon). Each case is
# (model, metallic, roughness); its file and manifest are NAME.gltf / NAME.yaml.
ENV_CASES = {
    "env-phong": ("phong", 0.0, 0.6),   # Kd E/pi + g prefiltered(R, r): g 0.04, r 0.6
    "env-pbr": ("pbr", 0.0, 1.0),       # a rough dielectric: the irradiance, mostly
    "env-metal": ("pbr", 1.0, 0.6),     # a metal: the prefiltered sky x (F0 A + B)
}
SKY_HORIZON = np.array([1.0, 0.98, 0.95])
SKY_ZENITH = np.array([0.45, 0.58, 0.85])
SKY_GROUND = np.array([0.32, 0.3, 0.28])
SKY_SCALE, GROUND_SCALE = 0.25, 0.05
# Tolerance of the environment cases, against the exact integrals here: max 3/255, RMSE
# 2/255. The renderers' irradiance is 9 spherical-harmonic terms, which for this sky
# (its kink at the horizon) give E(+Y) 2.2 % (red) to 0.7 % (blue) too high: 2.3/255 on
# the plane's 0.8 base colour (measured: env-pbr max 2.37/255, RMSE 1.67/255; env-phong
# 2.46, 1.52), every renderer alike. The prefiltered sky (an RGBA16F cube map of 8
# texels a face at roughness 0.6, read bilinearly, importance-sampled with 256
# directions) is within 0.8/255 of its integral (env-metal: max 0.78/255, RMSE 0.32/255).
ENV_MAX_TOL, ENV_RMSE_TOL = 3.0 / 255.0, 2.0 / 255.0


def sky(y):
    """The sky's radiance (N x 3) for the y of unit world directions."""
    y = np.clip(np.asarray(y, dtype=np.float64), -1.0, 1.0)[..., None]
    up = SKY_ZENITH + (SKY_HORIZON - SKY_ZENITH) * np.exp(-np.maximum(y, 0.0) / SKY_SCALE)
    down = SKY_GROUND + (SKY_HORIZON - SKY_GROUND) * np.exp(np.minimum(y, 0.0) / GROUND_SCALE)
    return np.where(y >= 0.0, up, down)


def irradiance_up():
    """E / pi for the normal +Y: (1/pi) x the integral of L cos over the upper hemisphere,
    = 2 x the integral of L(mu) mu over mu in [0, 1] (the sky is the same at every
    azimuth); Gauss-Legendre, 200 nodes."""
    x, w = np.polynomial.legendre.leggauss(200)
    mu = 0.5 * (x + 1.0)
    return 2.0 * 0.5 * np.sum((w * mu)[:, None] * sky(mu), axis=0)


def prefiltered(ry, roughness):
    """The split sum's first factor (Karis 2013) for reflection directions with world y
    ry: the sky weighted by the GGX distribution of light directions about R (N = V = R)
    times N.L, over the sphere: sum L(l) D(h) (N.h) / (4 V.h) N.L / sum of the weights,
    on a 400 x 800 (theta, phi) grid about R."""
    a = roughness * roughness
    a2 = a * a
    th = (np.arange(400) + 0.5) * (0.5 * math.pi / 400)     # angle of l from R: N.L > 0
    # the grid's 800 azimuths pair up as phi and 2 pi - phi, where l has the same world y
    # (the sky's one variable): the first 400, each counted twice
    ph = (np.arange(400) + 0.5) * (2.0 * math.pi / 800)
    TH, PH = np.meshgrid(th, ph, indexing="ij")
    ndl = np.cos(TH)
    ndh = np.cos(TH / 2.0)                                   # h halfway between R and l
    d = a2 / (math.pi * (ndh * ndh * (a2 - 1.0) + 1.0) ** 2)
    w = d * ndh / (4.0 * ndh) * ndl * np.sin(TH)             # pdf(l) N.L x the area element
    out = []
    for y in np.atleast_1d(ry):
        # l in R's frame: R = (sqrt(1 - y^2), y, 0); any tangent frame (the sky is the
        # same at every azimuth)
        c = math.sqrt(max(0.0, 1.0 - y * y))
        R, T = np.array([c, y, 0.0]), np.array([-y, c, 0.0])
        ly = ndl * R[1] + np.sin(TH) * np.cos(PH) * T[1]
        out.append(np.sum(w[..., None] * sky(ly), axis=(0, 1)) / np.sum(w))
    return np.array(out)


def env_brdf(roughness, ndv):
    """Karis 2014's analytic fit of the environment BRDF: F0 x A + B."""
    c0 = np.array([-1.0, -0.0275, -0.572, 0.022])
    c1 = np.array([1.0, 0.0425, 1.04, -0.04])
    r = roughness * c0 + c1
    a004 = np.minimum(r[0] * r[0], np.exp2(-9.28 * ndv)) * r[0] + r[1]
    return -1.04 * a004 + r[2], 1.04 * a004 + r[3]


# >>scene files
# What is taken from the project (its mapping of files and manifests onto the Phong
# model, and how the image is produced), each read from the code named:
#   scenes/file/file_materials.c  glTF pbrMetallicRoughness -> Phong: Kd = baseColorFactor;
#       g = 0.04 (1 - metallic) + luminance(baseColor) metallic, luminance = 0.2126 r +
#       0.7152 g + 0.0722 b; n = 2 / r^4 - 2 for roughness r (the Blinn-Phong exponent of
#       GGX alpha = r^2). KHR_lights_punctual: colour x intensity; position and direction
#       (-Z) from the light's node; point and spot: 1/d^2 cut off at `range`; spot: c =
#       outerConeAngle, f = 1 (innerConeAngle is not used). Cameras: at the node, looking
#       down -Z, yfov, the run's aspect. The ambient light of a file scene is 0.1 (grey).
#   scenes/file/file_assimp.c  scale (fit, the default: the bounds' diagonal made 20 units)
#       multiplies positions, a light's range and the camera's planes, and a point or spot
#       light's intensity by its square: the model here stays in the file's units.
#   scenes/scene_place.c  lights.placement grid with one light: at the centre of the light
#       bounds (a file scene's are its mesh bounds); colour r, g, b = rand() / RAND_MAX x
#       color_max in that order, from Visual C++'s rand (msvc_rand) seeded with
#       lights.seed; the attenuation form and its coefficients from lights.attenuation /
#       lights.quadratic.
#   scenes/scene.h  a point or spot light reaches nothing beyond its radius (range).
#   renderers/shaders/resolve.frag.glsl  the output is the HDR value clamped to [0, 1] (no
#       tone curve, no sRGB encoding), written to RGBA8: GL rounds to the nearest of the
#       255 levels; screenshots are that image, top row first (renderers/gl/context.c).
# The scenes avoid what the project adds to the paper: every light's range lies beyond
# the visible plane except linear-range's and windowed's (whose attenuation reaches 0
# there anyway), no light is within 1 cm of the plane (1/d^2 is clamped there), and every
# light is above the plane (N.L > 0 everywhere, so the project's gating of S by N.L > 0
# does not show).

def png_uniform(rgb, size):
    """A size x size RGB PNG of one colour, as a data URI."""
    raw = b"".join(b"\0" + bytes(rgb) * size for _ in range(size))
    def chunk(kind, body):
        return (struct.pack(">I", len(body)) + kind + body +
                struct.pack(">I", zlib.crc32(kind + body) & 0xffffffff))
    png = (b"\x89PNG\r\n\x1a\n" +
           chunk(b"IHDR", struct.pack(">IIBBBBB", size, size, 8, 2, 0, 0, 0)) +
           chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b""))
    return "data:image/png;base64," + base64.b64encode(png).decode()


def case_file(name, shading):
    """The file stem of a case under a shading model: the case's name, pbr-NAME."""
    return name if shading == "phong" else "pbr-" + name


def plane_gltf(case, shading):
    """The glTF of a case: the plane, the bounds triangle, the camera, the case's light."""
    metallic = METALLIC if shading == "phong" else PBR_METALLIC
    metallic = case.get("metallic", metallic)
    gain = 1.0 if shading == "phong" else PBR_GAIN
    L = HALF
    pos = [-L, 0, L, L, 0, L, L, 0, -L, -L, 0, -L,                      # the plane
           -0.1, TOP, L, 0.1, TOP, L, 0.0, TOP, L - 0.1]                 # the bounds triangle
    nrm = [0, 1, 0] * 7
    idx = [0, 1, 2, 0, 2, 3, 4, 5, 6]
    bin_ = struct.pack("<21f", *pos) + struct.pack("<21f", *nrm) + struct.pack("<9H", *idx)
    bin_ += b"\0" * (-len(bin_) % 4)
    uri = "data:application/octet-stream;base64," + base64.b64encode(bin_).decode()
    cam = CAMERA
    nodes = [{"mesh": 0},
             {"name": "cam", "translation": list(cam["t"]),
              "rotation": quat_axis((1, 0, 0), math.radians(cam["pitch_deg"])), "camera": 0}]
    doc = {
        "asset": {"version": "2.0"},
        "scene": 0,
        "scenes": [{"nodes": list(range(3 if "light" in case else 2))}],
        "nodes": nodes,
        "cameras": [{"type": "perspective",
                     "perspective": {"yfov": cam["yfov"], "znear": cam["znear"],
                                     "zfar": cam["zfar"], "aspectRatio": W / H}}],
        "materials": [{"pbrMetallicRoughness": {"baseColorFactor": list(BASE) + [1.0],
                                                "metallicFactor": metallic,
                                                "roughnessFactor": case.get("roughness",
                                                                            ROUGHNESS)}}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1}, "indices": 2,
                                    "material": 0}]}],
        "buffers": [{"byteLength": len(bin_), "uri": uri}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 84},
                        {"buffer": 0, "byteOffset": 84, "byteLength": 84},
                        {"buffer": 0, "byteOffset": 168, "byteLength": 18}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 7, "type": "VEC3",
                       "min": [-L, 0, -L], "max": [L, TOP, L]},
                      {"bufferView": 1, "componentType": 5126, "count": 7, "type": "VEC3"},
                      {"bufferView": 2, "componentType": 5123, "count": 9, "type": "SCALAR"}],
    }
    if "mr" in case:
        pbr = doc["materials"][0]["pbrMetallicRoughness"]
        pbr["metallicRoughnessTexture"] = {"index": 0}
        doc["materials"][0]["occlusionTexture"] = {"index": 1, "strength": case["strength"]}
        doc["textures"] = [{"source": 0}, {"source": 1}]
        doc["images"] = [{"uri": png_uniform(case["mr"], 4)},
                         {"uri": png_uniform(case["occlusion"], 2)}]
    if "light" in case:
        light = dict(case["light"], intensity=case["light"]["intensity"] * gain)
        doc["extensionsUsed"] = ["KHR_lights_punctual"]
        doc["extensions"] = {"KHR_lights_punctual": {"lights": [light]}}
        node = {"name": "light", "extensions": {"KHR_lights_punctual": {"light": 0}}}
        if "pos" in case:
            node["translation"] = list(case["pos"])
        d = case.get("dir")
        if d is None and "at" in case:
            d = np.subtract(case["at"], case["pos"])
        if d is not None:
            node["rotation"] = quat_towards(d)
        nodes.append(node)
    return doc


# The G-buffer renderers (deferred, tiled-deferred) run with `gbuffer: reference`
# (RGBA32F, position stored): with the default preset (curtis) the point light's
# highlight misses by one more level at one pixel (1.015/255), which is the G-buffer's
# precision, not the shading model. deferred-lighting reads no gbuffer key: its own
# G-buffer (the normal and shininess in RGBA16F, the position from depth) and its RGBA16F
# light buffer stay within the same tolerance (0.8/255 at most).
def manifest(name, case, shading):
    stem = name if "env" in case else case_file(name, shading)
    gain = 1.0 if shading == "phong" else PBR_GAIN
    # the grid cases' light is the manifest's, in the file's units: scale 1; the file's
    # own lights run at the default scale (fit, x0.35 here), which changes the units and
    # not the picture (their range scales with the file, their intensity with its square)
    scale = ", scale: 1" if "grid" in case else ""
    lines = ["shadesweep: 1", f"name: shading-{stem}",
             f"scene: {{file: {stem}.gltf, camera: cam{scale}}}",
             f"shading: {{model: {shading}}}",
             "renderers: [" + ", ".join(RENDERERS) + "]",
             f"resolution: {W}x{H}", "duration: {frames: 2}", "clock: fixed",
             "outputs: {screenshots: [0]}",
             # the deferred renderers' lossless G-buffer: this checks the shading model,
             # not what a G-buffer loses (gl-agreement and gbuffer-error measure that)
             "gbuffer: reference"]
    if "env" in case:
        lines.append("environment: sky")   # and no lights
    elif "light" in case:
        lines.append("lights: {placement: scene, count: 1}")
    else:
        g = case["grid"]
        q = g.get("quadratic")
        extra = (f", quadratic: {{a: {q['a']}, b: {q['b']}, c: {q['c']}}}" if q else "")
        lines.append(f"lights: {{placement: grid, count: 1, seed: {SEED}, rng: msvc, "
                     f"color_max: {COLOR_MAX * gain * g.get('boost', 1.0)!r}, "
                     f"radius: {g['radius']}, "
                     f"attenuation: {g['attenuation']}{extra}}}")
    return "\n".join(lines) + "\n"


def gen(d):
    os.makedirs(d, exist_ok=True)
    for shading, stem, case in all_cases():
        with open(os.path.join(d, stem + ".gltf"), "w") as f:
            json.dump(plane_gltf(case, shading), f)
        with open(os.path.join(d, stem + ".yaml"), "w") as f:
            f.write(manifest(stem if "env" in case else case_name(stem), case, shading))


def env_case(name):
    shading, metallic, roughness = ENV_CASES[name]
    return {"env": True, "metallic": metallic, "roughness": roughness}


def case_name(stem):
    return stem[4:] if stem.startswith("pbr-") else stem


def all_cases():
    """(model, file stem, case) of every case: the lights' under both models, then the
    environment's."""
    out = [(m, case_file(n, m), c) for m in MODELS for n, c in CASES.items()]
    return out + [(ENV_CASES[n][0], n, env_case(n)) for n in ENV_CASES]


# >>the model
# Written from the paper's formulas (seed 000 appendix D), not from our shaders:
#     A = ambient light * ambient material                      (our ambient material: Kd)
#     D = light * Kd * max(N.L, 0)
#     S = light * Ks * max(R.V, 0)^n,  R = 2 (N.L) N - L        (Ks: white, see g)
#     attenuation: 1 / (a d^2 + b d + c) | 1 / d^2 | max(0, 1 - d / maxRange)
#     spot = (-L.A)^f if -L.A > cos(c), else 0
#     I = A + attenuation * spot * (D + g * S)
# and glTF 2.0's metallic-roughness model (the specification's Appendix B, pbr_shade):
#     c_diff = base (1 - metallic),  F0 = 0.04 (1 - metallic) + base metallic
#     F = F0 + (1 - F0) (1 - V.H)^5,  D = a^2 / (pi ((N.H)^2 (a^2 - 1) + 1)^2),  a = r^2
#     Vis = 1 / ((|N.L| + sqrt(a^2 + (1 - a^2) (N.L)^2)) (|N.V| + sqrt(a^2 + (1 - a^2) (N.V)^2)))
#     I = A + light x attenuation x spot x ((1 - F) c_diff / pi + F D Vis) x N.L  (N.L > 0)
# with the project's ambient A = ambient light x base colour (x occlusion: none here),
# metallic PBR_METALLIC, roughness ROUGHNESS and the lights PBR_GAIN times brighter.
# The environment cases (issue 36): the split sum with its two integrals computed here
# from the sky's definition: the irradiance E(+Y)/pi (Gauss-Legendre) and the
# GGX-prefiltered sky about each pixel's reflection (a (theta, phi) grid), times Karis's
# analytic F0 A + B (its tolerance beside ENV_CASES).

def msvc_rand(seed, n):
    s, out = seed & 0xffffffff, []
    for _ in range(n):
        s = (s * 214013 + 2531011) & 0xffffffff
        out.append(((s >> 16) & 0x7fff) / 32767.0)
    return out


def light_of(case, gain=1.0):
    """The case's light in the model's terms: type, colour, position, unit direction of
    travel, attenuation (form, coefficients, range), spot cut-off and exponent."""
    if "light" in case:
        gl = case["light"]
        col = np.array(gl["color"]) * (gl["intensity"] * gain)
        lt = {"type": gl["type"], "color": col, "range": gl.get("range", math.inf),
              "att": "inverse-square"}
        if "pos" in case:
            lt["pos"] = np.array(case["pos"], dtype=np.float64)
        if gl["type"] != "point":
            d = case.get("dir")
            if d is None:
                d = np.subtract(case["at"], case["pos"])
            lt["dir"] = unit(d)
        if gl["type"] == "spot":
            lt["cos_c"] = math.cos(gl["spot"]["outerConeAngle"])
            lt["f"] = 1.0
        return lt
    g = case["grid"]
    q = g.get("quadratic", {"a": 1.0, "b": 0.0, "c": 1.0})
    return {"type": "point",
            "color": np.array(msvc_rand(SEED, 3)) * (COLOR_MAX * gain * g.get("boost", 1.0)),
            "pos": np.array([0.0, TOP / 2.0, 0.0]), "range": g["radius"],
            "att": g["attenuation"], "abc": (q["a"], q["b"], q["c"])}


def material():
    lum = 0.2126 * BASE[0] + 0.7152 * BASE[1] + 0.0722 * BASE[2]
    g = 0.04 * (1.0 - METALLIC) + lum * METALLIC
    a = ROUGHNESS * ROUGHNESS
    n = min(max(2.0 / (a * a) - 2.0, 1.0), 2048.0)
    return np.array(BASE), g, n


def pbr_shade(P, N, V, Ld, incoming, metallic, roughness):
    """glTF 2.0 Appendix B's metallic-roughness BRDF times N.L and the light (the
    project's floor on roughness, 0.045, does not act here)."""
    base = np.array(BASE)
    c_diff = base * (1.0 - metallic)
    f0 = 0.04 * (1.0 - metallic) + base * metallic
    a = roughness * roughness
    a2 = a * a
    ndl = Ld @ N
    Hh = Ld + V
    Hh /= np.linalg.norm(Hh, axis=-1, keepdims=True)
    vdh = np.clip(np.sum(V * Hh, axis=-1), 0.0, 1.0)
    ndh = np.clip(Hh @ N, 0.0, 1.0)
    ndv = np.abs(V @ N)
    F = f0 + (1.0 - f0) * ((1.0 - vdh) ** 5)[..., None]
    D = a2 / (math.pi * (ndh * ndh * (a2 - 1.0) + 1.0) ** 2)
    Vis = 1.0 / ((np.abs(ndl) + np.sqrt(a2 + (1.0 - a2) * ndl * ndl)) *
                 (ndv + np.sqrt(a2 + (1.0 - a2) * ndv * ndv)))
    f = (1.0 - F) * c_diff / math.pi + F * (D * Vis)[..., None]
    return np.where((ndl > 0.0)[..., None], incoming * f * ndl[..., None], 0.0)


def env_model(case, shading, V):
    """An environment case's image (no lights): the split sum of environment.inc, each
    factor integrated here. Phong: Kd E/pi + g prefiltered(R, r), with the file's g and
    n (material()) and r = (2 / (n + 2))^(1/4) (GGX's alpha = r^2 whose lobe matches n:
    the glTF roughness itself); pbr: c_diff E/pi + prefiltered(R, r) (F0 A + B)."""
    base = np.array(BASE)
    metallic, roughness = case["metallic"], case["roughness"]
    ndv = np.clip(V[..., 1], 0.0, 1.0)        # N = +Y
    ry = V[..., 1]                            # R = reflect(-V, N): R.y = V.y
    ys = np.linspace(ry.min(), ry.max(), 48)
    table = prefiltered(ys, roughness)
    P = np.stack([np.interp(ry, ys, table[:, c]) for c in range(3)], axis=-1)
    E = irradiance_up()
    if shading == "phong":
        lum = 0.2126 * BASE[0] + 0.7152 * BASE[1] + 0.0722 * BASE[2]
        g = 0.04 * (1.0 - metallic) + lum * metallic
        return base * E + g * P
    A, B = env_brdf(roughness, ndv)
    f0 = 0.04 * (1.0 - metallic) + base * metallic
    return base * (1.0 - metallic) * E + P * (f0 * A[..., None] + B[..., None])


MODELS_MADE = {}


def model(case, shading="phong"):
    """model_image, once per case (check() reads each case's model twice)."""
    key = json.dumps([case, shading], sort_keys=True)
    if key not in MODELS_MADE:
        MODELS_MADE[key] = model_image(case, shading)
    return MODELS_MADE[key]


def model_image(case, shading):
    """The expected image (H x W x 3, clamped to [0, 1]) and the mask of pixels on a
    spot cone's edge."""
    cam = CAMERA
    _, rot = quat_to_dir(quat_axis((1, 0, 0), math.radians(cam["pitch_deg"])))
    eye = np.array(cam["t"], dtype=np.float64)
    ty = math.tan(cam["yfov"] / 2.0)
    xs = (2.0 * (np.arange(W) + 0.5) / W - 1.0) * ty * (W / H)
    ys = (1.0 - 2.0 * (np.arange(H) + 0.5) / H) * ty
    X, Y = np.meshgrid(xs, ys)
    rays = np.stack([X, Y, -np.ones_like(X)], axis=-1) @ rot.T       # world space
    t = -eye[1] / rays[..., 1]
    if not np.all(t > 0):
        sys.exit("FAIL: the model: a pixel's ray misses the plane (the horizon is in view)")
    P = eye + rays * t[..., None]
    if np.abs(P[..., [0, 2]]).max() > HALF - 1.0:
        sys.exit("FAIL: the model: the plane does not fill the view")
    N = np.array([0.0, 1.0, 0.0])
    V = eye - P
    V /= np.linalg.norm(V, axis=-1, keepdims=True)
    if "env" in case:
        return np.clip(env_model(case, shading, V), 0.0, 1.0), np.zeros((H, W), dtype=bool)
    kd, g, n = material()
    lt = light_of(case, 1.0 if shading == "phong" else PBR_GAIN)
    edge = np.zeros((H, W), dtype=bool)
    if lt["type"] == "directional":
        Ld = np.broadcast_to(-lt["dir"], P.shape)
        att = np.ones((H, W))
    else:
        toL = lt["pos"] - P
        d = np.linalg.norm(toL, axis=-1)
        Ld = toL / d[..., None]
        if lt["att"] == "inverse-square":                      # appendix D form 2
            att = 1.0 / (d * d)
        elif lt["att"] == "linear-range":                      # form 3, maxRange = radius
            att = np.maximum(0.0, 1.0 - d / lt["range"])
        elif lt["att"] == "windowed":                          # Karis 2013
            w = np.clip(1.0 - (d / lt["range"]) ** 4, 0.0, 1.0)
            att = w * w / (d * d)
        else:                                                  # form 1
            a, b, c = lt["abc"]
            att = 1.0 / (a * d * d + b * d + c)
        att = np.where(d <= lt["range"], att, 0.0)
        if lt["type"] == "spot":
            s = -(Ld @ lt["dir"])                              # -L.A
            att = att * np.where(s > lt["cos_c"], np.maximum(s, 0.0) ** lt["f"], 0.0)
            edge = np.abs(s - lt["cos_c"]) < EDGE_EPS
    ndl = Ld @ N
    R = 2.0 * ndl[..., None] * N - Ld
    rv = np.maximum(np.sum(R * V, axis=-1), 0.0)
    D = lt["color"] * kd * np.maximum(ndl, 0.0)[..., None]
    S = lt["color"] * (rv ** n)[..., None]
    A = AMBIENT * kd
    if shading == "pbr":
        # the project's ambient term under pbr: ambient x base colour x occlusion; glTF
        # defines no ambient light. The maps (uniform) scale the factors (glTF 3.9.2).
        metallic, roughness, occlusion = PBR_METALLIC, ROUGHNESS, 1.0
        if "mr" in case:
            roughness *= case["mr"][1] / 255.0
            metallic *= case["mr"][2] / 255.0
            occlusion = 1.0 + case["strength"] * (case["occlusion"][0] / 255.0 - 1.0)
        I = A * occlusion + pbr_shade(P, N, V, Ld, lt["color"] * att[..., None], metallic,
                                      roughness)
    else:
        I = A + att[..., None] * (D + g * S)
    return np.clip(I, 0.0, 1.0), edge


# >>images

def read_png(path):
    """An 8-bit RGB or RGBA PNG (no interlace) as H x W x C uint8."""
    data = open(path, "rb").read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        sys.exit(f"FAIL: {path}: not a PNG")
    pos, idat, w = 8, b"", None
    while pos < len(data):
        n, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + n]
        pos += 12 + n
        if kind == b"IHDR":
            w, h, depth, ctype, _, _, inter = struct.unpack(">IIBBBBB", body)
            if depth != 8 or ctype not in (2, 6) or inter:
                sys.exit(f"FAIL: {path}: PNG depth {depth} colour type {ctype}")
            ch = 4 if ctype == 6 else 3
        elif kind == b"IDAT":
            idat += body
        elif kind == b"IEND":
            break
    raw = zlib.decompress(idat)
    stride = w * ch
    out = np.zeros((h, stride), dtype=np.int64)
    prev = np.zeros(stride, dtype=np.int64)
    for y in range(h):
        ft = raw[y * (stride + 1)]
        line = np.frombuffer(raw, np.uint8, stride, y * (stride + 1) + 1).astype(np.int64)
        if ft == 0:
            cur = line
        elif ft == 1:   # Sub: a running sum along the row, per channel, modulo 256
            cur = np.cumsum(line.reshape(w, ch), axis=0).reshape(stride) & 0xff
        elif ft == 2:   # Up
            cur = (line + prev) & 0xff
        else:           # Average, Paeth: each byte needs the one to its left, in ints
            cur, up, ln = [0] * stride, prev.tolist(), line.tolist()
            for x in range(stride):
                a = cur[x - ch] if x >= ch else 0
                b = up[x]
                if ft == 3:
                    p = (a + b) >> 1
                else:
                    c = up[x - ch] if x >= ch else 0
                    pa, pb, pc = abs(b - c), abs(a - c), abs(a + b - 2 * c)
                    p = a if pa <= pb and pa <= pc else (b if pb <= pc else c)
                cur[x] = (ln[x] + p) & 0xff
            cur = np.array(cur, dtype=np.int64)
        out[y] = cur
        prev = cur
    return out.reshape(h, w, ch).astype(np.uint8)


# Tolerance: per case and renderer, over every pixel, the largest channel difference
# between the screenshot (u8 / 255) and the model (clamped to [0, 1]) at most 1/255 (the
# 8-bit rounding alone is up to 0.5/255), and the RMSE at most 0.5/255. Pixels whose spot
# cosine lies within 1e-4 of cos(c) (the cone's edge, a step of cos(c) in the model) are
# left out of both and counted.
def check(d):
    failures, rows = [], []
    for shading, name, case in all_cases():
        want, edge = model(case, shading)
        max_tol, rmse_tol = (ENV_MAX_TOL, ENV_RMSE_TOL) if "env" in case else (MAX_TOL,
                                                                              RMSE_TOL)
        out = os.path.join(d, "out-" + name)
        summ = list(csv.DictReader(open(os.path.join(out, "summary.csv"))))
        got_renderers = [r["renderer"] for r in summ]
        if sorted(got_renderers) != sorted(RENDERERS):
            failures.append(f"{name}: renderers {got_renderers}")
            continue
        for r in summ:
            if r["status"] != "ok":
                failures.append(f"{name} {r['renderer']}: status {r['status']}")
                continue
            shots = glob.glob(os.path.join(out, "runs", r["run_id"], "screenshot-*.png"))
            if len(shots) != 1:
                failures.append(f"{name} {r['renderer']}: screenshots {shots}")
                continue
            img = read_png(shots[0])[..., :3].astype(np.float64) / 255.0
            if img.shape != want.shape:
                failures.append(f"{name} {r['renderer']}: image {img.shape}")
                continue
            diff = np.abs(img - want)[~edge]
            mx, rmse = float(diff.max()), float(np.sqrt(np.mean(diff ** 2)))
            rows.append((name, r["renderer"], mx * 255, rmse * 255, int(edge.sum())))
            if not (mx <= max_tol + 1e-9 and rmse <= rmse_tol):
                yx = np.unravel_index(np.argmax(np.where(edge[..., None], 0,
                                                         np.abs(img - want)).max(axis=-1)),
                                      edge.shape)
                failures.append(
                    f"{name} {r['renderer']}: max {mx * 255:.3f}/255 rmse {rmse * 255:.3f}/255 "
                    f"(tolerance {max_tol * 255:.1f}/255, {rmse_tol * 255:.1f}/255); worst pixel "
                    f"x={yx[1]} y={yx[0]}: image {np.round(img[yx] * 255, 1)} model "
                    f"{np.round(want[yx] * 255, 2)}")
    # the model itself must be far from flat, or the comparison proves nothing
    for shading, name, case in all_cases():
        want, _ = model(case, shading)
        if "env" in case:   # the sky is smooth: the image must be lit, not saturated
            if want.min() < 0.1 or (want >= 1.0).mean() > 0.02:
                failures.append(f"{name}: the model's image spans {want.min():.3f}.."
                                f"{want.max():.3f}: a weak case")
            continue
        if want.max() - want.min() < 0.3 or (want >= 1.0).mean() > 0.02:
            failures.append(f"{name}: the model's image spans {want.min():.3f}..{want.max():.3f} "
                            f"with {(want >= 1.0).mean():.1%} saturated: a weak case")
    print("case              renderer        max/255  rmse/255  edge px")
    for row in rows:
        print(f"{row[0]:17s} {row[1]:15s} {row[2]:7.3f}  {row[3]:7.3f}  {row[4]:6d}")
    if failures:
        for f in failures:
            print("FAIL:", f, file=sys.stderr)
        sys.exit(1)


if __name__ == "__main__":
    if len(sys.argv) != 3 or sys.argv[1] not in ("gen", "check"):
        sys.exit(__doc__)
    (gen if sys.argv[1] == "gen" else check)(sys.argv[2])
