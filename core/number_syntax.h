// Strict decimal number syntax for the file readers: std::strtod alone also accepts
// hexadecimal ("0x10"), "inf", "nan", leading spaces and more, none of which a scene or
// experiment file means as a number.
#pragma once

#include <string_view>

namespace dp::core {

// [+-] (digits [. [digits]] | . digits) [(e|E) [+-] digits], nothing else.
inline bool is_decimal_number(std::string_view s) {
  size_t i = 0;
  auto digits = [&] {
    const size_t start = i;
    while (i < s.size() && s[i] >= '0' && s[i] <= '9') ++i;
    return i - start;
  };
  if (i < s.size() && (s[i] == '+' || s[i] == '-')) ++i;
  size_t mantissa = digits();
  if (i < s.size() && s[i] == '.') {
    ++i;
    mantissa += digits();
  }
  if (mantissa == 0) return false;
  if (i < s.size() && (s[i] == 'e' || s[i] == 'E')) {
    ++i;
    if (i < s.size() && (s[i] == '+' || s[i] == '-')) ++i;
    if (digits() == 0) return false;
  }
  return i == s.size();
}

}  // namespace dp::core
