/* tests/t_mpi.c -- the render command under `mpirun -np 2` on this machine (src/cli_job.h, src/mpi/share.c):
 * frames spread over the ranks and one frame's bands gathered on rank 0 give the very files of a single process;
 * a rank that fails or is killed stops the job with one line naming the rank and the frame, leaves no partial
 * file, and -resume then finishes the job as an uninterrupted run would have. Every mpirun is bounded by
 * `timeout`, so that a hang fails the test instead of the suite. */
#include "iacsg.h"
#include "image.h"
#include "test.h"
#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

/* OpenMPI refuses root without these, and needs --oversubscribe for 2 ranks on fewer free cores; -q keeps its own
 * notices out of the output. Leak checking is off under mpirun: Open MPI's own allocations outlive
 * MPI_Finalize (the plain command's leaks are checked by the other tests). */
#define MPIRUN                                                                                                   \
    "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 ASAN_OPTIONS=detect_leaks=0 timeout 180 "         \
    "mpirun -q -np 2 --oversubscribe"

/* An animated scene: each frame differs. */
#define SCENE "'min(move(sphere(0.6), t, 0, 0), torus)'"

/* Runs `prefix iacsg args` in dir, stdout discarded and stderr into dir/stderr.txt; returns the exit status. */
static int run_in(const char *dir, const char *prefix, const char *args) {
    char cmd[2048];
    snprintf(cmd, sizeof cmd, "cd '%s' && %s '%s' %s >/dev/null 2>stderr.txt", dir, prefix, test_binary_path(), args);
    int rc = system(cmd);
    return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
}

/* Whether dir/a and dir/b hold the same bytes (both must exist). */
static int same_bytes(const char *dir, const char *a, const char *b) {
    char pa[1024], pb[1024];
    snprintf(pa, sizeof pa, "%s/%s", dir, a);
    snprintf(pb, sizeof pb, "%s/%s", dir, b);
    size_t na, nb;
    char *da = test_read_file(pa, &na), *db = test_read_file(pb, &nb);
    int same = da && db && na == nb && memcmp(da, db, na) == 0;
    free(da);
    free(db);
    return same;
}

/* Whether two float images hold the same values, bit for bit (an EXR file's header carries its time). */
static int same_pixels(const char *dir, const char *a, const char *b) {
    char pa[1024], pb[1024];
    snprintf(pa, sizeof pa, "%s/%s", dir, a);
    snprintf(pb, sizeof pb, "%s/%s", dir, b);
    int wa, ha, ca, wb, hb, cb;
    float *fa = NULL, *fb = NULL;
    iacsg_error err = {0};
    int same = iacsg_image_read(pa, &wa, &ha, &ca, &fa, &err) == IACSG_OK &&
               iacsg_image_read(pb, &wb, &hb, &cb, &fb, &err) == IACSG_OK && wa == wb && ha == hb && ca == cb &&
               memcmp(fa, fb, (size_t)wa * (size_t)ha * (size_t)ca * sizeof(float)) == 0;
    free(fa);
    free(fb);
    return same;
}

/* The lines of dir/stderr.txt that start "iacsg:", and the first of them in `first`. */
static int error_lines(const char *dir, char *first, size_t size) {
    char path[1024];
    snprintf(path, sizeof path, "%s/stderr.txt", dir);
    char *text = test_read_file(path, NULL);
    int count = 0;
    first[0] = '\0';
    for (char *line = text; line && *line;) {
        char *end = strchr(line, '\n');
        size_t len = end ? (size_t)(end - line) : strlen(line);
        if (strncmp(line, "iacsg:", 6) == 0 && count++ == 0)
            snprintf(first, size, "%.*s", (int)len, line);
        line = end ? end + 1 : line + len;
    }
    free(text);
    return count;
}

/* The names in dir other than the expected frames s_NNNN.png and m_NNNN.png, s.png and stderr.txt (a partial
 * file, a temporary one left behind): their count, and the first. */
