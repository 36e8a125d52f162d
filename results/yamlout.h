#pragma once
/* A small structured YAML writer over libyaml's emitter (block style, proper
 * quoting), into a file that appears under its final name only on commit.
 * Used for meta.yaml.
 *
 *   yaml_out *y = yo_open("runs/x/meta.yaml", err, sizeof err);
 *   yo_map_begin(y); yo_key(y, "width"); yo_int(y, 64); yo_map_end(y);
 *   yo_commit(y, err, sizeof err);
 *
 * Errors are sticky: after the first failure calls do nothing and commit fails. */
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

typedef struct yaml_out yaml_out;

yaml_out *yo_open(const char *final_path, char *err, size_t errlen);
void yo_map_begin(yaml_out *y);
void yo_map_end(yaml_out *y);
void yo_seq_begin(yaml_out *y);
void yo_seq_end(yaml_out *y);
void yo_key(yaml_out *y, const char *key);
void yo_str(yaml_out *y, const char *v);     /* NULL -> null */
void yo_i64(yaml_out *y, int64_t v);
void yo_f64(yaml_out *y, double v);          /* shortest round-trip; NAN -> .nan, Inf -> .inf */
void yo_bool(yaml_out *y, bool v);
bool yo_commit(yaml_out *y, char *err, size_t errlen);   /* frees y */
void yo_abort(yaml_out *y);                              /* frees y; NULL is fine */
