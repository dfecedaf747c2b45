#include "host/read/decompress.h"

#include <lz4frame.h>
#include <zstd.h>

#include <memory>

namespace evms::read {

bool lz4_frame_into(std::span<const unsigned char> frame, std::uint64_t size, std::vector<unsigned char>& out) {
  if (size > 255 * std::uint64_t{frame.size()} + 64) return false;
  LZ4F_dctx* dctx = nullptr;
  if (LZ4F_isError(LZ4F_createDecompressionContext(&dctx, LZ4F_VERSION))) return false;
  const std::unique_ptr<LZ4F_dctx, decltype(&LZ4F_freeDecompressionContext)> owned(dctx, LZ4F_freeDecompressionContext);
  out.resize(size);
  size_t written = size, read = frame.size();
  const size_t left = LZ4F_decompress(dctx, out.data(), &written, frame.data(), &read, nullptr);
  return !LZ4F_isError(left) && left == 0 && written == size;
}

bool zstd_frame_into(std::span<const unsigned char> frame, std::uint64_t size, std::vector<unsigned char>& out) {
  const unsigned long long says = ZSTD_getFrameContentSize(frame.data(), frame.size());
  if (says == ZSTD_CONTENTSIZE_ERROR || (says != ZSTD_CONTENTSIZE_UNKNOWN && says != size)) return false;
  out.resize(size);
  const size_t got = ZSTD_decompress(out.data(), out.size(), frame.data(), frame.size());
  return !ZSTD_isError(got) && got == size;
}

}  // namespace evms::read
