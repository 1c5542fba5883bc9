/* text_buffer.h - text built up by printf-style appends (the CSV, the plot's data and script). */
#ifndef CACAO_BENCH_TEXT_BUFFER_H
#define CACAO_BENCH_TEXT_BUFFER_H

#include <stdbool.h>
#include <stddef.h>

/* Zero-initialise; data is zero-terminated once anything is appended; free(data) when done.
 * failed: an append ran out of memory (every later one is skipped). */
typedef struct text_buffer {
    char *data;
    size_t length, capacity;
    bool failed;
} text_buffer;

void append(text_buffer *b, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

#endif /* CACAO_BENCH_TEXT_BUFFER_H */
