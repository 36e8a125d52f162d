/* File scenes through assimp: glTF 2.0 (.gltf + .bin + images, .glb, embedded data URIs)
 * and OBJ + MTL, and no other format (file_import.cpp). No GL in here; textures decode
 * through OpenImageIO (common/image_io.h).
 *
 * Every byte assimp reads goes through our own file callbacks (>>io), which read each
 * file whole, once, and feed it to the content hash; images the materials reference
 * are read the same way before they are decoded. scene_file_check and the builder share
 * one loader (>>load), so what validate accepts is exactly what a run builds.
 *
 * Untrusted input: only regular files are opened, references stay in the scene file's
 * folder (unless allow_outside), and glTF JSON is pre-scanned before assimp (>>prescan).
 * Sections, each its own file (scenes/file/file_internal.h): >>io file_io.c, >>prescan
 * file_prescan.c, >>load file_load.c, >>materials file_materials.c, >>unrendered
 * file_unrendered.c; here >>nodes >>check >>build. The mapping of a file's materials onto the Phong model: the comment above
 * file_add_material (file_materials.c). */
#include "scenes/file/file_internal.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "scenes/scene_anim.h"
#include "scenes/scene_fail.h"
#include "scenes/scene_internal.h"

uint64_t scene_fnv1a64_more(uint64_t h, const void *data, size_t len)
{
    const unsigned char *p = data;
    for (size_t i = 0; i < len; i++) {
        h ^= p[i];
        h *= UINT64_C(0x100000001b3);
    }
    return h;
}

// >>nodes

/* Our matrix (column-major, m[col][row]) from assimp's row-major one. */
/* The root transform: the file's scale, and z-up turned to y-up ((x, y, z) -> (x, z, -y)). */
static void root_transform(const scene_file_options *o, sm_mat4 m)
{
    float s = o->scale > 0.0f ? o->scale : 1.0f;
    sm_mat4_identity(m);
    if (o->up == SCENE_UP_Z) {
        m[1][1] = 0.0f;
        m[1][2] = -s;
        m[2][1] = s;
        m[2][2] = 0.0f;
        m[0][0] = s;
    } else {
        m[0][0] = m[1][1] = m[2][2] = s;
    }
}

typedef void (*node_fn)(const struct aiNode *n, const sm_mat4 world, void *user);

static void walk(const struct aiNode *n, const sm_mat4 parent, node_fn fn, void *user,
                 unsigned depth)
{
    sm_mat4 local, world;
    file_matrix_from_ai(&n->mTransformation, local);
    sm_mat4_mul(parent, local, world);
    fn(n, world, user);
    if (depth + 1 < FILE_MAX_NODE_DEPTH)
        for (unsigned i = 0; i < n->mNumChildren; i++)
            walk(n->mChildren[i], world, fn, user, depth + 1);
}

/* The world transform of the node named `name` (lights, cameras), false if none. */
typedef struct find_node {
    const char *name;
    bool found;
    sm_mat4 world;
    const struct aiNode *node;
} find_node;

static void find_fn(const struct aiNode *n, const sm_mat4 world, void *user)
{
    find_node *f = user;
    if (!f->found && strcmp(n->mName.data, f->name) == 0) {
        f->found = true;
        f->node = n;
        sm_mat4_copy(world, f->world);
    }
}

/* A float of a node's metadata (assimp keeps KHR_lights_punctual's range there as
 * "PBR_LightRange"); false if the node has none. */
static bool node_float(const struct aiNode *n, const char *key, float *out)
{
    const struct aiMetadata *m = n ? n->mMetaData : NULL;
    for (unsigned k = 0; m && k < m->mNumProperties; k++)
        if (strcmp(m->mKeys[k].data, key) == 0) {
            if (m->mValues[k].mType == AI_FLOAT && m->mValues[k].mData) {
                *out = *(const float *)m->mValues[k].mData;
                return true;
            }
            if (m->mValues[k].mType == AI_DOUBLE && m->mValues[k].mData) {
                *out = (float)*(const double *)m->mValues[k].mData;
                return true;
            }
        }
    return false;
}

