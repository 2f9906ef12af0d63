// lantern-raybench: replays the rays a render gave to Embree (dumped with
// `lantern render ... --dump-rays FILE`) through Embree alone and through
// Lantern's ray layer with each back end, one thread, so the cost of the
// layer and of each Embree interface is measured on exactly those rays.
//   lantern-raybench SCENE.pbrt RAYS.bin [Google Benchmark flags]
#include <benchmark/benchmark.h>

#include <cstdio>
#include <cstring>
#include <string>

#include "accel/ray_dump.h"
#include "accel/ray_stream.h"
#include "lantern/scene.h"
#include "scene/scene.h"

namespace {

using namespace lantern;

std::shared_ptr<Scene> g_scene;
std::vector<DumpedBatch> g_batches;
const char* kKindNames[] = {"camera", "eye_extension", "light_extension", "shadow"};

// Embree overwrites tfar (and hit fields): every replay starts from the
// recorded rays. Both variants pay the same reset.
void reset(RayBatch& work, const RayBatch& recorded) {
  std::memcpy(work.tfar.data(), recorded.tfar.data(), recorded.count * sizeof(float));
  work.count = recorded.count;
}

std::vector<RayBatch> working_copies(uint32_t kind, uint64_t* rays) {
  std::vector<RayBatch> out;
  *rays = 0;
  for (const DumpedBatch& b : g_batches)
    if (b.kind == kind) {
      out.push_back(b.rays);
      *rays += b.rays.count;
    }
  return out;
}

// rtcIntersectNp / rtcOccludedNp straight on the SoA arrays.
void embree_np(benchmark::State& state, uint32_t kind) {
  uint64_t rays;
  std::vector<RayBatch> work = working_copies(kind, &rays);
  RTCScene scene = g_scene->accel->handle();
  for (auto _ : state) {
    size_t k = 0;
    for (const DumpedBatch& b : g_batches) {
      if (b.kind != kind) continue;
      RayBatch& w = work[k++];
      reset(w, b.rays);
      RTCIntersectContext ctx;
      rtcInitIntersectContext(&ctx);
      ctx.flags = kind == 0 ? RTC_INTERSECT_CONTEXT_FLAG_COHERENT : RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
      RTCRayHitNp r{{w.org_x.data(), w.org_y.data(), w.org_z.data(), w.tnear.data(), w.dir_x.data(), w.dir_y.data(),
                     w.dir_z.data(), w.time.data(), w.tfar.data(), w.mask.data(), w.id.data(), w.flags.data()},
                    {w.ng_x.data(), w.ng_y.data(), w.ng_z.data(), w.u.data(), w.v.data(), w.prim_id.data(),
                     w.geom_id.data(), w.inst_id.data()}};
      if (kind == uint32_t(RayKind::Shadow)) {
        rtcOccludedNp(scene, &ctx, &r.ray, w.count);
      } else {
        std::fill(w.geom_id.begin(), w.geom_id.begin() + w.count, RTC_INVALID_GEOMETRY_ID);
        rtcIntersectNp(scene, &ctx, &r, w.count);
      }
    }
  }
  state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(rays));
}

// The same rays through RayStream, the only door the integrators use.
void lantern_stream(benchmark::State& state, uint32_t kind, RayBackend backend) {
  uint64_t rays;
  std::vector<RayBatch> work = working_copies(kind, &rays);
  RayStream stream(g_scene->accel->handle(), backend, nullptr);
  stream.set_scene(g_scene->accel->instance_base(), &g_scene->shapes);
  for (auto _ : state) {
    size_t k = 0;
    for (const DumpedBatch& b : g_batches) {
      if (b.kind != kind) continue;
      RayBatch& w = work[k++];
      reset(w, b.rays);
      if (kind == uint32_t(RayKind::Shadow))
        stream.occluded(w);
      else
        stream.intersect(w, RayKind(kind));
    }
  }
  state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(rays));
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: %s SCENE.pbrt RAYS.bin [benchmark flags]\n", argv[0]);
    return 2;
  }
  try {
    LoadOptions lo;
    lo.warn = [](const std::string&) {};
    g_scene = load_scene(argv[1], lo);
    g_batches = read_ray_dump(argv[2]);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
  uint64_t count[4] = {0, 0, 0, 0};
  for (const DumpedBatch& b : g_batches) count[b.kind] += b.rays.count;
  for (uint32_t k = 0; k < 4; ++k) {
    std::fprintf(stderr, "%s rays in the dump: %llu\n", kKindNames[k], (unsigned long long)count[k]);
    if (count[k] == 0) continue;
    benchmark::RegisterBenchmark((std::string("embree_np/") + kKindNames[k]).c_str(), embree_np, k);
    for (RayBackend be : {RayBackend::StreamNp, RayBackend::Stream1M, RayBackend::Single, RayBackend::Packet16})
      benchmark::RegisterBenchmark((std::string("lantern_") + name(be) + "/" + kKindNames[k]).c_str(),
                                   lantern_stream, k, be);
  }
  argv[2] = argv[0];  // Google Benchmark reads its own flags after the program name
  argc -= 2;
  argv += 2;
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  return 0;
}
