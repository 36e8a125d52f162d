/* results/contention.c: the first line of /proc/stat and /proc/loadavg parsed from
 * fixed strings, a trial's differences, a frame's CPU share, and the readings on this
 * machine being sane. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>

#include "assert_near.h"
#include "results/contention.h"

static void test_cpu_line(void **state)
{
    (void)state;
    cpu_times c;
    /* Linux >= 2.6.33: ten fields; guest and guest_nice are in user and nice already */
    assert_true(contention_parse_cpu_line("cpu  4705 356 584 3699 23 23 0 7 100 100\n", &c));
    assert_true(c.has_steal);
    assert_int_equal(c.total, 4705 + 356 + 584 + 3699 + 23 + 23 + 0 + 7);
    assert_int_equal(c.steal, 7);
    /* eight fields (steal, no guest), tabs, no line end */
    assert_true(contention_parse_cpu_line("cpu\t1 2 3 4 5 6 7 8", &c));
    assert_true(c.has_steal && c.total == 36 && c.steal == 8);
    /* before 2.6.11: no steal field */
    assert_true(contention_parse_cpu_line("cpu  1 2 3 4 5 6 7\n", &c));
    assert_false(c.has_steal);
    assert_int_equal(c.total, 28);
    assert_true(contention_parse_cpu_line("cpu 1 2 3 4\n", &c));
    assert_true(!c.has_steal && c.total == 10);
    /* large counters */
    assert_true(contention_parse_cpu_line("cpu  18446744073 0 0 1 0 0 0 2 0 0\n", &c));
    assert_true(c.total == 18446744076ull && c.steal == 2);
    /* not the machine's line */
    assert_false(contention_parse_cpu_line("cpu0 1 2 3 4 5 6 7 8 9 10\n", &c));
    assert_false(contention_parse_cpu_line("intr 1 2 3 4 5\n", &c));
    assert_false(contention_parse_cpu_line("cpu  1 2 3\n", &c));
    assert_false(contention_parse_cpu_line("cpu\n", &c));
    assert_false(contention_parse_cpu_line("", &c));
    assert_false(contention_parse_cpu_line("cpu  x 2 3 4\n", &c));
}

static void test_loadavg(void **state)
{
    (void)state;
    double v = -1;
    assert_true(contention_parse_loadavg("0.52 0.58 0.59 1/467 12345\n", &v));
    assert_near(v, 0.52, 1e-12);
    assert_true(contention_parse_loadavg("12.00 3.10 1.00 9/999 1\n", &v));
    assert_near(v, 12.0, 0);
    assert_false(contention_parse_loadavg("", &v));
    assert_false(contention_parse_loadavg("load\n", &v));
}

static void test_between(void **state)
{
    (void)state;
    contention_sample a = {.cpu_ok = true, .rusage_ok = true, .nvcsw = 10, .nivcsw = 3};
    contention_sample b = a;
    assert_true(contention_parse_cpu_line("cpu  100 0 50 800 0 0 0 50 0 0\n", &a.cpu));
    assert_true(contention_parse_cpu_line("cpu  200 0 100 1600 0 0 0 100 0 0\n", &b.cpu));
    b.nvcsw = 25;
    b.nivcsw = 7;
    contention_trial t;
    contention_between(&a, &b, 1.5, &t);
    assert_near(t.steal_frac, 50.0 / 1000.0, 1e-15);
    assert_near(t.vol_csw, 15, 0);
    assert_near(t.invol_csw, 4, 0);
    assert_near(t.loadavg_1m, 1.5, 0);
    /* no time passed: no fraction */
    contention_between(&a, &a, NAN, &t);
    assert_true(isnan(t.steal_frac) && isnan(t.loadavg_1m));
    assert_near(t.invol_csw, 0, 0);
    /* no steal reported, or nothing read */
    assert_true(contention_parse_cpu_line("cpu  1 2 3 4 5 6 7\n", &a.cpu));
    contention_between(&a, &b, 0.0, &t);
    assert_true(isnan(t.steal_frac));
    b.rusage_ok = b.cpu_ok = false;
    contention_between(&a, &b, 0.0, &t);
    assert_true(isnan(t.steal_frac) && isnan(t.invol_csw) && isnan(t.vol_csw));
}

static void test_frame_cpu(void **state)
{
    (void)state;
    frame_cpu c = contention_frame_cpu(1.0, 1.0005, 1000.0, 2);
    assert_near(c.us, 500.0, 1e-6);
    assert_near(c.share, 0.25, 1e-9);
    c = contention_frame_cpu(1.0, 1.0005, 0.0, 2);   /* a frame of no time: no share */
    assert_true(isfinite(c.us) && isnan(c.share));
    c = contention_frame_cpu(NAN, 1.0, 1000.0, 2);
    assert_true(isnan(c.us) && isnan(c.share));
}

/* This machine: a process that has run has CPU time, at least one usable CPU, and
 * getrusage works; /proc/stat, where there is one, parses. */
static void test_readings(void **state)
{
    (void)state;
    volatile double x = 0;
    for (int i = 0; i < 1000000; i++)
        x += i;
    double cpu = contention_process_cpu_s();
    assert_true(isfinite(cpu) && cpu > 0);
    assert_true(contention_usable_cpus() >= 1);
    contention_sample s;
    contention_sample_now(&s);
    assert_true(s.rusage_ok);
    double la = contention_loadavg_1m();
    assert_true(isnan(la) || la >= 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_cpu_line),
        cmocka_unit_test(test_loadavg),
        cmocka_unit_test(test_between),
        cmocka_unit_test(test_frame_cpu),
        cmocka_unit_test(test_readings),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
