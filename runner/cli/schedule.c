/* The sweep as rounds of trials (run.h run_plan; docs/architecture.md "Schedule"). */
#include "runner/trial/run.h"
#include "runner/cli/probe.h"
#include "runner/folder/bound_folder.h"

#include <errno.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "results/csvread.h"
#include "common/fsutil.h"
#include "common/nvml.h"
#include "results/verdict.h"
#include "runner/folder/folder.h"
#include "runner/manifest/hash.h"
#include "runner/folder/account.h"
#include "runner/folder/output.h"
#include "runner/plan/resume_plan.h"
#include "runner/answer/summary_md.h"
#include "runner/folder/trials.h"

/* Where each run of the plan stands. */
typedef struct run_slot {
    const run_spec *s;
    bool selected;             /* in this shard */
    bool complete;             /* its files are merged (or were, before a resume) */
    bool ended;                /* a trial's status ended it: no more trials */
    uint32_t done;             /* trials 1..done have complete folders */
    uint32_t ok;               /* ... of which ok */
    uint32_t *order;           /* order[k - 1]: trial k's place in its round */
    double *value;             /* value[k - 1]: trial k's metric_us (trials: auto; NAN:
                                * none), read once from its folder */
    uint32_t cap;              /* of order and value */
    char status[96];           /* the first failure among its trials, or "ok" */
    char message[512];         /* ... and why, for the rows of a run refused before a trial */
    char not_run[600];         /* a trial ended it: the message of the trials it did not
                                * run (failed:not-run, not the status that ended it) */
    double used_s;             /* wall time of its trials' processes */
} run_slot;

/* ---- the order of a round */

static uint64_t splitmix64(uint64_t *x)
{
    uint64_t z = (*x += UINT64_C(0x9e3779b97f4a7c15));
    z = (z ^ (z >> 30)) * UINT64_C(0xbf58476d1ce4e5b9);
    z = (z ^ (z >> 27)) * UINT64_C(0x94d049bb133111eb);
    return z ^ (z >> 31);
}

/* A permutation of idx[0..n) for round `round` of sweep point `point`: Fisher-Yates
 * from a generator seeded by (seed, point, round), so that a resumed sweep runs the
 * same order and a round's order does not depend on which runs of it are left. */
static void round_order(size_t *idx, size_t n, uint32_t seed, size_t point, uint32_t round)
{
    uint64_t key[3] = {seed, point, round};
    uint64_t x = fnv1a64(key, sizeof key);
    for (size_t i = n; i > 1; i--) {
        size_t j = (size_t)(splitmix64(&x) % i);
        size_t t = idx[i - 1];
        idx[i - 1] = idx[j];
        idx[j] = t;
    }
}

/* Room for trial `trial` in order and value (new places: 0 and NAN). */
static bool slot_grow(run_slot *r, uint32_t trial)
{
    if (trial <= r->cap)
        return true;
    uint32_t cap = r->cap ? r->cap * 2 : 8;
    while (cap < trial)
        cap *= 2;
    uint32_t *o = realloc(r->order, cap * sizeof *o);
    if (o)
        r->order = o;
    double *v = o ? realloc(r->value, cap * sizeof *v) : NULL;
    if (!v)
        return false;
    r->value = v;
    for (uint32_t i = r->cap; i < cap; i++) {
        o[i] = 0;
        v[i] = NAN;
    }
    r->cap = cap;
    return true;
}

static bool slot_order(run_slot *r, uint32_t trial, uint32_t place)
{
    if (!slot_grow(r, trial))
        return false;
    r->order[trial - 1] = place;
    return true;
}

/* ---- trial values, for trials: auto */

/* The value that ranks (summary.csv `metric_us`) of trial k of a run, from its folder;
 * NAN when it has none. */
