/* visibility: the visibility buffer (Burns and Hunt, JCGT 2(2), 2013). Passes: shadows;
 * visibility (the visible opaque objects into the R32UI id target, each
 * pixel the id draw << tri_bits | gl_PrimitiveID, see visibility.h); [cull] (forward-
 * plus's tile_cull.comp, when the scene has a point or spot light); shade
 * (visibility_shade.comp, a work group per tile, one dispatch per run of visible draws
 * that bind the same maps); then forward_end_frame (sky, [translucent], [edge-aa],
 * resolve). Draws: shadows + V + sky + T + [edge-aa] + 1; dispatches: [1 cull] + R.
 * MSAA: ids, depth and HDR multisampled; an edge pixel shades each distinct id once at
 * the centre. Refused at prepare: a scene whose ids or storage blocks do not fit.
 * The whole account (MSAA edge rule, refusals): docs/notes/visibility.md. */
#include "renderers/visibility/visibility.h"

#include "renderers/forward/forward_common.h"
#include "renderers/frame/shading.h"
#include "renderers/tiled/grid.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The pass names (passes.csv, meta.yaml), each written once: visibility_pass and
 * shade_pass begin them, visibility_id_traffic finds them by them. */
static const char VIS_PASS[] = "visibility";
static const char SHADE_PASS[] = "shade";

enum { VIS_MAP_VARIANTS = 16 };   /* the 4 map bits of FORWARD_VARIANT_* */

/* One visible draw as visibility_shade.comp reads it (std430, 160 bytes). */
typedef struct vis_draw {
    float model_view[16];
    float normal_matrix[12];         /* 3 columns, padded to vec4 */
    float diffuse_specular[4];
    float emissive_shininess[4];
    uint32_t geometry[4];            /* first index, base vertex, the maps on uv set 1 */
} vis_draw;
_Static_assert(sizeof(vis_draw) == 160, "visibility_shade.comp's Draw");

typedef struct vis_run {
    uint32_t first, end;             /* visible draws [first, end) */
    unsigned maps;                   /* FORWARD_VARIANT_* map bits */
    int map[4];                      /* diffuse, gloss, normal, emissive texture or -1 */
} vis_run;

typedef struct visibility {
    forward_common c;                /* first: forward_common_new makes the object */
    light_grid g;
    unsigned tri_bits;
    char tri_bits_define[24];
    gl_target target;                /* "visibility", R32UI */
    gl_target counts;                /* 3 x 1 R32UI: the shade pass's counts (shadings,
                                        samples covered, edge pixels) */
    size_t shade_index;              /* 1 + the shade pass's index this frame; 0: none */
    gl_framebuffer fb;               /* target + the base's depth */
    GLuint vis_program, vis_masked_program[2];   /* [has a diffuse map] */
    GLuint cull_program;
    GLuint shade_program[VIS_MAP_VARIANTS];
    GLuint draws, vertices, indices; /* storage buffers */
    GLuint depth_ranges;             /* msaa > 1 with the cull pass: per tile its range */
    char samples_define[24];
    uint64_t geometry_bytes;         /* the vertex and index copies */
    bool coloured;                   /* VERTEX_COLOR: the colour in the copy */
    bool uv2;                        /* UV2: the second uv set in the copy */
    bool skinned;                    /* SKINNING: the joints and weights in the copy */
    uint32_t words;                  /* words a vertex in the copy: 12 + 2 (UV2) + 1
                                        (VERTEX_COLOR) + 6 (SKINNING) */
    uint32_t *first_index, *base_vertex;   /* per scene mesh */
    vis_draw *draw_data;             /* nobjects */
    vis_run *runs;                   /* nobjects */
    uint32_t nruns;                  /* the last frame's */
} visibility;
_Static_assert(offsetof(visibility, c) == 0, "forward_common_new: the object begins with c");

gbuffer_traffic visibility_id_traffic(int width, int height, int samples, const frame_stats *fs)
{
    double written = NAN, dispatches = NAN;
    for (size_t i = 0; fs && i < fs->npasses; i++) {
        const pass_stats *p = &fs->pass[i];
        if (p->name && strcmp(p->name, VIS_PASS) == 0)
            written = p->samples;
        else if (p->name && strcmp(p->name, SHADE_PASS) == 0)
            dispatches = (double)p->dispatches;
    }
    double screen = (double)width * height * (samples > 1 ? samples : 1);
    return (gbuffer_traffic){s002_mrt_write_bytes(4.0, written),
                             s002_mrt_read_bytes(4.0, screen * dispatches)};
}

