/* The deferred renderer (seed 000 section 4.5; seeds 001-004 for the G-buffer
 * layouts and the light volumes).
 *
 * Every frame, in passes named as passes.csv names them (a pass the plan skips is
 * not run, and renderer_describe says why):
 *
 *   shadows      (some spot or directional light casts shadows, shadows not off;
 *                renderers/shadow.h) per visible shadow-casting light, its shadow map:
 *                one depth-only draw per object of its shadow-casting set (frontend.h)
 *   gbuffer      the G-buffer framebuffer (the layout's attachments + the shared
 *                depth-stencil target) cleared (colour 0, depth 1, stencil 0 or, for
 *                stencil-two-pass, 1), then one draw per visible object (frontend order:
 *                state buckets), mesh.vert + gbuffer.frag in the material's map variant,
 *                depth LESS with writes, back faces culled (as the forward renderers)
 *   ambient      full screen: ambient x diffuse + emissive written over the light target
 *                (no blend; it starts the accumulation)
 *   directional  full screen per visible directional light, blend ONE + ONE; a light
 *                with a shadow map is shaded by the SHADOWS variant (seed 000 4.5.6:
 *                the G-buffer position to the light's map, lighting.inc + shadow.inc),
 *                and so are spots; the variant is built only for a light type some
 *                light of which casts shadows
 *   point, spot  per visible light of that type, by renderer_options.light_volumes:
 *     fullscreen        a full-screen pass (the light's range and cone do the culling)
 *     volume            the volume's back faces (cull FRONT), depth test GREATER, no
 *                       writes: the pixels whose surface is in front of the volume's back
 *     stencil           (seed 003) mark: one draw, both faces (cull NONE), colour writes
 *                       off, depth LEQUAL without writes, two-sided stencil: back faces
 *                       increment (wrap) and front faces decrement on depth fail; shade:
 *                       back faces, depth test off, stencil NOTEQUAL 0, ZERO on pass (which
 *                       resets the stencil for the next light)
 *     stencil-two-pass  (seed 000) the stencil cleared to 1 with the G-buffer; mark front
 *                       faces (increment on depth fail), then back faces (decrement on
 *                       depth fail); shade back faces where the stencil is 0, INCR on pass
 *                       (which resets it to 1)
 *     hull              (seed 000 4.5.8's unoptimised baseline) the volume's back faces (cull
 *                       FRONT), no depth test, no stencil: every pixel the hull covers is
 *                       shaded, whatever surface lies there
 *     scissor           a full-screen pass with the scissor test on, the rectangle
 *                       deferred_scissor_rect (the projection of the box around the light's
 *                       volume; Policarpo & Fonseca as seed 000 4.5.8 cites them); passes.csv's
 *                       scissor_pixels is the sum of the pass's rectangles. GL_SCISSOR_TEST is
 *                       not state the cache keeps: it is switched off again after the pass
 *   compose      (separate_specular only, seed 001) the specular target added into the
 *                diffuse one, full screen
 *   fog          (fog.density > 0; seed 000 4.5.12) full screen into the light target
 *                alone (no depth attachment): each pixel's depth unprojected to view z,
 *                and deferred_fog.frag blends exp(-density z) of the light with the fog
 *                colour; pixels at depth 1 unchanged. Skipped (no program) when off
 *   sky          (the scene has a sky) scene_gpu_draw_sky into the light target's
 *                untouched depth (z = w, depth LEQUAL): last, as seed 000 4.5.11
 *   translucent  (the scene has MATERIAL_BLEND objects; seed 001 19.8.1: translucent
 *                geometry drawn by a forward renderer after the deferred one) the
 *                frontend's translucent objects, back to front, shaded by the forward
 *                single-pass program with every visible light and blended over the light
 *                target, testing (not writing) the G-buffer pass's depth
 *                (renderers/translucent.h); one draw each. Skipped, no program, otherwise.
 *                tiled-deferred and clustered deferred with point or spot lights: each
 *                fragment loops its tile's translucent list instead, which the tiled
 *                dispatch builds after the tile's opaque list (TLISTS, tile_cull.inc: near
 *                plane to the tile's max depth; same index buffer and overflow rule, heads
 *                after the opaque cells); the plan's "translucent-lists" says whether
 *   edge-aa      (aa: edge; renderers/edge_aa.h) seed 001 19.5.2's edge blur of the light
 *                target into "hdr.aa", its normals from the G-buffer (gbuffer.inc)
 *   resolve      scene_gpu_resolve: the light target (or "hdr.aa") clamped into the output
 *
 * MSAA (msaa > 1; docs/architecture.md): every G-buffer attachment, the light targets and
 * depth are multisampled. After the G-buffer pass, `edges` (edge_mark.frag, full screen,
 * per pixel) sets stencil EDGE_BIT (0x40) on every sample of a pixel whose samples differ
 * from sample 0 (surface / none, off its tangent plane by > 1 % of the view depth, normal
 * > acos(0.98)); the stencil
 * modes then count in bits 0-5. Every shading draw of ambient, the light passes (every
 * light-volume mode) and compose runs twice, edges first: the per-sample variant
 * (GB_SAMPLE gl_SampleID) where EDGE_BIT is set, the per-pixel one (sample 0) where it is
 * clear (class_begin, class_stencil; the draw counts above double for those passes). Fog
 * runs per sample everywhere. `msaa-resolve` (renderers/base.h) averages the light
 * before resolve. tiled-deferred and clustered deferred shading have no stencil pass: their
 * one dispatch classifies the pixels by the same rule (edge_rule.inc), shades sample 0 of
 * every pixel into all its samples off the edges and, from a per-tile edge list in shared
 * memory, the other samples of the edge pixels (Lauritzen 2010's compute path); the edge
 * pixels are counted into a small storage buffer (BIND_SSBO_EDGES), read back by collect.
 *
 * Sky mask (renderer_options.sky_stencil, deferred.sky_stencil; seed 001 section 19.7.2,
 * "Stencil Masking": the opaque geometry marks, at no extra draw, the pixels that deferred
 * shading will light, and the lighting passes skip the others by the stencil test): the
 * G-buffer draws set stencil bit 7 (SURFACE_BIT) where they pass the depth test (ALWAYS,
 * REPLACE on pass, write mask 0x80), so the pixels no geometry covers, the sky, keep it
 * clear; the full-screen passes (ambient, directional, point and spot in the fullscreen
 * and scissor modes, compose) test EQUAL 0x80 under read mask 0x80 and write nothing,
 * so each of their draws shades exactly the sky's pixel count fewer samples. The
 * stencil and stencil-two-pass modes then count in bits 0-6 (read and write masks
 * 0x7f: increment and decrement wrap within the seven bits, and reset them only), so
 * the mark survives every light. The volume, stencil and stencil-two-pass modes
 * already reject the sky by depth (nothing lies in front of a volume's back face
 * there); hull, seed 000's unoptimised baseline, is left as it is, and so is fog (its
 * framebuffer has no stencil; it leaves depth-1 pixels alone anyway). The ambient pass
 * no longer writes the sky's pixels, so with no sky pass to draw them the light
 * target is cleared to (0, 0, 0, 1) first (the ambient pass's value there); with one,
 * the sky covers exactly the unmarked pixels (depth 1). Not in tiled-deferred or
 * clustered deferred shading: their shading is one compute dispatch, which no stencil
 * test masks, and it already skips pixels without a surface (create refuses the
 * option there).
 *
 * Draw calls per frame (V visible objects, D / P / S visible directional / point / spot
 * lights this frame, frontend_build; [x] = 1 when the pass runs, else 0; C(l) the
 * shadow-casting set of a visible light l that casts shadows, Sh = sum of |C(l)| over
 * them, 0 when the shadows pass does not run):
 *
 *   fullscreen, scissor, volume, hull:
 *                      Sh + V + 1 + D + P + S            + [compose] + [fog] + [sky] + [aa] + 1
 *   stencil:           Sh + V + 1 + D + 2 (P + S)        + [compose] + [fog] + [sky] + [aa] + 1
 *   stencil-two-pass:  Sh + V + 1 + D + 3 (P + S)        + [compose] + [fog] + [sky] + [aa] + 1
 *
 * (shadows Sh, gbuffer V, ambient 1, directional D, point/spot 1 per light (shade), 2
 * (mark + shade) or 3 (front mark + back mark + shade), compose 1, fog 1, sky 1, edge-aa 1,
 * resolve 1; clears are not draws; V counts opaque objects, and the translucent pass adds
 * one draw per visible translucent object.) Without Sh they do not depend on where the camera is; the
 * shadow-casting sets do (frontend.h).
 *
 * Camera inside a volume, near and far planes. The volume passes run with GL_DEPTH_CLAMP
 * on (and it is switched off again after them; it is not state the cache keeps): the
 * near and far planes then clip nothing, and a volume's faces beyond the far plane are
 * drawn at depth 1. Every mode decides on depth FAIL only (the volume's face behind the
 * surface), which makes it exact whatever cuts the volume in front: a front face lost
 * behind the eye, or between the eye and the near plane (there at depth 0), would have
 * passed the test and counted nothing. So the same passes are correct with the camera
 * inside a point or spot volume, with the near plane cutting it (the frontend's
 * eye_inside is not needed: no per-light switch, and draw counts stay as above) and with
 * the far plane cutting it (depth clamp). Pixels that no surface covers keep depth 1,
 * where a clamped back face passes LEQUAL (fails GREATER): they are never lit, and the
 * shaders light nothing where the G-buffer holds no surface anyway (zero normal).
 *
 * G-buffer presets (deferred.h has the slots; an attachment no needed slot uses is not
 * allocated; gloss and shininess are needed when some object's material has specular >
 * 0, emissive when some object's material has an emissive colour > 0):
 *
 *   fat        (seed 000) RGBA16F position.xyz + shininess | RGBA16F normal.xyz +
 *              emissive intensity e (emissive = e x diffuse, as seed 000 modulates the
 *              diffuse colour) | RGBA16F diffuse + gloss
 *   curtis     (seed 003) RGBA16F normal.xyz + linear depth | RGBA16F diffuse + gloss
 *              ("specular") | RGBA16F shininess (the "specular colour" target: specular
 *              here is colourless, its exponent takes the place) | RGBA16F emissive (the
 *              unused fourth, written only by emissive scenes); position = view ray x
 *              depth
 *   compact    (seed 002's 96 bits) RG16F position.xy | R16F position.z | RGBA8 diffuse
 *              + normal.z | RG8 normal.xy (unorm), and beyond seed 002 (which stores no
 *              specular or emissive), when the scene needs them: RG8 gloss + shininess/255,
 *              RGBA8 emissive
 *   spheremap  (seed 004) RG8 normal (Lambert azimuthal) | RGBA16F linear depth + gloss +
 *              shininess | RGBA8 diffuse | RGBA8 emissive (when needed); position = the
 *              pixel's frustum-corner ray x depth
 *   reference  RGBA32F position.xyz + shininess | RGBA32F normal.xyz + gloss | RGBA32F
 *              diffuse | RGBA32F emissive
 *
 * Position from the depth buffer (gbuffer position: depth): the light passes test against
 * the shared depth-stencil target, which is attached to the light framebuffer, so they
 * cannot sample it too: texturing from an image attached to the bound draw framebuffer
 * is undefined in GL 4.5 (section 9.3), write masks off or not (llvmpipe gives the
 * expected texels, a GPU need not). So the G-buffer pass ends, after its draws, with one
 * glCopyImageSubData of the depth-stencil target into "depth.sampled" (the same format;
 * no draw, counted in the G-buffer pass's GPU time), and the light passes sample that.
 * tiled-deferred needs no copy: its one dispatch is the only reader, and the output
 * framebuffer (no texture attached) is bound for it, as forward-plus does for its cull.
 * Shadow maps do not touch it (they have their own depth targets). The state cache's
 * feedback-loop check (state.h) fails any draw or dispatch that samples an attached
 * texture in debug contexts (every test).
 *
 * Targets: the G-buffer attachments ("gbuffer.<slots>"), "light" (the run's HDR format,
 * RGBA16F or RGBA32F, renderers/base.h; with
 * separate_specular "light.diffuse" + "light.specular") and "depth" (depth24-stencil8,
 * shared by the G-buffer and light framebuffers so that volumes test against the scene's
 * depth), and with position from depth (deferred only) "depth.sampled", its copy.
 * gbuffer_bytes counts the G-buffer's colour attachments. */
