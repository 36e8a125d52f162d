/* The renderer registry and the thin dispatch over renderer_impl. */
#include "renderers/renderer_internal.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Every renderer the program knows, one line each (its renderer_X_impl), in the order
 * `info` and errors list them. */
#define RENDERER_REGISTRY(R)                                                               \
    R(null)                                                                                \
    R(deferred)                                                                            \
    R(forward_mpml)                                                                        \
    R(forward_spml)                                                                        \
    R(forward_plus)                                                                        \
    R(clustered)                                                                           \
    R(tiled_deferred)                                                                      \
    R(deferred_lighting)                                                                   \
    R(visibility)                                                                          \
    R(zbin)

#define RENDERER_EXTERN(x) extern const renderer_impl renderer_##x##_impl;
RENDERER_REGISTRY(RENDERER_EXTERN)
#define RENDERER_ENTRY(x) &renderer_##x##_impl,
static const renderer_impl *const registry[] = {RENDERER_REGISTRY(RENDERER_ENTRY)};

size_t renderer_kind_count(void) { return sizeof registry / sizeof registry[0]; }

const renderer_impl *renderer_kind_at(size_t i)
{
    return i < renderer_kind_count() ? registry[i] : NULL;
}

const renderer_impl *renderer_kind_find(const char *name)
{
    for (size_t i = 0; i < renderer_kind_count(); i++)
        if (strcmp(registry[i]->name, name) == 0)
            return registry[i];
    return NULL;
}

renderer *renderer_create(const char *kind, const renderer_options *opts, char *err, size_t errlen)
{
    const renderer_impl *impl = renderer_kind_find(kind);
    if (!impl) {
        snprintf(err, errlen, "unknown renderer '%s'", kind);
        return NULL;
    }
    const renderer_impl *design = impl->variant ? impl->variant(opts) : impl;
    void *(*create)(const renderer_options *, char *, size_t) =
        impl->create ? impl->create : design ? design->create : NULL;
    if (!design || !create || !design->prepare || !design->draw || !design->describe ||
        !design->destroy) {
        snprintf(err, errlen, "bug: renderer '%s' lacks an entry point", kind);
        return NULL;
    }
    renderer *r = calloc(1, sizeof *r);
    if (!r) {
        snprintf(err, errlen, "out of memory");
        return NULL;
    }
    r->impl = design;
    r->kind = impl->name;
    r->self = create(opts, err, errlen);
    if (!r->self) {
        free(r);
        return NULL;
    }
    return r;
}

bool renderer_prepare(renderer *r, const struct scene *s, char *err, size_t errlen)
{
    r->prepared = r->impl->prepare(r->self, s, err, errlen);
    return r->prepared;
}

static void draw_with(renderer *r, const struct scene *s, frame_stats *out,
                      void (*draw)(void *, const struct scene *, frame_stats *))
{
    memset(out, 0, sizeof *out);
    out->grid_lights_mean = out->grid_lights_max = out->light_evals_per_pixel = NAN;
    out->light_struct_bytes = NAN;
    out->edge_fraction = NAN;
    out->translucent_lights_mean = out->translucent_lights_max = NAN;
    if (!r->prepared) {   /* a caller's bug: say so, and leave the frame empty */
        fprintf(stderr, "bug: %s: draw before a successful prepare\n", r->kind);
        return;
    }
    draw(r->self, s, out);
}

void renderer_draw(renderer *r, const struct scene *s, frame_stats *out)
{
    draw_with(r, s, out, r->impl->draw);
}

void renderer_prime(renderer *r, const struct scene *s, frame_stats *out)
{
    draw_with(r, s, out, r->impl->prime ? r->impl->prime : r->impl->draw);
}

bool renderer_has_coverage(const renderer *r)
{
    return !r->impl->no_base;
}

