// model/model_internal.hpp (private to the model stage; tests include it as
// "model/model_internal.hpp"): the input frames of Arch::frame, shared by
// the network, its inference copy and whole-sequence transfer. Includes
// Torch.
#pragma once

#include "ptnet/model.hpp"

namespace ptnet {

// Arch::frame's input frames: x [N, T + 2 context, H, W] -> [N*T, 1 + 2
// context, H, W], each of the T centre frames with `context` neighbours on
// each side (the network's first layer reads them as channels).
torch::Tensor frame_inputs(const torch::Tensor& x, int context);
// A whole sequence [T, H, W] with `margin` copies of its first frame before
// and of its last after: [T + 2 margin, H, W], the input that gives every
// frame of the sequence its context.
torch::Tensor with_margin(const torch::Tensor& frames, int margin);

}  // namespace ptnet