/* glTF by its extension: assimp's glTF importer gives cameras its own way (below). */
bool file_is_gltf(const char *path)
{
    const char *dot = strrchr(path, '.');
    return dot && (strcasecmp(dot, ".gltf") == 0 || strcasecmp(dot, ".glb") == 0);
}

/* Counts and bounds over every mesh instance. */
typedef struct count_nodes {
    const struct aiScene *ai;
    uint32_t objects;
    uint64_t triangles;
    sm_vec3 lo, hi;
} count_nodes;

static void count_fn(const struct aiNode *n, const sm_mat4 world, void *user)
{
    count_nodes *c = user;
    for (unsigned i = 0; i < n->mNumMeshes; i++) {
        const struct aiMesh *m = c->ai->mMeshes[n->mMeshes[i]];
        c->objects++;
        c->triangles += m->mNumFaces;
        for (unsigned v = 0; v < m->mNumVertices; v++) {
            sm_vec3 p = {m->mVertices[v].x, m->mVertices[v].y, m->mVertices[v].z}, w;
            sm_mat4_mulv3(world, p, 1.0f, w);
            for (int k = 0; k < 3; k++) {
                c->lo[k] = fminf(c->lo[k], w[k]);
                c->hi[k] = fmaxf(c->hi[k], w[k]);
            }
        }
    }
}

static void counts_of(const scene_file_options *o, const loaded *l, count_nodes *c)
{
    memset(c, 0, sizeof *c);
    c->ai = l->ai;
    for (int k = 0; k < 3; k++) {
        c->lo[k] = INFINITY;
        c->hi[k] = -INFINITY;
    }
    sm_mat4 root;
    root_transform(o, root);
    walk(l->ai->mRootNode, root, count_fn, c, 0);
}

/* o with the scale a run applies (root_transform's) as a number > 0: the manifest's, or
 * with fit the one that makes the diagonal of the bounds at scale 1
 * SCENE_FILE_FIT_DIAGONAL; 1 where those bounds have no extent (one point, or no mesh:
 * the check refuses that) or the factor does not fit a float. The check and the builder
 * both take it, so they agree. */
static scene_file_options applied_options(const scene_file_options *o, const loaded *l)
{
    scene_file_options a = *o;
    a.fit = false;
    a.scale = o->scale > 0.0f && !o->fit ? o->scale : 1.0f;
    if (!o->fit)
        return a;
    count_nodes c;
    counts_of(&a, l, &c);
    double d2 = 0.0;
    for (int k = 0; k < 3; k++) {
        double e = (double)c.hi[k] - (double)c.lo[k];
        d2 += e * e;
    }
    double d = sqrt(d2);
    float s = d > 0.0 && isfinite(d) ? (float)(SCENE_FILE_FIT_DIAGONAL / d) : 1.0f;
    a.scale = isfinite(s) && s > 0.0f ? s : 1.0f;
    return a;
}

// >>check

/* The file's camera a run looks through: the one named, or with camera auto (the
 * default) the first perspective one; NULL for orbit and for auto without one. */
static const struct aiCamera *chosen_camera(const struct aiScene *ai, const char *camera)
{
    if (file_camera_is(camera, "orbit"))
        return NULL;
    bool any = file_camera_is(camera, "auto");
    for (unsigned i = 0; i < ai->mNumCameras; i++) {
        const struct aiCamera *cam = ai->mCameras[i];
        if (any ? cam->mOrthographicWidth <= 0.0f : strcmp(cam->mName.data, camera) == 0)
            return cam;
    }
    return NULL;
}


bool scene_file_check(const scene_file_options *o, scene_file_info *info, char *err,
                      size_t errlen)
{
    return scene_file_check_list(o, info, NULL, err, errlen);
}

