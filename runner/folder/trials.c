/* A run's files merged from its trials' folders (trials.h). */
#define _DEFAULT_SOURCE
#include "runner/folder/trials.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "common/fsutil.h"
#include "results/jsonout.h"
#include "runner/folder/folder.h"

/* The CSVs a trial may have, merged by rows (summary.csv last: the other merges can fail
 * first without a run that looks summarised). */
static const char *const csv_parts[] = {
    "frames.csv", "seconds.csv", "passes.csv", "convergence.csv", "errors.csv",
    "coverage.csv", "lightgrid.csv", "summary.csv",
};
#define NPARTS (sizeof csv_parts / sizeof csv_parts[0])

const char *trials_run_status(size_t trials, size_t ok, const char *failure, char *out,
                              size_t len)
{
    if (!failure || !*failure)
        failure = "failed:not-run";
    if (trials && ok >= trials)
        snprintf(out, len, "ok");
    else if (ok)
        snprintf(out, len, "partial:%s",
                 strncmp(failure, "failed:", 7) == 0 ? failure + 7 : failure);
    else
        snprintf(out, len, "%s", failure);
    return out;
}

bool trials_status_measured(const char *status)
{
    return strcmp(status, "ok") == 0 || strncmp(status, "partial:", 8) == 0;
}

static void trial_path(char *dst, size_t len, const char *run_dir, uint32_t k, const char *name)
{
    snprintf(dst, len, "%s/trial-%u/%s", run_dir, k, name);
}

/* Copies in to out, without its first line when skip_header (our headers hold no
 * quoted newline); false on a failure, its errno in *err_no and *writing true when the
 * write failed (else the read). */
static bool copy_rows(FILE *in, FILE *out, bool skip_header, int *err_no, bool *writing)
{
    int c;
    if (skip_header)
        while ((c = getc(in)) != EOF && c != '\n')
            ;
    char buf[1 << 16];
    size_t n;
    errno = 0;
    while ((n = fread(buf, 1, sizeof buf, in)) > 0)
        if (fwrite(buf, 1, n, out) != n) {
            *err_no = errno ? errno : EIO;
            *writing = true;
            return false;
        }
    *err_no = errno ? errno : EIO;
    *writing = false;
    return !ferror(in);
}

/* run_dir/name from the trials' copies, header once; nothing when no trial has one. */
static bool merge_csv(const char *run_dir, const char *name, uint32_t n, char *err,
                      size_t errlen)
{
    afile out = {0};
    bool open = false;
    char path[4600];
    for (uint32_t k = 1; k <= n; k++) {
        trial_path(path, sizeof path, run_dir, k, name);
        FILE *in = fopen(path, "rb");
        if (!in) {
            if (errno == ENOENT)
                continue;
            snprintf(err, errlen, "%s: %s", path, strerror(errno));
            if (open)
                afile_abort(&out);
            return false;
        }
        if (!open) {
            char final[4400];
            snprintf(final, sizeof final, "%s/%s", run_dir, name);
            if (!afile_open(&out, final, err, errlen)) {
                fclose(in);
                return false;
            }
        }
        int why = 0;
        bool writing = false;
        bool ok = copy_rows(in, out.fp, open, &why, &writing);
        fclose(in);
        open = true;
        if (!ok) {   /* the file that failed and why: "No space left on device" */
            if (writing)
                snprintf(err, errlen, "%s/%s: %s (copying %s's rows)", run_dir, name,
                         strerror(why), path);
            else
                snprintf(err, errlen, "%s: %s (copying its rows into the run's %s)", path,
                         strerror(why), name);
            afile_abort(&out);
            return false;
        }
    }
    return !open || afile_commit(&out, err, errlen);
}

static bool is_csv_part(const char *name)
{
    for (size_t i = 0; i < NPARTS; i++)
        if (strcmp(name, csv_parts[i]) == 0)
            return true;
    return false;
}

/* The trial's other files (images) linked into the run's folder: the trial folder keeps
 * its own, so that a merge cut off here can be done again. Their names carry the trial. */