/* NAN in any pass makes the total NAN: a partial sum would pass for a measurement. */
void renderer_collect(renderer *r, frame_stats *out)
{
    renderer_impl_collect(r->impl, r->self, out);
    pass_stats t = {.name = "total", .scissor_pixels = NAN};
    double n = out->msaa > 1 ? out->msaa : 1;
    for (size_t i = 0; i < out->npasses; i++) {
        pass_stats *p = &out->pass[i];
        /* a pixel shaded once covers n samples; a per-sample draw shades each */
        if (!p->shaded_counted)
            p->samples_shaded = n == 1 || p->single_sampled
                                    ? p->samples
                                    : (p->samples - p->per_sample_samples) / n +
                                          p->per_sample_samples;
        t.per_sample_samples += p->per_sample_samples;
        t.samples_shaded += p->samples_shaded;
        t.gpu_us += p->gpu_us;
        t.cpu_us += p->cpu_us;
        t.draw_calls += p->draw_calls;
        t.dispatches += p->dispatches;
        t.state_changes += p->state_changes;
        t.fragments += p->fragments;
        t.samples += p->samples;
        t.primitives += p->primitives;
    }
    if (out->npasses == 0)
        t.gpu_us = t.fragments = t.primitives = t.samples = t.samples_shaded = NAN;
    out->total = t;
}

void renderer_describe(const renderer *r, pass_plan *out)
{
    memset(out, 0, sizeof *out);
    r->impl->describe(r->self, out);
}

void renderer_destroy(renderer *r)
{
    if (!r)
        return;
    r->impl->destroy(r->self);
    free(r);
}

bool renderer_has_light_grid(const renderer *r)
{
    return r && r->impl->light_grid;
}

const uint32_t *renderer_light_grid(const renderer *r, size_t *n)
{
    *n = 0;
    if (!r || !r->impl->light_grid)
        return NULL;
    return r->impl->light_grid(r->self, n);
}

gbuffer_traffic renderer_traffic(const renderer *r, const frame_stats *fs)
{
    if (!r || !r->impl->traffic)
        return (gbuffer_traffic){NAN, NAN};
    return r->impl->traffic(r->self, fs);
}

bool renderer_read_hdr(renderer *r, float *rgba, int w, int h, size_t *nonfinite)
{
    if (nonfinite)
        *nonfinite = 0;
    if (!r || !rgba || !r->impl->read_hdr || w <= 0 || h <= 0 ||
        !r->impl->read_hdr(r->self, rgba, w, h))
        return false;
    if (nonfinite) {
        size_t n = (size_t)w * (size_t)h * 4, bad = 0;
        for (size_t i = 0; i < n; i++)
            bad += !isfinite(rgba[i]);
        *nonfinite = bad;
    }
    return true;
}

bool renderer_reads(const char *reads, const char *path)
{
    for (const char *s = reads ? reads : ""; *s;) {
        size_t len = strcspn(s, " ");
        if (strncmp(s, path, len) == 0 && (path[len] == '\0' || path[len] == '.'))
            return true;
        s += len;
        s += strspn(s, " ");
    }
    return false;
}

/* The design that serves kind with options o (its variant's, for clustered); NULL for
 * an unknown kind, or a variant without options. */
static const renderer_impl *design_of(const char *kind, const renderer_options *o)
{
    const renderer_impl *impl = kind ? renderer_kind_find(kind) : NULL;
    if (impl && impl->variant)
        impl = o ? impl->variant(o) : NULL;
    return impl;
}

bool renderer_design_reads(const char *kind, const renderer_options *o, const char *path)
{
    const renderer_impl *impl = design_of(kind, o);
    return impl && renderer_reads(impl->reads, path);
}

bool renderer_uses_gbuffer(const char *kind, const renderer_options *o)
{
    return renderer_design_reads(kind, o, "gbuffer");
}

const char *renderer_gbuffer_layout(const char *kind, const renderer_options *o)
{
    const renderer_impl *impl = design_of(kind, o);
    return impl && impl->gbuffer_layout ? impl->gbuffer_layout : "";
}

