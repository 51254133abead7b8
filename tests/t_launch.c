/* tests/t_launch.c -- the launcher (src/cli_launch.c, src/cli_launch_server.c): a second command reuses the
 * launcher the first started; the launched process runs in the command's directory with its umask, environment
 * and streams, and the command ends with its exit status, or by its signal; signals sent to the command reach it;
 * a command killed outright takes its process with it; the refusals; the idle end; no pipe held. Each test gives
 * its commands a launcher of its own (LD_LIBRARY_PATH, part of the launcher's name, set to a path that differs by
 * test and process), so that tests running at once do not share one. */
#include "test.h"
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#define LAUNCH_TRACE "iacsg: launcher: "

/* Runs `args` in `dir` with the test's launcher (tag) and IACSG_LAUNCH_TRACE, after `env`; returns the exit status
 * and the launcher's first trace line in `how`. */
static int run_traced(const char *dir, const char *tag, const char *env, const char *args, char *how, size_t size) {
    char before[512];
    snprintf(before, sizeof before, "%s LD_LIBRARY_PATH=/nonexistent-launch-%s-%d IACSG_LAUNCH_TRACE=1", env, tag,
             (int)getpid());
    return test_run_traced(dir, before, args, LAUNCH_TRACE, how, size);
}

/* dir/name's text without the launcher's trace lines (the caller frees it). */
static char *untraced(const char *dir, const char *name) { return test_read_without(dir, name, LAUNCH_TRACE); }

TEST(launch_reused_with_cwd_umask_environment_and_status) {
    char dir[256], how[256], path[512];
    test_make_dir(dir, sizeof dir, "launch");
    snprintf(path, sizeof path, "%s/sub", dir);
    CHECK(mkdir(path, 0755) == 0, "mkdir");
    int rc = run_traced(dir, "reuse", "", "sphere -size 8x8 -o first.png", how, sizeof how);
    CHECK(rc == 0 && strcmp(how, "server (started)") == 0, "first command: exit %d, launcher '%s'", rc, how);
    rc = run_traced(dir, "reuse", "umask 027 && IACSG_WRITER_TRACE=1", "sphere -size 8x8 -o sub/second.png", how,
                    sizeof how);
    CHECK(rc == 0 && strcmp(how, "server (reused)") == 0,
          "second command (another environment: a process forked for it): exit %d, launcher '%s'", rc, how);
    struct stat st;
    snprintf(path, sizeof path, "%s/sub/second.png", dir);
    CHECK(stat(path, &st) == 0, "sub/second.png was not written in the command's directory");
    CHECK((st.st_mode & 0777) == 0640, "mode %o, expected 640 under umask 027", (unsigned)(st.st_mode & 0777));
    char *err = untraced(dir, "err.txt");
    CHECK(err && strstr(err, "iacsg: image writer: "), "the command's environment (IACSG_WRITER_TRACE) was not the "
          "launched process's: stderr %s", err ? err : "(none)");
    free(err);
    /* Standard output and errors, and the exit status, as when the command runs itself. */
    const char *cases[] = {"devices", "'min(sphere,' -size 8x8", "sphere -size 8x8 -o /nonexistent/x.png",
                           "sphere -size 8x8 -nosuchoption"};
    for (int k = 0; k < 4; k++) {
        int rc1 = run_traced(dir, "reuse", "", cases[k], how, sizeof how);
        CHECK(strncmp(how, "server (reused)", 15) == 0, "%s: launcher '%s'", cases[k], how);
        char *out1 = untraced(dir, "out.txt"), *err1 = untraced(dir, "err.txt");
        int rc2 = run_traced(dir, "reuse", "IACSG_LAUNCH_IDLE=0", cases[k], how, sizeof how);
        CHECK(strcmp(how, "this process (IACSG_LAUNCH_IDLE=0)") == 0, "%s: launcher '%s'", cases[k], how);
        char *out2 = untraced(dir, "out.txt"), *err2 = untraced(dir, "err.txt");
        CHECK(rc1 == rc2 && (k == 0) == (rc1 == 0), "%s: exit %d launched, %d here", cases[k], rc1, rc2);
        CHECK(out1 && out2 && strcmp(out1, out2) == 0, "%s: stdout launched:\n%s\nhere:\n%s", cases[k], out1, out2);
        CHECK(err1 && err2 && strcmp(err1, err2) == 0, "%s: stderr launched:\n%s\nhere:\n%s", cases[k], err1, err2);
        free(out1), free(err1), free(out2), free(err2);
    }
    test_remove_dir(dir);
}

