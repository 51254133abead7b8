/* src/clrt.c -- see clrt.h. */
#define _XOPEN_SOURCE 700 /* sigaltstack */
#include "clrt.h"
#include "clrt_cache.h"
#include <pthread.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

const char *clrt_error_name(cl_int rc) {
    switch (rc) {
#define NAME(c) \
    case c: return #c;
        NAME(CL_SUCCESS) NAME(CL_DEVICE_NOT_FOUND) NAME(CL_DEVICE_NOT_AVAILABLE) NAME(CL_COMPILER_NOT_AVAILABLE)
        NAME(CL_MEM_OBJECT_ALLOCATION_FAILURE) NAME(CL_OUT_OF_RESOURCES) NAME(CL_OUT_OF_HOST_MEMORY)
        NAME(CL_PROFILING_INFO_NOT_AVAILABLE) NAME(CL_MEM_COPY_OVERLAP) NAME(CL_IMAGE_FORMAT_MISMATCH)
        NAME(CL_IMAGE_FORMAT_NOT_SUPPORTED) NAME(CL_BUILD_PROGRAM_FAILURE) NAME(CL_MAP_FAILURE)
        NAME(CL_MISALIGNED_SUB_BUFFER_OFFSET) NAME(CL_EXEC_STATUS_ERROR_FOR_EVENTS_IN_WAIT_LIST)
        NAME(CL_COMPILE_PROGRAM_FAILURE) NAME(CL_LINKER_NOT_AVAILABLE) NAME(CL_LINK_PROGRAM_FAILURE)
        NAME(CL_DEVICE_PARTITION_FAILED) NAME(CL_KERNEL_ARG_INFO_NOT_AVAILABLE) NAME(CL_INVALID_VALUE)
        NAME(CL_INVALID_DEVICE_TYPE) NAME(CL_INVALID_PLATFORM) NAME(CL_INVALID_DEVICE) NAME(CL_INVALID_CONTEXT)
        NAME(CL_INVALID_QUEUE_PROPERTIES) NAME(CL_INVALID_COMMAND_QUEUE) NAME(CL_INVALID_HOST_PTR)
        NAME(CL_INVALID_MEM_OBJECT) NAME(CL_INVALID_IMAGE_FORMAT_DESCRIPTOR) NAME(CL_INVALID_IMAGE_SIZE)
        NAME(CL_INVALID_SAMPLER) NAME(CL_INVALID_BINARY) NAME(CL_INVALID_BUILD_OPTIONS) NAME(CL_INVALID_PROGRAM)
        NAME(CL_INVALID_PROGRAM_EXECUTABLE) NAME(CL_INVALID_KERNEL_NAME) NAME(CL_INVALID_KERNEL_DEFINITION)
        NAME(CL_INVALID_KERNEL) NAME(CL_INVALID_ARG_INDEX) NAME(CL_INVALID_ARG_VALUE) NAME(CL_INVALID_ARG_SIZE)
        NAME(CL_INVALID_KERNEL_ARGS) NAME(CL_INVALID_WORK_DIMENSION) NAME(CL_INVALID_WORK_GROUP_SIZE)
        NAME(CL_INVALID_WORK_ITEM_SIZE) NAME(CL_INVALID_GLOBAL_OFFSET) NAME(CL_INVALID_EVENT_WAIT_LIST)
        NAME(CL_INVALID_EVENT) NAME(CL_INVALID_OPERATION) NAME(CL_INVALID_GL_OBJECT) NAME(CL_INVALID_BUFFER_SIZE)
        NAME(CL_INVALID_MIP_LEVEL) NAME(CL_INVALID_GLOBAL_WORK_SIZE) NAME(CL_INVALID_PROPERTY)
        NAME(CL_INVALID_IMAGE_DESCRIPTOR) NAME(CL_INVALID_COMPILER_OPTIONS) NAME(CL_INVALID_LINKER_OPTIONS)
        NAME(CL_INVALID_DEVICE_PARTITION_COUNT)
#undef NAME
    case -1001: return "CL_PLATFORM_NOT_FOUND_KHR";
    }
    static _Thread_local char unknown[40];
    snprintf(unknown, sizeof unknown, "CL_UNKNOWN_ERROR(%d)", (int)rc);
    return unknown;
}

