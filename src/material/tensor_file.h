// The tensor file format of tabulated BSDFs (the RGL's ".bsdf" files, which
// pbrt-v4's measured material reads): the 12 bytes "tensor_file\0", a
// version (1, 0), a field count, then per field its name, rank, element
// type, the byte offset of its data and its extent along each rank; all
// little-endian. Read whole; every offset and size is checked against the
// file before it is used.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace lantern {

class TensorFile {
 public:
  enum class Type : uint8_t {
    Invalid = 0,
    UInt8,
    Int8,
    UInt16,
    Int16,
    UInt32,
    Int32,
    UInt64,
    Int64,
    Float16,
    Float32,
    Float64
  };
  struct Field {
    Type type = Type::Invalid;
    std::vector<uint64_t> shape;
    std::vector<uint8_t> bytes;
    uint64_t count() const;
  };

  // Throws std::runtime_error naming the file and what is wrong.
  explicit TensorFile(const std::string& path);

  bool has(const std::string& name) const { return fields_.count(name) != 0; }
  // The field, which must exist with this type and rank; otherwise an
  // error naming the file, the field and what was expected.
  const Field& field(const std::string& name, Type type, size_t rank) const;
  // A Float32 field's values.
  std::vector<float> floats(const std::string& name, size_t rank) const;
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  std::map<std::string, Field> fields_;
};

// The bytes of a tensor file holding these fields (for tools and tests
// that write tabulated BSDFs).
struct TensorFieldOut {
  std::string name;
  TensorFile::Type type;
  std::vector<uint64_t> shape;
  std::vector<uint8_t> bytes;
};
std::vector<uint8_t> tensor_file_bytes(const std::vector<TensorFieldOut>& fields);

}  // namespace lantern
