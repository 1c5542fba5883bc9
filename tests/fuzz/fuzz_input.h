/* fuzz_input.h - what every harness here shares: the readers under test take a path, so each
 * input is written to one file of this process (in TMPDIR or /tmp) and the reader is run on it. */
#ifndef CACAO_FUZZ_INPUT_H
#define CACAO_FUZZ_INPUT_H

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>

/* Writes data to this process's file with the given extension; returns its path (or aborts). */
static const char *fuzz_input_file(const uint8_t *data, size_t size, const char *ext) {
    static char path[512];
    if (!path[0]) {
        const char *dir = getenv("TMPDIR");
        snprintf(path, sizeof path, "%s/cacao-fuzz-%ld%s", dir && dir[0] ? dir : "/tmp", (long)getpid(), ext);
    }
    FILE *f = fopen(path, "wb");
    if (!f || fwrite(data, 1, size, f) != size || fclose(f) != 0) abort();
    return path;
}

#endif