static double trial_value(const char *out_dir, const char *id, uint32_t k)
{
    char path[4400], err[256];
    snprintf(path, sizeof path, "%s/runs/%s/trial-%u/summary.csv", out_dir, id, k);
    csv_table t;
    if (!csv_read(path, &t, err, sizeof err))
        return NAN;
    int c = csv_col(&t, "metric_us"), st = csv_col(&t, "status");
    double v = NAN;
    if (c >= 0 && st >= 0 && t.nrows == 1 && strcmp(csv_get(&t, 0, st), "ok") == 0)
        v = csv_num(&t, 0, c);
    csv_table_free(&t);
    return v;
}

/* Keeps trial k's value for trials: auto (the trial is complete). */
static bool slot_value(const char *out_dir, run_slot *r, uint32_t k)
{
    if (r->s->p.trials != 0)
        return true;
    if (!slot_grow(r, k))
        return false;
    r->value[k - 1] = trial_value(out_dir, r->s->id, k);
    return true;
}

/* trials: auto: whether the point's verdicts are settled after `rounds` rounds: every
 * pair of its runs that did not end has a paired ratio that is precise enough or
 * excludes 1 (verdict_all_decided). */
static bool point_settled(run_slot *const *runs, size_t n, uint32_t rounds, double precision)
{
    if (rounds < TRIALS_AUTO_MIN)
        return false;
    if (n < 2)
        return true;   /* nothing to rank: the minimum is enough */
    ratio_ci *r = malloc(n * n * sizeof *r);
    if (!r)
        return true;   /* no memory to decide: stop adding rounds */
    size_t nr = 0;
    for (size_t i = 0; i < n; i++) {
        if (runs[i]->ended || runs[i]->cap < rounds)
            continue;
        for (size_t j = i + 1; j < n; j++)
            if (!runs[j]->ended && runs[j]->cap >= rounds)
                verdict_paired_ratio(runs[i]->value, runs[j]->value, rounds, &r[nr++]);
    }
    bool settled = verdict_all_decided(r, nr, precision);
    free(r);
    return settled;
}

/* ---- one trial, and a run's end */

static const char *schedule_name(const run_params *p)
{
    return p->schedule == RUN_SCHEDULE_SEQUENTIAL ? "sequential" : "interleaved";
}

/* Trial k of r ended with `status`: a status that ends the run (a timeout, a crash, a
 * refusal) makes its later trials failed:not-run, saying why; they never carry a
 * failure of their own they did not have. */
static void slot_ended(run_slot *r, uint32_t k, const char *status)
{
    if (!run_status_ends_run(status) || r->not_run[0])
        return;
    if (strcmp(status, "failed:timeout") == 0) {
        char limit[160];
        run_timeout_text(&r->s->p, limit, sizeof limit);
        snprintf(r->not_run, sizeof r->not_run, "not run: trial %u was stopped by its limit "
                 "(%s), which ends the run", k, limit);
    } else {
        snprintf(r->not_run, sizeof r->not_run, "not run: trial %u ended the run (%s)", k,
                 status);
    }
}

/* Runs trial k of r (place: its place in its round). False: the sweep cannot go on. */
static bool run_one_trial(const experiment *e, const run_options *o, progress *pg, run_slot *r,
                          uint32_t k, uint32_t place, size_t *nth)
{
    const run_spec *s = r->s;
    if (!slot_order(r, k, place)) {
        fprintf(stderr, "shadesweep: out of memory\n");
        return false;
    }
    progress_run_begin(pg, ++*nth, s->id, s->p.renderer, s->p.width, s->p.height, s->p.scene,
                       k, s->p.trials);
    trial_outcome out;
    if (!run_trial_isolated(e, s, o, pg, k, place, run_trial_timeout_s(&s->p), &out))
        return false;
    r->used_s += out.seconds;
    if (out.interrupted)
        return true;
    if (out.message[0])
        fprintf(stderr, "run %s: trial %u: %s\n", s->id, k, out.message);
    /* A trial that could not write its files may have no files.txt either: its row is
     * written again here (on a full disk this fails too, and the sweep stops). */
    run_check tc;
    char why[512];
    if (strcmp(out.status, RUN_STATUS_WRITE) == 0 &&
        !folder_check_trial(o->out_dir, s->id, k, &tc, why, sizeof why) &&
        !run_write_missing_trial(e, s, o, k, place, out.status, out.message))
        return false;
    progress_run_end(pg, out.status, out.fps);
    r->done = k;
    r->ok += strcmp(out.status, "ok") == 0;
    if (!slot_value(o->out_dir, r, k)) {
        fprintf(stderr, "shadesweep: out of memory\n");
        return false;
    }
    if (strcmp(out.status, "ok") != 0 && strcmp(r->status, "ok") == 0) {
        snprintf(r->status, sizeof r->status, "%s", out.status);
        snprintf(r->message, sizeof r->message, "%s", out.message);
    }
    if (run_status_ends_run(out.status)) {
        r->ended = true;
        uint32_t want = s->p.trials ? s->p.trials : TRIALS_AUTO_MIN;
        progress_unexpect(pg, s->p.renderer, s->p.width, s->p.height, s->p.scene,
                          want > k ? want - k : 0);
    }
    slot_ended(r, k, out.status);
    return true;
}

