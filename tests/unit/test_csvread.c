/* results/csvread.c: the CSVs shadesweep writes read back exactly (quotes, doubled
 * quotes, embedded newlines, CR LF, short rows padded), and broken files refused with
 * the file, line and reason. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "results/csv.h"
#include "results/csvread.h"

static char path[64];

static void write_file(const char *text)
{
    FILE *f = fopen(path, "wb");
    assert_non_null(f);
    fputs(text, f);
    fclose(f);
}

static int setup(void **state)
{
    (void)state;
    snprintf(path, sizeof path, "/tmp/test_csvread.%ld.csv", (long)getpid());
    return 0;
}

static int teardown(void **state)
{
    (void)state;
    unlink(path);
    return 0;
}

static void test_quoting_round_trip(void **state)
{
    (void)state;
    static const char *const cols[] = {"a", "b", "c"};
    char err[256];
    csv_writer *w = csv_open(path, cols, 3, err, sizeof err);
    assert_non_null(w);
    csv_str(w, "x,y");
    csv_str(w, "say \"hi\"");
    csv_str(w, "two\nlines");
    assert_true(csv_end_row(w));
    csv_f64(w, 1.5, 3);
    csv_f64(w, NAN, 3);
    csv_str(w, " padded ");
    assert_true(csv_end_row(w));
    assert_true(csv_commit(w, err, sizeof err));
    csv_table t;
    assert_true(csv_read(path, &t, err, sizeof err));
    assert_int_equal(t.ncols, 3);
    assert_int_equal(t.nrows, 2);
    assert_int_equal(csv_col(&t, "c"), 2);
    assert_int_equal(csv_col(&t, "d"), -1);
    assert_string_equal(csv_get(&t, 0, 0), "x,y");
    assert_string_equal(csv_get(&t, 0, 1), "say \"hi\"");
    assert_string_equal(csv_get(&t, 0, 2), "two\nlines");
    assert_true(csv_num(&t, 1, 0) == 1.5);
    assert_string_equal(csv_get(&t, 1, 1), "");
    assert_true(isnan(csv_num(&t, 1, 1)));
    assert_string_equal(csv_get(&t, 1, 2), " padded ");
    assert_string_equal(csv_get(&t, 1, -1), "");
    assert_true(isnan(csv_num(&t, 0, 0)));   /* "x,y" is not a number */
    csv_table_free(&t);
}

static void test_crlf(void **state)
{
    (void)state;
    write_file("k,v,w\r\n1,2,3\r\n4,,\r\n");
    csv_table t;
    char err[256];
    assert_true(csv_read(path, &t, err, sizeof err));
    assert_int_equal(t.ncols, 3);
    assert_int_equal(t.nrows, 2);
    assert_string_equal(t.header[2], "w");
    assert_string_equal(csv_get(&t, 0, 2), "3");
    assert_string_equal(csv_get(&t, 1, 0), "4");
    assert_string_equal(csv_get(&t, 1, 1), "");
    csv_table_free(&t);
}

/* csv_index: the rows of a key in file order, none for an absent key, and an empty
 * index for an absent column. */
static void test_index(void **state)
{
    (void)state;
    write_file("id,v\nb,0\na,1\nb,2\nc,3\nb,4\n");
    csv_table t;
    char err[256];
    assert_true(csv_read(path, &t, err, sizeof err));
    csv_index ix;
    assert_true(csv_index_build(&ix, &t, "id"));
    size_t first;
    assert_int_equal(csv_index_find(&ix, "b", &first), 3);
    for (size_t k = 0; k < 3; k++)
        assert_int_equal(ix.item[first + k].row, 2 * k);   /* rows 0, 2, 4 */
    assert_int_equal(csv_index_find(&ix, "a", &first), 1);
    assert_int_equal(ix.item[first].row, 1);
    assert_int_equal(csv_index_find(&ix, "bb", &first), 0);
    assert_int_equal(csv_index_find(&ix, "", &first), 0);
    csv_index_free(&ix);
    assert_true(csv_index_build(&ix, &t, "no-such-column"));
    assert_int_equal(csv_index_find(&ix, "b", &first), 0);
    csv_index_free(&ix);
    csv_table_free(&t);
}

static void expect_error(const char *text, const char *want)
{
    write_file(text);
    csv_table t;
    char err[256], full[320];
    assert_false(csv_read(path, &t, err, sizeof err));
    snprintf(full, sizeof full, "%s:%s", path, want);
    assert_string_equal(err, full);
    assert_int_equal(t.nrows, 0);
    assert_null(t.rows);
}

static void test_errors(void **state)
{
    (void)state;
    expect_error("", "1: empty (no header)");
    expect_error("a,b\n1,2,3\n", "2: a row whose field count differs from the header's");
    expect_error("a,b\n1,2\n3\n", "3: a row whose field count differs from the header's");
    expect_error("a,b\n1,\"open\n", "2: a malformed or cut-off row");
    /* a last row without its line end: a file cut off mid-row, never a short row */
    expect_error("a,b\n1,2\n3,4", "3: a malformed or cut-off row");
    csv_table t;
    char err[256];
    unlink(path);
    assert_false(csv_read(path, &t, err, sizeof err));
    char want[320];
    snprintf(want, sizeof want, "%s: No such file or directory", path);
    assert_string_equal(err, want);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(test_quoting_round_trip, setup, teardown),
        cmocka_unit_test_setup_teardown(test_crlf, setup, teardown),
        cmocka_unit_test_setup_teardown(test_index, setup, teardown),
        cmocka_unit_test_setup_teardown(test_errors, setup, teardown),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
