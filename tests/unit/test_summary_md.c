/* runner/summary_md.c on a summary.csv with known trial values: the paired ratio of two
 * runs, and the warnings (an outlier trial, a trial on a busy machine, a run too short
 * to judge), each naming the run and the trial. */
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

#include "runner/summary_md.h"

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

static void load(run_result **runs, size_t *n)
{
    char path[] = "/tmp/test_summary_md_XXXXXX";
    int fd = mkstemp(path);
    assert_true(fd >= 0);
    assert_int_equal(write(fd, csv, sizeof csv - 1), (ssize_t)(sizeof csv - 1));
    close(fd);
    char err[256];
    bool ok = summary_load_runs(path, runs, n, err, sizeof err);
    unlink(path);
    assert_true(ok);
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

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_trial_values_and_paired_ratio),
        cmocka_unit_test(test_warnings),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
