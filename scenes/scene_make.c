/* Scene construction and posing. Each catalog scene is built by its builder (the
 * registry below; scenes/builtin/scene_*.c); the run's lights are then placed from the manifest's
 * light parameters; scene_update poses everything from schedule time alone.
 *
 * Sections: >>registry >>build >>probe here (with scene_destroy and scene_make_opaque);
 * >>placement scene_place.c; >>posing >>camera-overrides scene_pose.c; >>coverage
 * scene_coverage.c. */
#include "scenes/scene.h"

#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "scenes/scene_anim.h"
#include "scenes/scene_build.h"
#include "scenes/scene_internal.h"

// >>registry

/* The scene sources: the catalog (catalog.c's table, each entry with its builder) and
 * files (file_assimp.c); each builder takes its source's argument. */
typedef struct source_plan {
    char name[64];
    scene_build_fn build;
    const void *arg;
    int fault;
} source_plan;

static bool plan_source(const scene_source *src, source_plan *p, char *err, size_t errlen)
{
    memset(p, 0, sizeof *p);
    if (src->file) {
        const char *path = src->file->path ? src->file->path : "";
        const char *base = strrchr(path, '/');
        snprintf(p->name, sizeof p->name, "%s", base ? base + 1 : path);
        p->build = scene_build_file;
        p->arg = src->file;
        return true;
    }
    const char *name = src->name ? src->name : "";
    const scene_catalog_entry *e = scene_catalog_find(name);
    if (!e) {
        snprintf(err, errlen, "unknown scene '%s'", name);
        return false;
    }
    snprintf(p->name, sizeof p->name, "%s", name);
    p->build = scene_catalog_builder(e);
    p->fault = scene_catalog_fault(e);
    if (!p->build) {
        snprintf(err, errlen, "bug: scene '%s' is in the catalog but has no builder", name);
        return false;
    }
    return true;
}

// >>build

scene *scene_build(const char *name, const light_params *lp, int width, int height,
                   char *err, size_t errlen)
{
    scene_source src = {.name = name, .file = NULL};
    return scene_build_source(&src, lp, width, height, err, errlen);
}

/* The scene from its builder, without the run's lights (nlights_total 0), at t = 0; the
 * builder's authored lights are left in *bout's authored (the caller frees *bout and its
 * authored). NULL with the message on failure. */
static scene *build_unlit(const scene_source *src, int width, int height, scene_builder **bout,
                          char *err, size_t errlen)
{
    *bout = NULL;
    source_plan plan;
    if (!plan_source(src, &plan, err, errlen))
        return NULL;
    const char *name = plan.name;
    if (width <= 0 || height <= 0) {
        snprintf(err, errlen, "bug: scene '%s' built for a %dx%d target", name, width, height);
        return NULL;
    }
    scene *s = calloc(1, sizeof *s);
    scene_builder *b = calloc(1, sizeof *b);
    if (!s || !b) {
        free(b);
        free(s);
        snprintf(err, errlen, "out of memory building scene '%s'", name);
        return NULL;
    }
    snprintf(s->name, sizeof s->name, "%s", name);
    s->from_file = src->file != NULL;
    s->width = width;
    s->height = height;
    s->hold = NAN;
    char why[256] = "";
    b->s = s;
    b->err = why;
    b->errlen = sizeof why;
    if (!plan.build(b, plan.arg) || b->failed) {
        snprintf(err, errlen, "scene '%s': %s", name, why);
        free(b->authored);
        free(b);
        scene_destroy(s);
        return NULL;
    }
    s->fault = plan.fault;
    *bout = b;
    return s;
}

scene *scene_build_source(const scene_source *src, const light_params *lp, int width,
                          int height, char *err, size_t errlen)
{
    return scene_build_cache(src, NULL, NULL, lp, width, height, err, errlen);
}