bool scene_file_check_list(const scene_file_options *o, scene_file_info *info,
                           scene_file_list *files, char *err, size_t errlen)
{
    loaded l;
    if (!file_load(o, &l, err, errlen))
        return false;
    scene_file_options applied = applied_options(o, &l);
    o = &applied;
    count_nodes c;
    counts_of(o, &l, &c);
    bool ok = true;
    if (c.objects == 0 || !(c.lo[0] <= c.hi[0])) {
        ok = scene_fail(err, errlen, "%s: empty scene: no node draws a mesh", o->path);
    } else if (!(isfinite(c.lo[0]) && isfinite(c.lo[1]) && isfinite(c.lo[2]) &&
                 isfinite(c.hi[0]) && isfinite(c.hi[1]) && isfinite(c.hi[2]))) {
        ok = scene_fail(err, errlen, "%s: node transforms put vertices at non-finite positions",
                        o->path);
    }
    if (ok && info) {
        memset(info, 0, sizeof *info);
        info->meshes = l.ai->mNumMeshes;
        info->triangles = c.triangles;
        info->objects = c.objects;
        info->materials = l.ai->mNumMaterials;
        info->textures = l.nimages;
        info->lights = l.ai->mNumLights;
        info->cameras = l.ai->mNumCameras;
        for (unsigned i = 0; i < l.ai->mNumMaterials; i++) {
            material_alpha a = file_alpha_mode(l.ai->mMaterials[i], NULL);
            info->materials_mask += a == MATERIAL_MASK;
            info->materials_blend += a == MATERIAL_BLEND;
        }
        info->files = l.files.n;
        uint64_t h = UINT64_C(0xcbf29ce484222325);
        for (uint32_t i = 0; i < l.files.n; i++)   /* names do not count */
            h = scene_file_hash_more(h, l.files.files[i].data, l.files.files[i].size);
        info->hash = h;
        sm_vec3_copy(c.lo, info->bounds_min);
        sm_vec3_copy(c.hi, info->bounds_max);
        info->scale = o->scale;
        file_not_rendered(&l, o->phong, info);
        const struct aiCamera *cam = chosen_camera(l.ai, o->camera);
        if (cam)
            snprintf(info->view, sizeof info->view, "the file's camera '%.60s'", cam->mName.data);
        else
            snprintf(info->view, sizeof info->view, "%s",
                     file_camera_is(o->camera, "orbit") ? "an orbit about the bounds"
                                                        : "the bounds framed from above and "
                                                          "to the side");
    }
    if (ok && files)
        ok = file_loaded_list(&l, files, err, errlen);
    file_loaded_free(&l);
    return ok;
}

// >>build

typedef struct build_nodes {
    scene_builder *b;
    const struct aiScene *ai;
    const uint32_t *mesh_index;    /* file mesh -> scene mesh */
    const uint32_t *mesh_mirror;   /* file mesh -> its mirrored copy, made on demand */
    uint32_t *mirror;
    const bool *moves;             /* per node in walk's order: animated (file_anim_load) */
    uint32_t node;                 /* the nodes walked so far */
} build_nodes;

/* ok, after add_mesh allocated m's arrays; else m freed and the failure said. */
static bool mesh_allocated(scene_builder *b, const char *path, const struct aiMesh *am, mesh *m,
                           bool ok)
{
    if (!ok) {
        mesh_free(m);
        sb_fail(b, "%s: out of memory for a mesh of %u vertices", path, am->mNumVertices);
    }
    return ok;
}

/* A mesh of the file as a scene mesh: uv v flipped (assimp gives GL's bottom-up v; ours
 * is the image's first row at v = 0), tangents computed. Index or -1. */
/* uvt: the material's texture transform baked into the mesh's uv (an affine map commutes
 * with interpolation, and tangents follow the transformed uv), or NULL. */
