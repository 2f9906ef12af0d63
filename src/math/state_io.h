// Byte sinks and sources for what a render keeps of itself between runs:
// the film's sums (Film::write_state) and what an integrator learnt, such
// as a guiding field (GuidingField::save), written into checkpoints
// (film/checkpoint.h). Values go as the machine holds them (little-endian
// on every machine Lantern builds for); a checkpoint's fingerprint and
// checksum tell another render's or a damaged file apart.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

namespace lantern {

class StateWriter {
 public:
  virtual void write(const void* bytes, size_t n) = 0;
  template <class T>
  void put(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    write(&v, sizeof v);
  }
  // A count, then the elements.
  template <class T>
  void put_vector(const std::vector<T>& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    put(uint64_t(v.size()));
    write(v.data(), v.size() * sizeof(T));
  }

 protected:
  ~StateWriter() = default;
};

class StateReader {
 public:
  virtual void read(void* bytes, size_t n) = 0;  // throws if the source ends early
  // The bytes left, where the source knows (a list longer than them is
  // damage, not a request for memory).
  virtual uint64_t left() const { return std::numeric_limits<uint64_t>::max(); }
  template <class T>
  T get() {
    static_assert(std::is_trivially_copyable_v<T>);
    T v;
    read(&v, sizeof v);
    return v;
  }
  // What put_vector wrote; a count of more than `most` elements throws
  // (a damaged count must not ask for the machine's memory).
  template <class T>
  std::vector<T> get_vector(uint64_t most) {
    const uint64_t n = get<uint64_t>();
    if (n > most || n > left() / sizeof(T))
      throw std::runtime_error("a list of " + std::to_string(n) + " elements, more than " +
                               (n > most ? std::to_string(most) : "the bytes left hold") + " (damaged)");
    std::vector<T> v(static_cast<size_t>(n));
    read(v.data(), v.size() * sizeof(T));
    return v;
  }

 protected:
  ~StateReader() = default;
};

// In memory: a checkpoint carries an integrator's state as one block of
// bytes, which it writes after the film's.
class StringWriter final : public StateWriter {
 public:
  void write(const void* p, size_t n) override { bytes.append(static_cast<const char*>(p), n); }
  std::string bytes;
};

class StringReader final : public StateReader {
 public:
  explicit StringReader(const std::string& bytes) : bytes_(bytes) {}
  void read(void* p, size_t n) override {
    if (n > bytes_.size() - at_) throw std::runtime_error("the state ends early (damaged)");
    if (n > 0) std::memcpy(p, bytes_.data() + at_, n);
    at_ += n;
  }
  uint64_t left() const override { return bytes_.size() - at_; }

 private:
  const std::string& bytes_;
  size_t at_ = 0;
};

}  // namespace lantern
