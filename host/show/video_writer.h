// Frames of the viewer as a video file (evms view --video FILE). The frames go as raw RGB24
// through a pipe to Debian's ffmpeg, which picks the encoder from the file's extension (H.264
// for .mp4 and .mkv, VP9 for .webm) and writes 4:2:0 colour, which every player shows; odd
// frame sizes are padded by one pixel, as 4:2:0 needs even sides.
#pragma once

#include <sys/types.h>

#include <string>

#include "host/show/canvas.h"

namespace evms::show {

class VideoWriter {
 public:
  // Starts ffmpeg; throws std::runtime_error naming `path` when ffmpeg is not installed.
  VideoWriter(const std::string& path, int width, int height, double fps);
  ~VideoWriter();
  VideoWriter(const VideoWriter&) = delete;
  VideoWriter& operator=(const VideoWriter&) = delete;

  // Throws std::runtime_error (with ffmpeg's own last line) when ffmpeg has stopped.
  void write(const Canvas& frame);
  // Ends the stream and waits for ffmpeg; throws as write does when the file is not complete.
  void close();
  std::int64_t frames() const { return frames_; }

 private:
  [[noreturn]] void fail(const std::string& what);
  int wait_for_ffmpeg();

  std::string path_, log_path_;
  int width_, height_;
  pid_t pid_ = -1;
  int pipe_ = -1;
  std::int64_t frames_ = 0;
};

}  // namespace evms::show
