/* src/cli_view_worker.h -- the viewer's render thread. It owns the renderer: it builds one for each scene
 * handed to it and renders the frame last asked for, so that the window never waits on a long frame or a
 * kernel build. A newer request, a new scene or stopping cancels the frame in progress through the library's
 * cancel callback (iacsg_view.cancel), between bands of rows. */
#ifndef IACSG_CLI_VIEW_WORKER_H
#define IACSG_CLI_VIEW_WORKER_H
#include "cli_view_scene.h"

typedef struct view_worker view_worker;

typedef struct {
    unsigned request;      /* the number view_worker_request returned for it */
    int tag;               /* as given with the request */
    unsigned scene;        /* the scene it shows: n for the n-th handed over (one that failed to build is
                              never shown) */
    iacsg_status status;   /* IACSG_OK: frame holds the images (the receiver frees them) */
    iacsg_error err;
    iacsg_frame frame;
    double seconds;        /* wall time of iacsg_render */
} view_result;

/* Starts the thread, which renders with `config`. Returns 0, or -1 when no thread could be started. */
int view_worker_start(const iacsg_render_config *config, view_worker **out);

/* Hands over a scene (ownership passes): its renderer is built before the next frame. A scene not yet built
 * when another comes is dropped. */
void view_worker_set_scene(view_worker *w, view_scene *s);

/* Asks for a frame of `view` (its callbacks are replaced), cancelling the one in progress; returns the
 * request's number, which grows with each call. */
unsigned view_worker_request(view_worker *w, const iacsg_view *view, int tag);

/* Takes the newest finished frame (older unclaimed ones are dropped): 1 and *out, or 0 when none. */
int view_worker_take_frame(view_worker *w, view_result *out);

/* Takes the failure of the last scene build, if one failed since the last call: 1 and *err, or 0. */
int view_worker_take_build_error(view_worker *w, iacsg_error *err);

/* Cancels the frame in progress, waits for the thread and frees everything it holds. NULL is allowed. */
void view_worker_stop(view_worker *w);

#endif
