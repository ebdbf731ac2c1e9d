// merge_datasets(): the shards of a sharded `ptnet simulate` (or compatible
// datasets) into one file (see ptnet/data.hpp).
#include <algorithm>
#include <cstdio>
#include <map>
#include <nlohmann/json.hpp>

#include "ptnet/data.hpp"
#include "ptnet/error.hpp"
#include "ptnet/io.hpp"

namespace ptnet {
namespace {

// The config without "shard", and the shard ("K/N", or "" when unsharded).
std::pair<std::string, std::string> split_shard(const Dataset& d) {
  nlohmann::ordered_json j;
  try {
    j = nlohmann::ordered_json::parse(d.info().config_json);
  } catch (const nlohmann::json::exception&) {
    return {d.info().config_json, ""};  // not JSON: compared as text
  }
  if (!j.is_object() || !j.contains("shard") || !j["shard"].is_string()) return {j.dump(), ""};
  const std::string shard = j["shard"].get<std::string>();
  j.erase("shard");
  return {j.dump(), shard};
}

bool same_body(const BodySpec& a, const BodySpec& b) {
  return a.id == b.id && a.sex == b.sex && a.height_cm == b.height_cm && a.weight_kg == b.weight_kg &&
         a.role == b.role;
}

// Every shard K/N of one N present once.
void check_shards(const std::vector<std::string>& inputs, const std::vector<std::string>& shards) {
  int count = -1;
  std::map<int, std::string> seen;  // K -> file
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    int k = -1, n = -1;
    char tail = 0;
    if (std::sscanf(shards[i].c_str(), "%d/%d%c", &k, &n, &tail) != 2 || k < 0 || n < 1 || k >= n)
      throw Error::in(inputs[i], "expected a shard K/N in its config, found " + escaped(shards[i]));
    if (count >= 0 && n != count)
      throw Error::in(inputs[i], "is shard " + shards[i] + ", " + inputs[0] + " one of " + std::to_string(count));
    count = n;
    if (!seen.emplace(k, inputs[i]).second)
      throw Error::in(inputs[i], "is shard " + shards[i] + ", as is " + seen[k]);
  }
  for (int k = 0; k < count; ++k)
    if (!seen.count(k))
      throw Error("merge: shard " + std::to_string(k) + "/" + std::to_string(count) + " is missing (" +
                  std::to_string(seen.size()) + " of " + std::to_string(count) + " given)");
}

}  // namespace

int merge_datasets(const std::vector<std::string>& inputs, const std::string& out_path, bool force) {
  if (inputs.empty()) throw Error("merge: no input datasets");
  check_output_path(out_path, force);
  std::vector<Dataset> sets;
  for (const auto& path : inputs) sets.push_back(Dataset::open(path));
  const Dataset& first = sets.front();
  const auto [config, first_shard] = split_shard(first);
  std::vector<std::string> shards;
  for (std::size_t i = 0; i < sets.size(); ++i) {
    const Dataset& d = sets[i];
    const auto [c, shard] = split_shard(d);
    shards.push_back(shard);
    const auto differs = [&](const std::string& what) {
      return Error::in(inputs[i], what + " differs from " + inputs[0] + "'s: not parts of one dataset");
    };
    if (!(d.info().mat == first.info().mat)) throw differs("the mat");
    if (d.info().fps != first.info().fps) throw differs("the frame rate");
    if (d.info().generator != first.info().generator) throw differs("the generator");
    if (c != config) throw differs("the config");
    if (d.bodies().size() != first.bodies().size() ||
        !std::equal(d.bodies().begin(), d.bodies().end(), first.bodies().begin(), same_body))
      throw differs("the bodies table");
  }
  const bool sharded = !first_shard.empty();
  for (std::size_t i = 0; i < sets.size(); ++i)
    if (shards[i].empty() == sharded)
      throw Error::in(inputs[i], std::string(sharded ? "is not a shard" : "is a shard") + ", " + inputs[0] +
                                     (sharded ? " is" : " is not"));
  if (sharded) check_shards(inputs, shards);
  // Shards in K order: the unsharded run's sequence order.
  std::vector<std::size_t> order(sets.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  if (sharded)
    std::sort(order.begin(), order.end(),
              [&](std::size_t a, std::size_t b) { return std::stoi(shards[a]) < std::stoi(shards[b]); });
  std::map<std::string, std::string> owner;  // sequence name -> file
  for (std::size_t i : order)
    for (const auto& m : sets[i].sequences())
      if (const auto [it, fresh] = owner.emplace(m.name, inputs[i]); !fresh)
        throw Error::in(inputs[i], "sequence " + escaped(m.name) + " is also in " + it->second);
  DatasetInfo info = first.info();
  info.config_json = config;
  DatasetWriter writer(out_path, info, first.bodies(), force);
  int written = 0;
  for (std::size_t i : order)
    for (const auto& m : sets[i].sequences()) {
      writer.add(m, sets[i].read(m.name));
      if (m.floor) writer.add_floor(m.name, sets[i].read_floor(m.name));
      ++written;
    }
  writer.commit();
  return written;
}

}  // namespace ptnet
