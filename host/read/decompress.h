// Whole-frame decompression into a buffer of the size the container says, for the bag formats
// whose records state it (ROS 1 bag chunks, ROS 2 bag messages, MCAP chunks). A size that the
// frame cannot hold is refused before anything is allocated for it.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace evms::read {

// One LZ4 frame (the standard frame format, liblz4's LZ4F) that decompresses to exactly `size`
// bytes, into `out`; false when it is corrupt, cut short or of another size. LZ4 shrinks at
// most 255 to 1, so a larger `size` is refused at once.
bool lz4_frame_into(std::span<const unsigned char> frame, std::uint64_t size, std::vector<unsigned char>& out);

// One zstd frame that decompresses to exactly `size` bytes, into `out`; false when it is
// corrupt, cut short, of another size, or says another content size in its header.
bool zstd_frame_into(std::span<const unsigned char> frame, std::uint64_t size, std::vector<unsigned char>& out);

}  // namespace evms::read
