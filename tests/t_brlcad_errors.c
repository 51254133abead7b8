/* tests/t_brlcad_errors.c -- every refusal of the BRL-CAD reader: the message names the object or record, the
 * line is the right one, and nothing is returned. */
#include "brlcad_exercise.h"
#include "implicits/brlcad.h"
#include "implicits/scene.h"
#include "test.h"
#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define IDENTITY " 1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1"
#define V4_HEAD "I 1 v4\ntitle\n"
#define V4_SPHERE(name) "S 19 " name " 1 0 0 0 1 0 0 0 1 0 0 0 1 0 0 0 0 0 0 0 0 0 0 0 0\n"
#define V5_SPHERE(name) "put {" name "} ell V {0 0 0} A {1 0 0} B {0 1 0} C {0 0 1}\n"

static const struct {
    const char *text;
    int line;
    const char *fragment;
} bad_databases[] = {
    /* v4 */
    {V4_HEAD "S 26 para 1 0 0 0 1 0 0 0 1 0 0 0 1 0 0 0 0 0 0 0 0 0 0 0 0\n", 3,
     "solid 'para' is of type 26 (rpc), which iacsg does not read"},
    {V4_HEAD "S 19 e 1 0 0 0 1 0 0\n", 3, "solid 'e': 10 fields, a solid record has 28"},
    {V4_HEAD "S 19 e 1 0 0 zero 1 0 0 0 1 0 0 0 1 0 0 0 0 0 0 0 0 0 0 0 0\n", 3,
     "'e': field 7 is not a finite number: 'zero'"},
    {V4_HEAD "S 19 e 1 0 0 1e999 1 0 0 0 1 0 0 0 1 0 0 0 0 0 0 0 0 0 0 0 0\n", 3, "is not a finite number: '1e999'"},
    {V4_HEAD V4_SPHERE("a") "C Y r 1 0 1 0 0 0 0 0 0 0\nM u b" IDENTITY "\n", 5,
     "combination 'r' has a member 'b' that the database does not define"},
    {V4_HEAD V4_SPHERE("a") "C Y r 1 0 1 0 0 0 0 0 0 0\nM x a" IDENTITY "\n", 5,
     "combination 'r': member operation 'x', expected u, - or +"},
    {V4_HEAD V4_SPHERE("a") "C Y r 1 0 1 0 0 0 0 0 0 0\nM u a 1 0 0\n", 5, "a member record has 19 or 20 fields"},
    {V4_HEAD "C Q r 1 0 1 0 0 0 0 0 0 0\n", 3, "combination 'r': region flag 'Q', expected Y, R, P, V or N"},
    {V4_HEAD "C Y r 1 0 1\n", 3, "combination 'r': 6 fields, a combination record has 13 to 16"},
    {V4_HEAD "C Y r 1 0 1 0 0 0 1 300 0 0\n", 3, "combination 'r': colour component 300 is not from 0 to 255"},
    {V4_HEAD "C N a 0 0 1 0 0 0 0 0 0 0\nM u b" IDENTITY "\nC N b 0 0 1 0 0 0 0 0 0 0\nM u a" IDENTITY "\n", 3,
     "combination 'a' contains itself (a cycle through 'b')"},
    {V4_HEAD "C N a 0 0 1 0 0 0 0 0 0 0\nM u a" IDENTITY "\n", 3, "combination 'a' contains itself"},
    {V4_HEAD "M u a" IDENTITY "\n", 3, "a member record (M) that follows no combination record"},
    {V4_HEAD "A 1 2 3\n", 3, "record type 'A' (ars) is not read"},
    {V4_HEAD "Sx 1\n", 3, "unknown record 'Sx'"},
    {V4_HEAD "m 0 1 2 300 4 5\n", 3, "a colour record's r, g, b must be from 0 to 255"},
    {V4_HEAD V4_SPHERE("a") V4_SPHERE("a"), 4, "'a' is already defined (line 3)"},
    {V4_HEAD "C Y r 1 0 1 0 0 0 0 0 0 0 1 0 0\n", 3, "the text ends before its shader lines"},
    {"I 1 v4\n", 1, "the text ends before the title line"},
    /* v5 */
    {"put {s} rpc V {0 0 0} H {0 0 1} B {0 1 0} r 1\n", 1, "'s' is a rpc, which iacsg does not read"},
    {"put {s} sph V {0 0 0} r 1\n", 1, "sph 's': unknown key 'r'"},
    {"put {s} ell V {0 0 0} A {1 0 0} B {0 1 0}\n", 1, "ell 's' has no C"},
    {"put {s} ell V {0 0 0} A {1 0 0} B {0 1 0} C {0 0 1} Q {1}\n", 1, "ell 's': unknown key 'Q'"},
    {"put {s} ell V {0 0} A {1 0 0} B {0 1 0} C {0 0 1}\n", 1, "'s': V has 2 numbers, expected 3"},
    {"put {s} ell V {0 0 x} A {1 0 0} B {0 1 0} C {0 0 1}\n", 1, "'s': V: 'x' is not a finite number"},
    {"\n" V5_SPHERE("s") "put {r} comb region yes tree {l t}\n", 3,
     "combination 'r' has a member 't' that the database does not define"},
    {"put {a} comb region no tree {l b}\nput {b} comb region no tree {u {l a} {l a}}\n", 1,
     "combination 'a' contains itself (a cycle through 'b')"},
    {V5_SPHERE("s") "put {r} comb region yes tree {! {l s}}\n", 2, "combination 'r': a tree node '! {l s}'"},
    {V5_SPHERE("s") "put {r} comb region yes tree {l s {1 0 0}}\n", 2, "'r': a member's matrix has 3 numbers"},
    {V5_SPHERE("s") "put {r} comb region yes tree {l s\n", 2, "a '{' that is never closed"},
    {V5_SPHERE("s") "draw s\n", 2, "unknown command 'draw'"},
    {V5_SPHERE("s") "attr set {t} {region_id} {1}\n", 2, "attr set for 't', which the database does not define"},
    {V5_SPHERE("s") "put {r} comb region yes tree {l s}\nattr set {r} {region_id} {x1}\n", 3,
     "'r': region_id 'x1' is not an integer"},
    {V5_SPHERE("s") "put {r} comb region yes tree {l s}\nattr set {r} {rgb} {red}\n", 3, "colour 'red' is not R/G/B"},
    {"put {p} pipe V0 {0 0 0} O0 1 I0 0 R0 1 V1 {0 0 1} O1 1 R1 1\n", 1, "pipe 'p': point 1 lacks one of"},
    {"put {p} pipe V0 {0 0 0} O0 1 I0 0 R0 1 W1 2\n", 1, "pipe 'p': unknown key 'W1'"},
    {"color 1 2 3 4\n", 1, "color takes 5 integers"},
    {"put {h} ehy V {0 0 0} H {0 0 1} A {0 0 0} r_1 1 r_2 1 c 1\n", 1, "ehy 'h': its A vector is zero"},
};

