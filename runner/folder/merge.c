#include "runner/folder/merge.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "common/fsutil.h"
#include "common/grow.h"
#include "runner/folder/folder.h"
#include "runner/folder/account.h"
#include "runner/folder/meta_read.h"
#include "runner/folder/output.h"

/* The whole file into a NUL-terminated buffer (caller frees); NULL with a message. */
static char *slurp(const char *path, size_t *len, char *err, size_t errlen)
{
    int e;
    char *buf = fs_read_all(path, 0, len, &e);
    if (!buf)
        snprintf(err, errlen, "%s: %s", path, strerror(e));
    return buf;
}

/* Run ids in plan order: the second field of each data row (ids are hex: no quoting). */
static bool plan_ids(const char *plan_text, char (**ids)[13], size_t *n, char *err, size_t errlen)
{
    size_t cap = 0;
    *n = 0;
    *ids = NULL;
    for (const char *line = strchr(plan_text, '\n'); line && line[1];
         line = strchr(line + 1, '\n')) {
        const char *c1 = strchr(line + 1, ',');
        const char *c2 = c1 ? strchr(c1 + 1, ',') : NULL;
        const char *why = !c2 || c2 - c1 - 1 != 12 ? "plan.csv: a row without a run id"
                          : !GROW(*ids, cap, *n + 1, 64) ? "out of memory"
                                                         : NULL;
        if (why) {   /* never a part of the plan: merge would miss the rest */
            snprintf(err, errlen, "%s", why);
            free(*ids);
            *ids = NULL;
            return false;
        }
        memcpy((*ids)[*n], c1 + 1, 12);
        (*ids)[(*n)++][12] = 0;
    }
    return true;
}

static bool copy_file(const char *from, const char *to, char *err, size_t errlen)
{
    if (link(from, to) == 0)
        return true;
    size_t len;
    char *data = slurp(from, &len, err, errlen);
    if (!data)
        return false;
    afile f;
    bool ok = afile_open(&f, to, err, errlen);
    if (ok) {
        if (fwrite(data, 1, len, f.fp) != len) {
            afile_abort(&f);
            snprintf(err, errlen, "%s: %s", to, strerror(errno));
            ok = false;
        } else {
            ok = afile_commit(&f, err, errlen);
        }
    }
    free(data);
    return ok;
}

/* copy_run's part of one entry: a regular file is copied into the folder ctx names. */
static bool copy_entry(const char *src, const char *name, void *ctx, char *err, size_t errlen)
{
    char dst[4608];
    snprintf(dst, sizeof dst, "%s/%s", (const char *)ctx, name);
    struct stat stt;
    if (strstr(name, ".tmp.") || lstat(src, &stt) != 0 || !S_ISREG(stt.st_mode))
        return true;
    return copy_file(src, dst, err, errlen);
}

/* Copies the regular files of one run folder. */
static bool copy_run(const char *from, const char *to, char *err, size_t errlen)
{
    return fs_mkdirs_tail(to, 2, err, errlen) && folder_each(from, copy_entry, (void *)to, err, errlen);
}

/* "version V, commit C" of the build that made run_dir: its meta.yaml's `shadesweep`
 * block ("unknown" for what it lacks; the run is complete, so meta.yaml is there). */
static void run_build(const char *run_dir, char *out, size_t len)
{
    static const char *const keys[] = {"version", "commit"};
    char v[2][61];
    meta_read_block(run_dir, "shadesweep", keys, 2, v[0], sizeof v[0]);
    snprintf(out, len, "version %s, commit %s", v[0][0] ? v[0] : "unknown",
             v[1][0] ? v[1] : "unknown");
}

