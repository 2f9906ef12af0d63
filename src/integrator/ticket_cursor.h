// The render loop's walk over its units (waves numbered through the whole
// render), pass by pass: all of them, or with MPI's tickets only those the
// tickets name (integrator/run_passes.h).
#pragma once

#include <cstdint>
#include <functional>

namespace lantern {

// Walks the units this render wants, pass by pass, stopping at those its
// tickets name (all of them without a ticket source).
class TicketCursor {
 public:
  explicit TicketCursor(const std::function<uint64_t()>& source) : source_(source) {}
  // Moves `wave` to the next unit of this pass to render; false when the
  // pass has none left (the ticket, if any, is kept for a later pass).
  template <class Wanted>
  bool next(uint32_t first, uint32_t& wave, uint32_t waves, const Wanted& wanted) {
    if (exhausted_) return false;
    if (source_ && !holding_) {
      target_ = source_();
      holding_ = true;
      if (target_ == UINT64_MAX) {
        exhausted_ = true;
        return false;
      }
    }
    for (; wave < waves; ++wave) {
      if (!wanted(first, wave)) continue;
      if (!source_ || seen_ == target_) {
        ++seen_;
        holding_ = false;
        return true;
      }
      ++seen_;
    }
    return false;
  }
  bool exhausted() const { return exhausted_; }

 private:
  const std::function<uint64_t()>& source_;
  uint64_t seen_ = 0, target_ = 0;  // wanted units passed; the ticket held
  bool holding_ = false, exhausted_ = false;
};

}  // namespace lantern
