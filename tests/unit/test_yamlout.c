/* YAML writer: a nested document read back through libyaml's parser, scalar by
 * scalar, with the style each came back in (plain or quoted decides its type),
 * plus the commit/abort life cycle and sticky misuse errors. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <dirent.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <yaml.h>

#include "common/fsutil.h"
#include "results/yamlout.h"
#include "tests/unit/tempdir.h"

typedef struct fixture {
    char dir[64];
    char path[128];
    yaml_document_t doc;
    bool loaded;
} fixture;

static int setup(void **state)
{
    fixture *f = calloc(1, sizeof *f);
    if (f == NULL)
        return -1;
    if (temp_dir_make(f->dir, sizeof f->dir, "test_yamlout") != 0) {
        free(f);
        return -1;
    }
    snprintf(f->path, sizeof f->path, "%s/meta.yaml", f->dir);
    *state = f;
    return 0;
}

static int teardown(void **state)
{
    fixture *f = *state;
    char err[256];
    if (f->loaded)
        yaml_document_delete(&f->doc);
    bool ok = fs_remove_tree(f->dir, err, sizeof err);
    free(f);
    return ok ? 0 : -1;
}


/* Loads f->path into f->doc with libyaml's parser; returns the root node. */
static yaml_node_t *load(fixture *f)
{
    FILE *fp = fopen(f->path, "rb");
    assert_non_null(fp);
    yaml_parser_t parser;
    assert_true(yaml_parser_initialize(&parser));
    yaml_parser_set_input_file(&parser, fp);
    int ok = yaml_parser_load(&parser, &f->doc);
    if (!ok)
        print_error("parse error: %s at line %zu\n", parser.problem ? parser.problem : "?",
                    parser.problem_mark.line + 1);
    yaml_parser_delete(&parser);
    fclose(fp);
    assert_true(ok);
    f->loaded = true;
    yaml_node_t *root = yaml_document_get_root_node(&f->doc);
    assert_non_null(root);
    return root;
}

/* Value node of key in mapping node m (the key compared as text). */
static yaml_node_t *get(fixture *f, yaml_node_t *m, const char *key)
{
    assert_non_null(m);
    assert_int_equal(m->type, YAML_MAPPING_NODE);
    for (yaml_node_pair_t *p = m->data.mapping.pairs.start; p < m->data.mapping.pairs.top; p++) {
        yaml_node_t *k = yaml_document_get_node(&f->doc, p->key);
        assert_int_equal(k->type, YAML_SCALAR_NODE);
        if (strcmp((const char *)k->data.scalar.value, key) == 0)
            return yaml_document_get_node(&f->doc, p->value);
    }
    print_error("key '%s' not found\n", key);
    fail();
    return NULL;
}

static yaml_node_t *item(fixture *f, yaml_node_t *s, size_t i)
{
    assert_non_null(s);
    assert_int_equal(s->type, YAML_SEQUENCE_NODE);
    assert_true(i < (size_t)(s->data.sequence.items.top - s->data.sequence.items.start));
    return yaml_document_get_node(&f->doc, s->data.sequence.items.start[i]);
}

static size_t seq_len(yaml_node_t *s)
{
    assert_int_equal(s->type, YAML_SEQUENCE_NODE);
    return (size_t)(s->data.sequence.items.top - s->data.sequence.items.start);
}

/* A scalar that reads back as this exact text in this style (plain: a number, bool,
 * null or safe string; quoted: a string whatever it looks like). */
static void check_scalar(yaml_node_t *n, const char *text, bool plain)
{
    assert_non_null(n);
    assert_int_equal(n->type, YAML_SCALAR_NODE);
    assert_int_equal(n->data.scalar.length, strlen(text));
    assert_memory_equal(n->data.scalar.value, text, strlen(text));
    if (plain)
        assert_int_equal(n->data.scalar.style, YAML_PLAIN_SCALAR_STYLE);
    else
        assert_int_not_equal(n->data.scalar.style, YAML_PLAIN_SCALAR_STYLE);
}

/* Strings that a plain scalar would turn into something else, or lose. */
static const char *const needs_quotes[] = {
    "1",      "true",  "null",  "",      " x",    "a: b",   "#c",  "x ",   "~",
    "1.5",    "0x10",  "yes",   "No",    "NULL",  "off",    "y",   ".inf", "-.inf",
    ".nan",   "nan",   "-",     "- a",   "[a]",   "{a}",    "*x",  "&x",   "!x",
    "|",      ">",     "%x",    "@x",    "`x",    "'q'",    "\"dq\"", "line\nbreak",
    "tab\there", "with # hash", "a:b", "2024-01-01", "1e5", "+1", "12:30", "caf\xc3\xa9",
    NULL,
};
/* Strings that stay plain (and still read back as strings). */
static const char *const plain_ok[] = {
    "shadesweep", "forward-spml", "plain words", "/usr/lib/x.so", "Mesa llvmpipe (LLVM 15.0.7)",
    "a.b_c", "x1280", NULL,
};

