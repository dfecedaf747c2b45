// AEDAT 4.0 (iniVation DV): "#!AER-DAT4.0\r\n", an int32 LE length and an IOHeader
// flatbuffer (compression, position of the data table, and an XML description of the
// streams), then packets {int32 streamId, int32 size, body}. Each body is compressed as one
// LZ4 or ZSTD frame (or stored), and holds a size-prefixed flatbuffer. Polarity events come in
// streams whose typeIdentifier is "EVTS", as {int64 timestamp_us, int16 x, int16 y, bool
// polarity}. The sensor size is the stream's sizeX/sizeY. Other streams (IMU, frames,
// triggers) are skipped and counted. Timestamps are absolute epoch microseconds.
#include <expat.h>
#include <lz4frame.h>
#include <zstd.h>

#include <charconv>
#include <cstring>
#include <map>

#include "aedat4_events_generated.h"
#include "aedat4_io_header_generated.h"
#include "host/read/bytes.h"
#include "host/read/event_source.h"

namespace evms::read {
namespace {

// What a stream's skipped packets are, by DV's type identifier.
std::string packets_of(const std::string& type) {
  if (type == "IMUS") return "IMU packets";
  if (type == "FRME") return "frame packets";
  if (type == "TRIG") return "trigger packets";
  return "packets of type '" + printable(type) + "'";
}

// A header or a packet, stored or decompressed, is at most 128 MiB: DV writes packets of a few
// MiB (10 ms of the densest sensor is 4 MiB), and a frame that would expand further is a
// decompression bomb or corrupt, refused before its buffer grows past the cap.
constexpr std::uint32_t kMaxPacketBytes = 1u << 27;

struct StreamInfo {
  std::string type;
  int size_x = 0;
  int size_y = 0;
};

// Collects each output stream's type and size from the header's XML.
class StreamXml {
 public:
  std::map<int, StreamInfo> parse(const std::string& xml, const std::string& path) {
    XML_Parser p = XML_ParserCreate(nullptr);
    XML_SetUserData(p, this);
    XML_SetElementHandler(p, &StreamXml::start, &StreamXml::end);
    XML_SetCharacterDataHandler(p, &StreamXml::text);
    const bool ok = XML_Parse(p, xml.data(), static_cast<int>(xml.size()), 1) != XML_STATUS_ERROR;
    std::string error = ok ? "" : XML_ErrorString(XML_GetErrorCode(p));
    XML_ParserFree(p);
    if (!ok) fail(path, {}, "bad header: the stream description XML does not parse (" + error + ")");
    return streams_;
  }

 private:
  static void start(void* self, const XML_Char* name, const XML_Char** attrs) {
    auto* s = static_cast<StreamXml*>(self);
    std::string element = name;
    std::map<std::string, std::string> a;
    for (int i = 0; attrs[i]; i += 2) a[attrs[i]] = attrs[i + 1];
    if (element == "node") {
      s->path_stack_.push_back(a["path"]);
    } else if (element == "attr") {
      s->key_ = a["key"];
      s->value_.clear();
      s->in_attr_ = true;
    }
  }
  static void end(void* self, const XML_Char* name) {
    auto* s = static_cast<StreamXml*>(self);
    std::string element = name;
    if (element == "node" && !s->path_stack_.empty()) {
      s->path_stack_.pop_back();
    } else if (element == "attr") {
      s->in_attr_ = false;
      s->record();
    }
  }
  static void text(void* self, const XML_Char* data, int len) {
    auto* s = static_cast<StreamXml*>(self);
    if (s->in_attr_) s->value_.append(data, static_cast<size_t>(len));
  }
  // Paths look like ".../outInfo/<id>/" and ".../outInfo/<id>/info/".
  void record() {
    if (path_stack_.empty()) return;
    const std::string& path = path_stack_.back();
    const size_t at = path.find("/outInfo/");
    if (at == std::string::npos) return;
    const std::string rest = path.substr(at + 9);
    const size_t slash = rest.find('/');
    if (slash == std::string::npos || slash == 0) return;
    int id = 0;
    if (std::from_chars(rest.data(), rest.data() + slash, id).ec != std::errc()) return;
    const std::string tail = rest.substr(slash + 1);
    StreamInfo& info = streams_[id];
    if (tail.empty() && key_ == "typeIdentifier") info.type = value_;
    if (tail == "info/" && key_ == "sizeX") std::from_chars(value_.data(), value_.data() + value_.size(), info.size_x);
    if (tail == "info/" && key_ == "sizeY") std::from_chars(value_.data(), value_.data() + value_.size(), info.size_y);
  }

