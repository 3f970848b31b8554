#include "hd_mem.h"

#include <stdlib.h>
#include <sys/mman.h>

#define HD_MEM_HUGE ((size_t)2 << 20)

void *hd_mem_alloc(size_t bytes) {
  size_t align = bytes >= HD_MEM_HUGE ? HD_MEM_HUGE : 64;
  size_t n = (bytes + align - 1) / align * align;
  if (n == 0) n = align;
  void *p = aligned_alloc(align, n);
#ifdef MADV_HUGEPAGE
  if (p && align == HD_MEM_HUGE) (void)madvise(p, n, MADV_HUGEPAGE); /* a hint: may be refused */
#endif
  return p;
}