iacsg_status clrt_record(iacsg_error *err, cl_int rc, const char *call, const char *func, int line) {
    int n = (int)strcspn(call, "(");
    if (call[n] != '(') /* CLRT_CHECK(err, rc) after a create call: the function is all we can name */
        return iacsg_error_set(err, IACSG_ERR_OPENCL, 0, 0, "an OpenCL call failed: %s (in %s, line %d)",
                               clrt_error_name(rc), func, line);
    return iacsg_error_set(err, IACSG_ERR_OPENCL, 0, 0, "%.*s failed: %s (in %s, line %d)", n, call,
                           clrt_error_name(rc), func, line);
}

#define MAX_PLATFORMS 16
#define MAX_DEVICES 64

static pthread_t warm_thread;
static int warm_running;

/* The loading thread. LLVM, loaded with PoCL, installs an alternate signal stack of its own on the thread that
 * loads it when the one there is smaller than it wants; a thread's exit then hands that stack to whoever set the
 * thread's first one (AddressSanitizer unmaps "its" stack there and aborts: it was LLVM's malloc'd block). The
 * thread's own alternate stack is put back before it exits; LLVM's is left as LLVM leaves it anywhere. */
static void *warm_platforms(void *unused) {
    (void)unused;
    stack_t own;
    int saved = sigaltstack(NULL, &own) == 0;
    cl_platform_id p[MAX_PLATFORMS];
    cl_uint np = 0;
    if (clGetPlatformIDs(MAX_PLATFORMS, p, &np) == CL_SUCCESS)
        for (cl_uint i = 0; i < np && i < MAX_PLATFORMS; i++) {
            cl_uint nd = 0;
            clGetDeviceIDs(p[i], CL_DEVICE_TYPE_ALL, 0, NULL, &nd);
        }
    if (saved)
        sigaltstack(&own, NULL);
    return NULL;
}

void clrt_warm_start(void) {
    if (!warm_running) /* without a thread, the platforms load when first needed, as before */
        warm_running = pthread_create(&warm_thread, NULL, warm_platforms, NULL) == 0;
}

void clrt_warm_join(void) {
    if (warm_running)
        pthread_join(warm_thread, NULL);
    warm_running = 0;
}

/* All (platform, device) pairs in index order. Returns the count, or -1 with err set. */
static int enumerate(cl_platform_id *plats, cl_device_id *devs, int max, iacsg_error *err) {
    cl_platform_id p[MAX_PLATFORMS];
    cl_uint np = 0;
    clrt_warm_join(); /* the ICD loader's first call is not meant to race another */
    cl_int rc = clGetPlatformIDs(MAX_PLATFORMS, p, &np);
    if (rc != CL_SUCCESS || np == 0) {
        const char *vendors = getenv("OCL_ICD_VENDORS");
        iacsg_error_set(err, IACSG_ERR_OPENCL, 0, 0,
                        "no OpenCL platform found (%s; OCL_ICD_VENDORS=%s); install pocl-opencl-icd or a GPU driver",
                        clrt_error_name(rc), vendors ? vendors : "unset, /etc/OpenCL/vendors");
        return -1;
    }
    int n = 0;
    for (cl_uint i = 0; i < np && n < max; i++) {
        cl_device_id d[MAX_DEVICES];
        cl_uint nd = 0;
        if (clGetDeviceIDs(p[i], CL_DEVICE_TYPE_ALL, MAX_DEVICES, d, &nd) != CL_SUCCESS)
            continue;
        for (cl_uint j = 0; j < nd && n < max; j++, n++) {
            plats[n] = p[i];
            devs[n] = d[j];
        }
    }
    if (n == 0)
        iacsg_error_set(err, IACSG_ERR_OPENCL, 0, 0, "no OpenCL device found on %u platform(s)", (unsigned)np);
    return n == 0 ? -1 : n;
}