#include "renderers/deferred.h"

#include "renderers/base.h"

#include "renderers/frontend.h"
#include "renderers/gl/loader.h"
#include "renderers/gl/program.h"
#include "renderers/gl/query.h"
#include "renderers/gl/state.h"
#include "renderers/gl/target.h"
#include "renderers/renderer.h"
#include "renderers/scene_gpu.h"
#include "renderers/shading.h"
#include "renderers/shadow.h"
#include "renderers/translucent.h"
#include "scenes/scene.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

_Static_assert(sizeof(gpu_light) == 80, "gpu_light is 5 vec4s, as lighting.inc's Light");

enum {
    DEFERRED_MAX_PASSES = 14,          /* shadows gbuffer [edges] ambient directional point
                                         spot compose fog sky translucent [msaa-resolve]
                                         edge-aa resolve */
    DEFERRED_VARIANTS = 32,           /* material map bits and the alpha test */
    DEFERRED_LIGHT_TYPES = 3,
};

// >>the renderer

typedef enum pass_id {
    PASS_SHADOWS,                    /* renderers/shadow.h */
    PASS_GBUFFER,
    PASS_AMBIENT,
    PASS_DIRECTIONAL,
    PASS_POINT,
    PASS_SPOT,
    PASS_COMPOSE,
    PASS_SKY,
    PASS_RESOLVE,
    PASS_TILED,                      /* tiled-deferred: ambient and every light, one dispatch */
    PASS_FOG,                        /* fog.density > 0: deferred_fog.frag after the lights */
    PASS_TRANSLUCENT,                /* MATERIAL_BLEND objects, forward, after the sky */
    PASS_EDGES,                      /* msaa > 1: edge_mark.frag sets EDGE_BIT */
    PASS_MSAA,                       /* msaa > 1: renderer_base_msaa_resolve_pass */
    PASS_TLISTS,                     /* not a pass: the tiled pass's translucent lists */
    PASS_COUNT
} pass_id;

static const char *const pass_names[PASS_COUNT] = {
    "shadows", "gbuffer", "ambient", "directional", "point", "spot", "compose", "sky", "resolve",
    "tiled", "fog", "translucent", "edges", "msaa-resolve", "translucent-lists",
};

/* The order describe lists them in (tiled-deferred's "tiled" after the G-buffer). */
static const pass_id describe_order[PASS_COUNT] = {
    PASS_SHADOWS, PASS_GBUFFER, PASS_EDGES, PASS_TILED, PASS_TLISTS, PASS_AMBIENT,
    PASS_DIRECTIONAL, PASS_POINT, PASS_SPOT, PASS_COMPOSE, PASS_FOG, PASS_SKY,
    PASS_TRANSLUCENT, PASS_MSAA, PASS_RESOLVE,
};

/* tiled-deferred's light culling and shading pass (tiled_deferred.comp). */
typedef struct tiled_pass {
    int tile;                        /* pixels per tile side */
    uint32_t slices_y;               /* clustered.shading: deferred: Olsson's S_y; else 0 */
    uint32_t slices;                 /* its depth slices to the far plane (prepare) */
    double slice_ratio;
    uint32_t tiles_x, tiles_y, ntiles;
    uint32_t ncells;                 /* tiles, or tiles x slices */
    bool grid;                       /* the scene has point or spot lights: lists are culled */
    uint32_t ntlists;                /* tiles: translucent lists built too (grid and the scene
                                        has translucent objects); 0: none */
    uint32_t max_lights, capacity;   /* entries of the light and index buffers */
    GLuint program;
    GLuint lights, tiles, indices, stats;
    GLuint edges;                    /* msaa > 1: the dispatch's edge-pixel count */
    uint32_t edge_pixels;            /* msaa > 1: the last frame's, after collect */
    gpu_light *staging;
    uint32_t *readback, *counts;
    bool counted;
    char tile_define[24], tiles_x_define[32], tiles_y_define[32], slices_define[24];
    char slices_y_define[24], tlists_define[24], msaa_define[24];
} tiled_pass;

typedef struct deferred_renderer {
    renderer_base b;                 /* first: name ("deferred", "tiled-deferred",
                                        "clustered"), options, size, caches, queries */
    bool tiled;                      /* tiled-deferred: PASS_TILED instead of the light passes */
    tiled_pass tp;

    /* >>made by prepare */
    bool prepared;                   /* (the scene on the GPU, the frontend and the shadow
                                        maps are the base's: renderer_base_scene) */
    deferred_needs needs;
    deferred_layout layout;
    translucent_pass translucent;    /* MATERIAL_BLEND objects after the sky (translucent.h) */
    gl_target gbuf[DEFERRED_MAX_ATTACHMENTS];
    gl_target specular;              /* separate_specular: light.specular */
    gl_target depth_sampled;         /* position from depth: the G-buffer's depth, copied */
    gl_framebuffer fb_gbuffer, fb_light, fb_compose;
    gl_framebuffer fb_fog;           /* the light target alone (fog reads depth) */
    GLuint fog_program;
    bool unclipped;                  /* full-screen passes draw the unclipped triangle */
    unsigned variants;               /* bit v: some object's material is of map variant v */
    unsigned light_types;            /* bit t: some light of the scene is of type t */
    uint32_t nobjects;
    bool run[PASS_COUNT];
    char reason[PASS_COUNT][96];
    GLuint gbuffer_program[DEFERRED_VARIANTS];
    GLuint ambient_program, compose_program, mark_program;
    GLuint light_program[DEFERRED_LIGHT_TYPES];
    /* msaa > 1: the per-sample variants (edge pixels) and the edge-mark program */
    GLuint ambient_sample_program, compose_sample_program, edge_program;
    GLuint light_sample_program[DEFERRED_LIGHT_TYPES];

    /* >>the last frame, for tests */
    uint64_t mark_draws[DEFERRED_LIGHT_TYPES], shade_draws[DEFERRED_LIGHT_TYPES];
    int64_t scissor_area;            /* light_volumes scissor: this pass's rectangles */
    size_t edges_pass;               /* msaa > 1: 1 + the edge pass's index; 0: none */
    size_t tiled_index;              /* tiled, msaa > 1: 1 + the tiled pass's index; 0: none */
} deferred_renderer;

static unsigned material_variant(const scene_material *m)
{
    return (m->diffuse_map >= 0 ? 1u : 0u) | (m->gloss_map >= 0 ? 2u : 0u) |
           (m->normal_map >= 0 ? 4u : 0u) | (m->emissive_map >= 0 ? 8u : 0u) |
           (m->alpha == MATERIAL_MASK ? 16u : 0u);
}

static void *create(const char *name, bool tiled, bool clustered,
                    const renderer_options *opts, char *err, size_t errlen)
{
    int slices = opts->clustered_slices ? opts->clustered_slices : 24;
    if (clustered && (slices < 1 || slices > 64)) {
        snprintf(err, errlen, "%s: clustered.slices %d: expected 1 to 64", name, slices);
        return NULL;
    }
    if (tiled && opts->sky_stencil) {
        snprintf(err, errlen, "%s: deferred.sky_stencil: the shading is one compute dispatch, "
                 "which no stencil test masks (it skips pixels without a surface itself)",
                 name);
        return NULL;
    }
    if (tiled && opts->separate_specular) {
        snprintf(err, errlen, "%s: deferred.separate_specular: the one light pass adds diffuse "
                 "and specular light together; there is no second target", name);
        return NULL;
    }
    int tile = opts->tile_size ? opts->tile_size : 16;
    if (tiled && tile != 8 && tile != 16 && tile != 32) {
        snprintf(err, errlen, "%s: tiles.size %d: expected 8, 16 or 32", name, tile);
        return NULL;
    }
    deferred_renderer *r = calloc(1, sizeof *r);
    if (!r) {
        snprintf(err, errlen, "%s: out of memory", name);
        return NULL;
    }
    r->tiled = tiled;
    r->tp.tile = tile;
    r->tp.slices_y = clustered ? (uint32_t)slices : 0u;
    /* Options are checked here, before any scene: a bad value never becomes a default. */
    deferred_layout probe;
    if (!deferred_layout_build(opts, (deferred_needs){true, true}, &probe, err, errlen)) {
        free(r);
        return NULL;
    }
    if ((unsigned)opts->light_volumes > (unsigned)LIGHT_VOLUMES_SCISSOR) {
        snprintf(err, errlen, "deferred: unknown light volume mode %d", (int)opts->light_volumes);
        free(r);
        return NULL;
    }
    if (!renderer_base_init(&r->b, name, opts, DEFERRED_MAX_PASSES, err, errlen)) {
        renderer_base_destroy(&r->b);
        free(r);
        return NULL;
    }
    return r;
}

static void *deferred_create(const renderer_options *opts, char *err, size_t errlen)
{
    return create("deferred", false, false, opts, err, errlen);
}

static void *tiled_deferred_create(const renderer_options *opts, char *err, size_t errlen)
{
    return create("tiled-deferred", true, false, opts, err, errlen);
}

void *deferred_clustered_create(const renderer_options *opts, char *err, size_t errlen)
{
    return create("clustered", true, true, opts, err, errlen);
}

static void release_tiled(tiled_pass *tp)
{
    GLuint b[5] = {tp->lights, tp->tiles, tp->indices, tp->stats, tp->edges};
    for (int i = 0; i < 5; i++)
        if (b[i])
            gl.DeleteBuffers(1, &b[i]);
    tp->lights = tp->tiles = tp->indices = tp->stats = tp->edges = 0;
    free(tp->staging);
    free(tp->readback);
    free(tp->counts);
    tp->staging = NULL;
    tp->readback = tp->counts = NULL;
    tp->counted = false;
    tp->program = 0;
}

