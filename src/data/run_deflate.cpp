// RunDeflater: tokens (literal bytes and zero runs), then one dynamic
// Huffman block (RFC 1951, 3.2.7) in a zlib wrapper (RFC 1950).
#include "data/run_deflate.hpp"

#include <libdeflate.h>

#include <algorithm>
#include <array>
#include <cstring>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace ptnet::h5 {
namespace {

static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "zero_run() counts bytes of little-endian words");

constexpr int kLitLen = 286;  // literal/length alphabet
constexpr int kEob = 256;     // end of block
constexpr int kMaxMatch = 258, kMinMatch = 3;

// Length 3-258 -> its symbol (257-285), extra bit count and extra value.
struct LenCode {
  std::uint16_t symbol;
  std::uint8_t bits;
  std::uint16_t extra;
};
const std::array<LenCode, kMaxMatch + 1>& len_codes() {
  static const std::array<LenCode, kMaxMatch + 1> table = [] {
    constexpr int base[29] = {3,  4,  5,  6,  7,  8,  9,  10, 11,  13,  15,  17,  19,  23, 27,
                              31, 35, 43, 51, 59, 67, 83, 99, 115, 131, 163, 195, 227, 258};
    constexpr int bits[29] = {0, 0, 0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2, 2, 3, 3, 3, 3, 4, 4, 4, 4, 5, 5, 5, 5, 0};
    std::array<LenCode, kMaxMatch + 1> t{};
    for (int s = 0; s < 29; ++s) {
      const int last = s == 28 ? 258 : s == 27 ? 257 : base[s + 1] - 1;  // 258 is symbol 285's alone
      for (int len = base[s]; len <= last; ++len)
        t[std::size_t(len)] = {std::uint16_t(257 + s), std::uint8_t(bits[s]), std::uint16_t(len - base[s])};
    }
    return t;
  }();
  return table;
}

// Zero bytes at p[0, m), counted 64 then 16 (SSE2) or 8 at a time.
inline std::size_t zero_run(const unsigned char* p, std::size_t m) {
  std::size_t k = 0;
#if defined(__SSE2__)
  const auto at = [&](std::size_t o) { return _mm_loadu_si128(reinterpret_cast<const __m128i*>(p + o)); };
  for (; k + 64 <= m; k += 64) {  // whole 64-byte blocks of zeros (the long runs between pressed cells)
    const __m128i v = _mm_or_si128(_mm_or_si128(at(k), at(k + 16)), _mm_or_si128(at(k + 32), at(k + 48)));
    if (_mm_movemask_epi8(_mm_cmpeq_epi8(v, _mm_setzero_si128())) != 0xffff) break;
  }
  for (; k + 16 <= m; k += 16) {
    const __m128i v = _mm_loadu_si128(reinterpret_cast<const __m128i*>(p + k));
    const unsigned nonzero = ~unsigned(_mm_movemask_epi8(_mm_cmpeq_epi8(v, _mm_setzero_si128()))) & 0xffffu;
    if (nonzero) return k + std::size_t(__builtin_ctz(nonzero));
  }
#endif
  for (; k + 8 <= m; k += 8) {
    std::uint64_t w;
    std::memcpy(&w, p + k, 8);
    if (w) return k + std::size_t(__builtin_ctzll(w) >> 3);
  }
  while (k < m && p[k] == 0) ++k;
  return k;
}