static int add_mesh(scene_builder *b, const char *path, const struct aiMesh *am,
                    const float (*uvt)[3])
{
    scene *s = b->s;
    if (!sb_reserve(b, (void **)&s->meshes, &b->cap_meshes, s->nmeshes, 1, sizeof *s->meshes,
                    "meshes"))
        return -1;
    mesh *m = &s->meshes[s->nmeshes];
    memset(m, 0, sizeof *m);
    m->vertices = calloc(am->mNumVertices, sizeof *m->vertices);
    m->indices = malloc((size_t)am->mNumFaces * 3 * sizeof *m->indices);
    if (!mesh_allocated(b, path, am, m, m->vertices && m->indices))
        return -1;
    m->nvertices = am->mNumVertices;
    m->nindices = am->mNumFaces * 3;
    if (am->mTextureCoords[1]) {   /* TEXCOORD_1, as the first set: v flipped, the
                                    * material's transform, not finite as 0 */
        m->uv2 = malloc(am->mNumVertices * sizeof *m->uv2);
        if (!mesh_allocated(b, path, am, m, m->uv2 != NULL))
            return -1;
        for (unsigned v = 0; v < am->mNumVertices; v++) {
            float u = am->mTextureCoords[1][v].x, w = 1.0f - am->mTextureCoords[1][v].y;
            if (uvt) {
                float tu = uvt[0][0] * u + uvt[0][1] * w + uvt[0][2];
                w = uvt[1][0] * u + uvt[1][1] * w + uvt[1][2];
                u = tu;
            }
            m->uv2[v][0] = isfinite(u) && isfinite(w) ? u : 0.0f;
            m->uv2[v][1] = isfinite(u) && isfinite(w) ? w : 0.0f;
        }
    }
    if (am->mColors[0]) {   /* COLOR_0: RGBA8, a channel that is not finite as 1 */
        m->colors = malloc(am->mNumVertices * sizeof *m->colors);
        if (!mesh_allocated(b, path, am, m, m->colors != NULL))
            return -1;
        for (unsigned v = 0; v < am->mNumVertices; v++) {
            const struct aiColor4D *c = &am->mColors[0][v];
            const float ch[4] = {c->r, c->g, c->b, c->a};
            uint32_t packed = 0;
            for (int k = 0; k < 4; k++) {
                float x = isfinite(ch[k]) ? sm_clamp(ch[k], 0.0f, 1.0f) : 1.0f;
                packed |= (uint32_t)lrintf(x * 255.0f) << (8 * k);
            }
            m->colors[v] = packed;
        }
    }
    for (unsigned v = 0; v < am->mNumVertices; v++) {
        mesh_vertex *mv = &m->vertices[v];
        mv->position[0] = am->mVertices[v].x;
        mv->position[1] = am->mVertices[v].y;
        mv->position[2] = am->mVertices[v].z;
        sm_vec3 n = {0.0f, 1.0f, 0.0f};
        if (am->mNormals && file_finite3(&am->mNormals[v])) {
            sm_vec3_make(am->mNormals[v].x, am->mNormals[v].y, am->mNormals[v].z, n);
            if (sm_vec3_norm(n) > 0.0f)
                sm_vec3_normalize(n);
            else
                sm_vec3_make(0.0f, 1.0f, 0.0f, n);
        }
        sm_vec3_copy(n, mv->normal);
        if (am->mTextureCoords[0]) {
            mv->uv[0] = am->mTextureCoords[0][v].x;
            mv->uv[1] = 1.0f - am->mTextureCoords[0][v].y;
            if (uvt) {
                float u = mv->uv[0], w = mv->uv[1];
                mv->uv[0] = uvt[0][0] * u + uvt[0][1] * w + uvt[0][2];
                mv->uv[1] = uvt[1][0] * u + uvt[1][1] * w + uvt[1][2];
            }
            if (!isfinite(mv->uv[0]) || !isfinite(mv->uv[1]))
                mv->uv[0] = mv->uv[1] = 0.0f;
        }
    }
    for (unsigned f = 0; f < am->mNumFaces; f++)
        for (unsigned k = 0; k < 3; k++)
            m->indices[3 * f + k] = am->mFaces[f].mIndices[k];
    if (!mesh_compute_tangents(m)) {
        mesh_free(m);
        sb_fail(b, "%s: out of memory computing tangents", path);
        return -1;
    }
    mesh_compute_bounds(m);
    return (int)s->nmeshes++;
}