static void release_prepared(deferred_renderer *r)
{
    translucent_release(&r->translucent);
    release_tiled(&r->tp);
    gl_framebuffer_destroy(&r->fb_gbuffer);
    gl_framebuffer_destroy(&r->fb_light);
    gl_framebuffer_destroy(&r->fb_compose);
    gl_framebuffer_destroy(&r->fb_fog);
    for (int i = 0; i < DEFERRED_MAX_ATTACHMENTS; i++)
        gl_target_destroy(&r->gbuf[i]);
    renderer_base_release_targets(&r->b);
    gl_target_destroy(&r->specular);
    gl_target_destroy(&r->depth_sampled);
    renderer_base_release_scene(&r->b);
    r->prepared = false;
}

static const char *light_type_name(int t)
{
    return t == LIGHT_POINT ? "point" : t == LIGHT_SPOT ? "spot" : "directional";
}

static const char *mode_name(light_volume_mode m)
{
    switch (m) {
    case LIGHT_VOLUMES_STENCIL: return "stencil";
    case LIGHT_VOLUMES_FULLSCREEN: return "fullscreen";
    case LIGHT_VOLUMES_VOLUME: return "volume";
    case LIGHT_VOLUMES_STENCIL_TWO_PASS: return "stencil-two-pass";
    case LIGHT_VOLUMES_HULL: return "hull";
    case LIGHT_VOLUMES_SCISSOR: return "scissor";
    }
    return "unknown";
}

/* Builds one program; the defines are the layout's plus `extra` (NULL-terminated). */
static bool build_program(deferred_renderer *r, const char *display, const char *vertex,
                          const char *fragment, const deferred_layout_defs *ld,
                          const char *const *extra, GLuint *program, char *err, size_t errlen)
{
    gl_program_desc d = {.name = display, .vertex = vertex, .fragment = fragment};
    unsigned n = 0;
    for (unsigned i = 0; extra && extra[i]; i++)
        d.defines[n++] = extra[i];
    for (int i = 0; ld && i < ld->n; i++) {
        if (n >= GLP_MAX_DEFINES) {
            snprintf(err, errlen, "bug: deferred: too many defines for %s", display);
            return false;
        }
        d.defines[n++] = ld->text[i];
    }
    char why[4096] = "";
    if (gl_program_get(r->b.programs, &d, program, why, sizeof why) != GLP_OK) {
        snprintf(err, errlen, "deferred: %s", why);
        return false;
    }
    return true;
}

/* The samples' positions in the pixel (GL_SAMPLE_POSITION of the multisampled framebuffer
 * fbo) into program's vec2[8] at location loc: edge_rule.inc, position from depth. */
static void set_sample_positions(deferred_renderer *r, GLuint fbo, GLuint program, GLint loc)
{
    GLfloat pos[8][2] = {{0.5f, 0.5f}};
    GLint prev = 0;
    gl.GetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &prev);
    gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, fbo);
    for (int i = 0; i < r->b.samples && i < 8; i++)
        gl.GetMultisamplefv(GL_SAMPLE_POSITION, (GLuint)i, pos[i]);
    gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, (GLuint)prev);
    gl.ProgramUniform2fv(program, loc, 8, &pos[0][0]);
}

/* build_program, and with msaa > 1 two variants over the multisampled G-buffer (GB_MSAA):
 * *pixel reads sample 0 (shaded once per pixel, off the edges) and *sample (when not
 * NULL) reads gl_SampleID (per-sample shading, on the edges). Single-sampled: *pixel
 * alone, with exactly build_program's defines. */
static bool build_msaa(deferred_renderer *r, const char *display, const char *vertex,
                       const char *fragment, const deferred_layout_defs *ld,
                       const char *const *extra, GLuint *pixel, GLuint *sample, char *err,
                       size_t errlen)
{
    if (r->b.samples <= 1)
        return build_program(r, display, vertex, fragment, ld, extra, pixel, err, errlen);
    const char *more[12];
    unsigned n = 0;
    for (unsigned i = 0; extra && extra[i] && n < 9; i++)
        more[n++] = extra[i];
    more[n++] = "GB_MSAA";
    more[n] = NULL;
    if (!build_program(r, display, vertex, fragment, ld, more, pixel, err, errlen))
        return false;
    if (!sample)
        return true;
    more[n++] = "GB_SAMPLE gl_SampleID";
    more[n] = NULL;
    return build_program(r, display, vertex, fragment, ld, more, sample, err, errlen);
}

/* The modes whose point and spot lights draw the full-screen triangle. */
static bool full_screen_mode(light_volume_mode m)
{
    return m == LIGHT_VOLUMES_FULLSCREEN || m == LIGHT_VOLUMES_SCISSOR;
}

static void plan(deferred_renderer *r, pass_id p, bool run, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));
static void plan(deferred_renderer *r, pass_id p, bool run, const char *fmt, ...)
{
    r->run[p] = run;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(r->reason[p], sizeof r->reason[p], fmt, ap);
    va_end(ap);
}

static bool make_targets(deferred_renderer *r, char *err, size_t errlen)
{
    char why[512] = "";
    const int w = r->b.width, h = r->b.height;
    gl_framebuffer_desc gdesc = {.name = "gbuffer", .depth_stencil = &r->b.depth};
    bool sep = r->b.opts.separate_specular;
    /* the light accumulation in the run's HDR format, and depth (renderers/base.h) */
    if (!renderer_base_targets(&r->b, sep ? "light.diffuse" : "light", why, sizeof why))
        goto fail;
    for (int i = 0; i < r->layout.nattachments; i++) {
        if (!gl_target_create(&r->gbuf[i], &(gl_target_desc){.name = r->layout.att[i].name,
                                                             .format = r->layout.att[i].format,
                                                             .width = w, .height = h,
                                                             .samples = r->b.samples},
                              why, sizeof why))
            goto fail;
        gdesc.color[i] = &r->gbuf[i];
    }
    if (!r->tiled && r->layout.position == DEFERRED_POSITION_DEPTH_BUFFER &&
        !gl_target_create(&r->depth_sampled,
                          &(gl_target_desc){.name = "depth.sampled",
                                            .format = r->b.depth.format,
                                            .width = w, .height = h,
                                            .samples = r->b.samples},
                          why, sizeof why))
        goto fail;
    if (sep && !renderer_base_hdr_target(&r->b, &r->specular, "light.specular", why, sizeof why))
        goto fail;
    if (!gl_framebuffer_create(&r->fb_gbuffer, &gdesc, why, sizeof why))
        goto fail;
    if (!gl_framebuffer_create(&r->fb_light,
                               &(gl_framebuffer_desc){.name = "light",
                                                      .color = {&r->b.hdr,
                                                                sep ? &r->specular : NULL},
                                                      .depth_stencil = &r->b.depth},
                               why, sizeof why))
        goto fail;
    if (sep && !gl_framebuffer_create(&r->fb_compose,
                                      &(gl_framebuffer_desc){.name = "compose",
                                                             .color = {&r->b.hdr},
                                                             .depth_stencil = &r->b.depth},
                                      why, sizeof why))
        goto fail;
    if (r->run[PASS_FOG] &&
        !gl_framebuffer_create(&r->fb_fog, &(gl_framebuffer_desc){.name = "fog",
                                                                  .color = {&r->b.hdr}},
                               why, sizeof why))
        goto fail;
    return true;
fail:
    snprintf(err, errlen, "deferred: %s", why);
    return false;
}

