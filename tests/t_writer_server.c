/* tests/t_writer_server.c -- the image writer server (src/cli_writer_server.c): a second command reuses the
 * server the first started; files land where a relative path names them, with the command's umask; errors read
 * as without the server; the server holds no caller's pipe open; it ends when idle; IACSG_WRITER_IDLE=0 keeps the
 * child per command. Each test gives its commands a server of its own (LD_LIBRARY_PATH, part of the server's
 * name, set to a path that differs by test and process), so that tests running at once do not share one. */
#include "test.h"
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#define WRITER_TRACE "iacsg: image writer: "

/* Runs `args` in `dir` with the test's server (tag) and IACSG_WRITER_TRACE, after `env`; returns the exit status
 * and the writer the command got in `how`. */
static int run_traced(const char *dir, const char *tag, const char *env, const char *args, char *how, size_t size) {
    char before[512];
    snprintf(before, sizeof before, "%s LD_LIBRARY_PATH=/nonexistent-%s-%d IACSG_WRITER_TRACE=1", env, tag,
             (int)getpid());
    return test_run_traced(dir, before, args, WRITER_TRACE, how, size);
}

TEST(writer_server_reused_with_cwd_and_umask) {
    char dir[256], how[256], path[512];
    test_make_dir(dir, sizeof dir, "wserver");
    snprintf(path, sizeof path, "%s/sub", dir);
    CHECK(mkdir(path, 0755) == 0, "mkdir");
    int rc = run_traced(dir, "reuse", "", "sphere -size 8x8 -o first.png", how, sizeof how);
    CHECK(rc == 0 && strstr(how, "server (started)"), "first command: exit %d, writer %s", rc, how);
    rc = run_traced(dir, "reuse", "umask 027 &&", "sphere -size 8x8 -o sub/second.png", how, sizeof how);
    CHECK(rc == 0 && strstr(how, "server (reused)"), "second command: exit %d, writer %s", rc, how);
    struct stat st;
    snprintf(path, sizeof path, "%s/sub/second.png", dir);
    CHECK(stat(path, &st) == 0, "sub/second.png was not written in the command's directory");
    CHECK((st.st_mode & 0777) == 0640, "mode %o, expected 640 under umask 027", (unsigned)(st.st_mode & 0777));
    test_remove_dir(dir);
}

/* A refused format and a file that cannot be made: the same message with the server as with the child. */
TEST(writer_server_errors_as_child) {
    char dir[256], how[256], path[512];
    test_make_dir(dir, sizeof dir, "wserver-err");
    snprintf(path, sizeof path, "%s/taken.png", dir);
    CHECK(mkdir(path, 0755) == 0, "mkdir"); /* a directory where the image would go: the rename fails */
    const char *cases[] = {"sphere -size 8x8 -o out.nosuchformat", "sphere -size 8x8 -o taken.png"};
    for (int k = 0; k < 2; k++) {
        int rc1 = run_traced(dir, "errors", "", cases[k], how, sizeof how);
        CHECK(strstr(how, "server"), "%s: writer %s", cases[k], how);
        char *served = test_read_without(dir, "err.txt", WRITER_TRACE);
        int rc2 = run_traced(dir, "errors", "IACSG_WRITER_IDLE=0", cases[k], how, sizeof how);
        CHECK(strstr(how, "child process"), "%s: writer %s with IACSG_WRITER_IDLE=0", cases[k], how);
        char *child = test_read_without(dir, "err.txt", WRITER_TRACE);
        CHECK(rc1 == 1 && rc2 == 1, "%s: exit %d with the server, %d without", cases[k], rc1, rc2);
        int same = served && child && served[0] && strcmp(served, child) == 0;
        CHECK(same, "%s: with the server:\n%swithout:\n%s", cases[k], served ? served : "", child ? child : "");
        free(served);
        free(child);
    }
    snprintf(path, sizeof path, "%s/out.nosuchformat", dir);
    CHECK(access(path, F_OK) != 0, "a file was written for an unknown format");
    test_remove_dir(dir);
}

