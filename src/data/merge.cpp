// merge_datasets(): the shards of a sharded `ptnet simulate` (or compatible
// datasets) into one file (see ptnet/data.hpp).
#include <algorithm>
#include <cstdint>
#include <map>
#include <nlohmann/json.hpp>

#include "core/rate.hpp"
#include "ptnet/data.hpp"
#include "ptnet/error.hpp"
#include "ptnet/io.hpp"
#include "ptnet/strings.hpp"

namespace ptnet {
namespace {

// A dataset's config without "shard" and "run", its shard ("K/N", or ""
// when unsharded) and its run's identity ("run": clips digest, sequences).
struct ShardConfig {
  std::string config, shard;
  nlohmann::ordered_json run;  // null when absent
};

ShardConfig split_shard(const Dataset& d) {
  nlohmann::ordered_json j;
  try {
    j = nlohmann::ordered_json::parse(d.info().config_json);
  } catch (const nlohmann::json::exception&) {
    return {d.info().config_json, "", nullptr};  // not JSON: compared as text
  }
  if (!j.is_object() || !j.contains("shard") || !j["shard"].is_string()) return {j.dump(), "", nullptr};
  ShardConfig c;
  c.shard = j["shard"].get<std::string>();
  if (j.contains("run")) c.run = j["run"];
  j.erase("shard");
  j.erase("run");
  c.config = j.dump();
  return c;
}

bool same_body(const BodySpec& a, const BodySpec& b) {
  return a.id == b.id && a.sex == b.sex && a.height_cm == b.height_cm && a.weight_kg == b.weight_kg &&
         a.role == b.role;
}

// Every shard K/N of one N present once, each of the same run (its clips'
// digest and sequence count in "run") and complete: shard K of a run of J
// sequences holds the J K / N .. J (K + 1) / N - 1 th.
void check_shards(const std::vector<std::string>& inputs, const std::vector<Dataset>& sets,
                  const std::vector<ShardConfig>& configs) {
  int count = -1;
  std::map<int, std::string> seen;  // K -> file
  const nlohmann::ordered_json& run = configs[0].run;
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    const std::string& shard = configs[i].shard;
    int k = -1, n = -1;
    if (!parse_shard(shard, k, n))
      throw Error::in(inputs[i], "expected a shard K/N in its config, found " + escaped(shard));
    if (count >= 0 && n != count)
      throw Error::in(inputs[i], "is shard " + shard + ", " + inputs[0] + " one of " + std::to_string(count));
    count = n;
    if (!seen.emplace(k, inputs[i]).second)
      throw Error::in(inputs[i], "is shard " + shard + ", as is " + seen[k]);
    const nlohmann::ordered_json& mine = configs[i].run;
    if (!mine.is_object() || !mine.contains("clips") || !mine.contains("sequences") ||
        !mine["sequences"].is_number_unsigned())
      throw Error::in(inputs[i], "is a shard whose config does not identify its run (\"run\": its clips' digest "
                                 "and sequence count; an older ptnet did not record it): simulate it again");
    if (mine["clips"] != run["clips"])
      throw Error::in(inputs[i], "is a shard of another run than " + inputs[0] + " (other clips: digest " +
                                     mine["clips"].dump() + ", " + run["clips"].dump() + ")");
    if (mine["sequences"] != run["sequences"])
      throw Error::in(inputs[i], "is a shard of a run of " + mine["sequences"].dump() + " sequences, " + inputs[0] +
                                     " of " + run["sequences"].dump());
    const std::uint64_t jobs = mine["sequences"].get<std::uint64_t>();
    const std::uint64_t block = jobs * std::uint64_t(k + 1) / std::uint64_t(n) - jobs * std::uint64_t(k) / std::uint64_t(n);
    if (sets[i].sequences().size() != block)
      throw Error::in(inputs[i], "shard " + shard + " of a run of " + std::to_string(jobs) + " sequences holds " +
                                     std::to_string(sets[i].sequences().size()) + " sequences, expected " +
                                     std::to_string(block) + ": an incomplete shard");
  }
  for (int k = 0; k < count; ++k)
    if (!seen.count(k))
      throw Error("merge: shard " + std::to_string(k) + "/" + std::to_string(count) + " is missing (" +
                  std::to_string(seen.size()) + " of " + std::to_string(count) + " given)");
}

}  // namespace

bool parse_shard(std::string_view text, int& index, int& count) {
  const std::size_t slash = text.find('/');
  std::int64_t k = 0, n = 0;
  if (slash == std::string_view::npos || !parse_integer(text.substr(0, slash), 0, INT32_MAX, k) ||
      !parse_integer(text.substr(slash + 1), 1, INT32_MAX, n) || k >= n)
    return false;
  index = int(k);
  count = int(n);
  return true;
}

int merge_datasets(const std::vector<std::string>& inputs, const std::string& out_path, bool force) {
  if (inputs.empty()) throw Error("merge: no input datasets");
  check_dataset_output(out_path, force);
  std::vector<Dataset> sets;
  for (const auto& path : inputs) sets.push_back(Dataset::open(path));
  const Dataset& first = sets.front();
  std::vector<ShardConfig> configs;
  for (const Dataset& d : sets) configs.push_back(split_shard(d));
  const std::string& config = configs[0].config;
  const std::string& first_shard = configs[0].shard;
  for (std::size_t i = 0; i < sets.size(); ++i) {
    const Dataset& d = sets[i];
    const std::string& c = configs[i].config;
    const auto differs = [&](const std::string& what) {
      return Error::in(inputs[i], what + " differs from " + inputs[0] + "'s: not parts of one dataset");
    };
    if (!(d.info().mat == first.info().mat)) throw differs("the mat");
    if (!same_rate(d.info().fps, first.info().fps)) throw differs("the frame rate");
    if (d.info().generator != first.info().generator) throw differs("the generator");
    if (c != config) throw differs("the config");
    if (d.bodies().size() != first.bodies().size() ||
        !std::equal(d.bodies().begin(), d.bodies().end(), first.bodies().begin(), same_body))
      throw differs("the bodies table");
  }
  const bool sharded = !first_shard.empty();
  for (std::size_t i = 0; i < sets.size(); ++i)
    if (configs[i].shard.empty() == sharded)
      throw Error::in(inputs[i], std::string(sharded ? "is not a shard" : "is a shard") + ", " + inputs[0] +
                                     (sharded ? " is" : " is not"));
  if (sharded) check_shards(inputs, sets, configs);
  // Shards in K order: the unsharded run's sequence order.
  std::vector<std::size_t> order(sets.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  if (sharded)
    std::sort(order.begin(), order.end(),
              [&](std::size_t a, std::size_t b) { return std::stoi(configs[a].shard) < std::stoi(configs[b].shard); });
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
