/* File scenes, >>materials: assimp's materials onto the Phong model, as the mapping in
 * scenes/file/file_assimp.c's opening comment says. */
#include "scenes/file/file_internal.h"

#include <assimp/GltfMaterial.h>

#include <stdlib.h>
#include <string.h>

/* assimp's aiGetMaterialFloat is a C99 `inline` function with no external definition: an
 * unoptimised build (the sanitizer suite's -O0) would not link. The array form is a real
 * export. */
static enum aiReturn mat_float(const struct aiMaterial *m, const char *key, unsigned type,
                               unsigned index, float *out)
{
    return aiGetMaterialFloatArray(m, key, type, index, out, NULL);
}

/* A material's alpha mode (glTF alphaMode; OBJ: d < 1 is translucent) and cutoff. */
material_alpha file_alpha_mode(const struct aiMaterial *am, float *cutoff)
{
    struct aiString mode;
    float opacity = 1.0f;
    if (aiGetMaterialString(am, AI_MATKEY_GLTF_ALPHAMODE, &mode) == aiReturn_SUCCESS) {
        if (strcmp(mode.data, "MASK") == 0) {
            float c = 0.5f;
            mat_float(am, AI_MATKEY_GLTF_ALPHACUTOFF, &c);
            if (cutoff)
                *cutoff = c;
            return MATERIAL_MASK;
        }
        return strcmp(mode.data, "BLEND") == 0 ? MATERIAL_BLEND : MATERIAL_OPAQUE;
    }
    mat_float(am, AI_MATKEY_OPACITY, &opacity);
    return opacity < 1.0f ? MATERIAL_BLEND : MATERIAL_OPAQUE;
}

static float luminance(const struct aiColor4D *c)
{
    return 0.2126f * c->r + 0.7152f * c->g + 0.0722f * c->b;
}

/* Blinn-Phong exponent for a roughness: GGX alpha = r^2, n = 2 / alpha^2 - 2. */
static float shininess_of_roughness(float r)
{
    r = sm_clamp(r, 0.0f, 1.0f);
    float a = r * r;
    float n = a > 0.0f ? 2.0f / (a * a) - 2.0f : 2048.0f;
    return sm_clamp(n, 1.0f, 2048.0f);
}

/* A texture of the file as a scene texture; its index, or -1 for none. */
static int scene_texture(scene_builder *b, loaded *l, const char *ref, int *map, bool emissive)
{
    if (!ref[0] || b->failed)
        return -1;
    int i = file_load_image(l, ref, b->err, b->errlen);
    if (i < 0) {
        b->failed = true;
        return -1;
    }
    if (map[i] >= 0 && !emissive)
        return map[i];
    scene *s = b->s;
    if (!sb_reserve(b, (void **)&s->textures, &b->cap_textures, s->ntextures, 1,
                    sizeof *s->textures, "textures"))
        return -1;
    const image *img = &l->images[i].img;
    texture_image *t = &s->textures[s->ntextures];
    size_t n = (size_t)img->width * (size_t)img->height * 4;
    t->data = malloc(n);
    if (!t->data) {
        sb_fail(b, "%s: out of memory for a %dx%d texture", l->path, img->width, img->height);
        return -1;
    }
    memcpy(t->data, img->pixels, n);
    t->width = (uint32_t)img->width;
    t->height = (uint32_t)img->height;
    t->channels = 4;
    if (emissive)   /* the emissive mask: the whole texel */
        for (size_t k = 3; k < n; k += 4)
            t->data[k] = 255;
    else
        map[i] = (int)s->ntextures;
    return (int)s->ntextures++;
}

/* The ORM map of scene.h from a file's metallic-roughness map (G roughness, B metallic)
 * and occlusion map (R), either of which may be absent ("": 255 in its channels, a
 * factor of 1); the occlusion map is sampled at the nearest texel when its size differs
 * (glTF allows it; most files pack both in one image). Its index, or -1 for neither. */
