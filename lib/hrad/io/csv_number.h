// One numeric CSV cell, parsed with std::from_chars (correctly rounded), for the CSV readers.
#pragma once

#include <cstddef>
#include <string>

namespace hrad {

/// The finite double in `text`, or an hrad::Error at `path:line` naming `column` ("column ny: 'abc'
/// is not a number"; empty, out of range and non-finite cells likewise). A leading '+' is allowed.
double parse_csv_number(const std::string& path, std::size_t line, const std::string& column, const char* text);

}  // namespace hrad