/* A command's effects end with it, and each command meets the files as they are when it starts: with PoCL's cache
 * in the test's directory, that cache removed right after each command stays removed (nothing of OpenCL starts
 * between commands: PoCL's start creates it), and the next command builds in it afresh. What OpenCL reads as it
 * starts is the command's environment: PoCL's device list with POCL_DEVICES=basic. */
TEST(launch_leaves_nothing_running_between_commands) {
    char dir[256], how[256], env[384], cache[300], cmd[320];
    test_make_dir(dir, sizeof dir, "launch-between");
    snprintf(cache, sizeof cache, "%s/pocl", dir);
    snprintf(env, sizeof env, "POCL_CACHE_DIR='%s'", cache);
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", cache);
    struct stat st;
    for (int k = 0; k < 3; k++) { /* `devices` starts PoCL's devices; the render builds in PoCL's cache */
        int rc = run_traced(dir, "between", env, k < 2 ? "devices" : "sphere -size 8x8 -o a.png", how, sizeof how);
        CHECK(rc == 0 && strcmp(how, k ? "server (reused)" : "server (started)") == 0,
              "command %d (PoCL's cache removed before it: %s): exit %d, launcher '%s'", k, k ? "yes" : "no", rc,
              how);
        CHECK(stat(cache, &st) == 0, "command %d: PoCL made no cache in %s", k, cache);
        CHECK(system(cmd) == 0, "command %d: the cache could not be removed right after the command", k);
        nanosleep(&(struct timespec){0, 500000000}, NULL);
        CHECK(stat(cache, &st) != 0, "command %d: PoCL's cache came back after the command ended", k);
    }
    for (int k = 0; k < 2; k++) {
        int rc = run_traced(dir, "between", "POCL_DEVICES=basic", "devices", how, sizeof how);
        char *out = untraced(dir, "out.txt");
        CHECK(rc == 0 && strcmp(how, "server (reused)") == 0 && out && strstr(out, "0: basic"),
              "POCL_DEVICES=basic: exit %d, launcher '%s', devices:\n%s", rc, how, out ? out : "(none)");
        free(out);
    }
    test_remove_dir(dir);
}

/* A long render in the background (after `prefix`: env --default-signal=INT, or nothing: a background command of
 * sh ignores SIGINT), sent `signals` in turn half a second apart once its launched process runs. The report:
 * "status N children M", M the commands' processes the launcher has a second later. Exit 3: no launcher found; 4:
 * the command's process never showed. */
static void signal_command(const char *dir, const char *prefix, const char *signals, char *report, size_t size) {
    char cmd[4096], path[512];
    snprintf(cmd, sizeof cmd,
             "cd '%s' && export LD_LIBRARY_PATH=/nonexistent-launch-sig-%d IACSG_LAUNCH_TRACE=1 && "
             "'%s' sphere -size 8x8 -o warm.png >/dev/null 2>&1; "
             TEST_SH_FIND_SERVER("iacsg-launch")
             "%s '%s' 'min(sphere,torus)' -size 2048x2048 -frames 200 -o long.png >/dev/null 2>err.txt & c=$!; "
             "for i in $(seq 100); do [ -n \"$(pgrep -x -P $server iacsg)\" ] && break; sleep 0.05; done; "
             "[ -n \"$(pgrep -x -P $server iacsg)\" ] || { kill -KILL $c; exit 4; }; "
             "for s in %s; do kill -$s $c; sleep 0.5; done; wait $c; s=$?; sleep 1; "
             "echo \"status $s children $(pgrep -x -P $server iacsg | wc -l)\" >report.txt",
             dir, (int)getpid(), test_binary_path(), prefix, test_binary_path(), signals);
    int rc = system(cmd);
    snprintf(path, sizeof path, "%s/report.txt", dir);
    char *text = test_read_file(path, NULL);
    snprintf(report, size, "exit %d: %s", WIFEXITED(rc) ? WEXITSTATUS(rc) : -1, text ? text : "(no report)");
    report[strcspn(report, "\n")] = '\0';
    free(text);
}

