// Strict option values and the CLI11 parse shared by the demos (command_line.h).
#include "shared/command_line.h"

#include <CLI/CLI.hpp>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <utility>

namespace adb::tools {

void failValue(const std::string& option, const std::string& value, const std::string& problem) {
  throw UsageError(option + " '" + value + "': " + problem);
}

double parseNumber(const std::string& option, const std::string& text) {
  if (text.empty()) failValue(option, text, "expected a number, got an empty item");
  errno = 0;
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (end != text.c_str() + text.size() || errno == ERANGE || !std::isfinite(v)) {
    failValue(option, text, "not a finite number");
  }
  return v;
}

long long parseInteger(const std::string& option, const std::string& text) {
  errno = 0;
  char* end = nullptr;
  const long long v = std::strtoll(text.c_str(), &end, 10);
  if (text.empty() || end != text.c_str() + text.size() || errno == ERANGE) {
    failValue(option, text, "not an integer");
  }
  return v;
}

long long parseIntegerIn(const std::string& option, const std::string& text, long long lo,
                         long long hi) {
  const long long v = parseInteger(option, text);
  if (v < lo || v > hi) {
    // An upper end no one types (a type's limit: 2147483647, 9223372036854775807) reads
    // better left out.
    const bool open = hi >= std::numeric_limits<int>::max();
    failValue(option, text,
              open ? "must be >= " + std::to_string(lo)
                   : "must be between " + std::to_string(lo) + " and " + std::to_string(hi));
  }
  return v;
}

CLI::Option* addValueOption(CLI::App& app, const std::string& name, const std::string& typeName,
                            const std::string& description,
                            std::function<void(const std::string&)> apply,
                            const std::string& defaultText) {
  // trigger_on_parse: the value is applied when it is read, so repeats and interleaved
  // options (--mesh and --model) keep their command-line order. The default is only shown:
  // the target already holds it.
  return app.add_option_function<std::string>(name, std::move(apply), description)
      ->type_name(typeName)
      ->default_str(defaultText)
      ->trigger_on_parse();
}

bool parseOrThrow(CLI::App& app, int argc, const char* const* argv) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp&) {
    return true;
  } catch (const CLI::ParseError& e) {
    // CLI11's own errors (unknown option, missing value) name the option; one error type
    // for the tools to report.
    throw UsageError(e.what());
  }
  return false;
}

std::optional<int> parseCommandLine(CLI::App& app, const std::string& tool, int argc,
                                    const char* const* argv) {
  try {
    if (parseOrThrow(app, argc, argv)) {
      std::fputs(app.help().c_str(), stdout);
      return 0;
    }
  } catch (const UsageError& e) {
    std::fprintf(stderr, "%s: error: %s\nrun '%s --help' for the options\n", tool.c_str(),
                 e.what(), tool.c_str());
    return 2;
  }
  return std::nullopt;
}

}  // namespace adb::tools
