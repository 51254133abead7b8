/* tests/t_cli_errors.c -- runs every row of tests/bad_inputs.tsv against the iacsg binary and checks the
 * promise of the README's "Errors" section: a one-line message naming the problem, the expected exit status,
 * no crash, no hang, no partial or lost file. */
#include "test.h"
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#define SENTINEL "sentinel"
#define MAX_WORDS 32

static void write_file(const char *dir, const char *name, const char *text, size_t repeat, const char *tail) {
    char path[4096];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    FILE *f = fopen(path, "w");
    CHECK(f, "cannot create %s", path);
    for (size_t i = 0; i < repeat; i++)
        fputs(text, f);
    fputs(tail, f);
    fclose(f);
}

static void make_fixture(const char *dir) {
    write_file(dir, "iacsg.png", SENTINEL, 1, "");
    write_file(dir, "scene.csg", "sphere\n", 1, "");
    write_file(dir, "scene.tif", "sphere\n", 1, "");
    write_file(dir, "notadir", "", 1, "");
    /* multi-material scenes refused by the parser whichever way the command reads them */
    write_file(dir, "final-expression.csg", "solid ball = sphere\nregion r = ball\nbox\n", 1, "");
    write_file(dir, "region-no-expression.csg", "region body = \n", 1, "");
    write_file(dir, "where-no-condition.csg", "surface s = plane where\n", 1, "");
    write_file(dir, "unknown-solid.csg", "solid ball = sphere\nregion r = ball | bal\n", 1, "");
    write_file(dir, "unknown-material.csg", "material red = rgb(1, 0, 0)\nsolid ball = sphere\nregion r = ball : rde\n", 1,
               "");
    write_file(dir, "light-kind.csg", "light sun = spot(0, 0, 5)\nsphere\n", 1, "");
    write_file(dir, "light-negative.csg", "light sun = point(0, 0, 5) intensity -1\nsphere\n", 1, "");
    write_file(dir, "opacity-two.csg", "material glass = rgb(1, 1, 1) opacity 2\nregion r = sphere : glass\n", 1, "");
    write_file(dir, "material-twice.csg", "material red = rgb(1, 0, 0)\nmaterial red = rgb(0, 1, 0)\nsphere\n", 1, "");
    /* BRL-CAD models (.asc): one that renders, and one refusal of each kind */
    write_file(dir, "model.asc", "put {s} ell V {0 0 0} A {1 0 0} B {0 1 0} C {0 0 1}\nput {r} comb region yes tree {l s}\n",
               1, "");
    write_file(dir, "rpc.asc", "I 1 v4\ntitle\nS 26 p 1 0 0 0 0 0 1 0 1 0 1 0 0 0 0 0 0 0 0 0 0 0 0 0 0\n", 1, "");
    write_file(dir, "dangling.asc", "put {r} comb region yes tree {u {l s} {l t}}\n", 1, "");
    write_file(dir, "cycle.asc", "put {a} comb region no tree {l b}\nput {b} comb region no tree {l a}\n", 1, "");
    write_file(dir, "malformed.asc", "put {s} ell V {0 0 0} A {1 0 0} B {0 1} C {0 0 1}\n", 1, "");
    char path[4096];
    snprintf(path, sizeof path, "%s/deep.csg", dir);
    FILE *f = fopen(path, "w");
    CHECK(f, "cannot create %s", path);
    for (int i = 0; i < 100000; i++)
        fputc('(', f);
    fputc('x', f);
    for (int i = 0; i < 100000; i++)
        fputc(')', f);
    fclose(f);
    write_file(dir, "long.csg", "x*0.5+", 1000000 / 6, "y\n");
}

static int count_entries(const char *dir) {
    DIR *d = opendir(dir);
    int n = 0;
    struct dirent *e;
    while (d && (e = readdir(d)))
        n += e->d_name[0] != '.';
    if (d)
        closedir(d);
    return n;
}

static void remove_tree(const char *dir) {
    DIR *d = opendir(dir);
    struct dirent *e;
    while (d && (e = readdir(d))) {
        if (e->d_name[0] == '.' && (e->d_name[1] == '\0' || (e->d_name[1] == '.' && e->d_name[2] == '\0')))
            continue;
        char path[4096];
        snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
        unlink(path);
    }
    if (d)
        closedir(d);
    rmdir(dir);
}

/* Runs the binary in dir with the row's words; returns the wait status (-1 on timeout) and stderr's text. */
static int run(const char *dir, char **words, int nwords, char *err_text, size_t err_size) {
    char err_path[4096];
    snprintf(err_path, sizeof err_path, "%s/.stderr", dir);
    pid_t pid = fork();
    CHECK(pid >= 0, "fork failed");
    if (pid == 0) {
        if (chdir(dir) != 0)
            _exit(126);
        int fd = open(err_path, O_WRONLY | O_CREAT | O_TRUNC, 0644);
        int null = open("/dev/null", O_RDWR);
        if (fd < 0 || null < 0)
            _exit(126);
        dup2(fd, 2);
        dup2(null, 1);
        dup2(null, 0);
        char *argv[MAX_WORDS + 2];
        int argc = 0;
        argv[argc++] = (char *)test_binary_path();
        for (int i = 0; i < nwords; i++) {
            char *eq = strchr(words[i], '=');
            if (argc == 1 && eq && eq != words[i] && strspn(words[i], "ABCDEFGHIJKLMNOPQRSTUVWXYZ_") ==
                                                         (size_t)(eq - words[i])) {
                *eq = '\0';
                setenv(words[i], eq + 1, 1);
                continue;
            }
            argv[argc++] = strcmp(words[i], "''") == 0 ? (char *)"" : words[i];
        }
        argv[argc] = NULL;
        execv(argv[0], argv);
        _exit(127);
    }
    int status = 0;
    struct timespec start, now;
    clock_gettime(CLOCK_MONOTONIC, &start);
    for (;;) {
        pid_t r = waitpid(pid, &status, WNOHANG);
        if (r == pid)
            break;
        clock_gettime(CLOCK_MONOTONIC, &now);
        if (now.tv_sec - start.tv_sec > 60) {
            kill(pid, SIGKILL);
            waitpid(pid, &status, 0);
            status = -1;
            break;
        }
        struct timespec nap = {0, 10000000};
        nanosleep(&nap, NULL);
    }
    FILE *f = fopen(err_path, "r");
    size_t n = f ? fread(err_text, 1, err_size - 1, f) : 0;
    err_text[n] = '\0';
    if (f)
        fclose(f);
    unlink(err_path);
    return status;
}

