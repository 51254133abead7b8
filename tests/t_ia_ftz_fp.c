/* tests/t_ia_ftz_fp.c -- ia/ built with IA_FTZ, run on the host with x86's flush-to-zero and
 * denormals-are-zero modes on (MXCSR), as a device that flushes subnormals would: containment against MPFR for
 * every op, on inputs without subnormal bounds (the precondition of IA_FTZ in ia/ia.h; the points inside may
 * be subnormal). The oracle runs with the modes off. Skipped where there is no SSE MXCSR. */
#define IA_FTZ 1
#include "ia/ia.h"
#include "oracle_ia.h"
#include <stdlib.h>
#if defined(__SSE2__) || defined(__x86_64__)
#include <pmmintrin.h>
#include <xmmintrin.h>
#define HAVE_MXCSR 1
#endif

#ifdef HAVE_MXCSR
#ifdef __GNUC__
__attribute__((noinline))
#endif
static int
eval_ftz(int op, const ia_case *k, long count, ia_real *out, char *msg, size_t size) {
    (void)msg, (void)size;
    unsigned int saved = _mm_getcsr();
    _mm_setcsr(saved | _MM_FLUSH_ZERO_ON | _MM_DENORMALS_ZERO_ON);
    for (long i = 0; i < count; i++)
        ia_apply(op, &k[i], out + 2 * i);
    _mm_setcsr(saved);
    return 0;
}
#endif

TEST_FP(ia_ftz_host) {
#ifndef HAVE_MXCSR
    test_note("no x86 MXCSR here: FTZ/DAZ host run skipped");
    return;
#else
    /* the modes really are on: a subnormal result flushes */
    {
        volatile ia_real tiny = IA_REAL_MIN_NORMAL, half = (ia_real)0.5, res;
        unsigned int saved = _mm_getcsr();
        _mm_setcsr(saved | _MM_FLUSH_ZERO_ON | _MM_DENORMALS_ZERO_ON);
        res = tiny * half;
        _mm_setcsr(saved);
        CHECK(res == 0, "FTZ is not in effect: MIN/2 = %s", oracle_hex(res));
    }
    long total = 0;
    char msg[2048];
    CHECK(!pt_check_all_ops(test_rng(), test_iters(3000), 1, eval_ftz, "host FTZ/DAZ", &total, msg, sizeof msg),
          "%s", msg);
    test_note("IA_FTZ with MXCSR FTZ+DAZ " FMT_NAME ": %ld checks over all ops, 0 violations", total);
#endif
}
