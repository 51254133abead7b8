/* src/cli_view_sdl.h -- SDL2 for `iacsg view`, loaded with dlopen when the viewer starts (src/cli_view_sdl.c).
 * The command is not linked with SDL2, so the dynamic linking of SDL2 and its libraries costs nothing to the
 * other subcommands, and the command runs (all but `view`) where SDL2 is not installed. Only SDL2's headers are
 * needed at build time, for the types.
 *
 * sdl.NAME is SDL_NAME, for the functions listed in VIEW_SDL_FUNCTIONS. */
#ifndef IACSG_CLI_VIEW_SDL_H
#define IACSG_CLI_VIEW_SDL_H
#include <SDL.h>

/* X(return type, name, parameter types) */
#define VIEW_SDL_FUNCTIONS                                                                                     \
    X(int, Init, (Uint32))                                                                                     \
    X(const char *, GetError, (void))                                                                          \
    X(SDL_Window *, CreateWindow, (const char *, int, int, int, int, Uint32))                                  \
    X(void, DestroyWindow, (SDL_Window *))                                                                     \
    X(void, SetWindowTitle, (SDL_Window *, const char *))                                                      \
    X(void, SetWindowMaximumSize, (SDL_Window *, int, int))                                                    \
    X(void, ShowWindow, (SDL_Window *))                                                                        \
    X(SDL_Renderer *, CreateRenderer, (SDL_Window *, int, Uint32))                                             \
    X(void, DestroyRenderer, (SDL_Renderer *))                                                                 \
    X(SDL_Texture *, CreateTexture, (SDL_Renderer *, Uint32, int, int, int))                                   \
    X(void, DestroyTexture, (SDL_Texture *))                                                                   \
    X(int, UpdateTexture, (SDL_Texture *, const SDL_Rect *, const void *, int))                                \
    X(int, RenderClear, (SDL_Renderer *))                                                                      \
    X(int, RenderCopy, (SDL_Renderer *, SDL_Texture *, const SDL_Rect *, const SDL_Rect *))                    \
    X(void, RenderPresent, (SDL_Renderer *))                                                                   \
    X(int, WaitEventTimeout, (SDL_Event *, int))                                                               \
    X(SDL_Keymod, GetModState, (void))

typedef struct {
#define X(ret, name, params) ret(SDLCALL *name) params;
    VIEW_SDL_FUNCTIONS
#undef X
} view_sdl;

/* Loads libSDL2-2.0.so.0 into *sdl; returns 0, or -1 after writing the reason into why[size]. The library
 * stays loaded until the process ends. */
int view_sdl_load(view_sdl *sdl, char *why, size_t size);

#endif
