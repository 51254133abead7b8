/* src/error.h -- the status and error record every library call reports through. Library code fills one of
 * these and returns; only the CLI prints or exits. */
#ifndef IACSG_ERROR_H
#define IACSG_ERROR_H
#include "api.h"

IACSG_API_BEGIN

typedef enum {
    IACSG_OK = 0,
    IACSG_ERR_SYNTAX,  /* the expression or scene text does not parse */
    IACSG_ERR_NAME,    /* unknown function, primitive, keyword or binding */
    IACSG_ERR_ARITY,   /* wrong number of arguments */
    IACSG_ERR_LIMIT,   /* nesting, size or resource limit exceeded */
    IACSG_ERR_ARG,     /* a bad option or parameter value */
    IACSG_ERR_IO,      /* a file could not be read or written */
    IACSG_ERR_OPENCL,  /* no platform or device, or an OpenCL call failed */
    IACSG_ERR_BUILD,   /* the OpenCL program failed to build */
    IACSG_ERR_NOMEM,   /* out of host memory */
    IACSG_ERR_CANCELLED /* the caller's cancel callback stopped a render */
} iacsg_status;

/* line and column are 1-based positions in the input text, 0 when the error has no place. */
typedef struct {
    iacsg_status status;
    int line, column;
    char message[512];
} iacsg_error;

/* Records an error (printf-style message, one line, no trailing period) and returns its status. A NULL err
 * is allowed and ignored. */
iacsg_status iacsg_error_set(iacsg_error *err, iacsg_status status, int line, int column, const char *fmt, ...)
#ifdef __GNUC__
    __attribute__((format(printf, 5, 6)))
#endif
    ;

/* A short name for a status, e.g. "syntax error" (a static string, not to be freed). */
const char *iacsg_status_name(iacsg_status status);

IACSG_API_END
#endif
