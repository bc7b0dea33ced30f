#pragma once
// The tokens of a pbrt-v4 scene file (docs/pbrt-import.md): words, numbers, quoted strings and
// brackets, with `#` comments to the end of the line dropped. Each token knows its line, so every
// message can say FILE:LINE.
#include <memory>
#include <string>
#include <string_view>

namespace kasha {

// Where a token stood: "scene.pbrt:12".
struct PbrtLocation {
  std::shared_ptr<const std::string> file;  // as named to the user
  int line = 0;
  std::string str() const;
};

struct PbrtToken {
  enum Kind { kEnd, kWord, kString, kOpen, kClose } kind = kEnd;
  std::string text;  // a word as written (a directive, a number, true/false), a string unquoted
  PbrtLocation where;
};

class PbrtTokenizer {
 public:
  // `text` is the file's content, `file` its name in messages.
  PbrtTokenizer(std::string text, const std::string& file);
  // The next token, or kEnd; a string without its closing quote, a control byte or a byte that
  // no token may hold is an Error naming the line.
  PbrtToken next();
  // Puts one token back (the parameter list reader looks one token ahead).
  void put_back(PbrtToken token);
  const std::string& file() const { return *file_; }

 private:
  std::string text_;
  std::shared_ptr<const std::string> file_;
  size_t pos_ = 0;
  int line_ = 1;
  bool has_back_ = false;
  PbrtToken back_;
};

}  // namespace kasha