static int orm_texture(scene_builder *b, loaded *l, const char *mr_ref, const char *occ_ref)
{
    if ((!mr_ref[0] && !occ_ref[0]) || b->failed)
        return -1;
    int mi = mr_ref[0] ? file_load_image(l, mr_ref, b->err, b->errlen) : -1;
    int oi = occ_ref[0] && !b->failed ? file_load_image(l, occ_ref, b->err, b->errlen) : -1;
    if ((mr_ref[0] && mi < 0) || (occ_ref[0] && oi < 0)) {
        b->failed = true;
        return -1;
    }
    scene *s = b->s;
    if (!sb_reserve(b, (void **)&s->textures, &b->cap_textures, s->ntextures, 1,
                    sizeof *s->textures, "textures"))
        return -1;
    /* both images are the loader's, which file_load_image may grow: taken after both */
    const image *mr = mi >= 0 ? &l->images[mi].img : NULL;
    const image *occ = oi >= 0 ? &l->images[oi].img : NULL;
    const image *size = mr ? mr : occ;
    size_t w = (size_t)size->width, h = (size_t)size->height;
    texture_image *t = &s->textures[s->ntextures];
    t->data = malloc(w * h * 4);
    if (!t->data) {
        sb_fail(b, "%s: out of memory for a %zux%zu texture", l->path, w, h);
        return -1;
    }
    const unsigned char *mp = mr ? mr->pixels : NULL, *op = occ ? occ->pixels : NULL;
    for (size_t y = 0; y < h; y++)
        for (size_t x = 0; x < w; x++) {
            unsigned char *o = t->data + 4 * (y * w + x);
            o[0] = o[1] = o[2] = o[3] = 255;
            if (mr) {
                o[1] = mp[4 * (y * w + x) + 1];
                o[2] = mp[4 * (y * w + x) + 2];
            }
            if (occ) {
                size_t ox = x * (size_t)occ->width / w, oy = y * (size_t)occ->height / h;
                o[0] = op[4 * (oy * (size_t)occ->width + ox)];
            }
        }
    t->width = (uint32_t)w;
    t->height = (uint32_t)h;
    t->channels = 4;
    return (int)s->ntextures++;
}

/* Mapping onto the Phong model (docs/notes/file-scenes.md):
 *   diffuse    base colour factor (glTF) or Kd (OBJ), times the base colour / diffuse map
 *   specular   metallic-roughness: F0 = mix(0.04, luminance(base colour), metallic);
 *              specular-glossiness and Phong: luminance of the specular colour
 *   shininess  glTF: from roughness (1 - glossiness) as the Blinn-Phong exponent that
 *              matches GGX's alpha = roughness^2, n = 2 / alpha^2 - 2, clamped to
 *              [1, 2048]; OBJ: Ns (0 counts as 1)
 *   normal map the normal texture, tangents from our own mesh_compute_tangents
 *   emissive   the emissive factor times the emissive map (mask alpha = 1)
 *   alpha      MASK -> MATERIAL_MASK with the cutoff; BLEND -> MATERIAL_BLEND (translucent,
 *              opacity: assimp's opacity, else the base colour's alpha) */
