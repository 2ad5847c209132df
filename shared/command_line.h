// The demos' command lines: CLI11 reads the options (names, --name=value, repeats, --help
// built from each option's description), and the strict value parsing here checks every
// value completely (no atoi-style "5x" -> 5, no "-1" wrapping to 2^64 - 1): a typo must not
// silently turn into another run. Every bad value gets one error naming the option and the
// value: "--rotations '-3': must be between 1 and 10000000".
//
// CLI11 is only declared here: headers that need UsageError (the study's options.h, read by
// most of its files) stay light; the files that build a CLI::App include <CLI/CLI.hpp>.
#pragma once

#include <cassert>
#include <functional>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>

namespace CLI {
class App;
class Option;
}  // namespace CLI

namespace adb::tools {

/// A usage error: a bad option or value. The tools print it and exit 2.
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Throws UsageError("OPTION 'VALUE': PROBLEM").
[[noreturn]] void failValue(const std::string& option, const std::string& value,
                            const std::string& problem);

/// The whole text as a finite number, else UsageError.
double parseNumber(const std::string& option, const std::string& text);
/// The whole text as a decimal integer that fits a long long, else UsageError.
long long parseInteger(const std::string& option, const std::string& text);
/// parseInteger, and lo <= value <= hi.
long long parseIntegerIn(const std::string& option, const std::string& text, long long lo,
                         long long hi);

/// Adds an option taking one value, handed to `apply` as it is read (so repeated options
/// apply in command-line order and the last one wins). `typeName` names the value in --help
/// ("N", "LIST"), `defaultText` (if any) is shown there as its default. `apply` throws
/// UsageError for a bad value.
CLI::Option* addValueOption(CLI::App& app, const std::string& name, const std::string& typeName,
                            const std::string& description,
                            std::function<void(const std::string&)> apply,
                            const std::string& defaultText = "");

/// An integer option in [lo, hi] stored into `target`; --help shows the value `target` holds
/// now as the default.
template <typename Int>
CLI::Option* addIntegerOption(CLI::App& app, const std::string& name, Int& target, long long lo,
                              long long hi, const std::string& description) {
  static_assert(std::numeric_limits<Int>::is_integer, "an integer option needs an integer");
  // A checked value is stored unchanged only if [lo, hi] fits the target type.
  assert(lo >= static_cast<long long>(std::numeric_limits<Int>::min()));
  assert(hi < 0 || static_cast<unsigned long long>(hi) <=
                       static_cast<unsigned long long>(std::numeric_limits<Int>::max()));
  Int* out = &target;
  return addValueOption(
      app, name, "N", description,
      [out, name, lo, hi](const std::string& text) {
        *out = static_cast<Int>(parseIntegerIn(name, text, lo, hi));
      },
      std::to_string(target));
}

/// Parses argv into the options of `app`. Returns true when --help (or -h) was asked for
/// (nothing else is checked then); throws UsageError for anything CLI11 or a value parser
/// rejects.
bool parseOrThrow(CLI::App& app, int argc, const char* const* argv);

/// For main(): parses argv; std::nullopt to go on, else the exit status: 0 after --help
/// (printed on stdout), 2 after a usage error (printed on stderr as "TOOL: error: ...").
std::optional<int> parseCommandLine(CLI::App& app, const std::string& tool, int argc,
                                    const char* const* argv);

}  // namespace adb::tools
