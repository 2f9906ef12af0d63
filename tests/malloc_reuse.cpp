// The test programs keep freed memory for their next allocation. A test
// renders dozens of times, and each render's pools, given back to the
// kernel and asked for again, cost a page fault per page: a quarter of a
// bdpt comparison's time went to the kernel (perf stat: 66,770 faults and
// 0.57 s of system time in a 1.6 s test; 4,940 and 0.06 s with this). One
// render per process, as `lantern render` makes, faults its pages once
// whatever glibc does, so the renderer itself leaves the allocator alone.
// The sanitizers' allocators ignore these settings.
#include <malloc.h>

namespace {

bool keep_freed_memory() {
  // Large blocks from the heap rather than their own mappings (32 MiB is
  // the most glibc takes), and the heap's top not handed back.
  mallopt(M_MMAP_THRESHOLD, 32 << 20);
  mallopt(M_TRIM_THRESHOLD, 1 << 30);
  return true;
}

const bool kKept = keep_freed_memory();

}  // namespace
