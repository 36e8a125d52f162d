/* What a file scene has that no renderer draws: the phrases of
 * scene_file_info.not_rendered (skin influences past four, orthographic cameras,
 * per-map texture transforms, glTF extensions that are read but not drawn, ...). */
#include "scenes/file/file_internal.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

/* One phrase of info->not_rendered (the list keeps its first SCENE_FILE_MAX_NOT_RENDERED). */
static void not_rendered(scene_file_info *info, const char *fmt, ...)
    __attribute__((format(printf, 2, 3)));
static void not_rendered(scene_file_info *info, const char *fmt, ...)
{
    if (info->nnot_rendered >= SCENE_FILE_MAX_NOT_RENDERED)
        return;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(info->not_rendered[info->nnot_rendered++], sizeof info->not_rendered[0], fmt, ap);
    va_end(ap);
}

/* The first place of key (n bytes) in the n_data bytes at data, or NULL. */
static const char *find_bytes(const unsigned char *data, size_t n_data, const char *key, size_t n)
{
    for (size_t i = 0; n <= n_data && i <= n_data - n; i++)
        if (data[i] == (unsigned char)key[0] && memcmp(data + i, key, n) == 0)
            return (const char *)data + i;
    return NULL;
}

/* The glTF extensions the file says it uses (its JSON's "extensionsUsed", in a .gltf or a
 * .glb's JSON chunk) that shadesweep does not implement: all but the lights
 * (lights.placement: scene), mesh quantization (assimp decodes it), specular-glossiness
 * (mapped onto Phong like metallic-roughness), texture transforms (baked into the uv;
 * where one material's maps differ, file_not_rendered says so) and emissive strength
 * (file_gltf_emissive_strengths: it scales the emissive). */
static void gltf_extensions(const read_file *f, scene_file_info *info)
{
    static const char *const implemented[] = {"KHR_lights_punctual", "KHR_mesh_quantization",
                                              "KHR_materials_pbrSpecularGlossiness",
                                              "KHR_texture_transform",
                                              "KHR_materials_emissive_strength"};
    /* the JSON only: a .glb's first chunk (its length at byte 12, validated by the
     * pre-scan), a .gltf whole; an OBJ or a binary chunk is not searched */
    size_t json = 0, start = 0;
    while (start < f->size && (f->data[start] == ' ' || f->data[start] == '\t' ||
                               f->data[start] == '\r' || f->data[start] == '\n'))
        start++;
    if (f->size >= 20 && memcmp(f->data, "glTF", 4) == 0) {
        start = 20;
        json = (size_t)f->data[12] | (size_t)f->data[13] << 8 | (size_t)f->data[14] << 16 |
               (size_t)f->data[15] << 24;
        json = json < f->size - start ? json : f->size - start;
    } else if (start < f->size && f->data[start] == '{') {
        json = f->size - start;
    }
    const char *end = (const char *)f->data + start + json;
    const char *at = find_bytes(f->data + start, json, "\"extensionsUsed\"", 16);
    if (!at || !(at = memchr(at, '[', (size_t)(end - at))))
        return;
    for (at++; at < end && *at != ']';) {
        if (*at != '"') {
            at++;
            continue;
        }
        const char *name = ++at;
        while (at < end && *at != '"')
            at++;
        size_t n = (size_t)(at - name);
        bool known = false;
        for (size_t i = 0; i < sizeof implemented / sizeof implemented[0]; i++)
            known |= strlen(implemented[i]) == n && strncmp(implemented[i], name, n) == 0;
        if (!known && n < 48) {
            char ext[48];
            memcpy(ext, name, n);
            ext[n] = '\0';
            not_rendered(info, "glTF extension %s", ext);
        }
        at++;
    }
}

