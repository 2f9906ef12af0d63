// FNV-1a, 64 bit: a cheap running hash, enough to tell a damaged or edited
// file from the one expected (checkpoint checksums, scene identity).
#pragma once

#include <cstddef>
#include <cstdint>

namespace lantern {

struct Fnv1a {
  uint64_t h = 0xcbf29ce484222325ull;
  void add(const void* p, size_t n) {
    const unsigned char* b = static_cast<const unsigned char*>(p);
    for (size_t i = 0; i < n; ++i) h = (h ^ b[i]) * 0x100000001b3ull;
  }
};

}  // namespace lantern
