/* kernels/render.cl -- the entry point iacsg_render, run for each band of rows: one work-item per block of 4x4
 * tiles of 8x8 pixels, which runs the tile pass over its tiles (tile.h), then traces their pixels in packets of
 * 4x4 rays (neighbouring rays take similar paths through the bisection, so they share SIMD lanes well).
 *
 * Per pixel: the camera ray (camera.h), clipped to the bounds (rays that miss the box cost nothing more); if the
 * tile may hold surface, the first root by stackless bisection (packet.h) from the tile's first coarse leaf on
 * (tile.h); then the normal and the colour at the leaf's midpoint (shade.h), or where the host gave an effects
 * block the colour with the effects (kernels/effects.cl: effects_centre traces the hit's shadow rays, reflected
 * rays and layers in the packet's lanes; the layers search only their tile's runs, tile.h: tile_runs). Outputs,
 * indexed by pixel of the whole image: rgb (3 floats, display-encoded), depth (the leaf's start t, +inf on a
 * miss), normal (3 floats, 0 on a miss), and with
 * KERNEL_STATS the evaluation counts (per tile, and per packet their sum and maximum, and the effects' secondary
 * rays and their evaluations).
 */
#include "camera.h"
#include "tile.h"
#include "shade.h"

/* A tile's words in tile_groups_of: a group mask per segment of the frame's tree, and for a tape each segment's
 * list of parts after them (kernels/tape_eval.h: tape_tile_parts; src/render.c sizes the buffer). */
#ifdef IACSG_TAPE
#define TILE_GROUPS_WORDS (SEGMENTS * (1 + TAPE_TILE_WORDS))
#else
#define TILE_GROUPS_WORDS SEGMENTS
#endif

/* Tiles are row-major, tiles_x per row. */
static inline size_t tile_index(int tx, int ty, int tiles_x) { return (size_t)ty * (size_t)tiles_x + (size_t)tx; }

/* The union of the group masks of the lanes whose tile is in the image. */
static inline ulong in_image(const ulong groups[IA_VW], const ia_real valid[IA_VW]) {
    ulong all = 0;
    for (int k = 0; k < IA_VW; k++)
        all |= valid[k] != 0 ? groups[k] : 0;
    return all;
}

/* The tile pass over the PACKET_W x PACKET_H tiles from (tx0, ty0), searched in SIMD lanes (tile.h).
 * tiles[2k], tiles[2k+1]: the level and index of tile k's first coarse leaf (row-major, tiles_x per row), as
 * reals (exact: the index has fewer bits than the mantissa, see traverse.h); level -1 when no ray of the tile
 * can meet the surface. tile_groups_of[SEGMENTS k + s]: for a union in groups, those that can matter in tile k
 * on segment s of the frame's tree. runs (NULL: none), per tile of the block: its runs for its rays' transparent
 * layers (tile.h: tile_runs), from its first coarse leaf on (a layer starts past its camera ray's hit, which is
 * past that leaf's start). */
