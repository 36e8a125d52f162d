#pragma once
/* Output folders that cannot lose anyone's data (docs/architecture.md "Output folders").
 *
 * - Ownership: a folder is shadesweep's only when its sweep.yaml starts with
 *   `format: shadesweep-output 1` (written before anything else). --force, --resume and
 *   merge -o refuse any other non-empty folder, and delete only the names shadesweep
 *   writes (FOLDER_OWN_NAMES below, runs/<id>/ files, their temporary twins).
 * - One writer: flock(LOCK_EX | LOCK_NB) on OUT's own descriptor for the command's
 *   whole life (deleting a file cannot undo it), and OUT/lock, flocked too, holding the
 *   holder's pid. The lock file is never removed.
 * - Completion: a run is complete when runs/<id>/files.txt (written last) lists its
 *   files with their sizes and FNV-1a 64 checksums, they all match, and its summary.csv
 *   parses with this version's header and column count. */
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include "runner/folder/output.h"

#define FOLDER_FORMAT "shadesweep-output 1"

typedef struct folder {
    char dir[4096];
    int lock_fd;               /* OUT/lock, holding the pid; -1: not held */
    int dir_fd;                /* OUT itself, flocked: the lock; -1: not held */
    bool created;              /* this process made the directory */
    bool fresh;                /* it was absent or empty: nothing of anyone's was there */
} folder;

typedef enum folder_mode {
    FOLDER_NEW,                /* must be absent or empty */
    FOLDER_FORCE,              /* a shadesweep folder's own files are removed first */
    FOLDER_RESUME,             /* a shadesweep folder of the same sweep (meta) is kept */
} folder_mode;

/* Opens (creating it when absent), locks and checks an output folder for `cmd`
 * ("run", "merge"); for FOLDER_NEW and FOLDER_FORCE it writes sweep.yaml (meta)
 * before anything else; FOLDER_RESUME compares meta with the folder's sweep.yaml and
 * refuses another manifest, shard, scale or smoke variant. False with a message (the
 * folder is left as it was, and a folder this call created is removed). */
bool folder_open(folder *f, const char *dir, folder_mode mode, const sweep_meta *meta,
                 char *err, size_t errlen);
/* Whether dir is a shadesweep output folder of this format, by the test folder_open
 * (run --resume, --force) applies: sweep.yaml parses, says `format: shadesweep-output 1`
 * and has a manifest hash (in meta). why says what it is otherwise. */
bool folder_is_output(const char *dir, sweep_meta *meta, char *why, size_t whylen);
/* Releases the lock. abandon: the command failed before it wrote any run: a folder
 * that was fresh is emptied of shadesweep's files (and removed if this process made it)
 * so that a plain rerun is not refused. */
void folder_close(folder *f, bool abandon);

/* Removes what a run folder holds of shadesweep's (files.txt first, so that a run cut
 * off while being removed is never taken for complete); keeps anything else, and the
 * folder when something else is in it. */
bool folder_clear_run(const char *run_dir, char *err, size_t errlen);
/* Calls each(dir/name, name, ctx, err, errlen) for every entry of dir ("." and ".."
 * too), in readdir's order, until one returns false; false then, or with "DIR: why"
 * when dir cannot be read. */
typedef bool (*folder_entry_fn)(const char *path, const char *name, void *ctx, char *err,
                                size_t errlen);
bool folder_each(const char *dir, folder_entry_fn each, void *ctx, char *err, size_t errlen);
/* Removes the temporary twins ("NAME.tmp.PID") of shadesweep's files in dir. */
void folder_remove_temp(const char *dir);

/* runs/<id>/files.txt: every file of the run folder but log.txt, with size and checksum. */
bool folder_write_run_files(const char *run_dir, char *err, size_t errlen);

/* The status of a trial that could not write one of its files (a full disk, a
 * read-only or failing device): the run is not complete, whatever else it measured, and
 * --resume runs it again (without --retry-failed). */
#define RUN_STATUS_WRITE "failed:write"

typedef struct run_check {
    size_t rows;               /* summary.csv's data rows */
    bool failed;               /* some row's status is not ok */
    bool unwritten;            /* some row's status is RUN_STATUS_WRITE */
    char status[96];           /* the first such row's status ("" when none failed) */
} run_check;
/* Whether OUT/runs/<id> is complete (see above); why says what is wrong when not.
 * all_files false: only summary.csv is checked against files.txt (the cheap check of
 * a run known to be whole). */
bool folder_check_run(const char *out_dir, const char *id, bool all_files, run_check *c,
                      char *why, size_t whylen);

/* Whether OUT/runs/<id>/trial-<k> holds a complete trial (the same rules as a run:
 * its own files.txt, summary.csv with this run's rows, meta.yaml). */
bool folder_check_trial(const char *out_dir, const char *id, uint32_t trial, run_check *c,
                        char *why, size_t whylen);
/* "trial-<digits>": a trial's folder inside a run's (folder_clear_run removes them). */
bool folder_is_trial_dir(const char *name);

/* st_dev/st_ino of two existing paths name one folder, or one lies inside the other. */
bool folder_overlaps(const char *a, const char *b);

/* Makes sure descriptors 0, 1 and 2 are open (on /dev/null when they were closed), so
 * that no file this program opens becomes "stderr" by accident. */
void folder_std_fds(void);
