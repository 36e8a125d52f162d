/* CSV writer: quoting, number formatting, whole files byte for byte, and the
 * temp-name-then-rename life cycle (see results/csv.h, common/fsutil.h). */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <stdbool.h>

#include <dirent.h>
#include <errno.h>
#include <float.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include "results/csv.h"
#include "results/numfmt.h"
#include "common/fsutil.h"
#include "tests/unit/tempdir.h"

typedef struct fixture {
    char dir[64];
    char path[128];
} fixture;

static int setup(void **state)
{
    fixture *f = calloc(1, sizeof *f);
    if (f == NULL)
        return -1;
    if (temp_dir_make(f->dir, sizeof f->dir, "test_csv") != 0) {
        free(f);
        return -1;
    }
    snprintf(f->path, sizeof f->path, "%s/out.csv", f->dir);
    *state = f;
    return 0;
}

static int teardown(void **state)
{
    fixture *f = *state;
    char err[256];
    bool ok = fs_remove_tree(f->dir, err, sizeof err);
    free(f);
    return ok ? 0 : -1;
}

/* Whole file as a NUL-terminated string (caller frees); NULL when it cannot be read. */
static char *slurp(const char *path, size_t *len)
{
    FILE *fp = fopen(path, "rb");
    if (fp == NULL)
        return NULL;
    size_t cap = 4096, n = 0;
    char *buf = malloc(cap);
    size_t got;
    while (buf != NULL && (got = fread(buf + n, 1, cap - n - 1, fp)) > 0) {
        n += got;
        if (cap - n - 1 == 0) {
            char *nb = realloc(buf, cap * 2);
            if (nb == NULL) {
                free(buf);
                buf = NULL;
                break;
            }
            buf = nb;
            cap *= 2;
        }
    }
    fclose(fp);
    if (buf != NULL)
        buf[n] = '\0';
    if (len != NULL)
        *len = n;
    return buf;
}


/* >>quoting */

static void test_quoting(void **state)
{
    (void)state;
    static const struct {
        const char *in, *want;
    } cases[] = {
        {"plain", "plain"},
        {"two words", "two words"},
        {"a,b", "\"a,b\""},
        {"say \"hi\"", "\"say \"\"hi\"\"\""},
        {"\"", "\"\"\"\""},
        {"cr\rhere", "\"cr\rhere\""},
        {"lf\nhere", "\"lf\nhere\""},
        {" lead", "\" lead\""},
        {"trail ", "\"trail \""},
        {"", ""},
        {"semi;colon", "semi;colon"},
        {NULL, NULL},
    };
    for (size_t i = 0; cases[i].in != NULL; i++) {
        char *buf = NULL;
        size_t len = 0;
        FILE *fp = open_memstream(&buf, &len);
        assert_non_null(fp);
        csv_write_field(fp, cases[i].in);
        assert_int_equal(fclose(fp), 0);
        assert_string_equal(buf, cases[i].want);
        free(buf);
    }
}

/* The writer quotes exactly like csv_write_field, including inside a full row. */
static void test_full_file_bytes(void **state)
{
    fixture *f = *state;
    char err[256];
    const char *cols[] = {"name", "count", "delta", "value", "g"};
    csv_writer *w = csv_open(f->path, cols, 5, err, sizeof err);
    assert_non_null(w);

    csv_str(w, "plain");
    csv_u64(w, 42);
    csv_i64(w, -7);
    csv_f64(w, 1.5, 3);
    csv_g(w, 0.1);
    assert_true(csv_end_row(w));

    csv_str(w, "has,comma \"q\"");
    csv_u64(w, UINT64_MAX);
    csv_i64(w, INT64_MIN);
    csv_f64(w, NAN, 2);
    csv_empty(w);
    assert_true(csv_end_row(w));

    csv_str(w, " line\nbreak");
    csv_u64(w, 0);
    csv_i64(w, 0);
    csv_f64(w, -INFINITY, 1);
    csv_g(w, INFINITY);
    assert_true(csv_end_row(w));

    assert_true(csv_commit(w, err, sizeof err));

    const char *want = "name,count,delta,value,g\n"
                       "plain,42,-7,1.500,0.1\n"
                       "\"has,comma \"\"q\"\"\",18446744073709551615,-9223372036854775808,,\n"
                       "\" line\nbreak\",0,0,-inf,inf\n";
    size_t len;
    char *got = slurp(f->path, &len);
    assert_non_null(got);
    assert_int_equal(len, strlen(want));
    assert_memory_equal(got, want, len);
    free(got);
    assert_int_equal(count_entries(f->dir), 1); /* no temp file remains */
}