/* Rows for the trials a run will not run, then the run's files from its trials. */
static bool finish_run(const experiment *e, const run_options *o, progress *pg, run_slot *r,
                       uint32_t n)
{
    const run_spec *s = r->s;
    for (uint32_t k = r->done + 1; k <= n; k++) {
        const char *st = r->not_run[0] || strcmp(r->status, "ok") == 0 ? "failed:not-run"
                                                                      : r->status;
        if (!run_write_missing_trial(e, s, o, k, 0, st, r->not_run[0] ? r->not_run : r->message))
            return false;
        if (!slot_order(r, k, 0))
            return false;
    }
    char err[600], status[96];
    trials_run_status(n, r->ok, strcmp(r->status, "ok") ? r->status : NULL, status,
                      sizeof status);
    trials_schedule ts = {.mode = schedule_name(&s->p), .seed = s->p.schedule_seed,
                          .point = s->group, .order = r->order};
    if (!trials_merge(o->out_dir, s->id, n, status, &ts, err, sizeof err)) {
        fprintf(stderr, "run %s: %s\n", s->id, err);
        return false;
    }
    r->complete = true;
    progress_run_complete(pg, status);
    return true;
}

/* The runs of one sweep point, in rounds (or sequentially). False: the sweep cannot go
 * on (a message was printed), or a stop signal came. */
static bool run_point(const experiment *e, const run_options *o, progress *pg,
                      run_slot **runs, size_t n, size_t *nth)
{
    const run_params *p = &runs[0]->s->p;
    const bool adaptive = p->trials == 0;
    const uint32_t max = adaptive ? TRIALS_AUTO_MAX : p->trials;
    /* --round K: the rounds up to K only; the runs are merged with the last round */
    const uint32_t upto = o->round && o->round < max ? o->round : max;
    size_t *idx = malloc(n * sizeof *idx);
    if (!idx) {
        fprintf(stderr, "shadesweep: out of memory\n");
        return false;
    }
    bool ok = true;
    uint32_t rounds = 0;
    if (p->schedule == RUN_SCHEDULE_SEQUENTIAL) {
        for (size_t i = 0; ok && i < n && !run_stop_signal(); i++)
            for (uint32_t k = runs[i]->done + 1; ok && k <= upto && !runs[i]->ended &&
                                                 !run_stop_signal(); k++)
                ok = run_one_trial(e, o, pg, runs[i], k, (uint32_t)i + 1, nth);
        rounds = max;
    } else {
        double spent = 0;
        for (uint32_t k = 1; ok && k <= upto && !run_stop_signal(); k++) {
            for (size_t i = 0; i < n; i++)
                idx[i] = i;
            round_order(idx, n, p->schedule_seed, runs[0]->s->group, k);
            for (size_t q = 0; ok && q < n && !run_stop_signal(); q++) {
                run_slot *r = runs[idx[q]];
                if (r->ended || r->done >= k) {
                    ok = slot_order(r, k, (uint32_t)q + 1) || (fprintf(stderr, "shadesweep: out of memory\n"), false);
                    continue;
                }
                double before = r->used_s;
                ok = run_one_trial(e, o, pg, r, k, (uint32_t)q + 1, nth);
                spent += r->used_s - before;
            }
            if (!ok || run_stop_signal())
                break;
            rounds = k;
            /* auto: at least TRIALS_AUTO_MIN rounds, then until decided or spent */
            if (adaptive && k >= TRIALS_AUTO_MIN) {
                bool settled = point_settled(runs, n, k, p->precision);
                if (!settled && spent >= p->budget_s)
                    fprintf(stderr, "sweep point %zu: measure.budget (%g s) spent after %u "
                            "rounds: some of its ratios are still undecided (summary.md: "
                            "differs no, intervals wider than measure.precision %g)\n",
                            runs[0]->s->group, p->budget_s, k, p->precision);
                if (settled || spent >= p->budget_s)
                    break;
            }
        }
    }
    free(idx);
    if (!ok || run_stop_signal() || upto < max)
        return ok;
    for (size_t i = 0; ok && i < n; i++) {
        uint32_t total = adaptive ? (rounds > runs[i]->done ? rounds : runs[i]->done) : max;
        ok = finish_run(e, o, pg, runs[i], total);
    }
    return ok;
}

