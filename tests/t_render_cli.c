/* tests/t_render_cli.c -- the `iacsg` render command end to end: it writes the images it names (depth as float,
 * +inf where the ray misses), exits 2 on a bad option, 1 on a failure, and never leaves or damages a file when
 * it fails. */
#include "iacsg.h"
#include "image.h"
#include "test.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
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
    test_make_dir(dir, sizeof dir, "cli");
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
    test_remove_dir(dir);
}

/* The command writes its images through a child process (src/cli_writer.c), converting the colours to 8 bits
 * itself: the file holds exactly the bytes OpenImageIO makes of the library's float frame. */
TEST(render_cli_png_matches_library) {
    char dir[256], path[1024];
    test_make_dir(dir, sizeof dir, "cli-png");
    const char *expr = "min((x-0.5)^2+y^2+z^2-1, (1-sqrt(x^2+y^2))^2+z^2-0.125)";
    char args[512];
    snprintf(args, sizeof args, "'%s' -size 64x48 -eye 0,-4,2.5 -at 0,0,0 -bounds -2,-2,-2,2,2,2 -o cli.png", expr);
    int rc = run_iacsg(dir, args);
    CHECK(rc == 0, "render exited with %d", rc);

    iacsg_error err = {0};
    iacsg_expr *e = NULL;
    CHECK(iacsg_expr_parse(expr, "<expr>", &e, &err) == IACSG_OK, "%s", err.message);
    iacsg_render_config config = {0};
    iacsg_renderer *r = NULL;
    iacsg_status st = iacsg_renderer_create_expr(e, &config, &r, &err);
    iacsg_expr_destroy(e);
    CHECK(st == IACSG_OK, "%s", err.message);
    iacsg_view v = {.width = 64, .height = 48, .eps = 0x1p-16, .bounds = {-2, -2, -2, 2, 2, 2},
                    .camera = {.eye = {0, -4, 2.5}, .at = {0, 0, 0}, .up = {0, 0, 1}, .fov = 40}};
    iacsg_frame fr;
    st = iacsg_render(r, &v, &fr, &err);
    iacsg_renderer_destroy(r);
    CHECK(st == IACSG_OK, "%s", err.message);
    snprintf(path, sizeof path, "%s/library.png", dir);
    st = iacsg_image_write(path, fr.width, fr.height, 3, fr.rgb, 0, &err);
    iacsg_frame_free(&fr);
    CHECK(st == IACSG_OK, "%s", err.message);

    float *from_cli = NULL, *from_library = NULL;
    int w[2], h[2], ch[2];
    snprintf(path, sizeof path, "%s/cli.png", dir);
    CHECK(iacsg_image_read(path, &w[0], &h[0], &ch[0], &from_cli, &err) == IACSG_OK, "%s", err.message);
    snprintf(path, sizeof path, "%s/library.png", dir);
    CHECK(iacsg_image_read(path, &w[1], &h[1], &ch[1], &from_library, &err) == IACSG_OK, "%s", err.message);
    CHECK(w[0] == 64 && h[0] == 48 && ch[0] == 3 && w[1] == 64 && h[1] == 48 && ch[1] == 3, "image sizes");
    long differ = 0;
    for (long k = 0; k < 64 * 48 * 3; k++)
        differ += from_cli[k] != from_library[k];
    free(from_cli);
    free(from_library);
    CHECK(differ == 0, "%ld channel values differ between the command's PNG and the library's", differ);
    test_remove_dir(dir);
}

/* Without its image library beside it, the command says so in one line, exits 1 and writes nothing. */
TEST(render_cli_without_image_library) {
    char dir[256], cmd[2048];
    test_make_dir(dir, sizeof dir, "cli-nolib");
    snprintf(cmd, sizeof cmd, "cp '%s' '%s/iacsg' && cd '%s' && ./iacsg sphere -size 8x8 -o out.png 2>err.txt >/dev/null",
             test_binary_path(), dir, dir);
    int rc = system(cmd);
    CHECK(WIFEXITED(rc) && WEXITSTATUS(rc) == 1, "exit %d, expected 1", WIFEXITED(rc) ? WEXITSTATUS(rc) : -1);
    CHECK(!exists(dir, "out.png"), "an image was written");
    char path[1024], line[1024] = "";
    snprintf(path, sizeof path, "%s/err.txt", dir);
    FILE *f = fopen(path, "r");
    CHECK(f, "no stderr file");
    CHECK(fgets(line, sizeof line, f), "empty stderr");
    fclose(f);
    const char *expected = "iacsg: cannot load the image library";
    CHECK(strncmp(line, expected, strlen(expected)) == 0, "stderr: %s", line);
    test_remove_dir(dir);
}
