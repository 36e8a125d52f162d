/* The device microbenchmarks (renderers/probe/probe.h). A figure is timed by
 * GL_TIME_ELAPSED on a GPU with timer queries, else (a software rasterizer, whose
 * queries time where it flushes, or no timer queries) by the CPU's clock around the
 * work and glFinish; the overheads (draw, state change, dispatch) always by the CPU's
 * clock, since they are the driver's CPU time. One warm-up call before the repeats. */
#define _POSIX_C_SOURCE 200809L
#include "renderers/probe/probe.h"
#include "renderers/gl/loader.h"
#include "renderers/gl/program.h"
#include "results/gl_device.h"

#include <math.h>
#include <stdio.h>
#include <string.h>
#include <time.h>

typedef struct probe {
    gl_program_cache *pc;
    bool gpu_timer;
    GLuint query[2];
    int w, h, draws, tiny;        /* fill size, draws a repeat, tiny calls a repeat */
    unsigned repeats;
    double min_repeat_s;          /* a repeat's least time (calls doubled up to it) */
    device_profile *out;
    GLuint vao, buf[2], fbo8, tex8;
    char *err;
    size_t errlen;
    bool failed;
} probe;

typedef void (*work_fn)(probe *pr, const void *arg);

static double now_s(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* Seconds `calls` calls of fn take (cpu: by the CPU's clock whatever the context has). */
static double time_work(probe *pr, work_fn fn, const void *arg, bool cpu, unsigned calls)
{
    gl.Finish();
    if (pr->gpu_timer && !cpu) {
        GLuint64 ns = 0;
        gl.BeginQuery(GL_TIME_ELAPSED, pr->query[0]);
        for (unsigned c = 0; c < calls; c++)
            fn(pr, arg);
        gl.EndQuery(GL_TIME_ELAPSED);
        gl.GetQueryObjectui64v(pr->query[0], GL_QUERY_RESULT, &ns);
        return (double)ns * 1e-9;
    }
    double t0 = now_s();
    for (unsigned c = 0; c < calls; c++)
        fn(pr, arg);
    gl.Finish();
    return now_s() - t0;
}

/* A figure over pr->repeats repeats, each `calls` calls of fn (amount each): amount per
 * second in units of 1e9 (a rate), or per_item: microseconds per one of the items. */
static void figure(probe *pr, const char *name, const char *unit, double amount, work_fn fn,
                   const void *arg, bool per_item)
{
    double x[DEVICE_PROFILE_MAX_REPEATS];
    time_work(pr, fn, arg, per_item, 1);   /* warm-up: shader variants, first touches */
    /* a GPU does a 1024 x 1024 call in microseconds: calls are doubled until a repeat
     * takes min_repeat_s (llvmpipe's take longer at once), so that a repeat times the
     * work more than the clock, and a stall of the CPU moves it less */
    unsigned calls = 1;
    while (calls < 1024 && time_work(pr, fn, arg, per_item, calls) < pr->min_repeat_s)
        calls *= 2;
    amount *= calls;
    for (unsigned r = 0; r < pr->repeats; r++) {
        double t = fmax(time_work(pr, fn, arg, per_item, calls), 1e-9);
        x[r] = per_item ? t * 1e6 / amount : amount / t * 1e-9;
    }
    if (!device_profile_add(pr->out, name, unit, x, pr->repeats) && !pr->failed) {
        pr->failed = true;
        snprintf(pr->err, pr->errlen, "probe: more figures than the profile holds");
    }
}

static GLuint program(probe *pr, const gl_program_desc *d)
{
    GLuint p = 0;
    if (!pr->failed && gl_program_get(pr->pc, d, &p, pr->err, pr->errlen) != GLP_OK)
        pr->failed = true;
    return p;
}

static void draw_triangles(probe *pr, const void *arg)
{
    (void)pr;
    for (int k = 0, n = *(const int *)arg; k < n; k++)
        gl.DrawArrays(GL_TRIANGLES, 0, 3);
}

/* A w x h target of format fmt (samples each) bound as the draw framebuffer, or 0. */
static GLuint target(probe *pr, GLenum fmt, bool depth, int samples, int w, int h, GLuint *tex)
{
    GLuint fbo = 0;
    GLenum kind = samples > 1 ? GL_TEXTURE_2D_MULTISAMPLE : GL_TEXTURE_2D;
    gl.CreateTextures(kind, 1, tex);
    if (samples > 1)
        gl.TextureStorage2DMultisample(*tex, samples, fmt, w, h, GL_TRUE);
    else
        gl.TextureStorage2D(*tex, 1, fmt, w, h);
    gl.CreateFramebuffers(1, &fbo);
    gl.NamedFramebufferTexture(fbo, depth ? GL_DEPTH_ATTACHMENT : GL_COLOR_ATTACHMENT0, *tex, 0);
    GLenum buf = depth ? GL_NONE : GL_COLOR_ATTACHMENT0;
    gl.NamedFramebufferDrawBuffers(fbo, 1, &buf);
    if (gl.CheckNamedFramebufferStatus(fbo, GL_DRAW_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
        if (!pr->failed)
            snprintf(pr->err, pr->errlen, "probe: a %dx%d target of format 0x%x at %d "
                     "samples is not complete", w, h, (unsigned)fmt, samples);
        pr->failed = true;
        gl.DeleteFramebuffers(1, &fbo);
        gl.DeleteTextures(1, tex);
        return 0;
    }
    gl.BindFramebuffer(GL_FRAMEBUFFER, fbo);
    gl.Viewport(0, 0, w, h);
    return fbo;
}

static const struct fill_format {
    const char *name;
    GLenum fmt;
    bool depth, uint_out;
} fill_formats[] = {
    {"rgba8", GL_RGBA8, false, false},     {"rgba16f", GL_RGBA16F, false, false},
    {"rgba32f", GL_RGBA32F, false, false}, {"r32ui", GL_R32UI, false, true},
    {"depth", GL_DEPTH_COMPONENT32F, true, false},
};

/* Fill rate: full-screen triangles into each format, blended where blending applies
 * (not to integer or depth targets), at 1 and 4 samples (4 where the context has it). */
static void probe_fill(probe *pr, int max_samples)
{
    for (size_t i = 0; i < sizeof fill_formats / sizeof *fill_formats && !pr->failed; i++) {
        const struct fill_format *f = &fill_formats[i];
        GLuint prog = program(pr, &(gl_program_desc){
            .name = "probe_fill", .vertex = "fullscreen.vert", .fragment = "probe_fill.frag",
            .defines = {f->uint_out ? "UINT_OUT" : NULL}});
        for (int samples = 1; samples <= 4 && samples <= max_samples && !pr->failed;
             samples += 3)
            for (int blend = 0; blend < (f->depth || f->uint_out ? 1 : 2); blend++) {
                GLuint tex, fbo = target(pr, f->fmt, f->depth, samples, pr->w, pr->h, &tex);
                if (!fbo)
                    return;
                gl.UseProgram(prog);
                if (f->depth) {
                    gl.Enable(GL_DEPTH_TEST);
                    gl.DepthFunc(GL_ALWAYS);
                    gl.DepthMask(GL_TRUE);
                }
                if (blend) {
                    gl.Enable(GL_BLEND);
                    gl.BlendFunc(GL_ONE, GL_ONE);
                }
                char name[48];
                snprintf(name, sizeof name, "fill_%s_%dx%s", f->name, samples,
                         blend ? "_blend" : "");
                figure(pr, name, "Gsamples/s", (double)pr->w * pr->h * samples * pr->draws,
                       draw_triangles, &pr->draws, false);
                gl.Disable(GL_BLEND);
                gl.Disable(GL_DEPTH_TEST);
                gl.BindFramebuffer(GL_FRAMEBUFFER, pr->fbo8);
                gl.DeleteFramebuffers(1, &fbo);
                gl.DeleteTextures(1, &tex);
            }
    }
}

typedef struct dispatch_arg {
    GLuint groups;
    int times;
} dispatch_arg;

static void dispatch(probe *pr, const void *arg)
{
    (void)pr;
    const dispatch_arg *d = arg;
    for (int k = 0; k < d->times; k++)
        gl.DispatchCompute(d->groups, 1, 1);
}

/* Bandwidth: a compute copy of a buffer, and a full-screen read of an RGBA32F texture. */
static void probe_bandwidth(probe *pr)
{
    GLuint copy = program(pr, &(gl_program_desc){.compute = "probe_copy.comp"});
    GLuint read = program(pr, &(gl_program_desc){.vertex = "fullscreen.vert",
                                                 .fragment = "probe_read.frag"});
    if (pr->failed)
        return;
    size_t bytes = (size_t)pr->w * pr->h * 64;   /* 64 MiB at 1024 x 1024 */
    gl.UseProgram(copy);
    gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, pr->buf[0]);
    gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, pr->buf[1]);
    dispatch_arg d = {.groups = (GLuint)(bytes / 16 / 256), .times = 1};
    figure(pr, "bandwidth_copy", "GB/s", 2.0 * (double)bytes, dispatch, &d, false);

    GLuint src, tex;
    gl.CreateTextures(GL_TEXTURE_2D, 1, &src);
    gl.TextureStorage2D(src, 1, GL_RGBA32F, pr->w, pr->h);
    GLuint fbo = target(pr, GL_RGBA32F, false, 1, pr->w / 4, pr->h / 4, &tex);
    if (fbo) {
        gl.UseProgram(read);
        gl.BindTextureUnit(0, src);
        int one = 1;
        figure(pr, "bandwidth_texture_read", "GB/s", 16.0 * pr->w * pr->h * (1 + 1.0 / 16),
               draw_triangles, &one, false);
        gl.BindFramebuffer(GL_FRAMEBUFFER, pr->fbo8);
        gl.DeleteFramebuffers(1, &fbo);
        gl.DeleteTextures(1, &tex);
    }
    gl.DeleteTextures(1, &src);
}

/* Arithmetic: the FMA loop in every fragment of the RGBA8 target, and in as many
 * compute invocations. */
static void probe_alu(probe *pr)
{
    enum { ITERATIONS = 64, FLOPS = 32 * ITERATIONS };
    GLuint frag = program(pr, &(gl_program_desc){.vertex = "fullscreen.vert",
                                                 .fragment = "probe_fma.frag"});
    GLuint comp = program(pr, &(gl_program_desc){.compute = "probe_fma.comp"});
    if (pr->failed)
        return;
    double n = (double)pr->w * pr->h;
    gl.Viewport(0, 0, pr->w, pr->h);
    gl.UseProgram(frag);
    gl.Uniform1i(0, ITERATIONS);
    int one = 1;
    figure(pr, "alu_fragment", "Gflop/s", n * FLOPS, draw_triangles, &one, false);
    gl.UseProgram(comp);
    gl.Uniform1i(0, ITERATIONS);
    gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, pr->buf[1]);
    dispatch_arg d = {.groups = (GLuint)(n / 64), .times = 1};
    figure(pr, "alu_compute", "Gflop/s", n * FLOPS, dispatch, &d, false);
}