static bool link_files(const char *run_dir, uint32_t k, char *err, size_t errlen)
{
    char list[4600];
    trial_path(list, sizeof list, run_dir, k, "files.txt");
    size_t len;
    int e;
    char *text = fs_read_all(list, 0, &len, &e);
    if (!text) {
        snprintf(err, errlen, "%s: %s", list, strerror(e));
        return false;
    }
    bool ok = true;
    char *save = NULL;
    for (char *line = strtok_r(text, "\n", &save); ok && line; line = strtok_r(NULL, "\n", &save)) {
        char name[256];
        if (line[0] == '#' || sscanf(line, "%255s", name) != 1 || is_csv_part(name) ||
            strcmp(name, "meta.yaml") == 0)
            continue;
        char src[4600], dst[4600];
        trial_path(src, sizeof src, run_dir, k, name);
        snprintf(dst, sizeof dst, "%s/%s", run_dir, name);
        if (link(src, dst) != 0 && !(errno == EEXIST && unlink(dst) == 0 && link(src, dst) == 0)) {
            snprintf(err, errlen, "%s: cannot link it into the run's folder: %s", src,
                     strerror(errno));
            ok = false;
        }
    }
    free(text);
    return ok;
}

/* The value of a top-level `key: value` line of a meta.yaml text (as written, quotes and
 * all), or "" when absent. */
static void top_value(const char *text, const char *key, char *out, size_t len)
{
    size_t kl = strlen(key);
    out[0] = 0;
    for (const char *line = text; line && *line; line = strchr(line, '\n') ? strchr(line, '\n') + 1 : NULL) {
        if (strncmp(line, key, kl) == 0 && line[kl] == ':' && line[kl + 1] == ' ') {
            const char *v = line + kl + 2, *end = strchr(v, '\n');
            size_t n = end ? (size_t)(end - v) : strlen(v);
            snprintf(out, len, "%.*s", (int)(n < len ? n : len - 1), v);
            return;
        }
    }
}

static char *read_meta(const char *run_dir, uint32_t k, char *err, size_t errlen)
{
    char path[4600];
    trial_path(path, sizeof path, run_dir, k, "meta.yaml");
    size_t len;
    int e;
    char *text = fs_read_all(path, 1u << 24, &len, &e);
    if (!text)
        snprintf(err, errlen, "%s: %s", path, strerror(e));
    return text;
}

/* The lines of a top-level block `key:` of a meta.yaml text (the indented lines after
 * it, each with its newline), malloc'd; NULL when absent or out of memory. */
static char *top_block(const char *text, const char *key)
{
    size_t kl = strlen(key);
    for (const char *line = text; line && *line; line = strchr(line, '\n') ? strchr(line, '\n') + 1 : NULL) {
        if (strncmp(line, key, kl) != 0 || line[kl] != ':' || line[kl + 1] != '\n')
            continue;
        const char *start = line + kl + 2, *end = start;
        while (*end == ' ') {
            const char *nl = strchr(end, '\n');
            end = nl ? nl + 1 : end + strlen(end);
        }
        return strndup(start, (size_t)(end - start));
    }
    return NULL;
}

/* What meta.yaml's `trials` list says of one trial: its top-level values as written,
 * how it loaded its scene (its scene_load block; each trial loads its own) and its GPU
 * clocks (its clocks block, NVML's: runner/trial/run_clocks.c; NULL without). */
typedef struct trial_meta {
    char status[160], started[128], finished[128];
    char *scene_load, *clocks;
} trial_meta;

/* A trial's block `key:` (top_block's lines) inside its entry of the `trials` list. */
static void put_block(FILE *fp, const char *key, const char *block)
{
    if (!block)
        return;
    fprintf(fp, "    %s:\n", key);
    for (const char *l = block; *l;) {
        const char *nl = strchr(l, '\n');
        size_t len = nl ? (size_t)(nl - l) + 1 : strlen(l);
        fprintf(fp, "    %.*s", (int)len, l);
        l += len;
    }
}

/* meta.yaml: trial 1's with the run's status and the last trial's end, then how the
 * trials were scheduled and what became of each. Each trial's meta.yaml is read once. */
