// The files evms writes:
//   labelled events   t_us,x,y,p,label          one row per input event, in input order
//   tracks            t_us,track_id,x,y,vx,vy   filtered estimate (px, px/s), one row per update
//   events.txt        t x y p                   RPG format, t in seconds with 9 decimals
//   ground truth      t_us,object,x,y           object centres (px)
#pragma once

#include <string>

#include "golden/event.h"
#include "host/write/text_writer.h"

namespace evms::write {

class LabelledEventsCsv {
 public:
  explicit LabelledEventsCsv(const std::string& path) : out_(path) { out_.text("t_us,x,y,p,label\n"); }
  void write(const LabelledEvent& e) {
    out_.integer(e.event.t).ch(',').integer(e.event.x).ch(',').integer(e.event.y).ch(',');
    out_.integer(e.event.p).ch(',').integer(e.label).ch('\n');
  }
  void close() { out_.close(); }

 private:
  TextWriter out_;
};

class TracksCsv {
 public:
  explicit TracksCsv(const std::string& path) : out_(path) { out_.text("t_us,track_id,x,y,vx,vy\n"); }
  void write(const TrackUpdate& u) {
    out_.integer(u.t).ch(',').integer(u.id).ch(',').fixed(u.x, 3).ch(',').fixed(u.y, 3).ch(',');
    out_.fixed(u.vx, 3).ch(',').fixed(u.vy, 3).ch('\n');
  }
  void close() { out_.close(); }

 private:
  TextWriter out_;
};

class RpgEventsTxt {
 public:
  explicit RpgEventsTxt(const std::string& path) : out_(path) {}
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