/* A header with a column that needs quotes. */
static void test_header_quoted(void **state)
{
    fixture *f = *state;
    char err[256];
    const char *cols[] = {"a", "b,c"};
    csv_writer *w = csv_open(f->path, cols, 2, err, sizeof err);
    assert_non_null(w);
    assert_true(csv_commit(w, err, sizeof err));
    char *got = slurp(f->path, NULL);
    assert_non_null(got);
    assert_string_equal(got, "a,\"b,c\"\n");
    free(got);
}

/* >>numbers */

/* One-column file of v written with csv_g (shortest) or csv_f64(decimals); returns its text. */
static char *write_column(fixture *f, const double *v, size_t n, int decimals, bool shortest)
{
    char err[256];
    const char *cols[] = {"v"};
    csv_writer *w = csv_open(f->path, cols, 1, err, sizeof err);
    assert_non_null(w);
    for (size_t i = 0; i < n; i++) {
        if (shortest)
            csv_g(w, v[i]);
        else
            csv_f64(w, v[i], decimals);
        assert_true(csv_end_row(w));
    }
    assert_true(csv_commit(w, err, sizeof err));
    char *got = slurp(f->path, NULL);
    assert_non_null(got);
    return got;
}

static void test_f64_formatting(void **state)
{
    fixture *f = *state;
    const double v[] = {1.23456, 2.5, -0.125, 1e6, NAN, INFINITY, -INFINITY};
    char *got = write_column(f, v, 7, 2, false);
    /* 2.5 -> "2.50"; -0.125 -> "-0.12" (round half to even on the exact binary value) */
    assert_string_equal(got, "v\n1.23\n2.50\n-0.12\n1000000.00\n\ninf\n-inf\n");
    free(got);

    const double w0[] = {2.4, 2.6, 123.0};
    got = write_column(f, w0, 3, 0, false);
    assert_string_equal(got, "v\n2\n3\n123\n");
    free(got);

    got = write_column(f, w0, 1, -3, false); /* negative decimals act as 0 */
    assert_string_equal(got, "v\n2\n");
    free(got);

    const double big[] = {DBL_MAX};
    got = write_column(f, big, 1, 3, false); /* 309 digits fit */
    assert_int_equal(strlen(got), 2 + 309 + 4 + 1);
    free(got);
}