static void write_document(const char *path)
{
    char err[256] = "";
    yaml_out *y = yo_open(path, err, sizeof err);
    assert_non_null(y);
    yo_map_begin(y);
    yo_key(y, "name");
    yo_str(y, "shadesweep");
    yo_key(y, "width");
    yo_i64(y, 1280);
    yo_key(y, "min");
    yo_i64(y, INT64_MIN);
    yo_key(y, "ratio");
    yo_f64(y, 0.1);
    yo_key(y, "one");
    yo_f64(y, 1.0);
    yo_key(y, "hundred");
    yo_f64(y, 100.0);
    yo_key(y, "big");
    yo_f64(y, 1e20);
    yo_key(y, "tiny");
    yo_f64(y, 1e-300);
    yo_key(y, "third");
    yo_f64(y, 1.0 / 3.0);
    yo_key(y, "nan");
    yo_f64(y, NAN);
    yo_key(y, "pinf");
    yo_f64(y, INFINITY);
    yo_key(y, "ninf");
    yo_f64(y, -INFINITY);
    yo_key(y, "yes");
    yo_bool(y, true);
    yo_key(y, "no");
    yo_bool(y, false);
    yo_key(y, "missing");
    yo_str(y, NULL);
    yo_key(y, "1");
    yo_str(y, "key that looks like a number");
    yo_key(y, "quoted");
    yo_seq_begin(y);
    for (size_t i = 0; needs_quotes[i] != NULL; i++)
        yo_str(y, needs_quotes[i]);
    yo_seq_end(y);
    yo_key(y, "plain");
    yo_seq_begin(y);
    for (size_t i = 0; plain_ok[i] != NULL; i++)
        yo_str(y, plain_ok[i]);
    yo_seq_end(y);
    yo_key(y, "nested");
    yo_map_begin(y);
    yo_key(y, "list");
    yo_seq_begin(y);
    yo_i64(y, 1);
    yo_map_begin(y);
    yo_key(y, "a");
    yo_i64(y, 2);
    yo_map_end(y);
    yo_seq_begin(y);
    yo_f64(y, -2.5);
    yo_seq_end(y);
    yo_seq_end(y);
    yo_key(y, "empty_map");
    yo_map_begin(y);
    yo_map_end(y);
    yo_key(y, "empty_seq");
    yo_seq_begin(y);
    yo_seq_end(y);
    yo_map_end(y);
    yo_map_end(y);
    /* nothing appears before commit */
    assert_false(fs_exists(path));
    assert_true(yo_commit(y, err, sizeof err));
}

static void test_document_round_trip(void **state)
{
    fixture *f = *state;
    write_document(f->path);
    assert_true(fs_exists(f->path));
    assert_int_equal(count_entries(f->dir), 1); /* no temp file left */

    yaml_node_t *root = load(f);
    check_scalar(get(f, root, "name"), "shadesweep", true);
    check_scalar(get(f, root, "width"), "1280", true);
    check_scalar(get(f, root, "min"), "-9223372036854775808", true);
    check_scalar(get(f, root, "ratio"), "0.1", true);
    check_scalar(get(f, root, "one"), "1.0", true);
    check_scalar(get(f, root, "hundred"), "100.0", true);
    check_scalar(get(f, root, "big"), "1.0e+20", true);
    check_scalar(get(f, root, "tiny"), "1.0e-300", true);
    check_scalar(get(f, root, "third"), "0.3333333333333333", true);
    assert_true(strtod((const char *)get(f, root, "third")->data.scalar.value, NULL) ==
                1.0 / 3.0);
    check_scalar(get(f, root, "nan"), ".nan", true);
    check_scalar(get(f, root, "pinf"), ".inf", true);
    check_scalar(get(f, root, "ninf"), "-.inf", true);
    check_scalar(get(f, root, "yes"), "true", true);
    check_scalar(get(f, root, "no"), "false", true);
    check_scalar(get(f, root, "missing"), "null", true);
    check_scalar(get(f, root, "1"), "key that looks like a number", true);

    /* the key "1" itself came back quoted */
    yaml_node_pair_t *p = root->data.mapping.pairs.start;
    bool seen = false;
    for (; p < root->data.mapping.pairs.top; p++) {
        yaml_node_t *k = yaml_document_get_node(&f->doc, p->key);
        if (strcmp((const char *)k->data.scalar.value, "1") == 0) {
            assert_int_not_equal(k->data.scalar.style, YAML_PLAIN_SCALAR_STYLE);
            seen = true;
        }
    }
    assert_true(seen);

    yaml_node_t *q = get(f, root, "quoted");
    size_t nq = 0;
    while (needs_quotes[nq] != NULL)
        nq++;
    assert_int_equal(seq_len(q), nq);
    for (size_t i = 0; i < nq; i++)
        check_scalar(item(f, q, i), needs_quotes[i], false);

    yaml_node_t *pl = get(f, root, "plain");
    size_t np = 0;
    while (plain_ok[np] != NULL)
        np++;
    assert_int_equal(seq_len(pl), np);
    for (size_t i = 0; i < np; i++)
        check_scalar(item(f, pl, i), plain_ok[i], true);

    yaml_node_t *nested = get(f, root, "nested");
    yaml_node_t *list = get(f, nested, "list");
    assert_int_equal(seq_len(list), 3);
    check_scalar(item(f, list, 0), "1", true);
    check_scalar(get(f, item(f, list, 1), "a"), "2", true);
    check_scalar(item(f, item(f, list, 2), 0), "-2.5", true);
    yaml_node_t *em = get(f, nested, "empty_map");
    assert_int_equal(em->type, YAML_MAPPING_NODE);
    assert_true(em->data.mapping.pairs.top == em->data.mapping.pairs.start);
    assert_int_equal(seq_len(get(f, nested, "empty_seq")), 0);
}

