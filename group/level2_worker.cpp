#include "group/level2_worker.hpp"

#include "comm/posix/thread_name.hpp"

namespace maptr::group {

Level2Worker::Level2Worker(bool oracle, std::chrono::milliseconds pause)
    : oracle_(oracle), pause_(pause), thread_([this] { loop(); }) {}

Level2Worker::~Level2Worker() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    quit_ = true;
  }
  cv_.notify_all();
  thread_.join();
}

void Level2Worker::start(const control::Level2Problem& p) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    problem_ = p;
    has_job_ = true;
    done_ = false;
    solving_ = true;
  }
  cv_.notify_all();
}

control::Level2Outcome Level2Worker::finish() {
  std::unique_lock<std::mutex> lock(mutex_);
  if (!done_) ++waited_;
  cv_.wait(lock, [this] { return done_; });
  done_ = false;
  ++finished_;
  return outcome_;
}

bool Level2Worker::solving() {
  std::lock_guard<std::mutex> lock(mutex_);
  return solving_;
}

void Level2Worker::loop() {
  comm::name_this_thread(comm::kLevel2Thread);
  std::unique_lock<std::mutex> lock(mutex_);
  for (;;) {
    cv_.wait(lock, [this] { return has_job_ || quit_; });
    if (quit_) return;
    has_job_ = false;
    const control::Level2Problem p = problem_;
    lock.unlock();
    control::Level2Outcome o = control::solve_level2(solver_, p, oracle_);
    if (pause_.count() > 0) std::this_thread::sleep_for(pause_);
    lock.lock();
    outcome_ = o;
    done_ = true;
    solving_ = false;
    cv_.notify_all();
  }
}

}  // namespace maptr::group
