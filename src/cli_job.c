/* src/cli_job.c -- see cli_job.h. */
#include "cli_job.h"
#include "cli_library.h"
#include "cli_mpi.h"
#include "clrt.h"
#include <dlfcn.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

struct cli_job {
    const cli_mpi_api *mpi; /* NULL when run plainly */
    int rank, size, frames, height, band_rows; /* band_rows > 0: the ranks share one frame in bands */
    int *items, count, next; /* the frames (or bands) to do: all of them on rank 0; next: run plainly */
    int last;                /* the item last handed out, or CLI_MPI_DONE (also before the first) */
    int failed, taken;
    iacsg_frame whole; /* rank 0 in band mode: the frame the bands are gathered into */
};

char *cli_job_path(const char *path, int frames, int frame) {
    if (!frames)
        return strdup(path);
    const char *slash = strrchr(path, '/'), *dot = strrchr(path, '.');
    size_t stem = dot && (!slash || dot > slash) ? (size_t)(dot - path) : strlen(path);
    size_t size = strlen(path) + 16;
    char *out = malloc(size);
    if (out)
        snprintf(out, size, "%.*s_%04d%s", (int)stem, path, frame, path + stem);
    return out;
}

/* Whether every file of the frame is in place (and so complete: see cli_job.h). */
static int frame_complete(const char *const outputs[CLI_MPI_IMAGES], int frames, int frame) {
    for (int k = 0; k < CLI_MPI_IMAGES; k++) {
        if (!outputs[k])
            continue;
        char *path = cli_job_path(outputs[k], frames, frame);
        int there = path && access(path, F_OK) == 0;
        free(path);
        if (!there)
            return 0;
    }
    return 1;
}

static void describe_item(int item, char *out, size_t size, void *ctx) {
    const cli_job *j = ctx;
    if (j->band_rows)
        snprintf(out, size, "rows %d-%d", item * j->band_rows,
                 (item + 1) * j->band_rows < j->height ? (item + 1) * j->band_rows - 1 : j->height - 1);
    else
        snprintf(out, size, "frame %d", item);
}

/* The images of a frame as rows to send or receive. */
static cli_mpi_images frame_images(const iacsg_frame *f) {
    cli_mpi_images im = {f->width, f->height, {f->rgb ? 3 : 0, f->depth ? 1 : 0, f->normal ? 3 : 0, f->ids ? 1 : 0},
                         {f->rgb, f->depth, f->normal, f->ids}};
    return im;
}

/* Rank 0 of a banded frame: the frame the bands are gathered into. */
static int alloc_whole(cli_job *j, int width, const char *const outputs[CLI_MPI_IMAGES]) {
    size_t n = (size_t)width * (size_t)j->height;
    j->whole.width = width;
    j->whole.height = j->height;
    j->whole.rgb = malloc(3 * n * sizeof(float));
    j->whole.depth = outputs[1] ? malloc(n * sizeof(float)) : NULL;
    j->whole.normal = outputs[2] ? malloc(3 * n * sizeof(float)) : NULL;
    j->whole.ids = outputs[3] ? malloc(n * sizeof(float)) : NULL;
    j->whole.rays = (long long)n;
    return j->whole.rgb && (j->whole.depth || !outputs[1]) && (j->whole.normal || !outputs[2]) &&
           (j->whole.ids || !outputs[3]);
}

/* Under mpirun: loads the MPI layer, joins the job, and (rank 0) hands out the items. */
static int start_mpi(cli_job *j, int width, const char *const outputs[CLI_MPI_IMAGES]) {
    iacsg_error err = {0};
    /* RTLD_GLOBAL: Open MPI's own plugins resolve their symbols against libmpi */
    void *lib = cli_library_open(CLI_MPI_LIBRARY, "the MPI layer", RTLD_NOW | RTLD_GLOBAL, &err);
    if (!lib) {
        fprintf(stderr, "iacsg: running under mpirun, but %s\n", err.message);
        return 0;
    }
    j->mpi = dlsym(lib, "cli_mpi");
    char why[256] = "";
    if (!j->mpi || j->mpi->init(&j->rank, &j->size, why, sizeof why) != 0) {
        fprintf(stderr, "iacsg: cannot join the MPI job: %s\n", j->mpi ? why : dlerror());
        return 0;
    }
    if (j->size > 1 && !j->frames) {
        /* a few bands a rank, so that one that finishes early takes another */
        int rows = (j->height + 4 * j->size - 1) / (4 * j->size);
        j->band_rows = (rows + IACSG_ROW_ALIGN - 1) / IACSG_ROW_ALIGN * IACSG_ROW_ALIGN;
        if (j->rank == 0) {
            j->count = j->count ? (j->height + j->band_rows - 1) / j->band_rows : 0;
            int *bands = realloc(j->items, (j->count ? j->count : 1) * sizeof(int));
            if (bands)
                j->items = bands;
            if (!bands || !alloc_whole(j, width, outputs)) {
                fprintf(stderr, "iacsg: out of memory for a %dx%d image\n", width, j->height);
                return 0;
            }
            for (int k = 0; k < j->count; k++)
                bands[k] = k;
        }
    }
    cli_mpi_images gather = frame_images(&j->whole);
    if (j->mpi->start(j->rank == 0 ? j->items : NULL, j->rank == 0 ? j->count : 0, j->band_rows, &gather,
                      describe_item, j, why, sizeof why) != 0) {
        fprintf(stderr, "iacsg: rank %d: %s\n", j->rank, why);
        return 0;
    }
    return 1;
}

