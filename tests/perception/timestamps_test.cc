#include "perception/io/timestamps.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <sstream>
#include <stdexcept>

#include "tests/support/message_of.h"

namespace aperture::perception {
namespace {

using test_support::MessageOf;

using ::testing::HasSubstr;

TimestampTable ParseTimes(const std::string& text) {
  std::istringstream in(text);
  return ParseTimesTxt(in, "seq/times.txt");
}

TimestampTable ParseCsv(const std::string& text) {
  std::istringstream in(text);
  return ParseEurocDataCsv(in, "cam0/data.csv");
}

TEST(TimesTxt, SingleColumnIsPositionalSecondsSkippingCommentsAndBlankLines) {
  const TimestampTable table = ParseTimes("# KITTI style\n0.000000e+00\n\n1.037359e-01\n  0.2075 \n");
  EXPECT_TRUE(table.names.empty());
  ASSERT_EQ(table.t_s.size(), 3u);
  EXPECT_DOUBLE_EQ(table.t_s[0], 0.0);
  EXPECT_DOUBLE_EQ(table.t_s[1], 0.1037359);
  EXPECT_DOUBLE_EQ(table.t_s[2], 0.2075);
  EXPECT_EQ(table.line_numbers, (std::vector<int>{2, 4, 5}));
}

TEST(TimesTxt, PairFormAcceptsNameFirstTimeFirstAndCommas) {
  const TimestampTable table = ParseTimes("a.png 0.5\n0.75 b.png\nc.png,1.25\n");
  EXPECT_EQ(table.names, (std::vector<std::string>{"a.png", "b.png", "c.png"}));
  EXPECT_EQ(table.t_s, (std::vector<double>{0.5, 0.75, 1.25}));
}

TEST(TimesTxt, MalformedLinesNameTheFileAndLine) {
  EXPECT_THAT(MessageOf([] { ParseTimes("0.1\nzero point two\n"); }),
              HasSubstr("seq/times.txt line 2"));
  EXPECT_THAT(MessageOf([] { ParseTimes("0.1\nabc\n"); }), HasSubstr("'abc' is not a number"));
  EXPECT_THAT(MessageOf([] { ParseTimes("a.png b.png\n"); }), HasSubstr("line 1"));
  EXPECT_THAT(MessageOf([] { ParseTimes("0.1 0.2\n"); }), HasSubstr("exactly one file name"));
  EXPECT_THAT(MessageOf([] { ParseTimes("nan\n"); }), HasSubstr("not a number"));
  EXPECT_THAT(MessageOf([] { ParseTimes("0.1\na.png 0.2\n"); }), HasSubstr("mixes"));
  // Nanoseconds or milliseconds written where seconds belong.
  EXPECT_THAT(MessageOf([] { ParseTimes("1403636579763555584\n"); }), HasSubstr("too large"));
  EXPECT_THAT(MessageOf([] { ParseTimes("a.png 1403636579763\n"); }), HasSubstr("too large"));
  EXPECT_EQ(ParseTimes("1403636579.763555\n").t_s.size(), 1u);  // Unix seconds are fine
}

TEST(EurocCsv, ParsesNanosecondsToSecondsExactlyInTheIntegerPart) {
  const TimestampTable table = ParseCsv(
      "#timestamp [ns],filename\n1403636579763555584,1403636579763555584.png\r\n"
      "1403636579813555456, 1403636579813555456.png\n");
  EXPECT_EQ(table.names, (std::vector<std::string>{"1403636579763555584.png",
                                                   "1403636579813555456.png"}));
  ASSERT_EQ(table.t_s.size(), 2u);
  // A double near 1.4e9 resolves 2.4e-7 s, so compare to within that; the 50 ms frame spacing of
  // EuRoC must come out to within the same resolution.
  EXPECT_NEAR(table.t_s[0], 1403636579.763555584, 2.4e-7);
  EXPECT_NEAR(table.t_s[1] - table.t_s[0], 0.049999872, 5e-7);
  EXPECT_EQ(table.line_numbers, (std::vector<int>{2, 3}));
}

TEST(EurocCsv, MalformedLinesNameTheFileLineAndContent) {
  const std::string header = "#timestamp [ns],filename\n";
  std::string message =
      MessageOf([&] { ParseCsv(header + "1403636579763555584,a.png\nabc,b.png\n"); });
  EXPECT_THAT(message, HasSubstr("cam0/data.csv line 3"));
  EXPECT_THAT(message, HasSubstr("'abc' is not an integer nanosecond timestamp"));
  EXPECT_THAT(MessageOf([&] { ParseCsv(header + "1.5,a.png\n"); }), HasSubstr("'1.5'"));
  EXPECT_THAT(MessageOf([&] { ParseCsv(header + "123\n"); }), HasSubstr("two comma-separated"));
  EXPECT_THAT(MessageOf([&] { ParseCsv(header + "1,a.png,x\n"); }), HasSubstr("two comma"));
  EXPECT_THAT(MessageOf([&] { ParseCsv(header + "1,\n"); }), HasSubstr("empty file name"));
  EXPECT_THAT(MessageOf([&] { ParseCsv(header + "99999999999999999999,a.png\n"); }),
              HasSubstr("not an integer nanosecond"));
}

TEST(FileNameTimes, LongDigitStemsAreNanosecondsShortOnesAreFrameCounters) {
  const std::optional<double> euroc = TimestampFromFileName("1403636579763555584.png");
  ASSERT_TRUE(euroc.has_value());
  EXPECT_NEAR(*euroc, 1403636579.763555584, 2.4e-7);  // double resolution at 1.4e9 s
  // Exactly kMinNanosecondDigits digits is a time, one fewer is a counter.
  ASSERT_TRUE(TimestampFromFileName("1000000000000000.png").has_value());
  EXPECT_DOUBLE_EQ(*TimestampFromFileName("1000000000000000.png"), 1e6);
  EXPECT_FALSE(TimestampFromFileName("100000000000000.png").has_value());
  EXPECT_FALSE(TimestampFromFileName("000123.png").has_value());
  EXPECT_FALSE(TimestampFromFileName("frame_1403636579763555584.png").has_value());
}

TEST(FileNameTimes, DecimalStemsAreSeconds) {
  ASSERT_TRUE(TimestampFromFileName("1305031102.175304.png").has_value());
  EXPECT_DOUBLE_EQ(*TimestampFromFileName("1305031102.175304.png"), 1305031102.175304);
  EXPECT_FALSE(TimestampFromFileName("12.5a.png").has_value());
  EXPECT_FALSE(TimestampFromFileName(".5.png").has_value());
}

TEST(NanosecondsToSeconds, SplitsSecondsAndFraction) {
  EXPECT_DOUBLE_EQ(NanosecondsToSeconds(1500000000), 1.5);
  EXPECT_DOUBLE_EQ(NanosecondsToSeconds(999), 999e-9);
}

TEST(CheckStrictlyIncreasing, AcceptsIncreasingAndNamesTheOffendingPair) {
  const std::vector<std::string> labels = {"'a.png'", "'b.png'", "'c.png'"};
  EXPECT_NO_THROW(CheckStrictlyIncreasing({0.0, 0.1, 0.2}, labels, "seq"));
  const std::string backwards = MessageOf([&] {
    CheckStrictlyIncreasing({0.0, 0.2, 0.1}, labels, "seq");
  });
  EXPECT_THAT(backwards, HasSubstr("'c.png'"));
  EXPECT_THAT(backwards, HasSubstr("is before that of 'b.png'"));
  const std::string duplicate = MessageOf([&] {
    CheckStrictlyIncreasing({0.0, 0.1, 0.1}, labels, "seq");
  });
  EXPECT_THAT(duplicate, HasSubstr("duplicates that of 'b.png'"));
}

}  // namespace
}  // namespace aperture::perception
