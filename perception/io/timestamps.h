#pragma once
// Timestamp sources of an image sequence, as separately testable parsers. All times are returned
// in seconds on the clock of the recording; nothing here touches images.
//
// Formats accepted (ImageFolderSource tries them in this order):
//  1. `times.txt` (seconds, one entry per non-empty line, `#` starts a comment line):
//       - single-column form: one timestamp per line; line i belongs to image i in natural file
//         order (KITTI style, e.g. "0.000000e+00"). The line count must equal the image count.
//       - pair form: "<file name> <t>" (or TUM style "<t> <file name>"), separated by spaces,
//         tabs or a comma. A name matches an image by full file name or by name without extension.
//     One file must use one form throughout.
//  2. EuRoC `data.csv`: header "#timestamp [ns],filename", then "<integer ns>,<file name>".
//  3. Numeric file names (see TimestampFromFileName).
//  4. An explicit frame rate: t_i = i / fps.
#include <istream>
#include <optional>
#include <string>
#include <vector>

namespace aperture::perception {

// Timestamps read from a file. `names` is empty for the single-column times.txt form (times are
// positional); otherwise names[i] is the file that t_s[i] belongs to. line_numbers[i] is the
// 1-based line t_s[i] came from, for error messages.
struct TimestampTable {
  std::vector<std::string> names;
  std::vector<double> t_s;
  std::vector<int> line_numbers;
};

// Parses a times.txt stream. `source` names the file in error messages. Throws
// std::invalid_argument naming the file and line for an unparsable line, a line with more than
// two fields, a non-finite time, a time >= 1e11 (not seconds: ms/us/ns), or a mix of the two
// forms. Does not check ordering.
TimestampTable ParseTimesTxt(std::istream& in, const std::string& source);

// Parses a EuRoC data.csv stream ("<timestamp ns>,<file name>" per line, '#' lines skipped).
// Throws std::invalid_argument naming the file, line and content for a malformed line.
TimestampTable ParseEurocDataCsv(std::istream& in, const std::string& source);

// Time encoded in an image file name, or nullopt when the name does not encode one.
// Disambiguation: a stem of only digits with >= kMinNanosecondDigits digits is a nanosecond
// timestamp (EuRoC: "1403636579763555584.png" -> 1403636579.763555584 s); a stem "<digits>.<digits>"
// is seconds (TUM: "1305031102.175304.png"). Shorter all-digit stems ("000123.png") are frame
// counters, not times, and give nullopt: 16 digits of ns are only 11.6 days after the epoch, so
// any real ns timestamp has >= 16 digits while frame counters have far fewer.
inline constexpr int kMinNanosecondDigits = 16;
std::optional<double> TimestampFromFileName(const std::string& file_name);

// Converts an integer nanosecond count to seconds, keeping the integer seconds exact.
double NanosecondsToSeconds(long long t_ns);

// Throws std::invalid_argument unless t_s is strictly increasing. labels[i] names entry i (file
// name or line) in the message; `source` names where the times came from.
void CheckStrictlyIncreasing(const std::vector<double>& t_s, const std::vector<std::string>& labels,
                             const std::string& source);

}  // namespace aperture::perception