static int stray_files(const char *dir, char *first, size_t size) {
    DIR *d = opendir(dir);
    int count = 0;
    first[0] = '\0';
    for (struct dirent *e; d && (e = readdir(d));) {
        int frame;
        char tail[8];
        if (strcmp(e->d_name, ".") == 0 || strcmp(e->d_name, "..") == 0 || strcmp(e->d_name, "stderr.txt") == 0 ||
            strcmp(e->d_name, "s.png") == 0 ||
            (sscanf(e->d_name, "%*1[sm]_%4d%7s", &frame, tail) == 2 && strcmp(tail, ".png") == 0))
            continue;
        if (count++ == 0)
            snprintf(first, size, "%s", e->d_name);
    }
    if (d)
        closedir(d);
    return count;
}

static int frame_exists(const char *dir, const char *stem, int frame) {
    char path[1024];
    snprintf(path, sizeof path, "%s/%s_%04d.png", dir, stem, frame);
    return access(path, F_OK) == 0;
}

/* Checks that the 8 frames m_NNNN.png equal s_NNNN.png. */
static void check_frames_equal(const char *dir) {
    for (int k = 0; k < 8; k++) {
        char a[32], b[32];
        snprintf(a, sizeof a, "s_%04d.png", k);
        snprintf(b, sizeof b, "m_%04d.png", k);
        CHECK(same_bytes(dir, a, b), "frame %d: %s and %s differ (or one is missing)", k, a, b);
    }
}

TEST(mpi_frames_match_single_process) {
    char dir[256];
    test_make_dir(dir, sizeof dir, "mpi-frames");
    int rc = run_in(dir, "", SCENE " -size 160x120 -frames 8 -o s.png");
    CHECK(rc == 0, "the single-process render exited with %d", rc);
    rc = run_in(dir, MPIRUN, SCENE " -size 160x120 -frames 8 -o m.png");
    CHECK(rc == 0, "mpirun -np 2 exited with %d", rc);
    check_frames_equal(dir);
    test_remove_dir(dir);
}

/* 2048 rows in bands of 256 over 2 ranks, the depth gathered too. */
TEST(mpi_bands_match_single_process) {
    char dir[256];
    test_make_dir(dir, sizeof dir, "mpi-bands");
    int rc = run_in(dir, "", "'min(sphere, torus)' -size 2048x2048 -o s.png -depth s.exr");
    CHECK(rc == 0, "the single-process render exited with %d", rc);
    rc = run_in(dir, MPIRUN, "'min(sphere, torus)' -size 2048x2048 -o m.png -depth m.exr");
    CHECK(rc == 0, "mpirun -np 2 exited with %d", rc);
    CHECK(same_bytes(dir, "s.png", "m.png"), "the image gathered from bands differs from the single-process one");
    CHECK(same_pixels(dir, "s.exr", "m.exr"), "the depth gathered from bands differs from the single-process one");
    test_remove_dir(dir);
}

/* A scene with regions (the segment path): bands of 32 rows over 2 ranks, the ids gathered too. */
TEST(mpi_scene_bands_match_single_process) {
    char dir[256], scene[512], args[1024];
    test_make_dir(dir, sizeof dir, "mpi-scene-bands");
    snprintf(scene, sizeof scene, "'%s/examples/fig2_cube_sphere_regions.csg' -size 256x256", test_source_dir());
    snprintf(args, sizeof args, "%s -o s.png -ids s.exr", scene);
    int rc = run_in(dir, "", args);
    CHECK(rc == 0, "the single-process render exited with %d", rc);
    snprintf(args, sizeof args, "%s -o m.png -ids m.exr", scene);
    rc = run_in(dir, MPIRUN, args);
    CHECK(rc == 0, "mpirun -np 2 exited with %d", rc);
    CHECK(same_bytes(dir, "s.png", "m.png"), "the image gathered from bands differs from the single-process one");
    CHECK(same_pixels(dir, "s.exr", "m.exr"), "the ids gathered from bands differ from the single-process ones");
    test_remove_dir(dir);
}

