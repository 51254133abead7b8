/* tests/t_pocl_binary.c -- PoCL's program binaries without their bitcode (src/clrt_pocl.c): the stripped binary
 * builds without the LLVM IR and runs every kernel at local sizes its binary has no specialised function for; a
 * binary it does not know (other drivers', truncated, another format version, a kernel without its generic
 * function, more than one root file) is left byte for byte as it was. */
#define _GNU_SOURCE /* memmem */
#include "clrt.h"
#include "clrt_pocl.h"
#include "test.h"
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static const char *const source =
    "__kernel void answer(__global int *out) { out[0] = 6 * 7 + SALT; }\n"
    "__kernel void ids(__global int *out) { out[get_global_id(0)] = 7 * (int)get_global_id(0) + SALT; }\n";

enum { IDS = 8 };

/* Runs `ids` over IDS work-items in work-groups of `local`, then `answer`: whether every value is right. */
static int run_kernels(clrt *rt, cl_program program, size_t local, int salt) {
    cl_int rc = CL_SUCCESS, out[IDS];
    cl_kernel ids = clCreateKernel(program, "ids", &rc), answer = clCreateKernel(program, "answer", &rc);
    cl_mem buf = clCreateBuffer(rt->context, CL_MEM_WRITE_ONLY, sizeof out, NULL, &rc);
    size_t global = IDS, one = 1;
    int ok = ids && answer && buf && clSetKernelArg(ids, 0, sizeof buf, &buf) == CL_SUCCESS &&
             clSetKernelArg(answer, 0, sizeof buf, &buf) == CL_SUCCESS &&
             clEnqueueNDRangeKernel(rt->queue, ids, 1, NULL, &global, &local, 0, NULL, NULL) == CL_SUCCESS &&
             clEnqueueReadBuffer(rt->queue, buf, CL_TRUE, 0, sizeof out, out, 0, NULL, NULL) == CL_SUCCESS;
    for (int k = 0; ok && k < IDS; k++)
        ok = out[k] == 7 * k + salt;
    ok = ok && clEnqueueNDRangeKernel(rt->queue, answer, 1, NULL, &one, &one, 0, NULL, NULL) == CL_SUCCESS &&
         clEnqueueReadBuffer(rt->queue, buf, CL_TRUE, 0, sizeof out[0], out, 0, NULL, NULL) == CL_SUCCESS &&
         out[0] == 42 + salt;
    if (buf)
        clReleaseMemObject(buf);
    if (ids)
        clReleaseKernel(ids);
    if (answer)
        clReleaseKernel(answer);
    return ok;
}

/* The binary of the test's program built from source and run once with work-groups of 1, into *bin (malloc'd). */
static size_t binary_of(clrt *rt, int salt, unsigned char **bin) {
    char options[64];
    snprintf(options, sizeof options, "-D SALT=%d", salt);
    cl_int rc = CL_SUCCESS;
    size_t size = 0;
    *bin = NULL;
    cl_program p = clCreateProgramWithSource(rt->context, 1, (const char **)&source, NULL, &rc);
    if (p && clBuildProgram(p, 1, &rt->device, options, NULL, NULL) == CL_SUCCESS && run_kernels(rt, p, 1, salt) &&
        clGetProgramInfo(p, CL_PROGRAM_BINARY_SIZES, sizeof size, &size, NULL) == CL_SUCCESS && size > 0 &&
        (*bin = malloc(size)) && clGetProgramInfo(p, CL_PROGRAM_BINARIES, sizeof *bin, bin, NULL) != CL_SUCCESS) {
        free(*bin);
        *bin = NULL;
    }
    if (p)
        clReleaseProgram(p);
    return *bin ? size : 0;
}

static int is_pocl(const clrt *rt) { return strstr(rt->platform_name, "Portable Computing Language") != NULL; }

/* Whether clrt_pocl_binary_without_ir leaves a copy of the n bytes alone (the copy exactly n bytes long, so that
 * the sanitizers see a read past it). */
static int left_alone(const unsigned char *bytes, size_t n) {
    unsigned char *copy = malloc(n ? n : 1);
    if (!copy)
        return 0;
    memcpy(copy, bytes, n);
    int same = clrt_pocl_binary_without_ir(copy, n) == n && memcmp(copy, bytes, n) == 0;
    free(copy);
    return same;
}

