#include "core/json_node.h"

#include <cmath>
#include <regex>
#include <sstream>

#include "core/error.h"
#include "core/input_file.h"
#include "core/printable.h"

namespace kasha {

JsonNode::JsonNode(std::shared_ptr<const nlohmann::json> root, const nlohmann::json* json,
                   std::string file, std::filesystem::path base_dir, std::string path)
    : root_(std::move(root)),
      json_(json),
      file_(std::move(file)),
      base_dir_(std::move(base_dir)),
      path_(std::move(path)),
      read_keys_(std::make_shared<std::set<std::string>>()) {}

// JSON Pointer escaping (RFC 6901) keeps paths unambiguous for keys holding '/' or '~'.
std::string escape_pointer(const std::string& key) {
  std::string out;
  for (char c : key) {
    if (c == '~')
      out += "~0";
    else if (c == '/')
      out += "~1";
    else
      out += c;
  }
  return out;
}

namespace {

// Follows the parser through the document so that a key repeated in one object is refused with
// its JSON path: nlohmann keeps the last one silently, and a scene would then not say what it
// means.
class DuplicateKeyCheck {
 public:
  // `where` starts the message: the file's name or the option, already printable.
  explicit DuplicateKeyCheck(const std::string& where) : where_(where) {}

  bool operator()(int, nlohmann::json::parse_event_t event, nlohmann::json& parsed) {
    using E = nlohmann::json::parse_event_t;
    switch (event) {
      case E::object_start:
      case E::array_start:
        element();
        frames_.push_back({event == E::object_start, {}, {}, -1});
        break;
      case E::key: {
        Frame& f = frames_.back();
        f.key = parsed.get<std::string>();
        if (!f.keys.insert(f.key).second)
          throw Error(where_ + ": " + printable(pointer()) + ": duplicate key \"" +
                      printable(f.key) + "\" (a key may appear once in an object)");
        break;
      }
      case E::value:
        element();
        break;
      case E::object_end:
      case E::array_end:
        frames_.pop_back();
        break;
    }
    return true;
  }

 private:
  struct Frame {
    bool object;
    std::set<std::string> keys;
    std::string key;  // the key being read, in an object
    long index;       // the element being read, in an array
  };
  // A value starts: in an array, that is its next element.
  void element() {
    if (!frames_.empty() && !frames_.back().object) ++frames_.back().index;
  }
  std::string pointer() const {
    std::string out;
    for (const Frame& f : frames_)
      out += "/" + (f.object ? escape_pointer(f.key) : std::to_string(f.index));
    return out;
  }

