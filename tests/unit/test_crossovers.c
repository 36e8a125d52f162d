/* runner/answer/crossovers.c on a plan and a summary.csv with known trial values: the crossings
 * along a numeric parameter per group of the other varying parameters, where each lies
 * (the log-log interpolation of the paired ratios, computed here independently), which
 * configuration is faster on either side, and a resolution as an axis of pixels; only
 * crossings between the leaders, with evidence on both sides, are kept. */
#define _DEFAULT_SOURCE
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "runner/answer/crossovers.h"

static void write_tmp(char *path, const char *text)
{
    int fd = mkstemp(path);
    assert_true(fd >= 0);
    assert_int_equal(write(fd, text, strlen(text)), (ssize_t)strlen(text));
    close(fd);
}

typedef struct fixture {
    run_result *runs;
    size_t n;
    csv_table pl;
    long prow[32];
    bool varies[8];
    char *cfg[32];
} fixture;

/* Loads summary and plan; every plan column but index, run_id and renderer varies. */
static void load(fixture *f, const char *summary, const char *plan)
{
    char sp[] = "/tmp/test_crossovers_s_XXXXXX", pp[] = "/tmp/test_crossovers_p_XXXXXX";
    write_tmp(sp, summary);
    write_tmp(pp, plan);
    char err[256];
    assert_true(summary_load_runs(sp, &f->runs, &f->n, err, sizeof err));
    assert_true(csv_read(pp, &f->pl, err, sizeof err));
    unlink(sp);
    unlink(pp);
    assert_true(f->n <= 32 && f->pl.ncols <= 8);
    int id = csv_col(&f->pl, "run_id");
    for (size_t r = 0; r < f->n; r++) {
        f->prow[r] = -1;
        for (size_t q = 0; q < f->pl.nrows; q++)
            if (strcmp(csv_get(&f->pl, q, id), f->runs[r].id) == 0)
                f->prow[r] = (long)q;
        f->cfg[r] = f->runs[r].renderer;
    }
    for (size_t c = 0; c < f->pl.ncols; c++)
        f->varies[c] = strcmp(f->pl.header[c], "index") && strcmp(f->pl.header[c], "run_id") &&
                       strcmp(f->pl.header[c], "renderer");
}

static void unload(fixture *f)
{
    summary_free_runs(f->runs, f->n);
    csv_table_free(&f->pl);
}

/* exp(mean(log(a_i / b_i))): the paired ratio's point estimate */
static double gratio(const double *a, const double *b)
{
    double s = 0;
    for (int i = 0; i < 3; i++)
        s += log(a[i] / b[i]);
    return exp(s / 3);
}