int clrt_list_devices(void (*fn)(int, const char *, const char *, void *), void *ctx, iacsg_error *err) {
    cl_platform_id plats[MAX_DEVICES];
    cl_device_id devs[MAX_DEVICES];
    int n = enumerate(plats, devs, MAX_DEVICES, err);
    for (int i = 0; i < n; i++) {
        char pname[256] = "", dname[256] = "";
        clGetPlatformInfo(plats[i], CL_PLATFORM_NAME, sizeof pname - 1, pname, NULL);
        clGetDeviceInfo(devs[i], CL_DEVICE_NAME, sizeof dname - 1, dname, NULL);
        fn(i, pname, dname, ctx);
    }
    return n < 0 ? 0 : n;
}

iacsg_status clrt_open(clrt *rt, int device_index, iacsg_error *err) {
    memset(rt, 0, sizeof *rt);
    cl_platform_id plats[MAX_DEVICES];
    cl_device_id devs[MAX_DEVICES];
    int n = enumerate(plats, devs, MAX_DEVICES, err);
    if (n < 0)
        return IACSG_ERR_OPENCL;
    if (device_index < 0 || device_index >= n)
        return iacsg_error_set(err, IACSG_ERR_ARG, 0, 0, "no OpenCL device %d: there are %d (see 'iacsg devices')",
                               device_index, n);
    rt->platform = plats[device_index];
    rt->device = devs[device_index];
    cl_int rc = CL_SUCCESS;
    char ext[8192] = "";
    cl_device_fp_config fp = 0;
    CLRT_CHECK(err, clGetPlatformInfo(rt->platform, CL_PLATFORM_NAME, sizeof rt->platform_name - 1,
                                      rt->platform_name, NULL));
    CLRT_CHECK(err, clGetDeviceInfo(rt->device, CL_DEVICE_NAME, sizeof rt->device_name - 1, rt->device_name, NULL));
    CLRT_CHECK(err, clGetDeviceInfo(rt->device, CL_DEVICE_EXTENSIONS, sizeof ext - 1, ext, NULL));
    CLRT_CHECK(err, clGetDeviceInfo(rt->device, CL_DEVICE_SINGLE_FP_CONFIG, sizeof fp, &fp, NULL));
    CLRT_CHECK(err, clGetDeviceInfo(rt->device, CL_DEVICE_MAX_COMPUTE_UNITS, sizeof rt->compute_units,
                                    &rt->compute_units, NULL));
    CLRT_CHECK(err, clGetDeviceInfo(rt->device, CL_DEVICE_PREFERRED_VECTOR_WIDTH_FLOAT, sizeof rt->float_lanes,
                                    &rt->float_lanes, NULL));
    CLRT_CHECK(err, clGetDeviceInfo(rt->device, CL_DEVICE_PREFERRED_VECTOR_WIDTH_DOUBLE, sizeof rt->double_lanes,
                                    &rt->double_lanes, NULL));
    CLRT_CHECK(err, clGetDeviceInfo(rt->device, CL_DEVICE_GLOBAL_MEM_SIZE, sizeof rt->global_mem_size,
                                    &rt->global_mem_size, NULL));
    CLRT_CHECK(err, clGetDeviceInfo(rt->device, CL_DEVICE_MAX_MEM_ALLOC_SIZE, sizeof rt->max_alloc_size,
                                    &rt->max_alloc_size, NULL));
    rt->has_fp64 = strstr(ext, "cl_khr_fp64") != NULL;
    rt->compiles_at_build = strcmp(rt->platform_name, "Portable Computing Language") != 0;
    rt->float_denorms = (fp & CL_FP_DENORM) != 0;
    const char *inexact = getenv("IACSG_INEXACT_DIVIDE_SQRT");
    rt->cr_divide_sqrt = (fp & CL_FP_CORRECTLY_ROUNDED_DIVIDE_SQRT) != 0 && !(inexact && *inexact);
    rt->context = clCreateContext(NULL, 1, &rt->device, NULL, NULL, &rc);
    CLRT_CHECK(err, rc);
    rt->queue = clCreateCommandQueue(rt->context, rt->device, 0, &rc);
    CLRT_CHECK(err, rc);
    return IACSG_OK;
fail:
    clrt_close(rt);
    return IACSG_ERR_OPENCL;
}