static void object_fn(const struct aiNode *n, const sm_mat4 world, void *user)
{
    build_nodes *bn = user;
    scene_builder *b = bn->b;
    uint32_t node = bn->node++;
    for (unsigned i = 0; i < n->mNumMeshes && !b->failed; i++) {
        unsigned fm = n->mMeshes[i];
        const struct aiMesh *am = bn->ai->mMeshes[fm];
        uint32_t me = bn->mesh_index[fm];
        sm_mat4 t;
        sm_mat4_copy(world, t);
        if (b->s->meshes[me].joints) {
            /* a skin: its joints place it, not its node (glTF); scene_anim.h */
            scene_object *o = sb_object(b, (int)me, am->mMaterialIndex, 0.0f, 0.0f, 0.0f, 1.0f);
            sm_mat4_identity(o->transform);
            continue;
        }
        if (sm_mat4_det(world) < 0.0f) {
            /* a mirroring node: renderers cull back faces by winding, so bake the mirror
             * into a copy of the mesh (mesh_transform flips its winding) */
            if (bn->mirror[fm] == UINT32_MAX) {
                scene *s = b->s;
                if (!sb_reserve(b, (void **)&s->meshes, &b->cap_meshes, s->nmeshes, 1,
                                sizeof *s->meshes, "meshes") ||
                    !mesh_append(&s->meshes[s->nmeshes], &s->meshes[me], NULL, b->err,
                                 b->errlen)) {
                    b->failed = true;
                    return;
                }
                sm_mat4 flip;
                sm_mat4_identity(flip);
                flip[0][0] = -1.0f;
                if (!mesh_transform(&s->meshes[s->nmeshes], flip, b->err, b->errlen)) {
                    b->failed = true;
                    return;
                }
                bn->mirror[fm] = s->nmeshes++;
            }
            me = bn->mirror[fm];
            sm_mat4 flip;
            sm_mat4_identity(flip);
            flip[0][0] = -1.0f;
            sm_mat4_mul(world, flip, t);
        }
        scene_object *o = sb_object(b, (int)me, am->mMaterialIndex, 0.0f, 0.0f, 0.0f, 1.0f);
        sm_mat4_copy(t, o->transform);
        if (bn->moves && bn->moves[node]) {   /* scene_update poses it (scene_anim.h) */
            o->anim_node = node + 1;
            o->anim_mirror = me == bn->mirror[fm];
        }
    }
}

/* The light of a KHR_lights_punctual (or any assimp) light, in world space; range: the
 * file's (KHR_lights_punctual range), or NAN for none; scale: root_transform's, which
 * changes the file's units and not its picture: the range is a length, and an
 * inverse-square light keeps its brightness at the scaled distance with its intensity
 * times scale^2. */
static void add_light(scene_builder *b, const struct aiLight *al, const sm_mat4 world,
                      float file_range, float scale)
{
    sm_vec3 p = {al->mPosition.x, al->mPosition.y, al->mPosition.z}, wp;
    sm_vec3 d = {al->mDirection.x, al->mDirection.y, al->mDirection.z}, wd;
    sm_mat4_mulv3(world, p, 1.0f, wp);
    sm_mat4_mulv3(world, d, 0.0f, wd);
    if (sm_vec3_norm(wd) > 0.0f)
        sm_vec3_normalize(wd);
    else
        sm_vec3_make(0.0f, 0.0f, -1.0f, wd);
    sm_vec3 color = {al->mColorDiffuse.r, al->mColorDiffuse.g, al->mColorDiffuse.b};
    if (al->mType != aiLightSource_DIRECTIONAL)
        sm_vec3_scale(color, scale * scale, color);
    /* glTF lights are inverse-square, cut off at their range; a light without one
     * reaches where 1 / d^2 falls to 1/256 of its brightest channel (a light volume
     * needs a range) */
    float peak = fmaxf(color[0], fmaxf(color[1], color[2]));
    float range = isfinite(file_range) && file_range > 0.0f
                      ? file_range * scale : sqrtf(fmaxf(peak, 1e-6f) * 256.0f);
    scene_light *l;
    switch (al->mType) {
    case aiLightSource_DIRECTIONAL:
        l = sb_directional(b, wd, color, false);
        return;
    case aiLightSource_SPOT: {
        sm_vec3 at;
        sm_vec3_add(wp, wd, at);
        l = sb_spot(b, wp, at, sm_rad2deg(al->mAngleOuterCone), 1.0f, range, color, false);
        l->spot_angle = al->mAngleOuterCone;   /* exactly the file's, not via degrees */
        break;
    }
    default:
        l = sb_point(b, wp[0], wp[1], wp[2], range, color[0], color[1], color[2]);
        break;
    }
    l->attenuation = ATTENUATION_INVERSE_SQUARE;
}

