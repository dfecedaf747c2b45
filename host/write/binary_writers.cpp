#include "host/write/binary_writers.h"

#include <filesystem>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <stdexcept>

#include <lz4frame.h>

#include "aedat4_events_generated.h"
#include "aedat4_io_header_generated.h"

namespace evms::write {
namespace {

// The header's shape field is padded so that the header's length does not depend on the
// count, which is known only at the end.
std::string npy_header(std::int64_t count) {
  const auto dict_of = [](const std::string& n) {
    return "{'descr': [('t', '<i8'), ('x', '<u2'), ('y', '<u2'), ('p', 'u1'), ('label', '<i4')], "
           "'fortran_order': False, 'shape': (" + n + ",), }";
  };
  // Magic, version and length take 10 bytes; the whole header is a multiple of 64 and ends in '\n'.
  const size_t total = (10 + dict_of(std::string(19, '9')).size() + 1 + 63) / 64 * 64;
  std::string dict = dict_of(std::to_string(count));
  dict.resize(total - 10 - 1, ' ');
  dict += '\n';
  std::string h = "\x93NUMPY";
  h += '\x01';
  h += '\x00';
  h += static_cast<char>(dict.size() & 0xFF);
  h += static_cast<char>(dict.size() >> 8);
  return h + dict;
}

template <class T>
void put_le(TextWriter& out, T v) {
  unsigned char b[sizeof(T)];
  for (size_t i = 0; i < sizeof(T); ++i) b[i] = static_cast<unsigned char>(static_cast<std::uint64_t>(v) >> (8 * i));
  out.bytes(b, sizeof b);
}

constexpr TimeUs kEpoch = TimeUs{1} << 24;
// Consecutive TIME_HIGH words further apart than half their 12-bit range would read as a
// wrap; a longer gap gets TIME_HIGH words in between. Gaps beyond this are refused.
constexpr TimeUs kMaxGapUs = TimeUs{1} << 40;

}  // namespace

LabelledEventsNpy::LabelledEventsNpy(const std::string& path) : path_(path), out_(path) {
  if (path == "-") throw std::runtime_error("npy output needs a file: it is rewritten at the end with the event count");
  out_.text(npy_header(0));
}

void LabelledEventsNpy::write(const LabelledEvent& e) {
  put_le<std::int64_t>(out_, e.event.t);
  put_le<std::uint16_t>(out_, e.event.x);
  put_le<std::uint16_t>(out_, e.event.y);
  put_le<std::uint8_t>(out_, e.event.p);
  put_le<std::int32_t>(out_, e.label);
  ++count_;
}

void LabelledEventsNpy::close() {
  out_.close();
  const std::string header = npy_header(count_);
  std::FILE* f = std::fopen(path_.c_str(), "r+b");
  const bool ok = f && std::fwrite(header.data(), 1, header.size(), f) == header.size();
  if (f && std::fclose(f) != 0) throw std::runtime_error(path_ + ": write failed: " + std::strerror(errno));
  if (!ok) throw std::runtime_error(path_ + ": cannot write the npy header: " + std::strerror(errno));
}

LabelsSideFile::LabelsSideFile(const std::string& path, const std::string& events_path) : out_(path) {
  // The events file by its name: the two sit side by side wherever they are moved.
  out_.text("# one label per event of " + std::filesystem::path(events_path).filename().string() + ", in its order\nlabel\n");
}

Aedat4Events::Aedat4Events(const std::string& path, const std::string& labels_path, SensorSize sensor)
    : out_(path), labels_(labels_path, path) {
  // The stream description as DV writes it: outInfo/<stream id>/ with the type, and its info/
  // node with the sensor size.
  const std::string xml =
      "<dv version=\"2.0\">\n"
      "  <node name=\"outInfo\" path=\"/outInfo/\">\n"
      "    <node name=\"0\" path=\"/outInfo/0/\">\n"
      "      <attr key=\"compression\" type=\"string\">LZ4</attr>\n"
      "      <attr key=\"originalModuleName\" type=\"string\">evms</attr>\n"
      "      <attr key=\"originalOutputName\" type=\"string\">events</attr>\n"
      "      <attr key=\"typeDescription\" type=\"string\">Array of events (polarity ON/OFF).</attr>\n"
      "      <attr key=\"typeIdentifier\" type=\"string\">EVTS</attr>\n"
      "      <node name=\"info\" path=\"/outInfo/0/info/\">\n"
      "        <attr key=\"sizeX\" type=\"int\">" + std::to_string(sensor.width) + "</attr>\n"
      "        <attr key=\"sizeY\" type=\"int\">" + std::to_string(sensor.height) + "</attr>\n"
      "        <attr key=\"source\" type=\"string\">evms</attr>\n"
      "      </node>\n"
      "    </node>\n"
      "  </node>\n"
      "</dv>\n";
  flatbuffers::FlatBufferBuilder header;
  header.FinishSizePrefixed(aedat4::CreateIOHeader(header, aedat4::Compression::LZ4, -1, header.CreateString(xml)),
                            aedat4::IOHeaderIdentifier());
  out_.text("#!AER-DAT4.0\r\n");
  out_.bytes(header.GetBufferPointer(), header.GetSize());
  packet_.reserve(kEventsPerPacket);
}

void Aedat4Events::write(const LabelledEvent& e) {
  packet_.push_back(e.event);
  labels_.write(e.label);
  if (packet_.size() == kEventsPerPacket) write_packet();
}

void Aedat4Events::write_packet() {
  std::vector<aedat4::PolarityEvent> elements;
  elements.reserve(packet_.size());
  for (const Event& e : packet_) elements.emplace_back(e.t, static_cast<std::int16_t>(e.x), static_cast<std::int16_t>(e.y), e.p != 0);
  flatbuffers::FlatBufferBuilder body(16 * packet_.size() + 64);
  body.FinishSizePrefixed(aedat4::CreateEventPacket(body, body.CreateVectorOfStructs(elements)),
                          aedat4::EventPacketIdentifier());
  compressed_.resize(LZ4F_compressFrameBound(body.GetSize(), nullptr));
  const size_t size = LZ4F_compressFrame(compressed_.data(), compressed_.size(), body.GetBufferPointer(), body.GetSize(), nullptr);
  if (LZ4F_isError(size)) throw std::runtime_error(std::string("AEDAT 4.0 output: LZ4 compression failed: ") + LZ4F_getErrorName(size));
  put_le<std::int32_t>(out_, 0);  // the stream
  put_le<std::int32_t>(out_, static_cast<std::int32_t>(size));
  out_.bytes(compressed_.data(), size);
  packet_.clear();
}

void Aedat4Events::close() {
  if (!packet_.empty()) write_packet();
  out_.close();
  labels_.close();
}

Evt3Events::Evt3Events(const std::string& raw_path, const std::string& labels_path, SensorSize sensor)
    : raw_path_(raw_path), raw_(raw_path), labels_(labels_path, raw_path) {
  if (sensor.width > 2048 || sensor.height > 2048) {
    throw std::runtime_error(raw_path + ": EVT 3.0 holds coordinates up to 2047; this sensor is " + std::to_string(sensor.width) + "x" +
                             std::to_string(sensor.height));
  }
  raw_.text("% evt 3.0\n% format EVT3;height=").integer(sensor.height).text(";width=").integer(sensor.width);
  raw_.text("\n% geometry ").integer(sensor.width).ch('x').integer(sensor.height).ch('\n');
}

void Evt3Events::word(unsigned type, unsigned payload) { put_le<std::uint16_t>(raw_, static_cast<std::uint16_t>((type << 12) | payload)); }

void Evt3Events::time_to(TimeUs t) {
  const TimeUs ticks = (t - base_) >> 12;
  if (ticks != ticks_) {
    if (ticks_ >= 0 && (ticks - ticks_) << 12 > kMaxGapUs) {
      throw std::runtime_error(raw_path_ + ": a gap of " + std::to_string(t - base_ - (ticks_ << 12)) +
                               " us between events is longer than EVT 3.0 output bridges (2^40 us)");
    }
    for (TimeUs k = ticks_ + 0x400; ticks_ >= 0 && k < ticks; k += 0x400) word(0x8, static_cast<unsigned>(k & 0xFFF));
    word(0x8, static_cast<unsigned>(ticks & 0xFFF));
    ticks_ = ticks;
    low_ = -1;
  }
  const TimeUs low = (t - base_) & 0xFFF;
  if (low != low_) word(0x6, static_cast<unsigned>(low)), low_ = low;
}

void Evt3Events::write(const LabelledEvent& e) {
  if (!started_) {
    base_ = e.event.t - e.event.t % kEpoch;
    raw_.text("% evms_time_base_us ").integer(base_).text("\n% end\n");
    started_ = true;
  }
  time_to(e.event.t);
  if (e.event.y != y_) word(0x0, e.event.y), y_ = e.event.y;
  word(0x2, (static_cast<unsigned>(e.event.p & 1) << 11) | e.event.x);
  labels_.write(e.label);
}

void Evt3Events::close() {
  if (!started_) raw_.text("% end\n");
  raw_.close();
  labels_.close();
}

}  // namespace evms::write
