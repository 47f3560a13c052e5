#include "async_writer.hpp"

namespace ugs::flowtool {

AsyncSeriesWriter::AsyncSeriesWriter(FieldSeriesWriter& writer, std::size_t max_queued)
    : writer_(writer), max_queued_(max_queued), thread_([this] { loop(); }) {}

AsyncSeriesWriter::~AsyncSeriesWriter() {
  {
    std::lock_guard lock(mutex_);
    closing_ = true;
    queue_.clear();  // finish() drained it on success; on an error nothing more is worth writing
  }
  changed_.notify_all();
  if (thread_.joinable()) thread_.join();
}

void AsyncSeriesWriter::rethrow() {
  if (error_) std::rethrow_exception(error_);
}

void AsyncSeriesWriter::push(std::string date, double time, std::vector<Field> fields) {
  std::unique_lock lock(mutex_);
  changed_.wait(lock, [&] { return queue_.size() < max_queued_ || error_; });
  rethrow();
  queue_.push_back({std::move(date), time, std::move(fields)});
  changed_.notify_all();
}

void AsyncSeriesWriter::finish() {
  std::unique_lock lock(mutex_);
  changed_.wait(lock, [&] { return queue_.empty() || error_; });
  rethrow();
}

void AsyncSeriesWriter::loop() {
  for (;;) {
    Step s;
    {
      std::unique_lock lock(mutex_);
      changed_.wait(lock, [&] { return !queue_.empty() || closing_; });
      if (queue_.empty() || error_) return;
      s = std::move(queue_.front());
    }
    try {
      writer_.add_step(s.date, s.time, s.fields);  // outside the lock: the solver keeps pushing
    } catch (...) {
      std::lock_guard lock(mutex_);
      error_ = std::current_exception();
      queue_.clear();
      changed_.notify_all();
      return;
    }
    std::lock_guard lock(mutex_);
    if (!queue_.empty()) queue_.pop_front();  // the destructor may have cleared it
    changed_.notify_all();
  }
}

}  // namespace ugs::flowtool