/* The nearest and farthest view depths (along the view direction from the eye) of the
 * scene's bounds: the box lo..hi (bind pose, skins at time 0) and, for an animated file,
 * every object's world sphere at ANIM_SAMPLES poses over one loop of the animation (the
 * code keeps no bounds over the animation; the fit's margin covers the poses between). */
static void view_depths(scene *s, const sm_vec3 lo, const sm_vec3 hi, const sm_vec3 eye,
                        const sm_vec3 target, float depth[2])
{
    enum { ANIM_SAMPLES = 32 };
    sm_vec3 dir, d;
    sm_vec3_sub(target, eye, dir);
    sm_vec3_normalize(dir);
    depth[0] = INFINITY;
    depth[1] = -INFINITY;
    for (int k = 0; k < 8; k++) {
        sm_vec3 c = {(k & 1) ? hi[0] : lo[0], (k & 2) ? hi[1] : lo[1], (k & 4) ? hi[2] : lo[2]};
        sm_vec3_sub(c, eye, d);
        float z = sm_vec3_dot(d, dir);
        depth[0] = fminf(depth[0], z);
        depth[1] = fmaxf(depth[1], z);
    }
    if (!s->anim)
        return;
    for (int i = 0; i < ANIM_SAMPLES; i++) {
        scene_update(s, s->anim->duration * i / ANIM_SAMPLES);
        for (uint32_t j = 0; j < s->nobjects; j++) {
            const float *bs = s->objects[j].bsphere;
            sm_vec3 c = {bs[0], bs[1], bs[2]};
            sm_vec3_sub(c, eye, d);
            float z = sm_vec3_dot(d, dir);
            depth[0] = fminf(depth[0], z - bs[3]);
            depth[1] = fmaxf(depth[1], z + bs[3]);
        }
    }
}

/* The camera's node pose and lens, held for the whole run; its planes fitted to the
 * scene in front of it (scene_fit_planes: the file's where they hold the scene, a
 * far/near ratio clustered and 24-bit depth can take). */
static void use_file_camera(scene_builder *b, const scene_file_options *o,
                            const struct aiScene *ai, const struct aiCamera *cam,
                            const sm_mat4 root, const sm_vec3 lo, const sm_vec3 hi, float size)
{
    find_node f = {cam->mName.data, false, {{0}}, NULL};
    walk(ai->mRootNode, root, find_fn, &f, 0);
    if (!f.found)
        sm_mat4_copy(root, f.world);
    bool gltf = file_is_gltf(o->path);
    /* glTF: the camera sits at its node's origin looking down -Z (assimp also copies the
     * node's translation into mPosition, which would count it twice) */
    sm_vec3 p = {cam->mPosition.x, cam->mPosition.y, cam->mPosition.z};
    if (gltf)
        sm_vec3_make(0.0f, 0.0f, 0.0f, p);
    sm_vec3 at = {p[0] + cam->mLookAt.x, p[1] + cam->mLookAt.y, p[2] + cam->mLookAt.z};
    float eye[1][3], target[1][3];
    sm_mat4_mulv3(f.world, p, 1.0f, eye[0]);
    sm_mat4_mulv3(f.world, at, 1.0f, target[0]);
    sb_set_keys(b, 1, (const float (*)[3])eye, (const float (*)[3])target, 60.0f);
    /* assimp documents mHorizontalFOV as half the horizontal angle; its glTF importer
     * stores yfov x aspect instead */
    float aspect = cam->mAspect > 0.0f ? cam->mAspect : 1.0f;
    float fovy = gltf ? cam->mHorizontalFOV / aspect
                      : 2.0f * atanf(tanf(cam->mHorizontalFOV) / aspect);
    /* the file's planes are in its units; size is scaled already */
    scene *s = b->s;
    s->file_camera = true;
    s->file_planes[0] = fmaxf(cam->mClipPlaneNear * o->scale, 0.0f);
    s->file_planes[1] = fmaxf(cam->mClipPlaneFar * o->scale, 0.0f);
    float depth[2], planes[2];
    view_depths(s, lo, hi, eye[0], target[0], depth);
    scene_fit_planes(s->file_planes[0], s->file_planes[1], depth[0], depth[1],
                     1.0f / tanf(0.5f * fovy), size, planes);
    sb_set_projection(b, sm_rad2deg(fovy), planes[0], planes[1]);
    s->fovy = fovy;   /* exactly, not through degrees */
}