// Huffman code lengths of at most `limit` bits for freq[0, n): a complete
// code (two symbols at least: a lone symbol gets a partner of length 1).
void huffman_lengths(const std::uint32_t* freq, int n, int limit, std::uint8_t* len) {
  std::fill(len, len + n, 0);
  struct Node {
    std::uint64_t weight;
    int parent;
  };
  std::vector<int> syms;  // used symbols, by ascending frequency (ties: by symbol)
  for (int s = 0; s < n; ++s)
    if (freq[s]) syms.push_back(s);
  if (syms.size() < 2) {
    const int s = syms.empty() ? 0 : syms[0];
    len[s] = 1;
    len[s == 0 ? 1 : 0] = 1;
    return;
  }
  std::stable_sort(syms.begin(), syms.end(), [&](int a, int b) { return freq[a] < freq[b]; });
  // Two-queue Huffman: leaves (sorted) and internal nodes (created in
  // ascending weight order).
  const int m = int(syms.size());
  std::vector<Node> nodes(std::size_t(2 * m - 1));
  for (int i = 0; i < m; ++i) nodes[std::size_t(i)] = {freq[syms[std::size_t(i)]], -1};
  int leaf = 0, inner = m, next = m;
  auto take = [&]() {
    if (leaf < m && (inner >= next || nodes[std::size_t(leaf)].weight <= nodes[std::size_t(inner)].weight))
      return leaf++;
    return inner++;
  };
  for (; next < 2 * m - 1; ++next) {
    const int a = take(), b = take();
    nodes[std::size_t(next)] = {nodes[std::size_t(a)].weight + nodes[std::size_t(b)].weight, -1};
    nodes[std::size_t(a)].parent = nodes[std::size_t(b)].parent = next;
  }
  // Depths (parents come after children), counted per length.
  std::vector<int> depth(nodes.size(), 0);
  std::array<int, 64> count{};
  for (int i = 2 * m - 3; i >= 0; --i) depth[std::size_t(i)] = depth[std::size_t(nodes[std::size_t(i)].parent)] + 1;
  for (int i = 0; i < m; ++i) ++count[std::size_t(std::min(depth[std::size_t(i)], 63))];
  // Limit the lengths, keeping the code complete (sum of 2^-len = 1).
  for (int d = limit + 1; d < 64; ++d) count[std::size_t(limit)] += count[std::size_t(d)], count[std::size_t(d)] = 0;
  std::uint64_t total = 0;
  for (int d = 1; d <= limit; ++d) total += std::uint64_t(count[std::size_t(d)]) << (limit - d);
  while (total > (std::uint64_t(1) << limit)) {
    --count[std::size_t(limit)];
    for (int d = limit - 1; d > 0; --d)
      if (count[std::size_t(d)]) {
        --count[std::size_t(d)];
        count[std::size_t(d + 1)] += 2;
        break;
      }
    --total;
  }
  // The longest codes to the rarest symbols.
  int i = 0;
  for (int d = limit; d >= 1; --d)
    for (int k = 0; k < count[std::size_t(d)]; ++k) len[syms[std::size_t(i++)]] = std::uint8_t(d);
}

// Canonical codes (RFC 1951, 3.2.2), bit-reversed for the LSB-first stream.
void canonical_codes(const std::uint8_t* len, int n, std::uint16_t* code) {
  int count[16] = {}, next[16] = {};
  for (int s = 0; s < n; ++s) ++count[len[s]];
  count[0] = 0;
  for (int b = 1, c = 0; b < 16; ++b) next[b] = c = (c + count[b - 1]) << 1;
  for (int s = 0; s < n; ++s) {
    if (!len[s]) continue;
    unsigned c = unsigned(next[len[s]]++), r = 0;
    for (int b = 0; b < len[s]; ++b) r = (r << 1) | ((c >> b) & 1);
    code[s] = std::uint16_t(r);
  }
}

// A code-length symbol (RFC 1951, 3.2.7) with its extra bits.
struct ClSym {
  std::uint8_t sym, bits, extra;
};

// The code lengths len[0, n) run-length coded with symbols 16 (repeat the
// previous 3-6 times), 17 (3-10 zeros) and 18 (11-138 zeros).
std::vector<ClSym> code_length_symbols(const std::uint8_t* len, int n) {
  std::vector<ClSym> cl;
  for (int i = 0; i < n;) {
    const std::uint8_t v = len[i];
    int run = 1;
    while (i + run < n && len[i + run] == v) ++run;
    i += run;
    if (v == 0) {
      for (; run >= 11; run -= std::min(run, 138)) cl.push_back({18, 7, std::uint8_t(std::min(run, 138) - 11)});
      if (run >= 3) cl.push_back({17, 3, std::uint8_t(run - 3)}), run = 0;
    } else {
      cl.push_back({v, 0, 0}), --run;
      for (; run >= 3; run -= std::min(run, 6)) cl.push_back({16, 2, std::uint8_t(std::min(run, 6) - 3)});
    }
    for (; run > 0; --run) cl.push_back({v, 0, 0});
  }
  return cl;
}

class BitWriter {
 public:
  explicit BitWriter(unsigned char* out) : out_(out) {}
  void put(std::uint32_t value, int bits) {  // bits <= 32
    acc_ |= std::uint64_t(value) << n_;
    n_ += bits;
    if (n_ >= 32) {
      const std::uint32_t w = std::uint32_t(acc_);
      std::memcpy(out_, &w, 4);
      out_ += 4, acc_ >>= 32, n_ -= 32;
    }
  }
  unsigned char* finish() {  // pads to a byte
    for (; n_ > 0; n_ -= 8) *out_++ = static_cast<unsigned char>(acc_), acc_ >>= 8;
    n_ = 0;
    return out_;
  }

