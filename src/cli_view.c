/* src/cli_view.c -- `iacsg view EXPR|SCENE [render options]`: a window on the render (SDL2, loaded at run
 * time: cli_view_sdl.h). Stages:
 *   options (the render command's, cli_render.h) -> a display? -> the scene (cli_view_scene.h) -> window ->
 *   loop: events (mouse moves the camera, cli_view_camera.h; keys) -> frame requests to the render thread
 *   (cli_view_worker.h): a quarter of the resolution while the view moves, full once it has rested
 *   SETTLE_SECONDS -> frames shown (cli_view_display.h) -> the scene file watched and reloaded on change.
 * Prints to stdout: the bounds line, `wrote FILE` for each screenshot, the command line of `p`, and
 * `reloaded NAME` once an edited scene is on screen; errors go to stderr and the window's title. */
#include "cli.h"
#include "cli_job.h"
#include "cli_render.h"
#include "cli_view_camera.h"
#include "cli_view_display.h"
#include "cli_view_scene.h"
#include "cli_view_sdl.h"
#include "cli_view_worker.h"
#include "cli_writer.h"
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#define SETTLE_SECONDS 0.2   /* no input for this long: the view has stopped, render at full resolution */
#define PREVIEW_DIVISOR 4    /* while moving, frames are this many times smaller each way */
#define SUPERSAMPLE 2        /* antialiasing: factor x factor rays a pixel */
#define WATCH_SECONDS 0.1    /* how often the scene file is checked */
#define MAX_SIDE 4096        /* the window's largest size (a screenshot's, the image writer's buffer) */

typedef struct {
    view_sdl sdl;
    SDL_Window *window;
    SDL_Renderer *screen;
    SDL_Texture *texture;
    int texture_w, texture_h;
    render_options o;
    const char *name;
    iacsg_camera home;
    double home_eps;
    view_worker *worker;
    cli_writer *writer;
    view_mode mode;
    int antialias, quit;
    int width, height;        /* the window's, and a full frame's */
    /* requests */
    unsigned wanted;          /* the newest request */
    int wanted_preview;       /* ... is a reduced one */
    int moving;
    double last_input;
    /* what is shown */
    iacsg_frame frame;        /* the latest frame (rgb, depth, normals), freed on the next */
    int frame_factor;         /* its supersampling */
    int frame_final;          /* it is the full frame of the newest request */
    double frame_seconds;
    float *shown;             /* what the window shows, 3 floats a pixel */
    unsigned char *shown_bytes;
    int shown_w, shown_h;
    int screenshot_pending;
    /* the scene */
    unsigned scenes_sent;     /* scenes handed to the worker; frames say which one they show */
    unsigned scene_reported;  /* the last scene whose first frame was reported */
    char error[800];          /* the current problem, shown in the title; "" when none */
    struct stat watched;
    double next_watch;
} viewer;

