#include "core/printable.h"

#include <cctype>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>

namespace kasha {

// The length of the valid UTF-8 sequence at s[i], or 0 when it is not one (overlong forms,
// surrogates and code points above U+10FFFF are invalid).
static size_t utf8_length(std::string_view s, size_t i) {
  const auto byte = [&](size_t k) { return static_cast<unsigned char>(s[k]); };
  const unsigned char c = byte(i);
  size_t n = c < 0x80 ? 1 : (c >> 5) == 0x6 ? 2 : (c >> 4) == 0xe ? 3 : (c >> 3) == 0x1e ? 4 : 0;
  if (n == 0 || i + n > s.size()) return 0;
  unsigned cp = n == 1 ? c : n == 2 ? (c & 0x1f) : n == 3 ? (c & 0x0f) : (c & 0x07);
  for (size_t k = 1; k < n; ++k) {
    if ((byte(i + k) >> 6) != 0x2) return 0;
    cp = (cp << 6) | (byte(i + k) & 0x3f);
  }
  static const unsigned least[] = {0, 0, 0x80, 0x800, 0x10000};
  if (cp < least[n] || cp > 0x10ffff || (cp >= 0xd800 && cp <= 0xdfff)) return 0;
  return n;
}

bool valid_utf8(std::string_view s) {
  for (size_t i = 0; i < s.size();) {
    size_t n = utf8_length(s, i);
    if (n == 0) return false;
    i += n;
  }
  return true;
}

std::string printable(std::string_view s) {
  std::string out;
  for (size_t i = 0; i < s.size();) {
    const unsigned char c = static_cast<unsigned char>(s[i]);
    size_t n = utf8_length(s, i);
    if (n > 1) {
      out.append(s.substr(i, n));
      i += n;
      continue;
    }
    if (n == 1 && c >= 0x20 && c != 0x7f && c != '\\') {
      out += static_cast<char>(c);
    } else if (c == '\\') {
      out += "\\\\";
    } else {
      char hex[8];
      std::snprintf(hex, sizeof hex, "\\x%02X", c);
      out += hex;
    }
    ++i;
  }
  return out;
}

std::string as_one_line(const std::string& message) {
  std::string out;
  for (size_t i = 0; i < message.size();) {
    auto special = [&](size_t k) {
      const unsigned char c = static_cast<unsigned char>(message[k]);
      return c < 0x20 || c >= 0x7f;
    };
    size_t j = i;
    while (j < message.size() && special(j)) ++j;
    if (j == i) {
      out += message[i++];
    } else {  // a run of control or non-ASCII bytes: printable() escapes only what must be
      out += printable(std::string_view(message).substr(i, j - i));
      i = j;
    }
  }
  return out;
}

std::string json_text(std::string_view bytes) {
  if (valid_utf8(bytes) && bytes.find('\\') == std::string_view::npos) return std::string(bytes);
  return printable(bytes);
}

std::string error_words(const std::error_code& ec) {
  std::string words = ec.message();
  // strerror's capital ("File name too long") would read as a new sentence after "WHERE: ".
  if (words.size() > 1 && std::isupper(static_cast<unsigned char>(words[0])) &&
      !std::isupper(static_cast<unsigned char>(words[1])))
    words[0] = static_cast<char>(std::tolower(static_cast<unsigned char>(words[0])));
  return words;
}

std::string library_error_text(const std::exception& e) {
  if (const auto* fs = dynamic_cast<const std::filesystem::filesystem_error*>(&e))
    return printable(fs->path1().empty() ? std::string("a file") : fs->path1().string()) + ": " +
           error_words(fs->code());
  std::string what = e.what();
  if (dynamic_cast<const nlohmann::json::exception*>(&e)) {
    const size_t at = what.find("] ");
    if (what.rfind("[json.exception.", 0) == 0 && at != std::string::npos)
      what = what.substr(at + 2);
  }
  return as_one_line(what);
}

}  // namespace kasha
