// The files evms writes:
//   labelled events   t_us,x,y,p,label          one row per input event, in input order
//   tracks            t_us,track_id,state,x,y,vx,vy,events,x_min,y_min,x_max,y_max,var_x,cov_xy,var_y
//                                               one row per update: the filtered estimate (px,
//                                               px/s), the cluster's event count and bounding
//                                               box, and the estimate's covariance (px^2)
//   events.txt        t x y p                   RPG format, t in seconds with 9 decimals
//   ground truth      t_us,object,x,y           object centres (px)
// The event files start with a comment line "# sensor WxH", which evms's readers take as the
// sensor size (other tools skip '#' lines).
#pragma once

#include <charconv>
#include <string>

#include "types/event.h"
#include "host/write/text_writer.h"

namespace evms::write {

inline void write_sensor_comment(TextWriter& out, SensorSize sensor) {
  out.text("# sensor ").integer(sensor.width).ch('x').integer(sensor.height).ch('\n');
}

class LabelledEventsCsv {
 public:
  LabelledEventsCsv(const std::string& path, SensorSize sensor) : out_(path) {
    write_sensor_comment(out_, sensor);
    out_.text("t_us,x,y,p,label\n");
  }
  void write(const LabelledEvent& e) {
    // At most 20 + 5 + 5 + 1 + 11 characters and 5 separators.
    char* p = out_.reserve(48);
    char* const end = p + 48;
    p = std::to_chars(p, end, e.event.t).ptr, *p++ = ',';
    p = std::to_chars(p, end, e.event.x).ptr, *p++ = ',';
    p = std::to_chars(p, end, e.event.y).ptr, *p++ = ',';
    *p++ = static_cast<char>('0' + e.event.p), *p++ = ',';
    p = std::to_chars(p, end, e.label).ptr, *p++ = '\n';
    out_.commit(p);
  }
  void close() { out_.close(); }

 private:
  TextWriter out_;
};

class TracksCsv {
 public:
  explicit TracksCsv(const std::string& path) : out_(path) {
    out_.text("t_us,track_id,state,x,y,vx,vy,events,x_min,y_min,x_max,y_max,var_x,cov_xy,var_y\n");
  }
  void write(const TrackUpdate& u) {
    out_.integer(u.t).ch(',').integer(u.id).ch(',').text(u.state == TrackState::kConfirmed ? "confirmed" : "tentative").ch(',');
    out_.fixed(u.x, 3).ch(',').fixed(u.y, 3).ch(',').fixed(u.vx, 3).ch(',').fixed(u.vy, 3).ch(',').integer(u.events).ch(',');
    out_.integer(u.x_min).ch(',').integer(u.y_min).ch(',').integer(u.x_max).ch(',').integer(u.y_max).ch(',');
    out_.fixed(u.var_x, 4).ch(',').fixed(u.cov_xy, 4).ch(',').fixed(u.var_y, 4).ch('\n');
  }
  void close() { out_.close(); }

 private:
  TextWriter out_;
};

class RpgEventsTxt {
 public:
  RpgEventsTxt(const std::string& path, SensorSize sensor) : out_(path) { write_sensor_comment(out_, sensor); }
  void write(const Event& e) {
    char frac[8];
    const auto us = static_cast<int>(e.t % 1000000);
    for (int i = 5, v = us; i >= 0; --i, v /= 10) frac[i] = static_cast<char>('0' + v % 10);
    out_.integer(e.t / 1000000).ch('.').text({frac, 6}).text("000 ");
    out_.integer(e.x).ch(' ').integer(e.y).ch(' ').integer(e.p).ch('\n');
  }
  void close() { out_.close(); }

 private:
  TextWriter out_;
};

class TruthCsv {
 public:
  explicit TruthCsv(const std::string& path) : out_(path) { out_.text("t_us,object,x,y\n"); }
  void write(TimeUs t, int object, double x, double y) {
    out_.integer(t).ch(',').integer(object).ch(',').fixed(x, 3).ch(',').fixed(y, 3).ch('\n');
  }
  void close() { out_.close(); }

 private:
  TextWriter out_;
};

}  // namespace evms::write