typedef struct switch_arg {
    GLuint prog[2];
    int times;
} switch_arg;

static void draw_switching(probe *pr, const void *arg)
{
    (void)pr;
    const switch_arg *s = arg;
    for (int k = 0; k < s->times; k++) {
        gl.UseProgram(s->prog[k & 1]);
        gl.DrawArrays(GL_TRIANGLES, 0, 3);
    }
}

/* Overheads: many draws into a 1x1 viewport, the same with the program switched
 * before each, many one-group dispatches (microseconds each, by the CPU's clock). */
static void probe_overhead(probe *pr)
{
    switch_arg s = {
        .prog = {program(pr, &(gl_program_desc){.vertex = "fullscreen.vert",
                                                .fragment = "probe_fill.frag"}),
                 program(pr, &(gl_program_desc){.name = "probe_fill_b",
                                                .vertex = "fullscreen.vert",
                                                .fragment = "probe_fill.frag",
                                                .defines = {"PROBE_SECOND 1"}})},
        .times = pr->tiny};
    GLuint comp = program(pr, &(gl_program_desc){.compute = "probe_fma.comp"});
    if (pr->failed)
        return;
    gl.Viewport(0, 0, 1, 1);
    gl.UseProgram(s.prog[0]);
    figure(pr, "draw_us", "us", pr->tiny, draw_triangles, &pr->tiny, true);
    figure(pr, "state_change_us", "us", pr->tiny, draw_switching, &s, true);
    gl.UseProgram(comp);
    gl.Uniform1i(0, 1);
    gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, pr->buf[1]);
    dispatch_arg d = {.groups = 1, .times = pr->tiny};
    figure(pr, "dispatch_us", "us", pr->tiny, dispatch, &d, true);
    gl.Viewport(0, 0, pr->w, pr->h);
}

