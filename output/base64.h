#pragma once
// Base64 (RFC 4648, standard alphabet, '=' padding) for embedding binary data in HTML/JSON.
#include <cstdint>
#include <string>
#include <vector>

namespace aperture::output {

std::string Base64Encode(const std::uint8_t* data, std::size_t size);
std::string Base64Encode(const std::vector<std::uint8_t>& data);
// std::invalid_argument on a length that is not a multiple of 4, a character outside the alphabet
// or misplaced padding.
std::vector<std::uint8_t> Base64Decode(const std::string& text);

}  // namespace aperture::output