static bool compile_programs(deferred_renderer *r, char *err, size_t errlen)
{
    deferred_layout_defs ld;
    deferred_layout_defines(&r->layout, &ld);
    const char *fs_vert = "fullscreen.vert";
    const char *unclipped = r->unclipped ? "FULLSCREEN_UNCLIPPED" : NULL;
    const char *sep = r->b.opts.separate_specular ? "SEPARATE_SPECULAR" : NULL;

    for (unsigned v = 0; v < DEFERRED_VARIANTS; v++) {
        if (!(r->variants & (1u << v)))
            continue;
        scene_material m = {.diffuse_map = (v & 1u) ? 0 : -1, .gloss_map = (v & 2u) ? 0 : -1,
                            .normal_map = (v & 4u) ? 0 : -1, .emissive_map = (v & 8u) ? 0 : -1,
                            .alpha = (v & 16u) ? MATERIAL_MASK : MATERIAL_OPAQUE};
        const char *defs[SHADING_MATERIAL_DEFINES + 1] = {NULL};
        shading_material_defines(&m, defs);
        if (!build_program(r, "deferred_gbuffer", "mesh.vert", "gbuffer.frag", &ld, defs,
                           &r->gbuffer_program[v], err, errlen))
            return false;
    }
    if (r->tiled) {
        tiled_pass *tp = &r->tp;
        const char *extra[16] = {tp->tile_define, tp->tiles_x_define};
        int n = 2;
        if (r->b.samples > 1) {   /* the multisampled G-buffer, per tile edge list */
            /* the count the driver gave (known once the targets exist) */
            snprintf(tp->msaa_define, sizeof tp->msaa_define, "MSAA_SAMPLES %d", r->b.samples);
            extra[n++] = "GB_MSAA";
            extra[n++] = tp->msaa_define;
        }
        if (renderer_base_hdr_define(&r->b))   /* the image store's format qualifier */
            extra[n++] = renderer_base_hdr_define(&r->b);
        if (tp->slices) {
            extra[n++] = tp->tiles_y_define;
            extra[n++] = tp->slices_define;
            extra[n++] = tp->slices_y_define;
        }
        if (!tp->grid)
            extra[n++] = "NO_GRID";
        if (tp->ntlists)
            extra[n++] = tp->tlists_define;
        n += (int)shadow_maps_defines(&r->b.shadows, extra + n);   /* any type: one program */
        gl_program_desc d = {.name = tp->slices ? (tp->ntlists ? "clustered_deferred_translucent"
                                                               : "clustered_deferred")
                                                : (tp->ntlists ? "tiled_deferred_translucent"
                                                               : "tiled_deferred"),
                             .compute = "tiled_deferred.comp"};
        unsigned k = 0;
        for (int i = 0; i < n; i++)
            d.defines[k++] = extra[i];
        for (int i = 0; i < ld.n && k < GLP_MAX_DEFINES; i++)
            d.defines[k++] = ld.text[i];
        if (k < (unsigned)n + (unsigned)ld.n) {
            snprintf(err, errlen, "bug: %s: too many defines for tiled_deferred", r->b.name);
            return false;
        }
        char why[4096] = "";
        if (gl_program_get(r->b.programs, &d, &tp->program, why, sizeof why) != GLP_OK) {
            snprintf(err, errlen, "%s: %s", r->b.name, why);
            return false;
        }
        if (r->b.samples > 1)   /* u_sample_pos, after u_light_count */
            set_sample_positions(r, r->fb_gbuffer.fbo, tp->program, DEFERRED_UNIFORM_LIGHT + 1);
        return true;
    }
    {
        const char *extra[3] = {NULL, NULL, NULL};
        int n = 0;
        if (unclipped)
            extra[n++] = unclipped;
        if (sep)
            extra[n++] = sep;
        if (!build_msaa(r, "deferred_ambient", fs_vert, "deferred_ambient.frag", &ld, extra,
                        &r->ambient_program, &r->ambient_sample_program, err, errlen))
            return false;
    }
    if (r->b.samples > 1) {
        const char *extra[2] = {unclipped, NULL};
        if (!build_msaa(r, "deferred_edges", fs_vert, "edge_mark.frag", &ld, extra,
                        &r->edge_program, NULL, err, errlen))
            return false;
    }
    if (r->b.samples > 1 && r->layout.position == DEFERRED_POSITION_DEPTH_BUFFER)
        set_sample_positions(r, r->fb_light.fbo, r->edge_program, DEFERRED_UNIFORM_LIGHT);
    static const pass_id light_pass[DEFERRED_LIGHT_TYPES] = {
        [LIGHT_POINT] = PASS_POINT, [LIGHT_SPOT] = PASS_SPOT,
        [LIGHT_DIRECTIONAL] = PASS_DIRECTIONAL};
    static const char *const type_define[DEFERRED_LIGHT_TYPES] = {
        [LIGHT_POINT] = "DEFERRED_LIGHT_TYPE 0", [LIGHT_SPOT] = "DEFERRED_LIGHT_TYPE 1",
        [LIGHT_DIRECTIONAL] = "DEFERRED_LIGHT_TYPE 2"};
    static const char *const display[DEFERRED_LIGHT_TYPES] = {
        [LIGHT_POINT] = "deferred_point", [LIGHT_SPOT] = "deferred_spot",
        [LIGHT_DIRECTIONAL] = "deferred_directional"};
    /* Shadow variants say so in their display name: the plan cuts a variant's name at
     * 63 characters, before the layout's defines end. */
    static const char *const display_shadowed[DEFERRED_LIGHT_TYPES] = {
        [LIGHT_POINT] = "deferred_point", [LIGHT_SPOT] = "deferred_spot_shadowed",
        [LIGHT_DIRECTIONAL] = "deferred_directional_shadowed"};
    bool volumes = false;
    for (int t = 0; t < DEFERRED_LIGHT_TYPES; t++) {
        if (!r->run[light_pass[t]])
            continue;
        bool full = t == LIGHT_DIRECTIONAL || full_screen_mode(r->b.opts.light_volumes);
        const char *extra[6] = {type_define[t], NULL, NULL, NULL, NULL, NULL};
        int n = 1;
        if (full && unclipped)
            extra[n++] = unclipped;
        if (sep)
            extra[n++] = sep;
        bool shadowed = shadow_maps_for_type(&r->b.shadows, t);
        if (shadowed)
            n += (int)shadow_maps_defines(&r->b.shadows, extra + n);
        if (!build_msaa(r, shadowed ? display_shadowed[t] : display[t],
                        full ? fs_vert : "light_volume.vert", "deferred_light.frag", &ld, extra,
                        &r->light_program[t], &r->light_sample_program[t], err, errlen))
            return false;
        if (!full)
            volumes = true;
    }
    if (volumes && (r->b.opts.light_volumes == LIGHT_VOLUMES_STENCIL ||
                    r->b.opts.light_volumes == LIGHT_VOLUMES_STENCIL_TWO_PASS) &&
        !build_program(r, "deferred_stencil_mark", "light_volume.vert", "stencil_mark.frag", NULL,
                       NULL, &r->mark_program, err, errlen))
        return false;
    if (r->run[PASS_COMPOSE]) {
        const char *extra[2] = {unclipped, NULL};
        if (!build_msaa(r, "deferred_compose", fs_vert, "deferred_compose.frag", NULL, extra,
                        &r->compose_program, &r->compose_sample_program, err, errlen))
            return false;
    }
    return true;
}

/* The fog pass's program (only when it runs): fullscreen.vert + deferred_fog.frag. */
static bool compile_fog(deferred_renderer *r, char *err, size_t errlen)
{
    if (!r->run[PASS_FOG])
        return true;
    /* msaa > 1: per sample everywhere (its one input, depth, differs per sample) */
    const char *extra[5] = {"FOG", NULL, NULL, NULL, NULL};
    int n = 1;
    if (r->unclipped)
        extra[n++] = "FULLSCREEN_UNCLIPPED";
    if (r->b.samples > 1) {
        extra[n++] = "GB_MSAA";
        extra[n++] = "GB_SAMPLE gl_SampleID";
    }
    if (!build_program(r, "deferred_fog", "fullscreen.vert", "deferred_fog.frag", NULL, extra,
                       &r->fog_program, err, errlen))
        return false;
    renderer_base_fog_uniform(&r->b, r->fog_program);
    return true;
}

/* aa: edge (edge_aa.h), its normals from this G-buffer (the layout's defines). */
static bool prepare_edge_aa(deferred_renderer *r, char *err, size_t errlen)
{
    deferred_layout_defs ld;
    deferred_layout_defines(&r->layout, &ld);
    const char *defs[DEFERRED_MAX_LAYOUT_DEFS];
    for (int i = 0; i < ld.n; i++)
        defs[i] = ld.text[i];
    return edge_aa_prepare(&r->b, defs, ld.n, err, errlen);
}

static GLuint make_buffer(size_t bytes)
{
    GLuint b = 0;
    gl.CreateBuffers(1, &b);
    gl.NamedBufferStorage(b, (GLsizeiptr)bytes, NULL, GL_DYNAMIC_STORAGE_BIT);
    return b;
}

/* tiled-deferred's buffers, as forward_plus.c sizes them. */
static bool make_tiled(deferred_renderer *r, const scene *s, char *err, size_t errlen)
{
    tiled_pass *tp = &r->tp;
    uint32_t n = s->nlights_total;
    tp->max_lights = n ? n : 1u;
    GLint max_block = 0;
    gl.GetIntegerv(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &max_block);
    if ((uint64_t)tp->max_lights * sizeof(gpu_light) > (uint64_t)(max_block > 0 ? max_block : 0)) {
        snprintf(err, errlen, "%s: %u lights need %llu bytes of storage buffer, this context "
                 "allows %d (GL_MAX_SHADER_STORAGE_BLOCK_SIZE)", r->b.name, n,
                 (unsigned long long)tp->max_lights * sizeof(gpu_light), max_block);
        return false;
    }
    uint32_t heads = tp->ncells + tp->ntlists;   /* opaque cells, then translucent lists */
    uint64_t want = r->b.opts.max_lights_per_tile
                        ? (uint64_t)heads * r->b.opts.max_lights_per_tile
                        : (uint64_t)heads * tp->max_lights;
    uint64_t block_entries = (uint64_t)max_block / 4u;
    if (want > block_entries)
        want = block_entries;
    if (want > (1u << 25))
        want = 1u << 25;
    tp->capacity = (uint32_t)(want ? want : 1u);
    snprintf(tp->tile_define, sizeof tp->tile_define, "TILE_SIZE %d", tp->tile);
    snprintf(tp->tiles_x_define, sizeof tp->tiles_x_define, "TILES_X %u", tp->tiles_x);
    snprintf(tp->tiles_y_define, sizeof tp->tiles_y_define, "TILES_Y %u", tp->tiles_y);
    snprintf(tp->slices_define, sizeof tp->slices_define, "SLICES %u", tp->slices);
    snprintf(tp->slices_y_define, sizeof tp->slices_y_define, "SLICES_Y %u", tp->slices_y);
    snprintf(tp->tlists_define, sizeof tp->tlists_define, "TLISTS %u", tp->ncells);
    if (!light_grid_heads_fit(r->b.name, heads, "cells", tp->slices > 0, max_block, err,
                              errlen))
        return false;
    tp->staging = calloc(tp->max_lights, sizeof *tp->staging);
    tp->readback = calloc((size_t)heads * 4u, sizeof *tp->readback);
    tp->counts = calloc(tp->ncells, sizeof *tp->counts);
    if (!tp->staging || !tp->readback || !tp->counts) {
        snprintf(err, errlen, "%s: out of memory for %u lights and %u tiles", r->b.name, n,
                 tp->ntiles);
        return false;
    }
    tp->lights = make_buffer((size_t)tp->max_lights * sizeof(gpu_light));
    tp->tiles = make_buffer((size_t)heads * 16u);
    tp->indices = make_buffer((size_t)tp->capacity * 4u);
    tp->stats = make_buffer(2 * sizeof(uint32_t));
    if (r->b.samples > 1)
        tp->edges = make_buffer(sizeof(uint32_t));
    return true;
}

