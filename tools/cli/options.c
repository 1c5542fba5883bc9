/* options.c - the flag table, argument parsing and the settings JSON of the `cacao` command. */
#include "options.h"

#include <cjson/cJSON.h>
#include <float.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#include "camera_json.h"
#include "image_io.h"

_Static_assert(sizeof(cacao_quality) == sizeof(int) && sizeof(cacao_precision) == sizeof(int),
               "enum settings are stored through int");

typedef enum flag_kind {
    FLAG_SECTION,       /* a heading of --help, not a flag */
    FLAG_PATH,          /* const char * of cli_options */
    FLAG_SETTINGS_FILE, /* the --settings file (read before the other flags apply) */
    FLAG_SWITCH,        /* bool of cli_options, set to true */
    FLAG_COUNT,         /* uint32_t of cli_options, 1..100000 */
    FLAG_COUNT0,        /* uint32_t of cli_options, 0..100000 */
    FLAG_POSITIVE,      /* double of cli_options, finite and > 0 */
    FLAG_BITS,          /* uint32_t of cli_options, 8 or 16 */
    SET_FLOAT,          /* float of cacao_settings */
    SET_FLOAT_PAIR,     /* two floats of cacao_settings, given as FROM,TO */
    SET_BLUR,           /* blur_pass_count, literal 0..8 */
    SET_ENUM,           /* an enum of cacao_settings, by name */
    SET_BOOL,           /* bool of cacao_settings; the flag sets it true */
    SET_INT,            /* int of cacao_settings, a whole number 0..int_max (0 = the runtime's default) */
} flag_kind;

typedef struct flag_def {
    const char *name;  /* "--radius" (FLAG_SECTION: the heading) */
    const char *alias; /* "-o" or NULL */
    const char *value; /* the value's name in --help; NULL for switches */
    flag_kind kind;
    size_t offset;    /* into cli_options (FLAG_*) or cacao_settings (SET_*) */
    const char *json; /* SET_*: key in the settings JSON */
    const char *help;
    size_t offset2; /* SET_FLOAT_PAIR: the second field */
    const char *json2;
    const char *(*name_of)(int value); /* SET_ENUM: the runtime's name of a value; NULL past the last */
    int int_max; /* SET_INT: largest value */
    unsigned estimators; /* the estimators it applies to, a bit per cacao_estimator; 0 = every one */
} flag_def;

/* cacao.h's names of the enum settings, for the int the table stores. */
static const char *quality_name(int value) { return cacao_quality_name((cacao_quality)value); }
static const char *precision_name(int value) { return cacao_precision_name((cacao_precision)value); }
static const char *estimator_name(int value) { return cacao_estimator_name((cacao_estimator)value); }
static const char *visibility_name(int value) { return cacao_visibility_name((cacao_visibility)value); }
static const char *shader_forms_name(int value) { return cacao_shader_forms_name((cacao_shader_forms)value); }
#define ESTIMATOR_NAME_COUNT (CACAO_ESTIMATOR_BITMASK + 1) /* the values, DEFAULT (0) included */
#define HORIZON_ESTIMATORS ((1u << CACAO_ESTIMATOR_GTAO) | (1u << CACAO_ESTIMATOR_BITMASK))

#define SECTION(title)                                                                                                 \
    { .name = title, .kind = FLAG_SECTION }
#define OPT(flag, alias_, value_, kind_, field, help_)                                                                 \
    {                                                                                                                  \
        .name = flag, .alias = alias_, .value = value_, .kind = kind_, .offset = offsetof(cli_options, field),         \
        .help = help_                                                                                                  \
    }
#define SET(flag, value_, kind_, field, help_)                                                                         \
    {                                                                                                                  \
        .name = flag, .value = value_, .kind = kind_, .offset = offsetof(cacao_settings, field), .json = #field,       \
        .help = help_                                                                                                  \
    }

