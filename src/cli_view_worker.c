/* src/cli_view_worker.c -- see cli_view_worker.h. One mutex guards the exchange (requests, scenes, results);
 * the renderer is touched by the thread alone. The thread's loop:
 *   wait for a scene, a request not yet done, or stop -> build the scene's renderer (a failure is kept for
 *   view_worker_take_build_error, and the last good renderer stays) -> render the newest request, cancelled
 *   when anything newer arrives -> publish the frame. */
#define _XOPEN_SOURCE 700 /* sigaltstack */
#include "cli_view_worker.h"
#include <pthread.h>
#include <signal.h>
#include <stdlib.h>
#include <time.h>

struct view_worker {
    pthread_t thread;
    pthread_mutex_t lock;
    pthread_cond_t wake;
    iacsg_render_config config;
    int stop;
    view_scene *new_scene;        /* handed over, not yet built */
    unsigned scenes_given;        /* scenes handed over so far: new_scene is the last */
    iacsg_view view;              /* the newest request */
    int tag;                      /* the newest request's, given back with its frame */
    unsigned wanted, done;        /* the newest request's number (0: none yet), and the last one rendered */
    unsigned rendering;           /* the request in progress */
    int have_result, have_build_error;
    view_result result;
    iacsg_error build_error;
    /* the thread's own */
    iacsg_renderer *renderer;
    unsigned renderer_scene;      /* which scene the renderer draws (n: the n-th handed over) */
    iacsg_effects effects;        /* the effects its scene is seen with (view_scene), when has_effects */
    int has_effects;
};

static double now_seconds(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* iacsg_view.cancel: something newer than the frame being rendered has arrived. */
static int superseded(void *ctx) {
    view_worker *w = ctx;
    pthread_mutex_lock(&w->lock);
    int yes = w->stop || w->new_scene || w->wanted != w->rendering;
    pthread_mutex_unlock(&w->lock);
    return yes;
}

/* Builds the renderer of scene `number` (unlocked: seconds) and installs it; returns with the lock held. */
static void build_scene(view_worker *w, view_scene *s, unsigned number) {
    iacsg_renderer *r = NULL;
    iacsg_error err = {0};
    iacsg_status st = view_scene_renderer(s, &w->config, &r, &err);
    iacsg_effects effects = s->effects;
    int has_effects = s->has_effects;
    view_scene_destroy(s);
    pthread_mutex_lock(&w->lock);
    if (st == IACSG_OK) {
        iacsg_renderer_destroy(w->renderer);
        w->renderer = r;
        w->renderer_scene = number;
        w->effects = effects;
        w->has_effects = has_effects;
        w->done = w->wanted - 1; /* the newest request again, with the new scene */
    } else {
        w->build_error = err;
        w->have_build_error = 1;
    }
}

static void *worker_main(void *arg) {
    view_worker *w = arg;
    /* LLVM, compiling kernels inside PoCL, installs an alternate signal stack of its own (malloc'ed) on the
     * first thread that compiles; the sanitizers' runtime unmaps whatever alternate stack a thread has when
     * it ends, and aborts on that one. The thread's own goes back before it ends. */
    stack_t own_signal_stack;
    int have_signal_stack = sigaltstack(NULL, &own_signal_stack) == 0;
    pthread_mutex_lock(&w->lock);
    for (;;) {
        while (!w->stop && !w->new_scene && (w->done == w->wanted || !w->wanted || !w->renderer))
            pthread_cond_wait(&w->wake, &w->lock);
        if (w->stop)
            break;
        if (w->new_scene) {
            view_scene *s = w->new_scene;
            unsigned number = w->scenes_given;
            w->new_scene = NULL;
            pthread_mutex_unlock(&w->lock);
            build_scene(w, s, number); /* returns with the lock held */
            continue;
        }
        unsigned request = w->rendering = w->wanted;
        int tag = w->tag;
        iacsg_view view = w->view;
        pthread_mutex_unlock(&w->lock);

        view.effects = w->has_effects ? &w->effects : NULL; /* the scene's lights too, as the render command's */
        view.progress = NULL;
        view.cancel = superseded;
        view.cancel_ctx = w;
        view_result res = {.request = request, .tag = tag, .scene = w->renderer_scene};
        double start = now_seconds();
        res.status = iacsg_render(w->renderer, &view, &res.frame, &res.err);
        res.seconds = now_seconds() - start;

        pthread_mutex_lock(&w->lock);
        if (res.status == IACSG_ERR_CANCELLED)
            continue; /* whatever cancelled it is waiting */
        w->done = request;
        if (w->have_result && w->result.status == IACSG_OK)
            iacsg_frame_free(&w->result.frame);
        w->result = res;
        w->have_result = 1;
    }
    pthread_mutex_unlock(&w->lock);
    if (have_signal_stack)
        sigaltstack(&own_signal_stack, NULL);
    return NULL;
}

int view_worker_start(const iacsg_render_config *config, view_worker **out) {
    view_worker *w = calloc(1, sizeof *w);
    *out = NULL;
    if (!w)
        return -1;
    w->config = *config;
    pthread_mutex_init(&w->lock, NULL);
    pthread_cond_init(&w->wake, NULL);
    if (pthread_create(&w->thread, NULL, worker_main, w) != 0) {
        pthread_cond_destroy(&w->wake);
        pthread_mutex_destroy(&w->lock);
        free(w);
        return -1;
    }
    *out = w;
    return 0;
}

void view_worker_set_scene(view_worker *w, view_scene *s) {
    pthread_mutex_lock(&w->lock);
    view_scene_destroy(w->new_scene);
    w->new_scene = s;
    w->scenes_given++;
    pthread_cond_signal(&w->wake);
    pthread_mutex_unlock(&w->lock);
}

unsigned view_worker_request(view_worker *w, const iacsg_view *view, int tag) {
    pthread_mutex_lock(&w->lock);
    w->view = *view;
    w->tag = tag;
    unsigned request = ++w->wanted;
    pthread_cond_signal(&w->wake);
    pthread_mutex_unlock(&w->lock);
    return request;
}

int view_worker_take_frame(view_worker *w, view_result *out) {
    pthread_mutex_lock(&w->lock);
    int have = w->have_result;
    if (have)
        *out = w->result;
    w->have_result = 0;
    pthread_mutex_unlock(&w->lock);
    return have;
}

int view_worker_take_build_error(view_worker *w, iacsg_error *err) {
    pthread_mutex_lock(&w->lock);
    int have = w->have_build_error;
    if (have)
        *err = w->build_error;
    w->have_build_error = 0;
    pthread_mutex_unlock(&w->lock);
    return have;
}

void view_worker_stop(view_worker *w) {
    if (!w)
        return;
    pthread_mutex_lock(&w->lock);
    w->stop = 1;
    pthread_cond_signal(&w->wake);
    pthread_mutex_unlock(&w->lock);
    pthread_join(w->thread, NULL);
    if (w->have_result && w->result.status == IACSG_OK)
        iacsg_frame_free(&w->result.frame);
    view_scene_destroy(w->new_scene);
    iacsg_renderer_destroy(w->renderer);
    pthread_cond_destroy(&w->wake);
    pthread_mutex_destroy(&w->lock);
    free(w);
}
