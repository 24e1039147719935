// standard_output.hpp - what a command prints on stdout is one of its results:
// a full disk or a closed pipe fails the command like a file it could not write;
// and the JSON values its reports are made of.
#pragma once
#include <string>
#include <string_view>

namespace vkfuse::cli {

// Writes text to stdout and flushes it; throws Error(Io) "stdout: write
// failed: ..." if any of it (or anything printed before) did not get there.
// Commands that publish files print their report with it first, so a report
// that cannot be delivered publishes nothing.
void print_checked(const std::string& text);

// The same check for everything a command printed, once it returns status;
// main() applies it to every command.
int checked_stdout(int status);

// A quoted JSON string: '"' and '\' escaped, control characters as \uXXXX,
// bytes that are not well-formed UTF-8 as \ufffd (json::quote).
std::string json_string(std::string_view text);

// %.17g, which round-trips every double; JSON has no NaN or Inf, so those are null.
std::string json_number(double value);

}  // namespace vkfuse::cli
