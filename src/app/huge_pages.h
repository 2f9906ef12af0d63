// Transparent huge pages for the heap. glibc's malloc asks the kernel for
// 2 MB pages when its tunable glibc.malloc.hugetlb=1 is set (glibc 2.35 and
// later); on a kernel that gives them only on request (transparent_hugepage
// "madvise", the common default), a production scene's load otherwise
// spends a third of its time in page faults, one per 4 KB of memory first
// touched (docs/performance.md, "Huge pages"). Tunables are read when a
// process starts, so the command starts itself once more with the tunable
// added to GLIBC_TUNABLES. LANTERN_HUGE_PAGES=0 leaves the process as it is.
#pragma once

#include <cstddef>

namespace lantern {

// Returns only if the process keeps running as it is: the tunable is set
// already, the kernel gives huge pages always or never, the user said no,
// or starting again failed.
void restart_with_huge_pages(char** argv);

// Whether the heap asks for huge pages (the tunable is set, the kernel's
// policy gives them), and how much of the process is in them now
// (AnonHugePages of /proc/self/smaps_rollup): --stats reports both.
bool heap_in_huge_pages();
size_t anon_huge_page_bytes();

}  // namespace lantern
