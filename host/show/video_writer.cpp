#include "host/show/video_writer.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <stdexcept>
#include <vector>

extern char** environ;

namespace evms::show {
namespace {

std::string extension_of(const std::string& path) {
  const size_t dot = path.rfind('.');
  const size_t slash = path.rfind('/');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string e = path.substr(dot + 1);
  for (char& c : e) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return e;
}

std::string last_line_of(const std::string& path) {
  std::ifstream in(path);
  std::string line, last;
  while (std::getline(in, line)) {
    if (!line.empty()) last = line;
  }
  return last;
}

}  // namespace

VideoWriter::VideoWriter(const std::string& path, int width, int height, double fps) : path_(path), width_(width), height_(height) {
  char log_template[] = "/tmp/evms-ffmpeg-XXXXXX";
  const int log_fd = mkstemp(log_template);
  if (log_fd < 0) throw std::runtime_error(path + ": cannot make a log file for ffmpeg: " + std::strerror(errno));
  log_path_ = log_template;
  int fds[2];
  if (pipe2(fds, O_CLOEXEC) != 0) {
    ::close(log_fd);
    throw std::runtime_error(path + ": cannot make a pipe to ffmpeg: " + std::strerror(errno));
  }
  // A write to an ffmpeg that has stopped must fail with EPIPE, to be reported with ffmpeg's
  // reason, not end evms by the signal.
  std::signal(SIGPIPE, SIG_IGN);
  const std::string size = std::to_string(width) + "x" + std::to_string(height);
  const std::string rate = std::to_string(fps);
  std::vector<std::string> args = {"ffmpeg", "-hide_banner", "-loglevel", "error", "-y", "-f", "rawvideo", "-pixel_format", "rgb24",
                                   "-video_size", size, "-framerate", rate, "-i", "pipe:0", "-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2"};
  // GIF has its own palette; every other container gets the 4:2:0 colour players expect.
  if (extension_of(path) != "gif") args.insert(args.end(), {"-pix_fmt", "yuv420p"});
  args.push_back(path);
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, fds[0], STDIN_FILENO);
  posix_spawn_file_actions_adddup2(&actions, log_fd, STDOUT_FILENO);
  posix_spawn_file_actions_adddup2(&actions, log_fd, STDERR_FILENO);
  const int spawned = posix_spawnp(&pid_, "ffmpeg", &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  ::close(fds[0]);
  ::close(log_fd);
  if (spawned != 0) {
    pid_ = -1;
    ::close(fds[1]);
    std::remove(log_path_.c_str());
    if (spawned == ENOENT) throw std::runtime_error(path + ": writing video needs ffmpeg, which is not installed (apt install ffmpeg)");
    throw std::runtime_error(path + ": cannot start ffmpeg: " + std::strerror(spawned));
  }
  pipe_ = fds[1];
}

VideoWriter::~VideoWriter() {
  if (pipe_ >= 0) ::close(pipe_);
  if (pid_ > 0) wait_for_ffmpeg();
  if (!log_path_.empty()) std::remove(log_path_.c_str());
}

int VideoWriter::wait_for_ffmpeg() {
  int status = 0;
  while (waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
  }
  pid_ = -1;
  return status;
}

void VideoWriter::fail(const std::string& what) {
  if (pipe_ >= 0) ::close(pipe_), pipe_ = -1;
  if (pid_ > 0) wait_for_ffmpeg();
  const std::string reason = last_line_of(log_path_);
  throw std::runtime_error(path_ + ": " + what + (reason.empty() ? "" : " (ffmpeg: " + reason + ")"));
}

void VideoWriter::write(const Canvas& frame) {
  if (frame.width() != width_ || frame.height() != height_) throw std::logic_error("video frames change size");
  if (pipe_ < 0) throw std::logic_error("video written after close");
  const auto* data = reinterpret_cast<const char*>(frame.pixels().data());
  size_t left = frame.pixels().size() * sizeof(Rgb);
  while (left > 0) {
    const ssize_t n = ::write(pipe_, data, left);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) fail("ffmpeg stopped taking frames");
    data += n;
    left -= static_cast<size_t>(n);
  }
  ++frames_;
}

void VideoWriter::close() {
  if (pipe_ >= 0) ::close(pipe_), pipe_ = -1;
  if (pid_ <= 0) return;
  const int status = wait_for_ffmpeg();
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) fail("ffmpeg could not write the video");
}

}  // namespace evms::show