static void block_tiles(PACKET_TAPE_PARAM __constant ia_real *params, int flags, int width, int height, int tx0,
                        int ty0, __global ia_real *tiles, __global uint *evals, __global ulong *tile_groups_of,
                        tile_layer_runs *runs) {
    int tiles_x = (width + TILE_SIZE - 1) / TILE_SIZE, ortho = flags & RENDER_ORTHO;
    iav base_v[3], dir_v[3];
    ia_real valid[IA_VW];
    ia_realv spread;
    tile_block_lanes(params, ortho, width, height, tx0, ty0, base_v, dir_v, &spread, valid);
    ia_real t0, w;
    frame_root(params, &t0, &w);
    ia_maskv searching = IAV_LOAD(valid) != 0;
    iav time = iav_const(params[PARAM_TIME_LO], params[PARAM_TIME_HI]);
    /* The groups of a union that matter in any of the tiles, over the whole tree, for their common search; then
     * each tile's own from its first leaf on, for its rays. */
    ulong groups[IA_VW];
    iav root = iav_make(packet_node_bound(t0, w, (packet_int)0, (packet_index)0),
                        packet_node_bound(t0, w, (packet_int)0, (packet_index)1));
    tile_groups(PACKET_TAPE_ARG base_v, dir_v, root, time, ~(ulong)0, groups);
    ulong any_tile = in_image(groups, valid);
    packet_int level = (packet_int)0;
    packet_index leaf = (packet_index)0, counts = (packet_index)0;
    ia_maskv found = tile_first_leaves(PACKET_TAPE_ARG any_tile, base_v, dir_v, spread, ortho, t0, w,
                                       params[PARAM_EPS], searching, time, &level, &leaf, &counts);
    tile_groups(PACKET_TAPE_ARG base_v, dir_v,
                iav_make(select(root.lo, packet_node_bound(t0, w, level, leaf), found), root.hi), time, any_tile,
                groups);
#ifdef IACSG_GROUPS /* (else no group masks are read: packet_groups is all ones) */
    /* then per segment of the tree (params.h), among the tile's own */
    ulong in_tiles = in_image(groups, valid);
    for (int s = 0; s < SEGMENTS; s++) {
        ulong segment[IA_VW];
        iav ts = iav_make(packet_node_bound(t0, w, (packet_int)SEGMENT_LEVEL, (packet_index)s),
                          packet_node_bound(t0, w, (packet_int)SEGMENT_LEVEL, (packet_index)(s + 1)));
#ifdef IACSG_TAPE
        ushort lists[IA_VW][TAPE_TILE_RECORD];
        iav box[3];
        for (int c = 0; c < 3; c++) /* tile_box */
            box[c] = iav_add(base_v[c], iav_mul(ts, dir_v[c]));
        tape_tile_parts(tape, in_tiles, box[0], box[1], box[2], time, segment, lists);
#else
        tile_groups(PACKET_TAPE_ARG base_v, dir_v, ts, time, in_tiles, segment);
#endif
        for (int k = 0; k < IA_VW; k++) {
            if (valid[k] == 0)
                continue;
            __global ulong *record =
                tile_groups_of + tile_index(tx0 + k % PACKET_W, ty0 + k / PACKET_W, tiles_x) * TILE_GROUPS_WORDS;
            record[s] = segment[k] & groups[k];
#ifdef IACSG_TAPE
            __global ushort *list = (__global ushort *)(record + SEGMENTS) + TAPE_TILE_RECORD * s;
            for (int n = 0; n < TAPE_TILE_RECORD; n++)
                list[n] = lists[k][n];
#endif
        }
    }
#endif
    if (runs) { /* for the layers: the tile's boxes grown by how far the layers' rays may be off the camera rays */
        iav grown[3];
        ia_real margin = tile_layer_margin(params);
        for (int c = 0; c < 3; c++)
            grown[c] = iav_add(base_v[c], iav_const(-margin, margin));
        ia_realv lo[TILE_RUNS], hi[TILE_RUNS];
        packet_int n;
        tile_runs(PACKET_TAPE_ARG ~(ulong)0, grown, dir_v, spread, ortho, t0, w, params[PARAM_EPS], found, level, leaf,
                  time, lo, hi, &n, &counts);
        ia_real lo_k[TILE_RUNS][IA_VW], hi_k[TILE_RUNS][IA_VW], n_k[IA_VW];
        for (int r = 0; r < TILE_RUNS; r++) {
            IAV_STORE(lo[r], lo_k[r]);
            IAV_STORE(hi[r], hi_k[r]);
        }
        IAV_STORE(packet_to_real(n), n_k);
        for (int k = 0; k < IA_VW; k++) {
            runs[k].n = (int)n_k[k];
            for (int r = 0; r < TILE_RUNS; r++) {
                runs[k].lo[r] = lo_k[r][k];
                runs[k].hi[r] = hi_k[r][k];
            }
        }
    }
    ia_real level_r[IA_VW], leaf_r[IA_VW];
    bisect_index count[IA_VW];
    IAV_STORE(select((ia_realv)-1, packet_to_real(level), found), level_r);
    IAV_STORE(packet_to_real(leaf), leaf_r);
    IAV_STORE(counts, count);
    for (int k = 0; k < IA_VW; k++) {
        if (valid[k] == 0)
            continue;
        size_t tile = tile_index(tx0 + k % PACKET_W, ty0 + k / PACKET_W, tiles_x);
        tiles[2 * tile] = level_r[k];
        tiles[2 * tile + 1] = leaf_r[k];
#ifdef KERNEL_STATS
        evals[tile] = (uint)count[k];
#else
        (void)count;
        (void)evals;
#endif
    }
}

