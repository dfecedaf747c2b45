// Labelled events in the binary forms users' tools read (evms run --format):
//   npy   one structured NumPy array (format 1.0), fields t <i8 (us), x <u2, y <u2, p u1,
//         label <i4, packed, one element per input event in input order; numpy.load and tonic
//         read it as it is
//   evt3  the events as a Prophesee EVT 3.0 RAW file (events.raw, which Metavision and evms
//         read) and their labels in a side file (labels.csv: one label per line, in the order
//         of the events). EVT 3.0 keeps 24 bits of time; the header line
//         "% evms_time_base_us N" says which multiple of 2^24 us its first event lies in, and
//         evms's reader adds it back, so that a round trip gives the same timestamps.
//   aedat4  the events as an iniVation AEDAT 4.0 file (events.aedat4, which DV, dv-processing
//         and evms read): one EVTS stream of the sensor's size, packets of up to 4,096 events,
//         each an LZ4 frame, no data table; the labels in the same side file as evt3.
#pragma once

#include <string>
#include <vector>

#include "types/event.h"
#include "host/write/text_writer.h"

namespace evms::write {

class LabelledEventsNpy {
 public:
  explicit LabelledEventsNpy(const std::string& path);
  void write(const LabelledEvent& e);
  // Writes the element count into the header; throws if anything failed.
  void close();

 private:
  std::string path_;
  TextWriter out_;
  std::int64_t count_ = 0;
};

// labels.csv beside a camera file: one label a line, in the order of the file's events.
class LabelsSideFile {
 public:
  LabelsSideFile(const std::string& path, const std::string& events_path);
  void write(std::int32_t label) { out_.integer(label).ch('\n'); }
  void close() { out_.close(); }

 private:
  TextWriter out_;
};

class Aedat4Events {
 public:
  static constexpr size_t kEventsPerPacket = 4096;
  Aedat4Events(const std::string& path, const std::string& labels_path, SensorSize sensor);
  void write(const LabelledEvent& e);
  void close();

 private:
  void write_packet();

  TextWriter out_;
  LabelsSideFile labels_;
  std::vector<Event> packet_;
  std::vector<std::uint8_t> compressed_;
};

class Evt3Events {
 public:
  // Throws when the sensor is wider or taller than EVT 3.0's 11-bit coordinates hold.
  Evt3Events(const std::string& raw_path, const std::string& labels_path, SensorSize sensor);
  void write(const LabelledEvent& e);
  void close();

 private:
  void word(unsigned type, unsigned payload);
  void time_to(TimeUs t);

  std::string raw_path_;
  TextWriter raw_;
  LabelsSideFile labels_;
  bool started_ = false;
  TimeUs base_ = 0;       // the multiple of 2^24 us below the first event
  TimeUs ticks_ = -1;     // t >> 12 of the last TIME_HIGH written (relative to base_)
  TimeUs low_ = -1;
  int y_ = -1;
};

}  // namespace evms::write
