/* tests/t_program_cache.c -- the cache of program binaries (src/clrt_cache.c): a program built a second time is
 * saved (by the detached saver, which the tests wait for), at its first build where the driver compiles there,
 * the next build loads it (and the kernel computes the same; PoCL's entry without the program's bitcode), a
 * damaged entry is refused and removed and the program still builds from source, and a cache directory that
 * cannot be made costs nothing but the cache. */
#define _GNU_SOURCE /* utimes, usleep */
#include "clrt.h"
#include "clrt_cache.h"
#include "test.h"
#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/time.h>
#include <sys/wait.h>
#include <unistd.h>

static const char *const source = "__kernel void answer(__global int *out) { out[0] = 6 * 7 + CACHE_TEST; }\n";

/* Builds the test's program in a fresh context, as on a driver that compiles at the build or not (`compiled`,
 * whatever this device does), and runs it: its answer, or -1 when it does not build. */
static int build_and_run(int salt, int compiled) {
    clrt rt;
    iacsg_error err = {0};
    if (clrt_open(&rt, 0, &err) != IACSG_OK)
        return -1;
    rt.compiles_at_build = compiled;
    char options[64];
    snprintf(options, sizeof options, "-D CACHE_TEST=%d", salt);
    cl_program program = NULL;
    cl_kernel k = NULL;
    cl_mem out = NULL;
    cl_int rc = CL_SUCCESS, answer = -1;
    if (clrt_build(&rt, &source, 1, options, &program, &err) == IACSG_OK &&
        (k = clCreateKernel(program, "answer", &rc)) &&
        (out = clCreateBuffer(rt.context, CL_MEM_WRITE_ONLY, sizeof answer, NULL, &rc)) &&
        clSetKernelArg(k, 0, sizeof out, &out) == CL_SUCCESS) {
        size_t one = 1;
        if (clEnqueueNDRangeKernel(rt.queue, k, 1, NULL, &one, &one, 0, NULL, NULL) != CL_SUCCESS ||
            clEnqueueReadBuffer(rt.queue, out, CL_TRUE, 0, sizeof answer, &answer, 0, NULL, NULL) != CL_SUCCESS)
            answer = -1;
    }
    if (out)
        clReleaseMemObject(out);
    if (k)
        clReleaseKernel(k);
    if (program)
        clReleaseProgram(program);
    clrt_close(&rt);
    return answer;
}

/* The one entry (*.bin) in dir/programs into path; 0 when there is none, -1 when there are several. */
static int the_entry(const char *dir, char *path, size_t size) {
    char programs[512];
    snprintf(programs, sizeof programs, "%s/programs", dir);
    DIR *d = opendir(programs);
    int found = 0;
    for (struct dirent *e; d && (e = readdir(d));) {
        size_t len = strlen(e->d_name);
        if (len > 4 && strcmp(e->d_name + len - 4, ".bin") == 0) {
            snprintf(path, size, "%s/%s", programs, e->d_name);
            found = found ? -1 : 1;
        }
    }
    if (d)
        closedir(d);
    return found;
}

static void use_cache(const char *dir) {
    setenv("IACSG_CACHE_DIR", dir, 1);
    setenv("IACSG_KERNEL_CACHE", "1", 1);
    clrt_cache_defer_saves(); /* as the command does */
}

/* The programs held back saved, as at the command's end, and the saver waited for (up to 60 s): the number of
 * entries then, as the_entry counts them. */
static int save_and_wait(const char *dir, char *entry, size_t size) {
    clrt_cache_save_deferred();
    int found = 0;
    for (int wait = 0; wait < 600 && (found = the_entry(dir, entry, size)) == 0; wait++)
        usleep(100000);
    return found;
}

static void cache_off(void) {
    unsetenv("IACSG_CACHE_DIR");
    setenv("IACSG_KERNEL_CACHE", "0", 1);
}

TEST(program_cache_saves_then_loads) {
    char dir[256], entry[1024];
    test_make_dir(dir, sizeof dir, "pcache");
    use_cache(dir);
    int salt = (int)getpid(); /* a program PoCL has not seen, so that this test's builds are its own */
    int first = build_and_run(salt, 0);
    clrt_cache_save_deferred(); /* nothing to save: the first build only marks the program */
    usleep(200000);
    int saved = the_entry(dir, entry, sizeof entry);
    int second = build_and_run(salt, 0);
    int now_saved = save_and_wait(dir, entry, sizeof entry);
    size_t bytes = 0;
    char *saved_bytes = now_saved == 1 ? test_read_file(entry, &bytes) : NULL;
    /* PoCL's LLVM IR, which the cache leaves out (src/clrt_pocl.h) */
    int bitcode = saved_bytes && memmem(saved_bytes, bytes, "BC\xc0\xde", 4) != NULL;
    free(saved_bytes);
    struct timeval old[2] = {{946684800, 0}, {946684800, 0}}; /* 2000-01-01: a hit makes it recent */
    utimes(entry, old);
    int third = build_and_run(salt, 0);
    struct stat st;
    int touched = stat(entry, &st) == 0 && st.st_mtime > 946684800;
    cache_off();
    CHECK(first == 42 + salt && second == 42 + salt && third == 42 + salt, "answers %d %d %d", first, second, third);
    CHECK(saved == 0, "the first build saved an entry (%d)", saved);
    CHECK(now_saved == 1, "the second build saved %d entries", now_saved);
    CHECK(touched, "the third build did not use the entry");
    CHECK(!bitcode, "the entry holds LLVM bitcode");
    test_remove_dir(dir);
}