  std::vector<std::string> path_stack_;
  std::string key_, value_;
  bool in_attr_ = false;
  std::map<int, StreamInfo> streams_;
};

class Aedat4Source final : public FileEventSource {
 public:
  Aedat4Source(ByteReader in, const SourceOptions& o) : FileEventSource(std::move(in), "AEDAT 4.0", o) {
    std::string_view magic = in_.peek(14);
    if (magic != "#!AER-DAT4.0\r\n") fail(in_.path(), InputPosition::byte(0), "bad header: expected '#!AER-DAT4.0' and CRLF");
    in_.skip(14);
    // The length and the flatbuffer form one size-prefixed buffer; its alignment counts
    // from the length field, so it is verified whole.
    unsigned char len_bytes[4];
    if (in_.read(len_bytes, 4) < 4) fail(in_.path(), InputPosition::byte(14), "bad header: truncated header length");
    const std::uint32_t len = le32(len_bytes);
    if (len > kMaxPacketBytes || 18 + std::uint64_t{len} > in_.size()) {
      fail(in_.path(), InputPosition::byte(14), "bad header: header length " + std::to_string(len) + " runs past the end of the file");
    }
    std::vector<std::uint8_t> header(4 + std::size_t{len});
    std::memcpy(header.data(), len_bytes, 4);
    in_.read(header.data() + 4, len);
    flatbuffers::Verifier verifier(header.data(), header.size());
    if (!aedat4::VerifySizePrefixedIOHeaderBuffer(verifier)) {
      fail(in_.path(), InputPosition::byte(18), "bad header: the IOHeader flatbuffer does not verify");
    }
    const aedat4::IOHeader* h = aedat4::GetSizePrefixedIOHeader(header.data());
    compression_ = h->compression();
    if (compression_ < aedat4::Compression::NONE || compression_ > aedat4::Compression::ZSTD_HIGH) {
      fail(in_.path(), InputPosition::byte(18), "bad header: unknown compression " + std::to_string(static_cast<int>(compression_)));
    }
    data_end_ = h->data_table_position() >= 0 ? static_cast<std::uint64_t>(h->data_table_position()) : in_.size();
    streams_ = StreamXml().parse(h->info_node() ? h->info_node()->str() : "", in_.path());
    std::optional<SensorSize> size;
    for (const auto& [id, s] : streams_) {
      if (s.type == "EVTS" && s.size_x > 0 && s.size_y > 0 && !size) size = SensorSize{s.size_x, s.size_y};
    }
    set_sensor(size, std::nullopt, "");
  }

 protected:
  bool decode_more() override {
    const std::uint64_t at = in_.offset();
    if (at >= data_end_) return false;
    unsigned char h[8];
    const size_t got = in_.read(h, 8);
    if (got == 0) return false;
    if (got < 8) fail(in_.path(), InputPosition::byte(at), "truncated packet header (" + std::to_string(got) + " of 8 bytes)");
    const std::int32_t stream = static_cast<std::int32_t>(le32(h));
    const std::uint32_t size = le32(h + 4);
    if (size > kMaxPacketBytes) too_large(at);
    if (at + 8 + size > in_.size()) {
      fail(in_.path(), InputPosition::byte(at), "truncated packet: body of " + std::to_string(size) + " bytes runs past the end of the file");
    }
    auto it = streams_.find(stream);
    if (it == streams_.end()) fail(in_.path(), InputPosition::byte(at), "packet of undeclared stream " + std::to_string(stream));
    if (it->second.type != "EVTS") {
      count_skipped(packets_of(it->second.type));
      in_.skip(size);
      return true;
    }
    compressed_.resize(size);
    in_.read(compressed_.data(), size);
    const std::vector<std::uint8_t>& body = decompress(at);
    flatbuffers::Verifier verifier(body.data(), body.size());
    if (!aedat4::VerifySizePrefixedEventPacketBuffer(verifier)) {
      fail(in_.path(), InputPosition::byte(at), "event packet flatbuffer does not verify");
    }
    const auto* packet = aedat4::GetSizePrefixedEventPacket(body.data());
    if (!packet->elements()) return true;
    for (const aedat4::PolarityEvent* e : *packet->elements()) {
      emit(e->timestamp(), e->x(), e->y(), e->polarity(), InputPosition::byte(at));
    }
    return true;
  }

