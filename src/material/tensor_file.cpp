#include "material/tensor_file.h"

#include <cstring>
#include <fstream>
#include <iterator>
#include <stdexcept>

namespace lantern {

namespace {

size_t type_size(TensorFile::Type t) {
  switch (t) {
    case TensorFile::Type::UInt8:
    case TensorFile::Type::Int8:
      return 1;
    case TensorFile::Type::UInt16:
    case TensorFile::Type::Int16:
    case TensorFile::Type::Float16:
      return 2;
    case TensorFile::Type::UInt32:
    case TensorFile::Type::Int32:
    case TensorFile::Type::Float32:
      return 4;
    case TensorFile::Type::UInt64:
    case TensorFile::Type::Int64:
    case TensorFile::Type::Float64:
      return 8;
    case TensorFile::Type::Invalid:
      break;
  }
  return 0;
}

const char* type_name(TensorFile::Type t) {
  static const char* names[] = {"invalid", "uint8",  "int8",  "uint16",  "int16",   "uint32",
                                "int32",   "uint64", "int64", "float16", "float32", "float64"};
  return uint8_t(t) < 12 ? names[uint8_t(t)] : "unknown";
}

// Reads little-endian values from the file's bytes, failing past the end.
struct Reader {
  const std::vector<uint8_t>& bytes;
  const std::string& path;
  size_t at = 0;
  template <class T>
  T read(const char* what) {
    if (bytes.size() - at < sizeof(T))
      throw std::runtime_error(path + ": tensor file ends inside its header (reading " + what + ")");
    T v;
    std::memcpy(&v, &bytes[at], sizeof(T));
    at += sizeof(T);
    return v;
  }
};

const char kTensorMagic[12] = {'t', 'e', 'n', 's', 'o', 'r', '_', 'f', 'i', 'l', 'e', '\0'};

}  // namespace

uint64_t TensorFile::Field::count() const {
  uint64_t n = 1;
  for (uint64_t s : shape) n *= s;
  return n;
}

TensorFile::TensorFile(const std::string& path) : path_(path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path + ": cannot open the tabulated BSDF file");
  const std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw std::runtime_error(path + ": cannot read the tabulated BSDF file");
  if (bytes.size() < 18 || std::memcmp(bytes.data(), kTensorMagic, 12) != 0)
    throw std::runtime_error(path + ": not a tensor file (expected it to begin with \"tensor_file\")");
  if (bytes[12] != 1 || bytes[13] != 0)
    throw std::runtime_error(path + ": tensor file version " + std::to_string(bytes[12]) + "." +
                             std::to_string(bytes[13]) + " (expected 1.0)");
  Reader r{bytes, path_, 14};
  const uint32_t n_fields = r.read<uint32_t>("the field count");
  for (uint32_t f = 0; f < n_fields; ++f) {
    const uint16_t name_length = r.read<uint16_t>("a field name's length");
    if (bytes.size() - r.at < name_length) throw std::runtime_error(path + ": tensor file ends inside a field name");
    std::string name(reinterpret_cast<const char*>(&bytes[r.at]), name_length);
    r.at += name_length;
    Field field;
    const uint16_t rank = r.read<uint16_t>("a field's rank");
    field.type = Type(r.read<uint8_t>("a field's type"));
    const uint64_t offset = r.read<uint64_t>("a field's offset");
    const size_t size = type_size(field.type);
    if (size == 0)
      throw std::runtime_error(path + ": field \"" + name + "\" has an unknown element type " +
                               std::to_string(int(field.type)));
    uint64_t total = size;
    for (uint16_t d = 0; d < rank; ++d) {
      field.shape.push_back(r.read<uint64_t>("a field's shape"));
      // The data must fit in the file: this bounds every product.
      if (field.shape.back() != 0 && total > bytes.size() / field.shape.back())
        throw std::runtime_error(path + ": field \"" + name + "\" is larger than the file");
      total *= field.shape.back();
    }
    if (offset > bytes.size() || total > bytes.size() - offset)
      throw std::runtime_error(path + ": field \"" + name + "\" lies past the end of the file (offset " +
                               std::to_string(offset) + ", " + std::to_string(total) + " bytes, file " +
                               std::to_string(bytes.size()) + " bytes)");
    field.bytes.assign(bytes.begin() + std::ptrdiff_t(offset), bytes.begin() + std::ptrdiff_t(offset + total));
    fields_[name] = std::move(field);
  }
}

const TensorFile::Field& TensorFile::field(const std::string& name, Type type, size_t rank) const {
  auto it = fields_.find(name);
  if (it == fields_.end()) throw std::runtime_error(path_ + ": the tabulated BSDF has no field \"" + name + "\"");
  const Field& f = it->second;
  if (f.type != type || f.shape.size() != rank)
    throw std::runtime_error(path_ + ": field \"" + name + "\" holds " + type_name(f.type) + " of rank " +
                             std::to_string(f.shape.size()) + " (expected " + type_name(type) + " of rank " +
                             std::to_string(rank) + ")");
  return f;
}

std::vector<float> TensorFile::floats(const std::string& name, size_t rank) const {
  const Field& f = field(name, Type::Float32, rank);
  std::vector<float> v(f.bytes.size() / 4);
  if (!v.empty()) std::memcpy(v.data(), f.bytes.data(), v.size() * 4);
  return v;
}

std::vector<uint8_t> tensor_file_bytes(const std::vector<TensorFieldOut>& fields) {
  std::vector<uint8_t> out(kTensorMagic, kTensorMagic + 12);
  auto put = [&](const void* p, size_t n) {
    const uint8_t* b = static_cast<const uint8_t*>(p);
    out.insert(out.end(), b, b + n);
  };
  out.push_back(1), out.push_back(0);
  const uint32_t n = uint32_t(fields.size());
  put(&n, 4);
  size_t header = out.size();
  for (const TensorFieldOut& f : fields) header += 2 + f.name.size() + 2 + 1 + 8 + 8 * f.shape.size();
  uint64_t offset = header;
  for (const TensorFieldOut& f : fields) {
    const uint16_t len = uint16_t(f.name.size()), rank = uint16_t(f.shape.size());
    put(&len, 2), put(f.name.data(), f.name.size()), put(&rank, 2);
    out.push_back(uint8_t(f.type));
    put(&offset, 8);
    for (uint64_t s : f.shape) put(&s, 8);
    offset += f.bytes.size();
  }
  for (const TensorFieldOut& f : fields) put(f.bytes.data(), f.bytes.size());
  return out;
}

}  // namespace lantern
