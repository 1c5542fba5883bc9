/* inspect_args.h - what cacao-inspect is given, checked before anything runs: its command line, and
 * the cacao-bench JSON of `list --costs`. Kept apart from the commands (main.c) so that the fuzz
 * harnesses (tests/fuzz) drive exactly this code.
 *
 * The standard: whatever a command cannot use is refused with one line naming the argument, never
 * ignored; no value is wrapped, cut or read past (a size is digits, x, digits and nothing else). */
#ifndef CACAO_INSPECT_ARGS_H
#define CACAO_INSPECT_ARGS_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "options.h"

typedef enum inspect_command {
    INSPECT_USAGE, /* --help, also after a command: the usage on stdout */
    INSPECT_LIST,
    INSPECT_SHOW,
    INSPECT_PLAN,
    INSPECT_STATS,
    INSPECT_VERIFY,
    INSPECT_FACTS,
} inspect_command;

typedef struct inspect_args {
    inspect_command command;
    /* list */
    const char *pass;       /* only this pass (a name cacaoi_pass_name gives); NULL: every pass */
    int quality;            /* only keys of this quality (index of cacaoi_quality_names); -1: every one */
    bool json;              /* --json */
    const char *costs_path; /* --costs BENCH.json; NULL: none */
    /* show */
    const char *key; /* a well-formed permutation key (whether it is embedded is main.c's to say) */
    /* plan: --size, or the inputs of the cacao command in options (scene_dir or depth_path) */
    uint32_t width, height; /* 0: no --size */
    cli_options options;    /* the flags of the cacao command that plan takes */
} inspect_args;

/* Parses argv (argv[0] the program). On error writes one line into err, without the program's
 * name, and returns false. */
bool inspect_parse_args(int argc, char **argv, inspect_args *args, char *err, size_t err_size);

/* Reads the cacao-bench --json file of `list --costs`. Returns its root (caller deletes with
 * cJSON_Delete) only if every entry of its "results" array is an object with a printable string
 * "config" and, where it has "passes", an array of objects each with a string "name" and a finite
 * "time_ms" of 0 or more; else NULL with one line in err naming the file and the field (or the
 * JSON error's line and column). */
struct cJSON *inspect_read_costs(const char *path, char *err, size_t err_size);

#endif /* CACAO_INSPECT_ARGS_H */
