// ptnet/viz.hpp: figures of pressure sequences (PNG strips, animated GIFs).
//
//   ptnet::Dataset d = ptnet::Dataset::open("data.h5");
//   ptnet::FigureOptions opt;
//   opt.cop = true;                                    // centre-of-pressure trace
//   ptnet::render_figure(d, {"walk__b1", "walk__b2"}, "fig.png", opt, /*force=*/false);
//
// A figure draws each sequence as one row of heatmaps (PNG: a strip of frames;
// GIF: the sequences side by side, animated at the sequence's frame rate).
// The mat is drawn with its long axis vertical, row 0 (the far end, +x) at the
// top and col 0 (the walker's left, +y) on the left, each cell an upscaled
// square (nearest neighbour). Colours: viridis (perceptual, from matplotlib's
// published table), zero pressure a light grey background, one kPa scale
// shared by all panels, shown by a colour bar with ticks.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "ptnet/data.hpp"
#include "ptnet/pressure.hpp"

namespace ptnet {

struct Rgb {
  std::uint8_t r = 0, g = 0, b = 0;
  bool operator==(const Rgb& o) const { return r == o.r && g == o.g && b == o.b; }
  bool operator!=(const Rgb& o) const { return !(*this == o); }
};

inline constexpr Rgb kZeroPressureColour{236, 236, 236};  // cells with no load
inline constexpr Rgb kPageColour{255, 255, 255};

// An RGB image, 8 bits per channel, row-major [height, width, 3].
struct Image {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;

  Image() = default;
  Image(int w, int h, Rgb fill = kPageColour);
  Rgb get(int x, int y) const;
  void set(int x, int y, Rgb c);  // ignores pixels outside the image
  void fill_rect(int x, int y, int w, int h, Rgb c);
  void blit(const Image& src, int x, int y);
};

// Writers (atomic, see io.hpp; refuse to overwrite without force).
void write_png(const std::string& path, const Image& image, bool force);
// Frames of one size; delays in hundredths of a second, one per frame. Loops forever.
void write_gif(const std::string& path, const std::vector<Image>& frames,
               const std::vector<int>& delays_cs, bool force);

struct FigureOptions {
  int cell_px = 7;                 // pixels per mat cell
  std::optional<double> vmax_kpa;  // top of the colour scale (> 0); none: max of the data, rounded up
  bool cop = false;                // draw the centre-of-pressure trace up to each frame
  std::optional<int> frames;       // N evenly spaced frames (>= 1); none: PNG 6, GIF every frame
  std::vector<int> frame_list;     // explicit frame indices (overrides `frames`)
};

struct FigurePanel {
  std::string title;             // e.g. the sequence name
  std::string subtitle;          // e.g. "female, 158 cm, 52 kg"
  const PressureSequence* sequence = nullptr;
};

// One row per panel, one column per frame, colour bar on the right.
Image render_strip(const std::vector<FigurePanel>& panels, const FigureOptions& options);
// Panels side by side; one image per shown frame, with delays (1/100 s) that
// follow the sequence's real frame rate.
std::vector<Image> render_animation(const std::vector<FigurePanel>& panels,
                                    const FigureOptions& options, std::vector<int>* delays_cs);

// Reads the named sequences and writes `out_path` (.png strip or .gif animation).
void render_figure(const Dataset& dataset, const std::vector<std::string>& sequences,
                   const std::string& out_path, const FigureOptions& options, bool force);

// ------------------------------------------------------- SVG charts, HTML
//
// Charts are standalone SVG documents (width and height set, so an <img>
// shows them; text escaped). Report pages are offline HTML: no script or
// style from the network, images beside the page.

struct BarSeries {
  std::string name;            // legend entry
  std::vector<double> values;  // one per group; NaN = no bar
  std::vector<double> errors;  // +- whisker per group (empty: none)
};
struct BarChart {
  std::string title, y_label;
  std::vector<std::string> groups;  // along x
  std::vector<BarSeries> series;    // bars side by side within a group, one colour each
  int width = 640, height = 300;    // px
};
std::string svg_bar_chart(const BarChart& chart);

struct LineSeries {
  std::string name;
  std::vector<double> x, y;  // same length; NaN y = gap
};
struct LineChart {
  std::string title, x_label, y_label;
  std::vector<LineSeries> series;
  int width = 640, height = 300;
  bool points = true;  // a dot (with its value as a tooltip) at every point; false for dense series
};
std::string svg_line_chart(const LineChart& chart);

// &, <, >, " and ' as entities: safe in HTML and SVG text and attributes.
std::string html_escape(const std::string& text);

// A complete page: inline style, `body_html` as given, and an inline check
// script: on load, document.body.dataset.ok becomes "yes" when every <img>
// loaded (naturalWidth > 0) and no script or resource error occurred, else
// "no", with the failures listed in data-failures (the browser test reads them).
std::string html_page(const std::string& title, const std::string& body_html);

}  // namespace ptnet
