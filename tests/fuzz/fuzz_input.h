/* fuzz_input.h - what every harness here shares: the readers under test take a path, so each
 * input is written to one file of this process (in TMPDIR or /tmp) and the reader is run on it;
 * the command-line parsers take an argument list, made from the input by fuzz_args. */
#ifndef CACAO_FUZZ_INPUT_H
#define CACAO_FUZZ_INPUT_H

#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* Writes data to this process's file with the given extension; returns its path (or aborts). */
static inline const char *fuzz_input_file(const uint8_t *data, size_t size, const char *ext) {
    static char path[512];
    if (!path[0]) {
        const char *dir = getenv("TMPDIR");
        snprintf(path, sizeof path, "%s/cacao-fuzz-%ld%s", dir && dir[0] ? dir : "/tmp", (long)getpid(), ext);
    }
    FILE *f = fopen(path, "wb");
    if (!f || fwrite(data, 1, size, f) != size || fclose(f) != 0) abort();
    return path;
}

/* An argument list from data, split at zero bytes: argv[0] = program, then at most max_args
 * arguments and a NULL (argv has room for max_args + 2), pointing into *text (a copy of data; caller frees);
 * returns argc, 0 when out of memory. *names_settings: an argument is "--settings", whose file the
 * parser would open (the harnesses leave such lists out: fuzz_settings_json covers the file). */
static inline int fuzz_args(const uint8_t *data, size_t size, char *program, char **argv, int max_args, char **text,
                            bool *names_settings) {
    *text = malloc(size + 1);
    if (!*text) return 0;
    memcpy(*text, data, size);
    (*text)[size] = '\0';
    int argc = 0;
    argv[argc++] = program;
    *names_settings = false;
    for (size_t at = 0; at <= size && argc <= max_args; at += strlen(*text + at) + 1) {
        *names_settings = *names_settings || strcmp(*text + at, "--settings") == 0;
        argv[argc++] = *text + at;
    }
    argv[argc] = NULL;
    return argc;
}

#endif
