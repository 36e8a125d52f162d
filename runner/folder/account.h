#pragma once
/* What an output folder's runs came to: OUT/summary.csv merged from the complete runs'
 * own rows (folder_check_run says which are complete) and each run's status
 * (trials_run_status), counted. Above output.h, folder.h and trials.h: the folder's
 * files are written below it, their account is taken here. */
#include <stddef.h>
#include <stdio.h>

#include "runner/folder/output.h"

/* What a folder's runs came to: each complete run's status (trials_run_status, from
 * its summary.csv rows), counted, and the runs that are not ok named. */
typedef struct run_account_entry {
    char id[13], renderer[32], status[96];
    size_t trials, trials_ok;
} run_account_entry;
typedef struct run_account {
    size_t runs;               /* the runs asked about (complete or not) */
    size_t ok, partial, failed, missing;   /* missing: not complete (left out) */
    run_account_entry *bad;    /* the partial and failed runs, in plan order */
    size_t nbad;
} run_account;
void output_account_free(run_account *a);
/* "N runs, F failed[, P partial][, M not complete]" into buf. */
void output_account_counts(const run_account *a, char *buf, size_t len);
/* A line per partial or failed run ("run ID (renderer): STATUS, K of N trials ok"), at
 * most `max` of them (then how many more). */
void output_account_print(FILE *out, const run_account *a, size_t max);

/* OUT/summary.csv rebuilt from the runs' own summary.csv files, in plan order, from
 * rows parsed with this version's column count only; runs of other shards, and runs
 * that are not complete (folder_check_run), are left out. *acct says what the folder
 * holds (free it with output_account_free; on failure it holds nothing). */
bool output_merge_summary(const char *out_dir, const plan *p, unsigned shard,
                          run_account *acct, char *err, size_t errlen);
/* The same from a list of run ids (plan order). */
bool output_merge_summary_ids(const char *out_dir, char (*const ids)[13], size_t nids,
                              run_account *acct, char *err, size_t errlen);