/* The timer's resolution: the smallest nonzero step between two readings taken back
 * to back (GL_TIMESTAMP where figures are timed by GL, else the CPU's clock), the
 * smallest of 64 pairs a repeat. */
static void probe_timer(probe *pr)
{
    double x[DEVICE_PROFILE_MAX_REPEATS];
    for (unsigned r = 0; r < pr->repeats; r++) {
        double best = INFINITY;
        for (int k = 0; k < 64; k++) {
            double step;
            if (pr->gpu_timer) {
                GLuint64 t[2] = {0, 0};
                gl.QueryCounter(pr->query[0], GL_TIMESTAMP);
                gl.QueryCounter(pr->query[1], GL_TIMESTAMP);
                gl.GetQueryObjectui64v(pr->query[0], GL_QUERY_RESULT, &t[0]);
                gl.GetQueryObjectui64v(pr->query[1], GL_QUERY_RESULT, &t[1]);
                step = (double)(t[1] - t[0]);
            } else {
                double t0 = now_s(), t1;
                while ((t1 = now_s()) == t0) {
                }
                step = (t1 - t0) * 1e9;
            }
            if (step > 0 && step < best)
                best = step;
        }
        x[r] = isfinite(best) ? best : 1e9;   /* no step seen: at most its span */
    }
    device_profile_add(pr->out, "timer_resolution_ns", "ns", x, pr->repeats);
}

