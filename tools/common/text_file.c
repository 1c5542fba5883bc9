/* text_file.c - see text_file.h. */
#define _POSIX_C_SOURCE 200809L /* fileno */
#include "text_file.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

bool cacao_check_input(const char *path, char *err, size_t err_size) {
    struct stat st;
    if (stat(path, &st) != 0) {
        cacao_set_err(err, err_size, "%s: cannot open: %s", path, strerror(errno));
        return false;
    }
    if (S_ISDIR(st.st_mode)) {
        cacao_set_err(err, err_size, "%s: is a directory, not a file", path);
        return false;
    }
    if (!S_ISREG(st.st_mode)) {
        cacao_set_err(err, err_size, "%s: is not a regular file (a FIFO, socket or device); give a file", path);
        return false;
    }
    return true;
}

FILE *cacao_open_input(const char *path, char *err, size_t err_size) {
    if (!cacao_check_input(path, err, err_size)) return NULL;
    FILE *file = fopen(path, "rb");
    if (!file) cacao_set_err(err, err_size, "%s: cannot open: %s", path, strerror(errno));
    return file;
}

char *cacao_read_file(const char *path, size_t max_bytes, size_t *length_out, char *err, size_t err_size) {
    FILE *file = cacao_open_input(path, err, err_size);
    if (!file) return NULL;
    /* Sized by the file (a regular file: checked above), not by the limit; a file that grows while
     * being read is cut at the size it had, and one larger than the limit is refused. */
    struct stat st;
    const bool sized = fstat(fileno(file), &st) == 0 && st.st_size >= 0;
    const size_t capacity = sized && (unsigned long long)st.st_size < max_bytes ? (size_t)st.st_size : max_bytes;
    char *text = sized ? malloc(capacity + 1) : NULL;
    const size_t length = text ? fread(text, 1, capacity, file) : 0;
    const bool too_big = text && (unsigned long long)st.st_size > max_bytes;
    const bool failed = !text || ferror(file) || too_big;
    fclose(file);
    if (failed) {
        if (too_big)
            cacao_set_err(err, err_size, "%s: larger than %zu bytes", path, max_bytes);
        else
            cacao_set_err(err, err_size, "%s: cannot read%s", path, text ? "" : " (out of memory)");
        free(text);
        return NULL;
    }
    text[length] = '\0';
    if (length_out) *length_out = length;
    return text;
}

char *cacao_read_whole_file(const char *path, size_t max_bytes, char *err, size_t err_size) {
    return cacao_read_file(path, max_bytes, NULL, err, err_size);
}

