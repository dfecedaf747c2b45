// evms info SOURCE : what a recording holds.
#include <algorithm>
#include <cstdio>

#include "host/cli/common.h"
#include "host/cli/commands.h"

namespace evms::cli {
namespace {

struct InfoOptions {
  std::string source;
  read::SourceOptions source_options;
};

void info(const InfoOptions& o) {
  auto source = read::open_source(o.source, o.source_options);
  Progress progress(true);
  std::vector<Event> batch(8192), first;
  std::int64_t count = 0, on = 0, peak = 0, in_window = 0;
  TimeUs t0 = 0, t1 = 0, window_start = 0;
  int xmin = 65535, xmax = -1, ymin = 65535, ymax = -1;
  constexpr TimeUs kWindow = 10000;  // peak rate over 10 ms windows
  for (;;) {
    const size_t n = source->read(batch);
    if (n == 0) break;
    for (size_t i = 0; i < n; ++i) {
      const Event& e = batch[i];
      if (count == 0) t0 = window_start = e.t;
      if (first.size() < 3) first.push_back(e);
      t1 = e.t;
      ++count;
      on += e.p;
      xmin = std::min<int>(xmin, e.x), xmax = std::max<int>(xmax, e.x);
      ymin = std::min<int>(ymin, e.y), ymax = std::max<int>(ymax, e.y);
      if (e.t - window_start >= kWindow) window_start += (e.t - window_start) / kWindow * kWindow, in_window = 0;
      peak = std::max(peak, ++in_window);
    }
    progress.update(source->progress(), count);
  }
  progress.done();
  const read::SourceInfo& si_ = source->info();
  const double duration = static_cast<double>(t1 - t0) * 1e-6;
  std::printf("file        %s\n", si_.name.c_str());
  std::printf("format      %s\n", si_.format.c_str());
  std::printf("sensor      %dx%d (%s%s)\n", si_.sensor.width, si_.sensor.height, si_.sensor_assumed() ? "" : "from ", si_.sensor_origin.c_str());
  std::printf("events      %s (ON %s / OFF %s)\n", grouped(count).c_str(), grouped(on).c_str(), grouped(count - on).c_str());
  if (count > 0) {
    std::printf("time        %lld .. %lld us (%.6f s)\n", static_cast<long long>(t0), static_cast<long long>(t1), duration);
    std::printf("x range     %d..%d\n", xmin, xmax);
    std::printf("y range     %d..%d\n", ymin, ymax);
    std::printf("mean rate   %sevents/s\n", duration > 0 ? si(count / duration).c_str() : "- ");
    // A recording shorter than a window has one partial window: its peak is its mean, not the
    // count spread over the whole window.
    if (t1 - t0 >= kWindow || duration <= 0) std::printf("peak rate   %sevents/s (over 10 ms windows)\n", si(peak * 1e6 / kWindow).c_str());
    else std::printf("peak rate   %sevents/s (the mean: the recording is shorter than a 10 ms window)\n", si(count / duration).c_str());
    std::printf("first       ");
    for (const Event& e : first) std::printf("(%lld,%d,%d,%d) ", static_cast<long long>(e.t), e.x, e.y, e.p);
    std::printf("\n");
  }
  if (source->reordered()) std::printf("reordered   %s events moved back into time order\n", grouped(source->reordered()).c_str());
  for (const auto& [kind, n] : source->skipped()) std::printf("skipped     %s %s\n", grouped(n).c_str(), kind.c_str());
}

}  // namespace

void register_info(CLI::App& app) {
  auto o = std::make_shared<InfoOptions>();
  CLI::App* cmd = app.add_subcommand("info", "print a source's format, sensor size, event count, duration and rates");
  cmd->add_option("source", o->source, "event file or URI")->required();
  add_source_options(*cmd, o->source_options);
  cmd->callback([o] { info(*o); });
}

}  // namespace evms::cli