static void test_crossing_per_group(void **state)
{
    (void)state;
    /* scene a: fp faster at 1 and 16 lights, slower at 256; scene b: fp faster at all */
    static const char summary[] =
        "run_id,renderer,experiment,trial,frametime_mean_us,status,metric,metric_us\n"
        "fpa001,fp,x,1,1,ok,cpu,1000\nfpa001,fp,x,2,1,ok,cpu,1100\nfpa001,fp,x,3,1,ok,cpu,1200\n"
        "cla001,cl,x,1,1,ok,cpu,2000\ncla001,cl,x,2,1,ok,cpu,2300\ncla001,cl,x,3,1,ok,cpu,2300\n"
        "fpa016,fp,x,1,1,ok,cpu,3000\nfpa016,fp,x,2,1,ok,cpu,3100\nfpa016,fp,x,3,1,ok,cpu,3300\n"
        "cla016,cl,x,1,1,ok,cpu,4000\ncla016,cl,x,2,1,ok,cpu,4200\ncla016,cl,x,3,1,ok,cpu,4100\n"
        "fpa256,fp,x,1,1,ok,cpu,9000\nfpa256,fp,x,2,1,ok,cpu,9500\nfpa256,fp,x,3,1,ok,cpu,9300\n"
        "cla256,cl,x,1,1,ok,cpu,6000\ncla256,cl,x,2,1,ok,cpu,6100\ncla256,cl,x,3,1,ok,cpu,6300\n"
        "fpb001,fp,x,1,1,ok,cpu,100\nfpb001,fp,x,2,1,ok,cpu,100\nfpb001,fp,x,3,1,ok,cpu,100\n"
        "clb001,cl,x,1,1,ok,cpu,200\nclb001,cl,x,2,1,ok,cpu,200\nclb001,cl,x,3,1,ok,cpu,210\n"
        "fpb256,fp,x,1,1,ok,cpu,300\nfpb256,fp,x,2,1,ok,cpu,300\nfpb256,fp,x,3,1,ok,cpu,300\n"
        "clb256,cl,x,1,1,ok,cpu,400\nclb256,cl,x,2,1,ok,cpu,400\nclb256,cl,x,3,1,ok,cpu,420\n";
    static const char plan[] =
        "index,run_id,renderer,scene,lights.count\n"
        "0,fpa001,fp,a,1\n1,cla001,cl,a,1\n2,fpa016,fp,a,16\n3,cla016,cl,a,16\n"
        "4,fpa256,fp,a,256\n5,cla256,cl,a,256\n6,fpb001,fp,b,1\n7,clb001,cl,b,1\n"
        "8,fpb256,fp,b,256\n9,clb256,cl,b,256\n";
    fixture f;
    load(&f, summary, plan);
    crossover_list l;
    assert_true(crossovers_find(f.runs, f.n, &f.pl, f.prow, f.varies, f.cfg, &l));
    assert_int_equal(l.axes, 1);   /* scene is not numeric */
    assert_int_equal(l.n, 1);
    const crossover_found *c = &l.item[0];
    assert_string_equal(c->axis, "lights.count");
    assert_string_equal(c->group, "scene=a");
    assert_string_equal(c->below, "fp");
    assert_string_equal(c->above, "cl");
    assert_true(c->x0 == 16 && c->x1 == 256);
    /* cl / fp (the pair in name order: cl first) falls through 1 between 16 and 256 */
    static const double fp16[] = {3000, 3100, 3300}, cl16[] = {4000, 4200, 4100};
    static const double fp256[] = {9000, 9500, 9300}, cl256[] = {6000, 6100, 6300};
    double l16 = log(gratio(cl16, fp16)), l256 = log(gratio(cl256, fp256));
    double x = exp(log(16) + l16 / (l16 - l256) * (log(256) - log(16)));
    assert_true(fabs(c->x - x) < 1e-9 * x);
    assert_true(16 < c->lo && c->lo < c->x && c->x < c->hi && c->hi < 256);
    assert_string_equal(c->differs0, "yes");
    assert_string_equal(c->differs1, "yes");
    crossovers_free(&l);
    unload(&f);
}

static void test_resolution_is_an_axis_of_pixels(void **state)
{
    (void)state;
    static const char summary[] =
        "run_id,renderer,experiment,trial,frametime_mean_us,status,metric,metric_us\n"
        "fp064,fp,x,1,1,ok,wall,100\nfp064,fp,x,2,1,ok,wall,100\nfp064,fp,x,3,1,ok,wall,100\n"
        "df064,df,x,1,1,ok,wall,200\ndf064,df,x,2,1,ok,wall,200\ndf064,df,x,3,1,ok,wall,200\n"
        "fp128,fp,x,1,1,ok,wall,800\nfp128,fp,x,2,1,ok,wall,800\nfp128,fp,x,3,1,ok,wall,800\n"
        "df128,df,x,1,1,ok,wall,400\ndf128,df,x,2,1,ok,wall,400\ndf128,df,x,3,1,ok,wall,400\n";
    static const char plan[] =
        "index,run_id,renderer,resolution\n"
        "0,fp064,fp,64x64\n1,df064,df,64x64\n2,fp128,fp,128x128\n3,df128,df,128x128\n";
    fixture f;
    load(&f, summary, plan);
    crossover_list l;
    assert_true(crossovers_find(f.runs, f.n, &f.pl, f.prow, f.varies, f.cfg, &l));
    assert_int_equal(l.axes, 1);
    assert_int_equal(l.n, 1);
    const crossover_found *c = &l.item[0];
    assert_true(c->x0 == 4096 && c->x1 == 16384);
    assert_string_equal(c->below, "fp");
    assert_string_equal(c->above, "df");
    assert_string_equal(c->group, "");
    /* df / fp: 2 at 4096 pixels, 1/2 at 16384: log-linear in log pixels crosses at the
     * geometric middle, 8192; constant trials give an interval of no width */
    assert_true(fabs(c->x - 8192) < 1e-6);
    assert_true(fabs(c->lo - 8192) < 1e-6 && fabs(c->hi - 8192) < 1e-6);
    crossovers_free(&l);
    unload(&f);
}

/* Writes dir/runs/ID/frames.csv: per trial 1..3, two frames at each light count, the
 * metric's column (cpu_us) at ms[level] milliseconds. */
