#include "perception/io/natural_sort.h"

#include <algorithm>
#include <cctype>

namespace aperture::perception {
namespace {

bool IsDigit(char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; }

char Lower(char c) { return static_cast<char>(std::tolower(static_cast<unsigned char>(c))); }

// Compares the digit runs a[ia, ea) and b[ib, eb) by value: -1, 0 or +1.
int CompareDigitRuns(const std::string& a, size_t ia, size_t ea, const std::string& b, size_t ib,
                     size_t eb) {
  while (ia < ea && a[ia] == '0') ++ia;
  while (ib < eb && b[ib] == '0') ++ib;
  const size_t length_a = ea - ia;
  const size_t length_b = eb - ib;
  if (length_a != length_b) return length_a < length_b ? -1 : 1;
  const int c = a.compare(ia, length_a, b, ib, length_b);
  return c < 0 ? -1 : (c > 0 ? 1 : 0);
}

// Natural comparison without the final byte-wise tie break: -1, 0 or +1.
int NaturalCompare(const std::string& a, const std::string& b) {
  size_t i = 0;
  size_t j = 0;
  while (i < a.size() && j < b.size()) {
    const bool digit_a = IsDigit(a[i]);
    const bool digit_b = IsDigit(b[j]);
    if (digit_a && digit_b) {
      size_t end_a = i;
      size_t end_b = j;
      while (end_a < a.size() && IsDigit(a[end_a])) ++end_a;
      while (end_b < b.size() && IsDigit(b[end_b])) ++end_b;
      const int c = CompareDigitRuns(a, i, end_a, b, j, end_b);
      if (c != 0) return c;
      i = end_a;
      j = end_b;
    } else if (digit_a != digit_b) {
      return digit_a ? -1 : 1;
    } else {
      const char ca = Lower(a[i]);
      const char cb = Lower(b[j]);
      if (ca != cb) return ca < cb ? -1 : 1;
      ++i;
      ++j;
    }
  }
  if (i < a.size()) return 1;
  if (j < b.size()) return -1;
  return 0;
}

}  // namespace

bool NaturalLess(const std::string& a, const std::string& b) {
  const int c = NaturalCompare(a, b);
  if (c != 0) return c < 0;
  return a < b;
}

void NaturalSort(std::vector<std::string>& names) {
  std::sort(names.begin(), names.end(), NaturalLess);
}

}  // namespace aperture::perception
