// Whole-frame decompression (host/read/decompress.h): a frame gives back exactly its bytes at
// the size it holds, and nothing at any other size, cut short, or with a byte changed.
#include <gtest/gtest.h>

#include <lz4frame.h>
#include <zstd.h>

#include <random>

#include "host/read/decompress.h"

namespace evms::read {
namespace {

std::vector<unsigned char> sample(size_t n) {
  std::mt19937 rng(5);
  std::vector<unsigned char> b(n);
  for (size_t i = 0; i < n; ++i) b[i] = static_cast<unsigned char>(i % 7 == 0 ? rng() : i / 64);  // compressible, not constant
  return b;
}

std::vector<unsigned char> lz4(const std::vector<unsigned char>& in) {
  std::vector<unsigned char> out(LZ4F_compressFrameBound(in.size(), nullptr));
  out.resize(LZ4F_compressFrame(out.data(), out.size(), in.data(), in.size(), nullptr));
  return out;
}

std::vector<unsigned char> zstd(const std::vector<unsigned char>& in) {
  std::vector<unsigned char> out(ZSTD_compressBound(in.size()));
  out.resize(ZSTD_compress(out.data(), out.size(), in.data(), in.size(), 3));
  return out;
}

using Decompress = bool (*)(std::span<const unsigned char>, std::uint64_t, std::vector<unsigned char>&);

void check(Decompress decompress, std::vector<unsigned char> (*compress)(const std::vector<unsigned char>&)) {
  for (size_t n : {size_t{0}, size_t{1}, size_t{1000}, size_t{300000}}) {
    SCOPED_TRACE(n);
    const auto plain = sample(n), frame = compress(plain);
    std::vector<unsigned char> out;
    ASSERT_TRUE(decompress(frame, n, out));
    EXPECT_EQ(out, plain);
    EXPECT_FALSE(decompress(frame, n + 1, out));
    if (n > 0) {
      EXPECT_FALSE(decompress(frame, n - 1, out));
    }
    const std::vector<unsigned char> cut(frame.begin(), frame.end() - 1);
    EXPECT_FALSE(decompress(cut, n, out));
    // A frame whose magic number is changed is no frame.
    std::vector<unsigned char> bad = frame;
    bad[0] ^= 0x5A;
    EXPECT_FALSE(decompress(bad, n, out));
    // A changed byte anywhere else may still decompress (neither frame carries a checksum by
    // default), but never past the buffer: the sanitizer builds run this.
    for (size_t k = 1; k < 64; ++k) {
      bad = frame;
      bad[k * frame.size() / 64] ^= 0x5A;
      decompress(bad, n, out);
    }
  }
}

TEST(Decompress, Lz4FramesGiveBackExactlyTheirBytes) {
  check(lz4_frame_into, lz4);
  // More than LZ4's 255 to 1 is refused before anything is allocated.
  std::vector<unsigned char> out;
  EXPECT_FALSE(lz4_frame_into(lz4(sample(10)), std::uint64_t{1} << 40, out));
  EXPECT_TRUE(out.empty());
}

TEST(Decompress, ZstdFramesGiveBackExactlyTheirBytes) {
  check(zstd_frame_into, zstd);
  // A frame whose header says another size is refused before anything is allocated.
  std::vector<unsigned char> out;
  EXPECT_FALSE(zstd_frame_into(zstd(sample(10)), std::uint64_t{1} << 40, out));
  EXPECT_TRUE(out.empty());
}

}  // namespace
}  // namespace evms::read