/* The gradients at the points o + t d of the lanes of `hit` (anything in the others). For a union in groups, by
 * differences over the groups of the segments of the frame's tree the points are on; else with the emitted point
 * code over lanes (iacsg_f_gradv), 0 in the other lanes, which it takes at the origin (a NaN or infinite point
 * would send sin and cos to their slow path). */
static void packet_gradients(PACKET_TAPE_PARAM const __global ulong *segment_groups, ia_real t0, ia_real w,
                             ia_maskv hit, const ia_realv o[3], const ia_realv d[3], ia_realv t, ia_real time,
                             ia_realv g[3]) {
    ia_realv p[3];
    for (int c = 0; c < 3; c++)
        p[c] = o[c] + t * d[c];
#ifdef IACSG_GROUPS
    ia_real on[IA_VW], tk[IA_VW];
    IAV_STORE(select(IAV_R(0), IAV_R(1), hit), on);
    IAV_STORE(t, tk);
    packet_parts parts = {0};
#ifdef IACSG_TAPE
    parts.records = (const __global ushort *)(segment_groups + SEGMENTS);
    parts.first = SEGMENTS;
    parts.last = -1;
#endif
    for (int k = 0; k < IA_VW; k++) {
        if (on[k] == 0)
            continue;
        int s = (int)node_at(t0, w, SEGMENT_LEVEL, tk[k]);
        parts.groups |= segment_groups[s];
#ifdef IACSG_TAPE
        parts.first = min(parts.first, s);
        parts.last = max(parts.last, s);
#endif
    }
    shade_gradients_by_differences(PACKET_TAPE_ARG parts, p, iav_point(time), g);
#else
    (void)segment_groups, (void)t0, (void)w;
    for (int c = 0; c < 3; c++)
        p[c] = select(IAV_R(0), p[c], hit);
    (void)iacsg_f_gradv(p[0], p[1], p[2], IAV_R(time), g);
    for (int c = 0; c < 3; c++)
        g[c] = select(IAV_R(0), g[c], hit);
#endif
}

/* The colours of a packet wholly in the image whose first pixel is `first`, row by row: a row's PACKET_W pixels
 * are 3 PACKET_W consecutive floats (or bytes), interleaved from the three colour vectors and stored as 8 + 4 (a
 * store per float, lane by lane, was a sixth of an empty frame's kernel time), or for 2 pixels as 4 + 2. The lanes
 * are picked by constant swizzles: shuffle2 with masks computed per row went through the stack element by element,
 * 30 % of the sphere's kernel. */
#if PACKET_H != 4 || (PACKET_W != 4 && PACKET_W != 2) || PACKET_LANES != IA_VW
#error "put_rgb_rows interleaves 4 rows of 4 or 2 pixels, a packet's lanes"
#endif
static void put_rgb_row(float4 r, float4 g, float4 b, __global float *at) {
    vstore8((float8)(r.s0, g.s0, b.s0, r.s1, g.s1, b.s1, r.s2, g.s2), 0, at);
    vstore4((float4)(b.s2, r.s3, g.s3, b.s3), 0, at + 8);
}
static void put_rgb_row2(float2 r, float2 g, float2 b, __global float *at) {
    vstore4((float4)(r.s0, g.s0, b.s0, r.s1), 0, at);
    vstore2((float2)(g.s1, b.s1), 0, at + 4);
}

