#include "perception/io/timestamps.h"

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <stdexcept>

namespace aperture::perception {
namespace {

std::string Trim(const std::string& s) {
  size_t begin = 0;
  size_t end = s.size();
  while (begin < end && std::isspace(static_cast<unsigned char>(s[begin]))) ++begin;
  while (end > begin && std::isspace(static_cast<unsigned char>(s[end - 1]))) --end;
  return s.substr(begin, end - begin);
}

bool AllDigits(const std::string& s) {
  if (s.empty()) return false;
  for (char c : s) {
    if (!std::isdigit(static_cast<unsigned char>(c))) return false;
  }
  return true;
}

// Parses the whole of `token` as a finite double.
std::optional<double> ParseSeconds(const std::string& token) {
  if (token.empty()) return std::nullopt;
  char* end = nullptr;
  errno = 0;
  const double value = std::strtod(token.c_str(), &end);
  if (end != token.c_str() + token.size() || errno == ERANGE || !std::isfinite(value)) {
    return std::nullopt;
  }
  return value;
}

// Parses an all-digit token as a non-negative nanosecond count.
std::optional<long long> ParseNanoseconds(const std::string& token) {
  if (!AllDigits(token)) return std::nullopt;
  errno = 0;
  const long long value = std::strtoll(token.c_str(), nullptr, 10);
  if (errno == ERANGE) return std::nullopt;  // beyond int64 (year 2262 in ns)
  return value;
}

// Splits on whitespace and commas.
std::vector<std::string> SplitFields(const std::string& line) {
  std::vector<std::string> fields;
  std::string current;
  for (char c : line) {
    if (c == ',' || std::isspace(static_cast<unsigned char>(c))) {
      if (!current.empty()) fields.push_back(current);
      current.clear();
    } else {
      current += c;
    }
  }
  if (!current.empty()) fields.push_back(current);
  return fields;
}

std::string LineRef(const std::string& source, int line_number, const std::string& line) {
  return source + " line " + std::to_string(line_number) + " ('" + line + "')";
}

}  // namespace

TimestampTable ParseTimesTxt(std::istream& in, const std::string& source) {
  static const char* const kFormatHelp =
      "; expected one time in seconds per line (line i = image i in natural file order) or "
      "'<file name> <t>' pairs";
  TimestampTable table;
  std::optional<bool> pair_form;
  std::string raw;
  int line_number = 0;
  while (std::getline(in, raw)) {
    ++line_number;
    const std::string line = Trim(raw);
    if (line.empty() || line[0] == '#') continue;
    const std::vector<std::string> fields = SplitFields(line);
    std::string name;
    std::optional<double> t_s;
    if (fields.size() == 1) {
      t_s = ParseSeconds(fields[0]);
      if (!t_s) {
        throw std::invalid_argument(LineRef(source, line_number, line) + ": '" + fields[0] +
                                    "' is not a number" + kFormatHelp);
      }
    } else if (fields.size() == 2) {
      const std::optional<double> first = ParseSeconds(fields[0]);
      const std::optional<double> second = ParseSeconds(fields[1]);
      if (second && !first) {
        name = fields[0];
        t_s = second;
      } else if (first && !second) {
        name = fields[1];
        t_s = first;
      } else {
        throw std::invalid_argument(LineRef(source, line_number, line) +
                                    ": need exactly one file name and one time" + kFormatHelp);
      }
    } else {
      throw std::invalid_argument(LineRef(source, line_number, line) + ": " +
                                  std::to_string(fields.size()) + " fields" + kFormatHelp);
    }
    // Unix time in seconds is ~1.7e9; a value this large is ms, us or ns written as seconds.
    constexpr double kMaxPlausibleSeconds = 1e11;
    if (std::abs(*t_s) >= kMaxPlausibleSeconds) {
      throw std::invalid_argument(LineRef(source, line_number, line) +
                                  ": time is too large for seconds (milli/micro/nanoseconds?); "
                                  "times.txt is in seconds, convert it or use a EuRoC data.csv "
                                  "for nanoseconds");
    }
    const bool is_pair = !name.empty();
    if (pair_form && *pair_form != is_pair) {
      throw std::invalid_argument(LineRef(source, line_number, line) +
                                  ": mixes single-time lines and '<file name> <t>' lines; use "
                                  "one form for the whole file");
    }
    pair_form = is_pair;
    if (is_pair) table.names.push_back(name);
    table.t_s.push_back(*t_s);
    table.line_numbers.push_back(line_number);
  }
  return table;
}

TimestampTable ParseEurocDataCsv(std::istream& in, const std::string& source) {
  static const char* const kFormatHelp =
      "; expected '<timestamp ns>,<file name>' as in EuRoC (header '#timestamp [ns],filename')";
  TimestampTable table;
  std::string raw;
  int line_number = 0;
  while (std::getline(in, raw)) {
    ++line_number;
    const std::string line = Trim(raw);
    if (line.empty() || line[0] == '#') continue;
    const size_t comma = line.find(',');
    if (comma == std::string::npos || line.find(',', comma + 1) != std::string::npos) {
      throw std::invalid_argument(LineRef(source, line_number, line) +
                                  ": need exactly two comma-separated fields" + kFormatHelp);
    }
    const std::string time_field = Trim(line.substr(0, comma));
    const std::string name = Trim(line.substr(comma + 1));
    const std::optional<long long> t_ns = ParseNanoseconds(time_field);
    if (!t_ns) {
      throw std::invalid_argument(LineRef(source, line_number, line) + ": '" + time_field +
                                  "' is not an integer nanosecond timestamp" + kFormatHelp);
    }
    if (name.empty()) {
      throw std::invalid_argument(LineRef(source, line_number, line) + ": empty file name" +
                                  kFormatHelp);
    }
    table.names.push_back(name);
    table.t_s.push_back(NanosecondsToSeconds(*t_ns));
    table.line_numbers.push_back(line_number);
  }
  return table;
}

double NanosecondsToSeconds(long long t_ns) {
  constexpr long long kNsPerS = 1000000000LL;
  return static_cast<double>(t_ns / kNsPerS) + static_cast<double>(t_ns % kNsPerS) * 1e-9;
}

std::optional<double> TimestampFromFileName(const std::string& file_name) {
  const size_t dot = file_name.rfind('.');
  const std::string stem = dot == std::string::npos ? file_name : file_name.substr(0, dot);
  if (AllDigits(stem)) {
    if (static_cast<int>(stem.size()) < kMinNanosecondDigits) return std::nullopt;
    const std::optional<long long> t_ns = ParseNanoseconds(stem);
    if (!t_ns) return std::nullopt;  // beyond int64: not a nanosecond timestamp
    return NanosecondsToSeconds(*t_ns);
  }
  const size_t stem_dot = stem.find('.');
  if (stem_dot != std::string::npos && AllDigits(stem.substr(0, stem_dot)) &&
      AllDigits(stem.substr(stem_dot + 1))) {
    return ParseSeconds(stem);
  }
  return std::nullopt;
}

void CheckStrictlyIncreasing(const std::vector<double>& t_s, const std::vector<std::string>& labels,
                             const std::string& source) {
  for (size_t i = 1; i < t_s.size(); ++i) {
    if (t_s[i] > t_s[i - 1]) continue;
    std::ostringstream message;
    message.precision(17);
    message << source << ": timestamp of " << labels[i] << " (t = " << t_s[i] << " s) "
            << (t_s[i] == t_s[i - 1] ? "duplicates" : "is before") << " that of " << labels[i - 1]
            << " (t = " << t_s[i - 1]
            << " s); timestamps must strictly increase in file order, fix or remove the entry";
    throw std::invalid_argument(message.str());
  }
}

}  // namespace aperture::perception