/* Checks one row; returns NULL if it keeps every promise, else what went wrong (static buffer). */
static const char *check_row(const char *dir, int baseline, const char *status_text, const char *fragment,
                             char *args) {
    static char why[32768]; /* room for every part in full: shown + stderr + fragment */
    char shown[4096];
    snprintf(shown, sizeof shown, "iacsg %s", args);
    char *words[MAX_WORDS];
    int nwords = 0;
    for (char *w = strtok(args, " "); w && nwords < MAX_WORDS; w = strtok(NULL, " "))
        words[nwords++] = w;
    char err_text[16384];
    int status = run(dir, words, nwords, err_text, sizeof err_text);
    char *nl = strchr(err_text, '\n');
    if (nl)
        *nl = '\0';
    char sentinel[64] = "", path[4096];
    snprintf(path, sizeof path, "%s/iacsg.png", dir);
    FILE *s = fopen(path, "r");
    size_t n = s ? fread(sentinel, 1, sizeof sentinel - 1, s) : 0;
    sentinel[n] = '\0';
    if (s)
        fclose(s);
    if (status == -1)
        snprintf(why, sizeof why, "%s: still running after 60 s", shown);
    else if (WIFSIGNALED(status))
        snprintf(why, sizeof why, "%s: killed by signal %d; stderr: %s", shown, WTERMSIG(status), err_text);
    else if (WEXITSTATUS(status) != atoi(status_text))
        snprintf(why, sizeof why, "%s: exit status %d, expected %s; stderr: %s", shown, WEXITSTATUS(status),
                 status_text, err_text);
    else if (!nl)
        snprintf(why, sizeof why, "%s: stderr is not a line: '%s'", shown, err_text);
    else if (strncmp(err_text, "iacsg: ", 7) != 0 || !strstr(err_text, fragment))
        snprintf(why, sizeof why, "%s: first line '%s' lacks '%s'", shown, err_text, fragment);
    else if (count_entries(dir) != baseline)
        snprintf(why, sizeof why, "%s: left a file behind", shown);
    else if (strcmp(sentinel, SENTINEL) != 0)
        snprintf(why, sizeof why, "%s: the existing iacsg.png was changed", shown);
    else
        return NULL;
    return why;
}

TEST(cli_bad_inputs) {
    char table[4096];
    snprintf(table, sizeof table, "%s/tests/bad_inputs.tsv", test_source_dir());
    FILE *f = fopen(table, "r");
    CHECK(f, "cannot open %s", table);
    int rows = 0, failures = 0;
    char line[4096];
    while (fgets(line, sizeof line, f)) {
        if (line[0] == '#' || line[0] == '\n')
            continue;
        line[strcspn(line, "\n")] = '\0';
        char *status_text = strtok(line, "\t"), *fragment = strtok(NULL, "\t"), *args = strtok(NULL, "\t");
        if (!status_text || !fragment || !args) {
            printf("    malformed row in %s\n", table);
            failures++;
            continue;
        }
        char tmpl[] = "/tmp/iacsg-bad-XXXXXX"; /* a fresh directory per row: one failure cannot mask the next */
        char *dir = mkdtemp(tmpl);
        CHECK(dir, "mkdtemp failed");
        make_fixture(dir);
        const char *why = check_row(dir, count_entries(dir), status_text, fragment, args);
        remove_tree(dir);
        if (why) {
            printf("    %s\n", why);
            failures++;
        }
        rows++;
    }
    fclose(f);
    CHECK(failures == 0, "%d of %d bad inputs broke a promise (listed above)", failures, rows);
    test_note("%d bad inputs: each a one-line error with the expected status, no crash, hang or stray file", rows);
}

/* A good input that the bad-input rules must not catch: an expression longer than a file name may be (its
 * fopen fails with ENAMETOOLONG, not ENOENT) is still an expression. */
TEST(cli_long_expression_is_not_a_file) {
    char tmpl[] = "/tmp/iacsg-long-XXXXXX";
    char *dir = mkdtemp(tmpl);
    CHECK(dir, "mkdtemp failed");
    static char expr[512];
    expr[0] = '\0';
    for (int k = 0; k < 40; k++)
        strcat(expr, k ? "+sphere(0.5)" : "sphere(0.5)");
    char *words[] = {expr, "-size", "8x8", "-o", "out.png"};
    char err_text[16384];
    int status = run(dir, words, 5, err_text, sizeof err_text);
    remove_tree(dir);
    CHECK(status != -1 && WIFEXITED(status) && WEXITSTATUS(status) == 0, "a %zu-character expression failed: %s",
          strlen(expr), err_text);
}
