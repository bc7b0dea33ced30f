#include "spectrum/spectrum_argument.h"

#include <cerrno>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/json_node.h"
#include "core/printable.h"
#include "spectrum/builtin_spectra.h"
#include "spectrum/spectrum_parser.h"

namespace kasha {

SpectrumPtr parse_spectrum_argument(const std::string& text, const std::string& option) {
  if (SpectrumPtr s = builtin_spectrum(text)) return s;
  const std::string where = option + " " + printable(text);
  // The error_code overload: a name too long or a link loop is this option's error, not
  // std::filesystem's text (and a long JSON value is no file name at all).
  std::error_code ec;
  const std::filesystem::file_status st = std::filesystem::status(text, ec);
  if (std::filesystem::is_regular_file(st)) return read_spectrum_csv(text);
  if (nlohmann::json::accept(text)) {
    // As strict as a file (duplicate keys refused); relative "csv" paths resolve against the
    // working directory, as a file name given on the command line does.
    return parse_spectrum(JsonNode::parse_text(text, option + " " + text, ""));
  }
  if (std::filesystem::exists(st)) return read_spectrum_csv(text);  // says what it is instead
  if (ec && ec != std::errc::no_such_file_or_directory && ec != std::errc::not_a_directory)
    throw Error(where + ": cannot open file: " + error_words(ec));
  std::string known;
  for (const auto& n : builtin_spectrum_names()) known += (known.empty() ? "" : ", ") + n;
  throw Error(where + ": not a built-in spectrum (" + known +
              "), an existing CSV file or a JSON spectrum value");
}

}  // namespace kasha
