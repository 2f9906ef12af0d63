// LANTERN_ASAN: 1 in a build under AddressSanitizer (GCC and clang tell it
// differently), where peak-memory figures are the sanitizer's, not Lantern's.
#pragma once

#if defined(__SANITIZE_ADDRESS__)
#define LANTERN_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define LANTERN_ASAN 1
#endif
#endif
#ifndef LANTERN_ASAN
#define LANTERN_ASAN 0
#endif