static bool deferred_prepare(void *self, const scene *s, char *err, size_t errlen)
{
    deferred_renderer *r = self;
    char why[512] = "";
    release_prepared(r);
    if (!s) {
        snprintf(err, errlen, "deferred: no scene to prepare for");
        return false;
    }
    /* Programs of an earlier scene are not this scene's: start a fresh cache. */
    gl_program_cache_destroy(r->b.programs);
    r->b.programs = gl_program_cache_create();
    if (!r->b.programs) {
        snprintf(err, errlen, "deferred: out of memory");
        return false;
    }
    memset(r->gbuffer_program, 0, sizeof r->gbuffer_program);
    memset(r->light_program, 0, sizeof r->light_program);
    memset(r->light_sample_program, 0, sizeof r->light_sample_program);
    r->ambient_program = r->compose_program = r->mark_program = 0;
    r->ambient_sample_program = r->compose_sample_program = r->edge_program = 0;
    r->fog_program = 0;

    if (!renderer_base_size(&r->b, s, err, errlen))
        return false;
    r->unclipped = gl_state_fullscreen_unclipped_fits(r->b.st, r->b.width, r->b.height);

    r->variants = 0;
    r->nobjects = s->nobjects;
    bool translucency = false;   /* translucent_prepare plans the same pass, later */
    for (uint32_t i = 0; i < s->nobjects; i++) {
        uint32_t m = s->objects[i].material;
        if (m >= s->nmaterials) {
            snprintf(err, errlen, "deferred: object %u has material %u, the scene has %u", i, m,
                     s->nmaterials);
            return false;
        }
        if (!scene_material_translucent(&s->materials[m]))   /* translucent.h's */
            r->variants |= 1u << material_variant(&s->materials[m]);
        else
            translucency = true;
    }
    r->light_types = 0;
    uint32_t count[DEFERRED_LIGHT_TYPES] = {0, 0, 0};
    for (uint32_t i = 0; i < s->nlights_total; i++) {
        unsigned t = (unsigned)s->lights[i].type;
        if (t >= DEFERRED_LIGHT_TYPES) {
            snprintf(err, errlen, "deferred: light %u has an unknown type %u", i, t);
            return false;
        }
        r->light_types |= 1u << t;
        count[t]++;
    }
    r->needs = deferred_needs_of(s);
    if (!deferred_layout_build(&r->b.opts, r->needs, &r->layout, err, errlen))
        return false;

    /* >>the scene on the GPU, the frontend (light volumes, not object sets) and the shadow
     * maps, whose plan the pass plan reads */
    if (!renderer_base_scene(&r->b, s, false, err, errlen))
        goto fail;

    /* >>the pass plan */
    plan(r, PASS_SHADOWS, r->b.shadows.run, "%s", r->b.shadows.reason);
    plan(r, PASS_GBUFFER, true, "%u objects into %d attachments (%s preset, %u bytes/pixel)",
         s->nobjects, r->layout.nattachments, deferred_preset_name(r->b.opts.gbuffer),
         deferred_layout_bytes_per_pixel(&r->layout));
    plan(r, PASS_AMBIENT, true, "%s%s",
         r->needs.emissive ? "ambient x diffuse + emissive, full screen"
                           : "ambient x diffuse, full screen (no material is emissive)",
         r->b.opts.sky_stencil ? "; the full-screen passes skip the sky by the stencil" : "");
    if (count[LIGHT_DIRECTIONAL])
        plan(r, PASS_DIRECTIONAL, true, "%u directional lights, full screen each",
             count[LIGHT_DIRECTIONAL]);
    else
        plan(r, PASS_DIRECTIONAL, false, "no directional light in the scene");
    for (int t = LIGHT_POINT; t <= LIGHT_SPOT; t++) {
        pass_id p = t == LIGHT_POINT ? PASS_POINT : PASS_SPOT;
        if (count[t])
            plan(r, p, true, "%u %s lights, light volumes: %s", count[t], light_type_name(t),
                 mode_name(r->b.opts.light_volumes));
        else
            plan(r, p, false, "no %s light in the scene", light_type_name(t));
    }
    plan(r, PASS_TILED, false, "deferred shades with light volumes, not tiles");
    if (r->tiled) {
        tiled_pass *tp = &r->tp;
        tp->tiles_x = (uint32_t)((r->b.width + tp->tile - 1) / tp->tile);
        tp->tiles_y = (uint32_t)((r->b.height + tp->tile - 1) / tp->tile);
        tp->ntiles = tp->tiles_x * tp->tiles_y;
        tp->slices = tp->slices_y ? shading_cluster_slices(s, (int)tp->slices_y,
                                                          &tp->slice_ratio)
                                  : 0u;
        if (tp->slices > 1024) {
            snprintf(err, errlen,
                     "%s: %u depth slices from near %g to far %g (each %.4g times deeper, "
                     "clustered.slices %u): at most 1024; raise near or lower clustered.slices",
                     r->b.name, tp->slices, (double)s->cam.znear, (double)s->cam.zfar,
                     tp->slice_ratio, tp->slices_y);
            goto fail;
        }
        tp->ncells = tp->ntiles * (tp->slices ? tp->slices : 1u);
        tp->grid = count[LIGHT_POINT] + count[LIGHT_SPOT] > 0;
        tp->ntlists = tp->grid && translucency ? tp->ntiles : 0u;
        if (tp->ntlists)
            plan(r, PASS_TLISTS, true, "in the %s dispatch: per tile, near plane to its max depth",
                 tp->slices ? "clustered" : "tiled");
        else
            plan(r, PASS_TLISTS, false, "%s", !translucency ? "skipped: no translucent materials"
                                                            : "skipped: no culling, every light");
        if (tp->slices)
            plan(r, PASS_TILED, true, "one dispatch: %ux%ux%u clusters (%d px), %s",
                 tp->tiles_x, tp->tiles_y, tp->slices, tp->tile,
                 tp->grid ? "lights culled per cluster, ambient and lights shaded"
                          : "no point or spot light: no culling, ambient and lights shaded");
        else
            plan(r, PASS_TILED, true, "one dispatch: %ux%u tiles of %d px, %s", tp->tiles_x,
                 tp->tiles_y, tp->tile,
                 tp->grid ? "lights culled per tile, ambient and lights shaded"
                          : "no point or spot light: no culling, ambient and lights shaded");
        const char *in = tp->slices ? "in the clustered pass" : "in the tiled pass";
        plan(r, PASS_AMBIENT, false, "%s", in);
        plan(r, PASS_DIRECTIONAL, false, "%s", in);
        plan(r, PASS_POINT, false, "%s", in);
        plan(r, PASS_SPOT, false, "%s", in);
    }
    plan(r, PASS_COMPOSE, r->b.opts.separate_specular, "%s",
         r->b.opts.separate_specular ? "specular light added into the diffuse light"
                                   : "diffuse and specular light share one target");
    if (renderer_base_fog(&r->b))
        plan(r, PASS_FOG, true, "full screen after the lights: depth to view z, exp(-%g z) "
             "of the light kept (seed 000 4.5.12)", (double)r->b.opts.fog_density);
    else
        plan(r, PASS_FOG, false, "fog off (fog.density 0)");
    plan(r, PASS_SKY, s->sky, "%s",
         s->sky ? "into untouched depth, last" : "the scene has no sky");
    plan(r, PASS_RESOLVE, true, "light clamped into the output framebuffer");
    if (r->tiled)
        plan(r, PASS_EDGES, false, "msaa %d: in the %s pass: pixels whose samples differ (the "
             "same rule) listed per tile; per sample there, per pixel elsewhere", r->b.samples,
             r->tp.slices_y ? "clustered" : "tiled");
    else
        plan(r, PASS_EDGES, r->b.samples > 1,
             "msaa %d: pixels whose samples differ (off the plane > 1%% of depth, normal > 11.5 "
             "deg) get stencil bit 0x40; per sample there, per pixel elsewhere", r->b.samples);
    plan(r, PASS_MSAA, r->b.samples > 1, "the %d samples of the light averaged (a blit, "
         "linear HDR)", r->b.samples);

    if (r->tiled && !make_tiled(r, s, err, errlen))
        goto fail;
    if (!make_targets(r, err, errlen) ||
        !compile_programs(r, err, errlen) || !compile_fog(r, err, errlen) ||
        !translucent_prepare(&r->translucent, &r->b, s, &r->b.shadows, r->tiled, err, errlen) ||
        !prepare_edge_aa(r, err, errlen))
        goto fail;
    if (r->tiled) {
        const translucent_grid tg = {{r->tp.tile_define, r->tp.tiles_x_define,
                                      r->tp.tlists_define},
                                     r->tp.lights, r->tp.tiles, r->tp.indices};
        if (!translucent_compile(&r->translucent, &r->b, &r->b.shadows,
                                 r->tp.ntlists ? &tg : NULL, err, errlen))
            goto fail;
    }
    translucent_reason(&r->translucent, true, why, sizeof why);
    plan(r, PASS_TRANSLUCENT, r->translucent.run, "%s", why);
    r->prepared = true;
    return true;
fail:
    release_prepared(r);
    return false;
}

// >>per frame

static void pass_begin(deferred_renderer *r, frame_stats *out, pass_id p)
{
    renderer_base_pass_begin(&r->b, out, pass_names[p]);
}

static void pass_end(deferred_renderer *r, frame_stats *out)
{
    renderer_base_pass_end(&r->b, out);
}

static const gls_blend BLEND_ADD = {.enabled = true, .src = GLS_BLEND_ONE, .dst = GLS_BLEND_ONE};

/* The sky mask (the file's header): bit 7 marks a surface, bits 0-6 count light volumes;
 * with msaa > 1 bit 6 marks edge pixels and bits 0-5 count. */
enum { SURFACE_BIT = 0x80, VOLUME_BITS = 0x7f, EDGE_BIT = 0x40, MSAA_VOLUME_BITS = 0x3f };

/* msaa > 1: each shading draw runs twice, for the edge pixels (per sample, stencil
 * EDGE_BIT set) and then for the others (per pixel); single-sampled once, for all. */
typedef enum draw_class { CLASS_ALL, CLASS_EDGE, CLASS_PIXEL } draw_class;

static int nclasses(const deferred_renderer *r)
{
    return r->b.samples > 1 ? 2 : 1;
}

/* The i-th class of a draw (edges first: the stencil mode's edge draw must reset the
 * edge samples' counts before the per-pixel draw tests them), and starts counting its
 * draws' samples as per-sample or not. */
static draw_class class_begin(deferred_renderer *r, int i)
{
    if (r->b.samples <= 1)
        return CLASS_ALL;
    draw_class c = i == 0 ? CLASS_EDGE : CLASS_PIXEL;
    renderer_base_per_sample(&r->b, c == CLASS_EDGE);
    return c;
}

static GLuint class_program(draw_class c, GLuint pixel, GLuint sample)
{
    return c == CLASS_EDGE ? sample : pixel;
}
static const gls_stencil SURFACE_MARK = {
    .enabled = true, .front = {.compare = GLS_COMPARE_ALWAYS, .pass = GLS_STENCIL_OP_REPLACE},
    .ref = SURFACE_BIT, .write_mask = SURFACE_BIT};
static const gls_stencil SURFACE_TEST = {
    .enabled = true, .front = {.compare = GLS_COMPARE_EQUAL}, .ref = SURFACE_BIT,
    .read_mask = SURFACE_BIT};   /* every op KEEP: writes nothing */

/* What a full-screen pass tests: the surface bit with the sky mask, else nothing; with a
 * class, the edge bit too (EQUAL: set for CLASS_EDGE, clear for CLASS_PIXEL). */
static const gls_stencil *class_stencil(const deferred_renderer *r, draw_class c,
                                        bool sky_mask, gls_stencil *buf)
{
    bool sky = sky_mask && r->b.opts.sky_stencil;
    if (c == CLASS_ALL)
        return sky ? &SURFACE_TEST : NULL;
    *buf = (gls_stencil){.enabled = true, .front = {.compare = GLS_COMPARE_EQUAL},
                         .ref = (uint8_t)((sky ? SURFACE_BIT : 0) |
                                          (c == CLASS_EDGE ? EDGE_BIT : 0)),
                         .read_mask = (uint8_t)((sky ? SURFACE_BIT : 0) | EDGE_BIT)};
    return buf;
}

static const gls_stencil *full_screen_stencil(const deferred_renderer *r, draw_class c,
                                              gls_stencil *buf)
{
    return class_stencil(r, c, true, buf);
}

/* The stencil modes' read and write masks: bits 0-6 with the sky mask, else 0 (0xff);
 * with msaa, bits 0-5. */
static uint8_t volume_bits(const deferred_renderer *r)
{
    if (r->b.samples > 1)
        return MSAA_VOLUME_BITS;
    return r->b.opts.sky_stencil ? VOLUME_BITS : 0;
}

static void bind_gbuffer_textures(deferred_renderer *r)
{
    for (int i = 0; i < r->layout.nattachments; i++)
        gl_state_texture(r->b.st, DEFERRED_FIRST_GBUFFER_UNIT + (unsigned)i, r->gbuf[i].texture);
    if (r->layout.position == DEFERRED_POSITION_DEPTH_BUFFER)
        gl_state_texture(r->b.st, DEFERRED_DEPTH_UNIT, r->depth_sampled.texture
                                                           ? r->depth_sampled.texture
                                                           : r->b.depth.texture);
}