 private:
  unsigned char* out_;
  std::uint64_t acc_ = 0;
  int n_ = 0;
};

}  // namespace

std::size_t RunDeflater::compress(const unsigned char* in, std::size_t n, unsigned char* out) {
  // 1. Tokens and literal/length frequencies.
  const auto& lens = len_codes();
  tokens_.resize(n);
  std::uint32_t freq[kLitLen] = {};
  std::size_t t = 0;
  for (std::size_t i = 0; i < n;) {
    if (i > 0 && in[i] == 0 && in[i - 1] == 0) {
      std::size_t run = zero_run(in + i, n - i);
      if (run >= std::size_t(kMinMatch)) {
        for (; run >= std::size_t(kMinMatch); run -= std::min<std::size_t>(run, kMaxMatch)) {
          const std::size_t len = std::min<std::size_t>(run, kMaxMatch);
          tokens_[t++] = std::uint16_t(256 + len);
          ++freq[lens[len].symbol];
          i += len;
        }
        continue;  // 0-2 zeros left: literals
      }
    }
    ++freq[in[i]];
    tokens_[t++] = in[i++];
  }
  freq[kEob] = 1;

  // 2. Codes. Distances are all 1: two distance codes of one bit (a
  //    complete code, which every inflater accepts), code 0 used.
  std::uint8_t len[kLitLen + 2];
  huffman_lengths(freq, kLitLen, 15, len);
  std::uint16_t code[kLitLen] = {};
  canonical_codes(len, kLitLen, code);
  int nlit = kLitLen;
  while (len[nlit - 1] == 0) --nlit;  // >= 257: EOB is used
  len[nlit] = len[nlit + 1] = 1;      // the two distance codes follow the literal/length lengths
  const int nall = nlit + 2;

  // 3. The code lengths, run-length coded (code_length_symbols).
  const std::vector<ClSym> cl = code_length_symbols(len, nall);
  std::uint32_t cl_freq[19] = {};
  for (const ClSym& c : cl) ++cl_freq[c.sym];
  std::uint8_t cl_len[19];
  std::uint16_t cl_code[19] = {};
  huffman_lengths(cl_freq, 19, 7, cl_len);
  canonical_codes(cl_len, 19, cl_code);
  static constexpr std::uint8_t kOrder[19] = {16, 17, 18, 0, 8, 7, 9, 6, 10, 5, 11, 4, 12, 3, 13, 2, 14, 1, 15};
  int nclen = 19;
  while (nclen > 4 && cl_len[kOrder[nclen - 1]] == 0) --nclen;

  // 4. zlib header, the block, Adler-32.
  out[0] = 0x78, out[1] = 0x01;  // deflate, 32 KiB window, fastest; (0x7801 % 31 == 0)
  BitWriter w(out + 2);
  w.put(1, 1);  // BFINAL
  w.put(2, 2);  // BTYPE: dynamic Huffman
  w.put(std::uint32_t(nlit - 257), 5);
  w.put(2 - 1, 5);
  w.put(std::uint32_t(nclen - 4), 4);
  for (int k = 0; k < nclen; ++k) w.put(cl_len[kOrder[k]], 3);
  for (const ClSym& c : cl) {
    w.put(cl_code[c.sym], cl_len[c.sym]);
    if (c.bits) w.put(c.extra, c.bits);
  }
  // Each token in one put: a literal's code, or a length's code, its extra
  // bits and the distance code 0 (distance 1, one bit), at most 21 bits.
  std::uint32_t tok_bits[256 + kMaxMatch + 1] = {};
  std::uint8_t tok_len[256 + kMaxMatch + 1] = {};
  for (int b = 0; b < 256; ++b) tok_bits[b] = code[b], tok_len[b] = len[b];
  for (int n_len = kMinMatch; n_len <= kMaxMatch; ++n_len) {
    const LenCode& lc = lens[std::size_t(n_len)];
    const int cl_bits = len[lc.symbol];
    tok_bits[256 + n_len] = code[lc.symbol] | (std::uint32_t(lc.extra) << cl_bits);  // then dist 0
    tok_len[256 + n_len] = std::uint8_t(cl_bits + lc.bits + 1);
  }
  for (std::size_t k = 0; k < t; ++k) w.put(tok_bits[tokens_[k]], tok_len[tokens_[k]]);
  w.put(code[kEob], len[kEob]);
  unsigned char* end = w.finish();
  const std::uint32_t adler = libdeflate_adler32(1, in, n);
  for (int s = 24; s >= 0; s -= 8) *end++ = static_cast<unsigned char>(adler >> s);
  return std::size_t(end - out);
}

}  // namespace ptnet::h5
