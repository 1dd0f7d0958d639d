#include "perception/led/led_configuration.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "temp_directory.h"

namespace aperture::perception {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;

std::string WriteFile(const test_support::TempDirectory& dir, const std::string& name,
                      const std::string& text) {
  const std::string path = (dir.path() / name).string();
  std::ofstream(path) << text;
  return path;
}

std::string RejectionMessage(const std::vector<Eigen::Vector3d>& p_T) {
  try {
    LedConfiguration(p_T, "test.yaml");
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "accepted";
}

TEST(LedConfigurationTest, DefaultIsValidAndSizedLikeTheThesisTargets) {
  const LedConfiguration configuration = LedConfiguration::Default();
  EXPECT_EQ(configuration.size(), 5);
  double radius = 0.0;
  for (const auto& p : configuration.p_T()) radius = std::max(radius, p.norm());
  EXPECT_NEAR(radius, 0.109, 0.01);  // Fig. C.2: circumsphere radius 10.9 cm
}

TEST(LedConfigurationTest, LoadsYamlFile) {
  test_support::TempDirectory dir;
  const std::string path = WriteFile(dir, "leds.yaml",
                                     "leds: [[0, 0.105, 0], [0.1, 0.01, 0], [0.02, -0.09, 0.03], "
                                     "[-0.09, -0.04, 0], [-0.04, 0.04, 0.08]]\n");
  const LedConfiguration configuration = LedConfiguration::Load(path);
  ASSERT_EQ(configuration.size(), 5);
  EXPECT_TRUE(configuration.p_T()[2].isApprox(Eigen::Vector3d(0.02, -0.09, 0.03)));
  EXPECT_EQ(configuration.source(), path);
}

TEST(LedConfigurationTest, RejectsBadFilesNamingThem) {
  test_support::TempDirectory dir;
  EXPECT_THROW(LedConfiguration::Load((dir.path() / "missing.yaml").string()), std::runtime_error);
  const std::string no_key = WriteFile(dir, "no_key.yaml", "lights: []\n");
  EXPECT_THAT([&] { LedConfiguration::Load(no_key); },
              ::testing::ThrowsMessage<std::invalid_argument>(
                  AllOf(HasSubstr("no_key.yaml"), HasSubstr("leds"))));
  const std::string extra = WriteFile(dir, "extra.yaml",
                                      "leds: [[0, 0.105, 0], [0.1, 0.01, 0], [0.02, -0.09, 0.03], "
                                      "[-0.09, -0.04, 0]]\ncolour: red\n");
  EXPECT_THAT([&] { LedConfiguration::Load(extra); },
              ::testing::ThrowsMessage<std::invalid_argument>(
                  AllOf(HasSubstr("extra.yaml"), HasSubstr("colour"))));
  const std::string bad_point = WriteFile(dir, "bad.yaml", "leds: [[0, 0.1], [1, 2, 3]]\n");
  EXPECT_THAT([&] { LedConfiguration::Load(bad_point); },
              ::testing::ThrowsMessage<std::invalid_argument>(HasSubstr("bad.yaml")));
}

TEST(LedConfigurationTest, ParsesTextAsLoadDoesNamingTheGivenSource) {
  std::istringstream good(
      "leds: [[0, 0.105, 0], [0.1, 0.01, 0], [0.02, -0.09, 0.03], [-0.09, -0.04, 0], "
      "[-0.04, 0.04, 0.08]]\n");
  const LedConfiguration configuration = LedConfiguration::Parse(good, "target_a.yaml");
  ASSERT_EQ(configuration.size(), 5);
  EXPECT_TRUE(configuration.p_T()[4].isApprox(Eigen::Vector3d(-0.04, 0.04, 0.08)));
  EXPECT_EQ(configuration.source(), "target_a.yaml");
  std::istringstream unclosed("leds: [[0, 0.1, 0]\n");
  EXPECT_THAT([&] { LedConfiguration::Parse(unclosed, "target_b.yaml"); },
              ::testing::ThrowsMessage<std::invalid_argument>(
                  AllOf(HasSubstr("target_b.yaml"), HasSubstr("not valid YAML"))));
}

TEST(LedConfigurationTest, RejectsTooFewLeds) {
  EXPECT_THAT(RejectionMessage({{0, 0, 0}, {0.1, 0, 0}, {0, 0.1, 0.05}}),
              AllOf(HasSubstr("test.yaml"), HasSubstr("3 LEDs")));
}

TEST(LedConfigurationTest, RejectsCoplanarLeds) {
  // An irregular (non-symmetric) quadrilateral in z = 0.
  EXPECT_THAT(RejectionMessage({{0, 0, 0}, {0.1, 0, 0}, {0.13, 0.07, 0}, {-0.02, 0.11, 0}}),
              AllOf(HasSubstr("test.yaml"), HasSubstr("coplanar")));
}

TEST(LedConfigurationTest, RejectsSymmetricLeds) {
  // A square pyramid: 90 deg rotations about its axis permute the base LEDs.
  EXPECT_THAT(
      RejectionMessage({{0.1, 0, 0}, {0, 0.1, 0}, {-0.1, 0, 0}, {0, -0.1, 0}, {0, 0, 0.08}}),
      AllOf(HasSubstr("test.yaml"), HasSubstr("symmetric")));
  // A tetrahedron with a two-fold axis (two pairs of equal edges swapped), 1 mm off: still
  // within the 15 mm tolerance.
  EXPECT_THAT(RejectionMessage({{0.1, 0, 0}, {-0.1, 0, 0}, {0, 0.07, 0.09}, {0, -0.07, 0.091}}),
              HasSubstr("symmetric"));
  // A mirror-symmetric set is not ambiguous for a proper rigid motion: accepted.
  EXPECT_EQ(RejectionMessage({{0.1, 0, 0}, {-0.1, 0, 0}, {0, 0.08, 0}, {0, -0.02, 0.15}}),
            "accepted");
}

TEST(LedConfigurationTest, RejectsLedsCloserThanOneCentimetre) {
  EXPECT_THAT(RejectionMessage({{0, 0, 0}, {0.005, 0, 0}, {0.1, 0.02, 0}, {0, 0.1, 0.05}}),
              HasSubstr("closer than 1 cm"));
}

}  // namespace
}  // namespace aperture::perception
