/* inspect_args.c - cacao-inspect's command line and its --costs JSON (see inspect_args.h). */
#include "inspect_args.h"

#include <cjson/cJSON.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cacao_keys.h"
#include "cacao_policy.h"
#include "cacao_shared.h"
#include "camera_json.h"
#include "image_io.h"

/* ---- list ----------------------------------------------------------------------------------------- */

/* Key quality (0-based) of a quality name, or -1. */
static int quality_from_word(const char *w) {
    cacao_quality q;
    return cacao_quality_from_name(w, &q) == CACAO_SUCCESS ? (int)cacaoi_key_quality(q) : -1;
}

static bool is_pass_name(const char *name) {
    for (unsigned p = 0; p < CACAO_PASS_COUNT; ++p)
        if (strcmp(name, cacaoi_pass_name(p)) == 0) return true;
    return false;
}

/* "a, b, c": the names of count things, by name_of. */
static void name_list(const char *(*name_of)(unsigned), unsigned count, char *out, size_t size) {
    out[0] = '\0';
    for (unsigned i = 0; i < count; ++i)
        snprintf(out + strlen(out), size - strlen(out), "%s%s", i ? ", " : "", name_of(i));
}

static const char *quality_name_of(unsigned q) { return cacao_quality_name((cacao_quality)(q + 1)); }

/* Applies --costs, --pass or --quality with its value; false after the message. */
static bool apply_list_value(const char *flag, const char *value, inspect_args *a, char *err, size_t n) {
    char choices[512];
    if (strcmp(flag, "--costs") == 0) {
        a->costs_path = value;
    } else if (strcmp(flag, "--pass") == 0) {
        a->pass = value;
        name_list(cacaoi_pass_name, CACAO_PASS_COUNT, choices, sizeof choices);
        if (!is_pass_name(value))
            return cacao_set_err(err, n, "list: --pass %s: no such pass (one of %s)", cacao_shown(value).text, choices);
    } else {
        a->quality = quality_from_word(value);
        name_list(quality_name_of, CACAO_KEY_QUALITY_COUNT, choices, sizeof choices);
        if (a->quality < 0)
            return cacao_set_err(err, n, "list: --quality %s: no such level (one of %s)", cacao_shown(value).text,
                                 choices);
    }
    return true;
}

static bool parse_list(int argc, char **argv, inspect_args *a, char *err, size_t n) {
    static const char *const valued[] = {"--costs", "--pass", "--quality"};
    bool given[4] = {false}; /* --json, then valued[] */
    for (int i = 0; i < argc; ++i) {
        const char *flag = argv[i];
        int k = strcmp(flag, "--json") == 0 ? 0 : -1;
        for (int v = 0; v < 3 && k < 0; ++v)
            if (strcmp(flag, valued[v]) == 0) k = v + 1;
        if (strcmp(flag, "--help") == 0 || strcmp(flag, "-h") == 0) {
            a->command = INSPECT_USAGE;
            return true;
        }
        if (k < 0) return cacao_set_err(err, n, "list: unknown argument '%s'", cacao_shown(flag).text);
        if (given[k]) return cacao_set_err(err, n, "list: %s is given twice", flag);
        given[k] = true;
        if (k == 0) {
            a->json = true;
            continue;
        }
        if (i + 1 >= argc || !argv[i + 1][0])
            return cacao_set_err(err, n, "list: %s needs a value (%s)", flag,
                                 k == 1   ? "a cacao-bench JSON file"
                                 : k == 2 ? "a pass name"
                                          : "a quality level");
        if (!apply_list_value(flag, argv[++i], a, err, n)) return false;
    }
    return true;
}

/* ---- show, stats, verify -------------------------------------------------------------------------- */

static bool wants_help(int argc, char **argv) {
    for (int i = 0; i < argc; ++i)
        if (strcmp(argv[i], "--help") == 0 || strcmp(argv[i], "-h") == 0) return true;
    return false;
}

static bool parse_show(int argc, char **argv, inspect_args *a, char *err, size_t n) {
    if (argc != 1) return cacao_set_err(err, n, "show: needs exactly one KEY (see 'cacao-inspect list')");
    cacao_key key;
    if (!cacaoi_key_parse(argv[0], &key))
        return cacao_set_err(err, n, "show: '%s' is not a permutation key", cacao_shown(argv[0]).text);
    a->key = argv[0];
    return true;
}