/* Rank 1 is killed (SIGKILL) when handed its first frame (the ranks start together, so it gets one): the job
 * fails with one line naming rank 1 and that frame, leaves only complete frames, and the same command with
 * -resume renders the rest, as an uninterrupted run would. */
TEST(mpi_killed_rank_then_resume) {
    char dir[256], line[512], stray[256];
    test_make_dir(dir, sizeof dir, "mpi-kill");
    int rc = run_in(dir, "", SCENE " -size 320x240 -frames 8 -o s.png");
    CHECK(rc == 0, "the single-process render exited with %d", rc);
    rc = run_in(dir, "IACSG_TEST_KILL=1:1 " MPIRUN, SCENE " -size 320x240 -frames 8 -o m.png");
    CHECK(rc != 0 && rc != 124, "a killed rank: mpirun exited with %d", rc);
    int lines = error_lines(dir, line, sizeof line);
    int frame = -1;
    const char *named = strstr(line, "rank 1 was on frame ");
    CHECK(lines == 1 && named && sscanf(named, "rank 1 was on frame %d", &frame) == 1,
          "expected one line naming rank 1 and its frame, got %d lines, the first '%s'", lines, line);
    CHECK(!frame_exists(dir, "m", frame), "the frame of the killed rank, %d, was written", frame);
    CHECK(stray_files(dir, stray, sizeof stray) == 0, "a file other than a frame was left: %s", stray);
    rc = run_in(dir, MPIRUN, SCENE " -size 320x240 -frames 8 -o m.png -resume");
    CHECK(rc == 0, "-resume exited with %d", rc);
    check_frames_equal(dir);
    test_remove_dir(dir);
}

/* A rank that cannot open its device: one line naming the rank, a failed job, no file. */
TEST(mpi_device_failure_one_line) {
    char dir[256], line[512], stray[256];
    test_make_dir(dir, sizeof dir, "mpi-fail");
    int rc = run_in(dir, MPIRUN, SCENE " -size 64x64 -frames 4 -device 99 -o m.png");
    CHECK(rc != 0 && rc != 124, "a device failure: mpirun exited with %d", rc);
    int lines = error_lines(dir, line, sizeof line);
    CHECK(lines == 1 && strstr(line, "iacsg: rank ") == line && strstr(line, " failed"),
          "expected one line naming the failed rank, got %d lines, the first '%s'", lines, line);
    CHECK(stray_files(dir, stray, sizeof stray) == 0 && !frame_exists(dir, "m", 0), "a file was left: %s", stray);
    test_remove_dir(dir);
}

/* Rank 1 killed on its first band of a frame shared in bands: no image at all (rank 0 never writes a frame with a
 * band missing), one line naming rank 1's rows; the rerun writes the whole frame. */
TEST(mpi_bands_killed_rank_leaves_no_file) {
    char dir[256], line[512], stray[256];
    test_make_dir(dir, sizeof dir, "mpi-bands-kill");
    int rc = run_in(dir, "IACSG_TEST_KILL=1:1 " MPIRUN, "'min(sphere, torus)' -size 512x512 -o m.png");
    CHECK(rc != 0 && rc != 124, "a killed rank: mpirun exited with %d", rc);
    int lines = error_lines(dir, line, sizeof line);
    CHECK(lines == 1 && strstr(line, "rank 1 was on rows "), "expected one line naming rank 1's rows, got %d, '%s'",
          lines, line);
    CHECK(stray_files(dir, stray, sizeof stray) == 0, "a file was left: %s", stray);
    rc = run_in(dir, "", "'min(sphere, torus)' -size 512x512 -o s.png");
    CHECK(rc == 0, "the single-process render exited with %d", rc);
    rc = run_in(dir, MPIRUN, "'min(sphere, torus)' -size 512x512 -o m.png -resume");
    CHECK(rc == 0 && same_bytes(dir, "s.png", "m.png"), "the rerun (exit %d) differs from the single process", rc);
    test_remove_dir(dir);
}