uint64_t renderer_own_bytes(const char *kind, const renderer_estimate *e)
{
    const renderer_impl *impl = design_of(kind, e->opts);
    return impl && impl->own_bytes ? impl->own_bytes(e) : 0;
}

/* >>defaults: the key tables' default texts as options (renderer_options_default) */

/* the enums' names, each value's text at its enumerator (declared in keys.h; the
 * runner validates against them) */
#define KEY_ENUM(type, names, values) const char *const names[] = {values NULL};
#define V(text, e) [e] = text,
#define VX(e)
#define PARAM_META(...)
#define PARAM(...)
#define KEY_OPTION(type, member, dims)
#include "renderers/keys.def"
#undef KEY_ENUM
#undef V
#undef VX
#undef PARAM
#define KEY_ENUM(...)

/* The keys' values as run_params holds them (the tables' decl column). */
#define KEY_DECL(...) __VA_ARGS__
#define PARAM(path, type, flags, field, decl, def, lim, values, readers, ref, apply, desc)  \
    KEY_DECL decl
typedef struct key_values {
#include "renderers/keys.def"
} key_values;
#undef PARAM

/* One default text into the value at `at`, read as its C type `kind` says (an enum's
 * by its names); the runner validates every default at every load, so each reads. */
static void key_default(const char *def, const char *const *names, void *at, char kind)
{
    if (names) {
        for (int i = 0; names[i]; i++)
            if (strcmp(names[i], def) == 0)
                memcpy(at, &i, sizeof i);
    } else if (kind == 'b') {
        *(bool *)at = strcmp(def, "true") == 0;
    } else if (kind == 'u') {
        *(uint32_t *)at = (uint32_t)strtoul(def, NULL, 10);
    } else if (kind == 'f') {
        *(float *)at = strtof(def, NULL);
    } else if (kind == 'd') {
        *(double *)at = strtod(def, NULL);
    } else if (kind == 'v') {
        float *v = at;
        if (sscanf(def, "[%f, %f, %f]", &v[0], &v[1], &v[2]) != 3)
            v[0] = v[1] = v[2] = 0;
    }
}

renderer_options renderer_options_default(void)
{
    key_values kv = {0}, *p = &kv;
    renderer_options opts = {0}, *o = &opts;
#define RP(m)                                                                               \
    &p->m, _Generic(p->m, bool: 'b', uint32_t: 'u', float: 'f', double: 'd', float *: 'v',   \
                    default: 'e')
#define PARAM(path, type, flags, field, decl, def, lim, values, readers, ref, apply, desc)  \
    key_default(def, values, field);
#include "renderers/keys.def"
#undef PARAM
#undef RP
#define PARAM(path, type, flags, field, decl, def, lim, values, readers, ref, apply, desc)  \
    apply;
#include "renderers/keys.def"
#undef PARAM
    return opts;
}

void renderer_options_complete(renderer_options *o)
{
    static const unsigned char zero[sizeof(renderer_options)];
    const renderer_options d = renderer_options_default();
#undef KEY_OPTION
#define KEY_OPTION(type, member, dims)                                                      \
    if (memcmp(&o->member, zero, sizeof o->member) == 0)                                    \
        memcpy(&o->member, &d.member, sizeof o->member);
#define PARAM(...)
#include "renderers/keys.def"
#undef PARAM
#undef KEY_OPTION
#undef PARAM_META
#undef KEY_ENUM
}

uint64_t renderer_draws_per_light(const char *kind, const renderer_estimate *e)
{
    const renderer_impl *impl = renderer_kind_find(kind);
    return impl && impl->draws_per_light ? impl->draws_per_light(e) : 0;
}

uint32_t renderer_max_lights(const char *kind, const renderer_options *o,
                             int max_uniform_block_size)
{
    const renderer_impl *impl = renderer_kind_find(kind);
    return impl && impl->max_lights ? impl->max_lights(o, max_uniform_block_size) : UINT32_MAX;
}