  std::string where_;
  std::vector<Frame> frames_;
};

}  // namespace

// The document in `text`, every key once; syntax errors and nlohmann's other exceptions become
// one line starting with `where` (already printable).
static nlohmann::json parse_document(const std::string& text, const std::string& where) {
  try {
    return nlohmann::json::parse(text, DuplicateKeyCheck(where));
  } catch (const nlohmann::json::parse_error& e) {
    // nlohmann's message reads "[json.exception.parse_error.101] parse error at line L, column C:
    // ..."; its "last read" part may hold input bytes, hence printable().
    // Worded as kasha words it: "malformed JSON at line L, column C: DETAIL (reading a value)".
    std::string what = e.what();
    size_t at = what.find("parse error");
    if (at != std::string::npos) what = what.substr(at);
    static const std::regex syntax(
        R"(^parse error at (line \d+, column \d+): syntax error while parsing (.*?) - (.*)$)");
    std::smatch m;
    if (std::regex_match(what, m, syntax))
      throw Error(where + ": malformed JSON at " + m[1].str() + ": " + printable(m[3].str()) +
                  " (reading " + (m[2] == "value" ? "a value" : "the " + m[2].str()) + ")");
    throw Error(where + ": malformed JSON: " + printable(what));
  } catch (const nlohmann::json::exception& e) {
    // A number beyond double range ("1e400") is an out_of_range error: nlohmann names the number
    // but not its place. Its "[json.exception...]" prefix is cut.
    std::string what = e.what();
    size_t at = what.find("] ");
    throw Error(where + ": malformed JSON: " +
                printable(at == std::string::npos ? what : what.substr(at + 2)));
  }
}

JsonNode JsonNode::load_file(const std::filesystem::path& file) {
  const std::string text = read_input_file(file.string(), kMaxTextInputBytes);
  auto root =
      std::make_shared<const nlohmann::json>(parse_document(text, printable(file.string())));
  std::filesystem::path base = file.parent_path();
  return JsonNode(root, root.get(), file.string(), base.empty() ? "." : base, "");
}

JsonNode JsonNode::parse_text(const std::string& text, const std::string& where,
                              const std::filesystem::path& base_dir) {
  auto root = std::make_shared<const nlohmann::json>(parse_document(text, printable(where)));
  return JsonNode(root, root.get(), where, base_dir, "");
}

JsonNode JsonNode::from_json(nlohmann::json document, const std::string& file) {
  auto root = std::make_shared<const nlohmann::json>(std::move(document));
  std::filesystem::path base = std::filesystem::path(file).parent_path();
  return JsonNode(root, root.get(), file, base.empty() ? "." : base, "");
}

JsonNode JsonNode::from_json(nlohmann::json document, const std::string& file,
                             std::shared_ptr<const JsonSourceMap> sources) {
  JsonNode node = from_json(std::move(document), file);
  node.sources_ = std::move(sources);
  return node;
}

std::string JsonNode::where() const {
  return where_at(path_);
}

std::string JsonNode::where_at(const std::string& path) const {
  if (sources_) {
    // The pointer and its parents, deepest first.
    for (std::string p = path; !p.empty(); p.erase(p.rfind('/'))) {
      auto s = sources_->find(p);
      if (s != sources_->end()) return s->second;
    }
  }
  return file_ + ": " + (path.empty() ? "/" : path);
}

// The whole line is escaped: keys and string values from the document reach `why` and the path.
void JsonNode::fail(const std::string& why) const {
  throw Error(printable(where() + ": " + why));
}

std::string JsonNode::type_name() const {
  switch (json_->type()) {
    case nlohmann::json::value_t::null:
      return "null";
    case nlohmann::json::value_t::object:
      return "an object";
    case nlohmann::json::value_t::array:
      return "an array";
    case nlohmann::json::value_t::string:
      return "a string";
    case nlohmann::json::value_t::boolean:
      return "a boolean";
    default:
      return "a number";
  }
}

void JsonNode::expect_object() const {
  if (!json_->is_object()) fail("expected an object, got " + type_name());
}

bool JsonNode::has(const std::string& key) const {
  expect_object();
  return json_->contains(key);
}

std::optional<JsonNode> JsonNode::find(const std::string& key) const {
  expect_object();
  auto it = json_->find(key);
  if (it == json_->end()) return std::nullopt;
  read_keys_->insert(key);
  JsonNode child(root_, &*it, file_, base_dir_, path_ + "/" + escape_pointer(key));
  child.sources_ = sources_;
  return child;
}

JsonNode JsonNode::at(const std::string& key) const {
  auto node = find(key);
  if (!node) fail("missing required key \"" + key + "\"");
  return *node;
}

std::vector<std::string> JsonNode::keys() const {
  expect_object();
  std::vector<std::string> out;
  for (auto it = json_->begin(); it != json_->end(); ++it) {
    out.push_back(it.key());
    read_keys_->insert(it.key());
  }
  return out;
}

size_t JsonNode::size() const {
  if (!json_->is_array()) fail("expected an array, got " + type_name());
  return json_->size();
}

JsonNode JsonNode::operator[](size_t index) const {
  if (index >= size()) fail("index " + std::to_string(index) + " out of range");
  JsonNode child(root_, &(*json_)[index], file_, base_dir_, path_ + "/" + std::to_string(index));
  child.sources_ = sources_;
  return child;
}

double JsonNode::number() const {
  if (!json_->is_number()) fail("expected a number, got " + type_name());
  double v = json_->get<double>();
  if (!std::isfinite(v)) fail("number is not finite");
  return v;
}

double JsonNode::number_in(double lo, double hi) const {
  double v = number();
  if (v < lo || v > hi) {
    std::ostringstream msg;
    msg << "value " << v << " is outside [" << lo << ", " << hi << "]";
    fail(msg.str());
  }
  return v;
}

int JsonNode::integer_in(int lo, int hi) const {
  double v = number();
  if (v != std::floor(v)) fail("expected an integer, got " + json_->dump());
  if (v < lo || v > hi)
    fail("value " + json_->dump() + " is outside [" + std::to_string(lo) + ", " +
         std::to_string(hi) + "]");
  return static_cast<int>(v);
}

std::string JsonNode::string() const {
  if (!json_->is_string()) fail("expected a string, got " + type_name());
  return json_->get<std::string>();
}

bool JsonNode::boolean() const {
  if (!json_->is_boolean()) fail("expected true or false, got " + type_name());
  return json_->get<bool>();
}

std::vector<double> JsonNode::numbers() const {
  std::vector<double> out(size());
  // Read straight from the document: a node per element (its path built as text) made a
  // million-vertex "triangles" shape take seconds. A bad element is reported through its node.
  for (size_t i = 0; i < out.size(); ++i) {
    const nlohmann::json& e = (*json_)[i];
    const double v = e.is_number() ? e.get<double>() : 0.0;
    out[i] = e.is_number() && std::isfinite(v) ? v : (*this)[i].number();
  }
  return out;
}

std::array<double, 3> JsonNode::vec3() const {
  if (size() != 3)
    fail("expected an array of 3 numbers, got " + std::to_string(size()) + " elements");
  return {(*this)[0].number(), (*this)[1].number(), (*this)[2].number()};
}

void JsonNode::finish() const {
  expect_object();
  for (auto it = json_->begin(); it != json_->end(); ++it)
    if (!read_keys_->count(it.key()))
      throw Error(printable(where_at(path_ + "/" + escape_pointer(it.key())) + ": unknown key"));
}

std::filesystem::path JsonNode::file_path() const {
  std::filesystem::path file(string());
  if (file.empty()) fail("empty file name");
  return file.is_relative() ? base_dir_ / file : file;
}

}  // namespace kasha
