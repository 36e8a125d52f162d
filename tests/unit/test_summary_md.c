/* runner/answer/summary_md.c on a summary.csv with known trial values: the paired ratio of two
 * runs, and the warnings (an outlier trial, a trial on a busy machine, a run too short
 * to judge), each naming the run and the trial; runner/answer/point_verdict.c's line of who
 * wins at a point (a clear winner, a tie, one trial). */
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
#include <unistd.h>

#include "runner/answer/point_verdict.h"
#include "runner/answer/summary_md.h"

static const char csv[] =
    "run_id,renderer,experiment,trial,frametime_mean_us,status,metric,metric_us,"
    "cpu_share_mean,steal_frac\n"
    /* a: trial 4 an outlier (10x), trial 2 starved (0.2 of a median 0.6) */
    "aaaaaaaaaaaa,deferred,x,1,1000,ok,cpu,100,0.6,0\n"
    "aaaaaaaaaaaa,deferred,x,2,1000,ok,cpu,101,0.2,0\n"
    "aaaaaaaaaaaa,deferred,x,3,1000,ok,cpu,99,0.6,0\n"
    "aaaaaaaaaaaa,deferred,x,4,1000,ok,cpu,1000,0.6,0\n"
    "aaaaaaaaaaaa,deferred,x,5,1000,ok,cpu,100,0.6,0\n"
    /* b: exactly twice a, round by round but for the outlier; trial 5 stolen from */
    "bbbbbbbbbbbb,forward-spml,x,1,2000,ok,cpu,200,0.6,0\n"
    "bbbbbbbbbbbb,forward-spml,x,2,2000,ok,cpu,202,0.6,0\n"
    "bbbbbbbbbbbb,forward-spml,x,3,2000,ok,cpu,198,0.6,0\n"
    "bbbbbbbbbbbb,forward-spml,x,4,2000,ok,cpu,2000,0.6,0\n"
    "bbbbbbbbbbbb,forward-spml,x,5,2000,ok,cpu,200,0.6,0.2\n"
    /* c: two trials, one failed: nothing to say of it */
    "cccccccccccc,null,x,1,10,ok,cpu,5,0.1,0\n"
    "cccccccccccc,null,x,2,,failed:sync,,,,\n";

static void load_text(const char *text, run_result **runs, size_t *n)
{
    char path[] = "/tmp/test_summary_md_XXXXXX";
    int fd = mkstemp(path);
    assert_true(fd >= 0);
    assert_int_equal(write(fd, text, strlen(text)), (ssize_t)strlen(text));
    close(fd);
    char err[256];
    bool ok = summary_load_runs(path, runs, n, err, sizeof err);
    unlink(path);
    assert_true(ok);
}

static void load(run_result **runs, size_t *n)
{
    load_text(csv, runs, n);
    assert_int_equal(*n, 3);
}

static void test_trial_values_and_paired_ratio(void **state)
{
    (void)state;
    run_result *runs;
    size_t n;
    load(&runs, &n);
    assert_string_equal(runs[0].metric, "cpu");
    assert_int_equal(runs[0].nvalues, 5);
    assert_true(runs[0].value[3] == 1000 && runs[0].wall[3] == 1000);
    assert_int_equal(runs[2].trials, 2);
    assert_int_equal(runs[2].trials_ok, 1);
    assert_true(isnan(runs[2].value[1]));
    /* b / a is 2 in every round: the geometric mean exactly, a zero-width interval */
    ratio_ci r;
    summary_paired_ratio(&runs[1], &runs[0], &r);
    assert_int_equal(r.n, 5);
    assert_true(fabs(r.ratio - 2) < 1e-12 && fabs(r.lo - 2) < 1e-9 && fabs(r.hi - 2) < 1e-9);
    summary_free_runs(runs, n);
}

static void test_warnings(void **state)
{
    (void)state;
    run_result *runs;
    size_t n;
    load(&runs, &n);
    char *text = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&text, &len);
    assert_non_null(f);
    size_t k = summary_warnings(runs, n, f, "w: ", false);
    fclose(f);
    assert_int_equal(k, 4);
    assert_non_null(strstr(text, "w: run aaaaaaaaaaaa (deferred) trial 4 is an outlier: 1 ms of "
                                 "cpu time a frame, the run's median 0.1 ms\n"));
    assert_non_null(strstr(text, "w: run aaaaaaaaaaaa (deferred) trial 2 ran on a busy machine: "
                                 "it got 20% of the CPU it could use (the run's median 60%), "
                                 "steal 0%\n"));
    assert_non_null(strstr(text, "w: run bbbbbbbbbbbb (forward-spml) trial 4 is an outlier"));
    assert_non_null(strstr(text, "w: run bbbbbbbbbbbb (forward-spml) trial 5 ran on a busy "
                                 "machine: it got 60% of the CPU it could use (the run's median "
                                 "60%), steal 20%\n"));
    assert_null(strstr(text, "cccccccccccc"));
    free(text);
    summary_free_runs(runs, n);
}

