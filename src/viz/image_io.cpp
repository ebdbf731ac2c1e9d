// PNG (libpng) and animated GIF (giflib) writers; both atomic.
#include <gif_lib.h>
#include <png.h>

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <map>

#include "ptnet/error.hpp"
#include "ptnet/io.hpp"
#include "ptnet/viz.hpp"

namespace ptnet {

void write_png(const std::string& path, const Image& image, bool force) {
  if (image.width <= 0 || image.height <= 0) throw Error::in(path, "empty image");
  AtomicFile out(path, force);
  FILE* fp = std::fopen(out.temp_path().c_str(), "wb");
  if (!fp)
    throw Error::in(path, std::string("cannot write: ") + std::strerror(errno), ErrorKind::io);
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (!png || !info) {
    png_destroy_write_struct(&png, nullptr);
    std::fclose(fp);
    throw Error::in(path, "libpng: out of memory");
  }
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    std::fclose(fp);
    throw Error::in(path, "libpng: write failed (disk full?)");
  }
  png_init_io(png, fp);
  png_set_IHDR(png, info, image.width, image.height, 8, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_text text{};
  text.compression = PNG_TEXT_COMPRESSION_NONE;
  text.key = const_cast<char*>("Software");
  text.text = const_cast<char*>("ptnet " PTNET_VERSION);
  png_set_text(png, info, &text, 1);
  png_write_info(png, info);
  for (int y = 0; y < image.height; ++y)
    png_write_row(png, const_cast<png_bytep>(&image.rgb[size_t(y) * image.width * 3]));
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  if (std::fclose(fp) != 0) throw Error::in(path, "write failed (disk full?)");
  out.commit();
}

namespace {
std::uint32_t key(const std::uint8_t* p) { return std::uint32_t(p[0]) << 16 | p[1] << 8 | p[2]; }

struct GifCloser {
  GifFileType* gif;
  ~GifCloser() {
    int err;
    if (gif) EGifCloseFile(gif, &err);
  }
};

// Palette: the exact colours used (figures use few), else nearest of the first 256.
class GifPalette {
 public:
  explicit GifPalette(const std::vector<Image>& frames) {
    for (const auto& f : frames)
      for (size_t i = 0; i < f.rgb.size(); i += 3) {
        auto k = key(&f.rgb[i]);
        if (!index_.count(k) && colours_.size() < 256) {
          index_[k] = int(colours_.size());
          colours_.push_back(GifColorType{f.rgb[i], f.rgb[i + 1], f.rgb[i + 2]});
        }
      }
    while (colours_.size() < 256) colours_.push_back(GifColorType{0, 0, 0});
  }
  GifColorType* colours() { return colours_.data(); }
  // Palette index of the pixel at p (RGB).
  int lookup(const std::uint8_t* p) {
    auto k = key(p);
    auto it = index_.find(k);
    if (it != index_.end()) return it->second;
    auto [c, inserted] = nearest_.emplace(k, 0);
    if (inserted) {
      int best = 0, best_d = 1 << 30;
      for (size_t j = 0; j < colours_.size(); ++j) {
        int dr = colours_[j].Red - p[0], dg = colours_[j].Green - p[1], db = colours_[j].Blue - p[2];
        int d = dr * dr + dg * dg + db * db;
        if (d < best_d) best_d = d, best = int(j);
      }
      c->second = best;
    }
    return c->second;
  }

 private:
  std::map<std::uint32_t, int> index_, nearest_;
  std::vector<GifColorType> colours_;
};

// The rectangle [x0, x1] x [y0, y1] of `img` that differs from `prev`; one
// pixel for identical frames.
std::array<int, 4> changed_rect(const Image& img, const Image& prev) {
  const int w = img.width, h = img.height;
  int x0 = w, y0 = h, x1 = -1, y1 = -1;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      size_t i = (size_t(y) * w + x) * 3;
      if (img.rgb[i] != prev.rgb[i] || img.rgb[i + 1] != prev.rgb[i + 1] || img.rgb[i + 2] != prev.rgb[i + 2]) {
        x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
      }
    }
  if (x1 < 0) x0 = y0 = x1 = y1 = 0;  // identical frame: one pixel
  return {x0, y0, x1, y1};
}

}  // namespace