/* The server a command starts inside $(...) holds no end of its pipe: the shell's read ends with the command. */
TEST(writer_server_holds_no_pipe) {
    char dir[256], cmd[2048];
    test_make_dir(dir, sizeof dir, "wserver-pipe");
    snprintf(cmd, sizeof cmd,
             "cd '%s' && timeout 20 sh -c 'out=$(LD_LIBRARY_PATH=/nonexistent-pipe-%d IACSG_WRITER_IDLE=60 "
             "IACSG_WRITER_TRACE=1 %s sphere -size 8x8 -o p.png 2>&1); echo \"$out\" >out.txt'",
             dir, (int)getpid(), test_binary_path());
    int rc = system(cmd);
    CHECK(WIFEXITED(rc) && WEXITSTATUS(rc) == 0, "the captured command did not end before its server (status %d)",
          WIFEXITED(rc) ? WEXITSTATUS(rc) : -1);
    char path[512];
    snprintf(path, sizeof path, "%s/out.txt", dir);
    char *out = test_read_file(path, NULL);
    CHECK(out && strstr(out, "server (started)"), "output: %s", out ? out : "(none)");
    free(out);
    test_remove_dir(dir);
}

TEST(writer_server_idle_exit_and_disabled) {
    char dir[256], how[256];
    test_make_dir(dir, sizeof dir, "wserver-idle");
    int rc = run_traced(dir, "idle", "IACSG_WRITER_IDLE=1", "sphere -size 8x8 -o a.png", how, sizeof how);
    CHECK(rc == 0 && strstr(how, "server (started)"), "exit %d, writer %s", rc, how);
    sleep(3);
    rc = run_traced(dir, "idle", "IACSG_WRITER_IDLE=1", "sphere -size 8x8 -o b.png", how, sizeof how);
    CHECK(rc == 0 && strstr(how, "server (started)"), "after 3 s idle: exit %d, writer %s", rc, how);
    rc = run_traced(dir, "idle", "IACSG_WRITER_IDLE=0", "sphere -size 8x8 -o c.png", how, sizeof how);
    CHECK(rc == 0 && strstr(how, "child process"), "disabled: exit %d, writer %s", rc, how);
    test_remove_dir(dir);
}

/* A server killed while a command renders: the command writes the image itself, with no other difference. */
TEST(writer_server_lost_mid_command) {
    char dir[256], cmd[4096], how[256];
    test_make_dir(dir, sizeof dir, "wserver-lost");
    int rc = run_traced(dir, "lost", "", "sphere -size 8x8 -o a.png", how, sizeof how);
    CHECK(rc == 0 && strstr(how, "server"), "exit %d, writer %s", rc, how);
    snprintf(cmd, sizeof cmd,
             "cd '%s' && export LD_LIBRARY_PATH=/nonexistent-lost-%d IACSG_WRITER_TRACE=1 && "
             TEST_SH_FIND_SERVER("iacsg-writer")
             "'%s' '%s/tests/data/brlcad/havoc.asc' havoc -size 1024x1024 -o b.png >/dev/null 2>err.txt & "
             "sleep 0.3; kill $server; wait $!",
             dir, (int)getpid(), test_binary_path(), test_source_dir());
    rc = system(cmd);
    rc = WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
    char path[512];
    snprintf(path, sizeof path, "%s/err.txt", dir);
    char *err = test_read_file(path, NULL);
    snprintf(path, sizeof path, "%s/b.png", dir);
    int written = access(path, F_OK) == 0;
    CHECK(rc == 0 && written, "exit %d (3: no server found), b.png %s; stderr: %s", rc, written ? "written" : "missing",
          err ? err : "");
    CHECK(err && strstr(err, "the server was lost"), "the server was not lost before the write: %s", err ? err : "");
    free(err);
    test_remove_dir(dir);
}