/* RENDER_BYTES' rounding of colours to bytes, exactly src/image_bytes.c's: NaN and below 0 give 0 (fmax passes
 * NaN over), the product and the sum rounded apart (not contracted into an fma), truncated. */
#define COLOR_BYTES(n)                                                                                          \
    static IAV_CAT(uchar, n) color_bytes##n(IAV_CAT(float, n) v) {                                            \
        _Pragma("OPENCL FP_CONTRACT OFF")                                                                       \
        IAV_CAT(float, n) scaled = fmin(fmax(v, 0.0f), 1.0f) * 255.0f;                                          \
        return IAV_CAT(convert_uchar, n)(scaled + 0.5f);                                                        \
    }
COLOR_BYTES(4)
COLOR_BYTES(8)

static void put_rgb_row_bytes(float4 r, float4 g, float4 b, __global uchar *at) {
    vstore8(color_bytes8((float8)(r.s0, g.s0, b.s0, r.s1, g.s1, b.s1, r.s2, g.s2)), 0, at);
    vstore4(color_bytes4((float4)(b.s2, r.s3, g.s3, b.s3)), 0, at + 8);
}
static void put_rgb_row2_bytes(float2 r, float2 g, float2 b, __global uchar *at) {
    vstore4(color_bytes4((float4)(r.s0, g.s0, b.s0, r.s1)), 0, at);
    vstore2(color_bytes4((float4)(g.s1, b.s1, 0.0f, 0.0f)).s01, 0, at + 4);
}

/* A whole packet's colours, as floats or with RENDER_BYTES as bytes (out then points to bytes), row by row: the
 * rows' lanes picked by the swizzles a, b, c, d. */
#define PUT_RGB_ROWS(put, at, row, a, b, c, d)                                                                  \
    do {                                                                                                        \
        put(rgb[0].a, rgb[1].a, rgb[2].a, (at));                                                               \
        put(rgb[0].b, rgb[1].b, rgb[2].b, (at) + (row));                                                       \
        put(rgb[0].c, rgb[1].c, rgb[2].c, (at) + 2 * (row));                                                   \
        put(rgb[0].d, rgb[1].d, rgb[2].d, (at) + 3 * (row));                                                   \
    } while (0)
#if PACKET_W == 4
#define PUT_RGB_ROW put_rgb_row
#define PUT_RGB_LANES s0123, s4567, s89ab, scdef
#else
#define PUT_RGB_ROW put_rgb_row2
#define PUT_RGB_LANES s01, s23, s45, s67
#endif
/* (one more level, so that PUT_RGB_LANES is spread into PUT_RGB_ROWS' four arguments) */
#define PUT_RGB_ROWS_OF(put, at, row, lanes) PUT_RGB_ROWS(put, at, row, lanes)
static void put_rgb_rows(const shade_colorv rgb[3], size_t first, int width, int bytes, __global float *out) {
    size_t row = 3 * (size_t)width;
    if (bytes)
        PUT_RGB_ROWS_OF(IAV_CAT(PUT_RGB_ROW, _bytes), (__global uchar *)out + 3 * first, row, PUT_RGB_LANES);
    else
        PUT_RGB_ROWS_OF(PUT_RGB_ROW, out + 3 * first, row, PUT_RGB_LANES);
}

/* Writes the outputs of the lanes' pixels (col, row) that are in the image (the packet's first is (i0, j0)): the
 * colours, and where the host asked for them (non-NULL) the depths (the leaf's start, +inf on a miss) and the
 * normals (0 on a miss). */
