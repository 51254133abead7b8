/* tests/t_clrt.c -- the OpenCL runtime's failure paths: a program that does not build is reported with its
 * build log saved to a file named in the message, and a device number that does not exist is an error. */
#include "clrt.h"
#include "test.h"
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

TEST(clrt_build_failure_saves_log) {
    clrt rt;
    iacsg_error err = {0};
    CHECK(clrt_open(&rt, 0, &err) == IACSG_OK, "no device: %s", err.message);
    const char *source = "__kernel void broken(__global float *out) { out[0] = undeclared_name; }\n";
    cl_program program = NULL;
    iacsg_status st = clrt_build(&rt, &source, 1, "", &program, &err);
    clrt_close(&rt);
    CHECK(st == IACSG_ERR_BUILD && program == NULL, "status %d", (int)st);
    const char *path = strstr(err.message, "build log in ");
    CHECK(path, "message names no log: %s", err.message);
    path += strlen("build log in ");
    FILE *f = fopen(path, "r");
    CHECK(f, "log file %s missing", path);
    char log[4096] = "";
    size_t n = fread(log, 1, sizeof log - 1, f);
    log[n] = '\0';
    fclose(f);
    unlink(path);
    CHECK(strstr(log, "undeclared_name"), "the log does not mention the error: %s", log);
    CHECK(!strchr(err.message, '\n'), "the message is not one line: %s", err.message);
}

TEST(clrt_rejects_missing_device) {
    clrt rt;
    iacsg_error err = {0};
    CHECK(clrt_open(&rt, 999, &err) == IACSG_ERR_ARG, "device 999 opened");
    CHECK(strstr(err.message, "no OpenCL device 999"), "message: %s", err.message);
}
