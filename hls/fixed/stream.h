// A bounded FIFO that mirrors hls::stream: the core's blocks talk only through these, as
// they would through hardware FIFOs. Depth is a template argument; there is no allocation.
// A write into a full stream is refused and remembered (overflowed()), the way a C
// simulation of hls::stream reports a deadlock instead of growing.
#pragma once

namespace evms::hls {

template <typename T, int Depth>
class Stream {
  static_assert(Depth >= 1, "Stream: depth must be at least 1");

 public:
  bool empty() const { return count_ == 0; }
  bool full() const { return count_ == Depth; }
  int size() const { return count_; }
  static constexpr int depth() { return Depth; }

  // Non-blocking write: false (and overflowed() from then on) when full.
  bool write(const T& v) {
    if (full()) {
      overflowed_ = true;
      return false;
    }
    buf_[(head_ + count_) % Depth] = v;
    ++count_;
    return true;
  }
  // Non-blocking read: false when empty.
  bool read(T& v) {
    if (empty()) return false;
    v = buf_[head_];
    head_ = (head_ + 1) % Depth;
    --count_;
    return true;
  }
  const T& front() const { return buf_[head_]; }
  // Drops everything held (a testbench that only counts).
  void clear() { head_ = count_ = 0; }
  bool overflowed() const { return overflowed_; }

 private:
  T buf_[Depth] = {};
  int head_ = 0;
  int count_ = 0;
  bool overflowed_ = false;
};

}  // namespace evms::hls
