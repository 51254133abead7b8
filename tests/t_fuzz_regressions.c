/* tests/t_fuzz_regressions.c -- replays every input saved in tests/data/fuzz/ (crashes the fuzzer found, and
 * hostile inputs kept as seeds) through the compiler: each must compile or be rejected with a message. And
 * every example scene must compile. */
#include "expr_exercise.h"
#include "test.h"
#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Runs every file of dir (with the given suffix, or all) through expr_exercise; with must_compile, each must
 * compile, else each must compile or be rejected with a message. Returns the number of files. */
static int replay_dir(const char *dir, const char *suffix, int must_compile, int *compiled) {
    DIR *d = opendir(dir);
    CHECK(d, "cannot open %s", dir);
    int replayed = 0;
    *compiled = 0;
    struct dirent *ent;
    while ((ent = readdir(d))) {
        size_t len = strlen(ent->d_name), slen = strlen(suffix);
        if (ent->d_name[0] == '.' || len < slen || strcmp(ent->d_name + len - slen, suffix) != 0)
            continue;
        char path[8192];
        snprintf(path, sizeof path, "%s/%s", dir, ent->d_name);
        size_t size = 0;
        char *data = test_read_file(path, &size);
        CHECK(data, "cannot read %s", path);
        int r = expr_exercise(data, size);
        free(data);
        CHECK(r >= 0, "%s: rejected without a message, or its scene is unsound", ent->d_name);
        CHECK(r == 1 || !must_compile, "%s: does not compile", ent->d_name);
        replayed++;
        *compiled += r;
    }
    closedir(d);
    CHECK(replayed > 0, "no inputs in %s", dir);
    return replayed;
}

TEST(fuzz_regressions) {
    char dir[4096];
    snprintf(dir, sizeof dir, "%s/tests/data/fuzz", test_source_dir());
    int compiled, replayed = replay_dir(dir, "", 0, &compiled);
    test_note("%d inputs replayed, %d compiled, %d rejected with a message", replayed, compiled, replayed - compiled);
}

/* Every example scene compiles, emits, bounds and evaluates (make test also runs this under valgrind). */
TEST(examples_compile) {
    char dir[4096];
    snprintf(dir, sizeof dir, "%s/examples", test_source_dir());
    int compiled, replayed = replay_dir(dir, ".csg", 1, &compiled);
    test_note("%d example scenes compiled", replayed);
}
