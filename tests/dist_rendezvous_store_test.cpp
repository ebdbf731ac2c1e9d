// The rendezvous stores (dist/rendezvous_store.hpp): the tcp store serves
// the c10d::Store calls the ranks and Gloo make, and holds against
// connections that are not ranks (oversized announcements, partial
// messages, silent or unauthenticated connections, a full store); the file store
// is created by rank 0 only and joined only when rank 0 made it.
#include <gtest/gtest.h>
#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <future>
#include <thread>

#include "cli_test_util.hpp"
#include "data_test_util.hpp"
#include "ptnet/error.hpp"
#include "distributed/rendezvous_store.hpp"
#include "distributed/store_protocol.hpp"

using namespace ptnet;
using ptnet::testing_cli::slurp;
using ptnet::testing_util::error_of;
namespace fs = std::filesystem;
using std::chrono::milliseconds;
using std::chrono::seconds;

namespace {

constexpr auto kTimeout = seconds(30);  // the stores' timeout: generous, nothing here waits for it
const std::string kToken = "0123456789abcdef-test-token";  // the run's secret

std::vector<uint8_t> bytes(const std::string& s) { return std::vector<uint8_t>(s.begin(), s.end()); }
std::string text(const std::vector<uint8_t>& v) { return std::string(v.begin(), v.end()); }

int connect_to(int port) {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  a.sin_port = htons(std::uint16_t(port));
  EXPECT_EQ(::connect(fd, reinterpret_cast<sockaddr*>(&a), sizeof a), 0);
  return fd;
}

void send_u32(int fd, std::uint32_t v) {
  const unsigned char b[4] = {std::uint8_t(v), std::uint8_t(v >> 8), std::uint8_t(v >> 16), std::uint8_t(v >> 24)};
  ASSERT_EQ(::send(fd, b, 4, MSG_NOSIGNAL), 4);
}

// True when the server closed `fd` within 30 s (reads return 0 or fail).
bool closed_by_server(int fd) {
  char buf[256];
  pollfd p{fd, POLLIN, 0};
  while (::poll(&p, 1, 30000) > 0) {
    const ssize_t n = ::recv(fd, buf, sizeof buf, 0);
    if (n <= 0) return true;
  }
  return false;
}

class Store : public ::testing::Test {
 protected:
  ptnet::testing_util::TempDir tmp_{"store_test"};
  const fs::path dir_ = tmp_.path;
};

}  // namespace

TEST_F(Store, TcpStoreServesTheCalls) {
  StoreServer server("127.0.0.1", 0, 5, kToken);
  auto a = tcp_store("127.0.0.1", server.port(), false, 2, kTimeout, kToken);
  auto b = tcp_store("127.0.0.1", server.port(), false, 2, kTimeout, kToken);
  a->set("k", bytes("v"));
  EXPECT_EQ(text(b->get("k")), "v");
  EXPECT_TRUE(b->check({"k"}));
  EXPECT_FALSE(b->check({"k", "absent"}));
  EXPECT_EQ(a->add("n", 2), 2);
  EXPECT_EQ(b->add("n", -5), -3);
  EXPECT_EQ(text(a->get("n")), "-3");  // c10d's convention: the number as text
  EXPECT_EQ(a->getNumKeys(), 2);
  EXPECT_EQ(text(a->compareSet("k", bytes("v"), bytes("w"))), "w");
  EXPECT_EQ(text(a->compareSet("k", bytes("v"), bytes("x"))), "w");
  EXPECT_TRUE(a->deleteKey("k"));
  EXPECT_FALSE(a->deleteKey("k"));
  // wait() returns once another client sets the key.
  auto later = std::async(std::launch::async, [&] {
    std::this_thread::sleep_for(milliseconds(200));
    b->set("late", bytes("1"));
  });
  EXPECT_NO_THROW(a->wait({"late"}));
  later.get();
  // ... and gives up after its timeout, bounded by the store's own too.
  EXPECT_THROW(a->wait({"never"}, milliseconds(300)), std::exception);
  auto quick = tcp_store("127.0.0.1", server.port(), false, 2, milliseconds(500), kToken);
  EXPECT_THROW(quick->wait({"never"}, seconds(3600)), std::exception) << "the store's timeout bounds every wait";
}