void clrt_close(clrt *rt) {
    if (rt->queue)
        clReleaseCommandQueue(rt->queue);
    if (rt->context)
        clReleaseContext(rt->context);
    rt->queue = NULL;
    rt->context = NULL;
}

iacsg_status clrt_ia_options(const clrt *rt, int fp64, int fast, char *buf, size_t size, iacsg_error *err) {
    if (fp64 && !rt->has_fp64)
        return iacsg_error_set(err, IACSG_ERR_ARG, 0, 0, "device '%s' has no double precision (cl_khr_fp64)",
                               rt->device_name);
    const char *warnings = getenv("IACSG_KERNEL_WARNINGS");
    snprintf(buf, size, "-cl-std=CL1.2%s%s%s%s%s", warnings && *warnings ? "" : " -w", fp64 ? " -D IA_FP64" : "",
             fast ? " -D IA_FAST" : "",
             rt->keep_subnormals && rt->float_denorms ? "" : " -cl-denorms-are-zero -D IA_FTZ",
             rt->cr_divide_sqrt ? " -cl-fp32-correctly-rounded-divide-sqrt -D IA_CR_DIVSQRT" : "");
    return IACSG_OK;
}

/* Writes the build log to a fresh temporary file; returns 0 and its path in `path`, or -1. */
static int save_log(const char *log, char *path, size_t size) {
    const char *dir = getenv("TMPDIR");
    snprintf(path, size, "%s/iacsg-build-XXXXXX", dir && *dir ? dir : "/tmp");
    int fd = mkstemp(path);
    if (fd < 0)
        return -1;
    size_t len = strlen(log), done = 0;
    while (done < len) {
        ssize_t w = write(fd, log + done, len - done);
        if (w <= 0)
            break;
        done += (size_t)w;
    }
    close(fd);
    return done == len ? 0 : -1;
}

iacsg_status clrt_build(clrt *rt, const char *const *sources, size_t count, const char *options,
                        cl_program *program, iacsg_error *err) {
    clrt_cache_entry entry;
    clrt_cache_find(rt, sources, count, options, &entry);
    if ((*program = clrt_cache_load(rt, &entry, options)))
        return IACSG_OK;
    cl_int rc = CL_SUCCESS;
    *program = clCreateProgramWithSource(rt->context, (cl_uint)count, (const char **)sources, NULL, &rc);
    CLRT_CHECK(err, rc);
    rc = clBuildProgram(*program, 1, &rt->device, options, NULL, NULL);
    if (rc == CL_SUCCESS) {
        clrt_cache_store(&entry, *program, rt->compiles_at_build);
        return IACSG_OK;
    }
    size_t len = 0;
    clGetProgramBuildInfo(*program, rt->device, CL_PROGRAM_BUILD_LOG, 0, NULL, &len);
    char *log = malloc(len + 1);
    char path[512] = "";
    if (log && clGetProgramBuildInfo(*program, rt->device, CL_PROGRAM_BUILD_LOG, len, log, NULL) == CL_SUCCESS) {
        log[len] = '\0';
        if (save_log(log, path, sizeof path) != 0)
            path[0] = '\0';
    }
    free(log);
    clReleaseProgram(*program);
    *program = NULL;
    if (path[0])
        return iacsg_error_set(err, IACSG_ERR_BUILD, 0, 0, "OpenCL program failed to build (%s); build log in %s",
                               clrt_error_name(rc), path);
    return iacsg_error_set(err, IACSG_ERR_BUILD, 0, 0, "OpenCL program failed to build (%s); no build log",
                           clrt_error_name(rc));
fail:
    return IACSG_ERR_OPENCL;
}
