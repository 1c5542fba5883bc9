/* test_output_files - tools/common/output_files.c, which cacao and cacao-bench write through
 * (issue 35, defects 3 and 4), against facts of the file system set up here:
 *   - two paths name the same file when they are the same existing file (a "./" spelling, a hard
 *     link, a symbolic link) or the same new name in the same existing folder ("a" and "d/../a");
 *     different names, or different folders, are different files;
 *   - an output naming another output, or an input, is refused with one line naming both flags
 *     and paths, control bytes escaped;
 *   - staging creates an empty temporary beside each output at once (a missing folder, a folder at
 *     the path and a device are refused then, naming the flag); abandoning deletes every temporary
 *     and leaves the destinations as they were; committing moves the written temporaries into
 *     place and leaves none behind. Argument: a scratch folder (emptied). */
#include <dirent.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "output_files.h"
#include "test_util.h"

static char dir[4096];

static const char *in_dir(const char *name) { return test_path(dir, name); }

static void write_file(const char *path, const char *text) {
    FILE *f = fopen(path, "wb");
    if (!f) {
        fprintf(stderr, "cannot write %s\n", path);
        exit(1);
    }
    fputs(text, f);
    fclose(f);
}

/* The file's whole text ("" when it cannot be read; at most 255 bytes). */
static const char *text_of(const char *path) {
    static char text[256];
    FILE *f = fopen(path, "rb");
    const size_t n = f ? fread(text, 1, sizeof text - 1, f) : 0;
    if (f) fclose(f);
    text[n] = '\0';
    return text;
}

/* Entries of the scratch folder, . and .. not counted. */
static int entries(void) {
    DIR *d = opendir(dir);
    int n = 0;
    for (struct dirent *e; d && (e = readdir(d));) n += strcmp(e->d_name, ".") != 0 && strcmp(e->d_name, "..") != 0;
    if (d) closedir(d);
    return n;
}

static void same_file(void) {
    write_file(in_dir("a"), "a");
    write_file(in_dir("b"), "b");
    mkdir(in_dir("d"), 0777);
    CHECK(link(in_dir("a"), in_dir("hard")) == 0);
    CHECK(symlink(in_dir("a"), in_dir("soft")) == 0);
    CHECK(cacao_same_file(in_dir("a"), in_dir("a")));
    CHECK(cacao_same_file(in_dir("a"), in_dir("./a")));
    CHECK(cacao_same_file(in_dir("a"), in_dir("d/../a")));
    CHECK(cacao_same_file(in_dir("a"), in_dir("hard")));
    CHECK(cacao_same_file(in_dir("soft"), in_dir("a")));
    CHECK(!cacao_same_file(in_dir("a"), in_dir("b")));
    CHECK(!cacao_same_file(in_dir("a"), NULL));
    /* not there yet: the same name in the same folder */
    CHECK(cacao_same_file(in_dir("new.json"), in_dir("./new.json")));
    CHECK(cacao_same_file(in_dir("new.json"), in_dir("d/../new.json")));
    CHECK(!cacao_same_file(in_dir("new.json"), in_dir("d/new.json")));
    CHECK(!cacao_same_file(in_dir("new.json"), in_dir("new.csv")));
    CHECK(!cacao_same_file(in_dir("a"), in_dir("d/a"))); /* there and not there */
}

static void collisions(void) {
    char err[1024] = "";
    const cacao_named_path outputs[] = {{"--json", in_dir("r.json")}, {"--csv", in_dir("./r.json")}};
    CHECK(!cacao_check_outputs(outputs, 2, NULL, 0, err, sizeof err));
    char expected[9000];
    snprintf(expected, sizeof expected, "--json %s and --csv %s name the same file", in_dir("r.json"),
             in_dir("./r.json"));
    CHECK(strcmp(err, expected) == 0);

    const cacao_named_path json_on_input[] = {{"--json", in_dir("hard")}, {"--csv", NULL}};
    const cacao_named_path inputs[] = {{"--reference", NULL}, {"--scene", in_dir("a")}};
    CHECK(!cacao_check_outputs(json_on_input, 2, inputs, 2, err, sizeof err));
    snprintf(expected, sizeof expected, "--json %s: is also the --scene input %s; it would be overwritten",
             in_dir("hard"), in_dir("a"));
    CHECK(strcmp(err, expected) == 0);

    const cacao_named_path escaped[] = {{"--json", in_dir("x\n\x1b[2J")}, {"--csv", in_dir("x\n\x1b[2J")}};
    CHECK(!cacao_check_outputs(escaped, 2, NULL, 0, err, sizeof err));
    CHECK(strchr(err, '\n') == NULL && strchr(err, 0x1b) == NULL && strstr(err, "x\\x0a\\x1b[2J") != NULL);

    const cacao_named_path distinct[] = {{"--json", in_dir("r.json")}, {"--csv", in_dir("r.csv")}};
    CHECK(cacao_check_outputs(distinct, 2, inputs, 2, err, sizeof err));
}

static void staging(void) {
    write_file(in_dir("old.json"), "old");
    const int before = entries();
    char err[1024];
    cacao_stage stage = {0};
    const char *json = cacao_stage_add(&stage, "--json", in_dir("old.json"), err, sizeof err);
    const char *csv = cacao_stage_add(&stage, "--csv", in_dir("new.csv"), err, sizeof err);
    CHECK(json && csv && strcmp(json, in_dir("old.json")) != 0);
    CHECK(entries() == before + 2 && strcmp(text_of(json), "") == 0 && strcmp(text_of(in_dir("old.json")), "old") == 0);
    CHECK(!cacao_stage_add(&stage, "--plot", in_dir("nodir/p.png"), err, sizeof err));
    CHECK(strstr(err, "--plot ") == err && strstr(err, "nodir/p.png: cannot create a file there") != NULL);
    CHECK(!cacao_stage_add(&stage, "--plot", in_dir("d"), err, sizeof err) && strstr(err, "d: is a folder") != NULL);
    CHECK(!cacao_stage_add(&stage, "--csv", "/dev/null", err, sizeof err) &&
          strstr(err, "/dev/null: is not a regular file") != NULL);
    cacao_stage_abandon(&stage);
    CHECK(entries() == before && strcmp(text_of(in_dir("old.json")), "old") == 0 &&
          access(in_dir("new.csv"), F_OK) != 0);

    stage = (cacao_stage){0};
    json = cacao_stage_add(&stage, "--json", in_dir("old.json"), err, sizeof err);
    csv = cacao_stage_add(&stage, "--csv", in_dir("new.csv"), err, sizeof err);
    CHECK(json && csv);
    if (json && csv) {
        write_file(json, "new json");
        write_file(csv, "new csv");
    }
    CHECK(cacao_stage_commit(&stage, err, sizeof err));
    CHECK(strcmp(text_of(in_dir("old.json")), "new json") == 0 && strcmp(text_of(in_dir("new.csv")), "new csv") == 0);
    CHECK(entries() == before + 1); /* new.csv, and no temporary */
}

int main(int argc, char **argv) {
    test_scratch_dir(argc, argv, dir, sizeof dir);
    same_file();
    collisions();
    staging();
    return test_report("test_output_files");
}