static const flag_def flags[] = {
    SECTION("Input (none given: the embedded test scene, 1280x720)"),
    OPT("--scene", NULL, "DIR", FLAG_PATH, scene_dir,
        "scene folder: depth.pfm (depth_reversed.pfm with --reverse-z), optional normals.pfm, camera.json"),
    OPT("--depth", NULL, "FILE", FLAG_PATH, depth_path,
        "depth image, raw [0,1] depth as the projection writes it: 1-channel .pfm, .exr (channel Z, R, Y or the "
        "only one) or 16-bit grey .png (value/65535; 8-bit PNG is refused as too coarse); 1 to 16384 pixels per "
        "side"),
    OPT("--normals", NULL, "FILE", FLAG_PATH, normals_path,
        "unit view-space normals, right-handed (+z towards the camera): 3-channel .pfm or .exr (R,G,B or X,Y,Z); "
        "without it normals are reconstructed from depth; depth with normals is staged together, at most "
        "214,748,364 pixels (about 14650x14650)"),
    OPT("--camera", NULL, "FILE", FLAG_PATH, camera_path,
        "camera.json: fov_y_deg, near, far; optional projection, projection_reversed, ao_radius_world"),
    OPT("--fov", NULL, "DEG", FLAG_POSITIVE, fov_y_deg,
        "vertical field of view (with --near/--far instead of, or "
        "overriding, the camera file)"),
    OPT("--near", NULL, "Z", FLAG_POSITIVE, near_z, "near plane distance"),
    OPT("--far", NULL, "Z", FLAG_POSITIVE, far_z, "far plane distance"),
    OPT("--reverse-z", NULL, NULL, FLAG_SWITCH, reverse_z, "depth is reverse-Z (1 = near, 0 = far)"),
    SECTION("Output"),
    OPT("--output", "-o", "FILE", FLAG_PATH, output_path,
        "AO visibility (1 = unoccluded), full size, top row first: .png, .pfm or .exr (channel Y); "
        "default cacao-out.png"),
    OPT("--bits", NULL, "N", FLAG_BITS, png_bits, "PNG sample depth, 8 (default) or 16"),
    OPT("--png16", NULL, NULL, FLAG_SWITCH, png16, "same as --bits 16"),
    OPT("--compare", NULL, "GT", FLAG_PATH, compare_path,
        "print RMSE, mean-abs and p99 error against a ground-truth AO image over non-background pixels"),
    OPT("--timings", NULL, NULL, FLAG_SWITCH, timings,
        "print per-pass GPU times (ms): median, min and max of the --repeat frames timed after --warmup"),
    OPT("--repeat", NULL, "N", FLAG_COUNT, repeat, "time the frame N times (default 1)"),
    OPT("--warmup", NULL, "N", FLAG_COUNT0, warmup,
        "run N untimed frames first (default 2; on lavapipe the first frames compile shader variants)"),
    OPT("--move-box", NULL, "X,Y,W,H", FLAG_PATH, move_box,
        "with --reuse: every other frame shifts the depth inside the box 8 pixels "
        "right, an object moving: each frame after the first changes those tiles"),
    OPT("--move-camera", NULL, NULL, FLAG_SWITCH, move_camera,
        "every other frame, the projection's x scale one part in a million larger: a camera that "
        "moves every frame (with --reuse: every frame a full one)"),
    OPT("--keep-output", NULL, NULL, FLAG_SWITCH, keep_output,
        "with --reuse: tell cacao the output holds its last frame (output_holds_previous): a frame "
        "with nothing changed writes nothing"),
    OPT("--json", NULL, "FILE", FLAG_PATH, json_path,
        "write settings, device, per-pass times, total, output path (and --compare errors) as JSON"),
    OPT("--print-settings", NULL, NULL, FLAG_SWITCH, print_settings,
        "print the effective settings as JSON (the --settings schema) and exit without rendering"),
    SECTION("Settings (defaults are the runtime's; flags override --settings wherever they stand)"),
    OPT("--settings", NULL, "FILE", FLAG_SETTINGS_FILE, settings_path,
        "read settings from JSON (keys as --print-settings writes them; absent keys keep their defaults)"),
    {.name = "--quality",
     .value = "LEVEL",
     .kind = SET_ENUM,
     .offset = offsetof(cacao_settings, quality),
     .json = "quality",
     .help = "lowest, low, medium, high or highest",
     .name_of = quality_name},
    SET("--downsample", NULL, SET_BOOL, downsample, "compute AO at quarter resolution, bilateral upsample"),
    SET("--blur", "N", SET_BLUR, blur_pass_count, "edge-aware blur passes, 0 (none) to 8"),
    SET("--radius", "R", SET_FLOAT, radius, "world-space AO radius; a camera's ao_radius_world replaces the default"),
    SET("--strength", "X", SET_FLOAT, shadow_multiplier, "AO strength (shadow multiplier), 0..5"),
    SET("--power", "X", SET_FLOAT, shadow_power, "AO contrast exponent, 0..10"),
    SET("--clamp", "X", SET_FLOAT, shadow_clamp, "largest occlusion before shaping, 0..1"),
    SET("--horizon", "X", SET_FLOAT, horizon_angle_threshold, "ignore samples this close to the surface plane, 0..1"),
    {.name = "--fade-out",
     .value = "FROM,TO",
     .kind = SET_FLOAT_PAIR,
     .offset = offsetof(cacao_settings, fade_out_from),
     .json = "fade_out_from",
     .offset2 = offsetof(cacao_settings, fade_out_to),
     .json2 = "fade_out_to",
     .help = "view distances where AO starts and finishes fading out"},
    SET("--sharpness", "X", SET_FLOAT, sharpness, "blur edge sharpness, 0..1"),
    SET("--detail", "X", SET_FLOAT, detail_shadow_strength, "small-scale detail AO strength, 0..5"),
    SET("--adaptive-limit", "X", SET_FLOAT, adaptive_quality_limit, "highest quality: mean importance budget, 0..1"),
    SET("--bilateral-sigma", "X", SET_FLOAT, bilateral_sigma_squared, "downsampled upsample: spatial variance"),
    SET("--bilateral-similarity", "X", SET_FLOAT, bilateral_similarity_distance_sigma,
        "downsampled upsample: depth variance"),
    {.name = "--precision",
     .value = "P",
     .kind = SET_ENUM,
     .offset = offsetof(cacao_settings, precision),
     .json = "precision",
     .help = "fp32 or fp16 (fp16 falls back to fp32 where the device lacks it)",
     .name_of = precision_name},
    SET("--no-normals", NULL, SET_BOOL, generate_normals,
        "reconstruct normals from depth even when normals are given (automatic without normals)"),
    SET("--all-tiles", NULL, SET_BOOL, compute_all_tiles,
        "skip nothing: every tile, and the taps of background and faded pixels (docs/tiles.md): the "
        "same output, slower; for measurement"),
    SET("--reuse", NULL, SET_BOOL, reuse_unchanged,
        "reuse the previous frame where nothing changed (docs/tiles.md); with --repeat every frame "
        "after the first is unchanged, unless --move-box changes some"),
    {.name = "--shader-forms",
     .value = "F",
     .kind = SET_ENUM,
     .offset = offsetof(cacao_settings, shader_forms),
     .json = "shader_forms",
     .help = "cpu or gpu: the shapes of the shaders (the same output; gpu: fewer texels per "
             "invocation, shared memory, no tile lists); the default picks by the device, cpu on lavapipe",
     .name_of = shader_forms_name},
    SECTION("Estimator (docs/estimators.md)"),
    {.name = "--estimator",
     .value = "E",
     .kind = SET_ENUM,
     .offset = offsetof(cacao_settings, estimator),
     .json = "estimator",
     .help = "cacao (AMD CACAO's look), gtao or bitmask (horizon-slice estimators of ray-traced visibility, full "
             "resolution; --quality picks their budget, --blur their denoise passes)",
     .name_of = estimator_name},
    {.name = "--visibility",
     .value = "V",
     .kind = SET_ENUM,
     .offset = offsetof(cacao_settings, visibility),
     .json = "visibility",
     .help = "gtao/bitmask: falloff (occluders weighted 1 - t^2/R^2 by hit distance t) or binary (occluded "
             "within R)",
     .name_of = visibility_name,
     .estimators = HORIZON_ESTIMATORS},
    {.name = "--frame",
     .value = "N",
     .kind = FLAG_COUNT0,
     .offset = offsetof(cli_options, frame_index),
     .help = "gtao/bitmask: frame index of the sample pattern (temporal accumulation; 0 = deterministic)",
     .estimators = HORIZON_ESTIMATORS},
    {.name = "--thickness",
     .value = "T",
     .kind = SET_FLOAT,
     .offset = offsetof(cacao_settings, thickness),
     .json = "thickness",
     .help = "bitmask: assumed occluder thickness, world units (default 1.0 R falloff, 0.5 R binary)",
     .estimators = 1u << CACAO_ESTIMATOR_BITMASK},
    {.name = "--slices",
     .value = "N",
     .kind = SET_INT,
     .offset = offsetof(cacao_settings, horizon_slices),
     .json = "horizon_slices",
     .help = "gtao/bitmask: slices per pixel, 1..16 (0 = by quality)",
     .int_max = 16,
     .estimators = HORIZON_ESTIMATORS},
    {.name = "--steps",
     .value = "N",
     .kind = SET_INT,
     .offset = offsetof(cacao_settings, horizon_steps),
     .json = "horizon_steps",
     .help = "gtao/bitmask: steps per slice side, 1..32 (0 = by quality); depth reads = 2 x slices x steps",
     .int_max = 32,
     .estimators = HORIZON_ESTIMATORS},
    {.name = "--temporal",
     .value = "N",
     .kind = SET_INT,
     .offset = offsetof(cacao_settings, temporal_frames),
     .json = "temporal_frames",
     .help = "gtao/bitmask: temporal accumulation over up to N frames, 2..64 (0 = off); with --repeat the "
             "frames advance the sample pattern (--frame, +1 a frame) under a still camera",
     .int_max = 64,
     .estimators = HORIZON_ESTIMATORS},
    SECTION("Device"),
    OPT("--device", NULL, "N|NAME", FLAG_PATH, device, "Vulkan device by index or name substring (default lavapipe)"),
    OPT("--list-devices", NULL, NULL, FLAG_SWITCH, list_devices, "list the Vulkan devices and exit"),
    OPT("--validate", NULL, NULL, FLAG_SWITCH, validate,
        "Khronos validation with synchronization validation; any message fails the run"),
    SECTION("Other"),
    OPT("--help", "-h", NULL, FLAG_SWITCH, help, "show this help and exit"),
    OPT("--version", NULL, NULL, FLAG_SWITCH, version, "print the version and embedded permutation count and exit"),
};
#define FLAG_COUNT_ALL (sizeof flags / sizeof flags[0])
_Static_assert(FLAG_COUNT_ALL <= CLI_FLAG_SLOTS, "cli_options.given has a slot per entry of the flag table");

