#include "distributed/mpi_render.h"

#include <mpi.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <stdexcept>

#include "film/film.h"
#include "film/unit_set.h"
#include "math/fixed_sum.h"

namespace lantern {

namespace {

constexpr int kClaimTag = 1, kTicketTag = 2, kDoneTag = 3, kLearntTag = 4, kLearntBytesTag = 5, kLearntTotalTag = 6;
// Tickets go out in runs of this many consecutive ones: a quarter of the
// round trips, and at the end at most a few waves of imbalance.
constexpr uint64_t kBatch = 4;
using Clock = std::chrono::steady_clock;

// Element-wise sum of 128-bit two's complement integers: exact, so the
// reduction's order (MPI chooses it) cannot change the result.
extern "C" void add_fixed_sums(void* in, void* inout, int* len, MPI_Datatype*) {
  auto* a = static_cast<const unsigned __int128*>(in);
  auto* b = static_cast<unsigned __int128*>(inout);
  for (int i = 0; i < *len; ++i) b[i] += a[i];
}

void check(int code, const char* what) {
  if (code != MPI_SUCCESS) throw std::runtime_error(std::string("MPI: ") + what + " failed");
}

// Bytes of any length to one rank, and from it, in runs MPI's int counts hold.
constexpr size_t kRun = size_t(1) << 30;
void send_bytes(const std::string& b, int to, int tag) {
  for (size_t at = 0; at < b.size(); at += kRun)
    check(MPI_Send(b.data() + at, int(std::min(kRun, b.size() - at)), MPI_BYTE, to, tag, MPI_COMM_WORLD), "send");
}
void receive_bytes(std::string& b, size_t n, int from, int tag) {
  b.resize(n);
  for (size_t at = 0; at < n; at += kRun)
    check(MPI_Recv(b.data() + at, int(std::min(kRun, n - at)), MPI_BYTE, from, tag, MPI_COMM_WORLD, MPI_STATUS_IGNORE),
          "receive");
}

// MPI_Reduce to rank 0 in chunks (MPI counts are ints), in place at the root.
template <class T>
void reduce_chunks(T* data, size_t n, MPI_Datatype type, MPI_Op op, int rank) {
  constexpr size_t kChunk = size_t(1) << 22;
  for (size_t at = 0; at < n; at += kChunk) {
    const int count = int(std::min(kChunk, n - at));
    if (rank == 0) check(MPI_Reduce(MPI_IN_PLACE, data + at, count, type, op, 0, MPI_COMM_WORLD), "reduce");
    else check(MPI_Reduce(data + at, nullptr, count, type, op, 0, MPI_COMM_WORLD), "reduce");
  }
}

}  // namespace

bool MpiSession::launched() {
  for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE"})
    if (std::getenv(v)) return true;
  return false;
}

MpiSession::MpiSession(int& argc, char**& argv) {
  int provided = 0;
  // Rank 0's scheduler thread calls MPI while its render threads run; the
  // calls never overlap, which SERIALIZED allows.
  check(MPI_Init_thread(&argc, &argv, MPI_THREAD_SERIALIZED, &provided), "init");
  if (provided < MPI_THREAD_SERIALIZED) throw std::runtime_error("MPI: this library does not allow threads to call it");
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
}

MpiSession::~MpiSession() { MPI_Finalize(); }

void MpiSession::abort_all(int code) {
  MPI_Abort(MPI_COMM_WORLD, code);
  std::abort();  // MPI_Abort does not return
}

MpiRender::MpiRender(const MpiSession& session, RenderOptions& o, RenderHooks& h)
    : session_(session), remote_(session.rank() == 0 ? size_t(session.size()) : 0) {
  if (session_.size() == 1) return;  // one rank: a plain render
  h.next_ticket = [this] { return next_ticket(); };
  h.reduce_film = [this](Film& film) { reduce(film); };
  h.sync_checkpoint = [this](UnitSet& done, double& elapsed, std::string& learnt) {
    sync_checkpoint(done, elapsed, learnt);
  };
  h.agree = [this](std::string& choice) { agree(choice); };
  h.share_learnt = [this](std::string& sums, uint8_t stop, uint64_t& passes) {
    return share_learnt(sums, stop, passes);
  };
  if (session_.rank() == 0) learnt_.resize(size_t(session_.size()));
  o.checkpoint_rank = session_.rank();
  o.resume_reads = session_.rank() == 0;
}

// Rank 0's scheduler starts with its first ticket, or at the end if it
// takes none: after sync_checkpoint, so that the main thread's collective
// calls and the scheduler's never overlap (MPI_THREAD_SERIALIZED). Claims
// sent before wait in MPI's queue.
void MpiRender::start_scheduler() {
  if (!scheduler_.joinable()) scheduler_ = std::thread([this] { serve(); });
}

MpiRender::~MpiRender() {
  stop_serving_ = true;
  if (scheduler_.joinable()) scheduler_.join();
}

uint64_t MpiRender::next_ticket() {
  ++report_.units;
  if (batch_left_ == 0) {
    if (session_.rank() == 0) {
      start_scheduler();
      batch_first_ = counter_.fetch_add(kBatch);
    } else {
      if (!claim_pending_) claim();
      const auto t0 = Clock::now();
      check(MPI_Wait(&claim_reply_, MPI_STATUS_IGNORE), "ticket");
      report_.ticket_seconds += std::chrono::duration<double>(Clock::now() - t0).count();
      claim_pending_ = false;
      batch_first_ = claimed_first_;
    }
    batch_left_ = kBatch;
  }
  // Half way through a run, ask for the next one, so that the answer is
  // there when this run ends: rank 0's scheduler may answer late when its
  // core is busy rendering.
  if (session_.rank() != 0 && batch_left_ == kBatch / 2 && !claim_pending_) claim();
  --batch_left_;
  return batch_first_++;
}

void MpiRender::claim() {
  claim_samples_ = local_samples_;
  check(MPI_Send(&claim_samples_, 1, MPI_UINT64_T, 0, kClaimTag, MPI_COMM_WORLD), "claim");
  check(MPI_Irecv(&claimed_first_, 1, MPI_UINT64_T, 0, kTicketTag, MPI_COMM_WORLD, &claim_reply_), "ticket");
  claim_pending_ = true;
}

// Answers claims until every other rank has said it is done. Polls with
// short sleeps: a blocking receive would spin a core the render needs.
void MpiRender::serve() {
  int done = 0;
  while (done < session_.size() - 1 && !stop_serving_) {
    int flag = 0;
    MPI_Status status;
    MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &flag, &status);
    if (!flag) {
      finish_sharing_if_complete();
      std::this_thread::sleep_for(std::chrono::microseconds(250));
      continue;
    }
    if (status.MPI_TAG == kLearntTag) {
      uint64_t header[3];
      MPI_Recv(header, 3, MPI_UINT64_T, status.MPI_SOURCE, kLearntTag, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
      receive_learnt(status.MPI_SOURCE, header);
      continue;
    }
    uint64_t samples = 0;
    MPI_Recv(&samples, 1, MPI_UINT64_T, status.MPI_SOURCE, status.MPI_TAG, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    remote_[size_t(status.MPI_SOURCE)] = samples;
    if (status.MPI_TAG == kDoneTag) {
      ++done;
    } else {
      const uint64_t ticket = counter_.fetch_add(kBatch);
      MPI_Send(&ticket, 1, MPI_UINT64_T, status.MPI_SOURCE, kTicketTag, MPI_COMM_WORLD);
    }
  }
}

void MpiRender::finish_scheduling() {
  if (finished_) return;
  finished_ = true;
  if (session_.rank() == 0) {
    start_scheduler();  // it serves the others until they are done
    scheduler_.join();
  } else {
    if (claim_pending_) check(MPI_Wait(&claim_reply_, MPI_STATUS_IGNORE), "ticket");  // a run left unused
    claim_pending_ = false;
    const uint64_t samples = local_samples_;
    check(MPI_Send(&samples, 1, MPI_UINT64_T, 0, kDoneTag, MPI_COMM_WORLD), "done");
  }
}

void MpiRender::reduce(Film& film) {
  report_.samples = double(film.total_samples());
  const auto wait = Clock::now();
  finish_scheduling();
  // Also the barrier where the ranks wait for the slowest.
  int any_splats = film.has_splats() ? 1 : 0;
  check(MPI_Allreduce(MPI_IN_PLACE, &any_splats, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD), "splat flag");
  const auto t0 = Clock::now();
  report_.end_wait_seconds = std::chrono::duration<double>(t0 - wait).count();
  Film::Buffers b = film.buffers(any_splats != 0);
  MPI_Datatype fixed;
  MPI_Op add;
  MPI_Type_contiguous(int(sizeof(unsigned __int128)), MPI_BYTE, &fixed);
  MPI_Type_commit(&fixed);
  MPI_Op_create(add_fixed_sums, 1, &add);
  const int rank = session_.rank();
  reduce_chunks(b.sums, b.values, fixed, add, rank);
  if (b.splats) reduce_chunks(b.splats, b.values, fixed, add, rank);
  reduce_chunks(b.counts, b.values / 3, MPI_UINT32_T, MPI_SUM, rank);
  if (b.negatives) reduce_chunks(b.negatives, b.values / 3, MPI_UINT32_T, MPI_SUM, rank);
  reduce_chunks(b.nonfinite, 1, MPI_UINT64_T, MPI_SUM, rank);
  reduce_chunks(b.light_paths, 1, MPI_UINT64_T, MPI_SUM, rank);
  MPI_Op_free(&add);
  MPI_Type_free(&fixed);
  report_.reduce_bytes =
      double((b.values * (b.splats ? 2 : 1)) * sizeof(unsigned __int128) + (b.values / 3) * sizeof(uint32_t) + 16);
  report_.reduce_seconds = std::chrono::duration<double>(Clock::now() - t0).count();
}

uint64_t MpiRender::remote_samples() const {
  uint64_t sum = 0;
  for (const auto& r : remote_) sum += r.load();
  return sum;
}

// Rank 0's units done, time spent and what they learnt, to every rank (and
// a barrier: rank 0 has saved and tidied the checkpoint's pieces by now).
void MpiRender::sync_checkpoint(UnitSet& done, double& elapsed_seconds, std::string& learnt) {
  std::vector<uint64_t> flat;
  for (const auto& [first, end] : done.intervals()) {
    flat.push_back(first);
    flat.push_back(end);
  }
  uint64_t n = flat.size();
  check(MPI_Bcast(&n, 1, MPI_UINT64_T, 0, MPI_COMM_WORLD), "units done");
  flat.resize(n);
  for (size_t at = 0; at < n; at += size_t(1) << 28)
    check(MPI_Bcast(flat.data() + at, int(std::min<size_t>(n - at, size_t(1) << 28)), MPI_UINT64_T, 0, MPI_COMM_WORLD),
          "units done");
  check(MPI_Bcast(&elapsed_seconds, 1, MPI_DOUBLE, 0, MPI_COMM_WORLD), "time spent");
  uint64_t bytes = learnt.size();
  check(MPI_Bcast(&bytes, 1, MPI_UINT64_T, 0, MPI_COMM_WORLD), "what was learnt");
  learnt.resize(size_t(bytes));
  for (size_t at = 0; at < bytes; at += size_t(1) << 30)
    check(
        MPI_Bcast(learnt.data() + at, int(std::min<size_t>(bytes - at, size_t(1) << 30)), MPI_BYTE, 0, MPI_COMM_WORLD),
        "what was learnt");
  if (session_.rank() != 0) {
    std::vector<UnitSet::Interval> runs;
    for (size_t i = 0; i + 1 < flat.size(); i += 2) runs.emplace_back(flat[i], flat[i + 1]);
    done = UnitSet::of(std::move(runs));
  }
}

// A guiding iteration's end: every rank sends rank 0 its sums, whether it
// stops and its predicted passes (a header of three numbers, then the
// bytes); rank 0's scheduler thread adds them up (as 128-bit integers, in
// any order: the totals are exact) and sends every rank the totals, the
// stop of any and rank 0's passes. Point to point, so that rank 0's
// scheduler goes on answering claims for the iteration's last units
// meanwhile, and its main thread, which waits, calls no MPI
// (MPI_THREAD_SERIALIZED).
uint8_t MpiRender::share_learnt(std::string& sums, uint8_t stop, uint64_t& passes) {
  if (session_.rank() == 0) {
    start_scheduler();
    std::unique_lock<std::mutex> lock(learnt_mutex_);
    learnt_[0] = {std::move(sums), stop, true, passes};
    learnt_ready_.wait(lock, [this] { return learnt_done_; });
    learnt_done_ = false;
    Learnt& total = learnt_[0];
    sums = std::move(total.sums);
    passes = total.passes;
    total.in = false;
    return total.stop;
  }
  const uint64_t header[3] = {uint64_t(stop), passes, sums.size()};
  check(MPI_Send(header, 3, MPI_UINT64_T, 0, kLearntTag, MPI_COMM_WORLD), "learnt");
  send_bytes(sums, 0, kLearntBytesTag);
  uint64_t total[3];
  check(MPI_Recv(total, 3, MPI_UINT64_T, 0, kLearntTotalTag, MPI_COMM_WORLD, MPI_STATUS_IGNORE), "learnt");
  if (total[2] != sums.size())
    throw std::runtime_error("MPI: rank 0's guiding field has " + std::to_string(total[2]) +
                             " bytes of sums, this one " + std::to_string(sums.size()));
  receive_bytes(sums, size_t(total[2]), 0, kLearntTotalTag);
  passes = total[1];
  return uint8_t(total[0]);
}

void MpiRender::receive_learnt(int source, const uint64_t header[3]) {
  std::string bytes;
  receive_bytes(bytes, size_t(header[2]), source, kLearntBytesTag);
  {
    std::lock_guard<std::mutex> lock(learnt_mutex_);
    learnt_[size_t(source)] = {std::move(bytes), uint8_t(header[0]), true, header[1]};
  }
  finish_sharing_if_complete();
}

void MpiRender::finish_sharing_if_complete() {
  std::unique_lock<std::mutex> lock(learnt_mutex_);
  if (learnt_.empty() || learnt_done_ ||
      !std::all_of(learnt_.begin(), learnt_.end(), [](const Learnt& l) { return l.in; }))
    return;
  Learnt& total = learnt_[0];
  for (size_t r = 1; r < learnt_.size(); ++r) {
    Learnt& l = learnt_[r];
    // (a rank whose field differs in shape cannot be added: the render fails on every rank)
    if (l.sums.size() == total.sums.size()) add_saturating_sums(total.sums, l.sums);
    total.stop = uint8_t(total.stop | l.stop);
    l.in = false;
    std::string().swap(l.sums);  // (added: freed until the next iteration)
  }
  const uint64_t header[3] = {uint64_t(total.stop), total.passes, total.sums.size()};
  for (int r = 1; r < session_.size(); ++r) {
    check(MPI_Send(header, 3, MPI_UINT64_T, r, kLearntTotalTag, MPI_COMM_WORLD), "learnt");
    send_bytes(total.sums, r, kLearntTotalTag);
  }
  learnt_done_ = true;
  learnt_ready_.notify_all();
}

// Rank 0 reads the checkpoint, and so makes the choices (RenderHooks::
// agree). Called before any ticket, so the scheduler thread is not running
// yet (MPI_THREAD_SERIALIZED).
void MpiRender::agree(std::string& choice) {
  uint64_t n = choice.size();
  check(MPI_Bcast(&n, 1, MPI_UINT64_T, 0, MPI_COMM_WORLD), "choice");
  if (n > (uint64_t(1) << 30)) throw std::runtime_error("MPI: a choice of " + std::to_string(n) + " bytes");
  choice.resize(size_t(n));
  if (n > 0) check(MPI_Bcast(choice.data(), int(n), MPI_BYTE, 0, MPI_COMM_WORLD), "choice");
}

std::vector<MpiRender::RankReport> MpiRender::gather(const RenderStats& stats) const {
  constexpr int kDoubles = int(sizeof(RankReport) / sizeof(double));
  static_assert(sizeof(RankReport) == 11 * sizeof(double));
  RankReport mine = report_;
  mine.render_seconds = stats.seconds;
  mine.rays[0] = double(stats.camera_rays);
  mine.rays[1] = double(stats.extension_rays);
  mine.rays[2] = double(stats.light_rays);
  mine.rays[3] = double(stats.shadow_rays);
  std::vector<RankReport> all(session_.rank() == 0 ? size_t(session_.size()) : 0);
  check(MPI_Gather(&mine, kDoubles, MPI_DOUBLE, all.data(), kDoubles, MPI_DOUBLE, 0, MPI_COMM_WORLD), "gather reports");
  return all;
}

}  // namespace lantern
