/* tests/t_image.c -- image files through OpenImageIO: formats by extension, float data kept in float files,
 * and the temporary-file rule: a failed write leaves no file and never touches an existing one; the colours'
 * conversion to bytes (src/image_bytes.c) as OpenImageIO would convert them. */
#include "image.h"
#include "image_bytes.h"
#include "test.h"
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* A fresh directory under /tmp for this test (removed by the caller's cleanup_dir). */
static void make_dir(char *dir, size_t size, const char *name) {
    snprintf(dir, size, "/tmp/iacsg-test-%s-%ld", name, (long)getpid());
    mkdir(dir, 0700);
}

static void cleanup_dir(const char *dir, const char *const *files, int n) {
    char path[512];
    for (int k = 0; k < n; k++) {
        snprintf(path, sizeof path, "%s/%s", dir, files[k]);
        remove(path);
    }
    rmdir(dir);
}

static int count_entries(const char *dir) {
    char cmd[600];
    snprintf(cmd, sizeof cmd, "ls -A %s | wc -l", dir);
    FILE *f = popen(cmd, "r");
    int n = -1;
    if (f) {
        if (fscanf(f, "%d", &n) != 1)
            n = -1;
        pclose(f);
    }
    return n;
}

TEST(image_round_trip) {
    char dir[256], path[512];
    make_dir(dir, sizeof dir, "rt");
    enum { W = 5, H = 3 };
    float rgb[W * H * 3], depth[W * H];
    for (int k = 0; k < W * H; k++) {
        for (int c = 0; c < 3; c++)
            rgb[3 * k + c] = (float)((k * 3 + c) % 11) / 10.0f;
        depth[k] = k == 4 ? INFINITY : 1.0f + (float)k * 0.123456789f;
    }
    static const char *const files[] = {"a.png", "a.tif", "d.exr", "d.tif"};
    for (int f = 0; f < 4; f++) {
        int is_depth = f >= 2;
        snprintf(path, sizeof path, "%s/%s", dir, files[f]);
        iacsg_error err = {0};
        iacsg_status st = iacsg_image_write(path, W, H, is_depth ? 1 : 3, is_depth ? depth : rgb, is_depth, &err);
        CHECK(st == IACSG_OK, "%s: %s", files[f], err.message);
        int w, h, ch;
        float *back = NULL;
        CHECK(iacsg_image_read(path, &w, &h, &ch, &back, &err) == IACSG_OK, "%s: %s", files[f], err.message);
        CHECK(w == W && h == H && ch == (is_depth ? 1 : 3), "%s: read %dx%dx%d", files[f], w, h, ch);
        for (int k = 0; k < W * H * ch; k++) {
            float want = is_depth ? depth[k] : rgb[k];
            /* 8-bit files quantize to 1/255; float files are exact, infinity included */
            int ok = is_depth ? (back[k] == want) : fabsf(back[k] - want) <= 0.5f / 255 + 1e-6f;
            CHECK(ok, "%s: value %d read back as %.9g, written %.9g", files[f], k, back[k], want);
        }
        free(back);
    }
    cleanup_dir(dir, files, 4);
}

TEST(image_failed_write_keeps_existing_file) {
    char dir[256], path[512];
    make_dir(dir, sizeof dir, "keep");
    float px[4 * 4 * 3] = {0};
    iacsg_error err = {0};
    snprintf(path, sizeof path, "%s/keep.png", dir);
    CHECK(iacsg_image_write(path, 4, 4, 3, px, 0, &err) == IACSG_OK, "%s", err.message);
    struct stat before, after;
    CHECK(stat(path, &before) == 0, "no file after a successful write");
    /* A write that fails inside the format plugin: more channels than PNG can store. */
    float wide[4 * 4 * 7] = {0};
    iacsg_status st = iacsg_image_write(path, 4, 4, 7, wide, 0, &err);
    CHECK(st == IACSG_ERR_IO, "7 channels to PNG: status %d, expected a failure", (int)st);
    CHECK(stat(path, &after) == 0 && after.st_size == before.st_size && after.st_mtime == before.st_mtime,
          "a failed write (status %d) changed the existing file", (int)st);
    /* An unknown extension fails before anything is written. */
    snprintf(path, sizeof path, "%s/new.notaformat", dir);
    CHECK(iacsg_image_write(path, 4, 4, 3, px, 0, &err) == IACSG_ERR_IO, "unknown extension accepted");
    CHECK(count_entries(dir) == 1, "the directory holds %d entries, expected only keep.png", count_entries(dir));
    static const char *const files[] = {"keep.png"};
    cleanup_dir(dir, files, 1);
}

/* The byte OpenImageIO stores for a display-encoded float: clamped to [0, 1] (NaN to 0), then v * 255 + 0.5 in
 * float, each step rounded to nearest, truncated. Spelled here through double: the sum of two floats is exact
 * there, and rounding it to float is the float sum. (Just below 0.5 / 255 that gives 1, not the 0 that rounding
 * the product half up would: the float sum rounds 0.49999997 + 0.5 up to 1.) */
static unsigned char expected_byte(float v) {
    if (!(v > 0))
        return 0;
    if (v >= 1)
        return 255;
    volatile float p = v * 255.0f, q = (float)((double)p + 0.5);
    return (unsigned char)floor(q);
}

static float float_of_bits(uint32_t u) {
    float f;
    memcpy(&f, &u, sizeof f);
    return f;
}

/* image_floats_to_bytes (the vector steps of 16 and the scalar tail) against expected_byte: every float within 300
 * ulps of each rounding boundary (k - 0.5) / 255, a stride through all of [0, 1], the specials, at an unaligned
 * start and a length that leaves a tail. */
TEST(image_floats_to_bytes_match_rounding) {
    enum { NEAR = 300, STRIDE = 251 };
    size_t cap = 256 * (2 * NEAR + 1) + 0x3f800000u / STRIDE + 64, n = 0;
    float *in = malloc((cap + 1) * sizeof *in);
    unsigned char *out = malloc(cap);
    CHECK(in && out, "out of memory");
    const float specials[] = {NAN, -NAN, INFINITY, -INFINITY, -0.0f, 0.0f, -1.0f, 1.0f, 1.5f, 255.0f, FLT_MAX,
                              -FLT_MAX, FLT_TRUE_MIN, FLT_MIN, 0.5f / 255, 254.5f / 255, 1 - FLT_EPSILON / 2};
    for (size_t k = 0; k < sizeof specials / sizeof specials[0]; k++)
        in[1 + n++] = specials[k];
    for (int k = 1; k <= 256; k++) {
        float b = (k - 0.5f) / 255;
        uint32_t u;
        memcpy(&u, &b, sizeof u);
        for (int d = -NEAR; d <= NEAR; d++)
            in[1 + n++] = float_of_bits(u + (uint32_t)d);
    }
    for (uint32_t u = 0; u < 0x3f800000u; u += STRIDE)
        in[1 + n++] = float_of_bits(u);
    if (n % 16 == 0)
        in[1 + n++] = 0.25f; /* a tail for the scalar loop */
    image_floats_to_bytes(in + 1, out, n);
    size_t wrong = 0, first = 0;
    for (size_t k = 0; k < n; k++)
        if (out[k] != expected_byte(in[1 + k]) && wrong++ == 0)
            first = k;
    CHECK(wrong == 0, "%zu of %zu bytes differ, the first for %a: %d, expected %d", wrong, n, (double)in[1 + first],
          out[first], expected_byte(in[1 + first]));
    test_note("%zu floats", n);
    free(in);
    free(out);
}