/* Its R32UI ids per sample, and the meshes' copies (at most the scene's bytes). */
static uint64_t visibility_own_bytes(const renderer_estimate *e)
{
    return 4u * e->samples * e->pixels + (e->scene ? e->scene_bytes : 0);
}

static gbuffer_traffic visibility_traffic(const void *self, const frame_stats *fs)
{
    const visibility *r = self;
    return visibility_id_traffic(r->c.b.width, r->c.b.height, r->c.b.samples, fs);
}

bool visibility_split(const char *name, uint32_t objects, uint32_t max_triangles,
                      unsigned *tri_bits, char *err, size_t errlen)
{
    unsigned bits = 1;
    while (bits < 32 && (uint64_t)max_triangles > (1ull << bits))
        bits++;
    if (bits >= 32) {
        snprintf(err, errlen, "%s: a mesh has %u triangles: the 32-bit visibility id needs "
                 "at least 1 bit for the draw, so at most 2^31 triangles a mesh",
                 name, max_triangles);
        return false;
    }
    uint64_t max_draws = (1ull << (32 - bits)) - 1u;   /* the all-ones id is "empty" */
    if (objects > max_draws) {
        snprintf(err, errlen, "%s: %u opaque objects do not fit the 32-bit visibility id: "
                 "its largest mesh's %u triangles take %u bits, which leaves %u bits, "
                 "%llu draws", name, objects, max_triangles, bits, 32 - bits,
                 (unsigned long long)max_draws);
        return false;
    }
    *tri_bits = bits;
    return true;
}

static void *visibility_create(const renderer_options *opts, char *err, size_t errlen)
{
    visibility *r = forward_common_new(sizeof *r, "visibility", opts, err, errlen);
    if (!r)
        return NULL;
    r->c.grid = &r->g;
    r->c.translucent_later = true;   /* visibility_prepare: over the tile lists or not */
    if (!light_grid_tile_option(&r->g, "visibility", opts, err, errlen)) {
        forward_common_free(&r->c);
        return NULL;
    }
    r->g.levels = 1;   /* tiles.levels: its one cull dispatch stays one level */
    return r;
}

static void release(visibility *r)
{
    light_grid_release(&r->g);
    gl_framebuffer_destroy(&r->fb);
    GL_TARGETS_DESTROY(&r->target, &r->counts);
    GLuint buffers[4] = {r->draws, r->vertices, r->indices, r->depth_ranges};
    for (int i = 0; i < 4; i++)
        if (buffers[i])
            gl.DeleteBuffers(1, &buffers[i]);
    r->draws = r->vertices = r->indices = r->depth_ranges = 0;
    free(r->first_index);
    free(r->base_vertex);
    free(r->draw_data);
    free(r->runs);
    r->first_index = r->base_vertex = NULL;
    r->draw_data = NULL;
    r->runs = NULL;
    r->nruns = 0;
    r->geometry_bytes = 0;
    r->vis_program = r->cull_program = 0;
    memset(r->vis_masked_program, 0, sizeof r->vis_masked_program);
    memset(r->shade_program, 0, sizeof r->shade_program);
}

/* The id's split from the scene's opaque objects and the largest mesh they use. */
static bool split(visibility *r, const scene *s, char *err, size_t errlen)
{
    uint32_t objects = 0, max_triangles = 0;
    for (uint32_t i = 0; i < s->nobjects; i++) {
        const scene_object *o = &s->objects[i];
        if (scene_material_translucent(&s->materials[o->material]))
            continue;
        objects++;
        if (o->mesh < s->nmeshes && s->meshes[o->mesh].nindices / 3u > max_triangles)
            max_triangles = s->meshes[o->mesh].nindices / 3u;
    }
    if (!visibility_split("visibility", objects, max_triangles, &r->tri_bits, err, errlen))
        return false;
    snprintf(r->tri_bits_define, sizeof r->tri_bits_define, "VIS_TRI_BITS %u", r->tri_bits);
    return true;
}

