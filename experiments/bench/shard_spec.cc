#include "experiments/bench/shard_spec.h"

namespace aperture::experiments {
namespace {

// The whole of `text` as a positive decimal integer, or -1.
int ParsePositive(const std::string& text) {
  if (text.empty() || text.size() > 9) return -1;
  int value = 0;
  for (char c : text) {
    if (c < '0' || c > '9') return -1;
    value = 10 * value + (c - '0');
  }
  return value > 0 ? value : -1;
}

}  // namespace

ShardSpec ParseShardSpec(const std::string& text) {
  const std::size_t slash = text.find('/');
  const int k = slash == std::string::npos ? -1 : ParsePositive(text.substr(0, slash));
  const int n = slash == std::string::npos ? -1 : ParsePositive(text.substr(slash + 1));
  if (k < 1 || n < 1 || k > n) {
    throw ShardSpecError("--shard '" + text +
                                "': expected K/N with integers 1 <= K <= N (e.g. --shard 2/4)");
  }
  return {k, n};
}

std::string ToString(const ShardSpec& shard) {
  return std::to_string(shard.index) + "/" + std::to_string(shard.count);
}

TrialRange ShardTrials(const ShardSpec& shard, const TrialRange& run) {
  if (shard.index < 1 || shard.count < 1 || shard.index > shard.count) {
    throw ShardSpecError("shard " + ToString(shard) + ": expected 1 <= K <= N");
  }
  if (shard.count > run.count) {
    throw ShardSpecError("--shard " + ToString(shard) + ": " + std::to_string(shard.count) +
                                " shards for " + std::to_string(run.count) +
                                " trials; use at most as many shards as trials");
  }
  const int base = run.count / shard.count;
  const int extra = run.count % shard.count;
  const int k = shard.index - 1;  // 0-based
  TrialRange part;
  part.first = run.first + k * base + (k < extra ? k : extra);
  part.count = base + (k < extra ? 1 : 0);
  return part;
}

}  // namespace aperture::experiments
