// An RGB image to draw events, tracks and text on, and to save as PNG (libpng). The viewer,
// its headless frames and the evaluation pictures all draw through it.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace evms::show {

struct Rgb {
  std::uint8_t r = 0, g = 0, b = 0;
  friend bool operator==(const Rgb&, const Rgb&) = default;
};
// A canvas's pixels are packed RGB24, as SDL textures and ffmpeg's rawvideo take them.
static_assert(sizeof(Rgb) == 3);

class Canvas {
 public:
  Canvas(int width, int height, Rgb background = {});
  int width() const { return width_; }
  int height() const { return height_; }
  void clear(Rgb c);
  void set(int x, int y, Rgb c) {
    if (x >= 0 && y >= 0 && x < width_ && y < height_) pixels_[static_cast<size_t>(y) * width_ + x] = c;
  }
  Rgb get(int x, int y) const { return pixels_[static_cast<size_t>(y) * width_ + x]; }
  void blend(int x, int y, Rgb c, double alpha);
  void fill_rect(int x, int y, int w, int h, Rgb c);
  void line(double x0, double y0, double x1, double y1, Rgb c, double alpha = 1.0);
  void circle(double cx, double cy, double r, Rgb c);
  // Text in a built-in 5x7 pixel font (digits, letters, a few symbols), scaled by `scale`.
  void text(int x, int y, const std::string& s, Rgb c, int scale = 1);
  const std::vector<Rgb>& pixels() const { return pixels_; }
  // Throws std::runtime_error naming the file when it cannot be written.
  void save_png(const std::string& path) const;

 private:
  int width_, height_;
  std::vector<Rgb> pixels_;
};

// A distinct, stable colour for a track ID (golden-angle hues).
Rgb label_colour(std::int32_t label);

}  // namespace evms::show
