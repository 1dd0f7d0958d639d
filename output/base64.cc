#include "output/base64.h"

#include <array>
#include <stdexcept>

namespace aperture::output {
namespace {

constexpr char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";

std::array<int, 256> MakeDecodeTable() {
  std::array<int, 256> table;
  table.fill(-1);
  for (int i = 0; i < 64; ++i) table[static_cast<unsigned char>(kAlphabet[i])] = i;
  return table;
}

}  // namespace

std::string Base64Encode(const std::uint8_t* data, std::size_t size) {
  std::string text;
  text.reserve((size + 2) / 3 * 4);
  std::size_t i = 0;
  for (; i + 2 < size; i += 3) {
    const std::uint32_t group = (data[i] << 16) | (data[i + 1] << 8) | data[i + 2];
    text += kAlphabet[(group >> 18) & 63];
    text += kAlphabet[(group >> 12) & 63];
    text += kAlphabet[(group >> 6) & 63];
    text += kAlphabet[group & 63];
  }
  const std::size_t rest = size - i;
  if (rest > 0) {
    const std::uint32_t group = (data[i] << 16) | (rest == 2 ? data[i + 1] << 8 : 0);
    text += kAlphabet[(group >> 18) & 63];
    text += kAlphabet[(group >> 12) & 63];
    text += rest == 2 ? kAlphabet[(group >> 6) & 63] : '=';
    text += '=';
  }
  return text;
}

std::string Base64Encode(const std::vector<std::uint8_t>& data) {
  return Base64Encode(data.data(), data.size());
}

std::vector<std::uint8_t> Base64Decode(const std::string& text) {
  static const std::array<int, 256> kDecode = MakeDecodeTable();
  if (text.size() % 4 != 0) {
    throw std::invalid_argument("base64 text of length " + std::to_string(text.size()) +
                                " is not a multiple of 4");
  }
  std::vector<std::uint8_t> data;
  data.reserve(text.size() / 4 * 3);
  for (std::size_t i = 0; i < text.size(); i += 4) {
    const bool last = i + 4 == text.size();
    int padding = 0;
    std::uint32_t group = 0;
    for (std::size_t k = 0; k < 4; ++k) {
      const char c = text[i + k];
      int value;
      if (c == '=' && last && k >= 2 && (k == 3 || text[i + 3] == '=')) {
        ++padding;
        value = 0;
      } else {
        value = kDecode[static_cast<unsigned char>(c)];
        if (value < 0 || padding > 0) {
          throw std::invalid_argument("invalid base64 character '" + std::string(1, c) +
                                      "' at offset " + std::to_string(i + k));
        }
      }
      group = (group << 6) | static_cast<std::uint32_t>(value);
    }
    data.push_back(static_cast<std::uint8_t>(group >> 16));
    if (padding < 2) data.push_back(static_cast<std::uint8_t>(group >> 8));
    if (padding < 1) data.push_back(static_cast<std::uint8_t>(group));
  }
  return data;
}

}  // namespace aperture::output