static void write_frames(const char *dir, const char *id, const double *ms, size_t nlevels)
{
    char path[512];
    snprintf(path, sizeof path, "%s/runs", dir);
    mkdir(path, 0700);
    snprintf(path, sizeof path, "%s/runs/%s", dir, id);
    mkdir(path, 0700);
    snprintf(path, sizeof path, "%s/runs/%s/frames.csv", dir, id);
    FILE *fp = fopen(path, "w");
    assert_non_null(fp);
    fputs("run_id,trial,frame,lights,frametime_us,cpu_us\n", fp);
    for (int t = 1; t <= 3; t++)
        for (size_t l = 0; l < nlevels; l++)
            for (int f = 0; f < 2; f++)   /* two frames: their mean is ms[l] */
                fprintf(fp, "%s,%d,%zu,%zu,1,%g\n", id, t, 2 * l + (size_t)f, 10 * l,
                        1000 * ms[l] + (f ? 50 : -50));
    fclose(fp);
}

static void test_growth_over_time(void **state)
{
    (void)state;
    char dir[] = "/tmp/test_crossovers_g_XXXXXX";
    assert_non_null(mkdtemp(dir));
    /* A at 0, 10, 20 lights: 1, 4, 9 ms; B: 2, 3, 4 ms. A / B = 1/2, 4/3, 9/4: A is
     * faster below the crossing between 0 and 10 lights, linear in lights from 0 */
    static const double a[] = {1, 4, 9}, b[] = {2, 3, 4};
    write_frames(dir, "aaaa", a, 3);
    write_frames(dir, "bbbb", b, 3);
    static const char summary[] =
        "run_id,renderer,experiment,trial,frametime_mean_us,status,metric,metric_us\n"
        "aaaa,fa,x,1,1,ok,cpu,4000\naaaa,fa,x,2,1,ok,cpu,4000\naaaa,fa,x,3,1,ok,cpu,4000\n"
        "bbbb,fb,x,1,1,ok,cpu,3000\nbbbb,fb,x,2,1,ok,cpu,3000\nbbbb,fb,x,3,1,ok,cpu,3000\n";
    static const char plan[] =
        "index,run_id,renderer,lights.count\n"
        "0,aaaa,fa,\"start:0,step:10,every:1,max:590\"\n"
        "1,bbbb,fb,\"start:0,step:10,every:1,max:590\"\n";
    fixture f;
    load(&f, summary, plan);
    size_t ranked[] = {1, 0};
    summary_point p = {.label = "all runs", .runs = ranked, .nruns = 2};
    crossover_list l = {0};
    assert_true(crossovers_growth(dir, f.runs, &p, 1, &f.pl, f.prow, f.cfg, &l));
    assert_int_equal(l.axes, 1);
    assert_int_equal(l.n, 1);
    const crossover_found *c = &l.item[0];
    assert_string_equal(c->axis, "lights (growing over time)");
    assert_string_equal(c->group, "");
    assert_string_equal(c->below, "fa");
    assert_string_equal(c->above, "fb");
    assert_true(c->x0 == 0 && c->x1 == 10);
    double l0 = log(0.5), l1 = log(4.0 / 3);
    assert_true(fabs(c->x - 10 * l0 / (l0 - l1)) < 1e-9);
    assert_true(fabs(c->lo - c->x) < 1e-9 && fabs(c->hi - c->x) < 1e-9);   /* no spread */
    /* without frames.csv (outputs.frames: false) the run is left out: nothing found */
    char path[512];
    snprintf(path, sizeof path, "%s/runs/bbbb/frames.csv", dir);
    unlink(path);
    crossovers_free(&l);
    assert_true(crossovers_growth(dir, f.runs, &p, 1, &f.pl, f.prow, f.cfg, &l));
    assert_int_equal(l.n, 0);
    crossovers_free(&l);
    unlink(path);
    snprintf(path, sizeof path, "%s/runs/aaaa/frames.csv", dir);
    unlink(path);
    snprintf(path, sizeof path, "%s/runs/aaaa", dir);
    rmdir(path);
    snprintf(path, sizeof path, "%s/runs/bbbb", dir);
    rmdir(path);
    snprintf(path, sizeof path, "%s/runs", dir);
    rmdir(path);
    rmdir(dir);
    unload(&f);
}