/* ---- resume */

/* What a resumed sweep keeps of a run: the whole run when complete, else its leading
 * complete trials (the later ones are removed: they run again). */
static void resume_slot(const run_options *o, run_slot *r, size_t *kept, size_t *retried)
{
    const run_spec *s = r->s;
    char dir[4200], why[512];
    snprintf(dir, sizeof dir, "%s/runs/%s", o->out_dir, s->id);
    run_check c;
    if (folder_check_run(o->out_dir, s->id, true, &c, why, sizeof why)) {
        /* a run that could not write a file is not complete: it runs again */
        if (c.unwritten) {
            char err[512];
            fprintf(stderr, "resuming: run %s could not write its files (%s): it runs again\n",
                    s->id, RUN_STATUS_WRITE);
            if (!folder_clear_run(dir, err, sizeof err))
                fprintf(stderr, "shadesweep: %s\n", err);
            return;
        }
        if (c.failed && o->retry_failed) {
            char err[512];
            if (!folder_clear_run(dir, err, sizeof err))
                fprintf(stderr, "shadesweep: %s\n", err);
            (*retried)++;
            return;
        }
        r->complete = true;
        (*kept)++;
        return;
    }
    if (!fs_exists(dir))
        return;
    uint32_t k = 1;
    run_check tc;
    char twhy[512];
    while (folder_check_trial(o->out_dir, s->id, k, &tc, twhy, sizeof twhy) && !tc.unwritten) {
        r->done = k;
        r->ok += !tc.failed;
        if (tc.failed && strcmp(r->status, "ok") == 0)
            snprintf(r->status, sizeof r->status, "%s", tc.status);
        if (tc.failed && run_status_ends_run(tc.status))
            r->ended = true;
        slot_ended(r, k, tc.status);
        /* without memory the value stays NAN: auto then sees one pair fewer */
        (void)slot_value(o->out_dir, r, k);
        k++;
    }
    /* trial folders after the first incomplete one: removed, they run again (trials
     * run in order, so there are none past a missing one) */
    for (uint32_t j = k;; j++) {
        char tdir[4400], err[512];
        snprintf(tdir, sizeof tdir, "%s/trial-%u", dir, j);
        if (!fs_exists(tdir))
            break;
        folder_clear_run(tdir, err, sizeof err);
    }
    fprintf(stderr, "resuming: run %s is incomplete (%s): %u of its trials kept, the others "
            "run again\n", s->id, why, r->done);
}

/* ---- the sweep */