/* Light li, whose shadow-map layer this frame is `layer` (FRONTEND_NO_SHADOW: none). */
static void set_light_uniform(const scene *s, uint32_t li, uint32_t layer)
{
    gpu_light pl;
    shading_pack_light(&s->lights[li], s->view, &pl);
    shading_set_shadow_layer(&pl, layer);
    gl.Uniform4fv(DEFERRED_UNIFORM_LIGHT, 5, &pl.v[0][0]);
}

static void fullscreen(deferred_renderer *r)
{
    gl_state_draw_fullscreen(r->b.st, r->b.width, r->b.height, r->unclipped);
}

int64_t deferred_scissor_rect(const scene *s, uint32_t light, int w, int h, int rect[4])
{
    const scene_light *l = &s->lights[light];
    rect[0] = rect[1] = 0;
    rect[2] = w;
    rect[3] = h;
    sm_mat4 model, mv, mvp;
    frontend_light_volume_model(l, model);
    /* the volume mesh's box in the model's frame, with room to spare (deferred.h) */
    float lo[3], hi[3];
    if (l->type == LIGHT_POINT) {
        const float b = 1.05f;   /* the sphere's vertices lie within 1.0389 */
        lo[0] = lo[1] = lo[2] = -b;
        hi[0] = hi[1] = hi[2] = b;
    } else {
        const float b = 1.03f;   /* the cone's base: (1 + 2e-4) / cos(pi / 16) = 1.0198 */
        lo[0] = lo[1] = -b;
        hi[0] = hi[1] = b;
        lo[2] = -1.001f;
        hi[2] = 0.001f;
    }
    sm_mat4_mul(s->view, model, mv);
    sm_mat4_mul(s->proj, mv, mvp);
    float x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;
    float clip[8][4];
    int behind = 0;
    for (int c = 0; c < 8; c++) {
        float p[3] = {(c & 1) ? hi[0] : lo[0], (c & 2) ? hi[1] : lo[1], (c & 4) ? hi[2] : lo[2]};
        for (int k = 0; k < 4; k++)
            clip[c][k] = mvp[0][k] * p[0] + mvp[1][k] * p[1] + mvp[2][k] * p[2] + mvp[3][k];
        behind += clip[c][3] <= 1e-6f;
    }
    if (behind == 8) {   /* wholly behind the eye: nothing */
        rect[2] = rect[3] = 0;
        return 0;
    }
    if (behind)          /* the box reaches the eye's plane: the whole screen */
        return (int64_t)w * h;
    for (int c = 0; c < 8; c++) {
        const float *cl = clip[c];
        float x = (cl[0] / cl[3] * 0.5f + 0.5f) * (float)w;
        float y = (cl[1] / cl[3] * 0.5f + 0.5f) * (float)h;
        x0 = fminf(x0, x);
        x1 = fmaxf(x1, x);
        y0 = fminf(y0, y);
        y1 = fmaxf(y1, y);
    }
    /* whole pixels that the box's projection touches, on the screen */
    float fx0 = fmaxf(floorf(x0), 0.0f), fy0 = fmaxf(floorf(y0), 0.0f);
    float fx1 = fminf(ceilf(x1), (float)w), fy1 = fminf(ceilf(y1), (float)h);
    if (!(fx1 > fx0 && fy1 > fy0)) {
        rect[2] = rect[3] = 0;
        return 0;
    }
    rect[0] = (int)fx0;
    rect[1] = (int)fy0;
    rect[2] = (int)fx1 - rect[0];
    rect[3] = (int)fy1 - rect[1];
    return (int64_t)rect[2] * rect[3];
}

/* Point and spot lights of type t by the light-volume mode (the file's header). */
static void draw_volume_light(deferred_renderer *r, const scene *s, int t, uint32_t li,
                              uint32_t layer)
{
    gl_state *st = r->b.st;
    GLuint prog = r->light_program[t];
    GLuint sprog = r->light_sample_program[t];
    gls_stencil sbuf;
    switch (r->b.opts.light_volumes) {
    case LIGHT_VOLUMES_SCISSOR: {
        int rect[4];
        r->scissor_area += deferred_scissor_rect(s, li, r->b.width, r->b.height, rect);
        gl.Scissor(rect[0], rect[1], rect[2], rect[3]);
        for (int i = 0; i < nclasses(r); i++) {
            draw_class c = class_begin(r, i);
            gl_state_stencil(st, full_screen_stencil(r, c, &sbuf));
            gl_state_program(st, class_program(c, prog, sprog));
            set_light_uniform(s, li, layer);
            fullscreen(r);
            r->shade_draws[t]++;
        }
        return;
    }
    case LIGHT_VOLUMES_HULL:
        gl_state_viewport(st, 0, 0, r->b.width, r->b.height);
        gl_state_cull(st, GLS_CULL_FRONT);
        gl_state_depth(st, NULL);
        for (int i = 0; i < nclasses(r); i++) {
            draw_class c = class_begin(r, i);
            gl_state_program(st, class_program(c, prog, sprog));
            set_light_uniform(s, li, layer);
            gl_state_stencil(st, class_stencil(r, c, false, &sbuf));
            scene_gpu_draw_light_volume(r->b.gpu, st, s, li);
            r->shade_draws[t]++;
        }
        return;
    case LIGHT_VOLUMES_FULLSCREEN:
        for (int i = 0; i < nclasses(r); i++) {
            draw_class c = class_begin(r, i);
            gl_state_stencil(st, full_screen_stencil(r, c, &sbuf));
            gl_state_program(st, class_program(c, prog, sprog));
            set_light_uniform(s, li, layer);
            fullscreen(r);
            r->shade_draws[t]++;
        }
        return;
    case LIGHT_VOLUMES_VOLUME:
        gl_state_viewport(st, 0, 0, r->b.width, r->b.height);
        gl_state_cull(st, GLS_CULL_FRONT);
        gl_state_depth(st, &(gls_depth){.compare = GLS_COMPARE_GREATER, .write = false});
        for (int i = 0; i < nclasses(r); i++) {
            draw_class c = class_begin(r, i);
            gl_state_program(st, class_program(c, prog, sprog));
            set_light_uniform(s, li, layer);
            gl_state_stencil(st, class_stencil(r, c, false, &sbuf));
            scene_gpu_draw_light_volume(r->b.gpu, st, s, li);
            r->shade_draws[t]++;
        }
        return;
    case LIGHT_VOLUMES_STENCIL:
        gl_state_viewport(st, 0, 0, r->b.width, r->b.height);
        renderer_base_shading(&r->b, false);   /* marks shade nothing: not in samples */
        gl_state_program(st, r->mark_program);
        gl_state_color_mask(st, GLS_COLOR_MASK_NONE);
        gl_state_cull(st, GLS_CULL_NONE);
        gl_state_depth(st, &(gls_depth){.compare = GLS_COMPARE_LEQUAL, .write = false});
        gl_state_stencil(st, &(gls_stencil){
                                 .enabled = true,
                                 .two_sided = true,
                                 .front = {.compare = GLS_COMPARE_ALWAYS,
                                           .depth_fail = GLS_STENCIL_OP_DECR_WRAP},
                                 .back = {.compare = GLS_COMPARE_ALWAYS,
                                          .depth_fail = GLS_STENCIL_OP_INCR_WRAP},
                                 .read_mask = volume_bits(r),
                                 .write_mask = volume_bits(r),
                             });
        scene_gpu_draw_light_volume(r->b.gpu, st, s, li);
        r->mark_draws[t]++;
        renderer_base_shading(&r->b, true);
        gl_state_color_mask(st, GLS_COLOR_MASK_RGBA);
        gl_state_cull(st, GLS_CULL_FRONT);
        gl_state_depth(st, NULL);
        for (int i = 0; i < nclasses(r); i++) {
            draw_class c = class_begin(r, i);
            gl_state_program(st, class_program(c, prog, sprog));
            set_light_uniform(s, li, layer);
            /* counts != 0; the edge draw first: EDGE_BIT < (edge | count) picks the lit
             * edge samples and zeroes their counts, then != 0 on the count bits alone
             * picks the lit samples of the other pixels */
            gl_state_stencil(st, &(gls_stencil){
                                     .enabled = true,
                                     .front = {.compare = c == CLASS_EDGE
                                                             ? GLS_COMPARE_LESS
                                                             : GLS_COMPARE_NOTEQUAL,
                                               .pass = GLS_STENCIL_OP_ZERO},
                                     .ref = c == CLASS_EDGE ? EDGE_BIT : 0,
                                     .read_mask = (uint8_t)(volume_bits(r) |
                                                            (c == CLASS_EDGE ? EDGE_BIT : 0)),
                                     .write_mask = volume_bits(r),
                                 });
            scene_gpu_draw_light_volume(r->b.gpu, st, s, li);
            r->shade_draws[t]++;
        }
        return;
    case LIGHT_VOLUMES_STENCIL_TWO_PASS:
        gl_state_viewport(st, 0, 0, r->b.width, r->b.height);
        renderer_base_shading(&r->b, false);
        gl_state_program(st, r->mark_program);
        gl_state_color_mask(st, GLS_COLOR_MASK_NONE);
        gl_state_depth(st, &(gls_depth){.compare = GLS_COMPARE_LEQUAL, .write = false});
        gl_state_cull(st, GLS_CULL_BACK);
        gl_state_stencil(st, &(gls_stencil){
                                 .enabled = true,
                                 .front = {.compare = GLS_COMPARE_ALWAYS,
                                           .depth_fail = GLS_STENCIL_OP_INCR_WRAP},
                                 .read_mask = volume_bits(r),
                                 .write_mask = volume_bits(r),
                             });
        scene_gpu_draw_light_volume(r->b.gpu, st, s, li);
        gl_state_cull(st, GLS_CULL_FRONT);
        gl_state_stencil(st, &(gls_stencil){
                                 .enabled = true,
                                 .front = {.compare = GLS_COMPARE_ALWAYS,
                                           .depth_fail = GLS_STENCIL_OP_DECR_WRAP},
                                 .read_mask = volume_bits(r),
                                 .write_mask = volume_bits(r),
                             });
        scene_gpu_draw_light_volume(r->b.gpu, st, s, li);
        r->mark_draws[t] += 2;
        renderer_base_shading(&r->b, true);
        gl_state_color_mask(st, GLS_COLOR_MASK_RGBA);
        gl_state_depth(st, NULL);
        for (int i = 0; i < nclasses(r); i++) {
            draw_class c = class_begin(r, i);
            gl_state_program(st, class_program(c, prog, sprog));
            set_light_uniform(s, li, layer);
            /* count == 0, and with msaa the edge bit as the class has it */
            gl_state_stencil(st, &(gls_stencil){
                                     .enabled = true,
                                     .front = {.compare = GLS_COMPARE_EQUAL,
                                               .pass = GLS_STENCIL_OP_INCR_WRAP},
                                     .ref = c == CLASS_EDGE ? EDGE_BIT : 0,
                                     .read_mask = (uint8_t)(volume_bits(r) |
                                                            (c == CLASS_ALL ? 0 : EDGE_BIT)),
                                     .write_mask = volume_bits(r),
                                 });
            scene_gpu_draw_light_volume(r->b.gpu, st, s, li);
            r->shade_draws[t]++;
        }
        return;
    }
}

