/* OUT/summary.csv merged from the complete runs, and the account of a folder's runs
 * (account.h). */
#include "runner/folder/account.h"

#include <stdlib.h>
#include <string.h>

#include "results/csv.h"
#include "results/csvread.h"
#include "common/fsutil.h"
#include "runner/folder/folder.h"
#include "runner/folder/trials.h"

/* Appends the rows of one complete run's summary.csv, each parsed with the right
 * column count, written again field by field; false (nothing appended) when a row
 * does not parse. *e: the run's id, renderer, status and trial counts. */
static bool append_rows(csv_writer *w, const char *path, const char *id, run_account_entry *e)
{
    size_t len = 0;
    int fe;
    char *text = fs_read_all(path, 0, &len, &fe);
    bool ok = text != NULL;
    /* parse everything first: a run goes in whole or not at all */
    csv_record r = {0};
    size_t pos = 0, rows = 0;
    int k = 0;
    for (bool header = true; ok && (k = csv_next_record(text, len, &pos, &r)) > 0; header = false) {
        if (r.n != summary_ncolumns)
            ok = false;
        else if (!header && strcmp(r.field[1], id) != 0)
            ok = false;
        rows += !header;
    }
    ok = ok && k == 0 && rows > 0;
    pos = 0;
    memset(e, 0, sizeof *e);
    snprintf(e->id, sizeof e->id, "%s", id);
    char failure[96] = "";
    for (bool header = true; ok && csv_next_record(text, len, &pos, &r) > 0; header = false) {
        if (header)
            continue;
        for (size_t i = 0; i < r.n; i++)
            csv_str(w, r.field[i]);
        csv_end_row(w);
        const char *st = r.field[summary_ncolumns - 2];
        if (!e->trials++)
            snprintf(e->renderer, sizeof e->renderer, "%s", r.field[2]);
        if (strcmp(st, "ok") == 0)
            e->trials_ok++;
        else if (!failure[0])
            snprintf(failure, sizeof failure, "%s", *st ? st : "unknown");
    }
    trials_run_status(e->trials, e->trials_ok, failure, e->status, sizeof e->status);
    csv_record_free(&r);
    free(text);
    return ok;
}

void output_account_free(run_account *a)
{
    free(a->bad);
    memset(a, 0, sizeof *a);
}

void output_account_counts(const run_account *a, char *buf, size_t len)
{
    int n = snprintf(buf, len, "%zu run%s, %zu failed", a->runs, a->runs == 1 ? "" : "s",
                     a->failed);
    if (a->partial && n >= 0 && (size_t)n < len)
        n += snprintf(buf + n, len - (size_t)n, ", %zu partial", a->partial);
    if (a->missing && n >= 0 && (size_t)n < len)
        snprintf(buf + n, len - (size_t)n, ", %zu not complete", a->missing);
}

void output_account_print(FILE *out, const run_account *a, size_t max)
{
    for (size_t i = 0; i < a->nbad && i < max; i++) {
        const run_account_entry *e = &a->bad[i];
        fprintf(out, "run %s (%s): %s, %zu of %zu trial%s ok\n", e->id, e->renderer, e->status,
                e->trials_ok, e->trials, e->trials == 1 ? "" : "s");
    }
    if (a->nbad > max)
        fprintf(out, "... and %zu more partial or failed runs (summary.csv)\n", a->nbad - max);
}

bool output_merge_summary_ids(const char *out_dir, char (*const ids)[13], size_t nids,
                              run_account *acct, char *err, size_t errlen)
{
    memset(acct, 0, sizeof *acct);
    acct->runs = nids;
    acct->bad = calloc(nids ? nids : 1, sizeof *acct->bad);
    if (!acct->bad) {
        snprintf(err, errlen, "out of memory");
        return false;
    }
    char path[4096];
    snprintf(path, sizeof path, "%s/summary.csv", out_dir);
    csv_writer *w = csv_open(path, summary_columns, summary_ncolumns, err, errlen);
    if (!w) {
        output_account_free(acct);
        return false;
    }
    for (size_t r = 0; r < nids; r++) {
        char run_summary[4096], why[512];
        run_check c;
        run_account_entry *e = &acct->bad[acct->nbad];
        snprintf(run_summary, sizeof run_summary, "%s/runs/%s/summary.csv", out_dir, ids[r]);
        if (!folder_check_run(out_dir, ids[r], false, &c, why, sizeof why) ||
            !append_rows(w, run_summary, ids[r], e)) {
            acct->missing++;
            continue;
        }
        if (strcmp(e->status, "ok") == 0) {
            acct->ok++;
            continue;
        }
        if (trials_status_measured(e->status))
            acct->partial++;
        else
            acct->failed++;
        acct->nbad++;
    }
    if (!csv_commit(w, err, errlen)) {
        output_account_free(acct);
        return false;
    }
    return true;
}

bool output_merge_summary(const char *out_dir, const plan *p, unsigned shard,
                          run_account *acct, char *err, size_t errlen)
{
    char(*ids)[13] = calloc(p->nruns ? p->nruns : 1, sizeof *ids);
    if (!ids) {
        snprintf(err, errlen, "out of memory");
        return false;
    }
    size_t n = 0;
    for (size_t r = 0; r < p->nruns; r++)
        if (!shard || p->runs[r].shard == shard)
            memcpy(ids[n++], p->runs[r].id, 13);
    bool ok = output_merge_summary_ids(out_dir, ids, n, acct, err, errlen);
    free(ids);
    return ok;
}