static bool is_setting(const flag_def *def) { return def->kind >= SET_FLOAT; }

static const flag_def *find_flag(const char *arg) {
    for (size_t i = 0; i < FLAG_COUNT_ALL; ++i)
        if (flags[i].kind != FLAG_SECTION &&
            (strcmp(arg, flags[i].name) == 0 || (flags[i].alias && strcmp(arg, flags[i].alias) == 0)))
            return &flags[i];
    return NULL;
}

/* ---- Literal values to cacao_settings' encoding --------------------------------------------- */

static float *float_field(cacao_settings *s, size_t offset) { return (float *)((char *)s + offset); }
static int *int_field(cacao_settings *s, size_t offset) { return (int *)((char *)s + offset); }
static bool *bool_field(cacao_settings *s, size_t offset) { return (bool *)((char *)s + offset); }

/* Whether the runtime takes CACAO_ZERO (a literal 0) for this float field: asked of the runtime
 * itself, so its one definition of the ranges stays the only one. */
static bool runtime_accepts_zero(size_t offset) {
    cacao_settings probe = {0}, resolved;
    *float_field(&probe, offset) = CACAO_ZERO;
    return cacao_settings_resolve(&probe, &resolved, NULL, 0) == CACAO_SUCCESS;
}

/* Whether the runtime's default of this float field is 0 itself (a default that depends on other
 * settings), so that a literal 0 is simply that default. */
