/* src/cli_render.c -- `iacsg EXPR|SCENE [options]`: render to image files; and `iacsg devices`. The options
 * are documented in cli_main.c's usage text and the README. */
#include "cli.h"
#include "cli_brlcad.h"
#include "cli_job.h"
#include "cli_effects.h"
#include "cli_render.h"
#include "cli_writer.h"
#include "clrt_cache.h"
#include "clrt.h"
#include "iacsg.h"
#include "implicits/brlcad.h"
#include "implicits/scene.h"
#include "ia/decimal.h"
#include <errno.h>
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

static double now_seconds(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

int cli_parse_numbers(const char *text, double *out, int count) {
    const char *p = text;
    for (int k = 0; k < count; k++) {
        char *end;
        errno = 0;
        out[k] = strtod(p, &end);
        if (end == p || errno == ERANGE || !isfinite(out[k]))
            return 0;
        if (k + 1 < count && *end != ',')
            return 0;
        p = end + (k + 1 < count);
    }
    return *p == '\0';
}

static int parse_size(const char *text, int *width, int *height) {
    char *end;
    long w = strtol(text, &end, 10);
    if (end == text || (*end != 'x' && *end != 'X'))
        return 0;
    const char *h_text = end + 1;
    long h = strtol(h_text, &end, 10);
    if (end == h_text || *end != '\0' || w < 1 || h < 1 || w > 32768 || h > 32768)
        return 0;
    *width = (int)w;
    *height = (int)h;
    return 1;
}

int cli_parse_int(const char *text, long lo, long hi, int *out) {
    char *end;
    errno = 0;
    long n = strtol(text, &end, 10);
    if (end == text || *end || errno == ERANGE || n < lo || n > hi)
        return 0;
    *out = (int)n;
    return 1;
}

void cli_print_bad_value(const char *option, const char *value, const char *expected) {
    fprintf(stderr, "iacsg: %s %s: expected %s\n", option, value, expected);
}

static int bad_value(const char *option, const char *value, const char *expected) {
    cli_print_bad_value(option, value, expected);
    return 2;
}

/* Fills *o from the command line; returns 0, or the exit status after printing the problem. */
int parse_options(int argc, char **argv, render_options *o) {
    memset(o, 0, sizeof *o);
    o->output = "iacsg.png";
    o->view.width = o->view.height = 1024;
    o->view.eps = 0x1p-16;
    o->view.camera.fov = 40;
    o->view.camera.up[2] = 1;
    o->az = 35;
    o->el = 25;
    cli_effects_init(&o->effects);
    int effects = 0;
    for (int k = 1; k < argc; k++) {
        const char *a = argv[k], *v = k + 1 < argc ? argv[k + 1] : NULL;
        double num[6];
        if (a[0] != '-' || a[1] == '\0' || (a[1] >= '0' && a[1] <= '9') || a[1] == '.') {
            if (o->input && cli_brlcad_input(o->input)) { /* the model's objects to render */
                if (o->nobjects == RENDER_OBJECTS_MAX) {
                    fprintf(stderr, "iacsg: more than %d objects named\n", RENDER_OBJECTS_MAX);
                    return 2;
                }
                o->objects[o->nobjects++] = a;
                continue;
            }
            if (o->input) {
                fprintf(stderr, "iacsg: more than one expression: '%s' and '%s' (quote the expression)\n",
                        o->input, a);
                return 2;
            }
            o->input = a;
            continue;
        }
        int fx = cli_effects_option(argc, argv, &k, &o->effects, &effects);
        if (fx < 0)
            return 2;
        if (fx > 0)
            continue;
        if (strcmp(a, "-fp64") == 0) {
            o->config.fp64 = 1;
            continue;
        }
        if (strcmp(a, "-fast") == 0) {
            o->config.fast = 1;
            continue;
        }
        if (strcmp(a, "-stats") == 0) {
            o->config.stats = 1;
            continue;
        }
        if (strcmp(a, "-resume") == 0) {
            o->resume = 1;
            continue;
        }
        if (!v) {
            fprintf(stderr, "iacsg: unknown option or missing value: %s (see iacsg --help)\n", a);
            return 2;
        }
        k++;
        if (strcmp(a, "-o") == 0) {
            o->output = v;
        } else if (strcmp(a, "-depth") == 0) {
            o->depth_file = v;
        } else if (strcmp(a, "-normals") == 0) {
            o->normals_file = v;
        } else if (strcmp(a, "-ids") == 0) {
            o->ids_file = v;
        } else if (strcmp(a, "-size") == 0) {
            if (!parse_size(v, &o->view.width, &o->view.height))
                return bad_value(a, v, "WxH with W and H from 1 to 32768, e.g. 1024x768");
        } else if (strcmp(a, "-eps") == 0) {
            if (!cli_parse_numbers(v, &o->view.eps, 1) || !(o->view.eps > 0))
                return bad_value(a, v, "a positive number");
        } else if (strcmp(a, "-bounds") == 0) {
            if (!cli_parse_numbers(v, o->view.bounds, 6) || !(o->view.bounds[0] < o->view.bounds[3]) ||
                !(o->view.bounds[1] < o->view.bounds[4]) || !(o->view.bounds[2] < o->view.bounds[5]))
                return bad_value(a, v, "X0,Y0,Z0,X1,Y1,Z1 with X0 < X1, Y0 < Y1, Z0 < Z1");
            o->have_bounds = 1;
        } else if (strcmp(a, "-eye") == 0 || strcmp(a, "-at") == 0 || strcmp(a, "-up") == 0) {
            if (!cli_parse_numbers(v, num, 3))
                return bad_value(a, v, "X,Y,Z");
            double *dst = a[1] == 'e' ? o->view.camera.eye : a[1] == 'a' ? o->view.camera.at : o->view.camera.up;
            memcpy(dst, num, 3 * sizeof(double));
            o->have_eye |= a[1] == 'e';
            o->have_at |= a[1] == 'a';
        } else if (strcmp(a, "-fov") == 0) {
            if (!cli_parse_numbers(v, &o->view.camera.fov, 1) || !(o->view.camera.fov > 0 && o->view.camera.fov < 180))
                return bad_value(a, v, "degrees in (0, 180)");
            o->have_fov = 1;
        } else if (strcmp(a, "-az") == 0 || strcmp(a, "-el") == 0) {
            if (!cli_parse_numbers(v, a[1] == 'a' ? &o->az : &o->el, 1))
                return bad_value(a, v, "degrees");
            o->have_azel = 1;
        } else if (strcmp(a, "-ortho") == 0) {
            if (!cli_parse_numbers(v, &o->view.camera.ortho_height, 1) || !(o->view.camera.ortho_height > 0))
                return bad_value(a, v, "a positive height");
        } else if (strcmp(a, "-time") == 0) {
            /* the real the text denotes, enclosed: -time 0.7 is 7/10, not the double nearest to it */
            if (ia_decimal_double(v, &o->view.time[0], &o->view.time[1]) != 0 || !isfinite(o->view.time[0]) ||
                !isfinite(o->view.time[1]))
                return bad_value(a, v, "a number");
            o->have_time = 1;
            o->time_text = v;
        } else if (strcmp(a, "-frames") == 0) {
            if (!cli_parse_int(v, 1, 100000, &o->frames))
                return bad_value(a, v, "a frame count from 1 to 100000");
        } else if (strcmp(a, "-tape") == 0) {
            const char *modes[] = {"auto", "off", "on"}; /* IACSG_TAPE_AUTO, _NEVER, _ALWAYS */
            int m = 0;
            while (m < 3 && strcmp(v, modes[m]) != 0)
                m++;
            if (m == 3)
                return bad_value(a, v, "auto, on or off");
            o->config.tape = m;
        } else if (strcmp(a, "-device") == 0) {
            if (!cli_parse_int(v, 0, 1000, &o->config.device))
                return bad_value(a, v, "a device number (see iacsg devices)");
            o->have_device = 1;
        } else {
            fprintf(stderr, "iacsg: unknown option %s (see iacsg --help)\n", a);
            return 2;
        }
    }
    o->view.effects = effects ? &o->effects : NULL;
    if (!o->input) {
        fprintf(stderr, "iacsg: no expression or scene given (see iacsg --help)\n");
        return 2;
    }
    if (o->have_eye && o->have_azel) {
        fprintf(stderr, "iacsg: -eye and -az/-el both place the eye; give one of them\n");
        return 2;
    }
    if (o->have_time && o->frames) {
        fprintf(stderr, "iacsg: -time and -frames both set the time; give one of them\n");
        return 2;
    }
    return 0;
}

/* Whether a text that names no file was meant as a file name: it ends in ".csg" or ".asc" or starts like a path.
 * (Expressions never do; "x/2" does not start with '/'.) */
static int looks_like_path(const char *input) {
    size_t n = strlen(input);
    return (n > 4 && strcmp(input + n - 4, ".csg") == 0) || cli_brlcad_input(input) || input[0] == '/' ||
           strncmp(input, "./", 2) == 0 || strncmp(input, "../", 3) == 0;
}

/* The text of a scene file when `input` names a file, else the input itself as an expression. The result is
 * malloc'ed; NULL (after a message) when the file cannot be read. */
char *read_input(const char *input, const char **name) {
    FILE *f = fopen(input, "rb");
    if (!f) {
        /* Decided by existence, not by fopen's errno: a long expression fails with ENAMETOOLONG. */
        struct stat st;
        if (stat(input, &st) == 0 || looks_like_path(input)) {
            fprintf(stderr, "iacsg: %s: cannot read the scene file (%s)\n", input, strerror(errno));
            return NULL;
        }
        *name = "<expr>";
        return strdup(input);
    }
    *name = input;
    char *text = NULL;
    size_t len = 0, cap = 0, n;
    char buf[65536];
    while ((n = fread(buf, 1, sizeof buf, f)) > 0) {
        if (len + n + 1 > cap) {
            cap = 2 * (len + n + 1);
            char *grown = realloc(text, cap);
            if (!grown)
                break;
            text = grown;
        }
        memcpy(text + len, buf, n);
        len += n;
    }
    int bad = ferror(f) || n > 0;
    fclose(f);
    if (bad || !text) {
        free(text);
        fprintf(stderr, "iacsg: %s: cannot read the scene file\n", input);
        return NULL;
    }
    text[len] = '\0';
    if (strlen(text) != len) { /* the rest would be lost without a word */
        int line = 1;
        for (const char *p = text; *p; p++)
            line += *p == '\n';
        fprintf(stderr, "iacsg: %s:%d: a NUL byte in the scene file\n", input, line);
        free(text);
        return NULL;
    }
    return text;
}

/* The times the command renders, as one interval: -time's (enclosed), or the hull of the frames' k/N. */
static void rendered_times(const render_options *o, double t[2]) {
    memcpy(t, o->view.time, 2 * sizeof(double));
    if (o->frames) {
        double last[2];
        iacsg_frame_time(o->frames - 1, o->frames, last);
        t[0] = 0;
        t[1] = last[1];
    }
}

/* The bounds (given, found by the compiler for the times rendered, or the default) and a phrase saying which
 * and what was proven (in `phrase`). A scene with items: the union of its solids' proven boxes. */
const char *choose_bounds(render_options *o, const iacsg_scene *s, char *phrase, size_t size) {
    if (o->have_bounds)
        return "given";
    double t[2];
    rendered_times(o, t);
    if (s->nitems > 0 && cli_brlcad_input(o->input) && brlcad_scene_bounds(s, o->view.bounds))
        return "rt's model box: its regions' proven boxes; an unbounded region (a half-space) is drawn inside it only";
    if (s->nitems > 0 && iacsg_scene_bounds(s, t, o->view.bounds))
        return "proven to enclose the solids";
    const iacsg_expr *e = s->nitems > 0 ? NULL : s->expr;
    char when[64] = "";
    if (e && iacsg_expr_uses_time(e) && o->frames)
        snprintf(when, sizeof when, " for t = 0/%d .. %d/%d", o->frames, o->frames - 1, o->frames);
    else if (e && iacsg_expr_uses_time(e))
        snprintf(when, sizeof when, " at t = %.40s", o->have_time ? o->time_text : "0");
    switch (e ? iacsg_expr_bounds(e, t, o->view.bounds) : IACSG_BOUNDS_NONE) {
    case IACSG_BOUNDS_EVERYWHERE:
        snprintf(phrase, size, "proven to enclose the surface%s", when);
        return phrase;
    case IACSG_BOUNDS_IN_CUBE:
        snprintf(phrase, size, "proven: no surface in [-%g,%g]^3 outside this box%s; beyond that cube, unknown",
                 IACSG_BOUNDS_CUBE, IACSG_BOUNDS_CUBE, when);
        return phrase;
    case IACSG_BOUNDS_NONE:
        break;
    }
    static const double fallback[6] = {-2, -2, -2, 2, 2, 2};
    memcpy(o->view.bounds, fallback, sizeof fallback);
    return "the default: no enclosing box could be found";
}

/* choose_bounds on a thread of its own while the renderer is made: the program does not depend on the bounds (they
 * are the launch's parameters), and a surface's proof of its box took up to 70 ms of CPU (the Hijazi seed scenes
 * without -bounds: the tangle | sphere, citrus | heart, the multiple unions), the time a cached program's build and
 * OpenCL's start take on the other CPU. Both only read the scene. */
typedef struct {
    render_options *o;
    const iacsg_scene *scene;
    char phrase[256];
    const char *which;
} bounds_search;

static void *bounds_search_run(void *arg) {
    bounds_search *b = arg;
    b->which = choose_bounds(b->o, b->scene, b->phrase, sizeof b->phrase);
    return NULL;
}

/* -at defaults to the centre of the bounds; without -eye, -az/-el place the eye to see all of the bounds. A
 * BRL-CAD model is seen as rt sees it: orthographic, as high as the bounds' diagonal, unless -ortho or -fov. */
void place_camera(render_options *o) {
    iacsg_camera *c = &o->view.camera;
    if (cli_brlcad_input(o->input) && !(c->ortho_height > 0) && !o->have_fov) {
        double d = 0;
        for (int k = 0; k < 3; k++)
            d += (o->view.bounds[k + 3] - o->view.bounds[k]) * (o->view.bounds[k + 3] - o->view.bounds[k]);
        c->ortho_height = sqrt(d);
    }
    if (!o->have_at)
        for (int k = 0; k < 3; k++)
            c->at[k] = 0.5 * (o->view.bounds[k] + o->view.bounds[k + 3]);
    if (!o->have_eye)
        iacsg_camera_fit_azel(c, o->view.bounds, o->az, o->el);
}

typedef struct {
    double start;
    int shown;
} progress_bar;

/* Draws a bar on stderr once the frame has taken more than a second (installed only when stderr is a tty). */
static void show_progress(double done, void *ctx) {
    progress_bar *bar = ctx;
    if (now_seconds() - bar->start < 1.0)
        return;
    int filled = (int)(done * 40 + 0.5);
    fprintf(stderr, "\r[%.*s%*s] %3.0f%%", filled, "########################################", 40 - filled, "",
            100 * done);
    fflush(stderr);
    bar->shown = 1;
}

static iacsg_status write_frame(cli_writer *writer, const render_options *o, const iacsg_frame *fr, int frame,
                                iacsg_error *err) {
    const char *paths[4] = {o->output, o->depth_file, o->normals_file, o->ids_file};
    const float *data[4] = {fr->rgb, fr->depth, fr->normal, fr->ids};
    const int channels[4] = {3, 1, 3, 1};
    for (int k = 0; k < 4; k++) {
        if (!paths[k])
            continue;
        char *path = cli_job_path(paths[k], o->frames, frame);
        if (!path)
            return iacsg_error_set(err, IACSG_ERR_NOMEM, 0, 0, "out of memory");
        iacsg_status st = k == 0 && fr->rgb8
                              ? cli_writer_write_bytes(writer, path, fr->width, fr->height, 3, fr->rgb8, err)
                              : cli_writer_write(writer, path, fr->width, fr->height, channels[k], data[k], k > 0, err);
        if (st == IACSG_OK)
            printf("wrote %s\n", path);
        free(path);
        if (st != IACSG_OK)
            return st;
    }
    return IACSG_OK;
}

/* read_seconds: the input read and parsed into its scene (a BRL-CAD database: its tree and primitives placed);
 * write_seconds: the frame's images from host memory to their files (conversion, encoding, rename). */
static void print_stats(const iacsg_renderer *r, const iacsg_frame *fr, const iacsg_scene *s, double read_seconds,
                        double write_seconds) {
    printf("device: %s\n", iacsg_renderer_device_name(r));
    printf("rays: %lld\n", fr->rays);
    printf("interval evaluations per ray: mean %.2f, max %u\n", fr->evals_mean, fr->evals_max);
    if (s->nitems > 0) {
        printf("segments per ray: mean %.2f, max %u\n", fr->segments_mean, fr->segments_max);
        printf("partitions per ray: mean %.2f, max %u\n", fr->partitions_mean, fr->partitions_max);
        printf("overlaps: %lld partitions claimed by two regions", fr->overlaps);
        for (int k = 0; k < fr->noverlap_pairs; k++) {
            const char *won = s->items[fr->overlap_pairs[k][0]].name, *lost = s->items[fr->overlap_pairs[k][1]].name;
            printf("%s%s (%d) over %s (%d)", k ? ", " : "; the first: ", won ? won : "?", fr->overlap_pairs[k][0],
                   lost ? lost : "?", fr->overlap_pairs[k][1]);
        }
        printf("\n");
        printf("per-ray buffers: %lld bytes a ray (%lld rays traced again with more room)\n", fr->ray_buffer_bytes,
               fr->retraced_rays);
    }
    if (fr->secondary_rays > 0)
        printf("secondary rays: %lld, interval evaluations per ray: mean %.2f\n", fr->secondary_rays,
               fr->secondary_evals_mean);
    if (s->nitems == 0) /* the first-root path */
        printf("program: %s\n", iacsg_renderer_program(r));
    printf("read: %.3f s\n", read_seconds);
    printf("kernel build: %.3f s\n", iacsg_renderer_build_seconds(r));
    printf("render: %.3f s\n", fr->render_seconds);
    printf("write: %.3f s\n", write_seconds);
}

/* The directory an output goes to must take new files (the image is written beside it, then renamed): checked
 * before rendering, so that a typo in a path does not cost a whole render. */
static iacsg_status check_directory_writable(const char *path, iacsg_error *err) {
    const char *slash = strrchr(path, '/');
    char dir[4096];
    if (!slash)
        snprintf(dir, sizeof dir, ".");
    else
        snprintf(dir, sizeof dir, "%.*s", slash == path ? 1 : (int)(slash - path), path);
    struct stat st;
    const char *why = stat(dir, &st) != 0                  ? strerror(errno)
                      : !S_ISDIR(st.st_mode)               ? "not a directory"
                      : access(dir, W_OK | X_OK) != 0 ? strerror(errno)
                                                           : NULL;
    return why ? iacsg_error_set(err, IACSG_ERR_IO, 0, 0, "%s: cannot write into '%s' (%s)", path, dir, why)
               : IACSG_OK;
}

/* An output that is the scene file itself would destroy it: refuse before rendering. */
static iacsg_status check_outputs_spare_input(const char *input, const char *const outputs[4], iacsg_error *err) {
    struct stat in;
    if (stat(input, &in) != 0)
        return IACSG_OK;
    for (int k = 0; k < 4; k++) {
        struct stat out;
        if (outputs[k] && stat(outputs[k], &out) == 0 && out.st_dev == in.st_dev && out.st_ino == in.st_ino)
            return iacsg_error_set(err, IACSG_ERR_ARG, 0, 0, "%s: the output would overwrite the scene file",
                                   outputs[k]);
    }
    return IACSG_OK;
}

iacsg_status parse_input(const char *text, const char *name, iacsg_scene **out, iacsg_error *err) {
    iacsg_status st = iacsg_scene_parse(text, name, out, err);
    if (st != IACSG_OK || (*out)->nitems == 0 || strcmp(name, "<expr>") != 0)
        return st;
    iacsg_scene_destroy(*out);
    *out = NULL;
    iacsg_expr *e = NULL;
    st = iacsg_expr_parse(text, name, &e, err); /* refuses the region or surface, at its place */
    iacsg_expr_destroy(e);
    return st != IACSG_OK ? st : iacsg_error_set(err, IACSG_ERR_SYNTAX, 1, 1, "regions need a scene file");
}

iacsg_status load_input(const render_options *o, const char *text, const char *name, iacsg_scene **out,
                        iacsg_error *err) {
    if (cli_brlcad_input(o->input) && name == o->input)
        return cli_brlcad_scene(text, o->objects, o->nobjects, out, err);
    return parse_input(text, name, out, err);
}

/* The error's line without "iacsg: ": "NAME:LINE:COL: message", or the message without a place. */
static void format_error(char *line, size_t size, const iacsg_error *err, const char *name) {
    if (err->line > 0)
        snprintf(line, size, "%.4096s:%d:%d: %s", name, err->line, err->column, err->message);
    else
        snprintf(line, size, "%s", err->message);
}

#define ERROR_LINE_SIZE (sizeof(((iacsg_error *)0)->message) + 4200)

void print_error(const iacsg_error *err, const char *name) {
    char line[ERROR_LINE_SIZE];
    format_error(line, sizeof line, err, name);
    fprintf(stderr, "iacsg: %s\n", line);
}

/* The error's line through the job (which prints it, or under mpirun hands it to rank 0). */
static void report_error(cli_job *job, int frame, const iacsg_error *err, const char *name) {
    char line[ERROR_LINE_SIZE];
    format_error(line, sizeof line, err, name);
    cli_job_fail(job, frame, line);
}

int cli_render(int argc, char **argv) {
    render_options o;
    int rc = parse_options(argc, argv, &o);
    if (rc)
        return rc;
    const char *name;
    double read_started = now_seconds(), read_seconds;
    char *text = read_input(o.input, &name);
    read_seconds = now_seconds() - read_started;
    if (!text)
        return 1;
    iacsg_error err = {0};
    iacsg_scene *scene = NULL;
    iacsg_renderer *r = NULL;
    cli_writer *writer = NULL;
    clrt_cache_defer_saves();
    /* first, so that the writer loads while OpenCL starts */
    iacsg_status st = cli_writer_start((size_t)o.view.width * (size_t)o.view.height * 3, &writer, &err);
    const char *outputs[CLI_MPI_IMAGES] = {o.output, o.depth_file, o.normals_file, o.ids_file};
    cli_job *job = cli_job_start(o.frames, o.view.width, o.view.height, o.resume, outputs);
    if (!job) {
        cli_writer_stop(writer);
        free(text);
        return 1;
    }
    clrt_warm_start(); /* after the writer's and the job's forks; while the input is read, parsed and compiled */
    cli_writer_prefault(writer, (size_t)o.view.width * (size_t)o.view.height * 3); /* the colours' bytes */
    if (!o.have_device)
        o.config.device = cli_job_device(job);
    for (int k = 0; k < CLI_MPI_IMAGES && st == IACSG_OK; k++)
        if (outputs[k]) {
            cli_writer_check(writer, outputs[k]);
            st = check_directory_writable(outputs[k], &err);
        }
    if (st == IACSG_OK && name == o.input) /* a scene file */
        st = check_outputs_spare_input(o.input, outputs, &err);
    if (st == IACSG_OK) {
        read_started = now_seconds();
        st = load_input(&o, text, name, &scene, &err);
        read_seconds += now_seconds() - read_started;
    }
    if (st == IACSG_OK) {
        if (cli_effects_from_scene(&o.effects, scene)) /* its lights, materials that reflect or are transparent */
            o.view.effects = &o.effects;
        if (o.view.effects && o.config.tape == IACSG_TAPE_AUTO) /* the effects' kernels call compiled code */
            o.config.tape = IACSG_TAPE_NEVER;
        bounds_search search = {&o, scene, "", NULL};
        pthread_t searching;
        int apart = pthread_create(&searching, NULL, bounds_search_run, &search) == 0;
        /* regions or surfaces: the segment path; else the expression by the first-root path */
        st = iacsg_renderer_create_scene(scene, &o.config, &r, &err);
        if (apart)
            pthread_join(searching, NULL);
        else
            bounds_search_run(&search);
        const double *b = o.view.bounds;
        if (cli_job_rank(job) == 0)
            printf("bounds %g,%g,%g,%g,%g,%g (%s)\n", b[0], b[1], b[2], b[3], b[4], b[5], search.which);
        place_camera(&o);
    }
    o.view.no_depth = !o.depth_file; /* images nobody writes are not computed */
    o.view.no_normals = !o.normals_file;
    o.view.no_ids = !o.ids_file;
    progress_bar bar = {0, 0};
    if (isatty(STDERR_FILENO)) {
        o.view.progress = show_progress;
        o.view.progress_ctx = &bar;
    }
    /* The formats are known before a render that may be long. Rendering while the writer still loads the image
     * library (~0.2 s, cancelling the render on a refusal) saved ~20 ms of the whole command but doubled the
     * render's own time: the writer's loading took one of the two CPUs from it. */
    if (st == IACSG_OK)
        st = cli_writer_checked(writer, &err);
    iacsg_frame fr = {0};
    cli_job_item item = {-1, 0, 0};
    o.view.rgb_bytes = cli_job_alone(job); /* the colours go to 8-bit files only (MPI gathers floats) */
    while (st == IACSG_OK && cli_job_next(job, &fr, &item)) {
        if (o.frames)
            iacsg_frame_time(item.frame, o.frames, o.view.time);
        o.view.row_first = item.row_first;
        o.view.row_count = item.row_count;
        bar.start = now_seconds();
        st = iacsg_render(r, &o.view, &fr, &err);
        if (bar.shown) {
            fprintf(stderr, "\r%50s\r", "");
            bar.shown = 0;
        }
        double written = now_seconds();
        if (st == IACSG_OK && cli_job_writes_frames(job))
            st = write_frame(writer, &o, &fr, item.frame, &err);
        if (st == IACSG_OK && o.config.stats)
            print_stats(r, &fr, scene, read_seconds, now_seconds() - written);
    }
    iacsg_frame_free(&fr);
    const iacsg_frame *whole = st == IACSG_OK ? cli_job_gathered(job) : NULL;
    if (whole)
        st = write_frame(writer, &o, whole, 0, &err);
    if (st != IACSG_OK)
        report_error(job, item.frame, &err, name);
    clrt_warm_join(); /* a command that failed before it needed OpenCL */
    rc = cli_job_end(job);
    cli_writer_stop(writer);
    iacsg_renderer_destroy(r);
    clrt_cache_save_deferred(); /* in a process of its own: the command does not wait */
    iacsg_scene_destroy(scene);
    free(text);
    return rc;
}

static void print_device(int index, const char *platform, const char *device, void *ctx) {
    (void)ctx;
    printf("%d: %s (%s)\n", index, device, platform);
}

int cli_devices(int argc, char **argv) {
    (void)argv;
    if (argc > 1) {
        fprintf(stderr, "iacsg devices: takes no arguments\n");
        return 2;
    }
    iacsg_error err = {0};
    if (clrt_list_devices(print_device, NULL, &err) == 0) {
        fprintf(stderr, "iacsg: %s\n", err.message[0] ? err.message : "no OpenCL device found");
        return 1;
    }
    return 0;
}
