#pragma once
// The command line's one error path: every CLI11 parse error as one line
// `kasha: error: WHERE: what is wrong` (WHERE: the option, argument or subcommand) with exit code
// 2, and the validators whose messages say what is wrong with a value (finite, in range, an
// integer, one of a list) without CLI11's own wording or its 309-digit DBL_MAX.
#include <CLI/CLI.hpp>
#include <string>
#include <vector>

namespace kasha {

constexpr int kUsageExitCode = 2;  // the command line is wrong; 1: input or run error

namespace cli {

CLI::Validator finite_number();                      // any finite number
CLI::Validator positive_number(double max = 1e300);  // finite, in (0, max]
CLI::Validator number_within(double lo, double hi);  // finite, in [lo, hi]
CLI::Validator integer_within(long long lo, long long hi);
CLI::Validator byte_size();  // bytes with an optional unit, as CLI::AsSizeValue, our wording
CLI::Validator utf8_text();  // the value goes into JSON, which needs valid UTF-8
CLI::Validator one_of(const std::vector<std::string>& names);
// A comma-separated list of distinct names, each one of `names` (each a `what`).
CLI::Validator list_of(const std::vector<std::string>& names, const std::string& what);
// `--device LIST`: an index, indices separated by commas or `all` (opencl/device_list.h).
CLI::Validator device_list();

// A safety net over every option and argument of `app` and its subcommands, whatever other checks
// it has: a value is not empty nor another option's name, a FLOAT is finite and an INT or UINT an
// integer.
void require_values(CLI::App& app);

// `WHERE: what is wrong` for a parse error of `app` (the top-level app, parsed or not).
std::string parse_error_line(const CLI::App& app, const CLI::ParseError& e);

// What main does with a ParseError: help and version as CLI11 prints them (exit 0), anything
// else as one error line on stderr (exit 2).
int exit_for_parse_error(const CLI::App& app, const CLI::ParseError& e);

}  // namespace cli
}  // namespace kasha