void write_gif(const std::string& path, const std::vector<Image>& frames,
               const std::vector<int>& delays_cs, bool force) {
  if (frames.empty()) throw Error::in(path, "no frames to write");
  if (delays_cs.size() != frames.size()) throw Error::in(path, "one delay per frame expected");
  const int w = frames[0].width, h = frames[0].height;
  for (const auto& f : frames)
    if (f.width != w || f.height != h) throw Error::in(path, "GIF frames differ in size");
  GifPalette palette(frames);

  AtomicFile out(path, force);
  int err = 0;
  const int fd = ::open(out.temp_path().c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0666);  // umask applies
  if (fd < 0)
    throw Error::in(path, std::string("cannot write: ") + std::strerror(errno), ErrorKind::io);
  GifCloser g{EGifOpenFileHandle(fd, &err)};
  if (!g.gif) ::close(fd);
  if (!g.gif)
    throw Error::in(path, std::string("cannot write GIF: ") + GifErrorString(err), ErrorKind::io);
  auto fail = [&](const char* what) {
    throw Error::in(path, std::string("GIF ") + what + " failed: " + GifErrorString(g.gif->Error));
  };
  EGifSetGifVersion(g.gif, true);
  ColorMapObject* cmap = GifMakeMapObject(256, palette.colours());
  int rc = EGifPutScreenDesc(g.gif, w, h, 8, 0, cmap);
  GifFreeMapObject(cmap);
  if (rc == GIF_ERROR) fail("screen descriptor");
  // Loop forever (NETSCAPE2.0 application extension).
  const unsigned char loop[3] = {1, 0, 0};
  if (EGifPutExtensionLeader(g.gif, APPLICATION_EXT_FUNC_CODE) == GIF_ERROR ||
      EGifPutExtensionBlock(g.gif, 11, "NETSCAPE2.0") == GIF_ERROR ||
      EGifPutExtensionBlock(g.gif, 3, loop) == GIF_ERROR || EGifPutExtensionTrailer(g.gif) == GIF_ERROR)
    fail("loop extension");

  std::vector<GifPixelType> line(w);
  for (size_t f = 0; f < frames.size(); ++f) {
    const Image& img = frames[f];
    // Only the rectangle that changed since the previous frame is stored.
    const auto [x0, y0, x1, y1] = f > 0 ? changed_rect(img, frames[f - 1]) : std::array<int, 4>{0, 0, w - 1, h - 1};
    GraphicsControlBlock gcb{};
    gcb.DisposalMode = DISPOSE_DO_NOT;
    gcb.UserInputFlag = false;
    gcb.DelayTime = std::max(delays_cs[f], 2);
    gcb.TransparentColor = NO_TRANSPARENT_COLOR;
    GifByteType ext[4];
    EGifGCBToExtension(&gcb, ext);
    if (EGifPutExtension(g.gif, GRAPHICS_EXT_FUNC_CODE, 4, ext) == GIF_ERROR) fail("frame delay");
    const int rw = x1 - x0 + 1, rh = y1 - y0 + 1;
    if (EGifPutImageDesc(g.gif, x0, y0, rw, rh, false, nullptr) == GIF_ERROR) fail("image descriptor");
    for (int y = y0; y <= y1; ++y) {
      for (int x = x0; x <= x1; ++x) line[x - x0] = GifPixelType(palette.lookup(&img.rgb[(size_t(y) * w + x) * 3]));
      if (EGifPutLine(g.gif, line.data(), rw) == GIF_ERROR) fail("write");
    }
  }
  GifFileType* gif = g.gif;
  g.gif = nullptr;
  if (EGifCloseFile(gif, &err) == GIF_ERROR) throw Error::in(path, std::string("GIF close failed: ") + GifErrorString(err));
  out.commit();
}

}  // namespace ptnet
