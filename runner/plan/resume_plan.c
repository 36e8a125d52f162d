/* --resume: the plan a resumed sweep would run against the one its folder holds
 * (plan.csv). The manifest's hash and the number of runs are compared by folder.c
 * before the lock; a file scene's run ids also follow the file's content (its hash
 * is in the id), so an edited scene file makes a plan of new ids under the same
 * manifest: resuming would orphan every run of the folder and start over in the
 * same place. That is refused here, naming what changed, and nothing is touched. */
#include "runner/plan/resume_plan.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "results/csvread.h"
#include "runner/manifest/params.h"

static int id_cmp(const void *a, const void *b)
{
    return strcmp(a, b);
}

/* The content hash of a file scene's canonical text ("file:HASH,scale:..."). */
static void scene_file_hash(const char *text, char *out, size_t len)
{
    const char *h = text + strlen("file:");
    size_t n = strcspn(h, ",");
    snprintf(out, len, "%.*s", (int)(n < 64 ? n : 64), h);
}

/* What differs between the folder's row r and run q of the plan: the scene file
 * whose content changed, or the first keys whose text differs. */
static void describe_change(const csv_table *t, size_t r, const run_spec *q, char *out,
                            size_t len)
{
    param_kv kv[PARAM_KV_MAX];
    size_t n = run_params_kv(&q->p, kv, PARAM_KV_MAX);
    size_t shown = 0, more = 0, used = 0;
    out[0] = '\0';
    for (size_t i = 0; i < n; i++) {
        int c = csv_col(t, kv[i].key);
        if (c < 0)
            continue;
        const char *was = csv_get(t, r, c);
        if (strcmp(was, kv[i].value) == 0)
            continue;
        if (shown == 2) {
            more++;
            continue;
        }
        char what[1400];
        if (strcmp(kv[i].key, "scene") == 0 && strncmp(was, "file:", 5) == 0 &&
            strncmp(kv[i].value, "file:", 5) == 0 && q->p.scene_file[0]) {
            char a[80], b[80];
            scene_file_hash(was, a, sizeof a);
            scene_file_hash(kv[i].value, b, sizeof b);
            if (strcmp(a, b) != 0)
                snprintf(what, sizeof what, "scene file %.1000s changed since: its content "
                         "hash was %s, is %s", q->p.scene_file, a, b);
            else
                snprintf(what, sizeof what, "scene was %.200s, is %.200s", was, kv[i].value);
        } else {
            snprintf(what, sizeof what, "%s was %.200s, is %.200s", kv[i].key,
                     was[0] ? was : "(empty)", kv[i].value[0] ? kv[i].value : "(empty)");
        }
        used += (size_t)snprintf(out + used, used < len ? len - used : 0, "%s%s",
                                 shown ? "; " : "", what);
        shown++;
    }
    if (more && used < len)
        snprintf(out + used, len - used, "; and %zu more key%s", more, more == 1 ? "" : "s");
    if (!shown)
        snprintf(out, len, "its run %s is %s in this plan", csv_get(t, r, csv_col(t, "run_id")),
                 q->id);
}

bool resume_plan_check(const char *dir, const plan *p, char *err, size_t errlen)
{
    char path[4200];
    snprintf(path, sizeof path, "%s/plan.csv", dir);
    struct stat st;
    if (stat(path, &st) != 0 && errno == ENOENT)
        return true;   /* killed before its plan was written: no run to orphan */
    csv_table t;
    char why[600];
    if (!csv_read(path, &t, why, sizeof why)) {
        snprintf(err, errlen, "--resume: cannot tell whether %s holds this plan (%s); use "
                 "--force to start over", dir, why);
        return false;
    }
    int cid = csv_col(&t, "run_id"), cindex = csv_col(&t, "index");
    if (cid < 0) {
        snprintf(err, errlen, "--resume: cannot tell whether %s holds this plan (%s has no "
                 "run_id column); use --force to start over", dir, path);
        csv_table_free(&t);
        return false;
    }
    char(*ids)[13] = malloc((p->nruns ? p->nruns : 1) * sizeof *ids);
    if (!ids) {
        snprintf(err, errlen, "--resume: out of memory comparing the plan with %s's", dir);
        csv_table_free(&t);
        return false;
    }
    for (size_t k = 0; k < p->nruns; k++)
        memcpy(ids[k], p->runs[k].id, sizeof ids[k]);
    qsort(ids, p->nruns, sizeof *ids, id_cmp);
    size_t gone = 0, first = 0;
    for (size_t r = 0; r < t.nrows; r++) {
        const char *id = csv_get(&t, r, cid);
        if (strlen(id) == 12 && bsearch(id, ids, p->nruns, sizeof *ids, id_cmp))
            continue;
        if (gone++ == 0)
            first = r;
    }
    free(ids);
    if (gone) {
        /* what changed, told on the first of them against the run at its place */
        char what[2400] = "";
        char *end;
        const char *at = csv_get(&t, first, cindex);
        unsigned long long i = strtoull(at, &end, 10);
        if (at[0] && !*end && i < p->nruns)
            describe_change(&t, first, &p->runs[i], what, sizeof what);
        snprintf(err, errlen, "--resume: the plan differs from %s's: %zu of its %zu runs "
                 "are not in this plan%s%s%s; use --force to start over (nothing was deleted)",
                 dir, gone, t.nrows, what[0] ? " (" : "", what, what[0] ? ")" : "");
    }
    csv_table_free(&t);
    return gone == 0;
}
