#include "scene/ply.h"

#include <zlib.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "lantern/error.h"

namespace lantern {

namespace {

enum class Scalar { I8, U8, I16, U16, I32, U32, F32, F64, None };

Scalar parse_scalar(const std::string& s) {
  if (s == "char" || s == "int8") return Scalar::I8;
  if (s == "uchar" || s == "uint8") return Scalar::U8;
  if (s == "short" || s == "int16") return Scalar::I16;
  if (s == "ushort" || s == "uint16") return Scalar::U16;
  if (s == "int" || s == "int32") return Scalar::I32;
  if (s == "uint" || s == "uint32") return Scalar::U32;
  if (s == "float" || s == "float32") return Scalar::F32;
  if (s == "double" || s == "float64") return Scalar::F64;
  return Scalar::None;
}

size_t scalar_size(Scalar s) {
  switch (s) {
    case Scalar::I8: case Scalar::U8: return 1;
    case Scalar::I16: case Scalar::U16: return 2;
    case Scalar::I32: case Scalar::U32: case Scalar::F32: return 4;
    case Scalar::F64: return 8;
    case Scalar::None: return 0;
  }
  return 0;
}

struct Property {
  std::string name;
  Scalar type = Scalar::None;
  Scalar count_type = Scalar::None;  // != None for list properties
};

struct Element {
  std::string name;
  uint64_t count = 0;
  std::vector<Property> props;
};

enum class Format { Ascii, BinaryLE, BinaryBE };

class Reader {
 public:
  Reader(const std::string& data, size_t pos, Format f, const std::string& name)
      : d_(data), pos_(pos), format_(f), name_(name) {}

  double read(Scalar t) {
    if (format_ == Format::Ascii) return read_ascii();
    size_t n = scalar_size(t);
    if (pos_ + n > d_.size()) fail("the binary data ends early (truncated file?)");
    unsigned char b[8];
    std::memcpy(b, d_.data() + pos_, n);
    pos_ += n;
    bool swap = (format_ == Format::BinaryBE) == (std::endian::native == std::endian::little);
    if (swap)
      for (size_t i = 0; i < n / 2; ++i) std::swap(b[i], b[n - 1 - i]);
    switch (t) {
      case Scalar::I8: return double(int8_t(b[0]));
      case Scalar::U8: return double(b[0]);
      case Scalar::I16: { int16_t v; std::memcpy(&v, b, 2); return v; }
      case Scalar::U16: { uint16_t v; std::memcpy(&v, b, 2); return v; }
      case Scalar::I32: { int32_t v; std::memcpy(&v, b, 4); return v; }
      case Scalar::U32: { uint32_t v; std::memcpy(&v, b, 4); return v; }
      case Scalar::F32: { float v; std::memcpy(&v, b, 4); return v; }
      case Scalar::F64: { double v; std::memcpy(&v, b, 8); return v; }
      case Scalar::None: break;
    }
    return 0.0;
  }
  size_t remaining() const { return d_.size() - pos_; }
  // The next n bytes of binary data, or nullptr (nothing consumed) if the
  // data ends first.
  const char* take(size_t n) {
    if (n > remaining()) return nullptr;
    const char* p = d_.data() + pos_;
    pos_ += n;
    return p;
  }
  bool native_binary() const {
    return format_ != Format::Ascii && (format_ == Format::BinaryLE) == (std::endian::native == std::endian::little);
  }
  [[noreturn]] void fail(const std::string& what) const { throw InputError({name_, 0, 0}, "PLY: " + what); }

