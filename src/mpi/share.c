/* src/mpi/share.c -- libiacsg_mpi.so: the render command's MPI layer (the interface and protocol are in
 * src/cli_mpi.h). The only file that includes mpi.h.
 *
 * Stages: init (MPI_Init_thread, serialized: rank 0 calls MPI from its dispatcher thread, and from its main
 * thread only before and after that thread runs) -> start (rank 0: the items, and a SIGTERM handler that says
 * which frames were under way when mpirun stops the job) -> start_together, at a rank's first next or fail (a
 * barrier; rank 0 then starts its dispatcher thread) -> next / fail per item -> end (rank 0 has joined the
 * dispatcher once every other rank was told to finish; MPI_Finalize).
 *
 * Messages, all to or from rank 0: a rank sends TAG_ASK {finished item or -1, failed}; in band mode the
 * finished band's rows follow (TAG_ROWS, one message an image), on a failure its line (TAG_FAILURE); rank 0
 * answers an ask with TAG_REPLY {next item, CLI_MPI_DONE or CLI_MPI_STOPPED}. The dispatcher polls with
 * MPI_Iprobe and sleeps a millisecond between polls: a blocking receive in Open MPI spins, and would take a
 * core from the render. */
#include "cli_mpi.h"
#include <mpi.h>
#include <pthread.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

enum { TAG_ASK = 1, TAG_ROWS, TAG_FAILURE, TAG_REPLY };
enum { FAILURE_TEXT = 512, STOP_LINE = 2048 };

static struct {
    int rank, size, band_rows;
    cli_mpi_images gather;
    cli_mpi_describe_fn describe;
    void *describe_ctx;
    /* rank 0: guarded by lock */
    pthread_mutex_t lock;
    const int *items;
    int count, next, failed, asking; /* asking: ranks not yet told to finish */
    int *current;                   /* the item each rank is on, -1 when none */
    int first_asks;                 /* the other ranks' first asks answered */
    char failure[FAILURE_TEXT + 256];
    pthread_t dispatcher;
    int dispatching;
    /* the SIGTERM handler's line, written whole into the one not in use, then switched */
    char stop_line[2][STOP_LINE];
    volatile sig_atomic_t stop_current;
} job = {.lock = PTHREAD_MUTEX_INITIALIZER};

static void on_sigterm(int sig) {
    (void)sig;
    const char *line = job.stop_line[job.stop_current];
    ssize_t written = write(STDERR_FILENO, line, strlen(line));
    (void)written;
    _exit(1);
}

/* Rewrites the SIGTERM handler's line from job.current; under the lock. */
static void update_stop_line(void) {
    char *line = job.stop_line[!job.stop_current];
    size_t n = (size_t)snprintf(line, STOP_LINE, "iacsg: the job was stopped (mpirun stops it when a rank fails or "
                                                 "is killed) while");
    int any = 0;
    for (int r = 0; r < job.size && n < STOP_LINE - 128; r++) {
        if (job.current[r] < 0)
            continue;
        char what[96];
        job.describe(job.current[r], what, sizeof what, job.describe_ctx);
        n += (size_t)snprintf(line + n, STOP_LINE - n, "%s rank %d was on %s", any ? "," : "", r, what);
        any = 1;
    }
    snprintf(line + n, STOP_LINE - n, "%s; run the same command with -resume to finish\n",
             any ? "" : " no rank was rendering");
    job.stop_current = !job.stop_current;
}

static void record_failure(int rank, int item, const char *text) {
    if (!job.failed) {
        char what[96] = "";
        if (item >= 0)
            job.describe(item, what, sizeof what, job.describe_ctx);
        snprintf(job.failure, sizeof job.failure, "rank %d failed%s%s: %s", rank, item >= 0 ? " on " : "", what,
                 text);
    }
    job.failed = 1;
    job.current[rank] = -1;
    update_stop_line();
}

/* The next item for `rank`; under the lock. */
static int take_item(int rank) {
    int next = job.failed ? CLI_MPI_STOPPED : job.next < job.count ? job.items[job.next++] : CLI_MPI_DONE;
    job.current[rank] = next >= 0 ? next : -1;
    update_stop_line();
    return next;
}