static void test_g_round_trip(void **state)
{
    fixture *f = *state;
    const double v[] = {0.1,         1e-300, 123456789.125, 1.0 / 3.0, -2.5, 5e-324,
                        DBL_MAX,     0.0,    100.0,         1e21,      0.5,  16777217.0,
                        2.0 / 3e10,  1000.0, 1e4,           1e5,       0.0001};
    const size_t n = sizeof v / sizeof v[0];
    char *got = write_column(f, v, n, 0, true);

    char *save = NULL;
    char *line = strtok_r(got, "\n", &save);
    assert_string_equal(line, "v");
    for (size_t i = 0; i < n; i++) {
        line = strtok_r(NULL, "\n", &save);
        assert_non_null(line);
        assert_true(strtod(line, NULL) == v[i]);
        assert_null(strchr(line, 'e'));   /* plain decimals, always */
        switch (i) {
        case 0: assert_string_equal(line, "0.1"); break;
        case 1: /* "0." then 299 zeros, then 1: never an exponent */
            assert_int_equal(strlen(line), 2 + 299 + 1);
            assert_int_equal(strspn(line + 2, "0"), 299);
            break;
        case 2: assert_string_equal(line, "123456789.125"); break;
        case 3: assert_string_equal(line, "0.3333333333333333"); break;
        case 4: assert_string_equal(line, "-2.5"); break;
        case 5: assert_int_equal(strlen(line), 2 + 323 + 1); break; /* 0.000...5 */
        case 6: assert_int_equal(strlen(line), 309); break;         /* DBL_MAX's digits */
        case 7: assert_string_equal(line, "0"); break;
        case 8: assert_string_equal(line, "100"); break;
        case 9: assert_string_equal(line, "1000000000000000000000"); break;
        case 10: assert_string_equal(line, "0.5"); break;
        case 11: assert_string_equal(line, "16777217"); break;
        case 13: assert_string_equal(line, "1000"); break;  /* not 1e+03 */
        case 14: assert_string_equal(line, "10000"); break; /* as long as 1e+04 */
        case 15: assert_string_equal(line, "100000"); break; /* not 1e+05 */
        case 16: assert_string_equal(line, "0.0001"); break;
        default: break;
        }
    }
    assert_null(strtok_r(NULL, "\n", &save));
    free(got);
}

/* The fewest digits that read back, by bisection (results/numfmt.c's
 * num_fewest_digits, which num_plain, num_shortest and num_plain_float print with),
 * against the plain scan from 1 digit up over random bit patterns (normal, subnormal,
 * huge), every power of two and short decimals, as double and as float. */
static int scan_digits(double v, bool single)
{
    char e[40];
    int prec = 1, max = single ? 9 : 17;
    for (; prec < max; prec++) {
        snprintf(e, sizeof e, "%.*e", prec - 1, v);
        if (single ? strtof(e, NULL) == (float)v : strtod(e, NULL) == v)
            break;
    }
    return prec;
}

static void expect_same_digits(double v, bool single)
{
    int got = num_fewest_digits(v, single), want = scan_digits(v, single);
    if (got != want)
        fail_msg("%.17g as a %s: %d digits, the scan %d", v, single ? "float" : "double",
                 got, want);
}

static void test_fewest_digits_as_scan(void **state)
{
    (void)state;
    uint64_t x = 1337;
    for (int i = 0; i < 20000; i++) {
        x = x * 6364136223846793005u + 1442695040888963407u;
        uint64_t bits = x;
        double d;
        memcpy(&d, &bits, sizeof d);
        if (isfinite(d))
            expect_same_digits(d, false);
        uint32_t fb = (uint32_t)(x >> 32);
        float f;
        memcpy(&f, &fb, sizeof f);
        if (isfinite(f))
            expect_same_digits(f, true);
    }
    for (int k = -1074; k <= 1023; k++)
        expect_same_digits(ldexp(1, k), false);
    for (int k = -149; k <= 127; k++)
        expect_same_digits(ldexpf(1, k), true);
    const double shorts[] = {0.1, 0.3, 1e-5, 123.456, 1e22, 0, -0.0, 2.5e-5, 65504};
    for (size_t i = 0; i < sizeof shorts / sizeof *shorts; i++) {
        expect_same_digits(shorts[i], false);
        expect_same_digits((float)shorts[i], true);
    }
}

/* >>life cycle */