/* Three trials of one run at one light count: "ID,R,x,k,1,ok,cpu,V" rows. */
static void rows(char **at, const char *id, const char *r, double v1, double v2, double v3)
{
    const double v[3] = {v1, v2, v3};
    for (int k = 0; k < 3; k++)
        *at += sprintf(*at, "%s,%s,x,%d,1,ok,cpu,%g\n", id, r, k + 1, v[k]);
}

static void test_only_leaders_with_evidence(void **state)
{
    (void)state;
    char summary[8192], plan[4096], *s = summary, *p = plan;
    s += sprintf(s, "run_id,renderer,experiment,trial,frametime_mean_us,status,metric,"
                    "metric_us\n");
    p += sprintf(p, "index,run_id,renderer,scene,lights.count\n");
    int idx = 0;
    /* scene l: df leads everywhere; fp and cl change places between 16 and 256 (both
     * intervals exclude 1), but neither leads: no crossover */
    static const double xl[] = {1, 16, 256}, fp[] = {100, 200, 900}, cl[] = {200, 300, 600};
    for (int k = 0; k < 3; k++) {
        char id[3][16];
        static const char *const ren[] = {"df", "fp", "cl"};
        const double v[] = {50, fp[k], cl[k]};
        for (int r = 0; r < 3; r++) {
            snprintf(id[r], sizeof id[r], "l%s%03g", ren[r], xl[k]);
            rows(&s, id[r], ren[r], v[r], v[r] * 1.01, v[r] * 0.99);
            p += sprintf(p, "%d,%s,%s,l,%g\n", idx++, id[r], ren[r], xl[k]);
        }
    }
    /* scene n: a is faster from 2 lights; at 1 light a / b is 1.01 with an interval that
     * holds 1, and only one value lies below the crossing: no crossover (the old rule
     * named one between 1 and 2) */
    static const double xs[] = {1, 2, 4, 8};
    static const double na[4][3] = {{105, 95, 104}, {50, 50, 50}, {40, 40, 40}, {30, 30, 30}};
    /* scene t: a / b above 1 at 1 and 2 lights, below at 4 and 8, no interval excluding 1:
     * two values each side agree, so the crossing between 2 and 4 stands */
    static const double ta[4][3] = {{110, 95, 108}, {108, 96, 110}, {92, 104, 90},
                                    {90, 105, 91}};
    for (int g = 0; g < 2; g++)
        for (int k = 0; k < 4; k++) {
            const double *a = g ? ta[k] : na[k];
            char ida[16], idb[16];
            snprintf(ida, sizeof ida, "%ca%g", g ? 't' : 'n', xs[k]);
            snprintf(idb, sizeof idb, "%cb%g", g ? 't' : 'n', xs[k]);
            rows(&s, ida, "a", a[0], a[1], a[2]);
            rows(&s, idb, "b", 100, 100, 100);
            p += sprintf(p, "%d,%s,a,%c,%g\n%d,%s,b,%c,%g\n", idx, ida, g ? 't' : 'n',
                         xs[k], idx + 1, idb, g ? 't' : 'n', xs[k]);
            idx += 2;
        }
    fixture f;
    load(&f, summary, plan);
    crossover_list l;
    assert_true(crossovers_find(f.runs, f.n, &f.pl, f.prow, f.varies, f.cfg, &l));
    assert_int_equal(l.n, 1);
    assert_int_equal(l.pruned, 2);   /* fp / cl in scene l, a / b at 1-2 in scene n */
    const crossover_found *c = &l.item[0];
    assert_string_equal(c->group, "scene=t");
    assert_string_equal(c->below, "b");
    assert_string_equal(c->above, "a");
    assert_true(c->x0 == 2 && c->x1 == 4 && 2 < c->x && c->x < 4);
    assert_string_equal(c->differs0, "no");
    assert_string_equal(c->differs1, "no");
    char *text = NULL;
    size_t len = 0;
    FILE *out = open_memstream(&text, &len);
    assert_non_null(out);
    crossovers_print(out, &l);
    fclose(out);
    assert_non_null(strstr(text, "crossover: b is the fastest below lights.count ~"));
    assert_non_null(strstr(text, "), a above (scene=t)\n"));
    assert_null(strchr(strchr(text, '\n') + 1, '\n'));   /* one line */
    free(text);
    crossovers_free(&l);
    unload(&f);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_crossing_per_group),
        cmocka_unit_test(test_resolution_is_an_axis_of_pixels),
        cmocka_unit_test(test_growth_over_time),
        cmocka_unit_test(test_only_leaders_with_evidence),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