bool gl_probe_run(gl_context *ctx, bool quick, device_profile *out, char *err, size_t errlen)
{
    const gl_info *gi = gl_context_info(ctx);
    device_profile_set_gl(out, (const char *const[6]){gi->vendor, gi->renderer, gi->version,
                                                       gi->glsl_version, gi->backend,
                                                       gi->device});
    out->software = gl_software_rasterizer(gi->renderer, gi->vendor, gi->version);
    probe pr = {
        .gpu_timer = gi->timer_query && !out->software,
        .w = quick ? 64 : 1024, .h = quick ? 64 : 1024, .draws = quick ? 2 : 8,
        .tiny = quick ? 200 : 4000, .repeats = quick ? 5 : 9, .min_repeat_s = quick ? 0.002 : 0.01,
        .out = out, .err = err, .errlen = errlen,
    };
    out->timing = pr.gpu_timer ? "gpu-timer" : "cpu-finish";
    out->quick = quick;
    out->width = pr.w;
    out->height = pr.h;
    pr.pc = gl_program_cache_create();
    if (!pr.pc) {
        snprintf(err, errlen, "probe: out of memory");
        return false;
    }
    size_t bytes = (size_t)pr.w * pr.h * 64;
    gl.GenQueries(2, pr.query);
    gl.CreateVertexArrays(1, &pr.vao);
    gl.BindVertexArray(pr.vao);
    gl.CreateBuffers(2, pr.buf);
    gl.NamedBufferStorage(pr.buf[0], (GLsizeiptr)bytes, NULL, 0);
    gl.NamedBufferStorage(pr.buf[1], (GLsizeiptr)bytes, NULL, 0);
    pr.fbo8 = target(&pr, GL_RGBA8, false, 1, pr.w, pr.h, &pr.tex8);
    gl.Disable(GL_DEPTH_TEST);
    gl.Disable(GL_STENCIL_TEST);
    gl.Disable(GL_CULL_FACE);
    probe_fill(&pr, gi->max_samples);
    probe_bandwidth(&pr);
    probe_alu(&pr);
    probe_overhead(&pr);
    if (!pr.failed)
        probe_timer(&pr);
    gl.Finish();
    gl_program_cache_destroy(pr.pc);
    gl.DeleteFramebuffers(1, &pr.fbo8);
    gl.DeleteTextures(1, &pr.tex8);
    gl.DeleteBuffers(2, pr.buf);
    gl.DeleteVertexArrays(1, &pr.vao);
    gl.DeleteQueries(2, pr.query);
    gl_context_bind_default(ctx);
    unsigned errors = gl_context_poll_errors(ctx, "probe");
    if (!pr.failed && errors) {
        snprintf(err, errlen, "probe: %u GL error(s) (printed above)", errors);
        return false;
    }
    return !pr.failed;
}
