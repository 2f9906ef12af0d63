// Rendering across MPI ranks (Open MPI: `mpirun -np N lantern render ...`).
//
// Every rank loads the scene and runs its own oneTBB threads. Rank 0 hands
// out the render's units (one wave of one pass each) one at a time, from a
// scheduler thread, to whichever rank asks next, so that unequal machines
// finish together. At the end the ranks' films are added at rank 0 with
// MPI_Reduce. The films' sums are fixed-point integers (math/fixed_sum.h),
// so the image is bit-identical to a single-process render of the same
// settings, whatever the number of ranks, threads or the order units
// finished in (docs/distributed.md).
#pragma once

#include <mpi.h>

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "lantern/render.h"

namespace lantern {

// MPI_Init and MPI_Finalize around the program, when it was started by
// mpirun (or srun): a plain `lantern` run never touches MPI.
class MpiSession {
 public:
  // True when the environment shows an MPI launcher (Open MPI, PMIx, PMI).
  static bool launched();
  MpiSession(int& argc, char**& argv);
  ~MpiSession();
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;
  int rank() const { return rank_; }
  int size() const { return size_; }
  // Ends every rank with `code` (MPI_Abort): a rank that fails must not
  // leave the others waiting for it.
  [[noreturn]] void abort_all(int code);

 private:
  int rank_ = 0, size_ = 1;
};

// Installs the hooks (RenderHooks::next_ticket, reduce_film,
// sync_checkpoint, agree) that make one rank's render() its part of the whole;
// lives across the render() call. With a checkpoint, rank r writes its own
// piece (FILE.rank<r>) and rank 0 alone reads them all on --resume, then
// tells the others which units are done.
class MpiRender {
 public:
  MpiRender(const MpiSession& session, RenderOptions& options, RenderHooks& hooks);
  ~MpiRender();  // stops the scheduler if the render threw
  MpiRender(const MpiRender&) = delete;
  MpiRender& operator=(const MpiRender&) = delete;

  // One progress line for all ranks: the other ranks report their samples
  // with each claim for tickets, and rank 0 adds them to its own.
  void note_local_samples(uint64_t samples) { local_samples_ = samples; }
  uint64_t remote_samples() const;

  // What one rank measured. Idle: waiting for tickets, and at the end for
  // the slowest rank; communication: the film reduction after that.
  struct RankReport {
    double units = 0, samples = 0, render_seconds = 0, ticket_seconds = 0, end_wait_seconds = 0,
           reduce_seconds = 0, reduce_bytes = 0;
    double rays[4] = {0, 0, 0, 0};  // camera, eye extension, light extension, shadow/connection
  };
  // Collective: every rank calls it after render(); rank 0 gets every
  // rank's report (in rank order), the others an empty list.
  std::vector<RankReport> gather(const RenderStats& stats) const;

 private:
  uint64_t next_ticket();
  void claim();  // asks rank 0 for a run of tickets, answer pending
  void serve();  // rank 0's scheduler thread
  void start_scheduler();
  void finish_scheduling();
  void reduce(Film& film);
  void sync_checkpoint(UnitSet& done, double& elapsed_seconds, std::string& learnt);
  void agree(std::string& choice);  // rank 0's, to every rank
  uint8_t share_learnt(std::string& sums, uint8_t stop, uint64_t& passes);  // RenderHooks::share_learnt
  // Rank 0's scheduler thread: a rank's learnt sums arrived from `source`
  // (its header already received); once every rank's are in, the totals
  // go back to each.
  void receive_learnt(int source, const uint64_t header[3]);
  void finish_sharing_if_complete();

  const MpiSession& session_;
  std::atomic<uint64_t> counter_{0};  // rank 0: the next ticket
  std::atomic<uint64_t> local_samples_{0};
  std::vector<std::atomic<uint64_t>> remote_;  // rank 0: each rank's last report
  uint64_t claim_samples_ = 0;  // the value a pending claim sends
  uint64_t batch_first_ = 0, batch_left_ = 0;  // this rank's run of tickets
  uint64_t claimed_first_ = 0;                  // the next run, once claim_reply_ completes
  bool claim_pending_ = false;
  MPI_Request claim_reply_ = MPI_REQUEST_NULL;
  std::thread scheduler_;
  std::atomic<bool> stop_serving_{false};
  bool finished_ = false;
  RankReport report_;
  // What the ranks learnt in a guiding iteration, gathered at rank 0 by its
  // scheduler thread (the only one that calls MPI there once it runs):
  // each rank's sums, stop and passes; rank 0's main thread waits for the
  // totals.
  struct Learnt {
    std::string sums;
    uint8_t stop = 0;
    bool in = false;
    uint64_t passes = 0;
  };
  std::mutex learnt_mutex_;
  std::condition_variable learnt_ready_;
  std::vector<Learnt> learnt_;  // rank 0: per rank
  bool learnt_done_ = false;    // rank 0: learnt_[0] holds the totals
};

}  // namespace lantern
