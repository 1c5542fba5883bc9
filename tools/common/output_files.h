/* output_files.h - the files a tool writes: checked against its inputs and each other before any
 * work, and written all or nothing.
 *
 * Collisions: two paths name the same file when they are the same existing file (st_dev, st_ino:
 * "./a.json" and "a.json", hard links) or, for a file that does not exist yet, the same name in the
 * same existing folder. An output that names an input would overwrite it; two outputs that name the
 * same file would keep only one.
 *
 * Staging: every output gets an empty temporary beside it as soon as it is known (so an output
 * that cannot be created fails before the run, not after it); the writers fill the temporaries;
 * only when every one is complete are they renamed into place. Abandoning the stage deletes every
 * temporary, so a failure leaves the old files as they were and nothing new.
 */
#ifndef CACAO_OUTPUT_FILES_H
#define CACAO_OUTPUT_FILES_H

#include <stdbool.h>
#include <stddef.h>

/* A path and the flag that gave it ("--json"), for messages. A NULL path is skipped. */
typedef struct cacao_named_path {
    const char *flag;
    const char *path;
} cacao_named_path;

/* Whether a and b name the same file (see above). */
bool cacao_same_file(const char *a, const char *b);

/* Checks every output against every other output and every input. On a collision writes one
 * line into err ("--json r.json and --csv r.json name the same file", "--json d.pfm: is also the
 * --scene depth input; it would be overwritten") and returns false. */
bool cacao_check_outputs(const cacao_named_path *outputs, size_t output_count, const cacao_named_path *inputs,
                         size_t input_count, char *err, size_t err_size);

/* The outputs of one run, staged. Zero-initialise; release with cacao_stage_commit or
 * cacao_stage_abandon. */
typedef struct cacao_stage {
    struct cacao_staged_file *files;
    size_t count, capacity;
} cacao_stage;

/* Creates the empty temporary of path beside it ("<path>.<pid>.<n>.tmp", never replacing a file)
 * and returns its path (owned by the stage) for the writer to fill; NULL with one line in err
 * naming the flag and path when it cannot be created (a missing folder, a folder at path, no
 * permission). */
const char *cacao_stage_add(cacao_stage *stage, const char *flag, const char *path, char *err, size_t err_size);

/* Renames every temporary into place and frees the stage. A rename that fails (which staging in
 * the destination's own folder makes unlikely) is reported and the temporaries not yet renamed
 * are deleted. */
bool cacao_stage_commit(cacao_stage *stage, char *err, size_t err_size);

/* Deletes every temporary and frees the stage. */
void cacao_stage_abandon(cacao_stage *stage);

#endif /* CACAO_OUTPUT_FILES_H */