/* Mesh me's vertices into buffer at vertex `base`, r->words each: mesh_vertex's 12, with
 * UV2 the second uv set (2 words, (0, 0) without one), with VERTEX_COLOR the RGBA8 colour
 * (white without colours), with SKINNING the 4 joints as 16-bit halves of 2 words and the
 * 4 weights (weights 0 without a skin). False when out of memory. */
static bool upload_extended(const visibility *r, uint32_t base, const mesh *me)
{
    const size_t n = r->words;
    uint32_t *w = malloc((size_t)(me->nvertices ? me->nvertices : 1) * n * sizeof *w);
    if (!w)
        return false;
    for (uint32_t v = 0; v < me->nvertices; v++) {
        uint32_t *out = w + n * (size_t)v;
        memcpy(out, &me->vertices[v], sizeof(mesh_vertex));
        size_t k = 12;
        if (r->uv2) {
            const float uv[2] = {me->uv2 ? me->uv2[v][0] : 0.0f, me->uv2 ? me->uv2[v][1] : 0.0f};
            memcpy(out + k, uv, sizeof uv);
            k += 2;
        }
        if (r->coloured)
            out[k++] = me->colors ? me->colors[v] : 0xffffffffu;
        if (r->skinned) {
            const uint16_t *j = me->joints ? me->joints[v] : (const uint16_t[4]){0, 0, 0, 0};
            const float none[4] = {0.0f, 0.0f, 0.0f, 0.0f};
            out[k] = (uint32_t)j[0] | (uint32_t)j[1] << 16;
            out[k + 1] = (uint32_t)j[2] | (uint32_t)j[3] << 16;
            memcpy(out + k + 2, me->weights ? me->weights[v] : none, sizeof none);
        }
    }
    gl.NamedBufferSubData(r->vertices, (GLintptr)((uint64_t)base * n * sizeof *w),
                          (GLsizeiptr)((size_t)me->nvertices * n * sizeof *w), w);
    free(w);
    return true;
}

/* Mesh m's vertices into the copy (again every frame for a mesh that deforms: morph
 * targets); false when out of memory. */
static bool upload_vertices(visibility *r, const scene *s, uint32_t m)
{
    _Static_assert(sizeof(mesh_vertex) == 12 * 4, "visibility_shade.comp reads 12 words");
    const mesh *me = &s->meshes[m];
    if (r->words > 12)
        return upload_extended(r, r->base_vertex[m], me);
    gl.NamedBufferSubData(r->vertices, (GLintptr)(r->base_vertex[m] * sizeof(mesh_vertex)),
                          (GLsizeiptr)(me->nvertices * sizeof(mesh_vertex)), me->vertices);
    return true;
}

/* Copies of every mesh's vertices and indices, concatenated, as storage buffers (the
 * GPU's vertex buffers are one per mesh), and the per-draw buffer. */
