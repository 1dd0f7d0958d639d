// --shard K/N (experiments/bench/shard_spec.h): parsing, and the blocks of every shard count tile
// the run exactly (each trial in one shard, in order, sizes within one of each other).
#include "experiments/bench/shard_spec.h"

#include <gtest/gtest.h>

#include <stdexcept>

namespace aperture::experiments {
namespace {

TEST(ShardSpec, ParsesKOverN) {
  const ShardSpec shard = ParseShardSpec("3/8");
  EXPECT_EQ(shard.index, 3);
  EXPECT_EQ(shard.count, 8);
  EXPECT_EQ(ToString(shard), "3/8");
  EXPECT_EQ(ParseShardSpec("1/1").count, 1);
}

TEST(ShardSpec, RejectsEverythingButKOverNWithKWithinN) {
  for (const char* text : {"", "4", "0/4", "5/4", "-1/4", "1/0", "a/4", "1/4/2", "1 /4", "2/"}) {
    try {
      ParseShardSpec(text);
      ADD_FAILURE() << "accepted '" << text << "'";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(std::string("'") + text + "'"), std::string::npos)
          << e.what();
    }
  }
}

TEST(ShardSpec, BlocksTileTheRunForEveryShardCount) {
  for (int trials = 1; trials <= 23; ++trials) {
    for (int count = 1; count <= trials; ++count) {
      const TrialRange run{7, trials};  // a run that starts at --first-trial 7
      int next = run.first;
      for (int k = 1; k <= count; ++k) {
        const TrialRange part = ShardTrials({k, count}, run);
        EXPECT_EQ(part.first, next) << k << "/" << count << " of " << trials;
        // Sizes differ by at most one: floor or ceil of trials / count.
        EXPECT_GE(part.count, trials / count);
        EXPECT_LE(part.count, (trials + count - 1) / count);
        next = part.end();
      }
      EXPECT_EQ(next, run.end()) << count << " shards of " << trials;
    }
  }
}

TEST(ShardSpec, RefusesMoreShardsThanTrials) {
  EXPECT_THROW(ShardTrials({1, 5}, {0, 4}), std::invalid_argument);
}

}  // namespace
}  // namespace aperture::experiments
