/* tests/t_render_scene_cli.c -- the command on a scene with regions: -ids writes each pixel's region (float32,
 * -1 where none; an expression: 0 where it hits), -stats reports the segment path's counts, and the bounds default
 * to the union of the solids' proven boxes. */
#include "iacsg.h"
#include "image.h"
#include "test.h"
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

/* Runs the command with `args` in `dir`, its standard output into dir/out.txt; returns its exit status. */
static int run_in(const char *dir, const char *args) {
    char cmd[2048];
    snprintf(cmd, sizeof cmd, "cd '%s' && '%s' %s >out.txt 2>&1", dir, test_binary_path(), args);
    int rc = system(cmd);
    return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
}

/* The float image dir/name, one channel of w x h (the test fails otherwise); the caller free()s it. */
static float *read_ids(const char *dir, const char *name, int w, int h) {
    char path[1024];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    int iw, ih, ch;
    float *ids = NULL;
    iacsg_error err = {0};
    CHECK(iacsg_image_read(path, &iw, &ih, &ch, &ids, &err) == IACSG_OK, "%s", err.message);
    CHECK(iw == w && ih == h && ch == 1, "%s is %dx%dx%d", name, iw, ih, ch);
    return ids;
}

TEST(render_scene_cli_ids) {
    char dir[256], path[1024];
    test_make_dir(dir, sizeof dir, "scene-cli");
    snprintf(path, sizeof path, "%s/two.csg", dir);
    FILE *f = fopen(path, "w");
    CHECK(f != NULL, "cannot write %s", path);
    fputs("material red = rgb(0.8, 0.2, 0.1)\nsolid ball = sphere(1.2)\nsolid bar = box(1.5, 0.4, 0.4)\n"
          "region body = ball \\ bar : red\nregion plug = ball & bar\n",
          f);
    fclose(f);
    int rc = run_in(dir, "two.csg -size 64x48 -az 0 -el 0 -ortho 3 -eps 1e-4 -ids ids.exr -o two.png -stats");
    CHECK(rc == 0, "render exited with %d", rc);
    float *ids = read_ids(dir, "ids.exr", 64, 48);
    int count[3] = {0};
    for (int k = 0; k < 64 * 48; k++) {
        CHECK(ids[k] == -1 || ids[k] == 0 || ids[k] == 1, "pixel %d has id %g", k, ids[k]);
        count[(int)ids[k] + 1]++;
    }
    /* seen along -x, 16 pixels a unit: the plug's end face in the middle, the body 0.75 left of it, background in the
     * corners */
    CHECK(ids[24 * 64 + 32] == 1 && ids[24 * 64 + 20] == 0 && ids[0] == -1, "middle %g, left %g, corner %g",
          ids[24 * 64 + 32], ids[24 * 64 + 20], ids[0]);
    free(ids);
    snprintf(path, sizeof path, "%s/out.txt", dir);
    char *out = test_read_file(path, NULL);
    CHECK(out && strstr(out, "(proven to enclose the solids)") && strstr(out, "segments per ray: mean") &&
              strstr(out, "partitions per ray: mean") && strstr(out, "overlaps: 0 partitions") &&
              strstr(out, "per-ray buffers:") && strstr(out, "\nread: ") && strstr(out, "\nkernel build: "),
          "output: %s", out ? out : "(none)");
    free(out);
    test_note("%d background, %d body, %d plug pixels", count[0], count[1], count[2]);

    rc = run_in(dir, "sphere -size 16x16 -ids plain.tif -o plain.png");
    CHECK(rc == 0, "plain render exited with %d", rc);
    ids = read_ids(dir, "plain.tif", 16, 16);
    CHECK(ids[8 * 16 + 8] == 0 && ids[0] == -1, "an expression's ids: middle %g, corner %g", ids[8 * 16 + 8], ids[0]);
    free(ids);
    test_remove_dir(dir);
}

/* Regions need a scene file: on the command line, an expression is one solid, and a region in it is refused at
 * its place, with no image written. */
TEST(render_scene_cli_region_in_expression) {
    char dir[256], path[1024];
    test_make_dir(dir, sizeof dir, "scene-expr");
    int rc = run_in(dir, "'solid a = sphere; region r = a'");
    snprintf(path, sizeof path, "%s/out.txt", dir);
    char *out = test_read_file(path, NULL);
    CHECK(rc == 1 && out && strstr(out, "iacsg: <expr>:1:19: a region makes a multi-material scene"), "exit %d: %s", rc,
          out ? out : "");
    free(out);
    snprintf(path, sizeof path, "%s/iacsg.png", dir);
    CHECK(access(path, F_OK) != 0, "an image was written");
    test_remove_dir(dir);
}
