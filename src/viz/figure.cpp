// Figures: heatmap strips (PNG) and animations (GIF) of pressure sequences.
//
// Dimension legend: T frames, R x C = mat rows x cols (80 x 28), s = cell_px.
// A mat panel is C*s wide and R*s tall: row 0 (far end) at the top, col 0
// (walker's left) on the left.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "ptnet/error.hpp"
#include "ptnet/io.hpp"
#include "ptnet/strings.hpp"
#include "ptnet/viz.hpp"
#include "viz/viz_internal.hpp"

namespace ptnet {

// 1, 2, 2.5 or 5 x 10^k, the smallest such step >= raw.
double nice_step(double raw) {
  if (!(raw > 0)) return 1;
  double p = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 2.5, 5.0, 10.0})
    if (m * p >= raw * (1 - 1e-9)) return m * p;
  return 10 * p;
}

namespace {
constexpr int kMargin = 24;        // page margin (px)
constexpr int kText = 2;           // text scale: 12 x 16 px glyph cells
constexpr int kColumnGap = 14;     // between mat panels (px)
constexpr int kRowGap = 28;        // between sequences in a strip (px)
constexpr int kBarWidth = 18;      // colour bar (px)
constexpr int kGifLevels = 240;    // colour levels in GIFs (palette <= 256 with text colours)
constexpr Rgb kInk{25, 25, 25};           // titles
constexpr Rgb kSubInk{90, 90, 90};        // subtitles, labels, captions
constexpr Rgb kFrameInk{130, 130, 130};   // mat outline, ticks
constexpr Rgb kCop{228, 26, 28};          // centre-of-pressure trace (red; far from viridis)
constexpr Rgb kWhite{255, 255, 255};

std::string format(const char* f, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

std::string tick_label(double v, double step) {
  if (step >= 1) return format("%.0f", v);
  if (step * 10 >= 1) return format("%.1f", v);
  return format("%.2f", v);
}

void draw_disc(Image& img, double cx, double cy, double r, Rgb c) {
  for (int y = int(std::floor(cy - r)); y <= int(std::ceil(cy + r)); ++y)
    for (int x = int(std::floor(cx - r)); x <= int(std::ceil(cx + r)); ++x)
      if ((x + 0.5 - cx) * (x + 0.5 - cx) + (y + 0.5 - cy) * (y + 0.5 - cy) <= r * r) img.set(x, y, c);
}

void draw_line(Image& img, double x0, double y0, double x1, double y1, double width, Rgb c) {
  const double len = std::hypot(x1 - x0, y1 - y0);
  const int steps = std::max(1, int(std::ceil(len * 2)));
  for (int i = 0; i <= steps; ++i) {
    double t = double(i) / steps;
    draw_disc(img, x0 + t * (x1 - x0), y0 + t * (y1 - y0), width / 2, c);
  }
}

struct Style {
  int cell_px;
  double vmax;
  int levels;
};

// One mat frame at (x, y), with its outline and optional CoP trace up to t.
void draw_mat(Image& img, int x, int y, const PressureSequence& seq, int t, const Style& st,
              const std::vector<std::pair<double, double>>* cop) {
  const MatSpec& m = seq.mat;
  const int s = st.cell_px;
  img.fill_rect(x - 1, y - 1, m.cols * s + 2, m.rows * s + 2, kFrameInk);
  for (int r = 0; r < m.rows; ++r)
    for (int c = 0; c < m.cols; ++c) {
      const float v = seq.at(t, r, c);
      img.fill_rect(x + c * s, y + r * s, s, s, v > 0 ? viridis(v / st.vmax, st.levels) : kZeroPressureColour);
    }
  if (!cop) return;
  auto px = [&](const std::pair<double, double>& p) {
    return std::pair<double, double>{x + p.second * s, y + p.first * s};
  };
  const double w = std::max(2.0, s * 0.3);
  const double jump_cells = 0.2 / m.pitch_m;  // a jump > 20 cm between frames is not one path
  for (int i = 1; i <= t; ++i) {
    const auto &a = (*cop)[i - 1], &b = (*cop)[i];
    if (std::isnan(a.first) || std::isnan(b.first)) continue;
    if (std::hypot(a.first - b.first, a.second - b.second) > jump_cells) continue;
    auto pa = px(a), pb = px(b);
    draw_line(img, pa.first, pa.second, pb.first, pb.second, w, kCop);
  }
  if (!std::isnan((*cop)[t].first)) {
    auto p = px((*cop)[t]);
    draw_disc(img, p.first, p.second, w * 1.6 + 1.5, kWhite);
    draw_disc(img, p.first, p.second, w * 1.6, kCop);
  }
}

void draw_text_centred(Image& img, int cx, int y, const std::string& text, Rgb c) {
  draw_text(img, cx - text_width(text, kText) / 2, y, text, c, kText);
}

std::string frame_label(int t, double fps) { return "#" + std::to_string(t) + "  " + format("%.2f s", t / fps); }

int min_frames(const std::vector<FigurePanel>& panels) {
  int n = panels.front().sequence->frames();
  for (const auto& p : panels) n = std::min(n, p.sequence->frames());
  return n;
}

void check_panels(const std::vector<FigurePanel>& panels) {
  if (panels.empty()) throw Error("figure: no sequences to draw");
  for (const auto& p : panels) {
    if (!p.sequence || p.sequence->frames() == 0) throw Error("figure: sequence '" + p.title + "' has no frames");
    if (!(p.sequence->mat == panels.front().sequence->mat))
      throw Error("figure: sequences '" + panels.front().title + "' and '" + p.title + "' have different mats");
  }
}

// Caption under the figure: orientation, scale bar, units.
int draw_caption(Image* img, int x, int y, const MatSpec& mat, int cell_px, bool cop) {
  const int h = text_height(kText);
  if (img) {
    const int bar = int(std::lround(0.10 / mat.pitch_m * cell_px));  // 10 cm scale bar
    img->fill_rect(x, y + h / 2 - 2, bar, 4, kInk);
    int cx = x + bar + 8;
    std::string text = "10 cm    top: far end of the mat (row 0)    left: walker's left (col 0)";
    if (cop) text += "    red: centre of pressure";
    draw_text(*img, cx, y, text, kSubInk, kText);
  }
  return h;
}
}  // namespace

std::vector<int> figure_frames(const FigureOptions& opt, int frames, int default_count) {
  std::vector<int> out;
  if (!opt.frame_list.empty()) {
    for (int f : opt.frame_list) {
      if (f < 0 || f >= frames)
        throw Error("frame " + std::to_string(f) + " outside the sequence (" + std::to_string(frames) +
                    " frames: 0-" + std::to_string(frames - 1) + ")");
      if (std::find(out.begin(), out.end(), f) != out.end())
        throw Error(field_text("frame_list") + ": frame " + std::to_string(f) + " given twice");
      out.push_back(f);
    }
    return out;
  }
  if (opt.frames && *opt.frames < 1) throw Error(field_text("frames") + ": expected at least 1, found " + std::to_string(*opt.frames));
  const int n = opt.frames.value_or(default_count);
  if (n <= 0 || n >= frames) {
    for (int t = 0; t < frames; ++t) out.push_back(t);
    return out;
  }
  for (int i = 0; i < n; ++i) out.push_back(n == 1 ? 0 : int(std::lround(double(i) * (frames - 1) / (n - 1))));
  return out;
}

double figure_vmax(const std::vector<FigurePanel>& panels, const FigureOptions& opt) {
  if (opt.vmax_kpa) {
    if (!(*opt.vmax_kpa > 0)) throw Error(field_text("vmax_kpa") + ": expected a positive kPa, found " + number_text(*opt.vmax_kpa));
    return *opt.vmax_kpa;
  }
  float peak = 0;
  for (const auto& p : panels)
    for (float v : p.sequence->kpa) peak = std::max(peak, v);
  if (!(peak > 0)) return 1;
  const double step = nice_step(peak / 5);
  return std::ceil(peak / step - 1e-9) * step;
}

std::vector<std::pair<double, double>> centre_of_pressure(const PressureSequence& seq) {
  std::vector<std::pair<double, double>> out(seq.frames());
  for (int t = 0; t < seq.frames(); ++t) {
    const FrameLoad f = frame_load(seq.frame(t), seq.mat);  // NaN when unloaded
    out[t] = {seq.mat.rows / 2.0 - f.x_m / seq.mat.pitch_m, seq.mat.cols / 2.0 - f.y_m / seq.mat.pitch_m};
  }
  return out;
}

static Image colour_bar(double vmax, int bar_h, int scale, int levels) {
  const double step = nice_step(vmax / 5);
  std::vector<double> ticks;
  for (double v = 0; v <= vmax * (1 + 1e-9); v += step) ticks.push_back(v);
  int label_w = text_width("kPa", scale);
  for (double v : ticks) label_w = std::max(label_w, text_width(tick_label(v, step), scale));
  const int th = text_height(scale);
  const int top = th * 3 / 2 + 8;  // "kPa" above the bar, clear of the top tick label
  Image img(kBarWidth + 6 + label_w + 2, top + bar_h + th / 2 + 2, kPageColour);
  draw_text(img, 0, 0, "kPa", kSubInk, scale);
  for (int y = 0; y < bar_h; ++y) {
    const double v = vmax * (1.0 - double(y) / std::max(1, bar_h - 1));
    img.fill_rect(0, top + y, kBarWidth, 1, viridis(v / vmax, levels));
  }
  // Outline.
  img.fill_rect(0, top - 1, kBarWidth, 1, kFrameInk);
  img.fill_rect(0, top + bar_h, kBarWidth, 1, kFrameInk);
  for (double v : ticks) {
    const int y = top + int(std::lround((1.0 - v / vmax) * (bar_h - 1)));
    img.fill_rect(kBarWidth, y, 4, 1, kFrameInk);
    const std::string label = tick_label(v, step);
    draw_text(img, kBarWidth + 6, std::clamp(y - th / 2 + scale, 0, img.height - th), label, kSubInk, scale);
  }
  return img;
}

Image render_colour_bar(double vmax_kpa, int bar_height_px, int text_scale) {
  return colour_bar(vmax_kpa, bar_height_px, text_scale, 256);
}

namespace {
Image render_strip_impl(const std::vector<FigurePanel>& panels, const FigureOptions& opt) {
  check_panels(panels);
  const MatSpec& mat = panels.front().sequence->mat;
  const int s = std::max(1, opt.cell_px);
  const Style st{s, figure_vmax(panels, opt), 256};
  const std::vector<int> frames = figure_frames(opt, min_frames(panels), 6);
  const int mat_w = mat.cols * s, mat_h = mat.rows * s;
  const int th = text_height(kText);
  int col_w = mat_w;
  for (int t : frames) col_w = std::max(col_w, text_width(frame_label(t, panels[0].sequence->fps), kText));
  const int mats_w = int(frames.size()) * col_w + (int(frames.size()) - 1) * kColumnGap;
  int title_w = 0;
  for (const auto& p : panels) title_w = std::max(title_w, text_width(p.title + "   " + p.subtitle, kText));
  const int row_h = th + 8 + th + 6 + mat_h + 2;
  const Image bar = colour_bar(st.vmax, mat_h, kText, 256);
  const int caption_w = text_width(std::string(80, 'x'), kText) + 60;
  const int width = kMargin * 2 + std::max({mats_w + 24 + bar.width, title_w, caption_w});
  const int height = kMargin * 2 + int(panels.size()) * row_h + (int(panels.size()) - 1) * kRowGap + 18 + th;
  Image img(width, height, kPageColour);

  int y = kMargin;
  for (size_t i = 0; i < panels.size(); ++i) {
    const FigurePanel& p = panels[i];
    draw_text(img, kMargin, y, p.title, kInk, kText);
    draw_text(img, kMargin + text_width(p.title + "   ", kText), y, p.subtitle, kSubInk, kText);
    const int label_y = y + th + 8;
    const int mat_y = label_y + th + 6;
    const auto cop = opt.cop ? centre_of_pressure(*p.sequence) : std::vector<std::pair<double, double>>{};
    for (size_t j = 0; j < frames.size(); ++j) {
      const int cx = kMargin + int(j) * (col_w + kColumnGap);
      draw_text_centred(img, cx + col_w / 2, label_y, frame_label(frames[j], p.sequence->fps), kSubInk);
      draw_mat(img, cx + (col_w - mat_w) / 2, mat_y, *p.sequence, frames[j], st, opt.cop ? &cop : nullptr);
    }
    if (i == 0) img.blit(bar, kMargin + mats_w + 24, mat_y - (th * 3 / 2 + 8));
    y += row_h + kRowGap;
  }
  draw_caption(&img, kMargin, height - kMargin - th, mat, s, opt.cop);
  return img;
}
}  // namespace

Image render_strip(const std::vector<FigurePanel>& panels, const FigureOptions& options) {
  return render_strip_impl(panels, options);
}

std::vector<Image> render_animation(const std::vector<FigurePanel>& panels, const FigureOptions& opt,
                                    std::vector<int>* delays_cs) {
  check_panels(panels);
  const MatSpec& mat = panels.front().sequence->mat;
  const double fps = panels.front().sequence->fps;
  const int s = std::max(1, opt.cell_px);
  const Style st{s, figure_vmax(panels, opt), kGifLevels};
  std::vector<int> frames = figure_frames(opt, min_frames(panels), 0);
  // GIF viewers clamp delays under 2/100 s: above 50 fps, keep every k-th frame.
  if (opt.frame_list.empty() && !opt.frames && fps > 50) {
    const int k = int(std::ceil(fps / 50));
    std::vector<int> kept;
    for (size_t i = 0; i < frames.size(); i += k) kept.push_back(frames[i]);
    frames = kept;
  }
  const int mat_w = mat.cols * s, mat_h = mat.rows * s;
  const int th = text_height(kText);
  int col_w = mat_w;
  for (const auto& p : panels)
    col_w = std::max({col_w, text_width(p.title, kText), text_width(p.subtitle, kText)});
  const int n = int(panels.size());
  const Image bar = colour_bar(st.vmax, mat_h, kText, kGifLevels);
  const int mats_w = n * col_w + (n - 1) * kColumnGap * 2;
  const int header = th + 12 + 2 * th + 6 + 16;  // frame label, title, subtitle
  const int width = kMargin * 2 + mats_w + 24 + bar.width;
  const int height = kMargin * 2 + header + mat_h + 2;
  std::vector<std::vector<std::pair<double, double>>> cops;
  for (const auto& p : panels) cops.push_back(opt.cop ? centre_of_pressure(*p.sequence) : std::vector<std::pair<double, double>>{});

  Image base(width, height, kPageColour);
  const int mat_y = kMargin + header;
  for (int i = 0; i < n; ++i) {
    const int cx = kMargin + i * (col_w + 2 * kColumnGap) + col_w / 2;
    draw_text_centred(base, cx, kMargin + th + 12, panels[i].title, kInk);
    draw_text_centred(base, cx, kMargin + 2 * th + 16, panels[i].subtitle, kSubInk);
  }
  base.blit(bar, kMargin + mats_w + 24, mat_y - (th * 3 / 2 + 8));

  std::vector<Image> images;
  images.reserve(frames.size());
  if (delays_cs) delays_cs->clear();
  for (size_t f = 0; f < frames.size(); ++f) {
    Image img = base;
    draw_text(img, kMargin, kMargin, frame_label(frames[f], fps), kInk, kText);
    for (int i = 0; i < n; ++i) {
      const int x = kMargin + i * (col_w + 2 * kColumnGap) + (col_w - mat_w) / 2;
      draw_mat(img, x, mat_y, *panels[i].sequence, frames[f], st, opt.cop ? &cops[i] : nullptr);
    }
    images.push_back(std::move(img));
    if (delays_cs) {
      // Real time: delay until the next shown frame, rounded so the sum stays exact.
      const int next = f + 1 < frames.size() ? frames[f + 1] : frames[f] + 1;
      const long a = std::lround(frames[f] * 100.0 / fps), b = std::lround(next * 100.0 / fps);
      delays_cs->push_back(int(std::max(2L, b - a)));
    }
  }
  return images;
}

void render_figure(const Dataset& d, const std::vector<std::string>& names, const std::string& out,
                   const FigureOptions& opt, bool force) {
  if (names.empty())
    throw Error("render: " + field_text("sequences") +
                ": expected at least one sequence name, found none");
  if (const std::string twice = first_repeat(names); !twice.empty())
    throw Error("render: " + field_text("sequences") + ": " + escaped(twice) + " given twice");
  check_output_name(out, {".png", ".gif"}, "a PNG strip or a GIF animation");
  const std::string ext = lower(std::filesystem::path(out).extension().string());
  check_output_path(out, force);
  std::vector<PressureSequence> seqs;
  std::vector<FigurePanel> panels;
  seqs.reserve(names.size());
  for (const auto& name : names) {
    const SequenceMeta& m = d.sequence(name);
    const BodySpec& b = d.body(m.body_id);
    seqs.push_back(d.read(name));
    char sub[128];
    std::snprintf(sub, sizeof sub, "%s, %.0f cm, %.0f kg", b.sex == Sex::male ? "male" : "female",
                  b.height_cm, b.weight_kg);
    panels.push_back(FigurePanel{name, sub, &seqs.back()});
  }
  try {
    if (ext == ".png") {
      write_png(out, render_strip(panels, opt), force);
    } else {
      std::vector<int> delays;
      auto images = render_animation(panels, opt, &delays);
      write_gif(out, images, delays, force);
    }
  } catch (const Error& e) {
    const std::string what = e.what();
    if (what.rfind("frame ", 0) == 0) throw Error::in(d.path(), what);
    throw;
  }
}

}  // namespace ptnet
