// pbrt-v4's Import in parallel: each Import'ed file is parsed on a worker
// thread into a recording (recorder.h), and the recordings are replayed on
// the importing thread in the order of the Import directives, so the
// target sees what one thread parsing the files in turn would show it.
#pragma once

#include <condition_variable>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include "scene/pbrt/recorder.h"

namespace lantern::pbrt {

class ImportQueue {
 public:
  // target: the real one; named: the importing parser's named materials
  // (replay reads and extends them); threads: parsing threads.
  ImportQueue(ParserTarget& target, std::string base_dir, std::map<std::string, MaterialHandle>& named,
              unsigned threads);
  // Cancels what was not replayed and waits for the threads.
  ~ImportQueue();
  ImportQueue(const ImportQueue&) = delete;
  ImportQueue& operator=(const ImportQueue&) = delete;

  // parse(recorder) runs on a worker thread; files start in submission order.
  void submit(std::function<void(Recorder&)> parse);
  // Replays every submitted file, in order; rethrows the first error.
  void drain();
  // The target for the importing parser: each call waits for the Imports
  // before it to be replayed, then goes to the real target.
  ParserTarget& ordered() { return *ordered_; }

 private:
  struct Job;
  void work();
  void cancel_all();

  ParserTarget& target_;
  // Replayed parameter lists warn straight to the target (the importing
  // parser's sink would wait for the replay in progress).
  WarningSink sink_ = [this](const std::string& s) { target_.warn_line(s); };
  std::string base_dir_;
  std::map<std::string, MaterialHandle>& named_;
  const unsigned thread_count_;
  std::unique_ptr<ParserTarget> ordered_;
  std::deque<std::shared_ptr<Job>> order_;  // submitted, not yet replayed (importing thread only)
  std::mutex mutex_;                        // guards waiting_ and stopping_
  std::condition_variable wake_;
  std::deque<std::shared_ptr<Job>> waiting_;  // not yet started
  bool stopping_ = false;
  std::vector<std::thread> threads_;
};

}  // namespace lantern::pbrt
