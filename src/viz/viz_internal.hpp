// viz/viz_internal.hpp (private to the viz stage; tests include it as
// "viz/viz_internal.hpp"): the pieces figures and charts are drawn with
// (colour map, bitmap font, frame choice, colour scale, centre of pressure,
// colour bar, axis ticks, series colours) beside ptnet/viz.hpp.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "ptnet/pressure.hpp"
#include "ptnet/viz.hpp"

namespace ptnet {

// Viridis colour map: t in [0, 1] (clamped) -> one of its 256 entries.
Rgb viridis(double t);
// The same map quantised to `levels` (2-256) evenly spaced entries.
Rgb viridis(double t, int levels);

// Built-in 5 x 7 bitmap font (ASCII 32-126). Each glyph takes 6 x 8 pixels
// times `scale`; other characters are drawn as '?'.
void draw_text(Image& image, int x, int y, const std::string& text, Rgb colour, int scale = 1);
int text_width(const std::string& text, int scale = 1);
inline int text_height(int scale = 1) { return 8 * scale; }

// ----------------------------------------------------------------- figures

// The frames a figure shows: frame_list, else `count` evenly spaced over
// [0, frames) including the first and last. Throws Error for indices out of range.
std::vector<int> figure_frames(const FigureOptions& options, int frames, int default_count);

// The colour-scale top the figure uses: options.vmax_kpa, or the data max
// rounded up to a tick step (1, 2, 2.5 or 5 x 10^k).
double figure_vmax(const std::vector<FigurePanel>& panels, const FigureOptions& options);

// Per-frame centre of pressure in cell coordinates (row, col of cell centres
// = index + 0.5); NaN for frames with no load. [T] pairs.
std::vector<std::pair<double, double>> centre_of_pressure(const PressureSequence& sequence);

// A vertical colour bar [0, vmax] kPa with tick labels and a "kPa" caption.
Image render_colour_bar(double vmax_kpa, int bar_height_px, int text_scale);

// ------------------------------------------------------------------ charts

// The tick step of an axis: 1, 2, 2.5 or 5 x 10^k, the smallest >= raw.
double nice_step(double raw);

// The colour of series i in every chart (a qualitative palette, cycling), as "#rrggbb".
std::string chart_colour(int i);

}  // namespace ptnet