int run_plan(const experiment *e, const plan *p, const run_options *o)
{
    char err[512];
    run_catch_stop_signals();
    int rc = 0;
    FILE *progress_out = NULL;
    run_slot *slots = NULL;
    run_slot **group = NULL;
    if (!output_write_plan(o->out_dir, p, err, sizeof err)) {
        fprintf(stderr, "shadesweep: %s\n", err);
        return 2;
    }
    folder_remove_temp(o->out_dir);

    for (size_t i = 0; o->round && i < p->nruns; i++)
        if (p->runs[i].p.trials == 0) {
            fprintf(stderr, "shadesweep run: --round: not with trials: auto (its rounds are "
                    "decided as they are measured)\n");
            return 2;
        }
    slots = calloc(p->nruns ? p->nruns : 1, sizeof *slots);
    group = calloc(p->nruns ? p->nruns : 1, sizeof *group);
    if (!slots || !group) {
        fprintf(stderr, "shadesweep: out of memory\n");
        rc = 2;
        goto done;
    }
    size_t selected = 0, kept = 0, retried = 0, trials_left = 0;
    for (size_t i = 0; i < p->nruns; i++) {
        run_slot *r = &slots[i];
        r->s = &p->runs[i];
        snprintf(r->status, sizeof r->status, "ok");
        if (o->shard && r->s->shard != o->shard)
            continue;
        r->selected = true;
        selected++;
        if (o->resume)
            resume_slot(o, r, &kept, &retried);
        if (!r->complete) {
            uint32_t want = r->s->p.trials ? r->s->p.trials : TRIALS_AUTO_MIN;
            trials_left += want > r->done ? want - r->done : 0;
        }
    }
    if (o->resume)
        fprintf(stderr, "resuming: %zu of %zu runs already complete\n", kept + retried,
                selected);
    if (retried)
        fprintf(stderr, "retrying %zu failed run%s\n", retried, retried == 1 ? "" : "s");

    char clocks[320] = "";   /* once a sweep: why meta.yaml has no clocks (common/nvml.h) */
    if (trials_left)
        nvml_availability(clocks, sizeof clocks);
    if (clocks[0])
        fprintf(stderr, "%s\n", clocks);

    /* Progress goes to the terminal (or log) the user sees; each child's own stderr
     * goes to its run's log.txt. */
    int fd = dup(STDERR_FILENO);
    progress_out = fd >= 0 ? fdopen(fd, "w") : NULL;
    if (!progress_out) {
        if (fd >= 0)
            close(fd);
        fprintf(stderr, "shadesweep: cannot duplicate stderr\n");
        rc = 2;
        goto done;
    }
    setvbuf(progress_out, NULL, _IOLBF, 0);

    progress pg;
    progress_init(&pg, trials_left, progress_out);
    for (size_t i = 0; i < p->nruns; i++) {   /* what the ETA counts */
        const run_slot *r = &slots[i];
        uint32_t want = r->s->p.trials ? r->s->p.trials : TRIALS_AUTO_MIN;
        if (r->selected && !r->complete && !r->ended && want > r->done)
            progress_expect(&pg, r->s->p.renderer, r->s->p.width, r->s->p.height,
                            r->s->p.scene, want - r->done);
    }
    size_t nth = 0;
    /* the sweep points in plan order, each with its runs in plan order */
    for (size_t g = 0; g < p->ngroups && !run_stop_signal(); g++) {
        size_t n = 0;
        for (size_t i = 0; i < p->nruns; i++)
            if (slots[i].selected && !slots[i].complete && p->runs[i].group == g)
                group[n++] = &slots[i];
        if (n && !run_point(e, o, &pg, group, n, &nth) && !run_stop_signal()) {
            rc = 2;
            break;
        }
    }
    /* The account and the exit status describe the folder as it stands, not this
     * invocation's runs. */
    progress_free(&pg);   /* the ETA's costs: only the closing line is left */
    run_account acct;
    if (!output_merge_summary(o->out_dir, p, o->shard, &acct, err, sizeof err)) {
        progress_finish(&pg, NULL);
        fprintf(stderr, "shadesweep: %s\n", err);
        rc = 2;
        goto done;
    }
    char counts[160];
    output_account_counts(&acct, counts, sizeof counts);
    progress_finish(&pg, counts);
    output_account_print(progress_out, &acct, 20);
    size_t missing = acct.missing, failed = acct.failed + acct.partial;
    output_account_free(&acct);
    if (run_stop_signal()) {
        fprintf(stderr,
                "interrupted by %s: %zu of %zu runs complete; to finish the others:\n"
                "  shadesweep run --resume -o %s %s\n",
                run_stop_name(run_stop_signal()), selected - missing, selected, o->out_dir,
                e->path);
        rc = 128 + run_stop_signal();
    } else if (!rc) {
        if (missing)
            fprintf(stderr, "shadesweep: %zu of %zu runs are not complete\n", missing, selected);
        rc = failed || missing ? 1 : 0;
    }
done:
    if (progress_out)
        fclose(progress_out);
    for (size_t i = 0; slots && i < p->nruns; i++) {
        free(slots[i].order);
        free(slots[i].value);
    }
    free(slots);
    free(group);
    return rc;
}

