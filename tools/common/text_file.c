/* text_file.c - see text_file.h. */
#include "text_file.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

char *cacao_read_text_file(const char *path, size_t max_bytes, char *err, size_t n) {
    FILE *f = fopen(path, "rb");
    if (!f) {
        snprintf(err, n, "%s: cannot open: %s", path, strerror(errno));
        return NULL;
    }
    char *text = NULL;
    size_t length = 0, capacity = 0;
    for (;;) {
        if (length + 4096 + 1 > capacity) {
            capacity = (length + 4096 + 1) * 2;
            char *grown = realloc(text, capacity);
            if (!grown) {
                snprintf(err, n, "%s: out of memory", path);
                break;
            }
            text = grown;
        }
        const size_t got = fread(text + length, 1, 4096, f);
        length += got;
        if (length > max_bytes) {
            snprintf(err, n, "%s: larger than %zu bytes", path, max_bytes);
            break;
        }
        if (got < 4096) {
            if (ferror(f)) {
                snprintf(err, n, "%s: read error", path);
                break;
            }
            text[length] = 0;
            fclose(f);
            return text;
        }
    }
    free(text);
    fclose(f);
    return NULL;
}
