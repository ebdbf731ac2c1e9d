// The ranks of a data-parallel run on c10d + Gloo (see communicator.hpp).
// The only translation unit that includes the process group (compiled with
// USE_C10D_GLOO).
#include "communicator.hpp"

#include <torch/csrc/distributed/c10d/PrefixStore.hpp>
#include <torch/csrc/distributed/c10d/ProcessGroupGloo.hpp>
#include <glog/logging.h>
#include <torch/torch.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <thread>

#include "ptnet/error.hpp"
#include "ptnet/strings.hpp"
#include "rendezvous_store.hpp"

namespace ptnet {
namespace {

using Clock = std::chrono::steady_clock;
constexpr auto kPoll = std::chrono::milliseconds(50);          // store polling while joining
constexpr auto kSurvivorWindow = std::chrono::seconds(5);      // survivors of a failure announce themselves

struct Address {
  bool tcp = false;
  std::string host, path;  // tcp: host; file: path
  int port = 0;
};

Address parse_rendezvous(const std::string& text) {
  Address a;
  const std::string bad = field_text("rendezvous") +
                          ": expected tcp://HOST:PORT or file://PATH, found " + escaped(text, 80);
  if (text.rfind("file://", 0) == 0) {
    a.path = text.substr(7);
    if (a.path.empty()) throw Error(bad);
    return a;
  }
  if (text.rfind("tcp://", 0) != 0) throw Error(bad);
  const std::string rest = text.substr(6);
  const auto colon = rest.rfind(':');
  if (colon == std::string::npos || colon == 0) throw Error(bad);
  a.tcp = true;
  a.host = rest.substr(0, colon);
  std::int64_t port = 0;  // decimal: not 0x7000, not 1e3
  if (!parse_integer(rest.substr(colon + 1), 1, 65535, port)) throw Error(bad);
  a.port = int(port);
  return a;
}

bool is_loopback(const std::string& host) { return host == "localhost" || host.rfind("127.", 0) == 0; }

std::string text_of(const std::vector<uint8_t>& v) { return std::string(v.begin(), v.end()); }
std::vector<uint8_t> bytes_of(const std::string& s) { return std::vector<uint8_t>(s.begin(), s.end()); }

std::string short_detail(const std::exception& e) {
  const auto* c10e = dynamic_cast<const c10::Error*>(&e);
  std::string d = one_line(c10e ? c10e->what_without_backtrace() : e.what());
  if (d.size() > 160) d = d.substr(0, 157) + "...";
  return d;
}

}  // namespace

struct Communicator::Impl {
  c10::intrusive_ptr<c10d::Store> store;
  c10::intrusive_ptr<c10d::ProcessGroupGloo> group;
  std::string where;  // the rendezvous, for messages
  std::chrono::milliseconds timeout{0};
};

Communicator::Communicator(int rank, int size, std::unique_ptr<Impl> impl)
    : rank_(rank), size_(size), impl_(std::move(impl)) {}
Communicator::~Communicator() = default;

// The Gloo process group over the joined store: on GLOO_SOCKET_IFNAME's
// interface, else loopback for a loopback rendezvous, else the default device.
static c10::intrusive_ptr<c10d::ProcessGroupGloo> gloo_group(const c10::intrusive_ptr<c10d::Store>& store,
                                                              const Address& a, const DistOptions& o,
                                                              std::chrono::milliseconds timeout) {
  auto options = c10d::ProcessGroupGloo::Options::create(timeout);
  if (const char* iface = std::getenv("GLOO_SOCKET_IFNAME"); iface && *iface)
    options->devices.push_back(c10d::ProcessGroupGloo::createDeviceForInterface(iface));
  else if (a.tcp && is_loopback(a.host))
    options->devices.push_back(c10d::ProcessGroupGloo::createDeviceForHostname("127.0.0.1"));
  else
    options->devices.push_back(c10d::ProcessGroupGloo::createDefaultDevice());
  options->threads = 1;  // one collective at a time
  auto prefixed = c10::make_intrusive<c10d::PrefixStore>("gloo", store);
  return c10::make_intrusive<c10d::ProcessGroupGloo>(prefixed, o.rank, o.world_size, options);
}

// The options of a run of more than one rank.
static void check_world(const DistOptions& o, const Address& a) {
  if (!(o.timeout_s > 0))
    throw Error(field_text("dist_timeout_s") + ": must be > 0, found " + number_text(o.timeout_s));
  if (!a.tcp) return;
  const std::string need = "the same secret on every rank of a tcp:// rendezvous, " + std::to_string(kMinToken) +
                           "-" + std::to_string(kMaxToken) + " printable characters";
  if (o.token.empty()) throw Error(field_text("dist_token") + ": needed: " + need);
  const bool printable =
      std::all_of(o.token.begin(), o.token.end(), [](char c) { return c > ' ' && c < 0x7f; });
  if (o.token.size() < kMinToken || o.token.size() > kMaxToken || !printable)
    throw Error(field_text("dist_token") + ": expected " + need + ", found " + std::to_string(o.token.size()) +
                (printable ? " characters" : " bytes, not all printable"));
}

std::unique_ptr<Communicator> Communicator::join(const DistOptions& o) {
  if (o.world_size < 1)
    throw Error(field_text("world_size") + ": must be >= 1, found " + std::to_string(o.world_size));
  if (o.rank < 0 || o.rank >= o.world_size)
    throw Error(field_text("rank") + ": must be in 0-" + std::to_string(o.world_size - 1) +
                ", found " + std::to_string(o.rank));
  if (o.world_size == 1) return std::unique_ptr<Communicator>(new Communicator(0, 1, nullptr));
  if (o.rendezvous.empty())
    throw Error(field_text("rendezvous") + ": needed with " + field_text("world_size") + " " +
                std::to_string(o.world_size));
  const Address a = parse_rendezvous(o.rendezvous);
  check_world(o, a);
  // c10d logs its connection retries and timeouts through glog on stderr;
  // every failure here becomes one Error line instead.
  FLAGS_minloglevel = google::GLOG_FATAL;
  auto impl = std::make_unique<Impl>();
  impl->where = o.rendezvous;
  impl->timeout = std::chrono::milliseconds(std::int64_t(o.timeout_s * 1000));
  const std::string me = "rank " + std::to_string(o.rank);
  const std::string secs = number_text(o.timeout_s) + " s";
  try {
    impl->store = a.tcp ? tcp_store(a.host, a.port, o.rank == 0, o.world_size, impl->timeout, o.token)
                        : file_store(a.path, o.rank, o.world_size, impl->timeout);
  } catch (const Error& e) {
    throw Error(field_text("rendezvous") + " " + o.rendezvous + ": " + me + " " + e.message(),
                e.kind());
  } catch (const std::exception& e) {
    throw Error(field_text("rendezvous") + " " + o.rendezvous + ": " + me + " could not " +
                (o.rank == 0 && a.tcp ? "listen" : "reach rank 0") + " within " + secs + " (" +
                short_detail(e) + ")");
  }
  // Joining: rank 0 publishes the world size; each rank checks it and
  // claims its rank; all wait until every rank has joined, or one refused.
  c10d::Store& store = *impl->store;
  const auto refuse = [&](const std::string& why) {
    store.set("ptnet/refused", bytes_of(why));
    throw Error(why);
  };
  try {
    if (o.rank == 0) store.set("ptnet/world_size", bytes_of(std::to_string(o.world_size)));
    const std::string theirs = text_of(store.get("ptnet/world_size"));  // waits up to the timeout
    if (theirs != std::to_string(o.world_size))
      refuse(field_text("world_size") + ": " + me + " was started with " +
             std::to_string(o.world_size) + ", rank 0 with " + theirs);
    if (store.add("ptnet/rank/" + std::to_string(o.rank), 1) > 1)
      refuse(
          field_text("rank") + ": " + me + " was started twice" +
          (a.tcp ? std::string() : " (or " + a.path + " is left from an earlier run: remove it)"));
    store.set("ptnet/joined/" + std::to_string(o.rank), bytes_of("1"));
    const auto deadline = Clock::now() + impl->timeout;
    for (int r = 0; r < o.world_size;) {
      if (store.check({"ptnet/refused"}))
        throw Error("distributed: a rank refused to join: " + text_of(store.get("ptnet/refused")));
      if (store.check({"ptnet/joined/" + std::to_string(r)})) {
        ++r;
        continue;
      }
      if (Clock::now() > deadline)
        throw Error(field_text("rendezvous") + " " + o.rendezvous + ": rank " + std::to_string(r) +
                    " did not join within " + secs + " (" + std::to_string(o.world_size) +
                    " ranks expected)");
      std::this_thread::sleep_for(kPoll);
    }
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    throw Error(field_text("rendezvous") + " " + o.rendezvous + ": " + me +
                " could not join within " + secs + " (" + short_detail(e) + ")");
  }
  try {
    impl->group = gloo_group(impl->store, a, o, impl->timeout);
  } catch (const std::exception& e) {
    throw Error("distributed: " + me + " could not connect to the other ranks within " + secs + " (" +
                short_detail(e) + ")");
  }
  return std::unique_ptr<Communicator>(new Communicator(o.rank, o.world_size, std::move(impl)));
}

void Communicator::lost(const std::string& what, const std::string& detail) {
  // Which ranks are gone: every survivor of a failure announces itself and
  // waits a moment for the others; the rank hosting the store is gone when
  // the store is.
  std::vector<int> missing;
  try {
    c10d::Store& store = *impl_->store;
    store.set("ptnet/survivor/" + std::to_string(rank_), bytes_of("1"));
    const auto deadline = Clock::now() + std::min<Clock::duration>(kSurvivorWindow, impl_->timeout);
    if (size_ == 2) missing = {1 - rank_};  // the store answered: the other rank is the lost one
    else do {
      missing.clear();
      for (int r = 0; r < size_; ++r)
        if (!store.check({"ptnet/survivor/" + std::to_string(r)})) missing.push_back(r);
      if (missing.empty() || Clock::now() > deadline) break;
      std::this_thread::sleep_for(kPoll);
    } while (true);
  } catch (const std::exception&) {
    missing = {0};  // the store (rank 0) is unreachable
  }
  std::string ranks;
  for (int r : missing) ranks += (ranks.empty() ? "" : ", ") + std::to_string(r);
  if (missing.empty())
    throw Error("distributed: rank " + std::to_string(rank_) + ": " + what + " failed (" + detail + ")");
  throw Error("distributed: lost rank " + ranks + " during " + what + "; rank " + std::to_string(rank_) +
              " stops (" + detail + ")");
}

void Communicator::sum(std::vector<at::Tensor>& buffer, const std::string& what) {
  const auto t0 = Clock::now();
  try {
    impl_->group->allreduce(buffer)->wait();
  } catch (const std::exception& e) {
    lost(what, short_detail(e));
  }
  stats_.seconds += std::chrono::duration<double>(Clock::now() - t0).count();
  stats_.calls += 1;
  stats_.bytes += buffer[0].numel() * std::int64_t(buffer[0].element_size());
}

void Communicator::allreduce(std::vector<at::Tensor>& tensors, const std::string& what) {
  if (size_ == 1 || tensors.empty()) return;
  std::vector<at::Tensor> flat_parts;
  for (const auto& t : tensors) flat_parts.push_back(t.detach().reshape({-1}).to(torch::kFloat32));
  std::vector<at::Tensor> buffer{torch::cat(flat_parts)};
  sum(buffer, what);
  std::int64_t offset = 0;
  for (auto& t : tensors) {
    const std::int64_t n = t.numel();
    torch::NoGradGuard no_grad;
    t.copy_(buffer[0].narrow(0, offset, n).view(t.sizes()));
    offset += n;
  }
}

void Communicator::allreduce(std::vector<double>& values, const std::string& what) {
  if (size_ == 1 || values.empty()) return;
  std::vector<at::Tensor> buffer{torch::tensor(values, torch::kFloat64)};
  sum(buffer, what);
  const double* p = buffer[0].data_ptr<double>();
  std::copy(p, p + values.size(), values.begin());
}

void Communicator::check_same(const std::vector<double>& values, const std::string& what) {
  if (size_ == 1 || values.empty()) return;
  // One MAX all-reduce of (v, -v): the maximum and the minimum of each value.
  std::vector<double> both(values);
  for (double v : values) both.push_back(-v);
  std::vector<at::Tensor> buffer{torch::tensor(both, torch::kFloat64)};
  c10d::AllreduceOptions opts;
  opts.reduceOp = c10d::ReduceOp::MAX;
  try {
    impl_->group->allreduce(buffer, opts)->wait();
  } catch (const std::exception& e) {
    lost("the start-up check", short_detail(e));
  }
  const double* p = buffer[0].data_ptr<double>();
  for (std::size_t i = 0; i < values.size(); ++i)
    if (p[i] != -p[i + values.size()])
      throw Error("distributed: the ranks disagree on " + what + " (rank " + std::to_string(rank_) +
                  "); start every rank with the same data, options and model folder");
}

void Communicator::barrier(const std::string& what) {
  if (size_ == 1) return;
  try {
    impl_->group->barrier()->wait();
  } catch (const std::exception& e) {
    lost(what, short_detail(e));
  }
}

}  // namespace ptnet