/* ---- plan ----------------------------------------------------------------------------------------- */

/* One side of WxH: digits only, 1..CACAO_MAX_SIZE, no sign, space or leading zero. */
static bool parse_side(const char *text, size_t length, uint32_t *out) {
    if (length == 0 || length > 5 || text[0] == '0') return false;
    uint32_t v = 0;
    for (size_t i = 0; i < length; ++i) {
        if (text[i] < '0' || text[i] > '9') return false;
        v = v * 10 + (uint32_t)(text[i] - '0');
    }
    *out = v;
    return v >= 1 && v <= CACAO_MAX_SIZE;
}

static bool parse_size(const char *text, uint32_t *w, uint32_t *h, char *err, size_t n) {
    const char *x = strchr(text, 'x');
    if (x && parse_side(text, (size_t)(x - text), w) && parse_side(x + 1, strlen(x + 1), h)) return true;
    *w = *h = 0;
    return cacao_set_err(err, n, "--size %s: needs WxH, each a whole number from 1 to %d", cacao_shown(text).text,
                         CACAO_MAX_SIZE);
}

/* The flags of the cacao command that plan refuses: those of its outputs and actions (plan prints
 * the plan and writes nothing), and, with --size, those of a frame (plan --size runs none). */
static bool refuse_plan_flags(const inspect_args *a, bool runs_frame, char *err, size_t n) {
    static const char *const never[] = {"--output",  "--bits",           "--png16",       "--compare",
                                        "--timings", "--repeat",         "--warmup",      "--json",
                                        "--version", "--print-settings", "--list-devices"};
    static const char *const frame[] = {"--device", "--validate", "--frame",   "--reverse-z", "--fov",
                                        "--near",   "--far",      "--normals", "--camera"};
    for (size_t i = 0; i < sizeof never / sizeof never[0]; ++i)
        if (cli_given(&a->options, never[i]))
            return cacao_set_err(
                err, n, "plan: %s is a flag of the cacao command; plan prints the plan and writes nothing", never[i]);
    for (size_t i = 0; !runs_frame && i < sizeof frame / sizeof frame[0]; ++i)
        if (cli_given(&a->options, frame[i]))
            return cacao_set_err(err, n, "plan --size: %s is for a plan of --scene or --depth, which runs a frame",
                                 frame[i]);
    return cli_check_estimator_flags(&a->options, a->options.settings.estimator, "this plan", err, n);
}

static bool parse_plan(int argc, char **argv, inspect_args *a, char *err, size_t n) {
    char **rest = calloc((size_t)argc + 1, sizeof *rest);
    if (!rest) return cacao_set_err(err, n, "plan: out of memory");
    int count = 0;
    bool ok = true;
    rest[count++] = "cacao-inspect plan";
    for (int i = 0; ok && i < argc; ++i) {
        if (strcmp(argv[i], "--size") != 0) {
            rest[count++] = argv[i];
        } else if (a->width) {
            ok = cacao_set_err(err, n, "--size is given twice");
        } else if (i + 1 >= argc) {
            ok = cacao_set_err(err, n, "--size: needs a value (WxH)");
        } else {
            ok = parse_size(argv[++i], &a->width, &a->height, err, n);
        }
    }
    char why[1024];
    if (ok && !cli_parse(count, rest, &a->options, why, sizeof why)) ok = cacao_set_err(err, n, "plan: %s", why);
    free(rest);
    if (!ok) return false;
    if (a->options.help) {
        a->command = INSPECT_USAGE;
        return true;
    }
    const bool on_inputs = a->options.scene_dir || a->options.depth_path;
    if (on_inputs && a->width)
        return cacao_set_err(err, n, "--size: not with --scene or --depth (the size is the depth's)");
    if (!on_inputs && !a->width) return cacao_set_err(err, n, "plan needs --size WxH, --scene DIR or --depth FILE");
    return refuse_plan_flags(a, on_inputs, err, n);
}

/* ---- The command ---------------------------------------------------------------------------------- */