/* camera auto without a perspective camera: the side to look from. Eight directions
 * from the centre, 30 degrees above or below the horizon, halfway between the axes
 * (above first, glTF's front +Z first); each scores the area of the front faces it
 * sees (sum of max(0, n.d) over the triangles, n their world-space area normals: a
 * mirrored node's copy has its winding flipped already). The first within 1% of the
 * best wins: a closed model keeps the first, a flat or single-sided one is seen from
 * the side its faces face, not edge-on or from behind. */
static void facing_side(const scene *s, sm_vec3 dir)
{
    enum { SIDES = 8 };
    sm_vec3 d[SIDES];
    double score[SIDES] = {0};
    static const float azimuth[4] = {45.0f, 315.0f, 135.0f, 225.0f};
    for (int k = 0; k < SIDES; k++) {
        float el = sm_deg2rad(k < 4 ? 30.0f : -30.0f), az = sm_deg2rad(azimuth[k % 4]);
        sm_vec3_make(cosf(el) * sinf(az), sinf(el), cosf(el) * cosf(az), d[k]);
    }
    for (uint32_t i = 0; i < s->nobjects; i++)
        for (uint32_t t = 0; t < s->meshes[s->objects[i].mesh].nindices / 3; t++) {
            sm_vec3 w[3], n;
            scene_triangle_at_0(s, &s->objects[i], t, w, n);
            for (int k = 0; k < SIDES; k++)
                score[k] += fmax(0.0, (double)sm_vec3_dot(n, d[k]));
        }
    int best = 0;
    for (int k = 1; k < SIDES; k++)
        best = score[k] > score[best] ? k : best;
    int pick = 0;
    while (score[pick] < 0.99 * score[best])
        pick++;
    sm_vec3_copy(d[pick], dir);
}

/* camera auto without a perspective camera in the file: a fixed view of the bounding
 * sphere (centre, radius) from facing_side's direction, at the distance where the
 * sphere fills the vertical field of view (at an aspect below 1 its sides may be cut).
 * Unlike an orbit, it never turns to a flat model's edge or a single-sided one's back. */
static void frame_bounds(scene_builder *b, const sm_vec3 centre, float radius)
{
    sm_vec3 dir;
    facing_side(b->s, dir);
    float dist = radius / sinf(0.5f * b->s->fovy);
    float eye[1][3], target[1][3] = {{centre[0], centre[1], centre[2]}};
    for (int k = 0; k < 3; k++)
        eye[0][k] = centre[k] + dist * dir[k];
    sb_set_keys(b, 1, (const float (*)[3])eye, (const float (*)[3])target, 60.0f);
}