/* One trial has no median CPU share to compare with: the steal alone, never "nan". */
static void test_one_trial_busy_warning(void **state)
{
    (void)state;
    static const char one[] =
        "run_id,renderer,experiment,trial,frametime_mean_us,status,metric,metric_us,"
        "cpu_share_mean,steal_frac\n"
        "aaaaaaaaaaaa,deferred,x,1,1000,ok,cpu,100,0.3,0.2\n"
        "bbbbbbbbbbbb,forward-spml,x,1,1000,ok,cpu,100,0.1,0\n";
    run_result *runs;
    size_t n;
    load_text(one, &runs, &n);
    char *text = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&text, &len);
    assert_non_null(f);
    assert_int_equal(summary_warnings(runs, n, f, "w: ", false), 1);
    fclose(f);
    assert_string_equal(text, "w: run aaaaaaaaaaaa (deferred) trial 1 ran on a busy machine: "
                              "the hypervisor stole 20% of the machine's CPU time\n");
    free(text);
    summary_free_runs(runs, n);
}

/* The verdict of runs[order[0..k)], ranked as given. */
static void verdict_of_point(run_result *runs, size_t *order, size_t k, char *out,
                             size_t len, bool want)
{
    char *cfg[6];   /* each run's configuration: its renderer */
    for (size_t i = 0; i < 6; i++)
        cfg[i] = runs[i].renderer;
    summary_point p = {.label = "all runs", .runs = order, .nruns = k};
    assert_int_equal(point_verdict(runs, &p, cfg, out, len), want);
}

static void test_point_verdict(void **state)
{
    (void)state;
    static const char text[] =
        "run_id,renderer,experiment,trial,frametime_mean_us,status,metric,metric_us\n"
        /* a; b ties with it (b / a: 1.05, 100/110, 95/90); c is exactly 3x a; d failed */
        "aaaaaaaaaaaa,deferred,x,1,1,ok,cpu,100\naaaaaaaaaaaa,deferred,x,2,1,ok,cpu,110\n"
        "aaaaaaaaaaaa,deferred,x,3,1,ok,cpu,90\n"
        "bbbbbbbbbbbb,forward-spml,x,1,1,ok,cpu,105\nbbbbbbbbbbbb,forward-spml,x,2,1,ok,cpu,100\n"
        "bbbbbbbbbbbb,forward-spml,x,3,1,ok,cpu,95\n"
        "cccccccccccc,clustered,x,1,1,ok,cpu,300\ncccccccccccc,clustered,x,2,1,ok,cpu,330\n"
        "cccccccccccc,clustered,x,3,1,ok,cpu,270\n"
        "dddddddddddd,null,x,1,,failed:sync,,\n"
        /* e, f: one trial each */
        "eeeeeeeeeeee,deferred,x,1,1,ok,cpu,100\nffffffffffff,tiled-deferred,x,1,1,ok,cpu,150\n";
    run_result *runs;
    size_t n;
    load_text(text, &runs, &n);
    assert_int_equal(n, 6);
    char out[512];
    size_t ac[] = {0, 2, 3};   /* a clear winner, then a failed run */
    verdict_of_point(runs, ac, 3, out, sizeof out, true);
    assert_string_equal(out, "fastest deferred, then clustered at 3.00x (3.00-3.00)");
    /* b / a = 1.0025, its interval 0.81-1.24 (t 4.303, 2 dof) holds 1: a tie */
    size_t abc[] = {0, 1, 2, 3};
    verdict_of_point(runs, abc, 4, out, sizeof out, true);
    assert_string_equal(out, "deferred and forward-spml tie (1.00x, interval 0.81-1.24 holds 1), "
                             "then clustered at 3.00x (3.00-3.00)");
    size_t ab[] = {0, 1};
    verdict_of_point(runs, ab, 2, out, sizeof out, true);
    assert_string_equal(out, "deferred and forward-spml tie (1.00x, interval 0.81-1.24 holds 1)");
    size_t ef[] = {4, 5};   /* one trial: no interval, and no "nan" */
    verdict_of_point(runs, ef, 2, out, sizeof out, true);
    assert_string_equal(out, "fastest deferred, then tiled-deferred at 1.50x (no interval: "
                             "fewer than 3 trials)");
    size_t ad[] = {0, 3}, a_only[] = {0}, ae[] = {0, 4};   /* nothing to compare */
    verdict_of_point(runs, ad, 2, out, sizeof out, false);
    assert_string_equal(out, "");
    verdict_of_point(runs, a_only, 1, out, sizeof out, false);
    verdict_of_point(runs, ae, 2, out, sizeof out, false);   /* one configuration */
    summary_free_runs(runs, n);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_trial_values_and_paired_ratio),
        cmocka_unit_test(test_warnings),
        cmocka_unit_test(test_one_trial_busy_warning),
        cmocka_unit_test(test_point_verdict),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