TEST(brlcad_bad_databases) {
    for (size_t k = 0; k < sizeof bad_databases / sizeof bad_databases[0]; k++) {
        brlcad_db *db = (brlcad_db *)&db; /* any non-NULL value: a failure must clear it */
        iacsg_error err = {0};
        const char *text = bad_databases[k].text;
        iacsg_status st = brlcad_db_read(text, strlen(text), &db, &err);
        CHECK(st != IACSG_OK && db == NULL, "case %zu was read", k);
        CHECK(err.line == bad_databases[k].line && strstr(err.message, bad_databases[k].fragment),
              "case %zu: line %d: %s\n  expected line %d: %s", k, err.line, err.message, bad_databases[k].line,
              bad_databases[k].fragment);
    }
}

TEST(brlcad_nul_byte_is_refused) {
    static const char text[] = V5_SPHERE("s") "\0" V5_SPHERE("t");
    brlcad_db *db = NULL;
    iacsg_error err = {0};
    CHECK(brlcad_db_read(text, sizeof text - 1, &db, &err) != IACSG_OK && !db, "read");
    CHECK(err.line == 2 && strstr(err.message, "NUL byte"), "line %d: %s", err.line, err.message);
}

/* Objects that the model cannot make: an unknown name (the message lists the tops) and nothing but air. */
TEST(brlcad_bad_objects) {
    const char *text = V5_SPHERE("s") "put {r} comb region yes tree {l s}\nattr set {r} {aircode} {1}\n"
                                      "put {top} comb region no tree {l r}\n";
    brlcad_db *db = NULL;
    iacsg_error err = {0};
    CHECK(brlcad_db_read(text, strlen(text), &db, &err) == IACSG_OK, "%s", err.message);
    brlcad_model m;
    const char *unknown[] = {"tpo"};
    CHECK(brlcad_model_build(db, unknown, 1, &m, &err) != IACSG_OK && !m.scene, "tpo was found");
    CHECK(strstr(err.message, "the database has no object 'tpo' (its top objects: top)"), "%s", err.message);
    CHECK(brlcad_model_build(db, NULL, 0, &m, &err) != IACSG_OK && !m.scene, "air was rendered");
    CHECK(strstr(err.message, "hold no region to render"), "%s", err.message);
    brlcad_db_destroy(db);
}

/* Every input kept in tests/data/fuzz-brlcad/ (hostile seeds and crashes the fuzzer found) is read or refused
 * with a message, and every sample database makes a sound scene. */
TEST(brlcad_fuzz_regressions) {
    static const char *const dirs[] = {"tests/data/fuzz-brlcad", "tests/data/brlcad"};
    for (int d = 0; d < 2; d++) {
        char dir[4096];
        snprintf(dir, sizeof dir, "%s/%s", test_source_dir(), dirs[d]);
        DIR *dp = opendir(dir);
        CHECK(dp, "cannot open %s", dir);
        int n = 0;
        struct dirent *e;
        while ((e = readdir(dp))) {
            size_t len = strlen(e->d_name);
            if (len < 5 || strcmp(e->d_name + len - 4, ".asc") != 0)
                continue;
            char path[8192];
            snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
            size_t size = 0;
            char *data = test_read_file(path, &size);
            CHECK(data, "cannot read %s", path);
            int r = brlcad_exercise(data, size);
            free(data);
            CHECK(r >= 0, "%s: refused without a message, or its scene is unsound", path);
            CHECK(r == 1 || d == 0, "%s: a sample database is refused", path);
            n++;
        }
        closedir(dp);
        CHECK(n > 0, "no databases in %s", dir);
        test_note("%s: %d databases", dirs[d], n);
    }
}