static bool make_buffers(visibility *r, const scene *s, char *err, size_t errlen)
{
    uint64_t nvert = 0, nind = 0;
    r->first_index = calloc(s->nmeshes ? s->nmeshes : 1, sizeof *r->first_index);
    r->base_vertex = calloc(s->nmeshes ? s->nmeshes : 1, sizeof *r->base_vertex);
    r->draw_data = calloc(s->nobjects ? s->nobjects : 1, sizeof *r->draw_data);
    r->runs = calloc(s->nobjects ? s->nobjects : 1, sizeof *r->runs);
    if (!r->first_index || !r->base_vertex || !r->draw_data || !r->runs) {
        snprintf(err, errlen, "visibility: out of memory for %u objects", s->nobjects);
        return false;
    }
    for (uint32_t m = 0; m < s->nmeshes; m++) {
        r->first_index[m] = (uint32_t)nind;
        r->base_vertex[m] = (uint32_t)nvert;
        nvert += s->meshes[m].nvertices;
        nind += s->meshes[m].nindices;
    }
    /* UV2 (scene_uses_uv2): 2 more words a vertex, its second uv set; VERTEX_COLOR (a
     * coloured mesh in the scene): one more, its colour; SKINNING: 6 more, its skin */
    bool coloured = scene_has_vertex_colors(s);
    r->coloured = coloured;
    r->uv2 = scene_uses_uv2(s);
    r->skinned = scene_has_skins(s);
    const uint64_t words = 12 + (r->uv2 ? 2 : 0) + (coloured ? 1 : 0) + (r->skinned ? 6 : 0);
    r->words = (uint32_t)words;
    uint64_t vbytes = nvert * words * 4, ibytes = nind * sizeof(uint32_t);
    uint64_t max_block = (uint64_t)light_grid_max_block();
    if (vbytes > max_block || ibytes > max_block || nvert * words > UINT32_MAX) {
        snprintf(err, errlen, "visibility: the scene's %llu vertices (%llu bytes) and %llu "
                 "indices do not fit one storage block (%llu bytes)",
                 (unsigned long long)nvert, (unsigned long long)vbytes,
                 (unsigned long long)nind, (unsigned long long)max_block);
        return false;
    }
    gl.CreateBuffers(1, &r->vertices);
    gl.CreateBuffers(1, &r->indices);
    gl.NamedBufferStorage(r->vertices, (GLsizeiptr)(vbytes ? vbytes : 4), NULL,
                          GL_DYNAMIC_STORAGE_BIT);
    gl.NamedBufferStorage(r->indices, (GLsizeiptr)(ibytes ? ibytes : 4), NULL,
                          GL_DYNAMIC_STORAGE_BIT);
    for (uint32_t m = 0; m < s->nmeshes; m++) {
        const mesh *me = &s->meshes[m];
        if (!upload_vertices(r, s, m)) {
            snprintf(err, errlen, "visibility: out of memory for %u vertices", me->nvertices);
            return false;
        }
        gl.NamedBufferSubData(r->indices, (GLintptr)(r->first_index[m] * sizeof(uint32_t)),
                              (GLsizeiptr)(me->nindices * sizeof(uint32_t)), me->indices);
    }
    gl.CreateBuffers(1, &r->draws);
    gl.NamedBufferStorage(r->draws, (GLsizeiptr)((s->nobjects ? s->nobjects : 1) *
                                                 sizeof(vis_draw)),
                          NULL, GL_DYNAMIC_STORAGE_BIT);
    r->geometry_bytes = vbytes + ibytes;
    return true;
}

/* A program of the run's program cache; fog's uniform set when it has FOG. */
static bool program(visibility *r, gl_program_desc *d, bool fog, GLuint *out, char *err,
                    size_t errlen)
{
    char why[4096] = "";
    if (gl_program_get(r->c.b.programs, d, out, why, sizeof why) != GLP_OK) {
        snprintf(err, errlen, "visibility: %s", why);
        return false;
    }
    if (fog)
        renderer_base_fog_uniform(&r->c.b, *out);
    return true;
}

/* The material defines (shading_material_defines) of a material with variant v's maps. */
static unsigned material_defines(unsigned v, const char **defs)
{
    scene_material mat = {.diffuse_map = (v & FORWARD_VARIANT_DIFFUSE) ? 0 : -1,
                          .gloss_map = (v & FORWARD_VARIANT_GLOSS) ? 0 : -1,
                          .normal_map = (v & FORWARD_VARIANT_NORMAL) ? 0 : -1,
                          .emissive_map = (v & FORWARD_VARIANT_EMISSIVE) ? 0 : -1,
                          .alpha = (v & FORWARD_VARIANT_ALPHA_TEST) ? MATERIAL_MASK
                                                                     : MATERIAL_OPAQUE};
    return shading_material_defines(&mat, defs);
}

