/* src/cli_view_sdl.c -- see cli_view_sdl.h. */
#include "cli_view_sdl.h"
#include <dlfcn.h>
#include <stdio.h>

#define VIEW_SDL_LIBRARY "libSDL2-2.0.so.0" /* the runtime package's name (libsdl2-2.0-0) */

int view_sdl_load(view_sdl *sdl, char *why, size_t size) {
    void *handle = dlopen(VIEW_SDL_LIBRARY, RTLD_NOW | RTLD_LOCAL);
    if (!handle) {
        snprintf(why, size, "cannot load SDL2 (%s; Debian: apt-get install libsdl2-2.0-0)", dlerror());
        return -1;
    }
#define X(ret, name, params)                                                                                   \
    *(void **)&sdl->name = dlsym(handle, "SDL_" #name);                                                        \
    if (!sdl->name) {                                                                                          \
        snprintf(why, size, "cannot load SDL2: %s has no SDL_%s", VIEW_SDL_LIBRARY, #name);                    \
        return -1;                                                                                             \
    }
    VIEW_SDL_FUNCTIONS
#undef X
    return 0;
}
