// Writes field steps on a second thread while the solver marches on: the HDF5 writing (deflate)
// of ~1,000 dates x 10^5 nodes costs as much as the solves, and the machine has two cores.
// Only this thread touches HDF5. Errors are rethrown to the caller at the next push or finish.
#pragma once
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <exception>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "ugs/formats/fields.hpp"

namespace ugs::flowtool {

class AsyncSeriesWriter {
public:
  // `max_queued` bounds the memory held by steps waiting to be written.
  AsyncSeriesWriter(FieldSeriesWriter& writer, std::size_t max_queued = 8);
  ~AsyncSeriesWriter();
  void push(std::string date, double time, std::vector<Field> fields);
  // Waits for the queue to drain; rethrows a writer error.
  void finish();

private:
  struct Step {
    std::string date;
    double time;
    std::vector<Field> fields;
  };
  void loop();
  void rethrow();
  FieldSeriesWriter& writer_;
  std::size_t max_queued_;
  std::deque<Step> queue_;
  std::mutex mutex_;
  std::condition_variable changed_;
  bool closing_ = false;
  std::exception_ptr error_;
  std::thread thread_;
};

}  // namespace ugs::flowtool