static bool compile(visibility *r, char *err, size_t errlen)
{
    forward_common *c = &r->c;
    light_grid *g = &r->g;
    /* the visibility pass: one program for opaque materials, the ALPHA_TEST ones for masks */
    gl_program_desc d = {.name = "visibility", .vertex = "mesh.vert",
                         .fragment = "visibility.frag", .defines = {r->tri_bits_define}};
    if (!program(r, &d, false, &r->vis_program, err, errlen))
        return false;
    for (unsigned v = 0; v < FORWARD_VARIANTS; v++) {
        if (!(c->variants & (1u << v)) || !(v & FORWARD_VARIANT_ALPHA_TEST))
            continue;
        unsigned dm = (v & FORWARD_VARIANT_DIFFUSE) ? 1u : 0u;
        if (r->vis_masked_program[dm])
            continue;
        gl_program_desc m = {.name = dm ? "visibility_masked_mapped" : "visibility_masked",
                             .vertex = "mesh.vert", .fragment = "visibility.frag",
                             .defines = {r->tri_bits_define}};
        const char *defs[SHADING_MATERIAL_DEFINES] = {NULL};
        unsigned n = material_defines(v & (FORWARD_VARIANT_DIFFUSE |
                                           FORWARD_VARIANT_ALPHA_TEST), defs);
        for (unsigned i = 0; i < n; i++)
            m.defines[1 + i] = defs[i];
        if (!program(r, &m, false, &r->vis_masked_program[dm], err, errlen))
            return false;
    }
    bool ms = c->b.samples > 1;
    snprintf(r->samples_define, sizeof r->samples_define, "MSAA_SAMPLES %d", c->b.samples);
    if (g->cull) {
        /* msaa: every sample's depth, and the tiles' ranges for the shading's fallback;
         * TLISTS: the translucent lists too (a NULL ends the defines) */
        const char *defs[7] = {g->tile_define, g->tiles_x_define};
        unsigned n = 2;
        if (light_grid_mask_define(g))
            defs[n++] = light_grid_mask_define(g);
        if (light_grid_prune_define(g))
            defs[n++] = light_grid_prune_define(g);
        if (ms) {
            defs[n++] = r->samples_define;
            defs[n++] = "TILE_DEPTH_RANGES";
        }
        if (g->ntlists)
            defs[n++] = g->tlists_define;
        gl_program_desc k = {.name = g->ntlists ? "tile_cull_translucent" : "tile_cull",
                             .compute = "tile_cull.comp",
                             .defines = {defs[0], defs[1], defs[2], defs[3], defs[4],
                                         defs[5], defs[6]}};
        if (!program(r, &k, false, &r->cull_program, err, errlen))
            return false;
    }
    bool fog = renderer_base_fog(&c->b);
    for (unsigned v = 0; v < FORWARD_VARIANTS; v++) {
        unsigned maps = v & (VIS_MAP_VARIANTS - 1u);
        if (!(c->variants & (1u << v)) || r->shade_program[maps])
            continue;
        gl_program_desc s = {.name = "visibility_shade", .compute = "visibility_shade.comp"};
        unsigned n = material_defines(maps, s.defines);
        s.defines[n++] = r->tri_bits_define;
        if (g->cull) {
            s.defines[n++] = g->tile_define;
            s.defines[n++] = g->tiles_x_define;
        } else {
            s.defines[n++] = g->tile_define;
            s.defines[n++] = "NO_GRID";
        }
        if (ms) {
            s.defines[n++] = r->samples_define;
            if (g->cull)
                s.defines[n++] = "TILE_DEPTH_RANGES";
            if (g->cull && light_grid_mask_define(g))
                s.defines[n++] = light_grid_mask_define(g);
        }
        if (fog)
            s.defines[n++] = "FOG";
        if (renderer_base_hdr_define(&c->b))
            s.defines[n++] = renderer_base_hdr_define(&c->b);
        n += forward_shadow_defines(c, -1, s.defines + n);
        if (!program(r, &s, fog, &r->shade_program[maps], err, errlen))
            return false;
    }
    return true;
}

static bool visibility_prepare(void *self, const scene *s, char *err, size_t errlen)
{
    visibility *r = self;
    forward_common *c = &r->c;
    release(r);
    if (!forward_common_prepare(c, s, err, errlen))
        return false;
    light_grid *g = &r->g;
    char why[512] = "";
    if (!split(r, s, err, errlen) ||
        !light_grid_size(g, s, c->b.width, c->b.height,
                         (c->light_types & ((1u << LIGHT_POINT) | (1u << LIGHT_SPOT))) != 0,
                         c->translucent.run, err, errlen))
        goto fail;
    int max_block = light_grid_max_block();
    if (!light_grid_heads_fit(g, "tiles", max_block, err, errlen) ||
        !light_grid_lights_fit(g, s->nlights_total, max_block, err, errlen))
        goto fail;
    light_grid_capacity(g, c->b.opts.max_lights_per_tile, max_block);
    light_grid_defines(g);
    if (!light_grid_alloc(g)) {
        snprintf(err, errlen, "visibility: out of memory for %u lights and %u tiles",
                 s->nlights_total, g->ntiles);
        goto fail;
    }
    if (!make_buffers(r, s, err, errlen))
        goto fail;
    if (!gl_target_create(&r->target,
                          &(gl_target_desc){.name = "visibility", .format = GLT_FORMAT_R32UI,
                                            .width = c->b.width, .height = c->b.height,
                                            .samples = c->b.samples},
                          why, sizeof why) ||
        !gl_framebuffer_create(&r->fb, &(gl_framebuffer_desc){.name = "visibility",
                                                              .color = {&r->target},
                                                              .depth_stencil = &c->b.depth},
                               why, sizeof why) ||
        !gl_target_create(&r->counts,
                          &(gl_target_desc){.name = "visibility-counts",
                                            .format = GLT_FORMAT_R32UI, .width = 3,
                                            .height = 1},
                          why, sizeof why)) {
        snprintf(err, errlen, "visibility: %s", why);
        goto fail;
    }
    if (!compile(r, err, errlen) || !forward_grid_prepare_end(c, &r->depth_ranges, err, errlen))
        goto fail;
    return true;
fail:
    release(r);
    c->prepared = false;
    return false;
}