static void put_pixels(int i0, int j0, packet_int col, packet_int row, int width, int height, int bytes,
                       ia_maskv hit, const shade_colorv rgb[3], ia_realv t_start, const ia_realv n[3],
                       __global float *rgb_out, __global float *depth, __global float *normal) {
    int whole = i0 + PACKET_W <= width && j0 + PACKET_H <= height;
    if (whole)
        put_rgb_rows(rgb, (size_t)j0 * (size_t)width + (size_t)i0, width, bytes, rgb_out);
    if (whole && !depth && !normal)
        return;
    int i[IA_VW], j[IA_VW];
    float color[3][IA_VW], normal_k[3][IA_VW];
    ia_real on[IA_VW], start[IA_VW];
    IAV_CAT(vstore, IA_VW)(IAV_CAT(convert_int, IA_VW)(col), 0, i);
    IAV_CAT(vstore, IA_VW)(IAV_CAT(convert_int, IA_VW)(row), 0, j);
    IAV_STORE(select(IAV_R(0), IAV_R(1), hit), on);
    IAV_STORE(t_start, start);
    for (int c = 0; c < 3; c++) {
        IAV_CAT(vstore, IA_VW)(rgb[c], 0, color[c]);
        IAV_CAT(vstore, IA_VW)(shade_to_color(select(IAV_R(0), n[c], hit)), 0, normal_k[c]);
    }
    for (int k = 0; k < IA_VW; k++) {
        if (i[k] >= width || j[k] >= height)
            continue;
        size_t pixel = (size_t)j[k] * (size_t)width + (size_t)i[k];
        if (depth)
            depth[pixel] = on[k] != 0 ? camera_depth_round_down(start[k]) : INFINITY;
        for (int c = 0; c < 3; c++) {
            if (!whole && bytes)
                ((__global uchar *)rgb_out)[3 * pixel + c] = color_bytes4((float4)color[c][k]).s0;
            else if (!whole)
                rgb_out[3 * pixel + c] = color[c][k];
            if (normal)
                normal[3 * pixel + c] = normal_k[c][k];
        }
    }
}

/* iacsg_render's effects (kernels/effects.cl: effects_centre shades a packet's pixels with them): the effects'
 * block, NULL for the plain lighting (shade.h); a union's groups all on, for the secondary rays; the secondary
 * rays' interval Newton window; with KERNEL_STATS, per packet the secondary rays and their evaluations (NULL
 * without). */
typedef struct {
    __constant ia_real *block;
    __global const ulong *all_groups;
    ia_real footprint;
    __global uint *counts;
} render_effects;

#ifndef IACSG_TAPE /* a tape's program has no effects (the host refuses them there) */
static void effects_centre(__constant ia_real *params, __constant ia_real *fx, __global const ulong *all_groups,
                           ia_real footprint, packet_int row, int height, ia_maskv live, ia_maskv hit,
                           const ia_realv o_ray[3], const ia_realv d_ray[3], ia_realv hit_lo, const ia_realv n_hit[3],
                           const tile_layer_runs *runs, shade_colorv color[3], packet_index *rays,
                           packet_index *evals);
#endif

#ifdef KERNEL_STATS
/* The sum and the maximum of a packet's lanes' counts, by halves in registers (stored whole and loaded back, the
 * load waited on the stores of its pieces). */
static uint lanes_sum(packet_index v) {
#if IA_VW == 16
    uint16 k = convert_uint16(v);
    uint8 k8 = k.lo + k.hi;
#else
    uint8 k8 = convert_uint8(v);
#endif
    uint4 k4 = k8.lo + k8.hi;
    uint2 k2 = k4.lo + k4.hi;
    return k2.x + k2.y;
}
static uint lanes_max(packet_index v) {
#if IA_VW == 16
    uint16 k = convert_uint16(v);
    uint8 k8 = max(k.lo, k.hi);
#else
    uint8 k8 = convert_uint8(v);
#endif
    uint4 k4 = max(k8.lo, k8.hi);
    uint2 k2 = max(k4.lo, k4.hi);
    return max(k2.x, k2.y);
}
#endif

/* The packet of PACKET_W x PACKET_H pixels from (i0, j0) (params.h), its rays traced together in SIMD lanes
 * (packet.h) after the tile pass of its tile, and shaded in lanes (shade.h). */
