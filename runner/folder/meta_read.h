#pragma once
/* Reading back what a complete run's meta.yaml says (runner/trial/run_meta.c writes it):
 * the scalars of one top-level block, for merge (the build that made a run) and the
 * answers (the GL device each run was measured on: runner/answer/device_note.h). */
#include <stdbool.h>
#include <stddef.h>

/* out + i * len receives the text of keys[i] in the top-level mapping `block` of
 * RUN_DIR/meta.yaml, cut to len - 1 bytes ("" where the block or the key is missing, or
 * its value is null or not a scalar). False, every value "", when the file cannot be read or
 * is not YAML. */
bool meta_read_block(const char *run_dir, const char *block, const char *const *keys,
                     size_t nkeys, char *out, size_t len);

/* The earliest `started` of the trials in RUN_DIR/meta.yaml (ISO 8601 UTC, which sorts
 * as text) into out; "" and false when the file cannot be read or no trial has one. */
bool meta_read_first_start(const char *run_dir, char *out, size_t len);

/* A device profile read back from the device.yaml at path (results/device_profile.c
 * writes it; docs/notes/device-profile.md): the GL strings and every figure's median,
 * spread and repeats. False, with a message, when the file cannot be read or is not
 * YAML, or holds no figure. */
typedef struct device_profile device_profile;
bool meta_read_profile(const char *path, device_profile *p, char *err, size_t errlen);
