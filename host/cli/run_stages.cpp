#include "host/cli/run_stages.h"

#include <chrono>
#include <exception>
#include <thread>

#include "host/cli/bounded_queue.h"

namespace evms::cli {
namespace {

// Events read at a time: one batch through the three stages.
constexpr size_t kBatchEvents = 16384;
// Listening: how long each wait for the board's frames lasts, so that Ctrl-C and the limit are
// seen within it.
constexpr int kListenMs = 100;

// Nanoseconds since `mark`, which moves to now.
std::int64_t since(std::chrono::steady_clock::time_point& mark) {
  const auto now = std::chrono::steady_clock::now();
  const auto ns = std::chrono::duration_cast<std::chrono::nanoseconds>(now - mark).count();
  mark = now;
  return ns;
}

}  // namespace

StageReport run_stages(read::EventSource& source, backend::Backend& backend, Collector& sink, Writers& writers, const StageOptions& o) {
  StageReport report;
  TimeUs& t_first = report.t_first;
  TimeUs& t_last = report.t_last;
  bool any = false;
  std::string& source_error = report.source_error;
  std::int64_t &read_ns = report.read_ns, &method_ns = report.method_ns, &write_ns = report.write_ns;
  // Reading: the next batch, or an empty one at the end (or at Ctrl-C, or after a failure).
  const auto read_batch = [&](InputBatch& b) {
    b.events.resize(kBatchEvents);
    size_t n = 0;
    if (!o.stop || !o.stop()) {
      try {
        n = source.read(b.events);
      } catch (const read::InputError& e) {
        source_error = e.what();
      }
    }
    b.events.resize(n);
    const auto arrivals = source.arrivals();
    b.arrivals.assign(arrivals.begin(), arrivals.end());
    b.progress = source.progress();
  };
  // The method: labels a batch into the collector; its outputs go to the writers.
  const auto label_batch = [&](const InputBatch& b) {
    if (!any) t_first = b.events.front().t, any = true;
    t_last = b.events.back().t;
    sink.latency.arrived(b.arrivals);
    backend.push(b.events, sink);
    sink.stamp_latency();
    if (o.progress) o.progress(b.progress, backend.stats().events_in);
  };
  const auto finish_method = [&] {
    backend.finish(sink);
    sink.stamp_latency();
  };

  if (o.threads <= 1) {
    InputBatch in;
    auto mark = std::chrono::steady_clock::now();
    for (;;) {
      read_batch(in);
      read_ns += since(mark);
      if (in.events.empty()) break;
      label_batch(in);
      method_ns += since(mark);
      OutputBatch out = sink.take();
      writers.write(out);
      sink.recycle(std::move(out));
      write_ns += since(mark);
    }
    finish_method();
    method_ns += since(mark);
    writers.write(sink.take());
    writers.close();
    write_ns += since(mark);
  } else {
    // Reading, the method and writing, each in a thread of its own, joined by queues: the
    // method sees the same batches in the same order, so the outputs are the same bytes. The
    // batches a stage is done with go back to the stage that fills them (spent_*), so that their
    // memory is reused rather than faulted in anew for every batch.
    BoundedQueue<InputBatch> inputs(4), spent_inputs(4);
    BoundedQueue<OutputBatch> outputs(4), spent_outputs(4);
    std::exception_ptr reader_failed, writer_failed;
    std::thread reader([&] {
      try {
        auto mark = std::chrono::steady_clock::now();
        for (;;) {
          InputBatch b;
          spent_inputs.try_pop(b);
          read_batch(b);
          read_ns += since(mark);
          const bool end = b.events.empty();
          if (!end && !inputs.push(std::move(b))) break;
          if (end) break;
          mark = std::chrono::steady_clock::now();
        }
      } catch (...) {
        reader_failed = std::current_exception();
      }
      inputs.close();
    });
    std::thread writer([&] {
      try {
        OutputBatch b;
        while (outputs.pop(b)) {
          auto mark = std::chrono::steady_clock::now();
          writers.write(b);
          write_ns += since(mark);
          spent_outputs.try_push(b);
        }
        auto mark = std::chrono::steady_clock::now();
        writers.close();
        write_ns += since(mark);
      } catch (...) {
        writer_failed = std::current_exception();
        outputs.close();  // the method stops handing over what could not be written
      }
    });
    try {
      InputBatch b;
      OutputBatch spent;
      while (inputs.pop(b)) {
        auto mark = std::chrono::steady_clock::now();
        label_batch(b);
        method_ns += since(mark);
        spent_inputs.try_push(b);
        if (spent_outputs.try_pop(spent)) sink.recycle(std::move(spent));
        outputs.push(sink.take());
      }
      auto mark = std::chrono::steady_clock::now();
      finish_method();
      method_ns += since(mark);
      outputs.push(sink.take());
    } catch (...) {
      inputs.close();
      outputs.close();
      reader.join();
      writer.join();
      throw;
    }
    outputs.close();
    reader.join();
    writer.join();
    if (reader_failed) std::rethrow_exception(reader_failed);
    if (writer_failed) std::rethrow_exception(writer_failed);
  }
  return report;
}

StageReport listen_stages(backend::Backend& backend, Collector& sink, Writers& writers, const StageOptions& o, std::int64_t limit) {
  StageReport report;
  bool any = false;
  auto mark = std::chrono::steady_clock::now();
  const auto write = [&] {
    OutputBatch b = sink.take();
    for (const TrackUpdate& u : b.tracks) {
      if (!any) report.t_first = u.t, any = true;
      report.t_last = u.t;
    }
    writers.write(b);
    report.write_ns += since(mark);
  };
  for (;;) {
    const std::int64_t events_in = backend.stats().events_in;
    if (o.progress) o.progress(-1.0, events_in);
    if ((o.stop && o.stop()) || (limit > 0 && events_in >= limit)) break;
    backend.listen(sink, kListenMs, limit);
    report.read_ns += since(mark);
    write();
  }
  backend.finish(sink);
  report.method_ns += since(mark);
  write();
  writers.close();
  report.write_ns += since(mark);
  return report;
}

}  // namespace evms::cli
