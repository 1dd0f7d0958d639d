#pragma once
// Natural ("human") ordering of file names so that an image sequence plays in capture order:
// "frame2.png" < "frame10.png", "img_9" < "img_010".
//
// Rules: names are split into runs of decimal digits and runs of other characters. Digit runs
// compare by numeric value (any length, no overflow: leading zeros are stripped and the digit
// strings compared by length, then lexicographically). Other runs compare character by character,
// ignoring ASCII case. A digit run sorts before a non-digit run at the same position. When two
// names are equal under these rules ("img01" vs "img1", "A" vs "a") the plain byte-wise string
// order decides, so the order is a strict weak ordering and deterministic.
#include <string>
#include <vector>

namespace aperture::perception {

// True when `a` sorts before `b` in natural order.
bool NaturalLess(const std::string& a, const std::string& b);

// Sorts `names` in place in natural order.
void NaturalSort(std::vector<std::string>& names);

}  // namespace aperture::perception
