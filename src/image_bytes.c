/* src/image_bytes.c -- see image_bytes.h. */
#include "image_bytes.h"
#ifdef __SSE2__
#include <emmintrin.h>
#endif

/* Floats to 8 bits as OpenImageIO converts them (clamped to [0, 1], rounded to nearest; NaN gives 0): done
 * here, in the copy to shared memory; in the writer it was ~14 ms of each frame's write. The loop below is not
 * vectorised by the compiler (4.4 ms for a 1024x1024 frame's 3M floats on the Intel Xeon at 2.1 GHz); SSE2, 16
 * floats a step, takes 1.2 ms with the same bytes: max(v, 0) gives 0 for NaN as the comparison does, the product
 * and the sum are rounded apart as the C expression's are (C11 does not contract them), and truncation to int
 * then saturating packs keep 0..255 (tests/t_image.c: image_floats_to_bytes_*). */
static void floats_to_bytes_scalar(const float *in, unsigned char *out, size_t n) {
    for (size_t k = 0; k < n; k++) {
        float v = in[k] > 0 ? in[k] : 0.0f;
        out[k] = (unsigned char)((v < 1 ? v : 1.0f) * 255.0f + 0.5f);
    }
}

void image_floats_to_bytes(const float *in, unsigned char *out, size_t n) {
    size_t k = 0;
#ifdef __SSE2__
    const __m128 zero = _mm_setzero_ps(), one = _mm_set1_ps(1), scale = _mm_set1_ps(255), half = _mm_set1_ps(0.5f);
    for (; k + 16 <= n; k += 16) {
        __m128i q[4];
        for (int j = 0; j < 4; j++) {
            __m128 v = _mm_min_ps(_mm_max_ps(_mm_loadu_ps(in + k + 4 * j), zero), one);
            q[j] = _mm_cvttps_epi32(_mm_add_ps(_mm_mul_ps(v, scale), half));
        }
        __m128i bytes = _mm_packus_epi16(_mm_packs_epi32(q[0], q[1]), _mm_packs_epi32(q[2], q[3]));
        _mm_storeu_si128((__m128i *)(void *)(out + k), bytes);
    }
#endif
    floats_to_bytes_scalar(in + k, out + k, n - k);
}

