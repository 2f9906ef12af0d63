// Render timelines (--trace, src/trace/timeline.h): the file parses as
// JSON in Chrome's trace-event format, spans nest on each thread, every
// wave appears once, the stage spans add up to --stats' stage times, a
// wave limit keeps only counters past it, and an interrupted render still
// yields a valid timeline.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <thread>

#include "lantern/render.h"
#include "lantern/scene.h"
#include "trace/timeline.h"

namespace lantern {
namespace {

using nlohmann::json;

std::shared_ptr<Scene> cornell() { return load_scene(std::string(LANTERN_SOURCE_DIR) + "/scenes/cornell-box.pbrt"); }

struct Traced {
  json trace;
  RenderResult result;
  size_t waves;
};

Traced traced_render(const std::string& integrator, uint64_t full_waves, int spp = 4) {
  auto scene = cornell();
  Timeline timeline(full_waves);
  RenderOptions o;
  o.integrator = parse_integrator(integrator);
  o.spp = spp;
  o.width = 64;
  o.height = 48;
  o.wave_size = 512;
  o.threads = 2;
  o.collect_stats = true;
  RenderHooks hooks;
  hooks.timeline = &timeline;
  Traced t;
  t.result = render(*scene, o, hooks);
  t.trace = json::parse(timeline.json());  // throws on malformed JSON
  const size_t pixels_per_wave = size_t(o.wave_size) / size_t(std::min(spp, 16));
  t.waves = (size_t(64 * 48) + pixels_per_wave - 1) / pixels_per_wave * size_t((spp + 15) / 16);
  return t;
}

// Spans of one thread, each inside the one before it that is still open:
// sorted by start (longer first at equal starts), a span must end by the
// time every open span does.
void expect_nested(const std::vector<std::pair<double, double>>& spans, int tid) {
  std::vector<std::pair<double, double>> s = spans;
  std::sort(s.begin(), s.end(),
            [](auto& a, auto& b) { return a.first < b.first || (a.first == b.first && a.second > b.second); });
  std::vector<double> open_ends;
  for (const auto& [ts, dur] : s) {
    const double end = ts + dur;
    while (!open_ends.empty() && open_ends.back() <= ts) open_ends.pop_back();
    if (!open_ends.empty())
      EXPECT_LE(end, open_ends.back() + 1e-3) << "thread " << tid << ": span at " << ts << " overlaps its parent";
    open_ends.push_back(end);
  }
}

TEST(Trace, TimelineOfABdptRenderIsWellFormed) {
  const Traced t = traced_render("bdpt", 0);
  ASSERT_TRUE(t.trace.contains("traceEvents"));
  std::map<int, std::vector<std::pair<double, double>>> per_thread;
  std::multiset<int64_t> waves;
  std::map<std::string, double> stage_seconds;
  std::set<int> named_threads;
  for (const json& e : t.trace["traceEvents"]) {
    const std::string ph = e.at("ph");
    if (ph == "M") {
      if (e.at("name") == "thread_name") named_threads.insert(e.at("tid").get<int>());
      continue;
    }
    ASSERT_TRUE(ph == "X" || ph == "C") << e.dump();
    const double ts = e.at("ts");
    EXPECT_GE(ts, 0.0);
    if (ph == "C") continue;
    const double dur = e.at("dur");
    ASSERT_GE(dur, 0.0) << e.dump();  // every span begins before it ends
    const int tid = e.at("tid");
    EXPECT_TRUE(named_threads.count(tid)) << "unnamed track " << tid;
    per_thread[tid].emplace_back(ts, dur);
    if (e.at("cat") == "wave") waves.insert(e.at("args").at("wave").get<int64_t>());
    if (e.at("cat") == "stage") stage_seconds[e.at("name")] += dur * 1e-6;
    if (e.at("cat") == "rays") EXPECT_GT(e.at("args").at("rays").get<int64_t>(), 0);
  }
  for (const auto& [tid, spans] : per_thread) expect_nested(spans, tid);
  // Every wave once.
  EXPECT_EQ(waves.size(), t.waves);
  for (int64_t w = 0; w < int64_t(t.waves); ++w) EXPECT_EQ(waves.count(w), 1u) << "wave " << w;
  // The stage spans are the stage times --stats reports, thread-seconds summed.
  ASSERT_FALSE(t.result.stats.stage_seconds.empty());
  for (const auto& [name, seconds] : t.result.stats.stage_seconds) {
    EXPECT_NEAR(stage_seconds[name], seconds, 0.02 * seconds + 1e-5) << name;
  }
  EXPECT_EQ(t.trace["otherData"]["waves_dropped"].get<int>(), 0);
}

TEST(Trace, WaveLimitKeepsCountersOnly) {
  const Traced t = traced_render("path", 3);
  std::set<int64_t> waves_with_spans;
  size_t counters = 0;
  for (const json& e : t.trace["traceEvents"]) {
    if (e.at("ph") == "C") ++counters;
    if (e.at("ph") == "X" && e.at("args").contains("wave"))
      waves_with_spans.insert(e.at("args").at("wave").get<int64_t>());
  }
  EXPECT_EQ(waves_with_spans, (std::set<int64_t>{0, 1, 2}));
  EXPECT_GE(counters, 2 * t.waves);  // the merge queue's, for every wave
  EXPECT_EQ(t.trace["otherData"]["waves_dropped"].get<size_t>(), t.waves - 3);
  EXPECT_EQ(t.trace["otherData"]["waves_kept_in_full"], "3");
}

// Cancelled part way: the waves that ran are in a timeline that parses.
TEST(Trace, InterruptedRenderStillGivesAValidTimeline) {
  auto scene = cornell();
  Timeline timeline;
  std::atomic<bool> cancel{false};
  RenderOptions o;
  o.integrator = Integrator::Bdpt;
  o.light_subpath_rate = 1.f;  // (no pilots: waves from the start, even in the sanitizer suite)
  o.spp = 1024;
  o.width = 64;
  o.height = 48;
  RenderHooks hooks;
  hooks.cancel = &cancel;
  hooks.timeline = &timeline;
  std::thread stopper([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    cancel = true;
  });
  const RenderResult r = render(*scene, o, hooks);
  stopper.join();
  EXPECT_TRUE(r.interrupted);
  const json trace = json::parse(timeline.json());
  size_t wave_spans = 0;
  for (const json& e : trace["traceEvents"])
    if (e.at("ph") == "X" && e.at("cat") == "wave") ++wave_spans;
  EXPECT_GT(wave_spans, 0u);
}

}  // namespace
}  // namespace lantern
