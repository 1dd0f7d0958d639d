#include "perception/io/frame_source_options_io.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <stdexcept>

#include "tests/support/message_of.h"
#include "tests/support/param_round_trip.h"

namespace aperture::perception {
namespace {

using ::testing::HasSubstr;

FrameSourceOptions LoadOptions(const std::string& yaml) {
  config::ParamReader reader(YAML::Load(yaml), "source.yaml");
  FrameSourceOptions options;
  LoadParams(reader, &options);
  return options;
}

std::string OptionsErrorOf(const std::string& yaml) {
  return test_support::MessageOf([&] { LoadOptions(yaml); });
}

TEST(FrameSourceOptionsIo, ReadsEveryFieldAndKeepsDefaultsForAbsentKeys) {
  const FrameSourceOptions all =
      LoadOptions("color_mode: color\nfps: 20\nskip_bad_frames: true\ncamera_id: 2\n");
  EXPECT_EQ(all.color_mode, ColorMode::kColor);
  EXPECT_EQ(all.fps, 20.0);
  EXPECT_TRUE(all.skip_bad_frames);
  EXPECT_EQ(all.camera_id, 2);

  const FrameSourceOptions defaults;
  const FrameSourceOptions partial = LoadOptions("fps: 30\n");
  EXPECT_EQ(partial.fps, 30.0);
  EXPECT_EQ(partial.color_mode, defaults.color_mode);
  EXPECT_EQ(partial.skip_bad_frames, defaults.skip_bad_frames);
}

TEST(FrameSourceOptionsIo, BadValuesNameTheLocationAndTheFix) {
  EXPECT_THAT(OptionsErrorOf("color_mode: rgb\n"), HasSubstr("gray, color"));
  EXPECT_THAT(OptionsErrorOf("fps: -1\n"), HasSubstr("source.yaml:1:"));
  EXPECT_THAT(OptionsErrorOf("fps: -1\n"), HasSubstr("positive rate"));
  EXPECT_THAT(OptionsErrorOf("fps: fast\n"), HasSubstr("fps"));
  EXPECT_THAT(OptionsErrorOf("skip_bad_frame: true\n"), HasSubstr("skip_bad_frame"));
}

TEST(FrameSourceOptionsIo, ParsesColorModeWords) {
  EXPECT_EQ(ParseColorMode("gray"), ColorMode::kGray);
  EXPECT_EQ(ParseColorMode("color"), ColorMode::kColor);
  try {
    ParseColorMode("grey");
    ADD_FAILURE() << "accepted 'grey'";
  } catch (const std::invalid_argument& e) {
    EXPECT_THAT(e.what(), HasSubstr("'grey'"));
    EXPECT_THAT(e.what(), HasSubstr("gray or color"));
  }
}

TEST(FrameSourceOptionsIo, RoundTripsThroughItsDump) {
  test_support::ExpectRoundTrip(FrameSourceOptions{});
}

}  // namespace
}  // namespace aperture::perception
