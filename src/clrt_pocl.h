/* src/clrt_pocl.h -- PoCL's program binaries made cheap to load: without the program's LLVM IR.
 *
 * PoCL's binary ("poclbin", format 9: PoCL 3.x) holds the program's LLVM bitcode (program.bc) and, for each kernel,
 * its compiled work-group functions: always the generic one, which takes any local size, and the specialised ones
 * the process had launched. Built from such a binary, PoCL parses the whole bitcode (in case a new specialisation
 * must be compiled later): 25-40 ms of every command for a BRL-CAD scene's 400 KB program, most of its cached
 * build. Without the bitcode it uses the compiled functions as they are, the specialised one where the launch
 * matches it, else the generic one, and parses nothing.
 *
 * So the program cache (src/clrt_cache.c) stores PoCL's binaries without their bitcode, where every kernel has its
 * generic function (without it PoCL would abort at a launch it cannot serve). PoCL unpacks a binary into its own
 * cache directory named by the binary's build hash, and reads program.bc back from there if that directory has
 * one (the build from source wrote it): the stripped binary gets a build hash of its own, the source's with its
 * last character outside PoCL's alphabet (A-P), so that it unpacks into a directory without the bitcode. */
#ifndef IACSG_CLRT_POCL_H
#define IACSG_CLRT_POCL_H
#include <stddef.h>

/* The binary rewritten in place without its bitcode; its new size (smaller), or `size` with the bytes untouched
 * where it is not a PoCL binary of the known format with one program.bc and a generic function for each kernel. */
size_t clrt_pocl_binary_without_ir(unsigned char *bin, size_t size);

#endif