cli_job *cli_job_start(int frames, int width, int height, int resume, const char *const outputs[CLI_MPI_IMAGES]) {
    cli_job *j = calloc(1, sizeof *j);
    int total = frames ? frames : 1;
    if (!j || !(j->items = malloc((size_t)total * sizeof(int)))) {
        free(j);
        fprintf(stderr, "iacsg: out of memory\n");
        return NULL;
    }
    j->frames = frames;
    j->height = height;
    j->size = 1;
    j->last = -1;
    for (int k = 0; k < total; k++)
        if (!resume || !frame_complete(outputs, frames, k))
            j->items[j->count++] = k;
    int complete = total - j->count;
    const char *under_mpirun = getenv("OMPI_COMM_WORLD_SIZE");
    if (under_mpirun && !start_mpi(j, width, outputs)) {
        free(j->items);
        iacsg_frame_free(&j->whole);
        free(j);
        return NULL;
    }
    if (complete && j->rank == 0)
        printf("resume: %d of %d frame%s complete already\n", complete, total, total > 1 ? "s" : "");
    return j;
}

int cli_job_rank(const cli_job *j) { return j->rank; }

static void count_device(int index, const char *platform, const char *device, void *ctx) {
    (void)index, (void)platform, (void)device, (void)ctx;
}

int cli_job_device(const cli_job *j) {
    const char *local = getenv("OMPI_COMM_WORLD_LOCAL_RANK");
    if (!j->mpi || !local)
        return 0;
    iacsg_error err = {0};
    int devices = clrt_list_devices(count_device, NULL, &err);
    return devices > 0 ? atoi(local) % devices : 0;
}

/* For the tests of a rank killed in the middle of a job: IACSG_TEST_KILL=RANK:N kills that rank (SIGKILL, as
 * `kill -9` would) when it is handed its N-th item (a frame, or a band), before it renders it. */
static void test_kill_hook(cli_job *j) {
    const char *hook = getenv("IACSG_TEST_KILL");
    int rank, nth;
    if (hook && sscanf(hook, "%d:%d", &rank, &nth) == 2 && rank == j->rank && ++j->taken == nth)
        raise(SIGKILL);
}

int cli_job_next(cli_job *j, iacsg_frame *done, cli_job_item *item) {
    int next;
    if (j->failed) {
        next = CLI_MPI_STOPPED;
    } else if (j->mpi) {
        cli_mpi_images rows = frame_images(done);
        next = j->mpi->next(done->rgb ? j->last : -1, &rows);
    } else {
        next = j->next < j->count ? j->items[j->next++] : CLI_MPI_DONE;
    }
    iacsg_frame_free(done);
    j->last = next;
    if (next < 0)
        return 0;
    test_kill_hook(j);
    item->frame = j->band_rows ? 0 : next;
    item->row_first = j->band_rows ? next * j->band_rows : 0;
    int left = j->height - item->row_first;
    item->row_count = !j->band_rows ? 0 : left < j->band_rows ? left : j->band_rows;
    return 1;
}

int cli_job_writes_frames(const cli_job *j) { return !j->band_rows; }

int cli_job_alone(const cli_job *j) { return !j->mpi; }

const iacsg_frame *cli_job_gathered(cli_job *j) {
    return j->band_rows && j->rank == 0 && j->count && !j->failed && j->last == CLI_MPI_DONE ? &j->whole : NULL;
}

void cli_job_fail(cli_job *j, int frame, const char *line) {
    if (j->failed)
        return;
    j->failed = 1;
    if (j->mpi)
        j->mpi->fail(frame < 0 ? -1 : j->last, line);
    else
        fprintf(stderr, "iacsg: %s\n", line);
}

int cli_job_end(cli_job *j) {
    if (!j)
        return 1;
    int failed = j->failed;
    if (j->mpi) {
        char line[1024] = "";
        failed = j->mpi->end(line, sizeof line);
        if (failed && j->rank == 0)
            fprintf(stderr, "iacsg: %s%s\n", line, j->frames ? "; run the same command with -resume to finish" : "");
    }
    free(j->items);
    iacsg_frame_free(&j->whole);
    free(j);
    return failed;
}