static void test_too_few_fields_fails(void **state)
{
    fixture *f = *state;
    char err[256] = "";
    const char *cols[] = {"a", "b", "c"};
    csv_writer *w = csv_open(f->path, cols, 3, err, sizeof err);
    assert_non_null(w);
    csv_u64(w, 1);
    csv_u64(w, 2);
    csv_u64(w, 3);
    assert_true(csv_end_row(w));
    csv_u64(w, 1);
    csv_u64(w, 2);
    assert_false(csv_end_row(w));
    /* the writer stays in error: a correct row afterwards does not repair it */
    csv_u64(w, 1);
    csv_u64(w, 2);
    csv_u64(w, 3);
    assert_false(csv_end_row(w));
    assert_false(csv_commit(w, err, sizeof err));
    assert_non_null(strstr(err, "2 fields"));
    assert_non_null(strstr(err, f->path));
    assert_false(fs_exists(f->path));
    assert_int_equal(count_entries(f->dir), 0);
}

static void test_too_many_fields_fails(void **state)
{
    fixture *f = *state;
    char err[256] = "";
    const char *cols[] = {"a"};
    csv_writer *w = csv_open(f->path, cols, 1, err, sizeof err);
    assert_non_null(w);
    csv_str(w, "x");
    csv_str(w, "y");
    assert_false(csv_end_row(w));
    assert_false(csv_commit(w, err, sizeof err));
    assert_false(fs_exists(f->path));
    assert_int_equal(count_entries(f->dir), 0);
}

static void test_unended_row_fails(void **state)
{
    fixture *f = *state;
    char err[256] = "";
    const char *cols[] = {"a", "b"};
    csv_writer *w = csv_open(f->path, cols, 2, err, sizeof err);
    assert_non_null(w);
    csv_str(w, "x");
    csv_str(w, "y");
    assert_false(csv_commit(w, err, sizeof err));
    assert_non_null(strstr(err, "not ended"));
    assert_false(fs_exists(f->path));
    assert_int_equal(count_entries(f->dir), 0);
}

static void test_abort_leaves_nothing(void **state)
{
    fixture *f = *state;
    char err[256];
    const char *cols[] = {"a"};
    csv_writer *w = csv_open(f->path, cols, 1, err, sizeof err);
    assert_non_null(w);
    csv_u64(w, 5);
    assert_true(csv_end_row(w));
    /* while open, only the temporary file exists */
    assert_false(fs_exists(f->path));
    assert_int_equal(count_entries(f->dir), 1);
    csv_abort(w);
    assert_false(fs_exists(f->path));
    assert_int_equal(count_entries(f->dir), 0);
    csv_abort(NULL);
}

static void test_open_fails_with_message(void **state)
{
    fixture *f = *state;
    char err[256] = "";
    char path[256];
    snprintf(path, sizeof path, "%s/missing/out.csv", f->dir);
    const char *cols[] = {"a"};
    assert_null(csv_open(path, cols, 1, err, sizeof err));
    assert_non_null(strstr(err, path));
    assert_non_null(strstr(err, "No such file"));
    assert_null(csv_open(f->path, cols, 0, err, sizeof err));
    assert_int_equal(count_entries(f->dir), 0);
}

/* More than the writer's buffer, in many small fields and in one huge field. */
static void test_large_output(void **state)
{
    fixture *f = *state;
    char err[256];
    const char *cols[] = {"i", "s"};
    csv_writer *w = csv_open(f->path, cols, 2, err, sizeof err);
    assert_non_null(w);
    const size_t rows = 20000;
    for (size_t i = 0; i < rows; i++) {
        csv_u64(w, i);
        csv_str(w, "a\"b");
        assert_true(csv_end_row(w));
    }
    size_t huge_len = 200000;
    char *huge = malloc(huge_len + 1);
    assert_non_null(huge);
    for (size_t i = 0; i < huge_len; i++)
        huge[i] = (i % 1000 == 999) ? '"' : 'x';
    huge[huge_len] = '\0';
    csv_u64(w, rows);
    csv_str(w, huge);
    assert_true(csv_end_row(w));
    assert_true(csv_commit(w, err, sizeof err));

    size_t len;
    char *got = slurp(f->path, &len);
    assert_non_null(got);
    char *p = got;
    assert_memory_equal(p, "i,s\n", 4);
    p += 4;
    for (size_t i = 0; i < rows; i++) {
        char want[64];
        int n = snprintf(want, sizeof want, "%zu,\"a\"\"b\"\n", i);
        assert_memory_equal(p, want, (size_t)n);
        p += n;
    }
    char want[64];
    int n = snprintf(want, sizeof want, "%zu,\"", rows);
    assert_memory_equal(p, want, (size_t)n);
    p += n;
    for (size_t i = 0; i < huge_len; i++) {
        if (huge[i] == '"') {
            assert_int_equal(*p++, '"');
            assert_int_equal(*p++, '"');
        } else {
            assert_int_equal(*p++, 'x');
        }
    }
    assert_string_equal(p, "\"\n");
    free(got);
    free(huge);
}

