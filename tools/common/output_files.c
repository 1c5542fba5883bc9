/* output_files.c - output collisions and all-or-nothing staging (see output_files.h). */
#include "output_files.h"

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "image_io.h"

/* ---- Collisions --------------------------------------------------------------------------------- */

/* What a path names: an existing file (dev, ino), or a name not there yet in an existing folder
 * (the folder's dev, ino and the name), or, where neither is known, only its text. */
typedef struct file_identity {
    enum { BY_TEXT, EXISTING, NEW_IN_FOLDER } kind;
    dev_t dev;
    ino_t ino;
    const char *text; /* the whole path (BY_TEXT) or the name in the folder (NEW_IN_FOLDER) */
} file_identity;

static file_identity identity_of(const char *path) {
    struct stat st;
    if (stat(path, &st) == 0) return (file_identity){EXISTING, st.st_dev, st.st_ino, path};
    const char *slash = strrchr(path, '/');
    const size_t folder_length = !slash ? 0 : slash == path ? 1 : (size_t)(slash - path);
    char *folder = malloc(folder_length + 2);
    file_identity id = {BY_TEXT, 0, 0, path};
    if (!folder) return id;
    if (folder_length)
        memcpy(folder, path, folder_length);
    else
        folder[0] = '.';
    folder[folder_length ? folder_length : 1] = '\0';
    if (stat(folder, &st) == 0) id = (file_identity){NEW_IN_FOLDER, st.st_dev, st.st_ino, slash ? slash + 1 : path};
    free(folder);
    return id;
}

static bool same_identity(const file_identity *a, const file_identity *b) {
    if (a->kind != b->kind) return false; /* one is there and the other not, or in no folder that is there */
    if (a->kind == BY_TEXT) return strcmp(a->text, b->text) == 0;
    return a->dev == b->dev && a->ino == b->ino && (a->kind == EXISTING || strcmp(a->text, b->text) == 0);
}

bool cacao_same_file(const char *a, const char *b) {
    if (!a || !b) return false;
    const file_identity x = identity_of(a), y = identity_of(b);
    return same_identity(&x, &y);
}

/* "FLAG PATH" with the path's control bytes escaped, for a message. */
static void describe(const cacao_named_path *p, char *out, size_t size) {
    char shown[1024];
    cacao_escape_text(p->path, shown, sizeof shown);
    snprintf(out, size, "%s %s", p->flag, shown);
}

static bool collision(const cacao_named_path *output, const cacao_named_path *other, bool other_is_input, char *err,
                      size_t err_size) {
    char a[1100], b[1100];
    describe(output, a, sizeof a);
    if (!other_is_input) {
        describe(other, b, sizeof b);
        return cacao_set_err(err, err_size, "%s and %s name the same file", a, b);
    }
    char shown[1024] = "";
    if (strcmp(output->path, other->path) != 0) cacao_escape_text(other->path, shown, sizeof shown);
    return cacao_set_err(err, err_size, "%s: is also the %s input%s%s; it would be overwritten", a, other->flag,
                         shown[0] ? " " : "", shown);
}

bool cacao_check_outputs(const cacao_named_path *outputs, size_t output_count, const cacao_named_path *inputs,
                         size_t input_count, char *err, size_t err_size) {
    const size_t total = output_count + input_count;
    file_identity *ids = malloc((total ? total : 1) * sizeof *ids);
    if (!ids) return cacao_set_err(err, err_size, "out of memory checking the output paths");
    for (size_t i = 0; i < total; ++i) {
        const char *path = i < output_count ? outputs[i].path : inputs[i - output_count].path;
        ids[i] = path ? identity_of(path) : (file_identity){BY_TEXT, 0, 0, NULL};
    }
    bool ok = true;
    for (size_t i = 0; ok && i < output_count; ++i) {
        if (!outputs[i].path) continue;
        for (size_t j = i + 1; ok && j < total; ++j) {
            const cacao_named_path *other = j < output_count ? &outputs[j] : &inputs[j - output_count];
            if (other->path && same_identity(&ids[i], &ids[j]))
                ok = collision(&outputs[i], other, j >= output_count, err, err_size);
        }
    }
    free(ids);
    return ok;
}

/* ---- Staging ------------------------------------------------------------------------------------- */

struct cacao_staged_file {
    char *path, *temp;
};

static void free_stage(cacao_stage *stage) {
    for (size_t i = 0; i < stage->count; ++i) {
        free(stage->files[i].path);
        free(stage->files[i].temp);
    }
    free(stage->files);
    *stage = (cacao_stage){0};
}

/* Refuses an output path that names a folder or something other than a regular file (renaming
 * onto a device or FIFO would replace it). */
static bool check_destination(const char *flag, const char *path, const char *shown, char *err, size_t err_size) {
    struct stat st;
    if (stat(path, &st) != 0 || S_ISREG(st.st_mode)) return true;
    return cacao_set_err(err, err_size, "%s %s: %s; give a file path", flag, shown,
                         S_ISDIR(st.st_mode) ? "is a folder" : "is not a regular file");
}

const char *cacao_stage_add(cacao_stage *stage, const char *flag, const char *path, char *err, size_t err_size) {
    char shown[1024];
    cacao_escape_text(path, shown, sizeof shown);
    if (!check_destination(flag, path, shown, err, err_size)) return NULL;
    if (stage->count == stage->capacity) {
        const size_t capacity = stage->capacity ? stage->capacity * 2 : 8;
        struct cacao_staged_file *grown = realloc(stage->files, capacity * sizeof *grown);
        if (!grown) return cacao_set_err(err, err_size, "%s %s: out of memory", flag, shown), NULL;
        stage->files = grown;
        stage->capacity = capacity;
    }
    const size_t length = strlen(path) + 64;
    char *temp = malloc(length), *copy = strdup(path);
    if (!temp || !copy) {
        free(temp);
        free(copy);
        return cacao_set_err(err, err_size, "%s %s: out of memory", flag, shown), NULL;
    }
    snprintf(temp, length, "%s.%ld.%zu.tmp", path, (long)getpid(), stage->count);
    const int fd = open(temp, O_WRONLY | O_CREAT | O_EXCL, 0666);
    if (fd < 0 || close(fd) != 0) {
        cacao_set_err(err, err_size, "%s %s: cannot create a file there: %s", flag, shown, strerror(errno));
        if (fd >= 0) remove(temp);
        free(temp);
        free(copy);
        return NULL;
    }
    stage->files[stage->count++] = (struct cacao_staged_file){copy, temp};
    return temp;
}

bool cacao_stage_commit(cacao_stage *stage, char *err, size_t err_size) {
    bool ok = true;
    for (size_t i = 0; i < stage->count; ++i) {
        const struct cacao_staged_file *f = &stage->files[i];
        if (ok && rename(f->temp, f->path) != 0) {
            char shown[1024];
            cacao_escape_text(f->path, shown, sizeof shown);
            ok = cacao_set_err(err, err_size, "%s: cannot rename the written file into place: %s", shown,
                               strerror(errno));
        }
        if (!ok) remove(f->temp);
    }
    free_stage(stage);
    return ok;
}

void cacao_stage_abandon(cacao_stage *stage) {
    for (size_t i = 0; i < stage->count; ++i) remove(stage->files[i].temp);
    free_stage(stage);
}
