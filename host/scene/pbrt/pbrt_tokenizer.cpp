#include "scene/pbrt/pbrt_tokenizer.h"

#include "core/error.h"
#include "core/printable.h"

namespace kasha {

std::string PbrtLocation::str() const {
  return (file ? *file : std::string("?")) + ":" + std::to_string(line);
}

PbrtTokenizer::PbrtTokenizer(std::string text, const std::string& file)
    : text_(std::move(text)), file_(std::make_shared<const std::string>(file)) {}

void PbrtTokenizer::put_back(PbrtToken token) {
  back_ = std::move(token);
  has_back_ = true;
}

PbrtToken PbrtTokenizer::next() {
  if (has_back_) {
    has_back_ = false;
    return std::move(back_);
  }
  const auto fail = [&](const std::string& why) {
    throw Error(PbrtLocation{file_, line_}.str() + ": " + why);
  };
  while (pos_ < text_.size()) {
    const char c = text_[pos_];
    if (c == '\n') {
      ++line_;
      ++pos_;
    } else if (c == ' ' || c == '\t' || c == '\r') {
      ++pos_;
    } else if (c == '#') {
      while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
    } else {
      break;
    }
  }
  PbrtToken t;
  t.where = PbrtLocation{file_, line_};
  if (pos_ >= text_.size()) return t;
  const char c = text_[pos_];
  if (c == '[' || c == ']') {
    ++pos_;
    t.kind = c == '[' ? PbrtToken::kOpen : PbrtToken::kClose;
    t.text = std::string(1, c);
    return t;
  }
  if (c == '"') {
    // pbrt-v4's escapes: \b \f \n \r \t \\ \' \"; a string ends on its line.
    ++pos_;
    t.kind = PbrtToken::kString;
    for (;;) {
      if (pos_ >= text_.size() || text_[pos_] == '\n') fail("a string without its closing quote");
      char s = text_[pos_++];
      if (s == '"') break;
      if (s == '\\') {
        if (pos_ >= text_.size()) fail("a string without its closing quote");
        char e = text_[pos_++];
        switch (e) {
          case 'b': s = '\b'; break;
          case 'f': s = '\f'; break;
          case 'n': s = '\n'; break;
          case 'r': s = '\r'; break;
          case 't': s = '\t'; break;
          case '\\': case '\'': case '"': s = e; break;
          default: fail("unknown escape \\" + printable(std::string(1, e)) + " in a string");
        }
      }
      t.text += s;
    }
    return t;
  }
  t.kind = PbrtToken::kWord;
  const size_t start = pos_;
  while (pos_ < text_.size()) {
    const unsigned char w = static_cast<unsigned char>(text_[pos_]);
    if (w == ' ' || w == '\t' || w == '\r' || w == '\n' || w == '"' || w == '[' || w == ']' ||
        w == '#')
      break;
    if (w < 0x20 || w == 0x7f)
      fail("a control byte " + printable(std::string(1, static_cast<char>(w))) + " in the file");
    ++pos_;
  }
  t.text = text_.substr(start, pos_ - start);
  return t;
}

}  // namespace kasha