/* Where the driver compiles at the build (NVIDIA's took two minutes for a camera kernel), its first build is
 * saved: a second would cost as much again. */
TEST(program_cache_saves_first_build_where_the_driver_compiles) {
    char dir[256], entry[1024];
    test_make_dir(dir, sizeof dir, "pcache-first");
    use_cache(dir);
    int salt = (int)getpid() + 3;
    int first = build_and_run(salt, 1);
    int saved = save_and_wait(dir, entry, sizeof entry);
    struct timeval old[2] = {{946684800, 0}, {946684800, 0}};
    utimes(entry, old);
    int second = build_and_run(salt, 1);
    struct stat st;
    int touched = saved == 1 && stat(entry, &st) == 0 && st.st_mtime > 946684800;
    cache_off();
    CHECK(first == 42 + salt && second == 42 + salt, "answers %d %d", first, second);
    CHECK(saved == 1, "the first build saved %d entries", saved);
    CHECK(touched, "the second build did not use the entry");
    test_remove_dir(dir);
}

TEST(program_cache_refuses_damaged_entry) {
    char dir[256], entry[1024];
    test_make_dir(dir, sizeof dir, "pcache-bad");
    use_cache(dir);
    int salt = (int)getpid() + 1;
    build_and_run(salt, 0);
    build_and_run(salt, 0);
    int saved = save_and_wait(dir, entry, sizeof entry);
    struct stat st;
    int damaged = 0;
    FILE *f = saved == 1 && stat(entry, &st) == 0 ? fopen(entry, "r+b") : NULL;
    if (f) { /* one byte of the binary, past the header, flipped */
        fseek(f, st.st_size / 2, SEEK_SET);
        int c = fgetc(f);
        fseek(f, st.st_size / 2, SEEK_SET);
        damaged = fputc(c ^ 0x5a, f) != EOF;
        fclose(f);
    }
    int answer = build_and_run(salt, 0);
    int left = the_entry(dir, entry, sizeof entry);
    cache_off();
    CHECK(saved == 1 && damaged, "no entry to damage (%d)", saved);
    CHECK(answer == 42 + salt, "with a damaged entry the program answered %d", answer);
    CHECK(left == 0, "the damaged entry was kept");
    test_remove_dir(dir);
}

TEST(program_cache_unwritable_dir) {
    char dir[256], blocker[512];
    test_make_dir(dir, sizeof dir, "pcache-ro");
    snprintf(blocker, sizeof blocker, "%s/file", dir);
    FILE *f = fopen(blocker, "w");
    CHECK(f, "cannot make %s", blocker);
    fclose(f);
    use_cache(blocker); /* a file where the directory should be made */
    int salt = (int)getpid() + 2;
    int first = build_and_run(salt, 0), second = build_and_run(salt, 0);
    clrt_cache_save_deferred();
    cache_off();
    CHECK(first == 42 + salt && second == 42 + salt, "answers %d %d", first, second);
    test_remove_dir(dir);
}

/* The command's image from a cached program is the image from the source's build, byte for byte. The command
 * saves through a detached process (clrt_cache_save_deferred), which the test waits for. */
TEST(program_cache_same_image) {
    char dir[256], cmd[2048];
    test_make_dir(dir, sizeof dir, "pcache-cli");
    char path[1024], entry[1024];
    snprintf(path, sizeof path, "%s/cache", dir);
    for (int k = 1; k <= 3; k++) { /* the first build marks it, the second has it saved, the third loads it */
        for (int wait = 0; k == 3 && wait < 600 && the_entry(path, entry, sizeof entry) != 1; wait++)
            usleep(100000); /* the command's saver runs after it, detached */
        snprintf(cmd, sizeof cmd,
                 "cd '%s' && IACSG_KERNEL_CACHE=1 IACSG_CACHE_DIR='%s/cache' '%s' 'sphere' -size 24x16 -eye 0,-4,1 "
                 "-o run%d.png >/dev/null 2>&1",
                 dir, dir, test_binary_path(), k);
        int rc = system(cmd);
        CHECK(WIFEXITED(rc) && WEXITSTATUS(rc) == 0, "run %d failed", k);
    }
    int saved = the_entry(path, entry, sizeof entry);
    size_t n1 = 0, n3 = 0;
    snprintf(path, sizeof path, "%s/run1.png", dir);
    char *a = test_read_file(path, &n1);
    snprintf(path, sizeof path, "%s/run3.png", dir);
    char *b = test_read_file(path, &n3);
    int same = a && b && n1 == n3 && memcmp(a, b, n1) == 0;
    free(a);
    free(b);
    CHECK(saved == 1, "%d cache entries", saved);
    CHECK(same, "the image from the cached program differs");
    test_remove_dir(dir);
}