static bool runtime_default_is_zero(size_t offset) {
    cacao_settings probe = {0}, resolved;
    return cacao_settings_resolve(&probe, &resolved, NULL, 0) == CACAO_SUCCESS && *float_field(&resolved, offset) == 0.0f;
}

/* A literal above the largest float: the runtime's range message for this field (asked with the
 * largest float, its value left out, as it is not the user's), else that the float range ends there. */
static bool refuse_beyond_float(size_t offset, const char *label, char *err, size_t n) {
    cacao_settings probe = {0}, resolved;
    *float_field(&probe, offset) = FLT_MAX;
    char why[256];
    if (cacao_settings_resolve(&probe, &resolved, why, sizeof why) == CACAO_SUCCESS)
        return cacao_set_err(err, n, "%s: larger than the largest float, %g", label, (double)FLT_MAX);
    const char *value = strstr(why, " = "), *range = strstr(why, " is outside ");
    if (value && range && value < range)
        return cacao_set_err(err, n, "%s: %.*s%s", label, (int)(value - why), why, range);
    return cacao_set_err(err, n, "%s: %s", label, why);
}

/* Stores a literal float: finite, not negative, 0 as CACAO_ZERO where the runtime allows 0. The
 * range is checked on the double as given, before the conversion: a value beyond the float range
 * gets the range message, and one that is nonzero but would become 0 (the default) or a denormal
 * float is refused rather than changed. */
static bool store_float(size_t offset, double literal, cacao_settings *s, const char *label, char *err, size_t n) {
    if (!isfinite(literal)) {
        cacao_set_err(err, n, "%s: not a finite number", label);
        return false;
    }
    if (literal < 0.0) {
        cacao_set_err(err, n, "%s: must not be negative", label);
        return false;
    }
    if (literal > FLT_MAX) return refuse_beyond_float(offset, label, err, n);
    if (literal > 0.0 && literal < FLT_MIN)
        return cacao_set_err(err, n, "%s: too small to keep: a nonzero value must be at least %g (a float)", label,
                             (double)FLT_MIN);
    if (literal == 0.0 && runtime_default_is_zero(offset)) { /* e.g. thickness: 0 = relative to R */
        *float_field(s, offset) = 0.0f;
        return true;
    }
    if (literal == 0.0 && !runtime_accepts_zero(offset)) {
        cacao_set_err(err, n, "%s: must be greater than 0", label);
        return false;
    }
    *float_field(s, offset) = literal == 0.0 ? CACAO_ZERO : (float)literal;
    return true;
}

static bool store_blur(double literal, cacao_settings *s, const char *label, char *err, size_t n) {
    if (!(literal >= 0 && literal <= 8) || literal != floor(literal)) {
        cacao_set_err(err, n, "%s: must be a whole number of passes, 0 (no blur) to 8", label);
        return false;
    }
    s->blur_pass_count = literal == 0 ? CACAO_BLUR_NONE : (int)literal;
    return true;
}

static bool store_int(const flag_def *def, double literal, cacao_settings *s, const char *label, char *err,
                      size_t n) {
    if (!(literal >= 0 && literal <= def->int_max) || literal != floor(literal)) {
        cacao_set_err(err, n, "%s: must be a whole number, 0 (default) to %d", label, def->int_max);
        return false;
    }
    *int_field(s, def->offset) = (int)literal;
    return true;
}

