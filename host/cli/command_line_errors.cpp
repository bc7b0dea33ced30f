#include "cli/command_line_errors.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <regex>
#include <set>
#include <sstream>

#include "core/printable.h"
#include "opencl/device_list.h"

namespace kasha::cli {

namespace {

// Bounds as a reader writes them: %g, so DBL_MAX is 1.79769e+308, not 309 digits.
std::string number_text(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

std::string in_quotes(const std::string& value) {
  return "\"" + printable(value) + "\"";
}

// The whole text as a double (strtod: also nan, inf, hex); false if anything is left over.
bool parse_number(const std::string& text, double& v) {
  if (text.empty()) return false;
  char* end = nullptr;
  v = std::strtod(text.c_str(), &end);
  return end == text.c_str() + text.size();
}

// "" if `text` is a finite number (stored in v), else what is wrong with it.
std::string finite_problem(const std::string& text, double& v) {
  if (!parse_number(text, v)) return in_quotes(text) + " is not a number";
  if (!std::isfinite(v)) return printable(text) + " is not a finite number";
  return "";
}

std::string join(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<size_t> row(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    size_t diagonal = row[0];
    row[0] = i;
    for (size_t j = 1; j <= b.size(); ++j) {
      size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] != b[j - 1])});
      diagonal = up;
    }
  }
  return row[b.size()];
}

// " (did you mean X?)" for the nearest of `names` within a typo or two, else "".
std::string suggestion(const std::string& given, const std::vector<std::string>& names) {
  std::string best;
  size_t best_distance = 3;
  for (const std::string& n : names) {
    size_t d = edit_distance(given, n);
    if (d < best_distance && d < n.size()) best = n, best_distance = d;
  }
  return best.empty() ? "" : " (did you mean " + best + "?)";
}

// The subcommand the parse error belongs to: the deepest one given.
const CLI::App* deepest_parsed(const CLI::App& app) {
  const CLI::App* at = &app;
  while (!at->get_subcommands().empty()) at = at->get_subcommands().front();
  return at;
}

std::vector<std::string> subcommand_names(const CLI::App& app) {
  std::vector<std::string> names;
  for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; }))
    names.push_back(sub->get_name());
  return names;
}

std::vector<std::string> option_names(const CLI::App& app) {
  std::vector<std::string> names;
  for (const CLI::Option* opt : app.get_options()) {
    for (const std::string& n : opt->get_lnames()) names.push_back("--" + n);
    for (const std::string& n : opt->get_snames()) names.push_back("-" + n);
  }
  return names;
}

// A value must be there: empty text is refused (an empty -o or --lamp would otherwise read as not
// given), and so is one that is another option of the command (`--lamp --png`, `--time= -o`):
// CLI11 takes the next argument as a required value whatever it looks like.
std::string missing_value(const std::string& text, const std::vector<std::string>& option_names) {
  if (text.empty()) return "the value is empty";
  if (std::find(option_names.begin(), option_names.end(), text) != option_names.end())
    return "a value is required (" + text + " is an option)";
  return "";
}

// "kasha render", for "see kasha render --help".
std::string command_name(const CLI::App& app) {
  const CLI::App* parent = app.get_parent();
  return parent == nullptr ? "kasha" : command_name(*parent) + " " + app.get_name();
}

const CLI::Option* find_option(const CLI::App& app, const std::string& name) {
  for (const CLI::Option* opt : app.get_options())
    if (opt->get_name() == name || opt->check_name(name)) return opt;
  return nullptr;
}

std::string value_kind(const CLI::Option* opt) {
  if (opt && opt->get_expected_max() == 0) return "true or false (a flag)";
  std::string type = opt ? opt->get_type_name() : "";
  type = type.substr(0, type.find(':'));
  if (type == "FLOAT") return "a number";
  if (type == "INT") return "an integer";
  if (type == "UINT") return "a non-negative integer";
  return "a value";
}

std::string unexpected_argument(const CLI::App& app, const std::string& arg) {
  const std::string where = command_name(app);
  if (arg.size() > 1 && arg[0] == '-')
    return printable(arg) + ": unknown option of " + where + suggestion(arg, option_names(app));
  return printable(arg) + ": unexpected argument to " + where;
}

