#pragma once
// Which part of a Monte-Carlo bench one process runs: shard K of N (`--shard K/N`, 1 <= K <= N,
// so Slurm's `--array=1-N` task id is K as it is). Shard K flies a contiguous block of the run's
// trial indices; every trial's seed comes from the bench seed and its global index only, so a
// trial's result does not depend on how the run is cut.
//
//   ShardSpec shard = ParseShardSpec("2/4");
//   TrialRange part = ShardTrials(shard, {0, 40});   // trials 10 .. 19
#include <stdexcept>
#include <string>

namespace aperture::experiments {

// A --shard value that does not fit (not K/N, or more shards than trials): a usage error.
class ShardSpecError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

struct ShardSpec {
  int index = 1;  // K, 1-based
  int count = 1;  // N
};

// "K/N" with integers 1 <= K <= N. ShardSpecError naming `text` and the expected form.
ShardSpec ParseShardSpec(const std::string& text);
std::string ToString(const ShardSpec& shard);  // "K/N"

// Global trial indices [first, first + count).
struct TrialRange {
  int first = 0;
  int count = 0;
  int end() const { return first + count; }
};

// Shard K/N's block of `run`: the first (run.count mod N) shards get one trial more than the
// others, in order, so the blocks tile `run` exactly. ShardSpecError when N exceeds the
// trial count (a shard would have nothing to fly).
TrialRange ShardTrials(const ShardSpec& shard, const TrialRange& run);

}  // namespace aperture::experiments
