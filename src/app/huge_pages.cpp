#include "app/huge_pages.h"

#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <string>

namespace lantern {

namespace {

constexpr const char* kTunable = "glibc.malloc.hugetlb=1";

// The kernel's policy, as /sys shows it: "always [madvise] never".
std::string policy() {
  std::ifstream f("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string p;
  std::getline(f, p);
  return p;
}
bool huge_pages_on_request() { return policy().find("[madvise]") != std::string::npos; }

bool tunable_set() {
  const char* t = std::getenv("GLIBC_TUNABLES");
  return t && std::string(t).find(kTunable) != std::string::npos;
}

}  // namespace

void restart_with_huge_pages(char** argv) {
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
  return;  // the sanitizers' allocators read no glibc tunables
#endif
  const char* no = std::getenv("LANTERN_HUGE_PAGES");
  if (no && std::string(no) == "0") return;
  // Under valgrind a restart would run on without it.
  const char* preload = std::getenv("LD_PRELOAD");
  if (preload && std::string(preload).find("vgpreload") != std::string::npos) return;
  const char* tunables = std::getenv("GLIBC_TUNABLES");
  const std::string given = tunables ? tunables : "";
  // Set (by the user, or by this process before it started again): as it is.
  if (given.find("glibc.malloc.hugetlb") != std::string::npos) return;
  if (!huge_pages_on_request()) return;
  const std::string with = given.empty() ? kTunable : given + ":" + kTunable;
  if (setenv("GLIBC_TUNABLES", with.c_str(), 1) != 0) return;
  execv("/proc/self/exe", argv);
  // Still here: the process goes on as it is, without the tunable in its
  // environment, so that nothing it starts tries again.
  if (tunables) setenv("GLIBC_TUNABLES", given.c_str(), 1);
  else unsetenv("GLIBC_TUNABLES");
}

bool heap_in_huge_pages() {
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
  return false;
#endif
  const std::string p = policy();
  return p.find("[always]") != std::string::npos || (p.find("[madvise]") != std::string::npos && tunable_set());
}

size_t anon_huge_page_bytes() {
  std::ifstream f("/proc/self/smaps_rollup");
  std::string key;
  size_t kb = 0;
  while (f >> key) {
    if (key == "AnonHugePages:" && f >> kb) return kb * 1024;
    f.ignore(1 << 20, '\n');
  }
  return 0;
}

}  // namespace lantern
