/* src/clrt_cache.h -- a cache of built OpenCL programs' binaries (clrt_build's): PoCL's own cache of a build from
 * source still preprocesses the whole source with clang to find its entry (26-50 ms for the reference view's
 * program, 175 ms for a large BRL-CAD scene's), where a build from the binary takes ~4 ms.
 *
 * An entry is keyed by SHA-256 of the sources, the build options, the device (name, device and driver versions,
 * platform version) and iacsg's version; it holds a header (magic, key, the binary's size and SHA-256) and the
 * binary, so that a damaged file is refused before the driver reads it. Directory: IACSG_CACHE_DIR, else
 * $XDG_CACHE_HOME/iacsg, else ~/.cache/iacsg (then programs/ in it); IACSG_KERNEL_CACHE=0 turns the cache off.
 * Entries are written to a temporary file renamed into place (never a partial entry), and the directory is kept
 * under 256 MB, the least recently used entries removed first. Every failure is silent: the program is then
 * built from source as without the cache. */
#ifndef IACSG_CLRT_CACHE_H
#define IACSG_CLRT_CACHE_H
#include "clrt.h"

typedef struct {
    char path[4096]; /* the entry's file; empty when the cache is off */
} clrt_cache_entry;

/* The entry of this build (off when the cache is turned off or has no directory). */
void clrt_cache_find(const clrt *rt, const char *const *sources, size_t count, const char *options,
                     clrt_cache_entry *entry);

/* The program built from the entry's binary, or NULL (no entry, refused, or it does not build; a refused entry
 * is removed). */
cl_program clrt_cache_load(const clrt *rt, const clrt_cache_entry *entry, const char *options);

/* Holds the built program back for clrt_cache_save_deferred (retained), if saves are asked for
 * (clrt_cache_defer_saves) and its program was built before (see seen_before), or at once where the driver
 * compiled it at its build (`compiled`: its binary costs nothing to query; NVIDIA's compiler took about two
 * minutes for a camera kernel, which a second build would repeat). Without that call the process only reads the
 * cache: the library saves nothing on its own, so a program embedding it never stalls on a save. */
void clrt_cache_store(const clrt_cache_entry *entry, cl_program program, int compiled);

/* For the command: programs built from here on may be saved. clrt_cache_save_deferred hands those held back to a
 * process of their own, detached and at the lowest priority, so that no command waits for PoCL's compile of the
 * binary (~4 s for the reference view's program, ~17 s for havoc's); it returns at once. That process is forked
 * after OpenCL's threads started: at the command's end, when no OpenCL call is under way, the saving thread needs
 * none of them; alarm() ends it should it ever block. With IACSG_CACHE_SAVE=wait the command saves them itself
 * before it ends (for scripts that time the runs that follow, which a saver at work would slow). */
void clrt_cache_defer_saves(void);
void clrt_cache_save_deferred(void);

#endif