static bool store_enum(const flag_def *def, const char *name, cacao_settings *s, const char *label, char *err,
                       size_t n) {
    for (int i = 1; def->name_of(i); ++i)
        if (strcmp(name, def->name_of(i)) == 0) {
            *int_field(s, def->offset) = i;
            return true;
        }
    char choices[128] = "";
    for (int i = 1; def->name_of(i); ++i)
        snprintf(choices + strlen(choices), sizeof choices - strlen(choices), "%s%s", i > 1 ? ", " : "",
                 def->name_of(i));
    cacao_set_err(err, n, "%s: unknown value '%s' (one of %s)", label, cacao_shown(name).text, choices);
    return false;
}

/* Checks one setting against the runtime's ranges: resolves settings holding only that setting
 * (both halves of a pair), so the message is about this flag or key alone. */
static bool check_with_runtime(const flag_def *def, const cacao_settings *s, const char *label, char *err, size_t n) {
    cacao_settings probe = {0}, resolved;
    const size_t size = def->kind == SET_BOOL ? sizeof(bool) : sizeof(float);
    memcpy((char *)&probe + def->offset, (const char *)s + def->offset, size);
    if (def->kind == SET_FLOAT_PAIR) memcpy((char *)&probe + def->offset2, (const char *)s + def->offset2, size);
    /* a setting of some estimators only is checked with the first of them (whether the run's
     * estimator takes it is the estimators mask's check) */
    for (int e = CACAO_ESTIMATOR_CACAO; def->estimators && e <= CACAO_ESTIMATOR_BITMASK; ++e)
        if (def->estimators & (1u << e)) {
            probe.estimator = (cacao_estimator)e;
            break;
        }
    char why[256];
    if (cacao_settings_resolve(&probe, &resolved, why, sizeof why) == CACAO_SUCCESS) return true;
    cacao_set_err(err, n, "%s: %s", label, why);
    return false;
}

static void note_setting(const flag_def *def, cli_options *o) {
    if (def->kind == SET_FLOAT && def->offset == offsetof(cacao_settings, radius)) o->radius_given = true;
}

/* ---- Flags ---------------------------------------------------------------------------------- */

static bool parse_number(const char *text, double *out) {
    char *end = NULL;
    *out = strtod(text, &end);
    return end != text && *end == '\0';
}

static bool parse_number_flag(const char *text, double *out, const char *label, char *err, size_t n) {
    if (parse_number(text, out)) return true;
    cacao_set_err(err, n, "%s: not a number", label);
    return false;
}

static bool apply_pair_flag(const flag_def *def, const char *value, cacao_settings *s, const char *label, char *err,
                            size_t n) {
    const char *comma = strchr(value, ',');
    char first[64];
    if (!comma || (size_t)(comma - value) >= sizeof first) {
        cacao_set_err(err, n, "%s: expected two numbers FROM,TO", label);
        return false;
    }
    memcpy(first, value, (size_t)(comma - value));
    first[comma - value] = '\0';
    double from, to;
    if (!parse_number(first, &from) || !parse_number(comma + 1, &to)) {
        cacao_set_err(err, n, "%s: expected two numbers FROM,TO", label);
        return false;
    }
    return store_float(def->offset, from, s, label, err, n) && store_float(def->offset2, to, s, label, err, n);
}

static bool apply_setting_flag(const flag_def *def, const char *value, cli_options *o, char *err, size_t n) {
    char label[320]; /* the flag and its value as given, control bytes escaped */
    snprintf(label, sizeof label, "%s%s%s", def->name, value ? " " : "", value ? cacao_shown(value).text : "");
    double number = 0;
    bool ok = true;
    switch (def->kind) {
    case SET_FLOAT:
        ok = parse_number_flag(value, &number, label, err, n) &&
             store_float(def->offset, number, &o->settings, label, err, n);
        break;
    case SET_FLOAT_PAIR:
        ok = apply_pair_flag(def, value, &o->settings, label, err, n);
        break;
    case SET_BLUR:
        ok = parse_number_flag(value, &number, label, err, n) && store_blur(number, &o->settings, label, err, n);
        break;
    case SET_ENUM:
        ok = store_enum(def, value, &o->settings, label, err, n);
        break;
    case SET_INT:
        ok = parse_number_flag(value, &number, label, err, n) && store_int(def, number, &o->settings, label, err, n);
        break;
    case SET_BOOL:
        *bool_field(&o->settings, def->offset) = true;
        break;
    default:
        break;
    }
    if (!ok || !check_with_runtime(def, &o->settings, label, err, n)) return false;
    note_setting(def, o);
    return true;
}

