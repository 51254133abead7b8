/* src/api.h -- what makes a declaration public. Each public header (PUBLIC_HEADERS in the Makefile, installed
 * under include/iacsg/) puts its declarations between IACSG_API_BEGIN and IACSG_API_END: they get C linkage
 * for C++ callers and default visibility, so that libiacsg.so, compiled with -fvisibility=hidden, exports them
 * and nothing else. A function added between the two is public with no further mark. */
#ifndef IACSG_API_H
#define IACSG_API_H

#ifdef __cplusplus
#define IACSG_EXTERN_C_BEGIN extern "C" {
#define IACSG_EXTERN_C_END }
#else
#define IACSG_EXTERN_C_BEGIN
#define IACSG_EXTERN_C_END
#endif

#if defined(__GNUC__) || defined(__clang__)
#define IACSG_API_BEGIN _Pragma("GCC visibility push(default)") IACSG_EXTERN_C_BEGIN
#define IACSG_API_END IACSG_EXTERN_C_END _Pragma("GCC visibility pop")
#else
#define IACSG_API_BEGIN IACSG_EXTERN_C_BEGIN
#define IACSG_API_END IACSG_EXTERN_C_END
#endif

#endif
