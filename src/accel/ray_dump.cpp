#include "accel/ray_dump.h"

#include <stdexcept>

namespace lantern {

RayDump::RayDump(const std::string& path) : file_(std::fopen(path.c_str(), "wb")) {
  if (!file_) throw std::runtime_error("cannot write the ray dump " + path);
}

RayDump::~RayDump() {
  if (file_) std::fclose(file_);
}

void RayDump::write(RayKind kind, const RayBatch& b) {
  std::lock_guard<std::mutex> lock(mutex_);
  buffer_.resize(size_t(b.count) * 8);
  for (uint32_t i = 0; i < b.count; ++i) {
    float* r = &buffer_[size_t(i) * 8];
    r[0] = b.org_x[i], r[1] = b.org_y[i], r[2] = b.org_z[i];
    r[3] = b.dir_x[i], r[4] = b.dir_y[i], r[5] = b.dir_z[i];
    r[6] = b.tnear[i], r[7] = b.tfar[i];
  }
  uint32_t header[2] = {uint32_t(kind), b.count};
  std::fwrite(header, sizeof header, 1, file_);
  std::fwrite(buffer_.data(), sizeof(float), buffer_.size(), file_);
}

std::vector<DumpedBatch> read_ray_dump(const std::string& path) {
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) throw std::runtime_error("cannot open the ray dump " + path);
  std::vector<DumpedBatch> batches;
  uint32_t header[2];
  std::vector<float> rec;
  while (std::fread(header, sizeof header, 1, f) == 1) {
    if (header[0] > 3 || header[1] > (1u << 26)) {
      std::fclose(f);
      throw std::runtime_error(path + ": not a ray dump (bad batch header)");
    }
    rec.resize(size_t(header[1]) * 8);
    if (std::fread(rec.data(), sizeof(float), rec.size(), f) != rec.size()) {
      std::fclose(f);
      throw std::runtime_error(path + ": truncated ray dump");
    }
    DumpedBatch& d = batches.emplace_back();
    d.kind = header[0];
    d.rays.reserve(header[1]);
    for (uint32_t i = 0; i < header[1]; ++i) {
      const float* r = &rec[size_t(i) * 8];
      d.rays.push(Vec3(r[0], r[1], r[2]), Vec3(r[3], r[4], r[5]), r[6], r[7], 0.f);  // (dumps keep no time: replayed at the shutter's start)
    }
  }
  std::fclose(f);
  return batches;
}

}  // namespace lantern
