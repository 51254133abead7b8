/* tests/t_ia_device_fp.c -- ia/ on the OpenCL device: the device runner shared by the ia tests (declared in
 * tests/oracle_ia.h; ia_dev_ops_in, for builds with extra options such as ia/vec.h's -D IA_VW, is declared in
 * tests/t_ia_vec_device_fp.c, its only user), the device's ulp errors for the built-ins ia/ uses (checked against the
 * IA_ULP_* table for the device in ia/round.h), the proof that the checker catches the fast mode (IA_FAST), whose
 * unwidened bounds must show violations while the rigorous build shows none, and the build that keeps subnormals.
 * The renderer's build (mode 0, clrt_ia_options) flushes them: the tests give it their cases as case_flushed
 * makes them, the inputs such a device must be given. */
#include "clrt.h"
#include "ia/ia.h"
#include "oracle_ia.h"
#include <stdlib.h>
#include <string.h>
#include <time.h>

extern const char iacsg_cl_ia[], iacsg_cl_tests[];

/* The precision this twin is compiled for (the device programs are built to match). */
#ifdef IA_FP64
enum { TWIN_FP64 = 1 };
#else
enum { TWIN_FP64 = 0 };
#endif

static struct {
    int tried, ok;
    clrt rt;
    cl_program prog[3]; /* modes: 0 rigorous, 1 fast (IA_FAST), 2 rigorous keeping subnormals (built on demand) */
    cl_kernel ops[3], bench[3], fns;
    char options[3][512];
    char describe[3][1400];
    char err[1024];
} dev;