static bool merge_meta(const char *run_dir, uint32_t n, const char *status,
                       const trials_schedule *sched, char *err, size_t errlen)
{
    char *first = NULL;
    trial_meta *tm = calloc(n ? n : 1, sizeof *tm);
    bool ok = tm != NULL;
    if (!ok)
        snprintf(err, errlen, "%s: out of memory", run_dir);
    for (uint32_t k = 1; ok && k <= n; k++) {
        char *m = read_meta(run_dir, k, err, errlen);
        if (!(ok = m != NULL))
            break;
        top_value(m, "status", tm[k - 1].status, sizeof tm[k - 1].status);
        top_value(m, "started", tm[k - 1].started, sizeof tm[k - 1].started);
        top_value(m, "finished", tm[k - 1].finished, sizeof tm[k - 1].finished);
        tm[k - 1].scene_load = top_block(m, "scene_load");
        tm[k - 1].clocks = top_block(m, "clocks");
        if (k == 1)
            first = m;   /* the run's meta.yaml is made from it */
        else
            free(m);
    }
    char final[4400];
    snprintf(final, sizeof final, "%s/meta.yaml", run_dir);
    afile out;
    if (!ok || !afile_open(&out, final, err, errlen)) {
        free(first);
        for (uint32_t k = 0; tm && k < n; k++) {
            free(tm[k].scene_load);
            free(tm[k].clocks);
        }
        free(tm);
        return false;
    }
    const char *finished = tm[n - 1].finished;
    bool in_clocks = false;   /* trial 1's clocks: not the run's, each trial's below */
    for (char *line = first; *line;) {
        char *nl = strchr(line, '\n');
        size_t len = nl ? (size_t)(nl - line) + 1 : strlen(line);
        in_clocks = strncmp(line, "clocks:\n", 8) == 0 || (in_clocks && line[0] == ' ');
        if (in_clocks) {
            /* left out */
        } else if (strncmp(line, "status: ", 8) == 0) {
            fputs("status: ", out.fp);
            json_quoted(out.fp, status, strlen(status), true);
            fputc('\n', out.fp);
        } else if (strncmp(line, "finished: ", 10) == 0 && finished[0]) {
            fprintf(out.fp, "finished: %s\n", finished);
        } else {
            fwrite(line, 1, len, out.fp);
        }
        line += len;
    }
    free(first);
    fprintf(out.fp, "schedule:\n  mode: %s\n  seed: %u\n  point: %zu\n", sched->mode,
            sched->seed, sched->point);
    fputs("trials:\n", out.fp);
    for (uint32_t k = 1; k <= n; k++) {
        const trial_meta *t = &tm[k - 1];
        fprintf(out.fp, "  - trial: %u\n    order: %u\n    status: %s\n    started: %s\n"
                "    finished: %s\n", k, sched->order ? sched->order[k - 1] : 0,
                t->status[0] ? t->status : "\"\"", t->started[0] ? t->started : "\"\"",
                t->finished[0] ? t->finished : "\"\"");
        put_block(out.fp, "scene_load", t->scene_load);
        put_block(out.fp, "clocks", t->clocks);
    }
    for (uint32_t k = 0; k < n; k++) {
        free(tm[k].scene_load);
        free(tm[k].clocks);
    }
    free(tm);
    return afile_commit(&out, err, errlen);
}

bool trials_merge(const char *out_dir, const char *id, uint32_t n, const char *status,
                  const trials_schedule *sched, char *err, size_t errlen)
{
    char run_dir[4200];
    snprintf(run_dir, sizeof run_dir, "%s/runs/%s", out_dir, id);
    /* files.txt first: a run cut off while merging is never taken for complete; and the
     * temporary twins an earlier merge left when it was killed (the folder's lock is
     * ours, so no one else is writing them) */
    folder_remove_temp(run_dir);
    char path[4400];
    snprintf(path, sizeof path, "%s/files.txt", run_dir);
    if (unlink(path) != 0 && errno != ENOENT) {
        snprintf(err, errlen, "%s: %s", path, strerror(errno));
        return false;
    }
    for (size_t i = 0; i < NPARTS; i++)
        if (!merge_csv(run_dir, csv_parts[i], n, err, errlen))
            return false;
    for (uint32_t k = 1; k <= n; k++)
        if (!link_files(run_dir, k, err, errlen))
            return false;
    if (!merge_meta(run_dir, n, status, sched, err, errlen) ||
        !folder_write_run_files(run_dir, err, errlen))
        return false;
    /* complete: the trial folders are no longer needed (a failure to remove one is
     * harmless: --force and a rerun remove them) */
    for (uint32_t k = 1; k <= n; k++) {
        char dir[4400], why[512];
        snprintf(dir, sizeof dir, "%s/trial-%u", run_dir, k);
        folder_clear_run(dir, why, sizeof why);
    }
    return true;
}
