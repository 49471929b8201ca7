// Fast C++ CSV Parser (Debian libfccp-dev), included once for the CSV readers: it splits, trims and
// matches the header; cells are parsed by parse_csv_number (csv_number.h: std::from_chars, which
// rounds correctly; the parser's own float reader does not). Its error types copy file names with
// strncpy, which GCC's inliner warns about.
#pragma once

#define CSV_IO_NO_THREAD
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wstringop-truncation"
#endif
#include <libfccp/csv.h>
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif
