/* tests/t_install.c -- `make install` and `make uninstall` (issue 13), into temporary prefixes: what is
 * installed, that a program builds against it with pkg-config (shared, and static) and renders what the
 * installed command renders, that the shared library exports only the iacsg_ API, that the command runs from
 * a prefix with no build tree, that uninstall leaves the prefix empty, and that an unwritable prefix is refused
 * in one line. Also: the man page carries every word of `iacsg --help`, and the version macros agree.
 *
 * The tests run make on the build they were compiled in (IACSG_INSTALL_BUILD_DEFAULT, the plain build for a
 * sanitizer build's tests); `make check` and `make test` build everything make install copies first, so
 * make only copies here. */
#include "iacsg.h"
#include "test.h"
#include <dirent.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#define SCENE "fig2_cube_sphere_difference.csg" /* an installed example, independent of t */

/* Where the test writes: a fresh /tmp/iacsg-install-XXXXXX. */
static void make_tmp(char *dir, size_t size) {
    snprintf(dir, size, "/tmp/iacsg-install-XXXXXX");
    CHECK(mkdtemp(dir), "mkdtemp failed");
}
static void remove_tmp(const char *dir) {
    char cmd[1100];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    CHECK(system(cmd) == 0, "cannot clean %s", dir);
}

/* Runs a shell command (printf-style) with its output in tmp/log; returns its exit status. On a failure the
 * log's last lines are in `log_tail`. */
static char log_tail[1024];
static int shell(const char *tmp, const char *fmt, ...) {
    char cmd[8192];
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(cmd, sizeof cmd, fmt, ap);
    va_end(ap);
    CHECK(n > 0 && (size_t)n < sizeof cmd - 200, "command too long");
    char full[8192 + 256];
    snprintf(full, sizeof full, "( %s ) > '%s/log' 2>&1", cmd, tmp);
    int rc = system(full);
    rc = WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
    snprintf(full, sizeof full, "%s/log", tmp);
    char *text = test_read_file(full, NULL);
    size_t len = text ? strlen(text) : 0;
    snprintf(log_tail, sizeof log_tail, "%s", text ? text + (len > 900 ? len - 900 : 0) : "");
    free(text);
    return rc;
}

/* `make TARGET VARS` on this build, in the source tree, as a fresh make (not a child of the one running the
 * tests, whose jobserver it must not inherit). */
#define MAKE_FMT "env -u MAKEFLAGS -u MFLAGS -u MAKELEVEL make -s -C '%s' BUILD='%s' "
#define MAKE_ARGS test_source_dir(), install_build()
static const char *install_build(void) {
    const char *b = getenv("IACSG_INSTALL_BUILD");
    return b && *b ? b : IACSG_INSTALL_BUILD_DEFAULT;
}

static int exists(const char *dir, const char *name) {
    char path[1200];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    return access(path, F_OK) == 0;
}

/* The names in a directory, other than . and ..; -1 if it cannot be read. */
static int entries(const char *dir) {
    DIR *d = opendir(dir);
    if (!d)
        return -1;
    int n = 0;
    for (struct dirent *e; (e = readdir(d));)
        n += strcmp(e->d_name, ".") != 0 && strcmp(e->d_name, "..") != 0;
    closedir(d);
    return n;
}

/* Under the prefix after make install: each kind of file the Makefile's install block puts there. */
static const char *const installed[] = {
    "bin/iacsg",
    "lib/libiacsg.so",
    "lib/libiacsg.so.0",
    "lib/libiacsg.a",
    "lib/iacsg/libiacsg_image.so",
    "lib/pkgconfig/iacsg.pc",
    "include/iacsg/iacsg.h",
    "share/man/man1/iacsg.1",
    "share/man/man7/iacsg-language.7",
    "share/doc/iacsg/examples/embed.c",
    "share/doc/iacsg/examples/" SCENE,
};

static void check_installed(const char *prefix) {
    for (size_t k = 0; k < sizeof installed / sizeof *installed; k++)
        CHECK(exists(prefix, installed[k]), "%s/%s is not installed", prefix, installed[k]);
}
static void check_empty(const char *prefix) {
    int left = entries(prefix);
    CHECK(left == 0, "%d entries left in %s after make uninstall", left, prefix);
}

static void install_into(const char *tmp, const char *prefix) {
    CHECK(shell(tmp, MAKE_FMT "PREFIX='%s' install", MAKE_ARGS, prefix) == 0, "make install: %s", log_tail);
    check_installed(prefix);
}
static void uninstall_from(const char *tmp, const char *prefix) {
    CHECK(shell(tmp, MAKE_FMT "PREFIX='%s' uninstall", MAKE_ARGS, prefix) == 0, "make uninstall: %s", log_tail);
    check_empty(prefix);
}