/* Block style: the file is readable line by line (a spot check of the layout). */
static void test_block_style(void **state)
{
    fixture *f = *state;
    char err[256];
    yaml_out *y = yo_open(f->path, err, sizeof err);
    assert_non_null(y);
    yo_map_begin(y);
    yo_key(y, "renderer");
    yo_str(y, "deferred");
    yo_key(y, "passes");
    yo_seq_begin(y);
    yo_str(y, "gbuffer");
    yo_str(y, "lighting");
    yo_seq_end(y);
    yo_key(y, "width");
    yo_i64(y, 64);
    yo_map_end(y);
    assert_true(yo_commit(y, err, sizeof err));

    FILE *fp = fopen(f->path, "rb");
    assert_non_null(fp);
    char buf[512];
    size_t n = fread(buf, 1, sizeof buf - 1, fp);
    fclose(fp);
    buf[n] = '\0';
    assert_string_equal(buf, "renderer: deferred\n"
                             "passes:\n"
                             "- gbuffer\n"
                             "- lighting\n"
                             "width: 64\n");
}

static void test_abort_leaves_nothing(void **state)
{
    fixture *f = *state;
    char err[256];
    yaml_out *y = yo_open(f->path, err, sizeof err);
    assert_non_null(y);
    yo_map_begin(y);
    yo_key(y, "a");
    yo_i64(y, 1);
    yo_map_end(y);
    assert_int_equal(count_entries(f->dir), 1); /* the temporary file */
    yo_abort(y);
    assert_false(fs_exists(f->path));
    assert_int_equal(count_entries(f->dir), 0);
    yo_abort(NULL);
}

/* Each misuse fails at commit, with a message, and leaves no file. */
static void test_misuse_is_sticky(void **state)
{
    fixture *f = *state;
    char err[256];
    for (int c = 0; c < 6; c++) {
        yaml_out *y = yo_open(f->path, err, sizeof err);
        assert_non_null(y);
        const char *want = NULL;
        switch (c) {
        case 0: /* key at the root */
            yo_key(y, "a");
            want = "outside a mapping";
            break;
        case 1: /* value where a key is expected */
            yo_map_begin(y);
            yo_str(y, "v");
            yo_map_end(y);
            want = "expects a key";
            break;
        case 2: /* mapping never closed */
            yo_map_begin(y);
            yo_key(y, "a");
            yo_i64(y, 1);
            want = "not closed";
            break;
        case 3: /* wrong end */
            yo_seq_begin(y);
            yo_map_end(y);
            yo_seq_end(y);
            want = "without a matching begin";
            break;
        case 4: /* two roots */
            yo_i64(y, 1);
            yo_i64(y, 2);
            want = "after the document's root";
            break;
        default: /* nothing at all */
            want = "empty document";
            break;
        }
        err[0] = '\0';
        assert_false(yo_commit(y, err, sizeof err));
        if (strstr(err, want) == NULL) {
            print_error("case %d: '%s' lacks '%s'\n", c, err, want);
            fail();
        }
        assert_false(fs_exists(f->path));
        assert_int_equal(count_entries(f->dir), 0);
    }
}

static void test_open_fails(void **state)
{
    fixture *f = *state;
    char err[256] = "";
    char path[256];
    snprintf(path, sizeof path, "%s/no/such/dir/meta.yaml", f->dir);
    assert_null(yo_open(path, err, sizeof err));
    assert_non_null(strstr(err, path));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(test_document_round_trip, setup, teardown),
        cmocka_unit_test_setup_teardown(test_block_style, setup, teardown),
        cmocka_unit_test_setup_teardown(test_abort_leaves_nothing, setup, teardown),
        cmocka_unit_test_setup_teardown(test_misuse_is_sticky, setup, teardown),
        cmocka_unit_test_setup_teardown(test_open_fails, setup, teardown),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