void file_add_material(scene_builder *b, loaded *l, unsigned index, int *map)
{
    const struct aiMaterial *am = l->ai->mMaterials[index];
    struct aiColor4D base = {1, 1, 1, 1}, spec = {0, 0, 0, 1}, emis = {0, 0, 0, 1};
    if (aiGetMaterialColor(am, AI_MATKEY_BASE_COLOR, &base) != aiReturn_SUCCESS)
        aiGetMaterialColor(am, AI_MATKEY_COLOR_DIFFUSE, &base);
    aiGetMaterialColor(am, AI_MATKEY_COLOR_EMISSIVE, &emis);
    float metallic = 0.0f, roughness = 1.0f, gloss = 0.0f, shininess = 0.0f;
    float specular, exponent;
    bool pbr = false;   /* glTF's own factors, else the Phong material's (sb_material) */
    if (mat_float(am, AI_MATKEY_ROUGHNESS_FACTOR, &roughness) == aiReturn_SUCCESS &&
        mat_float(am, AI_MATKEY_GLOSSINESS_FACTOR, &gloss) != aiReturn_SUCCESS) {
        mat_float(am, AI_MATKEY_METALLIC_FACTOR, &metallic);
        metallic = sm_clamp(metallic, 0.0f, 1.0f);
        specular = 0.04f * (1.0f - metallic) + luminance(&base) * metallic;
        exponent = shininess_of_roughness(roughness);
        pbr = true;
    } else if (mat_float(am, AI_MATKEY_GLOSSINESS_FACTOR, &gloss) == aiReturn_SUCCESS) {
        aiGetMaterialColor(am, AI_MATKEY_COLOR_SPECULAR, &spec);
        specular = luminance(&spec);
        exponent = shininess_of_roughness(1.0f - gloss);
        /* specular-glossiness under the metallic-roughness model: a dielectric of the
         * glossiness's roughness (its specular colour is not F0's 0.04; listed) */
        roughness = 1.0f - gloss;
        pbr = true;
    } else {
        aiGetMaterialColor(am, AI_MATKEY_COLOR_SPECULAR, &spec);
        mat_float(am, AI_MATKEY_SHININESS, &shininess);
        specular = luminance(&spec);
        exponent = sm_clamp(shininess, 1.0f, 2048.0f);
    }
    uint32_t mi = sb_material(b, base.r, base.g, base.b, sm_clamp(specular, 0.0f, 1.0f),
                              exponent);
    if (b->failed)
        return;
    material_refs r;
    file_material_refs(am, &r);
    int d = scene_texture(b, l, r.diffuse, map, false);
    int nm = scene_texture(b, l, r.normal, map, false);
    int em = scene_texture(b, l, r.emissive, map, true);
    int orm = orm_texture(b, l, r.mr, r.occlusion);
    if (b->failed)
        return;
    scene_material *m = &b->s->materials[mi];
    if (pbr) {
        m->metallic = metallic;
        m->roughness = isfinite(roughness) ? sm_clamp(roughness, 0.0f, 1.0f) : 1.0f;
    }
    m->orm_map = orm;
    if (orm >= 0 && r.occlusion[0]) {
        float strength = 1.0f;
        mat_float(am, AI_MATKEY_GLTF_TEXTURE_STRENGTH(aiTextureType_LIGHTMAP, 0), &strength);
        m->occlusion = isfinite(strength) ? sm_clamp(strength, 0.0f, 1.0f) : 1.0f;
    }
    m->diffuse_map = d;
    m->normal_map = nm;
    m->emissive_map = em;
    /* a map on the second uv set (texCoord 1) reads mesh.uv2 */
    m->uv1_maps = (d >= 0 && r.diffuse_uv == 1 ? 1u : 0u) | (nm >= 0 && r.normal_uv == 1 ? 4u : 0u) |
                  (em >= 0 && r.emissive_uv == 1 ? 8u : 0u) |
                  /* the ORM map reads the metallic-roughness map's set (or the occlusion
                   * map's without one): bit 1, the gloss map's, which it replaces */
                  (orm >= 0 && (r.mr[0] ? r.mr_uv : r.occlusion_uv) == 1 ? 2u : 0u);
    sm_vec3_make(emis.r, emis.g, emis.b, m->emissive);
    if (em >= 0 && emis.r == 0.0f && emis.g == 0.0f && emis.b == 0.0f)
        sm_vec3_make(1.0f, 1.0f, 1.0f, m->emissive);   /* OBJ: map_Ke without Ke */
    if (index < l->nemissive_strength)   /* glTF's KHR_materials_emissive_strength */
        sm_vec3_scale(m->emissive, l->emissive_strength[index], m->emissive);
    float cutoff = 0.5f;
    m->alpha = file_alpha_mode(am, &cutoff);
    if (m->alpha == MATERIAL_MASK)
        m->alpha_cutoff = cutoff;
    if (m->alpha == MATERIAL_BLEND) {
        /* glTF: the base colour factor's alpha (the map's alpha multiplies it in the
         * shader); OBJ: d (assimp's opacity) */
        float opacity = base.a;
        if (mat_float(am, AI_MATKEY_OPACITY, &opacity) != aiReturn_SUCCESS)
            opacity = base.a;
        m->opacity = isfinite(opacity) ? sm_clamp(opacity, 0.0f, 1.0f) : 1.0f;
    }
    int two_sided = 0;
    unsigned one = 1;
    m->double_sided = aiGetMaterialIntegerArray(am, AI_MATKEY_TWOSIDED, &two_sided, &one) ==
                          AI_SUCCESS && two_sided != 0;
}

