/* src/cli_mpi.h -- libiacsg_mpi.so, the command's MPI layer (src/mpi/share.c), as src/cli_job.c calls it.
 * The command is not linked with MPI: it loads this library only when it runs under mpirun, so that a plain
 * render pays nothing for it (README: MPI).
 *
 * Work is a list of items (ints: frame numbers, or band numbers of one frame) known to rank 0, which hands them
 * out one at a time as ranks ask (rank 0 renders too: a thread of its own answers the others). In band mode the
 * ranks send each band's rows to rank 0, which assembles the frame. A failure stops the job at the ranks' next
 * items; rank 0 prints it. */
#ifndef IACSG_CLI_MPI_H
#define IACSG_CLI_MPI_H
#include <stddef.h>

#define CLI_MPI_LIBRARY "libiacsg_mpi.so"

enum { CLI_MPI_DONE = -1, CLI_MPI_STOPPED = -2 };

/* Where the rows of the images go (rank 0) or come from (a rank's frame): up to three images of width x height
 * pixels, of channels[k] floats a pixel (0: no such image). */
/* image, depth, normals, ids */
#define CLI_MPI_IMAGES 4

typedef struct {
    int width, height, channels[CLI_MPI_IMAGES];
    float *planes[CLI_MPI_IMAGES];
} cli_mpi_images;

/* Describes an item for the messages ("frame 3", "rows 256-511 of frame 0"). */
typedef void (*cli_mpi_describe_fn)(int item, char *out, size_t size, void *ctx);

typedef struct {
    /* Joins the MPI job (MPI_Init_thread). 0, or nonzero with the reason in why. */
    int (*init)(int *rank, int *size, char *why, size_t why_size);
    /* Starts the job: on rank 0 the items and, in band mode (band_rows > 0), the images they are gathered
     * into (item b is rows b band_rows .. (b + 1) band_rows - 1); other ranks pass no items. */
    int (*start)(const int *items, int count, int band_rows, const cli_mpi_images *gather,
                 cli_mpi_describe_fn describe, void *describe_ctx, char *why, size_t why_size);
    /* Reports the item this rank has just rendered (-1: none yet) with its rows in band mode, and returns the
     * next item, CLI_MPI_DONE, or CLI_MPI_STOPPED when another rank failed. Rank 0 gets DONE only once every
     * rank has finished (its rows gathered), STOPPED if one failed. */
    int (*next)(int finished, const cli_mpi_images *rows);
    /* Reports that this rank failed on `item` (message: one line, without "iacsg: "); it takes no more. */
    void (*fail)(int item, const char *message);
    /* Ends the job and MPI. Collective. On rank 0 returns 1 and the failure's line (naming the rank and the
     * item) when a rank failed, else 0; other ranks return whether they failed. */
    int (*end)(char *failure, size_t size);
} cli_mpi_api;

/* The library's one exported symbol: the table above. */
extern const cli_mpi_api cli_mpi;

#endif
