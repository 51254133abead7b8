/* src/cli_view_display.c -- see cli_view_display.h. */
#include "cli_view_display.h"
#include <math.h>

const char *const view_mode_names[4] = {"colour", "depth", "normals", "ids"};

/* Colours of ids 0, 1, ... (cycled). */
static const float id_palette[6][3] = {{0.85f, 0.55f, 0.2f}, {0.3f, 0.6f, 0.9f}, {0.5f, 0.8f, 0.3f},
                                       {0.8f, 0.3f, 0.5f},   {0.9f, 0.85f, 0.3f}, {0.5f, 0.4f, 0.85f}};

static void depth_range(const iacsg_frame *fr, float *lo, float *hi) {
    *lo = INFINITY;
    *hi = -INFINITY;
    for (long p = 0; p < (long)fr->width * fr->height; p++)
        if (isfinite(fr->depth[p])) {
            *lo = fminf(*lo, fr->depth[p]);
            *hi = fmaxf(*hi, fr->depth[p]);
        }
}

/* The shown value of one pixel of the frame. */
static void shown_pixel(const iacsg_frame *fr, view_mode mode, long p, float lo, float hi, float out[3]) {
    int hit = isfinite(fr->depth[p]);
    for (int c = 0; c < 3; c++) {
        switch (mode) {
        case VIEW_COLOUR:
            out[c] = fr->rgb[3 * p + c];
            break;
        case VIEW_DEPTH:
            out[c] = !hit ? 0.0f : hi > lo ? 1.0f - 0.8f * (fr->depth[p] - lo) / (hi - lo) : 1.0f;
            break;
        case VIEW_NORMALS:
            out[c] = hit ? 0.5f + 0.5f * fr->normal[3 * p + c] : 0.0f;
            break;
        case VIEW_IDS: /* the frame's ids when it has them (regions, surfaces), else one id for the solid */
            out[c] = !hit ? 0.0f : id_palette[fr->ids && fr->ids[p] >= 0 ? (int)fr->ids[p] % 6 : 0][c];
            break;
        }
    }
}

void view_display(const iacsg_frame *fr, view_mode mode, int factor, float *out) {
    float lo = 0, hi = 0;
    if (mode == VIEW_DEPTH)
        depth_range(fr, &lo, &hi);
    int w = fr->width / factor, h = fr->height / factor;
    float weight = 1.0f / (float)(factor * factor);
    for (int j = 0; j < h; j++)
        for (int i = 0; i < w; i++) {
            float sum[3] = {0, 0, 0}, one[3];
            for (int dj = 0; dj < factor; dj++)
                for (int di = 0; di < factor; di++) {
                    shown_pixel(fr, mode, (long)(j * factor + dj) * fr->width + i * factor + di, lo, hi, one);
                    for (int c = 0; c < 3; c++)
                        sum[c] += one[c];
                }
            for (int c = 0; c < 3; c++)
                out[3 * ((long)j * w + i) + c] = factor == 1 ? sum[c] : sum[c] * weight;
        }
}

void view_display_bytes(const float *in, size_t count, unsigned char *out) {
    for (size_t k = 0; k < count; k++) {
        float v = fminf(1.0f, fmaxf(0.0f, in[k]));
        out[k] = (unsigned char)lrintf(v * 255.0f);
    }
}
