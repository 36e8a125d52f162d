/* A measured frame's row of frames.csv, generated from results/metrics.def. Here, not
 * in metrics.c, so that the table (metrics.h) stays below the frame record. */
#include "results/record.h"

#define METRIC_WRITE_F64(w, x, decimals) csv_f64(w, x, decimals)
#define METRIC_WRITE_U64(w, x, decimals) csv_u64(w, x)

void metrics_write_frame(csv_writer *w, const frame_record *r)
{
#define FRAME_METRIC(field, type, frames, fprec, ...) \
    METRIC_IF(frames, F, METRIC_CAT(METRIC_WRITE_, type)(w, r->field, fprec);)
#define FRAME_DERIVED(name, frames, fexpr, fprec, ...) \
    METRIC_IF(frames, F, csv_f64(w, fexpr, fprec);)
#include "results/metrics.def"
}