/* "#define IA_OP_ADD 0" ... from the op list of tests/oracle.h, so host and device number the ops alike. */
static const char *prelude(void) {
    static char s[4096];
    if (s[0])
        return s;
    size_t len = 0;
#define X(NAME, name, kind)                                                                                            \
    len += (size_t)snprintf(s + len, sizeof s - len, "#define IA_OP_" #NAME " %d\n", ORACLE_##NAME);
    ORACLE_OPS(X)
#undef X
    static const char *tests[] = {"SIN_COS_SIN", "SIN_COS_COS", "ADD_NN", "ADD_R_NN",
                                  "MUL_NN",      "MUL_R_NN",    "MUL_N",  "SQR_NN"};
    for (int i = 0; i < (int)(sizeof tests / sizeof tests[0]); i++)
        len += (size_t)snprintf(s + len, sizeof s - len, "#define IA_TEST_%s %d\n", tests[i], IA_TEST_SIN_COS_SIN + i);
    static const char *fns[] = {"DIV", "SQRT", "EXP", "LOG", "SIN", "COS", "TAN", "ATAN", "POW"};
    for (int i = 0; i < ORACLE_NFNS; i++)
        len += (size_t)snprintf(s + len, sizeof s - len, "#define IA_FN_%s %d\n", fns[i], i);
    return s;
}

/* Builds the test program in a mode (see dev.prog) with `extra` options (or NULL) after the mode's; the options
 * used are left in opt. */
static int build_program(int mode, int fp64, const char *extra, char *opt, size_t opt_size, cl_program *prog, char *err,
                         size_t size) {
    iacsg_error e = {0};
    const char *src[3] = {iacsg_cl_ia, prelude(), iacsg_cl_tests};
    dev.rt.keep_subnormals = mode == 2;
    iacsg_status st = clrt_ia_options(&dev.rt, fp64, mode == 1, opt, opt_size, &e);
    dev.rt.keep_subnormals = 0;
    if (st != IACSG_OK) {
        snprintf(err, size, "clrt_ia_options: %s", e.message);
        return -1;
    }
    if (extra && *extra)
        snprintf(opt + strlen(opt), opt_size - strlen(opt), " %s", extra);
    if (clrt_build(&dev.rt, src, 3, opt, prog, &e) != IACSG_OK) {
        snprintf(err, size, "building the ia/ test program (%s): %s", opt, e.message);
        return -1;
    }
    return 0;
}

static void describe_build(char *out, size_t size, const char *opt) { /* out may be in dev: format aside */
    char names[1400];
    snprintf(names, sizeof names, "%s / %s (%s)", dev.rt.platform_name, dev.rt.device_name, opt);
    snprintf(out, size, "%s", names);
}

/* Builds the test program in one mode (see dev.prog). */
static int build_mode(int mode, int fp64, char *err, size_t size) {
    cl_int rc = CL_SUCCESS;
    if (build_program(mode, fp64, NULL, dev.options[mode], sizeof dev.options[mode], &dev.prog[mode], err, size))
        return -1;
    dev.ops[mode] = clCreateKernel(dev.prog[mode], "ia_test_ops", &rc);
    if (rc == CL_SUCCESS)
        dev.bench[mode] = clCreateKernel(dev.prog[mode], "ia_bench_ops", &rc);
    if (rc == CL_SUCCESS && mode == 0)
        dev.fns = clCreateKernel(dev.prog[mode], "ia_test_fns", &rc);
    if (rc != CL_SUCCESS) {
        snprintf(err, size, "clCreateKernel: %s", clrt_error_name(rc));
        return -1;
    }
    describe_build(dev.describe[mode], sizeof dev.describe[mode], dev.options[mode]);
    return 0;
}

static int dev_open(char *err, size_t size) {
    if (dev.tried) {
        if (!dev.ok)
            snprintf(err, size, "%s", dev.err);
        return dev.ok ? 0 : -1;
    }
    dev.tried = 1;
    iacsg_error e = {0};
    const char *idx = getenv("IACSG_DEVICE");
    if (clrt_open(&dev.rt, idx ? atoi(idx) : 0, &e) != IACSG_OK) {
        snprintf(dev.err, sizeof dev.err, "no OpenCL device for the ia/ tests: %s", e.message);
        snprintf(err, size, "%s", dev.err);
        return -1;
    }
    for (int mode = 0; mode < 2; mode++)
        if (build_mode(mode, TWIN_FP64, dev.err, sizeof dev.err)) {
            snprintf(err, size, "%s", dev.err);
            return -1;
        }
    dev.ok = 1;
    return 0;
}

const char *FP_NAME(ia_dev_describe)(int mode) { return dev.describe[mode >= 0 && mode < 3 ? mode : 0]; }

/* Runs kernel k over `items` work items with the given buffers (inputs copied in, `out` read back). */
typedef struct {
    const void *data;
    size_t size;
    int is_output;
    int is_scalar_int; /* passed by value: *(const int *)data */
} karg;

static int run_kernel(cl_kernel k, const karg *args, int nargs, size_t items, void *out, size_t out_size,
                      double *seconds, char *err, size_t size) {
    cl_mem mem[8] = {0};
    cl_mem out_mem = NULL;
    cl_int rc = CL_SUCCESS;
    int status = -1;
    for (int i = 0; i < nargs; i++) {
        if (args[i].is_scalar_int) {
            rc = clSetKernelArg(k, (cl_uint)i, sizeof(int), args[i].data);
        } else {
            cl_mem_flags fl = args[i].is_output ? CL_MEM_WRITE_ONLY : (CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR);
            mem[i] =
                clCreateBuffer(dev.rt.context, fl, args[i].size, args[i].is_output ? NULL : (void *)args[i].data, &rc);
            if (rc != CL_SUCCESS)
                goto done;
            if (args[i].is_output)
                out_mem = mem[i];
            rc = clSetKernelArg(k, (cl_uint)i, sizeof(cl_mem), &mem[i]);
        }
        if (rc != CL_SUCCESS)
            goto done;
    }
    struct timespec t0, t1;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    rc = clEnqueueNDRangeKernel(dev.rt.queue, k, 1, NULL, &items, NULL, 0, NULL, NULL);
    if (rc == CL_SUCCESS)
        rc = clFinish(dev.rt.queue);
    clock_gettime(CLOCK_MONOTONIC, &t1);
    if (seconds)
        *seconds = (double)(t1.tv_sec - t0.tv_sec) + (double)(t1.tv_nsec - t0.tv_nsec) * 1e-9;
    if (rc == CL_SUCCESS)
        rc = clEnqueueReadBuffer(dev.rt.queue, out_mem, CL_TRUE, 0, out_size, out, 0, NULL, NULL);
    if (rc == CL_SUCCESS)
        status = 0;
done:
    if (status)
        snprintf(err, size, "OpenCL: %s", clrt_error_name(rc));
    for (int i = 0; i < nargs; i++)
        if (mem[i])
            clReleaseMemObject(mem[i]);
    return status;
}

static void pack(const ia_case *k, long count, ia_real *in, int *n) {
    for (long i = 0; i < count; i++) {
        in[5 * i] = k[i].a.lo, in[5 * i + 1] = k[i].a.hi, in[5 * i + 2] = k[i].b.lo, in[5 * i + 3] = k[i].b.hi;
        in[5 * i + 4] = k[i].c;
        n[i] = k[i].n;
    }
}

/* The cases on kernel k (the arguments of ia_test_ops), `lanes` cases per work item. */
static int run_ops(cl_kernel kern, int lanes, int op, const ia_case *k, long count, ia_real *out, char *err,
                   size_t size) {
    if (lanes < 1 || count % lanes) {
        snprintf(err, size, "%ld cases do not fill work items of %d", count, lanes);
        return -1;
    }
    ia_real *in = malloc(sizeof *in * 5 * (size_t)count);
    int *n = malloc(sizeof *n * (size_t)count);
    if (!in || !n) {
        free(in), free(n);
        snprintf(err, size, "out of memory");
        return -1;
    }
    pack(k, count, in, n);
    karg args[] = {{&op, sizeof op, 0, 1},
                   {in, sizeof *in * 5 * (size_t)count, 0, 0},
                   {n, sizeof *n * (size_t)count, 0, 0},
                   {NULL, sizeof *out * 2 * (size_t)count, 1, 0}};
    int rc = run_kernel(kern, args, 4, (size_t)(count / lanes), out, sizeof *out * 2 * (size_t)count, NULL, err, size);
    free(in), free(n);
    return rc;
}

int FP_NAME(ia_dev_ops)(int mode, int op, const ia_case *k, long count, ia_real *out, char *err, size_t size) {
    if (dev_open(err, size))
        return -1;
    if (mode < 0 || mode > 2)
        mode = 0;
#ifdef IA_FP64
    if (!dev.prog[mode] && build_mode(mode, 1, err, size))
        return -1;
#else
    if (!dev.prog[mode] && build_mode(mode, 0, err, size))
        return -1;
#endif
    return run_ops(dev.ops[mode], 1, op, k, count, out, err, size);
}

/* Programs built with extra options (tests/t_ia_vec_device_fp.c), once per mode and options, kept for the run. */
static struct {
    int mode;
    char extra[128], describe[1400];
    cl_program prog;
} built[8];
static int nbuilt;

static int find_built(int mode, const char *extra, char *err, size_t size) {
    if (dev_open(err, size))
        return -1;
    if (mode < 0 || mode > 2)
        mode = 0;
    for (int i = 0; i < nbuilt; i++)
        if (built[i].mode == mode && !strcmp(built[i].extra, extra))
            return i;
    if (nbuilt == (int)(sizeof built / sizeof built[0]) || strlen(extra) >= sizeof built[0].extra) {
        snprintf(err, size, "too many test program builds, or options too long: %s", extra);
        return -1;
    }
    char opt[512];
    if (build_program(mode, TWIN_FP64, extra, opt, sizeof opt, &built[nbuilt].prog, err, size))
        return -1;
    built[nbuilt].mode = mode;
    snprintf(built[nbuilt].extra, sizeof built[nbuilt].extra, "%s", extra);
    describe_build(built[nbuilt].describe, sizeof built[nbuilt].describe, opt);
    return nbuilt++;
}

/* ia_dev_ops on the kernel named `kernel` (with ia_test_ops's arguments), `lanes` cases per work item, in the
 * program built in `mode` with `extra` options after the mode's. */
int FP_NAME(ia_dev_ops_in)(int mode, const char *extra, const char *kernel, int lanes, int op, const ia_case *k,
                           long count, ia_real *out, char *err, size_t size) {
    int b = find_built(mode, extra, err, size);
    if (b < 0)
        return -1;
    cl_int rc = CL_SUCCESS;
    cl_kernel kern = clCreateKernel(built[b].prog, kernel, &rc);
    if (rc != CL_SUCCESS) {
        snprintf(err, size, "clCreateKernel %s: %s", kernel, clrt_error_name(rc));
        return -1;
    }
    int status = run_ops(kern, lanes, op, k, count, out, err, size);
    clReleaseKernel(kern);
    return status;
}

int FP_NAME(ia_dev_flushes)(int mode) {
    char err[1024];
    int b = mode == 2 ? find_built(2, "", err, sizeof err) : dev_open(err, sizeof err);
    if (b < 0)
        return 1; /* no device: the callers' device calls fail and say why */
    return strstr(mode == 2 ? built[b].describe : dev.options[mode == 1], "IA_FTZ") != NULL;
}

const char *FP_NAME(ia_dev_describe_in)(int mode, const char *extra) {
    for (int i = 0; i < nbuilt; i++)
        if (built[i].mode == mode && !strcmp(built[i].extra, extra))
            return built[i].describe;
    return "(not built)";
}

int FP_NAME(ia_dev_fns)(int fn, const ia_real *x, const ia_real *y, long count, ia_real *out, char *err, size_t size) {
    if (dev_open(err, size))
        return -1;
    karg args[] = {{&fn, sizeof fn, 0, 1},
                   {x, sizeof *x * (size_t)count, 0, 0},
                   {y, sizeof *y * (size_t)count, 0, 0},
                   {NULL, sizeof *out * (size_t)count, 1, 0}};
    return run_kernel(dev.fns, args, 4, (size_t)count, out, sizeof *out * (size_t)count, NULL, err, size);
}

int FP_NAME(ia_dev_bench)(int fast, int op, int reps, const ia_case *k, long count, long items, double *seconds,
                          char *err, size_t size) {
    if (dev_open(err, size))
        return -1;
    ia_real *in = malloc(sizeof *in * 5 * (size_t)count), *out = malloc(sizeof *out * (size_t)items);
    int *n = malloc(sizeof *n * (size_t)count);
    int cnt = (int)count, rc = -1;
    if (in && n && out) {
        pack(k, count, in, n);
        karg args[] = {{&op, sizeof op, 0, 1},
                       {&reps, sizeof reps, 0, 1},
                       {&cnt, sizeof cnt, 0, 1},
                       {in, sizeof *in * 5 * (size_t)count, 0, 0},
                       {n, sizeof *n * (size_t)count, 0, 0},
                       {NULL, sizeof *out * (size_t)items, 1, 0}};
        rc = run_kernel(dev.bench[fast ? 1 : 0], args, 6, (size_t)items, out, sizeof *out * (size_t)items, seconds, err,
                        size);
    } else {
        snprintf(err, size, "out of memory");
    }
    free(in), free(n), free(out);
    return rc;
}

int FP_NAME(ia_dev_ulp_table)(int *out, char *err, size_t size) {
    if (dev_open(err, size))
        return -1;
    cl_int rc = CL_SUCCESS;
    cl_kernel k = clCreateKernel(dev.prog[0], "ia_test_ulp_table", &rc);
    if (rc != CL_SUCCESS) {
        snprintf(err, size, "clCreateKernel: %s", clrt_error_name(rc));
        return -1;
    }
    karg args[] = {{NULL, sizeof(int) * (ORACLE_NFNS + 2), 1, 0}};
    int status = run_kernel(k, args, 1, 1, out, sizeof(int) * (ORACLE_NFNS + 2), NULL, err, size);
    clReleaseKernel(k);
    return status;
}

/* ---- the device's math built-ins against MPFR */

TEST_FP(ia_device_ulps) {
    char err[1024];
    int table[ORACLE_NFNS + 2];
    CHECK(FP_NAME(ia_dev_ulp_table)(table, err, sizeof err) == 0, "%s", err);
    test_note("device %s", FP_NAME(ia_dev_describe)(0));
    long count = test_iters(40000);
    ia_real *x = malloc(sizeof *x * (size_t)count), *y = malloc(sizeof *y * (size_t)count),
            *res = malloc(sizeof *res * (size_t)count);
    CHECK(x && y && res, "out of memory");
    ulp_report rep = {.bad = -1};
    int ftz = FP_NAME(ia_dev_flushes)(0);
    for (int fn = 0; fn < ORACLE_NFNS; fn++) {
        test_rng_t *r = test_rng();
        for (long i = 0; i < count; i++) {
            fn_args(fn, r, &x[i], &y[i]);
            if (ftz)
                x[i] = real_flushed(x[i]), y[i] = real_flushed(y[i]);
        }
        if (FP_NAME(ia_dev_fns)(fn, x, y, count, res, err, sizeof err)) {
            free(x), free(y), free(res);
            CHECK(0, "%s", err);
        }
        ulp_report_add(&rep, fn, table[fn], x, y, res, count, ftz);
    }
    free(x), free(y), free(res);
    ULP_REPORT_FINISH(rep, "device");
}

/* ---- ia_sin_cos: one argument reduction for both, the same bounds as ia_sin and ia_cos (checked against MPFR by
 * ia_op_sin and ia_op_cos), bit for bit: narrow intervals (ia/elem.h's midpoint way), wide ones, ones near a zero
 * of either (where the midpoint way gives way to the end points), past the double reduction's range, points, empty
 * and unbounded ones. */

/* The cases (count >= 3) in a calloc'ed array, and room for four results of each in out[0..3] (malloc'ed; all NULL
 * out of memory), for the tests of ia_sin_cos and of iav_sin_cos (tests/t_ia_vec_device_fp.c). */
ia_case *FP_NAME(ia_sin_cos_cases)(long count, ia_real *out[4]) {
    ia_case *k = calloc((size_t)count, sizeof *k);
    int ok = k != NULL;
    for (int j = 0; j < 4; j++)
        ok &= (out[j] = malloc(sizeof *out[j] * 2 * (size_t)count)) != NULL;
    if (!ok) {
        free(k), free(out[0]), free(out[1]), free(out[2]), free(out[3]);
        out[0] = out[1] = out[2] = out[3] = NULL;
        return NULL;
    }
    test_rng_t *r = test_rng();
    for (long i = 0; i < count; i++) {
        double centre = (test_rand_unit(r) * 2 - 1) * (i % 5 == 4 ? 0x1p21 : i % 5 == 3 ? 20 : 1e3);
        if (i % 7 == 0) /* near a multiple of pi/2: a zero of sin or cos */
            centre = (double)(long)(centre / 1.5707963267948966) * 1.5707963267948966 +
                     (test_rand_unit(r) - 0.5) * 1e-5;
        double half = i % 3 == 0 ? 0 : pow(2, -30 + 34 * test_rand_unit(r)); /* 2^-30 .. 16 */
        k[i].a = ia_make((ia_real)(centre - half), (ia_real)(centre + half));
    }
    k[0].a = ia_empty();
    k[1].a = ia_make(-IA_INF, 1);
    k[2].a = ia_entire();
    return k;
}

/* The bounds of the pair's sin (out[2]) and cos (out[3]) whose bits differ from sin's (out[0]) and cos's (out[1]); the
 * first one's case in *first where that is still -1. */
long FP_NAME(ia_sin_cos_differ)(ia_real *const out[4], long count, long *first) {
    long differ = 0;
    for (long i = 0; i < 2 * count; i++)
        for (int j = 0; j < 2; j++)
            if (memcmp(&out[j][i], &out[j + 2][i], sizeof(ia_real)) != 0 && differ++ == 0 && *first < 0)
                *first = i / 2;
    return differ;
}

TEST_FP(ia_device_sin_cos) {
    char err[1024];
    long count = test_iters(20000), first = -1, differ = 0;
    ia_real *out[4];
    ia_case *k = FP_NAME(ia_sin_cos_cases)(count, out);
    CHECK(k, "out of memory");
    const int ops[4] = {ORACLE_SIN, ORACLE_COS, IA_TEST_SIN_COS_SIN, IA_TEST_SIN_COS_COS};
    int failed = 0;
    for (int j = 0; j < 4 && !failed; j++)
        failed = FP_NAME(ia_dev_ops)(0, ops[j], k, count, out[j], err, sizeof err) != 0;
    if (!failed)
        differ = FP_NAME(ia_sin_cos_differ)(out, count, &first);
    ia_interval a = first >= 0 ? k[first].a : ia_empty();
    free(k), free(out[0]), free(out[1]), free(out[2]), free(out[3]);
    CHECK(!failed, "%s", err);
    CHECK(differ == 0, "%ld bounds of ia_sin_cos differ from ia_sin's or ia_cos's, first for [%a, %a]", differ,
          (double)a.lo, (double)a.hi);
    test_note("%ld intervals, sin and cos alike", count);
}

/* ---- the checker catches the fast mode */

TEST_FP(ia_device_fast_caught) {
    test_rng_t *r = test_rng();
    long count = test_iters(4000);
    const int np = 10;
    ia_case *k = malloc(sizeof *k * (size_t)count);
    ia_real *rig = malloc(sizeof *rig * 2 * (size_t)count), *fast = malloc(sizeof *fast * 2 * (size_t)count);
    CHECK(k && rig && fast, "out of memory");
    pt_t p[PT_MAX];
    pt_init(p, np);
    char msg[2048], line[2048] = "", first[2048] = "";
    size_t len = 0;
    long total_fast = 0, total_rig = 0, checks = 0, nops = 0;
    int saved_ftz = pt_ftz;
    pt_ftz = FP_NAME(ia_dev_flushes)(0); /* the fast build's options are the rigorous one's and IA_FAST */
    for (int op = 0; op < ORACLE_NOPS; op++) {
        int kind = oracle_op_kind[op];
        if (!(kind == ORACLE_K_UN || kind == ORACLE_K_BIN || kind == ORACLE_K_POWN || kind == ORACLE_K_REAL))
            continue;
        nops++;
        for (long i = 0; i < count; i++)
            k[i] = gen_case(r, pt_ftz ? GEN_NO_SUBNORMAL : 0);
        if (FP_NAME(ia_dev_ops)(0, op, k, count, rig, msg, sizeof msg) ||
            FP_NAME(ia_dev_ops)(1, op, k, count, fast, msg, sizeof msg)) {
            pt_ftz = saved_ftz;
            pt_clear(p, np);
            free(k), free(rig), free(fast);
            CHECK(0, "%s", msg);
        }
        long vf = 0, vr = 0, c0 = 0;
        for (long i = 0; i < count; i++) {
            pt_draw(op, &k[i], p, np, r);
            if (pt_check(op, &k[i], p, np, fast + 2 * i, "fast device", msg, sizeof msg, &c0)) {
                if (!vf && !first[0])
                    snprintf(first, sizeof first, "%s", msg);
                vf++;
            }
            vr += pt_check(op, &k[i], p, np, rig + 2 * i, "device", msg, sizeof msg, &checks);
        }
        total_fast += vf, total_rig += vr;
        if (vf)
            len += (size_t)snprintf(line + len, sizeof line - len, " %s %ld", oracle_op_name[op], vf);
    }
    pt_ftz = saved_ftz;
    pt_clear(p, np);
    free(k), free(rig), free(fast);
    test_note("fast mode (IA_FAST) " FMT_NAME ": %ld of %ld cases violate containment; rigorous: %ld", total_fast,
              count * nops, total_rig);
    test_note("fast violations per op:%s", line);
    test_note("first: %.400s", first);
    CHECK(total_rig == 0, "the rigorous build violated containment in %ld cases", total_rig);
    CHECK(total_fast > 0, "the checker found no violation in the fast build: it cannot see a 1-ulp slip");
}

/* ---- the build that keeps subnormals (ia/ as a program that does not flush them builds it) stays rigorous on
 * subnormal operands too, where the device has them */

static int device_kept_eval(int op, const ia_case *k, long count, ia_real *out, char *msg, size_t size) {
    return FP_NAME(ia_dev_ops)(2, op, k, count, out, msg, size);
}

TEST_FP(ia_device_subnormals_kept) {
    long checks = 0;
    char msg[2048];
    int ftz = FP_NAME(ia_dev_flushes)(2);
    CHECK(!pt_check_all_ops(test_rng(), test_iters(2000), ftz, device_kept_eval, "device", &checks, msg, sizeof msg),
          "%s", msg);
    test_note("%s: %ld checks over all ops%s, 0 violations", FP_NAME(ia_dev_describe_in)(2, ""), checks,
              ftz ? " (the device has no subnormals: without subnormal bounds)" : ", subnormal bounds among them");
}
