#include <algorithm>

#include "ptnet/viz.hpp"

namespace ptnet {

Image::Image(int w, int h, Rgb fill) : width(w), height(h), rgb(size_t(w) * h * 3) {
  fill_rect(0, 0, w, h, fill);
}

Rgb Image::get(int x, int y) const {
  const std::uint8_t* p = &rgb[(size_t(y) * width + x) * 3];
  return Rgb{p[0], p[1], p[2]};
}

void Image::set(int x, int y, Rgb c) {
  if (x < 0 || y < 0 || x >= width || y >= height) return;
  std::uint8_t* p = &rgb[(size_t(y) * width + x) * 3];
  p[0] = c.r, p[1] = c.g, p[2] = c.b;
}

void Image::fill_rect(int x, int y, int w, int h, Rgb c) {
  const int x0 = std::max(x, 0), y0 = std::max(y, 0);
  const int x1 = std::min(x + w, width), y1 = std::min(y + h, height);
  for (int yy = y0; yy < y1; ++yy) {
    std::uint8_t* p = &rgb[(size_t(yy) * width + x0) * 3];
    for (int xx = x0; xx < x1; ++xx, p += 3) p[0] = c.r, p[1] = c.g, p[2] = c.b;
  }
}

void Image::blit(const Image& src, int x, int y) {
  for (int yy = 0; yy < src.height; ++yy)
    for (int xx = 0; xx < src.width; ++xx) set(x + xx, y + yy, src.get(xx, yy));
}

}  // namespace ptnet
