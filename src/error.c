/* src/error.c -- filling iacsg_error records. */
#include "error.h"
#include <stdarg.h>
#include <stdio.h>

iacsg_status iacsg_error_set(iacsg_error *err, iacsg_status status, int line, int column, const char *fmt, ...) {
    if (!err)
        return status;
    err->status = status;
    err->line = line;
    err->column = column;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(err->message, sizeof err->message, fmt, ap);
    va_end(ap);
    return status;
}

const char *iacsg_status_name(iacsg_status status) {
    switch (status) {
    case IACSG_OK: return "ok";
    case IACSG_ERR_SYNTAX: return "syntax error";
    case IACSG_ERR_NAME: return "unknown name";
    case IACSG_ERR_ARITY: return "wrong number of arguments";
    case IACSG_ERR_LIMIT: return "limit exceeded";
    case IACSG_ERR_ARG: return "bad argument";
    case IACSG_ERR_IO: return "i/o error";
    case IACSG_ERR_OPENCL: return "OpenCL error";
    case IACSG_ERR_BUILD: return "OpenCL build error";
    case IACSG_ERR_NOMEM: return "out of memory";
    case IACSG_ERR_CANCELLED: return "cancelled";
    }
    return "unknown error";
}
