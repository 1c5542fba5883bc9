/* text_file.h - input files for every reader here (images, JSON, shader sources): checked, opened
 * once, or read whole; and the one printf-style error setter of the tools. */
#ifndef CACAO_TEXT_FILE_H
#define CACAO_TEXT_FILE_H

#include <stdarg.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>

/* printf-style message into err[0..err_size) (NULL-safe). Returns false, for "return cacao_set_err(...)"
 * in functions that report failure. */
static inline __attribute__((format(printf, 3, 4))) bool cacao_set_err(char *err, size_t err_size, const char *fmt,
                                                                      ...) {
    if (!err || err_size == 0) return false;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(err, err_size, fmt, ap);
    va_end(ap);
    return false;
}

/* One error line "<prefix><message>" on stderr, the tools' way of failing; returns false. */
static inline __attribute__((format(printf, 2, 3))) bool cacao_error_line(const char *prefix, const char *fmt, ...) {
    va_list ap;
    va_start(ap, fmt);
    fputs(prefix, stderr);
    vfprintf(stderr, fmt, ap);
    fputc('\n', stderr);
    va_end(ap);
    return false;
}

/* cacao_check_input says why path cannot be read as a file ("cannot open: <system reason>", "is a
 * directory", "is not a regular file" for a FIFO, socket or device, which are refused rather than
 * read so that no reader can block on them); it looks with stat() and opens nothing.
 * cacao_open_input checks, then opens once for binary reading. */
bool cacao_check_input(const char *path, char *err, size_t err_size);
FILE *cacao_open_input(const char *path, char *err, size_t err_size);

/* The whole of a file of at most max_bytes, zero-terminated (caller frees), its length in *length
 * when length is not NULL; NULL with a message naming the file in err on failure. */
char *cacao_read_file(const char *path, size_t max_bytes, size_t *length, char *err, size_t err_size);
/* The same for a text file, without the length. */
char *cacao_read_whole_file(const char *path, size_t max_bytes, char *err, size_t err_size);

#endif /* CACAO_TEXT_FILE_H */