/* The frame's visible draws into the draw buffer, and their runs of equal maps. */
static void upload_draws(visibility *r, const scene *s)
{
    const frontend *fe = &r->c.b.fe;
    r->nruns = 0;
    for (uint32_t k = 0; k < fe->nvisible; k++) {
        const scene_object *o = &s->objects[fe->visible[k]];
        const scene_material *m = &s->materials[o->material];
        vis_draw *d = &r->draw_data[k];
        sm_mat4 mv;
        sm_mat3 nm;
        sm_mat4_mul(s->view, o->model, mv);
        sm_mat4_normal(mv, nm);
        memcpy(d->model_view, &mv[0][0], sizeof d->model_view);
        for (int col = 0; col < 3; col++) {
            for (int row = 0; row < 3; row++)
                d->normal_matrix[col * 4 + row] = nm[col][row];
            d->normal_matrix[col * 4 + 3] = 0.0f;
        }
        d->normal_matrix[3] = m->occlusion;   /* SHADING_PBR: the ORM map's strength */
        for (int i = 0; i < 3; i++) {
            d->diffuse_specular[i] = m->diffuse[i];
            d->emissive_shininess[i] = m->emissive[i];
        }
        d->diffuse_specular[3] = m->specular;
        d->emissive_shininess[3] = m->shininess;
        d->geometry[0] = r->first_index[o->mesh];
        d->geometry[1] = r->base_vertex[o->mesh];
        d->geometry[2] = s->materials[o->material].uv1_maps;   /* UV2's maps */
        d->geometry[3] = 0;
        unsigned maps = forward_material_variant(m) & (VIS_MAP_VARIANTS - 1u);
        int map[4] = {m->diffuse_map, m->gloss_map, m->normal_map, m->emissive_map};
        vis_run *last = r->nruns ? &r->runs[r->nruns - 1] : NULL;
        if (last && last->maps == maps && !memcmp(last->map, map, sizeof map)) {
            last->end = k + 1;
        } else {
            vis_run *run = &r->runs[r->nruns++];
            *run = (vis_run){.first = k, .end = k + 1, .maps = maps};
            memcpy(run->map, map, sizeof map);
        }
    }
    if (fe->nvisible)
        gl.NamedBufferSubData(r->draws, 0, (GLsizeiptr)(fe->nvisible * sizeof(vis_draw)),
                              r->draw_data);
}

static void visibility_pass(visibility *r, const scene *s, frame_stats *out)
{
    forward_common *c = &r->c;
    gl_state *st = c->b.st;
    const frontend *fe = &c->b.fe;
    forward_pass_begin(c, out, VIS_PASS);
    forward_bind_target(c);
    gl_state_blend(st, NULL);
    gl_state_stencil(st, NULL);
    forward_clear_target(c);   /* hdr and the depth the visibility framebuffer shares */
    gl_state_framebuffer(st, r->fb.fbo);
    gl_state_color_mask(st, GLS_COLOR_MASK_RGBA);
    const GLuint empty[4] = {VIS_EMPTY, 0, 0, 0};
    gl.ClearBufferuiv(GL_COLOR, 0, empty);   /* an integer target: not gl_state_clear's floats */
    gl_state_depth(st, &(gls_depth){.compare = GLS_COMPARE_LESS, .write = true});
    gl_state_cull(st, GLS_CULL_BACK);
    for (uint32_t k = 0; k < fe->nvisible; k++) {
        uint32_t o = fe->visible[k];
        const scene_material *m = &s->materials[s->objects[o].material];
        if (m->alpha == MATERIAL_MASK) {
            gl_state_program(st, r->vis_masked_program[m->diffuse_map >= 0 ? 1 : 0]);
            gl.Uniform1i(LOC_RENDERER, (GLint)k);
            scene_gpu_draw_object(c->b.gpu, st, s, o);   /* the map and the cutoff */
        } else {
            gl_state_program(st, r->vis_program);
            gl.Uniform1i(LOC_RENDERER, (GLint)k);
            scene_gpu_draw_object_geometry(c->b.gpu, st, s, o);
        }
    }
    forward_pass_end(c, out);
}