 private:
  const std::vector<std::uint8_t>& decompress(std::uint64_t at) {
    using aedat4::Compression;
    if (compression_ == Compression::NONE) return compressed_;
    plain_.clear();
    if (compression_ == Compression::LZ4 || compression_ == Compression::LZ4_HIGH) {
      LZ4F_dctx* ctx = nullptr;
      LZ4F_createDecompressionContext(&ctx, LZ4F_VERSION);
      size_t in_pos = 0;
      size_t hint = 1;
      std::vector<std::uint8_t> chunk(1 << 16);
      while (in_pos < compressed_.size() && hint != 0) {
        size_t out_size = chunk.size();
        size_t in_size = compressed_.size() - in_pos;
        hint = LZ4F_decompress(ctx, chunk.data(), &out_size, compressed_.data() + in_pos, &in_size, nullptr);
        if (LZ4F_isError(hint)) {
          std::string why = LZ4F_getErrorName(hint);
          LZ4F_freeDecompressionContext(ctx);
          fail(in_.path(), InputPosition::byte(at), "LZ4 frame does not decompress (" + why + ")");
        }
        in_pos += in_size;
        if (plain_.size() + out_size > kMaxPacketBytes) {
          LZ4F_freeDecompressionContext(ctx);
          too_large(at);
        }
        plain_.insert(plain_.end(), chunk.begin(), chunk.begin() + static_cast<long>(out_size));
      }
      LZ4F_freeDecompressionContext(ctx);
      if (hint != 0) fail(in_.path(), InputPosition::byte(at), "truncated LZ4 frame");
    } else {
      ZSTD_DStream* ds = ZSTD_createDStream();
      ZSTD_initDStream(ds);
      ZSTD_inBuffer input{compressed_.data(), compressed_.size(), 0};
      std::vector<std::uint8_t> chunk(ZSTD_DStreamOutSize());
      size_t ret = 1;
      while (ret != 0) {
        ZSTD_outBuffer output{chunk.data(), chunk.size(), 0};
        ret = ZSTD_decompressStream(ds, &output, &input);
        if (ZSTD_isError(ret)) {
          std::string why = ZSTD_getErrorName(ret);
          ZSTD_freeDStream(ds);
          fail(in_.path(), InputPosition::byte(at), "ZSTD frame does not decompress (" + why + ")");
        }
        if (plain_.size() + output.pos > kMaxPacketBytes) {
          ZSTD_freeDStream(ds);
          too_large(at);
        }
        plain_.insert(plain_.end(), chunk.begin(), chunk.begin() + static_cast<long>(output.pos));
        if (input.pos == input.size && output.pos < output.size && ret != 0) break;
      }
      ZSTD_freeDStream(ds);
      if (ret != 0) fail(in_.path(), InputPosition::byte(at), "truncated ZSTD frame");
    }
    return plain_;
  }

  [[noreturn]] void too_large(std::uint64_t at) const {
    fail(in_.path(), InputPosition::byte(at),
         "packet of more than " + std::to_string(kMaxPacketBytes >> 20) + " MiB, stored or decompressed (a corrupt frame or a decompression bomb)");
  }

  aedat4::Compression compression_ = aedat4::Compression::NONE;
  std::uint64_t data_end_ = 0;
  std::map<int, StreamInfo> streams_;
  std::vector<std::uint8_t> compressed_;
  std::vector<std::uint8_t> plain_;
};

}  // namespace

std::unique_ptr<EventSource> open_aedat4(ByteReader in, const SourceOptions& o) {
  return std::make_unique<Aedat4Source>(std::move(in), o);
}

}  // namespace evms::read