static bool apply_option_flag(const flag_def *def, const char *value, cli_options *o, char *err, size_t n) {
    void *field = (char *)o + def->offset;
    double number = 0;
    switch (def->kind) {
    case FLAG_PATH:
    case FLAG_SETTINGS_FILE:
        if (!value[0]) {
            cacao_set_err(err, n, "%s: empty value", def->name);
            return false;
        }
        *(const char **)field = value;
        return true;
    case FLAG_SWITCH:
        *(bool *)field = true;
        return true;
    case FLAG_POSITIVE:
        if (!parse_number(value, &number) || !isfinite(number) || number <= 0) {
            cacao_set_err(err, n, "%s %s: must be a finite number greater than 0", def->name, cacao_shown(value).text);
            return false;
        }
        *(double *)field = number;
        return true;
    case FLAG_COUNT:
    case FLAG_COUNT0:
    case FLAG_BITS: {
        const bool bits = def->kind == FLAG_BITS;
        const double low = def->kind == FLAG_COUNT0 ? 0 : 1;
        const bool ok = parse_number(value, &number) && number == floor(number) &&
                        (bits ? (number == 8 || number == 16) : (number >= low && number <= 100000));
        if (!ok) {
            cacao_set_err(err, n, "%s %s: must be %s", def->name, cacao_shown(value).text,
                    bits  ? "8 or 16"
                    : low ? "a whole number from 1 to 100000"
                          : "a whole number from 0 to 100000");
            return false;
        }
        *(uint32_t *)field = (uint32_t)number;
        return true;
    }
    default:
        return false;
    }
}

/* One walk over argv. The first pass applies only --settings; the second everything else. */
static bool parse_pass(int argc, char **argv, cli_options *o, bool settings_file_pass, char *err, size_t n) {
    for (int i = 1; i < argc; ++i) {
        const flag_def *def = find_flag(argv[i]);
        if (!def) {
            char shown[256];
            cacao_escape_text(argv[i], shown, sizeof shown);
            cacao_set_err(err, n,
                    argv[i][0] == '-' ? "%s: unknown flag (see --help)" : "%s: unexpected argument (see --help)",
                    shown);
            return false;
        }
        const char *value = NULL;
        if (def->value) {
            if (i + 1 >= argc || find_flag(argv[i + 1])) { /* "--quality -o x.png": --quality lacks its value */
                cacao_set_err(err, n, "%s: needs a value (%s)%s%s", argv[i], def->value, i + 1 < argc ? " before " : "",
                        i + 1 < argc ? argv[i + 1] : "");
                return false;
            }
            value = argv[++i];
        }
        if ((def->kind == FLAG_SETTINGS_FILE) != settings_file_pass) continue;
        const bool ok =
            is_setting(def) ? apply_setting_flag(def, value, o, err, n) : apply_option_flag(def, value, o, err, n);
        if (!ok) return false;
        o->given[def - flags] = true;
    }
    return true;
}

/* ---- Settings JSON -------------------------------------------------------------------------- */

static const flag_def *find_json_key(const char *key, size_t *offset) {
    for (size_t i = 0; i < FLAG_COUNT_ALL; ++i) {
        if (!is_setting(&flags[i])) continue;
        if (strcmp(key, flags[i].json) == 0)
            *offset = flags[i].offset;
        else if (flags[i].json2 && strcmp(key, flags[i].json2) == 0)
            *offset = flags[i].offset2;
        else
            continue;
        return &flags[i];
    }
    return NULL;
}

static bool apply_json_item(const flag_def *def, size_t offset, const cJSON *item, cli_options *o, const char *label,
                            char *err, size_t n) {
    const bool want_number =
        def->kind == SET_FLOAT || def->kind == SET_FLOAT_PAIR || def->kind == SET_BLUR || def->kind == SET_INT;
    if (want_number && !cJSON_IsNumber(item)) {
        cacao_set_err(err, n, "%s: must be a number", label);
        return false;
    }
    if ((def->kind == SET_ENUM && !cJSON_IsString(item)) || (def->kind == SET_BOOL && !cJSON_IsBool(item))) {
        cacao_set_err(err, n, "%s: must be %s", label, def->kind == SET_ENUM ? "a string" : "true or false");
        return false;
    }
    switch (def->kind) {
    case SET_FLOAT:
    case SET_FLOAT_PAIR:
        return store_float(offset, item->valuedouble, &o->settings, label, err, n);
    case SET_BLUR:
        return store_blur(item->valuedouble, &o->settings, label, err, n);
    case SET_ENUM:
        return store_enum(def, item->valuestring, &o->settings, label, err, n);
    case SET_INT:
        return store_int(def, item->valuedouble, &o->settings, label, err, n);
    case SET_BOOL:
        *bool_field(&o->settings, offset) = cJSON_IsTrue(item);
        return true;
    default:
        return false;
    }
}

/* Applies every key, then checks each setting the file gave (pairs once both halves are in).
 * Flags override the file: a key whose flag is on the command line (overridden[flag]) is checked
 * to be a known key and is otherwise left alone, so only the values that are used are validated. */
static bool apply_json_settings(const cJSON *root, const char *path, const bool *overridden, cli_options *o, char *err,
                                size_t n) {
    bool given[FLAG_COUNT_ALL] = {false};
    char label[512], key[256];
    for (const cJSON *item = root->child; item; item = item->next) {
        size_t offset = 0;
        const flag_def *def = find_json_key(item->string, &offset);
        cacao_escape_text(item->string, key, sizeof key);
        snprintf(label, sizeof label, "%s: \"%s\"", path, key);
        if (!def) {
            cacao_set_err(err, n, "%s: unknown setting (see --print-settings for the schema)", label);
            return false;
        }
        if (overridden[def - flags]) continue;
        if (!apply_json_item(def, offset, item, o, label, err, n)) return false;
        given[def - flags] = true;
        note_setting(def, o);
    }
    for (size_t i = 0; i < FLAG_COUNT_ALL; ++i) {
        snprintf(label, sizeof label, "%s: \"%s\"", path, flags[i].json ? flags[i].json : "");
        if (given[i] && !check_with_runtime(&flags[i], &o->settings, label, err, n)) return false;
    }
    return true;
}