/* A write error (here EFBIG from a file size limit, as ENOSPC would be) fails the
 * commit with the reason, and neither the final nor the temporary file remains. */
static void test_write_error_fails_commit(void **state)
{
    fixture *f = *state;
    char err[256] = "";
    struct rlimit old, small;
    assert_int_equal(getrlimit(RLIMIT_FSIZE, &old), 0);
    void (*old_handler)(int) = signal(SIGXFSZ, SIG_IGN);
    small = old;
    small.rlim_cur = 16 * 1024;
    assert_int_equal(setrlimit(RLIMIT_FSIZE, &small), 0);

    const char *cols[] = {"i", "text"};
    csv_writer *w = csv_open(f->path, cols, 2, err, sizeof err);
    bool opened = w != NULL;
    bool committed = true;
    if (opened) {
        for (uint64_t i = 0; i < 20000; i++) {
            csv_u64(w, i);
            csv_str(w, "some text to fill the disk");
            csv_end_row(w);
        }
        committed = csv_commit(w, err, sizeof err);
    }
    setrlimit(RLIMIT_FSIZE, &old);
    signal(SIGXFSZ, old_handler);

    assert_true(opened);
    assert_false(committed);
    assert_non_null(strstr(err, strerror(EFBIG)));
    assert_false(fs_exists(f->path));
    assert_int_equal(count_entries(f->dir), 0);
}

/* >>fsutil */

static void test_mkdirs(void **state)
{
    fixture *f = *state;
    char err[256] = "", path[256];
    snprintf(path, sizeof path, "%s/a/b//c/", f->dir);
    assert_true(fs_mkdirs(path, err, sizeof err));
    snprintf(path, sizeof path, "%s/a/b/c", f->dir);
    struct stat st;
    assert_int_equal(stat(path, &st), 0);
    assert_true(S_ISDIR(st.st_mode));
    assert_true(fs_mkdirs(path, err, sizeof err)); /* exists already: fine */

    /* through a regular file: fails, naming the culprit */
    snprintf(path, sizeof path, "%s/a/file", f->dir);
    FILE *fp = fopen(path, "w");
    assert_non_null(fp);
    fclose(fp);
    snprintf(path, sizeof path, "%s/a/file/sub", f->dir);
    assert_false(fs_mkdirs(path, err, sizeof err));
    snprintf(path, sizeof path, "%s/a/file", f->dir);
    assert_non_null(strstr(err, path));
    assert_false(fs_mkdirs(path, err, sizeof err)); /* a file is not a directory */
    assert_false(fs_mkdirs("", err, sizeof err));
}