/* Builds the installed examples/embed.c against `prefix` with pkg-config (LINK is `shared` or `static`) into
 * tmp/embed, runs it on the installed scene, and checks its image against the installed command's rendering of
 * the same scene (the same default view): pixel for pixel, and not a blank image. */
static void check_embed(const char *tmp, const char *prefix, const char *link) {
    int shared = strcmp(link, "shared") == 0;
    /* With both libraries installed, -liacsg picks the shared one: a static link asks for the archive. */
    const char *libs = shared ? "$(pkg-config --libs iacsg)"
                              : "$(pkg-config --static --libs iacsg"
                                " | sed 's/-liacsg/-Wl,-Bstatic -liacsg -Wl,-Bdynamic/')";
    CHECK(shell(tmp, "export PKG_CONFIG_PATH='%s/lib/pkgconfig'; cc -std=c11 -Wall -Wextra -pedantic -Werror"
                     " -o '%s/embed' '%s/share/doc/iacsg/examples/embed.c' $(pkg-config --cflags iacsg) %s",
                prefix, tmp, prefix, libs) == 0,
          "building embed.c (%s): %s", link, log_tail);
    int needs_shared = shell(tmp, "readelf -d '%s/embed' | grep -q 'NEEDED.*libiacsg.so.0'", tmp) == 0;
    CHECK(needs_shared == shared, "embed (%s) %s libiacsg.so.0", link, shared ? "does not need" : "needs");
    CHECK(shell(tmp, "cd '%s' && LD_LIBRARY_PATH='%s/lib' ./embed embed.png 40 1 '%s/share/doc/iacsg/examples/%s'",
                tmp, prefix, prefix, SCENE) == 0,
          "embed (%s): %s", link, log_tail);
    CHECK(shell(tmp, "cd '%s' && '%s/bin/iacsg' '%s/share/doc/iacsg/examples/%s' -size 40x40 -o cli.png", tmp,
                prefix, prefix, SCENE) == 0,
          "the installed iacsg: %s", log_tail);

    float *pixels[2] = {NULL, NULL};
    const char *names[2] = {"embed.png", "cli.png"};
    int w[2], h[2], ch[2];
    iacsg_error err = {0};
    for (int k = 0; k < 2; k++) {
        char path[1200];
        snprintf(path, sizeof path, "%s/%s", tmp, names[k]);
        CHECK(iacsg_image_read(path, &w[k], &h[k], &ch[k], &pixels[k], &err) == IACSG_OK, "%s", err.message);
        CHECK(w[k] == 40 && h[k] == 40 && ch[k] == 3, "%s is %dx%dx%d", names[k], w[k], h[k], ch[k]);
    }
    long differ = 0, unlike_corner = 0;
    for (long k = 0; k < 40 * 40 * 3; k++) {
        differ += pixels[0][k] != pixels[1][k];
        unlike_corner += pixels[0][k] != pixels[0][k % 3];
    }
    free(pixels[0]);
    free(pixels[1]);
    CHECK(differ == 0, "%ld channel values differ between embed (%s) and the installed command", differ, link);
    CHECK(unlike_corner > 40 * 3, "embed's image is nearly uniform: %ld values unlike its corner", unlike_corner);
}

/* 1 if a function that the headers in include_dir declare (an iacsg_ name followed by '(', outside comments)
 * is not a line of `exports` (newline-framed names), and its name in `name`; 0 if every one is there. `count`
 * receives how many declarations were checked. */
static int first_unexported(const char *include_dir, const char *exports, char *name, size_t size, int *count) {
    DIR *d = opendir(include_dir);
    CHECK(d, "cannot read %s", include_dir);
    int missing = 0;
    *count = 0;
    for (struct dirent *e; !missing && (e = readdir(d));) {
        char path[1200];
        snprintf(path, sizeof path, "%s/%s", include_dir, e->d_name);
        char *text = e->d_name[0] == '.' ? NULL : test_read_file(path, NULL);
        for (char *c = text ? strstr(text, "/*") : NULL; c; c = strstr(c, "/*")) {
            char *close = strstr(c + 2, "*/");
            memset(c, ' ', close ? (size_t)(close + 2 - c) : strlen(c));
        }
        for (char *p = text; p && !missing && (p = strstr(p, "iacsg_"));) {
            size_t len = strspn(p, "abcdefghijklmnopqrstuvwxyz0123456789_");
            int declared = (p == text || !strchr("abcdefghijklmnopqrstuvwxyz0123456789_", p[-1] | 0x20)) &&
                           p[len + strspn(p + len, " ")] == '(';
            if (declared) {
                char framed[160];
                snprintf(framed, sizeof framed, "\n%.*s\n", (int)len, p);
                missing = strstr(exports, framed) == NULL;
                snprintf(name, size, "%.*s", (int)len, p);
                ++*count;
            }
            p += len;
        }
        free(text);
    }
    closedir(d);
    return missing;
}