static void trace_packet(PACKET_TAPE_PARAM __constant ia_real *params, int flags, int width, int height, int i0, int j0,
                         __global const ia_real *tiles, __global float *rgb, __global float *depth,
                         __global float *normal, __global uint *evals, __global const ulong *tile_groups_of,
                         const render_effects *fx, const tile_layer_runs *runs) {
    if (i0 >= width || j0 >= height)
        return;
    size_t tile = tile_index(i0 / TILE_SIZE, j0 / TILE_SIZE, (width + TILE_SIZE - 1) / TILE_SIZE);
    int level = (int)tiles[2 * tile];
    const __global ulong *segment_groups = tile_groups_of + tile * TILE_GROUPS_WORDS;
    ia_real t0, w, time = params[PARAM_TIME_LO]; /* for the shading's point gradients */
    frame_root(params, &t0, &w);
    packet_int lanes = packet_lane_numbers();
    packet_int col = i0 + lanes % PACKET_W, row = j0 + lanes / PACKET_W;
    ia_realv o[3] = {IAV_R(0), IAV_R(0), IAV_R(0)}, d[3] = {IAV_R(0), IAV_R(0), IAV_R(0)};
    ia_realv n[3] = {IAV_R(0), IAV_R(0), IAV_R(0)}, hit_lo = IAV_R(0), hit_hi = IAV_R(0);
    ia_maskv hit = (ia_maskv)0;
    packet_index counts = (packet_index)0;
    if (level >= 0) { /* else the tile pass proved the whole tile empty: no ray to set up */
        /* Each lane's ray, its part inside the bounds and its first node. */
        ia_realv t_near, t_far;
        packet_rays(params, flags & RENDER_ORTHO, min(col, width - 1), min(row, height - 1), width, height, o, d);
        ia_maskv searching = (col < width) & (row < height) & packet_clip(params, o, d, &t_near, &t_far);
        bisect_index leaf = (bisect_index)tiles[2 * tile + 1];
        packet_index start = max((packet_index)leaf, packet_node_at(t0, w, level, t_near));
        /* a pixel's footprint at distance t: 2 tan(fov/2) t / height, or 2 (HEIGHT/2) / height orthographic */
        ia_real pixel = (ia_real)2 * params[PARAM_SCALE_V] / (ia_real)height;
        int ortho = flags & RENDER_ORTHO;
        hit = packet_first_root(PACKET_TAPE_ARG segment_groups, o, d, t0, w, (packet_int)level, start, t_near, t_far,
                                searching, params[PARAM_EPS], ortho ? pixel : 0, ortho ? 0 : pixel,
                                iav_const(time, params[PARAM_TIME_HI]), &hit_lo, &hit_hi, &counts);
        if (iav_any(hit)) {
            ia_realv g[3];
            packet_gradients(PACKET_TAPE_ARG segment_groups, t0, w, hit, o, d,
                             hit_lo * (ia_real)0.5 + hit_hi * (ia_real)0.5, time, g);
            shade_normals(g, d, n);
        }
    }
    shade_colorv color[3];
    packet_index fx_rays = (packet_index)0, fx_evals = (packet_index)0; /* the effects' secondary rays */
#ifndef IACSG_TAPE
    if (fx->block) /* a miss needs no ray: where the tile pass proved them all misses, o and d are 0 */
        effects_centre(params, fx->block, fx->all_groups, fx->footprint, row, height, (col < width) & (row < height),
                       hit, o, d, hit_lo, n, runs, color, &fx_rays, &fx_evals);
    else
#endif
        shade_pixels(params, hit, n, d, row, height, color);
    put_pixels(i0, j0, col, row, width, height, flags & RENDER_BYTES, hit, color, hit_lo, n, rgb, depth, normal);
#ifdef KERNEL_STATS
    /* the packet's sum and maximum, all the host reads (a store per pixel was a fifth of an empty -stats frame's
     * kernel time, and 4 MB of fresh pages a 1024x1024 frame); lanes past the image counted nothing */
    size_t packet = (size_t)(j0 / PACKET_H) * (size_t)((width + PACKET_W - 1) / PACKET_W) + (size_t)(i0 / PACKET_W);
    evals[2 * packet] = lanes_sum(counts);
    evals[2 * packet + 1] = lanes_max(counts);
    if (fx->counts) {
        fx->counts[2 * packet] = lanes_sum(fx_rays);
        fx->counts[2 * packet + 1] = lanes_sum(fx_evals);
    }
#else
    (void)counts, (void)evals, (void)fx_rays, (void)fx_evals;
#endif
}

