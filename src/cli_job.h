/* src/cli_job.h -- which frames (or bands of rows) this process of the render command traces, and where they go.
 *
 * Stages: cli_job_start (the frames left to do; under mpirun, joining the MPI job through libiacsg_mpi.so,
 * src/cli_mpi.h) -> cli_job_next for each item (handing over the last one's rows when bands are gathered) ->
 * cli_job_gathered (rank 0 of a banded frame: the whole image) -> cli_job_end (the exit status; the one line of
 * a failure, naming the rank and the frame).
 *
 * Run plainly, a job is every frame in order, in this process. Under mpirun (OMPI_COMM_WORLD_SIZE set) with
 * -frames, ranks take frames as they finish their last one; without, the ranks share one frame's bands of
 * rows and rank 0 assembles and writes the image. With -resume, frames whose files are all there are skipped:
 * an image is only ever renamed into place once complete (src/image_oiio.cpp), so being there is being complete. */
#ifndef IACSG_CLI_JOB_H
#define IACSG_CLI_JOB_H
#include "cli_mpi.h"
#include "iacsg.h"

typedef struct cli_job cli_job;

typedef struct {
    int frame;                /* the frame's number (0 without -frames) */
    int row_first, row_count; /* the rows to trace (iacsg_view: row_count 0 is all of them) */
} cli_job_item;

/* Plans the job for `frames` frames (0: one frame, not numbered) of width x height pixels, written to
 * outputs[0..3] (image, depth, normals, ids; NULL: not written). Call after cli_writer_start, which forks. NULL after
 * printing why when it fails. */
cli_job *cli_job_start(int frames, int width, int height, int resume, const char *const outputs[CLI_MPI_IMAGES]);

/* This process's rank (0 when run plainly): rank 0 alone prints what the job says once. */
int cli_job_rank(const cli_job *j);

/* The OpenCL device this rank uses when -device is not given: the rank's number on its node, modulo the count
 * of devices, so that the ranks of a node with several GPUs use them all. */
int cli_job_device(const cli_job *j);

/* Frees `done` (the frame of the last item, or all NULL), in band mode after handing its rows to rank 0, and
 * gives the next item; 0 when there is none left for this process (or the job stopped). */
int cli_job_next(cli_job *j, iacsg_frame *done, cli_job_item *item);

/* Whether this process writes the frames it renders (not so for bands: rank 0 writes the assembled frame). */
int cli_job_writes_frames(const cli_job *j);

/* Whether this process renders every frame alone, with no MPI job (which gathers and reports floats). */
int cli_job_alone(const cli_job *j);

/* Rank 0 of a banded frame, after the last cli_job_next: the whole frame (owned by the job), else NULL. */
const iacsg_frame *cli_job_gathered(cli_job *j);

/* Reports a failure (one line, without "iacsg: ") on `frame` (-1: before any); run plainly it is printed,
 * under mpirun rank 0 prints the first of them, naming the rank. The process takes no more items. */
void cli_job_fail(cli_job *j, int frame, const char *line);

/* Ends the job (frees it) and gives the exit status: 1 when this process (or, on rank 0, any rank) failed. */
int cli_job_end(cli_job *j);

/* "dir/name.png" as written for frame k: "dir/name_0007.png" with -frames, else itself (malloc'ed). */
char *cli_job_path(const char *path, int frames, int frame);

#endif
