// har/confusion.png (ptnet/har.hpp): one row-normalised confusion matrix per
// training source, side by side; a second row of panels for the category
// labels when they were run. A minimal libpng writer with a 3 x 5 pixel font
// (the viz stage's writer was not available when this was written).
#include <png.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <map>

#include "ptnet/error.hpp"
#include "ptnet/har.hpp"
#include "ptnet/io.hpp"

namespace ptnet::har {
namespace {

constexpr int kScale = 2;     // font pixel size
constexpr int kMargin = 16;   // px around and between panels
constexpr int kLabelPx = 18;  // room for class indices

struct Rgb {
  unsigned char r, g, b;
};
constexpr Rgb kWhite{255, 255, 255}, kInk{30, 30, 30}, kFull{8, 48, 107}, kGrid{200, 200, 200};

// 3 x 5 glyphs (upper case), one string of 15 '#'/'.' per character, row by row.
const std::map<char, const char*>& font() {
  static const std::map<char, const char*> f = {
      {'0', "####.##.##.####"}, {'1', ".#.##..#..#.###"}, {'2', "###..#####..###"},
      {'3', "###..#.##..####"}, {'4', "#.##.####..#..#"}, {'5', "####..###..####"},
      {'6', "####..####.####"}, {'7', "###..#.#..#..#."}, {'8', "####.#####.####"},
      {'9', "####.####..####"}, {'+', "....#.###.#...."}, {'A', ".#.#.#####.##.#"},
      {'C', ".###..#..#...##"}, {'D', "##.#.##.##.###."}, {'E', "####..##.#..###"},
      {'G', ".###..#.##.#.##"}, {'H', "#.##.#####.##.#"}, {'I', "###.#..#..#.###"},
      {'L', "#..#..#..#..###"}, {'N', "##.#.##.##.##.#"}, {'O', ".#.#.##.##.#.#."},
      {'P', "##.#.###.#..#.."}, {'R', "##.#.###.#.##.#"}, {'S', ".###...#...###."},
      {'T', "###.#..#..#..#."}, {'U', "#.##.##.##.####"}, {'Y', "#.##.#.#..#..#."},
      {' ', "..............."}};
  return f;
}

class Canvas {
 public:
  Canvas(int w, int h) : w_(w), h_(h), px_(std::size_t(w) * h * 3, 255) {}
  void set(int x, int y, Rgb c) {
    if (x < 0 || y < 0 || x >= w_ || y >= h_) return;
    unsigned char* p = &px_[(std::size_t(y) * w_ + x) * 3];
    p[0] = c.r;
    p[1] = c.g;
    p[2] = c.b;
  }
  void fill(int x0, int y0, int w, int h, Rgb c) {
    for (int y = y0; y < y0 + h; ++y)
      for (int x = x0; x < x0 + w; ++x) set(x, y, c);
  }
  void text(int x, int y, const std::string& s, Rgb c) {
    for (char ch : s) {
      auto it = font().find(char(std::toupper((unsigned char)ch)));
      if (it != font().end())
        for (int i = 0; i < 15; ++i)
          if (it->second[i] == '#') fill(x + (i % 3) * kScale, y + (i / 3) * kScale, kScale, kScale, c);
      x += 4 * kScale;
    }
  }
  void save(const std::string& path, bool force) const {
    AtomicFile out(path, force);
    FILE* f = std::fopen(out.temp_path().c_str(), "wb");
    if (!f) throw Error::in(path, "cannot write", ErrorKind::io);
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
    png_infop info = png ? png_create_info_struct(png) : nullptr;
    if (!png || !info || setjmp(png_jmpbuf(png))) {
      png_destroy_write_struct(&png, &info);
      std::fclose(f);
      throw Error::in(path, "PNG write failed");
    }
    png_init_io(png, f);
    png_set_IHDR(png, info, w_, h_, 8, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_write_info(png, info);
    for (int y = 0; y < h_; ++y)
      png_write_row(png, const_cast<png_bytep>(&px_[std::size_t(y) * w_ * 3]));
    png_write_end(png, nullptr);
    png_destroy_write_struct(&png, &info);
    if (std::fclose(f) != 0) throw Error::in(path, "write failed (disk full?)");
    out.commit();
  }

 private:
  int w_, h_;
  std::vector<unsigned char> px_;
};

void panel(Canvas& c, int x0, int y0, int cell, const std::string& title, const Eigen::MatrixXi& m) {
  c.text(x0 + kLabelPx, y0, title, kInk);
  const int top = y0 + 8 * kScale + kLabelPx, left = x0 + kLabelPx;
  const int n = int(m.rows());
  for (int i = 0; i < n; ++i) {
    const double total = std::max(1, m.row(i).sum());
    for (int j = 0; j < n; ++j) {
      const double v = m(i, j) / total;  // row-normalised: recall on the diagonal
      const Rgb col{(unsigned char)(255 + v * (kFull.r - 255)),
                    (unsigned char)(255 + v * (kFull.g - 255)),
                    (unsigned char)(255 + v * (kFull.b - 255))};
      c.fill(left + j * cell, top + i * cell, cell - 1, cell - 1, col);
    }
    if (cell >= 4 * kScale * 2 || n <= 12) {
      c.text(x0, top + i * cell + (cell - 5 * kScale) / 2, std::to_string(i), kInk);
      c.text(left + i * cell + (cell - 3 * kScale) / 2, top - 7 * kScale, std::to_string(i), kInk);
    }
  }
  c.fill(left - 1, top - 1, n * cell + 1, 1, kGrid);
  c.fill(left - 1, top - 1, 1, n * cell + 1, kGrid);
}

}  // namespace

void write_confusion_png(const std::string& path, const HarResult& r, bool force) {
  if (r.sources.empty()) throw Error::in(path, "no results to draw");
  const bool categories = !r.sources[0].category_macro_f1.empty();
  const int n = std::max(1, r.clusters);
  const int cell = std::clamp(240 / n, 8, 32);
  const int cat_n = std::max(1, int(r.categories.size()));
  std::size_t title = 0;
  for (const auto& s : r.sources) title = std::max(title, s.source.size() + (categories ? 9 : 0));
  const int panel_w = kLabelPx + std::max(n * cell, int(title) * 4 * kScale) + kMargin;
  const int panel_h = 8 * kScale + kLabelPx + n * cell + kMargin;
  const int cat_h = 8 * kScale + kLabelPx + cat_n * cell + kMargin;
  const int width = kMargin + int(r.sources.size()) * panel_w;
  const int height = kMargin + panel_h + (categories ? cat_h : 0);
  Canvas c(width, height);
  for (std::size_t s = 0; s < r.sources.size(); ++s) {
    const int x0 = kMargin + int(s) * panel_w;
    panel(c, x0, kMargin, cell, r.sources[s].source, r.sources[s].confusion);
    if (categories)
      panel(c, x0, kMargin + panel_h, cell, r.sources[s].source + " category",
            r.sources[s].category_confusion);
  }
  c.save(path, force);
}

}  // namespace ptnet::har
