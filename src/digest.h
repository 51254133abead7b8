/* src/digest.h -- SHA-256 digests (Nettle's) as hex, for the keys of caches that must not mistake one input for
 * another: the program binaries of src/clrt_cache.c and the image writer server's name (src/cli_writer_server.c). */
#ifndef IACSG_DIGEST_H
#define IACSG_DIGEST_H
#include <nettle/sha2.h>
#include <stddef.h>

typedef struct sha256_ctx digest_ctx;

void digest_init(digest_ctx *c);
void digest_update(digest_ctx *c, const void *data, size_t size);
/* The digest as 64 lowercase hex digits and a NUL. */
void digest_hex(digest_ctx *c, char out[65]);

#endif