static void test_remove_tree(void **state)
{
    fixture *f = *state;
    char err[256] = "", path[256], outside[256], link[256];
    snprintf(path, sizeof path, "%s/t/x/y", f->dir);
    assert_true(fs_mkdirs(path, err, sizeof err));
    snprintf(path, sizeof path, "%s/t/x/y/file.csv", f->dir);
    FILE *fp = fopen(path, "w");
    assert_non_null(fp);
    fclose(fp);
    /* a symbolic link to a directory outside the tree: removed, not followed */
    snprintf(outside, sizeof outside, "%s/keep", f->dir);
    assert_true(fs_mkdirs(outside, err, sizeof err));
    snprintf(path, sizeof path, "%s/keep/precious", f->dir);
    fp = fopen(path, "w");
    assert_non_null(fp);
    fclose(fp);
    snprintf(link, sizeof link, "%s/t/x/link", f->dir);
    assert_int_equal(symlink(outside, link), 0);

    snprintf(path, sizeof path, "%s/t", f->dir);
    assert_true(fs_exists(path));
    assert_true(fs_remove_tree(path, err, sizeof err));
    assert_false(fs_exists(path));
    snprintf(path, sizeof path, "%s/keep/precious", f->dir);
    assert_true(fs_exists(path));
    snprintf(path, sizeof path, "%s/t", f->dir);
    assert_true(fs_remove_tree(path, err, sizeof err)); /* gone already: rm -rf */
    assert_false(fs_exists(NULL));
}

/* The reader: what the writer's quoting makes, read back field for field; records
 * that are cut off or malformed are refused. */
static void test_reader(void **state)
{
    (void)state;
    const char text[] = "a,b,c\n1,\"x,y\",\"say \"\"hi\"\"\"\n,\"multi\nline\",\r\n";
    size_t len = sizeof text - 1, pos = 0;
    csv_record r = {0};
    assert_int_equal(csv_next_record(text, len, &pos, &r), 1);
    assert_int_equal(r.n, 3);
    assert_string_equal(r.field[2], "c");
    assert_int_equal(csv_next_record(text, len, &pos, &r), 1);
    assert_int_equal(r.n, 3);
    assert_string_equal(r.field[1], "x,y");
    assert_string_equal(r.field[2], "say \"hi\"");
    assert_int_equal(csv_next_record(text, len, &pos, &r), 1);
    assert_int_equal(r.n, 3);
    assert_string_equal(r.field[0], "");
    assert_string_equal(r.field[1], "multi\nline");
    assert_string_equal(r.field[2], "");
    assert_int_equal(csv_next_record(text, len, &pos, &r), 0);
    static const char *const bad[] = {
        "a,b",            /* no line end: cut off */
        "a,\"b\n",        /* unterminated quote */
        "a,b\"c\n",       /* quote inside an unquoted field */
        "a,\"b\"c\n",      /* text after the closing quote */
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        pos = 0;
        assert_int_equal(csv_next_record(bad[i], strlen(bad[i]), &pos, &r), -1);
        assert_int_equal(pos, 0);
    }
    csv_record_free(&r);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_quoting),
        cmocka_unit_test(test_reader),
        cmocka_unit_test(test_fewest_digits_as_scan),
        cmocka_unit_test_setup_teardown(test_full_file_bytes, setup, teardown),
        cmocka_unit_test_setup_teardown(test_header_quoted, setup, teardown),
        cmocka_unit_test_setup_teardown(test_f64_formatting, setup, teardown),
        cmocka_unit_test_setup_teardown(test_g_round_trip, setup, teardown),
        cmocka_unit_test_setup_teardown(test_too_few_fields_fails, setup, teardown),
        cmocka_unit_test_setup_teardown(test_too_many_fields_fails, setup, teardown),
        cmocka_unit_test_setup_teardown(test_unended_row_fails, setup, teardown),
        cmocka_unit_test_setup_teardown(test_abort_leaves_nothing, setup, teardown),
        cmocka_unit_test_setup_teardown(test_open_fails_with_message, setup, teardown),
        cmocka_unit_test_setup_teardown(test_large_output, setup, teardown),
        cmocka_unit_test_setup_teardown(test_write_error_fails_commit, setup, teardown),
        cmocka_unit_test_setup_teardown(test_mkdirs, setup, teardown),
        cmocka_unit_test_setup_teardown(test_remove_tree, setup, teardown),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