static double now_seconds(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static void update_title(viewer *v) {
    char title[1200];
    if (v->error[0])
        snprintf(title, sizeof title, "iacsg view: %s | ERROR %s (showing the last good scene)", v->name, v->error);
    else
        snprintf(title, sizeof title, "iacsg view: %s | %dx%d%s | %.1f ms | %.2f evals/ray | eps %g | %s%s",
                 v->name, v->frame.width, v->frame.height, v->frame_final ? "" : " (moving)",
                 1e3 * v->frame_seconds, v->frame.evals_mean, v->o.view.eps, view_mode_names[v->mode],
                 v->antialias ? " | antialiased" : "");
    v->sdl.SetWindowTitle(v->window, title);
}

/* Keeps a problem for the title (shown until the scene next renders). */
static void set_error(viewer *v, const iacsg_error *err) {
    if (err->line > 0)
        snprintf(v->error, sizeof v->error, "%.200s:%d:%d: %s", v->name, err->line, err->column, err->message);
    else
        snprintf(v->error, sizeof v->error, "%s", err->message);
}

/* Reports a problem on stderr and in the title. */
static void report_error(viewer *v, const iacsg_error *err) {
    print_error(err, v->name);
    set_error(v, err);
    update_title(v);
}

static void request_frame(viewer *v, int preview) {
    iacsg_view view = v->o.view;
    int factor = !preview && v->antialias ? SUPERSAMPLE : 1;
    view.width = preview ? (v->width + PREVIEW_DIVISOR - 1) / PREVIEW_DIVISOR : v->width * factor;
    view.height = preview ? (v->height + PREVIEW_DIVISOR - 1) / PREVIEW_DIVISOR : v->height * factor;
    v->wanted = view_worker_request(v->worker, &view, factor);
    v->wanted_preview = preview;
}

/* The view moved by input: a preview now, the full frame once it rests. */
static void moved(viewer *v) {
    v->moving = 1;
    v->last_input = now_seconds();
    request_frame(v, 1);
}

static void present(viewer *v) {
    v->sdl.RenderClear(v->screen);
    if (v->texture)
        v->sdl.RenderCopy(v->screen, v->texture, NULL, NULL);
    v->sdl.RenderPresent(v->screen);
}

/* Converts the frame for the current mode and puts it in the window. */
static int show_frame(viewer *v) {
    int w = v->frame.width / v->frame_factor, h = v->frame.height / v->frame_factor;
    if (w != v->shown_w || h != v->shown_h) {
        free(v->shown);
        free(v->shown_bytes);
        v->shown = malloc((size_t)w * h * 3 * sizeof(float));
        v->shown_bytes = malloc((size_t)w * h * 3);
        v->shown_w = w;
        v->shown_h = h;
        if (v->texture)
            v->sdl.DestroyTexture(v->texture);
        v->texture = v->sdl.CreateTexture(v->screen, SDL_PIXELFORMAT_RGB24, SDL_TEXTUREACCESS_STREAMING, w, h);
        if (!v->shown || !v->shown_bytes || !v->texture)
            return -1;
    }
    view_display(&v->frame, v->mode, v->frame_factor, v->shown);
    view_display_bytes(v->shown, (size_t)w * h * 3, v->shown_bytes);
    v->sdl.UpdateTexture(v->texture, NULL, v->shown_bytes, 3 * w);
    present(v);
    update_title(v);
    return 0;
}

/* Writes what the window shows, at full resolution, to the next free numbered name of -o. */
static void save_screenshot(viewer *v) {
    v->screenshot_pending = 0;
    char *path = NULL;
    for (int k = 0; k < 100000; k++) {
        free(path);
        path = cli_job_path(v->o.output, 1, k);
        if (!path || access(path, F_OK) != 0)
            break;
    }
    iacsg_error err = {0};
    if (!path)
        iacsg_error_set(&err, IACSG_ERR_NOMEM, 0, 0, "out of memory");
    else if (cli_writer_write(v->writer, path, v->shown_w, v->shown_h, 3, v->shown, 0, &err) == IACSG_OK)
        printf("wrote %s\n", path);
    if (err.status != IACSG_OK)
        print_error(&err, v->name);
    free(path);
}

/* A word of a command line for a POSIX shell: as it is when it is plain, else single-quoted. */
static void print_shell_word(const char *word) {
    if (word[0] && strspn(word, "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-+=.,/:@%") ==
                       strlen(word)) {
        fputs(word, stdout);
        return;
    }
    putchar('\'');
    for (const char *p = word; *p; p++)
        fputs(*p == '\'' ? "'\\''" : (char[2]){*p, 0}, stdout);
    putchar('\'');
}

/* `p`: the render command that makes the image of this view (every number exact: %.17g reads back as the same
 * double). */
static void print_command_line(const viewer *v) {
    const iacsg_view *view = &v->o.view;
    const iacsg_camera *c = &view->camera;
    const double *b = view->bounds;
    fputs("iacsg ", stdout);
    print_shell_word(v->o.input);
    printf(" -size %dx%d -eps %.17g -bounds %.17g,%.17g,%.17g,%.17g,%.17g,%.17g", v->width, v->height, view->eps,
           b[0], b[1], b[2], b[3], b[4], b[5]);
    printf(" -eye %.17g,%.17g,%.17g -at %.17g,%.17g,%.17g -up %.17g,%.17g,%.17g", c->eye[0], c->eye[1], c->eye[2],
           c->at[0], c->at[1], c->at[2], c->up[0], c->up[1], c->up[2]);
    if (c->ortho_height > 0)
        printf(" -ortho %.17g", c->ortho_height);
    else
        printf(" -fov %.17g", c->fov);
    if (v->o.time_text) {
        fputs(" -time ", stdout);
        print_shell_word(v->o.time_text);
    }
    if (v->o.config.fp64)
        fputs(" -fp64", stdout);
    if (v->o.config.fast)
        fputs(" -fast", stdout);
    if (v->o.config.device)
        printf(" -device %d", v->o.config.device);
    putchar('\n');
    if (v->antialias)
        fprintf(stderr, "iacsg: antialiasing is the viewer's own (%dx%d rays a pixel); the command line "
                        "renders without it\n", SUPERSAMPLE, SUPERSAMPLE);
}

static void on_key(viewer *v, SDL_Keycode key) {
    switch (key) {
    case SDLK_q:
    case SDLK_ESCAPE:
        v->quit = 1;
        return;
    case SDLK_r:
        v->o.view.camera = v->home;
        v->o.view.eps = v->home_eps;
        break;
    case SDLK_LEFTBRACKET:
        v->o.view.eps /= 2;
        break;
    case SDLK_RIGHTBRACKET:
        v->o.view.eps *= 2;
        break;
    case SDLK_a:
        v->antialias = !v->antialias;
        break;
    case SDLK_1:
    case SDLK_2:
    case SDLK_3:
    case SDLK_4:
        v->mode = (view_mode)(key - SDLK_1);
        if (v->frame.rgb && show_frame(v) != 0)
            v->quit = 1;
        return;
    case SDLK_s:
        if (v->frame_final)
            save_screenshot(v);
        else
            v->screenshot_pending = 1; /* when the full frame comes */
        return;
    case SDLK_p:
        print_command_line(v);
        return;
    default:
        return;
    }
    v->frame_final = 0;
    request_frame(v, 0);
}

static void on_event(viewer *v, const SDL_Event *ev) {
    switch (ev->type) {
    case SDL_QUIT:
        v->quit = 1;
        break;
    case SDL_KEYDOWN:
        on_key(v, ev->key.keysym.sym);
        break;
    case SDL_MOUSEMOTION: {
        int pan = (ev->motion.state & SDL_BUTTON_RMASK) ||
                  ((ev->motion.state & SDL_BUTTON_LMASK) && (v->sdl.GetModState() & KMOD_SHIFT));
        if (pan)
            view_camera_pan(&v->o.view.camera, ev->motion.xrel, ev->motion.yrel, v->height);
        else if (ev->motion.state & SDL_BUTTON_LMASK)
            view_camera_orbit(&v->o.view.camera, ev->motion.xrel, ev->motion.yrel);
        if (ev->motion.state & (SDL_BUTTON_LMASK | SDL_BUTTON_RMASK))
            moved(v);
        break;
    }
    case SDL_MOUSEWHEEL:
        view_camera_zoom(&v->o.view.camera, ev->wheel.y);
        moved(v);
        break;
    case SDL_WINDOWEVENT:
        if (ev->window.event == SDL_WINDOWEVENT_SIZE_CHANGED) {
            v->width = ev->window.data1;
            v->height = ev->window.data2;
            v->frame_final = 0;
            request_frame(v, 0);
        } else if (ev->window.event == SDL_WINDOWEVENT_EXPOSED) {
            present(v);
        }
        break;
    default:
        break;
    }
}

/* Takes what the render thread finished: a frame to show, or a failure to report. */
static void collect(viewer *v) {
    iacsg_error err;
    if (view_worker_take_build_error(v->worker, &err))
        report_error(v, &err);
    view_result res;
    if (!view_worker_take_frame(v->worker, &res))
        return;
    if (res.status != IACSG_OK) {
        report_error(v, &res.err);
        return;
    }
    iacsg_frame_free(&v->frame);
    v->frame = res.frame;
    v->frame_factor = res.tag;
    v->frame_seconds = res.seconds;
    v->frame_final = res.request == v->wanted && !v->wanted_preview;
    int reloaded = res.scene == v->scenes_sent && v->scene_reported != res.scene && v->scene_reported;
    if (res.scene == v->scenes_sent) {
        v->scene_reported = res.scene;
        v->error[0] = '\0';
    }
    if (show_frame(v) != 0) {
        fprintf(stderr, "iacsg: out of memory\n");
        v->quit = 1;
        return;
    }
    if (reloaded)
        printf("reloaded %s\n", v->name);
    if (v->frame_final && v->screenshot_pending)
        save_screenshot(v);
}

/* Reads and compiles the input into a scene for the render thread; 0, or -1 after reporting the problem. */
static int load_scene(viewer *v) {
    view_scene *s;
    iacsg_error err = {0};
    if (view_scene_load(&v->o, &s, &v->name, &err) != IACSG_OK) {
        if (err.status != IACSG_ERR_IO) /* read_input has printed its own line */
            print_error(&err, v->name);
        set_error(v, &err);
        return -1;
    }
    const double *b = s->bounds;
    printf("bounds %g,%g,%g,%g,%g,%g (%s)\n", b[0], b[1], b[2], b[3], b[4], b[5], s->bounds_phrase);
    memcpy(v->o.view.bounds, s->bounds, sizeof s->bounds);
    view_worker_set_scene(v->worker, s);
    v->scenes_sent++;
    return 0;
}

/* Whether the scene file is another file or has been written since it was last read. */
static int scene_file_changed(viewer *v) {
    struct stat st;
    if (stat(v->o.input, &st) != 0)
        return 0; /* being replaced: look again later */
    int changed = st.st_ino != v->watched.st_ino || st.st_size != v->watched.st_size ||
                  st.st_mtim.tv_sec != v->watched.st_mtim.tv_sec || st.st_mtim.tv_nsec != v->watched.st_mtim.tv_nsec;
    v->watched = st;
    return changed;
}

static void watch_scene(viewer *v) {
    if (v->name != v->o.input || now_seconds() < v->next_watch)
        return;
    v->next_watch = now_seconds() + WATCH_SECONDS;
    if (!scene_file_changed(v))
        return;
    if (load_scene(v) != 0) {
        update_title(v);
        return;
    }
    v->frame_final = 0;
    request_frame(v, 0);
}

static int open_window(viewer *v) {
    if (v->sdl.Init(SDL_INIT_VIDEO) != 0) {
        fprintf(stderr, "iacsg: cannot open the display: %s\n", v->sdl.GetError());
        return -1;
    }
    v->window = v->sdl.CreateWindow("iacsg view", SDL_WINDOWPOS_UNDEFINED, SDL_WINDOWPOS_UNDEFINED, v->width,
                                    v->height, SDL_WINDOW_RESIZABLE | SDL_WINDOW_HIDDEN);
    if (v->window) {
        v->sdl.SetWindowMaximumSize(v->window, MAX_SIDE, MAX_SIDE);
        /* may replace the X window (another visual for OpenGL): shown only after it, so that what a user or a
         * test finds on screen is the window that stays */
        v->screen = v->sdl.CreateRenderer(v->window, -1, 0);
        if (v->screen)
            v->sdl.ShowWindow(v->window);
    }
    if (!v->screen) {
        fprintf(stderr, "iacsg: cannot open a window: %s\n", v->sdl.GetError());
        return -1;
    }
    return 0;
}

static void run(viewer *v) {
    request_frame(v, 0);
    while (!v->quit) {
        SDL_Event ev;
        if (v->sdl.WaitEventTimeout(&ev, 10))
            on_event(v, &ev);
        collect(v);
        if (v->moving && now_seconds() - v->last_input > SETTLE_SECONDS) {
            v->moving = 0;
            request_frame(v, 0);
        }
        watch_scene(v);
    }
}

/* Options that write files of the render command have no meaning here (-o names the screenshots). */
static int refuse_render_only_options(const render_options *o) {
    const char *option = o->depth_file ? "-depth" : o->normals_file ? "-normals" : o->frames ? "-frames" : NULL;
    if (option)
        fprintf(stderr, "iacsg: %s does not apply to the viewer (see iacsg --help)\n", option);
    return option != NULL;
}

int cli_view(int argc, char **argv) {
    static viewer v; /* large, and zero-initialised */
    int rc = parse_options(argc, argv, &v.o);
    if (rc)
        return rc;
    if (refuse_render_only_options(&v.o))
        return 2;
    if (v.o.view.width > MAX_SIDE || v.o.view.height > MAX_SIDE) {
        fprintf(stderr, "iacsg: -size %dx%d: the window is at most %dx%d\n", v.o.view.width,
                v.o.view.height, MAX_SIDE, MAX_SIDE);
        return 2;
    }
    /* Without a session bus, SDL's D-Bus calls (screensaver, input methods) make libdbus autolaunch one through
     * the X server, which can block the window for good: "disabled:" makes them fail at once. Set here, before
     * any thread starts. */
    setenv("DBUS_SESSION_BUS_ADDRESS", "disabled:", 0);
    const char *x11 = getenv("DISPLAY"), *wayland = getenv("WAYLAND_DISPLAY");
    if ((!x11 || !*x11) && (!wayland || !*wayland)) {
        fprintf(stderr, "iacsg: no display for the viewer's window (neither DISPLAY nor WAYLAND_DISPLAY is set); "
                        "iacsg EXPR|SCENE renders to a file\n");
        return 1;
    }
    char why[512];
    if (view_sdl_load(&v.sdl, why, sizeof why) != 0) {
        fprintf(stderr, "iacsg: %s\n", why);
        return 1;
    }
    setvbuf(stdout, NULL, _IOLBF, 0); /* each line out at once: other programs drive the viewer by them */
    iacsg_error err = {0};
    /* before any thread (it forks): SDL's and the render thread's */
    if (cli_writer_start((size_t)MAX_SIDE * MAX_SIDE * 3, &v.writer, &err) == IACSG_OK) {
        cli_writer_check(v.writer, v.o.output);
        cli_writer_checked(v.writer, &err);
    }
    if (err.status != IACSG_OK) {
        print_error(&err, v.o.input);
        cli_writer_stop(v.writer);
        return 1;
    }
    v.o.config.stats = 1; /* the title shows evaluations per ray */
    v.width = v.o.view.width;
    v.height = v.o.view.height;
    rc = 1;
    if (view_worker_start(&v.o.config, &v.worker) != 0)
        fprintf(stderr, "iacsg: cannot start the render thread\n");
    else if (load_scene(&v) == 0) {
        stat(v.o.input, &v.watched);
        place_camera(&v.o);
        v.home = v.o.view.camera;
        v.home_eps = v.o.view.eps;
        if (open_window(&v) == 0) {
            update_title(&v);
            run(&v);
            rc = 0;
        }
    }
    view_worker_stop(v.worker);
    iacsg_frame_free(&v.frame);
    free(v.shown);
    free(v.shown_bytes);
    if (v.texture)
        v.sdl.DestroyTexture(v.texture);
    if (v.screen)
        v.sdl.DestroyRenderer(v.screen);
    if (v.window)
        v.sdl.DestroyWindow(v.window);
    /* No SDL_Quit: it unloads the X11 libraries SDL loaded, and what they keep for the life of the process then
     * shows, to the sanitizers' leak check, as allocations of unknown code that no suppression can name. The
     * process ends here. */
    cli_writer_stop(v.writer);
    return rc;
}