 private:
  double read_ascii() {
    while (pos_ < d_.size() && std::isspace((unsigned char)d_[pos_])) ++pos_;
    if (pos_ >= d_.size()) fail("the ASCII data ends early (truncated file?)");
    const char* start = d_.data() + pos_;
    char* end = nullptr;
    double v = std::strtod(start, &end);
    if (end == start) fail("expected a number in the ASCII data, found \"" + printable(std::string_view(start, std::min<size_t>(16, remaining()))) + "\"");
    pos_ += size_t(end - start);
    return v;
  }
  const std::string& d_;
  size_t pos_;
  Format format_;
  const std::string& name_;
};

std::string read_whole_file(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::exists(path, ec) && !std::filesystem::is_regular_file(path, ec))
    throw InputError({path, 0, 0}, "PLY file is not a regular file");
  // Uncompressed: one read into a buffer of the file's size.
  {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError({path, 0, 0}, "cannot open PLY file");
    char magic[2] = {0, 0};
    in.read(magic, 2);
    if (!(magic[0] == '\x1f' && magic[1] == '\x8b')) {
      std::string out(std::filesystem::file_size(path, ec), '\0');
      if (ec) throw InputError({path, 0, 0}, "cannot read PLY file: " + ec.message());
      in.clear();
      in.seekg(0);
      if (!in.read(out.data(), std::streamsize(out.size()))) throw InputError({path, 0, 0}, "cannot read PLY file");
      return out;
    }
  }
  // gzip (.ply.gz): zlib, in chunks, the uncompressed size being unknown.
  gzFile f = gzopen(path.c_str(), "rb");
  if (!f) throw InputError({path, 0, 0}, "cannot open PLY file");
  gzbuffer(f, 1 << 20);
  std::string out;
  char buf[1 << 16];
  for (;;) {
    int n = gzread(f, buf, sizeof buf);
    if (n < 0) {
      int err;
      std::string msg = gzerror(f, &err);
      gzclose(f);
      throw InputError({path, 0, 0}, "cannot read PLY file: " + msg);
    }
    if (n == 0) break;
    out.append(buf, size_t(n));
  }
  gzclose(f);
  return out;
}

// Bulk path for an element "vertex" whose properties are all float32 in the
// machine's byte order: one memcpy per row. Returns false (nothing read) for
// any other layout.
bool read_float_vertices(Reader& r, const Element& e, std::array<int, 3> p, std::array<int, 3> n, std::array<int, 2> uv,
                         PlyMesh& mesh) {
  if (!r.native_binary() || e.props.size() > 32) return false;
  for (const Property& q : e.props)
    if (q.count_type != Scalar::None || q.type != Scalar::F32) return false;
  const size_t row = 4 * e.props.size();
  const char* data = r.take(row * e.count);
  if (!data) r.fail("the binary data ends early (truncated file?)");
  float v[32];
  for (uint64_t i = 0; i < e.count; ++i) {
    std::memcpy(v, data + i * row, row);
    mesh.positions.emplace_back(v[p[0]], v[p[1]], v[p[2]]);
    if (n[0] >= 0) mesh.normals.emplace_back(v[n[0]], v[n[1]], v[n[2]]);
    if (uv[0] >= 0) mesh.uvs.emplace_back(v[uv[0]], v[uv[1]]);
  }
  return true;
}

// Bulk path for an element "face" with the single property
// `list uchar int|uint vertex_indices` in the machine's byte order.
// Triangles are copied directly; other polygons are fan-split.
bool read_triangle_faces(Reader& r, const Element& e, PlyMesh& mesh) {
  if (!r.native_binary() || e.props.size() != 1) return false;
  const Property& q = e.props[0];
  if ((q.count_type != Scalar::U8 && q.count_type != Scalar::I8) || (q.type != Scalar::I32 && q.type != Scalar::U32) ||
      (q.name != "vertex_indices" && q.name != "vertex_index"))
    return false;
  mesh.triangles.reserve(mesh.triangles.size() + e.count);
  uint32_t poly[255];
  for (uint64_t i = 0; i < e.count; ++i) {
    const char* c = r.take(1);
    if (!c) r.fail("the binary data ends early (truncated file?)");
    const int count = q.count_type == Scalar::U8 ? int((unsigned char)*c) : int((signed char)*c);
    if (count < 3) r.fail("face " + std::to_string(i) + " has fewer than 3 vertices");
    const char* idx = r.take(4 * size_t(count));
    if (!idx) r.fail("the binary data ends early (truncated file?)");
    std::memcpy(poly, idx, 4 * size_t(count));
    if (q.type == Scalar::I32)
      for (int j = 0; j < count; ++j)
        if (int32_t(poly[j]) < 0) r.fail("face " + std::to_string(i) + " has an invalid vertex index");
    if (count == 4) mesh.quad_first.push_back(uint32_t(mesh.triangles.size()));
    for (int j = 1; j + 1 < count; ++j) mesh.triangles.emplace_back(poly[0], poly[j], poly[j + 1]);
  }
  return true;
}

}  // namespace