/* What the file has that no renderer draws (scene_file_info.not_rendered). */
void file_not_rendered(const loaded *l, bool phong, scene_file_info *info)
{
    const struct aiScene *ai = l->ai;
    unsigned over4 = 0, ortho = 0;   /* skinned vertices with influences dropped */
    for (unsigned i = 0; i < ai->mNumMeshes; i++)
        over4 += file_skin_over4(ai->mMeshes[i]);
    for (unsigned i = 0; i < ai->mNumCameras; i++)
        ortho += ai->mCameras[i]->mOrthographicWidth > 0.0f;
    unsigned uv_differ = 0, mr_maps = 0, occlusion = 0, used = 0, far_uv = 0, spec_gloss = 0,
             occ_uv = 0;
    for (unsigned i = 0; i < ai->mNumMaterials; i++) {
        const struct aiMaterial *am = ai->mMaterials[i];
        bool drawn = false;   /* not assimp's default material, where no mesh uses it */
        for (unsigned k = 0; k < ai->mNumMeshes && !drawn; k++)
            drawn = ai->mMeshes[k]->mMaterialIndex == i;
        if (!drawn)
            continue;
        used++;
        float uvt[2][3];
        uv_differ += file_uv_transform(am, uvt) < 0;
        material_refs refs;
        file_material_refs(am, &refs);
        far_uv += (refs.diffuse[0] && refs.diffuse_uv > 1) + (refs.normal[0] && refs.normal_uv > 1) +
                  (refs.emissive[0] && refs.emissive_uv > 1);
        if (!phong) {   /* pbr reads them (the ORM map: the metallic-roughness map's set) */
            far_uv += (refs.mr[0] && refs.mr_uv > 1) + (refs.occlusion[0] && refs.occlusion_uv > 1);
            occ_uv += refs.mr[0] && refs.occlusion[0] && refs.mr_uv != refs.occlusion_uv;
        }
        /* assimp 5.2's glTF importer: metallicRoughnessTexture under METALNESS (and
         * UNKNOWN), occlusionTexture under LIGHTMAP */
        mr_maps += aiGetMaterialTextureCount(am, aiTextureType_METALNESS) +
                       aiGetMaterialTextureCount(am, aiTextureType_UNKNOWN) > 0;
        occlusion += aiGetMaterialTextureCount(am, aiTextureType_LIGHTMAP) +
                         aiGetMaterialTextureCount(am, aiTextureType_AMBIENT_OCCLUSION) > 0;
        float gloss;
        spec_gloss += aiGetMaterialFloatArray(am, AI_MATKEY_GLOSSINESS_FACTOR, &gloss, NULL) ==
                      aiReturn_SUCCESS;
    }
    if (over4)   /* skins are drawn (file_skin.c) with 4 influences a vertex */
        not_rendered(info, "skin influences after the 4 largest (%u vertices)", over4);
    /* the first animation's node channels play (file_anim.c); the rest does not */
    if (ai->mNumAnimations > 1)
        not_rendered(info, "animations after the first (%u, not played)",
                     ai->mNumAnimations - 1);
    if (ai->mNumAnimations && ai->mAnimations[0]->mNumMeshChannels)
        not_rendered(info, "vertex animation (%u mesh channels, not played)",
                     ai->mAnimations[0]->mNumMeshChannels);
    if (ortho)
        not_rendered(info, "orthographic cameras (%u)", ortho);
    /* shading.model pbr (a file's default) renders glTF's materials and their maps;
     * phong maps them onto seed 000's model (file_materials.c) */
    if (phong && file_is_gltf(l->path) && used)
        not_rendered(info, "metallic-roughness shading (%u material%s, as Phong)", used,
                     used == 1 ? "" : "s");
    if (phong && mr_maps)
        not_rendered(info, "metallic-roughness maps (%u material%s)", mr_maps,
                     mr_maps == 1 ? "" : "s");
    if (phong && occlusion)
        not_rendered(info, "occlusion maps (%u material%s)", occlusion, occlusion == 1 ? "" : "s");
    if (!phong && spec_gloss)
        not_rendered(info, "specular colours of specular-glossiness materials (%u, drawn as "
                     "dielectrics)", spec_gloss);
    if (far_uv)
        not_rendered(info, "texture coordinate sets after the second (%u map%s, read from the "
                     "first)", far_uv, far_uv == 1 ? "" : "s");
    if (uv_differ)
        not_rendered(info, "per-map texture transforms (%u material%s: the base colour's used)",
                     uv_differ, uv_differ == 1 ? "" : "s");
    if (occ_uv)
        not_rendered(info, "occlusion maps read from the roughness map's uv set (%u)", occ_uv);
    if (l->files.n)
        gltf_extensions(&l->files.files[0], info);
}
