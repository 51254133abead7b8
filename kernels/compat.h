/* kernels/compat.h -- what the kernel headers need beyond ia/compat.h, so that they compile both as OpenCL C
 * (the device) and as host C11 (the tests check the very code the device runs, as hashcat does).
 *
 *   KERNEL_CONSTANT   the address space of the parameter block (__constant on the device, nothing on the host).
 *   KERNEL_GLOBAL     the address space of the scene's tables and per-ray buffers (__global on the device).
 *   bisect_index      the node index of the bisection: 32 bits for float, 64 for double (see traverse.h).
 */
#ifndef KERNELS_COMPAT_H
#define KERNELS_COMPAT_H
#include "../ia/ia.h"

#if IA_DEVICE
#define KERNEL_CONSTANT __constant
#define KERNEL_GLOBAL __global
typedef uint kernel_u32;
typedef ulong kernel_u64;
#else
#include <stdint.h>
#define KERNEL_CONSTANT
#define KERNEL_GLOBAL
typedef uint32_t kernel_u32;
typedef uint64_t kernel_u64;
#endif

#endif