bool scene_build_file(scene_builder *b, const void *arg)
{
    const scene_file_options *o = arg;
    loaded l;
    if (!file_load(o, &l, b->err, b->errlen)) {
        b->failed = true;
        return false;
    }
    scene_file_options applied = applied_options(o, &l);
    o = &applied;
    const struct aiScene *ai = l.ai;
    count_nodes c;
    counts_of(o, &l, &c);
    uint32_t *mesh_index = calloc(ai->mNumMeshes, sizeof *mesh_index);
    uint32_t *mirror = malloc(ai->mNumMeshes * sizeof *mirror);
    int *map = malloc((l.nimages ? l.nimages : 1) * sizeof *map);
    if (!mesh_index || !mirror || !map) {
        sb_fail(b, "%s: out of memory", o->path);
        goto out;
    }
    for (uint32_t i = 0; i < l.nimages; i++)
        map[i] = -1;
    for (unsigned i = 0; i < ai->mNumMeshes; i++)
        mirror[i] = UINT32_MAX;
    if (!sb_begin(b, c.objects))
        goto out;
    for (unsigned i = 0; i < ai->mNumMaterials && !b->failed; i++)
        file_add_material(b, &l, i, map);
    for (unsigned i = 0; i < ai->mNumMeshes && !b->failed; i++) {
        float uvt[2][3];
        const struct aiMesh *am = ai->mMeshes[i];
        bool transformed = file_uv_transform(ai->mMaterials[am->mMaterialIndex], uvt) != 0;
        int m = add_mesh(b, o->path, am, transformed ? (const float (*)[3])uvt : NULL);
        mesh_index[i] = m < 0 ? 0 : (uint32_t)m;
    }
    sm_mat4 root;
    root_transform(o, root);
    bool *moves = NULL;
    if (!b->failed && !file_anim_load(b, o->path, ai, mesh_index, root, &moves))
        goto out;
    build_nodes bn = {b, ai, mesh_index, NULL, mirror, moves, 0};
    if (!b->failed)
        walk(ai->mRootNode, root, object_fn, &bn, 0);
    free(moves);
    for (unsigned i = 0; i < ai->mNumLights && !b->failed; i++) {
        find_node f = {ai->mLights[i]->mName.data, false, {{0}}, NULL};
        walk(ai->mRootNode, root, find_fn, &f, 0);
        if (!f.found)
            sm_mat4_copy(root, f.world);
        float range = NAN;
        node_float(f.node, "PBR_LightRange", &range);
        add_light(b, ai->mLights[i], f.world, range, o->scale);
    }
    if (b->failed)
        goto out;

    /* bounds, camera and projection from the scene's extent */
    scene *s = b->s;
    file_skin_bounds(s, c.lo, c.hi);
    sm_vec3 centre, ext;
    for (int k = 0; k < 3; k++) {
        centre[k] = 0.5f * (c.lo[k] + c.hi[k]);
        ext[k] = c.hi[k] - c.lo[k];
    }
    float size = fmaxf(sm_vec3_norm(ext), 1e-3f);
    /* lights around: room on every side of a closed model for lights to stand in, an
     * eighth of the diagonal (fit: 2.5 units, a quarter of lights.radius 10, where
     * surface placement puts them) */
    float grow = o->lights_around ? 0.125f * size : 0.0f;
    sb_set_bounds(b, c.lo[0] - grow, c.lo[1] - grow, c.lo[2] - grow, c.hi[0] + grow,
                  c.hi[1] + grow, c.hi[2] + grow);
    s->lights_outside = o->lights_around;
    sm_vec3_make(0.1f, 0.1f, 0.1f, s->ambient);
    sb_set_projection(b, 60.0f, size * 1e-3f, size * 10.0f);
    const struct aiCamera *cam = chosen_camera(ai, o->camera);
    if (cam)
        use_file_camera(b, o, ai, cam, root, c.lo, c.hi, size);
    else if (file_camera_is(o->camera, "orbit"))
        sb_set_orbit(b, centre[0], centre[1], centre[2], size, 0.35f * size, 60.0f);
    else
        frame_bounds(b, centre, 0.5f * size);
out:
    free(mesh_index);
    free(mirror);
    free(map);
    file_loaded_free(&l);
    return !b->failed;
}
