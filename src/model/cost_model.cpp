// The cost model of a ModelConfig in closed form: trainable parameters,
// memory in training or inference, forward FLOPs (ptnet/model_config.hpp).
// No Torch here; tests check parameter_count against the module's count.
//
// Dimension legend: T window frames, H x W mat cells (pooled_size per
// level), c1, c2, c3 the encoder widths, A = 3 attributes.
#include <algorithm>
#include <cstdint>

#include "model/model_config_internal.hpp"
#include "ptnet/model_config.hpp"

namespace ptnet {

namespace {
// Arch::frame (model.hpp): six conv blocks (3x3, no bias; BatchNorm without
// affine; FiLM gamma and beta per channel), laterals 1x1, head 3x3 -> 1, FiLM
// MLP 2A -> hidden -> 2 x (sum of block widths). Per frame: parameters, and
// multiply-adds with p0, p1, p2 cells at full, half and quarter resolution.
struct FrameCounts {
  std::int64_t parameters = 0;
  double macs_per_frame = 0;
};
FrameCounts frame_counts(const ModelConfig& c) {
  using I = std::int64_t;
  const I k = 1 + 2 * I(c.context), c1 = c.channels[0], c2 = c.channels[1], c3 = c.channels[2];
  auto s0 = pooled_size(c, 0), s1 = pooled_size(c, 1), s2 = pooled_size(c, 2);
  const double p0 = double(s0[0]) * s0[1], p1 = double(s1[0]) * s1[1], p2 = double(s2[0]) * s2[1];
  const I blocks[6][2] = {{k, c1}, {c1, c2}, {c2, c3}, {c3, c3}, {c2, c2}, {c1, c1}};
  const double at[6] = {p0, p1, p2, p2, p1, p0};
  FrameCounts f;
  I film = 0;
  for (int i = 0; i < 6; ++i) {
    f.parameters += blocks[i][0] * blocks[i][1] * 9;
    f.macs_per_frame += at[i] * 9.0 * double(blocks[i][0] * blocks[i][1]);
    film += 2 * blocks[i][1];
  }
  const I outputs = c.contact ? 2 : 1;                                      // pressure (+ contact logit)
  f.parameters += c3 * c2 + c2 + c2 * c1 + c1 + outputs * (c1 * 9 + 1);     // laterals, head
  f.macs_per_frame += p1 * double(c3 * c2) + p0 * double(c2 * c1) + p0 * 9.0 * double(c1 * outputs);
  const I conditions = 2 * kAttributes;
  f.parameters += conditions * I(c.hidden) + c.hidden + I(c.hidden) * film + film;  // FiLM MLP
  f.macs_per_frame += double(conditions) * c.hidden + double(c.hidden) * double(film);
  return f;
}
}  // namespace

std::int64_t parameter_count(const ModelConfig& c) {
  using I = std::int64_t;
  if (c.arch == Arch::frame) return frame_counts(c).parameters;
  const I t = c.window, c1 = c.channels[0], c2 = c.channels[1], c3 = c.channels[2];
  const I k = 9, skip = has_skips(c.arch) ? 2 : 1, a = kAttributes;
  auto s3 = pooled_size(c, 3);
  const I flat = c3 * s3[0] * s3[1];
  I n = 0;
  n += t * c1 * k + c1 + 2 * c1;                  // conv1 + bn1
  n += c1 * c2 * k + c2 + 2 * c2;                 // conv2 + bn2
  n += c2 * c3 * k + c3 + 2 * c3;                 // conv3 + bn3
  n += flat * c.hidden + c.hidden;                // fc_features
  n += (I(c.hidden) + a) * c.latent + c.latent;   // fc_latent
  n += (I(c.latent) + a) * flat + flat;           // fc_decode
  n += skip * c3 * c2 * k + c2 + 2 * c2;          // deconv3 + dbn3
  n += skip * c2 * c1 * k + c1 + 2 * c1;          // deconv2 + dbn2
  n += skip * c1 * t * k + t;                     // deconv1
  return n;
}

std::uint64_t model_memory_bytes(const ModelConfig& c, int batch, bool training) {
  // Every factor is bounded by validate(): the products fit in 64 bits.
  const double params = double(parameter_count(c)) * 4 * (training ? 4 : 1);
  auto s0 = pooled_size(c, 0), s1 = pooled_size(c, 1), s2 = pooled_size(c, 2);
  const double per_window = 4.0 * (3.0 * c.window * s0[0] * s0[1] + 4.0 * c.channels[0] * s0[0] * s0[1] +
                                   4.0 * c.channels[1] * s1[0] * s1[1] + 4.0 * c.channels[2] * s2[0] * s2[1]);
  const double total = params + per_window * std::max(1, batch) * (training ? 2 : 1);
  return total > 1.8e19 ? std::uint64_t(1.8e19) : std::uint64_t(total);
}

double forward_flops(const ModelConfig& c) {
  if (c.arch == Arch::frame) return 2 * frame_counts(c).macs_per_frame * c.window;
  const double t = c.window, c1 = c.channels[0], c2 = c.channels[1], c3 = c.channels[2];
  const double k = 9, skip = has_skips(c.arch) ? 2 : 1, a = kAttributes;
  auto s0 = pooled_size(c, 0), s1 = pooled_size(c, 1), s2 = pooled_size(c, 2), s3 = pooled_size(c, 3);
  const double p0 = double(s0[0]) * s0[1], p1 = double(s1[0]) * s1[1], p2 = double(s2[0]) * s2[1];
  const double flat = c3 * s3[0] * s3[1];
  double macs = t * c1 * k * p0 + c1 * c2 * k * p1 + c2 * c3 * k * p2;                  // encoder
  macs += flat * c.hidden + (c.hidden + a) * c.latent + (c.latent + a) * flat;           // FCs
  macs += skip * (c3 * c2 * k * p2 + c2 * c1 * k * p1 + c1 * t * k * p0);               // decoder
  return 2 * macs;
}

}  // namespace ptnet
