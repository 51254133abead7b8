/* tests/main.c -- the runner: runs every TEST in build/tests.inc but the bench_* ones, or those whose names
 * start with one of the arguments, and ends with the line "N passed, N failed". Exit status 0 only if nothing failed. */
#include "test.h"
#include <setjmp.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#define X(name) void test_##name(void);
#include "tests.inc"
#undef X

static const struct {
    const char *name;
    void (*fn)(void);
} tests[] = {
#define X(name) {#name, test_##name},
#include "tests.inc"
#undef X
};

static jmp_buf on_fail;
static test_rng_t rng;
static char notes[8192];

void test_fail_at(const char *file, int line, const char *fmt, ...) {
    va_list ap;
    va_start(ap, fmt);
    fprintf(stdout, "    %s:%d: ", file, line);
    vfprintf(stdout, fmt, ap);
    fputc('\n', stdout);
    va_end(ap);
    longjmp(on_fail, 1);
}

void test_note(const char *fmt, ...) {
    size_t len = strlen(notes);
    va_list ap;
    va_start(ap, fmt);
    int n = snprintf(notes + len, sizeof notes - len, "    ");
    if (n > 0 && (size_t)n < sizeof notes - len)
        len += (size_t)n;
    n = vsnprintf(notes + len, sizeof notes - len, fmt, ap);
    va_end(ap);
    len = strlen(notes);
    if (len + 1 < sizeof notes)
        strcat(notes, "\n");
}

long test_iters(long base) {
    const char *m = getenv("IACSG_TEST_MULT");
    double mult = m ? atof(m) : 1.0;
    long n = (long)(base * (mult > 0 ? mult : 1.0));
    return n > 0 ? n : 1;
}

static uint64_t splitmix(uint64_t *x) {
    uint64_t z = (*x += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

void test_rng_reseed(const char *name, uint64_t seed) {
    uint64_t x = seed;
    for (const char *p = name; *p; p++)
        x = x * 31 + (unsigned char)*p;
    for (int i = 0; i < 4; i++)
        rng.s[i] = splitmix(&x);
}

test_rng_t *test_rng(void) { return &rng; }

static uint64_t rotl(uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }

uint64_t test_rand_u64(test_rng_t *r) {
    uint64_t *s = r->s, result = rotl(s[1] * 5, 7) * 9, t = s[1] << 17;
    s[2] ^= s[0];
    s[3] ^= s[1];
    s[1] ^= s[2];
    s[0] ^= s[3];
    s[2] ^= t;
    s[3] = rotl(s[3], 45);
    return result;
}

double test_rand_unit(test_rng_t *r) { return (double)(test_rand_u64(r) >> 11) * 0x1p-53; }

const char *test_source_dir(void) {
    const char *d = getenv("IACSG_SOURCE_DIR");
    return d && *d ? d : IACSG_SOURCE_DIR_DEFAULT;
}

/* With no arguments every test runs except the benchmarks (bench_*), which run only when named. */
void test_make_dir(char *dir, size_t size, const char *tag) {
    snprintf(dir, size, "/tmp/iacsg-%s-%ld", tag, (long)getpid());
    CHECK(mkdir(dir, 0700) == 0, "cannot create %s", dir);
}

void test_remove_dir(const char *dir) {
    char cmd[1024];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    CHECK(system(cmd) == 0, "cannot clean %s", dir);
}

char *test_read_file(const char *path, size_t *size) {
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    char *buf = NULL;
    size_t cap = 0, len = 0, n;
    char chunk[65536];
    while ((n = fread(chunk, 1, sizeof chunk, f)) > 0) {
        if (len + n + 1 > cap) {
            cap = 2 * (len + n + 1);
            char *grown = realloc(buf, cap);
            if (!grown) {
                free(buf);
                fclose(f);
                return NULL;
            }
            buf = grown;
        }
        memcpy(buf + len, chunk, n);
        len += n;
    }
    int failed = ferror(f);
    fclose(f);
    if (failed || (!buf && !(buf = malloc(1)))) {
        free(buf);
        return NULL;
    }
    buf[len] = '\0';
    if (size)
        *size = len;
    return buf;
}

const char *test_binary_path(void) {
    const char *b = getenv("IACSG_BIN");
    return b && *b ? b : IACSG_BINARY_DEFAULT;
}

int test_run_traced(const char *dir, const char *before, const char *args, const char *prefix, char *trace,
                    size_t size) {
    char cmd[4096], path[512], line[1024];
    snprintf(cmd, sizeof cmd, "cd '%s' && %s '%s' %s >out.txt 2>err.txt", dir, before, test_binary_path(), args);
    int rc = system(cmd);
    trace[0] = '\0';
    snprintf(path, sizeof path, "%s/err.txt", dir);
    FILE *f = fopen(path, "r");
    size_t n = strlen(prefix);
    while (f && fgets(line, sizeof line, f))
        if (!trace[0] && strncmp(line, prefix, n) == 0) {
            strncpy(trace, line + n, size - 1);
            trace[size - 1] = '\0';
            trace[strcspn(trace, "\n")] = '\0';
        }
    if (f)
        fclose(f);
    return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
}

char *test_read_without(const char *dir, const char *name, const char *prefix) {
    char path[512];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    char *text = test_read_file(path, NULL);
    size_t n = strlen(prefix), kept = 0;
    for (char *line = text; line && *line;) {
        char *end = strchr(line, '\n');
        size_t len = end ? (size_t)(end - line) + 1 : strlen(line);
        if (strncmp(line, prefix, n) != 0) {
            memmove(text + kept, line, len);
            kept += len;
        }
        line += len;
    }
    if (text)
        text[kept] = '\0';
    return text;
}

static int selected(const char *name, int argc, char **argv) {
    if (argc < 2)
        return strncmp(name, "bench_", 6) != 0;
    for (int i = 1; i < argc; i++)
        if (strncmp(name, argv[i], strlen(argv[i])) == 0)
            return 1;
    return 0;
}

int main(int argc, char **argv) {
    setvbuf(stdout, NULL, _IOLBF, 0);
    /* The program-binary cache (src/clrt_cache.c) saves a program the second time it is built, which costs PoCL
     * seconds; the suite builds the same programs again and again, so it runs without it unless the environment
     * says otherwise (t_program_cache.c turns it on for its own builds). */
    setenv("IACSG_KERNEL_CACHE", "0", 0);
    /* static: setjmp/longjmp may not restore locals the compiler kept in registers */
    static int passed, failed;
    static size_t i;
    for (i = 0; i < sizeof tests / sizeof tests[0]; i++) {
        if (!selected(tests[i].name, argc, argv))
            continue;
        notes[0] = '\0';
        const char *seed = getenv("IACSG_TEST_SEED");
        test_rng_reseed(tests[i].name, seed ? strtoull(seed, NULL, 0) : 0x1acc5eedull);
        struct timespec t0, t1;
        clock_gettime(CLOCK_MONOTONIC, &t0);
        int ok = setjmp(on_fail) == 0;
        if (ok)
            tests[i].fn();
        clock_gettime(CLOCK_MONOTONIC, &t1);
        double ms = (t1.tv_sec - t0.tv_sec) * 1e3 + (t1.tv_nsec - t0.tv_nsec) * 1e-6;
        printf("%s %s (%.0f ms)\n%s", ok ? "ok  " : "FAIL", tests[i].name, ms, notes);
        ok ? passed++ : failed++;
    }
    printf("%d passed, %d failed\n", passed, failed);
    return failed ? 1 : 0;
}
