/* text_buffer.c - see text_buffer.h. */
#include "text_buffer.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>

void append(text_buffer *b, const char *fmt, ...) {
    if (b->failed) return;
    va_list ap;
    va_start(ap, fmt);
    const int n = vsnprintf(NULL, 0, fmt, ap);
    va_end(ap);
    if (n < 0 || b->length + (size_t)n + 1 > b->capacity) {
        const size_t want = (b->length + (size_t)(n < 0 ? 0 : n) + 1) * 2 + 4096;
        char *grown = n < 0 ? NULL : realloc(b->data, want);
        if (!grown) {
            b->failed = true;
            return;
        }
        b->data = grown;
        b->capacity = want;
    }
    va_start(ap, fmt);
    vsnprintf(b->data + b->length, b->capacity - b->length, fmt, ap);
    va_end(ap);
    b->length += (size_t)n;
}