/* One map's KHR_texture_transform, as glTF defines it (offset, rotation, scale: uv' =
 * T(offset) R(rotation) S(scale) uv, R = [cos sin; -sin cos], in glTF's uv, whose v runs
 * down the image as ours does). assimp 5.2's glTF importer stores it as an aiUVTransform
 * for its own bottom-up v and a rotation about the centre: translation (tx, ty), scaling
 * (sx, sy), rotation -r, with tx = 0.5 sx (1 - cos r + sin r) + offset.x and ty =
 * 0.5 sy (sin r + cos r - 1) + 1 - sy - offset.y; those are inverted here
 * (tests/unit/test_scene_file.c checks a quad's corners; the Khronos TextureTransformTest's
 * arrows point at their green markers, seen by eye). False: no transform. */
static bool map_transform(const struct aiMaterial *am, enum aiTextureType type,
                          float out[2][3])
{
    struct aiUVTransform t;
    unsigned n = sizeof t / sizeof(ai_real);
    if (aiGetMaterialTextureCount(am, type) == 0 ||
        aiGetMaterialFloatArray(am, _AI_MATKEY_UVTRANSFORM_BASE, type, 0, (ai_real *)&t, &n) !=
            aiReturn_SUCCESS ||
        n != sizeof t / sizeof(ai_real))
        return false;
    float r = -t.mRotation, c = cosf(r), s = sinf(r), sx = t.mScaling.x, sy = t.mScaling.y;
    float ox = t.mTranslation.x - 0.5f * sx * (1.0f - c + s);
    float oy = 0.5f * sy * (s + c - 1.0f) + 1.0f - sy - t.mTranslation.y;
    const float m[2][3] = {{c * sx, s * sy, ox}, {-s * sx, c * sy, oy}};
    memcpy(out, m, sizeof m);
    return isfinite(ox) && isfinite(oy) && isfinite(c * sx) && isfinite(c * sy);
}

int file_uv_transform(const struct aiMaterial *am, float out[2][3])
{
    /* the base colour first (assimp gives glTF's under both types) */
    static const enum aiTextureType types[] = {aiTextureType_BASE_COLOR, aiTextureType_DIFFUSE,
                                               aiTextureType_NORMALS, aiTextureType_EMISSIVE,
                                               aiTextureType_UNKNOWN, aiTextureType_LIGHTMAP};
    static const float identity[2][3] = {{1, 0, 0}, {0, 1, 0}};
    bool have = false, differ = false;
    for (size_t k = 0; k < sizeof types / sizeof types[0]; k++) {
        float m[2][3];
        if (aiGetMaterialTextureCount(am, types[k]) == 0)
            continue;
        if (!map_transform(am, types[k], m))
            memcpy(m, identity, sizeof m);
        if (!have)
            memcpy(out, m, sizeof m);
        else
            differ |= memcmp(out, m, sizeof m) != 0;
        have = true;
    }
    if (!have)
        return 0;
    return differ ? -1 : memcmp(out, identity, sizeof identity) != 0;
}