/* The floats of image k of band `band` in `im`: where they start, and how many. */
static float *band_floats(const cli_mpi_images *im, int k, int band, int *count) {
    size_t row = (size_t)im->width * (size_t)im->channels[k];
    int left = im->height - band * job.band_rows;
    *count = (int)(row * (size_t)(left < job.band_rows ? left : job.band_rows));
    return im->planes[k] + row * (size_t)band * (size_t)job.band_rows;
}

/* Answers one ask (waiting for it, a millisecond between polls). */
static void serve_one(void) {
    int flag = 0;
    MPI_Status status;
    while (MPI_Iprobe(MPI_ANY_SOURCE, TAG_ASK, MPI_COMM_WORLD, &flag, &status), !flag)
        nanosleep(&(struct timespec){0, 1000000}, NULL);
    int src = status.MPI_SOURCE, ask[2];
    MPI_Recv(ask, 2, MPI_INT, src, TAG_ASK, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    if (ask[1]) {
        char text[FAILURE_TEXT];
        MPI_Recv(text, FAILURE_TEXT, MPI_CHAR, src, TAG_FAILURE, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
        text[FAILURE_TEXT - 1] = '\0';
        pthread_mutex_lock(&job.lock);
        record_failure(src, ask[0], text);
        pthread_mutex_unlock(&job.lock);
        job.asking--;
        return;
    }
    if (ask[0] >= 0 && job.band_rows)
        for (int k = 0; k < CLI_MPI_IMAGES; k++) {
            int count;
            float *to = band_floats(&job.gather, k, ask[0], &count);
            if (job.gather.channels[k])
                MPI_Recv(to, count, MPI_FLOAT, src, TAG_ROWS, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
        }
    pthread_mutex_lock(&job.lock);
    int reply = take_item(src);
    job.first_asks += ask[0] < 0;
    pthread_mutex_unlock(&job.lock);
    MPI_Send(&reply, 1, MPI_INT, src, TAG_REPLY, MPI_COMM_WORLD);
    if (reply < 0)
        job.asking--;
}

/* Rank 0's dispatcher thread: answers until every other rank has been told to finish (or has failed). */
static void *dispatch(void *unused) {
    (void)unused;
    while (job.asking > 0)
        serve_one();
    return NULL;
}

static int mpi_init(int *rank, int *size, char *why, size_t why_size) {
    int provided = 0;
    if (MPI_Init_thread(NULL, NULL, MPI_THREAD_SERIALIZED, &provided) != MPI_SUCCESS) {
        snprintf(why, why_size, "MPI_Init_thread failed");
        return 1;
    }
    MPI_Comm_rank(MPI_COMM_WORLD, &job.rank);
    MPI_Comm_size(MPI_COMM_WORLD, &job.size);
    *rank = job.rank;
    *size = job.size;
    if (provided < MPI_THREAD_SERIALIZED) {
        snprintf(why, why_size, "this MPI does not allow calls from a second thread (MPI_THREAD_SERIALIZED)");
        return 1;
    }
    return 0;
}

static int mpi_start(const int *items, int count, int band_rows, const cli_mpi_images *gather,
                     cli_mpi_describe_fn describe, void *describe_ctx, char *why, size_t why_size) {
    job.band_rows = band_rows;
    job.gather = *gather;
    job.describe = describe;
    job.describe_ctx = describe_ctx;
    if (job.rank != 0)
        return 0;
    job.items = items;
    job.count = count;
    job.asking = job.size - 1;
    job.current = malloc((size_t)job.size * sizeof(int));
    if (!job.current) {
        snprintf(why, why_size, "out of memory");
        return 1;
    }
    for (int r = 0; r < job.size; r++)
        job.current[r] = -1;
    update_stop_line();
    signal(SIGTERM, on_sigterm);
    return 0;
}

/* The ranks start taking items together, once each has built its kernel (or failed): otherwise a rank that is
 * up first takes the first frames while the others, slowed by its render, still build; and which rank renders
 * what would depend on that race. Each rank calls it at its first next or fail; rank 0 then starts answering. */
static void start_together(void) {
    static int started;
    if (started)
        return;
    started = 1;
    MPI_Barrier(MPI_COMM_WORLD);
    if (job.rank == 0) {
        if (pthread_create(&job.dispatcher, NULL, dispatch, NULL) == 0) {
            job.dispatching = 1;
        } else {
            pthread_mutex_lock(&job.lock);
            record_failure(0, -1, "cannot start the thread that hands out the work");
            pthread_mutex_unlock(&job.lock);
        }
    }
}

/* Under the tests' IACSG_TEST_KILL (src/cli_job.c), rank 0 takes its first item only once every other rank has
 * been answered (or 30 s have passed): otherwise, on a loaded machine, rank 0 may render every band before the
 * rank to be killed asks for one, and the test sees no kill. */
static void test_others_first(void) {
    static int waited;
    if (waited || !getenv("IACSG_TEST_KILL"))
        return;
    waited = 1;
    for (int ms = 0; ms < 30000; ms++) {
        pthread_mutex_lock(&job.lock);
        int all = job.first_asks >= job.size - 1 || job.failed;
        pthread_mutex_unlock(&job.lock);
        if (all)
            return;
        nanosleep(&(struct timespec){0, 1000000}, NULL);
    }
}

static int mpi_next(int finished, const cli_mpi_images *rows) {
    start_together();
    if (job.rank == 0) {
        if (finished >= 0 && job.band_rows)
            for (int k = 0; k < CLI_MPI_IMAGES; k++) {
                int count;
                float *to = band_floats(&job.gather, k, finished, &count);
                if (job.gather.channels[k])
                    memcpy(to, band_floats(rows, k, finished, &count), (size_t)count * sizeof(float));
            }
        if (job.dispatching)
            test_others_first();
        pthread_mutex_lock(&job.lock);
        int next = take_item(0);
        pthread_mutex_unlock(&job.lock);
        if (next < 0 && job.dispatching) {
            /* the others may still be on their last items (in band mode, rows rank 0 is about to write):
             * wait for all of them, and for whether one failed */
            pthread_join(job.dispatcher, NULL);
            job.dispatching = 0;
            next = job.failed ? CLI_MPI_STOPPED : CLI_MPI_DONE;
        }
        return next;
    }
    int ask[2] = {finished, 0}, reply;
    MPI_Send(ask, 2, MPI_INT, 0, TAG_ASK, MPI_COMM_WORLD);
    if (finished >= 0 && job.band_rows)
        for (int k = 0; k < CLI_MPI_IMAGES; k++) {
            int count;
            float *from = band_floats(rows, k, finished, &count);
            if (rows->channels[k])
                MPI_Send(from, count, MPI_FLOAT, 0, TAG_ROWS, MPI_COMM_WORLD);
        }
    MPI_Recv(&reply, 1, MPI_INT, 0, TAG_REPLY, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    return reply;
}

static int failed_here;

static void mpi_fail(int item, const char *message) {
    start_together();
    failed_here = 1;
    if (job.rank == 0) {
        pthread_mutex_lock(&job.lock);
        record_failure(0, item, message);
        pthread_mutex_unlock(&job.lock);
        return;
    }
    char text[FAILURE_TEXT] = "";
    snprintf(text, sizeof text, "%s", message);
    int ask[2] = {item, 1};
    MPI_Send(ask, 2, MPI_INT, 0, TAG_ASK, MPI_COMM_WORLD);
    MPI_Send(text, FAILURE_TEXT, MPI_CHAR, 0, TAG_FAILURE, MPI_COMM_WORLD);
}

static int mpi_end(char *failure, size_t size) {
    int failed = failed_here;
    if (job.rank == 0) {
        if (job.dispatching)
            pthread_join(job.dispatcher, NULL);
        else
            dispatch(NULL); /* it could not start: answer the others now (told to stop) */
        failed = job.failed;
        snprintf(failure, size, "%s", job.failure);
        signal(SIGTERM, SIG_DFL);
        free(job.current);
    }
    MPI_Finalize();
    return failed;
}

/* exported: objects under build/pic/ are built with hidden visibility */
__attribute__((visibility("default"))) const cli_mpi_api cli_mpi = {mpi_init, mpi_start, mpi_next, mpi_fail, mpi_end};