static void shade_pass(visibility *r, frame_stats *out, uint32_t nlights)
{
    forward_common *c = &r->c;
    gl_state *st = c->b.st;
    r->shade_index = out->npasses + 1;
    forward_pass_begin(c, out, SHADE_PASS);
    static const uint32_t zero[3] = {0, 0, 0};
    gl.TextureSubImage2D(r->counts.texture, 0, 0, 0, 3, 1, GL_RED_INTEGER, GL_UNSIGNED_INT,
                         zero);
    gl_state_image(st, BIND_IMAGE_VIS_COUNTS, r->counts.texture, GL_READ_WRITE, GL_R32UI);
    light_grid_bind_lights(&r->g, st);
    if (r->g.cull)
        light_grid_bind_lists(&r->g, st);
    if (r->depth_ranges)
        gl_state_storage_buffer(st, BIND_SSBO_TILE_DEPTH, r->depth_ranges);
    gl_state_storage_buffer(st, BIND_SSBO_VIS_DRAWS, r->draws);
    gl_state_storage_buffer(st, BIND_SSBO_VIS_VERTICES, r->vertices);
    gl_state_storage_buffer(st, BIND_SSBO_VIS_INDICES, r->indices);
    shadow_maps_bind(&c->b.shadows, st);
    gl_state_image(st, BIND_IMAGE_HDR, c->b.hdr.texture, GL_WRITE_ONLY,
                   renderer_base_hdr_image_format(&c->b));
    /* it samples the visibility target: no draw framebuffer that has it attached */
    gl_state_framebuffer(st, c->b.output_fbo);
    gl_state_texture(st, BIND_TEX_VISIBILITY, r->target.texture);
    static const unsigned bits[4] = {FORWARD_VARIANT_DIFFUSE, FORWARD_VARIANT_GLOSS,
                                     FORWARD_VARIANT_NORMAL, FORWARD_VARIANT_EMISSIVE};
    static const unsigned units[4] = {BIND_TEX_DIFFUSE, BIND_TEX_GLOSS, BIND_TEX_NORMAL,
                                      BIND_TEX_EMISSIVE};
    for (uint32_t i = 0; i < r->nruns; i++) {
        const vis_run *run = &r->runs[i];
        gl_state_program(st, r->shade_program[run->maps]);
        for (int t = 0; t < 4; t++)
            if (run->maps & bits[t])
                gl_state_texture(st, units[t], scene_gpu_texture(c->b.gpu, run->map[t]));
        gl.Uniform1i(LOC_RENDERER, (GLint)nlights);
        gl.Uniform1i(LOC_RENDERER + 1, (GLint)run->first);
        gl.Uniform1i(LOC_RENDERER + 2, (GLint)run->end);
        light_grid_dispatch(&r->g, st);
    }
    /* the sky draws into the target, the resolve samples it, collect reads the counts */
    gl_state_barrier(st, GL_FRAMEBUFFER_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT |
                             GL_TEXTURE_UPDATE_BARRIER_BIT);
    /* drawn to next frame: not bound for sampling meanwhile */
    gl_state_texture(st, BIND_TEX_VISIBILITY, 0);
    forward_pass_end(c, out);
}

