// Figures: files decode back with libpng / giflib to the expected sizes and
// frame counts; colour map endpoints; colour bar monotone; real-time GIF delays.
#include <gif_lib.h>
#include <gtest/gtest.h>
#include <png.h>

#include <cmath>

#include "data_test_util.hpp"
#include "ptnet/error.hpp"
#include "ptnet/viz.hpp"
#include "support/synthetic_walk.hpp"
#include "viz/viz_internal.hpp"

namespace ptnet {
namespace {
using testing_util::TempDir;

double luminance(Rgb c) { return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b; }

TEST(Viz, ViridisEndpointsAndMonotoneLuminance) {
  EXPECT_EQ(viridis(0.0), (Rgb{0x44, 0x01, 0x54}));  // matplotlib viridis(0)
  EXPECT_EQ(viridis(1.0), (Rgb{0xfd, 0xe7, 0x25}));  // matplotlib viridis(1)
  EXPECT_EQ(viridis(-3.0), viridis(0.0));
  EXPECT_EQ(viridis(7.0), viridis(1.0));
  EXPECT_EQ(viridis(NAN), viridis(0.0));
  // Perceived lightness rises along the map (8-bit rounding: compare every 8th entry).
  for (int i = 8; i < 256; i += 8) EXPECT_GT(luminance(viridis(i / 255.0)), luminance(viridis((i - 8) / 255.0))) << i;
  EXPECT_NE(kZeroPressureColour, viridis(0.0));
}

TEST(Viz, ColourBarRunsFromZeroAtTheBottomToVmaxAtTheTop) {
  Image bar = render_colour_bar(200, 300, 2);
  // Column 5 crosses the bar; find its coloured rows.
  std::vector<Rgb> bar_rows;
  for (int y = 0; y < bar.height; ++y) {
    Rgb c = bar.get(5, y);
    bool coloured = !(c.r == c.g && c.g == c.b);  // page, text and outline are grey
    if (coloured) bar_rows.push_back(c);
  }
  ASSERT_EQ(bar_rows.size(), 300u);
  // Row y shows viridis(1 - y / 299): the map's index falls monotonically downwards.
  for (size_t y = 0; y < bar_rows.size(); ++y) EXPECT_EQ(bar_rows[y], viridis(1.0 - y / 299.0)) << y;
  EXPECT_GT(luminance(bar_rows.front()), luminance(bar_rows.back()) + 100);
}

TEST(Viz, FigureFramesAndVmax) {
  FigureOptions o;
  EXPECT_EQ(figure_frames(o, 101, 6), (std::vector<int>{0, 20, 40, 60, 80, 100}));
  o.frame_list = {3, 9};
  EXPECT_EQ(figure_frames(o, 10, 6), (std::vector<int>{3, 9}));
  o.frame_list = {10};
  try {
    figure_frames(o, 10, 6);
    FAIL();
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "frame 10 outside the sequence (10 frames: 0-9)");
  }
  o.frame_list = {3, 9, 3};  // before: frame 3 drawn twice
  try {
    figure_frames(o, 10, 6);
    FAIL();
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "frame_list: frame 3 given twice");
  }
  PressureSequence s(MatSpec{}, 2, 30);
  s.at(1, 3, 3) = 287;
  EXPECT_EQ(figure_vmax({FigurePanel{"a", "", &s}}, FigureOptions{}), 300);
}

TEST(Viz, CentreOfPressureSitsOnTheLoadedCells) {
  PressureSequence s(MatSpec{}, 2, 30);
  s.at(0, 10, 4) = 100;
  s.at(0, 10, 6) = 100;
  auto cop = centre_of_pressure(s);
  EXPECT_DOUBLE_EQ(cop[0].first, 10.5);
  EXPECT_DOUBLE_EQ(cop[0].second, 5.5);
  EXPECT_TRUE(std::isnan(cop[1].first));
}

TEST(Viz, PngStripDecodesToTheDrawnSize) {
  TempDir dir("viz_png");
  auto a = synthetic_walk(MatSpec{}, 60, 30, 160, 55, 1), b = synthetic_walk(MatSpec{}, 60, 30, 185, 90, 2);
  FigureOptions o;
  o.cop = true;
  Image img = render_strip({{"a", "female", &a}, {"b", "male", &b}}, o);
  EXPECT_GT(img.width, 6 * 28 * 7);
  EXPECT_GT(img.height, 2 * 80 * 7);
  write_png(dir.file("f.png"), img, false);
  png_image png{};
  png.version = PNG_IMAGE_VERSION;
  ASSERT_TRUE(png_image_begin_read_from_file(&png, dir.file("f.png").c_str())) << png.message;
  png.format = PNG_FORMAT_RGB;
  std::vector<png_byte> pixels(PNG_IMAGE_SIZE(png));
  ASSERT_TRUE(png_image_finish_read(&png, nullptr, pixels.data(), 0, nullptr)) << png.message;
  EXPECT_EQ(int(png.width), img.width);
  EXPECT_EQ(int(png.height), img.height);
  EXPECT_TRUE(pixels == img.rgb);
  EXPECT_THROW(write_png(dir.file("f.png"), img, false), Error);  // no overwrite without force
}

TEST(Viz, GifHasOneFramePerSequenceFrameAtTheRealRate) {
  TempDir dir("viz_gif");
  auto a = synthetic_walk(MatSpec{}, 45, 30, 160, 55, 1);
  std::vector<int> delays;
  auto frames = render_animation({{"a", "female", &a}}, FigureOptions{}, &delays);
  ASSERT_EQ(frames.size(), 45u);
  int total = 0;
  for (int d : delays) total += d;
  EXPECT_EQ(total, 150);  // 45 frames at 30 fps = 1.50 s
  write_gif(dir.file("a.gif"), frames, delays, false);
  int err = 0;
  GifFileType* gif = DGifOpenFileName(dir.file("a.gif").c_str(), &err);
  ASSERT_NE(gif, nullptr);
  ASSERT_EQ(DGifSlurp(gif), GIF_OK);
  EXPECT_EQ(gif->ImageCount, 45);
  EXPECT_EQ(gif->SWidth, frames[0].width);
  EXPECT_EQ(gif->SHeight, frames[0].height);
  int gif_total = 0;
  for (int i = 0; i < gif->ImageCount; ++i) {
    GraphicsControlBlock gcb;
    ASSERT_EQ(DGifSavedExtensionToGCB(gif, i, &gcb), GIF_OK);
    gif_total += gcb.DelayTime;
  }
  EXPECT_EQ(gif_total, 150);
  DGifCloseFile(gif, &err);
}

}  // namespace
}  // namespace ptnet