static bool load_settings_file(const char *path, const bool *overridden, cli_options *o, char *err, size_t n) {
    cJSON *root = cacao_json_read_object(path, (size_t)1 << 20, err, n);
    if (!root) return false;
    const bool ok = apply_json_settings(root, path, overridden, o, err, n);
    cJSON_Delete(root);
    return ok;
}

/* Which setting flags the command line gives (they override the settings file). */
static void flags_given(int argc, char **argv, bool *given) {
    for (int i = 1; i < argc; ++i) {
        const flag_def *def = find_flag(argv[i]);
        if (!def) return; /* parse_pass has already refused it */
        if (is_setting(def)) given[def - flags] = true;
        if (def->value) ++i;
    }
}

bool cli_parse(int argc, char **argv, cli_options *o, char *err, size_t n) {
    memset(o, 0, sizeof *o);
    o->output_path = "cacao-out.png";
    o->warmup = 2;
    if (!parse_pass(argc, argv, o, true, err, n)) return false;
    bool overridden[FLAG_COUNT_ALL] = {false};
    flags_given(argc, argv, overridden);
    if (o->settings_path && !load_settings_file(o->settings_path, overridden, o, err, n)) return false;
    return parse_pass(argc, argv, o, false, err, n);
}

bool cli_given(const cli_options *o, const char *flag) {
    const flag_def *def = find_flag(flag);
    return def && o->given[def - flags];
}

/* "gtao and bitmask estimators" or "bitmask estimator": the estimators in the mask, by name. */
static void estimator_list(unsigned mask, char *out, size_t size) {
    out[0] = '\0';
    int count = 0;
    for (int e = 1; e < ESTIMATOR_NAME_COUNT; ++e)
        if (mask >> e & 1) ++count;
    for (int e = 1, shown = 0; e < ESTIMATOR_NAME_COUNT; ++e)
        if (mask >> e & 1)
            snprintf(out + strlen(out), size - strlen(out), "%s%s", shown++ ? (shown == count ? " and " : ", ") : "",
                     cacao_estimator_name((cacao_estimator)e));
    snprintf(out + strlen(out), size - strlen(out), " estimator%s", count > 1 ? "s" : "");
}

bool cli_check_estimator_flags(const cli_options *o, cacao_estimator estimator, const char *what, char *err,
                               size_t n) {
    const int e = estimator == CACAO_ESTIMATOR_DEFAULT ? CACAO_ESTIMATOR_CACAO : (int)estimator;
    for (size_t i = 0; i < FLAG_COUNT_ALL; ++i) {
        const flag_def *def = &flags[i];
        if (!def->estimators || !o->given[i] || (e > 0 && e < ESTIMATOR_NAME_COUNT && (def->estimators >> e & 1)))
            continue;
        char applies[64];
        estimator_list(def->estimators, applies, sizeof applies);
        return cacao_set_err(err, n, "%s: only for the %s, and %s uses the %s estimator", def->name, applies, what,
                             e > 0 && e < ESTIMATOR_NAME_COUNT ? cacao_estimator_name((cacao_estimator)e) : "?");
    }
    return true;
}

/* The shortest decimal that reads back as the same float, as a double (so JSON shows 0.06, not
 * 0.059999998658895493, and still round-trips exactly). */
static double shortest_decimal(float value) {
    char text[32];
    for (int digits = 6; digits <= 9; ++digits) {
        snprintf(text, sizeof text, "%.*g", digits, (double)value);
        if (strtof(text, NULL) == value) break;
    }
    return strtod(text, NULL);
}

/* A resolved value as the literal it stands for: resolved settings keep the explicit-zero
 * encodings (CACAO_ZERO, CACAO_BLUR_NONE; see cacao_settings_resolve). */
static double literal_float(float v) { return v == CACAO_ZERO ? 0.0 : shortest_decimal(v); }

