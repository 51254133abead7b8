/* tests/t_brlcad_cli.c -- the BRL-CAD commands end to end: `iacsg objects`, `iacsg regions`, and `iacsg MODEL.asc
 * OBJECT -ids` in its default view (rt's), whose every pixel must name the region nirt's first partition names
 * along that pixel's ray (tests/data/brlcad/nirt/boolean-ops.txt was made for this very view). */
#include "image.h"
#include "test.h"
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>

static int run_in(const char *dir, const char *args) {
    char cmd[16384];
    snprintf(cmd, sizeof cmd, "cd '%s' && '%s' %s >out.txt 2>&1", dir, test_binary_path(), args);
    int rc = system(cmd);
    return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
}

static char *output_of(const char *dir) {
    char path[512];
    snprintf(path, sizeof path, "%s/out.txt", dir);
    char *out = test_read_file(path, NULL);
    CHECK(out, "cannot read %s", path);
    return out;
}

TEST(brlcad_cli_objects_regions_and_default_view) {
    char dir[256], model[4096], data[4096];
    test_make_dir(dir, sizeof dir, "brlcad-cli");
    snprintf(model, sizeof model, "%s/tests/data/brlcad/boolean-ops.asc", test_source_dir());
    snprintf(data, sizeof data, "%s/tests/data/brlcad/nirt/boolean-ops.txt", test_source_dir());
    char args[8192];
    snprintf(args, sizeof args, "objects '%s'", model);
    CHECK(run_in(dir, args) == 0, "iacsg %s failed", args);
    char *out = output_of(dir);
    CHECK(strcmp(out, "aUbUc\na-b-c\na-b+c\nc-a-b\nall\n") == 0, "objects:\n%s", out);
    free(out);
    snprintf(args, sizeof args, "regions '%s' all", model);
    CHECK(run_in(dir, args) == 0, "iacsg %s failed", args);
    out = output_of(dir);
    CHECK(strstr(out, "(3 regions, 3 solid instances, 0 air regions left out)\n# bounds (rt's model box): -2,-2,-2,2,2,3\n"
                      "0 1000 /all/a.r\n1 1001 /all/b.r\n2 1002 /all/c.r\n"),
          "regions:\n%s", out);
    free(out);
    snprintf(args, sizeof args, "'%s' all -size 24x24 -ids ids.exr -o image.png", model);
    CHECK(run_in(dir, args) == 0, "iacsg %s failed", args);
    char path[512];
    snprintf(path, sizeof path, "%s/ids.exr", dir);
    int w, h, ch;
    float *ids = NULL;
    iacsg_error err = {0};
    CHECK(iacsg_image_read(path, &w, &h, &ch, &ids, &err) == IACSG_OK, "%s", err.message);
    CHECK(w == 24 && h == 24 && ch == 1, "ids %dx%dx%d", w, h, ch);
    static const char *const paths[] = {"/all/a.r", "/all/b.r", "/all/c.r"};
    FILE *f = fopen(data, "r");
    CHECK(f, "cannot open %s", data);
    char line[4096];
    int rays = 0, hits = 0;
    while (fgets(line, sizeof line, f)) {
        int i, j, n;
        char first[256] = "";
        if (sscanf(line, "ray %d %d %d %255s", &i, &j, &n, first) < 3)
            continue;
        int expected = -1;
        for (int k = 0; k < 3 && n > 0; k++)
            if (strcmp(first, paths[k]) == 0)
                expected = k;
        CHECK(n == 0 || expected >= 0, "nirt's region %s", first);
        CHECK(ids[j * 24 + i] == expected, "pixel %d %d: id %g, nirt's first region %d (%s)", i, j, ids[j * 24 + i],
              expected, n ? first : "none");
        rays++;
        hits += expected >= 0;
    }
    fclose(f);
    free(ids);
    CHECK(rays == 576, "%d rays", rays);
    test_note("the default view's 576 pixels name nirt's first region (%d hits)", hits);
    test_remove_dir(dir);
}
