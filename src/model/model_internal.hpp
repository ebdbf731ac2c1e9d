// model/model_internal.hpp (private to the model stage; tests include it as
// "model/model_internal.hpp"): the input frames of Arch::frame, shared by
// the network, its inference copy and whole-sequence transfer, and the
// InferenceNet's chunking and weight layout. Includes Torch.
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

// InferenceNet::forward cuts a batch of `n` windows into equal chunks, each
// run through the whole network, whose widest activation (float32, at full
// resolution) stays below `budget_bytes`: the windows of one chunk (n when
// one chunk holds them all). The budget keeps every tensor of a chunk below
// the 32 MB from which glibc gives a block its own mmap (the largest
// threshold it uses, and keep_freed_memory's, ptnet/memory.hpp): above it
// each tensor is faulted in page by page on every call. Measured, one
// thread: the paper's network 0.2-0.3x as fast in one chunk of 64 (36.7 MB
// tensors) as in two of 32; at or below the budget the chunk size made
// little difference (docs/model.md "Speed").
constexpr int64_t kInferenceChunkBytes = int64_t(20) << 20;
int64_t chunk_windows(const ModelConfig& config, int64_t n, int64_t budget_bytes);

// `t` [N, C, H, W] copied into `format` with that format's strides even
// where they are ambiguous (one channel): see inference.cpp.
torch::Tensor in_format(const torch::Tensor& t, at::MemoryFormat format);

}  // namespace ptnet
