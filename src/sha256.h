/* src/sha256.h -- SHA-256 (FIPS 180-4), for the keys of caches that must not mistake one input for another: the
 * program binaries of src/clrt_cache.c and the image writer server's name (src/cli_writer_server.c). */
#ifndef IACSG_SHA256_H
#define IACSG_SHA256_H
#include <stddef.h>
#include <stdint.h>

typedef struct {
    uint32_t h[8];
    uint64_t length; /* bytes hashed so far */
    unsigned char block[64];
    size_t used; /* bytes of `block` filled */
} sha256_ctx;

void sha256_init(sha256_ctx *c);
void sha256_update(sha256_ctx *c, const void *data, size_t size);
/* The digest as 64 lowercase hex digits and a NUL. */
void sha256_hex(sha256_ctx *c, char out[65]);

#endif