PlyMesh read_ply(const std::string& path) { return parse_ply(read_whole_file(path), path); }

PlyMesh parse_ply(const std::string& data, const std::string& name) {
  auto fail = [&](int line, const std::string& what) -> void { throw InputError({name, line, 0}, "PLY header: " + what); };
  size_t header_end = data.find("end_header");
  if (data.compare(0, 3, "ply") != 0) fail(1, "the file does not start with \"ply\"");
  if (header_end == std::string::npos) fail(0, "no \"end_header\" line");
  size_t body = data.find('\n', header_end);
  body = body == std::string::npos ? data.size() : body + 1;

  std::istringstream header(data.substr(0, header_end));
  std::string line;
  int lineno = 0;
  Format format = Format::Ascii;
  bool have_format = false;
  std::vector<Element> elements;
  while (std::getline(header, line)) {
    ++lineno;
    std::istringstream ls(line);
    std::string kw;
    ls >> kw;
    if (kw.empty() || kw == "ply" || kw == "comment" || kw == "obj_info") continue;
    if (kw == "format") {
      std::string f, version;
      ls >> f >> version;
      if (f == "ascii") format = Format::Ascii;
      else if (f == "binary_little_endian") format = Format::BinaryLE;
      else if (f == "binary_big_endian") format = Format::BinaryBE;
      else fail(lineno, "unknown format \"" + printable(f) + "\"; expected ascii, binary_little_endian or binary_big_endian");
      have_format = true;
    } else if (kw == "element") {
      Element e;
      long long count = -1;
      ls >> e.name >> count;
      if (e.name.empty() || count < 0) fail(lineno, "expected \"element NAME COUNT\"");
      e.count = uint64_t(count);
      elements.push_back(e);
    } else if (kw == "property") {
      if (elements.empty()) fail(lineno, "property before any element");
      Property p;
      std::string t;
      ls >> t;
      if (t == "list") {
        std::string ct, it;
        ls >> ct >> it >> p.name;
        p.count_type = parse_scalar(ct);
        p.type = parse_scalar(it);
        if (p.count_type == Scalar::None || p.type == Scalar::None) fail(lineno, "bad list property types \"" + printable(ct + " " + it) + "\"");
      } else {
        p.type = parse_scalar(t);
        ls >> p.name;
        if (p.type == Scalar::None) fail(lineno, "unknown property type \"" + printable(t) + "\"");
      }
      if (p.name.empty()) fail(lineno, "property without a name");
      elements.back().props.push_back(p);
    } else {
      fail(lineno, "unexpected keyword \"" + printable(kw) + "\"");
    }
  }
  if (!have_format) fail(0, "no \"format\" line");

  // Reject counts the data cannot possibly hold before allocating anything.
  size_t available = data.size() - body;
  for (const Element& e : elements) {
    size_t min_bytes = format == Format::Ascii ? 2 : 0;
    for (const Property& p : e.props) min_bytes += format == Format::Ascii ? 0 : scalar_size(p.count_type != Scalar::None ? p.count_type : p.type);
    if (min_bytes == 0) min_bytes = 1;
    if (e.count > available / min_bytes + 1)
      fail(0, "element \"" + printable(e.name) + "\" claims " + std::to_string(e.count) + " entries but the file holds only " +
                  std::to_string(available) + " bytes of data");
  }

  PlyMesh mesh;
  Reader r(data, body, format, name);
  for (const Element& e : elements) {
    bool is_vertex = e.name == "vertex", is_face = e.name == "face";
    int ix = -1, iy = -1, iz = -1, inx = -1, iny = -1, inz = -1, iu = -1, iv = -1, iidx = -1;
    for (int k = 0; k < int(e.props.size()); ++k) {
      const std::string& n = e.props[size_t(k)].name;
      if (n == "x") ix = k; else if (n == "y") iy = k; else if (n == "z") iz = k;
      else if (n == "nx") inx = k; else if (n == "ny") iny = k; else if (n == "nz") inz = k;
      else if (n == "u" || n == "s" || n == "texture_u" || n == "texture_s") iu = k;
      else if (n == "v" || n == "t" || n == "texture_v" || n == "texture_t") iv = k;
      else if (n == "vertex_indices" || n == "vertex_index") iidx = k;
    }
    if (is_vertex && (ix < 0 || iy < 0 || iz < 0)) r.fail("element \"vertex\" lacks x, y or z");
    bool has_n = is_vertex && inx >= 0 && iny >= 0 && inz >= 0, has_uv = is_vertex && iu >= 0 && iv >= 0;
    if (is_face && (iidx < 0 || e.props[size_t(iidx)].count_type == Scalar::None))
      r.fail("element \"face\" lacks a vertex_indices list");
    if (is_vertex) {
      mesh.positions.reserve(e.count + 1);  // + 1: the padding vertex the scene adds for Embree
      if (has_n) mesh.normals.reserve(e.count);
      if (has_uv) mesh.uvs.reserve(e.count);
    }
    // The layouts nearly every binary PLY uses take a bulk path: vertices
    // of float properties only, and faces of one list with a byte count and
    // 32-bit indices.
    if (is_vertex && read_float_vertices(r, e, {ix, iy, iz}, has_n ? std::array{inx, iny, inz} : std::array{-1, -1, -1},
                                         has_uv ? std::array{iu, iv} : std::array{-1, -1}, mesh))
      continue;
    if (is_face && read_triangle_faces(r, e, mesh)) continue;
    double vals[32];
    std::vector<uint32_t> poly;
    for (uint64_t i = 0; i < e.count; ++i) {
      for (int k = 0; k < int(e.props.size()); ++k) {
        const Property& p = e.props[size_t(k)];
        if (p.count_type == Scalar::None) {
          double v = r.read(p.type);
          if (k < 32) vals[k] = v;
          continue;
        }
        double c = r.read(p.count_type);
        if (!(c >= 0.0) || c > 1e6 || c != std::floor(c)) r.fail("bad list length " + std::to_string(c) + " in element \"" + printable(e.name) + "\"");
        size_t n = size_t(c);
        if (!(is_face && k == iidx)) {
          for (size_t j = 0; j < n; ++j) r.read(p.type);
          continue;
        }
        poly.resize(n);
        for (size_t j = 0; j < n; ++j) {
          double v = r.read(p.type);
          if (!(v >= 0.0) || v > 4294967295.0 || v != std::floor(v)) r.fail("face " + std::to_string(i) + " has an invalid vertex index");
          poly[j] = uint32_t(v);
        }
        if (n < 3) r.fail("face " + std::to_string(i) + " has fewer than 3 vertices");
        if (n == 4) mesh.quad_first.push_back(uint32_t(mesh.triangles.size()));
        for (size_t j = 1; j + 1 < n; ++j) mesh.triangles.emplace_back(poly[0], poly[j], poly[j + 1]);
      }
      if (is_vertex) {
        if (std::max({ix, iy, iz, inx, iny, inz, iu, iv}) >= 32)
          r.fail("x, y, z, normals and uvs must be among the first 32 vertex properties");
        mesh.positions.emplace_back(float(vals[ix]), float(vals[iy]), float(vals[iz]));
        if (has_n) mesh.normals.emplace_back(float(vals[inx]), float(vals[iny]), float(vals[inz]));
        if (has_uv) mesh.uvs.emplace_back(float(vals[iu]), float(vals[iv]));
      }
    }
  }
  for (const glm::uvec3& t : mesh.triangles)
    if (t.x >= mesh.positions.size() || t.y >= mesh.positions.size() || t.z >= mesh.positions.size())
      throw InputError({name, 0, 0}, "PLY: a face refers to vertex " + std::to_string(std::max({t.x, t.y, t.z})) +
                                         " but there are only " + std::to_string(mesh.positions.size()) + " vertices");
  return mesh;
}

}  // namespace lantern