/* Install, build embed.c against the shared library with pkg-config, run it, check its image and what the
 * library exports (every function the installed headers declare, and nothing but iacsg_ names), uninstall:
 * the prefix is empty again. */
TEST(install_shared_library) {
    char tmp[64], prefix[128], path[200];
    make_tmp(tmp, sizeof tmp);
    snprintf(prefix, sizeof prefix, "%s/prefix", tmp);
    install_into(tmp, prefix);
    CHECK(shell(tmp, "readelf -d '%s/lib/libiacsg.so' | grep -q 'Library soname: \\[libiacsg.so.0\\]'", prefix) == 0,
          "libiacsg.so has no SONAME libiacsg.so.0");
    CHECK(shell(tmp, "(echo; nm -D --defined-only '%s/lib/libiacsg.so' | awk '{ print $3 }') > '%s/exports'", prefix,
                tmp) == 0,
          "nm: %s", log_tail);
    snprintf(path, sizeof path, "%s/exports", tmp);
    char *exports = test_read_file(path, NULL);
    CHECK(exports, "no exports list");
    int count = 0, declared = 0, public = 1;
    char name[128] = "";
    for (const char *line = exports + 1; *line; line += strcspn(line, "\n") + 1, count++)
        if (public && strncmp(line, "iacsg_", 6) != 0) {
            public = 0;
            snprintf(name, sizeof name, "%.*s", (int)strcspn(line, "\n"), line);
        }
    CHECK(public, "libiacsg.so exports %s, not an iacsg_ name", name);
    snprintf(path, sizeof path, "%s/include/iacsg", prefix);
    int missing = first_unexported(path, exports, name, sizeof name, &declared);
    free(exports);
    CHECK(!missing, "%s, declared in the installed headers, is not exported", name);
    CHECK(declared > 0 && count > 0, "no declarations (%d) or no exports (%d)", declared, count);
    test_note("libiacsg.so exports %d symbols, all iacsg_; the headers' %d declarations are among them", count,
              declared);
    check_embed(tmp, prefix, "shared");
    uninstall_from(tmp, prefix);
    remove_tmp(tmp);
}

/* The same program linked with the static library (pkg-config --static). */
TEST(install_static_library) {
    char tmp[64], prefix[128];
    make_tmp(tmp, sizeof tmp);
    snprintf(prefix, sizeof prefix, "%s/prefix", tmp);
    install_into(tmp, prefix);
    check_embed(tmp, prefix, "static");
    uninstall_from(tmp, prefix);
    remove_tmp(tmp);
}

/* DESTDIR stages the files for PREFIX elsewhere; the staged command runs there, far from the build tree and
 * from PREFIX (it finds its image library relative to itself). */
TEST(install_destdir) {
    char tmp[64], stage[128], prefix[200];
    make_tmp(tmp, sizeof tmp);
    snprintf(stage, sizeof stage, "%s/stage", tmp);
    snprintf(prefix, sizeof prefix, "%s/opt/iacsg", stage);
    CHECK(shell(tmp, MAKE_FMT "DESTDIR='%s' PREFIX=/opt/iacsg install", MAKE_ARGS, stage) == 0, "make install: %s",
          log_tail);
    check_installed(prefix);
    CHECK(shell(tmp, "grep -qx 'prefix=/opt/iacsg' '%s/lib/pkgconfig/iacsg.pc'", prefix) == 0,
          "iacsg.pc does not say prefix=/opt/iacsg");
    CHECK(shell(tmp, "cd '%s' && '%s/bin/iacsg' sphere -size 16x16 -o staged.png", tmp, prefix) == 0,
          "the staged iacsg: %s", log_tail);
    CHECK(exists(tmp, "staged.png"), "the staged iacsg wrote no image");
    CHECK(shell(tmp, MAKE_FMT "DESTDIR='%s' PREFIX=/opt/iacsg uninstall", MAKE_ARGS, stage) == 0, "make uninstall: %s",
          log_tail);
    check_empty(prefix);
    remove_tmp(tmp);
}

/* A prefix its user cannot write to is refused before anything is done, in one line. As root, the install is
 * run as the user nobody (setpriv) from a copy of the Makefile it can read. */
