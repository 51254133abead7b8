/* tests/test.h -- the test harness. A test is `TEST(name) { ... }` in any tests/ .c file; the Makefile collects
 * the names, and build/iacsg-tests runs them all, or those whose names start with an argument.
 *
 *   CHECK(cond, fmt, ...)   on failure prints the place and the message and ends this test (others go on).
 *   test_iters(n)           n scaled by IACSG_TEST_MULT (default 1), for property tests.
 *   test_rng()              a per-test random state seeded from IACSG_TEST_SEED (default fixed), so failures
 *                           reproduce; test_rng_reseed(name, seed) gives it test `name`'s stream under that seed
 *                           (a stream that once found a defect, kept as a regression test).
 *   test_note(fmt, ...)     one line of summary (counts, measured bounds) printed under the test's result.
 */
#ifndef IACSG_TEST_H
#define IACSG_TEST_H
#include <stddef.h>
#include <stdint.h>

#define TEST(name) void test_##name(void)
/* In tests/ *_fp.c, compiled once for float and once for double intervals (-DIA_FP64): TEST_FP(name) defines
 * name_f32 or name_f64. */
#ifdef IA_FP64
#define TEST_FP(name) void test_##name##_f64(void)
#else
#define TEST_FP(name) void test_##name##_f32(void)
#endif

void test_fail_at(const char *file, int line, const char *fmt, ...)
#ifdef __GNUC__
    __attribute__((format(printf, 3, 4), noreturn))
#endif
    ;
void test_note(const char *fmt, ...)
#ifdef __GNUC__
    __attribute__((format(printf, 1, 2)))
#endif
    ;

#define CHECK(cond, ...)                                                                                      \
    do {                                                                                                      \
        if (!(cond))                                                                                          \
            test_fail_at(__FILE__, __LINE__, __VA_ARGS__);                                                    \
    } while (0)

long test_iters(long base);

/* xoshiro256** state, seeded per test. */
typedef struct {
    uint64_t s[4];
} test_rng_t;
test_rng_t *test_rng(void);
void test_rng_reseed(const char *name, uint64_t seed);
uint64_t test_rand_u64(test_rng_t *r);
double test_rand_unit(test_rng_t *r); /* uniform in [0, 1) */

/* The repository root (where tests/data lives): IACSG_SOURCE_DIR, else the compiled-in default. */
const char *test_source_dir(void);
/* The whole file, NUL-terminated (it may contain NULs: *size says how long); NULL if it cannot be read.
 * The caller free()s it. size may be NULL. */
char *test_read_file(const char *path, size_t *size);
/* The iacsg command under test: IACSG_BIN, else the binary of this build directory. */
const char *test_binary_path(void);
/* A fresh directory /tmp/iacsg-<tag>-<pid> into dir (the test fails if it cannot be made), and its removal with
 * everything in it. */
void test_make_dir(char *dir, size_t size, const char *tag);
void test_remove_dir(const char *dir);
/* Runs the command under test with `args` in `dir`, after `before` (shell text: variables, `umask 027 &&`),
 * stdout into dir/out.txt and stderr into dir/err.txt. Returns its exit status (-1: it did not exit), and in
 * `trace` the rest of the first stderr line that starts with `prefix` (empty: none). */
int test_run_traced(const char *dir, const char *before, const char *args, const char *prefix, char *trace,
                    size_t size);
/* dir/name's text without its lines that start with `prefix` (NULL if it cannot be read; the caller frees it). */
char *test_read_without(const char *dir, const char *name, const char *prefix);
/* Shell text that sets $server to the process named `name` (a string literal: iacsg-launch, iacsg-writer) whose
 * environment holds this shell's LD_LIBRARY_PATH (a test gives its servers one of its own), or exits 3 when there is
 * none; a process gone between pgrep and the read of its environment is passed over quietly. */
#define TEST_SH_FIND_SERVER(name)                                                                                   \
    "for p in $(pgrep -x " name "); do { tr '\\0' '\\n' </proc/$p/environ; } 2>/dev/null | "                       \
    "grep -qx \"LD_LIBRARY_PATH=$LD_LIBRARY_PATH\" && server=$p; done; [ -n \"$server\" ] || exit 3; "

#endif
