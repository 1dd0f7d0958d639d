#include "perception/io/natural_sort.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

namespace aperture::perception {
namespace {

TEST(NaturalSort, NumbersCompareByValueNotByCharacter) {
  EXPECT_TRUE(NaturalLess("frame2.png", "frame10.png"));
  EXPECT_FALSE(NaturalLess("frame10.png", "frame2.png"));
  EXPECT_TRUE(NaturalLess("img_9", "img_010"));
  EXPECT_TRUE(NaturalLess("a1b2", "a1b10"));
}

TEST(NaturalSort, DigitRunsLongerThan64BitsDoNotOverflow) {
  // 25-digit runs would overflow any integer type; comparison must still be by value.
  EXPECT_TRUE(NaturalLess("x9999999999999999999999999", "x10000000000000000000000000"));
  EXPECT_TRUE(NaturalLess("1403636579763555584.png", "1403636579813555456.png"));
}

TEST(NaturalSort, LeadingZerosAndCaseOnlyBreakTies) {
  // Equal by value and case-insensitively: the byte-wise order decides, in both directions
  // consistently (strict weak ordering).
  EXPECT_TRUE(NaturalLess("img01", "img1"));
  EXPECT_FALSE(NaturalLess("img1", "img01"));
  EXPECT_TRUE(NaturalLess("Frame", "frame"));
  EXPECT_FALSE(NaturalLess("frame", "Frame"));
  EXPECT_FALSE(NaturalLess("same", "same"));
  // Case does not override the text order: "apple" < "Banana" < "cherry".
  EXPECT_TRUE(NaturalLess("apple", "Banana"));
  EXPECT_TRUE(NaturalLess("Banana", "cherry"));
}

TEST(NaturalSort, PrefixSortsFirstAndDigitsBeforeLetters) {
  EXPECT_TRUE(NaturalLess("frame", "frame1"));
  EXPECT_TRUE(NaturalLess("a1", "ab"));
  EXPECT_TRUE(NaturalLess("", "a"));
}

TEST(NaturalSort, SortsAShuffledSequenceIntoCaptureOrder) {
  std::vector<std::string> expected;
  for (int i = 0; i <= 120; ++i) expected.push_back("frame" + std::to_string(i) + ".png");
  std::vector<std::string> names = expected;
  std::mt19937 random(7);
  std::shuffle(names.begin(), names.end(), random);
  NaturalSort(names);
  EXPECT_EQ(names, expected);
}

}  // namespace
}  // namespace aperture::perception