TEST(install_unwritable_prefix) {
    char tmp[64], path[200];
    make_tmp(tmp, sizeof tmp);
    CHECK(shell(tmp, "chmod 755 '%s' && mkdir '%s/locked' && chmod 555 '%s/locked' && cp '%s/Makefile' '%s/'", tmp,
                tmp, tmp, test_source_dir(), tmp) == 0,
          "setup: %s", log_tail);
    const char *as_user = geteuid() == 0 ? "setpriv --reuid=65534 --regid=65534 --clear-groups" : "";
    int rc = shell(tmp, "%s env -u MAKEFLAGS -u MFLAGS -u MAKELEVEL make -s -C '%s' PREFIX='%s/locked/prefix' install",
                   as_user, tmp, tmp);
    snprintf(path, sizeof path, "%s/log", tmp);
    char *out = test_read_file(path, NULL);
    CHECK(out, "no output");
    int lines = 0;
    for (const char *p = out; *p; p++)
        lines += *p == '\n';
    int says = strstr(out, "no write access to") != NULL && strstr(out, "/locked") != NULL;
    free(out);
    CHECK(rc != 0, "make install into an unwritable prefix succeeded");
    CHECK(lines == 1 && says, "expected one line naming the prefix: %s", log_tail);
    CHECK(!exists(tmp, "locked/prefix"), "the prefix was created");
    remove_tmp(tmp);
}

/* The next word of a text (separated by white space), without a trailing ':' (the page's headings drop it). */
static int next_word(const char **p, char *word, size_t size) {
    while (**p == ' ' || **p == '\n' || **p == '\t')
        (*p)++;
    size_t n = 0;
    while (**p && **p != ' ' && **p != '\n' && **p != '\t' && n + 1 < size)
        word[n++] = *(*p)++;
    if (n > 1 && word[n - 1] == ':')
        n--;
    word[n] = '\0';
    return n > 0;
}

/* iacsg(1) is made from `iacsg --help`: check that the page as man shows it carries every word of the help in
 * the same order (the page adds headings and sections, never drops a word), and that groff formats both pages
 * without a warning. */
TEST(install_man_page_carries_help) {
    char tmp[64], path[200];
    make_tmp(tmp, sizeof tmp);
    CHECK(shell(tmp, "cd '%s' && '%s/iacsg' --help > '%s/help.txt'", test_source_dir(), install_build(), tmp) == 0,
          "iacsg --help: %s", log_tail);
    const char *pages[] = {"man1/iacsg.1", "man7/iacsg-language.7"};
    for (int k = 0; k < 2; k++) {
        CHECK(shell(tmp, "cd '%s' && groff -k -man -Tascii -rcR=1 -P-cbou -ww '%s/man/%s' > '%s/page%d.txt' && "
                         "test ! -s '%s/log'",
                    test_source_dir(), install_build(), strchr(pages[k], '/') + 1, tmp, k, tmp) == 0,
              "groff on %s: %s", pages[k], log_tail);
    }
    snprintf(path, sizeof path, "%s/help.txt", tmp);
    char *help = test_read_file(path, NULL);
    snprintf(path, sizeof path, "%s/page0.txt", tmp);
    char *page = test_read_file(path, NULL);
    CHECK(help && page, "no help or page text");
    const char *h = help, *p = page;
    char hw[256], pw[256];
    int words = 0, found = 1;
    next_word(&h, hw, sizeof hw); /* "usage:", which the SYNOPSIS heading replaces */
    while (found && next_word(&h, hw, sizeof hw)) {
        found = 0;
        while (!found && next_word(&p, pw, sizeof pw))
            found = strcmp(hw, pw) == 0;
        words += found;
    }
    free(help);
    free(page);
    CHECK(found, "word %d of the help, '%s', is missing from the man page (or out of order)", words + 1, hw);
    test_note("the man page carries the help's %d words in order", words);
    remove_tmp(tmp);
}

/* The version macros say one version, and the library reports the one its headers say. */
TEST(install_version_macros_agree) {
    char joined[64];
    snprintf(joined, sizeof joined, "%d.%d.%d", IACSG_VERSION_MAJOR, IACSG_VERSION_MINOR, IACSG_VERSION_PATCH);
    CHECK(strcmp(joined, IACSG_VERSION) == 0, "IACSG_VERSION is %s, the parts say %s", IACSG_VERSION, joined);
    CHECK(strcmp(iacsg_version(), IACSG_VERSION) == 0, "iacsg_version() is %s, IACSG_VERSION %s", iacsg_version(),
          IACSG_VERSION);
}