static void light_pass(deferred_renderer *r, const scene *s, frame_stats *out, pass_id p,
                       int type)
{
    gl_state *st = r->b.st;
    pass_begin(r, out, p);
    gl_state_framebuffer(st, r->fb_light.fbo);
    gl_state_color_mask(st, GLS_COLOR_MASK_RGBA);
    gl_state_blend(st, &BLEND_ADD);
    bool volumes = type != LIGHT_DIRECTIONAL && !full_screen_mode(r->b.opts.light_volumes);
    bool scissor = type != LIGHT_DIRECTIONAL &&
                   r->b.opts.light_volumes == LIGHT_VOLUMES_SCISSOR;
    r->scissor_area = 0;
    if (scissor)
        gl.Enable(GL_SCISSOR_TEST);   /* not state the cache keeps: off again below */
    gls_stencil sbuf;
    if (!volumes) {
        gl_state_depth(st, NULL);
        gl_state_stencil(st, full_screen_stencil(r, CLASS_ALL, &sbuf));
        gl_state_cull(st, GLS_CULL_NONE);
        gl_state_program(st, r->light_program[type]);
    } else {
        gl.Enable(GL_DEPTH_CLAMP);
    }
    if (shadow_maps_for_type(&r->b.shadows, type))
        shadow_maps_bind(&r->b.shadows, st);
    for (uint32_t k = 0; k < r->b.fe.nlights; k++) {
        uint32_t li = r->b.fe.lights[k];
        if ((int)s->lights[li].type != type)
            continue;
        if (type == LIGHT_DIRECTIONAL) {
            for (int i = 0; i < nclasses(r); i++) {
                draw_class c = class_begin(r, i);
                gl_state_stencil(st, full_screen_stencil(r, c, &sbuf));
                gl_state_program(st, class_program(c, r->light_program[type],
                                                   r->light_sample_program[type]));
                set_light_uniform(s, li, r->b.fe.shadow_layer[k]);
                fullscreen(r);
                r->shade_draws[type]++;
            }
        } else {
            draw_volume_light(r, s, type, li, r->b.fe.shadow_layer[k]);
        }
        out->lights_drawn++;
    }
    if (volumes) {
        gl.Disable(GL_DEPTH_CLAMP);
        gl_state_color_mask(st, GLS_COLOR_MASK_RGBA);
    }
    if (scissor)
        gl.Disable(GL_SCISSOR_TEST);
    pass_end(r, out);
    if (scissor)
        out->pass[out->npasses - 1].scissor_pixels = (double)r->scissor_area;
}

/* tiled-deferred's pass: the frame's visible lights into the light buffer, then one
 * dispatch that culls per tile and stores ambient + lights into the "light" target. */
static void tiled_draw(deferred_renderer *r, const scene *s, frame_stats *out)
{
    gl_state *st = r->b.st;
    tiled_pass *tp = &r->tp;
    const frontend *fe = &r->b.fe;
    uint32_t n = fe->nlights < tp->max_lights ? fe->nlights : tp->max_lights;
    for (uint32_t k = 0; k < n; k++) {
        shading_pack_light(&s->lights[fe->lights[k]], s->view, &tp->staging[k]);
        shading_set_shadow_layer(&tp->staging[k], fe->shadow_layer[k]);
    }
    if (n)
        gl.NamedBufferSubData(tp->lights, 0, (GLsizeiptr)(n * sizeof(gpu_light)), tp->staging);
    out->grid_pass = tp->grid ? out->npasses + 1 : 0;
    pass_begin(r, out, PASS_TILED);
    const uint32_t reset[2] = {0, tp->capacity};
    gl.NamedBufferSubData(tp->stats, 0, sizeof reset, reset);
    if (tp->edges) {
        gl.NamedBufferSubData(tp->edges, 0, sizeof(uint32_t), reset);
        gl_state_storage_buffer(st, BIND_SSBO_EDGES, tp->edges);
    }
    gl_state_program(st, tp->program);
    gl.Uniform1i(LOC_RENDERER, (GLint)n);
    bind_gbuffer_textures(r);
    gl_state_texture(st, DEFERRED_DEPTH_UNIT, r->b.depth.texture);
    shadow_maps_bind(&r->b.shadows, st);
    gl_state_storage_buffer(st, BIND_SSBO_LIGHTS, tp->lights);
    gl_state_storage_buffer(st, BIND_SSBO_TILE_LISTS, tp->tiles);
    gl_state_storage_buffer(st, BIND_SSBO_TILE_INDICES, tp->indices);
    gl_state_storage_buffer(st, BIND_SSBO_TILE_STATS, tp->stats);
    gl_state_image(st, BIND_IMAGE_HDR, r->b.hdr.texture, GL_WRITE_ONLY,
                   renderer_base_hdr_image_format(&r->b));
    /* it samples the depth target: no draw framebuffer that has it attached (header) */
    gl_state_framebuffer(st, r->b.output_fbo);
    gl_state_dispatch(st, tp->tiles_x, tp->tiles_y, 1);
    /* the sky draws into the target, resolve samples it; the translucent pass reads
     * the translucent lists */
    gl_state_barrier(st, GL_FRAMEBUFFER_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT |
                             (tp->ntlists ? GL_SHADER_STORAGE_BARRIER_BIT : 0u));
    /* the depth target is drawn with (sky) next: not bound for sampling meanwhile */
    if (r->layout.position != DEFERRED_POSITION_DEPTH_BUFFER)
        gl_state_texture(st, DEFERRED_DEPTH_UNIT, 0);
    pass_end(r, out);
    if (tp->edges)
        r->tiled_index = out->npasses;   /* 1 + its index */
    out->lights_drawn = n;
}

/* Fog after the lights (deferred_fog.frag): into the light target alone, blended so
 * that light' = colour (1 - f) + light f, alpha kept; the sky comes after it. */
static const gls_blend BLEND_FOG = {.enabled = true, .src = GLS_BLEND_ONE,
                                    .dst = GLS_BLEND_SRC_ALPHA, .op = GLS_BLEND_OP_ADD,
                                    .src_alpha = GLS_BLEND_ZERO, .dst_alpha = GLS_BLEND_ONE,
                                    .op_alpha = GLS_BLEND_OP_ADD};

static void fog_pass(deferred_renderer *r, frame_stats *out)
{
    gl_state *st = r->b.st;
    pass_begin(r, out, PASS_FOG);
    gl_state_framebuffer(st, r->fb_fog.fbo);
    gl_state_color_mask(st, GLS_COLOR_MASK_RGBA);
    gl_state_blend(st, &BLEND_FOG);
    gl_state_depth(st, NULL);
    gl_state_stencil(st, NULL);
    gl_state_cull(st, GLS_CULL_NONE);
    gl_state_texture(st, DEFERRED_DEPTH_UNIT, r->b.depth.texture);
    gl_state_program(st, r->fog_program);
    renderer_base_per_sample(&r->b, r->b.samples > 1);   /* msaa: per sample everywhere */
    fullscreen(r);
    renderer_base_per_sample(&r->b, false);
    /* the depth target is drawn with (sky) next: not bound for sampling meanwhile */
    if (r->layout.position != DEFERRED_POSITION_DEPTH_BUFFER)
        gl_state_texture(st, DEFERRED_DEPTH_UNIT, 0);
    pass_end(r, out);
}