TEST(pocl_binary_without_ir_builds_and_runs) {
    clrt rt;
    iacsg_error err = {0};
    CHECK(clrt_open(&rt, 0, &err) == IACSG_OK, "no OpenCL device: %s", err.message);
    int salt = (int)getpid() + 11; /* a program PoCL has not built, so that its cache holds nothing of it */
    unsigned char *bin = NULL;
    size_t size = binary_of(&rt, salt, &bin), stripped = bin ? clrt_pocl_binary_without_ir(bin, size) : 0;
    int pocl = is_pocl(&rt), runs = 1;
    cl_int rc = CL_SUCCESS, status = CL_SUCCESS;
    const unsigned char *bins[1] = {bin};
    cl_program p = bin ? clCreateProgramWithBinary(rt.context, 1, &rt.device, &stripped, bins, &status, &rc) : NULL;
    int built = p && rc == CL_SUCCESS && status == CL_SUCCESS &&
                clBuildProgram(p, 1, &rt.device, "", NULL, NULL) == CL_SUCCESS;
    for (size_t local = 1; built && local <= IDS; local *= 2) /* 2, 4 and 8: no specialised function */
        runs = runs && run_kernels(&rt, p, local, salt);
    int bitcode = bin && memmem(bin, stripped, "BC\xc0\xde", 4) != NULL;
    if (p)
        clReleaseProgram(p);
    free(bin);
    clrt_close(&rt);
    CHECK(size > 0, "no binary of the test's program");
    CHECK(pocl ? stripped < size : stripped == size, "%s: %zu -> %zu bytes", rt.platform_name, size, stripped);
    CHECK(!pocl || !bitcode, "the stripped binary still holds LLVM bitcode");
    CHECK(built, "the stripped binary does not build");
    CHECK(runs, "a kernel of the stripped binary computed wrong values");
    test_note("%s: %zu -> %zu bytes", rt.platform_name, size, stripped);
}

/* Writes `v` as n little-endian bytes at p. */
static void put_le(unsigned char *p, unsigned long long v, int n) {
    for (int k = 0; k < n; k++, v >>= 8)
        p[k] = (unsigned char)v;
}

TEST(pocl_binary_without_ir_leaves_other_binaries) {
    clrt rt;
    iacsg_error err = {0};
    CHECK(clrt_open(&rt, 0, &err) == IACSG_OK, "no OpenCL device: %s", err.message);
    unsigned char *bin = NULL;
    size_t size = binary_of(&rt, (int)getpid() + 12, &bin);
    int pocl = is_pocl(&rt);
    clrt_close(&rt);
    CHECK(size > 0, "no binary of the test's program");
    static const unsigned char elf[] = "\x7f" "ELF\2\1\1\0\0\0\0\0\0\0\0\0";
    CHECK(left_alone(elf, sizeof elf) && left_alone(elf, 0), "a non-PoCL binary was changed");
    if (!pocl) {
        CHECK(left_alone(bin, size), "%s's binary was changed", rt.platform_name);
        free(bin);
        return;
    }
    /* Every prefix: the header, program.bc and the kernels' records cut anywhere (each 61st past the bitcode). */
    size_t cuts = 0;
    for (size_t n = 0; n < size; n += n < 4096 || size - n < 4096 ? 1 : 61, cuts++)
        CHECK(left_alone(bin, n), "the binary cut to %zu of %zu bytes was changed", n, size);
    unsigned char *changed = malloc(size);
    CHECK(changed, "out of memory");
    memcpy(changed, bin, size);
    put_le(changed + 16, 10, 4); /* another format version */
    CHECK(left_alone(changed, size), "a binary of format 10 was changed");
    memcpy(changed, bin, size);
    put_le(changed + 32, 2, 4); /* two root entries */
    CHECK(left_alone(changed, size), "a binary of two root entries was changed");
    memcpy(changed, bin, size);
    changed[36 + 39] = 'Z'; /* a build hash PoCL does not make: stripped before */
    CHECK(left_alone(changed, size), "a binary with a foreign build hash was changed");
    memcpy(changed, bin, size);
    int renamed = 0; /* the last kernel's generic function under another name */
    for (size_t k = size; k-- > 5 && !renamed;)
        if (memcmp(changed + k - 5, "0-0-0", 5) == 0)
            changed[k - 1] = '1', renamed = 1;
    CHECK(renamed && left_alone(changed, size), "a binary with a kernel without its generic function was changed");
    size_t stripped = clrt_pocl_binary_without_ir(bin, size);
    CHECK(stripped < size && left_alone(bin, stripped), "a stripped binary was stripped again");
    free(changed);
    free(bin);
    test_note("%zu prefixes of a %zu-byte binary left alone", cuts, size);
}
