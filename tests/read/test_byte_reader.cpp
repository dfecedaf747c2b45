// The forward reader under every decoder (host/read/byte_reader.h): a skip lands on the same
// byte whether the file seeks (a regular file) or is read through (a pipe), and stops at the end.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <csignal>
#include <cstdio>
#include <thread>

#include "host/read/byte_reader.h"
#include "tests/support/encoders.h"

namespace evms::test {
namespace {

TEST(ByteReader, ASkipLandsOnTheSameByteInAFileAndThroughAPipe) {
  TempDir dir;
  Bytes bytes(3 << 20);
  for (size_t i = 0; i < bytes.size(); ++i) bytes[i] = static_cast<unsigned char>(i * 7 % 251);
  const std::string file = dir.write("bytes.bin", bytes);
  const std::string fifo = dir.path("bytes.fifo");
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  std::signal(SIGPIPE, SIG_IGN);
  std::thread writer([&] {
    std::FILE* f = std::fopen(fifo.c_str(), "wb");
    if (f) std::fwrite(bytes.data(), 1, bytes.size(), f), std::fclose(f);
  });
  for (const std::string& path : {file, fifo}) {
    SCOPED_TRACE(path);
    read::ByteReader in(path);
    unsigned char got[8];
    const auto expect_bytes_at = [&](std::uint64_t at) {
      ASSERT_EQ(in.offset(), at);
      ASSERT_EQ(in.read(got, sizeof got), sizeof got);
      EXPECT_TRUE(std::equal(got, got + sizeof got, bytes.begin() + static_cast<long>(at)));
    };
    expect_bytes_at(0);
    in.skip(100);  // inside what is buffered
    expect_bytes_at(108);
    in.skip(2'000'000);  // beyond it
    expect_bytes_at(2'000'116);
    EXPECT_EQ(in.peek(4), std::string_view(reinterpret_cast<const char*>(&bytes[2'000'124]), 4));
    in.skip(~std::uint64_t{0});  // past the end: at the end
    EXPECT_EQ(in.offset(), bytes.size());
    EXPECT_TRUE(in.at_end());
    EXPECT_EQ(in.read(got, sizeof got), 0u);
  }
  writer.join();
}

}  // namespace
}  // namespace evms::test
