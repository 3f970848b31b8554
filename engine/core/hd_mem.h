/* hd_mem: allocation of the engine's large arrays (bodies, queue nodes, cell heads).  Arrays of
 * 2 MiB or more are aligned on 2 MiB and offered to the kernel for transparent huge pages, which
 * keeps TLB misses down when a large system is accessed at random (N = 1e6 bodies are 128 MB). */
#ifndef HD_MEM_H
#define HD_MEM_H

#include <stddef.h>

/* Allocates bytes (> 0 is not required: 0 gives a minimal block), aligned on a cache line, not
 * initialised; release with free().  NULL on failure. */
void *hd_mem_alloc(size_t bytes);

#endif
