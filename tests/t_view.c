/* tests/t_view.c -- `iacsg view` in a real window: an X server of the test's own (Xvfb, on a display number it
 * picks), input through xdotool, screenshots through the viewer's `s` key. The viewer's image of a dragged,
 * zoomed view must be the render command's image of the command line `p` printed; an edit of the scene file
 * must reach the window; a syntax error must leave the viewer running, reporting it, on the last good scene,
 * until the file is mended.
 * Every wait is bounded, and the viewer and the X server are killed whatever happens. */
#define _DEFAULT_SOURCE /* setenv, unsetenv */
#include "iacsg.h"
#include "image.h"
#include "test.h"
#include <fcntl.h>
#include <math.h>
#include <poll.h>
#include <signal.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#define VIEW_SIZE "160x120"

typedef struct {
    char dir[256];
    pid_t xvfb, viewer;
    int display;
    char window[32];
    char failure[1024];
} session;

static double now_seconds(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static void nap(void) {
    struct timespec ts = {0, 50000000};
    nanosleep(&ts, NULL);
}

/* Records the first failure of the session (formatted); returns -1 for `return fail(...)`. */
#if defined(__GNUC__)
__attribute__((format(printf, 2, 3)))
#endif
static int fail(session *s, const char *fmt, ...) {
    if (!s->failure[0]) {
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(s->failure, sizeof s->failure, fmt, ap);
        va_end(ap);
    }
    return -1;
}

static int on_path(const char *program) {
    char cmd[256];
    snprintf(cmd, sizeof cmd, "command -v %s >/dev/null 2>&1", program);
    return system(cmd) == 0;
}

/* Starts Xvfb on a free display (it writes the number it chose to the pipe given by -displayfd). */
static int start_xvfb(session *s) {
    int fds[2];
    if (pipe(fds) != 0)
        return fail(s, "pipe failed");
    s->xvfb = fork();
    if (s->xvfb == 0) {
        close(fds[0]);
        int null = open("/dev/null", O_RDWR);
        dup2(null, 0);
        dup2(null, 1);
        dup2(null, 2);
        char fd_text[16];
        snprintf(fd_text, sizeof fd_text, "%d", fds[1]);
        execlp("Xvfb", "Xvfb", "-displayfd", fd_text, "-screen", "0", "640x480x24", "-nolisten", "tcp", (char *)NULL);
        _exit(127);
    }
    close(fds[1]);
    char text[32] = "";
    size_t len = 0;
    struct pollfd p = {.fd = fds[0], .events = POLLIN};
    double deadline = now_seconds() + 15;
    while (!strchr(text, '\n') && len + 1 < sizeof text && now_seconds() < deadline &&
           poll(&p, 1, 200) >= 0) {
        if (!(p.revents & (POLLIN | POLLHUP)))
            continue;
        ssize_t n = read(fds[0], text + len, sizeof text - 1 - len);
        if (n <= 0)
            break;
        len += (size_t)n;
        text[len] = '\0';
    }
    close(fds[0]);
    if (s->xvfb < 0 || !strchr(text, '\n'))
        return fail(s, "Xvfb did not start within 15 s");
    s->display = atoi(text);
    return 0;
}

static int start_viewer(session *s, const char *scene) {
    s->viewer = fork();
    if (s->viewer == 0) {
        char display[32];
        snprintf(display, sizeof display, ":%d", s->display);
        setenv("DISPLAY", display, 1);
        unsetenv("WAYLAND_DISPLAY");
        if (chdir(s->dir) != 0)
            _exit(126);
        int out = open("out.txt", O_WRONLY | O_CREAT | O_TRUNC, 0644);
        int err = open("err.txt", O_WRONLY | O_CREAT | O_TRUNC, 0644);
        int null = open("/dev/null", O_RDWR);
        if (out < 0 || err < 0 || null < 0)
            _exit(126);
        dup2(null, 0);
        dup2(out, 1);
        dup2(err, 2);
        execl(test_binary_path(), test_binary_path(), "view", scene, "-size", VIEW_SIZE, "-o", "shot.png",
              (char *)NULL);
        _exit(127);
    }
    return s->viewer > 0 ? 0 : fail(s, "fork failed");
}

/* Kills what is still running (the viewer, then the X server) and reaps them. */
static void stop_all(session *s) {
    pid_t *pids[2] = {&s->viewer, &s->xvfb};
    for (int k = 0; k < 2; k++)
        if (*pids[k] > 0) {
            kill(*pids[k], SIGKILL);
            waitpid(*pids[k], NULL, 0);
            *pids[k] = 0;
        }
}

/* xdotool with `args` on the session's display (at most 10 s); its first line of output into out, if given. */
static int xdo(session *s, const char *args, char *out, size_t size) {
    char cmd[1024];
    snprintf(cmd, sizeof cmd, "DISPLAY=:%d timeout 10 xdotool %s 2>/dev/null", s->display, args);
    FILE *p = popen(cmd, "r");
    if (!p)
        return -1;
    char line[512] = "";
    if (!fgets(line, sizeof line, p))
        line[0] = '\0';
    while (fgetc(p) != EOF) /* the rest, so that xdotool never blocks on a full pipe */
        ;
    int rc = pclose(p);
    line[strcspn(line, "\n")] = '\0';
    if (out)
        snprintf(out, size, "%s", line);
    return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
}

/* Sends `actions` to the viewer's window (xdotool commands chained; %W stands for the window). */
static int send(session *s, const char *actions) {
    char args[1024];
    size_t n = 0;
    for (const char *p = actions; *p && n + 40 < sizeof args; p++) {
        if (p[0] == '%' && p[1] == 'W') {
            n += (size_t)snprintf(args + n, sizeof args - n, "%s", s->window);
            p++;
        } else {
            args[n++] = *p;
        }
    }
    args[n] = '\0';
    return xdo(s, args, NULL, 0) == 0 ? 0 : fail(s, "xdotool %s failed", args);
}

/* The file's text in the session's directory ("" when it cannot be read), into a static buffer. */
static const char *session_text(const session *s, const char *name) {
    static char text[65536];
    char path[512];
    snprintf(path, sizeof path, "%s/%s", s->dir, name);
    FILE *f = fopen(path, "r");
    size_t n = f ? fread(text, 1, sizeof text - 1, f) : 0;
    text[n] = '\0';
    if (f)
        fclose(f);
    return text;
}

static int count_text(const char *text, const char *needle) {
    int n = 0;
    for (const char *p = strstr(text, needle); p; p = strstr(p + 1, needle))
        n++;
    return n;
}

/* Waits up to `seconds` for the count-th `needle` in the session's file; 0 when it came. Gives up when the
 * viewer died. */
static int wait_for_nth(session *s, const char *name, const char *needle, int count, double seconds) {
    double deadline = now_seconds() + seconds;
    for (;;) {
        if (count_text(session_text(s, name), needle) >= count)
            return 0;
        int status;
        if (s->viewer > 0 && waitpid(s->viewer, &status, WNOHANG) == s->viewer) {
            s->viewer = 0;
            return fail(s, "the viewer exited (status %d) waiting for '%s' in %s; stderr: %s", status, needle, name,
                        session_text(s, "err.txt"));
        }
        if (now_seconds() > deadline)
            return fail(s, "no '%s' in %s within %.0f s; stderr: %s", needle, name, seconds,
                        session_text(s, "err.txt"));
        nap();
    }
}

static int wait_for_text(session *s, const char *name, const char *needle, double seconds) {
    return wait_for_nth(s, name, needle, 1, seconds);
}

/* Waits up to 10 s until the window's title has `needle` (or, with absent, has it not); 0 when so. */
static int wait_for_title(session *s, const char *needle, int absent) {
    char cmd[64], title[512] = "";
    snprintf(cmd, sizeof cmd, "getwindowname %s", s->window);
    double deadline = now_seconds() + 10;
    do {
        xdo(s, cmd, title, sizeof title);
        if ((strstr(title, needle) == NULL) == absent)
            return 0;
        nap();
    } while (now_seconds() < deadline);
    return fail(s, "the window's title %s '%s' after 10 s: '%s'", absent ? "still has" : "has no", needle, title);
}

/* Replaces the scene file at once (a rename), as editors save. */
static int write_scene(session *s, const char *text) {
    char tmp[512], path[512];
    snprintf(tmp, sizeof tmp, "%s/scene.tmp", s->dir);
    snprintf(path, sizeof path, "%s/scene.csg", s->dir);
    FILE *f = fopen(tmp, "w");
    if (!f || fputs(text, f) < 0 || fclose(f) != 0 || rename(tmp, path) != 0)
        return fail(s, "cannot write %s", path);
    return 0;
}

/* Pixels of the session's PNG (3 channels); NULL after recording why. */
static float *read_image(session *s, const char *name, int *w, int *h) {
    char path[512];
    snprintf(path, sizeof path, "%s/%s", s->dir, name);
    int channels;
    float *pixels = NULL;
    iacsg_error err = {0};
    if (iacsg_image_read(path, w, h, &channels, &pixels, &err) != IACSG_OK) {
        fail(s, "%s", err.message);
        return NULL;
    }
    if (channels != 3) {
        free(pixels);
        fail(s, "%s has %d channels", name, channels);
        return NULL;
    }
    return pixels;
}

/* The fraction of pixels of two same-sized PNGs that differ by more than `tolerance` in some channel; -1 (after
 * recording why) when they cannot be compared. */
static double differing_fraction(session *s, const char *a, const char *b, float tolerance) {
    int wa, ha, wb, hb;
    float *pa = read_image(s, a, &wa, &ha), *pb = pa ? read_image(s, b, &wb, &hb) : NULL;
    double fraction = -1;
    if (pa && pb && (wa != wb || ha != hb))
        fail(s, "%s is %dx%d, %s %dx%d", a, wa, ha, b, wb, hb);
    else if (pa && pb) {
        long differing = 0, n = (long)wa * ha;
        for (long p = 0; p < n; p++)
            differing += fabsf(pa[3 * p] - pb[3 * p]) > tolerance || fabsf(pa[3 * p + 1] - pb[3 * p + 1]) > tolerance ||
                         fabsf(pa[3 * p + 2] - pb[3 * p + 2]) > tolerance;
        fraction = (double)differing / (double)n;
    }
    free(pa);
    free(pb);
    return fraction;
}

/* Runs the render command in the session's directory with `args` (shell words); 0 when it succeeded. */
static int render_cli(session *s, const char *args, const char *output) {
    char cmd[4096];
    snprintf(cmd, sizeof cmd, "cd '%s' && timeout 120 '%s' %s -o %s >/dev/null 2>cli_err.txt", s->dir,
             test_binary_path(), args, output);
    int rc = system(cmd);
    if (!WIFEXITED(rc) || WEXITSTATUS(rc) != 0)
        return fail(s, "iacsg %s -o %s failed: %s", args, output, session_text(s, "cli_err.txt"));
    return 0;
}

/* The line of the viewer's stdout that `p` printed, less its leading "iacsg ". */
static int printed_command(session *s, char *out, size_t size) {
    const char *text = session_text(s, "out.txt"), *line = strstr(text, "\niacsg ");
    if (!line)
        return fail(s, "no command line in the viewer's output: %s", text);
    line += strlen("\niacsg ");
    snprintf(out, size, "%.*s", (int)strcspn(line, "\n"), line);
    return 0;
}

/* with a light of its own, which the window shows as the render command does */
static const char first_scene[] = "light sun = dir(1, -2, 1) intensity 0.9\ncube = pseudocube\nball = sphere(1.3)\n"
                                  "cube | ball\n";
static const char second_scene[] = "ring = torus(R = 1, r = 0.4)\nring | sphere(0.5)\n";
static const char broken_scene[] = "ring = torus(R = 1, r = 0.4\nring\n";

/* The session proper; returns 0, or -1 with s->failure set. */
static int view_session(session *s) {
    if (write_scene(s, first_scene) || start_xvfb(s) || start_viewer(s, "scene.csg"))
        return -1;
    /* the window waits on the first scene's programs: built cold under the sanitizers (.ci/run), the whole session
     * took 23 s on the quiet machine, and a CI run (2026-11-28 13:20 UTC) passed 30 s before a window showed */
    double deadline = now_seconds() + 120;
    while (!s->window[0]) {
        if (now_seconds() > deadline)
            return fail(s, "no viewer window within 120 s; stderr: %s", session_text(s, "err.txt"));
        xdo(s, "search --onlyvisible --name '^iacsg view'", s->window, sizeof s->window);
        nap();
    }
    /* A drag to orbit, a wheel step to zoom, eps doubled: then the command line and a screenshot. */
    if (send(s, "mousemove --window %W 40 60 mousedown 1 mousemove --window %W 60 64 mousemove --window %W 80 "
                "68 mousemove --window %W 100 72 mouseup 1 click 4 key bracketright key p key s") ||
        wait_for_text(s, "out.txt", "wrote shot_0000.png", 60))
        return -1;
    char args[2048];
    if (printed_command(s, args, sizeof args))
        return -1;
    if (!strstr(args, "-size " VIEW_SIZE) || !strstr(args, "-eps 3.0517578125e-05"))
        return fail(s, "the printed command line has not the window's size and the doubled eps: %s", args);
    if (render_cli(s, args, "cli.png") || render_cli(s, "scene.csg -size " VIEW_SIZE, "default.png"))
        return -1;
    double off = differing_fraction(s, "shot_0000.png", "cli.png", 2.0f / 255);
    if (off < 0 || off > 0.001)
        return off < 0 ? -1 : fail(s, "%.2f%% of the pixels of the screenshot and the command's render of its "
                                      "command line differ", 100 * off);
    double moved = differing_fraction(s, "shot_0000.png", "default.png", 2.0f / 255);
    if (moved < 0 || moved < 0.05)
        return moved < 0 ? -1 : fail(s, "the drag and zoom changed only %.2f%% of the pixels", 100 * moved);
    test_note("screenshot vs the printed command's render: %.3f%% of pixels differ; the drag changed %.1f%%",
              100 * off, 100 * moved);

    /* An edit of the scene: reloaded, and the next screenshot shows it. */
    if (write_scene(s, second_scene) || wait_for_text(s, "out.txt", "reloaded scene.csg", 60) ||
        send(s, "key s") || wait_for_text(s, "out.txt", "wrote shot_0001.png", 30))
        return -1;
    double edited = differing_fraction(s, "shot_0000.png", "shot_0001.png", 2.0f / 255);
    if (edited < 0 || edited < 0.05)
        return edited < 0 ? -1 : fail(s, "the edited scene changed only %.2f%% of the pixels", 100 * edited);

    /* A syntax error: on stderr and in the title, the viewer alive, the last good scene on screen. */
    if (write_scene(s, broken_scene) || wait_for_text(s, "err.txt", "iacsg: scene.csg:", 30))
        return -1;
    if (wait_for_title(s, "ERROR scene.csg:", 0) || send(s, "key s") ||
        wait_for_text(s, "out.txt", "wrote shot_0002.png", 30))
        return -1;
    double kept = differing_fraction(s, "shot_0001.png", "shot_0002.png", 0);
    if (kept != 0)
        return kept < 0 ? -1 : fail(s, "after the syntax error the window changed (%.2f%% of pixels)", 100 * kept);

    /* The error mended: reloaded again, the title clear. */
    if (write_scene(s, first_scene) || wait_for_nth(s, "out.txt", "reloaded scene.csg", 2, 60) ||
        wait_for_title(s, "ERROR", 1))
        return -1;

    /* q quits, with status 0. */
    if (send(s, "key q"))
        return -1;
    deadline = now_seconds() + 15;
    int status = 0;
    while (waitpid(s->viewer, &status, WNOHANG) != s->viewer) {
        if (now_seconds() > deadline)
            return fail(s, "the viewer did not quit within 15 s of q");
        nap();
    }
    s->viewer = 0;
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
        return fail(s, "the viewer quit with status %d; stderr: %s", status, session_text(s, "err.txt"));
    return 0;
}

TEST(view_window) {
    CHECK(on_path("Xvfb") && on_path("xdotool"),
          "the viewer's test needs Xvfb and xdotool (make deps installs them)");
    session s = {.xvfb = 0};
    snprintf(s.dir, sizeof s.dir, "/tmp/iacsg-view-%ld", (long)getpid());
    CHECK(mkdir(s.dir, 0700) == 0, "cannot create %s", s.dir);
    double start = now_seconds();
    view_session(&s);
    stop_all(&s);
    char cmd[512];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", s.dir);
    int cleaned = system(cmd) == 0;
    CHECK(!s.failure[0], "%s", s.failure);
    CHECK(cleaned, "cannot remove %s", s.dir);
    test_note("the window session took %.1f s", now_seconds() - start);
}

/* Without a display: one line that says so, exit status 1. */
TEST(view_no_display) {
    char cmd[1024], text[1024];
    snprintf(cmd, sizeof cmd, "env -u DISPLAY -u WAYLAND_DISPLAY timeout 60 '%s' view sphere 2>&1 >/dev/null; echo $?",
             test_binary_path());
    FILE *p = popen(cmd, "r");
    CHECK(p, "popen failed");
    size_t n = fread(text, 1, sizeof text - 1, p);
    text[n] = '\0';
    pclose(p);
    const char *last = strrchr(text, '\n');
    CHECK(last && last > text, "no output: %s", text);
    const char *first_newline = strchr(text, '\n');
    CHECK(strstr(text, "iacsg: no display") == text, "the message is not about the display: %s", text);
    CHECK(strcmp(first_newline + 1, "1\n") == 0, "not one line and exit status 1: %s", text);
}