scene *scene_build_cache(const scene_source *src, scene_cached *from, scene_cache_store *to,
                         const light_params *lp, int width, int height, char *err,
                         size_t errlen)
{
    scene_builder *b;
    scene *s;
    if (from) {
        source_plan plan;
        if (!plan_source(src, &plan, err, errlen)) {
            scene_cached_free(from);
            return NULL;
        }
        if (!(b = scene_cached_take(from, err, errlen)))
            return NULL;
        s = b->s;
        snprintf(s->name, sizeof s->name, "%s", plan.name);   /* the name is not cached */
        s->fault = plan.fault;
        s->width = width;
        s->height = height;
    } else {
        if (!(s = build_unlit(src, width, height, &b, err, errlen)))
            return NULL;
        if (to && to->path)
            scene_cache_write(to, b);
    }
    bool ok = scene_place_lights(s, b->authored, b->nauthored, b->ncoverage, lp, false, err,
                                 errlen);
    free(b->authored);
    free(b);
    if (!ok) {
        scene_destroy(s);
        return NULL;
    }
    scene_update(s, 0.0);
    return s;
}

// >>probe

struct scene_probe {
    scene *s;                  /* built without lights, at t = 0 */
    uint32_t nauthored, ncoverage;
};

scene_probe *scene_probe_build(const scene_source *src, char *err, size_t errlen)
{
    scene_probe *p = calloc(1, sizeof *p);
    if (!p) {
        snprintf(err, errlen, "out of memory building scene '%s'",
                 src->file ? (src->file->path ? src->file->path : "") : src->name);
        return NULL;
    }
    scene_builder *b;
    p->s = build_unlit(src, 1, 1, &b, err, errlen);
    if (!p->s) {
        free(p);
        return NULL;
    }
    p->nauthored = b->nauthored;
    p->ncoverage = b->ncoverage;
    free(b->authored);
    free(b);
    scene_update(p->s, 0.0);
    return p;
}

bool scene_probe_check(const scene_probe *p, const light_params *lp, const camera_params *cp,
                       int width, int height, scene_view *view, char *err, size_t errlen)
{
    if (width <= 0 || height <= 0) {
        snprintf(err, errlen, "bug: scene '%s' built for a %dx%d target", p->s->name, width,
                 height);
        return false;
    }
    /* a copy of the probe's values: scene_place_lights in check mode and scene_set_camera
     * change only values, and the copy's pointers stay the probe's */
    scene t = *p->s;
    t.width = width;
    t.height = height;
    t.lights = NULL;
    if (!scene_place_lights(&t, NULL, p->nauthored, p->ncoverage, lp, true, err, errlen))
        return false;
    t.count = lp->count;
    if (cp && !scene_set_camera(&t, cp, err, errlen))
        return false;
    if (view)
        *view = (scene_view){t.proj[1][1], t.cam.znear, t.cam.zfar};
    return true;
}

void scene_probe_destroy(scene_probe *p)
{
    if (!p)
        return;
    scene_destroy(p->s);
    free(p);
}

void scene_destroy(scene *s)
{
    if (!s)
        return;
    for (uint32_t i = 0; s->meshes && i < s->nmeshes; i++)
        mesh_free(&s->meshes[i]);
    for (uint32_t i = 0; s->textures && i < s->ntextures; i++)
        texture_free(&s->textures[i]);
    free(s->meshes);
    free(s->textures);
    free(s->materials);
    free(s->objects);
    free(s->lights);
    scene_anim_free(s->anim);
    free(s);
}

uint32_t scene_make_opaque(scene *s)
{
    uint32_t n = 0;
    for (uint32_t i = 0; i < s->nmaterials; i++) {
        scene_material *m = &s->materials[i];
        if (!scene_material_translucent(m))
            continue;
        m->alpha = MATERIAL_OPAQUE;
        m->opacity = 1.0f;
        n++;
    }
    return n;
}

bool scene_set_shading(scene *s, shading_model m)
{
    if (m == s->shading)
        return true;
    if (m != SHADING_PBR)
        return false;
    for (uint32_t i = 0; i < s->nmaterials; i++) {
        scene_material *mt = &s->materials[i];
        mt->specular = mt->metallic;
        mt->shininess = mt->roughness;
        mt->gloss_map = mt->orm_map;
    }
    s->shading = SHADING_PBR;
    return true;
}

shading_model scene_own_shading(const scene *s)
{
    return s->from_file ? SHADING_PBR : SHADING_PHONG;
}

void scene_set_environment(scene *s, scene_environment e, float intensity)
{
    s->environment = e;
    s->environment_intensity = e == ENVIRONMENT_NONE ? 0.0f : intensity;
    if (e != ENVIRONMENT_NONE)
        s->sky = true;   /* the sky pass draws the environment (sky.frag's ENVIRONMENT) */
}
