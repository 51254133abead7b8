/* src/digest.c -- see digest.h. */
#include "digest.h"

void digest_init(digest_ctx *c) { sha256_init(c); }

void digest_update(digest_ctx *c, const void *data, size_t size) { sha256_update(c, size, data); }

void digest_hex(digest_ctx *c, char out[65]) {
    static const char hex[] = "0123456789abcdef";
    unsigned char d[SHA256_DIGEST_SIZE];
    sha256_digest(c, sizeof d, d);
    for (int k = 0; k < SHA256_DIGEST_SIZE; k++) {
        out[2 * k] = hex[d[k] >> 4];
        out[2 * k + 1] = hex[d[k] & 15];
    }
    out[2 * SHA256_DIGEST_SIZE] = 0;
}
