/* src/version.c -- the library's version at run time (src/iacsg.h). */
#include "iacsg.h"

const char *iacsg_version(void) { return IACSG_VERSION; }