int run_sweep(const experiment *e, const plan *p, const char *out, bool force, run_options *o)
{
    if (run_stop_signal()) {
        fprintf(stderr, "shadesweep run: interrupted by signal %d before the sweep began; "
                "nothing was written\n", run_stop_signal());
        return 128 + run_stop_signal();
    }
    char dir[4096], err[4608];
    if (out)
        snprintf(dir, sizeof dir, "%s", out);
    else if (e->name[0])
        snprintf(dir, sizeof dir, "out/%s", e->name);
    else
        dir[0] = 0;   /* an empty name: refused by folder_open, never out/ itself */
    if (o->device >= 0 && !run_probe_device(o->device, err, sizeof err)) {
        fprintf(stderr, "shadesweep run: %s\n", err);
        return 2;
    }
    sweep_meta sm;
    output_sweep_meta_of(e, o->shard, o->nshards, p->nruns, &sm);
    folder fo;
    if (!folder_open(&fo, dir, force ? FOLDER_FORCE : o->resume ? FOLDER_RESUME : FOLDER_NEW,
                     &sm, err, sizeof err)) {
        fprintf(stderr, "shadesweep run: %s\n", err);
        return 2;
    }
    /* under the lock, before plan.csv is rewritten: a plan of other ids would orphan
     * the folder's runs */
    if (o->resume && !resume_plan_check(dir, p, err, sizeof err)) {
        fprintf(stderr, "shadesweep run: %s\n", err);
        folder_close(&fo, false);
        return 2;
    }
    o->out_dir = dir;
    int rc = run_plan(e, p, o);
    o->out_dir = NULL;
    if (rc != 2) {
        probe_copy_to_folder(dir, p);   /* device.yaml from the cache, never a probe */
        static folder_bound fb;         /* summary.csv's bound columns from it */
        char berr[4400];
        folder_bound_open(&fb, dir, NULL);
        if (!folder_bound_fill_summary(dir, &fb, berr, sizeof berr))
            fprintf(stderr, "shadesweep run: no bounds in summary.csv: %s\n", berr);
        folder_bound_close(&fb);
    }
    bool table = true;
    if (rc != 2 && !(o->round && rc != 0)) {
        /* the answer (runner/answer/summary_md.c): on stdout and as summary.md, written while
         * the folder is still ours; summaries that could not be written are a failure */
        char terr[1200];
        fprintf(stderr, "results: %s/summary.csv\n", dir);
        fflush(stderr);
        table = summary_table_write(dir, stdout, terr, sizeof terr);
        if (!table)
            fprintf(stderr, "shadesweep run: no summary table: %s\n", terr);
        fflush(stdout);
    }
    folder_close(&fo, rc == 2);   /* the runs stand: only a fresh folder's failure undoes */
    return table ? rc : 2;
}