TEST_F(Store, AnAnnouncedSizeOverTheLimitClosesTheConnection) {
  StoreServer server("127.0.0.1", 0, 4, kToken);
  const int stranger = connect_to(server.port());
  send_u32(stranger, 1u << 30);  // before the greeting: anything over 64 bytes
  EXPECT_TRUE(closed_by_server(stranger));
  ::close(stranger);
  // A rank's own messages are bounded too, and the store still serves.
  auto rank = tcp_store("127.0.0.1", server.port(), false, 2, kTimeout, kToken);
  EXPECT_THROW(rank->set("big", std::vector<uint8_t>(kMaxStoreMessage, 'x')), Error);
  rank->set("small", bytes("1"));
  EXPECT_EQ(text(rank->get("small")), "1");
}

TEST_F(Store, APartialMessageHoldsNeitherTheRanksNorTheEnd) {
  auto server = std::make_unique<StoreServer>("127.0.0.1", 0, 4, kToken);
  const int stranger = connect_to(server->port());
  ASSERT_EQ(::send(stranger, "\x05", 1, MSG_NOSIGNAL), 1);  // a quarter of a length, then nothing
  auto rank = tcp_store("127.0.0.1", server->port(), false, 2, kTimeout, kToken);
  rank->set("k", bytes("v"));
  EXPECT_EQ(text(rank->get("k")), "v");
  rank.reset();
  auto stopped = std::async(std::launch::async, [&] { server.reset(); });
  EXPECT_EQ(stopped.wait_for(seconds(30)), std::future_status::ready) << "the server waits for the stranger";
  stopped.wait();
  ::close(stranger);
}

TEST_F(Store, AFullStoreRefusesMore) {
  StoreServer server("127.0.0.1", 0, 4, kToken);
  auto rank = tcp_store("127.0.0.1", server.port(), false, 2, kTimeout, kToken);
  const std::vector<uint8_t> value(kMaxStoreMessage / 2, 'x');
  std::size_t held = 0;
  int i = 0;
  for (; held + value.size() < kMaxStoreBytes; ++i) {
    rank->set("v" + std::to_string(i), value);
    held += value.size() + 2 + std::to_string(i).size();
  }
  EXPECT_THROW(
      {
        for (int j = 0; j < 4; ++j) rank->set("w" + std::to_string(j), value);
      },
      Error);
  rank->set("v0", bytes("small"));  // a replaced value frees its bytes
  EXPECT_EQ(text(rank->get("v0")), "small");
}

// A whole message of the store's protocol (store_protocol.hpp).
std::string message(store_protocol::Op op, const std::vector<std::string>& fields) {
  return store_protocol::framed(store_protocol::request(op, fields));
}
using store_protocol::kHello;
using store_protocol::kSet;