static void deferred_draw(void *self, const scene *s, frame_stats *out)
{
    deferred_renderer *r = self;
    gl_state *st = r->b.st;
    out->npasses = 0;
    out->lights_drawn = 0;
    memset(r->mark_draws, 0, sizeof r->mark_draws);
    r->edges_pass = r->tiled_index = 0;
    memset(r->shade_draws, 0, sizeof r->shade_draws);
    if (!r->prepared || !s)
        return;
    renderer_base_begin_frame(&r->b, s, out);   /* every frame counted alike */
    renderer_base_shadow_pass(&r->b, s, out);      /* first: the light passes sample them */

    /* >>gbuffer */
    pass_begin(r, out, PASS_GBUFFER);
    gl_state_framebuffer(st, r->fb_gbuffer.fbo);
    gl_state_viewport(st, 0, 0, r->b.width, r->b.height);
    gl_state_clear(st, GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT, NULL,
                   1.0, r->b.opts.light_volumes == LIGHT_VOLUMES_STENCIL_TWO_PASS ? 1 : 0);
    gl_state_color_mask(st, GLS_COLOR_MASK_RGBA);
    gl_state_blend(st, NULL);
    gl_state_stencil(st, r->b.opts.sky_stencil ? &SURFACE_MARK : NULL);   /* the sky mask */
    gl_state_depth(st, &(gls_depth){.compare = GLS_COMPARE_LESS, .write = true});
    gl_state_cull(st, GLS_CULL_BACK);
    for (uint32_t k = 0; k < r->b.fe.nvisible; k++) {
        uint32_t o = r->b.fe.visible[k];
        unsigned v = material_variant(&s->materials[s->objects[o].material]);
        gl_state_program(st, r->gbuffer_program[v]);
        scene_gpu_draw_object(r->b.gpu, st, s, o);
    }
    if (r->depth_sampled.texture) {   /* position from depth: what the light passes sample */
        GLenum target = r->b.samples > 1 ? GL_TEXTURE_2D_MULTISAMPLE : GL_TEXTURE_2D;
        gl.CopyImageSubData(r->b.depth.texture, target, 0, 0, 0, 0, r->depth_sampled.texture,
                            target, 0, 0, 0, 0, r->b.width, r->b.height, 1);
    }
    pass_end(r, out);

    /* >>edges (msaa > 1): EDGE_BIT on every sample of the pixels whose samples differ */
    if (r->run[PASS_EDGES]) {
        pass_begin(r, out, PASS_EDGES);
        gl_state_framebuffer(st, r->fb_light.fbo);
        gl_state_color_mask(st, GLS_COLOR_MASK_NONE);
        gl_state_blend(st, NULL);
        gl_state_depth(st, NULL);
        gl_state_cull(st, GLS_CULL_NONE);
        gl_state_stencil(st, &(gls_stencil){
                                 .enabled = true,
                                 .front = {.compare = GLS_COMPARE_ALWAYS,
                                           .pass = GLS_STENCIL_OP_REPLACE},
                                 .ref = EDGE_BIT,
                                 .write_mask = EDGE_BIT,
                             });
        bind_gbuffer_textures(r);
        gl_state_program(st, r->edge_program);
        fullscreen(r);   /* samples: N per edge pixel (the others are discarded) */
        gl_state_color_mask(st, GLS_COLOR_MASK_RGBA);
        pass_end(r, out);
        r->edges_pass = out->npasses;
    }

    GLuint hdr_fbo = r->fb_light.fbo;   /* where the sky goes */
    if (r->tiled) {
        tiled_draw(r, s, out);
        goto sky;
    }

    /* >>ambient + emissive */
    pass_begin(r, out, PASS_AMBIENT);
    gl_state_framebuffer(st, r->fb_light.fbo);
    if (r->b.opts.sky_stencil && !r->run[PASS_SKY]) {
        /* the sky's pixels: what the ambient pass writes there, as nothing else will */
        static const float black[4] = {0.0f, 0.0f, 0.0f, 1.0f};
        gl_state_clear(st, GL_COLOR_BUFFER_BIT, black, 1.0, 0);
    }
    gl_state_blend(st, NULL);
    gl_state_depth(st, NULL);
    gl_state_cull(st, GLS_CULL_NONE);
    bind_gbuffer_textures(r);
    for (int i = 0; i < nclasses(r); i++) {
        gls_stencil sbuf;
        draw_class c = class_begin(r, i);
        gl_state_stencil(st, full_screen_stencil(r, c, &sbuf));
        gl_state_program(st, class_program(c, r->ambient_program, r->ambient_sample_program));
        fullscreen(r);
    }
    pass_end(r, out);

    /* >>lights */
    if (r->run[PASS_DIRECTIONAL])
        light_pass(r, s, out, PASS_DIRECTIONAL, LIGHT_DIRECTIONAL);
    if (r->run[PASS_POINT])
        light_pass(r, s, out, PASS_POINT, LIGHT_POINT);
    if (r->run[PASS_SPOT])
        light_pass(r, s, out, PASS_SPOT, LIGHT_SPOT);

    if (r->run[PASS_COMPOSE]) {
        pass_begin(r, out, PASS_COMPOSE);
        gl_state_framebuffer(st, r->fb_compose.fbo);
        gl_state_blend(st, &BLEND_ADD);
        gl_state_depth(st, NULL);
        gl_state_cull(st, GLS_CULL_NONE);
        gl_state_texture(st, DEFERRED_SPECULAR_UNIT, r->specular.texture);
        for (int i = 0; i < nclasses(r); i++) {
            gls_stencil sbuf;
            draw_class c = class_begin(r, i);
            gl_state_stencil(st, full_screen_stencil(r, c, &sbuf));
            gl_state_program(st,
                             class_program(c, r->compose_program, r->compose_sample_program));
            fullscreen(r);
        }
        pass_end(r, out);
        hdr_fbo = r->fb_compose.fbo;
    }

sky:
    if (r->run[PASS_FOG])
        fog_pass(r, out);

    /* >>sky: last, into untouched depth */
    if (r->run[PASS_SKY]) {
        pass_begin(r, out, PASS_SKY);
        gl_state_framebuffer(st, hdr_fbo);
        gl_state_viewport(st, 0, 0, r->b.width, r->b.height);
        gl_state_blend(st, NULL);
        gl_state_stencil(st, NULL);
        gl_state_cull(st, GLS_CULL_NONE);
        gl_state_depth(st, &(gls_depth){.compare = GLS_COMPARE_LEQUAL, .write = false});
        scene_gpu_draw_sky(r->b.gpu, st);
        pass_end(r, out);
    }

    /* >>translucent: forward, over the opaque light and depth (seed 001 19.8.1) */
    if (r->run[PASS_TRANSLUCENT])
        translucent_draw(&r->translucent, &r->b, r->b.gpu, &r->b.fe, s, &r->b.shadows, hdr_fbo, out);

    /* >>resolve: msaa > 1, the samples averaged first (renderers/base.h) */
    renderer_base_msaa_resolve_pass(&r->b, out);

    /* >>edge-aa (aa: edge), its normals from the G-buffer */
    GLuint gb[DEFERRED_MAX_ATTACHMENTS];
    for (int i = 0; i < r->layout.nattachments; i++)
        gb[i] = r->gbuf[i].texture;
    edge_aa_pass(&r->b, out, gb, r->layout.nattachments);

    /* >>resolve */
    pass_begin(r, out, PASS_RESOLVE);
    renderer_base_single_sampled(out);   /* the output */
    gl_state_blend(st, NULL);
    gl_state_stencil(st, NULL);
    gl_state_depth(st, NULL);
    gl_state_cull(st, GLS_CULL_NONE);
    scene_gpu_resolve(r->b.gpu, st, renderer_base_display(&r->b)->texture, r->b.output_fbo,
                      r->b.width, r->b.height);
    pass_end(r, out);
}

/* tiled-deferred's counters, as forward_plus.c collects them. */
static void tiled_collect(deferred_renderer *r, frame_stats *out)
{
    tiled_pass *tp = &r->tp;
    if (!r->prepared || !tp->grid)
        return;
    light_grid_collect(&(light_grid_readback){r->b.name, tp->tiles, tp->stats, tp->ncells,
                                              tp->ntiles, tp->tiles_x, tp->slices, tp->capacity,
                                              tp->readback, tp->counts, tp->ntlists},
                       out);
    tp->counted = true;
}

static void deferred_collect(void *self, frame_stats *out)
{
    deferred_renderer *r = self;
    if (r->tiled)
        tiled_collect(r, out);
    renderer_base_collect(&r->b, out);
    if (r->tiled_index && r->tiled_index <= out->npasses) {
        tiled_pass *tp = &r->tp;
        /* msaa N: the dispatch shades sample 0 of every pixel and N - 1 more samples of
         * each edge pixel; as deferred counts them: N samples per pixel, the edge pixels'
         * per sample (samples_shaded = pixels + edges (N - 1), renderer_collect) */
        gl.GetNamedBufferSubData(tp->edges, 0, sizeof(uint32_t), &tp->edge_pixels);
        double pixels = (double)r->b.width * r->b.height, n = r->b.samples;
        pass_stats *p = &out->pass[r->tiled_index - 1];
        p->samples = pixels * n;
        p->per_sample_samples = (double)tp->edge_pixels * n;
        out->edge_fraction = tp->edge_pixels / pixels;
    }
    /* the edge pass passes N samples per edge pixel and discards every other pixel */
    if (r->edges_pass && r->edges_pass <= out->npasses)
        out->edge_fraction = out->pass[r->edges_pass - 1].samples / r->b.samples /
                             ((double)r->b.width * r->b.height);
}

static const uint32_t *tiled_light_grid(const void *self, size_t *n)
{
    const deferred_renderer *r = self;
    *n = r->tp.counted ? r->tp.ncells : 0;
    return r->tp.counted ? r->tp.counts : NULL;
}

static void describe_target(const gl_target *t, pass_plan *out)
{
    if (!t->texture || out->ntargets >= sizeof out->target / sizeof out->target[0])
        return;
    gl_target_describe(t, &out->target[out->ntargets++]);
    out->target_bytes += t->bytes;
}

static void deferred_describe(const void *self, pass_plan *out)
{
    const deferred_renderer *r = self;
    memset(out, 0, sizeof *out);
    if (!r->prepared)
        return;
    for (int i = 0; i < PASS_COUNT && out->npasses < RENDERER_MAX_PASSES; i++) {
        pass_id p = describe_order[i];
        if ((p == PASS_TILED || p == PASS_TLISTS) && !r->tiled)
            continue;   /* deferred's plan is what it always was */
        if ((p == PASS_EDGES || p == PASS_MSAA) && r->b.samples <= 1)
            continue;   /* single-sampled: the plan is what it always was */
        if (p == PASS_RESOLVE)
            edge_aa_describe_pass(&r->b, out);   /* run or skipped, before the resolve */
        if (out->npasses >= RENDERER_MAX_PASSES)
            break;
        pass_plan_entry *e = &out->pass[out->npasses++];
        snprintf(e->name, sizeof e->name, "%s", pass_names[p]);
        e->run = r->run[p];
        snprintf(e->reason, sizeof e->reason, "%s", r->reason[p]);
    }
    renderer_base_describe(&r->b, out);
    scene_gpu_describe(r->b.gpu, out);
    for (int i = 0; i < r->layout.nattachments; i++) {
        describe_target(&r->gbuf[i], out);
        out->gbuffer_bytes += r->gbuf[i].bytes;
    }
    describe_target(&r->b.hdr, out);
    describe_target(&r->specular, out);
    describe_target(&r->b.depth, out);
    describe_target(&r->depth_sampled, out);
    describe_target(&r->b.hdr_resolved, out);
    edge_aa_describe_target(&r->b, out);
    shadow_maps_describe(&r->b.shadows, out);
}

static void deferred_destroy(void *self)
{
    deferred_renderer *r = self;
    if (!r)
        return;
    release_prepared(r);
    renderer_base_destroy(&r->b);
    free(r);
}

// >>for tests

const deferred_layout *deferred_gbuffer_layout(const void *self)
{
    const deferred_renderer *r = self;
    return r && r->prepared ? &r->layout : NULL;
}

const gl_target *deferred_hdr_target(const void *self)
{
    const deferred_renderer *r = self;
    return r && r->prepared ? &r->b.hdr : NULL;
}

const gl_target *deferred_gbuffer_target(const void *self, int k)
{
    const deferred_renderer *r = self;
    if (!r || !r->prepared || k < 0 || k >= r->layout.nattachments)
        return NULL;
    return &r->gbuf[k];
}

const gl_target *deferred_depth_target(const void *self)
{
    const deferred_renderer *r = self;
    return r && r->prepared ? &r->b.depth : NULL;
}

uint64_t deferred_last_mark_draws(const void *self, int type)
{
    const deferred_renderer *r = self;
    return r && type >= 0 && type < DEFERRED_LIGHT_TYPES ? r->mark_draws[type]
                                                                     : 0;
}

uint64_t deferred_last_shade_draws(const void *self, int type)
{
    const deferred_renderer *r = self;
    return r && type >= 0 && type < DEFERRED_LIGHT_TYPES ? r->shade_draws[type]
                                                                     : 0;
}

gl_state *deferred_state_cache(void *self)
{
    deferred_renderer *r = self;
    return r ? r->b.st : NULL;
}


// >>read_hdr


/* The "light" target (with separate_specular "light.diffuse", which the compose pass
 * has added "light.specular" into: the sum of both, what resolve clamps). */
static bool deferred_read_hdr(void *self, float *rgba, int width, int height)
{
    const deferred_renderer *r = self;
    return r && r->prepared && renderer_base_read_hdr(&r->b, rgba, width, height);
}

const renderer_impl renderer_deferred_impl = {
    .name = "deferred",
    .description = "G-buffer pass, then ambient, directional and light-volume passes "
                   "(fullscreen | volume | stencil | stencil-two-pass), sky last",
    .create = deferred_create,
    .prepare = deferred_prepare,
    .draw = deferred_draw,
    .collect = deferred_collect,
    .describe = deferred_describe,
    .destroy = deferred_destroy,
    .read_hdr = deferred_read_hdr,
};

const renderer_impl renderer_tiled_deferred_impl = {
    .name = "tiled-deferred",
    .description = "G-buffer pass (every preset and override of deferred), then one compute "
                   "pass that culls lights per screen tile and shades ambient, directional "
                   "and local lights into the HDR target by image store; sky last",
    .create = tiled_deferred_create,
    .prepare = deferred_prepare,
    .draw = deferred_draw,
    .collect = deferred_collect,
    .describe = deferred_describe,
    .destroy = deferred_destroy,
    .read_hdr = deferred_read_hdr,
    .light_grid = tiled_light_grid,
};
