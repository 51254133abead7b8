/* src/clrt.h -- the OpenCL runtime: device choice, context and queue, program builds with the ia/ options,
 * error names. Every OpenCL call in the library goes through CLRT_CHECK, which records the error name, the
 * statement, the function and the line into an iacsg_error. */
#ifndef IACSG_CLRT_H
#define IACSG_CLRT_H
#define CL_TARGET_OPENCL_VERSION 120
#include "error.h"
#include <CL/cl.h>
#include <stddef.h>

typedef struct {
    cl_platform_id platform;
    cl_device_id device;
    cl_context context;
    cl_command_queue queue;
    char device_name[256];
    char platform_name[256];
    int has_fp64;         /* cl_khr_fp64 */
    int float_denorms;    /* CL_FP_DENORM in the single-precision config */
    int keep_subnormals;  /* 0 (clrt_open's): ia/ is built to flush subnormals, see clrt_ia_options; 1: where the
                           * device has them, kept (the ia/ tests' build for subnormal operands) */
    int cr_divide_sqrt;   /* CL_FP_CORRECTLY_ROUNDED_DIVIDE_SQRT: build with -cl-fp32-correctly-rounded-...;
                           * 0 when the environment sets IACSG_INEXACT_DIVIDE_SQRT (non-empty): then float / and
                           * sqrt are widened by the spec's bounds as on a device without them (the tests use it) */
    int compiles_at_build; /* clBuildProgram compiles the kernels (every driver seen but PoCL, which compiles at the
                            * first launch and again for a binary): a built program's binary is then free to query,
                            * so the program cache saves it at its first build (src/clrt_cache.c) */
    cl_uint compute_units;
    cl_uint float_lanes, double_lanes; /* CL_DEVICE_PREFERRED_VECTOR_WIDTH_FLOAT and _DOUBLE (a CPU's SIMD width) */
    cl_ulong global_mem_size; /* CL_DEVICE_GLOBAL_MEM_SIZE */
    cl_ulong max_alloc_size;  /* CL_DEVICE_MAX_MEM_ALLOC_SIZE: the largest single buffer */
} clrt;

/* Calls an OpenCL function returning cl_int (or checks the cl_int a create call returned through its last
 * argument: CLRT_CHECK(err, rc)); on failure records it in `err` and jumps to the label `fail`. */
#define CLRT_CHECK(err, call)                                                                                 \
    do {                                                                                                      \
        cl_int clrt_rc_ = (call);                                                                             \
        if (clrt_rc_ != CL_SUCCESS) {                                                                         \
            clrt_record((err), clrt_rc_, #call, __func__, __LINE__);                                          \
            goto fail;                                                                                        \
        }                                                                                                     \
    } while (0)

/* Records a failed OpenCL call as IACSG_ERR_OPENCL: "clFoo(...) failed: CL_OUT_OF_RESOURCES (in f, line n)". */
iacsg_status clrt_record(iacsg_error *err, cl_int rc, const char *call, const char *func, int line);

/* "CL_OUT_OF_RESOURCES" and so on; "CL_UNKNOWN_ERROR(-n)" for codes it does not know (static buffer). */
const char *clrt_error_name(cl_int rc);

/* Starts loading the OpenCL platforms (the ICD loader, PoCL and its LLVM: ~20 ms of dynamic linking on a CPU
 * device) on a thread of its own, so that a command reads and compiles its input meanwhile. The first clrt call
 * that needs a platform waits for it; clrt_warm_join waits too (call it before the process exits, forks or
 * returns from a command). Start it only after any fork whose child goes on without exec: a child forked while
 * the thread holds the dynamic loader's lock would deadlock on its next dlopen. */
void clrt_warm_start(void);
void clrt_warm_join(void);

/* Calls fn(index, platform name, device name, ctx) for each device of each platform, in the order that
 * `device_index` counts them. Returns the number of devices (0 with err set when there is no platform). */
int clrt_list_devices(void (*fn)(int index, const char *platform, const char *device, void *ctx), void *ctx,
                      iacsg_error *err);

/* Opens device number `device_index` (see clrt_list_devices): context, in-order queue, capabilities.
 * On failure nothing stays allocated. */
iacsg_status clrt_open(clrt *rt, int device_index, iacsg_error *err);
void clrt_close(clrt *rt);

/* The build options that make ia/ rigorous on this device: never fast-math; -D IA_FP64 when fp64, -D IA_FAST
 * for the fast mode, correctly rounded divide/sqrt when the device offers it, and subnormals flushed to zero
 * (-cl-denorms-are-zero -D IA_FTZ) unless rt->keep_subnormals asks to keep those the device has: a subnormal
 * operand or result costs a microcode assist on x86 CPUs (the sigmoid blend's exp rendered 15x slower with them)
 * and GPUs flush at full speed; the host hands the device no subnormal bound (ia/flush.h). And -w: the device
 * compiler's warnings are not the user's (PoCL prints their count on stderr: "664 warnings generated." at each
 * first build on a CPU without AVX-512, clang's -Wpsabi note at every function that passes the 16 lanes' vectors,
 * which PoCL accepts no option to turn off), unless IACSG_KERNEL_WARNINGS is set (non-empty): then they are kept,
 * for the tests that read them (tests/t_expr_cli.c). Writes into buf (at least 256 bytes). */
iacsg_status clrt_ia_options(const clrt *rt, int fp64, int fast, char *buf, size_t size, iacsg_error *err);

/* Builds a program from the concatenation of `count` source strings. On a build failure the log is saved to a
 * temporary file whose path is named in the message (IACSG_ERR_BUILD). */
iacsg_status clrt_build(clrt *rt, const char *const *sources, size_t count, const char *options,
                        cl_program *program, iacsg_error *err);

#endif