cJSON *cli_settings_to_json(const cacao_settings *resolved) {
    cJSON *root = cJSON_CreateObject();
    cacao_settings s = *resolved;
    for (size_t i = 0; root && i < FLAG_COUNT_ALL; ++i) {
        const flag_def *def = &flags[i];
        switch (def->kind) {
        case SET_FLOAT_PAIR:
            cJSON_AddNumberToObject(root, def->json, literal_float(*float_field(&s, def->offset)));
            cJSON_AddNumberToObject(root, def->json2, literal_float(*float_field(&s, def->offset2)));
            break;
        case SET_FLOAT:
            cJSON_AddNumberToObject(root, def->json, literal_float(*float_field(&s, def->offset)));
            break;
        case SET_BLUR:
            cJSON_AddNumberToObject(root, def->json, s.blur_pass_count == CACAO_BLUR_NONE ? 0 : s.blur_pass_count);
            break;
        case SET_ENUM: {
            if (*int_field(&s, def->offset) == 0) break; /* left to the runtime (shader_forms): absent keeps it so */
            const char *name = def->name_of(*int_field(&s, def->offset));
            cJSON_AddStringToObject(root, def->json, name ? name : "?");
            break;
        }
        case SET_BOOL:
            cJSON_AddBoolToObject(root, def->json, *bool_field(&s, def->offset));
            break;
        case SET_INT: cJSON_AddNumberToObject(root, def->json, *int_field(&s, def->offset)); break;
        default:
            break;
        }
    }
    return root;
}

const char *cli_flag_of_message(const char *message) {
    const char *field = strncmp(message, "settings.", 9) == 0 ? message + 9 : NULL;
    if (!field) return NULL;
    const size_t len = strspn(field, "abcdefghijklmnopqrstuvwxyz_");
    for (size_t i = 0; i < FLAG_COUNT_ALL; ++i) {
        if (!is_setting(&flags[i])) continue;
        if ((flags[i].json && strlen(flags[i].json) == len && strncmp(flags[i].json, field, len) == 0) ||
            (flags[i].json2 && strlen(flags[i].json2) == len && strncmp(flags[i].json2, field, len) == 0))
            return flags[i].name;
    }
    return NULL;
}

/* ---- Help ----------------------------------------------------------------------------------- */

/* The runtime's default of a setting, as text for --help. */
static void default_text(const flag_def *def, const cacao_settings *d, char *text, size_t size) {
    cacao_settings s = *d;
    text[0] = '\0';
    switch (def->kind) {
    case SET_FLOAT:
        snprintf(text, size, "%g", shortest_decimal(*float_field(&s, def->offset)));
        break;
    case SET_FLOAT_PAIR:
        snprintf(text, size, "%g,%g", shortest_decimal(*float_field(&s, def->offset)),
                 shortest_decimal(*float_field(&s, def->offset2)));
        break;
    case SET_BLUR:
        snprintf(text, size, "%d", s.blur_pass_count);
        break;
    case SET_ENUM: /* a field the runtime leaves DEFAULT (shader_forms): its help says who decides */
        if (*int_field(&s, def->offset) != 0) snprintf(text, size, "%s", def->name_of(*int_field(&s, def->offset)));
        break;
    case SET_INT:
        snprintf(text, size, "%d", *int_field(&s, def->offset));
        break;
    default:
        break;
    }
}

/* Writes text from column `indent` on, breaking lines at spaces before column `width`. */
static void print_wrapped(FILE *out, const char *text, int indent, int width) {
    int column = indent;
    while (*text) {
        const int word = (int)strcspn(text, " ");
        const bool first = column == indent;
        if (!first && column + 1 + word > width) {
            fprintf(out, "\n%*s", indent, "");
            column = indent;
        }
        fprintf(out, "%s%.*s", column == indent ? "" : " ", word, text);
        column += word + (first ? 0 : 1);
        text += word;
        text += strspn(text, " ");
    }
    fputc('\n', out);
}

void cli_print_help(FILE *out) {
    cacao_settings defaults;
    cacao_settings_resolve(&(cacao_settings){0}, &defaults, NULL, 0);
    fprintf(out, "usage: cacao [options]\n"
                 "Screen-space ambient occlusion (after AMD FidelityFX CACAO) of a depth buffer, on a Vulkan device.\n"
                 "Writes AO visibility in [0,1] (1 = unoccluded) and says where on stdout; errors go to stderr as\n"
                 "one line, with a non-zero exit and no output file. Values are literal: --horizon 0 means 0.\n");
    for (size_t i = 0; i < FLAG_COUNT_ALL; ++i) {
        const flag_def *def = &flags[i];
        if (def->kind == FLAG_SECTION) {
            fprintf(out, "\n%s:\n", def->name);
            continue;
        }
        char head[64], fallback[64];
        snprintf(head, sizeof head, "%s%s%s%s%s", def->alias ? def->alias : "", def->alias ? ", " : "", def->name,
                 def->value ? " " : "", def->value ? def->value : "");
        default_text(def, &defaults, fallback, sizeof fallback);
        char text[512];
        snprintf(text, sizeof text, "%s%s%s%s", def->help, fallback[0] ? " (default " : "", fallback,
                 fallback[0] ? ")" : "");
        fprintf(out, "  %-26s ", head);
        print_wrapped(out, text, 29, 100);
    }
    fprintf(out, "\nThe settings JSON (--settings, --print-settings) uses the cacao_settings field names:");
    for (size_t i = 0; i < FLAG_COUNT_ALL; ++i)
        if (is_setting(&flags[i]))
            fprintf(out, " %s%s%s", flags[i].json, flags[i].json2 ? " " : "", flags[i].json2 ? flags[i].json2 : "");
    fprintf(out, ".\n");
}
