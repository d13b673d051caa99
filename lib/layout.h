/* layout.h - where a campaign's files live under the runs directory: the one place
 * that spells the layout the driver, the worker and the analysis tools share.
 *
 *   RUNS/study.db                          the database
 *   RUNS/NAME/ID.h5                        a run's output (its existence is completion)
 *   RUNS/NAME/ID.h5.{journal,ckpt}         the engine's, beside the output while it runs
 *   RUNS/NAME/jobs/ID.args, jobs/ID.lock   its argument file and per-run lock
 *   RUNS/NAME/logs/ID.log                  the engine's stderr, every attempt
 *   RUNS/NAME/cache/KEY.{args,h5,txt,log,lock}  a shared packing
 *   RUNS/NAME/{failed,damaged}/ID.attemptN.h5   outputs set aside
 *   RUNS/NAME/forgotten/                   files of runs forgotten with --forget-old
 *   RUNS/NAME/analysis/                    the analysis tools' outputs
 *   RUNS/.calibration/TAG.txt              the engine's measured CPU cost per grain-step, per
 *                                          build, CPU and integrator (study/report/calib.h); a
 *                                          campaign name never starts with '.'
 *
 * Paths are relative to the campaign directory (NAME/) where a job runs in it (the
 * worker, a remote host), else joined to it. Each function returns the length it
 * needed (snprintf's), so a caller can refuse a path that did not fit. */
#ifndef LIB_LAYOUT_H
#define LIB_LAYOUT_H

#include <stddef.h>

/* LAY_JOURNAL and LAY_CKPT: the engine's own (core/io/journal.h), beside a run's output */
enum lay_kind { LAY_OUTPUT, LAY_ARGS, LAY_LOCK, LAY_LOG, LAY_JOURNAL, LAY_CKPT, LAY_NKINDS };

/* RUNS/study.db (runs NULL: "runs"); db when given. */
int layout_db(const char *runs, const char *db, char *out, size_t len);
/* RUNS/.calibration (tag NULL) or RUNS/.calibration/TAG.txt */
int layout_calibration(const char *runs, const char *tag, char *out, size_t len);
/* RUNS/NAME */
int layout_campaign(const char *runs, const char *name, char *out, size_t len);
/* a run's file (cache = 0) or a packing's (cache = 1, id = its key) of the given kind,
 * under dir ("" for a path relative to the campaign directory) */
int layout_file(const char *dir, int cache, const char *id, enum lay_kind kind, char *out, size_t len);
/* the packing's particle file (what the runs start from) */
int layout_cache_particles(const char *dir, const char *key, char *out, size_t len);
/* dir/SUB (failed, damaged, forgotten, analysis, jobs, logs, cache) */
int layout_sub(const char *dir, const char *sub, char *out, size_t len);
/* dir/SUB/ID.attemptN.h5: an output set aside */
int layout_aside(const char *dir, const char *sub, const char *id, long attempt, char *out, size_t len);
/* 1 when a campaign named name would take, as RUNS/NAME, a name of the runs directory's
 * own files: the database's (db_file: its file name, NULL for study.db) and those kept
 * beside it (SQLite's -journal, -wal, -shm, the driver's .NAME.lock), which all begin
 * with it. */
int layout_reserved(const char *name, const char *db_file);

#endif