bool inspect_parse_args(int argc, char **argv, inspect_args *a, char *err, size_t n) {
    memset(a, 0, sizeof *a);
    a->quality = -1;
    if (argc < 2 || strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0) {
        a->command = INSPECT_USAGE;
        return argc < 2 || argc == 2
                   ? true
                   : cacao_set_err(err, n, "%s: takes nothing after it (got '%s')", argv[1], cacao_shown(argv[2]).text);
    }
    static const struct {
        const char *name;
        inspect_command command;
    } commands[] = {{"list", INSPECT_LIST},
                    {"show", INSPECT_SHOW},
                    {"plan", INSPECT_PLAN},
                    {"stats", INSPECT_STATS},
                    {"verify", INSPECT_VERIFY},
                    {"facts", INSPECT_FACTS}};
    const char *name = argv[1];
    int rest_count = argc - 2;
    char **rest = argv + 2;
    for (size_t i = 0; i < sizeof commands / sizeof commands[0]; ++i) {
        if (strcmp(name, commands[i].name) != 0) continue;
        a->command = commands[i].command;
        if (a->command != INSPECT_LIST && a->command != INSPECT_PLAN && wants_help(rest_count, rest)) {
            a->command = INSPECT_USAGE;
            return true;
        }
        switch (a->command) {
        case INSPECT_LIST:
            return parse_list(rest_count, rest, a, err, n);
        case INSPECT_SHOW:
            return parse_show(rest_count, rest, a, err, n);
        case INSPECT_PLAN:
            return parse_plan(rest_count, rest, a, err, n);
        default:
            return rest_count == 0
                       ? true
                       : cacao_set_err(err, n, "%s: takes no arguments (got '%s')", name, cacao_shown(rest[0]).text);
        }
    }
    return cacao_set_err(err, n, "unknown command '%s' (see cacao-inspect --help)", cacao_shown(name).text);
}

/* ---- --costs ------------------------------------------------------------------------------------- */

/* Checks one entry of "results" (where = "results[3]"); false after the message. */
static bool check_cost_result(const cJSON *r, const char *path, const char *where, char *err, size_t n) {
    if (!cJSON_IsObject(r)) return cacao_set_err(err, n, "--costs %s: %s: not an object", path, where);
    const cJSON *config = cJSON_GetObjectItemCaseSensitive(r, "config");
    if (!cJSON_IsString(config) || !cacao_text_is_printable(config->valuestring))
        return cacao_set_err(err, n, "--costs %s: %s.config: needs a string without control characters", path, where);
    const cJSON *passes = cJSON_GetObjectItemCaseSensitive(r, "passes"), *p;
    if (passes && !cJSON_IsArray(passes))
        return cacao_set_err(err, n, "--costs %s: %s.passes: not an array", path, where);
    int i = 0;
    cJSON_ArrayForEach(p, passes) {
        const cJSON *ms = cJSON_GetObjectItemCaseSensitive(p, "time_ms");
        if (!cJSON_IsObject(p) || !cJSON_IsString(cJSON_GetObjectItemCaseSensitive(p, "name")) || !cJSON_IsNumber(ms) ||
            !isfinite(ms->valuedouble) || ms->valuedouble < 0)
            return cacao_set_err(err, n,
                                 "--costs %s: %s.passes[%d]: needs a string \"name\" and a finite \"time_ms\" "
                                 "of 0 or more",
                                 path, where, i);
        ++i;
    }
    return true;
}

cJSON *inspect_read_costs(const char *path, char *err, size_t n) {
    char why[1024], file[512];
    cacao_escape_text(path, file, sizeof file);
    cJSON *root = cacao_json_read_object(path, 256u << 20, why, sizeof why);
    if (!root) {
        cacao_set_err(err, n, "--costs %s", why);
        return NULL;
    }
    const cJSON *results = cJSON_GetObjectItemCaseSensitive(root, "results");
    bool ok = cJSON_IsArray(results) ||
              cacao_set_err(err, n, "--costs %s: not a cacao-bench JSON (no \"results\" array)", file);
    int i = 0;
    for (const cJSON *r = ok ? results->child : NULL; ok && r; r = r->next) {
        char where[32];
        snprintf(where, sizeof where, "results[%d]", i++);
        ok = check_cost_result(r, file, where, err, n);
    }
    if (!ok) {
        cJSON_Delete(root);
        return NULL;
    }
    return root;
}