int merge_main(const char *out, bool force, bool allow_mixed, int ndirs, char **dirs)
{
    char err[8192];
    sweep_meta meta0 = {0};
    char *plan0 = NULL;
    size_t plan0_len = 0;
    char(*ids)[13] = NULL;
    size_t nids = 0;
    int rc = 2;
    folder fo;
    bool opened = false;
    int *from = NULL;

    for (int i = 0; i < ndirs; i++) {
        char path[4200], why[1024];
        sweep_meta meta;
        /* the test of run --resume: another output format is not merged (nor relabelled) */
        if (!folder_is_output(dirs[i], &meta, why, sizeof why)) {
            fprintf(stderr, "shadesweep merge: %s is not a shadesweep output folder (%s): not "
                    "merging it\n", dirs[i], why);
            goto done;
        }
        snprintf(path, sizeof path, "%s/plan.csv", dirs[i]);
        size_t len;
        char *text = slurp(path, &len, err, sizeof err);
        if (!text) {
            fprintf(stderr, "shadesweep merge: %s\n", err);
            goto done;
        }
        if (i == 0) {
            meta0 = meta;
            plan0 = text;
            plan0_len = len;
            continue;
        }
        bool same_plan = len == plan0_len && memcmp(text, plan0, len) == 0;
        free(text);
        if (strcmp(meta.manifest_hash, meta0.manifest_hash) != 0) {
            fprintf(stderr,
                    "shadesweep merge: %s was made from manifest %s (hash %s), %s from %s "
                    "(hash %s): shards of different manifests cannot be merged\n",
                    dirs[i], meta.manifest_path, meta.manifest_hash, dirs[0],
                    meta0.manifest_path, meta0.manifest_hash);
            goto done;
        }
        if (!same_plan) {
            fprintf(stderr,
                    "shadesweep merge: %s/plan.csv differs from %s/plan.csv (another shard "
                    "count?): not shards of one sweep\n",
                    dirs[i], dirs[0]);
            goto done;
        }
    }
    if (!plan_ids(plan0, &ids, &nids, err, sizeof err)) {
        fprintf(stderr, "shadesweep merge: %s/%s\n", dirs[0], err);
        goto done;
    }

    for (int i = 0; i < ndirs; i++)
        if (folder_overlaps(out, dirs[i])) {
            fprintf(stderr, "shadesweep merge: the output %s is (or holds, or lies in) the "
                    "input %s: merge never writes into its inputs; choose another -o\n",
                    out, dirs[i]);
            goto done;
        }
    /* Which folder each run comes from (-1: none has it complete), before OUT is
     * touched: a refusal below leaves it as it was. */
    from = malloc((nids ? nids : 1) * sizeof *from);
    if (!from) {
        fprintf(stderr, "shadesweep merge: out of memory\n");
        goto done;
    }
    size_t first = nids;   /* the first run taken: the build the others are held to */
    char build0[160] = "";
    bool mixed = false;
    for (size_t r = 0; r < nids; r++) {
        from[r] = -1;
        for (int i = 0; i < ndirs; i++) {
            char why[512], dir[4200];
            run_check c;
            if (!folder_check_run(dirs[i], ids[r], true, &c, why, sizeof why)) {
                snprintf(dir, sizeof dir, "%s/runs/%s", dirs[i], ids[r]);
                if (fs_exists(dir))
                    fprintf(stderr, "shadesweep merge: run %s in %s is incomplete (%s): not "
                            "taken\n", ids[r], dirs[i], why);
                continue;
            }
            if (from[r] < 0)
                from[r] = i;
            else
                fprintf(stderr, "shadesweep merge: run %s is in %s and %s; taking %s's\n",
                        ids[r], dirs[from[r]], dirs[i], dirs[from[r]]);
        }
        if (from[r] < 0 || mixed)
            continue;
        /* One build per merged folder: crossovers and rankings across builds would
         * compare the builds as much as the renderers. */
        char dir[4200], build[160];
        snprintf(dir, sizeof dir, "%s/runs/%s", dirs[from[r]], ids[r]);
        run_build(dir, build, sizeof build);
        if (first == nids) {
            first = r;
            snprintf(build0, sizeof build0, "%s", build);
        } else if (strcmp(build, build0) != 0) {
            mixed = true;
            fprintf(stderr, "shadesweep merge: %s runs of different builds: run %s in %s is "
                    "%s, run %s in %s is %s%s\n", allow_mixed ? "warning: merging" : "refusing",
                    ids[first], dirs[from[first]], build0, ids[r], dirs[from[r]], build,
                    allow_mixed ? " (--allow-mixed-builds)"
                                : "; --allow-mixed-builds merges them anyway");
            if (!allow_mixed)
                goto done;
        }
    }
    snprintf(meta0.shard, sizeof meta0.shard, "merged from %d folder%s", ndirs,
             ndirs == 1 ? "" : "s");
    if (!folder_open(&fo, out, force ? FOLDER_FORCE : FOLDER_NEW, &meta0, err, sizeof err)) {
        if (strstr(err, " exists; use --resume"))   /* run's advice; merge has no --resume */
            fprintf(stderr, "shadesweep merge: %s exists; use --force to replace it\n", out);
        else
            fprintf(stderr, "shadesweep merge: %s\n", err);
        goto done;
    }
    opened = true;
    size_t copied = 0;
    for (size_t r = 0; r < nids; r++) {
        if (from[r] < 0)
            continue;
        char src[4200], dst[4200];
        snprintf(src, sizeof src, "%s/runs/%s", dirs[from[r]], ids[r]);
        snprintf(dst, sizeof dst, "%s/runs/%s", out, ids[r]);
        if (!copy_run(src, dst, err, sizeof err)) {
            fprintf(stderr, "shadesweep merge: %s\n", err);
            goto done;
        }
        copied++;
    }
    char path[4200];
    snprintf(path, sizeof path, "%s/plan.csv", out);
    afile f;
    if (!afile_open(&f, path, err, sizeof err) ||
        (fwrite(plan0, 1, plan0_len, f.fp), !afile_commit(&f, err, sizeof err))) {
        fprintf(stderr, "shadesweep merge: %s\n", err);
        goto done;
    }
    run_account acct;
    if (!output_merge_summary_ids(out, ids, nids, &acct, err, sizeof err)) {
        fprintf(stderr, "shadesweep merge: %s\n", err);
        goto done;
    }
    fprintf(stderr, "merged %zu of %zu runs from %d folder%s into %s\n", copied, nids, ndirs,
            ndirs == 1 ? "" : "s", out);
    size_t missing = acct.missing, failed = acct.failed + acct.partial;
    output_account_print(stderr, &acct, 20);
    output_account_free(&acct);
    if (missing) {
        fprintf(stderr, "missing runs (no folder has them complete):");
        size_t shown = 0;
        for (size_t r = 0; r < nids && shown < 20; r++) {
            run_check c;
            char why[512];
            if (!folder_check_run(out, ids[r], false, &c, why, sizeof why)) {
                fprintf(stderr, " %s", ids[r]);
                shown++;
            }
        }
        fprintf(stderr, "%s\n", missing > shown ? " ..." : "");
    }
    rc = missing || failed ? 1 : 0;
done:
    if (opened)
        folder_close(&fo, rc == 2);
    free(plan0);
    free(ids);
    free(from);
    return rc;
}