/* No file but whole frames: a temporary image left behind would be a partial one. */
static int only_whole_frames(const char *dir) {
    char cmd[1024];
    snprintf(cmd, sizeof cmd, "cd '%s' && ls | grep -v -x -e 'long_[0-9]*\\.png' -e warm.png -e err.txt "
             "-e report.txt -e out.txt | grep -q .", dir);
    return system(cmd) != 0;
}

TEST(launch_relays_signals) {
    char dir[256], report[512];
    test_make_dir(dir, sizeof dir, "launch-sig");
    const char *cases[][3] = {
        {"env --default-signal=INT", "INT", "exit 0: status 130 children 0"}, /* 130: ended by SIGINT */
        {"", "INT TERM", "exit 0: status 143 children 0"}, /* SIGINT ignored, as the command ignores it */
        {"", "HUP", "exit 0: status 129 children 0"},
        {"", "KILL", "exit 0: status 137 children 0"}, /* the launched process ends with its command */
    };
    for (int k = 0; k < 4; k++) {
        signal_command(dir, cases[k][0], cases[k][1], report, sizeof report);
        CHECK(strcmp(report, cases[k][2]) == 0, "%s kill -%s: %s, expected %s", cases[k][0], cases[k][1], report,
              cases[k][2]);
    }
    CHECK(only_whole_frames(dir), "a signal left a file behind");
    test_remove_dir(dir);
}

TEST(launch_refusals_and_idle_end) {
    char dir[256], how[256];
    test_make_dir(dir, sizeof dir, "launch-idle");
    int rc = run_traced(dir, "idle", "IACSG_LAUNCH_IDLE=1", "sphere -size 8x8 -o a.png", how, sizeof how);
    CHECK(rc == 0 && strcmp(how, "server (started)") == 0, "exit %d, launcher '%s'", rc, how);
    sleep(3);
    rc = run_traced(dir, "idle", "IACSG_LAUNCH_IDLE=1", "sphere -size 8x8 -o b.png", how, sizeof how);
    CHECK(rc == 0 && strcmp(how, "server (started)") == 0, "after 3 s idle: exit %d, launcher '%s'", rc, how);
    rc = run_traced(dir, "idle", "", "sphere -size 8x8 -o c.png <&-", how, sizeof how);
    CHECK(rc == 0 && strcmp(how, "this process (a standard stream is closed)") == 0, "exit %d, launcher '%s'", rc,
          how);
    rc = run_traced(dir, "idle", "", "compile sphere", how, sizeof how);
    CHECK(rc == 0 && !how[0], "compile needs no launcher: exit %d, launcher '%s'", rc, how);
    test_remove_dir(dir);
}

/* The launcher a command starts inside $(...) holds no end of its pipe: the shell's read ends with the command. */
TEST(launch_holds_no_pipe) {
    char dir[256], cmd[2048], path[512];
    test_make_dir(dir, sizeof dir, "launch-pipe");
    snprintf(cmd, sizeof cmd,
             "cd '%s' && timeout 20 sh -c 'out=$(LD_LIBRARY_PATH=/nonexistent-launch-pipe-%d IACSG_LAUNCH_IDLE=60 "
             "IACSG_LAUNCH_TRACE=1 %s devices 2>&1); echo \"$out\" >out.txt'",
             dir, (int)getpid(), test_binary_path());
    int rc = system(cmd);
    CHECK(WIFEXITED(rc) && WEXITSTATUS(rc) == 0, "the captured command did not end before its launcher (status %d)",
          WIFEXITED(rc) ? WEXITSTATUS(rc) : -1);
    snprintf(path, sizeof path, "%s/out.txt", dir);
    char *out = test_read_file(path, NULL);
    CHECK(out && strstr(out, "server (started)") && strstr(out, "0: "), "output: %s", out ? out : "(none)");
    free(out);
    test_remove_dir(dir);
}