static void visibility_draw(void *self, const scene *s, frame_stats *out)
{
    visibility *r = self;
    forward_common *c = &r->c;
    forward_begin_frame(c, s, out);
    uint32_t n = light_grid_upload_lights(&r->g, s, &c->b.fe);
    upload_draws(r, s);
    for (uint32_t m = 0; m < s->nmeshes; m++)   /* morph targets: the frame's shape */
        if (s->meshes[m].deforms && !upload_vertices(r, s, m))
            fprintf(stderr, "visibility: out of memory for mesh %u's vertices: its last "
                    "shape is drawn\n", m);
    visibility_pass(r, s, out);
    if (r->g.cull) {
        out->grid_pass = out->npasses + 1;
        forward_pass_begin(c, out, "cull");
        light_grid_reset(&r->g);
        gl_state_program(c->b.st, r->cull_program);
        gl.Uniform1i(LOC_RENDERER, (GLint)n);
        /* no draw framebuffer that has the sampled depth attached */
        gl_state_framebuffer(c->b.st, c->b.output_fbo);
        gl_state_texture(c->b.st, BIND_TEX_DEPTH, c->b.depth.texture);
        light_grid_bind_lights(&r->g, c->b.st);
        light_grid_bind_lists(&r->g, c->b.st);
        if (r->depth_ranges)
            gl_state_storage_buffer(c->b.st, BIND_SSBO_TILE_DEPTH, r->depth_ranges);
        light_grid_dispatch(&r->g, c->b.st);
        gl_state_barrier(c->b.st, GL_SHADER_STORAGE_BARRIER_BIT);
        gl_state_texture(c->b.st, BIND_TEX_DEPTH, 0);   /* drawn to next (sky) */
        forward_pass_end(c, out);
    }
    shade_pass(r, out, n);
    out->lights_drawn = n;
    forward_end_frame(c, out, 0);
}

static void visibility_describe(const void *self, pass_plan *out)
{
    const visibility *r = self;
    const forward_common *c = &r->c;
    const light_grid *g = &r->g;
    forward_describe_begin(c, out);
    forward_describe_pass(out, VIS_PASS, true,
                          "the visible opaque objects: draw << %u | triangle, R32UI",
                          r->tri_bits);
    if (!c->prepared || g->cull)
        forward_describe_pass(out, "cull", true,
                              "one dispatch: %ux%u tiles of %d px, lights culled per tile",
                              g->tiles_x, g->tiles_y, g->tile);
    else
        forward_describe_pass(out, "cull", false,
                              "skipped, the scene has no point or spot light");
    forward_grid_describe_translucent(c, out);
    forward_describe_pass(out, SHADE_PASS, true,
                          "a dispatch per run of equal maps; geometry copies %llu bytes",
                          (unsigned long long)r->geometry_bytes);
    forward_describe_tail(c, out);
    if (r->target.texture && out->ntargets < sizeof out->target / sizeof out->target[0]) {
        gl_target_describe(&r->target, &out->target[out->ntargets++]);
        out->target_bytes += r->target.bytes;
        out->gbuffer_bytes += r->target.bytes;   /* the ids: its G-buffer, 4 bytes a sample */
    }
}

/* The grid's counters, and the shade pass's own (a compute pass: no query counts its
 * samples): its samples are those covered, its samples_shaded the shadings (one per
 * distinct id of a pixel), and at msaa > 1 edge_fraction the pixels with more than one. */
static void visibility_collect(void *self, frame_stats *out)
{
    visibility *r = self;
    forward_grid_collect(self, out);
    if (!r->shade_index || r->shade_index > out->npasses)
        return;
    uint32_t n[3] = {0, 0, 0};
    gl.GetTextureImage(r->counts.texture, 0, GL_RED_INTEGER, GL_UNSIGNED_INT, sizeof n, n);
    pass_stats *p = &out->pass[r->shade_index - 1];
    p->samples = n[1];
    p->samples_shaded = n[0];
    p->shaded_counted = true;
    if (r->c.b.samples > 1)
        out->edge_fraction = n[2] / ((double)r->c.b.width * r->c.b.height);
}

RENDERER_DESTROY(visibility, release, forward_common_free)

const renderer_impl renderer_visibility_impl = RENDERER_IMPL(
    visibility, "visibility", "tiles hdr msaa fog aa",
    "visibility buffer (Burns and Hunt 2013): draw and triangle ids into an R32UI "
    "target, lights culled per tile, then a compute pass that refetches each pixel's "
    "triangle and shades it with analytic derivatives",
    .collect = visibility_collect, .read_hdr = forward_read_hdr,
    .light_grid = forward_grid_counts, .traffic = visibility_traffic,
    .own_bytes = visibility_own_bytes, .gbuffer_layout = "ids");
