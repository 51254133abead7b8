/* tests/t_render_cli.c -- the `iacsg` render command end to end: it writes the images it names (depth as float,
 * +inf where the ray misses), exits 2 on a bad option, 1 on a failure, and never leaves or damages a file when
 * it fails. */
#include "image.h"
#include "test.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

/* Runs the command with `args` in `dir`, output discarded; returns its exit status. */
static int run_iacsg(const char *dir, const char *args) {
    char cmd[2048];
    snprintf(cmd, sizeof cmd, "cd '%s' && '%s' %s >/dev/null 2>&1", dir, test_binary_path(), args);
    int rc = system(cmd);
    return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
}

static int exists(const char *dir, const char *name) {
    char path[1024];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    return access(path, F_OK) == 0;
}

TEST(render_cli_writes_images) {
    char dir[256], path[1024];
    snprintf(dir, sizeof dir, "/tmp/iacsg-cli-%ld", (long)getpid());
    mkdir(dir, 0700);
    int rc = run_iacsg(dir, "'x^2+y^2+z^2-1' -size 40x30 -eye 0,-5,0 -fov 30 -o out.png -depth depth.exr");
    CHECK(rc == 0, "render exited with %d", rc);
    CHECK(exists(dir, "out.png"), "no out.png");
    snprintf(path, sizeof path, "%s/depth.exr", dir);
    int w, h, ch;
    float *depth = NULL;
    iacsg_error err = {0};
    CHECK(iacsg_image_read(path, &w, &h, &ch, &depth, &err) == IACSG_OK, "%s", err.message);
    CHECK(w == 40 && h == 30 && ch == 1, "depth image is %dx%dx%d", w, h, ch);
    /* The centre ray hits the unit sphere 4 units from the eye; the corner ray misses it. */
    float centre = depth[15 * 40 + 20], corner = depth[0];
    free(depth);
    CHECK(fabsf(centre - 4.0f) < 0.01f, "centre depth %g, expected about 4", centre);
    CHECK(isinf(corner) && corner > 0, "corner depth %g, expected +inf", corner);

    rc = run_iacsg(dir, "'sphere' -size 8x8 -frames 2 -o anim.png");
    CHECK(rc == 0 && exists(dir, "anim_0000.png") && exists(dir, "anim_0001.png"), "frames: exit %d", rc);

    struct stat before, after;
    snprintf(path, sizeof path, "%s/out.png", dir);
    CHECK(stat(path, &before) == 0, "out.png vanished");
    CHECK(run_iacsg(dir, "'sphere' -size 8x8 -bogus 1 -o out.png") == 2, "a bad option did not exit 2");
    CHECK(run_iacsg(dir, "'sphere(' -size 8x8 -o out.png") == 1, "a syntax error did not exit 1");
    CHECK(run_iacsg(dir, "'sphere' -size 8x8 -o nowhere/out.png") == 1, "an unwritable output did not exit 1");
    CHECK(stat(path, &after) == 0 && after.st_size == before.st_size && after.st_mtime == before.st_mtime,
          "a failed command changed out.png");
    snprintf(path, sizeof path, "rm -rf '%s'", dir);
    CHECK(system(path) == 0, "cannot clean %s", dir);
}