/* One work-item's block of PACKET_W x PACKET_H tiles (32x32 pixels): the tile pass over its tiles, then their
 * packets, shaded with the effects fx (its block NULL: the plain lighting). */
static void render_block(PACKET_TAPE_PARAM __constant ia_real *params, int flags, int width, int height,
                         int block_row0, __global ia_real *tiles, __global float *rgb, __global float *depth,
                         __global float *normal, __global uint *evals, __global uint *tile_evals,
                         __global ulong *tile_groups_of, const render_effects *fx) {
    int tiles_x = (width + TILE_SIZE - 1) / TILE_SIZE, tiles_y = (height + TILE_SIZE - 1) / TILE_SIZE;
    int tx0 = (int)get_global_id(0) * PACKET_W, ty0 = (block_row0 + (int)get_global_id(1)) * PACKET_H;
    if (tx0 >= tiles_x || ty0 >= tiles_y)
        return;
    /* the tiles' runs for the transparent layers, where the effects have them (the previews are opaque) */
    tile_layer_runs runs[IA_VW];
    int layered = fx->block && fx->block[EFFECTS_OPACITY] < 1 && fx->block[EFFECTS_SHADE] < EFFECTS_SHADE_NORMALS;
    block_tiles(PACKET_TAPE_ARG params, flags, width, height, tx0, ty0, tiles, tile_evals, tile_groups_of,
                layered ? runs : 0);
    for (int ty = ty0; ty < min(ty0 + PACKET_H, tiles_y); ty++)
        for (int tx = tx0; tx < min(tx0 + PACKET_W, tiles_x); tx++)
            for (int j = 0; j < TILE_SIZE; j += PACKET_H)
                for (int i = 0; i < TILE_SIZE; i += PACKET_W)
                    trace_packet(PACKET_TAPE_ARG params, flags, width, height, tx * TILE_SIZE + i, ty * TILE_SIZE + j,
                                 tiles, rgb, depth, normal, evals, tile_groups_of, fx,
                                 layered ? &runs[(ty - ty0) * PACKET_W + (tx - tx0)] : 0);
}

/* One work-item per block of tiles (render_block), run for bands of block rows. One kernel rather than a tile
 * kernel and a ray kernel: PoCL compiles each kernel of a program separately at its first launch, so the
 * expression was compiled twice (half of the first run's time, ~8 s for 1024 spheres). The effects have a kernel
 * of their own (kernels/effects.cl: iacsg_render_effects): in this one the effects' code is not there at all (a
 * branch on an argument made the plain render's kernel 40 % slower). `tape`: an interpreted expression's
 * (kernels/tape_eval.h, a program with IACSG_TAPE); a compiled one ignores it (NULL). */
__kernel void iacsg_render(__constant ia_real *params, int flags, int width, int height, int block_row0,
                           __global ia_real *tiles, __global float *rgb, __global float *depth, __global float *normal,
                           __global uint *evals, __global uint *tile_evals, __global ulong *tile_groups_of,
                           __global const uint *tape) {
#ifndef IACSG_TAPE
    (void)tape;
#endif
    render_effects none = {0, 0, 0, 0};
    render_block(PACKET_TAPE_ARG params, flags, width, height, block_row0, tiles, rgb, depth, normal, evals,
                 tile_evals, tile_groups_of, &none);
}
