/* tests/t_image.c -- image files through OpenImageIO: formats by extension, float data kept in float files,
 * and the temporary-file rule: a failed write leaves no file and never touches an existing one. */
#include "image.h"
#include "test.h"
#include <math.h>
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
