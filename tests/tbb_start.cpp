// The test programs start oneTBB's allocator before any test, with
// LeakSanitizer looking away, and clear glibc's last dlerror. The
// allocator's start-up opens a library (dlopen), and AddressSanitizer's own
// looks up functions glibc lacks (dlsym): glibc keeps what they allocate,
// a grown list of global objects and an error message, to the end.
// LeakSanitizer reported them in every test process, and matching them
// against scripts/lsan.supp started llvm-symbolizer each time: a quarter
// of a second of CPU at every exit (a parser test took 0.34 s, 0.08 s
// without leak checking), in each of the sanitizer suite's four hundred
// processes. Allocations made while LeakSanitizer is disabled are never
// reported; those of the tests themselves still are.
#include <dlfcn.h>
#include <oneapi/tbb/global_control.h>
#include <oneapi/tbb/parallel_for.h>

#include "sanitizer.h"

#if LANTERN_ASAN
#include <sanitizer/lsan_interface.h>
#endif

namespace {

bool start_tbb() {
#if LANTERN_ASAN
  __lsan_disable();
#endif
  // Attaching a handle allocates through oneTBB, which starts its
  // allocator; a first parallel loop starts its scheduler.
  oneapi::tbb::task_scheduler_handle handle{oneapi::tbb::attach{}};
  handle.release();
  oneapi::tbb::parallel_for(0, 2, [](int) {});
  // The first call hands the pending message over, the second frees it.
  dlerror();
  dlerror();
#if LANTERN_ASAN
  __lsan_enable();
#endif
  return true;
}

const bool kStarted = start_tbb();

}  // namespace