// Strangers on the port, 50 silent and 50 greeting without the run's token
// (with the store's older greeting, or with another token), cannot keep the
// ranks out nor write a key: the silent ones wait outside the ranks' slots
// (the oldest giving way to newcomers), the others are closed at their
// greeting. Before, 10 silent or greeted strangers took every slot of a
// 2-rank run for good.
TEST_F(Store, StrangersCannotKeepTheRanksOutNorWrite) {
  StoreServer server("127.0.0.1", 0, 2 + 8, kToken);
  std::vector<int> silent, greeting;
  for (int i = 0; i < 50; ++i) silent.push_back(connect_to(server.port()));
  for (int i = 0; i < 50; ++i) {
    const int fd = connect_to(server.port());
    const std::string hello = i % 2 ? message(kHello, {"ptnet-store 1"})
                                    : message(kHello, {"ptnet-store 2", "another run's token, long"});
    const std::string set = message(kSet, {"ptnet/refused", "a stranger ends the run"});
    ::send(fd, (hello + set).data(), hello.size() + set.size(), MSG_NOSIGNAL);
    greeting.push_back(fd);
  }
  for (int fd : greeting) EXPECT_TRUE(closed_by_server(fd)) << "a stranger was served";
  auto zero = tcp_store("127.0.0.1", server.port(), false, 2, kTimeout, kToken);
  auto one = tcp_store("127.0.0.1", server.port(), false, 2, kTimeout, kToken);
  zero->set("k", bytes("v"));
  EXPECT_EQ(text(one->get("k")), "v");
  EXPECT_FALSE(one->check({"ptnet/refused"}));
  // A client with another token is refused at its greeting, in one line.
  try {
    tcp_store("127.0.0.1", server.port(), false, 2, milliseconds(500), "another run's token, long");
    ADD_FAILURE() << "another token was served";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("closed the connection at the greeting: another dist_token than rank 0's"),
              std::string::npos)
        << e.what();
  }
  for (int fd : silent) ::close(fd);
  for (int fd : greeting) ::close(fd);
}

TEST_F(Store, FileStoreIsMadeByRankZeroAndJoinedByTheOthers) {
  const std::string path = (dir_ / "run.rdv").string();
  // Rank 1 first: it waits for rank 0's file.
  auto joined = std::async(std::launch::async, [&] { return file_store(path, 1, 2, kTimeout); });
  std::this_thread::sleep_for(milliseconds(300));
  auto zero = file_store(path, 0, 2, kTimeout);
  auto one = joined.get();
  zero->set("k", bytes("v"));
  EXPECT_EQ(text(one->get("k")), "v");
  for (const auto& e : fs::directory_iterator(dir_)) EXPECT_EQ(e.path().string(), path) << "a temporary file is left";
  // A second rank 0 on the same path is refused (a file left by a run).
  EXPECT_THROW(file_store(path, 0, 2, kTimeout), Error);
  zero.reset();
  one.reset();
  EXPECT_FALSE(fs::exists(path)) << "the last rank removes the file";
}

TEST_F(Store, FileStoreRefusesWhatRankZeroDidNotMake) {
  const fs::path user = dir_ / "v.csv", empty = dir_ / "empty", folder = dir_ / "folder";
  std::ofstream(user) << "id,sex\n";
  std::ofstream{empty};
  fs::create_directories(folder);
  for (const fs::path& p : {user, empty, folder})
    for (int rank : {0, 1}) {
      try {
        file_store(p.string(), rank, 2, seconds(1));
        ADD_FAILURE() << p << " accepted by rank " << rank;
      } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find(p.string()), std::string::npos) << e.what();
      }
    }
  EXPECT_EQ(slurp(user), "id,sex\n");
  EXPECT_EQ(fs::file_size(empty), 0u);
  EXPECT_TRUE(fs::is_empty(folder));
}

// A FIFO where rank 1 looks for rank 0's file is refused within the
// timeout: before the fix rank 1 opened it first, and blocked until a
// writer came (for ever), whatever its timeout.
TEST_F(Store, FileStoreRefusesAFifoWithinItsTimeout) {
  const fs::path fifo = dir_ / "run.rdv";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  auto joined = std::async(std::launch::async, [&] { return error_of([&] { file_store(fifo.string(), 1, 2, seconds(1)); }); });
  const bool ended = joined.wait_for(seconds(30)) == std::future_status::ready;
  if (!ended) ::close(::open(fifo.c_str(), O_WRONLY));  // lets the blocked open return
  EXPECT_TRUE(ended) << "rank 1 blocked on the FIFO";
  EXPECT_EQ(joined.get(), "found " + fifo.string() + " (a FIFO), which is not a rendezvous file made by rank 0: give a "
                          "path that does not exist");
  struct stat st {};
  ASSERT_EQ(::stat(fifo.c_str(), &st), 0);
  EXPECT_TRUE(S_ISFIFO(st.st_mode)) << "the FIFO was replaced";
}