// A missing subcommand or required option; nullopt for a message of another shape.
std::optional<std::string> required_message(const CLI::App& root, const CLI::App& at,
                                            const std::string& message) {
  if (&at == &root) {  // no subcommand: none given, or an unknown one
    const std::vector<std::string> extra = root.remaining();
    const std::vector<std::string> names = subcommand_names(root);
    if (extra.empty())
      return "command line: give a subcommand: " + join(names) + " (see kasha --help)";
    if (extra[0].size() > 1 && extra[0][0] == '-') return unexpected_argument(root, extra[0]);
    return printable(extra[0]) + ": unknown subcommand" + suggestion(extra[0], names) +
           "; the subcommands: " + join(names);
  }
  std::smatch m;
  static const std::regex required(R"(^(\S+) is required$)");
  if (std::regex_match(message, m, required))
    return m[1].str() + ": required (see " + command_name(at) + " --help)";
  // Subcommand counts and option groups: kasha's commands declare neither, but a CLI11 that
  // raised them would still be worded as kasha words it.
  static const std::regex subcommands(
      R"(^(A subcommand is required|Requires at least \d+ subcommands)$)");
  static const std::regex exactly(R"(^Exactly 1 option from \[(.*)\].*$)");
  static const std::regex at_least_one(R"(^At least 1 option from \[(.*)\] is required$)");
  static const std::regex at_least(R"(^Requires at least (\d+) options .* from \[(.*)\]$)");
  static const std::regex at_most(R"(^Requires at most (\d+) options .* from \[(.*)\]$)");
  if (std::regex_match(message, m, subcommands))
    return command_name(at) + ": give a subcommand (see " + command_name(at) + " --help)";
  if (std::regex_match(message, m, exactly))
    return command_name(at) + ": give exactly one of " + m[1].str();
  if (std::regex_match(message, m, at_least_one))
    return command_name(at) + ": give at least one of " + m[1].str();
  if (std::regex_match(message, m, at_least))
    return command_name(at) + ": give at least " + m[1].str() + " of " + m[2].str();
  if (std::regex_match(message, m, at_most))
    return command_name(at) + ": give at most " + m[1].str() + " of " + m[2].str();
  return std::nullopt;
}

// Arguments left over: the first one named; nullopt when none can be found.
std::optional<std::string> extras_message(const CLI::App& root, const CLI::App& at,
                                          const std::string& message) {
  if (!at.remaining().empty()) return unexpected_argument(at, at.remaining()[0]);
  if (!root.remaining(true).empty()) return unexpected_argument(root, root.remaining(true)[0]);
  std::smatch m;
  static const std::regex listed(R"(^The following arguments? (was|were) not expected: (\S+).*$)");
  if (std::regex_match(message, m, listed)) return unexpected_argument(at, m[2].str());
  return std::nullopt;
}

// A value that is not of the option's kind, or given to a flag.
std::optional<std::string> conversion_message(const CLI::App& at, const std::string& message) {
  std::smatch m;
  static const std::regex could_not(R"(^Could not convert: (\S+) = (.*)$)");
  static const std::regex not_allowed(R"(^The value (.*) is not an allowed value for (\S+)$)");
  static const std::regex flag(R"(^(\S+): (too many inputs for a flag|Should be true/false.*)$)");
  if (std::regex_match(message, m, could_not)) {
    const std::string missing = missing_value(m[2], option_names(at));
    if (!missing.empty()) return m[1].str() + ": " + missing;
    return m[1].str() + ": " + in_quotes(m[2]) + " is not " + value_kind(find_option(at, m[1]));
  }
  if (std::regex_match(message, m, not_allowed))
    return m[2].str() + ": " + in_quotes(m[1]) + " is not " + value_kind(find_option(at, m[2]));
  if (std::regex_match(message, m, flag)) return m[1].str() + ": a flag takes no value";
  return std::nullopt;
}

