/* src/clrt_pocl.c -- see clrt_pocl.h. Stages: the header read and checked; the one root entry, program.bc, found;
 * each kernel's record checked for its generic function; the root entry replaced by an empty placeholder file and
 * the build hash made the stripped binary's own. The layout is PoCL 3.x's lib/CL/pocl_binary.c, little-endian:
 *   header: "poclbin\0", device id u64, version u32, kernels u32, flags u64, root entries u32, build hash char[41]
 *   root entry: its bytes u64, then files: name length u32, name, content length u32, content
 *   kernel: record bytes u64, files' bytes u64, argument info bytes u32, name length u32, name, ... */
#define _GNU_SOURCE /* memmem */
#include "clrt_pocl.h"
#include <stdint.h>
#include <stdio.h>
#include <string.h>

enum {
    POCL_VERSION = 9,
    HASH_AT = 36,       /* the build hash: "XX/" and 37 more characters of A-P, then a NUL */
    HASH_CHARS = 40,
    ROOT_AT = HASH_AT + HASH_CHARS + 1,
    KERNEL_NAME_MAX = 256,
};

/* The stripped binary's single root file: empty, and not program.bc, which PoCL would parse. */
static const char placeholder[] = "/program.bc-removed-by-iacsg";

static uint64_t read_le(const unsigned char *p, int bytes) {
    uint64_t v = 0;
    for (int k = bytes - 1; k >= 0; k--)
        v = v << 8 | p[k];
    return v;
}

static void write_le(unsigned char *p, uint64_t v, int bytes) {
    for (int k = 0; k < bytes; k++, v >>= 8)
        p[k] = (unsigned char)v;
}

static int hash_is_pocls(const unsigned char *h) {
    for (int k = 0; k < HASH_CHARS; k++)
        if (!(k == 2 ? h[k] == '/' : h[k] >= 'A' && h[k] <= 'P'))
            return 0;
    return h[HASH_CHARS] == '\0';
}

/* Whether `len` bytes at `hay` hold `needle` (n bytes) preceded by its length as u32, as a file's name is. */
static int has_file_named(const unsigned char *hay, size_t len, const char *needle, size_t n) {
    unsigned char key[4 + 2 * KERNEL_NAME_MAX + 16];
    write_le(key, n, 4);
    memcpy(key + 4, needle, n);
    return memmem(hay, len, key, 4 + n) != NULL;
}

/* Whether each of the `kernels` records from `at` to the end has the file NAME/0-0-0/NAME.so, and they end at `end`. */
static int every_kernel_generic(const unsigned char *bin, size_t at, size_t end, uint64_t kernels) {
    for (uint64_t k = 0; k < kernels; k++) {
        if (end - at < 24)
            return 0;
        uint64_t record = read_le(bin + at, 8), name_len = read_le(bin + at + 20, 4);
        if (record < 24 + name_len || record > end - at || name_len == 0 || name_len > KERNEL_NAME_MAX)
            return 0;
        char generic[2 * KERNEL_NAME_MAX + 16];
        const char *name = (const char *)bin + at + 24;
        int n = snprintf(generic, sizeof generic, "/%.*s/0-0-0/%.*s.so", (int)name_len, name, (int)name_len, name);
        if (!has_file_named(bin + at, record, generic, (size_t)n))
            return 0;
        at += record;
    }
    return at == end;
}

size_t clrt_pocl_binary_without_ir(unsigned char *bin, size_t size) {
    static const char bitcode[] = "/program.bc";
    const size_t name_len = sizeof bitcode - 1, new_name_len = sizeof placeholder - 1;
    if (size < ROOT_AT + 8 || memcmp(bin, "poclbin", 8) != 0 || read_le(bin + 16, 4) != POCL_VERSION ||
        read_le(bin + 32, 4) != 1 || !hash_is_pocls(bin + HASH_AT))
        return size;
    uint64_t root = read_le(bin + ROOT_AT, 8);
    size_t files = ROOT_AT + 8;
    if (root > size - files || root < 8 + name_len || read_le(bin + files, 4) != name_len ||
        memcmp(bin + files + 4, bitcode, name_len) != 0 ||
        read_le(bin + files + 4 + name_len, 4) != root - 8 - name_len)
        return size; /* not exactly one file, program.bc */
    size_t kernels_at = files + root, new_root = 8 + new_name_len;
    if (new_root >= root || !every_kernel_generic(bin, kernels_at, size, read_le(bin + 20, 4)))
        return size;
    write_le(bin + ROOT_AT, new_root, 8);
    write_le(bin + files, new_name_len, 4);
    memcpy(bin + files + 4, placeholder, new_name_len);
    write_le(bin + files + 4 + new_name_len, 0, 4);
    memmove(bin + files + new_root, bin + kernels_at, size - kernels_at);
    bin[HASH_AT + HASH_CHARS - 1] = 'Z';
    return size - (root - new_root);
}
