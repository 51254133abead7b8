/* tests/t_expr_cli.c -- `iacsg eval` and `iacsg compile` as a user runs them: exact round trip of the printed
 * bounds, decimal boxes taken as reals, host and device agreement, error messages with a caret. */
#include "ia/decimal.h"
#include "implicits/expr_internal.h"
#include "test.h"
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>

/* Runs the iacsg binary with args (a shell-quoted string); stdout and stderr into out. Returns the exit status. */
static int run(const char *args, char *out, size_t size) {
    char cmd[2048];
    snprintf(cmd, sizeof cmd, "'%s' %s 2>&1", test_binary_path(), args);
    FILE *p = popen(cmd, "r");
    CHECK(p != NULL, "cannot run %s", cmd);
    size_t n = fread(out, 1, size - 1, p);
    out[n] = '\0';
    int status = pclose(p);
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

static void parse_pair(const char *s, double r[2]) {
    CHECK(sscanf(s, "[%lf, %lf]", &r[0], &r[1]) == 2, "not an interval: %s", s);
}

TEST(expr_cli_eval) {
    char out[8192];
    double r[2], d[2];
    /* x^2 over [0.1, 0.1] with 0.1 the real: the float interval must contain 1/100 and be tight */
    CHECK(run("eval 'x^2' --at 0.1,0,0", out, sizeof out) == 0, "%s", out);
    parse_pair(out, r);
    CHECK(r[0] < 0.01 && 0.01 < r[1] && r[1] - r[0] < 1e-8, "x^2 at 0.1: %s", out);
    CHECK(run("eval 'x^2' --at 0.1,0,0 --fp64", out, sizeof out) == 0, "%s", out);
    parse_pair(out, d);
    CHECK(d[0] < 0.01 && 0.01 < d[1] && d[1] - d[0] < 1e-16 && d[0] >= r[0] && d[1] <= r[1], "fp64: %s", out);
    /* printed bounds parse back to exactly the doubles the library computed */
    double lo, hi, v[8] = {0, 0, 0, 0, 0, 0, 0, 0}, want[2];
    iacsg_expr *e;
    CHECK(ia_decimal_double("0.1", &lo, &hi) == 0, "0.1");
    v[0] = lo, v[1] = hi;
    CHECK(iacsg_expr_parse("x^2", "<test>", &e, NULL) == IACSG_OK, "x^2");
    CHECK(iacsg_expr_eval_vars(e, 1, v, want, NULL) == IACSG_OK, "eval");
    iacsg_expr_destroy(e);
    CHECK(d[0] == want[0] && d[1] == want[1], "printed [%a, %a], computed [%a, %a]", d[0], d[1], want[0], want[1]);
    /* the device gives an enclosure of the same thing */
    CHECK(run("eval 'torus(R=1, r=0.25)' --box 0.5,1,0,0.5,-0.25,0.25 --device", out, sizeof out) == 0, "%s", out);
    parse_pair(out, d);
    CHECK(run("eval 'torus(R=1, r=0.25)' --box 0.5,1,0,0.5,-0.25,0.25", out, sizeof out) == 0, "%s", out);
    parse_pair(out, r);
    CHECK(d[0] <= 0 && 0 <= d[1] && r[0] <= 0 && 0 <= r[1] && d[1] - d[0] < 2 * (r[1] - r[0]) + 1e-3,
          "device %g..%g, host %g..%g", d[0], d[1], r[0], r[1]);
    /* scene files are read when the argument names one */
    char args[1024];
    snprintf(args, sizeof args, "eval '%s/examples/fig2_cube_sphere_difference.csg' --at 0,0,0 --fp64",
             test_source_dir());
    CHECK(run(args, out, sizeof out) == 0, "%s", out);
    parse_pair(out, r);
    CHECK(r[0] > 0, "the centre of the cube minus the ball is outside: %s", out);
}

TEST(expr_cli_errors) {
    char out[8192];
    CHECK(run("eval 'min(sphere, tours(R=2))'", out, sizeof out) == 1, "%s", out);
    CHECK(strstr(out, "iacsg: <expr>:1:13: unknown primitive 'tours', did you mean 'torus'?\n"
                      "  min(sphere, tours(R=2))\n"
                      "              ^\n"),
          "got:\n%s", out);
    CHECK(run("compile 'x); } __kernel void evil('", out, sizeof out) == 1 && strstr(out, "1:5: unexpected character") &&
              !strstr(out, "__kernel void evil(\n}"),
          "got:\n%s", out);
    CHECK(run("eval sphere --box 1,2,3", out, sizeof out) == 2 && strstr(out, "--box wants six numbers"), "%s", out);
    CHECK(run("compile sphere --dump nonsense", out, sizeof out) == 1 && strstr(out, "unknown stage"), "%s", out);
}

TEST(expr_cli_compile) {
    char out[65536];
    CHECK(run("compile 'sphere(0.5)'", out, sizeof out) == 0, "%s", out);
    CHECK(strstr(out, "IA_FN ia_interval iacsg_F(") && strstr(out, "ia_sqr(x)") && strstr(out, "iacsg_f_grad("),
          "%s", out);
    CHECK(run("compile 'sphere(0.5)' --prefix ball", out, sizeof out) == 0 && strstr(out, "ball_F("), "%s", out);
    static const char *const stages[] = {"tokens", "ast", "dag", "simple"};
    static const char *const marks[] = {"1:1 NAME sphere", "call sphere(n0)", "POW", "SQR"};
    for (int i = 0; i < 4; i++) {
        char args[128];
        snprintf(args, sizeof args, "compile 'sphere(0.5)' --dump %s", stages[i]);
        CHECK(run(args, out, sizeof out) == 0 && strstr(out, marks[i]), "--dump %s lacks '%s':\n%s", stages[i],
              marks[i], out);
    }
}

/* A first build (empty PoCL and program caches) prints nothing on stderr: the device compiler's warnings are not
 * the user's (clrt_ia_options builds with -w; PoCL printed "729 warnings generated." on a CPU without AVX-512).
 * Nor may the emitted code warn (a scale's division once tested its constant divisor for 0): built again with the
 * warnings kept (IACSG_KERNEL_WARNINGS), every warning in PoCL's build logs must be clang's -Wpsabi note on the
 * 16 lanes' vectors, which on such a CPU is at every function that passes them. */
static void first_build(const char *dir, const char *env, int *rc, char **err) {
    char cmd[2048], path[1024];
    snprintf(cmd, sizeof cmd,
             "cd '%s' && rm -rf pocl cache && %s POCL_CACHE_DIR='%s/pocl' IACSG_CACHE_DIR='%s/cache' '%s' "
             "'scale(sphere, 2, 1, 1) | move(scale(citrus, 2.4, 3.2, 2.4), 0, -1.6, 0)' -size 16x16 -o q.png "
             ">/dev/null 2>stderr.txt",
             dir, env, dir, dir, test_binary_path());
    *rc = system(cmd);
    snprintf(path, sizeof path, "%s/stderr.txt", dir);
    size_t n = 0;
    *err = test_read_file(path, &n);
}

TEST(expr_cli_first_build_is_quiet) {
    char dir[256], cmd[1024], path[1024];
    test_make_dir(dir, sizeof dir, "quiet-build");
    int rc;
    char *err;
    first_build(dir, "", &rc, &err);
    CHECK(WIFEXITED(rc) && WEXITSTATUS(rc) == 0, "the render failed: %s", err ? err : "");
    CHECK(err && err[0] == '\0', "the first build printed on stderr: %s", err ? err : "(no file)");
    free(err);
    first_build(dir, "IACSG_KERNEL_WARNINGS=1", &rc, &err);
    CHECK(WIFEXITED(rc) && WEXITSTATUS(rc) == 0, "the render with warnings kept failed: %s", err ? err : "");
    free(err);
    snprintf(cmd, sizeof cmd, "cd '%s' && find pocl -name build.log -exec cat {} + >logs.txt 2>/dev/null", dir);
    CHECK(system(cmd) == 0, "%s failed", cmd);
    snprintf(path, sizeof path, "%s/logs.txt", dir);
    size_t n = 0;
    char *logs = test_read_file(path, &n);
    int warnings = 0, abi = 0;
    for (char *line = logs; line && *line;) {
        char *end = strchr(line, '\n');
        if (end)
            *end = '\0';
        if (strstr(line, "warning:")) {
            warnings++;
            int note = strstr(line, "without 'avx512f' enabled changes the ABI") != NULL;
            abi += note;
            CHECK(note, "the emitted code warns: %s", line);
        }
        line = end ? end + 1 : line + strlen(line);
    }
    test_note("%d warnings in PoCL's build logs, %d of them -Wpsabi's", warnings, abi);
    free(logs);
    test_remove_dir(dir);
}