// Too many or too few values for an option.
std::optional<std::string> argument_count_message(const std::string& message) {
  std::smatch m;
  static const std::regex at_most(R"(^(\S+): At Most (\d+) required but received (\d+)$)");
  static const std::regex at_least(R"(^(\S+): At least (\d+) required but received (\d+)$)");
  static const std::regex overridden(R"(^(\S+) was given a disallowed flag override$)");
  if (std::regex_match(message, m, at_most))
    return m[1].str() + (m[2] == "1" ? ": given " + m[3].str() + " times; give it once"
                                     : ": at most " + m[2].str() + " values, got " + m[3].str());
  if (std::regex_match(message, m, at_least))
    return m[1].str() + ": at least " + m[2].str() + " values, got " + m[3].str();
  if (std::regex_match(message, m, overridden)) return m[1].str() + ": a flag takes no value";
  static const std::regex missing(R"(^(\S+): \d+ required .* missing$)");
  static const std::regex expected(R"(^Expected .* arguments to (\S+), got \d+$)");
  static const std::regex named(R"(^(\S+)(: | was given ).*$)");
  if (std::regex_match(message, m, missing) || std::regex_match(message, m, expected))
    return m[1].str() + ": a value is required";
  if (std::regex_match(message, m, named))
    return m[1].str() + ": " + message.substr(m[1].length() + (m[2] == ": " ? 2 : 1));
  return std::nullopt;
}

// An option given with one it excludes, or without one it needs.
std::optional<std::string> relation_message(const std::string& message) {
  std::smatch m;
  static const std::regex relation(R"(^(\S+) (excludes|requires) (\S+)$)");
  if (std::regex_match(message, m, relation))
    return m[1].str() + (m[2] == "excludes" ? ": cannot be given with " : ": needs ") + m[3].str();
  return std::nullopt;
}

// Validation errors are already `NAME: what` (our validators word the what). The option's own
// checks run before the safety net's, so a missing value is named here rather than as, say,
// "" is not a number. Any other message is the command's, in lower case.
std::string validation_message(const CLI::App& at, const std::string& message) {
  std::smatch m;
  static const std::regex named(R"(^(-{0,2}[A-Za-z][\w-]*): (.+)$)");
  if (std::regex_match(message, m, named)) {
    if (const CLI::Option* opt = find_option(at, m[1]))
      for (const std::string& value : opt->results()) {
        const std::string missing = missing_value(value, option_names(at));
        if (!missing.empty()) return m[1].str() + ": " + missing;
      }
    return message;
  }
  std::string what = message;
  if (!what.empty()) what[0] = static_cast<char>(std::tolower(static_cast<unsigned char>(what[0])));
  return command_name(at) + ": " + what;
}

// CLI11's messages have a few fixed shapes; each becomes WHERE: what. `at` is the subcommand.
std::string translate(const CLI::App& root, const CLI::App& at, const CLI::ParseError& e) {
  const std::string message = e.what();
  std::optional<std::string> line;
  if (dynamic_cast<const CLI::RequiredError*>(&e)) line = required_message(root, at, message);
  if (dynamic_cast<const CLI::ExtrasError*>(&e)) line = extras_message(root, at, message);
  if (dynamic_cast<const CLI::ConversionError*>(&e)) line = conversion_message(at, message);
  if (dynamic_cast<const CLI::ArgumentMismatch*>(&e)) line = argument_count_message(message);
  if (dynamic_cast<const CLI::ExcludesError*>(&e) || dynamic_cast<const CLI::RequiresError*>(&e))
    line = relation_message(message);
  // Configuration files, runtime and internal errors: kasha reads no CLI11 configuration file and
  // throws none of these itself, but their words are still not CLI11's.
  if (dynamic_cast<const CLI::FileError*>(&e) || dynamic_cast<const CLI::ConfigError*>(&e))
    line = command_name(at) +
           ": a configuration file is not taken (give the options on the "
           "command line)";
  if (dynamic_cast<const CLI::InvalidError*>(&e) || dynamic_cast<const CLI::HorribleError*>(&e) ||
      dynamic_cast<const CLI::RuntimeError*>(&e))
    line = command_name(at) + ": the command line could not be read";
  return line ? *line : validation_message(at, message);
}

}  // namespace

CLI::Validator finite_number() {
  return CLI::Validator(
      [](std::string& text) {
        double v;
        return finite_problem(text, v);
      },
      "finite", "FINITE");
}

CLI::Validator positive_number(double max) {
  const std::string range = max < 1e300 ? "in (0, " + number_text(max) + "]" : "> 0";
  return CLI::Validator(
      [max](std::string& text) {
        double v;
        std::string problem = finite_problem(text, v);
        if (!problem.empty()) return problem;
        if (v <= 0) return printable(text) + " is not positive";
        if (v > max) return printable(text) + " is more than " + number_text(max);
        return std::string();
      },
      range, "POSITIVE");
}

