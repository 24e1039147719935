// io/path_component.hpp - names that come from data and become file names.
//
// A serial, an object name or a frame path read from a manifest is hostile
// until checked: it must never choose a directory outside the one we write
// into or read from. These checks look at path components, not substrings, so
// "000040..png" is a fine name and "a/../b" is not.
#pragma once
#include <string>
#include <string_view>

namespace vkfuse::io {

// One plain file or directory name: 1..255 bytes, not "." or "..", no '/' or
// '\\', no NUL and no other control character.
bool is_plain_component(std::string_view name);

// Why name is not a plain component ("" when it is), naming it:
// "\"a/b\": not usable as a file name (one component: ...)".
std::string component_problem(std::string_view name);

// Throws Error(InvalidArgument) "<what> <component_problem>" unless is_plain_component;
// the name is shown with control and non-UTF-8 bytes escaped.
void check_plain_component(std::string_view name, const std::string& what);

// A relative path of plain components joined by single '/' (no leading '/',
// no empty, "." or ".." component): a path that cannot leave its base.
bool is_contained_relative_path(std::string_view path);

// base/relative for reading, once symbolic links are resolved: throws
// Error(Format) "<base>/<relative>: leads outside <base> (symbolic link)"
// when the file it names lies outside base. A path that does not resolve (a
// missing file) is returned as is, for the reader to report.
std::string resolve_inside(const std::string& base, const std::string& relative);

// name with every byte outside printable ASCII written as \xNN, for messages.
std::string printable(std::string_view name);

}  // namespace vkfuse::io