CLI::Validator number_within(double lo, double hi) {
  const std::string range = "in [" + number_text(lo) + ", " + number_text(hi) + "]";
  return CLI::Validator(
      [lo, hi, range](std::string& text) {
        double v;
        std::string problem = finite_problem(text, v);
        if (!problem.empty()) return problem;
        if (v < lo || v > hi) return printable(text) + " is not " + range;
        return std::string();
      },
      range, "WITHIN");
}

CLI::Validator integer_within(long long lo, long long hi) {
  const std::string range = "in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
  return CLI::Validator(
      [lo, hi, range](std::string& text) {
        // Base 10 digits only: "1.5", "1e3" and "0x10" are refused rather than cut or reread.
        static const std::regex digits(R"([+-]?[0-9]+)");
        if (!std::regex_match(text, digits)) return in_quotes(text) + " is not an integer";
        errno = 0;
        long long v = std::strtoll(text.c_str(), nullptr, 10);
        if (errno == ERANGE || v < lo || v > hi) return text + " is not " + range;
        return std::string();
      },
      range, "INTEGER");
}

CLI::Validator byte_size() {
  CLI::AsSizeValue as_size(false);
  return CLI::Validator(
      [as_size](std::string& text) {
        const std::string given = text;
        std::string problem;
        try {
          problem = as_size(text);
        } catch (const CLI::ValidationError&) {
          problem = "bad";
        }
        if (problem.empty()) return problem;
        return in_quotes(given) + " is not a size (bytes, or with a unit: 512MiB, 2GB)";
      },
      "SIZE", "SIZE");
}

CLI::Validator utf8_text() {
  return CLI::Validator(
      [](std::string& text) {
        return valid_utf8(text) ? std::string() : in_quotes(text) + " is not valid UTF-8";
      },
      "", "UTF8");
}

CLI::Validator one_of(const std::vector<std::string>& names) {
  return CLI::Validator(
      [names](std::string& text) {
        for (const std::string& n : names)
          if (text == n) return std::string();
        return in_quotes(text) + " is not one of " + join(names) + suggestion(text, names);
      },
      "one of " + join(names), "ONE_OF");
}

CLI::Validator list_of(const std::vector<std::string>& names, const std::string& what) {
  return CLI::Validator(
      [names, what](std::string& text) {
        std::stringstream list(text);
        std::set<std::string> seen;
        std::string name;
        bool any = false;
        while (std::getline(list, name, ',')) {
          any = true;
          if (std::find(names.begin(), names.end(), name) == names.end())
            return "unknown " + what + " " + in_quotes(name) + " (" + join(names) + ")" +
                   suggestion(name, names);
          if (!seen.insert(name).second) return in_quotes(name) + " is given twice";
        }
        if (!any || text.back() == ',') return "give a comma-separated list of " + join(names);
        return std::string();
      },
      "comma-separated list of " + join(names), "LIST_OF");
}

CLI::Validator device_list() {
  return CLI::Validator([](std::string& text) { return device_list_syntax_error(text); },
                        "INDEX, INDEX,INDEX... or all", "DEVICE_LIST");
}

static CLI::Validator a_value(const std::vector<std::string>& option_names) {
  return CLI::Validator(
      [option_names](std::string& text) { return missing_value(text, option_names); }, "", "VALUE");
}

void require_values(CLI::App& app) {
  const std::vector<std::string> names = option_names(app);
  for (CLI::Option* opt : app.get_options()) {
    if (opt->get_expected_max() == 0) continue;  // a flag
    // An empty description keeps the help's type column as it was.
    opt->check(CLI::Validator(a_value(names)).description(""));
    std::string type = opt->get_type_name();
    type = type.substr(0, type.find(':'));
    if (type == "FLOAT") opt->check(CLI::Validator(finite_number()).description(""));
    if (type == "INT" || type == "UINT")
      opt->check(CLI::Validator(integer_within(type == "UINT" ? 0 : LLONG_MIN, LLONG_MAX))
                     .description(""));
  }
  for (CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; })) require_values(*sub);
}

std::string parse_error_line(const CLI::App& app, const CLI::ParseError& e) {
  return as_one_line(translate(app, *deepest_parsed(app), e));
}

int exit_for_parse_error(const CLI::App& app, const CLI::ParseError& e) {
  if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
  std::fprintf(stderr, "kasha: error: %s\n", parse_error_line(app, e).c_str());
  return kUsageExitCode;
}

}  // namespace kasha::cli
